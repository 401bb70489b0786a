// The ring pack analysis: renders a ringpack `result` as the
// absolute gas pressures of every volume against crank angle (the cylinder
// first, the crankcase last), each ring's lift, the mass flow into the
// crankcase (the blow-by), the mass flow through every passage of the network
// with its net mass per cycle, and tables of each ring's model (name, DOF,
// why), the balance and the solver's cost.  Each ring's flank changes
// (rings[i].events) are marked on its lift curve, and with friction (any
// model) each ring's bore friction force is drawn.  With a flank band
// (numerics.flank_band > 0) each ring's lift is drawn over the band at its
// groove's flanks, in the ring's colour: where its flank changes are dated.
// With the lubricated
// friction model each ring's `lubrication` adds its readout (FMEP, friction
// work, the thinnest film and where, film_lag, the regime shares), its film
// and friction split against crank angle, and what the film model covers.
// A pure function of the result: optional fields may be missing.

import { svg, scale, ticks, axes, pathD, stepTicks, legend } from './svg.js';
import { h, fill, isNum, sig, seconds, kvTable, resultLinks, nums, um, deg } from './html.js';
import { isLube, thinnest, regimeText, filmPlot, lubeFrictionPlot, filmFactRows } from './lube.js';

const W = 720;
const BOX = { left: 64, width: W - 64 - 16 };
const COLORS = ['#b3261e', '#e07b00', '#6b7580', '#1f6feb', '#0b7d5a', '#7a3fb8', '#9a6700', '#333'];
const color = (i) => COLORS[i % COLORS.length];
// A ring's colour on every chart of the pack (its number n from 1).
const ringColor = (n) => color(n - 1);

export const ringpack = {
  id: 'ringpack',
  label: 'Ring pack',
  runLabel: 'Run ringpack analysis',

  // The page's shared Ring, Material and Segments fields on this tab: a pack
  // has no top-level ring (the server refuses one), so they are the top
  // ring's, /rings/0 (an engineer who types a closed gap there means the ring
  // the form shows; the other rings keep what the loaded scene gave); the
  // diameter is every ring's, as they share the bore.  A pack's rings are
  // split: the closed-ring box has no place ([]).
  fieldPaths(path, scene) {
    const n = Array.isArray(scene?.rings) && scene.rings.length ? scene.rings.length : 1;
    if (path === '/ring/diameter') return Array.from({ length: n }, (_, i) => `/rings/${i}/ring/diameter`);
    if (path.startsWith('/ring/')) return [`/rings/0${path}`];
    if (path === '/discretization/segments') return ['/rings/0/segments'];
    if (path.startsWith('/discretization/')) return [];
    return [path];
  },

  render(result, job, container) {
    const crank = nums(result.crank_deg);
    const volumes = Array.isArray(result.volumes) ? result.volumes : [];
    const rings = Array.isArray(result.rings) ? result.rings : [];
    const b = result.blowby || {};
    const rpm = result.scene?.engine?.speed_rpm;
    const figs = crank.length < 2 ? [h('p', { class: 'hint', id: 'rp-empty' }, 'This result has no samples to draw.')] : [
      h('figure', { class: 'plot wide' }, pressurePlot(crank, volumes),
        h('figcaption', {}, 'Absolute gas pressures of the last cycle against crank angle (0° = firing TDC): the cylinder (the input trace), the lands and grooves from the top down, the crankcase.')),
      h('figure', { class: 'plot wide' }, liftPlot(crank, rings, result), liftCaption(result, rings)),
      h('figure', { class: 'plot wide' }, blowbyPlot(crank, result),
        h('figcaption', {}, 'Mass flow into the crankcase (the blow-by; negative: back out of it).')),
      frictionFigure(crank, rings, result),
    ];
    fill(container,
      h('h3', {}, `Ring pack — ${rings.length} ring${rings.length === 1 ? '' : 's'}${isNum(rpm) ? ` at ${sig(rpm, 5)} rpm` : ''}`),
      h('p', { id: 'rp-summary' }, `Blow-by ${isNum(b.l_per_min) ? sig(b.l_per_min) : '—'} L/min (${isNum(b.kg_per_cycle) ? sig(b.kg_per_cycle) : '—'} kg per cycle, at 1.01325 bar and 20 °C); back into the cylinder ${isNum(b.reverse_kg_per_cycle) ? sig(b.reverse_kg_per_cycle) : '—'} kg per cycle; last cycle against the one before: ${isNum(result.periodicity) ? sig(result.periodicity, 2) : '—'}${periodicText(result)}.`),
      lubeSummary(crank, rings),
      resultLinks(job, 'ringpack', 'Ring pack table (CSV)'),
      h('div', { id: 'rp-plots' }, figs),
      crank.length < 2 ? null : flowSection(crank, rings, result),
      crank.length < 2 ? null : lubeSection(crank, rings, result),
      h('div', { class: 'table-wrap' }, modelTable(result)),
      h('div', { class: 'table-wrap' }, costTable(result)),
    );
  },
};

