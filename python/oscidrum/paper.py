"""Reproduce the paper's parametric studies (Figs. 7-22) and write a Markdown report.

    /usr/bin/python3 -m oscidrum.paper --out DIR [--format png|svg] [--threads N] [--quiet]

The studies and the check of the paper's statements are the library's (``src/validation.cpp``,
the single definition also used by ``oscidrum validate`` and ``oscidrum paper``):
:func:`oscidrum.run_paper_studies` runs every case of :func:`oscidrum.paper_series` on C++
threads and :func:`oscidrum.validate` checks every result the paper states (docs/validation.md).
This module only draws and writes. Into DIR go:

* ``figNN*.png`` (or svg) for Figs. 7-22 and the data behind each as ``figNN*.csv``
  (``name[unit]`` columns);
* ``cases.csv``: every case with its series, parameters, status and metrics;
* ``validation.md`` and ``validation.csv``: the validation table;
* ``report.md``: each figure beside the validation rows that concern it (by the row's
  ``figure`` field), and the whole table at the end.

Exit status: 0 if every checkable row of the table agrees, 1 otherwise (or on an error).
"""

from __future__ import annotations

import argparse
import csv
import io
import os
import re
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Set

import numpy as np

from . import _core as core
from . import plot
from ._files import write_file
from ._interrupt import run_main, signals_deferred
from .data import from_result, write_table

MN = 1e6
#: The four soils of the paper's time-history, spectrum and z-x figures [Pa].
SELECTED_G = (5 * MN, 25 * MN, 50 * MN, 70 * MN)

# Series of oscidrum.paper_series() drawn in the figures (ids defined in src/validation.cpp).
ROLLING = "rolling_MMd0_R0.606"
ROLLING_MMD = "rolling_MMd0.05_R0.606"
SLIP = "stickslip_MMd0_R0.606"
SLIP_MMD = "stickslip_MMd0.05_R0.606"
RADII = ("rolling_MMd0_R0.603", ROLLING, "rolling_MMd0_R0.620", "rolling_MMd0_R0.650")
CIRCLE = "shape_circle_R0.603"
SPIRAL = "shape_spiral_k0.002_a0.601"
SOFT = "rolling_soft_limit"

#: Title of validation.md (as `oscidrum paper` writes it without Python).
VALIDATION_TITLE = "# Validation against the paper\n\n"


@dataclass
class Run:
    """One case of the reproduction: its series, G [Pa] and what it produced."""

    series: Any  #: oscidrum.PaperSeries
    G: float
    status: str
    metrics: Any
    diagnostics: Any
    result: Any  #: oscidrum.Result with its steady-state samples

    @property
    def ok(self) -> bool:
        return self.status == "steady_state" and len(self.result.samples) > 0

    def state(self, label: str = "") -> Any:
        return from_result(self.result, label=label, metrics=self.metrics,
                           parameters=core.paper_case(self.series, self.G).to_dict())


def runs_of(results: Sequence[Any]) -> List[Run]:
    """Every case of run_paper_studies(keep_samples=True) as a Run, in paper_series() order."""
    runs = []
    for sr in results:
        for j, G in enumerate(sr.series.G):
            runs.append(Run(sr.series, G, sr.status[j], sr.metrics[j], sr.diagnostics[j],
                            sr.results[j]))
    return runs


class Results:
    """Look-ups into the finished runs."""

    def __init__(self, runs: List[Run]):
        self.runs = runs

    def series(self, sid: str) -> List[Run]:
        """The runs of one series, by increasing G."""
        return sorted((r for r in self.runs if r.series.id == sid), key=lambda r: r.G)

    def description(self, sid: str) -> str:
        runs = self.series(sid)
        return runs[0].series.description if runs else sid

    def at(self, sid: str, G: float) -> Optional[Run]:
        return next((r for r in self.series(sid) if abs(r.G - G) < 1e-6 * G), None)

    def selected(self, sid: str) -> List[Run]:
        """The runs of the four soils of SELECTED_G that reached a steady state."""
        return [r for r in self.series(sid) if r.G in SELECTED_G and r.ok]


def _g_label(G: float) -> str:
    return f"G = {G / MN:g} MN/m²"


def _metric(runs: Sequence[Run], name: str) -> np.ndarray:
    return np.array([getattr(r.metrics, name) if r.ok else np.nan for r in runs])


