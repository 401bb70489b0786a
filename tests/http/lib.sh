# Shared helpers of the HTTP test scripts (sourced; needs SERVER and JQ set).
# Every script prints "ok   - ..." / "FAIL - ..." lines and ends with "N passed, N failed".
WORK=$(mktemp -d "${TMPDIR:-/tmp}/ringdyn-http.XXXXXX")
PIDS=()
CURL_EXTRA=() # curl arguments added to every req (e.g. an Authorization header)

cleanup() {
  local p
  for p in "${PIDS[@]}"; do kill -KILL "$p" 2>/dev/null || true; done
  rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 130' INT TERM # so that the EXIT trap also runs when ctest times us out

PASSED=0 FAILED=0
LIB_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ANSWERS=0
ok() { PASSED=$((PASSED + 1)); echo "ok   - $1"; }
bad() { FAILED=$((FAILED + 1)); echo "FAIL - $1${2:+ ($2)}"; }
# check NAME COMMAND...: passes when the command succeeds.
check() { local name=$1; shift; if "$@"; then ok "$name"; else bad "$name"; fi; }
# same NAME GOT WANT
same() { if [ "$2" = "$3" ]; then ok "$1"; else bad "$1" "got '$2', want '$3'"; fi; }

# start_server NAME ARGS...: starts a server, sets BASE and SPID.
start_server() {
  local name=$1; shift
  local data=(--data :memory:) # unless the caller names a store
  case " $* " in *" --data "*) data=() ;; esac
  "$SERVER" --host 127.0.0.1 --port 0 "${data[@]}" "$@" >"$WORK/$name.out" 2>"$WORK/$name.err" &
  SPID=$!
  PIDS+=("$SPID")
  local i line=""
  for i in $(seq 1 150); do # 15 s: sanitizer builds start slowly
    line=$(head -n 1 "$WORK/$name.out" 2>/dev/null || true)
    [ -n "$line" ] && break
    kill -0 "$SPID" 2>/dev/null || break
    sleep 0.1
  done
  if [[ ! $line =~ ^ringdyn-server\ listening\ on\ http://127\.0\.0\.1:([0-9]+)$ ]]; then
    echo "server $name did not start; stdout: '$line'; stderr:" >&2
    cat "$WORK/$name.err" >&2
    exit 1
  fi
  BASE="http://127.0.0.1:${BASH_REMATCH[1]}"
  # the contract every answer is checked against (finish), from the first server
  [ -s "$WORK/openapi.json" ] ||
    curl -sS --max-time 30 -o "$WORK/openapi.json" "$BASE/api/v1/openapi.json" 2>/dev/null || true
}

# stop_server NAME PID: SIGTERM, then the exit status within 30 s.
stop_server() {
  local name=$1 pid=$2 i
  kill -TERM "$pid"
  for i in $(seq 1 300); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if kill -0 "$pid" 2>/dev/null; then
    bad "$name stops within 30 s of SIGTERM"
    return
  fi
  local rc=0
  wait "$pid" || rc=$?
  same "$name exits 0 after SIGTERM" "$rc" 0
  if grep -q "ERROR: \(Leak\|Address\)Sanitizer\|WARNING: ThreadSanitizer\|runtime error:" "$WORK/$name.err"; then
    bad "$name: sanitizer report" "$(grep -m 3 "Sanitizer\|runtime error" "$WORK/$name.err")"
  else
    ok "$name: no sanitizer report"
  fi
}

# req METHOD PATH [CURL ARGS...]: STATUS, $WORK/body, $WORK/headers.
req() {
  local method=$1 path=$2; shift 2
  local how=(-X "$method")
  if [ "$method" = HEAD ]; then how=(-I); fi
  rm -f "$WORK/body" # curl writes no file for an empty body: no stale one is read as this answer's
  STATUS=$(curl -sS --path-as-is --max-time 90 "${how[@]}" -o "$WORK/body" -D "$WORK/headers" \
             -w '%{http_code}' "${CURL_EXTRA[@]}" "$@" "$BASE$path" 2>"$WORK/curl.err") || STATUS=000
  record_answer "$method" "$path"
}
# record_answer METHOD PATH: keeps the last answer ($WORK/answers/N.meta and
# N.body) for finish, which validates every answer a script got against the
# served OpenAPI document (contract.py --answers). HEAD and no answer: not kept.
record_answer() {
  if [ "$1" = HEAD ] || [ "$STATUS" = 000 ]; then return 0; fi
  ANSWERS=$((ANSWERS + 1))
  mkdir -p "$WORK/answers"
  printf '%s\t%s\t%s\t%s\t%s\n' "$1" "$2" "$STATUS" "$(header Content-Type)" \
    "$(header Content-Encoding)" >"$WORK/answers/$ANSWERS.meta"
  cp "$WORK/body" "$WORK/answers/$ANSWERS.body" 2>/dev/null || : >"$WORK/answers/$ANSWERS.body"
}
# finish: every kept answer against the served document, then the summary
# line and the script's exit status.
finish() {
  if [ "$ANSWERS" -gt 0 ]; then
    if [ ! -s "$WORK/openapi.json" ]; then
      bad "the answers against the OpenAPI document" "no document was served"
    elif python3 "$LIB_DIR/contract.py" --answers "$WORK/openapi.json" "$WORK/answers" >"$WORK/contract.out" 2>&1; then
      ok "$(tail -n 1 "$WORK/contract.out")"
    else
      cat "$WORK/contract.out"
      bad "the answers against the OpenAPI document" "$(tail -n 1 "$WORK/contract.out")"
    fi
  fi
  echo "$PASSED passed, $FAILED failed"
  [ "$FAILED" -eq 0 ]
}
# post PATH BODY: a new job every time (the result cache would answer a
# repeated scene with the earlier job; cache.sh tests the cache).
post() { req POST "$1" -H 'Content-Type: application/json' -H 'Cache-Control: no-cache' --data-binary "$2"; }
# json POINTER [FILE]: the value, or "" when absent.
json() { "$JQ" "$1" "${2:-$WORK/body}" 2>/dev/null || true; }
jcount() { "$JQ" -n "$1" "${2:-$WORK/body}" 2>/dev/null || echo 0; }
header() { grep -i "^$1:" "$WORK/headers" | head -n 1 | cut -d ' ' -f 2- | tr -d '\r' || true; }

# expect_error NAME STATUS CODE [PATH]: the last answer is that error.
expect_error() {
  local name=$1 status=$2 code=$3 path=${4:-}
  if [ "$STATUS" = "$status" ] && [ "$(json /error/code)" = "$code" ] &&
     [ "$(json /error/path)" = "$path" ] && [ -n "$(json /error/message)" ] &&
     [[ $(header Content-Type) == application/json* ]]; then
    ok "$name -> $status $code${path:+ at $path}"
  else
    bad "$name -> $status $code${path:+ at $path}" "got $STATUS $(head -c 300 "$WORK/body")"
  fi
}

# ascending FILE: numbers, one a line, strictly increasing and positive.
