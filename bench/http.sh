#!/usr/bin/env bash
# The server under load: CLIENTS concurrent clients (default 200) for DURATION seconds
# (default 60), each submitting {"analysis":"modal"} with ?wait=60 again and
# again, against a Release ringdyn-server with its defaults and a job store on
# disk; RUNS runs (default 3), each on a fresh server, then the medians.
#   bench/http.sh [build-dir]     (default: build-rel, Release)
#   CLIENTS=200 DURATION=60 RUNS=3 bench/http.sh
set -euo pipefail
cd "$(dirname "$0")/.."
b=${1:-build-rel}
CLIENTS=${CLIENTS:-200} DURATION=${DURATION:-60} RUNS=${RUNS:-3}
cmake -S . -B "$b" -DCMAKE_BUILD_TYPE=Release -DRINGDYN_TESTS=OFF >/dev/null
cmake --build "$b" -j2 --target ringdyn-server bench_http >/dev/null
WORK=$(mktemp -d "${TMPDIR:-/tmp}/ringdyn-bench.XXXXXX")
SPID=""
trap '[ -n "$SPID" ] && kill "$SPID" 2>/dev/null; rm -rf "$WORK"' EXIT

for run in $(seq 1 "$RUNS"); do
  rm -rf "$WORK/data" "$WORK/out" # out: the '>' below truncates it only once the server has forked
  "$b/server/ringdyn-server" --port 0 --data "$WORK/data" >"$WORK/out" 2>"$WORK/err" &
  SPID=$!
  for _ in $(seq 1 100); do grep -q listening "$WORK/out" 2>/dev/null && break; sleep 0.1; done
  PORT=$(grep -o '[0-9]*$' "$WORK/out")
  "$b/bench/bench_http" "$PORT" "$CLIENTS" "$DURATION" "$SPID" | tee -a "$WORK/runs"
  kill -TERM "$SPID"
  wait "$SPID" || true
  SPID=""
done
# the median of each field over the runs
printf 'median of %d runs:' "$RUNS"
for key in $(head -n 1 "$WORK/runs" | tr ' ' '\n' | cut -d= -f1); do
  printf ' %s=%s' "$key" "$(tr ' ' '\n' <"$WORK/runs" | sed -n "s/^$key=//p" | sort -g |
                            awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')"
done
echo
