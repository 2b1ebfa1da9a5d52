#!/usr/bin/env python3
"""A random scan of plausible cases: which end in contact_lost with the paper's permanent contact,
and what the same cases give with contact.unilateral (docs/lift-off.md).

    PYTHONPATH=build/python /usr/bin/python3 scripts/contact_lost_scan.py [N] [SEED]

Draws N cases (default 1500): G 5-100 MN/m^2 (Appendix B), f 25-70 Hz with the paper's unbalance
(M0 follows f^2), mu 0.2-1.0 or pure rolling (one case in four), MMd 0-0.2 M0, circular trough
R 0.603-0.65 m. Prints the counts of the statuses with permanent contact, then, for the cases that
lost contact, the statuses and contact modes with unilateral contact; for those that still stop
in pure rolling, what a friction coefficient mu = 1 ... 10 makes of them.
"""

import collections
import sys
import time

import numpy as np

import oscidrum
from random_cases import draw_case

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1500
rng = np.random.default_rng(int(sys.argv[2]) if len(sys.argv) > 2 else 20261124)
cases = []
for _ in range(n):
    c = draw_case(rng, 0.2)
    c.set("trough.a", rng.uniform(0.603, 0.65))
    c.set("numerics.max_periods", 3000)
    cases.append(c)

t = time.perf_counter()
plain = oscidrum.run_study(cases, progress=False)
print(f"{n} cases with permanent contact in {time.perf_counter() - t:.0f} s:")
print(" ", dict(collections.Counter(o.result.status.name for o in plain)))
lost = [c for c, o in zip(cases, plain) if o.result.status.name == "contact_lost"]
for c in lost:
    c.set("contact.unilateral", True)
t = time.perf_counter()
again = oscidrum.run_study(lost, progress=False)
print(f"the {len(lost)} that lost contact, with contact.unilateral, in "
      f"{time.perf_counter() - t:.0f} s:")
print(" ", dict(collections.Counter(o.result.status.name for o in again)))
print("  contact modes:", dict(collections.Counter(
    o.result.diagnostics.contact_mode or o.result.status.name for o in again)))
still = [o for o in again if o.result.status.name == "contact_lost"]
if still:
    print("  still contact_lost:", dict(collections.Counter(
        "pure rolling" if "pure_rolling" in o.result.message else
        ("clearance" if "clearance" in o.result.message else "other") for o in still)))

# The pure-rolling cases that still stop: are they lift-offs that a friction limit would let
# happen? Run each again with a friction coefficient mu, with permanent and with unilateral contact.
pure = [c for c, o in zip(lost, again)
        if o.result.status.name == "contact_lost" and "pure_rolling" in o.result.message]
if pure:
    print(f"the {len(pure)} pure-rolling cases that stop, with a friction coefficient instead:")
    for mu in (1.0, 2.0, 3.0, 4.0, 5.0, 10.0):
        for unilateral in (False, True):
            for c in pure:
                c.set("contact.pure_rolling", False)
                c.set("contact.mu", mu)
                c.set("contact.unilateral", unilateral)
            runs = oscidrum.run_study(pure, progress=False)
            counts = dict(collections.Counter(
                "contact_lost (singular slip)" if "slip equations became singular" in
                o.result.message and o.result.status.name == "contact_lost"
                else o.result.status.name for o in runs))
            flying = sum(1 for o in runs if o.ok and o.metrics.flight_fraction > 0.0)
            print(f"  mu = {mu:g}, {'unilateral' if unilateral else 'permanent '} contact: "
                  f"{counts}; with flight: {flying}")
