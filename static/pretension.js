// The pretension analysis: renders a pretension `result` (API.md) as the free
// shape of the ring in its plane (closed reference and opened free shape,
// gap opening x_a marked), the axial gap opening against angle when there is
// a lateral force, and a table of the gap figures, accuracy and cost.
// A pure function of the result: optional fields may be missing.

import { svg, scale, ticks, axes, pathD, legend } from './svg.js';
import { h, fill, isNum, fixed, sig, seconds, percent, kvTable, resultLinks, newtonCost, nums, um } from './html.js';

const mm = (v, d = 2) => fixed(v, d, 1e3);

export const pretension = {
  id: 'pretension',
  label: 'Pretension',
  runLabel: 'Run pretension analysis',

  // Draws `result` of finished job `job` into `container` (emptied first).
  render(result, job, container) {
    const n = result.numerics || {};
    const xa = result.gap_opening_inner, xc = result.lateral_opening;
    const lateral = isNum(xc) && xc > 0 && nums(result.shape?.z).length > 1;
    const method = result.scene?.pretension?.method;
    fill(container,
      h('h3', {}, `Pretension — free shape${method ? ` (${method} method)` : ''}`),
      h('p', { id: 'pt-summary' },
        'Gap opening ', h('i', {}, 'x'), h('sub', {}, 'a'), ' = ', h('strong', {}, `${mm(xa)} mm`),
        isNum(result.free_gap_formula) ? ` (formula 1.5: ${mm(result.free_gap_formula)} mm)` : '',
        isNum(xc) ? [', lateral opening ', h('i', {}, 'x'), h('sub', {}, 'c'), ` = ${mm(xc, 3)} mm`] : '',
        '.'),
      modelNote(result),
      h('p', { id: 'cost', class: 'cost' }, h('strong', {}, 'Cost and accuracy: '), newtonCost(n)),
      resultLinks(job, 'pretension', 'Free shape (CSV)'),
      h('div', { class: 'result-grid' },
        h('figure', { class: 'plot' }, shapePlot(result),
          h('figcaption', {}, 'The ring in its plane seen from the cylinder head, gap (0°) to the right (+x), true scale. ' +
            'Dashed: closed (reference) shape; solid: free shape opened by the pretension.')),
        sectionPlot(result),
        freeShapePlot(result),
        lateral ? h('figure', { class: 'plot' }, zPlot(result),
          h('figcaption', {}, 'Axial (z) displacement of the centroid line against the angle from the gap: the lateral forces twist the ring out of its plane.')) : null),
      h('div', { class: 'table-wrap' }, figures(result)),
    );
  },
};

function figures(result) {
  const n = result.numerics || {};
  const xa = result.gap_opening_inner, m = result.free_gap_formula;
  const vsFormula = isNum(xa) && isNum(m) && m !== 0 ? ` (${xa >= m ? '+' : ''}${(((xa - m) / m) * 100).toFixed(1)} %)` : '';
  const support = result.support || {};
  const err = isNum(n.error_estimate)
    ? `${percent(n.error_estimate)}${n.reference_segments ? ` (vs ${n.reference_segments} segments)` : ''}`
    : 'not estimated';
  return kvTable({
    id: 'pt-table',
    caption: 'Gap figures, accuracy and cost',
    rows: [
      [['Gap opening ', h('i', {}, 'x'), h('sub', {}, 'a'), ' (inner corners)'], `${mm(xa, 3)} mm${vsFormula}`, { id: 'pt-xa' }],
      [['Lateral opening ', h('i', {}, 'x'), h('sub', {}, 'c')], `${mm(result.lateral_opening, 3)} mm`, { id: 'pt-xc' }],
      ['Gap opening at the neutral axis', isNum(result.gap_opening_neutral) ? `${mm(result.gap_opening_neutral, 3)} mm` : undefined],
      ['Free gap from the formula (1.5)', `${mm(m, 3)} mm`, { id: 'pt-formula' }],
      [['Conformability ', h('i', {}, 'k'), ' (1.4)'], sig(result.conformability, 4), { id: 'pt-k' }],
      ['Free gap at the running face', isNum(result.free_shape?.free_gap_m) ? `${mm(result.free_shape.free_gap_m, 3)} mm` : undefined, { id: 'pt-free-gap' }],
      ['Tangential force that closes it', isNum(result.free_shape?.tangential_force_n)
        ? `${sig(result.free_shape.tangential_force_n, 5)} N${result.free_shape_model && result.free_shape_model !== 'stress_free_closed' ? ' (computed)' : ' (given: F_t)'}` : undefined, { id: 'pt-ft' }],
      ['Support force / moment (opposite the gap)', isNum(support.force_n) || isNum(support.moment_nm)
        ? `${sig(support.force_n)} N / ${sig(support.moment_nm)} N·m` : undefined],
      ['Error estimate', err, { id: 'pt-error' }],
      // what the estimate covers, as text beside it (not a tooltip)
      ['What the estimate covers', n.error_method ?? undefined, { id: 'pt-error-scope' }],
      ['Segments / DOF', `${n.segments ?? '—'} / ${n.dof ?? '—'}`],
      ['Load steps / Newton iterations', `${n.load_steps ?? '—'} / ${n.iterations ?? '—'}`],
      ['Residual (tolerance)', isNum(n.residual) ? `${sig(n.residual, 2)} (${sig(n.tolerance, 2)})` : undefined],
      ['Wall time', seconds(n.wall_s)],
      ['Solver', n.solver],
    ],
  });
}

