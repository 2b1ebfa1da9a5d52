"""A bifurcation diagram of the paper's roller: the periodic orbits followed through the soil's
shear modulus on the paper's log-spiral trough, where the period doubles (docs/bifurcations.md).

    /usr/bin/python3 examples/bifurcation_diagram.py [OUT_DIR]

The roller with its unbalance at 25 Hz, mu = 0.7, trough k = 0.002, a = 0.601 m, soil by
Appendix B, G from 100 to 300 MN/m^2. oscidrum.continue_branch follows the period-1 orbit,
stable or not, locates the period doubling and follows the period-2 branch born there. Beside
the branches, the stroboscopic points of the motion at a few G (oscidrum.analyze_motion): one
point per G where the period-1 orbit is stable, two where the period-2 orbit is (the brute-force
view of the same diagram). Writes bifurcation_diagram.png into OUT_DIR (default: the current
directory) and prints the bifurcations.
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import oscidrum  # noqa: E402

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
case = oscidrum.Case()
for key, value in {"soil.input": "modulus", "trough.k": 0.002, "trough.a": 0.601,
                   "contact.mu": 0.7, "roller.f": 25.0, "roller.unbalance": 0.22877}.items():
    case.set(key, value)

branch = oscidrum.continue_branch(case, "soil.G", 100e6, 300e6)
for b in [branch, *branch["children"]]:
    for f in b["bifurcations"]:
        print(f"period {b['multiplicity']}: {f['kind']} at G = {f['parameter'] / 1e6:.4f} MN/m^2 "
              f"(+- {f['tolerance']:.0f} Pa): {f['description']}")

fig, ax = plt.subplots(figsize=(7, 4.2), layout="constrained")
for b, color in [(branch, "black"), *[(c, "tab:red") for c in branch["children"]]]:
    p = b["points"]
    G = np.asarray(p["parameter"]) / 1e6
    x = np.asarray(p["ddx_max"])
    stable = np.asarray(p["stable"]) > 0.5
    for k in range(len(G) - 1):  # solid where stable, dashed where not
        ax.plot(G[k:k + 2], x[k:k + 2], color=color, linestyle="-" if stable[k] else "--")
    ax.plot([], [], color=color, label=f"period {b['multiplicity']} T (dashed: unstable)")

# The brute-force view: where does the motion started from rest end up? Its stroboscopic points
# (delta, the drum's position angle, once per excitation period) over 40 periods.
G_points = np.linspace(110e6, 290e6, 7)
for G in G_points:
    c = oscidrum.Case(**{k: case.get(k) for k in ("trough.k", "trough.a", "contact.mu",
                                                 "roller.f", "roller.unbalance")})
    c.set("soil.input", "modulus")
    c.set("soil.G", G)
    r = oscidrum.simulate(c)
    section = oscidrum.analyze_motion(c, r, periods=40).section
    distinct = np.unique(np.round(section[-20:, 0], 6))
    ax2 = ax.twinx() if G == G_points[0] else ax2
    ax2.plot(np.full(len(distinct), G / 1e6), distinct, "o", color="tab:blue", markersize=4)
ax2.set_ylabel("stroboscopic delta [rad] (blue points)")
ax.set_xlabel("shear modulus G [MN/m^2]")
ax.set_ylabel("peak x_M'' [m/s^2]")
ax.legend(fontsize="small", loc="upper left")
ax.set_title("log-spiral trough k = 0.002, 25 Hz, mu = 0.7: a period doubling")
out.mkdir(parents=True, exist_ok=True)
fig.savefig(out / "bifurcation_diagram.png", dpi=120)
print(out / "bifurcation_diagram.png")
