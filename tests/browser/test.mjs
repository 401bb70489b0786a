// Headless-browser test of the ringdyn web page against a running server.
//   RINGDYN_URL       base URL of the server (required; run.sh starts one)
//   RINGDYN_SHOT_DIR  where the screenshots go (default /tmp)
// Run: node --test test.mjs   (the tests share one page and run in order)
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import * as fixtures from './fixtures.mjs';
import { interactTests } from './interact.mjs';
import { ringpackPageTests } from './ringpack_page.mjs';

const CHROMIUM = '/usr/bin/chromium';
const BASE = (process.env.RINGDYN_URL || '').replace(/\/$/, '');
const SHOT_DIR = process.env.RINGDYN_SHOT_DIR || '/tmp';

let chromium;
try {
  ({ chromium } = await import('playwright-core'));
} catch (e) {
  throw new Error(`playwright-core is not installed in tests/browser (run "npm install" there; scripts/test.sh does): ${e.message}`);
}
if (!BASE) throw new Error('RINGDYN_URL is not set: point it at a running ringdyn-server (tests/browser/run.sh does)');
if (!fs.existsSync(CHROMIUM)) throw new Error(`${CHROMIUM} is missing: install the Debian package chromium (scripts/install-deps.sh --test)`);

let browser, page;
const consoleErrors = [];
const pageErrors = [];
// The 422 of the invalid-segments case is logged by Chromium as a failed
// resource load; that one is expected, nothing else is.
const expectedConsole = (text) => /status of 422/.test(text);

before(async () => {
  browser = await chromium.launch({
    executablePath: CHROMIUM,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const context = await browser.newContext({ viewport: { width: 1280, height: 800 } });
  page = await context.newPage();
  page.setDefaultTimeout(20000);
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => pageErrors.push(e.message));
  await page.goto(`${BASE}/`);
  // app.js has run when the tab exists and the examples request has settled.
  await page.waitForSelector('#tab-modal[aria-selected="true"]');
});

after(async () => {
  await browser?.close();
});

const shot = (name, opts = {}) => page.screenshot({ path: path.join(SHOT_DIR, name), ...opts });

// Clicks the run button (named `label`) and waits until the job has ended
// (button enabled again).
async function runAnalysis(label = 'Run modal analysis', timeout = 90000) {
  await page.getByRole('button', { name: label }).click();
  await page.waitForFunction(() => !document.getElementById('run').disabled, null, { timeout });
}

async function modeRows() {
  return page.$$eval('#modes-table tbody tr', (rows) => rows.map((r) => ({
    mode: Number(r.querySelector('button.mode-select').textContent),
    kind: r.dataset.kind,
    kindText: r.querySelector('.kind').textContent.trim(),
    freq: Number(r.querySelector('.freq').textContent),
  })));
}

test('default modal analysis: table, plot, cost line, links', { timeout: 120000 }, async () => {
  // The form starts at the thesis defaults.
  assert.equal(await page.inputValue('#f-diameter'), '0.0765');
  assert.equal(await page.inputValue('#f-segments'), '20');
  assert.equal(await page.inputValue('#f-modes'), '6');
  // Those defaults are the served scene schema's: every field has one, and a
  // shared, a modal and a lift field match the document (no copy in the page).
  const missing = await page.$$eval('[data-path]:not([data-optional])',
    (els) => els.filter((e) => e.dataset.default === undefined).map((e) => e.id));
  assert.deepEqual(missing, []);
  const schemas = (await (await fetch(`${BASE}/api/v1/openapi.json`)).json()).components.schemas;
  const dflt = (id) => page.$eval(id, (e) => Number(e.dataset.default));
  assert.equal(await dflt('#f-youngs-modulus'), schemas.Ring.properties.material.properties.youngs_modulus.default);
  assert.equal(await dflt('#f-modes'), schemas.ModalOptions.properties.modes.default);
  assert.equal(await dflt('#f-lf-speed'), schemas.Engine.properties.speed_rpm.default);
  assert.match(await page.textContent('#f-diameter-hint'), /76\.5 mm/);

  await runAnalysis();
  assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);

  const rows = await modeRows();
  assert.equal(rows.length, 6, 'six elastic modes requested');
  rows.forEach((r, i) => {
    assert.equal(r.mode, i + 1);
    assert.ok(r.freq > 0, `mode ${r.mode} frequency ${r.freq} > 0`);
    if (i > 0) assert.ok(r.freq >= rows[i - 1].freq, `frequencies ascending at mode ${r.mode}`);
    assert.ok(['in_plane', 'out_of_plane'].includes(r.kind), `mode ${r.mode} kind ${r.kind}`);
    assert.match(r.kindText, /^(in-plane|out-of-plane)$/);
  });

  // One marker per mode, of the same kind as its row.
  const markers = await page.$$eval('#freq-plot .marker', (gs) => gs.map((g) => g.dataset.kind));
  assert.equal(markers.length, 6);
  assert.deepEqual(markers, rows.map((r) => r.kind));
  assert.equal(await page.locator('#freq-plot .legend').count(), 1);

  // A free ring has 6 rigid-body modes; each rigid segment has 6 DOF (6 x 20).
  assert.match(await page.textContent('#rigid-body'), /^6 rigid-body modes/);
  const cost = await page.textContent('#cost');
  assert.match(cost, /20 segments/);
  assert.match(cost, /120 DOF/);
  assert.match(cost, /iterations/);

  // The CSV and raw JSON links point at this job and answer.
  const csvHref = await page.getAttribute('#csv-link', 'href');
  assert.match(csvHref, /^\/api\/v1\/jobs\/[^/]+\/result\.csv$/);
  const csv = await page.request.get(`${BASE}${csvHref}`);
  assert.equal(csv.status(), 200);
  const lines = (await csv.text()).trim().split('\n');
  assert.ok(lines.length >= 7, `CSV has a header and 6 mode rows (got ${lines.length} lines)`);
  const json = await page.request.get(`${BASE}${await page.getAttribute('#json-link', 'href')}`);
  assert.equal(json.status(), 200);
  const job = await json.json();
  assert.equal(job.status, 'succeeded');
  // The table shows the job's modes (frequencies rounded to 0.1 Hz).
  job.result.modes.forEach((m, i) => {
    assert.ok(Math.abs(rows[i].freq - m.frequency_hz) <= 0.05 + 1e-9, `mode ${i + 1}: ${rows[i].freq} vs ${m.frequency_hz}`);
    assert.equal(rows[i].kind, m.kind);
  });

  assert.deepEqual(pageErrors, []);
  assert.deepEqual(consoleErrors, []);
  await shot('ringdyn-modal.png');
});

test('invalid segment count: message names the field, field highlighted', { timeout: 120000 }, async () => {
  await page.fill('#f-segments', '1');
  await runAnalysis();
  const error = page.locator('#error');
  assert.ok(await error.isVisible(), 'error box shown');
  const text = await error.textContent();
  assert.match(text, /segments/i, `error names the field: ${text}`);
  assert.match(text, /\/discretization\/segments/);
  assert.equal(await page.getAttribute('#f-segments', 'aria-invalid'), 'true');
  assert.ok(await page.locator('.field.invalid #f-segments').count() === 1, 'field marked invalid');
  assert.equal(await page.evaluate(() => document.activeElement.id), 'f-segments', 'invalid field focused');
  // Only that field is marked.
  assert.equal(await page.locator('[aria-invalid="true"]').count(), 1);
  await shot('ringdyn-error.png');

  // Editing the field clears its mark.
  await page.fill('#f-segments', '20');
  assert.equal(await page.getAttribute('#f-segments', 'aria-invalid'), null);
});

test('an example from the dropdown fills the form and runs', { timeout: 120000 }, async () => {
  const { examples } = await (await page.request.get(`${BASE}/api/v1/examples`)).json();
  assert.ok(Array.isArray(examples) && examples.length > 0, 'the server ships at least one example');
  const ex = examples.find((e) => e.scene?.analysis === 'modal') || examples[0];
  // One option per example plus the defaults (the list loads asynchronously).
  await page.waitForFunction((n) => document.querySelectorAll('#example option').length === n, examples.length + 1);
  await page.selectOption('#example', { index: examples.indexOf(ex) + 1 });

  // Every form field the example sets now shows its value.
  const fields = await page.$$eval('[data-path]', (is) => is.map((i) => ({
    path: i.dataset.path,
    value: i.type === 'checkbox' ? i.checked : i.tagName === 'SELECT' ? i.value : Number(i.value),
  })));
  let checked = 0;
  for (const f of fields) {
    const v = f.path.split('/').slice(1).reduce((o, k) => (o == null ? undefined : o[k]), ex.scene);
    if (v === undefined) continue;
    assert.equal(f.value, v, `${f.path} from example ${ex.name}`);
    checked += 1;
  }
  assert.ok(checked > 0, `example ${ex.name} sets at least one form field`);
  if (ex.description) assert.ok((await page.textContent('#example-desc')).startsWith(ex.description));

  if (ex.scene.analysis === 'modal') {
    await runAnalysis();
    assert.equal(await page.isVisible('#error'), false, `example ${ex.name} runs: ${await page.textContent('#error')}`);
    const rows = await modeRows();
    assert.equal(rows.length, ex.scene.modal?.modes ?? 6);
  }
});

test('selecting a mode shows its shape', { timeout: 60000 }, async () => {
  // Back to the thesis ring.
  await page.getByRole('button', { name: 'Reset to defaults' }).click();
  await runAnalysis();
  const rows = await modeRows();
  const inPlane = rows.find((r) => r.kind === 'in_plane');
  const outOfPlane = rows.find((r) => r.kind === 'out_of_plane');
  assert.ok(inPlane && outOfPlane, 'the thesis ring has both kinds among its first six modes');
  const segments = Number(await page.inputValue('#f-segments'));

  // Click: an in-plane mode is drawn on the ring.
  await page.click(`button.mode-select[data-mode="${inPlane.mode}"]`);
  const ring = page.locator('#shape-svg.ring-view');
  await ring.waitFor();
  assert.match(await ring.getAttribute('aria-label'), new RegExp(`^Mode ${inPlane.mode}, in-plane`));
  assert.equal(await page.locator('#shape-svg .nodes circle').count(), segments, 'one point per segment');
  assert.equal(await page.getAttribute(`button.mode-select[data-mode="${inPlane.mode}"]`, 'aria-pressed'), 'true');
  assert.equal(await page.locator(`#freq-plot .marker.selected[data-mode="${inPlane.mode}"]`).count(), 1);

  // Keyboard: an out-of-plane mode is drawn unrolled.
  await page.focus(`button.mode-select[data-mode="${outOfPlane.mode}"]`);
  await page.keyboard.press('Enter');
  const unrolled = page.locator('#shape-svg.unrolled-view');
  await unrolled.waitFor();
  assert.match(await unrolled.getAttribute('aria-label'), new RegExp(`^Mode ${outOfPlane.mode}, out-of-plane`));

  // Arrow keys move the selection.
  if (outOfPlane.mode < rows.length) {
    await page.keyboard.press('ArrowDown');
    assert.equal(await page.getAttribute(`button.mode-select[data-mode="${outOfPlane.mode + 1}"]`, 'aria-pressed'), 'true');
  }
  await page.click(`button.mode-select[data-mode="${inPlane.mode}"]`);
  await ring.waitFor();

  await page.evaluate(() => window.scrollTo(0, 0));
  await shot('ringdyn-page.png');
  await shot('ringdyn-page-full.png', { fullPage: true });
  // Narrow screen: one column, nothing wider than the viewport.
  await page.setViewportSize({ width: 390, height: 844 });
  const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
  assert.ok(overflow <= 0, `page scrolls sideways by ${overflow}px on a narrow screen`);
  await shot('ringdyn-narrow.png', { fullPage: true });
  await page.setViewportSize({ width: 1280, height: 800 });
});

test('a job that outlives ?wait is polled, with progress shown', { timeout: 120000 }, async () => {
  // /?wait=0 makes the page submit without waiting; 300 segments take long
  // enough (tenths of a second) that the POST answers 202 and the page polls.
  await page.goto(`${BASE}/?wait=0`);
  await page.waitForSelector('#tab-modal[aria-selected="true"]');
  await page.evaluate(() => {
    window.statusLog = [];
    new MutationObserver(() => window.statusLog.push({
      text: document.getElementById('status-text').textContent,
      bar: !document.getElementById('progress').hidden,
    })).observe(document.getElementById('status'), { subtree: true, childList: true, characterData: true, attributes: true });
  });
  await page.fill('#f-segments', '300');
  await runAnalysis();
  const log = await page.evaluate(() => window.statusLog);
  assert.ok(log.some((s) => /^Job \S+ (queued|running)/.test(s.text) && s.bar), `progress shown while polling: ${JSON.stringify(log)}`);
  assert.match(log.at(-1).text, /^Job \S+ succeeded/);
  assert.equal((await modeRows()).length, 6);
  assert.match(await page.textContent('#cost'), /300 segments/);
});

// ---- pretension, contact, lift --------------------------------------------

// Whether the server runs `analysis`.  A scene with a wrongly typed field is
// rejected before any job starts: with "not available" (path /analysis) when
// the analysis is missing, with a type error at /discretization/segments when
// it is there.  Only the first makes the live tests below skip.
async function unavailable(analysis) {
  const resp = await fetch(`${BASE}/api/v1/jobs?wait=0`, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ analysis, discretization: { segments: 'probe' } }),
  });
  const e = (await resp.json().catch(() => null))?.error;
  if (resp.status === 422 && e?.path === '/analysis' && /not available/.test(e.message || '')) {
    return `the server does not implement the ${analysis} analysis yet: ${e.message}`;
  }
  return false;
}
const SKIP = {};
for (const a of ['pretension', 'contact', 'lift']) SKIP[a] = await unavailable(a);

const pathPoints = (d) => (d?.match(/[ML]/g) || []).length;

async function selectTab(id) {
  await page.click(`#tab-${id}`);
  await page.waitForSelector(`fieldset[data-analysis="${id}"]:not([hidden])`);
}

// The finished job shown on the page, as the server has it.
async function shownJob() {
  const href = await page.getAttribute('#json-link', 'href');
  const resp = await page.request.get(`${BASE}${href}`);
  assert.equal(resp.status(), 200);
  return resp.json();
}

// The page's POST /api/v1/jobs is answered here, not by the server: with a
// succeeded job holding `result` for its analysis, else with a 422.  Returns
// the scenes the page sent and a function that stops this.
async function interceptJobs(result) {
  const sent = [];
  const match = (url) => url.pathname === '/api/v1/jobs';
  await page.route(match, async (route) => {
    if (route.request().method() !== 'POST') return route.continue();
    const scene = route.request().postDataJSON();
    sent.push(scene);
    if (scene.analysis !== result.analysis) {
      return route.fulfill({
        status: 422, contentType: 'application/json',
        body: JSON.stringify({ error: { code: 'test', message: 'not answered by this test', path: '' } }),
      });
    }
    return route.fulfill({
      status: 200, contentType: 'application/json',
      body: JSON.stringify({ id: `fixture-${sent.length}`, status: 'succeeded', progress: 1, result }),
    });
  });
  return { sent, stop: () => page.unroute(match) };
}

// Renders `result` with module `id` into a scratch element and reports what
// was drawn (the renderers are pure functions of the result).
async function renderFixture(id, result) {
  return page.evaluate(async ({ id, result }) => {
    const mod = await import(`/static/${id}.js`);
    const box = document.createElement('div');
    document.body.append(box);
    try {
      mod[id].render(result, null, box);
      const q = (sel) => box.querySelector(sel);
      const all = (sel) => [...box.querySelectorAll(sel)];
      const points = (sel) => (q(sel)?.getAttribute('d')?.match(/[ML]/g) || []).length;
      return {
        text: box.textContent,
        gapLabel: q('#pt-gap-label')?.textContent,
        xaCell: q('#pt-xa')?.textContent,
        freePoints: points('#pt-free'),
        referencePoints: points('#pt-reference'),
        zPlot: Boolean(q('#pt-z-plot')),
        sectionPoints: Number(q('#pt-section-outline')?.dataset.points ?? 0),
        sectionPath: (q('#pt-section-outline')?.getAttribute('d')?.match(/[ML]/g) || []).length,
        sectionCentroid: Boolean(q('#pt-section-centroid')),
        sectionAxis: Boolean(q('#pt-section-axis')),
        freeRadius: Number(q('#pt-free-radius')?.dataset.points ?? 0),
        modelNote: q('#pt-model')?.textContent,
        measuredPoints: Number(q('#pt-free-measured')?.dataset.points ?? 0),
        measuredDots: all('#pt-free-measured circle').length,
        ftCell: q('#pt-ft')?.textContent,
        pressurePoints: points('#ct-pressure'),
        lightGaps: all('.light-gaps .light-gap').length,
        maxGapLabel: q('#ct-max-gap-label')?.textContent,
        p0: Boolean(q('#ct-p0')),
        boreLabel: q('#ct-bore-label')?.textContent,
        distortionRows: all('#ct-distortion tbody tr').length,
        band: Boolean(q('#lf-band')),
        meanPoints: points('#lf-mean'),
        events: all('#lf-lift .event').map((g) => ({ kind: g.dataset.event, title: g.querySelector('title')?.textContent })),
        eventRows: all('#lf-events tbody tr').length,
        friction: Boolean(q('#lf-friction')),
        flankRuns: all('#lf-flank .flank-runs rect').map((r) => r.dataset.flank),
        crankTicks: all('#lf-lift .axes text.tick[text-anchor="middle"]').map((t) => t.textContent),
        upperLine: Boolean(q('#lf-upper')),
      };
    } finally {
      box.remove();
    }
  }, { id, result });
}

// Runs of equal flank states, as the strip draws them.
const runsOf = (flank) => flank.filter((f, i) => i === 0 || f !== flank[i - 1]);

test('four analysis tabs: arrow keys move between them, each shows its own labelled fields', { timeout: 60000 }, async () => {
  await page.goto(`${BASE}/`);
  await page.waitForSelector('#tab-modal[aria-selected="true"]');
  assert.deepEqual(await page.$$eval('#tabs [role="tab"]', (ts) => ts.map((t) => t.textContent)), ['Modal', 'Pretension', 'Contact', 'Lift', 'Ring pack']);
  await page.focus('#tab-modal');
  for (const id of ['pretension', 'contact', 'lift', 'ringpack', 'modal']) {
    await page.keyboard.press('ArrowRight');
    assert.equal(await page.evaluate(() => document.activeElement.id), `tab-${id}`);
    assert.equal(await page.getAttribute(`#tab-${id}`, 'aria-selected'), 'true');
    assert.equal(await page.getAttribute(`#tab-${id}`, 'tabindex'), '0');
    assert.equal(await page.textContent('#run'), `Run ${id} analysis`);
    const shown = await page.$$eval('fieldset[data-analysis]', (fs) => fs.filter((f) => !f.hidden).map((f) => f.dataset.analysis));
    assert.ok(shown.length >= 1 && shown.every((a) => a === id), `only ${id} fields shown: ${shown}`);
  }
  // Every control of the analysis fieldsets has a label with text.
  const unlabelled = await page.$$eval('fieldset[data-analysis] :is(input, select)', (els) => els
    .filter((e) => !document.querySelector(`label[for="${e.id}"]`)?.textContent.trim())
    .map((e) => e.id || e.outerHTML));
  assert.deepEqual(unlabelled, []);
});

test('pretension form: choice and checkbox encoding; other analyses leave its block out', { timeout: 60000 }, async () => {
  const jobs = await interceptJobs(fixtures.pretensionResult({ lateral: 1 }));
  try {
    await selectTab('pretension');
    await runAnalysis('Run pretension analysis');
    let scene = jobs.sent.at(-1);
    assert.equal(scene.analysis, 'pretension');
    assert.deepEqual(scene.pretension, { method: 'force', lateral_force: 0 });
    assert.deepEqual(scene.numerics, { error_estimate: true });
    assert.equal(scene.engine, undefined, 'no lift fields in a pretension scene');
    assert.equal(await page.locator('#result-body #pt-shape').count(), 1, 'the answer is drawn');

    await page.selectOption('#f-pt-method', 'field');
    await page.fill('#f-pt-lateral', '0.3');
    await page.uncheck('#f-pt-error-estimate');
    await runAnalysis('Run pretension analysis');
    scene = jobs.sent.at(-1);
    assert.deepEqual(scene.pretension, { method: 'field', lateral_force: 0.3 });
    assert.deepEqual(scene.numerics, { error_estimate: false });

    await selectTab('modal');
    await runAnalysis();
    scene = jobs.sent.at(-1);
    assert.equal(scene.analysis, 'modal');
    assert.equal(scene.pretension, undefined);
    assert.equal(scene.numerics, undefined);
  } finally {
    await jobs.stop();
  }
});

test('contact form: empty optional fields are left out, the distortion list is sent as rows', { timeout: 60000 }, async () => {
  const jobs = await interceptJobs(fixtures.contactResult());
  try {
    await page.getByRole('button', { name: 'Reset to defaults' }).click();
    await selectTab('contact');
    assert.equal(await page.inputValue('#f-ct-bore-diameter'), '');
    await runAnalysis('Run contact analysis');
    let scene = jobs.sent.at(-1);
    assert.equal(scene.bore, undefined, 'round bore of the ring diameter: no bore block');
    assert.deepEqual(scene.contact, { faces: 'flexible', points_per_segment: 10 });
    assert.equal(scene.numerics.error_estimate, true);

    const add = page.getByRole('button', { name: 'Add a distortion order' });
    for (let i = 0; i < 3; i++) await add.click();
    assert.equal(await page.locator('#f-distortion tbody tr').count(), 3);
    assert.equal(await page.evaluate(() => document.activeElement.id), 'f-distortion-2-order', 'focus on the new row');
    await page.fill('#f-distortion-1-order', '3');
    await page.fill('#f-distortion-1-amplitude', '4e-6');
    await page.fill('#f-distortion-1-phase_deg', '30');
    await page.fill('#f-distortion-2-order', '4');
    await page.fill('#f-distortion-2-amplitude', '6e-6');
    await page.fill('#f-distortion-2-phase_deg', '45');
    assert.match(await page.textContent('#f-distortion-2-amplitude-hint'), /6 µm/);
    await page.getByRole('button', { name: 'Remove distortion 1' }).click();
    assert.equal(await page.locator('#f-distortion tbody tr').count(), 2);
    // The rows are renumbered: labels, ids and paths.
    assert.equal(await page.textContent('label[for="f-distortion-0-order"]'), 'Distortion 1: order k');
    assert.equal(await page.getAttribute('#f-distortion-1-amplitude', 'data-path'), '/bore/distortion/1/amplitude');
    await page.fill('#f-ct-bore-diameter', '0.0766');
    await page.fill('#f-ct-stiffness', '2e13');
    await page.fill('#f-ct-points', '8');
    await page.selectOption('#f-ct-faces', 'rigid');
    await runAnalysis('Run contact analysis');
    scene = jobs.sent.at(-1);
    assert.deepEqual(scene.bore, {
      diameter: 0.0766,
      distortion: [{ order: 3, amplitude: 4e-6, phase_deg: 30 }, { order: 4, amplitude: 6e-6, phase_deg: 45 }],
    });
    assert.deepEqual(scene.contact, { faces: 'rigid', points_per_segment: 8, stiffness: 2e13 });

    // Emptied again, the optional fields are left out again.
    await page.fill('#f-ct-stiffness', '');
    await page.fill('#f-ct-bore-diameter', '');
    await runAnalysis('Run contact analysis');
    scene = jobs.sent.at(-1);
    assert.equal(scene.contact.stiffness, undefined);
    assert.equal(scene.bore.diameter, undefined);

    // A row with an empty amplitude stops the run on the page, naming the field.
    const before = jobs.sent.length;
    await page.fill('#f-distortion-0-amplitude', '');
    await runAnalysis('Run contact analysis');
    assert.equal(jobs.sent.length, before, 'nothing sent');
    const text = await page.textContent('#error');
    assert.match(text, /Distortion 1: amplitude \(m\)/);
    assert.equal(await page.getAttribute('#f-distortion-0-amplitude', 'aria-invalid'), 'true');
    assert.equal(await page.evaluate(() => document.activeElement.id), 'f-distortion-0-amplitude');

    // 0 to 16 rows: the add button stops at 16; removing all sends no list.
    for (let i = 2; i < 16; i++) await add.click();
    assert.equal(await page.locator('#f-distortion tbody tr').count(), 16);
    assert.equal(await add.isDisabled(), true, 'no 17th row');
    assert.match(await page.textContent('#f-distortion [data-list-count]'), /16 of 16/);
    while (await page.locator('#f-distortion [data-list-remove]').count()) {
      await page.locator('#f-distortion [data-list-remove]').first().click();
    }
    assert.equal(await page.evaluate(() => document.activeElement.id), 'f-distortion-add', 'focus back on the add button');
    await runAnalysis('Run contact analysis');
    assert.equal(jobs.sent.at(-1).bore, undefined);
  } finally {
    await jobs.stop();
  }
});

