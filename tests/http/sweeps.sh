#!/usr/bin/env bash
# Sweeps over real HTTP (issue 16): one spec through POST /api/v1/sweeps and
# through `ringdyn sweep run` x K chunks (in parallel) + `reduce` gives the
# same table, byte for byte, as JSON and as CSV; the list; cancel (DELETE of
# a running sweep stops it, DELETE of a finished one deletes it); a point
# over the time limit is a row with its error, not a failed sweep; a spec
# over the service limit is refused naming the cluster path; bad specs are
# 400 with the path of the problem, before anything runs; the fidelity
# request; finished sweeps survive a restart (the job store), unfinished
# ones end interrupted; the token and the Host allowlist.
#
#   sweeps.sh SERVER_BINARY RD_JSONQ RINGDYN_CLI
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 SERVER RD_JSONQ RINGDYN" >&2
  exit 2
fi
SERVER=$1 JQ=$2 CLI=$3
. "$(dirname "$0")/lib.sh"

# A Latin hypercube (deterministic expansion) over a random and a range
# parameter, with list outputs and an aggregate; no wall time, so the two
# tables can be compared byte for byte.
SPEC='{"base": {"analysis": "modal", "modal": {"modes": 3}},
 "parameters": [{"path": "/ring/closed_gap", "random": {"min": 1e-4, "max": 5e-4}},
                {"path": "/discretization/segments",
                 "range": {"start": 10, "stop": 40, "count": 4, "integer": true}}],
 "combine": "latin_hypercube", "samples": 9, "seed": 7,
 "outputs": ["/modes/0/frequency_hz", "/modes/2/frequency_hz", "max(/modes/*/error_estimate)",
             "count(/modes)"]}'
SLOW='{"analysis": "modal", "discretization": {"segments": 2000}, "modal": {"modes": 60}}'

# table_of FILE: the "table" member of a sweep's JSON (its last member; the
# service splices the table text in as rd_sweep_table_json writes it).
table_of() { sed -e 's/^.*"table"://' -e 's/}$//' "$1"; }
# wait_status ID STATUS: polls until the sweep has STATUS (30 s at most).
wait_status() {
  local _
  for _ in $(seq 1 300); do
    req GET "/api/v1/sweeps/$1"
    [ "$(json /status)" = "$2" ] && return 0
    sleep 0.1
  done
  return 1
}

start_server S --sweep-max-points 50 --job-timeout 0.5
S_PID=$SPID

# ---- the service's table = the cluster path's table ---------------------------
post '/api/v1/sweeps' "$SPEC"
same "POST /api/v1/sweeps -> 202" "$STATUS" 202
ID=$(json /id)
same "Location names the sweep" "$(header Location)" "/api/v1/sweeps/$ID"
same "9 points" "$(json /points)" 9
check "the sweep finishes" wait_status "$ID" succeeded
same "progress 1 when done" "$(json /progress)" 1
same "no point failed" "$(json /failed)" 0
table_of "$WORK/body" >"$WORK/service.json"
req GET "/api/v1/sweeps/$ID/table.csv"
same "table.csv -> 200" "$STATUS" 200
check "table.csv is text/csv" grep -qi '^Content-Type: text/csv' "$WORK/headers"
cp "$WORK/body" "$WORK/service.csv"

printf '%s' "$SPEC" >"$WORK/spec.json"
K=3
seq 0 $((K - 1)) | xargs -P "$K" -I{} "$CLI" sweep run "$WORK/spec.json" --index {} --chunks "$K" \
  --out "$WORK/chunks" 2>"$WORK/cli.err"
"$CLI" sweep reduce "$WORK/chunks" >"$WORK/cli.json"
"$CLI" sweep reduce "$WORK/chunks" --csv >"$WORK/cli.csv"
# reduce ends its JSON with a newline; the service's member has none.
check "service table = run x $K chunks + reduce (JSON, byte for byte)" \
  cmp -s <(cat "$WORK/service.json"; echo) "$WORK/cli.json"
check "service table.csv = reduce --csv (byte for byte)" cmp -s "$WORK/service.csv" "$WORK/cli.csv"
same "the table has 9 rows" "$(jcount /rows "$WORK/cli.json")" 9