function crankAxis(crank) {
  const c0 = Math.min(...crank), c1 = Math.max(...crank);
  return { x: scale(c0, c1, BOX.left, BOX.left + BOX.width), ticks: stepTicks(c0, c1, [90, 180, 360, 720], 12) };
}

// One chart of several series [{label, values, color?, dash?, attrs?}]
// against crank angle (colour: the series' index in COLORS unless given;
// dash: a stroke-dasharray; attrs: more attributes of its path).
// extra: {legend: [[swatch, text]...] after the series', yMax: a value (in
// the series' units times factor) the axis reaches at least, under(x, y,
// box) / over(x, y, box): elements drawn beneath / above the series}.
function chart(id, crank, series, yLabel, factor, label, extra = {}) {
  const H = 260;
  const box = { ...BOX, top: 40, height: H - 40 - 50 };
  const { x, ticks: xTicks } = crankAxis(crank);
  const all = series.flatMap((s) => s.values.map((v) => v * factor));
  const lo = Math.min(0, ...all), hi = Math.max(1e-12, ...all, extra.yMax ?? -Infinity);
  const pad = (hi - lo) * 0.06 || 1;
  const y = scale(lo, hi + pad, box.top + box.height, box.top);
  return svg('svg', { id, class: 'chart', viewBox: `0 0 ${W} ${H}`, role: 'img', 'aria-label': label },
    legend([
      ...series.map((s, i) => [svg('path', { d: 'M-2,0H12', style: lineStyle(s, i, 2) }), s.label]),
      ...(extra.legend || []),
    ], { x: box.left, y: 14 }),
    axes({ box, x, y, xTicks, yTicks: ticks(lo, hi + pad, 4), xLabel: 'crank angle (deg)', yLabel, yFormat: (v) => String(Number(v.toPrecision(4))) }),
    extra.under ? extra.under(x, y, box) : null,
    series.map((s, i) => svg('path', {
      id: `${id}-${i}`, 'data-name': s.label, 'data-points': s.values.length, style: `fill:none;${lineStyle(s, i, 1.6)}`,
      d: pathD(s.values.map((v, k) => [x(crank[k]), y(v * factor)])), ...s.attrs,
    })),
    extra.over ? extra.over(x, y, box) : null);
}

const lineStyle = (s, i, width) => `stroke:${s.color ?? color(i)};stroke-width:${width}${s.dash ? `;stroke-dasharray:${s.dash}` : ''}`;

function pressurePlot(crank, volumes) {
  const series = volumes.map((v) => ({ label: v.name, values: nums(v.pressure_pa) })).filter((s) => s.values.length === crank.length);
  const peak = (s) => Math.max(...s.values) / 1e5;
  return chart('rp-pressure', crank, series, 'pressure (bar, absolute)', 1e-5,
    `Gas pressures against crank angle: ${series.map((s) => `${s.label} peak ${sig(peak(s))} bar`).join('; ')}.`);
}

