// The Calibrate view of the results panel: a calibration spec (a base
// scene, the parameters to fit by JSON Pointer with bounds, measurements:
// a variation of the base, a pointer into its result, the measured value(s)
// and their sigma) is posted to POST /api/v1/calibrations and followed as a
// job; the result shows the fitted parameters with their standard errors
// (those the data cannot fix marked so), chi2 / dof, runs, why the fit
// stopped, the notes (what the numbers do not cover) as text, and measured
// against fitted: scalar measurements one point each (measured +- sigma as
// an error bar, the fitted value as a diamond), traces as two lines against
// the sample index.
//
// calibrateView({form, analysis}) wires the view (sweep.js's setupSweeps
// owns the tabs): `analysis()` is the id of the analysis whose form is shown.

import { getJSON, postJSON, watchJob, cancelJob, jobUrl, ApiError } from './api.js';
import { h, fill, isNum, seconds } from './html.js';
import { svg, scale, ticks, axes, pathD, legend } from './svg.js';
import { watchCharts } from './charts.js';

const $ = (id) => document.getElementById(id);
const EXAMPLE = 'calibration_ringpack_blowby';
// `digits` significant digits in JavaScript's shortest form (1e-8, 5.517e-8, 1500).
const sig = (v, digits = 3) => (isNum(v) ? String(Number(v.toPrecision(digits))) : '—');
const FINISHED = new Set(['succeeded', 'failed', 'cancelled', 'interrupted']);

// ---- the spec -----------------------------------------------------------------

// A shipped example as a spec: what POST /api/v1/calibrations takes (its
// name and description stay: a scene may carry them).
async function exampleSpec() {
  return getJSON(`/api/v1/examples/${EXAMPLE}`);
}

// The form's scene as base, nothing to fit yet: the user adds both lists.
function formSpec(scene) {
  return { analysis: 'calibration', base: scene, parameters: [], measurements: [] };
}

// "/engine/speed_rpm = 1500, /cylinder_pressure/synthetic/peak_pa = 4e6" ("base scene" when none).
const setText = (set) => {
  const e = Object.entries(set ?? {});
  return e.length ? e.map(([k, v]) => `${k} = ${typeof v === 'number' ? sig(v, 4) : JSON.stringify(v)}`).join(', ') : 'the base scene';
};

// A JSON Pointer that may break after each '/' on a narrow screen.
const ptr = (p) => String(p).split('/').flatMap((t, k) => (k ? [h('wbr', {}), `/${t}`] : t ? [t] : []));
// A number that does not break at the '-' of its exponent.
const nb = (text, cls) => h('span', { class: cls ? `nb ${cls}` : 'nb' }, text);

// The k-th sigma of a measurement: one for all values, or one per value.
const sigmaAt = (sigma, k) => (Array.isArray(sigma) ? (sigma.length === 1 ? sigma[0] : sigma[k]) : sigma);

// ---- plots --------------------------------------------------------------------

// A linear axis over values `v` (padded 6 %), with round ticks.
function axis(v, r0, r1) {
  let lo = Math.min(...v), hi = Math.max(...v);
  if (!(hi > lo)) { lo -= Math.abs(lo) * 0.1 || 1; hi += Math.abs(hi) * 0.1 || 1; }
  const pad = (hi - lo) * 0.06;
  const f = scale(lo - pad, hi + pad, r0, r1);
  return { map: f, ticks: ticks(lo - pad, hi + pad, 5), format: (x) => sig(x, 3) };
}

const W = 560, H = 350, BOX = { left: 76, top: 34, width: 456, height: 250 };

// The fitted marker: a diamond (another shape than the measured circle).
const diamond = (x, y, s, attrs) => svg('path', { d: `M${x},${y - s}L${x + s},${y}L${x},${y + s}L${x - s},${y}Z`, 'data-cx': x, 'data-cy': y, ...attrs });

