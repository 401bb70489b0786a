// ringdyn web page: one tab per analysis.  An analysis is an object
// {id, label, runLabel, render(result, job, container)} plus a
// <fieldset data-analysis="id"> in index.html for its own scene fields; the
// ring, material and discretization fields are shared by all analyses.
// To add one: write its module, add its fieldset, and list it in ANALYSES.
// An analysis may also have setup({form, examples, error}), called once the
// shipped examples are known (lift takes its gas tables from them).

import { getJSON, runJob, cancelJob, ApiError } from './api.js';
import { SceneForm } from './form.js';
import { modal } from './modal.js';
import { pretension } from './pretension.js';
import { contact } from './contact.js';
import { lift } from './lift.js';

const ANALYSES = [modal, pretension, contact, lift];

// How long the submit request waits for the result before the page polls
// instead (API.md ?wait=, 0..300 s); the page URL may set it: /?wait=0.
const WAIT_S = (() => {
  const v = Number(new URLSearchParams(location.search).get('wait') ?? 60);
  return Number.isInteger(v) && v >= 0 && v <= 300 ? v : 60;
})();

const $ = (id) => document.getElementById(id);

const state = {
  analysis: ANALYSES[0],
  results: new Map(), // analysis id -> {result, job}, so switching tabs keeps them
  run: null, // {controller, jobId} while a job is in flight
};

const form = new SceneForm($('scene-form'));

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
  const done = state.results.get(a.id);
  if (done) showResult(done.result, done.job);
  else clearResult();
}

function setStatus(text, progress) {
  $('status-text').textContent = text;
  const bar = $('progress');
  bar.hidden = progress === undefined;
  if (progress === null) bar.removeAttribute('value'); // indeterminate
  else if (progress !== undefined) bar.value = progress;
}

function showError(err) {
  const box = $('error');
  const fields = form.mark(err.path, 'error');
  const where = fields.length ? `${form.nameOf(fields)}: ` : '';
  box.replaceChildren();
  const strong = document.createElement('strong');
  strong.textContent = where;
  box.append(strong, err.message || 'Unknown error');
  if (err.path && !box.textContent.includes(err.path)) {
    const code = document.createElement('code');
    code.textContent = err.path;
    box.append(' (', code, ')');
  }
  box.hidden = false;
}

function clearError() {
  $('error').hidden = true;
  $('error').replaceChildren();
  form.clearMarks();
}

function clearResult() {
  $('result-body').replaceChildren();
  $('results-empty').hidden = false;
}

function showResult(result, job) {
  $('results-empty').hidden = true;
  state.analysis.render(result, job, $('result-body'));
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
    showError(err);
    return;
  }
  const controller = new AbortController();
  state.run = { controller, jobId: null };
  $('run').disabled = true;
  $('cancel').hidden = false;
  $('results').setAttribute('aria-busy', 'true');
  setStatus('Running…', null);
  const t0 = performance.now();
  try {
    const job = await runJob(scene, {
      wait: WAIT_S,
      signal: controller.signal,
      onUpdate: (j) => {
        state.run.jobId = j.id;
        const p = Number.isFinite(j.progress) ? j.progress : null;
        setStatus(`Job ${j.id} ${j.status}${p === null ? '' : ` — ${Math.round(p * 100)} %`}`, p);
      },
    });
    const secs = ((performance.now() - t0) / 1000).toFixed(2);
    if (job.status === 'succeeded') {
      state.results.set(analysis.id, { result: job.result, job });
      if (state.analysis === analysis) {
        showResult(job.result, job);
        // One column (narrow screen): the results are below the form.
        if (matchMedia('(max-width: 820px)').matches) $('results').scrollIntoView({ block: 'start' });
      }
      setStatus(`Job ${job.id} succeeded in ${secs} s.`);
    } else {
      setStatus(`Job ${job.id} ${job.status}.`);
      if (job.error) showError(job.error);
    }
  } catch (err) {
    if (err.name === 'AbortError') {
      setStatus('Cancelled.');
    } else {
      setStatus('');
      showError(err instanceof ApiError ? err : { message: String(err.message || err) });
    }
  } finally {
    state.run = null;
    $('run').disabled = false;
    $('cancel').hidden = true;
    $('results').removeAttribute('aria-busy');
  }
}

function cancel() {
  if (!state.run) return;
  if (state.run.jobId !== null) cancelJob(state.run.jobId);
  state.run.controller.abort();
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
$('scene-form').addEventListener('submit', run);
$('cancel').addEventListener('click', cancel);
$('reset').addEventListener('click', () => {
  form.reset();
  clearError();
  $('example').value = '';
  $('example-desc').textContent = '';
});
loadExamples();
loadVersion();
