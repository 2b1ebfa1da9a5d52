#!/usr/bin/env python3
"""The two rollers on the same soils (docs/vibratory.md, "Over a wider range of soils"): the paper's oscillation drum and the
vibratory drum (roller.type = vibratory, docs/model.md section 14), each at its operating point,
on the same Appendix B soils; their accelerations at one soil and how their CCC indicators follow
G. Writes docs/img/roller_comparison.png and prints the Markdown tables of docs/vibratory.md.

    PYTHONPATH=build/python /usr/bin/python3 scripts/roller_comparison.py [OUT_DIR]

Both drums are the paper's (Table 1: mass, inertia, radius, width, axle load, buffers), with
Coulomb friction mu = 0.5 and contact that can open (contact.unilateral), on Appendix B soil
(soil.input = modulus) under the circular trough R = 0.606 m:
- oscillation: the paper's exciter, M0 = 54 947 N m at 39 Hz (its unbalance 0.22877 kg m^2);
- vibratory: a rotating unbalance of static moment 0.9 kg m at 30 Hz (examples/vibratory.toml).
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
G_VALUES = np.arange(5.0, 100.1, 2.5)  # [MN/m^2]
G_SHOWN = 25.0                         # the soil of the time series [MN/m^2]
ROLLERS = ("oscillation", "vibratory")


def case(roller, G):
    c = oscidrum.Case()
    c.set("soil.input", "modulus")
    c.set("soil.G", G * 1e6)
    c.set("contact.mu", 0.5)
    c.set("contact.unilateral", True)
    if roller == "oscillation":
        c.set("roller.f", 39.0)
        c.set("roller.unbalance", 0.22877)
    else:
        c.set("roller.type", "vibratory")
        c.set("roller.static_moment", 0.9)
        c.set("roller.f", 30.0)
    return c


def run(roller):
    cases = [case(roller, G) for G in G_VALUES]
    t = time.perf_counter()
    outcomes = oscidrum.run_study(cases, progress=False)
    return outcomes, time.perf_counter() - t


def column(outcomes, name):
    return np.array([getattr(o.metrics, name) if o.ok else np.nan for o in outcomes])


def peak(outcomes, name):
    """The largest |value| of a signal over the steady period, from its max and min."""
    return np.maximum(np.abs(column(outcomes, name + "_max")), np.abs(column(outcomes, name + "_min")))


def sensitivity(values, at):
    """d ln(value) / d ln(G) at G = at, by central differences on the grid."""
    i = int(np.argmin(np.abs(G_VALUES - at)))
    i = min(max(i, 1), len(G_VALUES) - 2)
    return (np.log(values[i + 1]) - np.log(values[i - 1])) / (
        np.log(G_VALUES[i + 1]) - np.log(G_VALUES[i - 1]))


results = {}
for roller in ROLLERS:
    outcomes, seconds = run(roller)
    statuses = sorted({o.result.status.name if o.valid else "invalid" for o in outcomes})
    results[roller] = {
        "outcomes": outcomes,
        "seconds": seconds,
        "statuses": statuses,
        "x": peak(outcomes, "ddx"),
        "z": peak(outcomes, "ddz"),
        "cmv": column(outcomes, "cmv"),
        "kb": column(outcomes, "kb"),
        "evib": column(outcomes, "evib"),
        "area": column(outcomes, "area"),
        "x1": np.array([o.metrics.ddx_amplitude[1] if o.ok else np.nan for o in outcomes]),
        "z1": np.array([o.metrics.ddz_amplitude[1] if o.ok else np.nan for o in outcomes]),
        "flight": column(outcomes, "flight_fraction"),
        # The vibratory drum's mode by the literature's names (continuous contact, partial
        # uplift, double jump, ...), the oscillation drum's contact mode.
        "modes": [(o.result.diagnostics.operating_mode or o.result.diagnostics.contact_mode)
                  if o.ok else o.result.status.name for o in outcomes],
    }

# The time series at one soil.
series = {}
for roller in ROLLERS:
    r = oscidrum.simulate(case(roller, G_SHOWN))
    s = r.samples
    series[roller] = (np.asarray(s.t), np.asarray(s.ddx_M), np.asarray(s.ddz_M), r.status.name)

fig, ax = plt.subplots(2, 2, figsize=(11, 8))
colours = {"oscillation": "tab:blue", "vibratory": "tab:red"}
for roller in ROLLERS:
    t, x, z, status = series[roller]
    period = 1.0 / (39.0 if roller == "oscillation" else 30.0)
    tau = (t - t[0]) / period
    ax[0, 0].plot(tau, x, color=colours[roller], label=f"{roller}: x_M''")
    ax[0, 0].plot(tau, z, color=colours[roller], linestyle="--", label=f"{roller}: z_M''")
ax[0, 0].set_xlabel("time [excitation periods]")
ax[0, 0].set_ylabel("acceleration [m/s$^2$]")
ax[0, 0].set_title(f"steady state on G = {G_SHOWN:g} MN/m$^2$")
ax[0, 0].legend(fontsize=8)
for roller in ROLLERS:
    res = results[roller]
    ax[0, 1].plot(G_VALUES, res["x"], color=colours[roller], label=f"{roller}: max |x_M''|")
    ax[0, 1].plot(G_VALUES, res["z"], color=colours[roller], linestyle="--",
                  label=f"{roller}: max |z_M''|")
i25 = int(np.argmin(np.abs(G_VALUES - G_SHOWN)))
for roller, name, label, style in (
        ("vibratory", "cmv", "vibratory: CMV-type 300 A(2f)/A(f) of z_M''", "-"),
        ("vibratory", "z1", "vibratory: A(f) of z_M''", ":"),
        ("vibratory", "kb", "vibratory: Kb-type soil stiffness kb", "--"),
        ("vibratory", "evib", "vibratory: Evib-type modulus evib", "-."),
        ("oscillation", "area", "oscillation: area of z_M''(x_M'')", "-"),
        ("oscillation", "z", "oscillation: max |z_M''|", ":")):
    v = results[roller][name]
    ax[1, 0].plot(G_VALUES, v / v[i25], color=colours[roller], linestyle=style, label=label)
for roller in ROLLERS:
    ax[1, 1].plot(G_VALUES, results[roller]["flight"], color=colours[roller], label=roller)
ax[0, 1].set_xlabel("G [MN/m$^2$]")
ax[0, 1].set_ylabel("peak acceleration [m/s$^2$]")
ax[0, 1].set_title("peak accelerations")
ax[0, 1].legend(fontsize=8)
ax[1, 0].set_xlabel("G [MN/m$^2$]")
ax[1, 0].set_yscale("log")
ax[1, 0].set_ylabel(f"indicator / its value at G = {G_SHOWN:g} MN/m$^2$ [-]")
ax[1, 0].set_title("CCC indicators against G")
ax[1, 0].legend(fontsize=8)
ax[1, 1].set_xlabel("G [MN/m$^2$]")
ax[1, 1].set_ylabel("flight fraction [-]")
ax[1, 1].set_title("share of the period off the soil")
ax[1, 1].legend(fontsize=8)
for a in ax.flat:
    a.grid(alpha=0.3)
fig.tight_layout()
out.mkdir(parents=True, exist_ok=True)
fig.savefig(out / "roller_comparison.png", dpi=110)

print(f"{len(G_VALUES)} soils x 2 rollers; oscillation {results['oscillation']['seconds']:.1f} s, "
      f"vibratory {results['vibratory']['seconds']:.1f} s; statuses: "
      f"{results['oscillation']['statuses']}, {results['vibratory']['statuses']}")
print()
print("| G [MN/m^2] | roller | contact mode | max abs x_M'' [m/s^2] | max abs z_M'' [m/s^2] | "
      "A_1 of z_M'' [m/s^2] | CMV-type [-] | kb [MN/m] | evib [MN/m^2] | area [m^2/s^4] | "
      "flight fraction |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for G in (10.0, 25.0, 50.0, 75.0, 100.0):
    i = int(np.argmin(np.abs(G_VALUES - G)))
    for roller in ROLLERS:
        res = results[roller]
        # The oscillation drum's z_M'' has no component at f (docs/vibratory.md): '-'.
        at_f = roller == "vibratory"
        z1 = f"{res['z1'][i]:.1f}" if at_f else "-"
        cmv = f"{res['cmv'][i]:.1f}" if at_f else "-"
        kb = f"{res['kb'][i] / 1e6:.1f}" if at_f else "-"
        evib = f"{res['evib'][i] / 1e6:.1f}" if at_f else "-"  # vibratory drum only
        print(f"| {G_VALUES[i]:g} | {roller} | {res['modes'][i]} | {res['x'][i]:.1f} | "
              f"{res['z'][i]:.1f} | {z1} | {cmv} | {kb} | {evib} | {res['area'][i]:.0f} | "
              f"{res['flight'][i]:.3f} |")
print()
print("| indicator | roller | d ln / d ln G at 10 | at 25 | at 50 | at 90 MN/m^2 |")
print("|---|---|---|---|---|---|")
for name, label in (("x", "max abs x_M''"), ("z", "max abs z_M''"), ("z1", "A_1 of z_M''"),
                    ("cmv", "CMV-type"), ("kb", "kb"), ("evib", "evib"), ("area", "area")):
    for roller in ROLLERS:
        if roller == "oscillation" and name in ("z1", "cmv", "kb", "evib"):
            continue  # no component at f
        v = results[roller][name]
        cells = " | ".join(f"{sensitivity(v, G):+.2f}" for G in (10.0, 25.0, 50.0, 90.0))
        print(f"| {label} | {roller} | {cells} |")
