// The contact analysis: renders a contact `result` (API.md) as a polar plot
// of the contact pressure around the circumference with the uniform pressure
// p0 as a reference circle, the bore's distortion (exaggerated) and the light
// gaps, plus tables of the figures and of the distortion orders.
// A pure function of the result: optional fields may be missing.

import { svg, scale, ticks, axes, pathD, polar, legend } from './svg.js';
import { h, fill, isNum, fixed, sig, seconds, percent, kvTable, resultLinks, newtonCost, nums, um, deg } from './html.js';
import { boreMapFigure } from './boremap.js';

const MPa = (v, d = 3) => (isNum(v) ? `${sig(v / 1e6, d)} MPa` : '—');

export const contact = {
  id: 'contact',
  label: 'Contact',
  runLabel: 'Run contact analysis',

  render(result, job, container) {
    const n = result.numerics || {};
    const gaps = lightGaps(result);
    const count = nums(result.clearance).length;
    fill(container,
      h('h3', {}, `Contact with the bore — pressure around the circumference${isNum(result.height_m) ? ` at z = ${mm(result.height_m)} mm` : ''}`),
      h('p', { id: 'ct-summary' },
        `Mean pressure ${MPa(result.mean_pressure_pa)} against the uniform ${MPa(result.uniform_pressure_pa)}; `,
        isNum(result.contact_fraction) ? `${fixed(result.contact_fraction, 1, 100)} % of the circumference in contact; ` : '',
        gaps.length
          ? `light gaps on ${gaps.length} of ${count} segments, largest ${um(result.max_clearance)} µm at ${deg(maxGapAngle(result, gaps))}.`
          : 'no light gap: the ring touches the bore all round.'),
      mapReadout(result),
      h('p', { id: 'cost', class: 'cost' }, h('strong', {}, 'Cost and accuracy: '), newtonCost(n)),
      resultLinks(job, 'contact', 'Pressure table (CSV)'),
      h('div', { class: 'result-grid' },
        h('figure', { class: 'plot' }, polarPlot(result, gaps),
          h('figcaption', {}, 'Contact pressure against the angle from the gap: gap (0°) at the right, angle counter-clockwise, ring seen from the cylinder head. ' +
            'Radius = pressure; dashed circle: the uniform pressure p0. Outer curve: the bore, its distortion exaggerated; marked arcs: light gaps (clearance > 0).')),
        h('div', { class: 'table-wrap' }, figures(result, gaps))),
      nums(result.angle_deg).length > 1
        ? h('figure', { class: 'plot wide' }, cartesianPlot(result, gaps),
          h('figcaption', {}, 'The same pressure against the angle from the gap, its axis fitted to the values so that small departures from p0 show (dashed: p0).'))
        : null,
      boreMapFigure(result.scene, 'ct-map', { height: result.scene?.contact?.height ?? null, shown: result.height_m ?? null },
        result.scene?.contact?.height === 'all'
          ? 'Lines: the layers, where the ring was solved (the thick one is the layer shown above).'
          : 'Line: the height of the ring.'),
      layersTable(result),
      patchTable(result),
      distortionTable(result),
    );
  },
};

const mm = (m) => sig(m * 1e3, 4);

// With a bore map: the height of the ring and the bore there;
// with contact.height "all", which layer the plots show.
function mapReadout(result) {
  if (!isNum(result.height_m)) return null;
  const b = result.bore_at_height || {};
  const orders = (Array.isArray(b.distortion) ? b.distortion : []).filter((d) => isNum(d.amplitude) && d.amplitude !== 0);
  const bore = [
    isNum(b.diameter) ? `D = ${sig(b.diameter * 1e3, 5)} mm` : null,
    orders.length
      ? `order${orders.length > 1 ? 's' : ''} ${orders.map((d) => `${d.order} (${um(d.amplitude)} µm${d.phase_deg ? ` at ${deg(d.phase_deg)}` : ''})`).join(', ')}`
      : 'round',
  ].filter(Boolean).join(', ');
  const z = mm(result.height_m);
  return h('p', { id: 'ct-height' }, result.scene?.contact?.height === 'all'
    ? `Bore map, the ring at every layer: shown here is the layer with the largest light gap, z = ${z} mm down the bore (the bore there: ${bore}); the table below lists every layer.`
    : `Bore map: the ring at z = ${z} mm down the bore (the bore there: ${bore}).`);
}

