"""Reproduce the paper's parametric studies (Figs. 7-22) and write a Markdown report.

    python3 -m oscidrum.paper --out DIR [--format png|svg] [--threads N] [--G 5,25,70]

All cases run through :func:`oscidrum.run_study` (C++ threads). For each figure the data behind
it is written as ``figNN*.csv`` (``name[unit]`` columns), the figure as ``figNN*.png`` (or svg),
and ``report.md`` puts each figure beside what the paper states (MODEL.md section 8) and the
numbers computed here, with a verdict. ``cases.csv`` lists every case with its status and
metrics. If ``validation.md`` exists in DIR it is linked from the report.

Studies (MODEL.md section 8; HAMM HD+ 90 VO, Table 2 soils, G = 5 ... 70 MN/m^2):

* pure rolling and stick-slip (mu = 0.5), each with MMd = 0 and MMd = 0.05 M0, circular trough
  R = 0.606 m;
* radius study, pure rolling, MMd = 0: R = 0.603, 0.606, 0.62, 0.65 m (the paper prints only the
  ends and 0.606; 0.62 is our choice for the fourth);
* trough shape, pure rolling, MMd = 0, G = 5: spiral k = 0.002, a = 0.601 m against the circle
  R = 0.603 m.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import _core as core
from . import plot
from .data import from_result, write_table

MN = 1e6
#: Table 2 shear moduli [Pa].
G_VALUES: Tuple[float, ...] = tuple(g * MN for g in range(5, 75, 5))
#: The four soils of the paper's time-history, spectrum and z-x figures [Pa].
SELECTED_G: Tuple[float, ...] = (5 * MN, 25 * MN, 50 * MN, 70 * MN)
R_BASE = 0.606  #: base circular trough [m]
#: Radius study [m]: 0.603, 0.606 and 0.65 are in the paper; 0.62 is our choice.
R_VALUES: Tuple[float, ...] = (0.603, 0.606, 0.62, 0.65)
SPIRAL = (0.002, 0.601)  #: trough-shape study (k [-], a [m]) against the circle R = 0.603 m
MU = 0.5  #: friction coefficient of the stick-slip studies [-]
MMD_FRACTION = 0.05  #: MMd / M0 of the driving-torque studies [-]


def paper_case(G: float, pure_rolling: bool, MMd_fraction: float = 0.0, R: float = R_BASE,
               k: float = 0.0, a: Optional[float] = None,
               samples_per_period: Optional[int] = None) -> core.Case:
    """A case of the paper: Table 2 soil at G [Pa], trough (k [-], a [m]; a = R for a circle),
    pure rolling or Coulomb friction mu = 0.5, MMd = MMd_fraction * M0 [N m]."""
    case = core.Case(soil=core.table2_soil(G))
    case.trough.k = k
    case.trough.a = R if a is None else a
    case.contact.mu = MU
    case.contact.pure_rolling = pure_rolling
    case.MMd = MMd_fraction * case.roller.M0
    if samples_per_period is not None:
        case.numerics.samples_per_period = samples_per_period
    return case


@dataclass
class Run:
    """One case of the reproduction: where it belongs and what it produced."""

    study: str
    G: float
    R: float
    k: float
    a: float
    pure_rolling: bool
    MMd_fraction: float
    case: Any
    outcome: Any = None

    @property
    def ok(self) -> bool:
        return self.outcome is not None and self.outcome.valid and len(
            self.outcome.result.samples) > 0

    @property
    def metrics(self) -> Any:
        return self.outcome.metrics


#: study name -> (pure rolling, MMd/M0, R [m], description)
STUDIES: Dict[str, Tuple[bool, float, float, str]] = {
    "pure_MMd0": (True, 0.0, R_BASE, "pure rolling, MMd = 0, R = 0.606 m"),
    "pure_MMd5": (True, MMD_FRACTION, R_BASE, "pure rolling, MMd = 0.05 M0, R = 0.606 m"),
    "slip_MMd0": (False, 0.0, R_BASE, "stick-slip μ = 0.5, MMd = 0, R = 0.606 m"),
    "slip_MMd5": (False, MMD_FRACTION, R_BASE, "stick-slip μ = 0.5, MMd = 0.05 M0, R = 0.606 m"),
}


def build_runs(G_values: Sequence[float] = G_VALUES,
               samples_per_period: Optional[int] = None) -> List[Run]:
    """Every case of the reproduction, in a fixed order."""
    runs: List[Run] = []
    for name, (pure, frac, R, _) in STUDIES.items():
        for G in G_values:
            runs.append(Run(name, G, R, 0.0, R, pure, frac,
                            paper_case(G, pure, frac, R, samples_per_period=samples_per_period)))
    for R in R_VALUES:
        if R == R_BASE:
            continue  # pure_MMd0 is the radius study's R = 0.606 m
        for G in G_values:
            runs.append(Run(f"radius_R{R:g}", G, R, 0.0, R, True, 0.0,
                            paper_case(G, True, 0.0, R, samples_per_period=samples_per_period)))
    k, a = SPIRAL
    G5 = min(G_values)
    runs.append(Run("spiral", G5, a, k, a, True, 0.0,
                    paper_case(G5, True, 0.0, k=k, a=a, samples_per_period=samples_per_period)))
    if 0.603 not in R_VALUES:  # the circle the spiral is compared with
        runs.append(Run("radius_R0.603", G5, 0.603, 0.0, 0.603, True, 0.0,
                        paper_case(G5, True, 0.0, 0.603, samples_per_period=samples_per_period)))
    return runs


class Results:
    """Look-ups into the finished runs."""

    def __init__(self, runs: List[Run]):
        self.runs = runs

    def study(self, name: str) -> List[Run]:
        return sorted((r for r in self.runs if r.study == name), key=lambda r: r.G)

    def radius(self, R: float) -> List[Run]:
        return self.study("pure_MMd0" if R == R_BASE else f"radius_R{R:g}")

    def at(self, name: str, G: float) -> Optional[Run]:
        for r in self.study(name):
            if r.G == G:
                return r
        return None

    def selected(self, name: str) -> List[Run]:
        runs = [r for r in self.study(name) if r.G in SELECTED_G and r.ok]
        if not runs:  # a reduced G list: take what is there
            runs = [r for r in self.study(name) if r.ok][:4]
        return runs


def _g_label(G: float) -> str:
    return f"G = {G / MN:g} MN/m²"


def _metric(runs: Sequence[Run], name: str) -> np.ndarray:
    return np.array([getattr(r.metrics, name) if r.ok else math.nan for r in runs])


def _amp(run: Run, signal: str, n: int) -> float:
    if not run.ok:
        return math.nan
    amp = getattr(run.metrics, f"{signal}_amplitude")
    return float(amp[n]) if n < len(amp) else math.nan


def _G(runs: Sequence[Run]) -> np.ndarray:
    return np.array([r.G for r in runs])


def _argmax_G(runs: Sequence[Run], values: np.ndarray) -> float:
    if len(values) == 0 or np.all(np.isnan(values)):
        return math.nan
    return runs[int(np.nanargmax(values))].G / MN


def local_extrema(x: np.ndarray, y: np.ndarray) -> Tuple[List[float], List[float]]:
    """Interior local minima and maxima of y(x): ([x of minima], [x of maxima])."""
    mins, maxs = [], []
    for i in range(1, len(y) - 1):
        if y[i] < y[i - 1] and y[i] < y[i + 1]:
            mins.append(float(x[i]))
        if y[i] > y[i - 1] and y[i] > y[i + 1]:
            maxs.append(float(x[i]))
    return mins, maxs


def _list(values: Sequence[float]) -> str:
    return ", ".join(f"{v:g}" for v in values) if values else "none"


def _fmt(v: float, digits: int = 3) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "n/a"
    return f"{v:.{digits}g}"


@dataclass
class Check:
    """One statement of the paper and what this reproduction found."""

    claim: str  #: quoted from MODEL.md section 8
    computed: str
    agrees: Optional[bool]  #: None: judged by eye from the figure


@dataclass
class Figure:
    """One of the paper's figures: files written and the checks beside it."""

    number: str
    caption: str
    files: List[str]
    data: List[str]
    checks: List[Check]


