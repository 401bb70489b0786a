// The modal analysis: renders a modal `result` (API.md) as a summary, a
// frequency plot, a table of modes and the shape of the selected mode.

import { svg, scale, ticks, axes, kindMarker, markerIcon, legend } from './svg.js';
import { h, fill, seconds } from './html.js';

const KIND_TEXT = { in_plane: 'in-plane', out_of_plane: 'out-of-plane' };

const hz = (f) => (Number.isFinite(f) ? f.toFixed(Math.abs(f) < 10 ? 3 : 1) : '—');
const pct = (e) => (Number.isFinite(e) ? (Math.abs(e) * 100).toFixed(2) : '—');

export const modal = {
  id: 'modal',
  label: 'Modal',
  runLabel: 'Run modal analysis',
  selected: 1, // mode number shown in the shape view

  // Draws `result` of finished job `job` into `container` (emptied first).
  render(result, job, container) {
    const modes = result.modes.map((m, i) => ({ ...m, mode: m.mode ?? i + 1 }));
    const n = result.numerics || {};
    const links = (job && job.id !== undefined) ? h('p', { class: 'links' },
      h('a', { href: `/api/v1/jobs/${encodeURIComponent(job.id)}/result.csv`, id: 'csv-link', download: `ringdyn-modal-${job.id}.csv` }, 'Mode table (CSV)'),
      ' · ',
      h('a', { href: `/api/v1/jobs/${encodeURIComponent(job.id)}`, id: 'json-link', target: '_blank', rel: 'noopener' }, 'Raw result (JSON)'),
    ) : null;

    const shapeBox = h('div', { id: 'shape', class: 'shape-box' },
      h('p', { class: 'hint' }, 'Select a mode in the table (or a marker in the plot) to see its shape.'));
    const plot = frequencyPlot(modes, (m) => select(m));
    const table = modeTable(modes, (m) => select(m));

    fill(container,
      h('h3', {}, `Modal analysis — ${modes.length} elastic mode${modes.length === 1 ? '' : 's'}`),
      h('p', { id: 'rigid-body' },
        h('strong', {}, String(result.rigid_body_modes)),
        ` rigid-body modes found (a free ring has 6); they are not listed below.`),
      h('p', { id: 'cost', class: 'cost' }, h('strong', {}, 'Cost and accuracy: '), costLine(n)),
      h('p', { class: 'hint' }, [n.solver && `Solver: ${n.solver}.`, n.error_method && `Error estimate: ${n.error_method}.`].filter(Boolean).join(' ')),
      links,
      h('div', { class: 'modal-grid' },
        h('figure', { class: 'plot' }, plot,
          h('figcaption', {}, 'Natural frequency against mode number; bars: estimated discretization error.')),
        h('section', { class: 'shape-view', 'aria-labelledby': 'shape-title', 'data-figure': '' },
          h('h3', { id: 'shape-title' }, 'Mode shape'), shapeBox)),
      h('div', { class: 'table-wrap' }, table),
    );

    function select(m) {
      modal.selected = m.mode;
      for (const b of table.querySelectorAll('button.mode-select')) {
        const on = Number(b.dataset.mode) === m.mode;
        b.setAttribute('aria-pressed', String(on));
        b.closest('tr').classList.toggle('selected', on);
      }
      for (const g of plot.querySelectorAll('.marker')) {
        g.classList.toggle('selected', Number(g.dataset.mode) === m.mode);
      }
      shapeBox.replaceChildren(...shapeView(m, result));
    }
    // Keep the mode selected in the previous result, if this one has it.
    if (modes.length) select(modes.find((m) => m.mode === modal.selected) || modes[0]);
  },
};

function costLine(n) {
  const parts = [
    `${n.segments} segments`,
    `${n.dof} DOF`,
    `wall time ${seconds(n.wall_s)}`,
  ];
  if (n.iterations !== undefined) parts.push(`${n.iterations} iterations${n.block_size ? ` (block ${n.block_size})` : ''}`);
  if (Number.isFinite(n.max_residual)) parts.push(`max residual ${n.max_residual.toExponential(1)}`);
  if (Number.isFinite(n.error_estimate)) {
    parts.push(`estimated error ≤ ${pct(n.error_estimate)} %${n.reference_segments ? ` (vs ${n.reference_segments} segments)` : ''}`);
  } else {
    parts.push('error not estimated');
  }
  return parts.join(' · ');
}