# ---- ?wait, the list -------------------------------------------------------------
post '/api/v1/sweeps?wait=60' "$SPEC"
same "POST ?wait=60 of a short sweep -> 200" "$STATUS" 200
same "... succeeded" "$(json /status)" succeeded
check "... with Location" test -n "$(header Location)"
ID2=$(json /id)
req GET /api/v1/sweeps
same "GET /api/v1/sweeps -> 200" "$STATUS" 200
same "the list has both, newest first" "$(json /sweeps/0/id) $(json /sweeps/1/id)" "$ID2 $ID"
check "the list carries no tables" test -z "$(json /sweeps/0/table)"

# ---- a point over the time limit is a row with its error --------------------------
post '/api/v1/sweeps?wait=60' '{"base": '"${SLOW/60/3}"', "parameters": [
  {"path": "/discretization/segments", "values": [10, 2000]}, {"path": "/modal/modes", "values": [3, 60]}],
  "combine": "zip", "outputs": ["/modes/0/frequency_hz"]}'
same "a sweep with a point over the limit succeeds" "$(json /status)" succeeded
same "... one point failed" "$(json /failed)" 1
same "... the fast point's row is ok" "$(json /table/rows/0/3)" ok
same "... the slow point's row says time_limit" "$(json /table/rows/1/3)" time_limit
same "... with its parameter values and a null output" \
  "$(json /table/rows/1/0) $(json /table/rows/1/1) $(json /table/rows/1/2)" "2000 60 null"
check "... and names the limit" grep -q 'time limit of 0.5 s' "$WORK/body"

# ---- cancel ------------------------------------------------------------------------
post '/api/v1/sweeps' '{"base": '"$SLOW"', "parameters": [{"path": "/ring/tangential_force",
  "range": {"start": 5, "stop": 15, "count": 20}}], "outputs": ["/modes/0/frequency_hz"]}'
C=$(json /id)
check "the slow sweep runs" wait_status "$C" running
t0=$(date +%s.%N)
req DELETE "/api/v1/sweeps/$C"
t1=$(date +%s.%N)
same "DELETE of a running sweep -> 200" "$STATUS" 200
same "... cancelled" "$(json /status)" cancelled
check "... within 3 s of the DELETE" awk -v a="$t0" -v b="$t1" 'BEGIN { exit !(b - a < 3) }'
check "... with fewer rows than points" test "$(jcount /table/rows)" -lt 20
req GET /api/v1/health
same "the server serves on after the cancel" "$STATUS" 200
req DELETE "/api/v1/sweeps/$C"
same "DELETE of a finished sweep deletes it -> 204" "$STATUS" 204
req GET "/api/v1/sweeps/$C"
expect_error "GET of the deleted sweep" 404 not_found
req DELETE "/api/v1/sweeps/$C/table.csv"
expect_error "DELETE on table.csv" 405 method_not_allowed

# ---- at most 8 sweeps queued or running ----------------------------------------------
FULL=()
for i in $(seq 1 8); do
  post '/api/v1/sweeps' '{"base": '"$SLOW"', "parameters": [{"path": "/ring/tangential_force",
    "range": {"start": 5, "stop": 15, "count": 20}}], "outputs": ["/modes/0/frequency_hz"]}'
  FULL+=("$(json /id)")
done
post '/api/v1/sweeps' "$SPEC"
expect_error "a 9th unfinished sweep" 429 queue_full
check "... with Retry-After" test -n "$(header Retry-After)"
for id in "${FULL[@]}"; do
  req DELETE "/api/v1/sweeps/$id" # cancel
  req DELETE "/api/v1/sweeps/$id" # and delete
done
same "the 8 were cancelled and deleted" "$STATUS" 204

# ---- refused before anything runs --------------------------------------------------
post '/api/v1/sweeps' '{"base": {"analysis": "modal"}, "parameters": [{"path": "/ring/tangential_force",
  "range": {"start": 1, "stop": 20, "count": 51}}], "outputs": ["/modes/0/frequency_hz"]}'
expect_error "51 points over --sweep-max-points 50" 400 invalid_request /parameters
check "... naming the cluster path" grep -q 'ringdyn sweep run .*--chunks K' "$WORK/body"
post '/api/v1/sweeps' '{"base": {"analysis": "modal"}, "parameters": [{"path": "/ring/tangential_force",
  "values": []}], "outputs": ["/modes/0/frequency_hz"]}'
