#!/usr/bin/env bash
# Memory under bursts and many readers (issue 45), read from the server's
# /proc/PID/status (memprobe.py):
# - after bursts of 32 parallel 1 MiB POSTs, once the server is idle, VmRSS
#   comes back within BURST_MB of its value before them (up to 0.3.15 it
#   stayed up: 93-115 MB after two such bursts of 64 from 9 MB; ~540 MB in
#   the issue's test);
# - the CSV of a 21 MB result, plain and gzipped, and a gzipped result cache
#   hit on its 41 MB JSON, fetched by N connections that do not read: the
#   server's peak RSS grows by less than HELD_MB (one copy shared by all;
#   up to 0.3.15 each connection made and held its own: +190 MB for 16
#   CSVs), and every connection gets the same bytes as a lone reader.
#   memory.sh SERVER_BINARY RD_JSONQ
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 SERVER RD_JSONQ" >&2
  exit 2
fi
SERVER=$1 JQ=$2
. "$(dirname "$0")/lib.sh"
PROBE="$(dirname "$0")/memprobe.py"
BURST_MB=32 # four HTTP threads' arenas may keep 8 MiB each (main.c)
HELD_MB=8
N=16

if [ ! -r /proc/self/status ]; then
  echo "# no /proc: nothing to measure"
  finish
  exit
fi
start_server M
M_PID=$SPID
PORT=${BASE##*:}
rss() { awk '/^VmRSS:/ { printf "%.1f", $2 / 1024 }' "/proc/$M_PID/status"; }
field() { python3 -c 'import json, sys; print(json.loads(sys.argv[1])[sys.argv[2]])' "$1" "$2"; }

# ---- bursts of 1 MiB bodies ----
post '/api/v1/jobs?wait=10' '{"analysis":"modal"}' # warm: the first job's allocations
sleep 1.5                                          # idle: the server trims
BEFORE=$(rss)
for i in 1 2 3; do
  OUT=$(python3 "$PROBE" burst "$PORT" "$M_PID" 32 1048000)
  echo "# burst $i: $OUT"
done
AFTER=$(field "$OUT" rss_after_mb)
same "bursts of 1 MiB bodies: every one refused 422 (parsed whole)" "$(field "$OUT" statuses)" "[422]"
echo "# VmRSS before the bursts $BEFORE MB, after them, idle, $AFTER MB"
if grep -q __asan_init "$SERVER"; then # the sanitizer's allocator is not glibc's: not bounded here
  echo "# address sanitizer build: VmRSS after the bursts not checked"
else
  check "VmRSS back within $BURST_MB MB of its value before the bursts ($BEFORE -> $AFTER MB)" \
    awk -v a="$AFTER" -v b="$BEFORE" -v m="$BURST_MB" 'BEGIN { exit !(a - b < m) }'
fi

# ---- a large result read by many connections at once ----
# 200000 samples of the rigid ring: 21 MB of CSV (3.2 MB gzipped), 41 MB of JSON
SCENE='{"analysis":"lift","discretization":{"segments":4},"engine":{"cycles":1},"output":{"step_deg":0.004}}'
req POST '/api/v1/jobs?wait=120' -H 'Content-Type: application/json' --data-binary "$SCENE"
same "the large job -> 200 succeeded" "$STATUS $(json /status)" "200 succeeded"
ID=$(json /id)
req GET "/api/v1/jobs/$ID/result.csv"
cp "$WORK/body" "$WORK/plain.csv"
CSV_SHA=$(sha256sum <"$WORK/plain.csv" | cut -d ' ' -f 1)
CSV_BYTES=$(wc -c <"$WORK/plain.csv")
echo "# CSV: $CSV_BYTES bytes"
req GET "/api/v1/jobs/$ID/result.csv" -H 'Accept-Encoding: gzip'
same "the gzipped CSV is the CSV" "$(header Content-Encoding) $(gzip -dc <"$WORK/body" | sha256sum | cut -d ' ' -f 1)" "gzip $CSV_SHA"
# the cache hit, gzipped: the job with "cached":true first
req POST '/api/v1/jobs?wait=120' -H 'Content-Type: application/json' -H 'Accept-Encoding: gzip' \
  --data-binary "$SCENE"
same "a repeated POST, gzip: a cache hit" "$STATUS $(header X-Ringdyn-Cache) $(header Content-Encoding)" "200 hit gzip"
HIT_SHA=$(gzip -dc <"$WORK/body" | sha256sum | cut -d ' ' -f 1)
gzip -dc <"$WORK/body" >"$WORK/hit.json"
same "the hit starts with \"cached\":true" "$(head -c 15 "$WORK/hit.json")" '{"cached":true,'

printf 'GET /api/v1/jobs/%s/result.csv HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n' "$ID" >"$WORK/plain.req"
printf 'GET /api/v1/jobs/%s/result.csv HTTP/1.1\r\nHost: 127.0.0.1\r\nAccept-Encoding: gzip\r\n\r\n' \
  "$ID" >"$WORK/gzip.req"
printf 'POST /api/v1/jobs?wait=60 HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nAccept-Encoding: gzip\r\nContent-Length: %d\r\n\r\n%s' \
  "${#SCENE}" "$SCENE" >"$WORK/hit.req"
for what in plain:$CSV_SHA gzip:$CSV_SHA hit:$HIT_SHA; do
  name=${what%%:*} sha=${what#*:}
  OUT=$(python3 "$PROBE" held "$PORT" "$M_PID" "$N" "$WORK/$name.req" "$sha")
  echo "# $name x $N: $OUT"
  same "$name: $N held answers, each the lone reader's bytes" \
    "$(field "$OUT" statuses) $(field "$OUT" bodies_ok)" "[200] True"
  check "$name: the server's peak RSS grows < $HELD_MB MB for $N readers ($(field "$OUT" peak_growth_mb) MB)" \
    awk -v g="$(field "$OUT" peak_growth_mb)" -v m="$HELD_MB" 'BEGIN { exit !(g < m) }'
done
stop_server M "$M_PID"
finish
