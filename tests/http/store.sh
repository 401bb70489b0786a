#!/usr/bin/env bash
# The job store over real HTTP: finished jobs survive a restart (SIGTERM and
# kill -9, the second recovered from SQLite's WAL), jobs left running or
# queued come back `interrupted`, a client waiting with ?wait at SIGTERM gets
# a final job and the server exits within 1 s, retention by count, and 60
# clients that do not read a 1.2 MB result share one copy of it.
#
#   store.sh SERVER_BINARY RD_JSONQ
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 SERVER RD_JSONQ" >&2
  exit 2
fi
SERVER=$1 JQ=$2
. "$(dirname "$0")/lib.sh"

MODAL='{"analysis":"modal"}'
SLOW='{"analysis":"modal","discretization":{"segments":2000},"modal":{"modes":60}}'
DATA=$WORK/data

# submit_done N: N modal jobs with ?wait; their ids in IDS, bodies in $WORK/job-ID
submit_done() {
  local i
  for i in $(seq 1 "$1"); do
    post '/api/v1/jobs?wait=60' "$MODAL"
    IDS+=("$(json /id)")
    cp "$WORK/body" "$WORK/job-$(json /id)"
  done
}
# same_after NAME: every job in IDS is served byte for byte as before
same_after() {
  local id n=0
  for id in "${IDS[@]}"; do
    req GET "/api/v1/jobs/$id"
    if [ "$STATUS" = 200 ] && cmp -s "$WORK/body" "$WORK/job-$id"; then n=$((n + 1)); fi
  done
  same "$1: ${#IDS[@]} finished jobs served as before" "$n" "${#IDS[@]}"
}
wait_running() { # ID: until the job runs (10 s at most)
  local _
  for _ in $(seq 1 100); do
    req GET "/api/v1/jobs/$1"
    [ "$(json /status)" = running ] && return 0
    sleep 0.1
  done
  return 1
}
kill9() { kill -KILL "$1"; wait "$1" 2>/dev/null || true; }

# ---- restart after SIGTERM --------------------------------------------------------
IDS=()
start_server S1 --data "$DATA"
S1=$SPID
submit_done 3
same "3 jobs succeeded" "$(json /status)" succeeded
check "the store file exists" test -s "$DATA/jobs.sqlite3"
stop_server S1 "$S1"
start_server S2 --data "$DATA"
S2=$SPID
same_after "SIGTERM and restart"
rc=0
timeout 20 "$SERVER" --port 0 --data "$DATA" >"$WORK/second.out" 2>"$WORK/second.err" || rc=$?
check "a second server on the same --data is refused" \
  test "$rc" -ne 0 -a "$rc" -ne 124 -a -n "$(grep 'in use by another ringdyn-server' "$WORK/second.err")"
req GET /api/v1/jobs
same "the list after the restart: newest first" "$(json /jobs/0/id)" "${IDS[2]}"
req GET "/api/v1/jobs/${IDS[0]}/result.csv"
same "result.csv after the restart" "$STATUS" 200
check "result.csv has the mode table" grep -q '^mode,kind,frequency_hz' "$WORK/body"

# ---- restart after kill -9 (WAL recovery) ----------------------------------------
submit_done 2
check "the WAL holds the new jobs" test -s "$DATA/jobs.sqlite3-wal"
kill9 "$S2"
start_server S3 --data "$DATA"
S3=$SPID
same_after "kill -9 and restart"

# ---- a running and a queued job at kill -9 ---------------------------------------
stop_server S3 "$S3"
start_server S4 --data "$DATA" --threads 1
S4=$SPID
post /api/v1/jobs "$SLOW"
RUN_ID=$(json /id)
post /api/v1/jobs "$SLOW"
QUEUE_ID=$(json /id)
check "a slow job runs" wait_running "$RUN_ID"
kill9 "$S4"
start_server S5 --data "$DATA" --threads 1
S5=$SPID
req GET "/api/v1/jobs/$RUN_ID"
same "running at kill -9 -> interrupted" "$STATUS $(json /status) $(json /error/code)" "200 interrupted interrupted"
check "its message says it was running" grep -q 'was running' "$WORK/body"
req GET "/api/v1/jobs/$QUEUE_ID"
same "queued at kill -9 -> interrupted" "$(json /status)" interrupted
check "the log counts them" grep -q '1 queued and 1 running jobs of the last run are marked interrupted' "$WORK/S5.err"
same_after "after a crash with jobs in flight"