class Writer:
    """Draws the figures, writes their data and collects the report's entries."""

    def __init__(self, out: Path, fmt: str, results: Results):
        self.out, self.fmt, self.res = out, fmt, results
        self.figures: List[Figure] = []

    # -- helpers ---------------------------------------------------------------------------
    def save(self, fig: Any, name: str) -> str:
        path = plot.save(fig, self.out / f"{name}.{self.fmt}", self.fmt)
        return path.name

    def table(self, name: str, columns: Dict[str, Sequence[Any]], units: Dict[str, str]) -> str:
        write_table(self.out / f"{name}.csv", columns, units)
        return f"{name}.csv"

    def states(self, runs: Sequence[Run], label: Callable[[Run], str] = lambda r: _g_label(r.G)):
        return [from_result(r.outcome, label=label(r)) for r in runs if r.ok]

    def time_table(self, name: str, runs: Sequence[Run], columns: Sequence[str],
                   label: Callable[[Run], str]) -> str:
        """Two periods of the given sample columns, one column per run."""
        units = {"ddx_M": "m/s^2", "ddz_M": "m/s^2", "delta": "rad", "phi": "rad",
                 "torque": "N m", "phase": "-"}
        data: Dict[str, Sequence[Any]] = {}
        unit_of: Dict[str, str] = {"t/T": "-"}
        for run in runs:
            if not run.ok:
                continue
            state = from_result(run.outcome)
            idx = np.nonzero(state.tau() < 2 - 1e-9)[0]
            data.setdefault("t/T", state.tau()[idx])
            for column in columns:
                key = f"{column}_{label(run)}"
                data[key] = np.asarray(getattr(state.samples, column))[idx]
                unit_of[key] = units[column]
        return self.table(name, data, unit_of)

    def spectra_table(self, name: str, runs: Sequence[Run]) -> str:
        data: Dict[str, Sequence[Any]] = {"n": list(range(1, 11))}
        unit_of = {"n": "-"}
        for run in runs:
            if not run.ok:
                continue
            state = from_result(run.outcome)
            for column in ("ddx_M", "ddz_M"):
                key = f"{column}_G{run.G / MN:g}_normalised"
                data[key] = plot.normalised_spectrum(state, column, 10)
                unit_of[key] = "-"
        return self.table(name, data, unit_of)

    def add(self, number: str, caption: str, files: List[str], data: List[str],
            checks: List[Check]) -> None:
        self.figures.append(Figure(number, caption, files, data, checks))

    # -- figures ---------------------------------------------------------------------------
    def fig07_08(self) -> None:
        circle = self.res.at("radius_R0.603", min(r.G for r in self.res.runs))
        spiral = next((r for r in self.res.runs if r.study == "spiral"), None)
        runs = [r for r in (circle, spiral) if r is not None and r.ok]
        label = {id(circle): "circle R = 0.603 m", id(spiral): "spiral k = 0.002, a = 0.601 m"}
        lab = lambda r: label[id(r)]  # noqa: E731
        states = self.states(runs, lab)
        G = _g_label(runs[0].G) if runs else ""
        f7 = self.save(plot.plot_accelerations(
            states, title=f"Fig. 7: {G}, MMd = 0, pure rolling"), "fig07")
        d7 = self.time_table("fig07", runs, ("ddx_M", "ddz_M"),
                             lambda r: "circle" if r is circle else "spiral")
        f8a = self.save(plot.plot_delta_phi(states, title=f"Fig. 8a: {G}, pure rolling"),
                        "fig08a")
        f8b = self.save(plot.plot_figure_eight(states, title=f"Fig. 8b: {G}, pure rolling"),
                        "fig08b")
        d8 = self.time_table("fig08", runs, ("delta", "ddx_M", "ddz_M"),
                             lambda r: "circle" if r is circle else "spiral")
        checks = []
        if circle is not None and spiral is not None and circle.ok and spiral.ok:
            dc, ds = (np.asarray(r.outcome.result.samples.delta) for r in (circle, spiral))
            cm, sm = circle.metrics, spiral.metrics
            dx = abs(sm.ddx_max - cm.ddx_max) / cm.ddx_max
            checks.append(Check(
                "trough shape (G = 5, MMd = 0, pure rolling): spiral k = 0.002, a = 0.601 against "
                "circle R = 0.603: δ and zM'' slightly larger in the positive domain, xM'' "
                "virtually unchanged (Figs. 7, 8)",
                f"max δ: circle {_fmt(dc.max(), 4)} rad, spiral {_fmt(ds.max(), 4)} rad "
                f"(min: {_fmt(dc.min(), 4)}, {_fmt(ds.min(), 4)}); max zM'': circle "
                f"{_fmt(cm.ddz_max, 4)}, spiral {_fmt(sm.ddz_max, 4)} m/s²; max xM'' differs by "
                f"{dx * 100:.2g} %",
                bool(ds.max() > dc.max() and sm.ddz_max > cm.ddz_max and dx < 0.05)))
        self.add("7", "Time history of xM'' (a) and zM'' (b), G = 5 MN/m², MMd = 0, pure "
                 "rolling; circular against spiral trough", [f7], [d7], checks)
        self.add("8", "Position angle δ (a) and zM'' over xM'' (b), same cases", [f8a, f8b], [d8],
                 [])

    def fig09(self) -> None:
        data: Dict[str, Sequence[Any]] = {}
        units: Dict[str, str] = {"G": "Pa"}
        curves_x, curves_z = {}, {}
        ratios = {}
        for R in R_VALUES:
            runs = self.res.radius(R)
            if not runs:
                continue
            data.setdefault("G", _G(runs))
            x, z = _metric(runs, "ddx_max"), _metric(runs, "ddz_max")
            data[f"ddx_max_R{R:g}"], data[f"ddz_max_R{R:g}"] = x, z
            units[f"ddx_max_R{R:g}"] = units[f"ddz_max_R{R:g}"] = "m/s^2"
            curves_x[f"R = {R:g} m"] = x
            curves_z[f"R = {R:g} m"] = z
            ratios[R] = (np.nanmax(z) / np.nanmax(x), _argmax_G(runs, z), _argmax_G(runs, x))
        G = data.get("G", [])
        fa = self.save(plot.plot_sweep(G, curves_x, "soil.G", "ddx_max",
                                       title="Fig. 9a: pure rolling, MMd = 0"), "fig09a")
        fb = self.save(plot.plot_sweep(G, curves_z, "soil.G", "ddz_max",
                                       title="Fig. 9b: pure rolling, MMd = 0"), "fig09b")
        d = self.table("fig09", data, units)
        base = self.res.radius(R_BASE)
        x = _metric(base, "ddx_max")
        spread = np.nanmax([np.nanmax(np.abs(np.asarray(curves_x[k]) - x) / x)
                            for k in curves_x]) if curves_x else math.nan
        at = lambda G0: x[list(_G(base)).index(G0)] if G0 in list(_G(base)) else math.nan  # noqa
        checks = [
            Check("peak xM'' rises from about 25–28 m/s² (G = 5) to about 56 m/s² at G = 40 "
                  "(maximum), then falls slightly to about 50 m/s² (G = 70), almost independent "
                  "of R (Fig. 9a)",
                  f"R = 0.606: {_fmt(at(5 * MN))} m/s² at G = 5, maximum {_fmt(np.nanmax(x))} "
                  f"m/s² at G = {_fmt(_argmax_G(base, x))}, {_fmt(at(70 * MN))} m/s² at G = 70; "
                  f"largest difference between radii {spread * 100:.2g} %",
                  bool(24 <= at(5 * MN) <= 29 and 35 <= _argmax_G(base, x) <= 45
                       and spread < 0.1) if not math.isnan(at(5 * MN)) else None),
            Check("peak zM'' is largest at G = 15–20 and falls steeply beyond; the closer R is to "
                  "r, the larger it is; zM''max/xM''max is about 0.21 at R = 0.603, about 0.10 at "
                  "R = 0.606, about 0.01 at R = 0.65 (Fig. 9b) — ratios of the largest zM''max "
                  "over G to the largest xM''max over G",
                  "; ".join(f"R = {R:g}: ratio {_fmt(v[0], 2)}, zM''max largest at G = "
                            f"{_fmt(v[1])}" for R, v in ratios.items()),
                  bool(all(10 <= v[1] <= 25 for v in ratios.values())
                       and all(abs(ratios[R][0] - want) <= 0.4 * want + 0.01
                               for R, want in ((0.603, 0.21), (0.606, 0.10), (0.65, 0.01))
                               if R in ratios)) if ratios else None),
        ]
        self.add("9", "Peak xM'' (a) and zM'' (b) against G for four trough radii; pure rolling, "
                 "MMd = 0", [fa, fb], [d], checks)

    def fig10(self) -> None:
        runs = self.res.study("pure_MMd0")
        sel = self.res.selected("pure_MMd0")
        fa = self.save(plot.plot_torque_phi(self.states(sel), title="Fig. 10a: pure rolling, "
                                            "MMd = 0"), "fig10a")
        lag = _metric(runs, "phi_lag")
        fb = self.save(plot.plot_sweep(_G(runs), {"": lag}, "soil.G", "phi_lag",
                                       title="Fig. 10b: pure rolling, MMd = 0"), "fig10b")
        da = self.time_table("fig10a", sel, ("phi", "torque"), lambda r: f"G{r.G / MN:g}")
        db = self.table("fig10b", {"G": _G(runs), "phi_lag": lag}, {"G": "Pa",
                                                                    "phi_lag": "pi rad"})
        lag5 = lag[0] if len(runs) and runs[0].G == 5 * MN else math.nan
        checks = [Check("phase lag between MMu(t) and φ: −0.84π at G = 5, tending to −π as G → "
                        "0; its maximum is at G = 50 (Fig. 10)",
                        f"{_fmt(lag5)} π at G = 5; maximum {_fmt(np.nanmax(lag))} π at G = "
                        f"{_fmt(_argmax_G(runs, lag))}",
                        bool(abs(lag5 + 0.84) < 0.05 and 45 <= _argmax_G(runs, lag) <= 55)
                        if not math.isnan(lag5) else None)]
        self.add("10", "Drum rotation φ and excitation torque over one period (a); phase lag "
                 "between MMu(t) and φ against G (b); pure rolling, MMd = 0", [fa, fb], [da, db],
                 checks)

    def accelerations(self, number: str, study: str, caption: str,
                      checks: List[Check]) -> None:
        sel = self.res.selected(study)
        f = self.save(plot.plot_accelerations(self.states(sel),
                                              title=f"Fig. {number}: {STUDIES[study][3]}"),
                      f"fig{number}")
        d = self.time_table(f"fig{number}", sel, ("ddx_M", "ddz_M", "phase"),
                            lambda r: f"G{r.G / MN:g}")
        self.add(number, caption, [f], [d], checks)

    def fig11(self) -> None:
        r25, r50, r70 = (self.res.at("pure_MMd0", g * MN) for g in (25, 50, 70))
        checks = []
        if all(r is not None and r.ok for r in (r25, r50, r70)):
            q50 = r25.metrics.ddz_max / r50.metrics.ddz_max
            q70 = r25.metrics.ddz_max / r70.metrics.ddz_max
            a1 = _amp(r25, "ddz", 1) / _amp(r25, "ddz", 2)
            checks.append(Check(
                "at G = 25 the peak zM'' is about 3.3 (8.4) times that at G = 50 (70); the period "
                "of zM'' is half the excitation period (Fig. 11)",
                f"ratio {_fmt(q50, 2)} (G = 50), {_fmt(q70, 2)} (G = 70); at G = 25 zM'' has "
                f"A(f)/A(2f) = {_fmt(a1, 2)} (period T/2)",
                bool(abs(q50 - 3.3) < 0.5 and abs(q70 - 8.4) < 1.3 and a1 < 0.01)))
        self.accelerations("11", "pure_MMd0", "Steady-state xM'' (a) and zM'' (b) for four "
                           "soils; pure rolling, MMd = 0", checks)

    def fig12(self) -> None:
        runs = self.res.study("pure_MMd0")
        psi = _metric(runs, "psi_xz")
        f = self.save(plot.plot_sweep(_G(runs), {"": psi}, "soil.G", "psi_xz",
                                      title="Fig. 12: pure rolling, MMd = 0"), "fig12")
        d = self.table("fig12", {"G": _G(runs), "psi_xz": psi}, {"G": "Pa", "psi_xz": "rad"})
        G = _G(runs) / MN
        neg = [g for g, p in zip(G, psi) if p < 0]
        psi5 = psi[0] if len(G) and G[0] == 5 else math.nan
        checks = [Check(
            "phase lag between xM'' and zM'': about 0.11 rad at G = 5, maximum 0.64 at G = 25, "
            "negative for G ≥ 60 (Fig. 12); with ψ = θz − 2θx the independent check found "
            "0.104, max 0.626 at G = 25",
            f"ψ = {_fmt(psi5)} rad at G = 5, maximum {_fmt(np.nanmax(psi))} rad at G = "
            f"{_fmt(_argmax_G(runs, psi))}; negative for G = {', '.join(f'{g:g}' for g in neg)}",
            bool(abs(psi5 - 0.11) < 0.02 and _argmax_G(runs, psi) == 25
                 and abs(np.nanmax(psi) - 0.64) < 0.05 and (not neg or min(neg) >= 55))
            if not math.isnan(psi5) else None)]
        self.add("12", "Phase lag ψ between xM'' and zM'' against G; pure rolling, MMd = 0 "
                 "(ψ = θ₂(zM'') − 2 θ₁(xM''), MODEL.md section 8)", [f], [d], checks)

    def fig13(self) -> None:
        files, data, checks = [], [], []
        asym = {}
        for part, study in (("a", "pure_MMd0"), ("b", "pure_MMd5")):
            sel = self.res.selected(study)
            files.append(self.save(plot.plot_figure_eight(
                self.states(sel), title=f"Fig. 13{part}: {STUDIES[study][3]}"), f"fig13{part}"))
            data.append(self.time_table(f"fig13{part}", sel, ("ddx_M", "ddz_M"),
                                        lambda r: f"G{r.G / MN:g}"))
            asym[study] = max((_amp(r, "ddz", 1) / _amp(r, "ddz", 2) for r in sel), default=0)
        checks.append(Check(
            "zM'' against xM'' is a figure-eight (lemniscate-like) symmetric about the vertical "
            "axis (Fig. 13a); with MMd = 0.05 M0 it becomes asymmetric and loses its node for "
            "stiff soils (Fig. 13b)",
            f"symmetry about the vertical axis ⇔ no f harmonic in zM'': largest A(f)/A(2f) of "
            f"zM'' is {_fmt(asym['pure_MMd0'], 2)} for MMd = 0 and "
            f"{_fmt(asym['pure_MMd5'], 2)} for MMd = 0.05 M0 (node: see the figure)",
            bool(asym["pure_MMd0"] < 0.02 and asym["pure_MMd5"] > 0.2)))
        self.add("13", "zM'' over xM'', MMd = 0 (a) and MMd = 0.05 M0 (b); pure rolling", files,
                 data, checks)

    def spectra(self, number: str, study: str, caption: str, checks: List[Check]) -> None:
        sel = self.res.selected(study)
        f = self.save(plot.plot_spectra(self.states(sel),
                                        title=f"Fig. {number}: {STUDIES[study][3]}"),
                      f"fig{number}")
        d = self.spectra_table(f"fig{number}", sel)
        self.add(number, caption, [f], [d], checks)

    def fig14(self) -> None:
        sel = self.res.selected("pure_MMd0")
        dom_x = [int(np.argmax(r.metrics.ddx_amplitude[1:]) + 1) for r in sel]
        dom_z = [int(np.argmax(r.metrics.ddz_amplitude[1:]) + 1) for r in sel]
        self.spectra("14", "pure_MMd0", "Spectra of xM'' (a) and zM'' (b), amplitude / largest "
                     "amplitude against f/f_exc; pure rolling, MMd = 0", [Check(
                         "spectra: xM'' dominated by f, zM'' by 2f (Fig. 14)",
                         f"dominant harmonic of xM'': {dom_x}, of zM'': {dom_z} (for G = "
                         f"{', '.join(f'{r.G / MN:g}' for r in sel)})",
                         bool(sel) and all(n == 1 for n in dom_x) and all(n == 2 for n in dom_z))])

    def fig15(self) -> None:
        ratios = {g: _amp(r, "ddz", 2) / _amp(r, "ddz", 1) for g in (5, 70)
                  if (r := self.res.at("pure_MMd5", g * MN)) is not None}
        diffs = []
        for r5 in self.res.selected("pure_MMd5"):
            r0 = self.res.at("pure_MMd0", r5.G)
            if r0 is not None and r0.ok:
                a0 = plot.normalised_spectrum(from_result(r0.outcome), "ddx_M")
                a5 = plot.normalised_spectrum(from_result(r5.outcome), "ddx_M")
                diffs.append(float(np.max(np.abs(a0 - a5))))
        r5, r70 = ratios.get(5, math.nan), ratios.get(70, math.nan)
        self.spectra("15", "pure_MMd5", "Spectra of xM'' (a) and zM'' (b); pure rolling, MMd = "
                     "0.05 M0", [Check(
                         "zM'' has components at f and 2f; A(2f)/A(f) falls from 1.11 (G = 5) to "
                         "0.24 (G = 70); the xM'' spectrum is virtually unchanged (Fig. 15)",
                         f"A(2f)/A(f) of zM'': {_fmt(r5)} (G = 5), {_fmt(r70)} (G = 70); "
                         f"normalised xM'' spectra differ from MMd = 0 by at most "
                         f"{_fmt(max(diffs, default=math.nan), 2)}",
                         bool(abs(r5 - 1.11) < 0.15 and abs(r70 - 0.24) < 0.05
                              and max(diffs, default=1) < 0.05)
                         if not math.isnan(r5 + r70) else None)])

    def area(self, number: str, pure: bool, checks_for: Callable[[Dict[str, Any]], List[Check]],
             caption: str) -> None:
        names = ("pure_MMd0", "pure_MMd5") if pure else ("slip_MMd0", "slip_MMd5")
        curves, data, units = {}, {}, {"G": "Pa"}
        info: Dict[str, Any] = {}
        for name, label in zip(names, ("MMd = 0", "MMd = 0.05 M0")):
            runs = self.res.study(name)
            area = _metric(runs, "area")
            data.setdefault("G", _G(runs))
            data[f"area_{name}"] = area
            units[f"area_{name}"] = "m^2/s^4"
            curves[label] = area
            info[name] = (runs, area)
        kind = "pure rolling" if pure else "stick-slip, mu = 0.5"
        f = self.save(plot.plot_sweep(data.get("G", []), curves, "soil.G", "area",
                                      title=f"Fig. {number}: {kind}"), f"fig{number}")
        d = self.table(f"fig{number}", data, units)
        self.add(number, caption, [f], [d], checks_for(info))

    def fig16(self) -> None:
        def checks(info: Dict[str, Any]) -> List[Check]:
            r0, a0 = info["pure_MMd0"]
            r5, a5 = info["pure_MMd5"]
            g0, g5 = _argmax_G(r0, a0), _argmax_G(r5, a5)
            return [Check("zM''–xM'' area largest at G = 20–25 for MMd = 0 (Figs. 13a, 16); "
                          "with MMd = 0.05 M0 the area is largest at G = 40 (Fig. 16)",
                          f"largest area at G = {_fmt(g0)} (MMd = 0, {_fmt(np.nanmax(a0))} "
                          f"m²/s⁴) and G = {_fmt(g5)} (MMd = 0.05 M0, {_fmt(np.nanmax(a5))} "
                          "m²/s⁴)",
                          bool(20 <= g0 <= 25 and 35 <= g5 <= 45))]
        self.area("16", True, checks, "Area inside the zM''–xM'' figure against G; pure "
                  "rolling, MMd = 0 and 0.05 M0")

    def fig17(self) -> None:
        parts = []
        ok = True
        for r in self.res.selected("slip_MMd0"):
            p = self.res.at("pure_MMd0", r.G)
            if p is None or not p.ok:
                continue
            qx, qz = r.metrics.ddx_max / p.metrics.ddx_max, r.metrics.ddz_max / p.metrics.ddz_max
            ok = ok and qx < 1 and qz < 1
            parts.append(f"G = {r.G / MN:g}: xM''max {_fmt(qx, 2)}, zM''max {_fmt(qz, 2)}")
        self.accelerations("17", "slip_MMd0", "Steady-state xM'' (a) and zM'' (b) for four "
                           "soils; stick-slip (μ = 0.5), MMd = 0", [Check(
                               "stick-slip: amplitudes of xM'' and zM'' are much smaller than in "
                               "pure rolling; both peaks of xM'' are cut during slip, with a kink "
                               "at each stick/slip transition (Fig. 17)",
                               "ratio stick-slip / pure rolling: " + "; ".join(parts) +
                               " (cut peaks and kinks: see the figure)", ok if parts else None)])

    def fig18(self) -> None:
        sel = self.res.selected("slip_MMd5")
        halves = []
        for r in sel:
            sm = r.outcome.result.samples
            slip = np.asarray(sm.phase) != 0
            ddx = np.asarray(sm.ddx_M)
            pos, neg = np.count_nonzero(slip & (ddx > 0)), np.count_nonzero(slip & (ddx < 0))
            halves.append(neg / pos if pos else math.nan)
        ratios = {}
        for g in (5, 70):
            r5, r0 = self.res.at("slip_MMd5", g * MN), self.res.at("slip_MMd0", g * MN)
            if r5 is not None and r0 is not None and r5.ok and r0.ok:
                ratios[g] = r5.metrics.ddz_max / r0.metrics.ddz_max
        q5, q70 = ratios.get(5, math.nan), ratios.get(70, math.nan)
        self.accelerations("18", "slip_MMd5", "Steady-state xM'' (a) and zM'' (b) for four "
                           "soils; stick-slip (μ = 0.5), MMd = 0.05 M0", [Check(
                               "MMd = 0.05 M0: the negative slip phase lasts about half as long "
                               "as the positive one; positive zM'' amplitudes are 2 (G = 5) to "
                               "7.6 (G = 70) times those at MMd = 0 (Fig. 18)",
                               "slip time with xM'' < 0 over slip time with xM'' > 0 (the "
                               "paper's \"slip phase in the negative horizontal acceleration "
                               f"range\"): {', '.join(_fmt(h, 2) for h in halves)} (G = "
                               f"{', '.join(f'{r.G / MN:g}' for r in sel)}); zM''max ratio to "
                               f"MMd = 0: {_fmt(q5, 2)} (G = 5), {_fmt(q70, 2)} (G = 70)",
                               bool(halves and all(0.35 <= h <= 0.65 for h in halves)
                                    and abs(q5 - 2) < 0.5 and abs(q70 - 7.6) < 1.5)
                               if not math.isnan(q5 + q70) else None)])

    def fig19(self) -> None:
        sel = self.res.selected("slip_MMd0")
        even_x = max((max(_amp(r, "ddx", n) for n in (2, 4, 6)) / _amp(r, "ddx", 1)
                      for r in sel), default=math.nan)
        odd_z = max((max(_amp(r, "ddz", n) for n in (1, 3, 5)) / _amp(r, "ddz", 2)
                     for r in sel), default=math.nan)
        dom_z = [int(np.argmax(r.metrics.ddz_amplitude[1:]) + 1) for r in sel]
        self.spectra("19", "slip_MMd0", "Spectra of xM'' (a) and zM'' (b); stick-slip, MMd = 0",
                     [Check("MMd = 0: xM'' has only odd harmonics (f, 3f, 5f …), zM'' only even "
                            "ones (2f, 4f …), largest at 2f (Fig. 19)",
                            f"largest even harmonic of xM'' / A(f): {_fmt(even_x, 2)}; largest "
                            f"odd harmonic of zM'' / A(2f): {_fmt(odd_z, 2)}; dominant harmonic "
                            f"of zM'': {dom_z}",
                            bool(even_x < 1e-3 and odd_z < 1e-3 and all(n == 2 for n in dom_z))
                            if sel else None)])

    def fig20(self) -> None:
        sel = self.res.selected("slip_MMd5")
        ratios = {g: _amp(r, "ddz", 2) / _amp(r, "ddz", 1) for g in (5, 25, 70)
                  if (r := self.res.at("slip_MMd5", g * MN)) is not None}
        dom = {r.G / MN: (int(np.argmax(r.metrics.ddx_amplitude[1:]) + 1),
                          int(np.argmax(r.metrics.ddz_amplitude[1:]) + 1)) for r in sel}
        want = {5: 0.65, 25: 0.38, 70: 1.03}
        self.spectra("20", "slip_MMd5", "Spectra of xM'' (a) and zM'' (b); stick-slip, MMd = "
                     "0.05 M0", [Check(
                         "MMd = 0.05 M0: spectra hold odd and even harmonics, dominated by f "
                         "except at G = 70; in zM'', A(2f)/A(f) is 0.65 (G = 5), 0.38 (G = 25), "
                         "about 1.03 (G = 70) (Fig. 20)",
                         "A(2f)/A(f) of zM'': " + ", ".join(
                             f"{_fmt(v, 2)} (G = {g})" for g, v in ratios.items()) +
                         "; dominant harmonics (xM'', zM''): " + ", ".join(
                             f"G = {g:g}: {v}" for g, v in dom.items()),
                         bool(all(abs(ratios[g] - w) < 0.25 * w for g, w in want.items()))
                         if all(g in ratios for g in want) else None)])

    def fig21(self) -> None:
        files, data = [], []
        asym = {}
        for part, study in (("a", "slip_MMd0"), ("b", "slip_MMd5")):
            sel = self.res.selected(study)
            files.append(self.save(plot.plot_figure_eight(
                self.states(sel), title=f"Fig. 21{part}: {STUDIES[study][3]}"), f"fig21{part}"))
            data.append(self.time_table(f"fig21{part}", sel, ("ddx_M", "ddz_M"),
                                        lambda r: f"G{r.G / MN:g}"))
            asym[study] = max((_amp(r, "ddz", 1) / _amp(r, "ddz", 2) for r in sel), default=0)
        self.add("21", "zM'' over xM''; stick-slip, MMd = 0 (a) and MMd = 0.05 M0 (b)", files,
                 data, [Check(
                     "the zM''–xM'' plot is a twisted \"bow tie\" with MMd = 0.05 M0 (Fig. 21); "
                     "with MMd = 0 it stays symmetric about the vertical axis",
                     f"largest A(f)/A(2f) of zM'': {_fmt(asym['slip_MMd0'], 2)} (MMd = 0), "
                     f"{_fmt(asym['slip_MMd5'], 2)} (MMd = 0.05 M0); shape: see the figure",
                     bool(asym["slip_MMd0"] < 1e-3 and asym["slip_MMd5"] > 0.1))])

    def fig22(self) -> None:
        def checks(info: Dict[str, Any]) -> List[Check]:
            r0, a0 = info["slip_MMd0"]
            r5, a5 = info["slip_MMd5"]
            decreasing = bool(np.all(np.diff(a0) < 0))
            mins, maxs = local_extrema(_G(r5) / MN, a5)
            above = bool(np.all(a5 > a0)) if len(a5) == len(a0) else None
            return [Check("stick-slip, MMd = 0: the area decreases continuously with G; MMd = "
                          "0.05 M0: the area has a minimum at G = 20 and a maximum at G = 45 "
                          "(Fig. 22), above the MMd = 0 curve everywhere",
                          f"MMd = 0: {'decreasing' if decreasing else 'not monotonic'} "
                          f"({_fmt(a0[0] if len(a0) else math.nan)} → "
                          f"{_fmt(a0[-1] if len(a0) else math.nan)} m²/s⁴); MMd = 0.05 M0: "
                          f"local minima at G = {_list(mins)}, local maxima at G = {_list(maxs)}, "
                          f"largest at G = {_fmt(_argmax_G(r5, a5))}; above MMd = 0 everywhere: "
                          f"{above}",
                          bool(decreasing and 20 in mins and _argmax_G(r5, a5) == 45 and above))]
        self.area("22", False, checks, "Area inside the zM''–xM'' figure against G; stick-slip "
                  "(μ = 0.5), MMd = 0 and 0.05 M0")

    def all(self) -> None:
        for step in (self.fig07_08, self.fig09, self.fig10, self.fig11, self.fig12, self.fig13,
                     self.fig14, self.fig15, self.fig16, self.fig17, self.fig18, self.fig19,
                     self.fig20, self.fig21, self.fig22):
            try:
                step()
            except Exception as exc:  # one broken figure must not lose the others
                name = step.__name__.replace("fig", "")
                self.add(name, f"could not be drawn: {type(exc).__name__}: {exc}", [], [], [])


