// The lift analysis: renders a lift `result` (API.md) as the ring lift in its
// groove against crank angle (mean over the segments, the band between the
// lowest and highest segment, both flanks, the flank band where the events
// are dated, the flank events), a strip of the flank state, the friction
// force when friction is modelled, and tables of the events and the solver's
// cost.  A lubricated run's `lubrication` adds the minimum film thickness and
// the friction split (film shear, asperities, total) against crank angle, the
// friction work and FMEP of each cycle, and what the film model covers.
// A pure function of the result: optional fields may be missing.
//
// setup() is called once the shipped examples are known: the gas pressure
// tables of the scene come from one of them.

import { svg, scale, ticks, axes, pathD, stepTicks, legend } from './svg.js';
import { h, fill, isNum, fixed, sig, seconds, percent, kvTable, resultLinks, nums, um, deg } from './html.js';
import { W, BOX, isLube, thin, thinnest, filmPlot, filmCaption, lubeFrictionPlot, FRICTION_CAPTION, filmFactRows } from './lube.js';
import { boreMapFigure } from './boremap.js';

const GAS_EXAMPLE = 'thesis_lift_gas_6000rpm';
const EVENT_TEXT = {
  leave_lower: 'leaves the lower flank',
  reach_upper: 'reaches the upper flank',
  leave_upper: 'leaves the upper flank',
  reach_lower: 'reaches the lower flank',
};
const FLANK_TEXT = { lower: 'on the lower flank', upper: 'on the upper flank', free: 'free (between the flanks)' };
const EVENTS_SHOWN = 500; // rows of the event table
const CRANK_STEPS = [90, 180, 360, 720, 1440, 3600, 7200, 14400];
// The lubrication block's arrays with one value per output sample.
const LUBE_SAMPLES = ['min_film_m', 'hydrodynamic_friction_n', 'asperity_friction_n', 'friction_power_w', 'asperity_share', 'regime'];
const REGIME_TEXT = { hydrodynamic: 'hydrodynamic', mixed: 'mixed', boundary: 'boundary' };


export const lift = {
  id: 'lift',
  label: 'Lift',
  runLabel: 'Run lift analysis',

  // Offers the gas tables of the shipped examples that have them; without
  // any, the gas toggle is disabled and says why.
  setup({ form, examples, error }) {
    const withGas = (examples || []).filter((ex) => {
      const g = ex.scene?.physics?.gas;
      return g && Array.isArray(g.crank_deg) && g.crank_deg.length > 1;
    });
    const options = withGas.map((ex) => {
      const { active_area: _, ...tables } = ex.scene.physics.gas;
      return { value: ex.name, label: ex.name, title: ex.scene.name || ex.description, data: tables };
    });
    form.setSource('/physics/gas', options, GAS_EXAMPLE);
    const note = document.getElementById('f-lf-gas-note');
    if (!note) return;
    if (error) {
      note.textContent = `Unavailable: the gas pressure tables come from the shipped examples, which could not be loaded (${error.message}).`;
    } else if (!options.length) {
      note.textContent = `Unavailable: the gas pressure tables come from a shipped example (${GAS_EXAMPLE}), and this server has none with gas tables.`;
    } else {
      note.textContent = `Pressure tables (above, behind and below the ring against crank angle) from a shipped example${withGas.some((ex) => ex.name === GAS_EXAMPLE) ? '' : ` (${GAS_EXAMPLE} is missing; others have tables)`}.`;
    }
  },

  render(result, job, container) {
    const n = result.numerics || {};
    const crank = nums(result.crank_deg);
    const events = Array.isArray(result.events) ? result.events : [];
    const engine = result.scene?.engine || {};
    const title = [
      isNum(engine.cycles) ? `${sig(engine.cycles)} cycle${engine.cycles === 1 ? '' : 's'}` : null,
      isNum(engine.speed_rpm) ? `${sig(engine.speed_rpm, 5)} rpm` : null,
    ].filter(Boolean).join(' at ');
    const plots = h('div', { id: 'lf-plots' }, figures({ ...result, events }));
    fill(container,
      h('h3', {}, `Lift — the ring in its groove${title ? `, ${title}` : ''}`),
      h('p', { id: 'lf-summary' }, summary(result, events)),
      lubeSummary(result.lubrication, crank),
      h('p', { id: 'cost', class: 'cost' }, h('strong', {}, 'Cost and accuracy: '), costLine(n)),
      resultLinks(job, 'lift', 'Lift table (CSV)'),
      zoomControl(crank, (range) => fill(plots, figures(sliceRun(result, events, range)))),
      plots,
      liftBoreMap(result.scene),
      lubeReadout(result.lubrication, result.scene?.physics?.friction?.supply, result.scene?.physics?.friction?.cavitation),
      h('div', { class: 'lift-tables' },
        h('div', {},
          h('div', { class: 'table-wrap events-wrap' }, eventTable(events)),
          events.length ? datingNote(result) : null),
        h('div', { class: 'table-wrap' }, costTable(result))),
    );
  },
};

