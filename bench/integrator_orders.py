#!/usr/bin/env python3
"""Steps and right-hand sides per period of a steady orbit: Dormand-Prince 5(4) against 8(5,3).

The measurement that made oscidrum change from 5(4) (the paper's ode45) to 8(5,3).

The performance issue's cases from rest and warm cases are bounded by the number of integration
steps per excitation period (about 100 Dormand-Prince 5(4) steps at numerics.rtol = 1e-8). This
script measures what an integrator of higher order would save on the model's own equations: it
takes the steady orbit oscidrum computes, and integrates each phase of one period (stick, slip-,
stick, slip+; from switch to switch, as the flow restarts at each switch) with SciPy's RK45
(Dormand-Prince 5(4)) and DOP853 (Dormand-Prince 8(5,3), oscidrum's method now) at oscidrum's rtol
and atol, the right-hand side being oscidrum.accelerations. Each phase's start state is the
orbit's state at its switch (integrated back from the nearest sample at rtol 1e-13), and each
method's error is its end state's against an integration at rtol 1e-13 (largest component error
over atol + rtol |y|, the error controller's own norm).

    PYTHONPATH=build/python /usr/bin/python3 bench/integrator_orders.py

Needs python3-scipy (apt-get install python3-scipy) and the Python module (scripts/build.sh).
"""
import sys

import numpy as np

try:
    from scipy.integrate import solve_ivp
except ImportError:
    sys.exit("bench/integrator_orders.py: needs python3-scipy (apt-get install python3-scipy)")
import oscidrum as o

STATE = ("delta", "phi", "x_A", "s_A", "ddelta", "dphi", "dx_A", "ds_A")


def rhs_for(model, phase, beta):
    def rhs(t, y):
        q = o.State(**dict(zip(STATE, y)))
        a = o.accelerations(model, t, q, phase, beta)
        return [y[4], y[5], y[6], y[7], a.delta, a.phi, a.x_A, a.s_A]

    return rhs


def pieces(result, period):
    """(t0, t1, phase, y0) of each phase of the first sampled period."""
    s = result.samples
    t = np.asarray(s.t)
    t_start, t_end = t[0], t[0] + period
    switches = [e for e in result.events if t_start <= e.t < t_end]
    if not switches:  # pure rolling: one piece, the whole period
        y0 = [float(getattr(s, n)[0]) for n in STATE]
        return [(t_start, t_end, o.Phase(int(s.phase[0])), y0)]
    bounds = [e.t for e in switches] + [switches[0].t + period]
    out = []
    for e, t1 in zip(switches, bounds[1:]):
        j = int(np.searchsorted(t, e.t))
        out.append((e.t, t1, e.to_phase, j))
    return out


def main():
    cases = [
        ("stick-slip, the paper's defaults", o.Case()),
        ("stick-slip, MMd = 0.05 M0, G = 50 MN/m^2", o.Case(G=50e6, MMd_fraction=0.05)),
        ("pure rolling", o.Case(pure_rolling=True)),
    ]
    num = o.Numerics()
    print(f"rtol {num.rtol:g}, atol {num.atol:g}; per excitation period:")
    print("| case | oscidrum DP5: steps / RHS | RK45: steps / RHS / error | "
          "DOP853: steps / RHS (+ 3 per step for its dense output) / error |")
    print("|---|---:|---:|---:|")
    for name, case in cases:
        model = o.Model(case)
        r = o.simulate(case)
        if r.status != o.Status.steady_state:
            print(f"| {name} | {r.status.name} | | |")
            continue
        d = r.diagnostics
        s = r.samples
        period = 1.0 / r.frequency
        beta = num.slip_constraint_rate
        counts = {"RK45": [0, 0, 0.0], "DOP853": [0, 0, 0.0]}
        for t0, t1, phase, start in pieces(r, period):
            f = rhs_for(model, phase, beta)
            if isinstance(start, int):  # the state at the switch, from the sample after it
                y = [float(getattr(s, n)[start]) for n in STATE]
                y0 = solve_ivp(f, [s.t[start], t0], y, method="DOP853", rtol=1e-13,
                               atol=1e-16).y[:, -1]
            else:
                y0 = np.asarray(start)
            ref = solve_ivp(f, [t0, t1], y0, method="DOP853", rtol=1e-13, atol=1e-16).y[:, -1]
            for method, c in counts.items():
                sol = solve_ivp(f, [t0, t1], y0, method=method, rtol=num.rtol, atol=num.atol)
                c[0] += len(sol.t) - 1
                c[1] += sol.nfev
                err = np.abs(sol.y[:, -1] - ref) / (num.atol + num.rtol * np.abs(ref))
                c[2] = max(c[2], float(err.max()))
        n = d.periods_simulated
        rk, dp = counts["RK45"], counts["DOP853"]
        print(f"| {name} | {d.steps / n:.0f} / {d.rhs_evaluations / n:.0f} | "
              f"{rk[0]} / {rk[1]} / {rk[2]:.2g} | "
              f"{dp[0]} / {dp[1]} ({dp[1] + 3 * dp[0]}) / {dp[2]:.2g} |")


if __name__ == "__main__":
    main()