test('lift form: the friction and gas toggles put their blocks in the scene or leave them out', { timeout: 60000 }, async () => {
  const jobs = await interceptJobs(fixtures.liftResult());
  try {
    await page.getByRole('button', { name: 'Reset to defaults' }).click();
    await selectTab('lift');
    await runAnalysis('Run lift analysis');
    let scene = jobs.sent.at(-1);
    assert.deepEqual(scene.engine, { speed_rpm: 1000, crank_radius: 0.04345, rod_length: 0.13, kinematics: 'exact', cycles: 2 });
    assert.deepEqual(scene.groove, { axial_clearance: 3e-5, radial_clearance: 5e-4 });
    assert.deepEqual(scene.physics, { gravity: false }, 'friction and gas off: absent');
    assert.deepEqual(scene.output, { step_deg: 1, flank_band: 0.01 });
    assert.deepEqual(scene.numerics, { model: 'auto', accuracy_deg: 0.1, rtol: 1e-6, atol: 1e-9, error_estimate: true });
    assert.equal(await page.isDisabled('#f-lf-friction-coefficient'), true, 'friction fields off with their toggle');

    await page.check('#f-lf-friction');
    assert.equal(await page.isDisabled('#f-lf-friction-coefficient'), false);
    await page.selectOption('#f-lf-friction-model', 'stribeck');
    await page.fill('#f-lf-friction-coefficient', '0.12');
    await page.check('#f-lf-gravity');
    await page.selectOption('#f-lf-kinematics', 'approximate');
    await runAnalysis('Run lift analysis');
    scene = jobs.sent.at(-1);
    assert.deepEqual(scene.physics, { gravity: true, friction: { model: 'stribeck', coefficient: 0.12 } });
    assert.equal(scene.engine.kinematics, 'approximate');
    await page.uncheck('#f-lf-friction');
    await runAnalysis('Run lift analysis');
    assert.deepEqual(jobs.sent.at(-1).physics, { gravity: true });

    // Gas: the tables of a shipped example, or a disabled toggle that says why.
    const resp = await page.request.get(`${BASE}/api/v1/examples`);
    const examples = resp.status() === 200 ? (await resp.json()).examples : [];
    const withGas = examples.filter((e) => Array.isArray(e.scene?.physics?.gas?.crank_deg));
    await page.waitForFunction(() => !/^Pressure tables \(above/.test(document.getElementById('f-lf-gas-note').textContent) ||
      document.getElementById('f-lf-gas-source').options.length > 0);
    if (!withGas.length) {
      assert.equal(await page.isDisabled('#f-lf-gas'), true, 'no example with gas tables: toggle disabled');
      assert.match(await page.textContent('#f-lf-gas-note'), /^Unavailable/);
    } else {
      const preferred = withGas.find((e) => e.name === 'thesis_lift_gas_6000rpm') || withGas[0];
      assert.equal(await page.isDisabled('#f-lf-gas'), false);
      assert.equal(await page.inputValue('#f-lf-gas-source'), preferred.name);
      await page.check('#f-lf-gas');
      await page.selectOption('#f-lf-gas-area', 'dynamic');
      await runAnalysis('Run lift analysis');
      const gas = jobs.sent.at(-1).physics.gas;
      const { active_area: _, ...tables } = preferred.scene.physics.gas;
      assert.deepEqual(gas, { ...tables, active_area: 'dynamic' });
      await page.uncheck('#f-lf-gas');
      await runAnalysis('Run lift analysis');
      assert.equal(jobs.sent.at(-1).physics.gas, undefined);
    }
  } finally {
    await jobs.stop();
  }
});

test('lift form: the lubricated model sends the face, the roughness and the oil, and only with it', { timeout: 60000 }, async () => {
  const jobs = await interceptJobs(fixtures.liftResult());
  const shown = (id) => page.isVisible(id);
  try {
    await page.getByRole('button', { name: 'Reset to defaults' }).click();
    await selectTab('lift');
    await page.check('#f-lf-friction');
    assert.equal(await shown('#f-lf-lube'), false, 'coulomb: no lubricated inputs');
    assert.equal(await shown('#f-lf-friction-coefficient'), true);
    await page.selectOption('#f-lf-friction-model', 'lubricated');
    assert.equal(await shown('#f-lf-lube'), true);
    assert.equal(await shown('#f-lf-friction-coefficient'), false, 'lubricated: no Coulomb coefficient');
    assert.equal(await shown('#f-lf-oil-viscosity'), false, 'the Vogel law by default: no constant viscosity');
    // The defaults come from the served schema: the form sends them as they are
    // (the cavitation choice too, as every choice).
    await runAnalysis('Run lift analysis');
    let scene = jobs.sent.at(-1);
    assert.deepEqual(scene.physics.friction, { model: 'lubricated', cavitation: 'reynolds', oil: { temperature_c: 100 } });
    assert.deepEqual(scene.ring.face, { profile: 'barrel', crown_m: 5e-6, roughness_rq_m: 2e-7 });
    assert.equal(scene.bore, undefined, 'liner roughness empty: the server default');

    await page.fill('#f-lf-liner-rq', '3e-7');
    await page.selectOption('#f-lf-face-profile', 'taper');
    assert.equal(await shown('#f-lf-face-crown'), false, 'taper: no crown');
    await page.fill('#f-lf-face-taper', '0.5');
    await page.selectOption('#f-lf-oil-mode', 'constant');
    assert.equal(await shown('#f-lf-oil-temperature'), false);
    // A constant viscosity left empty is refused by the page, naming the field.
    await runAnalysis('Run lift analysis');
    assert.match(await page.textContent('#error'), /viscosity/i);
    assert.equal(await page.getAttribute('#f-lf-oil-viscosity', 'aria-invalid'), 'true');
    await page.fill('#f-lf-oil-viscosity', '0.012');
    await runAnalysis('Run lift analysis');
    scene = jobs.sent.at(-1);
    assert.deepEqual(scene.physics.friction, { model: 'lubricated', cavitation: 'reynolds', oil: { viscosity_pa_s: 0.012 } });
    assert.deepEqual(scene.ring.face, { profile: 'taper', taper_deg: 0.5, roughness_rq_m: 2e-7 });
    assert.deepEqual(scene.bore, { roughness_rq_m: 3e-7 });

    // Back to Coulomb: nothing of the lubricated model goes (it would be refused).
    await page.selectOption('#f-lf-friction-model', 'coulomb');
    await runAnalysis('Run lift analysis');
    scene = jobs.sent.at(-1);
    assert.deepEqual(scene.physics.friction, { model: 'coulomb', coefficient: 0.1 });
    assert.equal(scene.ring.face, undefined);
    assert.equal(scene.bore, undefined);

    // A loaded lubricated scene: its choices shown (constant oil), its fields
    // the form has no input for kept while lubricated, gone with Coulomb.
    const loaded = {
      analysis: 'lift', engine: { speed_rpm: 2400, cycles: 1 },
      ring: { face: { profile: 'barrel', crown_m: 4e-6, offset_m: 1e-4, roughness_rq_m: 1e-7 } },
      bore: { roughness_rq_m: 4e-7 },
      physics: { friction: { model: 'lubricated', oil: { viscosity_pa_s: 0.02 }, asperity: { boundary_coefficient: 0.12 } } },
    };
    await page.setInputFiles('#load-scene-file', { name: 'lube.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(loaded)) });
    await page.waitForFunction(() => document.getElementById('f-lf-friction-model').value === 'lubricated');
    assert.equal(await page.inputValue('#f-lf-oil-mode'), 'constant');
    assert.equal(await page.inputValue('#f-lf-oil-viscosity'), '0.02');
    await runAnalysis('Run lift analysis');
    scene = jobs.sent.at(-1);
    assert.deepEqual(scene.ring.face, loaded.ring.face);
    assert.deepEqual(scene.bore, loaded.bore);
    assert.deepEqual(scene.physics.friction, { ...loaded.physics.friction, cavitation: 'reynolds' }, 'as loaded, the cavitation choice at its default');
    await page.selectOption('#f-lf-friction-model', 'stribeck');
    await runAnalysis('Run lift analysis');
    scene = jobs.sent.at(-1);
    assert.deepEqual(scene.physics.friction, { model: 'stribeck', coefficient: 0.1 });
    assert.equal(scene.ring.face, undefined, 'a loaded face goes with another model');
    assert.equal(scene.bore, undefined);
  } finally {
    await jobs.stop();
    await page.getByRole('button', { name: 'Reset to defaults' }).click();
  }
});

test('examples with gas tables and distortion rows load into the toggles and the list (examples served by the test)', { timeout: 60000 }, async () => {
  const gas = { crank_deg: [0, 360, 375, 720], above: [1e5, 5e6, 4e6, 1e5], behind: [1e5, 3e6, 3e6, 1e5], below: [1e5, 1e6, 1e6, 1e5], active_area: 'dynamic' };
  const served = [
    { name: 'contact_two_orders', description: 'Two orders.', scene: { name: 'Two orders', analysis: 'contact', bore: { diameter: 0.0766, distortion: [{ order: 2, amplitude: 3e-6, phase_deg: 10 }, { order: 4, amplitude: 2e-6, phase_deg: 0 }] }, contact: { points_per_segment: 10 } } },
    { name: 'thesis_lift_gas_6000rpm', description: 'Gas at 6000 rpm.', scene: { name: 'Lift with gas', analysis: 'lift', engine: { speed_rpm: 6000, cycles: 1 }, physics: { gravity: true, friction: { model: 'coulomb', coefficient: 0.08, viscosity: 0.02 }, gas } } },
  ];
  const examplesUrl = (url) => url.pathname === '/api/v1/examples';
  await page.route(examplesUrl, (route) => route.fulfill({ status: 200, contentType: 'application/json', body: JSON.stringify({ examples: served }) }));
  const jobs = await interceptJobs(fixtures.liftResult());
  try {
    await page.goto(`${BASE}/`);
    await page.waitForFunction(() => document.querySelectorAll('#example option').length === 3);
    assert.equal(await page.isDisabled('#f-lf-gas'), false, 'gas tables available');
    assert.equal(await page.inputValue('#f-lf-gas-source'), 'thesis_lift_gas_6000rpm');
    assert.doesNotMatch(await page.textContent('#f-lf-gas-note'), /Unavailable|missing/);

    // The lift example: its tab, its toggles on, its values in the fields.
    await page.selectOption('#example', { index: 2 });
    assert.equal(await page.getAttribute('#tab-lift', 'aria-selected'), 'true');
    assert.equal(await page.inputValue('#f-lf-speed'), '6000');
    assert.equal(await page.isChecked('#f-lf-gravity'), true);
    assert.equal(await page.isChecked('#f-lf-friction'), true);
    assert.equal(await page.inputValue('#f-lf-friction-coefficient'), '0.08');
    assert.equal(await page.isChecked('#f-lf-gas'), true);
    assert.equal(await page.inputValue('#f-lf-gas-area'), 'dynamic');
    await runAnalysis('Run lift analysis');
    let scene = jobs.sent.at(-1);
    assert.deepEqual(scene.physics.gas, gas, 'the example\'s tables and area');
    assert.deepEqual(scene.physics.friction, { model: 'coulomb', coefficient: 0.08, viscosity: 0.02 }, 'fields without an input are kept');
    assert.equal(scene.name, undefined);
    // Unchecked, the example's blocks are dropped too.
    await page.uncheck('#f-lf-friction');
    await page.uncheck('#f-lf-gas');
    await runAnalysis('Run lift analysis');
    scene = jobs.sent.at(-1);
    assert.deepEqual(scene.physics, { gravity: true });

    // The contact example: one list row per distortion order.
    await page.selectOption('#example', { index: 1 });
    assert.equal(await page.getAttribute('#tab-contact', 'aria-selected'), 'true');
    assert.equal(await page.locator('#f-distortion tbody tr').count(), 2);
    assert.equal(await page.inputValue('#f-distortion-1-order'), '4');
    assert.equal(await page.inputValue('#f-ct-bore-diameter'), '0.0766');
    // Back to the defaults: no rows, toggles off.
    await page.getByRole('button', { name: 'Reset to defaults' }).click();
    assert.equal(await page.locator('#f-distortion tbody tr').count(), 0);
    assert.equal(await page.isChecked('#f-lf-gas'), false);
    assert.equal(await page.inputValue('#f-ct-bore-diameter'), '');
  } finally {
    await jobs.stop();
    await page.unroute(examplesUrl);
  }
  await page.goto(`${BASE}/`);
  await page.waitForSelector('#tab-modal[aria-selected="true"]');
});

test('renderers draw fixture results: points, marks and labels match the numbers', { timeout: 60000 }, async () => {
  // Pretension: shape points, the gap label in mm to 2 decimals, the z plot only with a lateral opening.
  const pt = fixtures.pretensionResult({ lateral: 1 });
  let r = await renderFixture('pretension', pt);
  assert.equal(r.gapLabel, `x_a = ${(pt.gap_opening_inner * 1e3).toFixed(2)} mm`);
  assert.equal(r.freePoints, pt.shape.x.length);
  assert.equal(r.referencePoints, pt.shape.reference_x.length);
  assert.equal(r.zPlot, true);
  assert.match(r.xaCell, /^9\.214 mm/);
  assert.equal(r.sectionPoints, pt.section.outline_m.length, 'the section outline: one point each');
  assert.equal(r.sectionPath, pt.section.outline_m.length, 'the outline path has a vertex per point');
  assert.ok(r.sectionCentroid && r.sectionAxis, 'the centroid and the principal axis are drawn');
  assert.equal(r.freeRadius, pt.free_shape.theta_deg.length, 'the free shape: one point each');
  assert.match(r.modelNote, /stress-free closed ring opened by F_t/);
  assert.match(r.ftCell, /^10 N \(given: F_t\)/);
  const made = fixtures.pretensionResult({ lateral: 0 });
  made.free_shape_model = 'pressure_distribution';
  made.scene.ring = { ...made.scene.ring, pressure_distribution: { orders: [{ order: 2, amplitude: 0.15 }, { order: 3, amplitude: -0.2 }] } };
  made.free_shape.tangential_force_n = 9.7346;
  r = await renderFixture('pretension', made);
  assert.equal(r.zPlot, false, 'no z plot without a lateral opening');
  assert.match(r.modelNote, /p\/p₀ = 1 \+ 0\.15 cos 2θ − 0\.2 cos 3θ/, 'the pressure named in words');
  assert.match(r.ftCell, /^9\.7346 N \(computed\)/);
  assert.equal(r.measuredPoints, 0, 'no measured points without ring.free_shape');
  // A measured free shape: the fit in words, the points drawn as dots.
  const meas = fixtures.pretensionResult({ lateral: 0 });
  meas.free_shape_model = 'measured_free_shape';
  meas.scene.ring = { ...meas.scene.ring, free_shape: { theta_deg: [0, 60, 120, 170], radius_m: [0.03826, 0.03839, 0.03871, 0.03900], fit_order: 3 } };
  meas.free_shape_fit = {
    orders: [{ order: 2, amplitude: 0.1501, standard_error: 7e-5, segments_error: 3e-5 }, { order: 3, amplitude: -0.2002, standard_error: 2.5e-4, segments_error: 1e-5 }],
    tangential_force_n: 10.0025, tangential_force_standard_error_n: 1.6e-4, residual_rms_m: 2.8e-8, residual_max_m: 5.8e-8,
    pressure_min_ratio: 0.706, pressure_min_theta_deg: -113.5, centre_m: [-2.6e-7, 0], rotation_deg: 0, points: 4,
  };
  r = await renderFixture('pretension', meas);
  assert.equal(r.measuredPoints, 4, 'one dot per measured point');
  assert.equal(r.measuredDots, 4);
  assert.match(r.modelNote, /p\/p₀ = 1 \+ 0\.15\(±7\.0e-5\) cos 2θ − 0\.2\(±2\.5e-4\) cos 3θ with F_t = 10\.002 N/, 'the fit in words');
  assert.match(r.modelNote, /0\.028 µm RMS/);
  assert.match(r.ftCell, /\(computed\)/);

  // Contact: one polar point per angle, one arc per segment with clearance > 0.
  const ct = fixtures.contactResult();
  r = await renderFixture('contact', ct);
  assert.equal(r.pressurePoints, ct.angle_deg.length);
  const gaps = ct.clearance.filter((c) => c > 0).length;
  assert.ok(gaps > 0);
  assert.equal(r.lightGaps, gaps);
  assert.equal(r.maxGapLabel, `max ${(ct.max_clearance * 1e6).toFixed(2)} µm`);
  assert.equal(r.p0, true);
  assert.match(r.boreLabel, /exaggerated/);
  assert.equal(r.distortionRows, ct.distortion.length);

  // Pretension, contact and ring pack: the estimate's scope is visible text in its own row beside
  // the number (the cell's text, not a title attribute), as lift's.
  for (const [id, result, method] of [
    ['pretension', fixtures.pretensionResult(), 'Richardson extrapolation from a second solve at 2n'],
    ['contact', fixtures.contactResult(), 'the last two refinement levels; the contact law from a re-solve at 2 k_c'],
    ['ringpack', fixtures.ringpackResult(), 'second run at rtol/10 and atol/10: the time integration only'],
  ]) {
    result.numerics = { ...result.numerics, error_estimate: 0.002, error_method: method };
    const scope = await page.evaluate(async ({ id, result }) => {
      const mod = await import(`/static/${id}.js`);
      const box = document.createElement('div');
      document.body.append(box);
      try {
        mod[id].render(result, null, box);
        const cell = box.querySelector(`#${{ pretension: 'pt', contact: 'ct', ringpack: 'rp' }[id]}-error-scope`);
        const row = cell?.closest('tr');
        const shown = (el) => Boolean(el) && el.getClientRects().length > 0 && getComputedStyle(el).visibility !== 'hidden';
        return {
          text: cell?.textContent, label: row?.querySelector('th')?.textContent, visible: shown(cell),
          titled: [...box.querySelectorAll('[title]')].some((e) => e.getAttribute('title') === result.numerics.error_method),
        };
      } finally {
        box.remove();
      }
    }, { id, result });
    assert.equal(scope.text, method, `${id}: the scope is the cell's text`);
    assert.equal(scope.label, 'What the estimate covers', `${id}: in a row of its own`);
    assert.ok(scope.visible, `${id}: the scope is visible`);
    assert.equal(scope.titled, false, `${id}: not (only) a tooltip`);
  }

  // Lift: band, one marker per event with its angle in the tooltip, flank runs, crank ticks every 90 deg for one cycle.
  const lf = fixtures.liftResult();
  r = await renderFixture('lift', lf);
  assert.equal(r.band, true);
  assert.equal(r.upperLine, true);
  assert.equal(r.events.length, lf.events.length);
  r.events.forEach((e, i) => {
    assert.equal(e.kind, lf.events[i].event);
    assert.ok(e.title.includes(`${lf.events[i].crank_deg}°`), e.title);
  });
  assert.equal(r.eventRows, lf.events.length);
  assert.deepEqual(r.flankRuns, runsOf(lf.flank));
  assert.deepEqual(r.crankTicks, ['0', '90', '180', '270', '360', '450', '540', '630', '720']);
  assert.equal(r.friction, true);
  r = await renderFixture('lift', fixtures.liftResult({ friction: false }));
  assert.equal(r.friction, false, 'no friction plot without friction in the scene');
  // The estimate's scope is text beside the number, not a tooltip.
  const scoped = fixtures.liftResult();
  scoped.numerics = { error_estimate: 0.001, error_method: 'second run at rtol/10 and atol/10; the time integration only' };
  r = await renderFixture('lift', scoped);
  assert.ok(r.text.includes('What the estimate covers'), 'the scope row is shown');
  assert.ok(r.text.includes('the time integration only'), 'the scope is visible text');

  // A long run: ticks every 180 deg for two cycles, and the lines are thinned.
  const two = fixtures.liftResult();
  two.crank_deg = [...two.crank_deg, ...two.crank_deg.slice(1).map((c) => c + 720)];
  for (const k of ['lift', 'lift_min', 'lift_max', 'flank', 'friction_force']) two[k] = [...two[k], ...two[k].slice(1)];
  r = await renderFixture('lift', two);
  assert.deepEqual(r.crankTicks, ['0', '180', '360', '540', '720', '900', '1080', '1260', '1440']);
  const long = fixtures.liftResult();
  long.crank_deg = Array.from({ length: 36001 }, (_, i) => i);
  long.lift = long.crank_deg.map((c) => 1.5e-5 * (1 + Math.sin(c / 7)));
  delete long.lift_min; delete long.lift_max; delete long.flank; delete long.friction_force;
  r = await renderFixture('lift', long);
  assert.ok(r.meanPoints > 0 && r.meanPoints <= 4 * 700, `36001 samples drawn with ${r.meanPoints} points`);
  assert.ok(r.crankTicks.length <= 13, `${r.crankTicks.length} crank ticks`);
});

test('lift renderer: a lubricated result draws its film and friction split, per cycle and cut to one cycle; a bare block draws nothing of it', { timeout: 60000 }, async () => {
  // Two cycles of a made-up film: thinnest (0.4 um) at 540 + 720 k deg.
  const lf = fixtures.liftResult();
  lf.crank_deg = [...lf.crank_deg, ...lf.crank_deg.slice(1).map((c) => c + 720)];
  for (const k of ['lift', 'lift_min', 'lift_max', 'flank', 'friction_force']) lf[k] = [...lf[k], ...lf[k].slice(1)];
  lf.scene.engine.cycles = 2;
  lf.scene.physics.friction = { model: 'lubricated', coefficient: 0.1, oil: { viscosity_pa_s: 0, temperature_c: 100 } };
  const c = lf.crank_deg, rad = (d) => (d * Math.PI) / 180;
  lf.lubrication = {
    min_film_m: c.map((a) => 0.4e-6 + 2e-6 * (1 - Math.cos(rad((a - 540) / 2)))),
    hydrodynamic_friction_n: c.map((a) => 3 * Math.sin(rad(2 * a))),
    asperity_friction_n: c.map((a) => (Math.cos(rad((a - 540) / 2)) > 0.99 ? 0.5 : 0)),
    friction_power_w: c.map(() => 1), asperity_share: c.map(() => 0),
    regime: c.map((a) => (Math.cos(rad((a - 540) / 2)) > 0.99 ? 'mixed' : 'hydrodynamic')),
    friction_work_j: [1.25, 1.5], fmep_pa: [3125, 3750], min_film_at_m: 6e-4, composite_roughness_m: 2.83e-7,
    viscosity_pa_s: { min: 0.0085, max: 0.0085 }, film_step_deg: 1, film_solves: 9000, periodic_change: 1e-5, held_steps: 0,
    method: 'a made-up film for the test',
  };
  const drawn = await page.evaluate(async (result) => {
    const mod = await import('/static/lift.js');
    const box = document.createElement('div');
    document.body.append(box);
    const points = (sel) => (box.querySelector(sel)?.getAttribute('d')?.match(/[ML]/g) || []).length;
    const state = () => ({
      film: points('#lf-film-line'), hydro: points('#lf-friction-hydro'), asperity: points('#lf-friction-asperity'), total: points('#lf-friction-total'),
      fmep: [...box.querySelectorAll('#lf-fmep td.fmep')].map((td) => td.textContent),
      work: [...box.querySelectorAll('#lf-fmep td.work')].map((td) => td.textContent),
      method: box.querySelector('#lf-lube-method')?.textContent, summary: box.querySelector('#lf-lube-summary')?.textContent,
      caption: box.querySelector('#lf-film')?.closest('figure').querySelector('figcaption').textContent,
    });
    try {
      mod.lift.render(result, null, box);
      const whole = state();
      const zoom = box.querySelector('#lf-zoom');
      zoom.value = zoom.options[2].value; // cycle 2
      zoom.dispatchEvent(new Event('change'));
      const second = state();
      // A distorted bore's films: how many, the load range, where the thinnest is.
      const lub = result.lubrication;
      mod.lift.render({ ...result, lubrication: { ...lub, films: 5, film_interpolation_error: 0.0012,
        film_load_n_per_m: { min: 146.3, max: 373.6 }, min_film_angle_deg: lub.min_film_m.map(() => 278.9) } }, null, box);
      const films = { summary: box.querySelector('#lf-lube-summary')?.textContent,
        text: box.querySelector('#lf-lube-facts')?.textContent };
      mod.lift.render({ ...result, lubrication: {} }, null, box);
      const bare = state();
      return { whole, second, bare, films };
    } finally {
      box.remove();
    }
  }, lf);
  assert.equal(drawn.whole.film, c.length);
  for (const k of ['hydro', 'asperity', 'total']) assert.equal(drawn.whole[k], c.length, k);
  assert.deepEqual(drawn.whole.fmep, ['3.125', '3.75'], 'FMEP in kPa, per cycle');
  assert.deepEqual(drawn.whole.work, ['1.25', '1.5']);
  assert.equal(drawn.whole.method, 'Film model: a made-up film for the test');
  assert.match(drawn.whole.summary, /thinnest oil film 0\.400 µm at 540°; FMEP 3\.13, 3\.75 kPa \(per cycle\)/);
  assert.match(drawn.whole.caption, /hydrodynamic 9\d %, mixed [1-9] %, boundary 0 %.*η = 8\.5 mPa s/);
  // Cut to cycle 2: the film and the split follow the zoom; the per-cycle table stays.
  assert.equal(drawn.second.film, 721);
  assert.equal(drawn.second.total, 721);
  assert.deepEqual(drawn.second.fmep, ['3.125', '3.75']);
  assert.match(drawn.films.summary, /thinnest oil film 0\.400 µm at 540°, on the segment 278\.9° from the gap middle/);
  assert.match(drawn.films.text, /5 films at loads across the range, each segment's interpolated at its load \(error estimate 0\.12 %\)/);
  assert.match(drawn.films.text, /146 to 374 N\/m around the ring/);
  assert.doesNotMatch(drawn.whole.summary, /from the gap middle/, 'one film: no angle');
  assert.deepEqual(drawn.bare, { film: 0, hydro: 0, asperity: 0, total: 0, fmep: [], work: [], method: undefined, summary: undefined, caption: undefined });
  assert.deepEqual(pageErrors, []);
});

test('renderers cope with results that have only the fields API.md promises', { timeout: 60000 }, async () => {
  let r = await renderFixture('pretension', fixtures.minimal(fixtures.pretensionResult()));
  assert.match(r.text, /9\.21 mm/);
  assert.match(r.text, /no free shape/);
  r = await renderFixture('contact', fixtures.minimal(fixtures.contactResult()));
  assert.equal(r.pressurePoints, fixtures.contactResult().angle_deg.length);
  assert.equal(r.lightGaps, 0, 'no clearance array: no light gaps drawn');
  assert.match(r.text, /Round bore/);
  const lf = fixtures.liftResult();
  r = await renderFixture('lift', fixtures.minimal(lf));
  assert.equal(r.band, false, 'no lift_min / lift_max: no band');
  assert.ok(r.meanPoints > 0);
  assert.equal(r.events.length, lf.events.length);
  assert.equal(r.upperLine, false, 'no scene: no clearance line');
  r = await renderFixture('lift', { analysis: 'lift' });
  assert.match(r.text, /no samples/);
  assert.deepEqual(pageErrors, []);
});

test('narrow screen: the new forms and results fit without sideways scrolling', { timeout: 60000 }, async () => {
  await page.setViewportSize({ width: 390, height: 844 });
  try {
    for (const result of [fixtures.pretensionResult({ lateral: 1 }), fixtures.contactResult(), fixtures.liftResult()]) {
      const jobs = await interceptJobs(result);
      try {
        await selectTab(result.analysis);
        if (result.analysis === 'contact') await page.getByRole('button', { name: 'Add a distortion order' }).click();
        await runAnalysis(`Run ${result.analysis} analysis`);
        assert.equal(await page.locator('#result-body svg.chart').first().isVisible(), true);
        const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
        assert.ok(overflow <= 0, `${result.analysis}: page scrolls sideways by ${overflow}px`);
        await shot(`ringdyn-narrow-${result.analysis}.png`, { fullPage: true });
      } finally {
        await jobs.stop();
      }
    }
  } finally {
    await page.setViewportSize({ width: 1280, height: 800 });
    await page.getByRole('button', { name: 'Reset to defaults' }).click();
  }
});

test('pretension against the server: the gap label and shape match the result; a negative lateral force is refused', { skip: SKIP.pretension, timeout: 180000 }, async () => {
  await page.getByRole('button', { name: 'Reset to defaults' }).click();
  await selectTab('pretension');
  await page.fill('#f-pt-lateral', '0.5');
  await runAnalysis('Run pretension analysis', 150000);
  assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
  const { result } = await shownJob();
  assert.equal(result.analysis, 'pretension');
  assert.equal(result.scene.pretension.lateral_force, 0.5);
  assert.equal(await page.textContent('#pt-gap-label'), `x_a = ${(result.gap_opening_inner * 1e3).toFixed(2)} mm`);
  assert.equal(pathPoints(await page.getAttribute('#pt-free', 'd')), result.shape.x.length);
  assert.equal(result.shape.x.length, result.numerics.segments + 2);
  assert.equal(await page.locator('#pt-z-plot').count(), result.lateral_opening > 0 ? 1 : 0);
  assert.match(await page.textContent('#pt-xa'), new RegExp(`^${(result.gap_opening_inner * 1e3).toFixed(3)} mm`));
  assert.match(await page.textContent('#cost'), new RegExp(`${result.numerics.segments} segments`));
  assert.equal((await page.request.get(`${BASE}${await page.getAttribute('#csv-link', 'href')}`)).status(), 200, 'CSV link answers');
  await shot('ringdyn-pretension.png', { fullPage: true });

  await page.fill('#f-pt-lateral', '-1');
  await runAnalysis('Run pretension analysis');
  const text = await page.textContent('#error');
  assert.match(text, /Lateral force/, `error names the field: ${text}`);
  assert.match(text, /\/pretension\/lateral_force/);
  assert.equal(await page.getAttribute('#f-pt-lateral', 'aria-invalid'), 'true');
  assert.equal(await page.locator('[aria-invalid="true"]').count(), 1);
  await page.fill('#f-pt-lateral', '0');
});

test('contact against the server: polar points, light gaps and the distortion table match the result; 3 segments are refused', { skip: SKIP.contact, timeout: 240000 }, async () => {
  await page.getByRole('button', { name: 'Reset to defaults' }).click();
  await selectTab('contact');
  await page.fill('#f-segments', '40');
  await page.getByRole('button', { name: 'Add a distortion order' }).click();
  await page.fill('#f-distortion-0-order', '4');
  await page.fill('#f-distortion-0-amplitude', '6e-6');
  await page.fill('#f-distortion-0-phase_deg', '45');
  await runAnalysis('Run contact analysis', 200000);
  assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
  const { result } = await shownJob();
  assert.equal(result.analysis, 'contact');
  assert.equal(result.scene.bore.distortion[0].order, 4);
  assert.equal(pathPoints(await page.getAttribute('#ct-pressure', 'd')), result.angle_deg.length);
  const gaps = result.clearance.filter((c) => c > 0).length;
  assert.equal(await page.locator('.light-gaps .light-gap').count(), gaps);
  if (gaps > 0) {
    assert.equal(await page.textContent('#ct-max-gap-label'), `max ${(result.max_clearance * 1e6).toFixed(2)} µm`);
  } else {
    assert.equal(await page.locator('#ct-max-gap-label').count(), 0);
  }
  assert.equal(await page.locator('#ct-p0').count(), 1);
  assert.equal(await page.locator('#ct-distortion tbody tr').count(), (result.distortion || []).length);
  // the contact patches (since 0.3.15): one row each, the force in N and its estimate in the caption
  assert.equal(await page.locator('#ct-patches tbody tr').count(), result.contact_patches.length);
  assert.ok(result.contact_patches.length >= 1, 'a distorted bore has a contact patch');
  assert.equal(await page.textContent('#ct-patches tbody tr:first-child td:nth-child(3)'),
    String(Number(result.contact_patches[0].force_n.toPrecision(4))));
  assert.match(await page.textContent('#ct-patches caption'), / \(± .* N, estimate\)$/);
  // and a mark on the polar plot where each patch's force acts, where the ring has light gaps
  assert.equal(await page.locator('#ct-patch-marks .patch-mark').count(), gaps > 0 ? result.contact_patches.length : 0);
  assert.match(await page.textContent('#ct-fraction'), new RegExp(`^${(result.contact_fraction * 100).toFixed(1)} %`));
  // each figure with its estimate: the contact fraction's, the tip forces (N) and theirs, the target's verdict
  const est = result.numerics.error_estimates;
  assert.match(await page.textContent('#ct-fraction'), new RegExp(` ± ${(est.contact_fraction * 100).toFixed(2)} %$`));
  const tip = (v) => String(Number(v.toPrecision(4)));
  assert.match(await page.textContent('#ct-tips'), new RegExp(`^${tip(result.tip_forces_n[0])} N, ${tip(result.tip_forces_n[1])} N ± `));
  assert.match(await page.textContent('#ct-accuracy'), result.numerics.accuracy_met ? /^met / : /^not met: /);
  // what the solve cost (since 0.3.5): tangents factored and multiplier updates
  assert.equal(await page.textContent('#ct-cost'), `${result.numerics.factorizations} / ${result.numerics.multiplier_updates}`);
  assert.ok(result.numerics.factorizations <= result.numerics.iterations, 'a factorization an iteration at most');
  // the pressure's estimate says where its largest part is (since 0.3.4)
  assert.ok(Number.isFinite(result.numerics.pressure_estimate_at_deg), 'the estimate has a place');
  assert.match(await page.textContent('#ct-error'), new RegExp(`; mostly .* at ${Number(result.numerics.pressure_estimate_at_deg.toFixed(1))}°$`));
  assert.equal((await page.request.get(`${BASE}${await page.getAttribute('#csv-link', 'href')}`)).status(), 200, 'CSV link answers');
  await shot('ringdyn-contact.png', { fullPage: true });

  await page.fill('#f-segments', '3');
  await runAnalysis('Run contact analysis');
  const text = await page.textContent('#error');
  assert.match(text, /Segments/, `error names the field: ${text}`);
  assert.match(text, /\/discretization\/segments/);
  assert.equal(await page.getAttribute('#f-segments', 'aria-invalid'), 'true');
  await page.fill('#f-segments', '20');
});

test('lift against the server: band, event markers, friction plot and flank strip match the result; a zero speed is refused', { skip: SKIP.lift, timeout: 300000 }, async () => {
  await page.getByRole('button', { name: 'Reset to defaults' }).click();
  await selectTab('lift');
  // Half a cycle on 8 segments: Coulomb friction makes CVODE take small
  // steps (a whole cycle on 20 segments takes over a minute).
  await page.fill('#f-segments', '8');
  await page.fill('#f-lf-cycles', '0.5');
  await page.uncheck('#f-lf-error-estimate');
  await page.check('#f-lf-friction');
  await runAnalysis('Run lift analysis', 280000);
  assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
  const { result } = await shownJob();
  assert.equal(result.analysis, 'lift');
  assert.equal(result.scene.physics.friction.model, 'coulomb');
  assert.equal(result.scene.physics.friction.coefficient, 0.1);
  assert.equal(await page.locator('#lf-band').count(), 1);
  assert.ok(pathPoints(await page.getAttribute('#lf-mean', 'd')) > 1);
  assert.equal(await page.locator('#lf-lift .event').count(), result.events.length);
  assert.equal(await page.locator('#lf-events tbody tr').count(), Math.min(result.events.length, 500));
  assert.equal(await page.locator('#lf-friction').count(), 1);
  assert.deepEqual(await page.$$eval('#lf-flank .flank-runs rect', (rs) => rs.map((r) => r.dataset.flank)), runsOf(result.flank));
  const ticks = (await page.$$eval('#lf-lift .axes text.tick[text-anchor="middle"]', (ts) => ts.map((t) => Number(t.textContent))));
  assert.ok(ticks.length >= 2 && ticks.every((t) => t % 90 === 0), `crank ticks every 90 or 180 deg: ${ticks}`);
  assert.ok([90, 180].includes(ticks[1] - ticks[0]), `tick step ${ticks[1] - ticks[0]}`);
  const csvResp = await page.request.get(`${BASE}${await page.getAttribute('#csv-link', 'href')}`);
  assert.equal(csvResp.status(), 200, 'CSV link answers');
  // The band the server used: drawn at both flanks, stated in the CSV's rows and under the events.
  assert.equal(result.numerics.flank_band, 0.01);
  assert.equal(await page.locator('#lf-lift rect.flank-band:not(.legend *)').count(), 2);
  const csvLines = (await csvResp.text()).trim().split('\n');
  assert.equal(csvLines[0], 'crank_deg,lift_m,lift_min_m,lift_max_m,twist_rad,friction_force_n,bore_pressure_min_pa,bore_pressure_max_pa,flank,flank_band,axial_clearance_m');
  assert.equal(csvLines.length, result.crank_deg.length + 1);
  assert.ok(csvLines.slice(1).every((l) => l.split(',').slice(-2).map(Number).join() === `0.01,${result.scene.groove.axial_clearance}`),
    `every CSV row ends with the band and the clearance: ${csvLines[1]}`);
  assert.equal(await page.locator('#lf-events tbody td.touch').count(), Math.min(result.events.length, 500));
  if (result.events.length) assert.match(await page.textContent('#lf-dating'), /band of 1 % of the axial clearance/);
  await shot('ringdyn-lift.png', { fullPage: true });

  await page.fill('#f-lf-speed', '0');
  await runAnalysis('Run lift analysis');
  const text = await page.textContent('#error');
  assert.match(text, /Engine speed/, `error names the field: ${text}`);
  assert.match(text, /\/engine\/speed_rpm/);
  assert.equal(await page.getAttribute('#f-lf-speed', 'aria-invalid'), 'true');
  await page.fill('#f-lf-speed', '1000');
});

// ---- live jobs, form <-> script, export, readable text, plots (issue 13) ----

// Visible text smaller than `minPx` on screen: every element holding text,
// its computed font size; for SVG text times the chart's scale on screen.
async function smallText(minPx = 10) {
  return page.evaluate((minPx) => {
    const out = [];
    const seen = new Set();
    const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
    for (let n = walker.nextNode(); n; n = walker.nextNode()) {
      const el = n.parentElement;
      if (!n.data.trim() || !el || seen.has(el)) continue;
      seen.add(el);
      // <title> is a tooltip, an <option> is drawn by its <select>.
      if (el.closest('title, option, script, style')) continue;
      const r = el.getBoundingClientRect();
      const cs = getComputedStyle(el);
      if (r.width <= 1 || r.height <= 1 || cs.visibility !== 'visible') continue; // not shown, or for screen readers only
      let px = parseFloat(cs.fontSize);
      if (el instanceof SVGElement) {
        const m = el.getScreenCTM();
        px *= Math.hypot(m.a, m.b);
      }
      if (px < minPx) out.push(`${el.tagName}#${el.id || ''} "${n.data.trim().slice(0, 30)}" ${px.toFixed(1)} px`);
    }
    return out;
  }, minPx);
}

// Two frames: the charts' ResizeObserver has refitted them.
const settled = () => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

// Chromium 156 drops a page's downloads that come too fast: the 11th of
// downloads 50 ms apart never starts, 16 at 600 ms apart all do (measured
// 2026-12-03; the suite passed before only where a loaded machine spaced
// them).  So one download at most every 700 ms.
let lastDownload = 0;
async function download(click) {
  const wait = lastDownload + 700 - Date.now();
  if (wait > 0) await new Promise((r) => setTimeout(r, wait));
  const [dl] = await Promise.all([page.waitForEvent('download'), click()]);
  lastDownload = Date.now();
  return { name: dl.suggestedFilename(), data: fs.readFileSync(await dl.path()) };
}

const jobInUrl = () => new URL(page.url()).searchParams.get('job');

async function serverJob(id) {
  const resp = await page.request.get(`${BASE}/api/v1/jobs/${id}`);
  assert.equal(resp.status(), 200);
  return resp.json();
}

// A lift of many cycles: runs for seconds (about 12 s for 20 cycles here).
async function fillLongLift() {
  await page.getByRole('button', { name: 'Reset to defaults' }).click();
  await selectTab('lift');
  await page.fill('#f-lf-cycles', '40');
  await page.uncheck('#f-lf-error-estimate');
}

// A lubricated lift: one cycle at 2400 rpm on the rigid ring (the film is
// solved on its own; about a second), at both widths.
for (const width of [1280, 390]) {
  test(`${width} px: a lubricated lift against the server draws the film and the friction split and shows FMEP per cycle and the model's method`, { skip: SKIP.lift, timeout: 180000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('lift');
      await page.fill('#f-lf-speed', '2400');
      await page.fill('#f-lf-cycles', '1');
      await page.selectOption('#f-lf-model', 'rigid');
      await page.uncheck('#f-lf-error-estimate');
      await page.check('#f-lf-friction');
      await page.selectOption('#f-lf-friction-model', 'lubricated');
      await page.fill('#f-lf-oil-temperature', '110');
      await runAnalysis('Run lift analysis', 150000);
      assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
      const { result } = await shownJob();
      assert.equal(result.scene.physics.friction.model, 'lubricated');
      assert.equal(result.scene.physics.friction.oil.temperature_c, 110);
      const lub = result.lubrication;
      assert.ok(lub && lub.min_film_m.length === result.crank_deg.length, 'the result has its lubrication block');

      // The film: one point per sample (fewer than 2800), the roughness line.
      assert.equal(await page.locator('#lf-film').isVisible(), true);
      assert.equal(pathPoints(await page.getAttribute('#lf-film-line', 'd')), result.crank_deg.length);
      assert.equal(await page.locator('#lf-film-sigma').count(), 1);
      const label = await page.getAttribute('#lf-film', 'aria-label');
      const lo = Math.min(...lub.min_film_m) * 1e6;
      assert.ok(label.includes(`${Number(lo.toPrecision(3))} to`), `film label names the thinnest film ${lo} µm: ${label}`);
      // The split: film shear, asperities and total, each over the run.
      assert.equal(await page.locator('#lf-lube-friction').isVisible(), true);
      for (const id of ['#lf-friction-hydro', '#lf-friction-asperity', '#lf-friction-total']) {
        assert.equal(pathPoints(await page.getAttribute(id, 'd')), result.crank_deg.length, id);
      }
      // Per cycle: work (J) and FMEP (kPa) as the result has them.
      const rows = await page.$$eval('#lf-fmep tbody tr', (trs) => trs.map((tr) => ({
        work: Number(tr.querySelector('.work').textContent), fmep: Number(tr.querySelector('.fmep').textContent),
      })));
      assert.equal(rows.length, 1, 'one cycle, one row');
      assert.ok(Math.abs(rows[0].work - lub.friction_work_j[0]) <= 1e-3 * lub.friction_work_j[0], `work ${rows[0].work} vs ${lub.friction_work_j[0]}`);
      assert.ok(Math.abs(rows[0].fmep - lub.fmep_pa[0] / 1e3) <= 1e-3 * lub.fmep_pa[0] / 1e3, `FMEP ${rows[0].fmep} kPa vs ${lub.fmep_pa[0]} Pa`);
      assert.equal(await page.isVisible('#lf-fmep'), true);
      assert.match(await page.textContent('#lf-lube-summary'), /FMEP \d.* kPa/);
      // The method is on the page as text (not a tooltip), whole.
      assert.equal(await page.isVisible('#lf-lube-method'), true);
      assert.ok((await page.textContent('#lf-lube-method')).includes(lub.method), 'the whole method text');
      // The CSV has the film's columns.
      const csv = await page.request.get(`${BASE}${await page.getAttribute('#csv-link', 'href')}`);
      assert.match((await csv.text()).split('\n')[0], /,min_film_m,hydrodynamic_friction_n,asperity_friction_n,friction_power_w,regime$/);
      await settled();
      const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
      assert.ok(overflow <= 0, `page scrolls sideways by ${overflow}px`);
      assert.deepEqual(await smallText(), [], 'no text below 10 px');
      await shot(`ringdyn-lift-lubricated-${width}.png`, { fullPage: true });
    } finally {
      await page.setViewportSize({ width: 1280, height: 800 });
    }
  });
}

for (const width of [1280, 390]) {
  test(`${width} px: a live lift job shows progress and an ETA in its first second, Cancel within that second cancels it on the server, the old result is marked stale`, { skip: SKIP.lift, timeout: 180000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    await page.goto(`${BASE}/`);
    await page.waitForSelector('#tab-modal[aria-selected="true"]');
    try {
      // A short lift without friction first: its result becomes the old one.
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('lift');
      await page.fill('#f-segments', '8');
      await page.fill('#f-lf-cycles', '0.5');
      await page.uncheck('#f-lf-error-estimate');
      await runAnalysis('Run lift analysis', 120000);
      assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
      const first = jobInUrl();
      assert.match(first, /^[0-9a-f]{16}$/, 'the page URL names the job');
      assert.equal((await serverJob(first)).status, 'succeeded');
      assert.doesNotMatch(await page.textContent('#result-body'), /\bnull\b|undefined|NaN/, 'no "null" above the event table (no friction)');
      assert.equal(await page.isVisible('#result-stale'), false);

      // The long job: progress from the first second, then Cancel before 1 s is out.
      // The full ring, so that it is long (auto would run the rigid ring here: seconds).
      await page.fill('#f-segments', '20');
      await page.fill('#f-lf-cycles', '40');
      await page.selectOption('#f-lf-model', 'full');
      const t0 = Date.now();
      await page.getByRole('button', { name: 'Run lift analysis' }).click();
      await page.waitForFunction(() => /^Job \S+ running — \d+ % · .* elapsed/.test(document.getElementById('status-text').textContent), null, { timeout: 1000 });
      assert.equal(await page.isVisible('#progress'), true, 'progress bar shown');
      assert.match(await page.textContent('#result-stale'), /Out of date: a new job is running/);
      assert.equal(await page.locator('#result-body.stale').count(), 1, 'the old result is dimmed');
      const id = jobInUrl();
      assert.ok(id && id !== first, `the URL names the new job (${id})`);
      const clicked = Date.now() - t0;
      await page.click('#cancel');
      assert.ok(clicked < 1000, `Cancel clicked ${clicked} ms after Run`);
      await page.waitForFunction(() => !document.getElementById('run').disabled, null, { timeout: 20000 });
      const job = await serverJob(id);
      assert.equal(job.status, 'cancelled', 'the server cancelled the job');
      assert.ok(job.progress < 0.5, `cancelled early (progress ${job.progress})`);
      if (job.result) { // a whole cycle was done before the cancel: shown as a partial result
        assert.equal(job.result.partial, true);
        assert.match(await page.textContent('#status-text'), new RegExp(`^Job ${id} cancelled; the cycles it finished \\(to \\d+°\\) are shown: a partial result\\.$`));
        assert.equal(await page.isVisible('#result-stale'), false, 'the partial result is current');
      } else {
        assert.equal(await page.textContent('#status-text'), `Job ${id} cancelled.`);
        assert.match(await page.textContent('#result-stale'), new RegExp(`job ${id} was cancelled.*\\(${first}\\)`));
      }
      assert.equal(await page.isVisible('#error'), false, 'a cancel is not an error');

      // Run and Cancel at once: the job has no id yet when Cancel is pressed;
      // the page cancels it as soon as the submission answers.
      await page.getByRole('button', { name: 'Run lift analysis' }).click();
      await page.click('#cancel');
      await page.waitForFunction(() => !document.getElementById('run').disabled, null, { timeout: 20000 });
      const quick = jobInUrl();
      assert.match(await page.textContent('#status-text'), new RegExp(`^Job ${quick} cancelled(\\.|; .* a partial result\\.)$`));
      assert.equal((await serverJob(quick)).status, 'cancelled');

      // An ETA once there is progress to go by (the server gives no eta_s yet).
      await page.getByRole('button', { name: 'Run lift analysis' }).click();
      await page.waitForFunction(() => /running — \d+ % · .* elapsed · about .* left/.test(document.getElementById('status-text').textContent), null, { timeout: 10000 });
      await page.click('#cancel');
      await page.waitForFunction(() => !document.getElementById('run').disabled, null, { timeout: 20000 });
      assert.equal((await serverJob(jobInUrl())).status, 'cancelled');

      // An error also leaves the old result marked.
      await page.fill('#f-lf-speed', '0');
      await runAnalysis('Run lift analysis');
      assert.equal(await page.isVisible('#error'), true);
      assert.match(await page.textContent('#result-stale'), /Out of date: the last run failed/);
      await page.fill('#f-lf-speed', '1000');
      assert.deepEqual(await smallText(), [], 'no text below 10 px');
      await shot(`ringdyn-live-${width}.png`, { fullPage: true });
    } finally {
      await page.setViewportSize({ width: 1280, height: 800 });
    }
  });

  test(`${width} px: /?job=<id> reopens a finished job (result, tab and form) and a running one (progress, Cancel)`, { timeout: 120000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.goto(`${BASE}/`);
      await page.waitForSelector('#tab-modal[aria-selected="true"]');
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('pretension');
      await page.fill('#f-segments', '16');
      await page.fill('#f-pt-lateral', '0.25');
      await runAnalysis('Run pretension analysis');
      const id = jobInUrl();
      const label = await page.textContent('#pt-gap-label');
      await page.goto(`${BASE}/?job=${id}`);
      await page.waitForFunction((id) => document.getElementById('status-text').textContent === `Job ${id} succeeded.`, id);
      assert.equal(await page.getAttribute('#tab-pretension', 'aria-selected'), 'true');
      assert.equal(await page.textContent('#pt-gap-label'), label, 'the same result');
      assert.equal(await page.inputValue('#f-segments'), '16', 'the job\'s scene in the form');
      assert.equal(await page.inputValue('#f-pt-lateral'), '0.25');

      if (!SKIP.lift) {
        // the full ring, so that it still runs when the page opens it in a
        // Release build too (auto picks the rigid ring here: 40 cycles in
        // ~0.1 s, finished before Cancel, whose DELETE then removes it)
        const resp = await page.request.post(`${BASE}/api/v1/jobs?wait=0`, { data: { analysis: 'lift', engine: { cycles: 40 }, numerics: { model: 'full', error_estimate: false } } });
        const running = await resp.json();
        await page.goto(`${BASE}/?job=${running.id}`);
        await page.waitForFunction(() => /^Job \S+ running/.test(document.getElementById('status-text').textContent));
        assert.equal(await page.getAttribute('#tab-lift', 'aria-selected'), 'true');
        await page.click('#cancel');
        await page.waitForFunction(() => !document.getElementById('run').disabled, null, { timeout: 20000 });
        assert.equal((await serverJob(running.id)).status, 'cancelled');
      }
      assert.deepEqual(await smallText(), [], 'no text below 10 px');
    } finally {
      await page.setViewportSize({ width: 1280, height: 800 });
      await page.goto(`${BASE}/`);
      await page.waitForSelector('#tab-modal[aria-selected="true"]');
    }
  });

  test(`${width} px: Copy as curl / Python run as they are; Download and Load scene JSON; a large modulus shows as 2.1e11`, { timeout: 120000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('modal');
      await page.fill('#f-segments', '12');
      await page.fill('#f-modes', '4');
      const { execFileSync } = await import('node:child_process');

      await page.context().grantPermissions(['clipboard-read', 'clipboard-write'], { origin: BASE });
      await page.click('#copy-curl');
      await page.waitForFunction(() => /on the clipboard/.test(document.getElementById('tools-status').textContent));
      const curl = await page.textContent('#script-out');
      assert.equal(await page.evaluate(() => navigator.clipboard.readText()), curl, 'the clipboard holds the command shown');
      const viaCurl = JSON.parse(execFileSync('bash', ['-c', curl], { encoding: 'utf8', timeout: 60000 }));
      assert.equal(viaCurl.status, 'succeeded');
      assert.equal(viaCurl.result.numerics.segments, 12);
      assert.equal(viaCurl.result.modes.length, 4);

      await page.click('#copy-python');
      const py = await page.textContent('#script-out');
      assert.doesNotMatch(py, /^import (?!json|sys|time|urllib)/m, 'standard library only');
      const viaPython = JSON.parse(execFileSync('python3', ['-'], { input: py, encoding: 'utf8', timeout: 60000 }));
      assert.deepEqual(viaPython.modes.map((m) => m.frequency_hz), viaCurl.result.modes.map((m) => m.frequency_hz), 'same scene, same frequencies');

      // A scene the server refuses: the Python program names the field.
      await page.fill('#f-segments', '1');
      await page.click('#copy-python');
      let failed = null;
      try { execFileSync('python3', ['-'], { input: await page.textContent('#script-out'), encoding: 'utf8', stdio: 'pipe', timeout: 60000 }); } catch (e) { failed = e; }
      assert.ok(failed && failed.status === 1, 'exit status 1');
      assert.match(failed.stderr, /HTTP 422: .* \(path \/discretization\/segments\)/);
      await page.fill('#f-segments', '12');

      // Download: the scene the form sends.
      const saved = await download(() => page.click('#save-scene'));
      assert.equal(saved.name, 'ringdyn-modal-scene.json');
      const scene = JSON.parse(saved.data.toString());
      const sentByCurl = JSON.parse(curl.slice(curl.indexOf('\n{') + 1, curl.lastIndexOf('}') + 1));
      assert.deepEqual(scene, sentByCurl);
      assert.equal(scene.discretization.segments, 12);

      // Load: another analysis's scene fills its tab; E = 210000000000 shows whole.
      const lift = { analysis: 'lift', ring: { material: { youngs_modulus: 210000000000, density: 7800 } }, engine: { speed_rpm: 3000, cycles: 1 } };
      await page.setInputFiles('#load-scene-file', { name: 'lift.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(lift)) });
      await page.waitForSelector('#tab-lift[aria-selected="true"]');
      assert.equal(await page.inputValue('#f-lf-speed'), '3000');
      assert.equal(await page.inputValue('#f-lf-cycles'), '1');
      assert.equal(await page.inputValue('#f-youngs-modulus'), '2.1e11');
      assert.match(await page.textContent('#f-youngs-modulus-hint'), /210 GPa/);
      // The whole value fits in the field (nothing cut off).
      assert.ok(await page.$eval('#f-youngs-modulus', (i) => i.scrollWidth <= i.clientWidth), 'the field shows the whole number');
      assert.match(await page.textContent('#tools-status'), /Loaded lift\.json/);
      // A file without a scene: an error that says so, the form unchanged.
      await page.setInputFiles('#load-scene-file', { name: 'notes.json', mimeType: 'application/json', buffer: Buffer.from('{"hello": 1}') });
      // The file is read asynchronously: wait for the message rather than reading it at once.
      await page.waitForFunction(() => /holds no scene/.test(document.getElementById('error').textContent), null, { timeout: 10000 });
      assert.match(await page.textContent('#error'), /notes\.json holds no scene/);
      assert.equal(await page.inputValue('#f-lf-speed'), '3000');
      await page.click('#copy-python');
      assert.deepEqual(await smallText(), [], 'no text below 10 px');
      if (width === 390) {
        const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
        assert.ok(overflow <= 0, `page scrolls sideways by ${overflow}px`);
      }
    } finally {
      await page.setViewportSize({ width: 1280, height: 800 });
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
    }
  });

  test(`${width} px: every figure exports as SVG and PNG; the CSV downloads as ringdyn-<analysis>-<id>.csv`, { timeout: 120000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('modal');
      await runAnalysis();
      const id = jobInUrl();
      const csv = await download(() => page.click('#csv-link'));
      assert.equal(csv.name, `ringdyn-modal-${id}.csv`);
      assert.equal(csv.data.toString(), await (await page.request.get(`${BASE}/api/v1/jobs/${id}/result.csv`)).text());
      await checkExports(`ringdyn-modal-${id}`, 2);
      // The analyses drawn from fixtures: each of their figures too.
      for (const [result, figures] of [[fixtures.pretensionResult({ lateral: 1 }), 2], [fixtures.contactResult(), 2], [fixtures.liftGasResult(), 2]]) {
        const jobs = await interceptJobs(result);
        try {
          await selectTab(result.analysis);
          if (result.analysis === 'contact') await page.getByRole('button', { name: 'Add a distortion order' }).click();
          await runAnalysis(`Run ${result.analysis} analysis`);
          await checkExports(`ringdyn-${result.analysis}-fixture-`, figures);
        } finally {
          await jobs.stop();
        }
      }
    } finally {
      await page.setViewportSize({ width: 1280, height: 800 });
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
    }
  });
}

// ---- the Sweep and Speed vs accuracy views (issue 16) ----

// The newest sweep on the server, whole (table, fidelity table).
async function newestSweep() {
  const list = await (await page.request.get(`${BASE}/api/v1/sweeps?limit=1`)).json();
  const resp = await page.request.get(`${BASE}/api/v1/sweeps/${list.sweeps[0].id}`);
  assert.equal(resp.status(), 200);
  return resp.json();
}
const sweepDone = (prefix, word = 'succeeded', timeout = 120000) => page.waitForFunction(
  ([p, w]) => new RegExp(`Sweep \\w+ ${w}:`).test(document.getElementById(`${p}-status-text`).textContent) && !document.getElementById(`${p}-run`).disabled,
  [prefix, word], { timeout });
const circles = (id) => page.$$eval(`#${id} circle.pt`, (cs) => cs.map((c) => ({
  x: Number(c.dataset.x), y: Number(c.dataset.y), cx: Number(c.getAttribute('cx')), cy: Number(c.getAttribute('cy')), cls: c.getAttribute('class') })));

for (const width of [1280, 390]) {
  test(`${width} px: a sweep from the form runs, plots an output against a parameter, downloads its CSV; bad specs and cancel`, { timeout: 240000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('modal');
      await page.click('#view-sweep');
      assert.equal(await page.isVisible('#result-view'), false, 'the result view is hidden');
      // The editor starts from the form's scene with one example parameter.
      const spec = JSON.parse(await page.inputValue('#sw-spec'));
      assert.equal(spec.base.analysis, 'modal');
      assert.equal(spec.base.ring.radial_width, Number(await page.inputValue('#f-radial-width')));
      assert.equal(spec.parameters[0].path, '/ring/radial_width');
      await page.click('#sw-run');
      await sweepDone('sw');
      const sw = await newestSweep();
      assert.equal(sw.status, 'succeeded');
      assert.equal(sw.executor, 'local');
      assert.match(await page.textContent('#sw-status-text'), /5 of 5 points on the service's workers\.$/);
      assert.equal(sw.table.rows.length, 5);
      // One marker per point; x = the parameter, y = the first output, as the server's table has them.
      const pts = await circles('sw-plot');
      assert.deepEqual(pts.map((p) => p.x), sw.table.rows.map((r) => r[0]));
      assert.deepEqual(pts.map((p) => p.y), sw.table.rows.map((r) => r[1]));
      // Screen y falls as the value grows (the frequency rises with the radial width).
      for (let i = 1; i < pts.length; i++) assert.ok((pts[i].y - pts[i - 1].y) * (pts[i].cy - pts[i - 1].cy) < 0, `marker ${i} is placed by its value`);
      // Another output from the dropdown redraws the markers at its values.
      await page.selectOption('#sw-y', { label: '/modes/1/frequency_hz' });
      assert.deepEqual((await circles('sw-plot')).map((p) => p.y), sw.table.rows.map((r) => r[2]));
      // The CSV is the server's table.csv.
      const csv = await download(() => page.click('#sw-csv'));
      assert.equal(csv.name, `ringdyn-sweep-${sw.id}.csv`);
      assert.equal(csv.data.toString(), await (await page.request.get(`${BASE}/api/v1/sweeps/${sw.id}/table.csv`)).text());
      if (width === 390) {
        const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
        assert.ok(overflow <= 0, `no sideways scrolling (${overflow} px)`);
        await settled();
        assert.deepEqual(await smallText(), [], 'sweep view');
      }
      await shot(`ringdyn-sweep-${width}.png`, { fullPage: true });

      // A bad spec: the server's message and the path into the spec; nothing runs.
      const before = (await (await page.request.get(`${BASE}/api/v1/sweeps`)).json()).sweeps.length;
      const bad = structuredClone(spec);
      bad.parameters = [{ path: '/discretization/segments', values: [10, 2001] }];
      await page.fill('#sw-spec', JSON.stringify(bad));
      await page.click('#sw-run');
      await page.waitForSelector('#sw-error:not([hidden])');
      assert.match(await page.textContent('#sw-error'), /2001 is out of range.*\/parameters\/0\/values\/1/);
      assert.equal((await (await page.request.get(`${BASE}/api/v1/sweeps`)).json()).sweeps.length, before);
      // Chromium logs the 400 as a failed resource load: expected here.
      for (let i = consoleErrors.length - 1; i >= 0; i--) if (/status of 400/.test(consoleErrors[i])) consoleErrors.splice(i, 1);

      // Cancel: slow points, cancelled while running.
      const slow = { base: { analysis: 'modal', discretization: { segments: 2000 }, modal: { modes: 60 } },
        parameters: [{ path: '/ring/tangential_force', range: { start: 5, stop: 15, count: 8 } }], outputs: ['/modes/0/frequency_hz'] };
      await page.fill('#sw-spec', JSON.stringify(slow));
      await page.click('#sw-run');
      await page.waitForFunction(() => / running /.test(document.getElementById('sw-status-text').textContent));
      await page.click('#sw-cancel');
      await sweepDone('sw', 'cancelled', 30000);
      assert.equal((await newestSweep()).status, 'cancelled');
      await page.click('#sw-fill');
      assert.equal(JSON.parse(await page.inputValue('#sw-spec')).parameters[0].path, '/ring/radial_width');
    } finally {
      await page.setViewportSize({ width: 1280, height: 800 });
      await page.click('#view-result');
    }
  });

  if (width === 1280) test('a sweep on Slurm says so with its job and chunks; a failed task fails it with the reason (canned answers, issue 43)', { timeout: 60000 }, async () => {
    // A server with --sweep-executor slurm answers like these (tests/cluster/slurm_server.sh runs the real one).
    const id = '00000000000000aa';
    const cluster = { job_id: '4242', chunks: 8, chunks_done: 3, tasks_pending: 2, tasks_running: 2, scheduler: '2 running, 2 pending', dir: '/shared/sweep-00000000000000aa' };
    const base = { id, kind: 'sweep', points: 512, runs: 512, failed: 0, spec_hash: '0123456789abcdef', created: '2026-12-03T08:00:00.000Z', started: '2026-12-03T08:00:01.000Z', executor: 'slurm',
      table: { columns: ['/ring/radial_width', '/modes/0/frequency_hz', 'status', 'error'], rows: [] } };
    const running = { ...base, status: 'running', progress: 0.375, done: 192, finished: null, cluster };
    const message = 'Array task 7 of Slurm job 4242 ended FAILED with exit code 2:0 (invalid input, retrying cannot help): segments = 2 is out of range';
    const failed = { ...base, status: 'failed', progress: 0.375, done: 192, finished: '2026-12-03T08:00:09.000Z',
      cluster: { ...cluster, tasks_pending: 0, tasks_running: 0, scheduler: 'no task pending or running' }, error: { code: 'invalid_scene', message } };
    let gets = 0;
    const json = (route, status, body) => route.fulfill({ status, contentType: 'application/json', body: JSON.stringify(body) });
    const post = (route) => (route.request().method() === 'POST' ? json(route, 202, running) : route.continue());
    const get = (route) => json(route, 200, ++gets < 3 ? running : failed);
    await page.route(`${BASE}/api/v1/sweeps`, post);
    await page.route(`${BASE}/api/v1/sweeps/${id}`, get);
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('modal');
      await page.click('#view-sweep');
      await page.click('#sw-run');
      await page.waitForFunction(() => /running — 192 of 512 points on Slurm job 4242: 3 of 8 chunks, 2 running, 2 pending$/.test(document.getElementById('sw-status-text').textContent));
      await sweepDone('sw', 'failed', 20000);
      assert.match(await page.textContent('#sw-status-text'), /failed: 192 of 512 points on Slurm job 4242: 3 of 8 chunks, no task pending or running\.$/);
      assert.equal(await page.isVisible('#sw-error'), true);
      assert.match(await page.textContent('#sw-error'), /Array task 7 of Slurm job 4242 ended FAILED with exit code 2:0/);
    } finally {
      await page.unroute(`${BASE}/api/v1/sweeps`, post);
      await page.unroute(`${BASE}/api/v1/sweeps/${id}`, get);
      await page.click('#view-result');
    }
  });

  test(`${width} px: an over sweep plots the mean against the parameter with a band from min to max (issue 42)`, { timeout: 240000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('contact');
      await page.click('#view-sweep');
      const over = { base: { analysis: 'contact', bore: { distortion: [{ order: 2, amplitude: 5e-6, phase_deg: 0 }] } },
        parameters: [{ path: '/ring/tangential_force', values: [8, 10, 12] }],
        over: { path: '/bore/distortion/0/phase_deg', range: { start: 0, stop: 90, count: 4 } },
        outputs: ['/mean_pressure_pa', 'max(/pressure_pa)'] };
      await page.fill('#sw-spec', JSON.stringify(over));
      await page.click('#sw-run');
      await sweepDone('sw');
      const sw = await newestSweep();
      assert.equal(sw.runs, 12, '3 points x 4 over values');
      const col = (name) => sw.table.columns.indexOf(name);
      assert.equal(col('min:max(/pressure_pa)'), 6);
      // The mean is plotted first, with its band: one bar per point, the area over all three.
      assert.equal(await page.$eval('#sw-y option:checked', (o) => o.textContent), 'mean:/mean_pressure_pa');
      const pts = await circles('sw-plot');
      assert.deepEqual(pts.map((p) => p.y), sw.table.rows.map((r) => r[col('mean:/mean_pressure_pa')]));
      assert.equal(await page.getAttribute('#sw-plot-band', 'data-points'), '3');
      const area = await page.locator('#sw-plot-band .band-area').boundingBox();
      assert.ok(area && area.width > 0 && area.height > 0, 'the band is drawn');
      // Choosing max(/pressure_pa)'s max column draws that output's band; each bar
      // spans min (below) to max (above) around its mean marker (screen y falls as values grow).
      await page.selectOption('#sw-y', { label: 'max:max(/pressure_pa)' });
      const bars = await page.$$eval('#sw-plot-band line.band-bar', (ls) => ls.map((l) => [Number(l.getAttribute('y1')), Number(l.getAttribute('y2'))]));
      const means = await circles('sw-plot');
      assert.equal(bars.length, 3);
      assert.deepEqual(means.map((p) => p.y), sw.table.rows.map((r) => r[col('mean:max(/pressure_pa)')]));
      bars.forEach(([lo, hi], i) => assert.ok(lo > hi && lo >= means[i].cy && means[i].cy >= hi, `bar ${i}: min below, max above the mean`));
      assert.match(await page.textContent('#sw-result figcaption'), /band from their min to their max/);
      if (width === 390) {
        const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
        assert.ok(overflow <= 0, `no sideways scrolling (${overflow} px)`);
        await settled();
        assert.deepEqual(await smallText(), [], 'over sweep view');
      }
      await shot(`ringdyn-sweep-over-${width}.png`, { fullPage: true });
    } finally {
      await page.fill('#sw-spec', ''); // the next opening of the view fills it from the form again
      await page.setViewportSize({ width: 1280, height: 800 });
      await page.click('#view-result');
    }
  });

  test(`${width} px: speed vs accuracy plots wall time against the error estimate, the Pareto front marked; a Pareto setting goes back into the form`, { timeout: 240000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('modal');
      await page.click('#view-fidelity');
      await page.click('#fd-run');
      await sweepDone('fd');
      const sw = await newestSweep();
      assert.equal(sw.kind, 'fidelity');
      const t = sw.fidelity, c = (name) => t.columns.indexOf(name);
      const ok = t.rows.filter((r) => r[c('status')] === 'ok');
      const pts = await circles('fd-plot');
      assert.equal(pts.length, ok.length);
      assert.deepEqual(pts.map((p) => p.x), ok.map((r) => r[c('/numerics/wall_s')]));
      assert.deepEqual(pts.map((p) => p.cls.includes('pareto')), ok.map((r) => r[c('pareto')]));
      // The front: cheaper means less accurate (sorted by time, the estimates fall).
      const front = pts.filter((p) => p.cls.includes('pareto')).sort((a, b) => a.x - b.x);
      assert.ok(front.length >= 1);
      for (let i = 1; i < front.length; i++) assert.ok(front[i].y < front[i - 1].y, 'the Pareto front trades time for error');
      assert.equal(pathPoints(await page.getAttribute('#fd-plot .front-line', 'd')), front.length);
      // The hover readout reads the front off its log axes (plotui.js).
      await page.locator('#fd-plot').scrollIntoViewIfNeeded();
      const fb = await page.$eval('#fd-plot', (s) => { const r = s.querySelector(':scope > .axes path.axis').getBoundingClientRect(); return { x: r.left, y: r.top, w: r.width, h: r.height }; });
      await page.mouse.move(1, 1);
      await page.mouse.move(fb.x + fb.w / 2, fb.y + fb.h / 2, { steps: 2 });
      const read = await page.$eval('.chart-readout:not([hidden]) tr[data-series="Pareto front"]', (r) => [Number(r.dataset.x), Number(r.dataset.y)]);
      assert.ok(front.some((p) => Math.abs(read[0] / p.x - 1) < 1e-3 && Math.abs(read[1] / p.y - 1) < 1e-3), `${read} is a point of the front`);
      await page.mouse.move(1, 1);
      assert.equal(await page.locator('#fd-table button.use').count(), front.length);
      // Each marker at the row's error on its basis (the modal estimate covers the segment count).
      assert.deepEqual(pts.map((p) => p.y), ok.map((r) => r[c('error_on_basis')]));
      // The cheapest setting within 1 %: what the table says, on a basis it has.
      const within = ok.filter((r) => r[c('basis')] && r[c('error_on_basis')] <= 0.01).sort((a, b) => a[c('/numerics/wall_s')] - b[c('/numerics/wall_s')])[0];
      assert.match(await page.textContent('#fd-cheapest'), new RegExp(`segments ${within[0]}\\b`));
      assert.ok(within[c('error_vs_finest')] <= 0.01, 'the recommended setting is within 1 % of the finest run');
      // A Pareto setting other than the form's goes into the form.
      const k = ok.findIndex((r) => r[c('pareto')] && r[0] !== 20);
      await page.click(`#fd-use-${k}`);
      assert.equal(await page.inputValue('#f-segments'), String(ok[k][0]));
      assert.match(await page.textContent('#fd-applied'), new RegExp(`segments = ${ok[k][0]} went into the form`));
      if (width === 390) {
        const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
        assert.ok(overflow <= 0, `no sideways scrolling (${overflow} px)`);
        await settled();
        assert.deepEqual(await smallText(), [], 'speed vs accuracy view');
      }
      await shot(`ringdyn-fidelity-${width}.png`, { fullPage: true });
    } finally {
      await page.setViewportSize({ width: 1280, height: 800 });
      await page.click('#view-result');
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
    }
  });
}

