#!/usr/bin/env bash
# ringdyn sweep end to end: a spec run as K chunks by parallel processes
# (xargs -P, and the array-job environment variables) and reduced gives the
# same table, byte for byte, as one process; reduce names missing chunks and
# refuses chunks of another spec; bad specs exit 2 with the spec path.  modal_over
# is an over sweep (its chunks hold whole points).
#   sweep_cli_test.sh RINGDYN SWEEPS_DIR
set -u
ringdyn=$1 sweeps=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
fail() { echo "FAIL: $*" >&2; failed=1; }

for spec in modal_grid modal_lhs modal_over; do
  s=$sweeps/$spec.json
  n=$("$ringdyn" sweep count "$s") || fail "$spec: count exit $?"
  "$ringdyn" sweep run "$s" --out "$work/$spec.1" || fail "$spec: single run exit $?"
  # K = 4 chunks, 4 processes at once; chunk 3 takes its index from the
  # Kubernetes variable and chunk 2 from Slurm's, as on a cluster.
  printf '0\n1\n' | xargs -P 2 -I{} "$ringdyn" sweep run "$s" --index {} --chunks 4 \
      --out "$work/$spec.4" || fail "$spec: xargs chunks"
  JOB_COMPLETION_INDEX=3 "$ringdyn" sweep run "$s" --chunks 4 --out "$work/$spec.4" &
  SLURM_ARRAY_TASK_ID=2 "$ringdyn" sweep run "$s" --chunks 4 --out "$work/$spec.4" &
  wait %1 || fail "$spec: JOB_COMPLETION_INDEX chunk"
  wait %2 || fail "$spec: SLURM_ARRAY_TASK_ID chunk"
  [ "$(ls -A "$work/$spec.4" | wc -l)" = 4 ] || fail "$spec: want exactly 4 files: $(ls -A "$work/$spec.4")"
  for fmt in json csv; do
    flag=; [ $fmt = csv ] && flag=--csv
    "$ringdyn" sweep reduce "$work/$spec.1" $flag > "$work/$spec.1.$fmt" || fail "$spec: reduce 1 $fmt"
    "$ringdyn" sweep reduce "$work/$spec.4" $flag > "$work/$spec.4.$fmt" || fail "$spec: reduce 4 $fmt"
    cmp "$work/$spec.1.$fmt" "$work/$spec.4.$fmt" || fail "$spec: $fmt tables differ"
  done
  rows=$(grep -c $'\r$' "$work/$spec.4.csv")
  [ "$rows" = $((n + 1)) ] || fail "$spec: $rows CSV lines, want header + $n"
done

# The deploy/ scripts: local (xargs -P) and the Slurm array task script, run
# here as a 3-task array would run it.
deploy=$sweeps/../../../deploy
RINGDYN=$ringdyn bash "$deploy/local-sweep.sh" "$sweeps/modal_grid.json" "$work/local" 5 2 \
  > "$work/local.json" || fail "deploy/local-sweep.sh"
cmp "$work/modal_grid.1.json" "$work/local.json" || fail "local-sweep.sh table differs"
for i in 0 1 2; do
  SLURM_ARRAY_TASK_ID=$i SLURM_ARRAY_TASK_COUNT=3 RINGDYN=$ringdyn \
    bash "$deploy/slurm-sweep.sh" "$sweeps/modal_grid.json" "$work/slurm" &
done
wait
"$ringdyn" sweep reduce "$work/slurm" > "$work/slurm.json" || fail "reduce of the Slurm chunks"
cmp "$work/modal_grid.1.json" "$work/slurm.json" || fail "slurm-sweep.sh table differs"

# The impossible corner of modal_grid is a row with its error, the rest ran.
grep -q '^0.02,0.01,8,,,,,invalid_scene,' "$work/modal_grid.4.csv" || fail "failed point row missing"
[ "$(grep -c ',ok,' "$work/modal_grid.4.csv")" = 16 ] || fail "want 16 ok rows"