def write_cases_csv(path: Path, runs: Sequence[Run]) -> None:
    """Every case: study, parameters, status, diagnostics and scalar metrics."""
    cols: Dict[str, List[Any]] = {k: [] for k in (
        "study", "soil.G", "trough.a", "trough.k", "contact.pure_rolling", "MMd_fraction",
        "status", "periods_to_steady", "multiplicity")}
    names = list(core.Metrics.scalar_names)
    for n in names:
        cols[n] = []
    for r in runs:
        res = r.outcome.result
        cols["study"].append(r.study)
        cols["soil.G"].append(float(r.G))
        cols["trough.a"].append(float(r.a))
        cols["trough.k"].append(float(r.k))
        cols["contact.pure_rolling"].append(bool(r.pure_rolling))
        cols["MMd_fraction"].append(float(r.MMd_fraction))
        cols["status"].append(res.status.name if r.outcome.valid else "invalid")
        cols["periods_to_steady"].append(res.diagnostics.periods_to_steady)
        cols["multiplicity"].append(res.diagnostics.multiplicity)
        for n in names:
            cols[n].append(float(getattr(r.metrics, n)) if r.ok else math.nan)
    units = {"soil.G": "Pa", "trough.a": "m", **dict(core.Metrics.units)}
    write_table(path, cols, units)


