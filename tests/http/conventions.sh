#!/usr/bin/env bash
# The conventions of a job service (issue 13 items 4 and 6) against a live
# server: unknown query parameters refused, job list filters and cursor
# pagination, Idempotency-Key (kept across a restart), gzip, DELETE of a
# finished job (204, then 404), ?time_limit_s=, eta_s of a running job, and
# /metrics counters that survive eviction plus ringdyn_build_info.
#   conventions.sh SERVER JQ
set -u
if [ $# -ne 2 ]; then
  echo "usage: conventions.sh SERVER JQ" >&2
  exit 2
fi
SERVER=$1 JQ=$2
. "$(dirname "$0")/lib.sh"

SLOW='{"analysis":"modal","discretization":{"segments":2000},"modal":{"modes":60}}'
named() { echo "{\"analysis\":\"modal\",\"name\":\"$1\",\"discretization\":{\"segments\":$2}}"; }

start_server conv --keep-jobs 100 --static "$(dirname "$0")/../../static"
# ---- unknown query parameters: 400 naming the parameter and the allowed ones ----
req GET '/api/v1/jobs?limt=3'
expect_error "GET /api/v1/jobs?limt=3" 400 invalid_request
check "  the message names limt and the allowed parameters" \
  grep -q 'limt.*allowed: limit, status, analysis, name, cursor' "$WORK/body"
post '/api/v1/jobs?wiat=5' '{"analysis":"modal"}'
expect_error "POST /api/v1/jobs?wiat=5" 400 invalid_request
check "  the message names wiat and wait, time_limit_s" grep -q 'wiat.*wait, time_limit_s' "$WORK/body"
for path in /api/v1/health /api/v1/examples /api/v1/openapi.json /metrics /api/v1/jobs/0123456789abcdef \
            /api/v1/sweeps/0123456789abcdef; do
  req GET "$path?verbose=1"
  expect_error "GET $path?verbose=1" 400 invalid_request
done
req GET '/?job=0123456789abcdef'
same "the page keeps its own query (?job=)" "$STATUS" 200

# ---- list: filters, names, cursor pagination ----
declare -A NAME_OF
for spec in "alpha 4" "beta 5" "alpha 6" "beta 7" "alpha 8"; do
  set -- $spec
  post '/api/v1/jobs?wait=60' "$(named "$1" "$2")"
  NAME_OF[$(json /id)]=$1
  ORDER=("$(json /id)" "${ORDER[@]:-}")
done
post '/api/v1/jobs?time_limit_s=0.01&wait=60' "$SLOW"
FAILED_ID=$(json /id)
same "?time_limit_s=0.01 on a long job -> failed time_limit" "$(json /status) $(json /error/code)" \
  "failed time_limit"
check "  its message gives the job's limit" grep -q 'time limit of 0.01 s' "$WORK/body"
post '/api/v1/jobs?time_limit_s=1000000' '{"analysis":"modal"}'
expect_error "?time_limit_s above the server's cap" 400 invalid_request
post '/api/v1/jobs?time_limit_s=0' '{"analysis":"modal"}'
expect_error "?time_limit_s=0" 400 invalid_request

req GET '/api/v1/jobs?name=alpha'
same "?name=alpha: three jobs" "$(jcount /jobs)" 3
same "  every item carries name alpha" "$(json '/jobs/*/name' | sort -u)" alpha
req GET '/api/v1/jobs?status=failed'
same "?status=failed: the timed-out job only" "$(json '/jobs/*/id')" "$FAILED_ID"
req GET '/api/v1/jobs?status=succeeded&name=beta&analysis=modal'
same "?status=succeeded&name=beta&analysis=modal: two" "$(jcount /jobs)" 2
req GET '/api/v1/jobs?analysis=lift'
same "?analysis=lift: none" "$(jcount /jobs)" 0
req GET '/api/v1/jobs?status=done'
expect_error "?status=done" 400 invalid_request
req GET '/api/v1/jobs?cursor=abc'
expect_error "?cursor=abc" 400 invalid_request

# pages of 2 over the five named jobs: 2 + 2 + 1, newest first, no repeats
PAGES=() cursor=""
for page in 1 2 3 4; do
  req GET "/api/v1/jobs?status=succeeded&limit=2${cursor:+&cursor=$cursor}"
  PAGES+=($(json '/jobs/*/id'))
  cursor=$(json /next_cursor)
  [ "$cursor" = null ] && break
done
same "cursor pages: 3 pages, the last with next_cursor null" "$page $cursor" "3 null"
same "  they list the five jobs newest first, once each" "${PAGES[*]}" "${ORDER[*]:0:5}"

# ---- Idempotency-Key ----
DATA=$WORK/data
stop_server conv "$SPID"
start_server idem --data "$DATA"
BODY_A='{"analysis":"modal","discretization":{"segments":9}}'
BODY_B='{"analysis":"modal","discretization":{"segments":10}}'
post_key() { req POST "$1" -H 'Content-Type: application/json' -H "Idempotency-Key: $2" --data-binary "$3"; }
post_key '/api/v1/jobs?wait=60' key-1 "$BODY_A"
FIRST=$(json /id)
same "Idempotency-Key: a first POST makes a job" "$STATUS $(json /status)" "200 succeeded"
post_key '/api/v1/jobs?wait=60' key-1 "$BODY_A"
same "  the retried POST (same key, same body) answers the same job" "$(json /id)" "$FIRST"
same "  and says it is a replay (Idempotent-Replayed: true)" "$(header Idempotent-Replayed)" true
post_key '/api/v1/jobs' key-1 "$BODY_B"
same "  the same key with another body -> 409 idempotency_conflict" "$STATUS $(json /error/code)" \
  "409 idempotency_conflict"
check "  the message names the job the key made" grep -q "$FIRST" "$WORK/body"
post_key '/api/v1/jobs?wait=60' key-2 "$BODY_A"
check "  another key with the same body: another answer is allowed" test "$STATUS" = 200
req POST /api/v1/jobs -H 'Content-Type: application/json' -H "Idempotency-Key;" --data-binary "$BODY_A"
expect_error "  an empty Idempotency-Key" 400 invalid_request
stop_server idem "$SPID"
start_server idem2 --data "$DATA"
post_key '/api/v1/jobs?wait=60' key-1 "$BODY_A"
same "  after a restart the key still answers the same job" "$(json /id)" "$FIRST"
post_key '/api/v1/jobs' key-1 "$BODY_B"
same "  and still refuses another body" "$STATUS" 409

# ---- gzip ----
req GET "/api/v1/jobs/$FIRST"
cp "$WORK/body" "$WORK/plain.json"
req GET "/api/v1/jobs/$FIRST" -H 'Accept-Encoding: gzip'
same "Accept-Encoding: gzip -> Content-Encoding: gzip" "$(header Content-Encoding)" gzip
same "  Vary: Accept-Encoding" "$(header Vary)" Accept-Encoding
check "  it unpacks to the plain body" cmp -s <(gzip -dc "$WORK/body") "$WORK/plain.json"
check "  and is smaller" test "$(wc -c <"$WORK/body")" -lt "$(wc -c <"$WORK/plain.json")"
req GET "/api/v1/jobs/$FIRST" -H 'Accept-Encoding: gzip'
check "  a second reader gets the same bytes (compressed once per body)" \
  cmp -s <(gzip -dc "$WORK/body") "$WORK/plain.json"
post '/api/v1/jobs?wait=60' '{"analysis":"modal","modal":{"modes":60}}'
MANY=$(json /id)
req GET "/api/v1/jobs/$MANY/result.csv"
cp "$WORK/body" "$WORK/plain.csv"
req GET "/api/v1/jobs/$MANY/result.csv" -H 'Accept-Encoding: br, gzip;q=0.5'
same "CSV: gzip when accepted (q=0.5)" "$(header Content-Encoding)" gzip
check "  it unpacks to the plain CSV" cmp -s <(gzip -dc "$WORK/body") "$WORK/plain.csv"
req GET "/api/v1/jobs/$FIRST" -H 'Accept-Encoding: gzip;q=0'
same "gzip;q=0: sent as it is" "$(header Content-Encoding)" ""
req GET /api/v1/health -H 'Accept-Encoding: gzip'
same "a small body is sent as it is" "$(header Content-Encoding)" ""

# ---- DELETE ----
req DELETE "/api/v1/jobs/$FIRST"
same "DELETE of a finished job -> 204, no body" "$STATUS $(wc -c <"$WORK/body")" "204 0"
req GET "/api/v1/jobs/$FIRST"
expect_error "  then GET" 404 not_found
req DELETE "/api/v1/jobs/$FIRST"
expect_error "  a second DELETE" 404 not_found
stop_server idem2 "$SPID"
start_server idem3 --data "$DATA"
req GET "/api/v1/jobs/$FIRST"
expect_error "  the deleted job stays deleted after a restart" 404 not_found

# ---- eta_s of a running job: elapsed + eta_s vs the run time it had ----
# One run of the same size first: the server scales its cost model to the
# machine (and a sanitizer build) by the runs it has seen.
post '/api/v1/jobs?wait=120' "$SLOW"
post /api/v1/jobs '{"analysis":"modal","name":"eta","discretization":{"segments":2000},"modal":{"modes":60}}' 
SLOW_ID=$(json /id)
ETA="" POLLED=""
for i in $(seq 1 300); do
  req GET "/api/v1/jobs/$SLOW_ID"
  st=$(json /status)
  if [ "$st" = running ] && [ -z "$ETA" ] && [ "$(json /eta_s)" != null ] &&
     awk -v p="$(json /progress)" 'BEGIN { exit !(p >= 0.05) }'; then
    ETA=$(json /eta_s) POLLED=$(date +%s.%N)
  fi
  case $st in succeeded|failed|cancelled|interrupted) break ;; esac
  sleep 0.05
