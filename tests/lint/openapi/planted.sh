#!/usr/bin/env bash
# The OpenAPI lint can fail: run.sh on a copy of the template with one planted
# warning (an unused component, Redocly's no-unused-components) must fail, and
# for that warning, not for a missing tool.
#   tests/lint/openapi/planted.sh <ringdyn-cli> <openapi-template> <out-dir>
set -euo pipefail
cli=$1 template=$2 out=$3
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
python3 - "$template" "$out/planted.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
doc["components"]["schemas"]["PlantedUnused"] = {"type": "string", "description": "planted"}
json.dump(doc, open(sys.argv[2], "w"), indent=2)
PY
if "$here/run.sh" "$cli" "$out/planted.json" "$out/lint" >"$out/run.out" 2>&1; then
  cat "$out/run.out"
  echo "FAIL - the lint passed a document with a planted warning"
  exit 1
fi
if grep -q 'no-unused-components.*PlantedUnused' "$out/run.out" && grep -q '0 errors, 1 warnings' "$out/run.out"; then
  echo "ok   - the lint fails on the planted warning (and only on it): $(grep 'redocly:' "$out/run.out")"
else
  cat "$out/run.out"
  echo "FAIL - the lint failed, but not for the planted warning"
  exit 1
fi