// The tilted-piston lift (issue 44): the lift estimate covers the time
// integration, and the segment count only where the full ring had its n/2
// run (16 segments and up).  At 4 segments it estimates 0.3 % and sits 14 %
// from the finest run: the view must not recommend it.  The first lift-off
// (~300 deg) carries the largest difference, so 0.45 cycle keeps the case at
// half the cost.  1280 px runs it on the server; 390 px shows the same answer.
let tiltedSweep = null;
for (const width of [1280, 390]) {
  test(`${width} px: speed vs accuracy on the tilted piston recommends only what it measured or what an estimate covers; each row states its basis and the estimate's scope`, { skip: SKIP.lift, timeout: 240000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    const { examples } = await (await page.request.get(`${BASE}/api/v1/examples`)).json();
    const tilted = examples.find((e) => e.name === 'lift_tilted');
    assert.ok(tilted, 'the tilted-piston lift example is served');
    const replay = (route) => (route.request().method() === 'POST' ? route.fulfill({ status: 200, json: tiltedSweep }) : route.continue());
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await page.waitForFunction((n) => document.querySelectorAll('#example option').length === n, examples.length + 1);
      await page.selectOption('#example', { index: examples.indexOf(tilted) + 1 });
      await selectTab('lift');
      await page.fill('#f-lf-cycles', '0.45');
      await page.click('#view-fidelity');
      if (tiltedSweep) await page.route(`${BASE}/api/v1/sweeps`, replay);
      await page.click('#fd-run');
      await sweepDone('fd', 'succeeded', 200000);
      const sw = tiltedSweep ?? await newestSweep();
      assert.equal(sw.kind, 'fidelity');
      if (!tiltedSweep) assert.equal(sw.fidelity.rows.length, 16, 'segments 4..32 x rtol 1e-4..1e-7');
      tiltedSweep = sw;
      const t = sw.fidelity, c = (name) => t.columns.indexOf(name);
      const ok = t.rows.filter((r) => r[c('status')] === 'ok');
      const wall = (r) => r[c('/numerics/wall_s')];
      const cheapest = (rs) => rs.slice().sort((a, b) => wall(a) - wall(b))[0];
      const finest = ok.find((r) => r[c('changes')] === '');
      assert.deepEqual([finest[0], finest[1]], [32, 1e-7], 'the finest setting');
      // The case: an estimate within 1 % that the measured difference contradicts.
      const misleading = ok.filter((r) => r[c('/numerics/error_estimate')] <= 0.01 && r[c('error_vs_finest')] > 0.01);
      assert.ok(misleading.some((r) => r[0] === 4), 'at 4 segments the time-only estimate is within 1 %, the run is not');
      // The server's basis: an estimate only where it covers every discretisation the setting changes.
      for (const r of ok) {
        const covers = (r[c('estimate_covers')] ?? '').split(' '), changes = r[c('changes')].split(' ').filter(Boolean);
        if (r[c('basis')] === 'estimate') {
          assert.ok(changes.every((w) => covers.includes(w)), `${r[0]}/${r[1]}: its estimate covers ${changes}`);
          assert.ok(r[c('error_on_basis')] >= r[c('error_vs_finest')]);
        } else assert.equal(r[c('error_on_basis')], r[c('error_vs_finest')]);
        if (r[0] < 12) assert.equal(r[c('basis')], 'measured', `${r[0]} segments: no n/2 run, the estimate covers time only`);
      }
      // Each row says its basis and shows the estimate's scope as text next to it.
      const cells = await page.$$eval('#fd-table tbody tr', (trs) => trs.map((tr) => ({
        basis: tr.querySelector('td.basis').textContent, est: tr.querySelector('td.est').textContent })));
      assert.equal(cells.length, ok.length);
      ok.forEach((r, i) => {
        const scope = (r[c('estimate_covers')] ?? '').split(' ').join(', ');
        assert.equal(cells[i].basis, r[c('basis')] === 'estimate' ? `estimate (covers: ${scope})` : 'measured vs finest', `row ${i}`);
        assert.match(cells[i].est, new RegExp(`covers ${scope}$`), `row ${i}: the estimate's scope beside it`);
      });
      assert.equal(await page.locator('#fd-result [title]').count(), 0, 'no scope hidden in a tooltip');
      assert.ok(await page.isVisible('#fd-row-0 td.est'));
      // The recommendation at several targets: the cheapest row on a basis it
      // has, whose measured difference from the finest run is within the target.
      for (const pct of ['1', '2', '0.1']) {
        await page.fill('#fd-target', pct);
        const target = Number(pct) / 100;
        const want = cheapest(ok.filter((r) => r[c('basis')] && r[c('error_on_basis')] <= target));
        const text = await page.textContent('#fd-cheapest');
        if (!want) {
          assert.match(text, /^No setting is within/, `${pct} %: ${text}`);
          continue;
        }
        assert.ok(want[c('error_vs_finest')] <= target, `${pct} %: measured ${want[c('error_vs_finest')]}`);
        assert.match(text, new RegExp(`: segments ${want[0]}, rtol ${want[1]} \\(`), `${pct} %: ${text}`);
        assert.match(text, want[c('basis')] === 'estimate'
          ? new RegExp(`on its estimate, .*\\(covers: ${want[c('estimate_covers')].split(' ').join(', ')}\\); measured against the finest run`)
          : /measured against the finest run \(segments 32, rtol 1e-7\)/, `${pct} %: says its basis`);
        assert.equal(await page.getAttribute('#fd-cheapest', 'data-basis'), want[c('basis')]);
        // A cheaper setting its estimate alone would have passed is named, with why not.
        const lure = cheapest(ok.filter((r) => r[c('/numerics/error_estimate')] <= target && !(r[c('error_on_basis')] <= target) && wall(r) < wall(want)));
        if (lure) assert.match(await page.textContent('#fd-distrusted'), new RegExp(`^Not segments ${lure[0]}, rtol ${lure[1]} .*not the segments it changes`));
      }
      // "Use it" puts the recommended setting (at 1 %) into the form.
      await page.fill('#fd-target', '1');
      const want = cheapest(ok.filter((r) => r[c('basis')] && r[c('error_on_basis')] <= 0.01));
      assert.ok(want[0] >= 16, `1 %: not a setting below 16 segments (${want[0]})`);
      await page.click('#fd-use-cheapest');
      assert.equal(await page.inputValue('#f-segments'), String(want[0]));
      assert.equal(Number(await page.inputValue('#f-lf-rtol')), want[1]);
      assert.match(await page.textContent('#fd-applied'), new RegExp(`segments = ${want[0]}, rtol = ${want[1]} went into the form`));
      if (width === 390) {
        const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
        assert.ok(overflow <= 0, `no sideways scrolling (${overflow} px)`);
        await settled();
        assert.deepEqual(await smallText(), [], 'speed vs accuracy view, tilted lift');
      }
      await shot(`ringdyn-fidelity-tilted-${width}.png`, { fullPage: true });
    } finally {
      await page.unroute(`${BASE}/api/v1/sweeps`, replay);
      await page.setViewportSize({ width: 1280, height: 800 });
      await page.click('#view-result');
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
    }
  });
}