def _G(runs: Sequence[Run]) -> np.ndarray:
    return np.array([r.G for r in runs])


def _alt(name: str) -> str:
    """The alt text of a figure file: "fig08a.png" -> "Fig. 8a"."""
    match = re.match(r"fig0*(\d+[a-z]?)", name)
    return f"Fig. {match.group(1)}" if match else name


def figures_of(figure: str) -> Set[int]:
    """The figure numbers a validation row's `figure` field names: "Fig. 9a" -> {9},
    "Figs. 11, 14" -> {11, 14}; "Sect. 3.4" -> set()."""
    found: Set[int] = set()
    for match in re.finditer(r"Figs?\.\s*([0-9a-z,\s]+)", figure):
        found.update(int(n) for n in re.findall(r"\d+", match.group(1)))
    return found


@dataclass
class Figure:
    """One of the paper's figures: the files written for it."""

    number: int
    caption: str
    files: List[str]
    data: List[str]
    error: str = ""


class Writer:
    """Draws the figures and writes their data."""

    def __init__(self, out: Path, fmt: str, results: Results):
        self.out, self.fmt, self.res = out, fmt, results
        self.figures: List[Figure] = []

    # -- helpers ---------------------------------------------------------------------------
    def save(self, fig: Any, name: str) -> str:
        return plot.save(fig, self.out / f"{name}.{self.fmt}", self.fmt).name

    def table(self, name: str, columns: Dict[str, Sequence[Any]], units: Dict[str, str]) -> str:
        write_table(self.out / f"{name}.csv", columns, units)
        return f"{name}.csv"

    def states(self, runs: Sequence[Run],
               label: Callable[[Run], str] = lambda r: _g_label(r.G)) -> List[Any]:
        return [r.state(label(r)) for r in runs if r.ok]

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
            state = run.state()
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
            state = run.state()
            for column in ("ddx_M", "ddz_M"):
                key = f"{column}_G{run.G / MN:g}_normalised"
                data[key] = plot.normalised_spectrum(state, column, 10)
                unit_of[key] = "-"
        return self.table(name, data, unit_of)

    def add(self, number: int, caption: str, files: List[str], data: List[str]) -> None:
        self.figures.append(Figure(number, caption, files, data))

    # -- figures ---------------------------------------------------------------------------
    def fig07_08(self) -> None:
        circle = self.res.series(CIRCLE)[0]
        spiral = self.res.series(SPIRAL)[0]
        names = {CIRCLE: "circle", SPIRAL: "spiral"}
        runs = [r for r in (circle, spiral) if r.ok]
        long_names = {CIRCLE: f"circle R = {circle.series.a:g} m",
                      SPIRAL: f"spiral k = {spiral.series.k:g}, a = {spiral.series.a:g} m"}
        states = self.states(runs, lambda r: long_names[r.series.id])
        # The titles name the figure; the plots add what the cases share (G, pure rolling, MMd,
        # f) from their parameters, the legend the troughs.
        f7 = self.save(plot.plot_accelerations(states, title="Fig. 7"), "fig07")
        d7 = self.time_table("fig07", runs, ("ddx_M", "ddz_M"), lambda r: names[r.series.id])
        f8a = self.save(plot.plot_delta_phi(states, title="Fig. 8a"), "fig08a")
        f8b = self.save(plot.plot_figure_eight(states, title="Fig. 8b"), "fig08b")
        d8 = self.time_table("fig08", runs, ("delta", "ddx_M", "ddz_M"),
                             lambda r: names[r.series.id])
        self.add(7, "Time history of xM'' (a) and zM'' (b), G = 5 MN/m², MMd = 0, pure "
                 "rolling; circular against spiral trough", [f7], [d7])
        self.add(8, "Position angle δ (a) and zM'' over xM'' (b), same cases", [f8a, f8b], [d8])

    def fig09(self) -> None:
        data: Dict[str, Sequence[Any]] = {}
        units: Dict[str, str] = {"G": "Pa"}
        curves_x, curves_z = {}, {}
        for sid in RADII:
            runs = self.res.series(sid)
            R = runs[0].series.a
            data.setdefault("G", _G(runs))
            x, z = _metric(runs, "ddx_max"), _metric(runs, "ddz_max")
            data[f"ddx_max_R{R:g}"], data[f"ddz_max_R{R:g}"] = x, z
            units[f"ddx_max_R{R:g}"] = units[f"ddz_max_R{R:g}"] = "m/s^2"
            curves_x[f"R = {R:g} m"] = x
            curves_z[f"R = {R:g} m"] = z
        G = data["G"]
        fa = self.save(plot.plot_sweep(G, curves_x, "soil.G", "ddx_max",
                                       title="Fig. 9a: pure rolling, MMd = 0"), "fig09a")
        fb = self.save(plot.plot_sweep(G, curves_z, "soil.G", "ddz_max",
                                       title="Fig. 9b: pure rolling, MMd = 0"), "fig09b")
        d = self.table("fig09", data, units)
        self.add(9, "Peak xM'' (a) and zM'' (b) against G for four trough radii; pure rolling, "
                 "MMd = 0", [fa, fb], [d])

    def fig10(self) -> None:
        runs, soft = self.res.series(ROLLING), self.res.series(SOFT)
        fa = self.save(plot.plot_torque_phi(self.states(self.res.selected(ROLLING)),
                                            title="Fig. 10a"), "fig10a")
        lag, lag_soft = _metric(runs, "phi_lag"), _metric(soft, "phi_lag")
        fb = self.save(plot.plot_sweep(None, {"Table 2": (_G(runs), lag),
                                              "softer (Appendix B)": (_G(soft), lag_soft)},
                                       "soil.G", "phi_lag",
                                       title="Fig. 10b: pure rolling, MMd = 0"), "fig10b")
        da = self.time_table("fig10a", self.res.selected(ROLLING), ("phi", "torque"),
                             lambda r: f"G{r.G / MN:g}")
        both = soft + runs
        db = self.table("fig10b", {"G": _G(both), "phi_lag": _metric(both, "phi_lag"),
                                   "series": [r.series.id for r in both]},
                        {"G": "Pa", "phi_lag": "pi rad"})
        self.add(10, "Drum rotation φ and excitation torque over one period (a); phase lag "
                 "between MMu(t) and φ against G (b), with softer soils than Table 2's towards "
                 "G → 0; pure rolling, MMd = 0", [fa, fb], [da, db])

    def accelerations(self, number: int, sid: str, caption: str) -> None:
        sel = self.res.selected(sid)
        f = self.save(plot.plot_accelerations(self.states(sel), title=f"Fig. {number}"),
                      f"fig{number}")
        d = self.time_table(f"fig{number}", sel, ("ddx_M", "ddz_M", "phase"),
                            lambda r: f"G{r.G / MN:g}")
        self.add(number, caption, [f], [d])

    def fig11(self) -> None:
        self.accelerations(11, ROLLING, "Steady-state xM'' (a) and zM'' (b) for four soils; "
                           "pure rolling, MMd = 0")

    def fig12(self) -> None:
        runs = self.res.series(ROLLING)
        psi = _metric(runs, "psi_xz")
        f = self.save(plot.plot_sweep(_G(runs), {"": psi}, "soil.G", "psi_xz",
                                      title="Fig. 12: pure rolling, MMd = 0"), "fig12")
        d = self.table("fig12", {"G": _G(runs), "psi_xz": psi}, {"G": "Pa", "psi_xz": "rad"})
        self.add(12, "Phase lag ψ between xM'' and zM'' against G; pure rolling, MMd = 0 "
                 "(ψ = θ₂(zM'') − 2 θ₁(xM''), docs/model.md section 8)", [f], [d])

    def figure_eights(self, number: int, parts: Sequence[str], caption: str) -> None:
        files, data = [], []
        for part, sid in zip("ab", parts):
            sel = self.res.selected(sid)
            files.append(self.save(plot.plot_figure_eight(
                self.states(sel), title=f"Fig. {number}{part}"), f"fig{number}{part}"))
            data.append(self.time_table(f"fig{number}{part}", sel, ("ddx_M", "ddz_M"),
                                        lambda r: f"G{r.G / MN:g}"))
        self.add(number, caption, files, data)

    def fig13(self) -> None:
        self.figure_eights(13, (ROLLING, ROLLING_MMD), "zM'' over xM'', MMd = 0 (a) and "
                           "MMd = 0.05 M0 (b); pure rolling")

    def spectra(self, number: int, sid: str, caption: str) -> None:
        sel = self.res.selected(sid)
        f = self.save(plot.plot_spectra(self.states(sel), title=f"Fig. {number}"),
                      f"fig{number}")
        d = self.spectra_table(f"fig{number}", sel)
        self.add(number, caption, [f], [d])

    def fig14(self) -> None:
        self.spectra(14, ROLLING, "Spectra of xM'' (a) and zM'' (b), amplitude / largest "
                     "amplitude against f/f_exc; pure rolling, MMd = 0")

    def fig15(self) -> None:
        self.spectra(15, ROLLING_MMD, "Spectra of xM'' (a) and zM'' (b); pure rolling, MMd = "
                     "0.05 M0")

    def area(self, number: int, sids: Sequence[str], kind: str, caption: str) -> None:
        curves, data, units = {}, {}, {"G": "Pa"}
        for sid, label, suffix in zip(sids, ("MMd = 0", "MMd = 0.05 M0"), ("MMd0", "MMd5")):
            runs = self.res.series(sid)
            area = _metric(runs, "area")
            data.setdefault("G", _G(runs))
            column = f"area_{'pure' if runs[0].series.pure_rolling else 'slip'}_{suffix}"
            data[column] = area
            units[column] = "m^2/s^4"
            curves[label] = area
        f = self.save(plot.plot_sweep(data["G"], curves, "soil.G", "area",
                                      title=f"Fig. {number}: {kind}"), f"fig{number}")
        d = self.table(f"fig{number}", data, units)
        self.add(number, caption, [f], [d])

    def fig16(self) -> None:
        self.area(16, (ROLLING, ROLLING_MMD), "pure rolling", "Area inside the zM''–xM'' "
                  "figure against G; pure rolling, MMd = 0 and 0.05 M0")

    def fig17(self) -> None:
        self.accelerations(17, SLIP, "Steady-state xM'' (a) and zM'' (b) for four soils; "
                           "stick-slip (μ = 0.5), MMd = 0")

    def fig18(self) -> None:
        self.accelerations(18, SLIP_MMD, "Steady-state xM'' (a) and zM'' (b) for four soils; "
                           "stick-slip (μ = 0.5), MMd = 0.05 M0")

    def fig19(self) -> None:
        self.spectra(19, SLIP, "Spectra of xM'' (a) and zM'' (b); stick-slip, MMd = 0")

    def fig20(self) -> None:
        self.spectra(20, SLIP_MMD, "Spectra of xM'' (a) and zM'' (b); stick-slip, MMd = "
                     "0.05 M0")

    def fig21(self) -> None:
        self.figure_eights(21, (SLIP, SLIP_MMD), "zM'' over xM''; stick-slip, MMd = 0 (a) and "
                           "MMd = 0.05 M0 (b)")

    def fig22(self) -> None:
        self.area(22, (SLIP, SLIP_MMD), "stick-slip, mu = 0.5", "Area inside the zM''–xM'' "
                  "figure against G; stick-slip (μ = 0.5), MMd = 0 and 0.05 M0")

    def all(self) -> None:
        for number, step in ((7, self.fig07_08), (9, self.fig09), (10, self.fig10),
                             (11, self.fig11), (12, self.fig12), (13, self.fig13),
                             (14, self.fig14), (15, self.fig15), (16, self.fig16),
                             (17, self.fig17), (18, self.fig18), (19, self.fig19),
                             (20, self.fig20), (21, self.fig21), (22, self.fig22)):
            try:
                step()
            except Exception as exc:  # one broken figure must not lose the others
                self.figures.append(Figure(number, "", [], [],
                                           f"could not be drawn: {type(exc).__name__}: {exc}"))


