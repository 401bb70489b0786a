// Hand-made result objects for the renderers of static/pretension.js,
// contact.js and lift.js, shaped as API.md describes them: the renderers are
// pure functions of the result, so these check what is drawn without the
// server, including results that lack the optional fields.  The numbers are
// plausible for the thesis ring, not computed.

const D = 0.0765, B = 0.0029, H = 0.0012, FT = 10;
const R = (D - B) / 2;
const rad = (deg) => (deg * Math.PI) / 180;
const ring = { diameter: D, radial_width: B, axial_height: H, closed_gap: 0.0003, tangential_force: FT };

// Free shape of a 20-segment ring: the closed ring opened by spreading the
// angles away from the side opposite the gap; z twists the ends apart.
export function pretensionResult({ lateral = 0 } = {}) {
  const n = 20;
  const t0 = 0.0003 / (2 * R); // half the closed gap, rad
  const angle = [(t0 * 180) / Math.PI, ...Array.from({ length: n }, (_, i) => (i + 0.5) * (360 / n)), 360 - (t0 * 180) / Math.PI];
  const spread = 0.04;
  const free = angle.map((a) => Math.PI + (rad(a) - Math.PI) * (1 - spread));
  const xc = lateral > 0 ? 2.4e-4 * lateral : 0;
  return {
    analysis: 'pretension',
    scene: { analysis: 'pretension', ring, discretization: { segments: n, closed: false }, pretension: { method: 'force', lateral_force: lateral } },
    gap_opening_inner: 0.0092137,
    lateral_opening: xc,
    gap_opening_neutral: 0.0094412,
    free_gap_formula: 0.0090518,
    conformability: 0.0214,
    support: { force_n: 1.2e-9, moment_nm: 3.4e-11 },
    // an inner bevel on the top edge: 0.6 x 0.4 mm off the 2.9 x 1.2 mm box
    section: {
      shape: 'general', area_m2: 3.36e-6, centroid_m: [0.0368, 0.00058], principal_angle_deg: -2.1,
      outline_m: [[0, 0], [0.0029, 0], [0.0029, 0.0012], [0.0006, 0.0012], [0, 0.0008]],
    },
    shape: {
      angle_deg: angle,
      x: free.map((t) => R * Math.cos(t)),
      y: free.map((t) => R * Math.sin(t)),
      z: angle.map((a) => (xc / 2) * Math.cos(rad(a) / 2)),
      reference_x: angle.map((a) => R * Math.cos(rad(a))),
      reference_y: angle.map((a) => R * Math.sin(rad(a))),
    },
    free_shape_model: 'stress_free_closed',
    free_shape: {
      theta_deg: free.map((t) => ((t * 180) / Math.PI) - 180),
      radius_m: free.map((t) => D / 2 + 0.0004 * (1 - Math.cos(t - Math.PI))),
      free_gap_m: 0.0096, tangential_force_n: FT,
    },
    numerics: {
      segments: n, dof: 6 * n, wall_s: 0.0123, solver: 'Newton, banded LU (dgbsv)', load_steps: 4, iterations: 17,
      residual: 3.1e-12, tolerance: 1e-9, reference_segments: 40, error_estimate: 0.0042, error_method: 'Richardson, n and 2n',
    },
  };
}

// A ring in a bore with a 4th-order distortion beyond what it follows: the
// segments where 1 + 1.3 cos 4θ < 0 lift off (light gaps).
export function contactResult() {
  const n = 24;
  const p0 = (2 * FT) / (D * H);
  const angle = Array.from({ length: n }, (_, i) => (i + 0.5) * (360 / n));
  const q = angle.map((a) => 1 + 1.3 * Math.cos(4 * rad(a)));
  const pressure = q.map((v) => Math.max(0, v) * p0);
  const clearance = q.map((v) => (v < 0 ? -v * 2e-6 : -1e-9 * v));
  const light = clearance.map((c, i) => [c, i]).filter(([c]) => c > 0);
  const [maxC, maxI] = light.reduce((m, e) => (e[0] > m[0] ? e : m), [0, -1]);
  return {
    analysis: 'contact',
    scene: { analysis: 'contact', ring, discretization: { segments: n, closed: false }, bore: { diameter: D, distortion: [{ order: 4, amplitude: 8e-6, phase_deg: 0 }] } },
    angle_deg: angle,
    pressure_pa: pressure,
    clearance,
    bore_radius: angle.map((a) => D / 2 + 8e-6 * Math.cos(4 * rad(a))),
    mean_pressure_pa: pressure.reduce((s, v) => s + v, 0) / n,
    uniform_pressure_pa: p0,
    contact_fraction: 1 - light.length / n,
    max_clearance: maxC,
    max_clearance_angle_deg: angle[maxI],
    max_penetration: 2.1e-8,
    contact_stiffness: 1.05e13,
    conformability: 0.0214,
    distortion: [{ order: 4, amplitude: 8e-6, phase_deg: 0, conformability_bound: 2.5e-6 }],
    numerics: { segments: n, dof: 6 * n, wall_s: 0.21, solver: 'Newton, banded LU (dgbsv)', load_steps: 6, iterations: 41, residual: 2e-11, tolerance: 1e-9, error_estimate: 0.011, reference_segments: 48 },
  };
}