// Scalar measurements of one observed pointer: x = measurement number, y = value.
// items: [{i (index in the result), m (result measurement), sigma}].
function scalarPlot(id, observe, items) {
  const ys = items.flatMap(({ m, sigma }) => [m.measured, m.fitted, m.measured - (sigma ?? 0), m.measured + (sigma ?? 0)]).filter(isNum);
  const n = items.length;
  const X = scale(0.5, n + 0.5, BOX.left, BOX.left + BOX.width);
  const Y = axis(ys, BOX.top + BOX.height, BOX.top);
  const cap = Math.min(8, BOX.width / n / 6);
  const label = `${observe}: measured (with ± 1 sigma) and fitted at ${n} measurement${n === 1 ? '' : 's'}`;
  return svg('svg', { id, class: 'chart cal-plot', viewBox: `0 0 ${W} ${H}`, role: 'img', 'aria-label': label, 'data-observe': observe },
    axes({ box: BOX, x: X, y: Y.map, xTicks: items.map((_, k) => k + 1), yTicks: Y.ticks, xLabel: 'measurement (its set: in the table below)', yLabel: observe, xFormat: (k) => `#${items[k - 1].i + 1}`, yFormat: Y.format }),
    items.map(({ i, m, sigma }, k) => {
      const x = X(k + 1), ok = isNum(sigma) && isNum(m.measured);
      const lo = ok ? Y.map(m.measured - sigma) : null, hi = ok ? Y.map(m.measured + sigma) : null;
      const what = `#${i + 1} (${setText(m.set)}): measured ${sig(m.measured, 4)}${isNum(sigma) ? ` ± ${sig(sigma, 3)}` : ''}, fitted ${sig(m.fitted, 4)}, residual ${sig(m.residual, 3)} sigma`;
      return svg('g', { class: 'cal-point', 'data-index': i },
        ok ? svg('g', { class: 'cal-errbar', 'data-lo': m.measured - sigma, 'data-hi': m.measured + sigma },
          svg('line', { x1: x, x2: x, y1: lo, y2: hi }),
          svg('line', { x1: x - cap, x2: x + cap, y1: lo, y2: lo }),
          svg('line', { x1: x - cap, x2: x + cap, y1: hi, y2: hi })) : null,
        isNum(m.measured) ? svg('circle', { class: 'cal-measured', cx: x.toFixed(2), cy: Y.map(m.measured).toFixed(2), r: 5, 'data-y': m.measured, 'data-name': 'measured' }, svg('title', {}, what)) : null,
        isNum(m.fitted) ? diamond(x + 0, Y.map(m.fitted), 6.5, { class: 'cal-fitted', 'data-y': m.fitted, 'data-name': 'fitted' }) : null);
    }),
    legend([
      [svg('g', {}, svg('line', { x1: 0, x2: 0, y1: -6, y2: 6, class: 'cal-errbar-line' }), svg('circle', { cx: 0, cy: 0, r: 4, class: 'cal-measured' })), 'measured ± 1 sigma'],
      [diamond(0, 0, 5.5, { class: 'cal-fitted' }), 'fitted'],
    ], { x: BOX.left + 4, y: 14, id: `${id}-legend` }));
}

