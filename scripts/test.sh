#!/usr/bin/env bash
# The whole test suite on a fresh Debian machine: installs what is missing,
# builds with -Wall -Wextra -Werror and ASan/UBSan into build-test/, runs every
# test (unit, API cases, curl against a live server, headless browser).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --test
# The npm packages of the tests (browser: playwright-core; lint/openapi: @redocly/cli;
# cluster/k8s: kubernetes-models, the Kubernetes API schema).
for dir in tests/browser tests/lint/openapi tests/cluster/k8s; do
  if [ -f "$dir/package.json" ]; then
    (cd "$dir" && npm install --no-audit --no-fund --loglevel=error)
  fi
done
cmake -S . -B build-test -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRINGDYN_SANITIZE=ON -DRINGDYN_WERROR=ON >/dev/null
cmake --build build-test -j"$(nproc)"
cd build-test
ctest --output-on-failure -j2 "$@"
