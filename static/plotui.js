// Hover values, zoom and a kept run on every chart drawn with svg.js axes().
//
// Values are read back off the drawn chart: axes() keeps its scales
// (svg.js plotOf), and every open polyline of the plot (pathD's M/L paths)
// is a series, inverted through them to data; a chart without lines offers
// its markers (circles, kindMarker's triangles) instead.  So every view gets
// this without telling it its data, and the numbers are the drawn ones: to
// 0.01 viewBox units, a few 1e-5 of the axis span, shown to 1e-3 of it
// (finer would show the drawing's rounding: 17.999 for 18).
//
//   hover / touch   a readout of the nearest point of each series (x, y)
//   drag            zooms to the dragged range of x (and of y when the box is
//                   taller than 10 px); Ctrl + wheel zooms x about the pointer
//   double-click    back to the whole range (also the Reset zoom button)
//
// Zooming keeps the drawing: each plot element's coordinates are mapped by
// the zoom's affine map (exact for linear scales; markers keep their size),
// clipped to the plot box, and the axes are drawn again at the new range.
//
// keepRun() / overlayKept(): a result's series kept in data units and drawn
// dashed over a later result's charts of the same id or data-compare key
// (compare runs).

import { svg, scale, ticks, axes, plotOf, pathD } from './svg.js';

const states = new WeakMap();
let clipIds = 0;

const GEOMETRY = {
  x: ['cx', 'x', 'x1', 'x2', 'data-cx'],
  y: ['cy', 'y', 'y1', 'y2', 'data-cy'],
};
const SKIP = '.axes, .legend, title, desc, defs, .hover-layer, .zoom-box, .kept-label';

// The one <g class="axes"> of a chart with invertible scales, or null.
function plotGroup(s) {
  const groups = [...s.children].filter((c) => c.classList?.contains('axes'));
  if (groups.length !== 1) return null;
  const p = plotOf(groups[0]);
  return p && p.x?.invert && p.y?.invert ? groups[0] : null;
}

// The chart's state, made on first use; null for a chart without axes().
export function chartState(s) {
  if (states.has(s)) return states.get(s);
  const g = plotGroup(s);
  if (!g) return null;
  const st = { s, axesG: g, plot: plotOf(g), zoom: null, orig: new Map(), series: null, clip: null, button: null };
  states.set(s, st);
  return st;
}

// ---- reading series off the drawing ---------------------------------------