// One trace: measured (with its sigma band) and fitted against the sample index.
function tracePlot(id, i, m, sigma) {
  const meas = Array.isArray(m.measured) ? m.measured : [], fit = Array.isArray(m.fitted) ? m.fitted : [];
  const n = Math.max(meas.length, fit.length);
  const sg = meas.map((_, k) => sigmaAt(sigma, k));
  const band = meas.map((v, k) => (isNum(v) && isNum(sg[k]) ? [v - sg[k], v + sg[k]] : null));
  const ys = [...meas, ...fit, ...band.flatMap((b) => b ?? [])].filter(isNum);
  if (!ys.length || !n) return h('p', { class: 'hint', id: `${id}-empty` }, `Measurement #${i + 1}: no numbers to plot.`);
  const X = axis([0, Math.max(1, n - 1)], BOX.left, BOX.left + BOX.width);
  const Y = axis(ys, BOX.top + BOX.height, BOX.top);
  const up = band.map((b, k) => (b ? [X.map(k), Y.map(b[1])] : [NaN, NaN]));
  const down = band.map((b, k) => (b ? [X.map(k), Y.map(b[0])] : [NaN, NaN])).reverse();
  const whole = band.every(Boolean);
  return svg('svg', { id, class: 'chart cal-plot', viewBox: `0 0 ${W} ${H}`, role: 'img', 'aria-label': `Measurement #${i + 1}, ${m.observe} (${setText(m.set)}): measured and fitted trace of ${n} samples`, 'data-observe': m.observe },
    axes({ box: BOX, x: X.map, y: Y.map, xTicks: X.ticks.filter((t) => Number.isInteger(t)), yTicks: Y.ticks, xLabel: 'sample index', yLabel: m.observe, xFormat: (t) => String(t), yFormat: Y.format }),
    whole && n > 1 ? svg('path', { class: 'cal-band', d: `${pathD(up.concat(down))}Z` }) : null,
    svg('path', { class: 'cal-measured-line', 'data-name': 'measured', d: pathD(meas.map((v, k) => [X.map(k), Y.map(v)])) }),
    svg('path', { class: 'cal-fitted-line', 'data-name': 'fitted', d: pathD(fit.map((v, k) => [X.map(k), Y.map(v)])) }),
    legend([
      [svg('line', { x1: -6, x2: 6, y1: 0, y2: 0, class: 'cal-measured-line' }), whole ? 'measured (band ± 1 sigma)' : 'measured'],
      [svg('line', { x1: -6, x2: 6, y1: 0, y2: 0, class: 'cal-fitted-line' }), 'fitted'],
    ], { x: BOX.left + 4, y: 14, id: `${id}-legend` }));
}

// ---- the result ---------------------------------------------------------------

const valueText = (p) => `${sig(p.value, 4)}${isNum(p.std_error) ? ` ± ${sig(p.std_error, 2)}` : ''}`;

function paramTable(r) {
  const rows = r.parameters.map((p, k) => h('tr', { id: `cal-param-${k}`, class: p.identifiable ? null : 'unidentifiable', 'data-identifiable': String(p.identifiable) },
    h('th', { scope: 'row', class: 'path' }, h('code', {}, ptr(p.path))),
    h('td', { class: 'num fit' },
      h('span', { class: 'nb value', 'data-value': p.value }, sig(p.value, 4)),
      isNum(p.std_error)
        ? [' ', h('span', { class: 'nb std', 'data-std-error': p.std_error }, `± ${sig(p.std_error, 2)}`),
          isNum(p.value) && p.value !== 0 ? h('span', { class: 'rel' }, `(${sig(Math.abs(p.std_error / p.value) * 100, 2)} %)`) : null].flat()
        : [' ', h('span', { class: 'std none' }, '± — (the data do not fix it)')]),
    h('td', { class: 'num bounds' }, nb(sig(p.min, 3)), ' to ', nb(sig(p.max, 3)), h('span', { class: 'start' }, 'start ', nb(sig(p.start, 3)))),
    h('td', { class: 'state' },
      p.identifiable ? 'identifiable' : h('strong', { class: 'bad' }, 'not identifiable'),
      p.at_bound ? h('span', { class: 'at-bound' }, `at its ${p.at_bound} bound`) : null)));
  return h('div', { class: 'table-wrap' }, h('table', { class: 'modes cal-table', id: 'cal-params' },
    h('caption', {}, 'Fitted parameters: the value with its standard error (linearised at the optimum, from the sigmas as given); "not identifiable": the measurements fix only a combination of it with other parameters, or its ±2 standard errors span its whole range — its value is one of many that fit equally.'),
    h('thead', {}, h('tr', {},
      h('th', { scope: 'col' }, 'Parameter'), h('th', { scope: 'col' }, 'Fitted ± std error'),
      h('th', { scope: 'col' }, 'Bounds'), h('th', { scope: 'col' }, 'Status'))),
    h('tbody', {}, rows)));
}

