#!/usr/bin/env bash
# Runs the scene-parser fuzzer for a while on a corpus seeded with the
# project's scenes and sweeps (examples/*.json, tests/api/cases/*/request.json,
# tests/api/sweeps/*.json, tests/fuzz/seeds/*.json, the bodies of
# tests/http/battery.txt).
#
#   run.sh [--parse-only] [--runs N] [--max-len N] FUZZER SECONDS SOURCE_ROOT [CORPUS_DIR]
#   run.sh --coverage FUZZER_COV SOURCE_ROOT CORPUS_DIR   (api/ coverage of a corpus)
#
# --coverage replays the corpus and the seeds (everything the fuzzer ran:
# libFuzzer keeps in CORPUS_DIR only the inputs it made, not the seeds that
# it started from); RINGDYN_FUZZ_COV_SEEDS=0 replays the corpus alone.
#
# --parse-only: RINGDYN_FUZZ_RUN=0, no analysis runs (parse, validate, echo,
# refusal contract, sweep parse only): several times faster, for
# the long run (ASan then keeps no allocation stacks: a finding's report
# lacks them, rerun its input without the option for them).  --runs N: stop
# after N executions (or SECONDS, first).  --max-len N: longest input
# (16384: room for gas tables and distortion lists; less is faster).
# The dictionary (-dict) is written by the fuzzer from the served OpenAPI
# document (RINGDYN_FUZZ_DICT), so it follows the schema.
#
# Without CORPUS_DIR the corpus is a temporary directory (ctest); with one it
# is kept and grows from run to run (the long run of the README).  Exit
# status: the fuzzer's (non-zero on a finding, whose input libFuzzer writes
# as crash-* / leak-* / timeout-* in the current directory).
set -euo pipefail
# The seeds into directory $1: the project's scenes and sweeps, then the
# scene bodies of the bad-input battery (one a line, "| BODY |").
make_seeds() {
  local i=0 f
  mkdir -p "$1"
  for f in "$ROOT"/examples/*.json "$ROOT"/tests/api/cases/*/request.json "$ROOT"/tests/api/sweeps/*.json \
    "$ROOT"/tests/fuzz/seeds/*.json; do
    [ -f "$f" ] && cp "$f" "$1/seed$((i += 1)).json"
  done
  grep '| POST /api/v1/jobs | ' "$ROOT"/tests/http/battery.txt | sed 's/^.*| POST \/api\/v1\/jobs | //; s/ | [A-Za-z-]*:.*$//' |
    while IFS= read -r body; do printf '%s' "$body" >"$1/battery$((i += 1)).json"; done
}
if [ "${1:-}" = --coverage ]; then
  COV=$2 ROOT=$3 CORPUS=$4
  WORK=$(mktemp -d "${TMPDIR:-/tmp}/ringdyn-fuzzcov.XXXXXX")
  trap 'rm -rf "$WORK"' EXIT
  SEEDS=()
  if [ "${RINGDYN_FUZZ_COV_SEEDS:-1}" != 0 ]; then make_seeds "$WORK/seeds"; SEEDS=("$WORK/seeds"); fi
  LLVM_PROFILE_FILE="$WORK/cov.profraw" "$COV" -runs=0 "$CORPUS" "${SEEDS[@]}" >/dev/null 2>&1
  PROFDATA=$(command -v llvm-profdata-14 || command -v llvm-profdata)
  LLVMCOV=$(command -v llvm-cov-14 || command -v llvm-cov)
  "$PROFDATA" merge -sparse "$WORK/cov.profraw" -o "$WORK/cov.profdata"
  "$LLVMCOV" report "$COV" -instr-profile="$WORK/cov.profdata" -show-branch-summary \
    "$ROOT"/api/*.c | tail -n 1 | awk '{ print "api/ total: regions " $4 " covered, functions " $7 ", lines " $10 ", branches " $13 }'
  "$LLVMCOV" report "$COV" -instr-profile="$WORK/cov.profdata" -show-branch-summary "$ROOT"/api/*.c |
    tee "$WORK/report"
  # rd_examples.c reads the example catalogue from disk: no body reaches it.
  awk '/^rd_.*\.c / && $1 != "rd_examples.c" { n += $11; m += $12 }
       END { printf "api/ without rd_examples.c: branches %.2f%% (%d of %d)\n", 100 * (n - m) / n, n - m, n }' \
    "$WORK/report"
  # The range checks live in core's *_validate functions: their lines too.
  "$LLVMCOV" report "$COV" -instr-profile="$WORK/cov.profdata" -show-functions "$ROOT"/core/*.c |
    awk '/validate/ { print "core " $1 ": regions " $4 ", lines " $7 }'
  exit 0
fi
RUNS=() MAXLEN=16384
while [ $# -gt 0 ]; do
  case $1 in
    --parse-only)
      export RINGDYN_FUZZ_RUN=0 ASAN_OPTIONS=${ASAN_OPTIONS:-malloc_context_size=0:quarantine_size_mb=16}
      shift ;;
    --max-len) MAXLEN=$2; shift 2 ;;
    --runs) RUNS=("-runs=$2"); shift 2 ;;
    *) break ;;
  esac
done
if [ $# -lt 3 ]; then
  echo "usage: $0 [--parse-only] [--runs N] [--max-len N] FUZZER SECONDS SOURCE_ROOT [CORPUS_DIR]" >&2
  exit 2
fi
FUZZER=$(realpath "$1") SECONDS_=$2 ROOT=$(realpath "$3") CORPUS=${4:+$(realpath "$4")}
HERE=$PWD
WORK=$(mktemp -d "${TMPDIR:-/tmp}/ringdyn-fuzz.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
if [ -z "$CORPUS" ]; then CORPUS=$WORK/corpus; fi
mkdir -p "$CORPUS"
make_seeds "$WORK/seeds"
RINGDYN_FUZZ_DICT="$WORK/dict" "$FUZZER" >/dev/null 2>&1
# -timeout: a parse of one input never takes a second, so 10 s is a hang.
cd "$WORK"
rc=0
"$FUZZER" -max_total_time="$SECONDS_" "${RUNS[@]}" -dict="$WORK/dict" -max_len="$MAXLEN" \
  -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 "$CORPUS" "$WORK/seeds" >"$WORK/log" 2>&1 || rc=$?
grep -E '^(#[0-9]+.*(INITED|DONE)|stat::|INFO: Loaded|==[0-9]+==|SUMMARY)' "$WORK/log" | tail -n 20 || true
if [ "$rc" -ne 0 ]; then
  tail -n 40 "$WORK/log"
  cp "$WORK"/crash-* "$WORK"/leak-* "$WORK"/timeout-* "$HERE"/ 2>/dev/null || true
fi
exit "$rc"
