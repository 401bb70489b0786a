// ringdyn web page: one tab per analysis.  An analysis is an object
// {id, label, runLabel, render(result, job, container)} plus a
// <fieldset data-analysis="id"> in index.html for its own scene fields; the
// ring, material and discretization fields are shared by all analyses.
// To add one: write its module, add its fieldset, and list it in ANALYSES.
// An analysis may also have setup({form, examples, error}), called once the
// shipped examples are known (lift takes its gas tables from them).

import { getJSON, getBlob, runJob, watchJob, cancelJob, ApiError } from './api.js';
import { SceneForm } from './form.js';
import { modal } from './modal.js';
import { pretension } from './pretension.js';
import { contact } from './contact.js';
import { lift } from './lift.js';
import { ringpack } from './ringpack.js';
import { curlText, pythonText, saveBlob } from './script.js';
import { watchCharts, addExportButtons } from './charts.js';
import { keepRun, keptRun, clearKept, overlayKept } from './plotui.js';
import { setupSweeps } from './sweep.js';
import { setupBoreMaps } from './boremap.js';

const ANALYSES = [modal, pretension, contact, lift, ringpack];

// How long the submit request waits for the result before the page polls
// (API.md ?wait=, 0..300 s).  0: the job's id, progress and Cancel are there
// at once; the page URL may set another: /?wait=5.
const PARAMS = new URLSearchParams(location.search);
const WAIT_S = (() => {
  const v = Number(PARAMS.get('wait') ?? 0);
  return Number.isInteger(v) && v >= 0 && v <= 300 ? v : 0;
})();

const $ = (id) => document.getElementById(id);

const state = {
  analysis: ANALYSES[0],
  // analysis id -> {result, job, stale}: switching tabs keeps them; `stale`
  // (a sentence) marks a result that a newer run has made out of date.
  results: new Map(),
  run: null, // while a job is in flight: {controller, jobId, t0, runningSince, cancelling, cancelSent}
};

const form = new SceneForm($('scene-form'));
for (const a of ANALYSES) if (a.fieldPaths) form.setFieldPaths(a.id, a.fieldPaths);

function buildTabs() {
  const list = $('tabs');
  for (const a of ANALYSES) {
    const tab = document.createElement('button');
    tab.type = 'button';
    tab.setAttribute('role', 'tab');
    tab.id = `tab-${a.id}`;
    tab.textContent = a.label;
    tab.setAttribute('aria-controls', 'panel');
    tab.addEventListener('click', () => selectAnalysis(a));
    list.append(tab);
  }
  list.addEventListener('keydown', (e) => {
    const step = { ArrowRight: 1, ArrowLeft: -1 }[e.key];
    if (!step) return;
    const i = ANALYSES.indexOf(state.analysis);
    const next = ANALYSES[(i + step + ANALYSES.length) % ANALYSES.length];
    selectAnalysis(next);
    $(`tab-${next.id}`).focus();
  });
}

function selectAnalysis(a) {
  state.analysis = a;
  for (const b of ANALYSES) {
    const tab = $(`tab-${b.id}`);
    tab.setAttribute('aria-selected', String(b === a));
    tab.tabIndex = b === a ? 0 : -1;
  }
  $('panel').setAttribute('aria-labelledby', `tab-${a.id}`);
  form.showAnalysis(a.id);
  $('run').textContent = a.runLabel;
  showEntry(state.results.get(a.id));
}

function setStatus(text, progress) {
  $('status-text').textContent = text;
  const bar = $('progress');
  bar.hidden = progress === undefined;
  if (progress === null) bar.removeAttribute('value'); // indeterminate
  else if (progress !== undefined) bar.value = progress;
}

// One problem of an error: "Field label: message (path)", its fields marked.
function errorItem(err, focus) {
  const fields = form.mark(err.path, 'error', focus);
  const where = fields.length ? `${form.nameOf(fields)}: ` : '';
  const strong = document.createElement('strong');
  strong.textContent = where;
  const parts = [strong, err.message || 'Unknown error'];
  if (err.path && !`${where}${err.message}`.includes(err.path)) {
    const code = document.createElement('code');
    code.textContent = err.path;
    parts.push(' (', code, ')');
  }
  return parts;
}

