// The sweep views of the results panel: "Sweep" runs a sweep spec
// through POST /api/v1/sweeps, follows its progress and plots an output
// column against a parameter column of its table (rows done so far); "Speed
// vs accuracy" runs the fidelity sweep of the form's scene ({"fidelity":
// scene}) and plots wall time against each setting's error on its basis
// (measured against the finest setting, or an estimate that covers what the
// setting changes), the Pareto front highlighted, with a button per Pareto
// setting that puts it into the form.
//
// A sweep with "over" has, per output O, the columns min:O max:O mean:O
// argmin:O argmax:O (rd_sweep.h): plotting any of the first three draws the
// mean line with a shaded band from min to max.
//
// setupSweeps({form, analysis, onApply}) wires the view tabs: `analysis()`
// is the id of the analysis whose form is shown; `onApply(text)` is told
// when a setting went into the form.

import { getBlob, getJSON, postJSON, deleteUrl, ApiError } from './api.js';
import { h, fill, isNum, sig, seconds } from './html.js';
import { svg, scale, ticks, axes, pathD } from './svg.js';
import { saveBlob } from './script.js';
import { calibrateView } from './calibrate.js';

const $ = (id) => document.getElementById(id);
// Each poll brings the whole table so far: every 0.4 s, every 2 s for a
// sweep of more than 1000 points (up to about 1 MB a poll at 10^4).
const POLL_MS = 400;
const POLL_LARGE_MS = 2000;
const FINAL = new Set(['succeeded', 'failed', 'cancelled', 'interrupted']);

// Where a sweep runs: the service's own workers, or a Slurm job array (a
// server started with --sweep-executor slurm; docs/cluster.md) with its job
// id, the chunk files read and the scheduler's state at the service's last poll.
export function sweepWhere(s) {
  if (s.executor !== 'slurm') return "on the service's workers";
  const c = s.cluster ?? {};
  const job = c.job_id ? `Slurm job ${c.job_id}` : 'Slurm (being submitted)';
  return `on ${job}: ${c.chunks_done ?? 0} of ${c.chunks ?? '?'} chunks${c.scheduler ? `, ${c.scheduler}` : ''}`;
}

// What a sweep of each analysis tabulates by default, and the parameter the
// example varies (+-20 % around the form's value, 5 points).
const DEFAULTS = {
  modal: { param: '/ring/radial_width', outputs: ['/modes/0/frequency_hz', '/modes/1/frequency_hz', 'max(/modes/*/error_estimate)', '/numerics/wall_s'] },
  pretension: { param: '/ring/radial_width', outputs: ['/gap_opening_inner', '/conformability', '/numerics/wall_s'] },
  contact: { param: '/ring/radial_width', outputs: ['/uniform_pressure_pa', 'max(/pressure_pa)', 'min(/pressure_pa)', '/numerics/wall_s'] },
  lift: { param: '/engine/speed_rpm', outputs: ['max(/lift)', 'count(/events)', '/numerics/wall_s'] },
  // the top ring's closed gap: what the blow-by answers to most directly
  ringpack: { param: '/rings/0/ring/closed_gap', outputs: ['/blowby/l_per_min', '/blowby/kg_per_cycle', '/numerics/wall_s'] },
};

const pointer = (obj, path) => path.split('/').slice(1)
  .map((t) => t.replace(/~1/g, '/').replace(/~0/g, '~'))
  .reduce((o, k) => (o === undefined || o === null ? undefined : o[k]), obj);

// The example spec: the form's scene as base, one parameter, the outputs.
export function exampleSpec(scene) {
  const d = DEFAULTS[scene.analysis] ?? DEFAULTS.modal;
  const v = Number(pointer(scene, d.param));
  const mid = isNum(v) && v > 0 ? v : 1;
  const round = (x) => Number(x.toPrecision(6));
  return {
    base: scene,
    parameters: [{ path: d.param, range: { start: round(mid * 0.8), stop: round(mid * 1.2), count: 5 } }],
    outputs: d.outputs,
  };
}

