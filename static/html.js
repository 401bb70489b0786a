// Small helpers to build the HTML of a result (no library), shared by the
// analysis modules.

// h('p', {class: 'x'}, child...) -> HTMLElement.  Strings become text nodes;
// null, undefined and false children and attributes are skipped.
export function h(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === undefined || v === null || v === false) continue;
    if (k === 'class') node.className = v;
    else node.setAttribute(k, v === true ? '' : String(v));
  }
  for (const c of children.flat()) if (c !== null && c !== undefined && c !== false) node.append(c);
  return node;
}

// Replaces the children of `container` with `children`, skipping null,
// undefined and false (replaceChildren itself would write them as text).
export function fill(container, ...children) {
  container.replaceChildren(...children.flat().filter((c) => c !== null && c !== undefined && c !== false));
}

export const isNum = (v) => typeof v === 'number' && Number.isFinite(v);

// v * factor with `digits` decimals, or '—' when v is not a finite number.
export function fixed(v, digits = 2, factor = 1) {
  return isNum(v) ? (v * factor).toFixed(digits) : '—';
}

// A result array as numbers ([] when absent).
export const nums = (a) => (Array.isArray(a) ? a.map(Number) : []);

// Metres shown in micrometres, `digits` decimals.
export const um = (v, digits = 2) => fixed(v, digits, 1e6);

// An angle in degrees to 0.1, "—" when missing.
export const deg = (v) => (isNum(v) ? `${Number(v.toFixed(1))}°` : '—');

// Significant digits, plain notation where it reads well.
export function sig(v, digits = 3) {
  if (!isNum(v)) return '—';
  const a = Math.abs(v);
  if (a !== 0 && (a < 1e-3 || a >= 1e6)) return v.toExponential(digits - 1);
  return String(Number(v.toPrecision(digits)));
}

export function seconds(s) {
  if (!isNum(s)) return '—';
  return s < 1 ? `${(s * 1e3).toPrecision(3)} ms` : `${s.toPrecision(3)} s`;
}

// A relative error estimate as "0.12 %", or a reason it is missing.
export function percent(e, digits = 2) {
  return isNum(e) ? `${(Math.abs(e) * 100).toFixed(digits)} %` : 'not estimated';
}

// The cost line of a static (Newton) result's numerics: segments, DOF,
// iterations and load steps, wall time, error estimate.
export function newtonCost(n) {
  const parts = [];
  if (n.segments !== undefined) parts.push(`${n.segments} segments`);
  if (n.dof !== undefined) parts.push(`${n.dof} DOF`);
  if (n.iterations !== undefined) parts.push(`${n.iterations} Newton iterations${n.load_steps !== undefined ? ` in ${n.load_steps} load steps` : ''}`);
  parts.push(`wall time ${seconds(n.wall_s)}`);
  parts.push(isNum(n.error_estimate) ? `estimated error ${percent(n.error_estimate)}` : 'error not estimated');
  return parts.join(' · ');
}

// A two-column table of [name, value] rows (a row may carry a third item:
// {id, title} for the value cell).  Rows whose value is undefined are left out.
export function kvTable({ id, caption, rows }) {
  const body = rows.filter((r) => r && r[1] !== undefined).map(([name, value, opts = {}]) =>
    h('tr', {}, h('th', { scope: 'row' }, name), h('td', { class: 'num', id: opts.id, title: opts.title }, value)));
  return h('table', { class: 'kv', id }, caption ? h('caption', {}, caption) : null, h('tbody', {}, body));
}

// Links to a finished job's raw JSON and (when it has one) its CSV table.
export function resultLinks(job, analysis, csvLabel) {
  if (!job || job.id === undefined) return null;
  const base = `/api/v1/jobs/${encodeURIComponent(job.id)}`;
  return h('p', { class: 'links' },
    csvLabel ? [h('a', { href: `${base}/result.csv`, id: 'csv-link', download: `ringdyn-${analysis}-${job.id}.csv` }, csvLabel), ' · '] : null,
    h('a', { href: base, id: 'json-link', target: '_blank', rel: 'noopener' }, 'Raw result (JSON)'));
}
