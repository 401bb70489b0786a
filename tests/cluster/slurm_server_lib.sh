# ringdyn-server on 127.0.0.1 for slurm_server.sh and bench/slurm_server.sh
# (sourced after slurm_lib.sh; uses $work, $server and fail).

servers=()
server_start() {  # server_start NAME ARGS...: a server on a free port; its URL in $NAME
  local name=$1 i u=
  shift
  : > "$work/$name.out"   # exists before the server starts: the polling below never races its redirect
  "$server" --port 0 --data :memory: "$@" > "$work/$name.out" 2> "$work/$name.err" &
  servers+=($!)
  server_names+=("$name")
  for ((i = 0; i < 100; i++)); do
    u=$(sed -n 's/^ringdyn-server listening on //p' "$work/$name.out")
    [ -n "$u" ] && break
    sleep 0.1
  done
  [ -n "$u" ] || fail "server $name did not start: $(cat "$work/$name.err")"
  printf -v "$name" '%s' "$u"
}
server_names=()
servers_stop() {  # the servers this script started, by pid
  local pid
  for pid in "${servers[@]}"; do kill "$pid" 2> /dev/null || true; done
  for pid in "${servers[@]}"; do wait "$pid" 2> /dev/null || true; done
  servers=()
}
servers_check() {  # stops the servers; none may have reported a sanitizer error or a leak
  local name
  servers_stop
  for name in "${server_names[@]}"; do
    ! grep -q 'Sanitizer\|runtime error' "$work/$name.err" \
      || fail "server $name: $(grep -m 5 'Sanitizer\|runtime error\|#[0-9]' "$work/$name.err")"
  done
}

post_sweep() {  # post_sweep URL SPEC: the new sweep's id
  curl -sS -f -H 'Content-Type: application/json' --data-binary "@$2" "$1/api/v1/sweeps" \
    | jq -r .id
}
sweep_get() {  # sweep_get URL ID FILE: the sweep's JSON into FILE
  curl -sS -f -o "$3" "$1/api/v1/sweeps/$2" || fail "GET sweep $2 at $1"
}
sweep_wait() {  # sweep_wait URL ID FILE [SECONDS]: until final (default 240 s); JSON into FILE
  local i s
  for ((i = 0; i < ${4:-240} * 5; i++)); do
    sweep_get "$1" "$2" "$3"
    s=$(jq -r .status "$3")
    case $s in succeeded | failed | cancelled | interrupted) return 0 ;; esac
    sleep 0.2
  done
  fail "sweep $2 at $1 not final after ${4:-240} s: $(jq -c 'del(.table)' "$3")"
}
sweep_table() {  # sweep_table FILE: the sweep's "table" exactly as served (the last member)
  python3 -c 'import sys; s = open(sys.argv[1]).read(); print(s[s.index("\"table\":") + 8:-1])' "$1"
}
