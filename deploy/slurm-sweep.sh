#!/usr/bin/env bash
# One task of a sweep as a Slurm job array, or the reduce after it.  Most
# users want deploy/slurm-submit.sh, which submits both (docs/cluster.md).
#
#   sbatch --array=0-$((T - 1))%P slurm-sweep.sh SPEC OUTDIR K [T]
#   sbatch --dependency=afterok:JOBID slurm-sweep.sh --reduce OUTDIR
#
# Task t of T runs chunks t, t+T, t+2T, ... of K (T = K: one chunk a task;
# T < K packs several chunks into a task when K is above the cluster's
# MaxArraySize), skipping chunks whose file is already in OUTDIR, so a task
# that was cancelled or lost is simply submitted again (--array=t, same K and
# T).  K defaults to the array's size, which only holds for a whole array.
# OUTDIR must be on a file system every node sees.  Each chunk file is
# written under a temporary name and renamed: it is complete or absent.
#
# Exit status (ringdyn's): 0 done; 2 invalid input (the spec or a scene in it
# is invalid; --reduce: chunks missing or from another spec): do not retry;
# 1 the run could not finish (cancelled, out of memory, disk full): retry.
# --reduce writes OUTDIR/table.json and OUTDIR/table.csv (complete or absent).
#SBATCH --job-name=ringdyn-sweep
#SBATCH --cpus-per-task=1
#SBATCH --time=01:00:00
#SBATCH --output=ringdyn-sweep-%A_%a.log
set -euo pipefail
usage='usage: sbatch --array=0-T-1 slurm-sweep.sh SPEC OUTDIR K [T] | slurm-sweep.sh --reduce OUTDIR'
ringdyn=${RINGDYN:-ringdyn}
# One thread per task: the solver is sequential, and BLAS threads would only
# compete with the other tasks on the node.
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1

if [ "${1:-}" = --reduce ]; then
  out=${2:?$usage}
  trap 'rm -f "$out/.table.json.tmp" "$out/.table.csv.tmp"' EXIT
  "$ringdyn" sweep reduce "$out" > "$out/.table.json.tmp"
  "$ringdyn" sweep reduce "$out" --csv > "$out/.table.csv.tmp"
  mv "$out/.table.json.tmp" "$out/table.json"
  mv "$out/.table.csv.tmp" "$out/table.csv"
  exit 0
fi

spec=${1:?$usage}
out=${2:?$usage}
K=${3:-${SLURM_ARRAY_TASK_COUNT:?not in a job array}}
T=${4:-$K}
t=${SLURM_ARRAY_TASK_ID:?not in a job array}
echo "ringdyn-sweep: task $t of $T (chunks of $K) on $(hostname)"
for ((i = t; i < K; i += T)); do
  [ -e "$out/$(printf 'chunk-%06d-of-%06d.json' "$i" "$K")" ] && continue
  "$ringdyn" sweep run "$spec" --index "$i" --chunks "$K" --out "$out"
done
