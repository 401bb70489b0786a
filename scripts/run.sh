#!/usr/bin/env bash
# Installs what is missing, builds (release) into build/, and starts the service
# on 127.0.0.1 (port 8080 unless PORT is set).  Extra arguments go to the server.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRINGDYN_TESTS=OFF -DRINGDYN_BENCH=OFF >/dev/null
cmake --build build -j"$(nproc)"
exec build/server/ringdyn-server --host 127.0.0.1 --port "${PORT:-8080}" \
  --static static --examples examples "$@"