// With contact.height "all": one row per layer of the map.
function layersTable(result) {
  const rows = Array.isArray(result.layers) ? result.layers : [];
  if (!rows.length) return null;
  const MPa0 = (v) => fixed(v, 4, 1e-6);
  const body = rows.map((l) => h('tr', { class: isNum(result.height_m) && Math.abs(l.z_m - result.height_m) < 1e-12 ? 'shown' : null },
    h('td', { class: 'num' }, isNum(l.z_m) ? mm(l.z_m) : '—'),
    h('td', { class: 'num' }, isNum(l.diameter_m) ? sig(l.diameter_m * 1e3, 5) : '—'),
    h('td', { class: 'num' }, isNum(l.contact_fraction) ? fixed(l.contact_fraction, 1, 100) : '—'),
    h('td', { class: 'num' }, isNum(l.max_clearance) ? `${um(l.max_clearance)}${l.max_clearance > 0 && isNum(l.max_clearance_angle_deg) ? ` at ${deg(l.max_clearance_angle_deg)}` : ''}` : '—'),
    h('td', { class: 'num' }, MPa0(l.mean_pressure_pa)),
    h('td', { class: 'num' }, `${MPa0(l.min_bin_pressure_pa)} – ${MPa0(l.max_bin_pressure_pa)}`),
    h('td', { class: 'num' }, isNum(l.segments) ? String(l.segments) : '—'),
    h('td', {}, l.accuracy_met === true ? 'met' : l.accuracy_met === false ? 'not met' : '—')));
  return h('div', { class: 'table-wrap' }, h('table', { class: 'data', id: 'ct-layers' },
    h('caption', {}, 'Contact at every layer of the bore map (the highlighted row is the one plotted)'),
    h('thead', {}, h('tr', {},
      h('th', { scope: 'col', class: 'num' }, 'z (mm)'),
      h('th', { scope: 'col', class: 'num' }, 'D (mm)'),
      h('th', { scope: 'col', class: 'num' }, 'Contact (%)'),
      h('th', { scope: 'col', class: 'num' }, 'Largest light gap (µm)'),
      h('th', { scope: 'col', class: 'num' }, 'Mean pressure (MPa)'),
      h('th', { scope: 'col', class: 'num' }, '10° bins (MPa)'),
      h('th', { scope: 'col', class: 'num' }, 'Segments'),
      h('th', { scope: 'col' }, 'Accuracy'))),
    h('tbody', {}, body)));
}

// Indices of the segments that do not touch the bore (clearance > 0).
function lightGaps(result) {
  const c = nums(result.clearance);
  return c.map((v, i) => (v > 0 ? i : -1)).filter((i) => i >= 0);
}

function maxGapAngle(result, gaps) {
  if (isNum(result.max_clearance_angle_deg)) return result.max_clearance_angle_deg;
  const c = nums(result.clearance), a = nums(result.angle_deg);
  const i = gaps.reduce((best, j) => (c[j] > c[best] ? j : best), gaps[0]);
  return a[i];
}

// What the largest part of the binned pressure's estimate is
// (numerics.pressure_estimate_source, since 0.3.4).
const ESTIMATE_SOURCE = {
  levels: "the bins' change between the last two levels",
  edge_segment: "a gap edge's segment across the bin boundary",
  edge: 'a gap edge beside the bin boundary',
  patch: 'a contact patch too narrow to split across the bin boundary',
  law: "the contact law's compliance",
};