def write_cases_csv(path: Path, runs: Sequence[Run]) -> None:
    """Every case: series, parameters, status, diagnostics and scalar metrics."""
    cols: Dict[str, List[Any]] = {k: [] for k in (
        "series", "soil.G", "soil.input", "trough.a", "trough.k", "contact.pure_rolling",
        "contact.mu", "MMd_fraction", "status", "periods_to_steady", "multiplicity")}
    names = list(core.Metrics.scalar_names)
    for n in names:
        cols[n] = []
    for r in runs:
        s = r.series
        cols["series"].append(s.id)
        cols["soil.G"].append(float(r.G))
        cols["soil.input"].append(core.paper_case(s, r.G).get("soil.input"))
        cols["trough.a"].append(float(s.a))
        cols["trough.k"].append(float(s.k))
        cols["contact.pure_rolling"].append(bool(s.pure_rolling))
        cols["contact.mu"].append(float(s.mu))
        cols["MMd_fraction"].append(float(s.MMd_fraction))
        cols["status"].append(r.status)
        cols["periods_to_steady"].append(r.diagnostics.periods_to_steady)
        cols["multiplicity"].append(r.diagnostics.multiplicity)
        for n in names:
            cols[n].append(float(getattr(r.metrics, n)) if r.ok else np.nan)
    units = {"soil.G": "Pa", "trough.a": "m", **dict(core.Metrics.units)}
    write_table(path, cols, units)