// A bore map (bore.layers) with the ring's travel down it, TDC to BDC.
function liftBoreMap(scene) {
  const z = scene?.bore?.ring_z_tdc_m, r = scene?.engine?.crank_radius;
  const travel = isNum(z) && isNum(r) ? [z, z + 2 * r] : null;
  return boreMapFigure(scene, 'lf-map', { travel }, travel ? 'Dashed band: the ring\'s travel, from its depth at TDC down two crank radii to BDC; the ring met the bore at its current depth.' : '');
}

// The figures of a (possibly cut to one cycle) lift result.
function figures(result) {
  const crank = nums(result.crank_deg);
  const friction = result.scene?.physics?.friction;
  if (crank.length < 2) return h('p', { class: 'hint', id: 'lf-empty' }, 'This result has no samples to draw.');
  const gas = gasTables(result.scene?.physics?.gas);
  const b = bandDrawn(result) ? flankBand(result) : null;
  return [
    h('figure', { class: 'plot wide' }, liftPlot(result, result.events), flankStrip(result),
      h('figcaption', {}, 'Ring lift above the groove\'s lower flank against crank angle (0° = top dead centre before the power stroke). ' +
        'Line: mean over the segments; band: lowest to highest segment; markers: flank events (hover for the angle). ' +
        (b !== null ? `Strips at the flanks: the flank band (${bandText(b)} of the clearance); an event is dated where the mean line crosses a strip's edge, and its marker sits on the flank at that angle. ` : '') +
        'Bar: flank state.')),
    gas ? h('figure', { class: 'plot wide' }, gasPlot(result, gas),
      h('figcaption', {}, `Gas pressures that drove the ring (the scene's tables, repeated every 720°; ${result.scene.physics.gas.active_area || 'fixed'} active areas).`))
      : null,
    friction && typeof friction === 'object'
      ? h('figure', { class: 'plot wide' }, frictionPlot(result),
        h('figcaption', {}, `Axial bore friction force on the ring (${friction.model || 'friction'}${isNum(friction.coefficient) && friction.model !== 'lubricated' ? `, μ = ${friction.coefficient}` : ''}).`))
      : null,
    ...lubeFigures(result),
  ];
}

// A choice of the crank range drawn: the whole run or one 720° cycle of it
// (none for a run of one cycle or less).  onChange(null | [c0, c1]).
function zoomControl(crank, onChange) {
  if (crank.length < 2) return null;
  const c0 = Math.min(...crank), c1 = Math.max(...crank);
  const first = Math.floor(c0 / 720 + 1e-9);
  const count = Math.ceil(c1 / 720 - 1e-9) - first;
  if (count < 2) return null;
  const select = h('select', { id: 'lf-zoom' },
    h('option', { value: '' }, `the whole run (${sig(c0, 5)}–${sig(c1, 5)}°)`),
    Array.from({ length: count }, (_, i) => {
      const a = Math.max(c0, (first + i) * 720), b = Math.min(c1, (first + i + 1) * 720);
      return h('option', { value: `${a},${b}` }, `cycle ${first + i + 1} (${sig(a, 5)}–${sig(b, 5)}°)${b - a < 720 - 1e-6 ? ', part' : ''}`);
    }));
  select.addEventListener('change', () => onChange(select.value ? select.value.split(',').map(Number) : null));
  return h('p', { class: 'lift-controls' }, h('label', { for: 'lf-zoom' }, 'Show'), select);
}

