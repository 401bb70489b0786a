#!/usr/bin/env bash
# One task of a sweep as a Slurm job array: task I of K runs chunk I.
#
#   K=64
#   jid=$(sbatch --parsable --array=0-$((K - 1)) deploy/slurm-sweep.sh spec.json /shared/out)
#   sbatch --dependency=afterok:$jid --wrap "ringdyn sweep reduce /shared/out --csv > table.csv"
#
# Limit how many tasks run at once with --array=0-63%16.  OUTDIR must be on a
# file system every node sees.  `ringdyn sweep run` reads its index from
# SLURM_ARRAY_TASK_ID; the chunk count is the array's size.  A task that
# fails (node lost) is rerun with `sbatch --array=I ...`: each chunk file is
# written under a temporary name and renamed, so a file is complete or absent.
#SBATCH --job-name=ringdyn-sweep
#SBATCH --cpus-per-task=1
#SBATCH --time=01:00:00
#SBATCH --output=ringdyn-sweep-%A_%a.log
set -euo pipefail
spec=${1:?usage: sbatch --array=0-K-1 slurm-sweep.sh SPEC OUTDIR}
out=${2:?usage: sbatch --array=0-K-1 slurm-sweep.sh SPEC OUTDIR}
# One thread per task: the solver is sequential, and BLAS threads would only
# compete with the other tasks on the node.
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
exec "${RINGDYN:-ringdyn}" sweep run "$spec" --chunks "${SLURM_ARRAY_TASK_COUNT:?not in a job array}" \
     --out "$out"
