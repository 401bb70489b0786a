#!/usr/bin/env bash
# OpenAPI lint: writes the document the server serves (`ringdyn openapi`, the
# template with the scene schemas generated from the api tables) and runs
# Redocly's recommended rules on it; any error or warning fails (counted from
# its JSON report).
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
# --format json: the totals are counted, not read off the text (the text
# says "Woohoo! Your API description is valid" with warnings too).
status=0
"$here/node_modules/.bin/redocly" lint --extends recommended --max-problems 1000 --format json \
  "$out/openapi.json" >"$out/redocly.json" 2>"$out/redocly.err" || status=$?
python3 - "$out/redocly.json" "$status" <<'PY' || fail "redocly reported problems (above), or its report could not be read"
import json, sys
try:
    report = json.load(open(sys.argv[1]))
    totals = report["totals"]
except (ValueError, KeyError) as e:
    print("no JSON report from redocly (exit status %s): %s" % (sys.argv[2], e))
    sys.exit(1)
for p in report.get("problems", []):
    where = "; ".join(loc.get("pointer", "") for loc in p.get("location", []))
    print("%s %s: %s at %s" % (p.get("severity"), p.get("ruleId"), p.get("message"), where))
print("redocly: %d errors, %d warnings" % (totals["errors"], totals["warnings"]))
sys.exit(1 if totals["errors"] or totals["warnings"] or sys.argv[2] != "0" else 0)
PY
echo "openapi lint: 0 errors, 0 warnings"