// The samples and events of `result` within [c0, c1] (all for range null).
function sliceRun(result, events, range) {
  if (!range) return { ...result, events };
  const [c0, c1] = range;
  const crank = nums(result.crank_deg);
  const keep = crank.map((c, i) => (c >= c0 - 1e-9 && c <= c1 + 1e-9 ? i : -1)).filter((i) => i >= 0);
  const cut = (a) => (Array.isArray(a) ? keep.map((i) => a[i]) : a);
  const out = { ...result, events: events.filter((e) => e.crank_deg >= c0 && e.crank_deg <= c1) };
  for (const k of ['crank_deg', 'lift', 'lift_min', 'lift_max', 'flank', 'friction_force']) out[k] = cut(result[k]);
  const lub = result.lubrication;
  if (lub && typeof lub === 'object') {
    out.lubrication = { ...lub };
    for (const k of LUBE_SAMPLES) out.lubrication[k] = cut(lub[k]);
  }
  return out;
}

// The gas tables of a scene ({crank_deg, above, behind, below}) when usable.
function gasTables(gas) {
  if (!gas || typeof gas !== 'object') return null;
  const x = nums(gas.crank_deg);
  if (x.length < 2) return null;
  const t = { crank_deg: x };
  for (const k of ['above', 'behind', 'below']) {
    t[k] = nums(gas[k]);
    if (t[k].length !== x.length) return null;
  }
  return t;
}

// A table's pressure at crank angle c: linear between the points, repeated
// every 720°, from the last point back to the first across 720 (as the
// solver reads it, core/rd_lift.c gas_at).
function gasAt(x, v, c) {
  const n = x.length;
  const d = ((c % 720) + 720) % 720;
  if (d < x[0] || d >= x[n - 1]) {
    const lo = x[n - 1], hi = x[0] + 720, e = d < x[0] ? d + 720 : d;
    return hi - lo <= 0 ? v[0] : v[n - 1] + ((v[0] - v[n - 1]) * (e - lo)) / (hi - lo);
  }
  let i = 0;
  while (x[i + 1] <= d) i++;
  return v[i] + ((v[i + 1] - v[i]) * (d - x[i])) / (x[i + 1] - x[i]);
}

// The table's points within [c0, c1] (every cycle), with both ends.
function gasSeries(t, key, c0, c1) {
  const pts = [[c0, gasAt(t.crank_deg, t[key], c0)]];
  for (let k = Math.floor(c0 / 720); k * 720 <= c1; k++) {
    t.crank_deg.forEach((x, i) => {
      const c = k * 720 + x;
      if (c > c0 && c < c1) pts.push([c, t[key][i]]);
    });
  }
  pts.push([c1, gasAt(t.crank_deg, t[key], c1)]);
  return pts;
}

const GAS_TEXT = { above: 'above the ring', behind: 'behind the ring', below: 'below the ring' };

function gasPlot(result, t) {
  const H = 240;
  const box = { ...BOX, top: 34, height: H - 34 - 50 };
  const crank = nums(result.crank_deg);
  const { x, c0, c1, ticks: xTicks } = crankAxis(crank);
  const series = Object.keys(GAS_TEXT).map((k) => [k, gasSeries(t, k, c0, c1).map(([c, p]) => [c, p / 1e5])]);
  const top = Math.max(1e-3, ...series.flatMap(([, pts]) => pts.map((q) => q[1])));
  const y = scale(0, top * 1.08, box.top + box.height, box.top);
  return svg('svg', {
    id: 'lf-gas', class: 'chart', viewBox: `0 0 ${W} ${H}`, role: 'img',
    'aria-label': `Gas pressures against crank angle, up to ${sig(top)} bar: ${series.map(([k, pts]) => `${GAS_TEXT[k]} ${sig(Math.min(...pts.map((q) => q[1])))} to ${sig(Math.max(...pts.map((q) => q[1])))} bar`).join('; ')}.`,
  },
  legend(series.map(([k]) => [svg('path', { class: `gas-${k}`, d: 'M-2,0H12' }), GAS_TEXT[k]]), { x: box.left, y: 14 }),
  axes({
    box, x, y, xTicks, yTicks: ticks(0, top * 1.08, 4),
    xLabel: 'crank angle (deg)', yLabel: 'pressure (bar)', yFormat: (v) => String(Number(v.toPrecision(4))),
  }),
  series.map(([k, pts]) => svg('path', { class: `gas-${k}`, id: `lf-gas-${k}`, 'data-name': GAS_TEXT[k], 'data-points': pts.length, d: pathD(pts.map(([c, p]) => [x(c), y(p)])) })));
}

