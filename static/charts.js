// Charts on any screen, and charts as files.
//
// Readable text: each chart is SVG drawn in a fixed viewBox and scaled to its
// box, so its text scales too (13 units in a 720-unit lift plot would be 6 px
// on a 390 px phone).  watchCharts() gives every chart the CSS variable
// --k = viewBox units per CSS px, and style.css sets its text to
// max(13 units, 10.5 px * k): never below 10.5 px on screen.  Larger text
// needs room, so then legends wrap into rows, a y-axis label moves left of
// its tick labels, and the viewBox grows to hold what sticks out (the chart
// gets a little taller; nothing is cut off).
//
// Export: a figure's charts as one standalone SVG file (the page's CSS
// written into each element, so it looks the same outside the page) or as a
// PNG drawn from that SVG at twice its size.

import { saveBlob } from './script.js';
import { interact, tidyReadout } from './plotui.js';

const NS = 'http://www.w3.org/2000/svg';
const CHARTS = 'svg[viewBox]:not(.icon)';

const known = new WeakSet();
const resize = new ResizeObserver((entries) => { for (const e of entries) fit(e.target); });

// Fits every chart below `root` now and whenever it is added or resized;
// onAdded() runs after charts were added (e.g. to give them export buttons).
export function watchCharts(root, onAdded = () => {}) {
  const scan = () => {
    tidyReadout();
    let added = false;
    for (const s of root.querySelectorAll(CHARTS)) {
      if (known.has(s)) continue;
      known.add(s);
      s.dataset.viewBox = s.getAttribute('viewBox');
      resize.observe(s);
      interact(s); // hover readout and zoom (plotui.js)
      added = true;
    }
    if (added) onAdded();
  };
  new MutationObserver(scan).observe(root, { childList: true, subtree: true });
  scan();
}

function fit(s) {
  // Removed (a chart redrawn as its inputs change): no longer watched.
  if (!s.isConnected) { resize.unobserve(s); return; }
  const width = s.getBoundingClientRect().width;
  if (width < 1) return; // hidden: fitted when shown
  const [x0, y0, w, h] = s.dataset.viewBox.split(/[\s,]+/).map(Number);
  let vb = [x0, y0, w, h];
  // Growing the viewBox shrinks the scale, which grows the text: 3 rounds settle it.
  for (let round = 0; round < 3; round++) {
    s.style.setProperty('--k', (vb[2] / width).toFixed(4));
    for (const g of s.querySelectorAll('.legend')) layoutLegend(g, x0 + w);
    for (const t of s.querySelectorAll('text.ylabel')) layoutYLabel(t);
    const b = contentBox(s);
    const pad = 2 * (vb[2] / width);
    const left = Math.min(x0, b.x0 - pad), top = Math.min(y0, b.y0 - pad);
    const next = [left, top, Math.max(x0 + w, b.x1 + pad) - left, Math.max(y0 + h, b.y1 + pad) - top];
    const same = next.every((v, i) => Math.abs(v - vb[i]) < 0.5);
    vb = next;
    if (same) break;
  }
  // Within half a unit of the box shown: kept.  Setting it would resize the
  // chart, whose next fit can land back here (0.1-0.2 units apart: a chart
  // that never settles, seen with the ring pack's friction chart at 390 px).
  const now = (s.getAttribute('viewBox') || '').split(/[\s,]+/).map(Number);
  if (now.length === 4 && vb.every((v, i) => Math.abs(v - now[i]) < 0.5)) return;
  s.setAttribute('viewBox', vb.map((v) => Number(v.toFixed(1))).join(' '));
}

// The box of what is drawn in `s`, in its viewBox units.
function contentBox(s) {
  const inv = s.getScreenCTM()?.inverse();
  const box = { x0: Infinity, y0: Infinity, x1: -Infinity, y1: -Infinity };
  if (!inv) return box;
  for (const el of s.children) {
    if (!(el instanceof SVGGraphicsElement)) continue;
    const r = el.getBoundingClientRect();
    if (r.width === 0 && r.height === 0) continue;
    for (const [px, py] of [[r.left, r.top], [r.right, r.bottom]]) {
      const p = new DOMPoint(px, py).matrixTransform(inv);
      box.x0 = Math.min(box.x0, p.x); box.x1 = Math.max(box.x1, p.x);
      box.y0 = Math.min(box.y0, p.y); box.y1 = Math.max(box.y1, p.y);
    }
  }
  return box;
}

const fontSize = (el) => parseFloat(getComputedStyle(el).fontSize) || 13;

// Legend items (svg.js legend()) in rows that fit before `right`; a legend
// at the top of a chart adds its extra rows above the first, else below.
function layoutLegend(g, right) {
  const items = [...g.children].filter((c) => c.tagName === 'g');
  const text = g.querySelector('text');
  if (!items.length || !text) return;
  const fs = fontSize(text);
  const avail = right - Number(g.dataset.x || 0) - 4;
  let at = 0, row = 0;
  const placed = items.map((it) => {
    const wItem = it.getBBox().width;
    if (at > 0 && at + wItem > avail) { row += 1; at = 0; }
    const p = [it, at, row];
    at += wItem + fs * 1.2;
    return p;
  });
  const up = g.dataset.wrap !== 'down';
  for (const [it, x, r] of placed) it.setAttribute('transform', `translate(${x.toFixed(1)},${((up ? r - row : r) * fs * 1.5).toFixed(1)})`);
}

