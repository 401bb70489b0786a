// The oil film of a lubricated run, shared by the Lift tab (the result's
// `lubrication`) and the Ring pack tab (each rings[i].lubrication): the
// minimum film thickness and the friction split (film shear, asperities,
// total) against crank angle, the regime shares, the film's facts.
// Pure functions of the block: optional fields may be missing.  Each chart is
// drawn on the caller's crank axis ({x, ticks}, a 720-unit-wide viewBox with
// the plot box at BOX) and its ids start with the caller's prefix: lf-film,
// rp-2-film, ...

import { svg, scale, ticks, axes, pathD, legend } from './svg.js';
import { fixed, isNum, sig, percent, nums, um, deg } from './html.js';

export const W = 720;
export const BOX = { left: 64, width: W - 64 - 16 };

export const isLube = (lub) => lub !== null && typeof lub === 'object';

// At most about 4 points per bucket of samples: the first, the lowest, the
// highest and the last, so a long run draws the same envelope with fewer points.
export function thin(xs, ys, buckets = 700) {
  const N = Math.min(xs.length, ys.length);
  if (N <= 4 * buckets) return xs.slice(0, N).map((x, i) => [x, ys[i]]);
  const out = [];
  const per = N / buckets;
  for (let b = 0; b < buckets; b++) {
    const i0 = Math.floor(b * per), i1 = Math.min(N, Math.floor((b + 1) * per));
    let lo = i0, hi = i0;
    for (let i = i0; i < i1; i++) {
      if (ys[i] < ys[lo]) lo = i;
      if (ys[i] > ys[hi]) hi = i;
    }
    for (const i of [...new Set([i0, lo, hi, i1 - 1])].sort((a, c) => a - c)) out.push([xs[i], ys[i]]);
  }
  return out;
}

// The oil's viscosity over the cycle ({min, max}, Pa s) in mPa s: one value
// when constant; null without one.
export function viscosityText(v) {
  if (!v || !isNum(v.min) || !isNum(v.max)) return null;
  return v.max - v.min <= 1e-9 * v.max ? `${sig(v.min * 1e3)} mPa s` : `${sig(v.min * 1e3)}–${sig(v.max * 1e3)} mPa s`;
}

export const REGIMES = ['hydrodynamic', 'mixed', 'boundary'];

// The share of the samples in regime r ("42 %"), of the block's regime array.
export function regimeShare(lub, r) {
  const regime = Array.isArray(lub?.regime) ? lub.regime : [];
  return `${((regime.filter((x) => x === r).length / Math.max(1, regime.length)) * 100).toFixed(0)} %`;
}

// "hydrodynamic 80 %, mixed 20 %, boundary 0 %" (null without a regime array).
export function regimeText(lub) {
  return Array.isArray(lub?.regime) && lub.regime.length ? REGIMES.map((r) => `${r} ${regimeShare(lub, r)}`).join(', ') : null;
}

// The thinnest film: {i, m} (index into the samples, metres); null without one.
export function thinnest(lub, crank) {
  const film = nums(lub?.min_film_m);
  if (!film.length || film.length !== crank.length) return null;
  const i = film.indexOf(Math.min(...film));
  return { i, m: film[i] };
}

// The caption of the film plot: what it shows, σ, the regimes, η.
export function filmCaption(lub) {
  const viscText = viscosityText(lub.viscosity_pa_s);
  const regimes = regimeText(lub);
  return 'Minimum oil film thickness between the running face and the liner against crank angle (one film for the whole circumference). ' +
    (isNum(lub.composite_roughness_m) ? `Dashed: the composite roughness σ = ${um(lub.composite_roughness_m, 3)} µm; the asperities take load as the film nears a few σ. ` : '') +
    (regimes ? `Regime by the asperities' share of the load: ${regimes} of the samples` : '') +
    (viscText ? `; η = ${viscText}.` : '.');
}

export const FRICTION_CAPTION = 'Friction on the ring from the film against crank angle, + upwards: the oil film\'s shear (hydrodynamic), the asperities\' contact friction and their total.';