// Shows an error and every problem it lists (the server's `errors`: the
// first is `error` itself), marking the field of each; the first is focused.
function showError(err) {
  const box = $('error');
  box.replaceChildren();
  const list = Array.isArray(err.errors) && err.errors.length ? err.errors : [err];
  if (list.length === 1) {
    box.append(...errorItem(list[0], true));
  } else {
    const ul = document.createElement('ul');
    ul.className = 'error-list';
    list.forEach((e, i) => {
      const li = document.createElement('li');
      li.dataset.path = e.path || '';
      li.append(...errorItem(e, i === 0));
      ul.append(li);
    });
    box.append(ul);
    if (err.errors_omitted > 0) box.append(`… and ${err.errors_omitted} more.`);
  }
  box.hidden = false;
}

function clearError() {
  $('error').hidden = true;
  $('error').replaceChildren();
  form.clearMarks();
}

// Shows a results entry ({result, job, stale}) of the shown analysis, or none.
function showEntry(entry) {
  const body = $('result-body');
  const note = $('result-stale');
  const warnings = $('result-warnings');
  if (!entry) {
    body.replaceChildren();
    $('compare').hidden = true;
    $('results-empty').hidden = false;
    note.hidden = true;
    warnings.hidden = true;
    return;
  }
  $('results-empty').hidden = true;
  state.analysis.render(entry.result, entry.job, body);
  markStale(entry);
  showCompare(entry);
  // Warnings the server attaches to a result (strings or {message, path}).
  const list = Array.isArray(entry.result.warnings) ? entry.result.warnings : [];
  warnings.replaceChildren(...list.map((w) => {
    const li = document.createElement('li');
    li.textContent = typeof w === 'string' ? w : `${w?.message ?? JSON.stringify(w)}${w?.path ? ` (${w.path})` : ''}`;
    return li;
  }));
  warnings.hidden = list.length === 0;
}

// ---- compare runs: a kept result drawn dashed under the next ones --------

const keptLabel = (job) => `job ${job?.id ?? 'unknown'}`;

// The keep / clear buttons and the note for the shown entry; a kept run of
// this analysis (another job) is drawn over its charts.
function showCompare(entry) {
  const k = keptRun();
  const mine = k && k.key === state.analysis.id;
  const same = mine && k.label === keptLabel(entry.job);
  $('compare').hidden = false;
  $('keep-run').disabled = Boolean(same);
  $('clear-kept').hidden = !k;
  if (!k) $('compare-note').textContent = '';
  else if (!mine) $('compare-note').textContent = `Kept for comparison: ${k.label} of ${k.key}.`;
  else if (same) $('compare-note').textContent = `This run (${k.label}) is kept: the next ${state.analysis.label.toLowerCase()} run draws over it, dashed.`;
  else {
    const n = overlayKept($('result-body'), k.key);
    $('compare-note').textContent = `Dashed: ${k.label}, kept for comparison${n ? '' : ' (no chart in common with this result)'}.`;
  }
}

function keepShown() {
  const entry = state.results.get(state.analysis.id);
  if (!entry) return;
  clearKept($('result-body'));
  keepRun($('result-body'), state.analysis.id, keptLabel(entry.job));
  showCompare(entry);
}

function clearShownKept() {
  clearKept($('result-body'));
  const entry = state.results.get(state.analysis.id);
  if (entry) showCompare(entry);
  $('compare-note').textContent = 'Comparison cleared.';
}

function markStale(entry) {
  const note = $('result-stale');
  note.textContent = entry.stale || '';
  note.hidden = !entry.stale;
  $('result-body').classList.toggle('stale', Boolean(entry.stale));
}

// Marks the shown analysis's result (if any) as out of date, saying why.
function staleResult(analysis, why) {
  const entry = state.results.get(analysis.id);
  if (!entry) return;
  entry.stale = `Out of date: ${why} The result below is from an earlier job (${entry.job?.id ?? 'unknown'}).`;
  if (state.analysis === analysis) markStale(entry);
}

// The page URL names the job shown or running: /?job=<id> reopens it.
function setJobInUrl(id) {
  const url = new URL(location.href);
  if (id) url.searchParams.set('job', id);
  else url.searchParams.delete('job');
  history.replaceState(null, '', url);
}

const clock = (s) => (s < 60 ? `${Math.round(s)} s` : `${Math.floor(s / 60)} min ${String(Math.round(s % 60)).padStart(2, '0')} s`);

