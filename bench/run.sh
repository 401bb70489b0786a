#!/usr/bin/env bash
# Benchmarks: the accuracy/cost table (wall time, median of repeats) and the
# cost exponent from instruction counts (callgrind: exact, unaffected by load).
#   bench/run.sh [build-dir]     (default: build-bench, Release)
set -euo pipefail
cd "$(dirname "$0")/.."
b=${1:-build-bench}
cmake -S . -B "$b" -DCMAKE_BUILD_TYPE=Release -DRINGDYN_TESTS=OFF >/dev/null
cmake --build "$b" -j2 --target bench_modal bench_static bench_lift bench_ringpack >/dev/null

# instructions BENCH: callgrind instruction counts of `BENCH --once n` for
# n = 100..800 and the exponent between each pair of sizes.
instructions() {
  echo "| n | instructions |"
  echo "|---|---|"
  local prev_n="" prev_i="" n out ins
  for n in 100 200 400 800; do
    out=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$b/bench/$1" --once $n 2>&1)
    ins=$(printf '%s\n' "$out" | sed -n 's/.*Collected : \([0-9]*\).*/\1/p')
    echo "| $n | $ins |"
    if [ -n "$prev_i" ]; then
      awk -v a="$prev_i" -v b="$ins" -v n1="$prev_n" -v n2="$n" \
        'BEGIN{printf "|   | exponent %d->%d: %.3f |\n", n1, n2, log(b/a)/log(n2/n1)}'
    fi
    prev_n=$n; prev_i=$ins
  done
}

echo "## modal: accuracy and cost vs n"
"$b/bench/bench_modal"
echo
echo "## modal: instructions vs n (callgrind, one solve with the error estimate, 6 modes)"
instructions bench_modal
echo
echo "## modal: predicted (rd_modal_cost_predict) vs measured CPU time"
"$b/bench/bench_modal" --predict

echo
echo "# pretension and contact"
"$b/bench/bench_static"
echo
echo "## contact: instructions vs n (callgrind, one round-bore solve, 10 points per segment)"
instructions bench_static
echo
"$b/bench/bench_static" --battery
echo
echo "## lift: cost per engine cycle vs n, and flank-change accuracy vs rtol"
"$b/bench/bench_lift"
echo
echo "## lift: models (auto, rigid, full) on the lift examples"
"$b/bench/bench_lift" --models examples
echo
echo "## lift: the modal model against the full model it reduces (lift examples)"
"$b/bench/bench_lift" --modal examples
echo
echo "## lift: the distorted-bore examples, per-segment flank changes of auto vs full n = 40 (target <= 0.2 deg)"
"$b/bench/bench_lift" --distorted examples
echo
echo "## lift: would a run at n/2 estimate the full model's segment-count error? (target: within x3 of the error vs full at 2n)"
"$b/bench/bench_lift" --segment-estimate examples
echo
echo "## ringpack: cost per engine cycle: axial and rigid rings (target <= 50 ms), a full top ring vs its lift run alone (target <= 10x)"
"$b/bench/bench_ringpack"