# ---- SIGTERM while a client waits: a final answer, exit within 1 s ---------------
curl -sS --max-time 60 -o "$WORK/waited" -w '%{http_code}' -H 'Content-Type: application/json' \
  --data-binary "$SLOW" "$BASE/api/v1/jobs?wait=300" >"$WORK/waited.status" 2>/dev/null &
WAITER=$!
for _ in $(seq 1 100); do
  req GET '/api/v1/jobs?limit=1'
  [ "$(json /jobs/0/status)" = running ] && break
  sleep 0.1
done
WAIT_ID=$(json /jobs/0/id)
same "a job runs and a client waits for it" "$(json /jobs/0/status)" running
T0=$(date +%s.%N)
kill -TERM "$S5"
for _ in $(seq 1 300); do kill -0 "$S5" 2>/dev/null || break; sleep 0.02; done
T1=$(date +%s.%N)
wait "$S5" || true
wait "$WAITER" || true
STOP_S=$(awk -v a="$T0" -v b="$T1" 'BEGIN { printf "%.2f", b - a }')
echo "# SIGTERM with a running job and a waiting client: exit after $STOP_S s"
check "SIGTERM drains within 1 s" awk -v s="$STOP_S" 'BEGIN { exit !(s < 1.0) }'
same "the waiting client gets 200" "$(cat "$WORK/waited.status")" 200
check "with a final job (interrupted or succeeded)" grep -qE '"status":"(interrupted|succeeded)"' "$WORK/waited"
start_server S6 --data "$DATA"
S6=$SPID
req GET "/api/v1/jobs/$WAIT_ID"
same "after the restart it is as the client was told" "$(json /status)" "$(json /status "$WORK/waited")"
same_after "after SIGTERM with a job in flight"
stop_server S6 "$S6"

# ---- retention by count, in the store -------------------------------------------
IDS=()
start_server R1 --data "$WORK/keep" --keep-jobs 2
R1=$SPID
submit_done 3
req GET "/api/v1/jobs/${IDS[0]}"
expect_error "--keep-jobs 2: the oldest of 3 is dropped" 404 not_found
stop_server R1 "$R1"
start_server R2 --data "$WORK/keep" --keep-jobs 2
R2=$SPID
req GET /api/v1/jobs
same "--keep-jobs 2: the store holds 2 after a restart" "$("$JQ" -n /jobs "$WORK/body")" 2
IDS=("${IDS[@]:1}")
same_after "--keep-jobs 2"
stop_server R2 "$R2"

# ---- 60 clients that do not read a >1 MB result (40 modes: the split Lanczos solve writes the other
# kind's shape components as exact zeros, so 20 modes no longer reach 1 MB) -----------------------------------
# One shared copy: the server grows by the connections' buffers, not by 60
# copies of the result (72 MB).  Bound 20 MB: 60 connections x MHD's 32 kB
# pool plus allocator slack, well under one tenth of the copies.
start_server M --data "$WORK/mem"
M_PID=$SPID
BIG='{"analysis": "modal", "discretization": {"segments": 1000}, "modal": {"modes": 40, "error_estimate": false}}'
post '/api/v1/jobs?wait=60' "$BIG"
BIG_ID=$(json /id)
BIG_BYTES=$(wc -c <"$WORK/body")
echo "# the result is $BIG_BYTES bytes"
check "the result is over 1 MB" test "$BIG_BYTES" -gt 1000000
rss_kb() { awk '/^VmRSS/ { print $2 }' "/proc/$1/status"; }
req GET "/api/v1/jobs/$BIG_ID" # warm: the first read allocates what every read needs
RSS0=$(rss_kb "$M_PID")
PORT=${BASE##*:}
FDS=()
for i in $(seq 1 60); do
  exec {fd}<>"/dev/tcp/127.0.0.1/$PORT"
  printf 'GET /api/v1/jobs/%s HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n' "$BIG_ID" >&"$fd"
  FDS+=("$fd")
done
sleep 2
RSS1=$(rss_kb "$M_PID")
GROWTH_MB=$(awk -v a="$RSS0" -v b="$RSS1" 'BEGIN { printf "%.1f", (b - a) / 1024 }')
echo "# 60 non-reading clients of a $BIG_BYTES-byte result: RSS $RSS0 kB -> $RSS1 kB (+$GROWTH_MB MB)"
check "60 non-reading clients add under 20 MB" awk -v g="$GROWTH_MB" 'BEGIN { exit !(g < 20) }'
req GET /api/v1/health
same "the server still answers" "$STATUS" 200
for fd in "${FDS[@]}"; do exec {fd}>&-; done
stop_server M "$M_PID"

finish
