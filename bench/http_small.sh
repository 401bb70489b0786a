#!/usr/bin/env bash
# Small jobs over HTTP (issue 14): the default modal job (n = 20 segments,
# 6 modes, with its error estimate) submitted with ?wait by CLIENTS
# keep-alive clients (default 8), against a Release ringdyn-server with its
# defaults and a job store on disk; twice per run: every submission computed
# (Cache-Control: no-cache) and every submission but the first answered by
# the result cache.  RUNS runs (default 3), each on a fresh server, then the
# medians.  The clients run on the same machine as the server.
#   bench/http_small.sh [build-dir]     (default: build-rel, Release)
#   CLIENTS=8 DURATION=10 RUNS=3 bench/http_small.sh
set -euo pipefail
cd "$(dirname "$0")/.."
b=${1:-build-rel}
CLIENTS=${CLIENTS:-8} DURATION=${DURATION:-10} RUNS=${RUNS:-3}
SCENE=${SCENE:-'{"analysis":"modal"}'}
cmake -S . -B "$b" -DCMAKE_BUILD_TYPE=Release -DRINGDYN_TESTS=OFF >/dev/null
cmake --build "$b" -j2 --target ringdyn-server bench_http >/dev/null
WORK=$(mktemp -d "${TMPDIR:-/tmp}/ringdyn-bench.XXXXXX")
SPID=""
trap '[ -n "$SPID" ] && kill "$SPID" 2>/dev/null; rm -rf "$WORK"' EXIT

median() { # median KEY FILE
  tr ' ' '\n' <"$2" | sed -n "s/^$1=//p" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'
}
for run in $(seq 1 "$RUNS"); do
  for mode in keepalive-nocache keepalive; do
    rm -rf "$WORK/data" "$WORK/out" # out: the '>' below truncates it only once the server has forked
    "$b/server/ringdyn-server" --port 0 --data "$WORK/data" >"$WORK/out" 2>"$WORK/err" &
    SPID=$!
    for _ in $(seq 1 100); do grep -q listening "$WORK/out" 2>/dev/null && break; sleep 0.1; done
    PORT=$(grep -o '[0-9]*$' "$WORK/out")
    echo "$mode: $("$b/bench/bench_http" "$PORT" "$CLIENTS" "$DURATION" "$SPID" "$SCENE" "$mode" |
                     tee -a "$WORK/$mode")"
    if ! kill -0 "$SPID" 2>/dev/null; then echo "the server died; its stderr:" >&2; cat "$WORK/err" >&2; fi
    kill -TERM "$SPID" 2>/dev/null || true
    wait "$SPID" || true
    SPID=""
  done
done
for mode in keepalive-nocache keepalive; do
  printf 'median of %d runs, %s:' "$RUNS" "$mode"
  for key in jobs_per_s p50_ms p99_ms ok_200 other failed server_cpu_s jobs_per_server_cpu_s; do printf ' %s=%s' "$key" "$(median "$key" "$WORK/$mode")"; done
  echo
done
