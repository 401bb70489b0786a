#!/usr/bin/env bash
# Browser test: starts ringdyn-server on a free port, runs test.mjs (headless
# Chromium via playwright-core) against it, and stops the server on exit.
#   tests/browser/run.sh <server-binary> <static-dir> <examples-dir> <shot-dir>
# Screenshots and the server's output go to <shot-dir>.  A missing chromium,
# node or playwright-core is a failure, not a skip.
set -euo pipefail
if [ $# -ne 4 ]; then
  echo "usage: $0 <server-binary> <static-dir> <examples-dir> <shot-dir>" >&2
  exit 2
fi
server=$1 static=$2 examples=$3 shots=$4
here=$(cd "$(dirname "$0")" && pwd)

fail() { echo "browser test FAILED: $*" >&2; exit 1; }
[ -x /usr/bin/chromium ] || fail "/usr/bin/chromium is missing; install it with scripts/install-deps.sh --test (Debian package chromium)"
command -v node >/dev/null 2>&1 || fail "node is missing; install it with scripts/install-deps.sh --test"
[ -f "$here/node_modules/playwright-core/package.json" ] ||
  fail "playwright-core is not installed in $here; run 'npm install' there (scripts/test.sh does)"
[ -x "$server" ] || fail "server binary '$server' does not exist"
mkdir -p "$shots"

out="$shots/browser-server.out" log="$shots/browser-server.log"
: >"$out" # exists before the server starts, so the polling below never races its redirect
"$server" --data :memory: --host 127.0.0.1 --port 0 --static "$static" --examples "$examples" >"$out" 2>"$log" &
pid=$!
cleanup() {
  kill "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
}
trap cleanup EXIT
trap 'exit 1' INT TERM

# The server prints one line: "ringdyn-server listening on http://HOST:PORT".
url=""
for _ in $(seq 100); do
  url=$(sed -n 's|^ringdyn-server listening on \(http://[^ ]*\).*$|\1|p' "$out" | head -n 1)
  [ -n "$url" ] && break
  kill -0 "$pid" 2>/dev/null || { cat "$log" >&2; fail "ringdyn-server exited before listening"; }
  sleep 0.1
done
[ -n "$url" ] || { cat "$log" >&2; fail "ringdyn-server did not print its address within 10 s"; }
echo "browser test: server at $url, screenshots in $shots"

cd "$here"
RINGDYN_URL=$url RINGDYN_SHOT_DIR=$shots node --test test.mjs