// One cycle at 1 deg: seated, lifted to the upper flank around 180-360 deg,
// a free excursion around 540-640 deg that dips into the lower flank band
// without touching the flank (600-605 deg) before it lands.  The events are
// dated as the server dates them with output.flank_band = band: where the
// mean lift crosses the band's edge (band * clearance from a flank; with
// band 0, at the flank), each with touch_deg where the lift itself touched
// or left the flank (null: it never touched in between).
export function liftResult({ friction = true, band = 0.01 } = {}) {
  const clearance = 3e-5;
  const crank = Array.from({ length: 721 }, (_, i) => i);
  const ramp = (a, a0, a1) => Math.min(1, Math.max(0, (a - a0) / (a1 - a0)));
  const lerp = (a, a0, a1, l0, l1) => l0 + (l1 - l0) * ramp(a, a0, a1);
  const dip = 1.5e-7; // inside a band of 1 % (3e-7), off the flank
  const lift = crank.map((a) => {
    if (a < 170) return 0;
    if (a < 200) return clearance * ramp(a, 170, 200);
    if (a < 360) return clearance;
    if (a < 390) return clearance * (1 - ramp(a, 360, 390));
    if (a < 540) return 0;
    if (a < 570) return lerp(a, 540, 570, 0, 1.5e-5);
    if (a < 600) return lerp(a, 570, 600, 1.5e-5, dip);
    if (a < 605) return dip;
    if (a < 620) return lerp(a, 605, 620, dip, 5e-6);
    if (a < 640) return lerp(a, 620, 640, 5e-6, 0);
    return 0;
  });
  const edge = (band > 0 ? band : 0.01) * clearance; // the flank column's threshold
  const flank = lift.map((l) => (l < edge ? 'lower' : l > clearance - edge ? 'upper' : 'free'));
  // Events from the samples: the band's state changes where the lift crosses
  // an edge (linear between samples, to 0.1 deg); band 0: at the flank.
  const e = band * clearance;
  const state = (l) => (band > 0 ? (l < e ? 'lower' : l > clearance - e ? 'upper' : 'free') : (l <= 0 ? 'lower' : l >= clearance ? 'upper' : 'free'));
  const atFlank = (l, side) => (side === 'lower' ? l <= 0 : l >= clearance);
  const KIND = { 'lower>free': 'leave_lower', 'free>upper': 'reach_upper', 'upper>free': 'leave_upper', 'free>lower': 'reach_lower' };
  const events = [];
  let touched = true, lastAt = 0, landing = null;
  for (let i = 1; i < crank.length; i++) {
    const from = state(lift[i - 1]), to = state(lift[i]);
    if (from !== 'free' && atFlank(lift[i - 1], from)) { touched = true; lastAt = crank[i - 1]; }
    if (landing && atFlank(lift[i], to)) { landing.touch_deg = crank[i]; landing = null; touched = true; lastAt = crank[i]; }
    const k = KIND[`${from}>${to}`];
    if (!k) continue;
    const level = k.endsWith('lower') ? (band > 0 ? e : 0) : clearance - (band > 0 ? e : 0);
    const t = (level - lift[i - 1]) / (lift[i] - lift[i - 1]);
    const at = Math.round((crank[i - 1] + t * (crank[i] - crank[i - 1])) * 10) / 10;
    if (k.startsWith('leave')) {
      events.push({ crank_deg: at, event: k, touch_deg: band > 0 ? (touched ? lastAt : null) : at });
      touched = false;
      landing = null;
    } else {
      const ev = { crank_deg: at, event: k, touch_deg: band > 0 ? null : at };
      events.push(ev);
      if (band > 0) landing = ev;
      if (band > 0 && atFlank(lift[i], to)) { ev.touch_deg = crank[i]; landing = null; touched = true; lastAt = crank[i]; }
    }
  }
  const spread = lift.map((l, i) => (flank[i] === 'free' ? 2e-6 : 0));
  const scene = { analysis: 'lift', ring, engine: { speed_rpm: 1000, cycles: 1 }, groove: { axial_clearance: clearance, radial_clearance: 5e-4 }, physics: { gravity: false }, output: { step_deg: 1, flank_band: band } };
  if (friction) scene.physics.friction = { model: 'coulomb', coefficient: 0.1 };
  return {
    analysis: 'lift',
    scene,
    crank_deg: crank,
    lift,
    lift_min: lift.map((l, i) => Math.max(0, l - spread[i])),
    lift_max: lift.map((l, i) => Math.min(clearance, l + spread[i])),
    lift_segments: lift.map((l) => [l, l, l, l]),
    twist_rad: lift.map(() => 0),
    friction_force: crank.map((a) => (friction ? 1.5 * Math.sin(rad(2 * a)) : 0)),
    flank,
    events,
    numerics: { segments: 4, dof: 24, wall_s: 1.7, solver: 'CVODE BDF, banded', steps: 5123, rhs_evals: 7012, jac_evals: 88, error_test_fails: 41, nonlinear_iterations: 6900, root_evals: 5200, error_estimate: 0.003, event_error_deg: 0.02, flank_band: band },
  };
}

