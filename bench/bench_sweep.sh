#!/usr/bin/env bash
# Sweep throughput: points per second of bench/sweeps/{modal_small,lift_small}
# run as 8 chunks by P = 1 and P = 2 processes (deploy/local-sweep.sh, the
# same commands as a cluster job), median of 3 wall times, plus the CPU time
# per point (user + sys of all processes: less sensitive to other load).
#   bench/bench_sweep.sh [build-dir]      (default: build-rel, Release)
set -euo pipefail
cd "$(dirname "$0")/.."
b=${1:-build-rel}
cmake -S . -B "$b" -DCMAKE_BUILD_TYPE=Release -DRINGDYN_TESTS=OFF >/dev/null
cmake --build "$b" -j2 --target ringdyn >/dev/null
export RINGDYN=$b/cli/ringdyn OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# run SPEC P: prints "wall_s cpu_s" of one whole sweep (8 chunks, P processes).
run() {
  rm -rf "$work/out"
  local t0 t1 c0 c1
  c0=$(awk '{print $14 + $15 + $16 + $17}' /proc/$$/stat)
  t0=$(date +%s.%N)
  bash deploy/local-sweep.sh "$1" "$work/out" 8 "$2" > "$work/table.json"
  t1=$(date +%s.%N)
  c1=$(awk '{print $14 + $15 + $16 + $17}' /proc/$$/stat)
  grep -q '"ok"' "$work/table.json"
  if grep -q '"not_converged"\|"numerical_failure"' "$work/table.json"; then
    echo "warning: failed points in $1" >&2
  fi
  awk -v a="$t0" -v b="$t1" -v c="$c0" -v d="$c1" -v hz="$(getconf CLK_TCK)" \
    'BEGIN{printf "%.3f %.3f\n", b - a, (d - c) / hz}'
}

echo "| sweep | points | P | wall (median of 3) | points/s | CPU s per point | speed-up 1 -> 2 |"
echo "|---|---|---|---|---|---|---|"
for spec in modal_small lift_small; do
  s=bench/sweeps/$spec.json
  n=$("$RINGDYN" sweep count "$s")
  one=
  for P in 1 2; do
    for r in 1 2 3; do run "$s" "$P"; done > "$work/times"
    wall=$(sort -n "$work/times" | sed -n 2p | cut -d' ' -f1)
    cpu=$(sort -n "$work/times" | sed -n 2p | cut -d' ' -f2)
    [ "$P" = 1 ] && one=$wall
    awk -v s="$spec" -v n="$n" -v p="$P" -v w="$wall" -v c="$cpu" -v o="$one" \
      'BEGIN{printf "| %s | %d | %d | %.2f s | %.1f | %.4f | %s |\n", s, n, p, w, n / w, c / n,
             p == 1 ? "" : sprintf("%.2f", o / w)}'
  done
done
echo
echo "load average while measuring: $(cut -d' ' -f1-3 /proc/loadavg) on $(getconf _NPROCESSORS_ONLN) cores"