// The flank band of the result (numerics.flank_band, else the scene's
// output.flank_band), a fraction of each groove's axial clearance; null when
// absent or 0 (flank changes dated at the flank itself).
function flankBand(result) {
  const b = result.numerics?.flank_band ?? result.scene?.output?.flank_band;
  return isNum(b) && b > 0 ? b : null;
}

const bandText = (b) => `${sig(b * 100)} %`;

// ---- flank changes (rings[i].events) ----------------------------------------

const EVENT_TEXT = {
  leave_lower: 'leaves the lower flank',
  reach_upper: 'reaches the upper flank',
  leave_upper: 'leaves the upper flank',
  reach_lower: 'reaches the lower flank',
};
// The order of the key: the ring moving up, then down.
const EVENT_KINDS = ['leave_lower', 'reach_upper', 'leave_upper', 'reach_lower'];

// A flank change's marker around (0, 0): a triangle pointing the way the ring
// moves (up: leaving the lower flank or reaching the upper), filled where it
// reaches a flank, open where it leaves one.  Relative path data: a zoom
// (plotui.js) moves the marker's translate() and keeps its size; the page's
// CSS enlarges it with the text on narrow screens.
function eventGlyph(kind, stroke) {
  const up = kind === 'leave_lower' || kind === 'reach_upper';
  const reach = kind.startsWith('reach');
  return svg('path', {
    class: `rp-ev-mk ${reach ? 'rp-ev-reach' : 'rp-ev-leave'}`,
    d: up ? 'm0,-6.5l6,10h-12z' : 'm0,6.5l6,-10h-12z',
    style: `stroke:${stroke};fill:${reach ? stroke : '#fff'}`,
  });
}

// A ring's events that can be drawn: [{event, crank_deg, touch_deg}].
const ringEvents = (r) => (Array.isArray(r?.events) ? r.events : [])
  .filter((e) => e && isNum(e.crank_deg) && typeof e.event === 'string');

// The lift at crank angle c, linear between the samples.
function liftAt(crank, lift, c) {
  let k = 1;
  while (k < crank.length - 1 && crank[k] < c) k++;
  const c0 = crank[k - 1], c1 = crank[k];
  const t = c1 === c0 ? 0 : Math.min(1, Math.max(0, (c - c0) / (c1 - c0)));
  return lift[k - 1] + t * (lift[k] - lift[k - 1]);
}

// Each drawn ring's events on its lift curve, in its colour.
function eventMarks(crank, series, x, y) {
  return svg('g', { class: 'rp-events', id: 'rp-events' }, series.flatMap((s) => ringEvents(s.r).map((e, k) => {
    const n = s.ring + 1;
    const touch = isNum(e.touch_deg) && Math.abs(e.touch_deg - e.crank_deg) > 1e-9
      ? ` (${e.event.startsWith('leave') ? 'left' : 'touched'} the flank itself at ${deg(e.touch_deg)})` : '';
    return svg('g', {
      class: 'rp-ev', 'data-ring': n, 'data-event': e.event, 'data-index': k, 'data-crank': e.crank_deg,
      transform: `translate(${x(e.crank_deg).toFixed(2)},${y(liftAt(crank, s.values, e.crank_deg) * 1e6).toFixed(2)})`,
    }, svg('title', {}, `Ring ${n} ${EVENT_TEXT[e.event] || e.event} at ${deg(e.crank_deg)} crank${touch}`), eventGlyph(e.event, ringColor(n)));
  })));
}

// A marker as a small inline icon for the caption's key.
const eventIcon = (kind) => svg('svg', { class: 'icon rp-ev-icon', viewBox: '-8 -8 16 16', width: 14, height: 14, 'aria-hidden': 'true' },
  eventGlyph(kind, '#1d232b'));

