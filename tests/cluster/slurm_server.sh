#!/usr/bin/env bash
# ringdyn-server --sweep-executor slurm on a real single-node Slurm cluster
# (slurm_lib.sh), against a server with its own workers (the local executor):
#   A  a sweep above --sweep-max-points runs as one job array (executor slurm,
#      its job id, progress from the chunks); its table and CSV are byte for
#      byte the local server's; its directory is removed once read;
#      a lift sweep (model auto) likewise, through --sweep-slurm-min-points 0,
#      and the executor's own cost (wall - the longest task) at most 8 s;
#   B  DELETE while tasks run: the array is cancelled (squeue shows nothing
#      left) and the sweep ends cancelled;
#   C  a task given an invalid scene (the spec in the shared directory swapped
#      while the partition is down) exits 2: the sweep fails with the task,
#      its exit code and ringdyn's message, without waiting;
#   D  the array cancelled outside the service (scancel): the sweep fails
#      saying so, not waiting forever; a server started without
#      --sweep-shared-dir refuses to start.
# Needs root, as slurm.sh.  slurm_server.sh SERVER RINGDYN DEPLOY_DIR
set -euo pipefail
server=$(realpath "$1") ringdyn=$(realpath "$2") deploy=$(realpath "$3")
here=$(cd "$(dirname "$0")" && pwd)
fail() { echo "FAIL: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || fail "the Slurm cluster test needs root (slurmd, SlurmdUser=root); not skipped"
for c in munged mungekey slurmctld slurmd sbatch squeue scontrol scancel curl jq /usr/bin/time; do
  command -v "$c" >/dev/null || fail "$c not found: scripts/install-deps.sh --test installs it"
done

work=$(mktemp -d /tmp/ringdyn-slurm.XXXXXX)
chmod 755 "$work"
exec 9> "$work/lock" && flock -n 9   # held while this run lives (slurm_lib.sh: reap_stale)
export SLURM_CONF=$work/slurm.conf
source "$here/slurm_lib.sh"
source "$here/slurm_server_lib.sh"
trap 'servers_stop; cluster_stop; rm -rf "$work"' EXIT
trap 'exit 1' TERM INT HUP
cluster_start "$work"
mkdir "$work/shared"
slurm_args=(--sweep-executor slurm --sweep-shared-dir "$work/shared"
  --sweep-slurm-script "$deploy/slurm-sweep.sh" --sweep-ringdyn "$ringdyn")

rc=0; "$server" --port 0 --data :memory: --sweep-executor slurm > /dev/null 2> "$work/noshared.err" || rc=$?
[ $rc != 0 ] && grep -q -- '--sweep-shared-dir' "$work/noshared.err" \
  || fail "a slurm server without --sweep-shared-dir started (rc $rc): $(cat "$work/noshared.err")"

server_start local --threads 2
server_start slurm --threads 2 --sweep-max-points 100 --sweep-slurm-tasks 8 "${slurm_args[@]}"

# A: 512 modal points (as slurm.sh), above the slurm server's limit of 100.
modal_spec "$work/modal.json"
t0=$(now)
lid=$(post_sweep "$local" "$work/modal.json")
sid=$(post_sweep "$slurm" "$work/modal.json")
sweep_get "$slurm" "$sid" "$work/A.first.json"
[ "$(jq -r .executor "$work/A.first.json")" = slurm ] || fail "A: executor $(jq -c .executor "$work/A.first.json")"
seen_part=0
for ((i = 0; i < 1200; i++)); do
  sweep_get "$slurm" "$sid" "$work/A.json"
  s=$(jq -r .status "$work/A.json")
  d=$(jq -r .cluster.chunks_done "$work/A.json")
  [ "$d" -gt 0 ] && [ "$d" -lt 8 ] && seen_part=1
  [ "$s" = running ] || [ "$s" = queued ] || break
  sleep 0.2
done
t_slurm=$(since "$t0")
sweep_wait "$local" "$lid" "$work/A.local.json"
[ "$(jq -r .status "$work/A.json")" = succeeded ] || fail "A: $(jq -c 'del(.table)' "$work/A.json")"
jid=$(jq -r .cluster.job_id "$work/A.json")
[[ $jid =~ ^[0-9]+$ ]] || fail "A: job id '$jid'"
[ "$(job_field "$jid" JobName)" = ringdyn-sweep ] || fail "A: job $jid is $(job_field "$jid" JobName)"
[ "$(array_tasks "$jid" | wc -l)" = 8 ] || fail "A: want 8 array tasks: $(array_tasks "$jid")"
[ "$(jq -r '.cluster.chunks, .cluster.chunks_done, .done, .progress' "$work/A.json" | tr '\n' ' ')" = "8 8 512 1 " ] \
  || fail "A: $(jq -c 'del(.table)' "$work/A.json")"
[ "$(jq -r .executor "$work/A.local.json")" = local ] || fail "A: local executor $(jq -c .executor "$work/A.local.json")"
[ "$(sweep_table "$work/A.json")" = "$(sweep_table "$work/A.local.json")" ] || fail "A: JSON tables differ"
curl -sSf -o "$work/A.csv" "$slurm/api/v1/sweeps/$sid/table.csv"
curl -sSf -o "$work/A.local.csv" "$local/api/v1/sweeps/$lid/table.csv"
cmp "$work/A.csv" "$work/A.local.csv" || fail "A: CSV tables differ"
[ "$(grep -c ',ok,' "$work/A.csv")" = 512 ] || fail "A: want 512 ok rows"
[ ! -e "$(jq -r .cluster.dir "$work/A.json")" ] || fail "A: the sweep's directory is left"
echo "A: 512 modal points as 8 Slurm tasks: $t_slurm s, table identical to the local executor's" \
  "(progress seen between chunks: $seen_part)"

# A': a lift sweep with model auto; every sweep to Slurm (--sweep-slurm-min-points 0).
# Its tasks' ringdyn under /usr/bin/time: the executor's own cost (the sweep's
# wall time minus its longest task's: submission, scheduling, polls, reading
# the chunks) is what the 15 % of issue 43 bounds; the machine's other load
# does not move it (bench/slurm_server.sh measures whole sweeps).
printf '#!/bin/sh\nexec /usr/bin/time -a -o %s -f "%%e" %s "$@"\n' "$work/tasks.time" "$ringdyn" > "$work/ringdyn-timed"
chmod +x "$work/ringdyn-timed"
server_start slurm0 --threads 2 --sweep-slurm-min-points 0 --sweep-slurm-tasks 2 \
  "${slurm_args[@]}" --sweep-ringdyn "$work/ringdyn-timed"
sed 's/"samples": 2000/"samples": 60/' "$here/../../bench/sweeps/lift_auto_2000.json" > "$work/lift.json"
t0=$(now)
sid=$(post_sweep "$slurm0" "$work/lift.json")
sweep_wait "$slurm0" "$sid" "$work/L.json"
t_slurm=$(since "$t0")
lid=$(post_sweep "$local" "$work/lift.json")
sweep_wait "$local" "$lid" "$work/L.local.json"
own=$(awk -v w="$t_slurm" '$1 > m { m = $1 } END { printf "%.1f", w - m }' "$work/tasks.time")
awk -v o="$own" 'BEGIN { exit !(o <= 8) }' \
  || fail "A': the executor's own cost is $own s (sweep $t_slurm s, tasks $(tr '\n' ' ' < "$work/tasks.time")s), want <= 8 s"
[ "$(jq -r .status,.executor "$work/L.json" | tr '\n' ' ')" = "succeeded slurm " ] \
  || fail "A': $(jq -c 'del(.table)' "$work/L.json")"
[ "$(sweep_table "$work/L.json")" = "$(sweep_table "$work/L.local.json")" ] || fail "A': lift tables differ"
[ "$(jq '[.table.rows[] | select(.[-2] == "ok")] | length' "$work/L.json")" = 60 ] || fail "A': want 60 ok rows"
echo "A': 60 lift points (model auto), every sweep to Slurm: table identical; $t_slurm s, of which" \
  "the executor's own cost (wall - longest task) $own s"

# B: DELETE while the tasks run (2000 lift points in 8 tasks: ~10 s each).
sid=$(post_sweep "$slurm" "$here/../../bench/sweeps/lift_auto_2000.json")
for ((i = 0; i < 300; i++)); do
  sweep_get "$slurm" "$sid" "$work/B.json"
  [ "$(jq -r .cluster.tasks_running "$work/B.json")" -gt 0 ] && break
  [ "$(jq -r .status "$work/B.json")" = running ] || [ "$(jq -r .status "$work/B.json")" = queued ] || break
  sleep 0.2
done
jid=$(jq -r .cluster.job_id "$work/B.json")
[ "$(jq -r .cluster.tasks_running "$work/B.json")" -gt 0 ] || fail "B: no task running: $(jq -c 'del(.table)' "$work/B.json")"
code=$(curl -sS -o "$work/B.del.json" -w '%{http_code}' -X DELETE "$slurm/api/v1/sweeps/$sid")
[ "$code" = 200 ] || fail "B: DELETE answered $code"
sweep_wait "$slurm" "$sid" "$work/B.json" 60
[ "$(jq -r .status "$work/B.json")" = cancelled ] || fail "B: $(jq -c 'del(.table)' "$work/B.json")"
[ -z "$(squeue -h -j "$jid" 2> /dev/null)" ] || fail "B: tasks left: $(squeue -j "$jid")"
[ "$(job_field "${jid}_7" JobState)" = CANCELLED ] || fail "B: task 7 $(job_field "${jid}_7" JobState)"
[ ! -e "$(jq -r .cluster.dir "$work/B.json")" ] || fail "B: the sweep's directory is left"
echo "B: DELETE cancelled array $jid: nothing left in squeue, sweep cancelled"

# C: a task given an invalid scene.  The partition is down, so the tasks wait;
# the spec in the sweep's directory is swapped for one with 2 segments.
scontrol update PartitionName=test State=DOWN
sid=$(post_sweep "$slurm" "$work/modal.json")
for ((i = 0; i < 100; i++)); do
  sweep_get "$slurm" "$sid" "$work/C.json"
  [ "$(jq -r .cluster.job_id "$work/C.json")" != null ] && break
  sleep 0.2
done
dir=$(jq -r .cluster.dir "$work/C.json")
sed 's/"segments": 120/"segments": 2/' "$work/modal.json" > "$dir/spec.json"
scontrol update PartitionName=test State=UP
t0=$(now)
sweep_wait "$slurm" "$sid" "$work/C.json" 120
[ "$(jq -r .status,.error.code "$work/C.json" | tr '\n' ' ')" = "failed invalid_scene " ] \
  || fail "C: $(jq -c 'del(.table)' "$work/C.json")"
msg=$(jq -r .error.message "$work/C.json")
[[ $msg == *"exit code 2:0"* && $msg == *segments* ]] || fail "C: message: $msg"
[ -d "$dir/logs" ] || fail "C: the failed sweep's logs are gone"
echo "C: invalid scene: failed $(since "$t0") s after the tasks could start: $msg"

# D: the array cancelled outside the service while its tasks wait.
scontrol update PartitionName=test State=DOWN
sid=$(post_sweep "$slurm" "$work/modal.json")
for ((i = 0; i < 100; i++)); do
  sweep_get "$slurm" "$sid" "$work/D.json"
  [ "$(jq -r .cluster.job_id "$work/D.json")" != null ] && break
  sleep 0.2
done
scancel "$(jq -r .cluster.job_id "$work/D.json")"
scontrol update PartitionName=test State=UP
sweep_wait "$slurm" "$sid" "$work/D.json" 60
[ "$(jq -r .status,.error.code "$work/D.json" | tr '\n' ' ')" = "failed cancelled " ] \
  || fail "D: $(jq -c 'del(.table)' "$work/D.json")"
[[ $(jq -r .error.message "$work/D.json") == *"cancelled outside the service"* ]] \
  || fail "D: $(jq -r .error.message "$work/D.json")"
echo "D: cancelled outside: $(jq -r .error.message "$work/D.json")"
servers_check   # a sanitizer build's servers (scripts/test.sh) report errors and leaks at exit
echo "slurm_server: all checks passed"