// Which ring was solved (result.free_shape_model), in words beside the result.
function modelNote(result) {
  const m = result.free_shape_model;
  if (!m) return null;
  const pd = result.scene?.ring?.pressure_distribution;
  const what = pd === 'uniform' ? 'a uniform pressure'
    : pd?.orders ? `p/p₀ = 1 ${pd.orders.map((o) => `${o.amplitude < 0 ? '−' : '+'} ${Math.abs(o.amplitude)} cos ${o.order}θ`).join(' ')}`
      : 'the tabulated pressure';
  if (m === 'measured_free_shape') return measuredNote(result.free_shape_fit || {});
  return h('p', { id: 'pt-model', class: 'hint' }, m === 'pressure_distribution'
    ? `The ring is made with the free shape that a round bore of its diameter closes to its closed gap with ${what} (θ from the point opposite the gap); that free shape is solved geometrically exactly, and its gap faces carry nothing.`
    : 'The ring is the stress-free closed ring opened by F_t on its gap faces (the thesis model). Give ring.pressure_distribution for a ring made with the free shape of a pressure distribution.');
}

// The pressure fitted to a measured free shape (result.free_shape_fit), in
// words with its standard errors (the table's scatter) and the chain's error.
function measuredNote(f) {
  const orders = (f.orders || []).map((o) => `${o.amplitude < 0 ? '−' : '+'} ${sig(Math.abs(o.amplitude), 3)}(±${sig(o.standard_error, 2)}) cos ${o.order}θ`).join(' ');
  return h('p', { id: 'pt-model', class: 'hint' },
    `The ring is made with the measured free shape (ring.free_shape, ${f.points ?? '—'} points): the pressure whose exact free shape is closest to it is p/p₀ = 1 ${orders} with F_t = ${sig(f.tangential_force_n, 5)} N (±${sig(f.tangential_force_standard_error_n, 2)}); `
    + `the points lie ${sig((f.residual_rms_m ?? NaN) * 1e6, 2)} µm RMS from that shape (largest ${sig((f.residual_max_m ?? NaN) * 1e6, 2)} µm). `
    + `± is the table's scatter; the chain's own error is ${sig(Math.max(...(f.orders || []).map((o) => o.segments_error ?? 0), 0), 2)} of p₀ at most; neither covers a systematic error of the table or orders above ${(f.orders || []).length + 1}. `
    + (isNum(f.pressure_min_ratio) && f.pressure_min_ratio < 0 ? `The fitted pressure falls to ${sig(f.pressure_min_ratio, 3)} p₀ at ${sig(f.pressure_min_theta_deg, 3)}°: the ring leaves a round bore there.` : ''));
}

// The measured points in the fitted shape's frame (the table's centre and
// angle origin as fitted): [theta_deg, radius_m] each, or [].
function measuredPoints(result) {
  const t = nums(result.scene?.ring?.free_shape?.theta_deg), r = nums(result.scene?.ring?.free_shape?.radius_m);
  const fit = result.free_shape_fit;
  if (!fit || !Array.isArray(fit.centre_m)) return [];
  const [x0, y0] = fit.centre_m, rot = (fit.rotation_deg || 0) * Math.PI / 180;
  return t.slice(0, r.length).map((a, i) => {
    const X = x0 + r[i] * Math.cos(a * Math.PI / 180 + rot), Y = y0 + r[i] * Math.sin(a * Math.PI / 180 + rot);
    return [Math.atan2(Y, X) * 180 / Math.PI, Math.hypot(X, Y)];
  });
}

