#!/usr/bin/env bash
# The bad-input battery, data-driven: battery.txt holds one case a line,
#
#   STATUS CODE PATH | METHOD URL | BODY | HEADER ;; HEADER ...
#
# PATH is the JSON Pointer the error must name ("-": none); CODE "-" marks
# an answer that is not ringdyn's JSON (libmicrohttpd's own page, README);
# STATUS 000: the connection is closed without an answer.  A POST carries
# Content-Type: application/json unless a header of the case says otherwise.
# METHOD RAW sends BODY as the whole request (printf %b escapes: \r\n) on a
# fresh connection.  Every case runs against one server; after the battery
# the server must still answer and must have queued no job.
#
#   battery.sh SERVER_BINARY RD_JSONQ BATTERY_FILE
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 SERVER RD_JSONQ BATTERY_FILE" >&2
  exit 2
fi
SERVER=$1 JQ=$2 CASES=$3
. "$(dirname "$0")/lib.sh"

trim() { local s=$1; s=${s#"${s%%[![:space:]]*}"}; s=${s%"${s##*[![:space:]]}"}; printf '%s' "$s"; }

# raw REQUEST: STATUS and $WORK/body from one connection (5 s at most)
raw() {
  local port=${BASE##*:}
  # The server may answer and close before the whole request is written:
  # the write may then fail (EPIPE), the answer is still read.
  timeout 5 bash -c 'trap "" PIPE; exec 3<>"/dev/tcp/127.0.0.1/$1" && { printf "%b" "$2" >&3 || true; } && cat <&3' \
    _ "$port" "$1" >"$WORK/raw" 2>/dev/null || true
  STATUS=$(head -n 1 "$WORK/raw" | awk '{ print $2 }')
  STATUS=${STATUS:-000}
  awk 'body { print } /^\r?$/ { body = 1 }' "$WORK/raw" >"$WORK/body"
  grep -i '^Content-Type:' "$WORK/raw" | head -n 1 >"$WORK/headers" || true
}

start_server B
B_PID=$SPID
n=0
while IFS= read -r line || [ -n "$line" ]; do
  case $line in '' | '#'*) continue ;; esac
  IFS='|' read -r want request body headers <<<"${line// | /|}"
  read -r status code path <<<"$want"
  read -r method url <<<"$request"
  body=$(trim "${body:-}")
  n=$((n + 1))
  name="#$n $method $url ${body:0:60}"
  if [ "$method" = RAW ]; then
    raw "$body"
  else
    args=()
    has_type=0
    if [ -n "${headers:-}" ]; then
      while IFS= read -r h; do
        h=$(trim "$h")
        [ -z "$h" ] && continue
        args+=(-H "$h")
        case ${h,,} in content-type:*) has_type=1 ;; esac
      done <<<"${headers// ;; /$'\n'}"
    fi
    if [ "$method" = POST ] && [ "$has_type" = 0 ]; then args+=(-H 'Content-Type: application/json'); fi
    if [ -n "$body" ]; then args+=(--data-binary "$body"); fi
    req "$method" "$url" "${args[@]}"
  fi
  if [ "$code" = - ]; then
    same "$name -> $status" "$STATUS" "$status"
  else
    [ "$path" = - ] && path=""
    expect_error "$name" "$status" "$code" "$path"
  fi
done <"$CASES"
echo "# $n cases"
check "at least 400 cases" test "$n" -ge 400

req GET /api/v1/health
same "the server still answers" "$STATUS" 200
req GET /api/v1/jobs
same "no bad input was queued" "$("$JQ" -n /jobs "$WORK/body")" 0
stop_server B "$B_PID"

finish