// ---- the Calibrate view (issue 42 item 1) --------------------------------------

const calDone = (word = 'succeeded', timeout = 90000) => page.waitForFunction(
  (w) => new RegExp(`^Calibration \\w+ ${w}`).test(document.getElementById('cal-status-text').textContent) && !document.getElementById('cal-run').disabled,
  word, { timeout });

for (const width of [1280, 390]) {
  test(`${width} px: the shipped calibration runs from the Calibrate view: fitted parameter ± standard error, notes as text, measured (± sigma) vs fitted; bounds reversed name their field`, { timeout: 150000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.click('#view-calibrate');
      assert.equal(await page.getAttribute('#view-calibrate', 'aria-selected'), 'true');
      assert.equal(await page.isVisible('#result-view'), false, 'the result view is hidden');
      await page.getByRole('button', { name: 'Fill from the example' }).click();
      await page.waitForFunction(() => document.getElementById('cal-spec').value.includes('leak_area_m2'));
      const spec = JSON.parse(await page.inputValue('#cal-spec'));
      const shipped = await (await page.request.get(`${BASE}/api/v1/examples/calibration_ringpack_blowby`)).json();
      assert.deepEqual(spec, shipped, 'the editor holds the shipped example');
      assert.equal(spec.measurements.length, 4);
      await page.getByRole('button', { name: 'Run calibration' }).click();
      await calDone();
      const id = /^Calibration (\w+) succeeded/.exec(await page.textContent('#cal-status-text'))[1];
      const job = await serverJob(id);
      const r = job.result;
      assert.equal(r.analysis, 'calibration');
      assert.match(await page.textContent('#cal-status-text'), new RegExp(`${r.runs} scene runs`));

      // The parameter table: the server's value and standard error, bounds, identifiable.
      const rows = await page.$$eval('#cal-params tbody tr', (trs) => trs.map((tr) => ({
        path: tr.querySelector('.path').textContent, value: Number(tr.querySelector('.value').dataset.value),
        std: Number(tr.querySelector('.std').dataset.stdError), stdText: tr.querySelector('.std').textContent,
        state: tr.querySelector('.state').textContent, bounds: tr.querySelector('.bounds').textContent })));
      assert.equal(rows.length, 1);
      assert.equal(rows[0].path, '/rings/2/leak_area_m2');
      assert.equal(rows[0].value, r.parameters[0].value);
      assert.ok(r.parameters[0].std_error > 0, 'the example is identifiable');
      assert.equal(rows[0].std, r.parameters[0].std_error);
      assert.match(rows[0].stdText, /^± \d/);
      assert.equal(rows[0].state, 'identifiable');
      assert.match(rows[0].bounds, /^1e-8 to 2e-7/);
      // the fit should find 5.5e-8 within a few standard errors (the example's own claim)
      assert.ok(Math.abs(r.parameters[0].value - 5.5e-8) < 4 * r.parameters[0].std_error, `${r.parameters[0].value} ± ${r.parameters[0].std_error}`);
      assert.match(await page.textContent('#cal-runs'), new RegExp(`^${r.runs}$`));
      assert.match(await page.textContent('#cal-chi2'), new RegExp(`/ ${r.dof}`));
      assert.match(await page.textContent('#cal-converged'), new RegExp(`\\(stop: ${r.stop}\\)`));

      // The notes: shown as text (not a tooltip), every one of the server's.
      assert.ok(r.notes.length > 0, 'the server gave notes');
      assert.deepEqual(await page.$$eval('#cal-notes li', (lis) => lis.map((li) => li.textContent)), r.notes);
      assert.equal(await page.isVisible('#cal-notes'), true);
      assert.match(await page.textContent('#cal-notes-title'), /do not cover/);

      // Measured vs fitted: 4 measured points with error bars of ± sigma, 4 fitted diamonds, none in the legend.
      const plot = await page.$eval('#cal-plot-0', (s) => {
        const data = (sel) => [...s.querySelectorAll(sel)].filter((e) => !e.closest('.legend'));
        return {
          label: s.getAttribute('aria-label'),
          measured: data('circle.cal-measured').map((c) => ({ y: Number(c.dataset.y), cy: Number(c.getAttribute('cy')), cx: Number(c.getAttribute('cx')), title: c.querySelector('title').textContent })),
          fitted: data('.cal-fitted').map((p) => ({ tag: p.tagName, y: Number(p.dataset.y) })),
          bars: data('g.cal-errbar').map((g) => {
            const l = g.querySelector('line');
            return { lo: Number(g.dataset.lo), hi: Number(g.dataset.hi), y1: Number(l.getAttribute('y1')), y2: Number(l.getAttribute('y2')), x: Number(l.getAttribute('x1')) };
          }),
          legend: [...s.querySelectorAll('.legend text')].map((t) => t.textContent),
        };
      });
      assert.match(plot.label, /\/blowby\/l_per_min: measured .* and fitted at 4 measurements/);
      assert.equal(plot.measured.length, 4);
      assert.equal(plot.fitted.length, 4);
      assert.equal(plot.bars.length, 4);
      assert.ok(plot.fitted.every((f) => f.tag === 'path'), 'fitted: another marker than the measured circles');
      assert.deepEqual(plot.measured.map((p) => p.y), r.measurements.map((m) => m.measured));
      assert.deepEqual(plot.fitted.map((p) => p.y), r.measurements.map((m) => m.fitted));
      plot.bars.forEach((b, i) => {
        const { value, sigma } = spec.measurements[i];
        assert.ok(Math.abs(b.lo - (value - sigma)) < 1e-12 && Math.abs(b.hi - (value + sigma)) < 1e-12, `bar ${i}: measured ± sigma`);
        assert.ok(b.y1 > plot.measured[i].cy && plot.measured[i].cy > b.y2, `bar ${i} spans its point`);
        assert.equal(b.x, plot.measured[i].cx);
      });
      assert.match(plot.measured[0].title, /\/engine\/speed_rpm = 1500/);
      assert.deepEqual(plot.legend, ['measured ± 1 sigma', 'fitted']);
      assert.equal(await page.locator('#cal-measurements tbody tr').count(), 4);

      const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
      assert.ok(overflow <= 0, `no sideways scrolling (${overflow} px)`);
      if (width === 390) {
        await settled();
        assert.deepEqual(await smallText(), [], 'calibrate view');
      }
      await shot(`ringdyn-calibrate-${width}.png`, { fullPage: true });

      // Bounds reversed: the server's message next to the editor with its path; no job.
      const jobsBefore = (await (await page.request.get(`${BASE}/api/v1/jobs?limit=200`)).json()).jobs.length;
      const bad = structuredClone(spec);
      Object.assign(bad.parameters[0], { min: 2e-7, max: 1e-8 });
      await page.fill('#cal-spec', JSON.stringify(bad, null, 2));
      await page.click('#cal-run');
      await page.waitForSelector('#cal-error:not([hidden])');
      assert.match(await page.textContent('#cal-error'), /min .* must be below max .*bounds reversed/);
      assert.equal(await page.textContent('#cal-error code'), '/parameters/0');
      assert.equal((await (await page.request.get(`${BASE}/api/v1/jobs?limit=200`)).json()).jobs.length, jobsBefore);
      assert.equal(await page.$$eval('#cal-result > *', (es) => es.length), 0, 'no result shown for a refused spec');
      // Chromium logs the 400 as a failed resource load: expected here.
      for (let i = consoleErrors.length - 1; i >= 0; i--) if (/status of 400/.test(consoleErrors[i])) consoleErrors.splice(i, 1);
      if (width === 390) {
        const o = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
        assert.ok(o <= 0, `no sideways scrolling with the error shown (${o} px)`);
      } else {
        // A parameter the data cannot fix (the pinned second ring's tangential force): marked, no std error.
        const unid = structuredClone(spec);
        unid.parameters.push({ path: '/rings/1/ring/tangential_force', min: 5, max: 20 });
        await page.fill('#cal-spec', JSON.stringify(unid, null, 2));
        await page.click('#cal-run');
        await calDone();
        const ru = (await serverJob(/^Calibration (\w+) succeeded/.exec(await page.textContent('#cal-status-text'))[1])).result;
        assert.equal(ru.parameters[1].identifiable, false);
        assert.equal(await page.getAttribute('#cal-param-1', 'data-identifiable'), 'false');
        assert.equal(await page.textContent('#cal-param-1 .state strong'), 'not identifiable');
        assert.equal(await page.$eval('#cal-param-1 .std', (e) => e.dataset.stdError ?? null), null, 'no standard error shown');
        assert.match(await page.textContent('#cal-verdict'), /^Not identifiable: \/rings\/1\/ring\/tangential_force/);
        assert.deepEqual(await page.$$eval('#cal-notes li', (lis) => lis.map((li) => li.textContent)), ru.notes);
        assert.equal(await page.locator('#cal-correlation').count(), 1);
      }
    } finally {
      await page.fill('#cal-spec', '');
      await page.setViewportSize({ width: 1280, height: 800 });
      await page.click('#view-result');
    }
  });
}

