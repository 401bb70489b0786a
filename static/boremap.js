// A bore map (bore.layers: the bore's out-of-roundness layer by layer down
// its height) drawn as a colour map: the radius's departure from the first
// layer's mean radius, dr(θ, z) = (D(z) − D₁)/2 + Σ A_k cos(k(θ − φ_k)),
// over the angle from the gap θ (x, 0–360°) and the depth z (y, down), linear
// in z between the layers as the server takes it.  The ring's travel (lift:
// TDC to BDC) or its height (contact) is marked on it.
//
// boreMapPlot() draws one from layers (a result's echo, or the form's);
// setupBoreMaps() keeps a live drawing under each map of the form.

import { svg, scale, ticks, axes, legend } from './svg.js';
import { h, isNum, sig } from './html.js';
import { watchCharts } from './charts.js';

// Diverging colours (ColorBrewer RdBu): blue inward (the bore narrower), white
// none, red outward (wider).
const STOPS = ['#053061', '#2166ac', '#4393c3', '#92c5de', '#d1e5f0', '#f7f7f7', '#fddbc7', '#f4a582', '#d6604d', '#b2182b', '#67001f'];
const RGB = STOPS.map((c) => [1, 3, 5].map((i) => parseInt(c.slice(i, i + 2), 16)));
const COLS = 180; // image columns: 2° each
const ROWS = 150; // image rows over the depth drawn

// The colour of u in [-1, 1] as [r, g, b].
function colour(u) {
  const x = (Math.max(-1, Math.min(1, u)) + 1) / 2 * (RGB.length - 1);
  const i = Math.min(RGB.length - 2, Math.floor(x));
  const t = x - i;
  return RGB[i].map((c, k) => Math.round(c + (RGB[i + 1][k] - c) * t));
}

const mm = (m) => sig(m * 1e3, 4);
const rad = (deg) => (deg * Math.PI) / 180;

// The layers as numbers: [{z, d (diameter used), terms}], or a reason they
// cannot be drawn.  `diameter`: the diameter of a layer that gives none.
export function mapLayers(layers, diameter) {
  if (!Array.isArray(layers) || !layers.length) return { error: 'no layers' };
  const out = [];
  for (const [i, l] of layers.entries()) {
    const z = Number(l?.z);
    if (!Number.isFinite(z)) return { error: `layer ${i + 1} has no depth z` };
    if (out.length && !(z > out[out.length - 1].z)) return { error: `the depths z must increase from layer to layer (layer ${i + 1}: ${mm(z)} mm after ${mm(out[out.length - 1].z)} mm)` };
    const d = Number(l.diameter) > 0 ? Number(l.diameter) : Number(diameter) > 0 ? Number(diameter) : 0;
    const terms = (Array.isArray(l.distortion) ? l.distortion : []).map((t) => ({
      k: Number(t?.order), a: Number(t?.amplitude), phi: Number(t?.phase_deg ?? 0),
    }));
    if (terms.some((t) => !Number.isInteger(t.k) || t.k < 1 || !Number.isFinite(t.a) || !Number.isFinite(t.phi))) {
      return { error: `a distortion order of layer ${i + 1} is incomplete` };
    }
    out.push({ z, d, terms });
  }
  return { layers: out };
}

// dr of each layer at the angles `thetas` (deg), m, from the first layer's radius.
function layerRows(layers, thetas) {
  const d1 = layers[0].d;
  return layers.map((l) => thetas.map((th) => (l.d && d1 ? (l.d - d1) / 2 : 0) +
    l.terms.reduce((s, t) => s + t.a * Math.cos(t.k * rad(th - t.phi)), 0)));
}

// dr at depth z from the rows of layerRows (linear between layers, clamped).
function rowAt(layers, rows, z) {
  const n = layers.length;
  if (n === 1 || z <= layers[0].z) return rows[0];
  if (z >= layers[n - 1].z) return rows[n - 1];
  let i = 0;
  while (z > layers[i + 1].z) i += 1;
  const t = (z - layers[i].z) / (layers[i + 1].z - layers[i].z);
  return rows[i].map((v, j) => v + (rows[i + 1][j] - v) * t);
}

