#!/usr/bin/env python3
"""bitcheck.py — do two builds give the same answers?  For refactorings that
must not change a number (docs/architecture.md).  The API's answers are
compared in every printed digit (results print 10 significant digits); the
contact battery's fingerprints hash the doubles themselves, so they are
bit for bit; test_lift_golden holds the lift trajectories bit for bit.

    bench/bitcheck.py run BUILD OUT      run BUILD's ringdyn and bench_contact_cost, answers into OUT
    bench/bitcheck.py compare OUT1 OUT2  numbers must be identical; exit 1 if any differs

`run` sends through `BUILD/cli/ringdyn run -` every scene of examples/ and these
variants: the four lift examples x numerics.model {full, rigid, modal (6
modes)} x friction {as given, Stribeck, Coulomb 0.12}, one cycle; the two 2400
rpm ring packs with Coulomb 0.1 x numerics.model {auto, rigid, full}, two
cycles.  It keeps the exit status, the answer without its wall-clock keys
(wall_s, cpu_s, ...) and stderr, and the fingerprints of
`BUILD/bench/bench_contact_cost --battery` (FNV-1a over every double of each
contact answer).  `compare` walks both answers: every number, length and key
must match; strings that differ are listed as information (a solver's
description may name a moved file).  A Release build takes ~5 minutes on 2
cores:  cmake -S . -B build-rel -DCMAKE_BUILD_TYPE=Release -DRINGDYN_TESTS=OFF
"""
import copy
import glob
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TIMING = {"wall_s", "cpu_s", "elapsed_s", "time_s"}


def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items() if k not in TIMING}
    if isinstance(o, list):
        return [strip(v) for v in o]
    return o


def scenes():
    out = {}
    for f in sorted(glob.glob(os.path.join(ROOT, "examples", "*.json"))):
        out[os.path.basename(f)[:-5]] = json.load(open(f))
    for name in ["thesis_lift_1000rpm", "thesis_lift_gas_6000rpm", "lift_distorted", "lift_tilted"]:
        for model in ["full", "rigid", "modal"]:
            for fr in [None, {"model": "stribeck"}, {"model": "coulomb", "coefficient": 0.12}]:
                s = copy.deepcopy(out[name])
                s.setdefault("numerics", {})["model"] = model
                s["engine"]["cycles"] = 1
                if fr is not None:
                    s.setdefault("physics", {})["friction"] = fr
                if model == "modal":
                    s["numerics"]["modes"] = 6
                out["%s_%s_%s" % (name, model, fr["model"] if fr else "asis")] = s
    for name in ["thesis_ringpack_full_load_2400rpm", "thesis_ringpack_motored_2400rpm"]:
        for model in ["auto", "rigid", "full"]:
            s = copy.deepcopy(out[name])
            s.setdefault("physics", {})["friction"] = {"model": "coulomb", "coefficient": 0.1}
            s.setdefault("numerics", {})["model"] = model
            s["engine"]["cycles"] = 2
            out[name + "_fric_" + model] = s
    return out


def run(build, dest):
    os.makedirs(dest, exist_ok=True)
    sc = scenes()
    for k, s in sc.items():
        p = subprocess.run([os.path.join(build, "cli", "ringdyn"), "run", "-"], input=json.dumps(s),
                           capture_output=True, text=True)
        ans = strip(json.loads(p.stdout)) if p.stdout.strip().startswith("{") else p.stdout
        json.dump({"rc": p.returncode, "out": ans, "err": p.stderr},
                  open(os.path.join(dest, k + ".json"), "w"), sort_keys=True)
    p = subprocess.run([os.path.join(build, "bench", "bench_contact_cost"), "--battery"],
                       capture_output=True, text=True, check=True)
    prints = [l.split("|")[-2].strip() for l in p.stdout.splitlines() if l.count("|") > 5]
    open(os.path.join(dest, "contact_fingerprints.txt"), "w").write("\n".join(prints) + "\n")
    print("bitcheck: %d scenes, %d fingerprint lines into %s" % (len(sc), len(prints), dest))


def walk(x, y, path, strs, bad):
    if isinstance(x, dict) and isinstance(y, dict):
        for k in sorted(set(x) | set(y)):
            if k not in x or k not in y:
                bad.append("%s/%s only in one" % (path, k))
            else:
                walk(x[k], y[k], path + "/" + k, strs, bad)
    elif isinstance(x, list) and isinstance(y, list):
        if len(x) != len(y):
            bad.append("%s: length %d vs %d" % (path, len(x), len(y)))
        for i, (u, v) in enumerate(zip(x, y)):
            walk(u, v, "%s/%d" % (path, i), strs, bad)
    elif isinstance(x, str) and isinstance(y, str):
        if x != y:
            strs.append(path)
    elif x != y:
        bad.append("%s: %r vs %r" % (path, x, y))


def compare(a, b):
    bad, strs = [], []
    files = sorted(glob.glob(os.path.join(a, "*.json")))
    if not files:
        sys.exit("bitcheck: no answers in %s" % a)
    for f in files:
        g = os.path.join(b, os.path.basename(f))
        if not os.path.exists(g):
            bad.append("%s missing in %s" % (os.path.basename(f), b))
            continue
        walk(json.load(open(f)), json.load(open(g)), os.path.basename(f), strs, bad)
    fa = open(os.path.join(a, "contact_fingerprints.txt")).read()
    fb = open(os.path.join(b, "contact_fingerprints.txt")).read()
    if fa != fb:
        bad.append("contact fingerprints differ")
    for s in strs:
        print("string differs (information): " + s)
    for line in bad[:40]:
        print("DIFFERS " + line)
    print("bitcheck: %d answers, %d numeric differences, fingerprints %s" %
          (len(files), len(bad), "identical" if fa == fb else "differ"))
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[1] not in ("run", "compare"):
        sys.exit(__doc__)
    (run if sys.argv[1] == "run" else compare)(sys.argv[2], sys.argv[3])
