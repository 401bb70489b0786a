#!/usr/bin/env python3
"""lift_friction_battery.py — auto on friction scenes against the full ring
(issue 39): the battery of scenes, each run by `ringdyn run` as auto would
run it and as the full ring at a reference resolution, the flank changes
compared (band-dated, output.flank_band default).

    bench/lift_friction_battery.py BUILD [--runs auto,full40,...] [--cache DIR]
                                         [--jobs J] [--only K,...] [--reduced]

BUILD is a build directory with cli/ringdyn (Release for timings).  Runs
are cached in DIR (default /tmp/ringdyn_battery) by scene and run, so a
second call only prints.  Runs: `auto` (the scene's defaults: n = 20, rtol
1e-6, estimate on), `rigid`, `fullN` (full ring, N segments, rtol 1e-8,
atol 1e-11 m x c_a / 30 um, no estimate).  Reference: the finest full run
given (default full40, full80).

Battery: the thesis ring (examples/thesis_lift_gas_6000rpm.json's ring and
engine, gravity, one cycle) over 100-8000 rpm x Coulomb mu 0.02-0.2 and
Stribeck x gas (that example's tables) on/off x axial clearance 10-100 um x
ring height 1.2 and 2 mm, a fixed sample of the factorial (seeded), plus the
named scenes of the issue (3000 rpm gas and Coulomb, where the rigid ring
bounces; 1000 rpm Coulomb, the twist-driven leave).
"""
import argparse
import concurrent.futures as cf
import hashlib
import json
import os
import random
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def base_scene():
    s = json.load(open(os.path.join(ROOT, 'examples', 'thesis_lift_gas_6000rpm.json')))
    s['engine']['cycles'] = 1
    s['physics']['gravity'] = True
    return s


def scene(rpm, fric, gas, ca_um, h_mm):
    s = base_scene()
    s['name'] = f'{rpm:g} rpm, {fric}, gas {gas}, c_a {ca_um:g} um, h {h_mm:g} mm'
    s['engine']['speed_rpm'] = rpm
    if fric == 'stribeck':
        s['physics']['friction'] = {'model': 'stribeck'}
    else:
        s['physics']['friction'] = {'model': 'coulomb', 'coefficient': float(fric)}
    if not gas:
        del s['physics']['gas']
    s['groove']['axial_clearance'] = ca_um * 1e-6
    s['ring']['axial_height'] = h_mm * 1e-3
    return s


def battery(reduced=False):
    named = [(3000, '0.1', 1, 30, 1.2), (3000, '0.1', 0, 30, 1.2), (1000, '0.1', 0, 30, 1.2),
             (6000, '0.1', 1, 30, 1.2), (8000, '0.1', 1, 30, 1.2), (8000, '0.1', 0, 30, 1.2),
             (100, '0.1', 0, 30, 1.2), (1000, 'stribeck', 0, 30, 1.2), (1000, '0.1', 0, 10, 1.2)]
    rng = random.Random(39)
    grid = [(r, f, g, c, h) for r in (100, 1000, 3000, 6000, 8000)
            for f in ('0.02', '0.1', '0.2', 'stribeck') for g in (0, 1) for c in (10, 30, 100)
            for h in (1.2, 2.0)]
    extra = [x for x in rng.sample(grid, len(grid)) if x not in named][:40]
    out = named + extra
    return out[:12] if reduced else out


def run_spec(spec):
    if spec == 'auto':
        return {}
    if spec == 'rigid':
        return {'numerics': {'model': 'rigid'}}
    if spec.startswith('full'):
        return {'numerics': {'model': 'full', 'rtol': 1e-8, 'error_estimate': False},
                'discretization': {'segments': int(spec[4:])}, '_atol': True}
    raise SystemExit('unknown run ' + spec)


def merge(s, o):
    for k, v in o.items():
        if isinstance(v, dict):
            merge(s.setdefault(k, {}), v)
        else:
            s[k] = v


CACHED_ONLY = False


