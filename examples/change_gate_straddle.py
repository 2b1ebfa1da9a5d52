"""A record whose soil changes 1 excitation period into the second 40-period window.

    /usr/bin/python3 examples/change_gate_straddle.py [OUT_DIR]

G = 30 MN/m^2 until t_c = 41/39 s, then 17.3 MN/m^2 (soil by Appendix B), 2 kHz, 2 % noise,
5 % drift, z positive up and in g with gravity kept, as a logger writes it: straddle.csv in
OUT_DIR (default: the current directory). The change gate of identification (its 5 % are of
the response's RMS) passes the window that straddles the change (docs/identify.md, "What the gate
misses"): the script identifies G in each window, prints the windows and draws them
(straddle.png), the straddling window's interval excluding both soils. `oscidrum identify
OUT_DIR/straddle.csv` gives the same windows.
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import oscidrum  # noqa: E402
from oscidrum.identify import identify, plot_pass  # noqa: E402

G0 = 9.80665  # [m/s^2]
out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
out.mkdir(parents=True, exist_ok=True)
tc = 41 / 39.0  # [s]
seg = tc / 8
n2 = round((2.2 - tc) / seg)
cases = ([oscidrum.Case(input="modulus", G=30e6)] * 8
         + [oscidrum.Case(input="modulus", G=17.3e6)] * n2)
r = oscidrum.synthetic_record(cases, duration=seg * len(cases), sample_rate=2000, noise=0.02,
                              drift=0.05, jitter=0.1, seed=3, speed=0.8)
with open(out / "straddle.csv", "w") as f:
    f.write("Time [s],Acc X [g],Acc Z [g]\n")
    for t, x, z in zip(r["t"], r["ddx_M"], r["ddz_M"]):
        f.write(f"{t:.7f},{x / G0:.6f},{-z / G0 + 1:.6f}\n")

# The file as written (g, z up) read back as identify's CLI reads it.
data = oscidrum.read_record(str(out / "straddle.csv"))
rows = identify(data["t"], data["ddx_M"], data["ddz_M"])
print("window  t [s]   G [MN/m^2]  95 % interval      change  valid")
for k, w in enumerate(rows):
    print(f"{k:6d}  {w['t']:.4f}  {w['G'] / 1e6:9.3f}  [{w['G_lo'] / 1e6:.2f}, "
          f"{w['G_hi'] / 1e6:.2f}]  {w['change']:+.4f}  {w['valid']}")
fig = plot_pass(rows, x="t")
ax = fig.axes[0]
ax.step([0.0, tc, seg * len(cases)], [30.0, 17.3, 17.3], where="post", color="k", ls="--",
        lw=0.8, label="the record's soil")
ax.legend()

fig.savefig(out / "straddle.png", dpi=120)
