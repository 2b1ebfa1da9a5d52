"""Paper Fig. 16: area inside the z_M''-x_M'' figure against the soil's shear modulus G,
pure rolling, MMd = 0 and MMd = 0.05 M0 (Paulmichl, Adam & Adam 2019).

    /usr/bin/python3 examples/fig16_area_pure_rolling.py [OUT_DIR]

Writes fig16_area_pure_rolling.png and .csv into OUT_DIR (default: the current directory).
The paper: the area is largest at G = 20-25 MN/m^2 without and at G = 40 MN/m^2 with the
driving torque.
"""

import sys
from pathlib import Path

import oscidrum
from oscidrum.data import write_table
from oscidrum.plot import plot_sweep, save

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
# The paper's two pure-rolling series on the circular trough R = 0.606 m (MMd = 0 and 0.05 M0),
# as the library defines them (oscidrum.paper_series(), the cases of `oscidrum validate`).
series = {s.MMd_fraction: s for s in oscidrum.paper_series()
          if s.id in ("rolling_MMd0_R0.606", "rolling_MMd0.05_R0.606")}
fractions = (0.0, 0.05)
G_values = list(series[0.0].G)  # Table 2: 5 ... 70 MN/m^2 [Pa]
cases = [oscidrum.paper_case(series[f], G) for f in fractions for G in G_values]

# All cases on all cores (C++ threads); one outcome per case, in order.
outcomes = oscidrum.run_study(cases)
assert all(o.ok for o in outcomes), [o.result.message for o in outcomes if not o.ok]
area = {f: [o.metrics.area for o in outcomes[i * len(G_values):(i + 1) * len(G_values)]]
        for i, f in enumerate(fractions)}  # [m^2/s^4]

for f in fractions:
    best = max(range(len(G_values)), key=lambda i: area[f][i])
    print(f"MMd = {f:g} M0: largest area {area[f][best]:.0f} m^2/s^4 at "
          f"G = {G_values[best] / 1e6:g} MN/m^2")

fig = plot_sweep(G_values, {"MMd = 0": area[0.0], "MMd = 0.05 M0": area[0.05]}, "soil.G", "area",
                 title="Fig. 16: pure rolling")
print(save(fig, out / "fig16_area_pure_rolling.png"))
write_table(out / "fig16_area_pure_rolling.csv",
            {"G": G_values, "area_MMd0": area[0.0], "area_MMd005": area[0.05]},
            {"G": "Pa", "area_MMd0": "m^2/s^4", "area_MMd005": "m^2/s^4"})
