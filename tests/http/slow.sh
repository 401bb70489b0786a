#!/usr/bin/env bash
# Slow clients over real HTTP: 300 slow-header connections (from 10 source
# addresses, 30 each) while a normal client is still answered within 1 s;
# the request deadline closes them; the per-address limit refuses the
# connections over it.
#
#   slow.sh SERVER_BINARY RD_JSONQ RD_SLOWCLIENTS
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 SERVER RD_JSONQ RD_SLOWCLIENTS" >&2
  exit 2
fi
SERVER=$1 JQ=$2 SLOWC=$3
. "$(dirname "$0")/lib.sh"

field() { sed -n "s/.*\\b$1=\\([0-9]*\\).*/\\1/p" "$WORK/slow.out"; }

# ---- 300 slowloris connections, deadline 3 s ----------------------------------
# Run 2.5 s: within the deadline every slow connection is held, and the
# normal client (from 127.0.0.1) is answered every 100 ms.
start_server L --request-deadline 3
L_PID=$SPID
PORT=${BASE##*:}
"$SLOWC" "$PORT" 300 10 2.5 >"$WORK/slow.out"
echo "# 300 slow within the deadline: $(cat "$WORK/slow.out")"
same "300 slow connections are all held" "$(field open_after_1s)" 300
check "the normal client got answers" test "$(field normal_total)" -ge 10
same "every normal request answered" "$(field normal_ok)" "$(field normal_total)"
check "each within 1 s" test "$(field normal_max_ms)" -lt 1000

# Run 5 s: the deadline (3 s, checked every 0.1 s) closes every one of them.
"$SLOWC" "$PORT" 300 10 5 >"$WORK/slow.out"
echo "# 300 slow past the deadline: $(cat "$WORK/slow.out")"
same "the deadline closed all 300" "$(field closed)" 300
same "every normal request answered" "$(field normal_ok)" "$(field normal_total)"
check "each within 1 s" test "$(field normal_max_ms)" -lt 1000
req GET /metrics
check "metrics count the deadline closes" \
  grep -q '^ringdyn_connections_deadline_total \(3[0-9][0-9]\|[4-9][0-9][0-9]\)' "$WORK/body"
stop_server L "$L_PID"

# ---- per-address limit ----------------------------------------------------------
start_server P --max-per-ip 16
P_PID=$SPID
PORT=${BASE##*:}
"$SLOWC" "$PORT" 40 1 2 >"$WORK/slow.out"
echo "# 40 slow from one address, limit 16: $(cat "$WORK/slow.out")"
same "16 held from one address" "$(field open_after_1s)" 16
same "24 refused" "$(field closed)" 24
same "every normal request answered (another address)" "$(field normal_ok)" "$(field normal_total)"
stop_server P "$P_PID"

finish
