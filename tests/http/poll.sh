#!/usr/bin/env bash
# GET /api/v1/jobs/{id}?wait=S (the long poll), ETag / If-None-Match on
# finished jobs and their CSV, and the CSV's Content-Disposition, against a
# live server on 127.0.0.1.
#   poll.sh SERVER JQ
set -u
if [ $# -ne 2 ]; then
  echo "usage: poll.sh SERVER JQ" >&2
  exit 2
fi
SERVER=$1 JQ=$2
. "$(dirname "$0")/lib.sh"

# about 3 s under the sanitizers, 1 s without; a small result (50 kB), so
# that sending it to 25 clients at once takes no time to speak of
SLOW='{"analysis":"lift","engine":{"cycles":3},"numerics":{"model":"full"},"output":{"step_deg":30}}'
now() { date +%s.%N; }
# within A B MAX: |A - B| <= MAX
within() { awk -v a="$1" -v b="$2" -v m="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= m) }'; }

# Two event-loop threads, so that 24 waiting polls would starve the server
# if each held a thread.
start_server poll --http-threads 2
POLL_PID=$SPID

# ---- the long poll ----
post '/api/v1/jobs' "$SLOW"
ID=$(json /id)
T0=$(now)
req GET "/api/v1/jobs/$ID?wait=0.3"
T1=$(now)
same "?wait=0.3 on a running job -> 200" "$STATUS" 200
check "  with its current state (queued or running)" grep -Eq '"status":"(queued|running)"' "$WORK/body"
check "  after its wait, not at once (0.25..2 s: $(awk -v a="$T0" -v b="$T1" 'BEGIN { print b - a }') s)" \
  awk -v a="$T0" -v b="$T1" 'BEGIN { exit !(b - a >= 0.25 && b - a < 2) }'
same "  no ETag on a job still running" "$(header ETag)" ""

# many clients waiting hold no thread: the server answers others meanwhile
POLLERS=()
for i in $(seq 1 24); do
  curl -sS --max-time 90 -o "$WORK/poll$i" -w '%{http_code}\n' "$BASE/api/v1/jobs/$ID?wait=60" \
    >"$WORK/poll$i.status" 2>/dev/null &
  POLLERS+=($!)
done
sleep 0.3
T0=$(now)
req GET /api/v1/health
T1=$(now)
same "24 long polls waiting: health still answers" "$STATUS" 200
check "  within 1 s" within "$T1" "$T0" 1

T0=$(now)
req GET "/api/v1/jobs/$ID?wait=60"
T1=$(now)
same "?wait=60 -> 200 once the job ends" "$STATUS $(json /status)" "200 succeeded"
FIN=$(date -d "$(json /finished)" +%s.%N)
check "  answered within 0.5 s of the job's end, not after its wait ($(awk -v a="$FIN" -v b="$T1" 'BEGIN { print b - a }') s)" \
  within "$T1" "$FIN" 0.5
wait "${POLLERS[@]}"
GOT=$(cat "$WORK"/poll*.status | sort | uniq -c | awk '{ print $1 " x " $2 }')
same "  the 24 other polls: 200 each" "$GOT" "24 x 200"
check "  each with the finished job" bash -c "grep -l '\"status\":\"succeeded\"' $WORK/poll[0-9]* | wc -l | grep -qx 24"

T0=$(now)
req GET "/api/v1/jobs/$ID?wait=30"
T1=$(now)
same "?wait=30 on a finished job -> 200 at once" "$STATUS $(json /status)" "200 succeeded"
check "  within 0.5 s" within "$T1" "$T0" 0.5
T1=$(now)
req GET "/api/v1/jobs/0123456789abcdef?wait=30"
T2=$(now)
expect_error "?wait=30 on an unknown job" 404 not_found
check "  at once" within "$T2" "$T1" 0.5
for w in 61 -1 abc 1e1 ''; do
  req GET "/api/v1/jobs/$ID?wait=$w"
  expect_error "?wait=$w" 400 invalid_request
  check "  names wait and its range 0 to 60" grep -q 'parameter wait must be a number of seconds from 0 to 60' "$WORK/body"
done
req DELETE "/api/v1/jobs/$ID?wait=1"
expect_error "DELETE ?wait=1 (no long poll there)" 400 invalid_request

# ---- ETag / If-None-Match on the finished job ----
req GET "/api/v1/jobs/$ID"
ETAG=$(header ETag)
check "a finished job has an ETag (weak, quoted): $ETAG" bash -c "[[ '$ETAG' =~ ^W/\\\"[0-9a-f]{32}\\\"$ ]]"
same "  Cache-Control: no-cache (keep it, revalidate)" "$(header Cache-Control)" no-cache
rm -f "$WORK/body" # curl writes no file for an empty body
req GET "/api/v1/jobs/$ID" -H "If-None-Match: $ETAG"
same "If-None-Match: the ETag -> 304" "$STATUS" 304
same "  no body" "$(cat "$WORK/body" 2>/dev/null | wc -c)" 0
same "  the ETag again" "$(header ETag)" "$ETAG"
req GET "/api/v1/jobs/$ID" -H "If-None-Match: \"other\", ${ETAG#W/}" -H 'Accept-Encoding: gzip'
same "If-None-Match: a list holding it (strong form), gzip asked -> 304" "$STATUS" 304
req GET "/api/v1/jobs/$ID" -H 'If-None-Match: *'
same "If-None-Match: * -> 304" "$STATUS" 304
req GET "/api/v1/jobs/$ID" -H 'If-None-Match: W/"0123"'
same "If-None-Match: another tag -> 200" "$STATUS" 200
req GET "/api/v1/jobs/$ID" -H 'Accept-Encoding: gzip'
same "  the gzip of the job carries the same (weak) ETag" "$(header Content-Encoding) $(header ETag)" "gzip $ETAG"
req HEAD "/api/v1/jobs/$ID" -H "If-None-Match: $ETAG"
same "HEAD with the ETag -> 304" "$STATUS" 304
req GET "/api/v1/jobs/$ID?wait=5" -H "If-None-Match: $ETAG"
same "a long poll of a finished job with its ETag -> 304 at once" "$STATUS" 304
post '/api/v1/jobs?wait=60' '{"analysis":"modal"}'
OTHER=$(json /id)
req GET "/api/v1/jobs/$OTHER" -H "If-None-Match: $ETAG"
same "another job with the first one's ETag -> 200" "$STATUS" 200
check "  its own ETag differs" test "$(header ETag)" != "$ETAG"

# ---- the CSV: Content-Disposition, ETag ----
req GET "/api/v1/jobs/$ID/result.csv"
same "result.csv -> 200 text/csv" "$STATUS $(header Content-Type)" "200 text/csv; charset=utf-8"
same "  saved as ringdyn-<analysis>-<id>.csv" "$(header Content-Disposition)" \
  "attachment; filename=\"ringdyn-lift-$ID.csv\""
CSV_ETAG=$(header ETag)
check "  with an ETag of its own: $CSV_ETAG" bash -c "[[ '$CSV_ETAG' =~ ^W/\\\"[0-9a-f]{32}\\\"$ && '$CSV_ETAG' != '$ETAG' ]]"
rm -f "$WORK/body"
req GET "/api/v1/jobs/$ID/result.csv" -H "If-None-Match: $CSV_ETAG"
same "result.csv with its ETag -> 304" "$STATUS $(cat "$WORK/body" 2>/dev/null | wc -c)" "304 0"
req GET "/api/v1/jobs/$ID/result.csv" -H "If-None-Match: $ETAG"
same "result.csv with the JSON's ETag -> 200" "$STATUS" 200

stop_server poll "$POLL_PID"
finish