// [[x, y], ...] of a path made of absolute M/L commands only, else null.
function polyline(d) {
  if (!d || /[^MLml\d\s,.eE+-]/.test(d) || /[ml]/.test(d)) return null;
  const nums = d.match(/[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?/g) || [];
  if (nums.length % 2) return null;
  const pts = [];
  for (let i = 0; i < nums.length; i += 2) pts.push([Number(nums[i]), Number(nums[i + 1])]);
  return pts;
}

const attr = (st, el, name) => {
  const o = st.orig.get(el);
  return o && name in o ? o[name] : el.getAttribute(name);
};

const nameOf = (el) => el.dataset.name || el.closest('[data-name]')?.dataset.name ||
  el.id || [...el.classList].join(' ') || el.tagName;

// The chart's series in data units: [{name, kind: 'line'|'points', points}].
export function seriesOf(st) {
  if (st.series) return st.series;
  const { x, y } = st.plot;
  const toData = ([px, py]) => [x.invert(px), y.invert(py)];
  const inPlot = (el) => !el.closest(SKIP) && !el.closest('.kept');
  const lines = [];
  for (const el of st.s.querySelectorAll('path')) {
    if (!inPlot(el)) continue;
    const pts = polyline(attr(st, el, 'd'));
    if (pts && pts.length >= 2) lines.push({ name: nameOf(el), kind: 'line', points: pts.map(toData) });
  }
  let out = lines;
  if (!lines.length) {
    const groups = new Map();
    for (const el of st.s.querySelectorAll('circle, path[data-cx]')) {
      if (!inPlot(el) || el.classList.contains('halo') || el.classList.contains('grid')) continue;
      const cx = Number(attr(st, el, el.tagName === 'circle' ? 'cx' : 'data-cx'));
      const cy = Number(attr(st, el, el.tagName === 'circle' ? 'cy' : 'data-cy'));
      if (!Number.isFinite(cx) || !Number.isFinite(cy)) continue;
      const name = nameOf(el);
      if (!groups.has(name)) groups.set(name, { name, kind: 'points', points: [] });
      groups.get(name).points.push(toData([cx, cy]));
    }
    out = [...groups.values()];
  }
  st.series = out;
  return out;
}

// ---- formatting -----------------------------------------------------------

// `v` to about 1e-3 of `span` (the drawing holds a few 1e-5 of it).
export function formatValue(v, span) {
  if (!Number.isFinite(v)) return '—';
  const res = Math.abs(span) * 1e-3 || Math.abs(v) * 1e-3 || 1e-12;
  if (Math.abs(v) < res) return '0';
  const digits = Math.floor(Math.log10(Math.abs(v))) - Math.floor(Math.log10(res)) + 1;
  return String(Number(v.toPrecision(Math.min(12, Math.max(1, digits)))));
}

// ---- zoom -----------------------------------------------------------------

// The scales now shown (zoomed or not).
function shownScales(st) {
  const { x, y } = st.plot;
  if (!st.zoom) return { x, y };
  return {
    x: scale(st.zoom.x[0], st.zoom.x[1], x.range[0], x.range[1]),
    y: scale(st.zoom.y[0], st.zoom.y[1], y.range[0], y.range[1]),
  };
}

// Affine screen map from the original drawing to the zoomed one, per axis.
function affine(from, to) {
  const p0 = from(to.domain[0]), p1 = from(to.domain[1]);
  const k = p1 === p0 ? 1 : (to.range[1] - to.range[0]) / (p1 - p0);
  return (p) => to.range[0] + (p - p0) * k;
}

function mapPath(d, fx, fy) {
  let axis = 'x', cmd = '';
  return d.replace(/([MLHVZmlhvz])|([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)/g, (m, c, n) => {
    if (c) { cmd = c; axis = c === 'V' ? 'y' : 'x'; return c; }
    const v = Number(n);
    const out = axis === 'x' ? fx(v) : fy(v);
    if (cmd === 'M' || cmd === 'L') axis = axis === 'x' ? 'y' : 'x';
    return out.toFixed(2);
  });
}

// The plot's drawn elements: children of the chart but the axes, legend
// and overlays, with their descendants.
function contentOf(st) {
  return [...st.s.children].filter((c) => c instanceof SVGGraphicsElement && !c.matches(SKIP));
}

function remember(st, el) {
  if (st.orig.has(el)) return;
  const o = {};
  for (const a of [...GEOMETRY.x, ...GEOMETRY.y, 'd', 'width', 'height', 'transform', 'clip-path']) {
    if (el.hasAttribute(a)) o[a] = el.getAttribute(a);
  }
  st.orig.set(el, o);
}

function remap(st, el, fx, fy) {
  remember(st, el);
  const o = st.orig.get(el);
  const tag = el.tagName;
  if (tag === 'path' && o.d) {
    if (/^[MLHVZ\d\s,.eE+-]*$/.test(o.d)) el.setAttribute('d', mapPath(o.d, fx, fy));
  } else if (tag === 'rect') {
    const x0 = fx(Number(o.x || 0)), x1 = fx(Number(o.x || 0) + Number(o.width || 0));
    const y0 = fy(Number(o.y || 0)), y1 = fy(Number(o.y || 0) + Number(o.height || 0));
    el.setAttribute('x', Math.min(x0, x1).toFixed(2));
    el.setAttribute('y', Math.min(y0, y1).toFixed(2));
    el.setAttribute('width', Math.abs(x1 - x0).toFixed(2));
    el.setAttribute('height', Math.abs(y1 - y0).toFixed(2));
  } else {
    for (const a of GEOMETRY.x) if (a in o && o[a] !== '') el.setAttribute(a, fx(Number(o[a])).toFixed(2));
    for (const a of GEOMETRY.y) if (a in o && o[a] !== '') el.setAttribute(a, fy(Number(o[a])).toFixed(2));
  }
  const t = /^translate\(\s*([-\d.eE+]+)[\s,]+([-\d.eE+]+)\s*\)$/.exec(o.transform || '');
  if (t) el.setAttribute('transform', `translate(${fx(Number(t[1])).toFixed(2)},${fy(Number(t[2])).toFixed(2)})`);
  for (const c of el.children) if (c instanceof SVGGraphicsElement) remap(st, c, fx, fy);
}

function restore(st) {
  for (const [el, o] of st.orig) {
    for (const a of [...GEOMETRY.x, ...GEOMETRY.y, 'd', 'width', 'height', 'transform', 'clip-path']) {
      if (a in o) el.setAttribute(a, o[a]);
      else if (a === 'clip-path') el.removeAttribute(a);
    }
  }
  st.orig.clear();
}

// A tick formatter that falls back to plain numbers where the view's own
// one cannot name a value (e.g. "#3" for a measurement index).
const safeFormat = (f, span) => (t) => {
  try {
    const r = f(t);
    if (r !== undefined && r !== null && !/undefined|NaN/.test(String(r))) return r;
  } catch { /* below */ }
  return formatValue(t, span);
};

// Ticks of a log axis (drawn at log10 of the value) between the decades.
const logFormat = (log) => (log ? (e) => (Number.isInteger(e) ? `1e${e}` : formatValue(10 ** e, 10 ** e)) : null);

function zoomTicks(lo, hi, original) {
  const t = ticks(lo, hi, 5);
  const integers = original.length > 0 && original.every(Number.isInteger);
  return integers && hi - lo >= 2 ? t.filter(Number.isInteger) : t;
}

function clipFor(st) {
  if (st.clip) return st.clip;
  const { box } = st.plot;
  const id = `plot-clip-${++clipIds}`;
  st.s.append(svg('defs', {}, svg('clipPath', { id }, svg('rect', { x: box.left, y: box.top, width: box.width, height: box.height }))));
  st.clip = `url(#${id})`;
  return st.clip;
}

function redrawAxes(st, xs, ys) {
  const p = st.plot;
  const xSpan = xs.domain[1] - xs.domain[0], ySpan = ys.domain[1] - ys.domain[0];
  const zoomed = Boolean(st.zoom);
  const g = axes({
    ...p,
    x: xs,
    y: ys,
    xTicks: zoomed ? zoomTicks(Math.min(...xs.domain), Math.max(...xs.domain), p.xTicks) : p.xTicks,
    yTicks: zoomed && st.zoom.yZoomed ? zoomTicks(Math.min(...ys.domain), Math.max(...ys.domain), p.yTicks) : p.yTicks,
    xFormat: zoomed ? logFormat(p.xLog) ?? safeFormat(p.xFormat || String, xSpan) : p.xFormat,
    yFormat: zoomed && st.zoom.yZoomed ? logFormat(p.yLog) ?? safeFormat(p.yFormat || String, ySpan) : p.yFormat,
  });
  st.axesG.replaceWith(g);
  st.axesG = g;
}

// Shows x in [x0, x1] (and y in [y0, y1] when given); null: the whole chart.
export function zoomTo(s, xr, yr = null) {
  const st = chartState(s);
  if (!st) return;
  seriesOf(st); // read before anything moves
  const { x, y } = st.plot;
  if (!xr) {
    restore(st);
    st.zoom = null;
    redrawAxes(st, x, y);
  } else {
    const order = (r, d) => (d[0] <= d[1] ? [Math.min(...r), Math.max(...r)] : [Math.max(...r), Math.min(...r)]);
    // An x-only zoom keeps a y range zoomed before.
    const yNow = yr ?? (st.zoom?.yZoomed ? st.zoom.y : null);
    st.zoom = { x: order(xr, x.domain), y: yNow ? order(yNow, y.domain) : [...y.domain], yZoomed: Boolean(yNow) };
    const z = shownScales(st);
    const fx = affine(x, z.x), fy = affine(y, z.y);
    const clip = clipFor(st);
    for (const el of contentOf(st)) {
      remap(st, el, fx, fy);
      el.setAttribute('clip-path', clip);
    }
    redrawAxes(st, z.x, z.y);
  }
  s.dataset.zoomed = st.zoom ? 'true' : 'false';
  resetButton(st);
  hideHover(st);
  s.dispatchEvent(new CustomEvent('chartzoom', { bubbles: true }));
}

function resetButton(st) {
  if (!st.zoom) {
    st.button?.remove();
    st.button = null;
    return;
  }
  if (st.button?.isConnected) return;
  const b = document.createElement('button');
  b.type = 'button';
  b.className = 'zoom-reset';
  b.textContent = 'Reset zoom';
  b.setAttribute('aria-label', `Reset the zoom of ${st.s.getAttribute('aria-label')?.split(/[:,.]/)[0] || 'the chart'}`);
  b.addEventListener('click', () => zoomTo(st.s, null));
  st.s.after(b);
  st.button = b;
}

// ---- hover ----------------------------------------------------------------

// One readout for the page, beside the pointer (position: fixed): hidden
// when the page scrolls or its chart is redrawn away.
let readout = null, owner = null;
function readoutBox() {
  if (readout?.isConnected) return readout;
  readout = document.createElement('div');
  readout.className = 'chart-readout';
  readout.hidden = true;
  document.body.append(readout);
  addEventListener('scroll', () => { if (owner && !owner.s.matches(':hover')) hideHover(owner); }, { passive: true, capture: true });
  return readout;
}

function hideHover(st) {
  st.s.querySelector(':scope > .hover-layer')?.remove();
  if (readout && owner === st) readout.hidden = true;
}

// Hides a readout whose chart has left the page (charts.js calls it as
// charts come and go).
export function tidyReadout() {
  if (owner && !owner.s.isConnected) {
    if (readout) readout.hidden = true;
    owner = null;
  }
}

// The chart's point under the pointer, in viewBox units.
function svgPoint(s, e) {
  const m = s.getScreenCTM();
  return m ? new DOMPoint(e.clientX, e.clientY).matrixTransform(m.inverse()) : null;
}

function inBox(box, p, margin = 0) {
  return p.x >= box.left - margin && p.x <= box.left + box.width + margin &&
    p.y >= box.top - margin && p.y <= box.top + box.height + margin;
}

// The nearest point of each series to the data point (qx, qy): by x for
// lines, on screen for markers; only points inside the shown x range.
function nearest(st, qx, qy) {
  const z = shownScales(st);
  const [xa, xb] = [Math.min(...z.x.domain), Math.max(...z.x.domain)];
  const out = [];
  for (const se of seriesOf(st)) {
    let best = null, bestD = Infinity;
    for (const [px, py] of se.points) {
      if (!Number.isFinite(px) || !Number.isFinite(py) || px < xa || px > xb) continue;
      const d = se.kind === 'line' ? Math.abs(px - qx) : Math.hypot(z.x(px) - z.x(qx), z.y(py) - z.y(qy));
      if (d < bestD) { bestD = d; best = [px, py]; }
    }
    // A log axis (sweep.js) is drawn at log10 of the value.
    const [bx, by] = [st.plot.xLog ? 10 ** best?.[0] : best?.[0], st.plot.yLog ? 10 ** best?.[1] : best?.[1]];
    if (best) out.push({ name: se.name, x: bx, y: by, at: best, kept: Boolean(se.kept) });
  }
  return out;
}

function showHover(st, e) {
  const p = svgPoint(st.s, e);
  if (!p || !inBox(st.plot.box, p, 4)) { hideHover(st); return; }
  const z = shownScales(st);
  const hits = nearest(st, z.x.invert(p.x), z.y.invert(p.y));
  if (!hits.length) { hideHover(st); return; }
  const { box } = st.plot;
  const layer = svg('g', { class: 'hover-layer', 'pointer-events': 'none' },
    svg('line', { class: 'hover-guide', x1: p.x, x2: p.x, y1: box.top, y2: box.top + box.height }),
    hits.map((h) => svg('circle', { class: `hover-dot${h.kept ? ' kept-dot' : ''}`, cx: z.x(h.at[0]), cy: z.y(h.at[1]), r: 4 })));
  st.s.querySelector(':scope > .hover-layer')?.remove();
  st.s.append(layer);

  const r = readoutBox();
  const span = (f, log, v) => (log ? v : f.domain[1] - f.domain[0]);
  const cell = (tag, text, cls) => { const c = document.createElement(tag); c.textContent = text; if (cls) c.className = cls; return c; };
  const table = document.createElement('table');
  const head = document.createElement('tr');
  head.append(cell('th', ''), cell('th', st.plot.xLabel || 'x'), cell('th', st.plot.yLabel || 'y'));
  table.append(head);
  for (const h of hits) {
    const tr = document.createElement('tr');
    tr.dataset.x = String(h.x);
    tr.dataset.y = String(h.y);
    tr.dataset.series = h.name;
    if (h.kept) tr.className = 'kept-row';
    tr.append(cell('th', h.name), cell('td', formatValue(h.x, span(z.x, st.plot.xLog, h.x)), 'rx'),
      cell('td', formatValue(h.y, span(z.y, st.plot.yLog, h.y)), 'ry'));
    table.append(tr);
  }
  r.replaceChildren(table);
  r.dataset.chart = st.s.id || '';
  owner = st;
  r.hidden = false;
  // Beside the pointer, inside the window.
  const w = r.offsetWidth, hgt = r.offsetHeight;
  let left = e.clientX + 14, top = e.clientY + 14;
  if (left + w > innerWidth - 4) left = Math.max(4, e.clientX - w - 14);
  if (top + hgt > innerHeight - 4) top = Math.max(4, e.clientY - hgt - 14);
  r.style.left = `${left}px`;
  r.style.top = `${top}px`;
}

// ---- wiring ---------------------------------------------------------------

function dragBox(st, a, b) {
  let rect = st.s.querySelector(':scope > .zoom-box');
  if (!rect) { rect = svg('rect', { class: 'zoom-box', 'pointer-events': 'none' }); st.s.append(rect); }
  const { box } = st.plot;
  const clampX = (v) => Math.min(box.left + box.width, Math.max(box.left, v));
  const clampY = (v) => Math.min(box.top + box.height, Math.max(box.top, v));
  const x0 = clampX(Math.min(a.x, b.x)), x1 = clampX(Math.max(a.x, b.x));
  const tall = Math.abs(b.clientY - a.clientY) >= 10;
  const y0 = tall ? clampY(Math.min(a.y, b.y)) : box.top, y1 = tall ? clampY(Math.max(a.y, b.y)) : box.top + box.height;
  for (const [k, v] of Object.entries({ x: x0, y: y0, width: x1 - x0, height: y1 - y0 })) rect.setAttribute(k, v.toFixed(2));
  return { x0, x1, y0, y1, tall };
}

// Gives chart `s` its hover readout and zoom (once; charts without axes()
// are left alone).
export function interact(s) {
  const st = chartState(s);
  if (!st || st.wired) return;
  st.wired = true;
  s.classList.add('interactive');
  let drag = null;
  s.addEventListener('pointerdown', (e) => {
    if (e.button !== 0) return;
    const p = svgPoint(s, e);
    if (!p || !inBox(st.plot.box, p)) return;
    drag = { x: p.x, y: p.y, clientX: e.clientX, clientY: e.clientY, id: e.pointerId };
    if (e.pointerType === 'mouse') e.preventDefault(); // no text selection
    else showHover(st, e); // a tap has no move before it
  });
  s.addEventListener('pointermove', (e) => {
    showHover(st, e);
    if (!drag || e.pointerId !== drag.id) return;
    if (Math.abs(e.clientX - drag.clientX) < 6) return;
    const p = svgPoint(s, e);
    if (p) {
      if (!s.hasPointerCapture?.(e.pointerId)) s.setPointerCapture?.(e.pointerId);
      dragBox(st, drag, { x: p.x, y: p.y, clientX: e.clientX, clientY: e.clientY });
    }
  });
  const end = (e, apply) => {
    if (!drag || e.pointerId !== drag.id) return;
    const a = drag;
    drag = null;
    s.querySelector(':scope > .zoom-box')?.remove();
    const p = svgPoint(s, e);
    if (!apply || !p || Math.abs(e.clientX - a.clientX) < 6) return;
    const b = dragBox(st, a, { x: p.x, y: p.y, clientX: e.clientX, clientY: e.clientY });
    s.querySelector(':scope > .zoom-box')?.remove();
    if (b.x1 - b.x0 < 1) return;
    const z = shownScales(st);
    zoomTo(s, [z.x.invert(b.x0), z.x.invert(b.x1)], b.tall ? [z.y.invert(b.y1), z.y.invert(b.y0)] : null);
    // The click that ends a drag is not a click on what it ends over (a mode's marker).
    st.dragged = true;
    setTimeout(() => { st.dragged = false; }, 0);
  };
  s.addEventListener('click', (e) => {
    if (st.dragged) { e.stopPropagation(); e.preventDefault(); st.dragged = false; }
  }, true);
  s.addEventListener('pointerup', (e) => end(e, true));
  s.addEventListener('pointercancel', (e) => end(e, false));
  s.addEventListener('pointerleave', (e) => { if (e.pointerType === 'mouse' && !drag) hideHover(st); });
  s.addEventListener('dblclick', (e) => {
    if (!st.zoom) return;
    e.preventDefault();
    zoomTo(s, null);
  });
  s.addEventListener('wheel', (e) => {
    if (!(e.ctrlKey || e.metaKey) || !e.deltaY) return;
    const p = svgPoint(s, e);
    if (!p || !inBox(st.plot.box, p)) return;
    e.preventDefault();
    const z = shownScales(st);
    const at = z.x.invert(p.x);
    const f = e.deltaY < 0 ? 1 / 1.25 : 1.25;
    const [d0, d1] = z.x.domain;
    const full = st.plot.x.domain;
    const lo = at + (d0 - at) * f, hi = at + (d1 - at) * f;
    const wider = Math.abs(hi - lo) >= Math.abs(full[1] - full[0]);
    if (wider && !st.zoom?.yZoomed) zoomTo(s, null);
    else zoomTo(s, wider ? full : [lo, hi]);
  }, { passive: false });
}

// ---- a kept run -------------------------------------------------------------

let kept = null; // {key, label, charts: Map(compareKey -> series)}

// What a chart shows, to match it with a kept one: its id, or its
// data-compare (a view whose chart of one id shows different things, e.g.
// the shape of the mode selected).
const compareKey = (s) => s.dataset.compare || s.id;

// Keeps the series of every chart (with an id) under `root` as run `label`
// of `key` (an analysis); overlayKept draws them over later charts.
export function keepRun(root, key, label) {
  const charts = new Map();
  for (const s of root.querySelectorAll('svg[id]')) {
    const st = chartState(s);
    if (!st) continue;
    const series = seriesOf(st).filter((se) => !se.kept);
    if (series.length) charts.set(compareKey(s), series.map((se) => ({ ...se, points: se.points.map((p) => [...p]) })));
  }
  kept = { key, label, charts };
  return charts.size;
}

export function keptRun() {
  return kept ? { key: kept.key, label: kept.label, charts: [...kept.charts.keys()] } : null;
}

export function clearKept(root) {
  kept = null;
  for (const s of root?.querySelectorAll('svg[id]') ?? []) {
    const st = chartState(s);
    if (!st) continue;
    if (st.zoom) zoomTo(s, null);
    for (const el of s.querySelectorAll(':scope > .kept, :scope > .kept-label')) el.remove();
    if (st.series) st.series = st.series.filter((se) => !se.kept);
    delete s.dataset.kept;
  }
}

// Draws the kept run (when it is of `key`) dashed under the series of each
// chart below `root` that has the same id; returns how many charts got it.
export function overlayKept(root, key) {
  if (!kept || kept.key !== key) return 0;
  let n = 0;
  for (const s of root.querySelectorAll('svg[id]')) {
    const series = kept.charts.get(compareKey(s));
    const st = series && chartState(s);
    if (!st || s.dataset.kept) continue;
    if (st.zoom) zoomTo(s, null);
    seriesOf(st);
    const { x, y, box } = st.plot;
    const clip = clipFor(st);
    const drawn = series.map((se) => (se.kind === 'line'
      ? svg('path', { class: 'kept', 'clip-path': clip, 'data-name': `${se.name} (${kept.label})`, d: pathD(se.points.map(([a, b]) => [x(a), y(b)])) })
      : svg('g', { class: 'kept', 'clip-path': clip, 'data-name': `${se.name} (${kept.label})` },
        se.points.map(([a, b]) => svg('circle', { class: 'kept-pt', cx: x(a).toFixed(2), cy: y(b).toFixed(2), r: 6 })))));
    st.axesG.after(...drawn);
    s.append(svg('text', { class: 'kept-label tick halo', x: box.left + box.width - 4, y: box.top + 4, dy: '0.8em', 'text-anchor': 'end' }, `dashed: ${kept.label}`));
    st.series.push(...series.map((se) => ({ ...se, name: `${se.name} (${kept.label})`, kept: true })));
    s.dataset.kept = kept.label;
    n += 1;
  }
  return n;
}
