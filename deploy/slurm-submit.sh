#!/usr/bin/env bash
# A sweep on Slurm: the chunks as one job array, the reduce as a job that runs
# once every task succeeded (afterok).  Prints "ARRAY_JOBID REDUCE_JOBID"
# (ARRAY_JOBID is "-" when every chunk is already there).
#
#   deploy/slurm-submit.sh SPEC OUTDIR [K] [P]
#
# K chunks (default 64, at most the number of points), at most P tasks
# running at once (--array=...%P; default: no limit).  The table appears as
# OUTDIR/table.json and OUTDIR/table.csv, the logs in OUTDIR/logs/.
#
# Limits: array indices go up to MaxArraySize - 1 (scontrol show config).
# When K is above, the array has T = MaxArraySize tasks and task t runs
# chunks t, t+T, t+2T, ...: one array and one dependency whatever K.
#
# Submitting again with the same arguments runs only the chunks that are not
# in OUTDIR (a task cancelled, failed or lost) and a new reduce; the reduce
# left waiting on the earlier array (DependencyNeverSatisfied) is cancelled.
# Submit again once the earlier array has ended.  Partition, account and
# time limit come from sbatch's own variables (SBATCH_PARTITION,
# SBATCH_ACCOUNT, SBATCH_TIMELIMIT).  RINGDYN names the binary (default:
# ringdyn on PATH, else build/cli/ringdyn); it must be at the same path on
# every node.
set -euo pipefail
usage='usage: slurm-submit.sh SPEC OUTDIR [K] [P]'
spec=$(realpath -e "${1:?$usage}")
out=$(realpath -m "${2:?$usage}")
P=${4:-}
here=$(cd "$(dirname "$0")" && pwd)
RINGDYN=$(realpath -e "${RINGDYN:-$(command -v ringdyn || echo build/cli/ringdyn)}")
export RINGDYN

K=${3:-64}
[[ $K =~ ^[1-9][0-9]*$ && $P =~ ^([1-9][0-9]*)?$ ]] || { echo "$usage (K, P: positive)" >&2; exit 2; }
n=$("$RINGDYN" sweep count "$spec")      # validates the spec: exit 2, nothing submitted
[ "$K" -le "$n" ] || K=$n
max=$(scontrol show config | sed -n 's/^MaxArraySize *= *//p')
[ -n "$max" ] || { echo "slurm-submit: no MaxArraySize in scontrol show config" >&2; exit 1; }
T=$((K < max ? K : max))

# The tasks with at least one chunk missing, as an --array list (3-5,9).
list='' start=-1 prev=-2
for ((t = 0; t < T; t++)); do
  for ((i = t; i < K; i += T)); do
    [ -e "$out/$(printf 'chunk-%06d-of-%06d.json' "$i" "$K")" ] && continue
    if [ $t -ne $((prev + 1)) ]; then
      [ $start -lt 0 ] || list+="$start$([ $prev = $start ] || echo "-$prev"),"
      start=$t
    fi
    prev=$t
    break
  done
done
[ $start -lt 0 ] || list+="$start$([ $prev = $start ] || echo "-$prev")"

mkdir -p "$out/logs"
jid=- dep=()
if [ -n "$list" ]; then
  jid=$(sbatch --parsable --job-name=ringdyn-sweep --array="$list${P:+%$P}" \
        --output="$out/logs/%A_%a.log" "$here/slurm-sweep.sh" "$spec" "$out" "$K" "$T")
  jid=${jid%%;*}
  dep=(--dependency="afterok:$jid")
fi
# An earlier reduce of this OUTDIR still pending waits for an array that
# failed or was cancelled: it would never run.
squeue -h -t PD -n ringdyn-sweep-reduce -o '%i %k' | while read -r id comment; do
  [ "$comment" != "$out" ] || scancel "$id"
done
rid=$(sbatch --parsable --job-name=ringdyn-sweep-reduce --comment="$out" "${dep[@]}" \
      --output="$out/logs/reduce-%j.log" "$here/slurm-sweep.sh" --reduce "$out")
echo "$jid ${rid%%;*}"
