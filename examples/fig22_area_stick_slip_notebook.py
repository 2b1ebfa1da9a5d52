# %% [markdown]
# # Paper Fig. 22: area inside the z_M''-x_M'' figure, stick-slip
#
# Paulmichl, Adam & Adam (2019) simulate the HAMM HD+ 90 VO oscillation drum on the soils of
# their Table 2 (G = 5 ... 70 MN/m^2) with Coulomb friction mu = 0.5, with and without a driving
# torque MMd = 0.05 M0. They report that the area inside the z_M''-x_M'' figure
#
# * decreases continuously with G for MMd = 0, and
# * has a minimum at G = 20 and a maximum at G = 45 MN/m^2 for MMd = 0.05 M0.
#
# This is a notebook-style script: run it whole (`/usr/bin/python3 examples/...py [OUT_DIR]`) or
# cell by cell (`# %%`) in an editor or Jupyter (with jupytext).

# %%
import sys
from pathlib import Path

import numpy as np

import oscidrum
from oscidrum import plot

out = Path(sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else ".")
out.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## The cases
# The library defines every series of the paper (`oscidrum.paper_series()`, the same cases that
# `oscidrum validate` checks): here the two stick-slip series on the circular trough
# R = 0.606 m, mu = 0.5, with MMd = 0 and 0.05 M0. `paper_case(series, G)` gives the Case of one
# Table 2 soil.

# %%
series = {s.MMd_fraction: s for s in oscidrum.paper_series()
          if s.id in ("stickslip_MMd0_R0.606", "stickslip_MMd0.05_R0.606")}
print(series[0.05])
G_values = np.array(series[0.0].G)  # [Pa]
cases = {f: [oscidrum.paper_case(s, G) for G in s.G] for f, s in series.items()}
print(cases[0.05][0])

# %% [markdown]
# ## Run the study
# `run_study` runs the cases on C++ threads with the GIL released. `keep_samples=True` keeps
# the steady states so that we can also look at the curves themselves.

# %%
outcomes = {f: oscidrum.run_study(c, keep_samples=True) for f, c in cases.items()}
for f, outs in outcomes.items():
    bad = [o for o in outs if not o.ok]
    assert not bad, [o.result.message for o in bad]
area = {f: np.array([o.metrics.area for o in outs]) for f, outs in outcomes.items()}  # [m^2/s^4]

# %% [markdown]
# ## The figure and the paper's statements
# The library checks these statements, with every other one the paper makes, in
# `oscidrum.validate(oscidrum.run_paper_studies())` (rows `fig22.*`; `python3 -m oscidrum.paper`
# puts them beside the figure). Here we look at the numbers ourselves.

# %%
fig = plot.plot_sweep(G_values, {"MMd = 0": area[0.0], "MMd = 0.05 M0": area[0.05]}, "soil.G",
                      "area", title="Fig. 22: stick-slip, mu = 0.5")
print(plot.save(fig, out / "fig22_area_stick_slip.png"))

decreasing = bool(np.all(np.diff(area[0.0]) < 0))
a = area[0.05]
interior_minima = [G_values[i] / 1e6 for i in range(1, len(a) - 1) if a[i] < a[i - 1] and
                   a[i] < a[i + 1]]
print(f"MMd = 0: area decreasing with G: {decreasing}")
print(f"MMd = 0.05 M0: local minima at G = {interior_minima} MN/m^2, largest area at "
      f"G = {G_values[np.argmax(a)] / 1e6:g} MN/m^2")

# %% [markdown]
# ## Behind the numbers: the z_M''-x_M'' figures of four soils

# %%
pick = [i for i, G in enumerate(G_values) if G in (5e6, 25e6, 50e6, 70e6)]
states = [outcomes[0.05][i] for i in pick]
labels = [f"G = {G_values[i] / 1e6:g} MN/m²" for i in pick]
fig = plot.plot_figure_eight(states, labels, title="Fig. 21b: stick-slip, MMd = 0.05 M0")
print(plot.save(fig, out / "fig21b_figure_eight.png"))