function modeTable(modes, onSelect) {
  const rows = modes.map((m) => {
    const button = h('button', {
      type: 'button', class: 'mode-select', 'data-mode': m.mode, 'aria-pressed': 'false',
      'aria-label': `Show shape of mode ${m.mode}`,
    }, String(m.mode));
    button.addEventListener('click', () => onSelect(m));
    const tr = h('tr', { 'data-kind': m.kind },
      h('td', {}, button),
      h('td', { class: 'kind' }, markerIcon(m.kind), ` ${KIND_TEXT[m.kind] || m.kind}`),
      h('td', { class: 'num freq' }, hz(m.frequency_hz)),
      h('td', { class: 'num' }, pct(m.error_estimate)),
      h('td', { class: 'num' }, hz(m.frequency_extrapolated_hz)),
    );
    tr.addEventListener('click', (e) => { if (!e.target.closest('button, a')) onSelect(m); });
    return tr;
  });
  const tbody = h('tbody', {}, rows);
  // Arrow keys move the selection between rows.
  tbody.addEventListener('keydown', (e) => {
    const buttons = [...tbody.querySelectorAll('button.mode-select')];
    const i = buttons.indexOf(document.activeElement);
    if (i < 0) return;
    const j = { ArrowDown: i + 1, ArrowUp: i - 1, Home: 0, End: buttons.length - 1 }[e.key];
    if (j === undefined || j < 0 || j >= buttons.length) return;
    e.preventDefault();
    buttons[j].focus();
    buttons[j].click();
  });
  return h('table', { class: 'modes', id: 'modes-table' },
    h('caption', {}, 'Elastic modes, ascending. Select a mode number to see its shape (arrow keys move).'),
    h('thead', {}, h('tr', {},
      h('th', { scope: 'col' }, 'Mode'),
      h('th', { scope: 'col' }, 'Kind'),
      h('th', { scope: 'col', class: 'num' }, heading('Frequency (Hz)', 'Freq. (Hz)')),
      h('th', { scope: 'col', class: 'num' }, heading('Est. error (%)', 'Error (%)')),
      h('th', { scope: 'col', class: 'num' }, heading('Extrapolated (Hz)', 'Extrap. (Hz)')))),
    tbody);
}

// A column heading with a short form for narrow screens (style.css picks one;
// screen readers always get the full one).
function heading(full, short) {
  return [h('span', { class: 'full' }, full), h('span', { class: 'short', 'aria-hidden': 'true' }, short)];
}

// Frequency against mode number; marker shape and colour by kind, error bars
// from the per-mode relative error estimate.
function frequencyPlot(modes, onSelect) {
  const W = 480, H = 290;
  const box = { left: 62, top: 38, width: W - 62 - 12, height: H - 38 - 50 };
  const bar = (m) => (Number.isFinite(m.error_estimate) ? Math.abs(m.error_estimate) * m.frequency_hz : 0);
  const top = Math.max(1, ...modes.map((m) => m.frequency_hz + bar(m)));
  const step = (() => { const t = ticks(0, top, 5); return t.length > 1 ? t[1] - t[0] : top; })();
  const yMax = Math.ceil((top * 1.02) / step) * step;
  const yTicks = [];
  for (let v = 0; v <= yMax + step * 1e-9; v += step) yTicks.push(v);
  const k = modes.length;
  const x = scale(0.5, k + 0.5, box.left, box.left + box.width);
  const y = scale(0, yMax, box.top + box.height, box.top);
  const xTicks = ticks(1, Math.max(k, 1), Math.min(Math.max(k, 1), 10)).filter(Number.isInteger);

  const markers = modes.map((m) => {
    const px = x(m.mode), py = y(m.frequency_hz), e = bar(m);
    const g = svg('g', { class: 'marker', 'data-mode': m.mode, 'data-kind': m.kind },
      svg('title', {}, `Mode ${m.mode}, ${KIND_TEXT[m.kind] || m.kind}: ${hz(m.frequency_hz)} Hz` +
        (Number.isFinite(m.error_estimate) ? ` ± ${pct(m.error_estimate)} %` : '')),
      e > 0 ? svg('path', {
        class: 'errbar',
        d: `M${px - 4},${y(m.frequency_hz + e)}H${px + 4}M${px},${y(m.frequency_hz + e)}V${y(m.frequency_hz - e)}M${px - 4},${y(m.frequency_hz - e)}H${px + 4}`,
      }) : null,
      svg('circle', { class: 'halo', cx: px, cy: py, r: 10 }),
      kindMarker(m.kind, px, py, 5.5));
    g.addEventListener('click', () => onSelect(m));
    return g;
  });

  const key = legend([
    [kindMarker('out_of_plane', 5, 0, 5), 'out-of-plane'],
    [kindMarker('in_plane', 5, 0, 5), 'in-plane'],
    [svg('path', { class: 'errbar', d: 'M1,-6H9M5,-6V6M1,6H9' }), 'est. error'],
  ], { x: box.left + 8, y: 16 });

  const summary = modes.map((m) => `mode ${m.mode} ${KIND_TEXT[m.kind] || m.kind} ${hz(m.frequency_hz)} Hz`).join('; ');
  return svg('svg', {
    class: 'freq-plot', id: 'freq-plot', viewBox: `0 0 ${W} ${H}`, role: 'img',
    'aria-label': `Frequency against mode number: ${summary}`,
  },
  axes({
    box, x, y, xTicks, yTicks, xLabel: 'mode number', yLabel: 'frequency (Hz)',
    yFormat: (v) => String(Number(v.toPrecision(6))),
  }),
  key,
  svg('g', { class: 'markers' }, markers));
}

