#!/usr/bin/env python3
"""A random scan of plausible cases for the motions that do not settle: each case that reaches no
periodic steady state gets its verdict with the numbers behind it (docs/bifurcations.md, "The
verdicts of a random scan").

    PYTHONPATH=build/python /usr/bin/python3 scripts/aperiodic_scan.py [N] [SEED]

Draws N cases (default 3000, seed 20261124) of the paper's roller with its unbalance (M0 follows
f^2) and contact that can open (contact.unilateral): G 5-100 MN/m^2 (Appendix B), f 25-70 Hz,
mu 0.2-1.0 or pure rolling (one case in four), MMd 0-0.1 M0, a circular trough R 0.603-0.615 m or
(one case in three) the paper's log spiral k 0-0.003 with a = 0.601 m; numerics.max_periods =
1500, so that a run without a steady state is examined (numerics.max_periods >= 400), and every
case independent of the others (numerics.continuation = false). Prints the
counts of the statuses, then a Markdown table of the cases without a periodic steady state
(status max_periods_reached or aperiodic): their parameters, Diagnostics.motion, the largest
Lyapunov exponent per period (lambda T) and its halves, the recurrence or convergence period, and
the verdict's evidence (analyze_motion over the same 400 periods simulate examined).
"""

import collections
import re
import sys
import time

import numpy as np

import oscidrum
from random_cases import draw_case

n = int(sys.argv[1]) if len(sys.argv) > 1 else 3000
seed = int(sys.argv[2]) if len(sys.argv) > 2 else 20261124
rng = np.random.default_rng(seed)
cases = []
for _ in range(n):
    c = draw_case(rng, 0.1)
    if rng.uniform() < 1 / 3:
        c.set("trough.k", rng.uniform(0.0, 0.003))
        c.set("trough.a", 0.601)
    else:
        c.set("trough.a", rng.uniform(0.603, 0.615))
    c.set("contact.unilateral", True)
    c.set("numerics.max_periods", 1500)
    c.set("numerics.continuation", False)  # each case alone, as simulate() runs it
    cases.append(c)

t = time.perf_counter()
outcomes = oscidrum.run_study(cases, progress=False)
print(f"{n} cases (seed {seed}) in {time.perf_counter() - t:.0f} s:")
print(" ", dict(collections.Counter(o.result.status.name for o in outcomes)))
unsettled = [(c, o.result) for c, o in zip(cases, outcomes)
             if o.result.status.name in ("max_periods_reached", "aperiodic")]
print(f"{len(unsettled)} without a periodic steady state; the study's verdicts:",
      dict(collections.Counter(r.diagnostics.motion or "-" for _, r in unsettled)))
# A study keeps no samples: each of these cases again, alone (simulate), and the examination
# simulate made of it (from its first sample over 400 or 1600 periods) again, for the numbers the
# diagnostics do not keep. The table is of these runs.
rows = []
for c, r_study in unsettled:
    r = oscidrum.simulate(c)
    # simulate examines 400 periods, and 1600 when 400 do not decide (docs/bifurcations.md).
    periods = 1600 if "(400 periods did not decide)" in r.message else 400
    rows.append((c, r, r_study, oscidrum.analyze_motion(c, r, periods=periods)))
print("verdicts of the same cases run alone:",
      dict(collections.Counter(r.diagnostics.motion or r.status.name for _, r, _, _ in rows)))
differ = [(c, r, rs) for c, r, rs, _ in rows
          if (r.status.name, r.diagnostics.motion) != (rs.status.name, rs.diagnostics.motion)]
for c, r, rs in differ:
    print(f"  G = {c.get('soil.G') / 1e6:.1f} MN/m^2, f = {c.get('roller.f'):.1f} Hz: "
          f"{rs.status.name}/{rs.diagnostics.motion} in the study, "
          f"{r.status.name}/{r.diagnostics.motion} alone")
print()
print("| G [MN/m^2] | f [Hz] | mu | MMd [N m] | trough | status | verdict | lambda T | halves "
      "| p | evidence |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for c, r, _, m in sorted(rows, key=lambda x: (x[1].diagnostics.motion, x[0].get("soil.G"))):
    T = 1.0 / c.get("roller.f")
    p = m.recurrence or m.converging_period
    mu = "rolling" if c.get("contact.pure_rolling") else f"{c.get('contact.mu'):.2f}"
    trough = (f"spiral k={c.get('trough.k'):.4f}" if c.get("trough.k") > 0
              else f"circle R={c.get('trough.a'):.3f}")
    # The evidence in words, its numbers to 4 digits.
    evidence = re.sub(r"-?\d+\.\d{5,}(e-?\d+)?", lambda x: f"{float(x.group()):.4g}", m.evidence)
    evidence = evidence.replace("|", "\\|")
    print(f"| {c.get('soil.G') / 1e6:.1f} | {c.get('roller.f'):.1f} | {mu} | "
          f"{c.get('MMd'):.0f} | {trough} | {r.status.name} | {r.diagnostics.motion or '-'} | "
          f"{r.diagnostics.lyapunov_exponent * T:.4f} | "
          f"{m.lyapunov_first * T:.4f}, {m.lyapunov_second * T:.4f} | {p or '-'} | {evidence} |")
