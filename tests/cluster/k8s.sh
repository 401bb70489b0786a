#!/usr/bin/env bash
# The Kubernetes manifests of deploy/: after envsubst, valid batch/v1 Jobs
# under the Kubernetes API schema with no unknown field (k8s/k8s.mjs, npm
# kubernetes-models; a misspelt field must be caught, or the check is
# broken); then the pods' commands run here as Kubernetes runs them: each
# index in a clean environment with only JOB_COMPLETION_INDEX (and the
# manifest's env), the volumes as local folders, 2 at once; the reduce pod's
# command; the table equals `ringdyn sweep run` in one process, byte for
# byte.  The exit code of an invalid spec fails the Job at once
# (podFailurePolicy), an interrupted pod's does not.
#   k8s.sh RINGDYN DEPLOY_DIR SWEEPS_DIR (tests/api/sweeps)
set -euo pipefail
ringdyn=$(realpath "$1") deploy=$(realpath "$2") sweeps=$(realpath "$3")
spec=$sweeps/modal_lhs.json
here=$(cd "$(dirname "$0")" && pwd)
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v node > /dev/null || fail "node is missing; install it with scripts/install-deps.sh --test"
[ -d "$here/k8s/node_modules/kubernetes-models" ] \
  || fail "kubernetes-models is not installed in $here/k8s; run 'npm install' there (scripts/test.sh does)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
k8s() { node "$here/k8s/k8s.mjs" "$@"; }

export K=5 PARALLELISM=2 IMAGE=registry.example/ringdyn:test
for f in k8s-sweep-job k8s-sweep-reduce; do
  envsubst '$K $PARALLELISM $IMAGE' < "$deploy/$f.yaml" > "$work/$f.yaml"
  ! grep -n '\${' "$work/$f.yaml" || fail "$f.yaml: a variable envsubst does not know"
done
k8s check "$work/k8s-sweep-job.yaml" "$work/k8s-sweep-reduce.yaml" || fail "manifests invalid"
sed 's/backoffLimit:/backoffLimt:/' "$work/k8s-sweep-job.yaml" > "$work/typo.yaml"
out=$(k8s check "$work/typo.yaml" 2>&1) && fail "a misspelt field passed the check"
[[ $out == *'/spec/backoffLimt: unknown field'* ]] || fail "misspelt field: $out"
sed 's/completionMode: Indexed/completionMode: indexed/' "$work/k8s-sweep-job.yaml" > "$work/enum.yaml"
k8s check "$work/enum.yaml" 2> /dev/null && fail "a wrong completionMode passed the check"

# The pods, here: ringdyn on PATH as in the image, /spec and /results as folders.
mkdir -p "$work/bin" "$work/root/spec" "$work/root/results"
ln -s "$ringdyn" "$work/bin/ringdyn"
cp "$spec" "$work/root/spec/spec.json"
k8s command "$work/k8s-sweep-job.yaml" "$work/root" > "$work/job.cmd"
k8s command "$work/k8s-sweep-reduce.yaml" "$work/root" > "$work/reduce.cmd"
pod() {  # pod CMDFILE [VAR=VALUE...]: the container's command as Kubernetes starts it
  local -a cmd
  mapfile -d '' cmd < "$1"
  shift
  env -i PATH="$work/bin:/usr/bin:/bin" "$@" "${cmd[@]}"
}
export -f pod
export work
seq 0 $((K - 1)) | xargs -P "$PARALLELISM" -I{} bash -c 'pod "$work/job.cmd" JOB_COMPLETION_INDEX={}' \
  || fail "a chunk pod failed"
[ "$(ls "$work/root/results/sweep" | wc -l)" = "$K" ] || fail "want $K chunk files: $(ls "$work/root/results/sweep")"
pod "$work/reduce.cmd" || fail "the reduce pod failed"
"$ringdyn" sweep run "$spec" --out "$work/ref"
"$ringdyn" sweep reduce "$work/ref" > "$work/ref.json"
"$ringdyn" sweep reduce "$work/ref" --csv > "$work/ref.csv"
cmp "$work/ref.json" "$work/root/results/sweep.json" || fail "JSON table differs from one process's"
cmp "$work/ref.csv" "$work/root/results/sweep.csv" || fail "CSV table differs from one process's"

# Exit codes against the podFailurePolicy.
failjob=" $(k8s failjob "$work/k8s-sweep-job.yaml") "
echo '{"base": {"analysis": "modal", "discretization": {"segments": 2}}, "outputs": ["/x"]}' \
  > "$work/root/spec/spec.json"
rc=0; pod "$work/job.cmd" JOB_COMPLETION_INDEX=0 2> /dev/null || rc=$?
[[ $failjob == *" $rc "* ]] || fail "invalid spec: exit $rc, not in the FailJob codes ($failjob)"
cp "$sweeps/lift_long.json" "$work/root/spec/spec.json"
rm -rf "$work/root/results/sweep"
mapfile -d '' cmd < "$work/job.cmd"
env -i PATH="$work/bin:/usr/bin:/bin" JOB_COMPLETION_INDEX=0 "${cmd[@]}" 2> /dev/null &
pid=$!   # env execs ringdyn: the pod's process, stopped as the kubelet stops it
sleep 0.5
kill -TERM $pid
rc=0; wait $pid || rc=$?
[ $rc != 0 ] && [[ $failjob != *" $rc "* ]] || fail "interrupted pod: exit $rc (FailJob codes:$failjob)"
echo "k8s: all checks passed"