// The lift chart's caption: what is drawn, the markers' key, each ring's count.
function liftCaption(result, rings) {
  const b = flankBand(result);
  const counts = rings.map((r, i) => ({ n: i + 1, count: ringEvents(r).length }));
  return h('figcaption', { id: 'rp-lift-caption' },
    `Each ring's lift above its groove's lower flank (${modelsText(result)})${b !== null
      ? `; strips: the flank band at each flank of each groove, ${bandText(b)} of its axial clearance, whose edge dates the ring's flank changes` : ''}. `,
    h('span', { id: 'rp-event-key' }, 'Markers on each ring\'s curve, in its colour: its flank changes — ',
      EVENT_KINDS.flatMap((kind, i) => [i ? ', ' : '', eventIcon(kind), ` ${EVENT_TEXT[kind]}`]),
      ' (hover a marker for its angle). '),
    h('span', { id: 'rp-event-counts' }, 'Flank changes in the cycle: ',
      counts.flatMap(({ n, count }, i) => [i ? ', ' : '', h('span', { class: 'rp-event-count', 'data-ring': n, 'data-count': count }, `ring ${n}: ${count}`)]),
      '.'));
}

function liftPlot(crank, rings, result) {
  const series = rings.map((r, i) => ({ label: `ring ${i + 1}`, ring: i, r, color: ringColor(i + 1), values: nums(r.lift) }))
    .filter((s) => s.values.length === crank.length);
  // Each drawn ring's band at both flanks of its groove, in the ring's colour.
  const b = flankBand(result);
  const grooves = Array.isArray(result.scene?.rings) ? result.scene.rings : [];
  const banded = b === null ? [] : series.map((s) => ({ ring: s.ring, ca: grooves[s.ring]?.groove?.axial_clearance }))
    .filter((g) => isNum(g.ca) && g.ca > 0);
  const under = (x, y, box) => banded.map(({ ring, ca }) => {
    const color = ringColor(ring + 1);
    const ca6 = ca * 1e6, edge = b * ca6;
    const strip = (side, from, to) => [
      svg('rect', {
        class: 'flank-band', 'data-ring': ring + 1, 'data-side': side, style: `fill:${color}`,
        x: box.left, width: box.width, y: Math.min(y(from), y(to)), height: Math.abs(y(from) - y(to)),
      }),
      svg('line', { class: 'flank-band-edge', style: `stroke:${color}`, x1: box.left, x2: box.left + box.width, y1: y(to), y2: y(to) }),
    ];
    return svg('g', { class: 'flank-band-strip', id: `rp-flank-band-${ring + 1}` }, strip('lower', 0, edge), strip('upper', ca6, ca6 - edge));
  });
  const over = (x, y) => eventMarks(crank, series, x, y);
  const events = series.map((s) => `${s.label} ${ringEvents(s.r).length} flank change${ringEvents(s.r).length === 1 ? '' : 's'}`).join(', ');
  return chart('rp-lift', crank, series, 'lift (µm)', 1e6,
    `Ring lifts against crank angle: ${series.map((s) => `${s.label} up to ${um(Math.max(...s.values))} µm`).join('; ')}${banded.length ? `; flank band ${bandText(b)} of each groove's axial clearance` : ''}; markers: ${events}.`,
    banded.length ? {
      under,
      over,
      yMax: Math.max(...banded.map((g) => g.ca * 1e6)),
      legend: [[svg('rect', { class: 'flank-band', style: 'fill:#6b7580;stroke:#39414a', x: -2, y: -5, width: 14, height: 10 }), `flank bands (${bandText(b)} of each groove's clearance)`]],
    } : { over });
}

function blowbyPlot(crank, result) {
  const flows = (Array.isArray(result.flows) ? result.flows : []).filter((f) => f.to === 'crankcase');
  const total = crank.map((_, k) => flows.reduce((s, f) => s + (nums(f.mass_flow_kg_s)[k] ?? 0), 0));
  return chart('rp-blowby', crank, [{ label: 'into the crankcase', values: total }], 'mass flow (g/s)', 1e3,
    `Blow-by mass flow against crank angle, up to ${sig(Math.max(...total) * 1e3)} g/s.`);
}