function summary(result, events) {
  const lmax = nums(result.lift_max).length ? nums(result.lift_max) : nums(result.lift);
  const flank = Array.isArray(result.flank) ? result.flank : [];
  const clearance = result.scene?.groove?.axial_clearance;
  const parts = [];
  if (lmax.length) parts.push(`Largest lift ${um(Math.max(...lmax))} µm${isNum(clearance) ? ` of ${um(clearance)} µm clearance` : ''}`);
  if (flank.length) {
    const share = (s) => `${((flank.filter((f) => f === s).length / flank.length) * 100).toFixed(0)} %`;
    parts.push(`samples on the lower flank ${share('lower')}, upper ${share('upper')}, free ${share('free')}`);
  }
  parts.push(`${events.length} flank event${events.length === 1 ? '' : 's'}`);
  return `${parts.join('; ')}.`;
}

function costLine(n) {
  const parts = [];
  if (n.model && n.model.name) parts.push(`${n.model.name} model`);
  if (n.segments !== undefined) parts.push(`${n.segments} segments`);
  if (n.dof !== undefined) parts.push(`${n.dof} DOF`);
  if (n.steps !== undefined) parts.push(`${n.steps} steps`);
  if (n.rhs_evals !== undefined) parts.push(`${n.rhs_evals} RHS evaluations`);
  parts.push(`wall time ${seconds(n.wall_s)}`);
  parts.push(isNum(n.error_estimate) ? `estimated error ${percent(n.error_estimate)}` : 'error not estimated');
  return parts.join(' · ');
}

function crankAxis(crank) {
  const c0 = Math.min(...crank), c1 = Math.max(...crank);
  const x = scale(c0, c1, BOX.left, BOX.left + BOX.width);
  return { x, c0, c1, ticks: stepTicks(c0, c1, CRANK_STEPS, 12) };
}

// The band at each flank where the flank changes are dated (the result's
// numerics.flank_band, a fraction of the axial clearance); null when the
// result has none or it is 0 (dated at the flank itself).
function flankBand(result) {
  const b = result.numerics?.flank_band;
  return isNum(b) && b > 0 ? b : null;
}

// Whether the lift plot draws the band: it needs the clearance too.
const bandDrawn = (result) => flankBand(result) !== null && isNum(result.scene?.groove?.axial_clearance);

// A band's fraction of the clearance as a percentage: 0.01 -> "1 %".
const bandText = (b) => `${sig(b * 100)} %`;

// An event marker: circle at the lower flank, square at the upper; filled
// when the ring arrives, open when it leaves.
function eventMarker(kind, px, py) {
  const upper = kind === 'reach_upper' || kind === 'leave_upper';
  const cls = `ev-mk ${upper ? 'ev-upper' : 'ev-lower'} ${kind.startsWith('reach') ? 'ev-reach' : 'ev-leave'}`;
  return upper
    ? svg('rect', { class: cls, x: px - 4.5, y: py - 4.5, width: 9, height: 9 })
    : svg('circle', { class: cls, cx: px, cy: py, r: 5 });
}