// The same results with only the fields API.md lists as always present.
export function minimal(result) {
  switch (result.analysis) {
    case 'pretension':
      return { analysis: 'pretension', gap_opening_inner: result.gap_opening_inner, lateral_opening: result.lateral_opening, numerics: {} };
    case 'contact':
      return {
        analysis: 'contact', angle_deg: result.angle_deg, pressure_pa: result.pressure_pa,
        mean_pressure_pa: result.mean_pressure_pa, uniform_pressure_pa: result.uniform_pressure_pa,
        contact_fraction: result.contact_fraction, max_clearance: result.max_clearance,
      };
    case 'lift':
      return { analysis: 'lift', crank_deg: result.crank_deg, lift: result.lift, flank: result.flank, events: result.events };
    default:
      throw new Error(`no minimal form of ${result.analysis}`);
  }
}

// Gas tables (Pa against crank angle, one 720° cycle) and a two-cycle lift
// result driven by them: the peak above the ring (60 bar at 360°) comes back
// at 1080°.
export const GAS = {
  crank_deg: [0, 180, 360, 380, 540, 720],
  above: [1e5, 2e5, 60e5, 40e5, 3e5, 1e5],
  behind: [1e5, 1.8e5, 45e5, 35e5, 2.5e5, 1e5],
  below: [1e5, 1.2e5, 8e5, 8e5, 1.5e5, 1e5],
  active_area: 'fixed',
};

export function liftGasResult() {
  const one = liftResult({ friction: false });
  const two = { ...one, scene: { ...one.scene, engine: { speed_rpm: 1000, cycles: 2 }, physics: { gravity: false, gas: GAS } } };
  two.crank_deg = [...one.crank_deg, ...one.crank_deg.slice(1).map((c) => c + 720)];
  for (const k of ['lift', 'lift_min', 'lift_max', 'flank', 'friction_force']) two[k] = [...one[k], ...one[k].slice(1)];
  two.lift_segments = two.lift.map((l) => [l, l, l, l]);
  two.twist_rad = two.lift.map(() => 0);
  two.events = [...one.events, ...one.events.map((e) => ({ ...e, crank_deg: e.crank_deg + 720, touch_deg: e.touch_deg === null ? null : e.touch_deg + 720 }))];
  return two;
}