test('after its first quick polls the page long-polls (?wait=1); a job the server interrupted ends the wait at once', { timeout: 60000 }, async () => {
  await page.goto(`${BASE}/`);
  await page.waitForSelector('#tab-modal[aria-selected="true"]');
  const urls = [];
  const match = (url) => url.pathname.startsWith('/api/v1/jobs');
  await page.route(match, (route) => {
    if (route.request().method() === 'POST') return route.fulfill({ status: 202, json: { id: 'cut-job', status: 'running', progress: 0.1 } });
    urls.push(new URL(route.request().url()).search);
    if (urls.length < 5) return route.fulfill({ json: { id: 'cut-job', status: 'running', progress: 0.2 } });
    return route.fulfill({ json: { id: 'cut-job', status: 'interrupted', progress: 0.3, error: { code: 'interrupted', message: 'The server stopped while the job ran.', path: '' } } });
  });
  try {
    const t0 = Date.now();
    await runAnalysis('Run modal analysis', 20000);
    assert.ok(Date.now() - t0 < 15000, 'not polled until a timeout');
    assert.deepEqual(urls, ['', '', '', '?wait=1', '?wait=1']);
    assert.equal(await page.textContent('#status-text'), 'Job cut-job interrupted.');
    assert.match(await page.textContent('#error'), /The server stopped while the job ran/);
  } finally {
    await page.unroute(match);
    await page.getByRole('button', { name: 'Reset to defaults' }).click();
  }
});

test('the server\'s eta_s is shown when a job has one; a job that fails leaves the old result marked out of date', { timeout: 60000 }, async () => {
  await page.goto(`${BASE}/`);
  await page.waitForSelector('#tab-modal[aria-selected="true"]');
  const jobs = await interceptJobs(fixtures.pretensionResult());
  try {
    await selectTab('pretension');
    await runAnalysis('Run pretension analysis');
  } finally {
    await jobs.stop();
  }
  assert.equal(await page.locator('#result-body #pt-shape').count(), 1);
  // Then a job the test answers: queued, running with eta_s, failed.
  let polls = 0;
  const match = (url) => url.pathname.startsWith('/api/v1/jobs');
  await page.route(match, (route) => {
    if (route.request().method() === 'POST') return route.fulfill({ status: 202, json: { id: 'eta-job', status: 'queued', progress: 0 } });
    polls += 1;
    if (polls < 5) return route.fulfill({ json: { id: 'eta-job', status: 'running', progress: 0.25, eta_s: 95 } });
    return route.fulfill({ json: { id: 'eta-job', status: 'failed', progress: 0.3, error: { code: 'solver_failed', message: 'Newton did not converge in load step 3.', path: '' } } });
  });
  try {
    await page.evaluate(() => {
      window.statusLog = [];
      new MutationObserver(() => window.statusLog.push(document.getElementById('status-text').textContent))
        .observe(document.getElementById('status'), { subtree: true, childList: true, characterData: true });
    });
    await runAnalysis('Run pretension analysis');
    const log = await page.evaluate(() => window.statusLog);
    assert.ok(log.some((t) => /^Job eta-job running — 25 % · \d+ s elapsed · about 1 min 35 s left$/.test(t)), `eta_s shown: ${JSON.stringify(log)}`);
    assert.equal(log.at(-1), 'Job eta-job failed.');
    assert.match(await page.textContent('#error'), /Newton did not converge in load step 3/);
    assert.match(await page.textContent('#result-stale'), /Out of date: job eta-job failed\./);
    assert.equal(await page.locator('#result-body #pt-shape').count(), 1, 'the old result is still there, marked');
    assert.equal(jobInUrl(), 'eta-job');
  } finally {
    await page.unroute(match);
  }
});

// Clicks the SVG and PNG button of every figure shown (at least `count`):
// the SVG is a standalone document holding the chart's text, with its font
// size written in; the PNG is twice the SVG's size.
async function checkExports(prefix, count) {
  const figures = page.locator('#result-body :is(figure, [data-figure])');
  assert.ok(await figures.count() >= count, `${await figures.count()} figures, at least ${count}`);
  for (let i = 0; i < await figures.count(); i++) {
    const fig = figures.nth(i);
    const texts = await fig.locator('svg[viewBox]:not(.icon) text').allTextContents();
    const svgFile = await download(() => fig.locator('button[data-export="svg"]').click());
    assert.ok(svgFile.name.startsWith(prefix) && svgFile.name.endsWith('.svg'), svgFile.name);
    const doc = svgFile.data.toString();
    const parsed = await page.evaluate((doc) => {
      const d = new DOMParser().parseFromString(doc, 'image/svg+xml');
      const root = d.documentElement;
      return {
        error: d.querySelector('parsererror')?.textContent ?? null,
        root: root.localName, width: Number(root.getAttribute('width')), height: Number(root.getAttribute('height')),
        texts: [...d.querySelectorAll('text')].map((t) => t.textContent),
        styled: [...d.querySelectorAll('text')].every((t) => /font-size:\s*[\d.]+px/.test(t.getAttribute('style') || '')),
        classes: d.querySelectorAll('[class]').length,
      };
    }, doc);
    assert.equal(parsed.error, null);
    assert.equal(parsed.root, 'svg');
    assert.deepEqual(parsed.texts, texts, 'the exported file holds the chart\'s text');
    assert.ok(parsed.styled && parsed.classes === 0, 'styles written in, no dependence on the page\'s CSS');
    const button = fig.locator('button[data-export="png"]');
    const png = await download(() => button.click()).catch(async (e) => {
      throw new Error(`PNG of figure ${i} (${await fig.locator('svg').first().getAttribute('id')}): ${await button.getAttribute('title')} ${e.message}`);
    });
    assert.ok(png.name.startsWith(prefix) && png.name.endsWith('.png'), png.name);
    assert.equal(png.data.subarray(1, 4).toString(), 'PNG');
    assert.equal(png.data.readUInt32BE(16), Math.round(parsed.width * 2), 'PNG width: twice the SVG');
    assert.equal(png.data.readUInt32BE(20), Math.round(parsed.height * 2));
  }
}

test('390 px: no text below 10 px in any analysis, form or result; warnings of a result are listed', { timeout: 120000 }, async () => {
  await page.setViewportSize({ width: 390, height: 844 });
  try {
    await page.getByRole('button', { name: 'Reset to defaults' }).click();
    await selectTab('modal');
    await runAnalysis();
    await settled();
    assert.deepEqual(await smallText(), [], 'modal');
    // The frequency plot's text was enlarged in viewBox units to stay readable.
    const tick = await page.$eval('#freq-plot text.tick', (t) => parseFloat(getComputedStyle(t).fontSize) * t.getScreenCTM().a);
    assert.ok(tick >= 10, `tick label ${tick} px`);
    const cases = [
      fixtures.pretensionResult({ lateral: 1 }), fixtures.contactResult(), fixtures.contactRoundResult(),
      fixtures.liftResult(), fixtures.liftResult({ friction: false }), fixtures.liftGasResult(),
    ];
    for (const result of cases) {
      const warned = { ...result, warnings: ['Density 7.85 kg/m³ is below 1000 kg/m³: g/cm³ typed as kg/m³?', { code: 'estimate', message: 'The estimated error is 22 %.', path: '/numerics/error_estimate' }] };
      const jobs = await interceptJobs(warned);
      try {
        await selectTab(result.analysis);
        if (result.analysis === 'contact') await page.getByRole('button', { name: 'Add a distortion order' }).click();
        await runAnalysis(`Run ${result.analysis} analysis`);
        await settled();
        assert.deepEqual(await smallText(), [], `${result.analysis}`);
        assert.deepEqual(await page.$$eval('#result-warnings li', (ls) => ls.map((l) => l.textContent)),
          [warned.warnings[0], 'The estimated error is 22 %. (/numerics/error_estimate)']);
        assert.doesNotMatch(await page.textContent('#result-body'), /\bnull\b|undefined|NaN/);
        const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
        assert.ok(overflow <= 0, `${result.analysis}: page scrolls sideways by ${overflow}px`);
        if (result === cases.at(-1)) await shot('ringdyn-narrow-lift-gas.png', { fullPage: true });
      } finally {
        await jobs.stop();
      }
    }
    // No warnings: no list.
    const jobs = await interceptJobs(fixtures.pretensionResult());
    try {
      await selectTab('pretension');
      await runAnalysis('Run pretension analysis');
      assert.equal(await page.isVisible('#result-warnings'), false);
    } finally {
      await jobs.stop();
    }
  } finally {
    await page.setViewportSize({ width: 1280, height: 800 });
    await page.getByRole('button', { name: 'Reset to defaults' }).click();
  }
});

// The vertices of a path's d ("M x,y L x,y ..."), as [x, y] pairs.
const vertices = (d) => [...d.matchAll(/[ML](-?[\d.]+),(-?[\d.]+)/g)].map((m) => [Number(m[1]), Number(m[2])]);

for (const width of [1280, 390]) {
  test(`${width} px: lift draws its gas pressures and zooms to one cycle; contact shows the ±1 % round-bore ripple against angle`, { timeout: 60000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      const lf = fixtures.liftGasResult();
      let jobs = await interceptJobs(lf);
      try {
        await selectTab('lift');
        await runAnalysis('Run lift analysis');
      } finally {
        await jobs.stop();
      }
      // The crank axis in px per degree, from its tick labels.
      const axis = async () => {
        const t = await page.$$eval('#lf-gas .axes text.tick[text-anchor="middle"]', (ts) => ts.map((e) => [Number(e.textContent), Number(e.getAttribute('x'))]));
        return { first: t[0][0], last: t.at(-1)[0], x: (c) => t[0][1] + ((c - t[0][0]) * (t.at(-1)[1] - t[0][1])) / (t.at(-1)[0] - t[0][0]) };
      };
      const peaks = async () => {
        const v = vertices(await page.getAttribute('#lf-gas-above', 'd'));
        const top = Math.min(...v.map((p) => p[1]));
        return v.filter((p) => Math.abs(p[1] - top) < 0.01).map((p) => p[0]);
      };
      assert.match(await page.getAttribute('#lf-gas', 'aria-label'), /up to 60 bar: above the ring 1 to 60 bar; behind the ring 1 to 45 bar; below the ring 1 to 8 bar/);
      let a = await axis();
      assert.deepEqual([a.first, a.last], [0, 1440]);
      // The table's 60 bar at 360° repeats each cycle: at 360° and 1080°.
      assert.deepEqual((await peaks()).map((px) => Math.round((px - a.x(0)) / ((a.x(720) - a.x(0)) / 720))), [360, 1080]);
      assert.equal(await page.locator('#lf-lift .event').count(), lf.events.length);

      // One cycle: the second.
      await page.selectOption('#lf-zoom', { index: 2 });
      await page.waitForFunction(() => document.querySelector('#lf-lift .axes text.tick[text-anchor="middle"]')?.textContent === '720');
      a = await axis();
      assert.deepEqual([a.first, a.last], [720, 1440]);
      assert.deepEqual((await peaks()).map((px) => Math.round(720 + (px - a.x(720)) / ((a.x(1440) - a.x(720)) / 720))), [1080]);
      assert.equal(await page.locator('#lf-lift .event').count(), lf.events.filter((e) => e.crank_deg >= 720).length);
      const flank = await page.$$eval('#lf-flank .flank-runs rect', (rs) => rs.map((r) => r.dataset.flank));
      assert.deepEqual(flank, runsOf(lf.flank.slice(720)));
      assert.equal(await page.locator('#lf-gas').locator('xpath=ancestor::figure').locator('button[data-export="svg"]').count(), 1, 'the redrawn figure has its export buttons');
      await page.selectOption('#lf-zoom', { index: 0 });
      await page.waitForFunction(() => document.querySelector('#lf-lift .axes text.tick[text-anchor="middle"]')?.textContent === '0');
      await settled();
      assert.deepEqual(await smallText(), [], 'lift with gas');

      // Contact in a round bore: the ripple fills most of the Cartesian plot's height.
      const ct = fixtures.contactRoundResult();
      jobs = await interceptJobs(ct);
      try {
        await selectTab('contact');
        await runAnalysis('Run contact analysis');
      } finally {
        await jobs.stop();
      }
      const q = ct.pressure_pa.map((p) => p / ct.uniform_pressure_pa - 1);
      const dev = (await page.getAttribute('#ct-cartesian', 'data-deviation')).split(' ').map(Number);
      assert.ok(Math.abs(dev[0] - Math.min(...q)) < 1e-6 && Math.abs(dev[1] - Math.max(...q)) < 1e-6, `deviation ${dev}`);
      const pts = vertices(await page.getAttribute('#ct-cart-line', 'd'));
      assert.equal(pts.length, ct.angle_deg.length);
      const box = await page.$eval('#ct-cartesian .axes .axis', (p) => p.getAttribute('d').match(/M([\d.]+),([\d.]+)V([\d.]+)/).slice(1).map(Number));
      const extent = Math.max(...pts.map((p) => p[1])) - Math.min(...pts.map((p) => p[1]));
      assert.ok(extent > 0.5 * (box[2] - box[1]), `the ${((Math.max(...q) - Math.min(...q)) * 100).toFixed(2)} % ripple spans ${extent.toFixed(0)} of ${box[2] - box[1]} units`);
      const polar = vertices(await page.getAttribute('#ct-pressure', 'd'));
      assert.equal(polar.length, ct.angle_deg.length);
      await settled();
      assert.deepEqual(await smallText(), [], 'contact');
      await shot(`ringdyn-plots-${width}.png`, { fullPage: true });
    } finally {
      await page.setViewportSize({ width: 1280, height: 800 });
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
    }
  });
}

// ---- the flank band (issue 39): drawn, dated, in the event table ----------

// What a lift or ring pack plot draws of the flank band, in viewBox units:
// the strips (not the legend's swatch) with their flank side and ring, the
// strip edges, the flank lines and the y axis' ticks [value, y].
async function bandDrawing(chart) {
  return page.$eval(chart, (svgEl) => {
    const n = (el, a) => Number(el.getAttribute(a));
    return {
      strips: [...svgEl.querySelectorAll('rect.flank-band')].filter((r) => !r.closest('.legend'))
        .map((r) => ({ side: r.dataset.side, ring: Number(r.dataset.ring || 0), y: n(r, 'y'), height: n(r, 'height') })),
      edges: [...svgEl.querySelectorAll('line.flank-band-edge')].map((l) => n(l, 'y1')),
      lower: svgEl.querySelector('#lf-lower line') ? n(svgEl.querySelector('#lf-lower line'), 'y1') : null,
      upper: svgEl.querySelector('#lf-upper line') ? n(svgEl.querySelector('#lf-upper line'), 'y1') : null,
      yTicks: [...svgEl.querySelectorAll('.axes text.tick[text-anchor="end"]')].map((t) => [Number(t.textContent), n(t, 'y')]),
      legend: [...svgEl.querySelectorAll('.legend text')].map((t) => t.textContent),
    };
  }, null);
}

// The y axis as drawn: value (µm) -> viewBox y, from the first and last tick labels.
function yAxis(ticks) {
  const [v0, p0] = ticks[0], [v1, p1] = ticks.at(-1);
  assert.ok(v1 !== v0, `two distinct y ticks: ${JSON.stringify(ticks)}`);
  return (v) => p0 + ((v - v0) * (p1 - p0)) / (v1 - v0);
}

// A strip spans [y(a), y(b)] on screen (either order), to 0.05 units (the
// tick labels are rounded to 4 digits, so the scale is read to about that).
function assertSpan(strip, ya, yb, what) {
  const top = Math.min(ya, yb), bottom = Math.max(ya, yb);
  assert.ok(Math.abs(strip.y - top) < 0.05 && Math.abs(strip.y + strip.height - bottom) < 0.05,
    `${what}: strip ${strip.y.toFixed(3)}..${(strip.y + strip.height).toFixed(3)}, want ${top.toFixed(3)}..${bottom.toFixed(3)}`);
}