#: The fields of a ValidationRow, in table order (the columns of validation.csv).
ROW_FIELDS = ("id", "figure", "claim", "paper", "oscidrum", "rule", "agrees", "checkable", "note")


def write_validation(out: Path, rows: Sequence[Any]) -> None:
    """validation.md (the table of docs/validation.md) and validation.csv (one row per claim,
    the columns of ROW_FIELDS; the same file as `oscidrum validate --csv`)."""
    write_file(out / "validation.md", VALIDATION_TITLE + core.validation_markdown(rows))
    fh = io.StringIO()
    writer = csv.writer(fh, lineterminator="\n")
    writer.writerow(ROW_FIELDS)
    for r in rows:
        writer.writerow([("true" if v else "false") if isinstance(v, bool) else v
                         for v in (getattr(r, f) for f in ROW_FIELDS)])
    write_file(out / "validation.csv", fh.getvalue())


def all_agree(rows: Sequence[Any]) -> bool:
    """True if every checkable row agrees."""
    return all(r.agrees for r in rows if r.checkable)


def write_report(out: Path, writer: Writer, runs: Sequence[Run], rows: Sequence[Any],
                 seconds: float) -> Path:
    """report.md: each figure beside the validation rows about it; the whole table at the end."""
    failed = [r for r in runs if r.status != "steady_state"]
    table = core.validation_markdown(rows)
    summary = table.rstrip().splitlines()[-1]
    shown = {f.number for f in writer.figures}
    elsewhere = [r for r in rows if not figures_of(r.figure) & shown]
    lines = [
        "# Reproduction of Paulmichl, Adam & Adam (2019), Figs. 7–22",
        "",
        f"Generated by `oscidrum paper` (the module `oscidrum.paper`, oscidrum {core.__version__}): "
        f"{len(runs)} cases in {seconds:.1f} s, {len(runs) - len(failed)} reached a steady "
        "state. The cases and the check of every result the paper states (docs/validation.md) "
        "are the library's (`src/validation.cpp`: `oscidrum.paper_series`, "
        "`oscidrum.validate`, the same as `oscidrum validate`); each figure is shown beside the "
        "rows of the validation table that concern it, and the whole table is at the end (also "
        "in [validation.md](validation.md) and [validation.csv](validation.csv)). Shapes "
        "(kinks, nodes, bow ties) are left to the eye.",
        "",
        f"**Summary: {summary}**",
        "",
        f"Set-up: HAMM HD+ 90 VO (paper Table 1), μ = 0.5 for stick-slip, MMd = 0.05 M0 = "
        f"{0.05 * core.Roller().M0:.1f} N m where stated. Every case and its metrics: "
        "[cases.csv](cases.csv). The series:",
        "",
        "| series | description | G [MN/m²] |",
        "|---|---|---|",
    ]
    for sr in dict.fromkeys(r.series.id for r in runs):
        s = next(r.series for r in runs if r.series.id == sr)
        lines.append(f"| `{s.id}` | {s.description} | "
                     f"{', '.join(f'{G / MN:g}' for G in s.G)} |")
    lines.append("")
    if failed:
        lines += ["Cases without a steady state:", ""]
        lines += [f"- {r.series.id}, G = {r.G / MN:g} MN/m²: {r.status}" for r in failed]
        lines.append("")
    if elsewhere:
        lines += ["## The whole study", "", "Rows of the validation table about every case or "
                  "about no figure drawn here:", "", core.validation_markdown(elsewhere)]
    for f in writer.figures:
        lines += [f"## Fig. {f.number}", ""]
        if f.error:
            lines += [f.error, ""]
            continue
        lines += [f.caption + ".", ""]
        lines += [f"![{_alt(name)}]({name})" for name in f.files]
        if f.files:
            lines.append("")
        if f.data:
            lines += ["Data: " + ", ".join(f"[{d}]({d})" for d in f.data), ""]
        mine = [r for r in rows if f.number in figures_of(r.figure)]
        if mine:
            lines += [core.validation_markdown(mine)]
        else:
            lines += ["No row of the validation table concerns this figure; judge it by eye.",
                      ""]
    lines += ["## Validation table", "", table]
    path = out / "report.md"
    write_file(path, "\n".join(lines))
    return path


