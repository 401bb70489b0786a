#!/usr/bin/env bash
# Size limits of issue 9: no core, api or server source file over 800 lines, no
# function in core/, api/ or server/ over 80 lines (from the line of its opening
# brace to its closing one; functions open with "{" alone on a line, .clang-format).
#   sizes.sh SOURCE_DIR       prints the offenders; exit 1 if there are any
set -euo pipefail
cd "$1"
bad=0
for f in core/*/*.c core/*/*.h api/*.c api/*.h server/*.c server/*.h; do
  n=$(wc -l <"$f")
  if [ "$n" -gt 800 ]; then echo "file over 800 lines: $f ($n)"; bad=1; fi
done
long=$(awk '
  FNR == 1 { start = 0 }
  /^\{$/ { start = FNR; name = prev }
  /^\}/ && start { len = FNR - start + 1; if (len > 80) printf "function over 80 lines: %s:%d %s (%d)\n", FILENAME, start, name, len; start = 0 }
  { prev = $0 }' core/*/*.c api/*.c server/*.c server/*.h)
if [ -n "$long" ]; then echo "$long"; bad=1; fi
[ "$bad" -eq 0 ] && echo "sizes: core/api/server files <= 800 lines, core/api/server functions <= 80 lines"
exit "$bad"