for (const width of [1280, 390]) {
  test(`${width} px: the lift plot draws the flank band where events are dated, the event table shows where the lift touched the flank and the dating rule; band 0 draws none; the ring pack draws each ring's band`, { timeout: 90000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await selectTab('lift');
      for (const band of [0.01, 0.05]) {
        const lf = fixtures.liftResult({ band });
        const ca = lf.scene.groove.axial_clearance * 1e6;
        const jobs = await interceptJobs(lf);
        try {
          await runAnalysis('Run lift analysis');
        } finally {
          await jobs.stop();
        }
        await settled();
        // The strips: from each flank to b c_a into the groove, on the plot's own y scale.
        const d = await bandDrawing('#lf-lift');
        const y = yAxis(d.yTicks);
        assert.ok(Math.abs(d.lower - y(0)) < 0.05 && Math.abs(d.upper - y(ca)) < 0.05, `flank lines at 0 and ${ca} µm`);
        assert.deepEqual(d.strips.map((s) => s.side), ['lower', 'upper']);
        assertSpan(d.strips[0], d.lower, y(band * ca), `lower band ${band}`);
        assertSpan(d.strips[1], d.upper, y(ca - band * ca), `upper band ${band}`);
        assert.ok(d.strips.every((s) => s.height > 0.5), 'the strips have a visible height');
        const edgesWant = [y(band * ca), y(ca - band * ca)];
        assert.ok(d.edges.length === 2 && d.edges.every((e, k) => Math.abs(e - edgesWant[k]) < 0.05), `dashed edges ${d.edges}, want ${edgesWant}`);
        assert.ok(d.legend.includes(`flank band (${band * 100} % of the clearance)`), `legend: ${d.legend}`);
        // The markers stay on the flanks at their crank angles, one per event.
        assert.equal(await page.locator('#lf-lift .event').count(), lf.events.length);
        // The table: where the lift touched or left the flank, — where it never did.
        assert.equal(await page.textContent('#lf-touch-head'), 'Touches / leaves the flank at (deg)');
        const touch = await page.$$eval('#lf-events tbody td.touch', (tds) => tds.map((t) => t.textContent));
        assert.deepEqual(touch, lf.events.map((e) => (e.touch_deg === null ? '—' : e.touch_deg.toFixed(2))));
        assert.ok(touch.includes('—') && lf.events.some((e) => e.touch_deg !== null && e.touch_deg !== e.crank_deg),
          'the fixture has a landing that never touched and events dated off their touch');
        assert.match(await page.textContent('#lf-dating'),
          new RegExp(`^Dated where the mean lift crosses the edge of a band of ${band * 100} % of the axial clearance \\(${(band * ca).toFixed(3)} µm\\) at the flank; the last column is where it touched or left the flank itself`));
        assert.match(await page.textContent('#lf-plots figcaption'), new RegExp(`flank band \\(${band * 100} % of the clearance\\)`));
        const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
        assert.ok(overflow <= 0, `no sideways scrolling (${overflow} px)`);
        assert.deepEqual(await smallText(), [], `lift with a ${band} band`);
        if (band === 0.01) await shot(`ringdyn-lift-band-${width}.png`, { fullPage: true });
      }

      // Band 0: nothing drawn, dated at the flank, the touch column still there.
      const lf0 = fixtures.liftResult({ band: 0 });
      const jobs = await interceptJobs(lf0);
      try {
        await runAnalysis('Run lift analysis');
      } finally {
        await jobs.stop();
      }
      const d0 = await bandDrawing('#lf-lift');
      assert.deepEqual([d0.strips, d0.edges], [[], []], 'flank_band 0: no band drawn');
      assert.ok(!d0.legend.some((t) => /flank band/.test(t)), `legend: ${d0.legend}`);
      assert.equal(await page.textContent('#lf-dating'), 'Dated where the mean lift touches the flank (landings) or the load turns away (leaves).');
      assert.deepEqual(await page.$$eval('#lf-events tbody td.touch', (tds) => tds.map((t) => t.textContent)), lf0.events.map((e) => e.touch_deg.toFixed(2)));
      assert.doesNotMatch(await page.textContent('#lf-plots figcaption'), /flank band/);

      // The ring pack: each ring's band at both flanks of its groove, on the lift plot's scale.
      await selectTab('ringpack');
      for (const band of [0.01, 0, null]) {
        // cycles "periodic": the summary says whether it settled (band 0.01: not, 0: yes)
        const periodic = band === 0.01 ? false : band === 0 ? true : undefined;
        const rp = fixtures.ringpackResult({ band, periodic });
        const rjobs = await interceptJobs(rp);
        try {
          await runAnalysis('Run ringpack analysis');
        } finally {
          await rjobs.stop();
        }
        await page.waitForSelector('#rp-lift');
        const said = await page.textContent('#rp-summary');
        if (periodic === false) assert.match(said, /periodic: NOT settled within 2 cycles/);
        else if (periodic === true) assert.match(said, /periodic: settled after 2 cycles/);
        else assert.doesNotMatch(said, /periodic:/);
        const d = await bandDrawing('#rp-lift');
        if (!band) {
          assert.deepEqual(d.strips, [], `ring pack, flank_band ${band}: no band drawn`);
          continue;
        }
        const y = yAxis(d.yTicks);
        const want = rp.scene.rings.flatMap((r, i) => ['lower', 'upper'].map((side) => ({ ring: i + 1, side, ca: r.groove.axial_clearance * 1e6 })));
        assert.deepEqual(d.strips.map((s) => [s.ring, s.side]), want.map((w) => [w.ring, w.side]));
        d.strips.forEach((s, k) => {
          const { ca, side, ring } = want[k];
          if (side === 'lower') assertSpan(s, y(0), y(band * ca), `ring ${ring} lower`);
          else assertSpan(s, y(ca), y(ca - band * ca), `ring ${ring} upper`);
        });
        assert.ok(d.legend.includes('flank bands (1 % of each groove\'s clearance)'), `legend: ${d.legend}`);
        assert.deepEqual(await smallText(), [], 'ring pack with bands');
        await shot(`ringdyn-ringpack-band-${width}.png`, { fullPage: true });
      }
    } finally {
      await page.setViewportSize({ width: 1280, height: 800 });
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
    }
  });
}

test('lift form: the flank band field has the schema\'s default and range, reaches the scene, and the server refuses 0.3 naming it', { timeout: 60000 }, async () => {
  const schemas = (await (await fetch(`${BASE}/api/v1/openapi.json`)).json()).components.schemas;
  const field = schemas.Output.properties.flank_band;
  await page.getByRole('button', { name: 'Reset to defaults' }).click();
  await selectTab('lift');
  assert.equal(Number(await page.inputValue('#f-lf-flank-band')), field.default);
  assert.equal(field.default, 0.01);
  assert.deepEqual([await page.getAttribute('#f-lf-flank-band', 'min'), await page.getAttribute('#f-lf-flank-band', 'max')].map(Number), [field.minimum, field.maximum]);
  assert.equal(await page.textContent('#f-lf-flank-band-hint'), '= 1 %');
  const jobs = await interceptJobs(fixtures.liftResult());
  try {
    await page.fill('#f-lf-flank-band', '0.05');
    await runAnalysis('Run lift analysis');
    assert.equal(jobs.sent.at(-1).output.flank_band, 0.05);
    await page.fill('#f-lf-flank-band', '0');
    await runAnalysis('Run lift analysis');
    assert.equal(jobs.sent.at(-1).output.flank_band, 0);
  } finally {
    await jobs.stop();
  }
  if (!SKIP.lift) {
    // Out of range: refused before any run, the message names the field and it is marked.
    await page.fill('#f-lf-flank-band', '0.3');
    await runAnalysis('Run lift analysis');
    await page.waitForSelector('#error:not([hidden])');
    const text = await page.textContent('#error');
    assert.match(text, /\/output\/flank_band/, `error names the field: ${text}`);
    assert.equal(await page.getAttribute('#f-lf-flank-band', 'aria-invalid'), 'true');
  }
  await page.getByRole('button', { name: 'Reset to defaults' }).click();
});

// ---- /docs: the API docs page, built from the OpenAPI document (issue 13) ----

for (const width of [1280, 390]) {
  test(`${width} px: /docs lists every path and operation of the OpenAPI document, readable, linked from the page`, { timeout: 60000 }, async () => {
    const doc = await (await fetch(`${BASE}/api/v1/openapi.json`)).json();
    try {
      await page.setViewportSize({ width, height: 844 });
      await page.goto(`${BASE}/`);
      await page.waitForSelector('#tab-modal[aria-selected="true"]');
      await page.getByRole('link', { name: 'API docs' }).click();
      await page.waitForSelector('#docs[data-ready]');
      assert.equal(new URL(page.url()).pathname, '/docs');
      // Every path with each of its methods, as a heading of its own section and in the contents.
      const want = [];
      for (const [p, item] of Object.entries(doc.paths)) {
        for (const m of ['get', 'put', 'post', 'delete', 'patch']) if (item[m]) want.push(`${m.toUpperCase()} ${p}`);
      }
      const norm = (t) => t.replace(/\s+/g, ' ').trim();
      const headings = (await page.$$eval('#docs-operations section.op h3', (hs) => hs.map((h) => h.textContent))).map(norm);
      const toc = (await page.$$eval('#docs-toc ul.toc a', (as) => as.map((a) => a.textContent))).map(norm);
      assert.deepEqual(headings.sort(), [...want].sort());
      assert.deepEqual(toc.sort(), [...want].sort());
      assert.ok(want.length >= 10, `${want.length} operations`);
      // Every schema has its section, and the scene's fields show their ranges and defaults.
      const schemas = await page.$$eval('#docs-schemas section.schema', (ss) => ss.map((s) => s.id));
      assert.deepEqual(schemas.sort(), Object.keys(doc.components.schemas).map((n) => `schema-${n}`).sort());
      const ring = await page.$eval('#schema-Ring', (s) => s.textContent);
      assert.match(ring, /diameter/);
      assert.match(ring, /default 0\.0765/);
      // The request body's examples are shown as JSON.
      const examples = await page.$$eval('#op-submitJob pre.json', (ps) => ps.map((p) => JSON.parse(p.textContent)));
      assert.ok(examples.some((e) => e.analysis === 'modal'), 'the modal example of POST /api/v1/jobs');
      // Readable: no text below 10 px, nothing wider than the screen.
      assert.deepEqual(await smallText(), [], 'no text below 10 px');
      const overflow = await page.evaluate(() => document.documentElement.scrollWidth - document.documentElement.clientWidth);
      assert.ok(overflow <= 1, `no sideways scrolling (${overflow} px)`);
      await shot(`docs-${width}.png`);
    } finally {
      await page.setViewportSize({ width: 1280, height: 800 });
      await page.goto(`${BASE}/`);
      await page.waitForSelector('#tab-modal[aria-selected="true"]');
    }
  });
}

// ---- ring pack ---------------------------------------------------

test('ring pack tab: a live two-cycle run draws every volume\'s pressure, the lifts and the blow-by', { timeout: 120000 }, async () => {
  const skip = await unavailable('ringpack');
  if (skip) return;
  await page.goto(`${BASE}/`);
  await page.waitForSelector('#tab-modal[aria-selected="true"]');
  await selectTab('ringpack');
  await page.fill('#f-rp-cycles', '2');
  await page.fill('#f-rp-speed', '3000');
  await runAnalysis('Run ringpack analysis');
  await page.waitForSelector('#rp-pressure');
  const job = await shownJob();
  const r = job.result;
  assert.equal(r.analysis, 'ringpack');
  assert.equal(r.scene.engine.cycles, 2);
  assert.equal(r.scene.engine.speed_rpm, 3000);
  // one path per volume, one point per sample (cylinder first, crankcase last)
  const paths = await page.$$eval('#rp-pressure path[data-points]', (ps) => ps.map((p) => Number(p.dataset.points)));
  assert.deepEqual(paths, r.volumes.map(() => r.crank_deg.length));
  assert.equal(r.volumes[0].name, 'cylinder');
  assert.equal(r.volumes.at(-1).name, 'crankcase');
  const lifts = await page.$$eval('#rp-lift path[data-points]', (ps) => ps.length);
  assert.equal(lifts, r.rings.length);
  assert.ok(await page.$('#rp-blowby path[data-points]'));
  const summary = await page.textContent('#rp-summary');
  assert.match(summary, /Blow-by [\d.e+-]+ L\/min/);
  assert.ok(summary.includes(String(Number(r.blowby.l_per_min.toPrecision(3)))), `${summary} vs ${r.blowby.l_per_min}`);
  await shot('ringdyn-ringpack.png', { fullPage: true });
});

for (const width of [1280, 390]) {
  test(`${width} px: ring pack form: the piston tilt, active areas and ring model reach the scene; each ring's model (name, DOF, why) is shown; a refused model names its field`, { timeout: 180000 }, async () => {
    const skip = await unavailable('ringpack');
    if (skip) return;
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('ringpack');
      // the defaults come from the server's schema
      assert.equal(await page.inputValue('#f-rp-area'), 'fixed');
      assert.equal(await page.inputValue('#f-rp-pressure'), 'linear');
      assert.equal(await page.inputValue('#f-rp-passage'), 'viscous_limited');
      assert.equal(await page.inputValue('#f-rp-model'), 'auto');
      assert.equal(Number(await page.inputValue('#f-rp-tilt')), 0);
      await page.fill('#f-rp-cycles', '2');
      // dynamic active areas (with full flank pressure): auto runs the lift
      // analysis' rigid ring and says why
      await page.selectOption('#f-rp-pressure', 'full');
      await page.selectOption('#f-rp-area', 'dynamic');
      await runAnalysis('Run ringpack analysis');
      await page.waitForSelector('#rp-models');
      let r = (await shownJob()).result;
      assert.equal(r.scene.physics.gas.active_area, 'dynamic');
      assert.equal(r.scene.physics.gas.flank_pressure, 'full');
      assert.equal(r.scene.numerics.model, 'auto');
      const rows = await page.$$eval('#rp-models tbody tr', (trs) => trs.map((tr) => [...tr.children].map((c) => c.textContent)));
      assert.equal(rows.length, r.rings.length);
      r.numerics.model.forEach((m, i) => {
        assert.deepEqual(rows[i].slice(0, 2), [String(i + 1), m.name]);
        assert.ok(rows[i][2].startsWith(String(m.dof)), `DOF ${rows[i][2]} vs ${m.dof}`);
        assert.equal(rows[i][3], m.why);
      });
      assert.equal(rows[0][1], 'rigid');
      assert.match(rows[0][3], /dynamic active areas/);
      if (width === 390) {
        const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
        assert.ok(overflow <= 0, `no sideways scrolling (${overflow} px)`);
        await settled();
        assert.deepEqual(await smallText(), [], 'ring pack models');
      }
      await shot(`ringdyn-ringpack-models-${width}.png`, { fullPage: true });
      // a tilt with the axial ring asked for: the server's 422 names /numerics/model, which is marked
      await page.fill('#f-rp-tilt', '0.1');
      await page.selectOption('#f-rp-model', 'axial');
      await runAnalysis('Run ringpack analysis');
      await page.waitForSelector('#error:not([hidden])');
      const text = await page.textContent('#error');
      assert.match(text, /\/numerics\/model = axial cannot represent a tilted piston/);
      assert.equal(await page.getAttribute('#f-rp-model', 'aria-invalid'), 'true');
      // auto with the tilt: the full ring
      await page.selectOption('#f-rp-model', 'auto');
      await page.selectOption('#f-rp-area', 'fixed');
      await runAnalysis('Run ringpack analysis');
      await page.waitForSelector('#rp-models');
      r = (await shownJob()).result;
      assert.equal(r.scene.engine.piston_tilt_deg, 0.1);
      assert.equal(await page.textContent('#rp-model-1 td'), 'full');
      assert.match(await page.textContent('#rp-model-1 td.why'), /piston tilt/);
    } finally {
      await page.setViewportSize({ width: 1280, height: 800 });
    }
  });
}

// A ring pack has no top-level ring: the page's Ring fields are the top
// ring's on this tab, the diameter every ring's, the closed-ring box off, and
// the blocks of a scene loaded on another tab stay behind (the server refuses
// what an analysis does not read).
for (const width of [1280, 390]) {
  test(`${width} px: ring pack tab: the Ring fields go to the first ring, nothing else is sent, a refused value marks its field`, { timeout: 180000 }, async () => {
    const skip = await unavailable('ringpack');
    if (skip) return;
    await page.setViewportSize({ width, height: 844 });
    try {
      const { examples } = await (await page.request.get(`${BASE}/api/v1/examples`)).json();
      const pack = examples.find((e) => e.scene?.analysis === 'ringpack' && e.scene.rings?.length === 3);
      const lift = examples.find((e) => e.scene?.analysis === 'lift');
      assert.ok(pack && lift, 'a three-ring pack example and a lift example');
      await page.waitForFunction((n) => document.querySelectorAll('#example option').length === n, examples.length + 1);
      // a lift scene first: its groove, physics, output ... must not follow the tab change
      await page.selectOption('#example', { index: examples.indexOf(lift) + 1 });
      await selectTab('ringpack');
      assert.ok(await page.isVisible('#f-ring-pack-note'));
      assert.equal(await page.isDisabled('#f-closed'), true, 'a pack has no closed ring');
      await page.fill('#f-rp-cycles', '2');
      await page.fill('#f-closed-gap', '0.0006');
      await runAnalysis('Run ringpack analysis');
      await page.waitForSelector('#rp-models');
      let r = (await shownJob()).result;
      assert.equal(r.scene.rings.length, 1, 'no pack loaded: one ring');
      assert.equal(r.scene.rings[0].ring.closed_gap, 0.0006, 'the typed closed gap is the ring\'s');
      assert.equal(r.scene.groove, undefined);
      // the three-ring example: the Ring fields show the top ring, edits go there only
      await page.selectOption('#example', { index: examples.indexOf(pack) + 1 });
      assert.equal(Number(await page.inputValue('#f-closed-gap')), pack.scene.rings[0].ring.closed_gap);
      await page.fill('#f-rp-cycles', '2');
      await page.fill('#f-closed-gap', '0.0005');
      await page.fill('#f-diameter', '0.0766');
      await runAnalysis('Run ringpack analysis');
      await page.waitForSelector('#rp-models');
      r = (await shownJob()).result;
      assert.deepEqual(r.scene.rings.map((x) => x.ring.closed_gap),
        [0.0005, ...pack.scene.rings.slice(1).map((x) => x.ring.closed_gap)]);
      assert.deepEqual(r.scene.rings.map((x) => x.ring.diameter), [0.0766, 0.0766, 0.0766], 'one bore');
      // the server's error at /rings/0/ring/closed_gap marks the Closed gap field
      await page.fill('#f-closed-gap', '0.5');
      await runAnalysis('Run ringpack analysis');
      await page.waitForSelector('#error:not([hidden])');
      assert.match(await page.textContent('#error'), /\/rings\/0\/ring\/closed_gap/);
      assert.equal(await page.getAttribute('#f-closed-gap', 'aria-invalid'), 'true');
      if (width === 390) {
        const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
        assert.ok(overflow <= 0, `no sideways scrolling (${overflow} px)`);
      }
      await shot(`ringdyn-ringpack-ring-fields-${width}.png`, { fullPage: true });
      // a sweep filled from this tab varies the top ring's closed gap and tabulates the blow-by
      await page.fill('#f-closed-gap', '0.0005');
      await page.click('#view-sweep');
      await page.click('#sw-fill');
      const spec = JSON.parse(await page.inputValue('#sw-spec'));
      assert.equal(spec.parameters[0].path, '/rings/0/ring/closed_gap');
      assert.equal(spec.base.ring, undefined);
      assert.equal(spec.outputs[0], '/blowby/l_per_min');
      spec.parameters[0].range.count = 2;
      await page.fill('#sw-spec', JSON.stringify(spec));
      await page.click('#sw-run');
      await sweepDone('sw');
      const sw = await newestSweep();
      assert.equal(sw.table.rows.length, 2);
      assert.ok(sw.table.rows.every((r) => r[1] > 0), `blow-by in every row: ${JSON.stringify(sw.table.rows)}`);
      await page.click('#view-result');
      // the other tabs get their shared fields back
      await selectTab('modal');
      assert.equal(await page.isDisabled('#f-closed'), false);
      assert.equal(await page.isVisible('#f-ring-pack-note'), false);
    } finally {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await page.setViewportSize({ width: 1280, height: 800 });
    }
  });
}

// ---- ring pack, lubricated: each ring's oil film ----------------------------

const LUBE_PACK = 'ringpack_lubricated_2400rpm';

// Loads the shipped example `name` from the example list (the page moves to its tab).
async function loadExample(name) {
  const { examples } = await (await page.request.get(`${BASE}/api/v1/examples`)).json();
  const i = examples.findIndex((e) => e.name === name);
  assert.ok(i >= 0, `the server ships ${name}`);
  await page.waitForFunction((n) => document.querySelectorAll('#example option').length === n, examples.length + 1);
  await page.selectOption('#example', { index: i + 1 });
  return examples[i].scene;
}

// A scene POSTed to the server as it is: its status (202 accepted, 422
// refused) and message; an accepted job is cancelled at once.
async function serverTakes(scene) {
  const resp = await page.request.post(`${BASE}/api/v1/jobs?wait=0`, { data: scene });
  const body = await resp.json();
  if (resp.status() === 202) await page.request.delete(`${BASE}/api/v1/jobs/${body.id}`);
  return { status: resp.status(), message: body.error?.message };
}

// A number in a readout cell ("3.408 kPa" -> 3.408).
const cellNumber = (text) => Number(text.trim().split(/\s/)[0]);
const near = (a, b, rel, what) => assert.ok(Math.abs(a - b) <= rel * Math.abs(b), `${what}: ${a} vs ${b}`);

for (const width of [1280, 390]) {
  test(`${width} px: ring pack, lubricated: the shipped example runs and each ring's film, friction split and readout show the result's numbers`, { timeout: 180000 }, async () => {
    const skip = await unavailable('ringpack');
    if (skip) return;
    await page.setViewportSize({ width, height: 844 });
    try {
      const ex = await loadExample(LUBE_PACK);
      await page.waitForSelector('fieldset[data-analysis="ringpack"]:not([hidden])');
      // the form shows the friction model and each ring's face as loaded
      assert.equal(await page.isChecked('#f-rp-friction'), true);
      assert.equal(await page.inputValue('#f-rp-friction-model'), 'lubricated');
      assert.equal(await page.isVisible('#f-rp-friction-coefficient'), false, 'lubricated: no Coulomb coefficient');
      assert.deepEqual(await page.$$eval('#f-rp-faces select', (ss) => ss.map((x) => x.value)), ex.rings.map((r) => r.ring.face.profile));
      assert.equal(Number(await page.inputValue('#f-rp-face-1-crown')), ex.rings[0].ring.face.crown_m);
      assert.equal(Number(await page.inputValue('#f-rp-face-2-taper')), ex.rings[1].ring.face.taper_deg);
      assert.equal(Number(await page.inputValue('#f-rp-face-3-crown')), ex.rings[2].ring.face.crown_m);
      assert.equal(await page.isVisible('#f-rp-face-1-taper'), false, 'a barrel has no taper angle');
      await runAnalysis('Run ringpack analysis', 150000);
      assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
      await page.waitForSelector('#rp-lube');
      const { result } = await shownJob();
      const crank = result.crank_deg;
      assert.equal(result.scene.physics.friction.model, 'lubricated');
      assert.deepEqual(result.scene.rings.map((r) => r.ring.face.profile), ex.rings.map((r) => r.ring.face.profile));
      let fmepSum = 0;
      for (const [k, ring] of result.rings.entries()) {
        const lub = ring.lubrication, id = `#rp-${k + 1}`;
        assert.ok(lub && lub.min_film_m.length === crank.length, `ring ${k + 1} has its lubrication block`);
        // the film and the split: one point per sample
        assert.equal(await page.locator(`${id}-film`).isVisible(), true);
        assert.equal(pathPoints(await page.getAttribute(`${id}-film-line`, 'd')), crank.length);
        assert.equal(await page.locator(`${id}-film-sigma`).count(), 1);
        for (const line of ['hydro', 'asperity', 'total']) {
          assert.equal(pathPoints(await page.getAttribute(`${id}-friction-${line}`, 'd')), crank.length, `${id} ${line}`);
        }
        // the readout: FMEP (kPa), work (J), the thinnest film and where, film_lag, the regimes
        near(cellNumber(await page.textContent(`${id}-fmep`)), lub.fmep_pa[0] / 1e3, 1e-3, `ring ${k + 1} FMEP`);
        assert.match(await page.textContent(`${id}-fmep`), / kPa$/);
        near(cellNumber(await page.textContent(`${id}-work`)), lub.friction_work_j[0], 1e-3, `ring ${k + 1} work`);
        const lo = Math.min(...lub.min_film_m), at = crank[lub.min_film_m.indexOf(lo)];
        assert.equal(await page.textContent(`${id}-thinnest`), `${(lo * 1e6).toFixed(3)} µm at ${Number(at.toFixed(1))}°`);
        near(cellNumber(await page.textContent(`${id}-film-lag`)), lub.film_lag, 5e-3, `ring ${k + 1} film_lag`);
        const share = (r) => `${((lub.regime.filter((x) => x === r).length / lub.regime.length) * 100).toFixed(0)} %`;
        assert.equal(await page.textContent(`${id}-regime`), `hydrodynamic ${share('hydrodynamic')}, mixed ${share('mixed')}, boundary ${share('boundary')}`);
        // the film model's text, whole, in a collapsed details element
        assert.equal(await page.$eval(`${id}-method`, (d) => d.open), false);
        await page.click(`${id}-method summary`);
        assert.equal(await page.isVisible(`${id}-method p`), true);
        assert.equal(await page.textContent(`${id}-method p`), lub.method);
        fmepSum += lub.fmep_pa[0];
      }
      assert.ok((await page.textContent('#rp-lube-summary')).includes(`FMEP of the pack ${Number((fmepSum / 1e3).toPrecision(3))} kPa`));
      await settled();
      const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
      assert.ok(overflow <= 0, `page scrolls sideways by ${overflow}px`);
      assert.deepEqual(await smallText(), [], 'no text below 10 px');
      await shot(`ringdyn-ringpack-lubricated-${width}.png`, { fullPage: true });
    } finally {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await page.setViewportSize({ width: 1280, height: 800 });
    }
  });
}