# Missing chunks are named; a chunk of another spec is refused.
rm "$work/modal_grid.4/chunk-000002-of-000004.json"
out=$("$ringdyn" sweep reduce "$work/modal_grid.4" 2>&1 >/dev/null); rc=$?
[ $rc = 2 ] && [[ $out == *'1 of 4 chunks missing'*': 2"'* ]] || fail "missing chunk: rc $rc, $out"
"$ringdyn" sweep run "$sweeps/modal_lhs.json" --index 2 --chunks 4 --out "$work/modal_grid.4" \
    || fail "foreign chunk run"
out=$("$ringdyn" sweep reduce "$work/modal_grid.4" 2>&1 >/dev/null); rc=$?
[ $rc = 2 ] && [[ $out == *'another spec'* ]] || fail "foreign chunk: rc $rc, $out"

# An interrupted chunk (Ctrl-C, or SIGTERM from the cluster) leaves no file,
# not even its temporary one, and exits 1.
"$ringdyn" sweep run "$sweeps/lift_long.json" --out "$work/int" &
pid=$!
sleep 0.5
kill -TERM $pid
wait $pid; rc=$?
[ $rc = 1 ] && [ -z "$(ls -A "$work/int" 2>/dev/null)" ] || fail "interrupted: rc $rc, $(ls -A "$work/int")"

# Bad input: exit 2 and the error JSON with the spec path.
echo '{"base": {"analysis": "modal"}, "parameters": [{"path": "/discretization/segments", "values": [2001]}], "outputs": ["/numerics/dof"]}' > "$work/bad.json"
out=$("$ringdyn" sweep count "$work/bad.json" 2>&1); rc=$?
[ $rc = 2 ] && [[ $out == *'"path":"/parameters/0/values/0"'* ]] || fail "bad spec: rc $rc, $out"
out=$("$ringdyn" sweep run "$sweeps/modal_lhs.json" --index 7 --chunks 4 --out "$work/x" 2>&1); rc=$?
[ $rc = 2 ] && [[ $out == *'--index 7 is out of range'* ]] || fail "bad index: rc $rc, $out"
out=$(env -u JOB_COMPLETION_INDEX -u SLURM_ARRAY_TASK_ID "$ringdyn" sweep run \
      "$sweeps/modal_lhs.json" --chunks 4 --out "$work/x" 2>&1); rc=$?
[ $rc = 2 ] && [[ $out == *'no chunk index'* ]] || fail "no index: rc $rc, $out"
"$ringdyn" sweep 2>/dev/null; [ $? = 2 ] || fail "bare sweep is a usage error"

# fidelity: in one process, and as a spec run in 2 chunks, reduced, tabulated.
scene=$sweeps/../../../examples/thesis_pretension.json
"$ringdyn" sweep fidelity "$scene" --segments 10,20,40 --csv > "$work/fid.csv" || fail "fidelity run"
head -1 "$work/fid.csv" | grep -q '^/discretization/segments,/numerics/wall_s,/numerics/error_estimate,error_vs_finest,estimate_covers,changes,basis,error_on_basis,pareto,status,error' \
  || fail "fidelity columns: $(head -1 "$work/fid.csv")"
# The finest row: 0 against itself, its error on its own estimate (which covers the segment count).
grep -q '^40,[0-9.e-]*,[0-9.e-]*,0,segments,,estimate,[0-9.e-]*,true,ok,' "$work/fid.csv" || fail "finest row: $(cat "$work/fid.csv")"
"$ringdyn" sweep fidelity "$scene" --segments 10,20,40 --spec > "$work/fid_spec.json" || fail "fidelity --spec"
for i in 0 1; do "$ringdyn" sweep run "$work/fid_spec.json" --index $i --chunks 2 --out "$work/fid" & done
wait
"$ringdyn" sweep reduce "$work/fid" > "$work/fid_table.json" || fail "fidelity reduce"
"$ringdyn" sweep fidelity --table "$work/fid_table.json" --csv > "$work/fid2.csv" || fail "fidelity --table"
# Wall times differ between runs; every other cell must not.
cut -d, -f1,3- "$work/fid.csv" > "$work/a"; cut -d, -f1,3- "$work/fid2.csv" | sed 's/,\(true\|false\),/,P,/' > "$work/b"
sed -i 's/,\(true\|false\),/,P,/' "$work/a"
cmp "$work/a" "$work/b" || fail "fidelity: chunked table differs from the in-process one"

[ $failed = 0 ] && echo "sweep CLI: all checks passed"
exit $failed