// ---- following a sweep ------------------------------------------------------

const sleep = (ms, signal) => new Promise((resolve, reject) => {
  const t = setTimeout(resolve, ms);
  signal?.addEventListener('abort', () => { clearTimeout(t); reject(new DOMException('Aborted', 'AbortError')); }, { once: true });
});

// Submits `body` and polls the sweep until it is final; onUpdate(sweep) sees
// every state (the first as soon as it has an id).  Resolves with the final sweep.
async function runSweep(body, { signal, onUpdate }) {
  let sweep = await postJSON('/api/v1/sweeps', body, { signal });
  for (;;) {
    onUpdate(sweep);
    if (FINAL.has(sweep.status)) return sweep;
    await sleep(sweep.points > 1000 ? POLL_LARGE_MS : POLL_MS, signal);
    sweep = await getJSON(`/api/v1/sweeps/${encodeURIComponent(sweep.id)}`, { signal });
  }
}

// One runner per view: Run / Cancel buttons, status line, error box.
function runner(prefix, { submit, onUpdate, onDone }) {
  const state = { run: null };
  const status = (text, progress) => {
    $(`${prefix}-status-text`).textContent = text;
    const bar = $(`${prefix}-progress`);
    bar.hidden = progress === undefined;
    if (progress !== undefined) bar.value = progress;
  };
  const showError = (err) => {
    const box = $(`${prefix}-error`);
    fill(box, err.message || String(err), err.path ? [' (', h('code', {}, err.path), ')'] : null);
    box.hidden = false;
  };
  async function start() {
    if (state.run) return;
    $(`${prefix}-error`).hidden = true;
    let body;
    try {
      body = submit();
    } catch (err) {
      showError(err);
      return;
    }
    const controller = new AbortController();
    const run = { controller, id: null };
    state.run = run;
    $(`${prefix}-run`).disabled = true;
    $(`${prefix}-cancel`).hidden = false;
    status('Submitting…', 0);
    try {
      const sweep = await runSweep(body, {
        signal: controller.signal,
        onUpdate: (s) => {
          run.id = s.id;
          const runs = s.runs && s.runs !== s.points ? ` (${s.runs} runs)` : '';
          status(`Sweep ${s.id} ${s.status} — ${s.done} of ${s.points} points${runs}${s.failed ? ` (${s.failed} failed)` : ''} ${sweepWhere(s)}`, s.progress);
          onUpdate(s);
        },
      });
      const runs = sweep.runs && sweep.runs !== sweep.points ? ` (${sweep.runs} runs)` : '';
      status(`Sweep ${sweep.id} ${sweep.status}: ${sweep.done} of ${sweep.points} points${runs}${sweep.failed ? `, ${sweep.failed} failed (see their rows)` : ''} ${sweepWhere(sweep)}.`);
      // A sweep on Slurm fails as a whole when a task does: the task, its exit code and why.
      if (sweep.error) showError(sweep.error);
      onDone(sweep);
    } catch (err) {
      if (err.name === 'AbortError') status(run.id ? `Stopped following sweep ${run.id}.` : 'Cancelled.');
      else {
        status('');
        showError(err instanceof ApiError ? err : { message: String(err.message || err) });
      }
    } finally {
      state.run = null;
      $(`${prefix}-run`).disabled = false;
      $(`${prefix}-cancel`).hidden = true;
    }
  }
  // DELETE cancels it; the next poll sees it end "cancelled".
  async function cancel() {
    const run = state.run;
    if (!run) return;
    if (!run.id) { run.controller.abort(); return; }
    status(`Cancelling sweep ${run.id}…`, undefined);
    const resp = await deleteUrl(`/api/v1/sweeps/${encodeURIComponent(run.id)}`);
    if (!resp?.ok) run.controller.abort();
  }
  $(`${prefix}-run`).addEventListener('click', start);
  $(`${prefix}-cancel`).addEventListener('click', cancel);
  return { showError };
}