def write_report(out: Path, writer: Writer, runs: Sequence[Run], seconds: float) -> Path:
    """report.md: each figure beside the paper's statements and the computed numbers."""
    n_ok = sum(1 for r in runs if r.ok and r.outcome.result.status.name == "steady_state")
    failed = [r for r in runs if not (r.ok and r.outcome.result.status.name == "steady_state")]
    checks = [c for f in writer.figures for c in f.checks]
    agree = sum(1 for c in checks if c.agrees is True)
    differ = sum(1 for c in checks if c.agrees is False)
    lines = [
        "# Reproduction of Paulmichl, Adam & Adam (2019), Figs. 7–22",
        "",
        f"Generated by `python3 -m oscidrum.paper` (oscidrum {core.__version__}): "
        f"{len(runs)} cases in {seconds:.1f} s, {n_ok} reached a steady state. The paper's "
        "statements are quoted from MODEL.md section 8. A verdict compares the computed numbers "
        "with them within a tolerance stated in `oscidrum/paper.py`; shapes (kinks, nodes, "
        "bow ties) are left to the eye.",
        "",
        f"**Summary: {agree} statements reproduced, {differ} not reproduced, "
        f"{len(checks) - agree - differ} to judge from the figures.**",
        "",
    ]
    if (out / "validation.md").exists():
        lines += ["The C++ validation table is in [validation.md](validation.md).", ""]
    lines += ["Set-up: HAMM HD+ 90 VO (paper Table 1), Table 2 soil coefficients, circular "
              "trough R = 0.606 m unless stated, μ = 0.5 for stick-slip, MMd = 0.05 M0 = "
              f"{0.05 * core.Roller().M0:.1f} N m where stated. Radius study R = "
              f"{', '.join(f'{R:g}' for R in R_VALUES)} m (0.62 m is our choice: the paper does "
              "not print the third radius). All cases and metrics: [cases.csv](cases.csv).", ""]
    if failed:
        lines += ["Cases without a steady state:", ""]
        lines += [f"- {r.study}, G = {r.G / MN:g} MN/m²: "
                  f"{r.outcome.error if not r.outcome.valid else r.outcome.result.status.name}"
                  for r in failed]
        lines.append("")
    mark = {True: "✅ reproduced", False: "❌ not reproduced", None: "👁 judge from the figure"}
    for f in writer.figures:
        lines += [f"## Fig. {f.number}", "", f.caption + ".", ""]
        lines += [f"![Fig. {f.number}]({name})" for name in f.files]
        if f.files:
            lines.append("")
        if f.data:
            lines += ["Data: " + ", ".join(f"[{d}]({d})" for d in f.data), ""]
        if f.checks:
            lines += ["| the paper (MODEL.md §8) | computed here | verdict |", "|---|---|---|"]
            for c in f.checks:
                lines.append(f"| {c.claim} | {c.computed} | {mark[c.agrees]} |")
            lines.append("")
    path = out / "report.md"
    path.write_text("\n".join(lines), encoding="utf-8")
    return path


