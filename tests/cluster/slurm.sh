#!/usr/bin/env bash
# A real single-node Slurm cluster (munged, slurmctld, slurmd from Debian's
# slurm-wlm) in a temporary directory, running deploy/slurm-submit.sh:
#   A  K = 8 chunks as 8 array tasks, at most 3 at once, reduce afterok: the
#      table equals `ringdyn sweep run` in one process, byte for byte;
#   B  one task cancelled while it runs (scancel JOBID_I): no chunk file, the
#      reduce never runs; submitted again, only that task runs: same table;
#   C  K = 24 above MaxArraySize = 10: 10 tasks, several chunks each; same table;
#      chunks lost: submitted again, their tasks rerun those chunks alone;
#   D  a spec whose scene is invalid: slurm-submit.sh refuses it (exit 2), and
#      array tasks given it directly end FAILED with exit code 2 (don't retry);
#   E  the per-task overhead, printed: 10 one-point tasks, 2 at once, against
#      xargs -P 2 ((Slurm wall - xargs wall) x 2 / 10); with every chunk
#      there, submitting again runs the reduce alone.
# Needs root (slurmd runs jobs as any user): without it, it fails, saying so.
# The daemons are stopped on every exit (trap).
#   slurm.sh RINGDYN DEPLOY_DIR
set -euo pipefail
ringdyn=$(realpath "$1") deploy=$(realpath "$2")
fail() { echo "FAIL: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || fail "the Slurm cluster test needs root (slurmd, SlurmdUser=root); not skipped"
for c in munged mungekey slurmctld slurmd sbatch squeue scontrol scancel; do
  command -v "$c" >/dev/null || fail "$c not found: scripts/install-deps.sh --test installs slurm-wlm and munge"
done

work=$(mktemp -d /tmp/ringdyn-slurm.XXXXXX)
chmod 755 "$work"   # munged wants the socket's directories searchable by all
exec 9> "$work/lock" && flock -n 9   # held while this run lives (slurm_lib.sh: reap_stale)
export SLURM_CONF=$work/slurm.conf
source "$(dirname "$0")/slurm_lib.sh"
trap 'cluster_stop; rm -rf "$work"' EXIT
trap 'exit 1' TERM INT HUP   # so that the EXIT trap runs
cluster_start "$work"

# The spec (slurm_lib.sh: modal_spec): 512 points of a modal scene.
modal_spec "$work/spec.json"
export RINGDYN=$ringdyn
t0=$(now)
"$ringdyn" sweep run "$work/spec.json" --out "$work/ref"
"$ringdyn" sweep reduce "$work/ref" > "$work/ref.json"
"$ringdyn" sweep reduce "$work/ref" --csv > "$work/ref.csv"
echo "one process: $(since "$t0") s"
[ "$(grep -c ',ok,' "$work/ref.csv")" = 512 ] || fail "reference: want 512 ok rows"
submit() {  # submit DIR K P: sets jid and rid
  local ids
  ids=$(bash "$deploy/slurm-submit.sh" "$work/spec.json" "$work/$1" "$2" "$3") \
    || fail "slurm-submit.sh $1 $2 $3: exit $?"
  read -r jid rid <<< "$ids"
}
same_table() {  # same_table DIR WHAT
  cmp "$work/ref.json" "$1/table.json" || fail "$2: JSON table differs from one process's"
  cmp "$work/ref.csv" "$1/table.csv" || fail "$2: CSV table differs from one process's"
}

# A: 8 tasks, %3.  Concurrency is sampled while it runs (the node has 4 slots).
t0=$(now)
submit A 8 3
[ "$(job_field "$jid" ArrayTaskThrottle)" = 3 ] || fail "A: array not throttled to 3"
most=$(wait_job "$rid" "$jid")
t_slurm=$(since "$t0")
[ "$most" -le 3 ] || fail "A: $most tasks ran at once, limit 3"
[ "$(job_field "$rid" JobState)" = COMPLETED ] || fail "A: reduce $(job_field "$rid" JobState)"
[ "$(array_tasks "$jid" | wc -l)" = 8 ] || fail "A: want 8 array tasks: $(array_tasks "$jid")"
same_table "$work/A" "A (8 tasks)"
echo "A: 8 tasks %3: $t_slurm s from submit to table, at most $most at once"

# B: task 5 cancelled while its chunk runs, then submitted again.
submit B 8 2
wait_ringdyn "${jid}_5"
scancel "${jid}_5"
wait_gone "$jid"
[ "$(job_field "${jid}_5" JobState)" = CANCELLED ] || fail "B: task 5 $(job_field "${jid}_5" JobState)"
[ ! -e "$work/B/chunk-000005-of-000008.json" ] || fail "B: task 5 finished before the scancel"
[ "$(ls "$work/B" | grep -c '^chunk-')" = 7 ] || fail "B: want 7 chunks: $(ls -A "$work/B")"
[ -z "$(ls -A "$work/B" | grep -v '^chunk-\|^logs$')" ] || fail "B: files left: $(ls -A "$work/B")"
t0=$(now)
wait_field "$rid" Reason DependencyNeverSatisfied
echo "B: the reduce saw its dependency fail after $(since "$t0") s"
old=$rid
submit B 8 2
wait_job "$rid" "$jid" >/dev/null
[ "$(array_tasks "$jid")" = 5 ] || fail "B: resubmitted $(array_tasks "$jid"), want task 5 only"
[ "$(job_field "$old" JobState)" = CANCELLED ] || fail "B: stale reduce $(job_field "$old" JobState)"
same_table "$work/B" "B (task 5 cancelled, resubmitted)"

# C: K = 24 above MaxArraySize = 10: 10 tasks of 2-3 chunks.
submit C 24 3
wait_job "$rid" "$jid" >/dev/null
[ "$(array_tasks "$jid" | tr '\n' ' ')" = "0 1 2 3 4 5 6 7 8 9 " ] || fail "C: tasks $(array_tasks "$jid")"
[ "$(ls "$work/C" | grep -c '^chunk-.*-of-000024.json$')" = 24 ] || fail "C: want 24 chunks"
same_table "$work/C" "C (24 chunks in 10 tasks)"
# Chunks lost from packed tasks 3, 4 and 7: the same command runs those
# tasks (--array=3-4,7), each only its lost chunk (the others keep their files).
for i in 13 14 17; do rm "$work/C/chunk-0000$i-of-000024.json"; done
rm "$work/C/table.json" "$work/C/table.csv"
touch -d '2000-01-01' "$work/C"/chunk-0000{03,23}-of-000024.json
submit C 24 3
wait_job "$rid" "$jid" > /dev/null
[ "$(array_tasks "$jid" | tr '\n' ' ')" = "3 4 7 " ] || fail "C: resubmitted $(array_tasks "$jid"), want 3 4 7"
[ "$(find "$work/C" -name 'chunk-*' -mtime +1000 | wc -l)" = 2 ] || fail "C: chunk 3 or 23 run again"
same_table "$work/C" "C (chunks 13, 14, 17 lost, resubmitted)"

# D: an invalid scene.  Refused before anything is submitted; run anyway, exit 2.
sed 's/"segments": 120/"segments": 2/' "$work/spec.json" > "$work/bad.json"
rc=0; bash "$deploy/slurm-submit.sh" "$work/bad.json" "$work/D" 8 2 2> "$work/D.err" || rc=$?
[ $rc = 2 ] && grep -q '"path":"/base/discretization/segments"' "$work/D.err" \
  || fail "D: slurm-submit.sh rc $rc: $(cat "$work/D.err")"
[ ! -e "$work/D" ] || fail "D: something was submitted"
mkdir -p "$work/D"
jid=$(sbatch --parsable --array=0-1 --output="$work/D/%A_%a.log" "$deploy/slurm-sweep.sh" "$work/bad.json" "$work/D" 2)
wait_gone "$jid"
for t in 0 1; do
  s="$(job_field "${jid}_$t" JobState) $(job_field "${jid}_$t" ExitCode)"
  [ "$s" = "FAILED 2:0" ] || fail "D: task $t: $s, want FAILED 2:0"
done
# E: the cost of a task itself: 10 one-point chunks, 2 at once, on Slurm and by xargs.
echo '{"base": {"analysis": "modal", "modal": {"modes": 1}, "discretization": {"segments": 6}},
 "parameters": [{"path": "/ring/tangential_force", "range": {"start": 8, "stop": 12, "count": 10}}],
 "outputs": ["count(/modes)"]}' > "$work/tiny.json"