// ---- friction (rings[i].friction_n) -----------------------------------------

// Each ring's bore friction force, when any is non-zero (the scene has
// friction, of any model); null otherwise.
function frictionFigure(crank, rings, result) {
  const series = rings.map((r, i) => ({ label: `ring ${i + 1}`, color: ringColor(i + 1), values: nums(r.friction_n) }))
    .filter((s) => s.values.length === crank.length);
  if (!series.some((s) => s.values.some((v) => v !== 0))) return null;
  const f = result.scene?.physics?.friction;
  const model = f && typeof f === 'object' && typeof f.model === 'string'
    ? ` (${f.model}${isNum(f.coefficient) && f.model !== 'lubricated' ? `, μ = ${sig(f.coefficient)}` : ''})` : '';
  const peak = (s) => Math.max(...s.values.map(Math.abs));
  return h('figure', { class: 'plot wide', id: 'rp-friction-figure' },
    chart('rp-friction', crank, series, 'friction (N)', 1,
      `Bore friction force on each ring against crank angle: ${series.map((s) => `${s.label} up to ${sig(peak(s))} N`).join('; ')}.`),
    h('figcaption', { id: 'rp-friction-caption' }, `Bore friction force on each ring against crank angle${model}, N, + upwards: the force the bore puts on the ring.`));
}

// ---- flow splits (result.flows) ---------------------------------------------

const volumeText = (v) => (typeof v === 'string' ? v : '?');
const flowRing = (f) => Number(/^ring_(\d+)_/.exec(String(f?.name))?.[1]) || null;
// A passage's series label: its name less the ring's prefix (none for a
// name that only says its volumes, "cylinder_to_top_land"), its volumes.
function flowLabel(f) {
  const part = f.name === `${f.from}_to_${f.to}` ? '' : String(f.name).replace(/^ring_\d+_/, '').replace(/_/g, ' ');
  return `${part ? `${part}: ` : ''}${volumeText(f.from)} → ${volumeText(f.to)}`;
}
const FLOW_DASH = { upper_flank: '6 3', lower_flank: '2 2.5' };

// The mass through `flow` over the reported cycle, kg: {net, forward, back},
// the trapezoidal rule over the samples of the flow, of its positive part
// and of its negative part (net = forward - back), dt = Δcrank / (6 rpm) s;
// null without the engine speed.
function flowMass(crank, flow, rpm) {
  const m = nums(flow.mass_flow_kg_s);
  if (!isNum(rpm) || rpm <= 0 || m.length !== crank.length) return null;
  let net = 0, forward = 0, back = 0;
  for (let k = 0; k + 1 < crank.length; k++) {
    const dt = (crank[k + 1] - crank[k]) / (6 * rpm);
    net += 0.5 * (m[k] + m[k + 1]) * dt;
    forward += 0.5 * (Math.max(m[k], 0) + Math.max(m[k + 1], 0)) * dt;
    back += 0.5 * (Math.max(-m[k], 0) + Math.max(-m[k + 1], 0)) * dt;
  }
  return { net, forward, back };
}

// The passages grouped for their charts: each ring's (upper flank, lower
// flank, end gap or leak) with any passage not of a ring that feeds it (the
// top-land entry: its `to` is the ring's upper volume); the rest alone.
function flowGroups(flows) {
  const groups = [];
  const of = (key) => groups.find((g) => g.key === key) ?? (groups.push({ key, flows: [] }), groups.at(-1));
  for (const f of flows) {
    const n = flowRing(f);
    if (n) { of(n).flows.push(f); continue; }
    const fed = flows.find((g) => flowRing(g) && g.from === f.to);
    of(fed ? flowRing(fed) : 'other').flows.push(f);
  }
  return groups;
}

