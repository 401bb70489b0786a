// Browser tests of the ring pack's result view (static/ringpack.js, issue 44
// item 4's last part), at 1280 and 390 px: each ring's flank changes marked
// on its own lift curve, as many as its events and of their kind; the
// friction chart with friction and not without; one labelled series per
// passage in the flow charts; and the per-cycle table against the result's
// flows integrated here.  On the canned result (fixtures.mjs) and on live
// two-cycle runs of the default pack with Coulomb friction and without.
// Registered by test.mjs, which owns the page: ringpackPageTests({page, ...}).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import * as fixtures from './fixtures.mjs';

// What the page should show, computed from the result alone.

// The net, forward and reversed mass through each flow over the reported
// cycle, kg: the trapezoidal rule over the samples, dt = Δcrank / (6 rpm).
export function flowMasses(result) {
  const c = result.crank_deg, rpm = result.scene.engine.speed_rpm;
  return result.flows.map((f) => {
    const m = f.mass_flow_kg_s, out = { net: 0, forward: 0, back: 0 };
    for (let k = 0; k + 1 < c.length; k++) {
      const dt = (c[k + 1] - c[k]) / (6 * rpm);
      out.net += ((m[k] + m[k + 1]) / 2) * dt;
      out.forward += ((Math.max(m[k], 0) + Math.max(m[k + 1], 0)) / 2) * dt;
      out.back += ((Math.max(-m[k], 0) + Math.max(-m[k + 1], 0)) / 2) * dt;
    }
    return out;
  });
}

// A passage's label: its name less "ring_N_" (nothing when the name only
// joins its volumes), then "from → to".
function flowLabel(f) {
  const part = f.name === `${f.from}_to_${f.to}` ? '' : f.name.replace(/^ring_\d+_/, '').replace(/_/g, ' ');
  return `${part ? `${part}: ` : ''}${f.from} → ${f.to}`;
}