// ---- a scatter plot -----------------------------------------------------------

// Axis mapping for values `v`: linear, or log10 when `log` (positive values only).
function axis(v, log, r0, r1) {
  const t = log ? v.map(Math.log10) : v;
  let lo = Math.min(...t), hi = Math.max(...t);
  if (!(hi > lo)) { lo -= log ? 0.5 : Math.abs(lo) * 0.1 || 1; hi += log ? 0.5 : Math.abs(hi) * 0.1 || 1; }
  const pad = (hi - lo) * 0.05;
  const f = scale(lo - pad, hi + pad, r0, r1);
  const tk = log
    ? Array.from({ length: Math.floor(hi + pad) - Math.ceil(lo - pad) + 1 }, (_, i) => Math.ceil(lo - pad) + i)
    : ticks(lo - pad, hi + pad, 5);
  return { map: (x) => f(log ? Math.log10(x) : x), ticks: tk, at: f, format: log ? (e) => `1e${e}` : (x) => sig(x, 3) };
}

// The shaded band from p.lo to p.hi over the points (in x order), and a bar
// from lo to hi at each point (all a single point shows).
function band(id, pts, X, Y) {
  const b = pts.filter((p) => isNum(p.lo) && isNum(p.hi));
  if (!b.length) return null;
  const up = b.map((p) => [X.map(p.x), Y.map(p.hi)]), down = b.map((p) => [X.map(p.x), Y.map(p.lo)]).reverse();
  return svg('g', { class: 'band', id: `${id}-band`, 'data-points': b.length },
    b.length > 1 ? svg('path', { class: 'band-area', d: `${pathD(up.concat(down))}Z` }) : null,
    b.map((p) => svg('line', { class: 'band-bar', x1: X.map(p.x), x2: X.map(p.x), y1: Y.map(p.lo), y2: Y.map(p.hi) })));
}

// points: [{x, y, cls, title, id}, optional lo/hi: the band], `line` joins
// them in x order (or the `front` subset); returns the <svg>.
function scatter({ id, points, xLabel, yLabel, xLog = false, yLog = false, front = null, label }) {
  const W = 560, H = 340, box = { left: 72, top: 16, width: 460, height: 260 };
  const ok = points.filter((p) => isNum(p.x) && isNum(p.y) && (!xLog || p.x > 0) && (!yLog || p.y > 0));
  if (!ok.length) return h('p', { class: 'hint', id: `${id}-empty` }, 'No point with numbers in both columns yet.');
  const X = axis(ok.map((p) => p.x), xLog, box.left, box.left + box.width);
  const ys = ok.flatMap((p) => [p.y, p.lo, p.hi].filter((v) => isNum(v) && (!yLog || v > 0)));
  const Y = axis(ys, yLog, box.top + box.height, box.top);
  const line = (front ?? ok).filter((p) => ok.includes(p)).slice().sort((a, b) => a.x - b.x);
  return svg('svg', { id, class: 'chart sweep-plot', viewBox: `0 0 ${W} ${H}`, role: 'img', 'aria-label': label },
    axes({ box, x: X.at, y: Y.at, xTicks: X.ticks, yTicks: Y.ticks, xLabel, yLabel, xFormat: X.format, yFormat: Y.format, xLog, yLog }),
    band(id, line, X, Y),
    svg('path', { class: front ? 'front-line' : 'series', 'data-name': front ? 'Pareto front' : yLabel, d: pathD(line.map((p) => [X.map(p.x), Y.map(p.y)])) }),
    ok.map((p) => svg('circle', { cx: X.map(p.x).toFixed(2), cy: Y.map(p.y).toFixed(2), r: 5, class: `pt ${p.cls ?? ''}`, id: p.id, 'data-x': p.x, 'data-y': p.y },
      svg('title', {}, p.title))));
}