function liftPlot(result, events) {
  const H = 320;
  const box = { ...BOX, top: 34, height: H - 34 - 50 };
  const crank = nums(result.crank_deg);
  const N = crank.length;
  const mean = nums(result.lift).slice(0, N).map((v) => v * 1e6);
  const lo = nums(result.lift_min).slice(0, N).map((v) => v * 1e6);
  const hi = nums(result.lift_max).slice(0, N).map((v) => v * 1e6);
  const clearance = Number(result.scene?.groove?.axial_clearance);
  const cl = isNum(clearance) ? clearance * 1e6 : null;
  const values = [...mean, ...lo, ...hi].filter(isNum);
  const y0 = Math.min(0, ...values), y1 = Math.max(cl ?? 0, ...values, 1e-3);
  const pad = (y1 - y0) * 0.08;
  const { x, ticks: xTicks } = crankAxis(crank);
  const y = scale(y0 - pad, y1 + pad, box.top + box.height, box.top);

  // The flank band: a strip from each flank to the band's edge, b c_a into
  // the groove, with the edge dashed (the mean lift's crossing dates an event).
  const b = bandDrawn(result) ? flankBand(result) : null;
  const bandStrip = (side, from, edge) => svg('g', { class: 'flank-band-strip', id: `lf-flank-band-${side}` },
    svg('rect', {
      class: 'flank-band', 'data-side': side, 'data-edge-um': edge,
      x: box.left, width: box.width, y: Math.min(y(from), y(edge)), height: Math.abs(y(from) - y(edge)),
    }),
    svg('line', { class: 'flank-band-edge', x1: box.left, x2: box.left + box.width, y1: y(edge), y2: y(edge) }));
  const flankBands = b !== null
    ? [bandStrip('lower', 0, b * cl), bandStrip('upper', cl, cl - b * cl)]
    : [];

  const band = lo.length === N && hi.length === N
    ? svg('path', {
      class: 'band', id: 'lf-band',
      d: pathD([...thin(crank, hi).map(([c, v]) => [x(c), y(v)]), ...thin(crank, lo).reverse().map(([c, v]) => [x(c), y(v)])], true),
    })
    : null;
  // The label above the lower line, below the upper one (clear of the legend).
  const flankLine = (id, v, text, below = false) => svg('g', { class: 'flank-line', id },
    svg('line', { x1: box.left, x2: box.left + box.width, y1: y(v), y2: y(v) }),
    svg('text', { class: 'tick halo', x: box.left + box.width - 4, y: below ? y(v) + 4 : y(v) - 5, dy: below ? '0.8em' : null, 'text-anchor': 'end' }, text));
  const atFlank = (kind) => (kind === 'reach_upper' || kind === 'leave_upper' ? cl ?? y1 : 0);
  const markers = events.map((e, i) => {
    const kind = String(e.event);
    const touch = isNum(e.touch_deg) && Math.abs(e.touch_deg - e.crank_deg) > 1e-9
      ? ` (${kind.startsWith('leave') ? 'left' : 'touched'} the flank itself at ${deg(e.touch_deg)})` : '';
    const g = svg('g', { class: 'event', 'data-event': kind, 'data-index': i },
      svg('title', {}, `${EVENT_TEXT[kind] || kind} at ${deg(e.crank_deg)} crank${touch}`),
      eventMarker(kind, x(e.crank_deg), y(atFlank(kind))));
    return g;
  });
  return svg('svg', {
    id: 'lf-lift', class: 'chart', viewBox: `0 0 ${W} ${H}`, role: 'img',
    'aria-label': `Ring lift against crank angle, ${N} samples, ${um(Math.min(...values) / 1e6)} to ${um(Math.max(...values) / 1e6)} µm; ${events.length} flank events${b !== null ? `; flank band ${bandText(b)} of the clearance at each flank` : ''}.`,
  },
  legend([
    [svg('path', { class: 'mean', d: 'M-2,0H12' }), 'mean lift'],
    [svg('rect', { class: 'band', x: -2, y: -5, width: 14, height: 10 }), 'segment range'],
    [eventMarker('reach_lower', 5, 0), 'reach'],
    [eventMarker('leave_lower', 5, 0), 'leave (circle: lower, square: upper)'],
    b !== null ? [svg('rect', { class: 'flank-band', x: -2, y: -5, width: 14, height: 10 }), `flank band (${bandText(b)} of the clearance)`] : null,
  ].filter(Boolean), { x: box.left, y: 14 }),
  axes({
    box, x, y, xTicks, yTicks: ticks(y0 - pad, y1 + pad, 5),
    xLabel: 'crank angle (deg)', yLabel: 'lift (µm)', yFormat: (v) => String(Number(v.toPrecision(4))),
  }),
  band,
  flankBands,
  flankLine('lf-lower', 0, 'lower flank'),
  cl !== null ? flankLine('lf-upper', cl, `upper flank (clearance ${um(clearance)} µm)`, true) : null,
  mean.length === N ? svg('path', { class: 'mean', id: 'lf-mean', 'data-name': 'mean lift', d: pathD(thin(crank, mean).map(([c, v]) => [x(c), y(v)])) }) : null,
  svg('g', { class: 'events' }, markers));
}