// A round bore: the pressure within about ±1 % of p0, the ripple near the gap.
export function contactRoundResult() {
  const r = contactResult();
  const n = r.angle_deg.length;
  const p0 = r.uniform_pressure_pa;
  const q = r.angle_deg.map((a) => 1 + 0.01 * Math.cos(rad(3 * a)) * Math.exp(-((Math.min(a, 360 - a) / 40) ** 2)));
  const pressure = q.map((v) => v * p0);
  return {
    ...r,
    scene: { ...r.scene, bore: { diameter: D } },
    pressure_pa: pressure,
    clearance: q.map((v) => -1e-9 * v),
    bore_radius: r.angle_deg.map(() => D / 2),
    mean_pressure_pa: pressure.reduce((s, v) => s + v, 0) / n,
    contact_fraction: 1,
    max_clearance: 0,
    max_clearance_angle_deg: undefined,
    distortion: [],
  };
}

// A ring pack of three rings over one cycle at 2 deg (the shape of
// api/rd_an_ringpack.c's result): ring 1 (30 µm clearance) lifts to its upper
// flank around 90-300 deg, ring 2 (40 µm) hops half-way, ring 3 (40 µm) stays
// seated.  The flank band, when not null, is numerics.flank_band.
export function ringpackResult({ band = 0.01, periodic } = {}) {
  const crank = Array.from({ length: 361 }, (_, i) => 2 * i);
  const ramp = (a, a0, a1) => Math.min(1, Math.max(0, (a - a0) / (a1 - a0)));
  const cas = [3e-5, 4e-5, 4e-5];
  const lifts = [
    crank.map((a) => cas[0] * (ramp(a, 80, 100) - ramp(a, 290, 310))),
    crank.map((a) => 2e-5 * Math.sin(Math.PI * ramp(a, 300, 400))),
    crank.map(() => 0),
  ];
  const names = ['cylinder', 'top_land', 'groove_1', 'second_land', 'groove_2', 'third_land', 'groove_3', 'crankcase'];
  const cylinder = crank.map((a) => 1e5 + 59e5 * Math.exp(-(((a - 375) / 40) ** 2)));
  const volumes = names.map((name, k) => ({ name, pressure_pa: cylinder.map((p) => 1e5 + (p - 1e5) / (1 + 3 * k)) }));
  const flankOf = (l, ca) => (l < 0.01 * ca ? 'lower' : l > 0.99 * ca ? 'upper' : 'free');
  const rings = lifts.map((lift, i) => ({
    lift,
    flank: lift.map((l) => flankOf(l, cas[i])),
    events: [],
    friction_n: lift.map(() => 0),
  }));
  rings[0].events = [
    { crank_deg: 80.2, event: 'leave_lower', touch_deg: 80 }, { crank_deg: 99.8, event: 'reach_upper', touch_deg: 100 },
    { crank_deg: 290.2, event: 'leave_upper', touch_deg: 290 }, { crank_deg: 309.8, event: 'reach_lower', touch_deg: 310 },
  ];
  const scene = {
    analysis: 'ringpack', engine: { speed_rpm: 2400, cycles: 2 },
    rings: cas.map((ca) => ({ ring, groove: { axial_clearance: ca, radial_clearance: 5e-4 }, land: { height: 0.005, radial_clearance: 4e-4 } })),
    output: { step_deg: 2 },
  };
  if (band !== null) scene.output.flank_band = band;
  const model = { name: 'axial', dof: 1, modes: 0, why: 'auto: an axisymmetric pack ring without friction' };
  return {
    analysis: 'ringpack',
    scene,
    crank_deg: crank,
    volumes,
    rings,
    flows: [{ name: 'ring_3_end_gap', from: 'third_land', to: 'crankcase', mass_flow_kg_s: crank.map((a) => 2e-5 * Math.exp(-(((a - 380) / 50) ** 2))) }],
    blowby: { kg_per_cycle: 1.4e-6, l_per_min: 1.39, reverse_kg_per_cycle: 2.9e-5, inflow_kg_per_cycle: 3.0e-5, mass_balance_residual: 6e-10 },
    periodicity: 0.004,
    ...(periodic !== undefined ? { periodic_reached: periodic } : {}),
    numerics: {
      model: [model, model, model], steps: 1200, restarts: 8, cycles: 2, wall_s: 0.37, error_estimate: null, event_error_deg: null,
      ...(band !== null ? { flank_band: band } : {}),
    },
    warnings: [],
  };
}