@dataclass
class Reproduction:
    """What :func:`reproduce` wrote and found."""

    report: Path  #: report.md
    rows: List[Any]  #: the oscidrum.ValidationRow list
    results: List[Any]  #: the oscidrum.SeriesResult list (with samples)
    seconds: float  #: time of the simulations [s]

    @property
    def agrees(self) -> bool:
        """True if every checkable row of the validation table agrees."""
        return all_agree(self.rows)


def reproduce(out: str | os.PathLike, fmt: str = "png", threads: int = 0,
              progress: bool = False) -> Reproduction:
    """Run every study (oscidrum.run_paper_studies), validate it and write figures, data,
    validation.md/.csv and report.md into `out` (created if needed). Everything is written
    into a temporary folder inside `out` first and moved into place at the end, so that an
    interrupted or failed run leaves no partial output (the folder is removed)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=".partial-", dir=out))
    try:
        rep = _reproduce_into(staging, fmt, threads, progress)
        with signals_deferred():  # all files or none
            for item in sorted(staging.iterdir()):
                if item.is_file():
                    write_file(out / item.name, item.read_bytes())
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    rep.report = out / rep.report.name
    return rep


def _reproduce_into(out: Path, fmt: str, threads: int, progress: bool) -> Reproduction:
    tty = sys.stderr.isatty()

    def show(done: int, total: int) -> None:
        if tty:
            print(f"\r[{done}/{total}] cases", end="" if done < total else "\n",
                  file=sys.stderr, flush=True)
        elif done == total or done % max(total // 10, 1) == 0:
            print(f"[{done}/{total}] cases", file=sys.stderr, flush=True)

    start = time.perf_counter()
    results = core.run_paper_studies(threads=threads, keep_samples=True,
                                     progress=show if progress else None)
    seconds = time.perf_counter() - start
    rows = core.validate(results)
    runs = runs_of(results)
    write_cases_csv(out / "cases.csv", runs)
    write_validation(out, rows)
    writer = Writer(out, fmt, Results(runs))
    writer.all()
    report = write_report(out, writer, runs, rows, seconds)
    return Reproduction(report, rows, results, seconds)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python3 -m oscidrum.paper",
        description="Reproduce the paper's Figs. 7-22: run its studies, check every result it "
        "states and write figures, data, validation.md/.csv and report.md. Exit status 0 if "
        "every checkable claim agrees, 1 otherwise.")
    parser.add_argument("--out", required=True, help="output directory")
    parser.add_argument("--format", choices=("png", "svg"), default="png")
    parser.add_argument("--threads", type=int, default=0, help="worker threads (0: all cores)")
    parser.add_argument("--quiet", action="store_true", help="no progress on stderr")
    args = parser.parse_args(argv)
    try:
        rep = reproduce(args.out, args.format, args.threads, progress=not args.quiet)
    except (core.Error, OSError) as exc:
        print(f"oscidrum.paper: error: {exc}", file=sys.stderr)
        return 1
    print(rep.report)
    differ = [r for r in rep.rows if r.checkable and not r.agrees]
    for r in differ:
        print(f"oscidrum.paper: does not agree: {r.id} ({r.figure}): paper {r.paper}, oscidrum "
              f"{r.oscidrum}, rule {r.rule}", file=sys.stderr)
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(run_main(main, "oscidrum.paper"))