// ---- the Sweep view --------------------------------------------------------------

function sweepView({ form, analysis }) {
  let shown = null; // the sweep on screen
  const textarea = $('sw-spec');
  const fillSpec = () => {
    try {
      textarea.value = JSON.stringify(exampleSpec(form.read(analysis())), null, 2);
    } catch (err) {
      textarea.value = '';
      ui.showError(err);
    }
  };
  const columns = () => shown?.table?.columns ?? [];
  const nParams = () => (shown?.spec_parameters ?? 0);
  const numericCol = (k) => (shown?.table?.rows ?? []).some((r) => isNum(r[k]));
  // Over columns: "min:O" -> {min, max, mean} column indices of O (all three present).
  const overOf = (k) => {
    const cols = columns(), m = /^(min|max|mean):(.*)$/.exec(cols[k] ?? '');
    if (!m) return null;
    const at = (a) => cols.indexOf(`${a}:${m[2]}`);
    const o = { name: m[2], min: at('min'), max: at('max'), mean: at('mean') };
    return o.min >= 0 && o.max >= 0 && o.mean >= 0 ? o : null;
  };
  const chosen = { x: null, y: null }; // what the user picked, kept while the columns have it
  function setChoices() {
    const cols = columns();
    const opts = (ks) => ks.map((k) => h('option', { value: String(k) }, cols[k]));
    const params = cols.map((_, k) => k).filter((k) => k < nParams());
    // the means first: what an over table is plotted by (its band from min to max)
    const outs = cols.map((_, k) => k).filter((k) => k >= nParams() && k < cols.length - 2 && numericCol(k))
      .sort((a, b) => (cols[b].startsWith('mean:') ? 1 : 0) - (cols[a].startsWith('mean:') ? 1 : 0) || a - b);
    fill($('sw-x'), opts(params.concat(outs)));
    fill($('sw-y'), opts(outs.concat(params)));
    for (const a of ['x', 'y']) {
      const sel = $(`sw-${a}`);
      if (chosen[a] !== null && [...sel.options].some((o) => o.value === chosen[a])) sel.value = chosen[a];
    }
  }
  function draw() {
    if (!shown?.table) return;
    const cols = columns(), rows = shown.table.rows;
    const xk = Number($('sw-x').value), ykChosen = Number($('sw-y').value);
    const st = cols.length - 2;
    const over = overOf(ykChosen), yk = over ? over.mean : ykChosen;
    const yName = over ? `${over.name} (mean, band min to max)` : cols[yk] ?? '';
    const range = (r) => (over && isNum(r[over.min]) ? `, range ${sig(r[over.min], 4)} to ${sig(r[over.max], 4)}` : '');
    const pts = rows.map((r, i) => ({ x: r[xk], y: r[yk], lo: over ? r[over.min] : null, hi: over ? r[over.max] : null, cls: r[st] === 'ok' ? '' : 'failed', id: `sw-pt-${i}`, title: `${cols[xk]} = ${sig(r[xk], 4)}, ${cols[yk]} = ${sig(r[yk], 4)}${range(r)}${r[st] === 'ok' ? '' : ` — ${r[st]}: ${r[st + 1]}`}` }));
    const failed = rows.filter((r) => r[st] !== 'ok');
    const caption = over
      ? `${over.name} against ${cols[xk]}: the mean over the over values (line and markers) and the band from their min to their max, per point done (${rows.length} of ${shown.points}); hover a marker for its values.`
      : `${cols[yk]} against ${cols[xk]}, one marker per point done (${rows.length} of ${shown.points}); hover a marker for its values.`;
    fill($('sw-result'),
      h('figure', { class: 'plot wide' },
        scatter({ id: 'sw-plot', points: pts, xLabel: cols[xk] ?? '', yLabel: yName, label: `${yName} against ${cols[xk]}: ${rows.length} of ${shown.points} points` }),
        h('figcaption', {}, caption)),
      failed.length ? h('ul', { class: 'warnings', id: 'sw-failed' }, failed.slice(0, 20).map((r) =>
        h('li', {}, `${cols.slice(0, nParams()).map((c, k) => `${c} = ${sig(r[k], 4)}`).join(', ')}: ${r[st]} — ${r[st + 1]}`))) : null);
  }
  function show(sweep, spec) {
    const first = !shown || shown.id !== sweep.id;
    shown = { ...sweep, spec_parameters: spec ? (spec.parameters ?? []).length : shown?.spec_parameters ?? 0 };
    if (first) chosen.x = chosen.y = null;
    setChoices();
    $('sw-choose').hidden = false;
    $('sw-csv').hidden = false;
    draw();
  }
  let spec = null;
  const ui = runner('sw', {
    submit: () => {
      try {
        spec = JSON.parse(textarea.value);
      } catch (err) {
        throw { message: `The spec is not JSON: ${err.message}` };
      }
      return spec;
    },
    onUpdate: (s) => show(s, spec),
    onDone: (s) => show(s, spec),
  });
  $('sw-fill').addEventListener('click', fillSpec);
  for (const a of ['x', 'y']) {
    $(`sw-${a}`).addEventListener('change', (e) => { chosen[a] = e.target.value; draw(); });
  }
  $('sw-csv').addEventListener('click', async () => {
    if (!shown) return;
    try {
      saveBlob(await getBlob(`/api/v1/sweeps/${encodeURIComponent(shown.id)}/table.csv`, { headers: { Accept: 'text/csv' } }), `ringdyn-sweep-${shown.id}.csv`);
    } catch (err) {
      ui.showError(err);
    }
  });
  return { opened: () => { if (!textarea.value.trim()) fillSpec(); } };
}