def reproduce(out: str | os.PathLike, fmt: str = "png", threads: int = 0,
              G_values: Sequence[float] = G_VALUES, samples_per_period: Optional[int] = None,
              progress: bool = False) -> Path:
    """Run every study, write figures, data and report.md into `out`; returns the report."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    runs = build_runs(G_values, samples_per_period)

    tty = sys.stderr.isatty()

    def show(done: int, total: int) -> None:
        if tty:
            print(f"\r[{done}/{total}] cases", end="" if done < total else "\n",
                  file=sys.stderr, flush=True)
        elif done == total or done % max(total // 10, 1) == 0:
            print(f"[{done}/{total}] cases", file=sys.stderr, flush=True)

    start = time.perf_counter()
    outcomes = core.run_study([r.case for r in runs], threads=threads, keep_samples=True,
                              progress=show if progress else None)
    seconds = time.perf_counter() - start
    for run, outcome in zip(runs, outcomes):
        run.outcome = outcome
    write_cases_csv(out / "cases.csv", runs)
    writer = Writer(out, fmt, Results(runs))
    writer.all()
    return write_report(out, writer, runs, seconds)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m oscidrum.paper",
                                     description="Reproduce the paper's Figs. 7-22 and write "
                                     "report.md.")
    parser.add_argument("--out", required=True, help="output directory")
    parser.add_argument("--format", choices=("png", "svg"), default="png")
    parser.add_argument("--threads", type=int, default=0, help="worker threads (0: all cores)")
    parser.add_argument("--G", help="comma-separated subset of Table 2's G in MN/m^2 "
                        "(default: all 14), e.g. 5,25,50,70")
    parser.add_argument("--samples-per-period", type=int, default=None,
                        help="samples per excitation period (default: the library's)")
    parser.add_argument("--quiet", action="store_true", help="no progress on stderr")
    args = parser.parse_args(argv)
    G_values = G_VALUES
    if args.G:
        try:
            G_values = tuple(sorted(float(g) * MN for g in args.G.split(",")))
        except ValueError:
            parser.error(f"--G must be numbers separated by commas; got '{args.G}'")
    try:
        report = reproduce(args.out, args.format, args.threads, G_values,
                           args.samples_per_period, progress=not args.quiet)
    except core.Error as exc:
        print(f"oscidrum.paper: error: {exc}", file=sys.stderr)
        return 1
    print(report)
    return 0


if __name__ == "__main__":
    sys.exit(main())
