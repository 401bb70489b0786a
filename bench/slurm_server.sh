#!/usr/bin/env bash
# The Slurm executor against the service's own workers on one machine: the
# same sweep (default bench/sweeps/lift_auto_2000.json, 2000 lift points with
# model auto) POSTed to a ringdyn-server with --threads 2 and to one with
# --sweep-executor slurm --sweep-slurm-min-points 0 on a throw-away
# single-node Slurm cluster (tests/cluster/slurm_lib.sh; needs root and
# Debian's slurm-wlm and munge), alternately (local first in odd runs, Slurm first in even ones), R times each.  Wall time = from
# the POST to the GET that shows the sweep final (GET every 0.2 s); every
# table must equal the local server's byte for byte.  Prints each pair and
# the medians.
#   bench/slurm_server.sh [BUILD_DIR] [R] [TASKS] [SPEC]
# (defaults: build, 3 runs, 2 tasks = the machine's 2 cores)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
b=$(realpath "${1:-$root/build}") R=${2:-3} T=${3:-2} spec=$(realpath "${4:-$root/bench/sweeps/lift_auto_2000.json}")
server=$b/server/ringdyn-server ringdyn=$b/cli/ringdyn
fail() { echo "FAIL: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || fail "needs root (slurmd, SlurmdUser=root)"
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
server_start local --threads 2
server_start slurm --threads 2 --sweep-executor slurm --sweep-shared-dir "$work/shared" \
  --sweep-slurm-script "$root/deploy/slurm-sweep.sh" --sweep-ringdyn "$ringdyn" \
  --sweep-slurm-min-points 0 --sweep-slurm-tasks "$T"

timed() {  # timed URL NAME: the wall time of one sweep of $spec
  local t0 id
  t0=$(now)
  id=$(post_sweep "$1" "$spec")
  sweep_wait "$1" "$id" "$work/$2.json" 1200
  echo "$(since "$t0")"
  [ "$(jq -r .status "$work/$2.json")" = succeeded ] || fail "$2: $(jq -c 'del(.table)' "$work/$2.json")"
  curl -sS -o /dev/null -X DELETE "$1/api/v1/sweeps/$id"
}
echo "spec $(basename "$spec"): $("$ringdyn" sweep count "$spec") points; $T Slurm tasks; load $(cut -d' ' -f1-3 /proc/loadavg)"
: > "$work/times"
for ((r = 1; r <= R; r++)); do
  if ((r % 2)); then  # the order alternates, so that a drift in the load favours neither
    tl=$(timed "$local" L) ts=$(timed "$slurm" S)
  else
    ts=$(timed "$slurm" S) tl=$(timed "$local" L)
  fi
  [ "$(sweep_table "$work/S.json")" = "$(sweep_table "$work/L.json")" ] || fail "run $r: tables differ"
  echo "$tl $ts" >> "$work/times"
  awk -v l="$tl" -v s="$ts" -v r="$r" -v la="$(cut -d' ' -f1 /proc/loadavg)" \
    'BEGIN { printf "run %d: local %.1f s, slurm %.1f s (%+.1f %%), tables identical, load %s\n", r, l, s, (s / l - 1) * 100, la }'
done
sort -n -k1 "$work/times" | awk '{ l[NR] = $1 } END { printf "median local %.1f s, ", l[int((NR + 1) / 2)] }'
sort -n -k2 "$work/times" | awk '{ s[NR] = $2 } END { printf "median slurm %.1f s\n", s[int((NR + 1) / 2)] }'