t0=$(now)
bash "$deploy/local-sweep.sh" "$work/tiny.json" "$work/tiny-xargs" 10 2 > "$work/tiny.table.json"
t_xargs=$(since "$t0")
t0=$(now)
ids=$(bash "$deploy/slurm-submit.sh" "$work/tiny.json" "$work/E" 10 2) || fail "E: submit"
read -r jid rid <<< "$ids"
wait_job "$rid" "$jid" > /dev/null
t_slurm=$(since "$t0")
cmp "$work/tiny.table.json" "$work/E/table.json" || fail "E: tables differ"
# Every chunk there: no array, the reduce alone (ARRAY_JOBID "-").
rm "$work/E/table.json"
ids=$(bash "$deploy/slurm-submit.sh" "$work/tiny.json" "$work/E" 10 2) || fail "E: submit again"
read -r jid rid <<< "$ids"
[ "$jid" = - ] || fail "E: all chunks there, yet array $jid submitted"
wait_job "$rid" - > /dev/null
cmp "$work/tiny.table.json" "$work/E/table.json" || fail "E: reduce alone: tables differ"
rc=0; bash "$deploy/slurm-submit.sh" "$work/tiny.json" "$work/E" 0 2 2> /dev/null || rc=$?
[ $rc = 2 ] || fail "E: K = 0 accepted (exit $rc)"
awk -v s="$t_slurm" -v x="$t_xargs" 'BEGIN { printf "E: 10 one-point tasks, 2 at once: \
Slurm %.1f s, xargs %.1f s: per-task overhead %.2f s ((Slurm - xargs) x 2 / 10)\n", s, x, (s - x) * 2 / 10 }'
echo "slurm: all checks passed"