// ---- the Speed vs accuracy view -------------------------------------------------------

// The fidelity table's columns by role (rd_sweep.h: the parameters, then
// wall time, the estimate, [lift: the model that ran], error_vs_finest,
// estimate_covers, changes, basis, error_on_basis, pareto, status, error).
function roles(cols) {
  const wall = cols.indexOf('/numerics/wall_s');
  const at = (name) => cols.indexOf(name);
  return {
    params: cols.slice(0, wall).map((c, k) => [c, k]), wall, est: wall + 1, vs: at('error_vs_finest'),
    covers: at('estimate_covers'), changes: at('changes'), basis: at('basis'), err: at('error_on_basis'),
    pareto: at('pareto'), status: at('status'),
  };
}

const SHORT = { '/discretization/segments': 'segments', '/numerics/rtol': 'rtol', '/numerics/model': 'model' };
// "segments time" (the table's words) as the page says them.
const scope = (words) => (words ? words.split(' ').join(', ') : '');
const percent = (x) => `${sig(x * 100, 2)} %`;

// What a row's error rests on, as its row says it.
function basisText(r, c) {
  if (r[c.basis] === 'estimate') return `estimate (covers: ${scope(r[c.covers])})`;
  if (r[c.basis] === 'measured') return 'measured vs finest';
  return 'none (not comparable with the finest run)';
}

// Why a row's estimate was not its basis (null when it was).
function distrust(r, c) {
  if (r[c.basis] !== 'measured' || !isNum(r[c.est])) return null;
  const missing = (r[c.changes] || '').split(' ').filter((w) => w && !(r[c.covers] || '').split(' ').includes(w));
  return missing.length
    ? `its estimate covers ${scope(r[c.covers]) || 'nothing'}, not the ${missing.join(', ')} it changes`
    : 'its estimate is below its measured difference from the finest run';
}

