// Small helpers to draw charts as inline SVG (no library).

const NS = 'http://www.w3.org/2000/svg';

// svg('circle', {cx: 1, r: 2}, child...) -> SVGElement.  Strings become text nodes.
export function svg(tag, attrs = {}, ...children) {
  const node = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v !== undefined && v !== null && v !== false) node.setAttribute(k, String(v));
  }
  for (const c of children.flat()) {
    if (c !== null && c !== undefined && c !== false) node.append(c);
  }
  return node;
}

// Linear map from [d0, d1] to [r0, r1]; f.domain, f.range and f.invert
// (screen back to data) let charts.js read values off a drawn chart.
export function scale(d0, d1, r0, r1) {
  const k = d1 === d0 ? 0 : (r1 - r0) / (d1 - d0);
  const f = (v) => r0 + (v - d0) * k;
  f.domain = [d0, d1];
  f.range = [r0, r1];
  f.invert = (p) => (k === 0 ? d0 : d0 + (p - r0) / k);
  return f;
}

// What axes() drew with, by its <g>: charts.js reads values off the chart
// (hover readout), zooms it (redraws the axes at a new range) and draws a
// kept run over it.  Only scales from scale() can be read back.
const plots = new WeakMap();
export function plotOf(axesGroup) {
  return plots.get(axesGroup) ?? null;
}

// About `count` round tick values (1, 2, 5 x 10^k steps) covering [lo, hi].
export function ticks(lo, hi, count = 5) {
  if (!(hi > lo)) return [lo];
  const raw = (hi - lo) / count;
  const mag = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * mag).find((s) => s >= raw);
  const out = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) {
    out.push(Math.abs(v) < step * 1e-9 ? 0 : v);
  }
  return out;
}

// The marker of each mode kind: different shape *and* colour so the chart
// also reads in grey scale.  (x, y) is the centre, s the half size.
export function kindMarker(kind, x, y, s = 5, attrs = {}) {
  // data-cx / data-cy: the centre, where charts.js reads the value.
  if (kind === 'in_plane') {
    return svg('circle', { cx: x, cy: y, r: s, class: 'mk mk-in', 'data-name': 'in-plane', ...attrs });
  }
  const h = s * 1.15;
  return svg('path', {
    d: `M${x},${y - h * 1.15}L${x + h},${y + h * 0.85}L${x - h},${y + h * 0.85}Z`,
    class: 'mk mk-out',
    'data-name': 'out-of-plane',
    'data-cx': x,
    'data-cy': y,
    ...attrs,
  });
}

// A tiny inline SVG holding one marker, for legends in HTML text.
export function markerIcon(kind) {
  return svg('svg', { class: 'icon', viewBox: '0 0 14 14', width: 14, height: 14, 'aria-hidden': 'true' },
    kindMarker(kind, 7, 7.5, 4.5));
}

// Axes with ticks, grid and labels for a plot area inside `box`
// ({left, top, width, height}); returns a <g>.
export function axes(args) {
  const { box, x, y, xTicks, yTicks, xLabel, yLabel, xFormat = String, yFormat = String } = args;
  const g = svg('g', { class: 'axes' });
  plots.set(g, args);
  const bottom = box.top + box.height;
  const right = box.left + box.width;
  for (const t of yTicks) {
    const py = y(t);
    g.append(svg('line', { x1: box.left, x2: right, y1: py, y2: py, class: 'grid' }));
    g.append(svg('text', { x: box.left - 6, y: py, class: 'tick', 'text-anchor': 'end', 'dominant-baseline': 'middle' }, yFormat(t)));
  }
  for (const t of xTicks) {
    const px = x(t);
    g.append(svg('line', { x1: px, x2: px, y1: bottom, y2: bottom + 4, class: 'tickmark' }));
    // Offsets in em: they grow with the text (charts.js enlarges it on narrow screens).
    g.append(svg('text', { x: px, y: bottom + 6, dy: '0.8em', class: 'tick', 'text-anchor': 'middle' }, xFormat(t)));
  }
  g.append(svg('path', { d: `M${box.left},${box.top}V${bottom}H${right}`, class: 'axis' }));
  g.append(svg('text', { x: box.left + box.width / 2, y: bottom + 6, dy: '2.05em', class: 'label', 'text-anchor': 'middle' }, xLabel));
  // data-left / data-mid: charts.js moves it left of wider tick labels.
  g.append(svg('text', {
    x: 0, y: 0, class: 'label ylabel', 'text-anchor': 'middle', 'data-left': box.left, 'data-mid': box.top + box.height / 2,
    transform: `translate(${box.left - 46},${box.top + box.height / 2}) rotate(-90)`,
  }, yLabel));
  return g;
}

// Path data through `points` ([[x, y], ...]): "M x,y L x,y ..."; `close` adds Z.
// Non-finite points break the line (a new M starts after them).
export function pathD(points, close = false) {
  let d = '';
  let pen = false;
  for (const [px, py] of points) {
    if (!Number.isFinite(px) || !Number.isFinite(py)) { pen = false; continue; }
    d += `${pen ? 'L' : 'M'}${px.toFixed(2)},${py.toFixed(2)}`;
    pen = true;
  }
  return d && close ? `${d}Z` : d;
}

// Ticks at multiples of the first of `steps` that gives at most `max` of
// them over [lo, hi] (e.g. crank angle: every 90 or 180 deg).
export function stepTicks(lo, hi, steps, max = 12) {
  const step = steps.find((s) => (hi - lo) / s <= max) ?? steps[steps.length - 1];
  const out = [];
  for (let v = Math.ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step) out.push(v);
  return out;
}

// The point at angle `deg` and radius `r` around (cx, cy) on screen: 0 deg
// points right, angles grow counter-clockwise (as x, y with y up).
export function polar(cx, cy, r, deg) {
  const t = (deg * Math.PI) / 180;
  return [cx + r * Math.cos(t), cy - r * Math.sin(t)];
}

// A legend: a row of [swatch element, text] items from (x, y), spaced by the
// length of their text.  Each swatch is drawn around (0, 0), about 12 px wide.
// Where the text is enlarged (charts.js), the items wrap into rows: above the
// first row, or below it with wrap = 'down'.
export function legend(items, { x = 0, y = 0, id, wrap = 'up' } = {}) {
  const g = svg('g', { class: 'legend', transform: `translate(${x},${y})`, id, 'data-x': x, 'data-wrap': wrap });
  let at = 0;
  for (const [swatch, text] of items) {
    g.append(svg('g', { transform: `translate(${at},0)` }, swatch,
      svg('text', { x: 14, y: 0, 'dominant-baseline': 'middle' }, text)));
    at += 14 + 7.2 * text.length + 16;
  }
  return g;
}
