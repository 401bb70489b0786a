#!/usr/bin/env bash
# HTTP protocol behaviour over real HTTP on 127.0.0.1 (issue 45, item 6):
# keep-alive and pipelining (every answer, in order, on one connection),
# the page's security headers (and no inline script in static/*.html), the
# per-address limit answered 429 JSON with Retry-After, SIGXFSZ ignored (a
# store write past `ulimit -f` fails, the server lives).
#
#   protocol.sh SERVER_BINARY RD_JSONQ STATIC_DIR
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 SERVER RD_JSONQ STATIC_DIR" >&2
  exit 2
fi
SERVER=$1 JQ=$2 STATIC=$3
. "$(dirname "$0")/lib.sh"

# pipe REQUESTS: writes them all at once on one connection, reads until the
# server closes it (the last request says Connection: close) into $WORK/pipe.
pipe() {
  local port=${BASE##*:}
  timeout 10 bash -c 'exec 3<>"/dev/tcp/127.0.0.1/$1" && printf "%b" "$2" >&3 && cat <&3' \
    _ "$port" "$1" >"$WORK/pipe" 2>/dev/null || true
}
# statuses: the status codes of every answer in $WORK/pipe, space-separated.
statuses() { grep -ao 'HTTP/1\.1 [0-9][0-9][0-9]' "$WORK/pipe" | awk '{ printf "%s%s", sep, $2; sep = " " }'; }

start_server A --static "$STATIC"
A_PID=$SPID
H='Host: 127.0.0.1\r\n'

# ---- keep-alive ------------------------------------------------------------------
curl -sS -v -o /dev/null -o /dev/null "$BASE/api/v1/health" "$BASE/api/v1/jobs" 2>"$WORK/kv" || true
check "two GETs share one connection (curl reuses it)" grep -q 'Re-using existing connection' "$WORK/kv"
check "a GET is not answered Connection: close" \
  bash -c "! grep -qi '^< Connection: close' '$WORK/kv'"

# ---- pipelining: every answer, in order --------------------------------------------
pipe "GET /api/v1/health HTTP/1.1\r\n$H\r\nGET /api/v1/nothing HTTP/1.1\r\n$H\r\nHEAD / HTTP/1.1\r\n$H\r\nGET /api/v1/health HTTP/1.1\r\n${H}Connection: close\r\n\r\n"
same "4 pipelined GET/HEAD get 4 answers in order" "$(statuses)" "200 404 200 200"
check "the 404 among them is JSON" grep -q '"code":"not_found"' "$WORK/pipe"
BODY422='{"analysis":"modal","ring":{"diameter":-1}}'
pipe "POST /api/v1/jobs HTTP/1.1\r\n${H}Content-Type: application/json\r\nContent-Length: ${#BODY422}\r\n\r\n${BODY422}GET /api/v1/health HTTP/1.1\r\n${H}Connection: close\r\n\r\n"
same "a GET pipelined behind a POST is answered too" "$(statuses)" "422 200"

# ---- the page's security headers ----------------------------------------------------
for path in / /static/app.js /static/style.css; do
  req GET "$path"
  csp=$(header Content-Security-Policy)
  check "$path: CSP runs scripts from this origin only" \
    bash -c "[[ \"\$1\" == *\"script-src 'self';\"* && \"\$1\" != *unsafe-eval* ]]" _ "$csp"
  check "$path: CSP forbids framing" bash -c "[[ \"\$1\" == *\"frame-ancestors 'none'\"* ]]" _ "$csp"
  same "$path: X-Frame-Options" "$(header X-Frame-Options)" DENY
  same "$path: Referrer-Policy" "$(header Referrer-Policy)" no-referrer
done
check "CSP: no inline script allowed anywhere" \
  bash -c "! grep -q \"script-src[^;]*unsafe-inline\" <<<\"\$1\"" _ "$csp"
# the page must work under that policy: no inline <script> body, no on*= handler
inline=$(grep -hoiE '<script[^>]*>[^<[:space:]]|<[a-z][^>]*[[:space:]]on[a-z]+=' "$STATIC"/*.html || true)
same "static/*.html: no inline script or event-handler attribute" "$inline" ""
check "every <script> of the page has a src" \
  bash -c "! grep -hoi '<script[^>]*>' \"\$1\"/*.html | grep -vqi 'src='" _ "$STATIC"
stop_server A "$A_PID"

# ---- over the per-address limit: 429, JSON, Retry-After ------------------------------
start_server P --max-per-ip 2
P_PID=$SPID
PORT=${BASE##*:}
exec 5<>"/dev/tcp/127.0.0.1/$PORT" 6<>"/dev/tcp/127.0.0.1/$PORT"
sleep 0.2
req GET /api/v1/health
expect_error "a third connection from one address (limit 2)" 429 too_many_connections
same "429 carries Retry-After" "$(header Retry-After)" 1
exec 5>&- 6>&-
sleep 0.3
req GET /api/v1/health
same "once they close, the address is served again" "$STATUS" 200
stop_server P "$P_PID"

# ---- SIGXFSZ: a store write past the file-size limit fails, the server lives ----------
# (ulimit -f 64: 64 KiB; a default lift result with its per-segment table is larger)
mkdir -p "$WORK/xfsz"
SAVED=$SERVER
SERVER=$WORK/limited
printf '#!/usr/bin/env bash\nulimit -f 64\nexec "%s" "$@"\n' "$SAVED" >"$SERVER"
chmod +x "$SERVER"
start_server X --data "$WORK/xfsz"
X_PID=$SPID
SERVER=$SAVED
post '/api/v1/jobs?wait=60' '{"analysis":"lift"}'
check "the job's store write failed cleanly with a JSON error" \
  bash -c "[[ \$1 == 5?? ]] && [ -n \"\$2\" ]" _ "$STATUS" "$(json /error/code)"
check "the server still runs" kill -0 "$X_PID"
req GET /api/v1/health
same "and answers" "$STATUS" 200
stop_server X "$X_PID"

finish
