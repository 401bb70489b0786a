# A throw-away single-node Slurm cluster and the waits of slurm.sh (sourced).
# Everything lives in $work: munge key and socket, slurm.conf, state, spool,
# logs, pid files; SLURM_CONF points the client commands at it.  Ports are
# picked free.  The node has 4 CPU slots (config_overrides: whatever the
# machine has), so a %3 limit, not the node, bounds the tasks at once.
# MaxArraySize is small (10) to test packing.  No cgroups: proctrack/linuxproc
# and task/none work in a container or a VM without systemd.

now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }

free_port() {  # free_port FROM: the first port from FROM that nothing listens on
  local p
  for ((p = $1; p < $1 + 200; p++)); do
    (exec 3<> "/dev/tcp/127.0.0.1/$p") 2> /dev/null || { echo $p; return 0; }
  done
  return 1
}

cluster_logs() {
  local f
  for f in "$work"/munged.log "$work"/slurmctld.log "$work"/slurmd.log; do
    [ -e "$f" ] && { echo "--- $f"; tail -n 20 "$f"; }
  done >&2
}

reap_stale() {  # daemons of an earlier run killed before its trap ran (a ctest timeout)
  local d f pid
  for d in /tmp/ringdyn-slurm.*; do
    # A live run holds its lock (fd 9 of slurm.sh): leave it alone.
    [ "$d" != "$work" ] && [ -e "$d/lock" ] && flock -n "$d/lock" true || continue
    for f in "$d"/slurmd.pid "$d"/slurmctld.pid "$d"/munged.pid; do
      pid=$(cat "$f" 2> /dev/null) || continue
      grep -qF "$d/" "/proc/$pid/cmdline" 2> /dev/null && kill -KILL "$pid"
    done
    rm -rf "$d"
  done
}

cluster_start() {
  local h p1 p2 i
  reap_stale
  h=$(hostname -s)
  p1=$(free_port $((10000 + RANDOM % 20000)))   # below the ephemeral ports
  p2=$(free_port $((p1 + 1)))
  mkdir -p "$work/state" "$work/spool"
  mungekey --create --keyfile="$work/munge.key"
  munged 9>&- --force --key-file="$work/munge.key" --socket="$work/munge.sock" \
    --pid-file="$work/munged.pid" --log-file="$work/munged.log" --seed-file="$work/munged.seed" \
    || { cluster_logs; fail "munged did not start"; }
  cat > "$SLURM_CONF" << EOF
ClusterName=ringdyntest
SlurmctldHost=$h(127.0.0.1)
SlurmctldPort=$p1
SlurmdPort=$p2
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge.sock
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
KillWait=2
MinJobAge=600
MaxArraySize=10
SlurmdParameters=config_overrides
NodeName=$h NodeAddr=127.0.0.1 CPUs=4 State=UNKNOWN
PartitionName=test Nodes=$h Default=YES MaxTime=INFINITE State=UP
EOF
  slurmctld -f "$SLURM_CONF" 9>&- || { cluster_logs; fail "slurmctld did not start"; }
  slurmd -f "$SLURM_CONF" -N "$h" 9>&- || { cluster_logs; fail "slurmd did not start"; }
  for ((i = 0; i < 100; i++)); do
    [ "$(sinfo -h -o %T 2> /dev/null)" = idle ] && return 0
    sleep 0.2
  done
  cluster_logs
  fail "the node is not idle after 20 s: $(sinfo -h -o '%T %E' 2>&1)"
}

cluster_stop() {  # jobs cancelled, then slurmd, slurmctld, munged; never fails
  local i f pid
  [ -e "$SLURM_CONF" ] || return 0
  scancel --user=root 2> /dev/null || true
  for ((i = 0; i < 50; i++)); do
    [ -z "$(squeue -h 2> /dev/null)" ] && break
    sleep 0.2
  done
  for f in slurmd slurmctld munged; do
    pid=$(cat "$work/$f.pid" 2> /dev/null) || continue
    kill "$pid" 2> /dev/null || continue
    for ((i = 0; i < 50; i++)); do
      kill -0 "$pid" 2> /dev/null || break
      sleep 0.1
    done
    kill -KILL "$pid" 2> /dev/null || true
  done
}

job_field() {  # job_field JOB FIELD: FIELD=value of `scontrol show job` (the first record's)
  # awk reads to the end: an early exit would kill scontrol with SIGPIPE (pipefail).
  scontrol show job -o "$1" | awk -v f="$2=" \
    '!done { for (i = 1; i <= NF; i++) if (index($i, f) == 1) { print substr($i, length(f) + 1); done = 1; break } }'
}

array_tasks() {  # the task ids of array job JID, one a line
  scontrol show job -o "$1" | grep -o 'ArrayTaskId=[^ ]*' | cut -d= -f2 | sort -n
}

wait_field() {  # wait_field JOB FIELD VALUE: up to 60 s
  local i
  for ((i = 0; i < 600; i++)); do
    [ "$(job_field "$1" "$2")" = "$3" ] && return 0
    sleep 0.1
  done
  cluster_logs
  fail "job $1: $2 is not $3 after 60 s: $(job_field "$1" "$2")"
}

wait_ringdyn() {  # wait_ringdyn JOB: until a ringdyn process runs in JOB (60 s)
  local i id pid
  for ((i = 0; i < 600; i++)); do
    id=$(job_field "$1" JobId)
    for pid in $(scontrol listpids "$id" 2> /dev/null | awk 'NR > 1 { print $1 }'); do
      [ "$(cat "/proc/$pid/comm" 2> /dev/null)" = ringdyn ] && return 0
    done
    sleep 0.1
  done
  cluster_logs
  fail "no ringdyn process in job $1 after 60 s: $(job_field "$1" JobState)"
}

wait_gone() {  # wait_gone JID: until no task of JID is pending or running (120 s)
  local i
  for ((i = 0; i < 600; i++)); do
    [ -z "$(squeue -h -j "$1" 2> /dev/null)" ] && return 0
    sleep 0.2
  done
  cluster_logs
  fail "job $1 still queued after 120 s: $(squeue -j "$1")"
}

wait_job() {  # wait_job RID JID: until RID ends (120 s); prints the most JID tasks seen running
  local i most=0 r
  for ((i = 0; i < 600; i++)); do
    case $(job_field "$1" JobState) in
      PENDING | RUNNING | CONFIGURING | COMPLETING) ;;
      *)
        echo $most
        return 0
        ;;
    esac
    if [ "$2" != - ]; then
      r=$(squeue -h -r -t R -j "$2" 2> /dev/null | wc -l)
      [ "$r" -le "$most" ] || most=$r
    fi
    sleep 0.2
  done
  cluster_logs
  fail "job $1 not done after 120 s: $(scontrol show job "$1" | head -n 5)"
}

# modal_spec FILE: the sweep both cluster tests run, 512 points of a modal
# scene (~25 ms each here: a chunk lasts long enough to be cancelled while
# it runs); no output depends on timing.
modal_spec() {
  cat > "$1" <<'EOF'
{"base": {"analysis": "modal", "modal": {"modes": 4}, "discretization": {"segments": 120}},
 "parameters": [
   {"path": "/ring/diameter", "random": {"min": 0.06, "max": 0.1}},
   {"path": "/ring/radial_width", "random": {"min": 0.002, "max": 0.004}}],
 "combine": "latin_hypercube", "samples": 512, "seed": 43,
 "outputs": ["/modes/0/frequency_hz", "max(/modes/*/error_estimate)", "count(/modes)"]}
EOF
}
