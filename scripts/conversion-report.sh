#!/usr/bin/env bash
# Counts the -Wsign-conversion warnings left in the shipped code (core, api,
# cli, server), per file, for docs/warnings.md.  Builds into a scratch dir.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DRINGDYN_TESTS=OFF -DRINGDYN_BENCH=OFF \
  -DRINGDYN_SIGN_CONVERSION=ON >/dev/null
cmake --build "$dir" -j"$(nproc)" 2>&1 | grep -E 'warning: .*\[-Wsign-conversion\]' |
  sed -E "s|^$PWD/||; s|^([^:]*):.*|\1|" | sort | uniq -c | sort -rn
