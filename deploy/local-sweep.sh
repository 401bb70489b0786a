#!/usr/bin/env bash
# A sweep on one machine: K chunks run by P processes at once (xargs -P),
# then reduced to one table.  The same commands a cluster array job runs.
#
#   deploy/local-sweep.sh SPEC OUTDIR [K] [P]     > table.json
#   CSV=1 deploy/local-sweep.sh SPEC OUTDIR       > table.csv
#
# K (chunks) defaults to 4 x P so that uneven points balance out; P
# (processes) to the number of cores.  RINGDYN names the binary (default:
# ringdyn on PATH, else build/cli/ringdyn).  Chunks already in OUTDIR from an
# earlier, interrupted run of the same K are kept: rerun to finish the rest.
set -euo pipefail
spec=${1:?usage: local-sweep.sh SPEC OUTDIR [K] [P]}
out=${2:?usage: local-sweep.sh SPEC OUTDIR [K] [P]}
P=${4:-$(env -u OMP_NUM_THREADS nproc)}   # nproc alone would obey OMP_NUM_THREADS
K=${3:-$((4 * P))}
ringdyn=${RINGDYN:-$(command -v ringdyn || echo build/cli/ringdyn)}

n=$("$ringdyn" sweep count "$spec")      # validates the spec before anything runs
[ "$K" -le "$n" ] || K=$n
mkdir -p "$out"
seq 0 $((K - 1)) | while read -r i; do
  [ -e "$out/$(printf 'chunk-%06d-of-%06d.json' "$i" "$K")" ] || echo "$i"
done | xargs -r -P "$P" -I{} "$ringdyn" sweep run "$spec" --index {} --chunks "$K" --out "$out"
"$ringdyn" sweep reduce "$out" ${CSV:+--csv}