def run_one(build, cache, key, sc, spec):
    s = json.loads(json.dumps(sc))
    o = run_spec(spec)
    atol = o.pop('_atol', False)
    merge(s, o)
    if atol:
        s['numerics']['atol'] = 1e-11 * s['groove']['axial_clearance'] / 3e-5
    # the references are keyed by scene; what auto and rigid give, by build too
    key_text = json.dumps(s, sort_keys=True) + ('' if spec.startswith('full') else build)
    h = hashlib.sha1(key_text.encode()).hexdigest()[:16]
    path = os.path.join(cache, f'{h}.json')
    if os.path.exists(path):
        return key, spec, json.load(open(path))
    if CACHED_ONLY:
        return key, spec, {'error': {'message': 'not run yet'}}
    t = time.time()
    r = subprocess.run([os.path.join(build, 'cli', 'ringdyn'), 'run', '-'],
                       input=json.dumps(s), capture_output=True, text=True)
    wall = time.time() - t
    try:
        res = json.loads(r.stdout)
    except ValueError:
        res = {'error': {'message': r.stderr[-400:] or r.stdout[-400:]}}
    keep = {'wall': wall, 'status': r.returncode}
    if 'error' in res and 'events' not in res:
        keep['error'] = res['error']
    else:
        res = res.get('result', res)
        keep['events'] = res.get('events')
        keep['numerics'] = res.get('numerics')
        keep['warnings'] = res.get('warnings')
        if spec in ('rigid', 'auto', 'auto20'):
            for k in ('crank_deg', 'lift', 'twist_rad', 'friction_force', 'flank'):
                keep[k] = res.get(k)
    json.dump(keep, open(path + '.tmp', 'w'))
    os.replace(path + '.tmp', path)
    return key, spec, keep


def ediff(a, b):
    """Largest angle difference of two event lists; None if they differ."""
    if a is None or b is None or len(a) != len(b):
        return None
    d = 0.0
    for x, y in zip(a, b):
        if x['event'] != y['event']:
            return None
        d = max(d, abs(x['crank_deg'] - y['crank_deg']))
    return d


def fmt(d):
    return 'list' if d is None else f'{d:.3f}'


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('build')
    ap.add_argument('--runs', default='auto,rigid,full20,full40')
    ap.add_argument('--cache', default='/tmp/ringdyn_battery')
    ap.add_argument('--jobs', type=int, default=1)
    ap.add_argument('--only', default='')
    ap.add_argument('--reduced', action='store_true')
    ap.add_argument('--cached', action='store_true', help='print what the cache holds, run nothing')
    a = ap.parse_args()
    os.makedirs(a.cache, exist_ok=True)
    global CACHED_ONLY
    CACHED_ONLY = a.cached
    runs = a.runs.split(',')
    scenes = battery(a.reduced)
    if a.only:
        scenes = [scenes[int(k)] for k in a.only.split(',')]
    res = {}
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        futs = [ex.submit(run_one, a.build, a.cache, i, scene(*p), r)
                for i, p in enumerate(scenes) for r in runs]
        for f in cf.as_completed(futs):
            k, r, v = f.result()
            res.setdefault(k, {})[r] = v
    fulls = sorted([r for r in runs if r.startswith('full')], key=lambda r: int(r[4:]))
    ref = fulls[-1] if fulls else None
    print('| # | scene | auto model | auto warn | auto wall [s] | ' +
          ' | '.join(f'{r} - {ref}' for r in runs if r != ref) + ' |')
    print('|' + '---|' * (5 + len(runs) - 1))
    for i, p in enumerate(scenes):
        rr = res[i]
        au = rr.get('auto', {})
        n = au.get('numerics') or {}
        warn = ','.join(w.get('code', '?') for w in (au.get('warnings') or []))
        cols = []
        for r in runs:
            if r == ref:
                continue
            x = rr.get(r, {})
            cols.append('err' if 'error' in x else fmt(ediff(x.get('events'), rr[ref].get('events'))))
        print(f"| {i} | {scene(*p)['name']} | {(n.get('model') or {}).get('name')} | {warn} | "
              f"{au.get('wall', 0):.3f} | " + ' | '.join(cols) + ' |')


if __name__ == '__main__':
    main()
