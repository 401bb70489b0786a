#!/usr/bin/env python3
"""layers.py — the layering lint: who calls whom, read off the built objects.

    layers.py SOURCE_DIR LIB.a...

Every object file in the archives is one source file (found under SOURCE_DIR by
its name).  File A calls file B when A's object has an undefined symbol that
B's object defines (`nm`: functions and data alike, so a function pointer
counts as a call).  Reading the objects, not the text, sees exactly what the
linker sees: no parsing, no missed macro, no static name mistaken for a call.

It fails (exit 1) on
  - a circle: files that call each other, directly or round a loop (every
    strongly connected component of more than one file is printed);
  - a call into a higher floor of core: core/<folder>/ files may call only
    their own folder and the folders below it, in the order of FLOORS.
It prints the counts it checked, so a run that found nothing to check fails
(no objects, no edges) instead of passing on an empty graph.
"""
import collections
import os
import subprocess
import sys

# core's folders, lowest first (docs/architecture.md, "Floors").
FLOORS = ["include", "base", "numerics", "ring", "engine", "liner", "statics", "lift", "ringpack"]


def objects(archives):
    """{object name: (defined symbols, undefined symbols)} over the archives."""
    out = subprocess.run(["nm", "-A", "--defined-only", "-g"] + archives, capture_output=True,
                         text=True, check=True).stdout
    undef = subprocess.run(["nm", "-A", "-u"] + archives, capture_output=True, text=True,
                           check=True).stdout
    objs = collections.defaultdict(lambda: (set(), set()))
    for text, slot in ((out, 0), (undef, 1)):
        for line in text.splitlines():
            # "archive:member:[address]  TYPE symbol"
            parts = line.split()
            if len(parts) < 2 or parts[0].count(":") < 2:
                continue
            member = parts[0].split(":")[1]
            if slot == 0 and (len(parts) < 3 or parts[-2] not in "TDBRCGS"):
                continue
            objs[member][slot].add(parts[-1])
    return objs


def source_of(root, member):
    """The source path (relative to root) of an object member such as rd_lift.c.o."""
    name = member[:-2] if member.endswith(".o") else member
    hits = []
    for d in ("core", "api", "server", "cli"):
        for dirpath, _, files in os.walk(os.path.join(root, d)):
            if name in files:
                hits.append(os.path.relpath(os.path.join(dirpath, name), root))
    if len(hits) != 1:
        sys.exit("layers: %s maps to %d source files (%s)" % (member, len(hits), hits))
    return hits[0]


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
    src = {m: source_of(root, m) for m in objs}
    owner = {}
    for m, (defs, _) in objs.items():
        for s in defs:
            owner[s] = src[m]
    edges = collections.defaultdict(set)
    count = 0
    for m, (_, undefs) in objs.items():
        for s in undefs:
            b = owner.get(s)
            if b and b != src[m]:
                if b not in edges[src[m]]:
                    count += 1
                edges[src[m]].add(b)
    bad = 0
    for comp in circles(set(src.values()), edges):
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
    if not objs or count == 0:
        sys.exit("layers: no objects or no calls found in %s" % " ".join(archives))
    print("layers: %d files, %d file-to-file calls, %d circles, %d calls into a higher folder"
          % (len(objs), count, bad, up))
    sys.exit(1 if bad or up else 0)


if __name__ == "__main__":
    main()