// The colour image of dr over [z0, z1] (m) as a PNG data URL; rows outside
// the layers are transparent (the hatching under them shows).
function mapImage(layers, z0, z1, limit) {
  const thetas = Array.from({ length: COLS }, (_, j) => (j + 0.5) * (360 / COLS));
  const rows = layerRows(layers, thetas);
  const canvas = document.createElement('canvas');
  canvas.width = COLS;
  canvas.height = ROWS;
  const ctx = canvas.getContext('2d');
  const img = ctx.createImageData(COLS, ROWS);
  const dz = (z1 - z0) / ROWS;
  const top = layers[0].z, bottom = layers[layers.length - 1].z;
  for (let r = 0; r < ROWS; r++) {
    const z = z0 + (r + 0.5) * dz;
    if (z < top - dz || z > bottom + dz) continue; // a single layer still shows as a stripe
    const row = rowAt(layers, rows, z);
    for (let j = 0; j < COLS; j++) {
      const [cr, cg, cb] = colour(limit > 0 ? row[j] / limit : 0);
      const k = 4 * (r * COLS + j);
      img.data[k] = cr; img.data[k + 1] = cg; img.data[k + 2] = cb; img.data[k + 3] = 255;
    }
  }
  ctx.putImageData(img, 0, 0);
  return canvas.toDataURL('image/png');
}

// The largest |dr| of the map, m: at a layer (dr is linear between them).
function largest(layers) {
  const thetas = Array.from({ length: 1440 }, (_, j) => j / 4);
  return Math.max(0, ...layerRows(layers, thetas).map((r) => Math.max(...r.map(Math.abs))));
}

