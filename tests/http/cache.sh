#!/usr/bin/env bash
# The result cache and inline runs (issue 14 items 2 and 3) against a live
# server: a scene that runs the same computation as a finished job (other key
# order, spacing, spelling of numbers, defaults written out) is answered by
# that job, marked cached, with the same result; Cache-Control: no-cache
# bypasses it; another value misses; the cache outlives a restart; small
# jobs that wait run inline, others queue.
#   cache.sh SERVER JQ
set -u
if [ $# -ne 2 ]; then
  echo "usage: cache.sh SERVER JQ" >&2
  exit 2
fi
SERVER=$1 JQ=$2
. "$(dirname "$0")/lib.sh"

# cpost PATH BODY [CURL ARGS]: a POST the cache may answer (post() bypasses it)
cpost() { local p=$1 b=$2; shift 2; req POST "$p" -H 'Content-Type: application/json' --data-binary "$b" "$@"; }
metric() { curl -sS "$BASE/metrics" | grep "^$1 " | awk '{print $2}'; }

DATA=$WORK/data
start_server cache --data "$DATA"
SCENE='{"analysis":"modal","name":"c1","discretization":{"segments":12}}'
# The same computation written differently: keys reordered, spaces, a
# default written out (modes 6... as the echoed scene shows) and 12 as 1.2e1.
cpost '/api/v1/jobs?wait=60' "$SCENE"
FIRST=$(json /id)
cp "$WORK/body" "$WORK/first.json"
same "a first POST: computed (X-Ringdyn-Cache: miss)" "$STATUS $(header X-Ringdyn-Cache) $(json /cached)" "200 miss "
MODES=$(json /result/scene/modal/modes)
check "  the echoed scene gives the default modes" test -n "$MODES"
SAME="{ \"discretization\" : {\"segments\": 1.2e1}, \"modal\": {\"modes\": $MODES}, \"name\": \"c1\", \"analysis\": \"modal\" }"
cpost '/api/v1/jobs?wait=60' "$SAME"
same "the same scene written differently: a hit" "$STATUS $(header X-Ringdyn-Cache) $(json /cached)" "200 hit true"
same "  answered by the first job" "$(json /id)" "$FIRST"
same "  with the same result" "$(json /result)" "$("$JQ" /result "$WORK/first.json")"
cpost '/api/v1/jobs' "$SAME"
same "  without ?wait: 202 as before, the job final and cached" "$STATUS $(json /status) $(json /cached)" \
  "202 succeeded true"
check "  Location names the first job" test "$(header Location)" = "/api/v1/jobs/$FIRST"
cpost '/api/v1/jobs?wait=60' "$SAME" -H 'Accept-Encoding: gzip'
gzip -dc "$WORK/body" >"$WORK/unzipped" 2>/dev/null
same "  gzipped: still marked cached" "$(header Content-Encoding) $("$JQ" /cached "$WORK/unzipped")" "gzip true"
req GET "/api/v1/jobs/$FIRST"
same "GET of the job itself is not marked cached" "$(json /cached)" ""

cpost '/api/v1/jobs?wait=60' "$SCENE" -H 'Cache-Control: no-cache'
same "Cache-Control: no-cache: computed again" "$STATUS $(header X-Ringdyn-Cache) $(json /cached)" "200 bypass "
SECOND=$(json /id)
check "  as a new job" test "$SECOND" != "$FIRST"
same "  with the same frequencies (results are deterministic)" \
  "$(json '/result/modes/*/frequency_hz')" "$("$JQ" '/result/modes/*/frequency_hz' "$WORK/first.json")"
cpost '/api/v1/jobs?wait=60' '{"analysis":"modal","name":"c1","discretization":{"segments":13}}'
same "another value (segments 13): a miss" "$(header X-Ringdyn-Cache)" miss
cpost '/api/v1/jobs?wait=60' '{"analysis":"modal","name":"c2","discretization":{"segments":12}}'
same "another name (the result echoes it): a miss" "$(header X-Ringdyn-Cache)" miss

same "metrics: hits counted" "$(metric 'ringdyn_result_cache_total{result="hit"}')" 3
same "metrics: misses counted" "$(metric 'ringdyn_result_cache_total{result="miss"}')" 3
same "metrics: bypasses counted" "$(metric 'ringdyn_result_cache_total{result="bypass"}')" 1

# ---- inline runs: a small job that waits runs on the HTTP thread ----
before=$(metric ringdyn_inline_runs_total)
cpost '/api/v1/jobs?wait=60' '{"analysis":"modal","discretization":{"segments":8}}'
same "a small modal job with ?wait: succeeded" "$STATUS $(json /status)" "200 succeeded"
same "  ran inline" "$(metric ringdyn_inline_runs_total)" "$((before + 1))"
cpost '/api/v1/jobs' '{"analysis":"modal","discretization":{"segments":9}}'
same "the same size without ?wait: queued for a worker, not inline" "$(metric ringdyn_inline_runs_total)" \
  "$((before + 1))"
cpost '/api/v1/jobs?wait=60' '{"analysis":"modal","discretization":{"segments":2000},"modal":{"modes":60}}'
same "a large modal job with ?wait: not inline" "$STATUS $(metric ringdyn_inline_runs_total)" "200 $((before + 1))"
cpost '/api/v1/jobs?wait=60' '{"analysis":"pretension"}'
same "an analysis without a cost model: not inline" "$STATUS $(metric ringdyn_inline_runs_total)" \
  "200 $((before + 1))"

# ---- persisted: the cache outlives a restart ----
stop_server cache "$SPID"
start_server cache2 --data "$DATA"
cpost '/api/v1/jobs?wait=60' "$SAME"
# Two kept jobs computed this scene (the first and the no-cache one); the
# newest answers.
same "after a restart: still a hit, on the newest job of that scene" \
  "$(header X-Ringdyn-Cache) $(json /id)" "hit $SECOND"
req DELETE "/api/v1/jobs/$SECOND"
cpost '/api/v1/jobs?wait=60' "$SAME"
same "  deleted, the other one answers" "$(header X-Ringdyn-Cache) $(json /id)" "hit $FIRST"
req DELETE "/api/v1/jobs/$FIRST"
cpost '/api/v1/jobs?wait=60' "$SAME"
same "  both deleted: a miss" "$(header X-Ringdyn-Cache)" miss
stop_server cache2 "$SPID"

finish
