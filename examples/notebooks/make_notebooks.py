#!/usr/bin/env python3
"""Write the example notebooks (*.ipynb) of this folder from the cells below, without outputs.
Edit the cells here and rerun: /usr/bin/python3 examples/notebooks/make_notebooks.py"""

import pathlib

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

HERE = pathlib.Path(__file__).resolve().parent

NOTEBOOKS = {
    "01_first_case.ipynb": [
        ("md", """# A first case

The oscillation drum of Paulmichl, Adam & Adam (2019) on soil: the paper's roller (HAMM HD+ 90 VO)
on the Table 2 soil at G = 25 MN/m², Coulomb friction mu = 0.5. All values are SI."""),
        ("code", """import oscidrum
from oscidrum import plot

case = oscidrum.Case(table2_G=25e6, mu=0.5)   # soil of paper Table 2 at G = 25 MN/m^2
case"""),
        ("md", "Simulate from rest to the steady state (a few milliseconds) and read the metrics "
               "the paper uses."),
        ("code", """result = oscidrum.simulate(case)
print(result.status.name, '-', result.message)
m = oscidrum.compute_metrics(result)
print(f"peak x_M'' = {m.ddx_max:.1f} m/s^2, area = {m.area:.2f} m^2/s^4, "
      f"stick {m.stick_fraction:.0%} of the time")"""),
        ("md", "The steady state as a pandas DataFrame (units in `df.attrs['units']`)."),
        ("code", """df = result.to_dataframe()
df[["t", "ddx_M", "ddz_M", "phase"]].describe()"""),
        ("code", """fig = plot.plot_accelerations(result)
fig2 = plot.plot_figure_eight(result)"""),
    ],
    "02_study_G_mu_heatmap.ipynb": [
        ("md", """# A study over G and mu, as a heat map

Every Table 2 soil (G = 5 ... 70 MN/m²) against four friction coefficients: 56 cases on all
cores, in about a second. The result becomes an xarray Dataset over (soil.G, contact.mu)."""),
        ("code", """import numpy as np
import matplotlib.pyplot as plt
import oscidrum

G_values = [row.G for row in oscidrum.table2()]          # [Pa]
mu_values = [0.3, 0.4, 0.5, 0.6]                          # [-]
cases = [oscidrum.Case(table2_G=G, mu=mu) for G in G_values for mu in mu_values]
res = oscidrum.run_study(cases)
df = res.to_dataframe()
df[["soil.G", "contact.mu", "status", "area", "stick_fraction"]].head()"""),
        ("code", """ds = res.to_xarray()
area = ds["area"]                       # [m^2/s^4] over (soil.G, contact.mu)
fig, ax = plt.subplots(figsize=(7, 4))
mesh = ax.pcolormesh(area["contact.mu"], area["soil.G"] / 1e6, area.values, shading="nearest")
fig.colorbar(mesh, ax=ax, label=r"area of $z_M''$ over $x_M''$ [m$^2$/s$^4$]")
ax.set_xlabel(r"friction coefficient $\\mu$ [-]")
ax.set_ylabel(r"shear modulus $G$ [MN/m$^2$]")
ax.set_title("oscidrum: area of the acceleration figure")"""),
        ("md", "The same Dataset as a netCDF file, readable by any netCDF tool:"),
        ("code", """import tempfile, os, xarray as xr
path = os.path.join(tempfile.mkdtemp(), "study.nc")
res.to_netcdf(path)
xr.open_dataset(path)"""),
    ],
    "03_paper_fig22.ipynb": [
        ("md", """# Reproducing paper Fig. 22

Stick-slip (mu = 0.5) on the Table 2 soils, circular trough R = 0.606 m, without and with the
driving torque MMd = 0.05 M0. The paper reports that the area inside the z_M''-x_M'' figure
decreases with G for MMd = 0, and has a minimum at G = 20 and a maximum at G = 45 MN/m² for
MMd = 0.05 M0."""),
        ("code", """import numpy as np
import matplotlib.pyplot as plt
import oscidrum

G_values = [row.G for row in oscidrum.table2()]          # [Pa]
cases = [oscidrum.Case(table2_G=G, mu=0.5, R=0.606, MMd_fraction=f)
         for f in (0.0, 0.05) for G in G_values]
res = oscidrum.run_study(cases)
df = res.to_dataframe("all")
df["MMd_fraction"] = df["MMd"] / df["roller.M0"]
assert df["ok"].all()"""),
        ("code", """fig, ax = plt.subplots(figsize=(7, 4))
for f, part in df.groupby("MMd_fraction"):
    ax.plot(part["soil.G"] / 1e6, part["area"], "+-", label=f"MMd = {f:g} M0")
ax.set_xlabel(r"shear modulus $G$ [MN/m$^2$]")
ax.set_ylabel(r"area [m$^2$/s$^4$]")
ax.legend()
ax.set_title("paper Fig. 22 by oscidrum")"""),
        ("md", "The extrema the paper states, for MMd = 0.05 M0:"),
        ("code", """part = df[np.isclose(df["MMd_fraction"], 0.05)].set_index("soil.G")["area"]
inner = part.iloc[1:-1]
g_min, g_max = inner.idxmin() / 1e6, inner.idxmax() / 1e6
print(f"minimum at G = {g_min:g} MN/m^2 (paper: 20), maximum at G = {g_max:g} MN/m^2 (paper: 45)")
assert (g_min, g_max) == (20, 45)"""),
    ],
    "04_dask_study.ipynb": [
        ("md", """# A study on a Dask cluster

`run_study(cases, executor=...)` takes any `concurrent.futures.Executor`. Here a local Dask
cluster of two worker processes stands in for a real one (`distributed.Client("scheduler:8786")`
on a cluster). Each task is a chunk of cases that runs on all cores of its worker in C++; the
results come back in case order, identical to a local run."""),
        ("code", """import distributed
import oscidrum

cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                   host="127.0.0.1", dashboard_address=None)
client = distributed.Client(cluster)
client"""),
        ("code", """cases = [oscidrum.Case(table2_G=G, mu=mu) for G in (5e6, 15e6, 25e6, 40e6, 70e6)
         for mu in (0.3, 0.5, 0.7)]
res = oscidrum.run_study(cases, executor=client.get_executor(), chunk_size=5)
local = oscidrum.run_study(cases)
assert [o.metrics.area for o in res] == [o.metrics.area for o in local]
res.to_dataframe()[["soil.G", "contact.mu", "area"]]"""),
        ("code", """client.close()
cluster.close()"""),
    ],
}


def main():
    for name, cells in NOTEBOOKS.items():
        nb = new_notebook(cells=[new_markdown_cell(text) if kind == "md" else new_code_cell(text)
                                 for kind, text in cells])
        nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                     "language": "python"}
        nbformat.write(nb, HERE / name)
        print("wrote", HERE / name)


if __name__ == "__main__":
    main()