// The free shape as a gauge measures it (result.free_shape): the running
// face's radius less d/2 (mm) against the angle from the point opposite the
// gap.  Nothing without it.
function freeShapePlot(result) {
  const f = result.free_shape || {};
  const t = nums(f.theta_deg), r = nums(f.radius_m), d = Number(result.scene?.ring?.diameter);
  const k = Math.min(t.length, r.length);
  if (k < 2 || !isNum(d)) return null;
  const dr = r.slice(0, k).map((v) => (v - d / 2) * 1e3);
  const meas = measuredPoints(result).map(([a, v]) => [a, (v - d / 2) * 1e3]);
  const W = 420, H = 240;
  const box = { left: 62, top: 14, width: W - 62 - 12, height: H - 14 - 50 };
  const lo = Math.min(0, ...dr), hi = Math.max(0, ...dr), pad = (hi - lo) * 0.08 || 0.01;
  const x = scale(-180, 180, box.left, box.left + box.width);
  const y = scale(lo - pad, hi + pad, box.top + box.height, box.top);
  return h('figure', { class: 'plot' },
    svg('svg', {
      id: 'pt-free-shape', class: 'chart', viewBox: `0 0 ${W} ${H}`, role: 'img',
      'aria-label': `Free shape: running-face radius less d/2 from ${sig(Math.min(...dr), 3)} to ${sig(Math.max(...dr), 3)} mm, ${k} points; free gap ${mm(f.free_gap_m)} mm.`,
    },
    axes({
      box, x, y, xTicks: [-180, -90, 0, 90, 180], yTicks: ticks(lo - pad, hi + pad, 4),
      xLabel: 'angle from the point opposite the gap (deg)', yLabel: 'r − d/2 (mm)', yFormat: (v) => String(Number(v.toPrecision(4))),
    }),
    svg('line', { class: 'zero', x1: box.left, x2: box.left + box.width, y1: y(0), y2: y(0) }),
    svg('path', { class: 'free', id: 'pt-free-radius', 'data-points': k, d: pathD(t.slice(0, k).map((a, i) => [x(a), y(dr[i])])) }),
    meas.length ? svg('g', { id: 'pt-free-measured', class: 'measured', 'data-points': meas.length },
      ...meas.map(([a, v]) => svg('circle', { cx: x(a), cy: y(v), r: 2 }))) : null),
    h('figcaption', {}, `The free shape as a gauge measures it: the running face's radius about the closed ring's centre less the bore's d/2, against the angle from the point opposite the gap; the free gap between its tips is ${mm(f.free_gap_m, 3)} mm.`
      + (meas.length ? ` Dots: the measured points (ring.free_shape) placed as fitted; the line is the fitted ring's free shape.` : '')));
}