expect_error "an empty list" 400 invalid_request /parameters/0/values
post '/api/v1/sweeps' '{"base": {"analysis": "modal"}, "parameters": [{"path": "/ring/no_such_field",
  "values": [1]}], "outputs": ["/modes/0/frequency_hz"]}'
expect_error "an unknown pointer" 400 invalid_request /parameters/0/values/0
post '/api/v1/sweeps' '{"base": {"analysis": "modal"}, "parameters": [{"path": "/discretization/segments",
  "values": [10, 2001]}], "outputs": ["/modes/0/frequency_hz"]}'
expect_error "a value outside the scene's range" 400 invalid_request /parameters/0/values/1
post '/api/v1/sweeps' '{"base": {"analysis": "modal"}, "parameters": [{"path": "/ring/tangential_force",
  "random": {"min": -1e308, "max": 1e308}}], "combine": "latin_hypercube", "samples": 40,
  "outputs": ["/modes/0/frequency_hz"]}'
expect_error "finite min and max whose samples overflow (issue 45)" 422 invalid_scene /parameters/0/random
check "... naming the parameter, the value and the allowed range" \
  grep -q '/ring/tangential_force.*is -\?inf.*needs |max - min| <= 1.79769e+308' "$WORK/body"
post '/api/v1/sweeps' '{"base": {"analysis": "modal"}'
expect_error "not JSON" 400 invalid_json
req POST /api/v1/sweeps -H 'Content-Type: text/plain' --data-binary "$SPEC"
expect_error "text/plain" 415 unsupported_media_type
req GET /api/v1/sweeps
same "nothing refused was queued (3 sweeps left)" "$(jcount /sweeps)" 3

# ---- fidelity ------------------------------------------------------------------------
post '/api/v1/sweeps?wait=60' '{"fidelity": {"analysis": "modal", "modal": {"modes": 3}},
  "segments": [5, 10, 20, 40]}'
same "a fidelity sweep -> 200" "$STATUS" 200
same "... kind fidelity" "$(json /kind)" fidelity
same "... its fidelity table has 4 rows" "$(jcount /fidelity/rows)" 4
same "... the finest run's error vs itself is 0" "$(json /fidelity/rows/3/3)" 0
same "... the modal estimate covers the segment count" "$(json /fidelity/rows/0/4)" segments
same "... the finest run changes nothing against itself" "$(json /fidelity/rows/3/5)" ""
same "... so its error rests on its estimate" "$(json /fidelity/rows/3/6)" estimate
check "... the finest run is on the Pareto front" test "$(json /fidelity/rows/3/8)" = true
post '/api/v1/sweeps' '{"fidelity": {"analysis": "modal"}, "segments": [5, 2]}'
expect_error "fidelity segments out of range" 400 invalid_request /segments/1
post '/api/v1/sweeps' '{"fidelity": {"analysis": "modal", "ring": {"diameter": -1}}}'
expect_error "fidelity scene invalid" 400 invalid_request /fidelity/ring/diameter
post '/api/v1/sweeps' '{"fidelity": {"analysis": "modal"}, "segmnts": [5]}'
expect_error "fidelity unknown field" 400 invalid_request /segmnts
# ---- over: the service's table = the cluster path's; runs count -------------------
OVER='{"base": {"analysis": "modal", "modal": {"modes": 3, "error_estimate": false}},
 "parameters": [{"path": "/ring/radial_width", "values": [0.0029, 0.0032, 0.0035]}],
 "over": {"path": "/ring/closed_gap", "range": {"start": 1e-4, "stop": 5e-4, "count": 4}},
 "outputs": ["/modes/0/frequency_hz", "/modes/2/frequency_hz"]}'
post '/api/v1/sweeps?wait=60' "$OVER"
same "an over sweep -> 200" "$STATUS" 200
same "... 3 points, 12 runs" "$(json /points) $(json /runs)" "3 12"
same "... progress 1 when done" "$(json /progress)" 1
same "... its columns: min, max, mean, argmin, argmax per output" \
  "$(json /table/columns/1) $(json /table/columns/5) $(json /table/columns/10)" \
  "min:/modes/0/frequency_hz argmax:/modes/0/frequency_hz argmax:/modes/2/frequency_hz"