// "Job … running — 42 % · 3 s elapsed · about 4 s left": the server's eta_s
// when it gives one, else progress against the time it has been running.
function progressLine(j, run) {
  const now = performance.now();
  if (j.status === 'running' && run.runningSince === null) run.runningSince = run.seenQueued ? now : run.t0;
  if (j.status === 'queued') run.seenQueued = true;
  const p = Number.isFinite(j.progress) ? j.progress : null;
  const parts = [`Job ${j.id} ${j.status}${p !== null && j.status === 'running' ? ` — ${Math.round(p * 100)} %` : ''}`];
  if (run.runningSince !== null) {
    const elapsed = (now - run.runningSince) / 1000;
    parts.push(`${clock(elapsed)} elapsed`);
    let eta = Number.isFinite(j.eta_s) ? j.eta_s : null;
    if (eta === null && p > 0.02 && p < 1 && elapsed > 0.3) eta = (elapsed * (1 - p)) / p;
    parts.push(eta === null ? 'estimating the time left' : `about ${clock(eta)} left`);
  }
  return parts.join(' · ');
}

// Follows a job until it ends: `start(signal, onUpdate)` resolves with the
// finished job (runJob for a new one, watchJob for a reopened one).
async function follow(analysis, start) {
  const controller = new AbortController();
  const run = { controller, jobId: null, t0: performance.now(), runningSince: null, seenQueued: false, cancelling: false, cancelSent: false };
  state.run = run;
  $('run').disabled = true;
  $('cancel').hidden = false;
  $('cancel').disabled = false;
  $('results').setAttribute('aria-busy', 'true');
  staleResult(analysis, 'a new job is running.');
  setStatus('Submitting…', null);
  try {
    const job = await start(controller.signal, (j) => {
      if (run.jobId === null) {
        run.jobId = j.id;
        setJobInUrl(j.id);
        if (run.cancelling) sendCancel(run); // Cancel was pressed before the job had an id
      }
      const p = Number.isFinite(j.progress) && j.status === 'running' ? j.progress : null;
      setStatus(run.cancelling ? `Cancelling job ${j.id}…` : progressLine(j, run), p);
    });
    setJobInUrl(job.id);
    // A job reopened already finished was never followed: no time to give.
    const secs = run.jobId === null ? '' : ` in ${((performance.now() - run.t0) / 1000).toFixed(2)} s`;
    if (job.status === 'succeeded') {
      state.results.set(analysis.id, { result: job.result, job, stale: '' });
      if (state.analysis === analysis) {
        showEntry(state.results.get(analysis.id));
        // One column (narrow screen): the results are below the form.
        if (matchMedia('(max-width: 820px)').matches) $('results').scrollIntoView({ block: 'start' });
      }
      setStatus(`Job ${job.id} succeeded${secs}.`);
    } else if (job.result && job.result.partial) {
      // A lift job stopped by Cancel or the time limit keeps its whole cycles.
      state.results.set(analysis.id, { result: job.result, job, stale: '' });
      if (state.analysis === analysis) showEntry(state.results.get(analysis.id));
      const upTo = job.result.crank_deg[job.result.crank_deg.length - 1];
      setStatus(`Job ${job.id} ${job.status}; the cycles it finished (to ${upTo}°) are shown: a partial result.`);
      if (job.status !== 'cancelled' && job.error) showError(job.error);
    } else if (job.status === 'cancelled') {
      setStatus(`Job ${job.id} cancelled.`);
      staleResult(analysis, `job ${job.id} was cancelled.`);
    } else {
      setStatus(`Job ${job.id} ${job.status}.`);
      staleResult(analysis, `job ${job.id} ${job.status}.`);
      if (job.error) showError(job.error);
    }
  } catch (err) {
    if (err.name === 'AbortError') {
      setStatus(run.jobId ? `Stopped following job ${run.jobId}.` : 'Cancelled.');
      staleResult(analysis, 'the last run was cancelled.');
    } else {
      setStatus('');
      staleResult(analysis, 'the last run failed (see the message by the Run button).');
      showError(err instanceof ApiError ? err : { message: String(err.message || err) });
    }
  } finally {
    state.run = null;
    $('run').disabled = false;
    $('cancel').hidden = true;
    $('results').removeAttribute('aria-busy');
  }
}

async function run(event) {
  event.preventDefault();
  if (state.run) return;
  clearError();
  const analysis = state.analysis;
  let scene;
  try {
    scene = form.read(analysis.id);
  } catch (err) {
    staleResult(analysis, 'the form has an error.');
    showError(err);
    return;
  }
  views.select('result'); // the run's result is what to see now
  await follow(analysis, (signal, onUpdate) => runJob(scene, { wait: WAIT_S, signal, onUpdate }));
}

