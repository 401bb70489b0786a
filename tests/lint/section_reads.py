#!/usr/bin/env python3
"""section_reads.py — the cross-section lint: core asks rd_section for b and h.

    section_reads.py SOURCE_DIR

Every core source and header (core/*/*.c, core/*/*.h) is read with its
comments and string literals blanked; a read is a member access
`.radial_width`, `->radial_width`, `.axial_height` or `->axial_height`.
Allowed:
  - core/ring/rd_section.c, which turns them into the section (rd_section.h);
  - core/ring/rd_ring.c inside rd_ring_params_default and rd_ring_validate,
    core/ringpack/rd_ringpack.c inside rd_ringpack_params_thesis (the
    parameters are their input: defaults they write, values they check);
  - the files of ALLOWED, which still read them until they are ported; an
    entry whose file reads them no more fails too, so the list only shrinks.
It prints the files it checked and the allowed reads left, and fails on an
empty file list instead of passing on nothing.
"""
import glob
import os
import re
import sys

OWNER = "core/ring/rd_section.c"
INPUT_FUNCTIONS = {"core/ring/rd_ring.c": {"rd_ring_params_default", "rd_ring_validate"},
                   "core/ringpack/rd_ringpack.c": {"rd_ringpack_params_thesis"}}
ALLOWED = set()  # files still reading b and h raw until ported: none
READ = re.compile(r"(?:\.|->)\s*(radial_width|axial_height)\b")


def blank(text):
    """The text with comments and string/char literals replaced by spaces
    (newlines kept, so line numbers stay)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + re.sub(r"[^\n]", " ", text[i + 1:j - 1]) + c)
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def function_at(lines):
    """For each line index, the name of the function whose body holds it
    (functions open with "{" alone on a line, .clang-format), or None."""
    names, current = [], None
    for k, line in enumerate(lines):
        if line.rstrip() == "{":
            current = None
            for back in range(k - 1, max(k - 6, -1), -1):
                m = re.match(r"^[A-Za-z_].*?\b([A-Za-z_]\w*)\s*\(", lines[back])
                if m:
                    current = m.group(1)
                    break
        names.append(current)
        if line.startswith("}"):
            current = None
    return names


def main():
    root = sys.argv[1]
    files = sorted(os.path.relpath(f, root) for pattern in ("core/*/*.c", "core/*/*.h")
                   for f in glob.glob(os.path.join(root, pattern)))
    if not files:
        print("section_reads: no core files under %s" % root)
        return 1
    bad, allowed_left = [], {}
    for rel in files:
        with open(os.path.join(root, rel), encoding="utf-8") as fh:
            lines = blank(fh.read()).split("\n")
        funcs = function_at(lines)
        for k, line in enumerate(lines):
            for m in READ.finditer(line):
                where = "%s:%d %s" % (rel, k + 1, m.group(1))
                if rel == OWNER or funcs[k] in INPUT_FUNCTIONS.get(rel, ()):
                    continue
                if rel in ALLOWED:
                    allowed_left.setdefault(rel, []).append(k + 1)
                    continue
                bad.append(where + (" in %s" % funcs[k] if funcs[k] else ""))
    stale = sorted(ALLOWED - set(allowed_left))
    print("section_reads: checked %d core files (%d .c, %d .h)" %
          (len(files), sum(f.endswith(".c") for f in files), sum(f.endswith(".h") for f in files)))
    print("  owner %s; input functions %s" %
          (OWNER, ", ".join("%s: %s" % (f, " ".join(sorted(v)))
                            for f, v in INPUT_FUNCTIONS.items())))
    for rel in sorted(allowed_left):
        print("  allowed until ported: %s lines %s" %
              (rel, " ".join(str(n) for n in allowed_left[rel])))
    for rel in stale:
        print("stale allow-list entry (reads b and h no more; remove it from ALLOWED): %s" % rel)
    for where in bad:
        print("raw read of the ring's b or h (ask rd_section.h): %s" % where)
    if bad or stale:
        return 1
    print("section_reads: no raw reads outside the section and the ring's validation")
    return 0


if __name__ == "__main__":
    sys.exit(main())
