#!/usr/bin/env bash
# Every symbol the ringdyn libraries export carries the rd_ prefix (STYLE.md:
# one prefix per library, so ringdyn links beside anything).
#   symbols.sh LIB.a...      prints the offenders; exit 1 if there are any
set -euo pipefail
bad=$(nm -g --defined-only "$@" | awk 'NF == 3 && $2 ~ /[TDBRCGS]/ && $3 !~ /^__(odr_asan|asan|ubsan|sanitizer)/ { print $3 }' | grep -v '^rd_' | sort -u || true)
count=$(nm -g --defined-only "$@" | awk 'NF == 3 && $2 ~ /[TDBRCGS]/' | wc -l)
if [ "$count" -eq 0 ]; then
  echo "symbols: no exported symbols found in $* (wrong files?)" >&2
  exit 1
fi
if [ -n "$bad" ]; then
  echo "symbols without the rd_ prefix:"; echo "$bad"
  exit 1
fi
echo "symbols: $count exported, all rd_"