function figures(result, gaps) {
  const n = result.numerics || {};
  const mean = result.mean_pressure_pa, p0 = result.uniform_pressure_pa;
  const ratio = isNum(mean) && isNum(p0) && p0 !== 0 ? ` (${(mean / p0).toFixed(3)} p0)` : '';
  // the levels' part from the pair solved again on shifted meshes (since 0.3.10)
  const from = n.pressure_estimate_source === 'levels' && n.pressure_shifted_meshes === true
    ? "the bins' change between the last two levels, as far as shifting their segments does not explain it"
    : ESTIMATE_SOURCE[n.pressure_estimate_source];
  const where = from && isNum(n.pressure_estimate_at_deg) ? `; mostly ${from} at ${deg(n.pressure_estimate_at_deg)}` : '';
  const err = isNum(n.error_estimate)
    ? `${percent(n.error_estimate)}${n.reference_segments ? ` (vs ${n.reference_segments} segments)` : ''}${where}`
    : 'not estimated';
  // each figure with its own error estimate (numerics.error_estimates), when there is one
  const est = n.error_estimates || {};
  const pm = (v, text) => (isNum(v) ? ` ± ${text(v)}` : '');
  const tips = nums(result.tip_forces_n);
  const accuracy = n.accuracy_met === true
    ? `met (${percent(n.accuracy, 1)} of p0 for the binned pressure)`
    : n.accuracy_met === false ? `not met: ${n.accuracy_note || 'see the estimates'}` : undefined;
  return kvTable({
    id: 'ct-table',
    caption: 'Contact figures, accuracy and cost',
    rows: [
      ['Mean contact pressure', `${MPa(mean)}${ratio}`, { id: 'ct-mean' }],
      ['Uniform pressure p0 = 2 Ft / (d h)', MPa(p0), { id: 'ct-p0-value' }],
      ['Contact fraction', isNum(result.contact_fraction)
        ? `${fixed(result.contact_fraction, 1, 100)} %${pm(est.contact_fraction, (v) => `${fixed(v, 2, 100)} %`)}` : '—', { id: 'ct-fraction' }],
      ['Largest light gap', gaps.length || isNum(result.max_clearance)
        ? `${um(result.max_clearance)} µm${gaps.length ? `${pm(est.max_clearance, (v) => `${sig(v * 1e6, 2)} µm`)} at ${deg(maxGapAngle(result, gaps))}` : ''}` : '—', { id: 'ct-max-clearance' }],
      ['Light-gap edges', Array.isArray(result.light_gaps) && result.light_gaps.length && isNum(est.gap_edges_deg)
        ? `± ${sig(est.gap_edges_deg, 2)}° (estimate)` : undefined, { id: 'ct-edges' }],
      ['Tip forces (free ends)', tips.length === 2
        ? `${sig(tips[0], 4)} N, ${sig(tips[1], 4)} N${pm(est.tip_forces_n, (v) => `${sig(v, 2)} N`)}` : undefined, { id: 'ct-tips' }],
      ['Segments with a light gap', `${gaps.length} of ${nums(result.clearance).length}`],
      ['Largest penetration', isNum(result.max_penetration) ? `${um(result.max_penetration, 3)} µm` : undefined],
      ['Contact stiffness', isNum(result.contact_stiffness) ? `${sig(result.contact_stiffness)} Pa/m` : undefined],
      ['Conformability k (1.4)', isNum(result.conformability) ? sig(result.conformability, 4) : undefined],
      ['Error estimate (binned pressure)', err, { id: 'ct-error' }],
      // what the estimates cover, as text beside them (not a tooltip)
      ['What the estimate covers', n.error_method ?? undefined, { id: 'ct-error-scope' }],
      ['Accuracy target', accuracy, { id: 'ct-accuracy' }],
      ['Segments / DOF', `${n.segments ?? '—'} / ${n.dof ?? '—'}`],
      ['Load steps / Newton iterations', `${n.load_steps ?? '—'} / ${n.iterations ?? '—'}`],
      ['Factorizations / multiplier updates', isNum(n.factorizations)
        ? `${n.factorizations} / ${n.multiplier_updates ?? '—'}` : undefined, { id: 'ct-cost' }],
      ['Wall time', seconds(n.wall_s)],
      ['Solver', n.solver],
    ],
  });
}