// DELETE the job; the poll then sees it end "cancelled".  If the server
// cannot be asked, stop following the job instead.
async function sendCancel(run) {
  if (run.cancelSent) return;
  run.cancelSent = true;
  const resp = await cancelJob(run.jobId);
  if (!resp?.ok && state.run === run) run.controller.abort();
}

function cancel() {
  const run = state.run;
  if (!run || run.cancelling) return;
  run.cancelling = true;
  $('cancel').disabled = true;
  setStatus(run.jobId ? `Cancelling job ${run.jobId}…` : 'Cancelling…', null);
  // Without an id yet (the submission is on its way) the update that brings it cancels.
  if (run.jobId !== null) sendCancel(run);
}

// /?job=<id>: shows that job — its result and scene, or its progress while it runs.
async function reopen(id) {
  let job;
  try {
    job = await getJSON(`/api/v1/jobs/${encodeURIComponent(id)}`);
  } catch (err) {
    showError({ ...err, errors: null, message: `Job ${id} from the page address: ${err.message}` });
    return;
  }
  const name = job.analysis ?? job.result?.analysis;
  const analysis = ANALYSES.find((a) => a.id === name);
  if (analysis) selectAnalysis(analysis);
  if (job.result?.scene) form.load(job.result.scene);
  if (!analysis) {
    setStatus(`Job ${job.id} (${name ?? 'unknown analysis'}) ${job.status}: this page does not show it.`);
    return;
  }
  await follow(analysis, (signal, onUpdate) => watchJob(job, { signal, onUpdate }));
}

// ---- the form as a file or a script ------------------------------------

function toolStatus(text) {
  $('tools-status').textContent = text;
}

// The scene of the form, or null after showing why there is none.
function currentScene() {
  clearError();
  try {
    return form.read(state.analysis.id);
  } catch (err) {
    showError(err);
    toolStatus('');
    return null;
  }
}

async function copyScript(kind) {
  const scene = currentScene();
  if (!scene) return;
  const text = kind === 'curl' ? curlText(scene, location.origin) : pythonText(scene, location.origin);
  const out = $('script-out');
  out.textContent = text;
  out.hidden = false;
  out.dataset.kind = kind;
  const what = kind === 'curl' ? 'The curl command' : 'The Python program (standard library only)';
  toolStatus(`${what} is below.`);
  // The clipboard may be refused, or wait for a permission that never comes.
  const refused = new Promise((_, reject) => setTimeout(() => reject(new Error('no answer')), 2000));
  try {
    await Promise.race([navigator.clipboard.writeText(text), refused]);
    toolStatus(`${what} is on the clipboard and below.`);
  } catch {
    toolStatus(`${what} is below (the browser did not allow copying it to the clipboard).`);
  }
}

function saveScene() {
  const scene = currentScene();
  if (!scene) return;
  saveBlob(new Blob([`${JSON.stringify(scene, null, 2)}\n`], { type: 'application/json' }), `ringdyn-${scene.analysis}-scene.json`);
  toolStatus(`Saved as ringdyn-${scene.analysis}-scene.json.`);
}

// A scene file: a scene, or anything holding one (an example, a job's result).
async function loadSceneFile(file) {
  clearError();
  let data;
  try {
    data = JSON.parse(await file.text());
  } catch (err) {
    showError({ message: `${file.name} is not JSON: ${err.message}` });
    return;
  }
  const scene = [data, data?.scene, data?.result?.scene].find((s) => s && typeof s === 'object' && typeof s.analysis === 'string');
  if (!scene) {
    showError({ message: `${file.name} holds no scene: a scene is a JSON object with an "analysis" (see API.md).` });
    return;
  }
  form.load(scene);
  const target = ANALYSES.find((a) => a.id === scene.analysis);
  if (target) selectAnalysis(target);
  $('example').value = '';
  $('example-desc').textContent = '';
  toolStatus(target
    ? `Loaded ${file.name} (${scene.analysis}${typeof scene.name === 'string' ? `: ${scene.name}` : ''}).`
    : `Loaded the ring fields of ${file.name}; its analysis “${scene.analysis}” is not one this page runs.`);
}