function fidelityView({ form, analysis, onApply }) {
  let table = null, scene = null;
  function apply(row) {
    const c = roles(table.columns);
    let now;
    try {
      now = form.read(scene.analysis);
    } catch {
      now = structuredClone(scene);
    }
    const set = [];
    for (const [path, k] of c.params) {
      const keys = path.split('/').slice(1);
      let o = now;
      for (const key of keys.slice(0, -1)) o = o[key] ??= {};
      o[keys.at(-1)] = row[k];
      set.push(`${SHORT[path] ?? path} = ${row[k]}`);
    }
    form.load(now);
    const text = `${set.join(', ')} went into the form.`;
    $('fd-applied').textContent = text;
    onApply?.(text);
  }
  function draw() {
    if (!table) return;
    const c = roles(table.columns);
    const rows = table.rows.filter((r) => r[c.status] === 'ok');
    const name = (r) => c.params.map(([p, k]) => `${SHORT[p] ?? p} ${r[k]}`).join(', ');
    const target = Number($('fd-target').value) / 100;
    const cheapest = (rs) => rs.slice().sort((a, b) => a[c.wall] - b[c.wall])[0];
    // Only rows with a basis: measured against the finest run, or an estimate
    // covering every discretisation the row changes (error_on_basis).
    const within = cheapest(rows.filter((r) => r[c.basis] && isNum(r[c.err]) && r[c.err] <= target));
    // A cheaper row whose estimate alone would have passed: say why it is not taken.
    const misled = cheapest(rows.filter((r) => isNum(r[c.est]) && r[c.est] <= target && isNum(r[c.vs]) && !(r[c.err] <= target)
      && (!within || r[c.wall] < within[c.wall])));
    const finest = rows.find((r) => r[c.changes] === '');
    const pts = rows.map((r, i) => ({ x: r[c.wall], y: r[c.err], cls: `${r[c.pareto] ? 'pareto' : 'dominated'} ${r[c.basis] ?? 'none'}`, id: `fd-pt-${i}`, title: `${name(r)}: ${seconds(r[c.wall])}, error ${sig(r[c.err], 2)} (${basisText(r, c)})${r[c.pareto] ? ', Pareto front' : ''}` }));
    const front = pts.filter((p) => p.cls.startsWith('pareto'));
    const body = rows.map((r, i) => h('tr', { class: [r[c.pareto] ? 'pareto' : '', r === within ? 'chosen' : ''].join(' ').trim() || null, id: `fd-row-${i}`, 'data-basis': r[c.basis] ?? 'none' },
      c.params.map(([, k]) => h('td', { class: 'num' }, String(r[k]))),
      h('td', { class: 'num' }, seconds(r[c.wall])),
      h('td', { class: 'est' }, isNum(r[c.est]) ? `${sig(r[c.est], 2)}, covers ${scope(r[c.covers])}` : '—'),
      h('td', { class: 'num' }, sig(r[c.vs], 2)),
      h('td', { class: 'basis' }, basisText(r, c)),
      h('td', { class: 'num' }, sig(r[c.err], 2)),
      h('td', {}, r[c.pareto] ? h('button', { type: 'button', class: 'use', id: `fd-use-${i}`, 'aria-label': `Use ${name(r)} in the form` }, 'Use') : '')));
    const useButtons = new Map(rows.map((r, i) => [`fd-use-${i}`, r]));
    const on = (r) => (r[c.basis] === 'estimate'
      ? `on its estimate, ${percent(r[c.err])} (covers: ${scope(r[c.covers])}); measured against the finest run: ${percent(r[c.vs])}`
      : `measured against the finest run${finest ? ` (${name(finest)})` : ''}: ${percent(r[c.err])}`);
    fill($('fd-result'),
      h('figure', { class: 'plot wide' },
        scatter({ id: 'fd-plot', points: pts, front, xLog: true, yLog: true, xLabel: 'wall time (s, with the estimate)', yLabel: 'error on its basis', label: `Wall time against error of ${rows.length} settings, each on its basis; ${front.length} on the Pareto front` }),
        h('figcaption', {}, 'Each fidelity setting of the scene: its cost (wall time of the run with its error estimate) against its error, both log scales. A setting\'s error is its difference from the finest setting\'s result (measured), or its own estimate where that covers every discretisation the setting changes and is not below the measured difference; the table says which. Filled and joined: the Pareto front, the settings no other beats in both.')),
      h('p', { id: 'fd-cheapest', 'data-basis': within?.[c.basis] ?? null }, within
        ? ['Cheapest setting within ', `${sig(target * 100, 3)} %`, `: ${name(within)} (${seconds(within[c.wall])}), ${on(within)}. `, h('button', { type: 'button', id: 'fd-use-cheapest' }, 'Use it')]
        : `No setting is within ${sig(target * 100, 3)} % measured against the finest run, or on an estimate that covers what the setting changes.`),
      misled ? h('p', { class: 'hint', id: 'fd-distrusted' }, `Not ${name(misled)} (${seconds(misled[c.wall])}): ${distrust(misled, c) ?? 'its estimate is not its basis'}, and it differs from the finest run by ${percent(misled[c.vs])}.`) : null,
      h('div', { class: 'table-wrap' }, h('table', { class: 'modes', id: 'fd-table' },
        h('caption', {}, 'Fidelity settings (ok runs). Vs finest: the measured difference from the finest setting\'s result, which falls short of the true error by that run\'s own. Basis: what the error the recommendation uses rests on.'),
        h('thead', {}, h('tr', {}, c.params.map(([p]) => h('th', { scope: 'col' }, SHORT[p] ?? p)), h('th', { scope: 'col' }, 'wall'), h('th', { scope: 'col' }, 'estimate, its scope'), h('th', { scope: 'col' }, 'vs finest'), h('th', { scope: 'col' }, 'basis'), h('th', { scope: 'col' }, 'error'), h('th', { scope: 'col' }, 'Pareto'))),
        h('tbody', {}, body))));
    for (const [id, r] of useButtons) $(id)?.addEventListener('click', () => apply(r));
    $('fd-use-cheapest')?.addEventListener('click', () => apply(within));
  }
  runner('fd', {
    submit: () => {
      scene = form.read(analysis());
      table = null;
      fill($('fd-result'));
      $('fd-applied').textContent = '';
      return { fidelity: scene };
    },
    onUpdate: () => {},
    onDone: (s) => {
      table = s.fidelity ?? null;
      if (table) draw();
      else fill($('fd-result'), h('p', { class: 'hint' }, `The sweep ${s.status} before every setting ran: no fidelity table.`));
    },
  });
  $('fd-target').addEventListener('input', draw);
  return { opened: () => {} };
}

// ---- the view tabs ---------------------------------------------------------------

export function setupSweeps({ form, analysis, onApply }) {
  const views = { result: null, sweep: sweepView({ form, analysis }), fidelity: fidelityView({ form, analysis, onApply }), calibrate: calibrateView({ form, analysis }) };
  const ids = Object.keys(views);
  const select = (id) => {
    for (const v of ids) {
      const tab = $(`view-${v}`);
      tab.setAttribute('aria-selected', String(v === id));
      tab.tabIndex = v === id ? 0 : -1;
      $(`${v}-view`).hidden = v !== id;
    }
    views[id]?.opened();
  };
  for (const v of ids) $(`view-${v}`).addEventListener('click', () => select(v));
  $('views').addEventListener('keydown', (e) => {
    const step = { ArrowRight: 1, ArrowLeft: -1 }[e.key];
    if (!step) return;
    const i = ids.findIndex((v) => $(`view-${v}`).getAttribute('aria-selected') === 'true');
    const next = ids[(i + step + ids.length) % ids.length];
    select(next);
    $(`view-${next}`).focus();
  });
  select('result');
  return { select };
}
