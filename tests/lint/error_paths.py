#!/usr/bin/env python3
"""error_paths.py — the error-path lint: core writes paths relative to its block.

    error_paths.py [--expect N] SOURCE_DIR RINGDYN TEMPLATE

Core's functions write error paths relative to the block they were given,
and their callers enter the block's pointer (rd_error_enter, rd_error.h;
docs/architecture.md, "Error paths").  So no string literal in core
(core/**/*.c, core/**/*.h; comments left out, adjacent literals joined as
the compiler joins them) may start with an absolute scene block path,
"/<key>/" for a top-level key of a scene: "/ring/diameter",
"/numerics/rtol", "@/..." is the relative form.  The keys are read off the
OpenAPI document `RINGDYN openapi TEMPLATE` prints (every property of every
*Scene schema), not written down here.  Allowed:
  - "/<key>/%d", an array block's pointer built to be entered ("/rings/%d");
  - the (file, literal) pairs of ALLOWED: text that is no error's path or
    message; an entry that is no longer there fails too, so the list only
    shrinks.
It prints the counts it checked and fails on an empty file list or key set
instead of passing on nothing.  With --expect N it passes when it finds
exactly N violations (the planted tree's self-test: error_paths_planted/).
"""
import glob
import json
import os
import re
import subprocess
import sys

ALLOWED = {
    # a partial lift result's warning (rd_lift_partial.c), not an error
    ("core/lift/rd_lift_partial.c", "/numerics/max_steps = %ld ran out"),
}


def scene_keys(ringdyn, template):
    doc = json.loads(subprocess.run([ringdyn, "openapi", template], capture_output=True, text=True,
                                    check=True).stdout)
    keys = set()
    for name, schema in doc.get("components", {}).get("schemas", {}).items():
        if not name.endswith("Scene"):
            continue
        parts = [schema] + schema.get("allOf", []) + schema.get("oneOf", [])
        for part in parts:
            keys |= set(part.get("properties", {}))
    return keys


def literals(text):
    """[(line, joined literal)]: the string literals outside comments, each run
    of adjacent literals (only blanks, newlines or a line's backslash between
    them) joined into one, as the compiler does."""
    out, i, n = [], 0, len(text)
    run, run_line, line = None, 0, 1
    while i < n:
        c = text[i]
        if text.startswith("/*", i) or text.startswith("//", i):
            end = text.find("*/", i + 2) + 2 if text[i + 1] == "*" else text.find("\n", i)
            end = n if end < 2 or end < i else end
            line += text.count("\n", i, end)
            i = end
            continue
        if c == "'":
            j = i + 1
            while j < n and text[j] != "'":
                j += 2 if text[j] == "\\" else 1
            i = j + 1
            run = None if run is None else (out.append((run_line, run)) or None)
            continue
        if c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            body = text[i + 1:j]
            if run is None:
                run, run_line = body, line
            else:
                run += body
            i = j + 1
            continue
        if c == "\n":
            line += 1
        if not (c.isspace() or c == "\\") and run is not None:
            out.append((run_line, run))
            run = None
        i += 1
    if run is not None:
        out.append((run_line, run))
    return out


def main(argv):
    expect = None
    if len(argv) > 1 and argv[1] == "--expect":
        expect = int(argv[2])
        argv = argv[:1] + argv[3:]
    if len(argv) != 4:
        print(__doc__)
        return 2
    root, ringdyn, template = argv[1:]
    keys = scene_keys(ringdyn, template)
    files = sorted(glob.glob(os.path.join(root, "core", "**", "*.[ch]"), recursive=True))
    if not keys or not files:
        print(f"error_paths: {len(files)} files, {len(keys)} scene keys: nothing to check")
        return 1
    absolute = re.compile(r"^/(%s)/" % "|".join(sorted(map(re.escape, keys))))
    block = re.compile(r"^/(%s)/%%d$" % "|".join(sorted(map(re.escape, keys))))
    bad, seen, count = [], set(), 0
    for path in files:
        rel = os.path.relpath(path, root)
        with open(path, encoding="utf-8") as f:
            for line, lit in literals(f.read()):
                count += 1
                if not absolute.match(lit) or block.match(lit):
                    continue
                if (rel, lit) in ALLOWED:
                    seen.add((rel, lit))
                    continue
                bad.append(f"{rel}:{line}: \"{lit[:70]}\" starts with an absolute scene path")
    gone = [] if expect is not None else sorted(ALLOWED - seen)
    for line in bad:
        print(line)
    for rel, lit in gone:
        print(f"{rel}: ALLOWED \"{lit}\" is no longer there: drop it from the list")
    print(f"error_paths: {len(files)} files, {count} literals, {len(keys)} scene keys "
          f"({', '.join(sorted(keys))}); {len(bad)} absolute paths, {len(seen)} allowed")
    if expect is not None:
        ok = len(bad) == expect
        print(f"error_paths: expected {expect} violations, found {len(bad)}: "
              f"{'ok' if ok else 'FAIL'}")
        return 0 if ok else 1
    return 1 if bad or gone else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