done
if [ -n "$ETA" ] && [ "$st" = succeeded ]; then
  started=$(date -d "$(json /started)" +%s.%N) finished=$(date -d "$(json /finished)" +%s.%N)
  # The progress of a modal run moves in steps (per Lanczos restart), so the
  # rate it implies is rough; a factor 3 either way is what a progress bar
  # needs, and a wrong formula (e.g. eta = elapsed) misses it.
  echo "# eta_s $ETA polled at $POLLED, run $started .. $finished"
  check "eta_s: elapsed + eta_s within x3 of the run time (eta $ETA)" awk -v s="$started" -v p="$POLLED" \
    -v e="$ETA" -v f="$finished" 'BEGIN { t = f - s; g = p - s + e; exit !(g > t / 3 && g < 3 * t) }'
else
  bad "eta_s: a running job with progress and eta_s" "eta '$ETA' status $st"
fi
stop_server idem3 "$SPID"

# ---- metrics survive eviction ----
start_server metrics --keep-jobs 1
for i in 1 2 3; do post '/api/v1/jobs?wait=60' "$(named m "$((3 + i))")"; done
req GET /api/v1/jobs
same "--keep-jobs 1 keeps one job" "$(jcount /jobs)" 1
req GET /metrics
check "metrics: ringdyn_jobs_total counts all 3 after eviction" \
  grep -q '^ringdyn_jobs_total{analysis="modal",outcome="succeeded"} 3$' "$WORK/body"
check "metrics: ringdyn_job_run_seconds_count by analysis and outcome" \
  grep -q '^ringdyn_job_run_seconds_count{analysis="modal",outcome="succeeded"} 3$' "$WORK/body"
req GET /api/v1/health
check "metrics: ringdyn_build_info{version=\"$(json /version)\"} 1" \
  grep -q "^ringdyn_build_info{version=\"$(json /version)\"} 1$" <(curl -sS "$BASE/metrics")
stop_server metrics "$SPID"

finish
