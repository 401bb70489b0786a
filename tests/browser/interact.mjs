// Browser tests of the charts' interaction (static/plotui.js) and the error
// list (issue 44 item 4), at 1280 and 390 px: the hover readout against the
// result's numbers on every chart of every analysis, zoom by drag, Ctrl +
// wheel and reset, a kept run drawn under the next one and cleared, and a
// scene with two bad fields listing both.  Registered by test.mjs, which
// owns the page: interactTests({page, BASE, ...helpers}).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import * as fixtures from './fixtures.mjs';

export function interactTests({ page: pageOf, BASE, runAnalysis, selectTab, shownJob, pageErrors }) {
  const page = () => pageOf();

  // The page's POST /api/v1/jobs answered with `results` in turn (each a
  // succeeded job of its analysis, ids fixture-1, fixture-2, ...).
  async function answerJobs(results) {
    let n = 0;
    const match = (url) => url.pathname === '/api/v1/jobs';
    await page().route(match, async (route) => {
      if (route.request().method() !== 'POST') return route.continue();
      const result = results[Math.min(n, results.length - 1)];
      n += 1;
      return route.fulfill({
        status: 200, contentType: 'application/json',
        body: JSON.stringify({ id: `fixture-${n}`, status: 'succeeded', progress: 1, result }),
      });
    });
    return () => page().unroute(match);
  }

  async function fresh(width) {
    await page().setViewportSize({ width, height: width < 600 ? 844 : 800 });
    await page().goto(`${BASE}/`);
    await page().waitForSelector('#tab-modal[aria-selected="true"]');
  }

  // The plot box of chart `sel` on screen (its axis line spans it), scrolled into view.
  async function plotBox(sel) {
    await page().locator(sel).scrollIntoViewIfNeeded();
    return page().$eval(sel, (s) => {
      const r = s.querySelector(':scope > .axes path.axis').getBoundingClientRect();
      return { x: r.left, y: r.top, width: r.width, height: r.height };
    });
  }

  // The x range shown by chart `sel`, from its first and last x tick (value
  // and place) extrapolated to the plot box's edges.
  function xRange(sel) {
    return page().$eval(sel, (s) => {
      const axis = s.querySelector(':scope > .axes path.axis').getBBox();
      const t = [...s.querySelectorAll(':scope > .axes text.tick[text-anchor="middle"]')]
        .map((e) => [Number(e.textContent.replace(/[^\d.eE+-]/g, '')), Number(e.getAttribute('x'))]);
      const [[v0, p0], [v1, p1]] = [t[0], t[t.length - 1]];
      const at = (p) => v0 + ((p - p0) * (v1 - v0)) / (p1 - p0);
      return { lo: at(axis.x), hi: at(axis.x + axis.width), ticks: t.map(([v]) => v) };
    });
  }

  // Moves the pointer to fraction (fx, fy) of chart `sel`'s plot box (off it
  // first, so the move is seen) and returns the readout's rows.
  async function hover(sel, fx, fy = 0.5) {
    const b = await plotBox(sel);
    await page().mouse.move(1, 1);
    await page().mouse.move(b.x + b.width * fx, b.y + b.height * fy, { steps: 2 });
    await page().waitForSelector('.chart-readout:not([hidden])');
    return page().$$eval('.chart-readout tr[data-series]', (rows) => rows.map((r) => ({
      series: r.dataset.series, x: Number(r.dataset.x), y: Number(r.dataset.y),
      xText: r.querySelector('.rx').textContent, yText: r.querySelector('.ry').textContent,
    })));
  }

  // A readout's text is its value to 1e-3 of the span (plotui.js formatValue).
  const shownClose = (text, v, span, what) => {
    assert.ok(Math.abs(Number(text) - v) <= Math.abs(span) * 1e-3, `${what}: shown ${text} for ${v}`);
  };

  async function drag(sel, f0, f1, fy0 = 0.5, fy1 = fy0 + 0.01) {
    const b = await plotBox(sel);
    await page().mouse.move(b.x + b.width * f0, b.y + b.height * fy0);
    await page().mouse.down();
    await page().mouse.move(b.x + b.width * ((f0 + f1) / 2), b.y + b.height * ((fy0 + fy1) / 2), { steps: 3 });
    await page().mouse.move(b.x + b.width * f1, b.y + b.height * fy1, { steps: 3 });
    await page().mouse.up();
  }

  for (const width of [1280, 390]) {
    test(`charts at ${width} px: a hover readout on every chart, its numbers the result's (modal live; pretension, contact, lift, ring pack fixtures)`, { timeout: 120000 }, async () => {
      await fresh(width);
      await page().fill('#f-segments', '20');
      await runAnalysis();
      const job = await shownJob();
      const modes = job.result.modes;
      // Mode 3's marker: x = 3, y its frequency (the y axis is 0 to its top tick).
      const yMax = await page().$eval('#freq-plot', (s) => Math.max(...[...s.querySelectorAll(':scope > .axes text.tick[text-anchor="end"]')].map((t) => Number(t.textContent))));
      const rows = await hover('#freq-plot', (3 - 0.5) / modes.length, 1 - modes[2].frequency_hz / yMax);
      const m3 = rows.find((r) => r.x === 3);
      assert.ok(m3, JSON.stringify(rows));
      assert.ok(Math.abs(m3.y - modes[2].frequency_hz) <= yMax * 1e-4, `${m3.y} vs ${modes[2].frequency_hz}`);
      assert.equal(m3.series, modes[2].kind === 'in_plane' ? 'in-plane' : 'out-of-plane');
      assert.equal(m3.xText, '3');
      shownClose(m3.yText, modes[2].frequency_hz, yMax, 'mode 3');
      // Every row is a mode's point.
      for (const r of rows) assert.ok(modes.some((m) => m.mode === r.x && Math.abs(m.frequency_hz - r.y) <= yMax * 1e-4), JSON.stringify(r));
      // The mode shape chart (unrolled, an out-of-plane mode) reads too.
      const oop = modes.find((m) => m.kind === 'out_of_plane');
      await page().click(`button.mode-select[data-mode="${oop.mode}"]`);
      await page().waitForSelector('#shape-svg.unrolled-view');
      const shape = await hover('#shape-svg', 0.5);
      assert.ok(shape.some((r) => r.series === 'axial displacement' && Math.abs(r.x - 180) < 360 / job.result.scene.discretization.segments), JSON.stringify(shape));

      // Lift (fixture): the mean lift and friction against crank angle.
      const lf = fixtures.liftResult();
      let stop = await answerJobs([lf]);
      try {
        await page().click('#tab-lift');
        await page().waitForSelector('fieldset[data-analysis="lift"]:not([hidden])');
        await runAnalysis('Run lift analysis');
        await page().waitForSelector('#lf-lift');
        const r = await xRange('#lf-lift');
        for (const f of [0.3, 0.55]) {
          const at = (await hover('#lf-lift', f)).find((x) => x.series === 'mean lift');
          assert.ok(at, 'a mean lift row');
          const i = lf.crank_deg.indexOf(Math.round(at.x));
          assert.ok(i >= 0 && Math.abs(at.x - lf.crank_deg[i]) < 0.05, `x ${at.x}`);
          assert.ok(Math.abs(at.x - (r.lo + f * (r.hi - r.lo))) <= 2, `x ${at.x} under the pointer at ${f}`);
          assert.ok(Math.abs(at.y - lf.lift[i] * 1e6) < 0.02, `lift ${at.y} µm vs ${lf.lift[i] * 1e6}`);
          shownClose(at.xText, lf.crank_deg[i], r.hi - r.lo, 'crank');
        }
        const fr = (await hover('#lf-friction', 0.4)).find((x) => x.series === 'friction');
        const i = Math.round(fr.x);
        assert.ok(Math.abs(fr.y - lf.friction_force[i]) < 3.6 * 1e-3, `friction ${fr.y} vs ${lf.friction_force[i]}`);
      } finally {
        await stop();
      }

      // Every chart on axes of every analysis shows a readout.
      for (const [id, result] of [['pretension', fixtures.pretensionResult({ lateral: 0.5 })], ['contact', fixtures.contactResult()], ['lift', fixtures.liftResult()], ['ringpack', fixtures.ringpackResult()]]) {
        stop = await answerJobs([result]);
        try {
          await page().click(`#tab-${id}`);
          await page().waitForSelector(`fieldset[data-analysis="${id}"]:not([hidden])`);
          await runAnalysis(`Run ${id} analysis`);
          // Each shown chart, by a mark of its own (not every chart has an id).
          const charts = await page().$$eval('#result-body svg.interactive', (s) => s
            .filter((c) => c.getBoundingClientRect().width > 0)
            .map((c, i) => { c.dataset.probe = String(i); return `[data-probe="${i}"]`; }));
          assert.ok(charts.length >= 1, `${id}: charts with axes`);
          for (const c of charts) {
            const got = await hover(c, 0.5);
            assert.ok(got.length >= 1 && got.every((g) => Number.isFinite(g.x) && Number.isFinite(g.y)), `${id} ${c}: ${JSON.stringify(got)}`);
          }
          // Charts not on axes (ring drawings, polar plots) are left alone.
          const plain = await page().$$eval('#result-body svg[viewBox]:not(.icon):not(.interactive)', (s) => s.filter((c) => c.querySelector(':scope > .axes')).length);
          assert.equal(plain, 0, `${id}: every chart with axes is interactive`);
        } finally {
          await stop();
        }
      }
      // The mouse leaving hides it.
      await page().mouse.move(1, 1);
      assert.equal(await page().isVisible('.chart-readout'), false);
      assert.deepEqual(pageErrors, []);
    });

    test(`charts at ${width} px: drag zooms the x range, double-click restores it; Ctrl + wheel zooms, Reset zoom restores; a box zooms y too`, { timeout: 90000 }, async () => {
      await fresh(width);
      const lf = fixtures.liftResult();
      const stop = await answerJobs([lf]);
      try {
        await page().click('#tab-lift');
        await page().waitForSelector('fieldset[data-analysis="lift"]:not([hidden])');
        await runAnalysis('Run lift analysis');
        await page().waitForSelector('#lf-lift');
        const before = await xRange('#lf-lift');
        const span = before.hi - before.lo;
        const yTicks = () => page().$$eval('#lf-lift > .axes text.tick[text-anchor="end"]', (t) => t.map((e) => e.textContent));
        const y0 = await yTicks();
        await drag('#lf-lift', 0.25, 0.6);
        assert.equal(await page().getAttribute('#lf-lift', 'data-zoomed'), 'true');
        const z = await xRange('#lf-lift');
        assert.ok(Math.abs(z.lo - (before.lo + 0.25 * span)) < span * 0.01, `lo ${z.lo}`);
        assert.ok(Math.abs(z.hi - (before.lo + 0.6 * span)) < span * 0.01, `hi ${z.hi}`);
        assert.ok(z.ticks.every((t) => t >= z.lo - 1e-9 && t <= z.hi + 1e-9), JSON.stringify(z));
        assert.deepEqual(await yTicks(), y0, 'an x drag keeps y');
        assert.equal(await page().isVisible('#lf-lift + .zoom-reset'), true);
        // The mean line is clipped to the box and drawn at the new range:
        // the readout under the pointer reads the zoomed axis.
        const at = (await hover('#lf-lift', 0.5)).find((r) => r.series === 'mean lift');
        assert.ok(Math.abs(at.x - (z.lo + z.hi) / 2) <= 1.5, `${at.x} in the zoomed middle`);
        assert.equal(await page().getAttribute('#lf-mean', 'clip-path') !== null, true);
        // Double-click: the whole range again, ticks as before.
        const b = await plotBox('#lf-lift');
        await page().mouse.dblclick(b.x + b.width / 2, b.y + b.height / 2);
        const back = await xRange('#lf-lift');
        assert.deepEqual(back.ticks, before.ticks);
        assert.ok(Math.abs(back.lo - before.lo) < 1e-6 && Math.abs(back.hi - before.hi) < 1e-6);
        assert.equal(await page().getAttribute('#lf-lift', 'data-zoomed'), 'false');
        assert.equal(await page().isVisible('#lf-lift + .zoom-reset'), false);
        assert.equal(await page().getAttribute('#lf-mean', 'clip-path'), null);

        // Ctrl + wheel: x zooms about the pointer; Reset zoom restores.
        await page().mouse.move(b.x + b.width / 2, b.y + b.height / 2);
        await page().keyboard.down('Control');
        await page().mouse.wheel(0, -100);
        await page().keyboard.up('Control');
        await page().waitForSelector('#lf-lift[data-zoomed="true"]');
        const w = await xRange('#lf-lift');
        assert.ok(Math.abs((w.hi - w.lo) - span / 1.25) < span * 0.01, `wheel span ${w.hi - w.lo}`);
        await page().click('#lf-lift + .zoom-reset');
        assert.deepEqual((await xRange('#lf-lift')).ticks, before.ticks);

        // A tall box zooms y as well; the friction chart zooms on its own.
        const f0 = await page().$$eval('#lf-friction > .axes text.tick[text-anchor="end"]', (t) => t.map((e) => e.textContent));
        await drag('#lf-friction', 0.2, 0.4, 0.2, 0.5);
        const f1 = await page().$$eval('#lf-friction > .axes text.tick[text-anchor="end"]', (t) => t.map((e) => e.textContent));
        assert.notDeepEqual(f1, f0, 'a box zooms y');
        assert.equal(await page().getAttribute('#lf-lift', 'data-zoomed'), 'false');
        await page().click('#lf-friction + .zoom-reset');
        assert.deepEqual(await page().$$eval('#lf-friction > .axes text.tick[text-anchor="end"]', (t) => t.map((e) => e.textContent)), f0);
        // An exported figure carries no pointer marks.
        await hover('#lf-lift', 0.5);
        const svgText = await page().evaluate(async () => (await import('/static/charts.js')).figureSvg(document.getElementById('lf-lift').closest('figure, [data-figure]')).text);
        assert.doesNotMatch(svgText, /hover-|zoom-box/);
      } finally {
        await stop();
      }
      assert.deepEqual(pageErrors, []);
    });

    test(`compare at ${width} px: a kept run is drawn dashed under the next one, labelled, in the readout, and cleared`, { timeout: 120000 }, async () => {
      await fresh(width);
      // Modal, live: two runs, their markers overlaid.
      await page().fill('#f-segments', '20');
      await runAnalysis();
      const first = await shownJob();
      assert.equal(await page().isVisible('#keep-run'), true);
      await page().click('#keep-run');
      assert.match(await page().textContent('#compare-note'), new RegExp(`job ${first.id}.* is kept`));
      assert.equal(await page().locator('#freq-plot .kept').count(), 0, 'the kept run itself is not drawn twice');
      await page().fill('#f-segments', '12');
      await runAnalysis();
      const second = await shownJob();
      assert.notEqual(second.id, first.id);
      assert.equal(await page().locator('#freq-plot path.kept, #freq-plot g.kept').count() > 0, true);
      const kept = await page().$$eval('#freq-plot .kept-pt', (c) => c.length);
      assert.equal(kept, first.result.modes.length);
      assert.match(await page().textContent('#freq-plot .kept-label'), new RegExp(`job ${first.id}`));
      assert.match(await page().textContent('#compare-note'), new RegExp(`Dashed: job ${first.id}`));
      const rows = await hover('#freq-plot', 0.5);
      const mine = rows.filter((r) => !r.series.includes('(job'));
      const theirs = rows.filter((r) => r.series.includes(`(job ${first.id})`));
      assert.ok(mine.length >= 1 && theirs.length >= 1, JSON.stringify(rows));
      const yMax = await page().$eval('#freq-plot', (s) => Math.max(...[...s.querySelectorAll(':scope > .axes text.tick[text-anchor="end"]')].map((t) => Number(t.textContent))));
      for (const r of theirs) assert.ok(first.result.modes.some((m) => m.mode === r.x && Math.abs(m.frequency_hz - r.y) <= yMax * 1e-4), JSON.stringify(r));
      for (const r of mine) assert.ok(second.result.modes.some((m) => m.mode === r.x && Math.abs(m.frequency_hz - r.y) <= yMax * 1e-4), JSON.stringify(r));
      await page().click('#clear-kept');
      assert.equal(await page().locator('#freq-plot .kept, #freq-plot .kept-label').count(), 0);
      assert.equal(await page().isVisible('#clear-kept'), false);

      // Lift (fixtures): the kept mean lift is a dashed line at the first run's values.
      const a = fixtures.liftResult();
      const b = fixtures.liftResult();
      b.lift = b.lift.map((v) => v * 0.5);
      const stop = await answerJobs([a, b]);
      try {
        await page().click('#tab-lift');
        await page().waitForSelector('fieldset[data-analysis="lift"]:not([hidden])');
        await runAnalysis('Run lift analysis');
        await page().click('#keep-run');
        await runAnalysis('Run lift analysis');
        assert.match(await page().textContent('#compare-note'), /Dashed: job fixture-1/);
        const lines = await page().$$eval('#lf-lift path.kept', (p) => p.map((e) => e.dataset.name));
        assert.ok(lines.includes('mean lift (job fixture-1)'), JSON.stringify(lines));
        const at = await hover('#lf-lift', 0.3);
        const now = at.find((r) => r.series === 'mean lift');
        const then = at.find((r) => r.series === 'mean lift (job fixture-1)');
        const i = Math.round(now.x), j = Math.round(then.x);
        assert.ok(Math.abs(now.y - b.lift[i] * 1e6) < 0.02 && Math.abs(then.y - a.lift[j] * 1e6) < 0.02, JSON.stringify(at));
        // Another analysis is not compared with it; the note says what is kept.
        await page().click('#tab-modal');
        assert.match(await page().textContent('#compare-note'), /job fixture-1 of lift/);
        await page().click('#tab-lift');
        await page().click('#clear-kept');
        assert.equal(await page().locator('#lf-lift .kept').count(), 0);
      } finally {
        await stop();
      }
      assert.deepEqual(pageErrors, []);
    });

    test(`errors at ${width} px: a scene with two bad fields lists both, each field marked`, { timeout: 60000 }, async () => {
      await fresh(width);
      await page().fill('#f-segments', '1');
      await page().fill('#f-diameter', '-1');
      await runAnalysis();
      const items = await page().$$eval('#error li', (li) => li.map((e) => ({ path: e.dataset.path, text: e.textContent })));
      const paths = items.map((i) => i.path).sort();
      assert.deepEqual(paths, ['/discretization/segments', '/ring/diameter'], JSON.stringify(items));
      assert.match(items.find((i) => i.path === '/ring/diameter').text, /^Nominal diameter d \(m\): .*-1 .*out of range/);
      assert.match(items.find((i) => i.path === '/discretization/segments').text, /^Segments n .*= 1 is out of range/);
      for (const id of ['#f-segments', '#f-diameter']) assert.equal(await page().getAttribute(id, 'aria-invalid'), 'true', id);
      // Fixed: gone, and one error alone reads as before (no list).
      await page().fill('#f-diameter', '0.0765');
      await runAnalysis();
      assert.equal(await page().locator('#error li').count(), 0);
      assert.match(await page().textContent('#error'), /^Segments n .*= 1 is out of range/);
      assert.equal(await page().getAttribute('#f-diameter', 'aria-invalid'), null);
      await page().fill('#f-segments', '20');
      await runAnalysis();
      assert.equal(await page().isVisible('#error'), false);
    });
  }

  test('the page says what it measured: the ring pack caption names its models; no "doubles" for the error estimate', { timeout: 30000 }, async () => {
    const rp = fixtures.ringpackResult();
    const text = await page().evaluate(async (result) => {
      const { ringpack } = await import('/static/ringpack.js');
      const box = document.createElement('div');
      document.body.append(box);
      const out = [];
      try {
        ringpack.render(result, null, box);
        out.push(box.querySelector('#rp-lift-caption').textContent);
        result.numerics.model = [{ name: 'full' }, { name: 'axial' }, { name: 'axial' }];
        ringpack.render(result, null, box);
        out.push(box.querySelector('#rp-lift-caption').textContent);
      } finally {
        box.remove();
      }
      return out;
    }, rp);
    assert.match(text[0], /\(axial rings\)/);
    assert.match(text[1], /\(ring 1 full, rings 2–3 axial\)/);
    assert.doesNotMatch(text.join(' '), /rigid rings/);
    const html = await (await fetch(`${BASE}/`)).text();
    assert.doesNotMatch(html, /doubles/);
    assert.match(html, /×3–3\.6/);
  });
}