// [[x, y]...] of an absolute M/L path.
function points(d) {
  const n = d.match(/[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?/g).map(Number);
  const out = [];
  for (let i = 0; i + 1 < n.length; i += 2) out.push([n[i], n[i + 1]]);
  return out;
}

// y of the polyline `pts` at x (linear between its points).
function yAt(pts, x) {
  let k = 1;
  while (k < pts.length - 1 && pts[k][0] < x) k++;
  const [[x0, y0], [x1, y1]] = [pts[k - 1], pts[k]];
  return x1 === x0 ? y0 : y0 + ((x - x0) / (x1 - x0)) * (y1 - y0);
}

export function ringpackPageTests({ page: pageOf, BASE, runAnalysis, selectTab, shownJob, smallText, settled, pageErrors }) {
  const page = () => pageOf();

  // The page's POST /api/v1/jobs answered with `result` as a succeeded job.
  async function answerWith(result) {
    const match = (url) => url.pathname === '/api/v1/jobs';
    await page().route(match, (route) => (route.request().method() !== 'POST' ? route.continue()
      : route.fulfill({ status: 200, contentType: 'application/json', body: JSON.stringify({ id: 'fixture-rp', status: 'succeeded', progress: 1, result }) })));
    return () => page().unroute(match);
  }

  // What the result view drew, read off the page.
  function drawn() {
    return page().evaluate(() => {
      const all = (sel) => [...document.querySelectorAll(sel)];
      const lift = document.getElementById('rp-lift');
      return {
        markers: all('#rp-lift .rp-ev').map((g) => {
          const t = /translate\(([-\d.e+]+),([-\d.e+]+)\)/.exec(g.getAttribute('transform'));
          const mk = g.querySelector('path.rp-ev-mk');
          return {
            ring: Number(g.dataset.ring), event: g.dataset.event, crank: Number(g.dataset.crank),
            x: Number(t[1]), y: Number(t[2]), d: mk.getAttribute('d'), reach: mk.classList.contains('rp-ev-reach'),
            stroke: mk.style.stroke, fill: mk.style.fill, title: g.querySelector('title').textContent,
            shown: mk.getBoundingClientRect().width,
          };
        }),
        curves: all('#rp-lift > path[data-points]').map((p) => ({ name: p.dataset.name, d: p.getAttribute('d'), stroke: p.style.stroke })),
        // the crank axis: x of 0 and of the last tick, from the tick labels
        xTicks: lift ? [...lift.querySelectorAll(':scope > .axes text.tick[text-anchor="middle"]')].map((e) => [Number(e.textContent), Number(e.getAttribute('x'))]) : [],
        counts: all('#rp-event-counts .rp-event-count').map((s) => ({ ring: Number(s.dataset.ring), count: Number(s.dataset.count), text: s.textContent })),
        key: document.getElementById('rp-event-key')?.textContent ?? null,
        keyIcons: all('#rp-event-key svg.icon path.rp-ev-mk').length,
        friction: Boolean(document.getElementById('rp-friction')),
        frictionCurves: all('#rp-friction > path[data-points]').map((p) => ({ name: p.dataset.name, points: Number(p.dataset.points), stroke: p.style.stroke })),
        frictionCaption: document.getElementById('rp-friction-caption')?.textContent ?? null,
        flowCharts: all('#rp-flows svg.chart').map((s) => ({
          id: s.id, interactive: s.classList.contains('interactive'),
          series: [...s.querySelectorAll(':scope > path[data-flow]')].map((p) => ({ flow: p.dataset.flow, name: p.dataset.name, points: Number(p.dataset.points) })),
          legend: [...s.querySelectorAll(':scope > .legend text')].map((t) => t.textContent),
        })),
        interactive: all('#rp-plots svg.chart, #rp-flows svg.chart').map((s) => [s.id, s.classList.contains('interactive')]),
        rows: all('#rp-flow-table tbody tr').map((tr) => ({
          flow: tr.dataset.flow,
          cells: ['net', 'forward', 'back'].map((c) => {
            const td = tr.querySelector(`td.${c}`);
            return { kg: Number(td.dataset.kg), text: td.textContent };
          }),
          volumes: tr.querySelector('td').textContent,
        })),
      };
    });
  }

  // Everything the view should draw for `r`, checked against what it drew.
  async function check(r, what, { friction }) {
    const d = await drawn();

    // Events: one marker per event of each ring, on that ring's curve, at its
    // angle, in its colour, its shape by kind; the caption counts them.
    const want = r.rings.flatMap((ring, i) => ring.events.map((e) => ({ ring: i + 1, event: e.event, crank: e.crank_deg })));
    assert.deepEqual(d.markers.map((m) => [m.ring, m.event, m.crank]), want.map((e) => [e.ring, e.event, e.crank]), `${what}: one marker per event`);
    for (const [i, ring] of r.rings.entries()) {
      assert.equal(d.markers.filter((m) => m.ring === i + 1).length, ring.events.length, `${what}: ring ${i + 1}'s markers`);
    }
    assert.deepEqual(d.counts.map((c) => [c.ring, c.count, c.text]), r.rings.map((ring, i) => [i + 1, ring.events.length, `ring ${i + 1}: ${ring.events.length}`]), `${what}: counts`);
    assert.match(d.key, /leaves the lower flank.*reaches the upper flank.*leaves the upper flank.*reaches the lower flank/);
    assert.equal(d.keyIcons, 4, 'one icon per kind in the caption');
    const [[v0, p0], [v1, p1]] = [d.xTicks[0], d.xTicks.at(-1)];
    const xOf = (c) => p0 + ((c - v0) * (p1 - p0)) / (v1 - v0);
    for (const m of d.markers) {
      const curve = d.curves.find((c) => c.name === `ring ${m.ring}`);
      assert.ok(curve, `${what}: ring ${m.ring} has its curve`);
      assert.ok(Math.abs(m.x - xOf(m.crank)) < 0.05, `${what}: ring ${m.ring} ${m.event} at x ${m.x}, want ${xOf(m.crank)}`);
      assert.ok(Math.abs(m.y - yAt(points(curve.d), m.x)) < 0.5, `${what}: ring ${m.ring} ${m.event} on its curve (y ${m.y})`);
      assert.equal(m.stroke, curve.stroke, `${what}: marker in ring ${m.ring}'s colour`);
      // up for a move up (leave lower, reach upper), filled where it reaches a flank
      const up = m.event === 'leave_lower' || m.event === 'reach_upper';
      assert.equal(m.d.startsWith('m0,-'), up, `${what}: ${m.event} points ${up ? 'up' : 'down'}`);
      assert.equal(m.reach, m.event.startsWith('reach'));
      assert.equal(m.fill === m.stroke, m.reach, `${what}: ${m.event} ${m.reach ? 'filled' : 'open'}`);
      assert.match(m.title, new RegExp(`^Ring ${m.ring} (leaves|reaches) the (lower|upper) flank at `));
      assert.ok(m.shown >= 7, `${what}: marker ${m.shown} px wide on screen`);
    }

    // Friction: drawn with friction (one curve per ring), not without.
    assert.equal(d.friction, friction, `${what}: friction chart ${friction ? 'drawn' : 'absent'}`);
    if (friction) {
      assert.deepEqual(d.frictionCurves.map((c) => [c.name, c.points]), r.rings.map((_, i) => [`ring ${i + 1}`, r.crank_deg.length]));
      assert.deepEqual(d.frictionCurves.map((c) => c.stroke), r.rings.map((_, i) => d.curves[i].stroke), 'each ring in its lift colour');
      assert.match(d.frictionCaption, /N, \+ upwards/);
      assert.match(d.frictionCaption, new RegExp(`\\(${r.scene.physics.friction.model}`));
    }

    // Flows: one labelled series per passage, every chart interactive.
    const series = d.flowCharts.flatMap((c) => c.series);
    assert.deepEqual(series.map((s) => s.flow).sort(), r.flows.map((f) => f.name).sort(), `${what}: one series per passage`);
    for (const f of r.flows) {
      const chart = d.flowCharts.find((c) => c.series.some((s) => s.flow === f.name));
      const s = chart.series.find((x) => x.flow === f.name);
      assert.equal(s.name, flowLabel(f), `${what}: ${f.name}'s label`);
      assert.equal(s.points, r.crank_deg.length);
      assert.ok(chart.legend.includes(flowLabel(f)), `${what}: ${f.name} in ${chart.id}'s legend: ${chart.legend}`);
    }
    assert.deepEqual(d.interactive.filter(([, on]) => !on), [], `${what}: every chart has hover and zoom`);

    // The table: each passage's net, forward and back mass per cycle.
    const m = flowMasses(r);
    assert.deepEqual(d.rows.map((row) => row.flow), r.flows.map((f) => f.name));
    d.rows.forEach((row, k) => {
      const f = r.flows[k];
      assert.equal(row.volumes, `${f.from} → ${f.to}`);
      ['net', 'forward', 'back'].forEach((part, j) => {
        const want = m[k][part], { kg, text } = row.cells[j];
        assert.ok(Math.abs(kg - want) <= 1e-6 * Math.abs(want) + 1e-300, `${what}: ${f.name} ${part} ${kg} vs ${want} kg`);
        // shown in mg to 4 significant digits
        assert.ok(Math.abs(Number(text) - want * 1e6) <= 5e-4 * Math.abs(want * 1e6) + 1e-300, `${what}: ${f.name} ${part} shown ${text} mg vs ${want * 1e6}`);
      });
    });
    return d;
  }

  // The readout of chart `sel` with the pointer at fraction fx of its plot box.
  async function hover(sel, fx) {
    await page().locator(sel).scrollIntoViewIfNeeded();
    const b = await page().$eval(sel, (s) => {
      const r = s.querySelector(':scope > .axes path.axis').getBoundingClientRect();
      return { x: r.left, y: r.top, width: r.width, height: r.height };
    });
    await page().mouse.move(1, 1);
    await page().mouse.move(b.x + b.width * fx, b.y + b.height * 0.5, { steps: 2 });
    await page().waitForSelector('.chart-readout:not([hidden])');
    return page().$$eval('.chart-readout tr[data-series]', (rows) => rows.map((r) => ({ series: r.dataset.series, x: Number(r.dataset.x), y: Number(r.dataset.y) })));
  }

  const noOverflow = async (what) => {
    const overflow = await page().evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
    assert.ok(overflow <= 0, `${what}: page scrolls sideways by ${overflow}px`);
  };

  for (const width of [1280, 390]) {
    test(`${width} px: ring pack result: events marked on each ring's lift, friction only with friction, one series per passage, net mass per cycle (canned result and live runs)`, { timeout: 180000 }, async () => {
      await page().setViewportSize({ width, height: width < 600 ? 844 : 800 });
      await page().goto(`${BASE}/`);
      await page().waitForSelector('#tab-modal[aria-selected="true"]');
      try {
        await selectTab('ringpack');

        // The canned result: ring 1's four events, no friction, one passage.
        const rp = fixtures.ringpackResult();
        const stop = await answerWith(rp);
        try {
          await runAnalysis('Run ringpack analysis');
        } finally {
          await stop();
        }
        await page().waitForSelector('#rp-lift .rp-ev');
        await settled();
        await check(rp, 'fixture', { friction: false });
        await noOverflow('fixture');

        // Live: the default pack, two cycles, Coulomb friction μ 0.1.
        await page().fill('#f-rp-cycles', '2');
        await page().check('#f-rp-friction');
        await page().selectOption('#f-rp-friction-model', 'coulomb');
        await page().fill('#f-rp-friction-coefficient', '0.1');
        await runAnalysis('Run ringpack analysis', 120000);
        assert.equal(await page().isVisible('#error'), false, `unexpected error: ${await page().textContent('#error')}`);
        await page().waitForSelector('#rp-friction');
        const { result: r } = await shownJob();
        assert.equal(r.scene.physics.friction.model, 'coulomb');
        assert.ok(r.rings.some((ring) => ring.friction_n.some((v) => v !== 0)), 'the run has friction');
        assert.ok(r.rings.some((ring) => ring.events.length > 0), 'the run has flank changes');
        assert.ok(r.flows.length >= 3 * r.rings.length, `every ring's passages (${r.flows.length})`);
        await settled();
        await check(r, 'coulomb', { friction: true });
        await noOverflow('coulomb');
        assert.deepEqual(await smallText(), [], 'no text below 10 px');
        await page().screenshot({ path: path.join(process.env.RINGDYN_SHOT_DIR || '/tmp', `ringdyn-ringpack-flows-${width}.png`), fullPage: true });

        // The new charts read back: the friction readout has each ring's value.
        const rows = await hover('#rp-friction', 0.25);
        assert.deepEqual(rows.map((x) => x.series), r.rings.map((_, i) => `ring ${i + 1}`));
        for (const [i, row] of rows.entries()) {
          const k = r.crank_deg.indexOf(r.crank_deg.reduce((a, c) => (Math.abs(c - row.x) < Math.abs(a - row.x) ? c : a)));
          const f = r.rings[i].friction_n, span = Math.max(...r.rings.flatMap((x) => x.friction_n)) - Math.min(0, ...r.rings.flatMap((x) => x.friction_n));
          assert.ok(Math.abs(row.y - f[k]) <= span * 2e-3, `ring ${i + 1} friction at ${row.x}: read ${row.y}, result ${f[k]}`);
        }
        const flowRows = await hover('#rp-flow-1', 0.5);
        const ring1 = (await drawn()).flowCharts.find((c) => c.id === 'rp-flow-1');
        assert.deepEqual(flowRows.map((x) => x.series), ring1.series.map((s) => s.name));
        await page().mouse.move(1, 1);

        // Zoomed (plotui.js), each marker moves with the axis and keeps its size.
        const [z0, z1] = [r.crank_deg.at(-1) * 0.25, r.crank_deg.at(-1) * 0.75];
        await page().evaluate(async (range) => (await import('/static/plotui.js')).zoomTo(document.getElementById('rp-lift'), range), [z0, z1]);
        const z = await drawn();
        const [[a0, q0], [a1, q1]] = [z.xTicks[0], z.xTicks.at(-1)];
        assert.ok(a0 >= z0 && a1 <= z1, `zoomed ticks ${a0}..${a1}`);
        const before = (await page().$$eval('#rp-lift .rp-ev path', (ps) => ps.map((p) => p.getAttribute('d'))));
        z.markers.forEach((m) => {
          assert.ok(Math.abs(m.x - (q0 + ((m.crank - a0) * (q1 - q0)) / (a1 - a0))) < 0.05, `zoomed: ring ${m.ring} ${m.event} at x ${m.x}`);
          assert.ok(/^m0,-?6\.5l6,-?10h-12z$/.test(m.d), `zoomed: marker ${m.d} keeps its size`);
        });
        assert.equal(before.length, z.markers.length);
        await page().evaluate(async () => (await import('/static/plotui.js')).zoomTo(document.getElementById('rp-lift'), null));

        // Live without friction: no friction chart, the rest as before.
        await page().uncheck('#f-rp-friction');
        await runAnalysis('Run ringpack analysis', 120000);
        assert.equal(await page().isVisible('#error'), false, `unexpected error: ${await page().textContent('#error')}`);
        await page().waitForSelector('#rp-flow-table');
        const { result: r0 } = await shownJob();
        assert.equal(r0.scene.physics?.friction ?? null, null);
        await settled();
        await check(r0, 'no friction', { friction: false });
        await noOverflow('no friction');
        assert.deepEqual(pageErrors, []);
      } finally {
        await page().setViewportSize({ width: 1280, height: 800 });
        await page().getByRole('button', { name: 'Reset to defaults' }).click();
      }
    });
  }
}
