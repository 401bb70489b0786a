#!/usr/bin/env bash
# OpenAPI lint: writes the document the server serves (`ringdyn openapi`, the
# template with the scene schemas generated from the api tables) and runs
# Redocly's recommended rules on it; any error or warning fails.
#   tests/lint/openapi/run.sh <ringdyn-cli> <openapi-template> <out-dir>
# @redocly/cli comes from npm (package.json here; scripts/test.sh runs npm
# install).  A missing node or package is a failure, not a skip.
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 <ringdyn-cli> <openapi-template> <out-dir>" >&2
  exit 2
fi
cli=$1 template=$2 out=$3
here=$(cd "$(dirname "$0")" && pwd)
fail() { echo "openapi lint FAILED: $*" >&2; exit 1; }
command -v node >/dev/null 2>&1 || fail "node is missing; install it with scripts/install-deps.sh --test"
[ -x "$here/node_modules/.bin/redocly" ] ||
  fail "@redocly/cli is not installed in $here; run 'npm install' there (scripts/test.sh does)"
mkdir -p "$out"
"$cli" openapi "$template" >"$out/openapi.json" || fail "ringdyn openapi failed"
# No telemetry or update check: the test must not depend on the network.
export REDOCLY_TELEMETRY=off REDOCLY_SUPPRESS_UPDATE_NOTICE=true
"$here/node_modules/.bin/redocly" lint --extends recommended --max-problems 1000 "$out/openapi.json" \
  >"$out/redocly.out" 2>&1 || { cat "$out/redocly.out" >&2; fail "redocly reported errors"; }
cat "$out/redocly.out"
# Warnings do not change redocly's exit status; the contract is none at all.
if grep -q "warning" "$out/redocly.out" && ! grep -q "Woohoo" "$out/redocly.out"; then
  fail "redocly reported warnings"
fi
echo "openapi lint: 0 errors, 0 warnings"