// The contact patches (since 0.3.15): where the ring touches between its
// light gaps and how hard, N, with the estimate of the patch forces' error.
function patchTable(result) {
  const rows = Array.isArray(result.contact_patches) ? result.contact_patches : [];
  if (!rows.length) return null;
  const est = result.numerics?.error_estimates?.patch_forces_n;
  const body = rows.map((p) => h('tr', {},
    h('td', { class: 'num' }, isNum(p.start_deg) ? p.start_deg.toFixed(2) : '—'),
    h('td', { class: 'num' }, isNum(p.end_deg) ? p.end_deg.toFixed(2) : '—'),
    h('td', { class: 'num' }, isNum(p.force_n) ? sig(p.force_n, 4) : '—'),
    h('td', { class: 'num' }, isNum(p.centroid_deg) ? p.centroid_deg.toFixed(2) : '—')));
  return h('div', { class: 'table-wrap' }, h('table', { class: 'data', id: 'ct-patches' },
    h('caption', {}, `Contact patches: where the ring touches the bore between its light gaps, and the bore's force on each${isNum(est) ? ` (± ${sig(est, 2)} N, estimate)` : ''}`),
    h('thead', {}, h('tr', {},
      h('th', { scope: 'col', class: 'num' }, 'From (deg)'),
      h('th', { scope: 'col', class: 'num' }, 'To (deg)'),
      h('th', { scope: 'col', class: 'num' }, 'Force (N)'),
      h('th', { scope: 'col', class: 'num' }, 'Acting at (deg)'))),
    h('tbody', {}, body)));
}

// Each distortion order: its amplitude against the thin-ring conformability
// bound F_t R^3 / (E I (k^2 - 1)^2): a ring follows distortions below it.
function distortionTable(result) {
  const rows = Array.isArray(result.distortion) ? result.distortion : [];
  if (!rows.length) return h('p', { class: 'hint', id: 'ct-round' }, 'Round bore: no distortion orders.');
  const body = rows.map((d) => {
    const a = Number(d.amplitude), b = Number(d.conformability_bound);
    const verdict = isNum(b) && isNum(a) ? (Math.abs(a) <= b ? 'follows' : 'light gap likely') : '—';
    return h('tr', {},
      h('td', { class: 'num' }, String(d.order ?? '—')),
      h('td', { class: 'num' }, um(a, 2)),
      h('td', { class: 'num' }, isNum(d.phase_deg) ? d.phase_deg.toFixed(1) : '—'),
      h('td', { class: 'num' }, isNum(b) ? um(b, 2) : '—'),
      h('td', {}, verdict));
  });
  return h('div', { class: 'table-wrap' }, h('table', { class: 'data', id: 'ct-distortion' },
    h('caption', {}, 'Bore distortion orders against the thin-ring conformability bound (the largest amplitude the ring follows)'),
    h('thead', {}, h('tr', {},
      h('th', { scope: 'col', class: 'num' }, 'Order k'),
      h('th', { scope: 'col', class: 'num' }, 'Amplitude (µm)'),
      h('th', { scope: 'col', class: 'num' }, 'Phase (deg)'),
      h('th', { scope: 'col', class: 'num' }, 'Bound (µm)'),
      h('th', { scope: 'col' }, 'Ring'))),
    h('tbody', {}, body)));
}

