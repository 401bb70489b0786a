#!/usr/bin/env bash
# Server instructions per computed small job (issue 14), independent of the
# machine's load: a Release ringdyn-server under valgrind's callgrind, with a
# job store on disk, serves the default modal job (n = 20, 6 modes, with its
# error estimate) to CLIENTS keep-alive clients (default 4) sending
# Cache-Control: no-cache for SECONDS (default 40); then the server's
# user-space instructions (all threads, start-up included: ~0.1 % at 300
# jobs) divided by the jobs answered.  Kernel work (socket, store writes,
# page faults) is not counted: bench/http_small.sh's server CPU has it.
#   bench/http_callgrind.sh [build-dir]      (default: build-rel, Release)
#   CLIENTS=4 SECONDS_=40 bench/http_callgrind.sh
set -euo pipefail
cd "$(dirname "$0")/.."
b=${1:-build-rel}
CLIENTS=${CLIENTS:-4} SECONDS_=${SECONDS_:-40}
SCENE=${SCENE:-'{"analysis":"modal"}'}
command -v valgrind >/dev/null || { echo "http_callgrind.sh: valgrind is not installed" >&2; exit 2; }
cmake -S . -B "$b" -DCMAKE_BUILD_TYPE=Release -DRINGDYN_TESTS=OFF >/dev/null
cmake --build "$b" -j2 --target ringdyn-server bench_http >/dev/null
WORK=$(mktemp -d "${TMPDIR:-/tmp}/ringdyn-cg.XXXXXX")
SPID=""
trap '[ -n "$SPID" ] && kill "$SPID" 2>/dev/null; rm -rf "$WORK"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$WORK/cg" "$b/server/ringdyn-server" --port 0 \
  --data "$WORK/data" >"$WORK/out" 2>"$WORK/err" &
SPID=$!
for _ in $(seq 1 600); do grep -q listening "$WORK/out" 2>/dev/null && break; sleep 0.1; done
PORT=$(grep -o '[0-9]*$' "$WORK/out")
line=$("$b/bench/bench_http" "$PORT" "$CLIENTS" "$SECONDS_" "$SPID" "$SCENE" keepalive-nocache)
kill -TERM "$SPID"
wait "$SPID" || true
SPID=""
jobs=$(grep -o 'ok_200=[0-9]*' <<<"$line" | cut -d= -f2)
total=$(sed -n 's/^totals: *//p; s/^summary: *//p' "$WORK/cg" | head -1)
echo "$line"
awk -v t="$total" -v n="$jobs" 'BEGIN { printf "server instructions: %.0f in all, %d jobs, %.2f M per job\n", t, n, t / n / 1e6 }'