function corrTable(r) {
  const n = r.parameters.length;
  if (n < 2 || !Array.isArray(r.correlation)) return null;
  const name = (k) => `p${k + 1}`;
  return h('div', { class: 'table-wrap' }, h('table', { class: 'modes cal-table', id: 'cal-correlation' },
    h('caption', {}, `Correlation of the fitted parameters (${r.parameters.map((p, k) => `${name(k)} = ${p.path}`).join(', ')}); — where a parameter is not identifiable.`),
    h('thead', {}, h('tr', {}, h('td', {}), r.parameters.map((_, k) => h('th', { scope: 'col' }, name(k))))),
    h('tbody', {}, r.correlation.map((row, a) => h('tr', {}, h('th', { scope: 'row' }, name(a)),
      (row ?? []).map((c) => h('td', { class: 'num' }, isNum(c) ? c.toFixed(3) : '—')))))));
}

function measTable(r, sigmas) {
  const cell = (v) => (Array.isArray(v) ? `trace of ${v.length}` : nb(sig(v, 4)));
  const sgText = (s) => {
    const one = Array.isArray(s) && s.length === 1 ? s[0] : s;
    if (Array.isArray(one)) return [' ', '± per sample'];
    return isNum(one) ? [' ', nb(`± ${sig(one, 3)}`)] : null;
  };
  return h('div', { class: 'table-wrap' }, h('table', { class: 'modes cal-table', id: 'cal-measurements' },
    h('caption', {}, 'Each measurement: its variation of the base scene, what it observes, the measured value(s) with sigma, the model at the fitted parameters, and the residual in sigmas (a trace: the root mean square of its samples\').'),
    h('thead', {}, h('tr', {}, h('th', { scope: 'col' }, '#'), h('th', { scope: 'col' }, 'Set, observed'), h('th', { scope: 'col' }, 'Measured'), h('th', { scope: 'col' }, 'Fitted'), h('th', { scope: 'col' }, 'Resid\u00adual (σ)'))),
    h('tbody', {}, r.measurements.map((m, i) => h('tr', { id: `cal-meas-${i}` },
      h('td', { class: 'num' }, String(i + 1)),
      h('td', { class: 'set' }, Object.keys(m.set ?? {}).length
        ? Object.entries(m.set).map(([k, v]) => h('span', { class: 'set-item' }, ptr(k), ' = ', nb(typeof v === 'number' ? sig(v, 4) : JSON.stringify(v))))
        : h('span', { class: 'set-item' }, 'the base scene'),
      h('code', { class: 'set-item' }, ptr(m.observe))),
      h('td', { class: 'num' }, cell(m.measured), sgText(sigmas[i])),
      h('td', { class: 'num' }, cell(m.fitted)),
      h('td', { class: 'num' }, nb(sig(m.residual, 3))))))));
}

function plots(r, sigmas) {
  const scalars = new Map(); // observe -> [{i, m, sigma}]
  const traces = [];
  r.measurements.forEach((m, i) => {
    if (Array.isArray(m.measured) || Array.isArray(m.fitted)) traces.push({ i, m, sigma: sigmas[i] });
    else {
      if (!scalars.has(m.observe)) scalars.set(m.observe, []);
      scalars.get(m.observe).push({ i, m, sigma: sigmaAt(sigmas[i], 0) });
    }
  });
  const figs = [];
  let k = 0;
  for (const [observe, items] of scalars) {
    figs.push(h('figure', { class: 'plot wide' },
      scalarPlot(`cal-plot-${k++}`, observe, items),
      h('figcaption', {}, `${observe}, measured against fitted: one point per measurement (numbered as in the table below), the measured value as a circle with a bar of ± 1 sigma, the model at the fitted parameters as a diamond. Hover a point for its values.`)));
  }
  for (const { i, m, sigma } of traces) {
    figs.push(h('figure', { class: 'plot wide' },
      tracePlot(`cal-plot-${k++}`, i, m, sigma),
      h('figcaption', {}, `Measurement #${i + 1} (${setText(m.set)}): ${m.observe}, measured (solid) and fitted (dashed) against the sample index; residual ${sig(m.residual, 3)} sigma (root mean square).`)));
  }
  return figs;
}