test('ring pack form: lubricated with changed faces, Coulomb and no friction each build a scene the server accepts, with nothing the model does not read', { timeout: 120000 }, async () => {
  const skip = await unavailable('ringpack');
  if (skip) return;
  const jobs = await interceptJobs(fixtures.ringpackResult());
  const sent = async () => {
    await runAnalysis('Run ringpack analysis');
    assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
    return jobs.sent.at(-1);
  };
  const faces = (scene) => scene.rings.map((r) => r.ring.face);
  try {
    const ex = await loadExample(LUBE_PACK);
    // ring 1 a smaller crown, ring 2 flat instead of taper, ring 3 a taper, a constant viscosity
    await page.fill('#f-rp-face-1-crown', '3e-6');
    await page.selectOption('#f-rp-face-2-profile', 'flat');
    assert.equal(await page.isVisible('#f-rp-face-2-taper'), false);
    await page.fill('#f-rp-face-2-edge', '0.0002');
    await page.selectOption('#f-rp-face-3-profile', 'taper');
    await page.fill('#f-rp-face-3-taper', '1');
    await page.fill('#f-rp-face-3-rq', '3e-7');
    await page.fill('#f-rp-liner-rq', '1.5e-7');
    let scene = await sent();
    assert.deepEqual(faces(scene), [
      { profile: 'barrel', crown_m: 3e-6 },
      { profile: 'flat', edge_radius_m: 0.0002 },
      { profile: 'taper', taper_deg: 1, roughness_rq_m: 3e-7 },
    ]);
    assert.deepEqual(scene.physics.friction, { model: 'lubricated', cavitation: 'reynolds', oil: { temperature_c: 100 } });
    assert.deepEqual(scene.bore, { roughness_rq_m: 1.5e-7 });
    assert.deepEqual(scene.rings.map((r) => r.groove), ex.rings.map((r) => r.groove), 'the rest of the pack as loaded');
    assert.deepEqual(await serverTakes(scene), { status: 202, message: undefined });

    // Coulomb: μ, no face, oil or liner roughness
    await page.selectOption('#f-rp-friction-model', 'coulomb');
    assert.equal(await page.isVisible('#f-rp-lube'), false);
    await page.fill('#f-rp-friction-coefficient', '0.12');
    scene = await sent();
    assert.deepEqual(scene.physics.friction, { model: 'coulomb', coefficient: 0.12 });
    assert.deepEqual(faces(scene), [undefined, undefined, undefined]);
    assert.equal(scene.bore, undefined);
    assert.deepEqual(await serverTakes(scene), { status: 202, message: undefined });

    // no friction
    await page.uncheck('#f-rp-friction');
    scene = await sent();
    assert.equal(scene.physics.friction, undefined);
    assert.deepEqual(faces(scene), [undefined, undefined, undefined]);
    assert.deepEqual(await serverTakes(scene), { status: 202, message: undefined });

    // without a loaded pack: one ring, its face at the schema's defaults
    await page.getByRole('button', { name: 'Reset to defaults' }).click();
    await selectTab('ringpack');
    assert.equal(await page.locator('#f-rp-faces .ring-face').count(), 1);
    await page.check('#f-rp-friction');
    await page.selectOption('#f-rp-friction-model', 'lubricated');
    await page.fill('#f-rp-cycles', '2');
    scene = await sent();
    assert.deepEqual(faces(scene), [{ profile: 'barrel', crown_m: 5e-6 }]);
    assert.deepEqual(await serverTakes(scene), { status: 202, message: undefined });
  } finally {
    await jobs.stop();
    await page.getByRole('button', { name: 'Reset to defaults' }).click();
  }
});

// ---- the oil supply: physics.friction.supply, starved by the film on the liner

// Loads `scene` as a scene file; waits until `ready` (a page function) holds.
async function loadSceneFile(scene, ready, arg) {
  await page.setInputFiles('#load-scene-file', { name: 'scene.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(scene)) });
  await page.waitForFunction(ready, arg);
}

// The scene the form builds for `analysis`, as the page POSTs it (answered
// by interceptJobs), with no error shown.
async function formScene(jobs, analysis) {
  await runAnalysis(`Run ${analysis} analysis`);
  assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
  return jobs.sent.at(-1);
}

// The server accepts `scene`: 202 (queued, then cancelled by serverTakes)
// or 200 (a quarter-cycle lift can finish within ?wait=0).
async function takes(scene) {
  const r = await serverTakes(scene);
  assert.ok(r.status === 202 || r.status === 200, `the server refused the scene: ${r.status} ${r.message}`);
}

// A field that fits the viewport and shows its µm hint.
async function fieldFits(id) {
  const box = await page.locator(id).boundingBox();
  const width = await page.evaluate(() => window.innerWidth);
  assert.ok(box && box.x >= 0 && box.x + box.width <= width, `${id} within the ${width} px viewport: ${JSON.stringify(box)}`);
  const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
  assert.ok(overflow <= 0, `page scrolls sideways by ${overflow}px`);
}

for (const width of [1280, 390]) {
  test(`${width} px: lift, lubricated: the oil film on the liner is sent as physics.friction.supply {film_m}, the server runs it and the readout says the inlet is starved; its echo loads back; Coulomb sends no supply`, { skip: SKIP.lift, timeout: 180000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('lift');
      await page.fill('#f-lf-speed', '2400');
      await page.fill('#f-lf-cycles', '0.25');
      await page.selectOption('#f-lf-model', 'rigid');
      await page.uncheck('#f-lf-error-estimate');
      await page.check('#f-lf-friction');
      assert.equal(await page.isVisible('#f-lf-supply-film'), false, 'coulomb: no oil film field');
      await page.selectOption('#f-lf-friction-model', 'lubricated');
      assert.equal(await page.isVisible('#f-lf-supply-film'), true);
      assert.equal(await page.inputValue('#f-lf-supply-film'), '', 'empty by default: flooded');
      assert.equal(await page.getAttribute('#f-lf-supply-film', 'placeholder'), 'flooded');
      const jobs = await interceptJobs(fixtures.liftResult());
      let scene;
      try {
        scene = await formScene(jobs, 'lift');
        assert.equal(scene.physics.friction.supply, undefined, 'empty: no supply sent (the server floods the face)');
        await page.fill('#f-lf-supply-film', '1e-6');
        assert.equal(await page.textContent('#f-lf-supply-film-hint'), '= 1 µm');
        await fieldFits('#f-lf-supply-film');
        scene = await formScene(jobs, 'lift');
        assert.deepEqual(scene.physics.friction.supply, { film_m: 1e-6 });
        assert.equal(scene.physics.friction.model, 'lubricated');
        await takes(scene);
        // Coulomb: no supply (the server would refuse it with that model).
        await page.selectOption('#f-lf-friction-model', 'coulomb');
        const coulomb = await formScene(jobs, 'lift');
        assert.equal(coulomb.physics.friction.model, 'coulomb');
        assert.equal(coulomb.physics.friction.supply, undefined);
        await takes(coulomb);
        const refused = structuredClone(coulomb);
        refused.physics.friction.supply = { film_m: 1e-6 };
        assert.equal((await serverTakes(refused)).status, 422, 'what the page must not send');
        await page.selectOption('#f-lf-friction-model', 'lubricated');
        assert.equal(await page.inputValue('#f-lf-supply-film'), '1e-6', 'the field keeps its value while hidden');
      } finally {
        await jobs.stop();
      }

      // Run against the server: the readout names the starved inlet.
      await runAnalysis('Run lift analysis', 150000);
      assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
      const job = await shownJob();
      assert.deepEqual(job.result.scene.physics.friction.supply, { film_m: 1e-6 }, 'the echo');
      assert.ok(job.result.lubrication, 'a lubrication block');
      assert.equal(await page.textContent('#lf-supply'), 'starved inlet: 1 µm of oil on the liner');
      assert.equal(await page.isVisible('#lf-supply'), true);
      await settled();
      const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
      assert.ok(overflow <= 0, `page scrolls sideways by ${overflow}px`);
      await shot(`ringdyn-lift-supply-${width}.png`, { fullPage: true });

      // The job reopened from its address: the echo fills the form and is sent as it was.
      await page.goto(`${BASE}/?job=${encodeURIComponent(job.id)}`);
      await page.waitForFunction(() => document.getElementById('f-lf-supply-film').value === '1e-6' &&
        document.getElementById('f-lf-friction-model').value === 'lubricated');
      assert.equal(await page.textContent('#f-lf-supply-film-hint'), '= 1 µm');
      const again = await interceptJobs(fixtures.liftResult());
      try {
        scene = await formScene(again, 'lift');
        assert.deepEqual(scene.physics.friction.supply, { film_m: 1e-6 });
        await takes(scene);
        // An echo of a flooded run ("supply": "flooded", a string): the field
        // empty, the word sent back as it was; a film typed in replaces it.
        const flooded = structuredClone(job.result.scene);
        flooded.physics.friction.supply = 'flooded';
        await loadSceneFile(flooded, () => document.getElementById('f-lf-supply-film').value === '');
        assert.equal(await page.inputValue('#f-lf-friction-model'), 'lubricated');
        assert.equal(await page.textContent('#f-lf-supply-film-hint'), '');
        scene = await formScene(again, 'lift');
        assert.equal(scene.physics.friction.supply, 'flooded');
        await takes(scene);
        await page.fill('#f-lf-supply-film', '2e-6');
        scene = await formScene(again, 'lift');
        assert.deepEqual(scene.physics.friction.supply, { film_m: 2e-6 });
        // Another model drops the loaded word too.
        await loadSceneFile(flooded, () => document.getElementById('f-lf-supply-film').value === '');
        await page.selectOption('#f-lf-friction-model', 'stribeck');
        scene = await formScene(again, 'lift');
        assert.equal(scene.physics.friction.supply, undefined);
        await takes(scene);
      } finally {
        await again.stop();
      }
    } finally {
      await page.goto(`${BASE}/`);
      await page.waitForSelector('#tab-modal[aria-selected="true"]');
      await page.setViewportSize({ width: 1280, height: 800 });
    }
  });

  test(`${width} px: ring pack, lubricated: the oil film on the liner is sent as physics.friction.supply {film_m} and the server takes it; its echo loads back; Coulomb sends no supply`, { timeout: 120000 }, async () => {
    const skip = await unavailable('ringpack');
    if (skip) return;
    await page.setViewportSize({ width, height: 844 });
    const jobs = await interceptJobs(fixtures.ringpackResult());
    try {
      const ex = await loadExample(LUBE_PACK);
      await page.waitForSelector('fieldset[data-analysis="ringpack"]:not([hidden])');
      assert.equal(await page.inputValue('#f-rp-friction-model'), 'lubricated');
      assert.equal(await page.isVisible('#f-rp-supply-film'), true);
      assert.equal(await page.inputValue('#f-rp-supply-film'), '', 'the example is flooded');
      let scene = await formScene(jobs, 'ringpack');
      assert.equal(scene.physics.friction.supply, ex.physics.friction.supply, 'as the example has it');
      await page.fill('#f-rp-supply-film', '1e-6');
      assert.equal(await page.textContent('#f-rp-supply-film-hint'), '= 1 µm');
      await fieldFits('#f-rp-supply-film');
      scene = await formScene(jobs, 'ringpack');
      assert.deepEqual(scene.physics.friction.supply, { film_m: 1e-6 });
      await takes(scene);
      await page.locator('#f-rp-lube').screenshot({ path: path.join(SHOT_DIR, `ringdyn-ringpack-supply-form-${width}.png`) });

      // The echo of each kind loads back: {film_m} into the field, "flooded" as an empty field.
      const echo = structuredClone(scene);
      echo.physics.friction.supply = { film_m: 3e-6 };
      await loadSceneFile(echo, () => document.getElementById('f-rp-supply-film').value === '0.000003' ||
        document.getElementById('f-rp-supply-film').value === '3e-6');
      scene = await formScene(jobs, 'ringpack');
      assert.deepEqual(scene.physics.friction.supply, { film_m: 3e-6 });
      echo.physics.friction.supply = 'flooded';
      await loadSceneFile(echo, () => document.getElementById('f-rp-supply-film').value === '');
      assert.equal(await page.inputValue('#f-rp-friction-model'), 'lubricated');
      scene = await formScene(jobs, 'ringpack');
      assert.equal(scene.physics.friction.supply, 'flooded');
      await takes(scene);

      // Coulomb: no supply, typed or loaded.
      await page.fill('#f-rp-supply-film', '1e-6');
      await page.selectOption('#f-rp-friction-model', 'coulomb');
      assert.equal(await page.isVisible('#f-rp-supply-film'), false);
      scene = await formScene(jobs, 'ringpack');
      assert.equal(scene.physics.friction.model, 'coulomb');
      assert.equal(scene.physics.friction.supply, undefined);
      await takes(scene);
    } finally {
      await jobs.stop();
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await page.setViewportSize({ width: 1280, height: 800 });
    }
  });
}

test('lube readouts: a starved supply in the scene is named next to the film facts (lift and each ring of a pack); flooded says nothing', { timeout: 60000 }, async () => {
  const lub = (n) => ({ min_film_m: Array.from({ length: n }, () => 1e-6), composite_roughness_m: 2.8e-7 });
  const lf = fixtures.liftResult();
  lf.scene.physics.friction = { model: 'lubricated', supply: { film_m: 2.5e-6 } };
  lf.lubrication = lub(lf.crank_deg.length);
  const rp = fixtures.ringpackResult();
  rp.scene.physics = { friction: { model: 'lubricated', supply: { film_m: 1e-6 } } };
  for (const ring of rp.rings) ring.lubrication = lub(rp.crank_deg.length);
  const drawn = await page.evaluate(async ({ lf, rp }) => {
    const out = {};
    for (const [id, result] of [['lift', lf], ['ringpack', rp]]) {
      const mod = await import(`/static/${id}.js`);
      const box = document.createElement('div');
      document.body.append(box);
      const cells = () => [...box.querySelectorAll('[id$="-supply"]')].map((td) => [td.id, td.textContent, td.closest('tr').querySelector('th').textContent]);
      try {
        mod[id].render(result, null, box);
        out[id] = cells();
        result.scene.physics.friction.supply = 'flooded';
        mod[id].render(result, null, box);
        out[`${id} flooded`] = cells();
      } finally {
        box.remove();
      }
    }
    return out;
  }, { lf, rp });
  assert.deepEqual(drawn.lift, [['lf-supply', 'starved inlet: 2.5 µm of oil on the liner', 'Oil supply']]);
  assert.deepEqual(drawn.ringpack, [1, 2, 3].map((n) => [`rp-${n}-supply`, 'starved inlet: 1 µm of oil on the liner', 'Oil supply']));
  assert.deepEqual(drawn['lift flooded'], []);
  assert.deepEqual(drawn['ringpack flooded'], []);
  assert.deepEqual(pageErrors, []);
});

// ---- the cavitation condition: physics.friction.cavitation, Reynolds or JFO

// The cavitation select of tab `pre` (lf, rp): shown, its two choices, its note.
async function cavitationSelect(pre) {
  const id = `#f-${pre}-cavitation`;
  assert.equal(await page.isVisible(id), true);
  assert.deepEqual(await page.$$eval(`${id} option`, (os) => os.map((o) => [o.value, o.textContent])),
    [['reynolds', 'Reynolds (Swift–Stieber)'], ['jfo', 'JFO (mass-conserving)']]);
  assert.equal(await page.textContent(`label[for="f-${pre}-cavitation"]`), 'Cavitation');
  assert.ok((await page.getAttribute(id, 'aria-describedby')).split(/\s+/).includes(`f-${pre}-cavitation-note`));
  assert.equal(await page.isVisible(`#f-${pre}-cavitation-note`), true);
  assert.match(await page.textContent(`#f-${pre}-cavitation-note`), /Reynolds: .*JFO: /);
}

for (const width of [1280, 390]) {
  test(`${width} px: lift, lubricated: the cavitation select sends physics.friction.cavitation "jfo", the server runs it and the readout says JFO; its echo loads back; Coulomb sends no cavitation`, { skip: SKIP.lift, timeout: 180000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('lift');
      await page.fill('#f-lf-speed', '2400');
      await page.fill('#f-lf-cycles', '0.25');
      await page.selectOption('#f-lf-model', 'rigid');
      await page.uncheck('#f-lf-error-estimate');
      await page.check('#f-lf-friction');
      assert.equal(await page.isVisible('#f-lf-cavitation'), false, 'coulomb: no cavitation select');
      await page.selectOption('#f-lf-friction-model', 'lubricated');
      await cavitationSelect('lf');
      assert.equal(await page.inputValue('#f-lf-cavitation'), 'reynolds', 'the schema\'s default');
      const jobs = await interceptJobs(fixtures.liftResult());
      let scene;
      try {
        scene = await formScene(jobs, 'lift');
        assert.equal(scene.physics.friction.cavitation, 'reynolds', 'the default, sent as every choice is');
        await takes(scene);
        await page.selectOption('#f-lf-cavitation', 'jfo');
        await fieldFits('#f-lf-cavitation');
        scene = await formScene(jobs, 'lift');
        assert.equal(scene.physics.friction.cavitation, 'jfo');
        assert.equal(scene.physics.friction.model, 'lubricated');
        await takes(scene);
        // Coulomb: no cavitation (the server would refuse "jfo" with that model).
        await page.selectOption('#f-lf-friction-model', 'coulomb');
        assert.equal(await page.isVisible('#f-lf-cavitation'), false);
        const coulomb = await formScene(jobs, 'lift');
        assert.equal(coulomb.physics.friction.model, 'coulomb');
        assert.equal(coulomb.physics.friction.cavitation, undefined);
        await takes(coulomb);
        const refused = structuredClone(coulomb);
        refused.physics.friction.cavitation = 'jfo';
        const r = await serverTakes(refused);
        assert.equal(r.status, 422, 'what the page must not send');
        assert.match(r.message, /\/physics\/friction\/cavitation/);
        await page.selectOption('#f-lf-friction-model', 'lubricated');
        assert.equal(await page.inputValue('#f-lf-cavitation'), 'jfo', 'the select keeps its choice while hidden');
      } finally {
        await jobs.stop();
      }

      // Run against the server: the readout names the JFO condition.
      await runAnalysis('Run lift analysis', 150000);
      assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
      const job = await shownJob();
      assert.equal(job.result.scene.physics.friction.cavitation, 'jfo', 'the echo');
      assert.ok(job.result.lubrication, 'a lubrication block');
      assert.equal(await page.textContent('#lf-cavitation'), 'JFO (mass-conserving)');
      assert.equal(await page.$eval('#lf-cavitation', (td) => td.closest('tr').querySelector('th').textContent), 'Cavitation');
      assert.equal(await page.isVisible('#lf-cavitation'), true);
      await settled();
      const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
      assert.ok(overflow <= 0, `page scrolls sideways by ${overflow}px`);
      await shot(`ringdyn-lift-cavitation-${width}.png`, { fullPage: true });

      // The job reopened from its address: the echo sets the select and is sent as it was.
      await page.goto(`${BASE}/?job=${encodeURIComponent(job.id)}`);
      await page.waitForFunction(() => document.getElementById('f-lf-cavitation').value === 'jfo' &&
        document.getElementById('f-lf-friction-model').value === 'lubricated');
      assert.equal(await page.isVisible('#f-lf-cavitation'), true);
      const again = await interceptJobs(fixtures.liftResult());
      try {
        scene = await formScene(again, 'lift');
        assert.equal(scene.physics.friction.cavitation, 'jfo');
        await takes(scene);
        // An echo of a Reynolds run sets it back; a scene without the field: the default.
        const reynolds = structuredClone(job.result.scene);
        reynolds.physics.friction.cavitation = 'reynolds';
        await loadSceneFile(reynolds, () => document.getElementById('f-lf-cavitation').value === 'reynolds');
        scene = await formScene(again, 'lift');
        assert.equal(scene.physics.friction.cavitation, 'reynolds');
        await loadSceneFile(job.result.scene, () => document.getElementById('f-lf-cavitation').value === 'jfo');
        const bare = structuredClone(job.result.scene);
        delete bare.physics.friction.cavitation;
        await loadSceneFile(bare, () => document.getElementById('f-lf-cavitation').value === 'reynolds');
        // Another model drops a loaded "jfo".
        await loadSceneFile(job.result.scene, () => document.getElementById('f-lf-cavitation').value === 'jfo');
        await page.selectOption('#f-lf-friction-model', 'stribeck');
        scene = await formScene(again, 'lift');
        assert.equal(scene.physics.friction.model, 'stribeck');
        assert.equal(scene.physics.friction.cavitation, undefined);
        await takes(scene);
      } finally {
        await again.stop();
      }
    } finally {
      await page.goto(`${BASE}/`);
      await page.waitForSelector('#tab-modal[aria-selected="true"]');
      await page.setViewportSize({ width: 1280, height: 800 });
    }
  });

  test(`${width} px: ring pack, lubricated: the cavitation select sends physics.friction.cavitation "jfo" and the server takes it; its echo loads back; Coulomb sends no cavitation`, { timeout: 120000 }, async () => {
    const skip = await unavailable('ringpack');
    if (skip) return;
    await page.setViewportSize({ width, height: 844 });
    const jobs = await interceptJobs(fixtures.ringpackResult());
    try {
      const ex = await loadExample(LUBE_PACK);
      await page.waitForSelector('fieldset[data-analysis="ringpack"]:not([hidden])');
      assert.equal(await page.inputValue('#f-rp-friction-model'), 'lubricated');
      assert.equal(ex.physics.friction.cavitation, undefined, 'the example leaves it to the default');
      await cavitationSelect('rp');
      assert.equal(await page.inputValue('#f-rp-cavitation'), 'reynolds');
      let scene = await formScene(jobs, 'ringpack');
      assert.equal(scene.physics.friction.cavitation, 'reynolds');
      await page.selectOption('#f-rp-cavitation', 'jfo');
      await fieldFits('#f-rp-cavitation');
      scene = await formScene(jobs, 'ringpack');
      assert.equal(scene.physics.friction.cavitation, 'jfo');
      await takes(scene);
      await page.locator('#f-rp-lube').screenshot({ path: path.join(SHOT_DIR, `ringdyn-ringpack-cavitation-form-${width}.png`) });

      // The echo of each choice loads back into the select.
      const echo = structuredClone(scene);
      echo.physics.friction.cavitation = 'reynolds';
      await loadSceneFile(echo, () => document.getElementById('f-rp-cavitation').value === 'reynolds');
      scene = await formScene(jobs, 'ringpack');
      assert.equal(scene.physics.friction.cavitation, 'reynolds');
      echo.physics.friction.cavitation = 'jfo';
      await loadSceneFile(echo, () => document.getElementById('f-rp-cavitation').value === 'jfo');
      scene = await formScene(jobs, 'ringpack');
      assert.equal(scene.physics.friction.cavitation, 'jfo');

      // Coulomb: no cavitation, chosen or loaded.
      await page.selectOption('#f-rp-friction-model', 'coulomb');
      assert.equal(await page.isVisible('#f-rp-cavitation'), false);
      scene = await formScene(jobs, 'ringpack');
      assert.equal(scene.physics.friction.model, 'coulomb');
      assert.equal(scene.physics.friction.cavitation, undefined);
      await takes(scene);
    } finally {
      await jobs.stop();
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await page.setViewportSize({ width: 1280, height: 800 });
    }
  });
}

test('lube readouts: the scene\'s cavitation condition is named next to the film facts (lift and each ring of a pack): JFO for "jfo", Reynolds otherwise', { timeout: 60000 }, async () => {
  const lub = (n) => ({ min_film_m: Array.from({ length: n }, () => 1e-6), composite_roughness_m: 2.8e-7 });
  const lf = fixtures.liftResult();
  lf.scene.physics.friction = { model: 'lubricated', cavitation: 'jfo' };
  lf.lubrication = lub(lf.crank_deg.length);
  const rp = fixtures.ringpackResult();
  rp.scene.physics = { friction: { model: 'lubricated', cavitation: 'jfo' } };
  for (const ring of rp.rings) ring.lubrication = lub(rp.crank_deg.length);
  const drawn = await page.evaluate(async ({ lf, rp }) => {
    const out = {};
    for (const [id, result] of [['lift', lf], ['ringpack', rp]]) {
      const mod = await import(`/static/${id}.js`);
      const box = document.createElement('div');
      document.body.append(box);
      const cells = () => [...box.querySelectorAll('[id$="-cavitation"]')].map((td) => [td.id, td.textContent, td.closest('tr').querySelector('th').textContent]);
      try {
        mod[id].render(result, null, box);
        out[id] = cells();
        result.scene.physics.friction.cavitation = 'reynolds';
        mod[id].render(result, null, box);
        out[`${id} reynolds`] = cells();
        delete result.scene.physics.friction.cavitation;
        mod[id].render(result, null, box);
        out[`${id} absent`] = cells();
      } finally {
        box.remove();
      }
    }
    return out;
  }, { lf, rp });
  assert.deepEqual(drawn.lift, [['lf-cavitation', 'JFO (mass-conserving)', 'Cavitation']]);
  assert.deepEqual(drawn.ringpack, [1, 2, 3].map((n) => [`rp-${n}-cavitation`, 'JFO (mass-conserving)', 'Cavitation']));
  for (const k of ['reynolds', 'absent']) {
    assert.deepEqual(drawn[`lift ${k}`], [['lf-cavitation', 'Reynolds', 'Cavitation']], k);
    assert.deepEqual(drawn[`ringpack ${k}`], [1, 2, 3].map((n) => [`rp-${n}-cavitation`, 'Reynolds', 'Cavitation']), k);
  }
  assert.deepEqual(pageErrors, []);
});

// ---- the bore map: bore.layers on the Contact and Lift tabs ------------------

// Two layers down 100 mm: order 2 growing from 2 to 10 µm, order 4 below.
const MAP = [
  { z: 0, distortion: [{ order: 2, amplitude: 2e-6, phase_deg: 0 }] },
  { z: 0.1, distortion: [{ order: 2, amplitude: 10e-6, phase_deg: 0 }, { order: 4, amplitude: 3e-6, phase_deg: 20 }] },
];

