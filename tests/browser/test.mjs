// Headless-browser test of the ringdyn web page against a running server.
//   RINGDYN_URL       base URL of the server (required; run.sh starts one)
//   RINGDYN_SHOT_DIR  where the screenshots go (default /tmp)
// Run: node --test test.mjs   (the tests share one page and run in order)
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';

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

// Clicks the run button and waits until the job has ended (button enabled again).
async function runAnalysis() {
  await page.getByRole('button', { name: 'Run modal analysis' }).click();
  await page.waitForFunction(() => !document.getElementById('run').disabled, null, { timeout: 90000 });
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
    path: i.dataset.path, value: i.type === 'checkbox' ? i.checked : Number(i.value),
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

test('no console errors or uncaught exceptions', () => {
  assert.deepEqual(pageErrors, []);
  assert.deepEqual(consoleErrors.filter((t) => !expectedConsole(t)), []);
});