// The drawing: an <svg> (role img), or null when the layers cannot be drawn.
//   layers    bore.layers ({z, diameter?, distortion?})
//   diameter  the diameter of layers that give none (bore's or ring's)
//   travel    [z TDC, z BDC] (lift), or null
//   height    the contact height: a number (m), 'all', or null
//   shown     with height 'all': the layer the result reports (height_m)
//   id        the svg's id; its marks are id-travel, id-height, id-layers
//   width     viewBox width (480 for the form's column, 720 in the results)
//   aspect    viewBox height / width
export function boreMapPlot({ layers: given, diameter, travel = null, height = null, shown = null, id = 'bore-map', width = 720, aspect = 0.56 }) {
  const { layers, error } = mapLayers(given, diameter);
  if (error) return null;
  const W = width, H = Math.round(width * aspect);
  const box = { left: 66, top: 40, width: W - 66 - 92, height: H - 40 - 54 };
  const first = layers[0].z, last = layers[layers.length - 1].z;
  const marks = [first, last];
  if (travel && travel.every(isNum)) marks.push(...travel);
  if (isNum(height)) marks.push(height);
  let z0 = Math.min(...marks), z1 = Math.max(...marks);
  if (!(z1 > z0)) { z0 = Math.max(0, z0 - 0.001); z1 = z0 + 0.002; }
  const limit = largest(layers);
  const x = scale(0, 360, box.left, box.left + box.width);
  const y = scale(z0 * 1e3, z1 * 1e3, box.top, box.top + box.height); // mm, down
  const yz = (z) => y(z * 1e3);
  const right = box.left + box.width, bottom = box.top + box.height;
  const outside = first > z0 + 1e-12 || last < z1 - 1e-12;

  // Colour bar: +limit at the top, -limit at the bottom, ticks in µm.
  const L = limit * 1e6;
  const bar = { x: right + 16, w: 14 };
  const yBar = scale(L || 1, -(L || 1), box.top, bottom);
  const barTicks = L > 0 ? ticks(-L, L, 4) : [0];
  const grad = `${id}-grad`, hatch = `${id}-hatch`;
  const defs = svg('defs', {},
    svg('linearGradient', { id: grad, x1: 0, y1: 0, x2: 0, y2: 1 },
      STOPS.slice().reverse().map((c, i) => svg('stop', { offset: (i / (STOPS.length - 1)).toFixed(3), 'stop-color': L > 0 ? c : STOPS[5] }))),
    svg('pattern', { id: hatch, width: 8, height: 8, patternUnits: 'userSpaceOnUse', patternTransform: 'rotate(45)' },
      svg('rect', { width: 8, height: 8, fill: '#eef1f4' }),
      svg('line', { x1: 0, y1: 0, x2: 0, y2: 8, stroke: '#9aa3ad', 'stroke-width': 2 })));

  const travelOk = travel && travel.every(isNum);
  const covered = travelOk && travel[0] >= first - 1e-12 && travel[1] <= last + 1e-12;
  const heightMark = [];
  if (isNum(height)) {
    heightMark.push(svg('line', { id: `${id}-height`, class: 'bm-height', x1: box.left, x2: right, y1: yz(height), y2: yz(height), 'data-z': height },
      svg('title', {}, `The ring at z = ${mm(height)} mm`)));
    heightMark.push(svg('text', { class: 'tick halo bm-label', x: box.left + 6, y: yz(height) - 5 }, `ring, z = ${mm(height)} mm`));
  } else if (height === 'all') {
    heightMark.push(svg('g', { id: `${id}-height`, 'data-z': 'all' }, layers.map((l) => svg('line', {
      class: `bm-height bm-each${isNum(shown) && Math.abs(shown - l.z) < 1e-12 ? ' bm-shown' : ''}`, x1: box.left, x2: right, y1: yz(l.z), y2: yz(l.z), 'data-z': l.z,
    }, svg('title', {}, `The ring at the layer z = ${mm(l.z)} mm${isNum(shown) && Math.abs(shown - l.z) < 1e-12 ? ' (the result shown)' : ''}`)))));
    const at = isNum(shown) ? shown : first;
    heightMark.push(svg('text', { class: 'tick halo bm-label', x: box.left + 6, y: yz(at) + (at === first ? 16 : -5) },
      isNum(shown) ? `ring at every layer; shown: z = ${mm(shown)} mm` : 'ring at every layer'));
  }
  const travelMark = travelOk ? [
    svg('rect', {
      id: `${id}-travel`, class: `bm-travel${covered ? '' : ' bm-uncovered'}`, x: box.left, width: box.width,
      y: yz(travel[0]), height: Math.max(0, yz(travel[1]) - yz(travel[0])), 'data-z0': travel[0], 'data-z1': travel[1],
    }, svg('title', {}, `The ring's travel: ${mm(travel[0])} mm (TDC) to ${mm(travel[1])} mm (BDC)${covered ? '' : ', beyond the map'}`)),
    svg('text', { class: 'tick halo bm-label', x: right - 6, y: yz(travel[0]) + 16, 'text-anchor': 'end' }, `TDC ${mm(travel[0])} mm`),
    svg('text', { class: 'tick halo bm-label', x: right - 6, y: yz(travel[1]) - 6, 'text-anchor': 'end' }, `BDC ${mm(travel[1])} mm`),
  ] : [];

  const items = [];
  if (travelOk) items.push([svg('rect', { class: 'bm-travel', x: 0, y: -5, width: 10, height: 10 }), 'ring travel']);
  if (isNum(height) || height === 'all') items.push([svg('path', { class: 'bm-height', d: 'M-2,0H12' }), 'ring height']);
  items.push([svg('path', { class: 'bm-layer', d: 'M0,-5V5' }), 'layer']);
  if (outside) items.push([svg('rect', { x: -2, y: -5, width: 14, height: 10, fill: `url(#${hatch})`, stroke: '#9aa3ad' }), 'no map']);

  const range = L > 0 ? `${sig(-L, 3)} to +${sig(L, 3)} µm` : '0 µm everywhere (the layers are one round bore)';
  const label = `Bore map: the radius's departure from the first layer's mean radius, ${range}, ` +
    `over the angle from the gap (0 to 360°) and the depth z ${mm(first)} to ${mm(last)} mm (${layers.length} layer${layers.length === 1 ? '' : 's'})` +
    (travelOk ? `; the ring's travel ${mm(travel[0])} to ${mm(travel[1])} mm (TDC to BDC)${covered ? '' : ', beyond the map'}` : '') +
    (isNum(height) ? `; the ring at z = ${mm(height)} mm` : height === 'all' ? '; the ring at every layer' : '') + '.';

  return svg('svg', {
    id, class: 'chart bore-map', viewBox: `0 0 ${W} ${H}`, role: 'img', 'aria-label': label,
    'data-zmin': z0, 'data-zmax': z1, 'data-box': [box.left, box.top, box.width, box.height].join(' '), 'data-limit-um': L,
  },
  defs,
  legend(items, { x: box.left, y: 14 }),
  outside ? svg('rect', { x: box.left, y: box.top, width: box.width, height: box.height, fill: `url(#${hatch})` }) : null,
  svg('image', {
    href: mapImage(layers, z0, z1, limit), x: box.left, y: box.top, width: box.width, height: box.height,
    preserveAspectRatio: 'none', class: 'bm-image',
  }),
  axes({
    box, x, y, xTicks: [0, 90, 180, 270, 360], yTicks: ticks(z0 * 1e3, z1 * 1e3, 5),
    xLabel: 'angle from the gap θ (deg)', yLabel: 'depth z (mm)', yFormat: (v) => String(Number(v.toPrecision(6))),
  }),
  svg('rect', { class: 'bm-frame', x: box.left, y: box.top, width: box.width, height: box.height }),
  svg('g', { id: `${id}-layers` }, layers.map((l) => svg('path', {
    class: 'bm-layer', d: `M${box.left},${yz(l.z).toFixed(2)}h9M${right},${yz(l.z).toFixed(2)}h-9`, 'data-z': l.z,
  }, svg('title', {}, `Layer at z = ${mm(l.z)} mm`)))),
  travelMark,
  heightMark,
  svg('rect', { class: 'bm-bar', x: bar.x, y: box.top, width: bar.w, height: box.height, fill: `url(#${grad})` }),
  svg('g', { class: 'bm-bar-ticks' }, barTicks.flatMap((t) => [
    svg('line', { class: 'tickmark', x1: bar.x + bar.w, x2: bar.x + bar.w + 4, y1: yBar(t), y2: yBar(t) }),
    svg('text', { class: 'tick', x: bar.x + bar.w + 6, y: yBar(t), 'dominant-baseline': 'middle' }, `${t > 0 ? '+' : ''}${sig(t, 3)}`),
  ])),
  svg('text', { class: 'tick', x: bar.x - 2, y: box.top - 8 }, 'dr (µm)'));
}