// Enters `layers` into the map of tab `pre` (ct, lf) with its buttons.
async function enterMap(pre, layers) {
  for (const [i, l] of layers.entries()) {
    assert.equal(await page.textContent(`#f-${pre}-layers-add`), 'Add a layer');
    await page.click(`#f-${pre}-layers-add`);
    assert.equal(await page.evaluate(() => document.activeElement.id), `f-${pre}-layers-${i}-z`, 'focus on the new layer');
    await page.fill(`#f-${pre}-layers-${i}-z`, String(l.z));
    if (l.diameter) await page.fill(`#f-${pre}-layers-${i}-diameter`, String(l.diameter));
    for (const [j, d] of (l.distortion || []).entries()) {
      await page.getByRole('button', { name: `Add an order to layer ${i + 1}`, exact: true }).click();
      await page.fill(`#f-${pre}-layers-${i}-distortion-${j}-order`, String(d.order));
      await page.fill(`#f-${pre}-layers-${i}-distortion-${j}-amplitude`, String(d.amplitude));
      await page.fill(`#f-${pre}-layers-${i}-distortion-${j}-phase_deg`, String(d.phase_deg ?? 0));
    }
  }
}

// Removes every layer of the map of tab `pre` with its buttons.
async function emptyMap(pre) {
  while (await page.locator(`#f-${pre}-layers .layer`).count()) {
    await page.getByRole('button', { name: 'Remove layer 1', exact: true }).click();
  }
  assert.equal(await page.evaluate(() => document.activeElement.id), `f-${pre}-layers-add`, 'focus back on the add button');
  await settled(); // the drawing follows at the next frame
}

// What a bore map drawing (svg#id) shows: its label, the depth range and
// plot box, the layer marks, the travel band and the height line.
async function mapDrawing(id) {
  await settled();
  return page.$eval(`#${id}`, (s) => {
    const [left, top, width, height] = s.dataset.box.split(' ').map(Number);
    const travel = s.querySelector(`#${s.id}-travel`);
    const line = s.querySelector(`line#${s.id}-height`);
    const r = s.getBoundingClientRect();
    return {
      label: s.getAttribute('aria-label'), role: s.getAttribute('role'), visible: r.width > 0 && r.height > 0,
      zmin: Number(s.dataset.zmin), zmax: Number(s.dataset.zmax), box: { left, top, width, height },
      layers: [...s.querySelectorAll(`#${s.id}-layers .bm-layer`)].map((p) => Number(p.dataset.z)),
      travel: travel && { y: Number(travel.getAttribute('y')), h: Number(travel.getAttribute('height')), z0: Number(travel.dataset.z0), z1: Number(travel.dataset.z1) },
      height: line && { y: Number(line.getAttribute('y1')), z: Number(line.dataset.z) },
      image: Boolean(s.querySelector('image.bm-image')?.getAttribute('href')?.startsWith('data:image/png')),
      bar: s.querySelectorAll('.bm-bar-ticks text').length,
    };
  });
}

// The y of depth z (m) in a drawing from mapDrawing.
const mapY = (d, z) => d.box.top + ((z - d.zmin) / (d.zmax - d.zmin)) * d.box.height;

for (const width of [1280, 390]) {
  test(`${width} px: lift, bore map: two layers are sent as bore.layers with bore.ring_z_tdc_m (no /bore/distortion), drawn with the ring's travel; the server runs it; its echo loads back; a map short of the stroke shows the server's 422 at the field; an empty map sends neither`, { skip: SKIP.lift, timeout: 180000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('lift');
      await page.fill('#f-segments', '12');
      await page.fill('#f-lf-speed', '1000');
      await page.fill('#f-lf-cycles', '0.05');
      await page.uncheck('#f-lf-error-estimate');
      await page.check('#f-lf-friction');
      await page.selectOption('#f-lf-friction-model', 'coulomb');
      // No layers: no depth field, no drawing.
      assert.equal(await page.isVisible('#f-lf-ring-z'), false);
      assert.equal(await page.isVisible('#f-lf-map'), false);
      assert.equal(await page.isVisible('fieldset:has(#f-lf-layers) > legend:text-is("Bore map (layers down the bore)")'), true);
      const jobs = await interceptJobs(fixtures.liftResult());
      let scene;
      try {
        scene = await formScene(jobs, 'lift');
        assert.equal(scene.bore, undefined, 'no map: no bore block');

        await enterMap('lf', MAP);
        assert.match(await page.textContent('label[for="f-lf-layers-1-z"]'), /^Layer 2: Depth z \(m\)$/);
        assert.equal(await page.textContent('#f-lf-layers-1-z-hint'), '= 100 mm');
        assert.equal(await page.textContent('#f-lf-layers > .list-actions [data-list-count]'), '2 of 50 layers');
        assert.equal(await page.textContent('#f-lf-layers-1-distortion [data-list-count]'), '2 of 16 orders');
        assert.equal(await page.isVisible('#f-lf-ring-z'), true, 'a map asks for the ring depth');
        // The ring depth is required with a map: empty, the page says so.
        const before = jobs.sent.length;
        await runAnalysis('Run lift analysis');
        assert.equal(jobs.sent.length, before, 'nothing sent');
        assert.match(await page.textContent('#error'), /Ring depth at TDC \(m\): must be a number/);
        assert.equal(await page.getAttribute('#f-lf-ring-z', 'aria-invalid'), 'true');
        await page.fill('#f-lf-ring-z', '0.005');
        assert.equal(await page.textContent('#f-lf-ring-z-hint'), '= 5 mm');
        for (const id of ['#f-lf-ring-z', '#f-lf-layers-1-z', '#f-lf-layers-1-diameter', '#f-lf-layers-1-distortion-1-amplitude', '.layer[aria-labelledby="f-lf-layers-1-head"] .layer-head .remove', '#f-lf-layers-add', '#f-lf-map-plot']) await fieldFits(id);
        scene = await formScene(jobs, 'lift');
        assert.deepEqual(scene.bore, { layers: MAP, ring_z_tdc_m: 0.005 });
        assert.deepEqual(scene.physics.friction.model, 'coulomb');
        await takes(scene);

        // The drawing: both layers, the depth range, the travel band where the ring runs.
        let d = await mapDrawing('f-lf-map-plot');
        assert.ok(d.visible && d.image && d.role === 'img', 'drawn');
        assert.match(d.label, /^Bore map: the radius's departure from the first layer's mean radius, -[\d.]+ to \+[\d.]+ µm, over the angle from the gap \(0 to 360°\) and the depth z 0 to 100 mm \(2 layers\); the ring's travel 5 to 91\.9 mm \(TDC to BDC\)\.$/);
        const limit = await page.$eval('#f-lf-map-plot', (s) => Number(s.dataset.limitUm));
        assert.ok(limit > 10 && limit <= 13, `largest departure ${limit} µm: order 2 at 10 µm plus order 4 at 3 µm at 100 mm`);
        assert.deepEqual(d.layers, [0, 0.1]);
        assert.ok(d.bar >= 3, 'a colour scale with ticks');
        const crank = Number(await page.inputValue('#f-lf-crank'));
        assert.equal(d.travel.z0, 0.005);
        assert.ok(Math.abs(d.travel.z1 - (0.005 + 2 * crank)) < 1e-12);
        assert.ok(Math.abs(d.travel.y - mapY(d, 0.005)) < 0.01, `TDC at y ${d.travel.y} vs ${mapY(d, 0.005)}`);
        assert.ok(Math.abs(d.travel.y + d.travel.h - mapY(d, 0.005 + 2 * crank)) < 0.01, 'BDC');
        assert.ok(d.travel.y > d.box.top && d.travel.y < d.box.top + d.box.height / 10, 'TDC just below the top layer');
        // It follows the form: a deeper ring moves the band.
        await page.fill('#f-lf-ring-z', '0.01');
        d = await mapDrawing('f-lf-map-plot');
        assert.equal(d.travel.z0, 0.01);
        assert.ok(Math.abs(d.travel.y - mapY(d, 0.01)) < 0.01);
        assert.match(d.label, /travel 10 to 96\.9 mm/);
        await page.fill('#f-lf-ring-z', '0.005');
        if (width === 390) assert.deepEqual(await smallText(), [], 'the map and its drawing are readable at 390 px');
        await page.locator('fieldset[data-analysis="lift"]:has(#f-lf-layers)').screenshot({ path: path.join(SHOT_DIR, `ringdyn-lift-map-form-${width}.png`) });

        // A loaded scene's single distortion is not sent with a map.
        const loaded = structuredClone(scene);
        loaded.bore = { distortion: [{ order: 2, amplitude: 4e-6 }] };
        await loadSceneFile(loaded, () => document.querySelectorAll('#f-lf-layers .layer').length === 0);
        assert.equal(await page.isVisible('#f-lf-bore-note'), true);
        scene = await formScene(jobs, 'lift');
        assert.deepEqual(scene.bore, { distortion: [{ order: 2, amplitude: 4e-6 }] }, 'no map: the loaded distortion goes');
        await enterMap('lf', MAP);
        await page.fill('#f-lf-ring-z', '0.005');
        assert.equal(await page.isVisible('#f-lf-bore-note'), false);
        scene = await formScene(jobs, 'lift');
        assert.deepEqual(scene.bore, { layers: MAP, ring_z_tdc_m: 0.005 }, 'with a map it does not');
      } finally {
        await jobs.stop();
      }

      // Run against the server: the result draws the map with the travel.
      await runAnalysis('Run lift analysis', 150000);
      assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
      const job = await shownJob();
      assert.equal(job.result.scene.bore.ring_z_tdc_m, 0.005, 'the echo');
      assert.deepEqual(job.result.scene.bore.layers.map((l) => l.z), [0, 0.1]);
      assert.ok(job.result.crank_deg.length > 1, 'lift samples');
      assert.equal(await page.locator('#lf-plots svg.chart').first().isVisible(), true);
      const r = await mapDrawing('lf-map');
      assert.ok(r.visible && r.image);
      assert.deepEqual(r.layers, [0, 0.1]);
      assert.match(r.label, /the depth z 0 to 100 mm \(2 layers\); the ring's travel 5 to 91\.9 mm/);
      assert.ok(Math.abs(r.travel.y - mapY(r, 0.005)) < 0.01);
      await settled();
      const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
      assert.ok(overflow <= 0, `page scrolls sideways by ${overflow}px`);
      await shot(`ringdyn-lift-map-${width}.png`, { fullPage: true });

      // The job reopened from its address: the echo fills the map and is sent as it was.
      await page.goto(`${BASE}/?job=${encodeURIComponent(job.id)}`);
      await page.waitForFunction(() => document.getElementById('f-lf-layers-1-distortion-1-order')?.value === '4' &&
        document.getElementById('f-lf-ring-z').value === '0.005');
      assert.equal(await page.getAttribute('#tab-lift', 'aria-selected'), 'true');
      assert.equal(await page.inputValue('#f-lf-layers-1-z'), '0.1');
      assert.equal(await page.inputValue('#f-lf-layers-1-distortion-1-phase_deg'), '20');
      assert.equal(await page.inputValue('#f-lf-layers-0-diameter'), String(job.result.scene.bore.layers[0].diameter), 'the diameter used');
      await page.waitForSelector('#f-lf-map-plot', { state: 'visible' }); // drawn from the echo
      const again = await interceptJobs(fixtures.liftResult());
      try {
        scene = await formScene(again, 'lift');
        assert.deepEqual(scene.bore.layers, job.result.scene.bore.layers);
        assert.equal(scene.bore.ring_z_tdc_m, 0.005);
        await takes(scene);
        // Emptied, the map sends neither its layers nor the ring depth.
        await emptyMap('lf');
        assert.equal(await page.isVisible('#f-lf-ring-z'), false);
        assert.equal(await page.isVisible('#f-lf-map'), false);
        scene = await formScene(again, 'lift');
        assert.equal(scene.bore.layers, undefined);
        assert.equal(scene.bore.ring_z_tdc_m, undefined);
        await takes(scene);
      } finally {
        await again.stop();
      }

      // A map that does not cover the ring's travel: the server's 422 at the map.
      await enterMap('lf', [{ z: 0 }, { z: 0.05 }]);
      await page.fill('#f-lf-ring-z', '0.005');
      const short = await mapDrawing('f-lf-map-plot');
      assert.match(short.label, /, beyond the map\.$/);
      assert.match(await page.textContent('#f-lf-map-msg'), /leaves the map/);
      await runAnalysis('Run lift analysis');
      const text = await page.textContent('#error');
      assert.match(text, /^Bore map \(layers down the bore\): /, `named by the map: ${text}`);
      assert.match(text, /\/bore\/layers covers 0 to 0\.05 m: the map must cover the ring's whole travel/);
      assert.equal(await page.getAttribute('#f-lf-layers-1-z', 'aria-invalid'), 'true');
      assert.equal(await page.getAttribute('#f-lf-ring-z', 'aria-invalid'), null);
      assert.equal(await page.isVisible('#f-lf-layers-1-z'), true);
      await shot(`ringdyn-lift-map-refused-${width}.png`);
      await page.fill('#f-lf-layers-1-z', '0.1');
      assert.equal(await page.getAttribute('#f-lf-layers-1-z', 'aria-invalid'), null, 'editing clears the mark');
    } finally {
      await page.goto(`${BASE}/`);
      await page.waitForSelector('#tab-modal[aria-selected="true"]');
      await page.setViewportSize({ width: 1280, height: 800 });
    }
  });

  test(`${width} px: contact, bore map: layers with a height send bore.layers and contact.height (the distortion list is hidden and not sent), "all" by its checkbox; the server runs it and shows height_m; its echo loads back; an empty map sends neither`, { skip: SKIP.contact, timeout: 180000 }, async () => {
    await page.setViewportSize({ width, height: 844 });
    try {
      await page.getByRole('button', { name: 'Reset to defaults' }).click();
      await selectTab('contact');
      await page.fill('#f-segments', '12');
      await page.getByRole('button', { name: 'Add a distortion order' }).click();
      assert.equal(await page.isVisible('#f-ct-height'), false, 'no map: no height');
      assert.equal(await page.isVisible('#f-distortion-off'), false);
      const jobs = await interceptJobs(fixtures.contactResult());
      let scene;
      try {
        await enterMap('ct', MAP);
        // The map replaces the one distortion list: hidden, a note in its place.
        assert.equal(await page.isVisible('#f-distortion'), false);
        assert.equal(await page.isVisible('#f-distortion-off'), true);
        assert.equal(await page.isVisible('#f-ct-height'), true);
        assert.equal(await page.isChecked('#f-ct-height-all'), false);
        await page.fill('#f-ct-height', '0.02');
        assert.equal(await page.textContent('#f-ct-height-hint'), '= 20 mm');
        for (const id of ['#f-ct-height', '#f-ct-height-all', '#f-ct-layers-0-z', '#f-ct-layers-1-distortion-1-phase_deg', '#f-ct-map-plot']) await fieldFits(id);
        scene = await formScene(jobs, 'contact');
        assert.deepEqual(scene.bore, { layers: MAP });
        assert.equal(scene.contact.height, 0.02);
        await takes(scene);
        const d = await mapDrawing('f-ct-map-plot');
        assert.ok(d.visible && d.image);
        assert.match(d.label, /the depth z 0 to 100 mm \(2 layers\); the ring at z = 20 mm\.$/);
        assert.deepEqual(d.layers, [0, 0.1]);
        assert.equal(d.height.z, 0.02);
        assert.ok(Math.abs(d.height.y - mapY(d, 0.02)) < 0.01, 'the height line at 20 mm');
        assert.equal(d.travel, null);
        // "all" by the checkbox: the number field is set aside.
        await page.check('#f-ct-height-all');
        assert.equal(await page.isDisabled('#f-ct-height'), true);
        scene = await formScene(jobs, 'contact');
        assert.equal(scene.contact.height, 'all');
        assert.match((await mapDrawing('f-ct-map-plot')).label, /the ring at every layer\.$/);
        await page.uncheck('#f-ct-height-all');
        assert.equal(await page.isDisabled('#f-ct-height'), false);
        if (width === 390) assert.deepEqual(await smallText(), [], 'the map and its drawing are readable at 390 px');
        await page.locator('fieldset[data-analysis="contact"]').screenshot({ path: path.join(SHOT_DIR, `ringdyn-contact-map-form-${width}.png`) });

        // Emptied, the map sends neither layers nor height; the list is back and sent.
        await emptyMap('ct');
        assert.equal(await page.isVisible('#f-ct-height'), false);
        assert.equal(await page.isVisible('#f-distortion'), true);
        assert.equal(await page.isVisible('#f-ct-map'), false);
        scene = await formScene(jobs, 'contact');
        assert.equal(scene.bore.layers, undefined);
        assert.equal(scene.contact.height, undefined);
        assert.deepEqual(scene.bore.distortion, [{ order: 2, amplitude: 5e-6, phase_deg: 0 }]);
        await page.getByRole('button', { name: 'Remove distortion 1' }).click();
        await enterMap('ct', MAP);
        await page.fill('#f-ct-height', '0.02');
      } finally {
        await jobs.stop();
      }

      // Run against the server: the height and the bore there are named, the map drawn.
      await runAnalysis('Run contact analysis', 150000);
      assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
      const job = await shownJob();
      assert.equal(job.result.height_m, 0.02);
      assert.match(await page.textContent('#ct-height'), /^Bore map: the ring at z = 20 mm down the bore \(the bore there: D = 76\.5 mm, orders 2 \(3\.60 µm\), 4 \(0\.60 µm at 20°\)\)\.$/);
      assert.match(await page.textContent('#result-body h3'), /at z = 20 mm$/);
      const r = await mapDrawing('ct-map');
      assert.ok(r.visible && r.image);
      assert.ok(Math.abs(r.height.y - mapY(r, 0.02)) < 0.01);
      await settled();
      const overflow = await page.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
      assert.ok(overflow <= 0, `page scrolls sideways by ${overflow}px`);
      await shot(`ringdyn-contact-map-${width}.png`, { fullPage: true });

      // The job reopened from its address: the echo fills the map and the height.
      await page.goto(`${BASE}/?job=${encodeURIComponent(job.id)}`);
      await page.waitForFunction(() => document.getElementById('f-ct-layers-1-distortion-1-order')?.value === '4' &&
        document.getElementById('f-ct-height').value === '0.02');
      assert.equal(await page.getAttribute('#tab-contact', 'aria-selected'), 'true');
      assert.equal(await page.isVisible('#f-distortion'), false);
      const again = await interceptJobs(fixtures.contactResult());
      try {
        scene = await formScene(again, 'contact');
        assert.deepEqual(scene.bore.layers, job.result.scene.bore.layers);
        assert.equal(scene.contact.height, 0.02);
        assert.equal(scene.bore.distortion, undefined, 'the echo\'s empty list is not sent with the map');
        await takes(scene);
        // An echo of "all" checks the box.
        const all = structuredClone(job.result.scene);
        all.contact.height = 'all';
        await loadSceneFile(all, () => document.getElementById('f-ct-height-all').checked);
        assert.equal(await page.inputValue('#f-ct-height'), '');
        scene = await formScene(again, 'contact');
        assert.equal(scene.contact.height, 'all');
      } finally {
        await again.stop();
      }
      // The server runs "all": a row per layer, the plotted one marked.
      await runAnalysis('Run contact analysis', 150000);
      assert.equal(await page.isVisible('#error'), false, `unexpected error: ${await page.textContent('#error')}`);
      const allJob = await shownJob();
      assert.equal(await page.locator('#ct-layers tbody tr').count(), allJob.result.layers.length);
      assert.equal(await page.locator('#ct-layers tbody tr.shown').count(), 1);
      assert.match(await page.textContent('#ct-height'), new RegExp(`every layer: .* z = ${Number((allJob.result.height_m * 1e3).toPrecision(4))} mm`));
      assert.equal(await page.locator('#ct-map-height .bm-each').count(), 2);
      // A height outside the map: the server's 422 at the height field.
      await page.uncheck('#f-ct-height-all');
      await page.fill('#f-ct-height', '0.2');
      await runAnalysis('Run contact analysis');
      const text = await page.textContent('#error');
      assert.match(text, /^Height of the ring z \(m down the bore\): .*outside the bore map: allowed 0 to 0\.1 m/, text);
      assert.equal(await page.getAttribute('#f-ct-height', 'aria-invalid'), 'true');
    } finally {
      await page.goto(`${BASE}/`);
      await page.waitForSelector('#tab-modal[aria-selected="true"]');
      await page.setViewportSize({ width: 1280, height: 800 });
    }
  });
}

test('bore map renderers: an "all" contact lists every layer and marks the one plotted; a lift draws the travel; results without a map draw none', { timeout: 60000 }, async () => {
  const ct = fixtures.contactResult();
  ct.scene.bore = { diameter: 0.0765, layers: [{ z: 0, diameter: 0.0765, distortion: [] }, { z: 0.02, diameter: 0.0765, distortion: [{ order: 4, amplitude: 8e-6, phase_deg: 0 }] }, { z: 0.04, diameter: 0.07652, distortion: [] }] };
  ct.scene.contact = { height: 'all' };
  ct.height_m = 0.02;
  ct.bore_at_height = { diameter: 0.0765, distortion: [{ order: 4, amplitude: 8e-6, phase_deg: 0 }] };
  ct.layers = ct.scene.bore.layers.map((l, i) => ({ z_m: l.z, diameter_m: l.diameter, contact_fraction: [1, 0.8, 1][i], max_clearance: [0, 2e-6, 0][i], max_clearance_angle_deg: [null, 45, null][i], mean_pressure_pa: 2.1e5, min_bin_pressure_pa: [2e5, 0, 2e5][i], max_bin_pressure_pa: 2.3e5, light_gaps: [0, 4, 0][i], segments: 80, accuracy_met: true }));
  const lf = fixtures.liftResult();
  lf.scene.bore = { layers: [{ z: 0, distortion: [{ order: 2, amplitude: 3e-6 }] }, { z: 0.1 }], ring_z_tdc_m: 0.004 };
  lf.scene.engine.crank_radius = 0.04;
  const drawn = await page.evaluate(async ({ ct, lf, plain }) => {
    const out = {};
    for (const [name, id, result] of [['ct', 'contact', ct], ['lf', 'lift', lf], ['ct plain', 'contact', plain.ct], ['lf plain', 'lift', plain.lf]]) {
      const mod = await import(`/static/${id}.js`);
      const box = document.createElement('div');
      document.body.append(box);
      try {
        mod[id].render(result, null, box);
        const map = box.querySelector('svg.bore-map');
        out[name] = {
          map: map?.id ?? null, label: map?.getAttribute('aria-label'),
          layers: [...box.querySelectorAll('svg.bore-map [id$="-layers"] .bm-layer')].length,
          each: [...box.querySelectorAll('svg.bore-map .bm-each')].map((l) => [Number(l.dataset.z), l.classList.contains('bm-shown')]),
          travel: box.querySelector('svg.bore-map rect[id$="-travel"]') && ['z0', 'z1'].map((k) => Number(box.querySelector('svg.bore-map rect[id$="-travel"]').dataset[k])),
          rows: [...box.querySelectorAll('#ct-layers tbody tr')].map((tr) => [...tr.children].map((td) => td.textContent)),
          shown: [...box.querySelectorAll('#ct-layers tbody tr')].map((tr) => tr.classList.contains('shown')),
          height: box.querySelector('#ct-height')?.textContent ?? null,
          text: box.textContent,
        };
      } finally {
        box.remove();
      }
    }
    return out;
  }, { ct, lf, plain: { ct: fixtures.contactResult(), lf: fixtures.liftResult() } });
  assert.equal(drawn.ct.map, 'ct-map');
  assert.equal(drawn.ct.layers, 3);
  assert.deepEqual(drawn.ct.each, [[0, false], [0.02, true], [0.04, false]]);
  assert.match(drawn.ct.label, /depth z 0 to 40 mm \(3 layers\); the ring at every layer\./);
  // order 4 at 8 µm in the middle, +10 µm of radius at the bottom
  assert.match(drawn.ct.label, /-10 to \+10 µm/);
  assert.deepEqual(drawn.ct.shown, [false, true, false]);
  assert.deepEqual(drawn.ct.rows[1], ['20', '76.5', '80.0', '2.00 at 45°', '0.2100', '0.0000 – 0.2300', '80', 'met']);
  assert.equal(drawn.ct.rows[2][1], '76.52');
  assert.equal(drawn.ct.height, 'Bore map, the ring at every layer: shown here is the layer with the largest light gap, z = 20 mm down the bore (the bore there: D = 76.5 mm, order 4 (8.00 µm)); the table below lists every layer.');
  assert.doesNotMatch(drawn.ct.text, /\bnull\b|undefined|NaN/);
  assert.equal(drawn.lf.map, 'lf-map');
  assert.equal(drawn.lf.travel[0], 0.004);
  assert.ok(Math.abs(drawn.lf.travel[1] - 0.084) < 1e-12);
  assert.match(drawn.lf.label, /the ring's travel 4 to 84 mm \(TDC to BDC\)\.$/);
  assert.doesNotMatch(drawn.lf.text, /\bnull\b|undefined|NaN/);
  for (const k of ['ct plain', 'lf plain']) {
    assert.equal(drawn[k].map, null, k);
    assert.equal(drawn[k].height, null, k);
    assert.deepEqual(drawn[k].rows, [], k);
  }
  assert.deepEqual(pageErrors, []);
});

// Hover readout, zoom, compare runs and the error list (interact.mjs).
interactTests({ page: () => page, BASE, runAnalysis, selectTab, shownJob, pageErrors });
test('interact tests leave the page at 1280 px', async () => {
  await page.setViewportSize({ width: 1280, height: 800 });
  await page.goto(`${BASE}/`);
  await page.waitForSelector('#tab-modal[aria-selected="true"]');
});

// The ring pack's events, friction and flow splits (ringpack_page.mjs).
ringpackPageTests({ page: () => page, BASE, runAnalysis, selectTab, shownJob, smallText, settled, pageErrors });

test('no console errors or uncaught exceptions', () => {
  assert.deepEqual(pageErrors, []);
  assert.deepEqual(consoleErrors.filter((t) => !expectedConsole(t)), []);
});