// The free and the closed shape in the ring plane, x right, y up, one scale
// for both axes.  x_a is marked between the inner gap corners, which lie
// half a radial width inside the first and last centroid points.
function shapePlot(result) {
  const s = result.shape || {};
  const X = nums(s.x), Y = nums(s.y), RX = nums(s.reference_x), RY = nums(s.reference_y);
  const k = Math.min(X.length, Y.length), kr = Math.min(RX.length, RY.length);
  if (k < 2) return h('p', { class: 'hint', id: 'pt-shape-missing' }, 'This result has no free shape to draw.');
  const free = X.slice(0, k).map((x, i) => [x, Y[i]]);
  const ref = RX.slice(0, kr).map((x, i) => [x, RY[i]]);
  const all = free.concat(ref).filter(([x, y]) => isNum(x) && isNum(y));
  const xs = all.map((p) => p[0]), ys = all.map((p) => p[1]);
  const x0 = Math.min(...xs), x1 = Math.max(...xs), y0 = Math.min(...ys), y1 = Math.max(...ys);
  const W = 420, H = 420, pad = 30, top = 36;
  const span = Math.max(x1 - x0, y1 - y0) || 1;
  const cxData = (x0 + x1) / 2, cyData = (y0 + y1) / 2;
  const cx = W / 2, cy = top + (H - top - pad) / 2;
  const k2 = Math.min(W - 2 * pad, H - top - pad) / span; // px per m, both axes
  const X_ = (x) => cx + (x - cxData) * k2;
  const Y_ = (y) => cy - (y - cyData) * k2;
  const screen = (pts) => pts.map(([x, y]) => [X_(x), Y_(y)]);

  // Ring centre: the middle of the reference (closed) shape.
  const rxs = ref.length ? ref.map((p) => p[0]) : xs, rys = ref.length ? ref.map((p) => p[1]) : ys;
  const c = [(Math.min(...rxs) + Math.max(...rxs)) / 2, (Math.min(...rys) + Math.max(...rys)) / 2];
  const b = Number(result.scene?.ring?.radial_width) || 0;
  const inner = ([x, y]) => {
    const dx = x - c[0], dy = y - c[1], r = Math.hypot(dx, dy) || 1;
    return [x - (b / 2) * (dx / r), y - (b / 2) * (dy / r)];
  };
  const [qa, qb] = screen([inner(free[0]), inner(free[k - 1])]);
  const xa = result.gap_opening_inner;
  const label = `x_a = ${mm(xa)} mm`;
  const lx = Math.min(qa[0], qb[0]) - 10, ly = (qa[1] + qb[1]) / 2;

  const dim = svg('g', { class: 'gap-mark', id: 'pt-gap' },
    svg('title', {}, `Gap opening between the inner corners: ${mm(xa, 3)} mm`),
    svg('path', { class: 'dimension', d: pathD([qa, qb]) }),
    svg('circle', { class: 'corner', cx: qa[0], cy: qa[1], r: 3 }),
    svg('circle', { class: 'corner', cx: qb[0], cy: qb[1], r: 3 }),
    svg('text', { id: 'pt-gap-label', class: 'gap-label halo', x: lx, y: ly, 'text-anchor': 'end', 'dominant-baseline': 'middle' }, label));
  const [gx, gy] = [X_(Math.max(...xs)) + 4, Y_(c[1])];
  return svg('svg', {
    id: 'pt-shape', class: 'chart ring-plane', viewBox: `0 0 ${W} ${H}`, role: 'img',
    'aria-label': `Free shape of the ring in its plane: ${k} points; gap opening x_a ${mm(xa)} mm at the right.`,
  },
  legend([
    [svg('path', { class: 'reference', d: 'M-2,0H12' }), 'closed (reference)'],
    [svg('path', { class: 'free', d: 'M-2,0H12' }), 'free shape'],
  ], { x: 12, y: 14 }),
  svg('path', { class: 'crosshair', d: `M${X_(c[0]) - 6},${Y_(c[1])}H${X_(c[0]) + 6}M${X_(c[0])},${Y_(c[1]) - 6}V${Y_(c[1]) + 6}` }),
  svg('path', { class: 'reference', id: 'pt-reference', d: pathD(screen(ref)) }),
  svg('path', { class: 'free', id: 'pt-free', d: pathD(screen(free)) }),
  dim,
  svg('text', { class: 'tick', x: Math.min(gx, W - 2), y: gy, 'text-anchor': 'end', 'dominant-baseline': 'middle', transform: `rotate(-90 ${Math.min(gx, W - 2)} ${gy})` }, 'gap 0°'));
}

// Axial displacement z (µm) of the centroid line against the angle from the gap.
function zPlot(result) {
  const s = result.shape || {};
  const z = nums(s.z), a = nums(s.angle_deg);
  const k = Math.min(z.length, a.length);
  const W = 420, H = 240;
  const box = { left: 62, top: 14, width: W - 62 - 12, height: H - 14 - 50 };
  const zs = z.slice(0, k).map((v) => v * 1e6);
  const lo = Math.min(0, ...zs), hi = Math.max(0, ...zs);
  const pad = (hi - lo) * 0.08 || 1;
  const x = scale(0, 360, box.left, box.left + box.width);
  const y = scale(lo - pad, hi + pad, box.top + box.height, box.top);
  return svg('svg', {
    id: 'pt-z-plot', class: 'chart', viewBox: `0 0 ${W} ${H}`, role: 'img',
    'aria-label': `Axial displacement against angle from the gap, ${sig(Math.min(...zs))} to ${sig(Math.max(...zs))} µm; lateral opening x_c ${um(result.lateral_opening, 1)} µm.`,
  },
  axes({
    box, x, y, xTicks: [0, 90, 180, 270, 360], yTicks: ticks(lo - pad, hi + pad, 4),
    xLabel: 'angle from the gap (deg)', yLabel: 'z (µm)', yFormat: (v) => String(Number(v.toPrecision(4))),
  }),
  svg('line', { class: 'zero', x1: box.left, x2: box.left + box.width, y1: y(0), y2: y(0) }),
  svg('path', { class: 'free', 'data-name': 'free shape', d: pathD(a.slice(0, k).map((ang, i) => [x(ang), y(zs[i])])) }));
}