function flowSection(crank, rings, result) {
  const flows = (Array.isArray(result.flows) ? result.flows : [])
    .filter((f) => f && typeof f.name === 'string' && nums(f.mass_flow_kg_s).length === crank.length);
  if (!flows.length) return null;
  const scene = Array.isArray(result.scene?.rings) ? result.scene.rings : [];
  const figures = flowGroups(flows).map(({ key, flows: group }) => {
    const n = key === 'other' ? null : key;
    const oil = n && scene[n - 1]?.kind === 'oil';
    const title = n ? `Ring ${n}${oil ? ' (oil ring)' : ''}` : 'Other passages';
    // The ring's passages in its colour (end gap solid, upper flank dashed,
    // lower flank dotted); a passage feeding it (the top-land entry) grey.
    const series = group.map((f) => ({
      label: flowLabel(f), values: nums(f.mass_flow_kg_s), attrs: { 'data-flow': f.name, class: 'rp-flow' },
      color: !n ? color(flows.indexOf(f)) : flowRing(f) ? ringColor(n) : '#39414a',
      dash: flowRing(f) ? FLOW_DASH[String(f.name).replace(/^ring_\d+_/, '')] : undefined,
    }));
    const id = `rp-flow-${n ?? 'other'}`;
    return h('figure', { class: 'plot wide' },
      chart(id, crank, series, 'mass flow (g/s)', 1e3,
        `${title}: mass flow through ${series.length === 1 ? 'its passage' : `its ${series.length} passages`} against crank angle: ${series.map((s) => s.label).join('; ')}.`),
      h('figcaption', {}, `${title}: the mass flow through each passage against crank angle, positive from the first volume named to the second${oil ? '; the oil ring\'s gas leak is its end gap' : ''}.`));
  });
  return h('section', { id: 'rp-flows', 'aria-label': 'Flow splits' },
    h('h4', {}, 'Where the gas goes: the flow through each passage'),
    figures,
    h('div', { class: 'table-wrap' }, flowTable(crank, flows, result.scene?.engine?.speed_rpm)));
}

// Each passage's net mass per cycle (and its forward and reversed parts), mg.
function flowTable(crank, flows, rpm) {
  const mg = (v, cls) => h('td', { class: `num ${cls}`, 'data-kg': isNum(v) ? v : null }, isNum(v) ? sig(v * 1e6, 4) : '—');
  return h('table', { class: 'data', id: 'rp-flow-table' },
    h('caption', {}, `Mass through each passage per cycle, mg (the reported cycle's samples integrated by the trapezoidal rule${isNum(rpm) ? ` at ${sig(rpm, 5)} rpm` : ''}); net: from the first volume to the second, back: the part that flowed the other way`),
    h('thead', {}, h('tr', {}, h('th', { scope: 'col' }, 'Passage'), h('th', { scope: 'col' }, 'From → to'),
      h('th', { scope: 'col' }, 'Net'), h('th', { scope: 'col' }, 'Forward'), h('th', { scope: 'col' }, 'Back'))),
    h('tbody', {}, flows.map((f) => {
      const m = flowMass(crank, f, rpm);
      return h('tr', { 'data-flow': f.name },
        h('th', { scope: 'row' }, f.name), h('td', {}, `${volumeText(f.from)} → ${volumeText(f.to)}`),
        mg(m?.net, 'net'), mg(m?.forward, 'forward'), mg(m?.back, 'back'));
    })));
}

// ---- each ring's oil film (rings[i].lubrication) ---------------------------

// The rings with a lubrication block: [{lub, n}], n = the ring's number.
const lubed = (rings) => rings.map((r, i) => ({ lub: r?.lubrication, n: i + 1 })).filter(({ lub }) => isLube(lub));

// The reported cycle's value of a one-element array (friction_work_j, fmep_pa).
const cycleValue = (a) => nums(a).at(-1);