// The flank state along the crank axis: one bar per run of equal states.
function flankStrip(result) {
  const crank = nums(result.crank_deg);
  const flank = Array.isArray(result.flank) ? result.flank : [];
  const N = Math.min(crank.length, flank.length);
  if (N < 2) return null;
  const H = 58, top = 6, height = 16;
  const { x } = crankAxis(crank);
  const runs = [];
  for (let i = 0; i < N; i++) {
    const last = runs[runs.length - 1];
    if (last && last.state === flank[i]) last.end = i;
    else runs.push({ state: flank[i], start: i, end: i });
  }
  // Each run reaches to the middle between its last sample and the next run's first.
  const edge = (i) => (i <= 0 ? crank[0] : i >= N ? crank[N - 1] : (crank[i - 1] + crank[i]) / 2);
  const bars = runs.map((r) => svg('rect', {
    class: `flank-run flank-${r.state}`, 'data-flank': r.state,
    x: x(edge(r.start)), y: top, width: Math.max(0.5, x(edge(r.end + 1)) - x(edge(r.start))), height,
  }, svg('title', {}, `${FLANK_TEXT[r.state] || r.state}: ${deg(crank[r.start])} to ${deg(crank[r.end])}`)));
  const swatch = (state) => svg('rect', { class: `flank-run flank-${state}`, x: -2, y: -5, width: 14, height: 10 });
  const count = (s) => runs.filter((r) => r.state === s).length;
  return svg('svg', {
    id: 'lf-flank', class: 'chart strip', viewBox: `0 0 ${W} ${H}`, role: 'img',
    'aria-label': `Flank state along the crank axis: ${runs.length} stretches (${count('lower')} on the lower flank, ${count('upper')} on the upper, ${count('free')} free).`,
  },
  svg('text', { class: 'tick', x: BOX.left - 6, y: top + height / 2, 'text-anchor': 'end', 'dominant-baseline': 'middle' }, 'flank'),
  svg('g', { class: 'flank-runs' }, bars),
  legend([[swatch('lower'), 'lower'], [swatch('upper'), 'upper'], [swatch('free'), 'free']], { x: BOX.left, y: top + height + 20, wrap: 'down' }));
}

function frictionPlot(result) {
  const H = 220;
  const box = { ...BOX, top: 14, height: H - 14 - 50 };
  const crank = nums(result.crank_deg);
  const f = nums(result.friction_force).slice(0, crank.length);
  const vals = f.filter(isNum);
  const f0 = Math.min(0, ...vals), f1 = Math.max(0, ...vals);
  const pad = (f1 - f0) * 0.08 || 1;
  const { x, ticks: xTicks } = crankAxis(crank);
  const y = scale(f0 - pad, f1 + pad, box.top + box.height, box.top);
  return svg('svg', {
    id: 'lf-friction', class: 'chart', viewBox: `0 0 ${W} ${H}`, role: 'img',
    'aria-label': `Friction force against crank angle, ${sig(f0)} to ${sig(f1)} N.`,
  },
  axes({
    box, x, y, xTicks, yTicks: ticks(f0 - pad, f1 + pad, 4),
    xLabel: 'crank angle (deg)', yLabel: 'friction (N)', yFormat: (v) => String(Number(v.toPrecision(4))),
  }),
  svg('line', { class: 'zero', x1: box.left, x2: box.left + box.width, y1: y(0), y2: y(0) }),
  f.length === crank.length ? svg('path', { class: 'friction', id: 'lf-friction-line', 'data-name': 'friction', d: pathD(thin(crank, f).map(([c, v]) => [x(c), y(v)])) }) : null);
}