// The minimum film (m per sample) in µm with the composite roughness σ (m).
export function filmPlot(crank, film, sigma, { id, axis }) {
  const H = 240;
  const box = { ...BOX, top: 34, height: H - 34 - 50 };
  const v = film.map((f) => f * 1e6);
  const s = isNum(sigma) ? sigma * 1e6 : null;
  const vals = v.filter(isNum);
  const y0 = Math.min(0, ...vals), y1 = Math.max(1e-3, ...vals, s ?? 0);
  const pad = (y1 - y0) * 0.08;
  const { x, ticks: xTicks } = axis;
  const y = scale(y0, y1 + pad, box.top + box.height, box.top);
  const i = v.indexOf(Math.min(...vals));
  return svg('svg', {
    id: `${id}-film`, class: 'chart', viewBox: `0 0 ${W} ${H}`, role: 'img',
    'aria-label': `Minimum oil film thickness against crank angle, ${sig(Math.min(...vals))} to ${sig(Math.max(...vals))} µm, thinnest at ${deg(crank[i])}.`,
  },
  legend([
    [svg('path', { class: 'film', d: 'M-2,0H12' }), 'minimum film'],
    s !== null ? [svg('path', { class: 'sigma', d: 'M-2,0H12' }), 'composite roughness σ'] : null,
  ].filter(Boolean), { x: box.left, y: 14 }),
  axes({
    box, x, y, xTicks, yTicks: ticks(y0, y1 + pad, 4),
    xLabel: 'crank angle (deg)', yLabel: 'film (µm)', yFormat: (t) => String(Number(t.toPrecision(4))),
  }),
  s !== null ? svg('line', { class: 'sigma', id: `${id}-film-sigma`, x1: box.left, x2: box.left + box.width, y1: y(s), y2: y(s) }) : null,
  svg('path', { class: 'film', id: `${id}-film-line`, 'data-name': 'minimum film', d: pathD(thin(crank, v).map(([c, f]) => [x(c), y(f)])) }),
  svg('circle', { class: 'film-min', cx: x(crank[i]), cy: y(v[i]), r: 4 }, svg('title', {}, `thinnest: ${sig(v[i])} µm at ${deg(crank[i])}`)));
}

// [key, id suffix, legend text] of the friction split's lines.
const SPLIT = [
  ['hydrodynamic', 'friction-hydro', 'oil film (hydrodynamic)'],
  ['asperity', 'friction-asperity', 'asperities'],
  ['total', 'friction-total', 'total'],
];

// The split's series over the N samples (null where the block lacks one).
function splitSeries(lub, N) {
  const hydro = nums(lub.hydrodynamic_friction_n).slice(0, N), asp = nums(lub.asperity_friction_n).slice(0, N);
  return {
    hydrodynamic: hydro.length === N ? hydro : null,
    asperity: asp.length === N ? asp : null,
    total: hydro.length === N && asp.length === N ? hydro.map((f, i) => f + asp[i]) : null,
  };
}

// The friction split against crank angle, N.
export function lubeFrictionPlot(crank, lub, { id, axis }) {
  const H = 240;
  const box = { ...BOX, top: 34, height: H - 34 - 50 };
  const series = splitSeries(lub, crank.length);
  const shown = SPLIT.filter(([k]) => series[k]);
  const vals = Object.values(series).filter(Boolean).flat().filter(isNum);
  const f0 = Math.min(0, ...vals), f1 = Math.max(0, ...vals);
  const pad = (f1 - f0) * 0.08 || 1;
  const { x, ticks: xTicks } = axis;
  const y = scale(f0 - pad, f1 + pad, box.top + box.height, box.top);
  const range = ([k, , text]) => `${text} ${sig(Math.min(...series[k]))} to ${sig(Math.max(...series[k]))} N`;
  return svg('svg', {
    id: `${id}-lube-friction`, class: 'chart', viewBox: `0 0 ${W} ${H}`, role: 'img',
    'aria-label': `Friction split against crank angle: ${shown.map(range).join('; ')}.`,
  },
  legend(shown.map(([k, , text]) => [svg('path', { class: `split-${k}`, d: 'M-2,0H12' }), text]), { x: box.left, y: 14 }),
  axes({
    box, x, y, xTicks, yTicks: ticks(f0 - pad, f1 + pad, 4),
    xLabel: 'crank angle (deg)', yLabel: 'friction (N)', yFormat: (v) => String(Number(v.toPrecision(4))),
  }),
  svg('line', { class: 'zero', x1: box.left, x2: box.left + box.width, y1: y(0), y2: y(0) }),
  shown.map(([k, suffix, text]) => svg('path', { class: `split-${k}`, id: `${id}-${suffix}`, 'data-name': text, d: pathD(thin(crank, series[k]).map(([c, f]) => [x(c), y(f)])) })));
}

