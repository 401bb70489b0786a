#!/usr/bin/env bash
# Access control over real HTTP: the Host allowlist (DNS rebinding gets 403)
# and the bearer token of --token-file.
#
#   access.sh SERVER_BINARY RD_JSONQ
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 SERVER RD_JSONQ" >&2
  exit 2
fi
SERVER=$1 JQ=$2
. "$(dirname "$0")/lib.sh"

# ---- Host allowlist: loopback names (any port) and --allow-host ------------
start_server H --allow-host Ringdyn.LAN
H_PID=$SPID
for host in evil.example evil.example:80 '127.0.0.1.evil.example' 'localhost:abc' 'localhost:' \
            '[::2]' 'ringdyn.lan.evil' '[::1'; do
  req GET /api/v1/health -H "Host: $host"
  expect_error "Host: $host on /api/v1/health" 403 forbidden_host
done
req GET / -H 'Host: evil.example'
expect_error "Host: evil.example on the page" 403 forbidden_host
req POST /api/v1/jobs -H 'Host: evil.example' -H 'Content-Type: application/json' \
  --data-binary '{"analysis":"modal"}'
expect_error "Host: evil.example on POST /api/v1/jobs" 403 forbidden_host
req GET /api/v1/jobs
same "the refused POST queued nothing" "$("$JQ" -n /jobs "$WORK/body")" 0
for host in 127.0.0.1 127.0.0.1:8080 localhost LOCALHOST:1 '[::1]' '[::1]:443' ringdyn.lan \
            ringdyn.lan:8080; do
  req GET /api/v1/health -H "Host: $host"
  same "Host: $host served" "$STATUS" 200
done
# HTTP/1.0 may omit Host; browsers (the DNS-rebinding threat) never do.
STATUS=$(curl -sS -0 -H 'Host:' -o /dev/null -w '%{http_code}' "$BASE/api/v1/health" || echo 000)
same "HTTP/1.0 without Host served" "$STATUS" 200
stop_server H "$H_PID"

# ---- token ---------------------------------------------------------------------
head -c 24 /dev/urandom | base64 >"$WORK/token"
TOKEN=$(cat "$WORK/token")
start_server T --token-file "$WORK/token"
T_PID=$SPID
for path in /api/v1/jobs /api/v1/jobs/0123456789abcdef /api/v1/examples /metrics; do
  req GET "$path"
  expect_error "no token: GET $path" 401 unauthorized
done
check "401 carries WWW-Authenticate: Bearer" grep -qi '^WWW-Authenticate: Bearer' "$WORK/headers"
req POST /api/v1/jobs -H 'Content-Type: application/json' --data-binary '{"analysis":"modal"}'
expect_error "no token: POST /api/v1/jobs" 401 unauthorized
req GET /api/v1/jobs -H "Authorization: Bearer ${TOKEN}x"
expect_error "a longer token" 401 unauthorized
req GET /api/v1/jobs -H "Authorization: Bearer ${TOKEN%?}"
expect_error "a shorter token" 401 unauthorized
req GET /api/v1/jobs -H "Authorization: Basic ${TOKEN}"
expect_error "the token under another scheme" 401 unauthorized
req GET /api/v1/health
same "health needs no token" "$STATUS" 200
req GET /api/v1/openapi.json
same "openapi needs no token" "$STATUS" 200
CURL_EXTRA=(-H "Authorization: Bearer $TOKEN")
post '/api/v1/jobs?wait=60' '{"analysis":"modal"}'
same "with the token: POST ?wait -> 200" "$STATUS" 200
same "with the token: the job succeeded" "$(json /status)" succeeded
req GET /api/v1/jobs -H "Authorization: bearer  $TOKEN"
same "scheme in any case, extra blanks" "$STATUS" 200
req GET /metrics
same "with the token: metrics" "$STATUS" 200
CURL_EXTRA=()
stop_server T "$T_PID"

# ---- start-up refusals -------------------------------------------------------------
refuses() { # NAME WANT_IN_STDERR ARGS...
  local name=$1 want=$2 rc=0; shift 2
  timeout 20 "$SERVER" --data :memory: "$@" >"$WORK/refuse.out" 2>"$WORK/refuse.err" || rc=$?
  if [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] && grep -q -- "$want" "$WORK/refuse.err"; then
    ok "$name"
  else
    bad "$name" "exit $rc: $(head -c 300 "$WORK/refuse.err")"
  fi
}
refuses "--host 0.0.0.0 without a token is refused" --token-file --host 0.0.0.0 --port 0
printf 'short\n' >"$WORK/short"
refuses "a 5-character token is refused" --token-file --port 0 --token-file "$WORK/short"
refuses "a missing token file is refused" --token-file --port 0 --token-file "$WORK/none"
refuses "--allow-host with a port is refused" --allow-host --port 0 --allow-host a.example:80

# 0.0.0.0 with a token starts, and the token is asked for
"$SERVER" --data :memory: --host 0.0.0.0 --port 0 --token-file "$WORK/token" >"$WORK/any.out" 2>"$WORK/any.err" &
PIDS+=($!)
ANY_PID=$!
for _ in $(seq 1 150); do
  grep -q listening "$WORK/any.out" 2>/dev/null && break
  sleep 0.1
done
PORT=$(grep -o '[0-9]*$' "$WORK/any.out" || true)
check "--host 0.0.0.0 with a token starts" test -n "$PORT"
BASE="http://127.0.0.1:$PORT"
req GET /api/v1/jobs
expect_error "on 0.0.0.0: no token" 401 unauthorized
stop_server any "$ANY_PID"

finish