function render(job, spec) {
  const r = job.result;
  const sigmas = (r.scene?.measurements ?? spec?.measurements ?? []).map((m) => m?.sigma);
  const ratio = isNum(r.chi2) && r.dof > 0 ? r.chi2 / r.dof : null;
  const n = r.numerics ?? {};
  const warnings = (r.warnings ?? []).map((w) => (typeof w === 'string' ? w : `${w.message ?? w.code ?? ''}${w.path ? ` (${w.path})` : ''}`));
  fill($('cal-result'),
    h('p', { id: 'cal-verdict', class: r.identifiable ? 'cal-ok' : 'cal-bad' }, r.identifiable
      ? `Every parameter is identifiable from these measurements${r.converged ? '' : ', but the fit did not converge'}.`
      : `Not identifiable: ${r.parameters.filter((p) => !p.identifiable).map((p) => p.path).join(', ')} — the measurements do not fix ${r.parameters.filter((p) => !p.identifiable).length === 1 ? 'it' : 'them'}.`),
    paramTable(r),
    h('table', { class: 'kv', id: 'cal-summary' }, h('caption', {}, 'The fit'), h('tbody', {},
      h('tr', {}, h('th', { scope: 'row' }, 'chi² / dof'), h('td', { class: 'num', id: 'cal-chi2' }, `${sig(r.chi2, 3)} / ${r.dof}${isNum(ratio) ? ` = ${sig(ratio, 3)}` : ''}`)),
      h('tr', {}, h('th', { scope: 'row' }, 'Scene runs'), h('td', { class: 'num', id: 'cal-runs' }, String(r.runs))),
      h('tr', {}, h('th', { scope: 'row' }, 'Converged'), h('td', { id: 'cal-converged' }, `${r.converged ? 'yes' : 'no'} (stop: ${r.stop})`)),
      h('tr', {}, h('th', { scope: 'row' }, 'Cost'), h('td', { id: 'cal-cost' },
        [isNum(n.evaluations) ? `${n.evaluations} evaluations` : null, isNum(n.iterations) ? `${n.iterations} iterations` : null,
          isNum(n.threads) ? `${n.threads} threads` : null, `wall time ${seconds(n.wall_s)}`,
          n.cond === null ? 'condition number infinite' : isNum(n.cond) ? `condition number ${sig(n.cond, 2)}` : null].filter(Boolean).join(' · '))))),
    h('section', { class: 'cal-notes', 'aria-labelledby': 'cal-notes-title' },
      h('h3', { id: 'cal-notes-title' }, 'Notes: what these numbers do not cover'),
      (r.notes ?? []).length ? h('ul', { id: 'cal-notes' }, r.notes.map((t) => h('li', {}, t))) : h('p', { id: 'cal-notes', class: 'hint' }, 'No notes.')),
    warnings.length ? h('ul', { class: 'warnings', id: 'cal-warnings', 'aria-label': 'Warnings about this calibration' }, warnings.map((t) => h('li', {}, t))) : null,
    plots(r, sigmas),
    measTable(r, sigmas),
    corrTable(r),
    h('p', { class: 'links' }, h('a', { href: jobUrl(job.id), id: 'cal-json-link', target: '_blank', rel: 'noopener' }, 'Raw result (JSON)')));
}

// ---- the view -----------------------------------------------------------------