// The bore's radius change (m) at angle `a` (deg): from the distortion
// orders when the result lists them, else from the per-segment radii.
function boreDeviation(result) {
  const orders = (Array.isArray(result.distortion) ? result.distortion : result.scene?.bore?.distortion) || [];
  const valid = orders.filter((d) => isNum(d.order) && isNum(d.amplitude));
  if (valid.length) {
    return {
      smooth: true,
      at: (a) => valid.reduce((s, d) => s + d.amplitude * Math.cos((d.order * (a - (d.phase_deg || 0)) * Math.PI) / 180), 0),
    };
  }
  const r = nums(result.bore_radius), ang = nums(result.angle_deg);
  if (r.length < 3 || r.length !== ang.length) return null;
  const mean = r.reduce((s, v) => s + v, 0) / r.length;
  if (r.every((v) => Math.abs(v - mean) <= 1e-12 * Math.abs(mean))) return null;
  return { smooth: false, points: ang.map((a, i) => [a, r[i] - mean]) };
}

function polarPlot(result, gaps) {
  const S = 480, cx = S / 2, cy = S / 2 + 14;
  const RP = 125; // px of the pressure axis maximum
  const RB = 160; // px of the bore's nominal radius
  const angles = nums(result.angle_deg);
  const p = nums(result.pressure_pa);
  const k = Math.min(angles.length, p.length);
  const p0 = result.uniform_pressure_pa;
  const pm = Math.max(isNum(p0) ? p0 : 0, ...p.slice(0, k).filter(isNum), 1);
  const t = ticks(0, pm, 3);
  const step = t.length > 1 ? t[1] - t[0] : pm;
  const pAxis = Math.ceil((pm * 1.0001) / step) * step;
  const rOf = (v) => (RP * Math.max(0, v)) / pAxis;

  const grid = svg('g', { class: 'polar-grid' });
  for (let v = step; v <= pAxis + step * 1e-9; v += step) {
    grid.append(svg('circle', { class: 'grid', cx, cy, r: rOf(v), fill: 'none' }));
    const [tx, ty] = polar(cx, cy, rOf(v), 100);
    grid.append(svg('text', { class: 'tick', x: tx, y: ty - 2, 'text-anchor': 'middle' }, `${sig(v / 1e6)} MPa`));
  }
  for (const a of [0, 90, 180, 270]) {
    const [x1, y1] = polar(cx, cy, RB + 22, a);
    grid.append(svg('line', { class: 'grid', x1: cx, y1: cy, x2: x1, y2: y1 }));
    const [lx, ly] = polar(cx, cy, RB + 28, a);
    grid.append(svg('text', {
      class: 'tick', x: lx, y: ly, 'dominant-baseline': 'middle',
      'text-anchor': a === 0 ? 'start' : a === 180 ? 'end' : 'middle',
    }, a === 0 ? '0° gap' : `${a}°`));
  }

  // The bore: a circle of radius RB, its distortion exaggerated to <= 18 px.
  const dev = boreDeviation(result);
  let borePath, boreText = 'bore (round)', exaggerate = 0;
  let boreAt = () => RB; // px radius of the drawn bore at an angle
  const D = Number(result.scene?.bore?.diameter) || Number(result.scene?.ring?.diameter) || 0;
  if (dev) {
    const samples = dev.smooth ? Array.from({ length: 361 }, (_, i) => [i, dev.at(i)]) : dev.points;
    const maxDev = Math.max(...samples.map((s) => Math.abs(s[1])));
    exaggerate = maxDev > 0 ? 18 / maxDev : 0; // px per m of radius change
    borePath = pathD(samples.map(([a, d]) => polar(cx, cy, RB + d * exaggerate, a)), true);
    if (dev.smooth) boreAt = (a) => RB + dev.at(a) * exaggerate;
    if (D > 0 && exaggerate > 0) boreText = `bore, distortion ×${sig(exaggerate / (RB / (D / 2)), 2)} (exaggerated)`;
    else boreText = 'bore, distortion exaggerated';
  }
  const bore = dev
    ? svg('path', { class: 'bore', id: 'ct-bore', d: borePath })
    : svg('circle', { class: 'bore', id: 'ct-bore', cx, cy, r: RB });

  // Light gaps: an arc per segment with clearance > 0, just inside the bore.
  const c = nums(result.clearance);
  const half = k > 0 ? 180 / k : 5;
  const RG = (a) => boreAt(a) - 8;
  const arcs = gaps.map((i) => {
    const a = angles[i];
    const pts = [];
    for (let j = 0; j <= 8; j++) {
      const t = a - half + (2 * half * j) / 8;
      pts.push(polar(cx, cy, RG(t), t));
    }
    return svg('path', { class: 'light-gap', d: pathD(pts), 'data-index': i },
      svg('title', {}, `Light gap ${um(c[i])} µm at ${deg(a)}`));
  });
  let maxMark = null;
  if (gaps.length) {
    const am = maxGapAngle(result, gaps);
    const [mx, my] = polar(cx, cy, RG(am), am);
    const [lx, ly] = polar(cx, cy, RG(am) - 14, am);
    const cos = Math.cos((am * Math.PI) / 180);
    maxMark = svg('g', { class: 'max-gap' },
      svg('circle', { cx: mx, cy: my, r: 4 }),
      svg('text', {
        id: 'ct-max-gap-label', class: 'halo', x: lx, y: ly, 'dominant-baseline': 'middle',
        'text-anchor': cos > 0.3 ? 'end' : cos < -0.3 ? 'start' : 'middle',
      }, `max ${um(result.max_clearance)} µm`));
  }

  // Contact patches (since 0.3.15) where the ring has light gaps: a mark on
  // the bore where each patch's force acts, the force in its tooltip.
  const patches = gaps.length && Array.isArray(result.contact_patches) ? result.contact_patches : [];
  const patchMarks = patches.filter((q) => isNum(q.centroid_deg) && isNum(q.force_n)).map((q) => {
    const [px, py] = polar(cx, cy, boreAt(q.centroid_deg) + 7, q.centroid_deg);
    return svg('circle', { class: 'patch-mark', cx: px, cy: py, r: 4 },
      svg('title', {}, `Contact patch ${deg(q.start_deg)}–${deg(q.end_deg)}: ${sig(q.force_n, 4)} N at ${deg(q.centroid_deg)}`));
  });
  const pressure = pathD(angles.slice(0, k).map((a, i) => polar(cx, cy, rOf(p[i]), a)));
  const summary = `Polar plot of the contact pressure at ${k} points, up to ${MPa(Math.max(...p.slice(0, k).filter(isNum), 0))}; ` +
    `uniform pressure ${MPa(p0)}; ${gaps.length} light-gap segments${gaps.length ? `, largest ${um(result.max_clearance)} µm` : ''}.`;
  return svg('svg', { id: 'ct-polar', class: 'chart polar', viewBox: `0 0 ${S} ${S + 28}`, role: 'img', 'aria-label': summary },
    legend([
      [svg('path', { class: 'pressure', d: 'M-2,0H12' }), 'pressure'],
      [svg('path', { class: 'p0', d: 'M-2,0H12' }), 'p0'],
      [svg('path', { class: 'light-gap', d: 'M-2,0H12' }), 'light gap'],
      ...(patchMarks.length ? [[svg('circle', { class: 'patch-mark', cx: 5, cy: 0, r: 4 }), 'contact patch']] : []),
    ], { x: 10, y: 12 }),
    svg('text', { class: 'tick', x: 10, y: 32, id: 'ct-bore-label' }, boreText),
    grid,
    bore,
    isNum(p0) ? svg('circle', { class: 'p0', id: 'ct-p0', cx, cy, r: rOf(p0) },
      svg('title', {}, `Uniform pressure p0 = ${MPa(p0)}`)) : null,
    svg('path', { class: 'pressure', id: 'ct-pressure', d: pressure }),
    svg('g', { class: 'light-gaps' }, arcs),
    svg('g', { class: 'patch-marks', id: 'ct-patch-marks' }, patchMarks),
    maxMark);
}

