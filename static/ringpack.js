// The ring pack analysis: renders a ringpack `result` as the
// absolute gas pressures of every volume against crank angle (the cylinder
// first, the crankcase last), each ring's lift, the mass flow into the
// crankcase (the blow-by), and tables of each ring's model (name, DOF, why),
// the balance and the solver's cost.  With a flank band (numerics.flank_band
// > 0) each ring's lift is drawn over the band at its groove's flanks, in the
// ring's colour: where its flank changes are dated.  With the lubricated
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
      h('figure', { class: 'plot wide' }, liftPlot(crank, rings, result),
        h('figcaption', { id: 'rp-lift-caption' }, `Each ring's lift above its groove's lower flank (${modelsText(result)})${flankBand(result) !== null
          ? `; strips: the flank band at each flank of each groove, ${bandText(flankBand(result))} of its axial clearance, whose edge dates the ring's flank changes` : ''}.`)),
      h('figure', { class: 'plot wide' }, blowbyPlot(crank, result),
        h('figcaption', {}, 'Mass flow into the crankcase (the blow-by; negative: back out of it).')),
    ];
    fill(container,
      h('h3', {}, `Ring pack — ${rings.length} ring${rings.length === 1 ? '' : 's'}${isNum(rpm) ? ` at ${sig(rpm, 5)} rpm` : ''}`),
      h('p', { id: 'rp-summary' }, `Blow-by ${isNum(b.l_per_min) ? sig(b.l_per_min) : '—'} L/min (${isNum(b.kg_per_cycle) ? sig(b.kg_per_cycle) : '—'} kg per cycle, at 1.01325 bar and 20 °C); back into the cylinder ${isNum(b.reverse_kg_per_cycle) ? sig(b.reverse_kg_per_cycle) : '—'} kg per cycle; last cycle against the one before: ${isNum(result.periodicity) ? sig(result.periodicity, 2) : '—'}${periodicText(result)}.`),
      lubeSummary(crank, rings),
      resultLinks(job, 'ringpack', 'Ring pack table (CSV)'),
      h('div', { id: 'rp-plots' }, figs),
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

// One chart of several series [{label, values}] against crank angle.
// extra: {legend: [[swatch, text]...] after the series', yMax: a value (in
// the series' units times factor) the axis reaches at least, under(x, y,
// box): elements drawn beneath the series}.
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
      ...series.map((s, i) => [svg('path', { d: 'M-2,0H12', style: `stroke:${COLORS[i % COLORS.length]};stroke-width:2` }), s.label]),
      ...(extra.legend || []),
    ], { x: box.left, y: 14 }),
    axes({ box, x, y, xTicks, yTicks: ticks(lo, hi + pad, 4), xLabel: 'crank angle (deg)', yLabel, yFormat: (v) => String(Number(v.toPrecision(4))) }),
    extra.under ? extra.under(x, y, box) : null,
    series.map((s, i) => svg('path', {
      id: `${id}-${i}`, 'data-name': s.label, 'data-points': s.values.length, style: `fill:none;stroke:${COLORS[i % COLORS.length]};stroke-width:1.6`,
      d: pathD(s.values.map((v, k) => [x(crank[k]), y(v * factor)])),
    })));
}

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

function liftPlot(crank, rings, result) {
  const series = rings.map((r, i) => ({ label: `ring ${i + 1}`, ring: i, values: nums(r.lift) })).filter((s) => s.values.length === crank.length);
  // Each drawn ring's band at both flanks of its groove, in the ring's colour.
  const b = flankBand(result);
  const grooves = Array.isArray(result.scene?.rings) ? result.scene.rings : [];
  const banded = b === null ? [] : series.map((s, i) => ({ i, ring: s.ring, ca: grooves[s.ring]?.groove?.axial_clearance }))
    .filter((g) => isNum(g.ca) && g.ca > 0);
  const under = (x, y, box) => banded.map(({ i, ring, ca }) => {
    const color = COLORS[i % COLORS.length];
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
  return chart('rp-lift', crank, series, 'lift (µm)', 1e6,
    `Ring lifts against crank angle: ${series.map((s) => `${s.label} up to ${um(Math.max(...s.values))} µm`).join('; ')}${banded.length ? `; flank band ${bandText(b)} of each groove's axial clearance` : ''}.`,
    banded.length ? {
      under,
      yMax: Math.max(...banded.map((g) => g.ca * 1e6)),
      legend: [[svg('rect', { class: 'flank-band', style: 'fill:#6b7580;stroke:#39414a', x: -2, y: -5, width: 14, height: 10 }), `flank bands (${bandText(b)} of each groove's clearance)`]],
    } : {});
}

function blowbyPlot(crank, result) {
  const flows = (Array.isArray(result.flows) ? result.flows : []).filter((f) => f.to === 'crankcase');
  const total = crank.map((_, k) => flows.reduce((s, f) => s + (nums(f.mass_flow_kg_s)[k] ?? 0), 0));
  return chart('rp-blowby', crank, [{ label: 'into the crankcase', values: total }], 'mass flow (g/s)', 1e3,
    `Blow-by mass flow against crank angle, up to ${sig(Math.max(...total) * 1e3)} g/s.`);
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
