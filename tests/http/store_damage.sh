#!/usr/bin/env bash
# The store never lies (issue 45): each kind of damage to the job store's
# files has one clear, logged outcome (README, "The job store"):
#   0-byte file, truncated file, zeroed page -> moved aside to
#       jobs.sqlite3.damaged-<time>, a log line saying so, an empty store;
#   damaged bytes inside a stored result -> that job is a 500 error JSON
#       naming it ("damaged on disk"), every other job served as before;
#   damaged bytes inside a finished sweep -> left out (404), named in the log;
#   damaged WAL -> a log line with the commits lost, a copy of the WAL kept;
#   an intact WAL after kill -9 -> no such line, every job back (the control).
#
#   store_damage.sh SERVER_BINARY RD_JSONQ
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 SERVER RD_JSONQ" >&2
  exit 2
fi
SERVER=$1 JQ=$2
. "$(dirname "$0")/lib.sh"

JOBS=6
# fill DIR STOP: JOBS finished modal jobs and one finished sweep in DIR, then
# stop the server with STOP (TERM: a clean store file; KILL: all in the WAL).
fill() {
  local i
  start_server F --data "$1"
  for i in $(seq 1 "$JOBS"); do
    post '/api/v1/jobs?wait=60' "{\"analysis\":\"modal\",\"ring\":{\"tangential_force\":1$i}}"
  done
  post '/api/v1/sweeps?wait=60' '{"base": {"analysis": "modal"}, "parameters": [{"path":
    "/ring/tangential_force", "values": [8, 9]}], "outputs": ["/modes/0/frequency_hz"]}'
  SWEEP=$(json /id)
  if [ "$2" = KILL ]; then
    kill -KILL "$SPID"
    wait "$SPID" 2>/dev/null || true
  else
    stop_server F "$SPID" >/dev/null
  fi
}
fill "$WORK/clean" TERM
CLEAN_SWEEP=$SWEEP
fill "$WORK/crash" KILL
check "a clean stop leaves no WAL" test ! -s "$WORK/clean/jobs.sqlite3-wal"
check "kill -9 leaves the jobs in the WAL" test -s "$WORK/crash/jobs.sqlite3-wal"

# exists GLOB: a file matches
exists() { compgen -G "$1" >/dev/null; }
# from COPY: a fresh copy of a filled store in $WORK/d
from() { rm -rf "$WORK/d"; cp -r "$WORK/$1" "$WORK/d"; }
# listed: the number of jobs the server lists
listed() { req GET /api/v1/jobs; jcount /jobs; }
# quarantined NAME: the server started, said the file is damaged and where it
# went, the damaged file is there, and the store is empty but works.
quarantined() {
  start_server Q --data "$WORK/d"
  check "$1: the log says the store file is damaged and was moved aside" \
    grep -q "jobs.sqlite3 is damaged (.*moved aside to .*jobs.sqlite3.damaged-" "$WORK/Q.err"
  check "... and how to recover it" grep -q "sqlite3 .*\.recover" "$WORK/Q.err"
  check "... the damaged file is kept" exists "$WORK/d/jobs.sqlite3.damaged-*"
  same "... no job is listed" "$(listed)" 0
  post '/api/v1/jobs?wait=60' '{"analysis":"modal"}'
  same "... a new job runs and is stored" "$STATUS $(listed)" "200 1"
  stop_server Q "$SPID" >/dev/null
}

from clean
: >"$WORK/d/jobs.sqlite3"
quarantined "0-byte store file"
check "... saying it was 0 bytes" grep -q "0 bytes long" "$WORK/Q.err"

from clean
truncate -s "$(($(stat -c %s "$WORK/d/jobs.sqlite3") / 2))" "$WORK/d/jobs.sqlite3"
quarantined "store file truncated to half"

from clean
dd if=/dev/zero of="$WORK/d/jobs.sqlite3" bs=4096 seek=4 count=1 conv=notrunc 2>/dev/null
quarantined "page 5 zeroed"
check "... with SQLite's finding" grep -q "quick_check" "$WORK/Q.err"

# One byte of one stored result: the JSON breaks, SQLite's structure does not.
from clean
off=$(grep -obUa '"rigid_body_modes":' "$WORK/d/jobs.sqlite3" | head -n 1 | cut -d: -f1)
printf 'X' | dd of="$WORK/d/jobs.sqlite3" bs=1 seek="$off" conv=notrunc 2>/dev/null
start_server R --data "$WORK/d"
check "damaged result: no quarantine (the file is sound)" \
  test ! -e "$(compgen -G "$WORK/d/jobs.sqlite3.damaged-*" || echo /none)"
same "... every job is listed" "$(listed)" "$JOBS"
served=0 damaged=0
for k in $(seq 0 $((JOBS - 1))); do
  req GET /api/v1/jobs
  id=$(json "/jobs/$k/id")
  req GET "/api/v1/jobs/$id"
  if [ "$STATUS" = 200 ] && "$JQ" /result/analysis "$WORK/body" >/dev/null 2>&1; then
    served=$((served + 1))
  elif [ "$STATUS" = 500 ] && [ "$(json /error/code)" = internal_error ] &&
    grep -q "result of job $id is damaged on disk" "$WORK/body"; then
    damaged=$((damaged + 1))
  fi
done
same "... the damaged one is an error JSON naming it, the others are served" \
  "$damaged $served" "1 $((JOBS - 1))"
stop_server R "$SPID" >/dev/null

# One byte of the finished sweep's CSV.
from clean
off=$(grep -obUa 'frequency_hz,status,error' "$WORK/d/jobs.sqlite3" | head -n 1 | cut -d: -f1)
printf 'X' | dd of="$WORK/d/jobs.sqlite3" bs=1 seek="$off" conv=notrunc 2>/dev/null
start_server W --data "$WORK/d"
check "damaged sweep: named in the log" grep -q "sweeps damaged on disk.*$CLEAN_SWEEP" "$WORK/W.err"
req GET "/api/v1/sweeps/$CLEAN_SWEEP"
expect_error "... and not served" 404 not_found
same "... the jobs are all there" "$(listed)" "$JOBS"
stop_server W "$SPID" >/dev/null

# The WAL of a killed server, intact and damaged in its middle.
from crash
start_server C --data "$WORK/d"
check "intact WAL after kill -9: nothing reported" test -z "$(grep 'job store' "$WORK/C.err" || true)"
same "... every job is back" "$(listed)" "$JOBS"
stop_server C "$SPID" >/dev/null

from crash
wal=$WORK/d/jobs.sqlite3-wal
printf 'XXXX' | dd of="$wal" bs=1 seek=$(($(stat -c %s "$wal") / 2)) conv=notrunc 2>/dev/null
start_server V --data "$WORK/d"
check "damaged WAL: the log says what is lost" \
  grep -q "the WAL .* is damaged at frame [0-9]* of its [0-9]* frames: the last [1-9][0-9]* committed" \
  "$WORK/V.err"
check "... a copy of the WAL is kept" exists "$WORK/d/jobs.sqlite3-wal.damaged-*"
n=$(listed)
check "... fewer jobs come back ($n of $JOBS)" test "$n" -lt "$JOBS"
stop_server V "$SPID" >/dev/null

from crash
printf 'XXXX' | dd of="$WORK/d/jobs.sqlite3-wal" bs=1 seek=30 conv=notrunc 2>/dev/null
start_server H --data "$WORK/d"
check "WAL header damaged: the log says every commit in it is lost" \
  grep -q "damaged in its header, so SQLite drops all" "$WORK/H.err"
same "... no job comes back" "$(listed)" 0
stop_server H "$SPID" >/dev/null

finish