// ---- the oil film of a lubricated run (result.lubrication) ------------------

// The thinnest film and the FMEP in one line under the summary.
function lubeSummary(lub, crank) {
  if (!isLube(lub)) return null;
  const parts = [];
  const least = thinnest(lub, crank);
  const at = Array.isArray(lub.min_film_angle_deg) ? lub.min_film_angle_deg[least?.i] : undefined;
  if (least) parts.push(`thinnest oil film ${um(least.m, 3)} µm at ${deg(crank[least.i])}${isNum(at) ? `, on the segment ${deg(at)} from the gap middle` : ''}`);
  const fmep = nums(lub.fmep_pa);
  if (fmep.length) parts.push(`FMEP ${fmep.map((p) => sig(p / 1e3)).join(', ')} kPa (${fmep.length === 1 ? 'the cycle' : 'per cycle'})`);
  else if (Array.isArray(lub.fmep_pa)) parts.push('no whole cycle, so no FMEP');
  return parts.length ? h('p', { id: 'lf-lube-summary' }, `Lubricated: ${parts.join('; ')}.`) : null;
}

// The two plots of the film: its minimum thickness and the friction split
// (none without a lubrication block).
function lubeFigures(result) {
  const lub = result.lubrication;
  if (!isLube(lub)) return [];
  const crank = nums(result.crank_deg);
  const film = nums(lub.min_film_m);
  const opts = { id: 'lf', axis: crankAxis(crank) };
  return [
    film.length === crank.length && crank.length > 1
      ? h('figure', { class: 'plot wide' }, filmPlot(crank, film, lub.composite_roughness_m, opts), h('figcaption', {}, filmCaption(lub)))
      : null,
    crank.length > 1
      ? h('figure', { class: 'plot wide' }, lubeFrictionPlot(crank, lub, opts), h('figcaption', {}, FRICTION_CAPTION))
      : null,
  ];
}

// Per cycle: friction work and FMEP; the film's facts; what the model is
// (shown as text, not a tooltip).
function lubeReadout(lub, supply, cavitation) {
  if (!isLube(lub)) return null;
  const work = nums(lub.friction_work_j), fmep = nums(lub.fmep_pa);
  const cycles = !Array.isArray(lub.friction_work_j) ? null : h('table', { class: 'data', id: 'lf-fmep' },
    h('caption', {}, work.length ? 'Friction of the ring per 720° cycle' : 'Friction per cycle: none (the run is shorter than one 720° cycle)'),
    h('thead', {}, h('tr', {},
      h('th', { scope: 'col', class: 'num' }, 'Cycle'),
      h('th', { scope: 'col', class: 'num' }, 'Friction work (J)'),
      h('th', { scope: 'col', class: 'num' }, 'FMEP (kPa)'))),
    h('tbody', {}, work.map((w, i) => h('tr', {},
      h('td', { class: 'num' }, String(i + 1)),
      h('td', { class: 'num work' }, sig(w, 4)),
      h('td', { class: 'num fmep' }, isNum(fmep[i]) ? sig(fmep[i] / 1e3, 4) : '—')))));
  const facts = kvTable({
    id: 'lf-lube-facts',
    caption: 'Oil film',
    rows: filmFactRows(lub, { supply, cavitation, id: 'lf' }),
  });
  return h('section', { class: 'lube-readout', id: 'lf-lube', 'aria-label': 'Oil film' },
    h('div', { class: 'lift-tables' }, h('div', { class: 'table-wrap' }, cycles), h('div', { class: 'table-wrap' }, facts)),
    typeof lub.method === 'string' && lub.method
      ? h('p', { class: 'method', id: 'lf-lube-method' }, h('strong', {}, 'Film model: '), lub.method)
      : null);
}

