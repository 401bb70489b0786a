#!/usr/bin/env bash
# The Slurm executor against the service's own workers on one machine: the
# same sweep (default bench/sweeps/lift_auto_2000.json, 2000 lift points with
# model auto) POSTed to a ringdyn-server with --threads 2 and to one with
# --sweep-executor slurm --sweep-slurm-min-points 0 on a throw-away
# single-node Slurm cluster (tests/cluster/slurm_lib.sh; needs root and
# Debian's slurm-wlm and munge), alternately (local first in odd runs, Slurm
# first in even ones), R times each.  Wall time = from the POST to the GET
# that shows the sweep final (GET every 0.2 s); every table must equal the
# local server's byte for byte.
#
# On a shared machine the wall times move with the other load far more than
# by the executor, so each run also prints what does not: the CPU seconds of
# the work (the local server's, from /proc; the tasks', from /usr/bin/time
# around ringdyn) and the executor's own cost, Slurm's wall time minus its
# longest task's (submission, scheduling, polling, reading the chunks).
#   bench/slurm_server.sh [BUILD_DIR] [R] [TASKS] [SPEC]
# (defaults: build, 3 runs, 2 tasks = the machine's 2 cores)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
b=$(realpath "${1:-$root/build}") R=${2:-3} T=${3:-2} spec=$(realpath "${4:-$root/bench/sweeps/lift_auto_2000.json}")
server=$b/server/ringdyn-server ringdyn=$b/cli/ringdyn
fail() { echo "FAIL: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || fail "needs root (slurmd, SlurmdUser=root)"
[ -x /usr/bin/time ] || fail "/usr/bin/time is missing (Debian package time)"
work=$(mktemp -d /tmp/ringdyn-slurm.XXXXXX)
chmod 755 "$work"
exec 9> "$work/lock" && flock -n 9
export SLURM_CONF=$work/slurm.conf
source "$root/tests/cluster/slurm_lib.sh"
source "$root/tests/cluster/slurm_server_lib.sh"
trap 'servers_stop; cluster_stop; rm -rf "$work"' EXIT
trap 'exit 1' TERM INT HUP
cluster_start "$work"
mkdir "$work/shared"
# Each task's ringdyn under /usr/bin/time: "wall user sys" a line.
printf '#!/bin/sh\nexec /usr/bin/time -a -o %s -f "%%e %%U %%S" %s "$@"\n' "$work/tasks.time" "$ringdyn" > "$work/ringdyn-timed"
chmod +x "$work/ringdyn-timed"
server_start local --threads 2
server_start slurm --threads 2 --sweep-executor slurm --sweep-shared-dir "$work/shared" \
  --sweep-slurm-script "$root/deploy/slurm-sweep.sh" --sweep-ringdyn "$work/ringdyn-timed" \
  --sweep-slurm-min-points 0 --sweep-slurm-tasks "$T"
local_pid=${servers[0]}

cpu_of() { awk '{ print $14 + $15 }' "/proc/$1/stat"; }  # utime + stime, clock ticks
timed() {  # timed URL NAME: "wall_s" of one sweep of $spec
  local t0 id
  t0=$(now)
  id=$(post_sweep "$1" "$spec")
  sweep_wait "$1" "$id" "$work/$2.json" 1200
  since "$t0"
  [ "$(jq -r .status "$work/$2.json")" = succeeded ] || fail "$2: $(jq -c 'del(.table)' "$work/$2.json")"
  curl -sS -o /dev/null -X DELETE "$1/api/v1/sweeps/$id"
}
run_local() { local c0 w; c0=$(cpu_of "$local_pid"); w=$(timed "$local" L)
  echo "$w $(awk -v a="$c0" -v b="$(cpu_of "$local_pid")" -v hz="$(getconf CLK_TCK)" 'BEGIN { printf "%.1f", (b - a) / hz }')"; }
run_slurm() { local w; : > "$work/tasks.time"; w=$(timed "$slurm" S)
  echo "$w $(awk '{ u += $2 + $3; if ($1 > m) m = $1 } END { printf "%.1f %.1f", u, m }' "$work/tasks.time")"; }

echo "spec $(basename "$spec"): $("$ringdyn" sweep count "$spec") points; $T Slurm tasks; load $(cut -d' ' -f1-3 /proc/loadavg)"
: > "$work/times"
for ((r = 1; r <= R; r++)); do
  if ((r % 2)); then
    l=$(run_local) s=$(run_slurm)
  else
    s=$(run_slurm) l=$(run_local)
  fi
  [ "$(sweep_table "$work/S.json")" = "$(sweep_table "$work/L.json")" ] || fail "run $r: tables differ"
  read -r lw lc <<< "$l"
  read -r sw sc longest <<< "$s"
  echo "$lw $sw $lc $sc $longest" >> "$work/times"
  awk -v lw="$lw" -v sw="$sw" -v lc="$lc" -v sc="$sc" -v m="$longest" -v r="$r" -v la="$(cut -d' ' -f1 /proc/loadavg)" \
    'BEGIN { printf "run %d: local %.1f s (CPU %.1f s), slurm %.1f s (%+.1f %%; tasks CPU %.1f s, longest task %.1f s: executor %.1f s), tables identical, load %s\n",
             r, lw, lc, sw, (sw / lw - 1) * 100, sc, m, sw - m, la }'
done
med() { sort -n | awk '{ v[NR] = $1 } END { printf "%.1f", (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
echo "medians: local $(cut -d' ' -f1 "$work/times" | med) s, slurm $(cut -d' ' -f2 "$work/times" | med) s;" \
  "CPU local $(cut -d' ' -f3 "$work/times" | med) s, tasks $(cut -d' ' -f4 "$work/times" | med) s;" \
  "executor (slurm wall - longest task) $(awk '{ print $2 - $5 }' "$work/times" | med) s"