// A result's CSV link: fetched and saved under its download name
// (ringdyn-<analysis>-<id>.csv; the server's own header names only the id).
async function saveCsv(e) {
  const a = e.target.closest('a[download][href$=".csv"]');
  if (!a) return;
  e.preventDefault();
  try {
    saveBlob(await getBlob(a.href, { headers: { Accept: 'text/csv' } }), a.getAttribute('download'));
  } catch (err) {
    showError(err instanceof ApiError ? err : { message: `The CSV could not be fetched: ${err.message}` });
  }
}

async function loadExamples() {
  const select = $('example');
  let examples = [];
  try {
    examples = (await getJSON('/api/v1/examples')).examples || [];
  } catch (err) {
    select.disabled = true;
    $('example-desc').textContent = `Examples unavailable: ${err.message}`;
    for (const a of ANALYSES) a.setup?.({ form, examples: [], error: err });
    return;
  }
  for (const a of ANALYSES) a.setup?.({ form, examples });
  examples.forEach((ex, i) => {
    const opt = document.createElement('option');
    opt.value = String(i);
    opt.textContent = typeof ex.scene?.name === 'string' ? ex.scene.name : ex.name;
    if (ex.description) opt.title = ex.description;
    select.append(opt);
  });
  select.addEventListener('change', () => {
    clearError();
    const ex = examples[Number(select.value)];
    if (!ex) {
      form.reset();
      $('example-desc').textContent = '';
      return;
    }
    form.load(ex.scene || {});
    const target = ANALYSES.find((a) => a.id === ex.scene?.analysis);
    if (target && target !== state.analysis) selectAnalysis(target);
    let text = ex.description || '';
    if (!target && ex.scene?.analysis) {
      text += ` (A “${ex.scene.analysis}” scene: this page runs ${ANALYSES.map((a) => a.label.toLowerCase()).join(', ')} only; its ring fields were loaded.)`;
    }
    $('example-desc').textContent = text;
  });
}

async function loadVersion() {
  try {
    const h = await getJSON('/api/v1/health');
    $('version').textContent = `ringdyn ${h.version || ''}`.trim();
  } catch {
    $('version').textContent = 'server not reachable';
  }
}

// The form's defaults come from the server's scene schemas (one source with
// the scene parser); the tabs appear once they are in.
try {
  form.setDefaults(await getJSON('/api/v1/openapi.json'), ANALYSES[0].id);
} catch (err) {
  setStatus(`Field defaults unavailable (${err.message}); fill in every field.`);
}
buildTabs();
selectAnalysis(state.analysis);
// Every figure shown gets SVG / PNG buttons, also one redrawn later (lift's
// cycle zoom, modal's mode shape).
watchCharts($('result-body'), () => {
  const entry = state.results.get(state.analysis.id);
  addExportButtons($('result-body'), `ringdyn-${state.analysis.id}-${entry?.job?.id ?? 'result'}`);
  // A chart redrawn (a mode shape, a cycle zoom) gets the kept run again.
  const k = keptRun();
  if (entry && k && k.key === state.analysis.id && k.label !== keptLabel(entry.job)) overlayKept($('result-body'), k.key);
});
$('keep-run').addEventListener('click', keepShown);
$('clear-kept').addEventListener('click', clearShownKept);
// The bore maps of the Contact and Lift tabs, drawn as they are entered.
setupBoreMaps(form);
$('scene-form').addEventListener('submit', run);
$('cancel').addEventListener('click', cancel);
$('reset').addEventListener('click', () => {
  form.reset();
  clearError();
  $('example').value = '';
  $('example-desc').textContent = '';
});
$('copy-curl').addEventListener('click', () => copyScript('curl'));
$('copy-python').addEventListener('click', () => copyScript('python'));
$('save-scene').addEventListener('click', saveScene);
$('load-scene').addEventListener('click', () => $('load-scene-file').click());
$('load-scene-file').addEventListener('change', (e) => {
  const file = e.target.files?.[0];
  e.target.value = '';
  if (file) loadSceneFile(file);
});
$('result-body').addEventListener('click', saveCsv);
// The Sweep and Speed vs accuracy views: their base scene is the form's, of
// the analysis shown.
const views = setupSweeps({ form, analysis: () => state.analysis.id, onApply: (text) => setStatus(text) });
watchCharts($('sweep-view'));
watchCharts($('fidelity-view'));
loadVersion();
// A job in the address is reopened once the examples (the gas tables the
// form offers) are known.
loadExamples().then(() => {
  const id = PARAMS.get('job');
  if (id) reopen(id);
});