// The shape of mode `m`: in-plane modes as the ring seen from above deformed
// radially, out-of-plane modes as axial displacement against angle (unrolled).
function shapeView(m, result) {
  const angles = result.segment_angle_deg || [];
  const closed = Boolean(result.scene?.discretization?.closed);
  const kind = KIND_TEXT[m.kind] || m.kind;
  const frac = Number.isFinite(m.in_plane_energy_fraction) ? ` · in-plane energy ${(m.in_plane_energy_fraction * 100).toFixed(1)} %` : '';
  const caption = document.createElement('p');
  caption.className = 'shape-caption';
  caption.textContent = `Mode ${m.mode} · ${kind} · ${hz(m.frequency_hz)} Hz${frac}`;
  const note = document.createElement('p');
  note.className = 'hint';
  let drawing;
  if (m.kind === 'in_plane') {
    drawing = ringView(angles, m.shape?.radial || [], closed, `Mode ${m.mode}, ${kind}, ${hz(m.frequency_hz)} Hz: radial displacement around the ring`);
    note.textContent = `Ring seen along the cylinder axis, ${closed ? 'joint' : 'gap'} at the top; dashed: undeformed. Radial displacement, exaggerated.`;
  } else {
    drawing = unrolledView(angles, m.shape?.axial || [], m.shape?.twist || [], `Mode ${m.mode}, ${kind}, ${hz(m.frequency_hz)} Hz: axial displacement against angle`);
    drawing.dataset.compare = `shape-mode-${m.mode}`; // a kept run is compared mode for mode (plotui.js)
    note.textContent = 'Ring unrolled: axial displacement against angle from the gap (0°); dashed: twist, scaled to fit.';
  }
  return [caption, drawing, note];
}

const maxAbs = (a) => a.reduce((s, v) => Math.max(s, Math.abs(v)), 0);

function ringView(angles, radial, closed, label) {
  const S = 360, c = S / 2, R = 118;
  const amp = maxAbs(radial) > 0 ? (0.22 * R) / maxAbs(radial) : 0;
  const pt = (deg, r) => {
    const t = (deg * Math.PI) / 180;
    return [c + r * Math.sin(t), c - r * Math.cos(t)];
  };
  const line = (pts, close) => `M${pts.map((p) => p.map((v) => v.toFixed(2)).join(',')).join('L')}${close ? 'Z' : ''}`;
  // Undeformed centroid line: from the first to the last segment (or all round).
  const a0 = closed ? 0 : (angles[0] ?? 0), a1 = closed ? 360 : (angles[angles.length - 1] ?? 360);
  const base = [];
  for (let i = 0; i <= 180; i++) base.push(pt(a0 + ((a1 - a0) * i) / 180, R));
  const pts = angles.map((a, i) => pt(a, R + amp * (radial[i] || 0)));
  const labels = [[0, closed ? 'joint' : 'gap'], [90, '90°'], [180, '180°'], [270, '270°']].map(([a, t]) => {
    const [px, py] = pt(a, R + 44);
    return svg('text', { x: px, y: py, class: 'tick', 'text-anchor': 'middle', 'dominant-baseline': 'middle' }, t);
  });
  return svg('svg', { id: 'shape-svg', class: 'shape ring-view', viewBox: `0 0 ${S} ${S}`, role: 'img', 'aria-label': label },
    svg('path', { class: 'undeformed', d: line(base, closed) }),
    svg('path', { class: 'deformed', d: line(pts, closed) }),
    svg('g', { class: 'nodes' }, pts.map(([px, py]) => svg('circle', { cx: px, cy: py, r: 2.5 }))),
    labels);
}

function unrolledView(angles, axial, twist, label) {
  const W = 400, H = 300;
  const box = { left: 62, top: 14, width: W - 62 - 12, height: H - 14 - 50 };
  const m = maxAbs(axial) || 1;
  const lim = m * 1.1;
  const x = scale(0, 360, box.left, box.left + box.width);
  const y = scale(-lim, lim, box.top + box.height, box.top);
  const tw = maxAbs(twist) > 0 ? m / maxAbs(twist) : 0;
  const path = (vals) => `M${angles.map((a, i) => `${x(a).toFixed(2)},${y(vals[i] || 0).toFixed(2)}`).join('L')}`;
  return svg('svg', { id: 'shape-svg', class: 'shape unrolled-view', viewBox: `0 0 ${W} ${H}`, role: 'img', 'aria-label': label },
    axes({
      box, x, y, xTicks: [0, 90, 180, 270, 360], yTicks: ticks(-lim, lim, 4),
      xLabel: 'angle from gap (deg)', yLabel: 'axial displacement',
      yFormat: (v) => String(Number(v.toPrecision(3))),
    }),
    svg('line', { class: 'zero', x1: box.left, x2: box.left + box.width, y1: y(0), y2: y(0) }),
    tw ? svg('path', { class: 'twist', 'data-name': 'twist (scaled)', d: path(twist.map((v) => v * tw)) }) : null,
    svg('path', { class: 'deformed', 'data-name': 'axial displacement', d: path(axial) }),
    svg('g', { class: 'nodes' }, angles.map((a, i) => svg('circle', { cx: x(a), cy: y(axial[i] || 0), r: 2.5 }))));
}
