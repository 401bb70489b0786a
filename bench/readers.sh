#!/usr/bin/env bash
# Memory of slow readers: a Release server computes one lift result of about
# 30 MB, then READERS clients (default 60) each request it and never read;
# prints the server's RSS before and after (one shared copy: the growth is
# the connections' buffers, not READERS copies of the result).
#   bench/readers.sh [build-dir]     (default: build-rel, Release)
set -euo pipefail
cd "$(dirname "$0")/.."
b=${1:-build-rel}
READERS=${READERS:-60}
cmake -S . -B "$b" -DCMAKE_BUILD_TYPE=Release -DRINGDYN_TESTS=OFF >/dev/null
cmake --build "$b" -j2 --target ringdyn-server >/dev/null
WORK=$(mktemp -d "${TMPDIR:-/tmp}/ringdyn-readers.XXXXXX")
"$b/server/ringdyn-server" --port 0 --data "$WORK/data" >"$WORK/out" 2>"$WORK/err" &
SPID=$!
trap 'kill "$SPID" 2>/dev/null; rm -rf "$WORK"' EXIT
for _ in $(seq 1 100); do grep -q listening "$WORK/out" && break; sleep 0.1; done
PORT=$(grep -o '[0-9]*$' "$WORK/out")
# 20001 samples x 100 segments: the largest lift result the limits allow
SCENE='{"analysis":"lift","discretization":{"segments":100},"engine":{"cycles":5},"output":{"step_deg":0.2},"numerics":{"error_estimate":false}}'
curl -sS -o "$WORK/job" -H 'Content-Type: application/json' -d "$SCENE" \
  "http://127.0.0.1:$PORT/api/v1/jobs?wait=300"
ID=$(sed -n 's/^{"id":"\([0-9a-f]*\)".*/\1/p' "$WORK/job")
echo "result: $(wc -c <"$WORK/job") bytes"
rss() { awk '/^VmRSS/ { print $2 }' "/proc/$SPID/status"; }
curl -sS -o /dev/null "http://127.0.0.1:$PORT/api/v1/jobs/$ID"
R0=$(rss)
FDS=()
for _ in $(seq 1 "$READERS"); do
  exec {fd}<>"/dev/tcp/127.0.0.1/$PORT"
  printf 'GET /api/v1/jobs/%s HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n' "$ID" >&"$fd"
  FDS+=("$fd")
done
sleep 3
R1=$(rss)
echo "$READERS non-reading clients: RSS $R0 kB -> $R1 kB (+$(( (R1 - R0) / 1024 )) MB)"
for fd in "${FDS[@]}"; do exec {fd}>&-; done
