"""A bifurcation diagram of the paper's roller: the periodic orbits followed through the soil's
shear modulus on the paper's log-spiral trough, where the period doubles (docs/bifurcations.md).

    /usr/bin/python3 examples/bifurcation_diagram.py [OUT_DIR]

The roller with its unbalance at 25 Hz, mu = 0.7, trough k = 0.002, a = 0.601 m, soil by
Appendix B, G from 100 to 300 MN/m^2. oscidrum.continue_branch follows the period-1 orbit,
stable or not, locates the period doubling and follows the period-2 branch born there. Beside
the branches, the brute-force diagram (oscidrum.bifurcation_diagram): the stroboscopic points of
x_M'' at a row of G, one point per G where the period-1 orbit is stable, two where the period-2
orbit is. Writes bifurcation_diagram.png into OUT_DIR (default: the current
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

# The brute-force view (oscidrum.bifurcation_diagram, `oscidrum diagram`): the motion swept up
# through G, each value started from the previous one's final state; its stroboscopic points of
# x_M'' (one per period on the period-1 orbit, two on the period-2 one).
diagram = oscidrum.bifurcation_diagram(case, "soil.G", 110e6, 290e6, steps=9)
points = diagram["points"]
ax.plot(np.asarray(points["parameter"]) / 1e6, points["ddx_M"], "o", color="tab:blue",
        markersize=3, label="x_M'' at t0 + k T (oscidrum diagram)")
for G, verdict, p in zip(diagram["values"]["parameter"], diagram["values"]["verdict"],
                         diagram["values"]["period"]):
    print(f"G = {G / 1e6:.0f} MN/m^2: {verdict}, period {int(p)}")
ax.set_xlabel("shear modulus G [MN/m^2]")
ax.set_ylabel("peak x_M'' (lines), x_M'' at the section (points) [m/s^2]")
ax.legend(fontsize="small", loc="upper left")
ax.set_title("log-spiral trough k = 0.002, 25 Hz, mu = 0.7: a period doubling")
out.mkdir(parents=True, exist_ok=True)
fig.savefig(out / "bifurcation_diagram.png", dpi=120)
print(out / "bifurcation_diagram.png")
