#!/usr/bin/env python3
"""Measured against fitted values of a calibration result, as an SVG.

   scripts/plot-calibration.py RESULT.json OUT.svg

RESULT.json is a calibration job's `result` (or the whole job, or the
output of `ringdyn calibrate`).  Scalar measurements only: one column per
measurement, the measured value with its +-1 sigma bar and the fitted value
as a cross, labelled with what the measurement set."""
import json
import sys


def main():
    doc = json.load(open(sys.argv[1]))
    r = doc.get("result", doc)
    spec = r["scene"]["measurements"]
    ms = [(m, s) for m, s in zip(r["measurements"], spec) if isinstance(m["measured"], (int, float))]
    sig = [s["sigma"] if isinstance(s["sigma"], (int, float)) else s["sigma"][0] for _, s in ms]
    ys = [m["measured"] for m, _ in ms] + [m["fitted"] for m, _ in ms]
    lo = min(y - s for y, s in zip(ys, sig + sig))
    hi = max(y + s for y, s in zip(ys, sig + sig))
    pad = 0.1 * (hi - lo)
    lo, hi = lo - pad, hi + pad
    W, H, L, R, T, B = 560, 300, 70, 20, 30, 60
    x = lambda i: L + (i + 0.5) * (W - L - R) / len(ms)
    y = lambda v: T + (hi - v) / (hi - lo) * (H - T - B)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="11">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<line x1="{L}" y1="{T}" x2="{L}" y2="{H - B}" stroke="black"/>',
           f'<line x1="{L}" y1="{H - B}" x2="{W - R}" y2="{H - B}" stroke="black"/>']
    for k in range(5):
        v = lo + k * (hi - lo) / 4
        out.append(f'<text x="{L - 6}" y="{y(v) + 4:.1f}" text-anchor="end">{v:.3g}</text>')
        out.append(f'<line x1="{L - 3}" y1="{y(v):.1f}" x2="{L}" y2="{y(v):.1f}" stroke="black"/>')
    out.append(f'<text x="14" y="{(T + H - B) / 2}" transform="rotate(-90 14 {(T + H - B) / 2})" text-anchor="middle">{ms[0][0]["observe"]}</text>')
    for i, ((m, s), sd) in enumerate(zip(ms, sig)):
        xm, ym, yf = x(i), y(m["measured"]), y(m["fitted"])
        out.append(f'<line x1="{xm:.1f}" y1="{y(m["measured"] - sd):.1f}" x2="{xm:.1f}" y2="{y(m["measured"] + sd):.1f}" stroke="#1f5fa8"/>')
        out.append(f'<circle cx="{xm:.1f}" cy="{ym:.1f}" r="4" fill="#1f5fa8"/>')
        out.append(f'<path d="M{xm - 5:.1f},{yf - 5:.1f} l10,10 m0,-10 l-10,10" stroke="#c0392b" stroke-width="2"/>')
        label = ", ".join(f'{k.split("/")[-1]} {v:g}' for k, v in (s.get("set") or {}).items())
        for j, part in enumerate(label.split(", ")):
            out.append(f'<text x="{xm:.1f}" y="{H - B + 16 + 13 * j}" text-anchor="middle">{part}</text>')
    out.append(f'<circle cx="{L + 10}" cy="14" r="4" fill="#1f5fa8"/><text x="{L + 18}" y="18">measured +- sigma</text>')
    out.append(f'<path d="M{L + 145},9 l10,10 m0,-10 l-10,10" stroke="#c0392b" stroke-width="2"/><text x="{L + 162}" y="18">fitted</text>')
    out.append("</svg>")
    open(sys.argv[2], "w").write("\n".join(out) + "\n")


main()