// Pressure against angle on axes fitted to the values (p0 included): the
// polar plot starts at 0, where a ±1 % ripple near the gap cannot be seen.
function cartesianPlot(result, gaps) {
  const W = 720, H = 280;
  const box = { left: 72, top: 34, width: W - 72 - 16, height: H - 34 - 50 };
  const angles = nums(result.angle_deg), p = nums(result.pressure_pa);
  const k = Math.min(angles.length, p.length);
  const p0 = result.uniform_pressure_pa;
  const mpa = p.slice(0, k).map((v) => v / 1e6);
  const vals = [...mpa, ...(isNum(p0) ? [p0 / 1e6] : [])].filter(isNum);
  const lo = Math.min(...vals), hi = Math.max(...vals);
  const pad = (hi - lo) * 0.12 || Math.abs(hi) * 0.01 || 1;
  const x = scale(0, 360, box.left, box.left + box.width);
  const y = scale(lo - pad, hi + pad, box.top + box.height, box.top);
  const rel = (v) => `${v >= 0 ? '+' : '−'}${Math.abs(v * 100).toFixed(2)} %`;
  const dev = isNum(p0) && p0 > 0 ? [Math.min(...mpa) / (p0 / 1e6) - 1, Math.max(...mpa) / (p0 / 1e6) - 1] : null;
  const yTicks = ticks(lo - pad, hi + pad, 5);
  const digits = Math.max(3, Math.ceil(Math.log10(Math.abs(hi) / (yTicks.length > 1 ? yTicks[1] - yTicks[0] : 1) || 1)) + 2);
  return svg('svg', {
    id: 'ct-cartesian', class: 'chart', viewBox: `0 0 ${W} ${H}`, role: 'img',
    'data-deviation': dev ? dev.map((v) => v.toFixed(6)).join(' ') : null,
    'aria-label': `Contact pressure against angle, ${sig(lo)} to ${sig(hi)} MPa${dev ? ` (${rel(dev[0])} to ${rel(dev[1])} of p0)` : ''}.`,
  },
  legend([
    [svg('path', { class: 'p-line', d: 'M-2,0H12' }), 'pressure'],
    [svg('path', { class: 'p0', d: 'M-2,0H12' }), `p0 = ${MPa(p0)}`],
    ...(dev ? [[svg('g', {}), `range ${rel(dev[0])} to ${rel(dev[1])} of p0`]] : []),
  ], { x: box.left, y: 14 }),
  axes({
    box, x, y, xTicks: [0, 45, 90, 135, 180, 225, 270, 315, 360], yTicks,
    xLabel: 'angle from the gap (deg)', yLabel: 'pressure (MPa)', yFormat: (v) => String(Number(v.toPrecision(digits))),
  }),
  isNum(p0) ? svg('line', { class: 'p0', id: 'ct-cart-p0', x1: box.left, x2: box.left + box.width, y1: y(p0 / 1e6), y2: y(p0 / 1e6) }) : null,
  gaps.map((i) => svg('rect', { class: 'band', x: x(angles[i]) - box.width / (2 * k), y: box.top, width: box.width / k, height: box.height },
    svg('title', {}, `Light gap at ${deg(angles[i])}`))),
  svg('path', { class: 'p-line', id: 'ct-cart-line', 'data-name': 'pressure', d: pathD(angles.slice(0, k).map((a, i) => [x(a), y(mpa[i])])) }),
  svg('g', { class: 'p-points' }, angles.slice(0, k).map((a, i) => svg('circle', { class: 'p-mk', cx: x(a), cy: y(mpa[i]), r: 2.5 },
    svg('title', {}, `${deg(a)}: ${MPa(p[i], 5)}`)))));
}