// The events, each with where the mean lift touched the flank itself (after
// a landing) or left it (before a leave): touch_deg, "—" when it never
// touched.  A result without touch_deg (older than the flank band) has no
// such column.
function eventTable(events) {
  const shown = events.slice(0, EVENTS_SHOWN);
  const touch = events.some((e) => e && typeof e === 'object' && 'touch_deg' in e);
  const rows = shown.map((e, i) => h('tr', { 'data-event': e.event },
    h('td', { class: 'num' }, String(i + 1)),
    h('td', { class: 'num' }, fixed(e.crank_deg, 2)),
    h('td', { class: 'num' }, isNum(e.crank_deg) ? (((e.crank_deg % 720) + 720) % 720).toFixed(2) : '—'),
    h('td', {}, EVENT_TEXT[e.event] || String(e.event)),
    touch ? h('td', { class: 'num touch' }, fixed(e.touch_deg, 2)) : null));
  return h('table', { class: 'data', id: 'lf-events' },
    h('caption', {}, events.length
      ? `Flank events${events.length > EVENTS_SHOWN ? ` (first ${EVENTS_SHOWN} of ${events.length}; all are in the raw result)` : ''}`
      : 'Flank events: none (the ring stays where it started)'),
    h('thead', {}, h('tr', {},
      h('th', { scope: 'col', class: 'num' }, '#'),
      h('th', { scope: 'col', class: 'num' }, 'Crank (deg)'),
      h('th', { scope: 'col', class: 'num' }, 'In cycle (deg)'),
      h('th', { scope: 'col' }, 'The ring…'),
      touch ? h('th', { scope: 'col', class: 'num', id: 'lf-touch-head' }, 'Touches / leaves the flank at (deg)') : null)),
    h('tbody', {}, rows));
}

// How the events are dated (numerics.flank_band); nothing for a result that
// does not say.
function datingNote(result) {
  const b = result.numerics?.flank_band;
  if (!isNum(b)) return null;
  const clearance = result.scene?.groove?.axial_clearance;
  const text = b > 0
    ? `Dated where the mean lift crosses the edge of a band of ${bandText(b)} of the axial clearance` +
      `${isNum(clearance) ? ` (${um(b * clearance, 3)} µm)` : ''} at the flank; ` +
      'the last column is where it touched or left the flank itself (—: it did not touch the flank).'
    : 'Dated where the mean lift touches the flank (landings) or the load turns away (leaves).';
  return h('p', { class: 'hint', id: 'lf-dating' }, text);
}

function costTable(result) {
  const n = result.numerics || {};
  return kvTable({
    id: 'lf-cost',
    caption: 'Accuracy and cost (CVODE)',
    rows: [
      ['Error estimate (lift)', percent(n.error_estimate), { id: 'lf-error' }],
      // what the estimate covers, as text beside it (not a tooltip): a time-only estimate says so
      ['What the estimate covers', n.error_method ?? undefined, { id: 'lf-error-scope' }],
      ['Event angle change in the check run', isNum(n.event_error_deg) ? `${sig(n.event_error_deg, 2)}°` : undefined],
      ['Ring model', n.model ? `${n.model.name} (${n.model.dof} DOF)` : undefined, { id: 'lf-model', title: n.model ? n.model.why : undefined }],
      ['Why this model', n.model ? n.model.why : undefined],
      ['Segments / DOF', `${n.segments ?? '—'} / ${n.dof ?? '—'}`],
      ['Steps', n.steps],
      ['RHS evaluations', n.rhs_evals],
      ['Jacobian evaluations', n.jac_evals],
      ['Error test failures', n.error_test_fails],
      ['Nonlinear iterations', n.nonlinear_iterations],
      ['Root function evaluations', n.root_evals],
      ['Wall time', seconds(n.wall_s)],
      ['Solver', n.solver],
    ].map((r) => (r[1] === undefined || r[1] === null ? [r[0], undefined] : [r[0], String(r[1]), r[2]])),
  });
}