table_of "$WORK/body" >"$WORK/over-service.json"
printf '%s' "$OVER" >"$WORK/over.json"
seq 0 2 | xargs -P 3 -I{} "$CLI" sweep run "$WORK/over.json" --index {} --chunks 3 \
  --out "$WORK/over-chunks" 2>"$WORK/cli.err"
"$CLI" sweep reduce "$WORK/over-chunks" >"$WORK/over-cli.json"
check "over: service table = run x 3 chunks + reduce (byte for byte)" \
  cmp -s <(cat "$WORK/over-service.json"; echo) "$WORK/over-cli.json"
post '/api/v1/sweeps' '{"base": {"analysis": "modal"}, "parameters": [{"path": "/ring/radial_width",
  "range": {"start": 0.0025, "stop": 0.0035, "count": 13}}], "over": {"path": "/ring/closed_gap",
  "values": [2e-4, 3e-4, 4e-4, 5e-4]}, "outputs": ["/modes/0/frequency_hz"]}'
expect_error "13 points x 4 over values over --sweep-max-points 50" 400 invalid_request /over
check "... the message counts the runs" grep -q '13 points x 4 over values = 52 runs, more than the limit of 50 runs' "$WORK/body"

stop_server S "$S_PID"

# ---- finished sweeps outlive the server; unfinished ones end interrupted ------------
DATA=$WORK/data
start_server P --data "$DATA"
P_PID=$SPID
post '/api/v1/sweeps?wait=60' "$SPEC"
PID_=$(json /id)
cp "$WORK/body" "$WORK/before.json"
req GET "/api/v1/sweeps/$PID_/table.csv"
cp "$WORK/body" "$WORK/before.csv"
post '/api/v1/sweeps' '{"base": '"$SLOW"', "parameters": [{"path": "/ring/tangential_force",
  "range": {"start": 5, "stop": 15, "count": 20}}], "outputs": ["/modes/0/frequency_hz"]}'
RUNNING=$(json /id)
check "a slow sweep runs at the stop" wait_status "$RUNNING" running
stop_server P "$P_PID"
start_server P2 --data "$DATA"
P2_PID=$SPID
req GET "/api/v1/sweeps/$PID_"
check "after a restart the finished sweep is served byte for byte as before" cmp -s "$WORK/body" "$WORK/before.json"
req GET "/api/v1/sweeps/$PID_/table.csv"
check "... and its table.csv" cmp -s "$WORK/body" "$WORK/before.csv"
req GET "/api/v1/sweeps/$RUNNING"
same "the sweep running at the stop is interrupted" "$(json /status)" interrupted
check "... with fewer rows than points" test "$(jcount /table/rows)" -lt 20
req GET /api/v1/sweeps
same "the list after the restart: both, newest first" "$(json /sweeps/0/id) $(json /sweeps/1/id)" "$RUNNING $PID_"
req DELETE "/api/v1/sweeps/$PID_"
same "DELETE of the stored sweep -> 204" "$STATUS" 204
stop_server P2 "$P2_PID"
start_server P3 --data "$DATA"
P3_PID=$SPID
req GET "/api/v1/sweeps/$PID_"
expect_error "a deleted sweep stays deleted after a restart" 404 not_found
stop_server P3 "$P3_PID"

# ---- token and Host ----------------------------------------------------------------------
head -c 24 /dev/urandom | base64 >"$WORK/token"
start_server T --token-file "$WORK/token"
T_PID=$SPID
post '/api/v1/sweeps' "$SPEC"
expect_error "POST /api/v1/sweeps without the token" 401 unauthorized
req GET /api/v1/sweeps
expect_error "GET /api/v1/sweeps without the token" 401 unauthorized
CURL_EXTRA=(-H "Authorization: Bearer $(head -n 1 "$WORK/token")")
post '/api/v1/sweeps?wait=60' "$SPEC"
same "with the token -> 200" "$STATUS" 200
TID=$(json /id)
CURL_EXTRA=()
req GET "/api/v1/sweeps/$TID/table.csv"
expect_error "table.csv without the token" 401 unauthorized
CURL_EXTRA=(-H "Authorization: Bearer $(head -n 1 "$WORK/token")" -H 'Host: evil.example')
req GET "/api/v1/sweeps/$TID"
expect_error "a foreign Host with the token" 403 forbidden_host
CURL_EXTRA=()
stop_server T "$T_PID"

finish