// The rotated y-axis label of svg.js axes(), just left of the widest tick label.
function layoutYLabel(t) {
  const ticks = [...t.parentNode.querySelectorAll('text.tick[text-anchor="end"]')];
  const widest = Math.max(0, ...ticks.map((k) => k.getBBox().width));
  const x = Number(t.dataset.left) - 6 - widest - 0.7 * fontSize(t);
  t.setAttribute('transform', `translate(${x.toFixed(1)},${t.dataset.mid}) rotate(-90)`);
}

// ---- export ---------------------------------------------------------------

// What the page's CSS sets on chart elements, written into the exported file.
const STYLE_PROPS = ['fill', 'fill-opacity', 'stroke', 'stroke-width', 'stroke-dasharray', 'stroke-opacity',
  'stroke-linejoin', 'opacity', 'font-size', 'font-family', 'font-weight', 'font-style', 'paint-order'];

function inlineStyles(from, to) {
  const cs = getComputedStyle(from);
  to.setAttribute('style', STYLE_PROPS.map((p) => `${p}:${cs.getPropertyValue(p)}`).join(';'));
  to.removeAttribute('class');
  for (let i = 0; i < from.children.length; i++) inlineStyles(from.children[i], to.children[i]);
}

// The charts of `figure` stacked into one standalone SVG document:
// {text, width, height} (width and height in viewBox units).
export function figureSvg(figure) {
  const charts = [...figure.querySelectorAll(CHARTS)].filter((s) => !s.parentNode.closest('svg'));
  const boxes = charts.map((s) => s.viewBox.baseVal);
  const width = Math.max(...boxes.map((b) => b.width));
  const height = boxes.reduce((sum, b) => sum + b.height, 0);
  const out = document.createElementNS(NS, 'svg');
  out.setAttribute('xmlns', NS);
  out.setAttribute('width', width);
  out.setAttribute('height', height);
  out.setAttribute('viewBox', `0 0 ${width} ${height}`);
  const title = document.createElementNS(NS, 'title');
  title.textContent = charts.map((c) => c.getAttribute('aria-label')).filter(Boolean).join(' ');
  out.append(title);
  const bg = document.createElementNS(NS, 'rect');
  for (const [k, v] of Object.entries({ width, height, fill: '#fff' })) bg.setAttribute(k, v);
  out.append(bg);
  let y = 0;
  charts.forEach((s, i) => {
    // The pointer's marks are not the figure's.
    for (const el of s.querySelectorAll(':scope > .hover-layer, :scope > .zoom-box')) el.remove();
    const copy = s.cloneNode(true);
    inlineStyles(s, copy);
    copy.removeAttribute('style'); // the outer box's CSS size
    const b = boxes[i];
    for (const [k, v] of Object.entries({ x: 0, y, width: b.width, height: b.height })) copy.setAttribute(k, v);
    out.append(copy);
    y += b.height;
  });
  return { text: `<?xml version="1.0" encoding="UTF-8"?>\n${new XMLSerializer().serializeToString(out)}\n`, width, height };
}

export function saveSvg(figure, name) {
  saveBlob(new Blob([figureSvg(figure).text], { type: 'image/svg+xml' }), `${name}.svg`);
}

export async function savePng(figure, name, scale = 2) {
  const { text, width, height } = figureSvg(figure);
  const img = new Image();
  img.src = `data:image/svg+xml;charset=utf-8,${encodeURIComponent(text)}`;
  await img.decode();
  const canvas = document.createElement('canvas');
  canvas.width = Math.round(width * scale);
  canvas.height = Math.round(height * scale);
  canvas.getContext('2d').drawImage(img, 0, 0, canvas.width, canvas.height);
  const blob = await new Promise((resolve) => canvas.toBlob(resolve, 'image/png'));
  if (!blob) throw new Error('the browser could not draw the PNG');
  saveBlob(blob, `${name}.png`);
}

// Download buttons (SVG, PNG) under every figure of `root`: each <figure>,
// and each element marked data-figure (a view whose chart is redrawn).
export function addExportButtons(root, baseName) {
  for (const fig of root.querySelectorAll('figure, [data-figure]')) {
    if (!fig.querySelector(CHARTS) || fig.querySelector(':scope > .export')) continue;
    const id = fig.querySelector(CHARTS).id || 'figure';
    const bar = document.createElement('p');
    bar.className = 'export';
    bar.append('Download figure: ');
    for (const kind of ['SVG', 'PNG']) {
      const b = document.createElement('button');
      b.type = 'button';
      b.textContent = kind;
      b.dataset.export = kind.toLowerCase();
      b.setAttribute('aria-label', `Download ${fig.querySelector(CHARTS).getAttribute('aria-label')?.split(/[:,.]/)[0] || 'figure'} as ${kind}`);
      b.addEventListener('click', async () => {
        // The chart shown now (a view may have redrawn it since).
        const name = `${baseName}-${fig.querySelector(CHARTS)?.id || id}`;
        try {
          if (kind === 'SVG') saveSvg(fig, name);
          else await savePng(fig, name);
        } catch (e) {
          b.title = `Failed: ${e.message}`;
        }
      });
      bar.append(b, ' ');
    }
    fig.append(bar);
  }
}