// The pack's FMEP (the rings' sum) and each ring's, under the summary.
function lubeSummary(crank, rings) {
  const list = lubed(rings);
  if (!list.length) return null;
  const fmep = list.map(({ lub }) => cycleValue(lub.fmep_pa));
  const least = list.map(({ lub, n }) => ({ n, t: thinnest(lub, crank) })).filter((x) => x.t)
    .reduce((a, b) => (a && a.t.m <= b.t.m ? a : b), null);
  const parts = [];
  if (fmep.every(isNum)) parts.push(`FMEP of the pack ${sig(fmep.reduce((a, b) => a + b, 0) / 1e3)} kPa (${list.map(({ n }, k) => `ring ${n} ${sig(fmep[k] / 1e3)}`).join(', ')} kPa)`);
  if (least) parts.push(`thinnest oil film ${um(least.t.m, 3)} µm (ring ${least.n} at ${deg(crank[least.t.i])})`);
  return parts.length ? h('p', { id: 'rp-lube-summary' }, `Lubricated: ${parts.join('; ')}.`) : null;
}

// A face as the scene gives it: "barrel, crown 5 µm".
function faceText(face) {
  if (!face || typeof face !== 'object') return null;
  const p = face.profile;
  if (p === 'barrel' && isNum(face.crown_m)) return `barrel face, crown ${sig(face.crown_m * 1e6)} µm`;
  if (p === 'taper' && isNum(face.taper_deg)) return `taper face, ${sig(face.taper_deg)}°`;
  if (p === 'flat' && isNum(face.edge_radius_m)) return `flat face, edge radius ${sig(face.edge_radius_m * 1e3)} mm`;
  return typeof p === 'string' ? `${p} face` : null;
}

function lubeSection(crank, rings, result) {
  const list = lubed(rings);
  if (!list.length) return null;
  const scene = Array.isArray(result.scene?.rings) ? result.scene.rings : [];
  const friction = result.scene?.physics?.friction;
  return h('section', { id: 'rp-lube', 'aria-label': 'Oil film of each ring' },
    list.map(({ lub, n }) => ringLube(crank, lub, n, scene[n - 1]?.ring?.face, friction?.supply, friction?.cavitation)));
}

// One ring's readout, its two plots and its film model (collapsed).
function ringLube(crank, lub, n, face, supply, cavitation) {
  const id = `rp-${n}`;
  const film = nums(lub.min_film_m);
  const least = thinnest(lub, crank);
  const work = cycleValue(lub.friction_work_j), fmep = cycleValue(lub.fmep_pa);
  const readout = kvTable({
    id: `${id}-lube`,
    caption: `Ring ${n}: friction over the reported cycle and its film`,
    rows: [
      ['FMEP', isNum(fmep) ? `${sig(fmep / 1e3, 4)} kPa` : '—', { id: `${id}-fmep` }],
      ['Friction work', isNum(work) ? `${sig(work, 4)} J` : '—', { id: `${id}-work` }],
      ['Thinnest film', least ? `${um(least.m, 3)} µm at ${deg(crank[least.i])}` : '—', { id: `${id}-thinnest` }],
      ['Film lag (film_lag)', isNum(lub.film_lag) ? sig(lub.film_lag, 3) : '—', { id: `${id}-film-lag` }],
      ['Regime (share of the samples)', regimeText(lub) ?? '—', { id: `${id}-regime` }],
      ...filmFactRows(lub, { supply, cavitation, id }),
    ],
  });
  const axis = crankAxis(crank);
  const sigma = isNum(lub.composite_roughness_m) ? `; dashed: the composite roughness σ = ${um(lub.composite_roughness_m, 3)} µm` : '';
  return h('section', { class: 'rp-ring-lube', id: `${id}-oil`, 'aria-label': `Ring ${n}'s oil film` },
    h('h4', {}, `Ring ${n}: oil film${faceText(face) ? ` (${faceText(face)})` : ''}`),
    h('div', { class: 'table-wrap' }, readout),
    film.length === crank.length ? h('figure', { class: 'plot wide' }, filmPlot(crank, film, lub.composite_roughness_m, { id, axis }),
      h('figcaption', {}, `Ring ${n}: the minimum oil film thickness against crank angle${sigma}.`)) : null,
    h('figure', { class: 'plot wide' }, lubeFrictionPlot(crank, lub, { id, axis }),
      h('figcaption', {}, `Ring ${n}: friction from its film against crank angle, + upwards: the film's shear (hydrodynamic), the asperities' and their total.`)),
    typeof lub.method === 'string' && lub.method
      ? h('details', { class: 'method', id: `${id}-method` }, h('summary', {}, `Ring ${n}'s film model: what it covers`), h('p', {}, lub.method))
      : null);
}