// The oil the scene fed the face (its physics.friction.supply): "starved
// inlet: 1 µm of oil on the liner" for {film_m}; null when flooded (the
// default, "flooded" or absent) or not readable.
export function supplyText(supply) {
  const h = supply !== null && typeof supply === 'object' ? supply.film_m : undefined;
  return isNum(h) && h > 0 ? `starved inlet: ${sig(h * 1e6)} µm of oil on the liner` : null;
}

// The scene's cavitation condition (its physics.friction.cavitation): "jfo"
// the mass-conserving one, anything else (the default "reynolds", absent)
// the Reynolds (Swift-Stieber) one.
export function cavitationText(cavitation) {
  return cavitation === 'jfo' ? 'JFO (mass-conserving)' : 'Reynolds';
}

// A distorted bore's films (lubrication.films > 1): how many, and whether
// each segment has its own or they are interpolated (with the estimate);
// undefined for one film.
export function filmsText(lub) {
  if (!isNum(lub?.films) || lub.films <= 1) return undefined;
  const e = lub.film_interpolation_error;
  const map = lub.film_load_n_per_m?.depths > 1;
  if (isNum(e))
    return map
      ? `${lub.films} films at loads across the range, each segment's interpolated at its load at the ring's depth (error estimate ${percent(e, 2)})`
      : `${lub.films} films at loads across the range, each segment's interpolated at its load (error estimate ${percent(e, 2)})`;
  return map ? `${lub.films} films, one per segment load history along the stroke` : `${lub.films} films, one per segment load`;
}

// The segments' elastic load range on the liner (N/m) where it varies: around
// the ring, and on a bore map along the stroke too.
export function loadRangeText(lub) {
  const r = lub?.film_load_n_per_m;
  const map = r?.depths > 1;
  if (!isNum(lub?.films) || (lub.films <= 1 && !map) || !isNum(r?.min) || !isNum(r?.max)) return undefined;
  if (!map) return `${sig(r.min, 3)} to ${sig(r.max, 3)} N/m around the ring (2 F_t / D in a round bore)`;
  const e = isNum(r.depth_error) ? `, linear between them within ${percent(r.depth_error, 2)} of 2 F_t / D` : '';
  return `${sig(r.min, 3)} to ${sig(r.max, 3)} N/m around the ring and along the stroke (solved at ${r.depths} depths of the bore map${e})`;
}

// The film's facts as kvTable rows (a value undefined where the block lacks
// it); `supply` is the scene's physics.friction.supply (a row when starved),
// `cavitation` its physics.friction.cavitation (always a row), `id` the
// prefix of those rows' ids (lf, rp-2: lf-supply, rp-2-cavitation).
export function filmFactRows(lub, { supply, cavitation, id } = {}) {
  return [
    ['Films around the ring', filmsText(lub), { id: id ? `${id}-films` : undefined }],
    ['Elastic load on the liner', loadRangeText(lub), { id: id ? `${id}-film-load` : undefined }],
    ['Oil supply', supplyText(supply) ?? undefined, { id: id ? `${id}-supply` : undefined }],
    ['Cavitation', cavitationText(cavitation), { id: id ? `${id}-cavitation` : undefined }],
    ['Composite roughness σ', isNum(lub.composite_roughness_m) ? `${um(lub.composite_roughness_m, 3)} µm` : undefined],
    ['Thinnest point of the face', isNum(lub.min_film_at_m) ? `${fixed(lub.min_film_at_m, 3, 1e3)} mm above its lower edge` : undefined],
    ['Viscosity', viscosityText(lub.viscosity_pa_s) ?? undefined],
    ['Film steps (largest)', isNum(lub.film_step_deg) ? `${sig(lub.film_step_deg)}° crank` : undefined],
    ['Film solves', isNum(lub.film_solves) ? String(lub.film_solves) : undefined],
    ['Change over the last cycle (periodicity)', isNum(lub.periodic_change) ? percent(lub.periodic_change, 3) : undefined],
    ['Steps held off the liner', isNum(lub.held_steps) ? String(lub.held_steps) : undefined],
  ];
}
