#!/usr/bin/env bash
# Installs the Debian packages ringdyn needs, only those that are missing.
#   scripts/install-deps.sh          build + run dependencies
#   scripts/install-deps.sh --test   also what the test suite needs (curl, chromium, node/npm, python3,
#                                    python3-jsonschema for the OpenAPI contract test, clang with libFuzzer for
#                                    the fuzz test, clang-format for the style check, Slurm and munge for the
#                                    cluster tests, jq and GNU time for the Slurm executor's)
set -euo pipefail
pkgs=(build-essential cmake pkg-config libmicrohttpd-dev libjansson-dev libsqlite3-dev zlib1g-dev libsundials-dev
      liblapack-dev liblapacke-dev libgsl-dev curl)
if [ "${1:-}" = "--test" ]; then
  pkgs+=(chromium nodejs npm valgrind python3 python3-jsonschema clang clang-format libclang-rt-14-dev
         slurmctld slurmd slurm-client munge jq time)
fi
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# node/npm may come from outside Debian (e.g. a preinstalled toolchain): accept working binaries.
if command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1; then
  missing=("${missing[@]/nodejs}"); missing=("${missing[@]/npm}")
fi
read -r -a missing <<< "${missing[*]:-}"
if [ "${#missing[@]}" -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "install-deps: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