// The models that ran, for a caption: "axial rings", or per ring when they
// differ ("ring 1 full, rings 2–3 axial"); from numerics.model.
function modelsText(result) {
  const models = Array.isArray(result.numerics?.model) ? result.numerics.model : [];
  const names = models.map((m) => (typeof m?.name === 'string' ? m.name : '?'));
  if (!names.length) return 'ring models not reported';
  if (names.every((n) => n === names[0])) return `${names[0]} ring${names.length === 1 ? '' : 's'}`;
  const runs = [];
  names.forEach((n, i) => {
    const last = runs[runs.length - 1];
    if (last && last.name === n) last.to = i + 1;
    else runs.push({ name: n, from: i + 1, to: i + 1 });
  });
  return runs.map((r) => (r.from === r.to ? `ring ${r.from} ${r.name}` : `rings ${r.from}–${r.to} ${r.name}`)).join(', ');
}

// Each ring's model from numerics.model [{name, dof, modes, why}]: which
// equations ran (auto's choice or the one asked for) and why.
function modelTable(result) {
  const models = Array.isArray(result.numerics?.model) ? result.numerics.model : [];
  if (!models.length) return null;
  const dof = (m) => (isNum(m.dof) ? `${m.dof}${m.modes > 0 ? ` (${m.modes} modes)` : ''}` : '—');
  return h('table', { class: 'data', id: 'rp-models' },
    h('caption', {}, 'Ring models'),
    h('thead', {}, h('tr', {}, h('th', { scope: 'col' }, 'Ring'), h('th', { scope: 'col' }, 'Model'),
      h('th', { scope: 'col' }, 'DOF'), h('th', { scope: 'col' }, 'Why'))),
    h('tbody', {}, models.map((m, i) => h('tr', { id: `rp-model-${i + 1}` },
      h('th', { scope: 'row' }, String(i + 1)), h('td', {}, m.name ?? '—'), h('td', { class: 'num' }, dof(m)),
      h('td', { class: 'why' }, m.why ?? '')))));
}

// With cycles "periodic": whether the run settled, and after how many cycles.
function periodicText(result) {
  const n = result.numerics?.cycles;
  if (result.periodic_reached === true) return ` (periodic: settled after ${n} cycles)`;
  if (result.periodic_reached === false) return ` (periodic: NOT settled within ${n} cycles; the last is reported)`;
  return '';
}

function costTable(result) {
  const n = result.numerics || {};
  const b = result.blowby || {};
  return kvTable({
    id: 'rp-cost', caption: 'Balance and cost',
    rows: [
      ['Into the top land per cycle', isNum(b.inflow_kg_per_cycle) ? `${sig(b.inflow_kg_per_cycle)} kg` : '—'],
      ['Mass balance residual (of the throughput)', isNum(b.mass_balance_residual) ? sig(b.mass_balance_residual, 2) : '—'],
      ['Cycles', n.cycles ?? '—'],
      ['CVODE steps', n.steps ?? '—'],
      ['Restarts at flank changes', n.restarts ?? '—'],
      ['Error estimate', isNum(n.error_estimate) ? sig(n.error_estimate, 2) : '—', { id: 'rp-error' }],
      // what the estimate covers (the time integration only), as text beside it
      ['What the estimate covers', n.error_method ?? undefined, { id: 'rp-error-scope' }],
      ['Event angle error', isNum(n.event_error_deg) ? `${sig(n.event_error_deg, 2)}°` : '—'],
      ['Wall time', isNum(n.wall_s) ? seconds(n.wall_s) : '—'],
    ],
  });
}