// The cross-section the beam's properties come from (section.outline_m:
// [radial from its inner edge, axial from its bottom], m), true scale, the
// running face to the right and the combustion side up; its centroid and
// the in-plane principal axis (section.principal_angle_deg from the radial
// axis toward +z).  Nothing without an outline.
function sectionPlot(result) {
  const sec = result.section || {};
  const pts = (Array.isArray(sec.outline_m) ? sec.outline_m : [])
    .filter((p) => Array.isArray(p) && isNum(p[0]) && isNum(p[1]));
  if (pts.length < 3) return null;
  const us = pts.map((p) => p[0]), vs = pts.map((p) => p[1]);
  const u0 = Math.min(...us), u1 = Math.max(...us), v0 = Math.min(...vs), v1 = Math.max(...vs);
  const W = 420, H = 260, pad = 40;
  const k = Math.min((W - 2 * pad) / ((u1 - u0) || 1), (H - 2 * pad) / ((v1 - v0) || 1));
  const X = (u) => W / 2 + (u - (u0 + u1) / 2) * k, Y = (v) => H / 2 - (v - (v0 + v1) / 2) * k;
  const D = Number(result.scene?.ring?.diameter), b = u1 - u0;
  const c = Array.isArray(sec.centroid_m) ? sec.centroid_m : [];
  // the centroid's radius counts from the ring's axis: the inner edge is at D/2 - b
  const cu = isNum(c[0]) && isNum(D) ? c[0] - (D / 2 - b) : NaN, cv = c[1];
  const parts = [svg('path', { class: 'section-outline', id: 'pt-section-outline', 'data-points': pts.length, d: pathD(pts.map(([u, v]) => [X(u), Y(v)]), true) })];
  if (isNum(cu) && isNum(cv)) {
    const a = ((Number(sec.principal_angle_deg) || 0) * Math.PI) / 180, L = 0.45 * Math.max(u1 - u0, v1 - v0) * k;
    const x = X(cu), y = Y(cv);
    parts.push(svg('path', { class: 'dimension', id: 'pt-section-axis', d: pathD([[x - L * Math.cos(a), y + L * Math.sin(a)], [x + L * Math.cos(a), y - L * Math.sin(a)]]) }),
      svg('circle', { class: 'corner', id: 'pt-section-centroid', cx: x, cy: y, r: 3.5 }, svg('title', {}, `Centroid: ${mm(c[0], 3)} mm from the ring's axis, ${mm(cv, 3)} mm above the bottom`)));
  }
  parts.push(svg('text', { class: 'tick', x: W - 4, y: H / 2, 'text-anchor': 'end', 'dominant-baseline': 'middle' }, 'face'),
    svg('text', { class: 'tick', x: W / 2, y: 14, 'text-anchor': 'middle' }, 'top (combustion side)'));
  const shape = sec.shape === 'general' ? (result.scene?.ring?.section?.shape || 'general').replace(/_/g, ' ') : (sec.shape || 'section');
  return h('figure', { class: 'plot' },
    svg('svg', { id: 'pt-section', class: 'chart', viewBox: `0 0 ${W} ${H}`, role: 'img', 'aria-label': `The ${shape} cross-section, ${pts.length} outline points, true scale.` }, ...parts),
    h('figcaption', {}, `The cross-section (${shape}, ${mm(b, 2)} × ${mm(v1 - v0, 2)} mm, true scale), the running face to the right, the combustion side up: `
      + `the dot is its centroid, the line its in-plane principal axis at ${isNum(sec.principal_angle_deg) ? sig(sec.principal_angle_deg, 3) : '—'}° from the radial direction.`));
}