export const MAP_CAPTION = 'Bore map: the radius\'s departure from the first layer\'s mean radius (red outward, blue inward; µm on the bar), ' +
  'against the angle from the gap and the depth down the bore, linear in depth between the layers (marks at the edges).';

// A result's bore map as a figure, or null without one.  `marks`: travel,
// height and shown as boreMapPlot takes them.
export function boreMapFigure(scene, id, marks = {}, caption = '') {
  const layers = scene?.bore?.layers;
  if (!Array.isArray(layers) || !layers.length) return null;
  const plot = boreMapPlot({ layers, diameter: scene.bore.diameter || scene.ring?.diameter, id, ...marks });
  if (!plot) return null;
  return h('figure', { class: 'plot wide bore-map-figure' }, plot, h('figcaption', {}, `${MAP_CAPTION} ${caption}`.trim()));
}

// ---- live drawings in the form ---------------------------------------------

// Each figure[data-bore-map="<list id>"] of the form shows its map while the
// list has layers: data-diameter (ids of inputs, "base" for the loaded
// scene's /bore/diameter: the first > 0 is the diameter of layers without
// one), data-travel ("<ring depth id> <crank radius id>") or data-height
// (the height input's id; its data-word-for checkbox means "all").
export function setupBoreMaps(form) {
  const figures = [...form.form.querySelectorAll('figure[data-bore-map]')];
  let queued = false;
  const redraw = () => {
    if (queued) return;
    queued = true;
    requestAnimationFrame(() => {
      queued = false;
      for (const fig of figures) drawLive(form, fig);
    });
  };
  for (const fig of figures) watchCharts(fig);
  for (const type of ['input', 'change', 'formchange']) form.form.addEventListener(type, redraw);
  redraw();
}

const num = (id) => {
  const v = document.getElementById(id)?.valueAsNumber;
  return Number.isFinite(v) ? v : null;
};

function drawLive(form, fig) {
  const list = document.getElementById(fig.dataset.boreMap);
  let layers;
  let problem = null;
  try {
    layers = list ? form.readList(list) : [];
  } catch (err) {
    const input = err.path ? form.form.querySelector(`[data-path="${err.path}"]`) : null;
    const name = input ? form.form.querySelector(`label[for="${input.id}"]`)?.textContent : null;
    problem = `${name ? `${name}: ` : ''}${err.message}`;
    layers = null;
  }
  if (layers && !layers.length) {
    fig.hidden = true;
    fig.replaceChildren();
    return;
  }
  fig.hidden = false;
  const base = form.base?.bore?.diameter;
  const diameter = (fig.dataset.diameter || '').split(/\s+/).filter(Boolean)
    .map((d) => (d === 'base' ? (Number(base) > 0 ? Number(base) : null) : num(d))).find((d) => d > 0);
  let travel = null, height = null;
  if (fig.dataset.travel) {
    const [z, r] = fig.dataset.travel.split(/\s+/).map(num);
    if (z !== null && r !== null) travel = [z, z + 2 * r];
  }
  if (fig.dataset.height) {
    const all = form.form.querySelector(`[data-word-for="${fig.dataset.height}"]`);
    height = all?.checked ? all.dataset.word : num(fig.dataset.height);
  }
  const checked = layers ? mapLayers(layers, diameter) : null;
  if (!problem && checked.error) problem = checked.error;
  const msgId = `${fig.id}-msg`;
  if (problem) {
    fig.replaceChildren(h('p', { class: 'hint', id: msgId }, `The bore map is drawn once it is complete: ${problem}.`));
    return;
  }
  const id = `${fig.id}-plot`;
  const covered = !travel || (travel[0] >= checked.layers[0].z - 1e-12 && travel[1] <= checked.layers.at(-1).z + 1e-12);
  fig.replaceChildren(
    boreMapPlot({ layers, diameter, travel, height, id, width: 480, aspect: 0.72 }),
    h('figcaption', { id: msgId },
      'The map as entered: the radius\'s departure from the first layer\'s mean radius (red outward, blue inward), against the angle from the gap and the depth (down). ',
      travel ? (covered ? 'Dashed band: the ring\'s travel, TDC to BDC.' : h('strong', {}, 'The ring\'s travel (dashed band) leaves the map: the layers must cover it.')) : null,
      fig.dataset.height && height !== null ? 'Line: the ring\'s height.' : null));
}
