#!/usr/bin/env bash
# Configuration checked at start (issue 45): a file of --examples that GET
# /api/v1/examples could not serve (a name outside A-Z a-z 0-9 _ -, invalid
# JSON, an invalid scene), a missing --examples directory, a bad --token-file
# and a --data that is not a directory each stop the server before it listens,
# with a message naming the option, the file and the rule, and before the
# store is touched; a good directory starts and serves its examples.
#
#   config.sh SERVER_BINARY RD_JSONQ EXAMPLES_DIR
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 SERVER RD_JSONQ EXAMPLES" >&2
  exit 2
fi
SERVER=$1 JQ=$2 EXAMPLES=$3
. "$(dirname "$0")/lib.sh"

# refuses NAME ARGS... -- WANT...: the server exits non-zero without listening,
# and its stderr holds every WANT (fixed strings).
refuses() {
  local name=$1 rc=0 args=() want=()
  shift
  while [ "$1" != -- ]; do args+=("$1"); shift; done
  shift
  want=("$@")
  timeout 20 "$SERVER" --port 0 "${args[@]}" >"$WORK/refuse.out" 2>"$WORK/refuse.err" || rc=$?
  local missing=""
  for w in "${want[@]}"; do grep -qF -- "$w" "$WORK/refuse.err" || missing="$w"; done
  if [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] && [ -z "$missing" ] && ! [ -s "$WORK/refuse.out" ]; then
    ok "$name"
  else
    bad "$name" "exit $rc, missing '$missing': $(head -c 300 "$WORK/refuse.err")"
  fi
}

# A copy of the shipped examples, one bad file at a time.
fresh() { rm -rf "$WORK/ex"; mkdir "$WORK/ex"; cp "$EXAMPLES"/thesis_modal.json "$WORK/ex/"; }

fresh
echo '{"analysis": "modal"}' >"$WORK/ex/my example.json"
refuses "a misnamed example file stops the start" --data :memory: --examples "$WORK/ex" -- \
  "--examples $WORK/ex" '"my example.json"' "A-Z, a-z, 0-9, _ and -" "fix or remove that file"
fresh
echo '{"analysis": "modal",' >"$WORK/ex/broken.json"
refuses "an example that is not JSON stops the start" --data :memory: --examples "$WORK/ex" -- \
  '"broken.json" is not valid JSON' "line 2"
fresh
echo '{"analysis": "modal", "ring": {"diameter": -1}}' >"$WORK/ex/negative.json"
refuses "an example that is not a valid scene stops the start" --data :memory: \
  --examples "$WORK/ex" -- '"negative.json" is not a valid scene' "/ring/diameter = -1" "allowed"
refuses "a missing examples directory stops the start" --data :memory: \
  --examples "$WORK/nothing" -- "--examples $WORK/nothing" "cannot open the examples directory"

# Refused before the store is opened: nothing is created in --data.
printf 'short\n' >"$WORK/short"
refuses "a bad token file stops the start" --data "$WORK/store" --token-file "$WORK/short" -- \
  "--token-file $WORK/short" "16..4096 printable characters"
check "... before the store was created" test ! -e "$WORK/store"
fresh
echo '[]' >"$WORK/ex/list.json"
refuses "a bad example stops the start before the store opens" --data "$WORK/store" \
  --examples "$WORK/ex" -- '"list.json"'
check "... nothing created in --data" test ! -e "$WORK/store"
echo 'not a directory' >"$WORK/file"
refuses "--data naming a file stops the start" --data "$WORK/file" -- \
  "--data $WORK/file" "not a directory"

# The shipped directory starts, and every file is served.
start_server G --examples "$EXAMPLES"
G_PID=$SPID
req GET /api/v1/examples
same "the shipped examples are served" "$STATUS" 200
same "... all of them" "$("$JQ" -n /examples "$WORK/body")" "$(ls "$EXAMPLES"/*.json | wc -l)"
stop_server G "$G_PID"

finish
