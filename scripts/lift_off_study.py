#!/usr/bin/env python3
"""Where the paper's roller lifts off (contact.unilateral, docs/model.md section 13): maps of the
contact mode and of the flight fraction over G x f and over G x MMd, with the CCC metrics on both
sides of the boundary. Writes docs/img/lift_off_maps.png and prints the Markdown tables of
docs/lift-off.md.

    PYTHONPATH=build/python /usr/bin/python3 scripts/lift_off_study.py [OUT_DIR]

The roller is the paper's (Table 1) with its unbalance (M0 follows f^2, 0.22877 kg m^2), the
soil by Appendix B (soil.input = modulus), the circular trough R = 0.606 m. Each map is run twice:
pure rolling (the paper's pure-rolling studies) and Coulomb friction mu = 0.5.
"""

import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import oscidrum  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
out = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "img"
G_VALUES = np.arange(10.0, 101.0, 10.0)        # [MN/m^2]
F_VALUES = np.arange(35.0, 76.0, 5.0)          # [Hz]
MMD_FRACTIONS = np.arange(0.0, 0.081, 0.01)    # [-] of M0
F_FOR_MMD = 65.0                               # [Hz]


def case(G, f, pure, fraction=0.0):
    c = oscidrum.Case()
    c.set("soil.input", "modulus")
    c.set("soil.G", G * 1e6)
    c.set("roller.f", f)
    c.set("roller.unbalance", 0.22877)
    c.set("contact.unilateral", True)
    if pure:
        c.set("contact.pure_rolling", True)
    c.set("MMd", fraction * 4 * 0.22877 * (2 * np.pi * f) ** 2)
    c.set("numerics.max_periods", 3000)
    return c


MODES = {"permanent contact": 0, "periodic lift-off": 1, "lift-off every 2 periods": 2,
         "lift-off every 3 periods": 3}


def mode_code(o):
    if not o.valid:
        return np.nan
    mode = o.result.diagnostics.contact_mode
    status = o.result.status.name
    if status == "steady_state":
        return MODES.get(mode, 4 if "lift-off" in mode else 0)
    if status in ("max_periods_reached", "aperiodic"):
        return 5  # aperiodic
    if status == "gross_slip":
        return 6
    if status == "contact_lost":
        return 7  # what the model cannot answer (docs/model.md section 13)
    return 8  # another status (chattering, ...)


def run_map(xs, ys, make):
    cases = [make(x, y) for y in ys for x in xs]
    t = time.perf_counter()
    outcomes = oscidrum.run_study(cases, progress=False)
    seconds = time.perf_counter() - t
    mode = np.array([mode_code(o) for o in outcomes]).reshape(len(ys), len(xs))
    flight = np.array([o.metrics.flight_fraction if o.ok else np.nan
                       for o in outcomes]).reshape(len(ys), len(xs))
    return mode, flight, outcomes, seconds


LABELS = ["permanent contact", "periodic lift-off", "lift-off every 2nd period",
          "lift-off every 3rd period", "other subharmonic with lift-off", "aperiodic",
          "gross slip", "contact lost (beyond the model)", "other status"]
COLORS = ["#dfe8f1", "#f4a261", "#e76f51", "#9c2f1d", "#6d2e46", "#555555", "#8ab17d",
          "#264653", "#000000"]


def draw(ax, xs, ys, mode, title, ylabel):
    cmap = matplotlib.colors.ListedColormap(COLORS)
    ax.pcolormesh(xs, ys, mode, cmap=cmap, vmin=-0.5, vmax=8.5, shading="nearest")
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("G [MN/m$^2$]")
    ax.set_ylabel(ylabel)


total = 0
fig, axes = plt.subplots(2, 2, figsize=(10, 8.6))
fig.subplots_adjust(left=0.07, right=0.98, top=0.92, bottom=0.16, hspace=0.3, wspace=0.22)
tables = []
for row, pure in enumerate((True, False)):
    friction = "pure rolling" if pure else "mu = 0.5"
    mode, flight, outs, s1 = run_map(G_VALUES, F_VALUES, lambda G, f: case(G, f, pure))
    draw(axes[row][0], G_VALUES, F_VALUES, mode, f"G x f, {friction}", "f [Hz]")
    mode2, flight2, outs2, s2 = run_map(G_VALUES, MMD_FRACTIONS,
                                        lambda G, q: case(G, F_FOR_MMD, pure, q))
    draw(axes[row][1], G_VALUES, MMD_FRACTIONS, mode2,
         f"G x MMd at f = {F_FOR_MMD:g} Hz, {friction}", "MMd / M0 [-]")
    total += len(outs) + len(outs2)
    tables.append((friction, mode, flight, outs, s1 + s2, len(outs) + len(outs2)))
handles = [matplotlib.patches.Patch(color=c, label=label) for c, label in zip(COLORS, LABELS)]
fig.legend(handles=handles, loc="lower center", ncols=5, fontsize=8, frameon=False)
fig.suptitle("Contact modes of the paper's roller with unilateral contact (Appendix B soil)",
             fontsize=11)
out.mkdir(parents=True, exist_ok=True)
fig.savefig(out / "lift_off_maps.png", dpi=100)
print(out / "lift_off_maps.png", file=sys.stderr)

# The tables: flight fraction over G x f, and the CCC metrics on both sides of the boundary.
for friction, mode, flight, outs, seconds, n_both in tables:
    # The time is that of both maps (G x f and G x MMd) of this friction.
    print(f"\n**{friction}**: flight fraction (share of the period off the soil; '-' no steady "
          f"state; both maps' {n_both} cases in {seconds:.1f} s on all cores)\n")
    print("| f [Hz] \\ G [MN/m^2] | " + " | ".join(f"{G:g}" for G in G_VALUES) + " |")
    print("|---" * (len(G_VALUES) + 1) + "|")
    for i, f in enumerate(F_VALUES):
        cells = ["-" if np.isnan(v) else f"{v:.3f}" for v in flight[i]]
        print(f"| {f:g} | " + " | ".join(cells) + " |")
for friction, mode, flight, outs, seconds, n_both in tables[:1]:
    print(f"\n**{friction}**, along G at each f where lift-off starts: the last case in permanent "
          "contact and the first with lift-off\n")
    print("| f [Hz] | G [MN/m^2] | contact mode | max abs x_M'' [m/s^2] | z_M'' max [m/s^2] | "
          "area [m^2/s^4] | flight fraction |")
    print("|---|---|---|---|---|---|---|")
    for i, f in enumerate(F_VALUES):
        row = [outs[i * len(G_VALUES) + j] for j in range(len(G_VALUES))]
        for j in range(1, len(G_VALUES)):
            a, b = row[j - 1], row[j]
            if a.ok and b.ok and a.metrics.flight_fraction == 0 and b.metrics.flight_fraction > 0:
                for G, o in ((G_VALUES[j - 1], a), (G_VALUES[j], b)):
                    m = o.metrics
                    print(f"| {f:g} | {G:g} | {o.result.diagnostics.contact_mode} | "
                          f"{max(abs(m.ddx_max), abs(m.ddx_min)):.1f} | {m.ddz_max:.2f} | {m.area:.0f} | "
                          f"{m.flight_fraction:.3f} |")
                break
