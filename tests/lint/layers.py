#!/usr/bin/env python3
"""layers.py — the layering lint: who calls whom, read off the built objects.

    layers.py SOURCE_DIR LIB.a...   (each LIB.a built in the build tree's folder
                                     of the same name as its source: core/, api/)

Every object file in the archives is one source file (found under SOURCE_DIR by
its name).  File A calls file B when A's object has an undefined symbol that
B's object defines (`nm`: functions and data alike, so a function pointer
counts as a call).  Reading the objects, not the text, sees exactly what the
linker sees: no parsing, no missed macro, no static name mistaken for a call.

It fails (exit 1) on
  - a circle: files that call each other, directly or round a loop (every
    strongly connected component of more than one file is printed);
  - a call into a higher floor of core: core/<folder>/ files may call only
    their own folder and the folders below it, in the order of FLOORS;
  - a call into a higher layer (core -> api -> cli -> server, LAYERS).
Objects generated in the build tree (no source of that name in the
archive's source folder) are listed, not checked.
It prints the counts it checked, so a run that found nothing to check fails
(no objects, no edges) instead of passing on an empty graph.
"""
import collections
import os
import subprocess
import sys

# core's folders, lowest first (docs/architecture.md, "Floors").
FLOORS = ["include", "base", "numerics", "ring", "engine", "liner", "statics", "lift", "ringpack"]
# the layers, lowest first: core knows no JSON, api no HTTP (STYLE.md).
LAYERS = ["core", "api", "cli", "server"]


def objects(archives):
    """{(archive, object name): (defined symbols, undefined symbols)}."""
    objs = collections.defaultdict(lambda: (set(), set()))
    for archive in archives:
        for flags, slot in ((["--defined-only", "-g"], 0), (["-u"], 1)):
            out = subprocess.run(["nm", "-A"] + flags + [archive], capture_output=True, text=True,
                                 check=True).stdout
            for line in out.splitlines():
                # "archive:member:[address]  TYPE symbol"
                parts = line.split()
                if len(parts) < 2 or parts[0].count(":") < 2:
                    continue
                member = parts[0].split(":")[-2]
                if slot == 0 and (len(parts) < 3 or parts[-2] not in "TDBRCGS"):
                    continue
                objs[(archive, member)][slot].add(parts[-1])
    return objs


def source_of(root, archive, member):
    """The source path (relative to root) of an object of an archive built from
    the source folder of the same name (build/core/libx.a: core/); None for an
    object generated in the build tree (no such source)."""
    folder = os.path.basename(os.path.dirname(os.path.abspath(archive)))
    name = member[:-2] if member.endswith(".o") else member
    hits = []
    for dirpath, _, files in os.walk(os.path.join(root, folder)):
        if name in files and "node_modules" not in dirpath:
            hits.append(os.path.relpath(os.path.join(dirpath, name), root))
    if len(hits) > 1:
        sys.exit("layers: %s maps to %d source files (%s)" % (member, len(hits), hits))
    return hits[0] if hits else None


def circles(nodes, edges):
    """Tarjan's strongly connected components with more than one node."""
    index, low, stack, on, comps, counter = {}, {}, [], set(), [], [0]
    sys.setrecursionlimit(10000)

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))

    for v in sorted(nodes):
        if v not in index:
            visit(v)
    return comps


def floor(path):
    parts = path.split("/")
    if parts[0] != "core" or len(parts) < 3:
        return None
    return FLOORS.index(parts[1]) if parts[1] in FLOORS else -1


def main():
    root, archives = sys.argv[1], sys.argv[2:]
    objs = objects(archives)
    src = {k: source_of(root, k[0], k[1]) for k in objs}
    generated = sorted(k[1] for k, v in src.items() if v is None)
    objs = {k: v for k, v in objs.items() if src[k] is not None}
    owner = {}
    for k, (defs, _) in objs.items():
        for sym in defs:
            owner[sym] = src[k]
    edges = collections.defaultdict(set)
    count = 0
    for k, (_, undefs) in objs.items():
        for sym in undefs:
            b = owner.get(sym)
            if b and b != src[k]:
                if b not in edges[src[k]]:
                    count += 1
                edges[src[k]].add(b)
    bad = 0
    for comp in circles({v for k, v in src.items() if v}, edges):
        print("circle: " + " <-> ".join(comp))
        bad += 1
    up = 0
    for a in sorted(edges):
        fa = floor(a)
        for b in sorted(edges[a]):
            fb = floor(b)
            if fa is not None and fb is not None and (fa < 0 or fb < 0):
                print("core file outside the floors: %s -> %s" % (a, b))
                up += 1
            elif fa is not None and fb is not None and fb > fa:
                print("call into a higher folder: %s -> %s" % (a, b))
                up += 1
            elif LAYERS.index(b.split("/")[0]) > LAYERS.index(a.split("/")[0]):
                print("call into a higher layer: %s -> %s" % (a, b))
                up += 1
    if not objs or count == 0:
        sys.exit("layers: no objects or no calls found in %s" % " ".join(archives))
    if generated:
        print("layers: generated objects, not checked: " + " ".join(generated))
    print("layers: %d files, %d file-to-file calls, %d circles, %d calls into a higher folder"
          % (len(objs), count, bad, up))
    sys.exit(1 if bad or up else 0)


if __name__ == "__main__":
    main()