export function calibrateView({ form, analysis }) {
  const textarea = $('cal-spec');
  const state = { run: null };
  let spec = null;
  const status = (text, progress) => {
    $('cal-status-text').textContent = text;
    const bar = $('cal-progress');
    bar.hidden = progress === undefined;
    if (progress === null) bar.removeAttribute('value');
    else if (progress !== undefined) bar.value = progress;
  };
  const showError = (err) => {
    const box = $('cal-error');
    fill(box, err.message || String(err), err.path ? [' (', h('code', { class: 'path' }, err.path), ')'] : null);
    box.hidden = false;
  };
  const hideError = () => { $('cal-error').hidden = true; };

  async function fillExample() {
    hideError();
    try {
      textarea.value = JSON.stringify(await exampleSpec(), null, 2);
      status('The shipped example calibration_ringpack_blowby is in the editor.');
    } catch (err) {
      showError(err);
    }
  }
  function fillForm() {
    hideError();
    try {
      textarea.value = JSON.stringify(formSpec(form.read(analysis())), null, 2);
      status('The form\'s scene is the base: add the parameters ({"path", "min", "max"}) and measurements ({"set", "observe", "value", "sigma"}).');
    } catch (err) {
      showError(err);
    }
  }

  async function start() {
    if (state.run) return;
    hideError();
    try {
      spec = JSON.parse(textarea.value);
    } catch (err) {
      showError({ message: `The spec is not JSON: ${err.message}` });
      return;
    }
    const controller = new AbortController();
    const run = { controller, id: null };
    state.run = run;
    $('cal-run').disabled = true;
    $('cal-cancel').hidden = false;
    fill($('cal-result'));
    status('Submitting…', null);
    const line = (j) => `Calibration ${j.id} ${j.status}${isNum(j.progress) && j.status === 'running' ? ` — ${Math.round(j.progress * 100)} %` : ''}${isNum(j.eta_s) ? `, about ${seconds(j.eta_s)} left` : ''}`;
    try {
      let job = await postJSON('/api/v1/calibrations?wait=0', spec, { signal: controller.signal });
      run.id = job.id;
      if (!FINISHED.has(job.status)) {
        job = await watchJob(job, {
          signal: controller.signal,
          onUpdate: (j) => {
            run.id = j.id;
            status(run.cancelling ? `Cancelling calibration ${j.id}…` : line(j), j.status === 'running' && isNum(j.progress) ? j.progress : null);
          },
        });
      }
      if (job.status === 'succeeded' && job.result) {
        const r = job.result;
        status(`Calibration ${job.id} succeeded: ${r.runs} scene runs, ${r.converged ? 'converged' : 'not converged'} (${r.stop}), wall time ${seconds(r.numerics?.wall_s)}.`);
        render(job, spec);
      } else {
        status(`Calibration ${job.id} ${job.status}.`);
        if (job.error) showError(job.error);
      }
    } catch (err) {
      if (err.name === 'AbortError') status(run.id ? `Stopped following calibration ${run.id}.` : 'Cancelled.');
      else {
        status('');
        showError(err instanceof ApiError ? err : { message: String(err.message || err) });
      }
    } finally {
      state.run = null;
      $('cal-run').disabled = false;
      $('cal-cancel').hidden = true;
    }
  }
  // DELETE cancels the job; the next poll sees it end "cancelled".
  async function cancel() {
    const run = state.run;
    if (!run) return;
    if (!run.id) { run.controller.abort(); return; }
    run.cancelling = true;
    status(`Cancelling calibration ${run.id}…`, null);
    const resp = await cancelJob(run.id);
    if (!resp?.ok) run.controller.abort();
  }

  $('cal-run').addEventListener('click', start);
  $('cal-cancel').addEventListener('click', cancel);
  $('cal-fill').addEventListener('click', fillExample);
  $('cal-fill-form').addEventListener('click', fillForm);
  watchCharts($('calibrate-view'));
  return { opened: () => {} };
}
