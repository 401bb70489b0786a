/* lift_battery.h — the synthetic scenes of the lift model battery, shared by
 * test_lift_auto, test_lift_rigid and bench_lift_friction so that the bench
 * measures the scenes the tests check.  Header-only; static inline functions.
 *
 * The firing pulse (the shape of the gas example's): 58 bar gauge peak at
 * 20 deg above the ring, the groove back 2 deg later, the second land 30 %
 * of it 20 deg later, tabulated every 2 deg over 0..720. */
#ifndef RD_LIFT_BATTERY_H
#define RD_LIFT_BATTERY_H

#include <math.h>

#include "rd_lift.h"

#define LIFT_BATTERY_GAS_POINTS 361

static double lift_battery_gas[4][LIFT_BATTERY_GAS_POINTS];

/* The firing pulse as p's gas tables (static storage, shared), `area` its
 * active areas (enum rd_gas_area). */
static inline void lift_battery_gas_tables(rd_lift_params *p, int area)
{
    double(*t)[LIFT_BATTERY_GAS_POINTS] = lift_battery_gas;
    for (int i = 0; i < LIFT_BATTERY_GAS_POINTS; i++) {
        double d = 2.0 * i;
        t[0][i] = d;
        t[1][i] = 58e5 * exp(-pow((d - 20.0) / 25.0, 2));
        t[2][i] = 58e5 * exp(-pow((d - 22.0) / 25.0, 2));
        t[3][i] = 0.3 * 58e5 * exp(-pow((d - 40.0) / 30.0, 2));
    }
    p->gas = (rd_gas_params){LIFT_BATTERY_GAS_POINTS, t[0], t[1], t[2], t[3], area};
}

/* One battery scene: the thesis ring's defaults, `rpm`, axial clearance
 * `ca`, gravity, friction model `fric`, the pulse with dynamic areas if
 * `gas`, one cycle sampled every `step_deg`, no estimate; atol scales with
 * the clearance (1e-3 rtol c_a / 30 um). */
static inline void lift_battery_scene(rd_lift_params *p, double rpm, double ca, int gas, int fric,
                                      double rtol, double step_deg)
{
    rd_lift_params_default(p);
    p->engine.speed_rpm = rpm;
    p->engine.cycles = 1.0;
    p->groove.axial_clearance = ca;
    p->gravity = 1;
    p->friction.model = fric;
    p->estimate_error = 0;
    p->step_deg = step_deg;
    p->rtol = rtol;
    p->atol = 1e-3 * rtol * ca / 3e-5;
    if (gas)
        lift_battery_gas_tables(p, RD_GAS_AREA_DYNAMIC);
}

#endif
