#!/usr/bin/env bash
# Every C source and header of the tree is formatted as .clang-format says.
#   format.sh SOURCE_DIR      lists the files that are not; exit 1 if any
set -euo pipefail
cd "$1"
command -v clang-format >/dev/null 2>&1 || {
  echo "clang-format is missing; scripts/install-deps.sh --test installs it" >&2
  exit 1
}
bad=()
while IFS= read -r f; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done < <(find core api cli server tests bench -name '*.[ch]' -not -path '*/node_modules/*' | sort)
if [ "${#bad[@]}" -gt 0 ]; then
  echo "not formatted (run clang-format -i on them):"; printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "format: every C file matches .clang-format"
