#!/usr/bin/env bash
# The Python client of examples/python (standard library only) against a live
# ringdyn-server: as a program (a shipped example, its CSV, a refused scene
# with the field's JSON Pointer, an unreachable server) and as a module (the
# result's numbers against the server's own answer, a cancelled job).
#
#   python_client.sh SERVER_BINARY EXAMPLES_DIR CLIENT_DIR PYTHON3
# Last line: "N passed, N failed".
set -euo pipefail
if [ $# -ne 4 ]; then
  echo "usage: $0 SERVER EXAMPLES_DIR CLIENT_DIR PYTHON3" >&2
  exit 2
fi
SERVER=$1 EXAMPLES=$2 CLIENT=$3 PY=$4
WORK=$(mktemp -d "${TMPDIR:-/tmp}/ringdyn-pyclient.XXXXXX")
SPID=""
cleanup() {
  [ -n "$SPID" ] && kill -KILL "$SPID" 2>/dev/null || true
  rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

PASSED=0 FAILED=0
ok() { PASSED=$((PASSED + 1)); echo "ok   - $1"; }
bad() { FAILED=$((FAILED + 1)); echo "FAIL - $1${2:+ ($2)}"; }

"$SERVER" --data :memory: --host 127.0.0.1 --port 0 --examples "$EXAMPLES" >"$WORK/server.out" 2>"$WORK/server.err" &
SPID=$!
line=""
for _ in $(seq 1 150); do # 15 s: sanitizer builds start slowly
  line=$(head -n 1 "$WORK/server.out" 2>/dev/null || true)
  [ -n "$line" ] && break
  kill -0 "$SPID" 2>/dev/null || break
  sleep 0.1
done
if [[ ! $line =~ ^ringdyn-server\ listening\ on\ (http://127\.0\.0\.1:[0-9]+)$ ]]; then
  echo "server did not start; stdout: '$line'; stderr:" >&2
  cat "$WORK/server.err" >&2
  exit 1
fi
BASE=${BASH_REMATCH[1]}
run_client() { timeout 120 "$PY" "$CLIENT/ringdyn_client.py" --server "$BASE" "$@"; }

# 1. A shipped example as a program: exit 0, a summary line, the CSV table.
if out=$(run_client --csv "$WORK/modal.csv" "$EXAMPLES/thesis_modal.json" 2>"$WORK/modal.err"); then
  ok "thesis_modal.json runs (exit 0)"
else
  bad "thesis_modal.json runs (exit 0)" "$(cat "$WORK/modal.err")"
fi
if [[ $out =~ ^job\ [0-9a-f]{16}\ succeeded:\ modal:\ first\ frequencies ]]; then ok "summary line"; else bad "summary line" "$out"; fi
modes=$(sed -n 's/.*"modes"[^0-9]*\([0-9]*\).*/\1/p' "$EXAMPLES/thesis_modal.json" | head -n 1)
rows=$(($(wc -l <"$WORK/modal.csv") - 1))
if [ -n "$modes" ] && [ "$rows" -eq "$modes" ]; then ok "CSV: a header and one row per mode ($rows)"; else bad "CSV rows" "$rows rows, $modes modes"; fi

# 2. A refused scene: exit 1 and the field's JSON Pointer with the server's message.
printf '{"analysis":"modal","discretization":{"segments":1}}' >"$WORK/bad.json"
rc=0
err=$(run_client "$WORK/bad.json" 2>&1 >/dev/null) || rc=$?
if [ "$rc" -eq 1 ] && [[ $err == "ringdyn: /discretization/segments: "*"out of range"* ]]; then
  ok "refused scene: exit 1, path and message"
else
  bad "refused scene: exit 1, path and message" "rc $rc: $err"
fi

# 3. No server there: exit 1 with a network error, not a traceback.
rc=0
err=$(timeout 60 "$PY" "$CLIENT/ringdyn_client.py" --server http://127.0.0.1:9 "$EXAMPLES/thesis_modal.json" 2>&1 >/dev/null) || rc=$?
if [ "$rc" -eq 1 ] && [[ $err == "ringdyn: cannot reach"* ]]; then ok "unreachable server: exit 1"; else bad "unreachable server" "rc $rc: $err"; fi

# 4. As a module: the result equals the server's own job; a cancelled job raises.
if out=$(cd "$CLIENT" && timeout 120 "$PY" - "$BASE" 2>&1 <<'PY'
import json, sys, time, urllib.request
from ringdyn_client import Client, RingdynError
base = sys.argv[1]
c = Client(base)
job = c.run({"analysis": "pretension", "discretization": {"segments": 12}})
with urllib.request.urlopen(f"{base}/api/v1/jobs/{job['id']}") as r:
    direct = json.load(r)
assert direct["result"]["gap_opening_inner"] == job["result"]["gap_opening_inner"], "same result"
assert job["result"]["gap_opening_inner"] > 0, job["result"]["gap_opening_inner"]
# A lift of many cycles runs for minutes: cancelled at once, wait() raises.
long = c.submit({"analysis": "lift", "engine": {"cycles": 20},
                 "physics": {"friction": {"model": "coulomb", "coefficient": 0.1}}})
c.cancel(long["id"])
try:
    c.wait(long["id"], timeout=60)
    raise SystemExit("a cancelled job did not raise")
except RingdynError as e:
    assert e.job is not None and e.job["status"] == "cancelled", (e.code, e.job)
# wait() long-polls: a job of a few seconds is back as soon as it ends, not
# after `poll` (the old client slept it between requests).
t0 = time.monotonic()
slow = c.wait(c.submit({"analysis": "lift", "engine": {"cycles": 3}, "numerics": {"model": "full"},
                        "output": {"step_deg": 30}}), poll=30)
assert slow["status"] == "succeeded" and time.monotonic() - t0 < 20, time.monotonic() - t0
# A job the server stopped by its restart ends "interrupted": final at once,
# not polled until the timeout (a client that knew only three final
# statuses waited its 600 s).
import time as _t
class Stub(Client):
    def job(self, job_id, wait=0):
        return {"id": job_id, "status": "interrupted",
                "error": {"code": "interrupted", "message": "the server restarted"}}
t0 = _t.monotonic()
try:
    Stub(base).wait({"id": "x", "status": "running"}, poll=0.01, timeout=30)
    raise SystemExit("an interrupted job did not raise")
except RingdynError as e:
    assert e.code == "interrupted" and e.job["status"] == "interrupted", (e.code, e.job)
assert _t.monotonic() - t0 < 5, "an interrupted job was polled"
try:
    c.submit({"analysis": "modal", "ring": {"material": {"density": -1}}})
    raise SystemExit("a negative density was accepted")
except RingdynError as e:
    assert e.status == 422 and e.path == "/ring/material/density", (e.status, e.path)
print("module ok")
PY
); then
  [ "$out" = "module ok" ] && ok "module: result, cancel, 422 path" || bad "module" "$out"
else
  bad "module: result, cancel, 422 path" "$out"
fi

kill -TERM "$SPID"
wait "$SPID" 2>/dev/null || true
SPID=""
if grep -q "ERROR: \(Leak\|Address\)Sanitizer\|runtime error:" "$WORK/server.err"; then
  bad "no sanitizer report" "$(grep -m 3 "Sanitizer\|runtime error" "$WORK/server.err")"
else
  ok "no sanitizer report"
fi
echo "$PASSED passed, $FAILED failed"
[ "$FAILED" -eq 0 ]
