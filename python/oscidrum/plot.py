"""Plots of steady states and studies (matplotlib, Agg: no display needed).

Every function takes steady states in any form :func:`oscidrum.data.as_steady_state` accepts (a
``Result``, a study's ``CaseOutcome``, a :class:`~oscidrum.data.SteadyState` read from the CLI's
CSV, or the CSV's path) and returns a :class:`matplotlib.figure.Figure`; :func:`save` writes it
as PNG or SVG. Figures are built with the object-oriented API (no pyplot state), so they are
safe in scripts, tests and threads; in Jupyter, ``display(fig)`` shows them.

Command line (the C++ CLI's ``oscidrum run --plot DIR`` calls the first form)::

    python3 -m oscidrum.plot case --csv FILE [--json FILE] --out DIR [--format png|svg]
    python3 -m oscidrum.plot sweep --csv results.csv --x soil.G --y area [--y ddx_max]
                                   [--group MMd_fraction] [--where contact.pure_rolling=true]
                                   --out DIR [--format png|svg]
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from .data import (SteadyState, as_steady_state, harmonic_amplitudes, read_case,
                   read_csv_columns, resolve_column, split_header)

# Axis labels with units (mathtext).
TAU_LABEL = r"$t\,/\,T_{exc}$ [-]  ($T_{exc} = 1/f$)"
DDX_LABEL = r"$\ddot{x}_M$ [m/s$^2$]"
DDZ_LABEL = r"$\ddot{z}_M$ [m/s$^2$] (down +)"
DELTA_LABEL = r"$\delta$ [rad]"
PHI_LABEL = r"$\varphi$ [rad]"
TORQUE_LABEL = r"$M_M(t)$ [kN m]"
FORCE_LABEL = r"contact force [kN]"
FREQ_LABEL = r"$f\,/\,f_{exc}$ [-]"
AMP_LABEL = r"$A\,/\,A_{max}$ [-]"

#: Display of swept keys and metrics: key -> (label, unit shown, factor from SI).
DISPLAY: Dict[str, Tuple[str, str, float]] = {
    "soil.G": (r"shear modulus $G$", r"MN/m$^2$", 1e-6),
    "soil.table2_G": (r"shear modulus $G$", r"MN/m$^2$", 1e-6),
    "trough.a": (r"trough radius $R$", "m", 1.0),
    "trough.k": (r"spiral parameter $k$", "-", 1.0),
    "MMd": (r"driving torque $M_{Md}$", "kN m", 1e-3),
    "MMd_fraction": (r"$M_{Md}/M_0$", "-", 1.0),
    "contact.mu": (r"friction coefficient $\mu$", "-", 1.0),
    "roller.f": (r"excitation frequency $f$", "Hz", 1.0),
    "area": (r"area inside $\ddot{z}_M$-$\ddot{x}_M$", r"m$^2$/s$^4$", 1.0),
    "ddx_max": (r"peak $\ddot{x}_M$", r"m/s$^2$", 1.0),
    "ddx_min": (r"min $\ddot{x}_M$", r"m/s$^2$", 1.0),
    "ddz_max": (r"peak $\ddot{z}_M$", r"m/s$^2$", 1.0),
    "ddz_min": (r"min $\ddot{z}_M$", r"m/s$^2$", 1.0),
    "phi_lag": (r"phase lag $M_{Mu}$ to $\varphi$", r"$\pi$ rad", 1.0),
    "phi_amplitude": (r"amplitude of $\varphi$", "rad", 1.0),
    "psi_xz": (r"phase lag $\psi$ between $\ddot{x}_M$ and $\ddot{z}_M$", "rad", 1.0),
    "stick_fraction": ("stick fraction", "-", 1.0),
    "slip_positive_fraction": ("slip+ fraction", "-", 1.0),
    "slip_negative_fraction": ("slip- fraction", "-", 1.0),
}

#: Colours of up to four cases (the paper's figures show four soils) and of more.
COLORS = ("black", "tab:red", "tab:blue", "tab:green", "tab:purple", "tab:orange", "tab:brown",
          "tab:pink", "tab:gray", "tab:olive", "tab:cyan")
MARKERS = ("+", "o", "s", "^", "v", "D", "x", "*", "<", ">", "p")
SLIP_COLORS = {1: ("tab:orange", "slip+ ($v_{rel} > 0$)"),
               -1: ("tab:cyan", "slip- ($v_{rel} < 0$)")}


def axis_label(key: str, unit: str = "") -> Tuple[str, float]:
    """(axis label with unit, factor from SI) for a swept key or a metric name."""
    name, csv_unit = split_header(key)
    unit = unit or csv_unit
    if name in DISPLAY:
        label, shown, factor = DISPLAY[name]
        return f"{label} [{shown}]", factor
    return (f"{name} [{unit}]" if unit else name), 1.0


def new_figure(nrows: int = 1, ncols: int = 1, width: float = 7.0,
               height: Optional[float] = None, **kwargs: Any) -> Tuple[Figure, Any]:
    """A Figure with an Agg canvas and its axes (squeezed like pyplot.subplots)."""
    fig = Figure(figsize=(width, height or 3.0 * nrows + 0.6), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(nrows, ncols, **kwargs)
    return fig, axes


def save(fig: Figure, path: str | os.PathLike, fmt: Optional[str] = None) -> Path:
    """Write `fig` to `path` (format from `fmt`, else from the suffix; png or svg)."""
    path = Path(path)
    fmt = (fmt or path.suffix.lstrip(".") or "png").lower()
    if fmt not in ("png", "svg"):
        raise ValueError(f"format must be png or svg; got '{fmt}'")
    if path.suffix.lower() != "." + fmt:
        path = path.with_suffix("." + fmt)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, format=fmt, dpi=150)
    return path


def _cases(cases: Any, labels: Optional[Sequence[str]]) -> List[SteadyState]:
    if not isinstance(cases, (list, tuple)):
        cases = [cases]
    out = []
    for i, case in enumerate(cases):
        label = labels[i] if labels is not None and i < len(labels) else ""
        state = as_steady_state(case, label=label)
        if label:
            state.label = label
        out.append(state)
    return out


def _label(state: SteadyState, i: int) -> str:
    return state.label or f"case {i + 1}"


def _window(state: SteadyState, periods: Optional[float]) -> np.ndarray:
    """Indices of the first `periods` excitation periods of the sampled window."""
    tau = state.tau()
    if periods is None:
        return np.arange(len(tau))
    return np.nonzero(tau < periods - 1e-9)[0]


def shade_phases(ax: Any, tau: np.ndarray, phase: np.ndarray) -> List[Patch]:
    """Shade the slip phases of a time plot (x axis tau = t/T); returns legend handles."""
    phase = np.asarray(phase).astype(int)
    handles = []
    if len(tau) < 2:
        return handles
    dtau = tau[1] - tau[0]
    for value, (color, name) in SLIP_COLORS.items():
        mask = phase == value
        if not mask.any():
            continue
        edges = np.diff(np.concatenate(([0], mask.astype(int), [0])))
        starts, ends = np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0]
        for a, b in zip(starts, ends):
            ax.axvspan(tau[a] - 0.5 * dtau, tau[b - 1] + 0.5 * dtau, color=color, alpha=0.2,
                       lw=0, zorder=0)
        handles.append(Patch(color=color, alpha=0.35, label=name))
    return handles


def _legend(ax: Any, extra: Sequence[Any] = (), **kwargs: Any) -> None:
    handles, labels = ax.get_legend_handles_labels()
    handles = list(handles) + list(extra)
    if handles:
        ax.legend(handles=handles, fontsize="small", **kwargs)


def _time_panels(states: List[SteadyState], panels: Sequence[Tuple[str, str, float]],
                 periods: Optional[float], shade: Optional[bool], title: Optional[str],
                 ) -> Figure:
    fig, axes = new_figure(len(panels), 1, sharex=True)
    axes = np.atleast_1d(axes)
    shade = (len(states) == 1) if shade is None else shade
    for ax, (column, ylabel, factor) in zip(axes, panels):
        handles: List[Any] = []
        for i, state in enumerate(states):
            idx = _window(state, periods)
            tau = state.tau()[idx]
            y = np.asarray(getattr(state.samples, column))[idx] * factor
            ax.plot(tau, y, color=COLORS[i % len(COLORS)], lw=1.2, label=_label(state, i))
            if shade and i == 0:
                patches = shade_phases(ax, tau, np.asarray(state.samples.phase)[idx])
                handles = patches if ax is axes[0] else []
        ax.set_ylabel(ylabel)
        ax.axhline(0.0, color="0.6", lw=0.5)
        ax.grid(alpha=0.3)
        _legend(ax, handles, loc="best")
    axes[-1].set_xlabel(TAU_LABEL)
    if title:
        fig.suptitle(title)
    return fig


def plot_accelerations(cases: Any, labels: Optional[Sequence[str]] = None, periods: float = 2,
                       shade: Optional[bool] = None, title: Optional[str] = None) -> Figure:
    """x_M'' (a) and z_M'' (b) [m/s^2] over `periods` excitation periods against t/T (paper
    Figs. 7, 11, 17, 18). Slip phases are shaded when one case is shown (or shade=True: those
    of the first case)."""
    states = _cases(cases, labels)
    return _time_panels(states, [("ddx_M", DDX_LABEL, 1.0), ("ddz_M", DDZ_LABEL, 1.0)], periods,
                        shade, title)


def plot_delta_phi(cases: Any, labels: Optional[Sequence[str]] = None, periods: float = 2,
                   shade: Optional[bool] = None, title: Optional[str] = None) -> Figure:
    """Position angle delta (a) and drum rotation phi (b) [rad] against t/T (paper Fig. 8a)."""
    states = _cases(cases, labels)
    return _time_panels(states, [("delta", DELTA_LABEL, 1.0), ("phi", PHI_LABEL, 1.0)], periods,
                        shade, title)


def plot_forces(cases: Any, labels: Optional[Sequence[str]] = None, periods: float = 2,
                mu: Optional[float] = None, shade: Optional[bool] = None,
                title: Optional[str] = None) -> Figure:
    """Normal force N (a) and tangential force T (b) [kN] against t/T, with +-mu N on (b)
    when mu is known (argument or the case's contact.mu)."""
    states = _cases(cases, labels)
    fig = _time_panels(states, [("N", "normal force $N$ [kN]", 1e-3),
                                ("T", "tangential force $T$ [kN]", 1e-3)], periods, shade, title)
    ax = fig.axes[1]
    for i, state in enumerate(states):
        m = mu if mu is not None else state.parameters.get("contact.mu")
        pure = state.parameters.get("contact.pure_rolling")
        if m is None or pure in (True, 1, "true"):
            continue
        idx = _window(state, periods)
        limit = float(m) * np.asarray(state.samples.N)[idx] * 1e-3
        ax.plot(state.tau()[idx], limit, color=COLORS[i % len(COLORS)], ls=":", lw=0.8)
        ax.plot(state.tau()[idx], -limit, color=COLORS[i % len(COLORS)], ls=":", lw=0.8,
                label=r"$\pm\mu N$" if i == 0 else None)
    _legend(ax, loc="upper right")
    return fig


def remove_drift(state: SteadyState) -> np.ndarray:
    """phi [rad] without its net rotation per period (slip with a driving torque) and mean: the
    drift per period is phi(t + T) - phi(t), averaged over the window."""
    phi = np.asarray(state.samples.phi, dtype=float)
    n = state.samples_per_period
    slope = float(np.mean(phi[n:2 * n] - phi[:n])) if len(phi) >= 2 * n > 0 else 0.0
    phi = phi - slope * state.tau()
    return phi - np.mean(phi)


def plot_torque_phi(cases: Any, labels: Optional[Sequence[str]] = None,
                    title: Optional[str] = None) -> Figure:
    """One excitation period of the drum rotation phi [rad] (solid) with the excitation torque
    M_M(t) [kN m] (dashed, right axis), as paper Fig. 10a. phi's drift (net slip) is removed."""
    states = _cases(cases, labels)
    fig, ax = new_figure(1, 1, height=3.6)
    right = ax.twinx()
    for i, state in enumerate(states):
        idx = _window(state, 1)
        tau = state.tau()[idx]
        phi = remove_drift(state)[idx]
        ax.plot(tau, phi, color=COLORS[i % len(COLORS)], lw=1.2, label=_label(state, i))
        if i == 0:
            right.plot(tau, np.asarray(state.samples.torque)[idx] * 1e-3, color="0.4", ls="--",
                       lw=1.0, label=r"$M_M(t)$")
    ax.set_xlabel(TAU_LABEL)
    ax.set_ylabel(PHI_LABEL + " (drift removed)")
    right.set_ylabel(TORQUE_LABEL)
    ax.grid(alpha=0.3)
    _legend(ax, right.get_legend_handles_labels()[0], loc="upper right")
    if title:
        fig.suptitle(title)
    return fig


def plot_figure_eight(cases: Any, labels: Optional[Sequence[str]] = None,
                      title: Optional[str] = None) -> Figure:
    """z_M'' over x_M'' [m/s^2] (paper Figs. 8b, 13, 21): a closed curve per case."""
    states = _cases(cases, labels)
    fig, ax = new_figure(1, 1, width=5.6, height=4.6)
    for i, state in enumerate(states):
        x = np.asarray(state.samples.ddx_M)
        z = np.asarray(state.samples.ddz_M)
        ax.plot(np.append(x, x[:1]), np.append(z, z[:1]), color=COLORS[i % len(COLORS)],
                lw=1.2, label=_label(state, i))
    ax.set_xlabel(DDX_LABEL)
    ax.set_ylabel(DDZ_LABEL)
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.axvline(0.0, color="0.6", lw=0.5)
    ax.grid(alpha=0.3)
    _legend(ax, loc="best")
    if title:
        fig.suptitle(title)
    return fig


def spectrum(state: SteadyState, column: str, n_max: int = 10) -> np.ndarray:
    """Amplitudes A_0 ... A_n_max [m/s^2] of ddx_M or ddz_M: the case's metrics if it carries
    them, else a DFT over the whole sampled window (the same transform)."""
    key = {"ddx_M": "ddx_amplitude", "ddz_M": "ddz_amplitude"}.get(column)
    if state.metrics and key in state.metrics and len(state.metrics[key]) > n_max:
        return np.asarray(state.metrics[key][: n_max + 1], dtype=float)
    return harmonic_amplitudes(getattr(state.samples, column), state.sample_periods, n_max)


def normalised_spectrum(state: SteadyState, column: str, n_max: int = 10) -> np.ndarray:
    """A_n / max_{n >= 1} A_n for n = 1 ... n_max (the paper's normalisation, Figs. 14, 15,
    19, 20)."""
    amp = spectrum(state, column, n_max)[1:]
    peak = float(np.max(amp)) if len(amp) else 0.0
    return amp / peak if peak > 0 else amp


def plot_spectra(cases: Any, labels: Optional[Sequence[str]] = None, n_max: int = 10,
                 title: Optional[str] = None) -> Figure:
    """Harmonic spectra of x_M'' (a) and z_M'' (b): amplitude / largest amplitude against
    f / f_exc = 1 ... n_max, one bar group per harmonic (paper Figs. 14, 15, 19, 20)."""
    states = _cases(cases, labels)
    fig, axes = new_figure(2, 1, sharex=True)
    width = 0.8 / max(len(states), 1)
    for ax, column, ylabel in zip(axes, ("ddx_M", "ddz_M"), (DDX_LABEL, DDZ_LABEL)):
        for i, state in enumerate(states):
            amp = normalised_spectrum(state, column, n_max)
            n = np.arange(1, len(amp) + 1)
            ax.bar(n - 0.4 + width * (i + 0.5), amp, width=width, color=COLORS[i % len(COLORS)],
                   label=_label(state, i))
        name = ylabel.split(" [")[0]
        ax.set_ylabel(f"{AMP_LABEL} of {name}")
        ax.set_ylim(0.0, 1.05)
        ax.grid(alpha=0.3, axis="y")
        _legend(ax, loc="upper right")
    axes[-1].set_xlabel(FREQ_LABEL)
    axes[-1].set_xticks(np.arange(1, n_max + 1))
    if title:
        fig.suptitle(title)
    return fig


def plot_sweep(x: Optional[Sequence[float]], curves: Mapping[str, Any], xkey: str = "soil.G",
               ykey: str = "area", title: Optional[str] = None, xunit: str = "",
               yunit: str = "", ax: Any = None) -> Figure:
    """Metric-versus-parameter curves (paper Figs. 9, 10b, 12, 16, 22).

    x: parameter values in SI units, shared by all curves; curves: {legend label: metric values}
    or {legend label: (x values, metric values)} for curves on their own x (then x may be None).
    xkey / ykey name the parameter and the metric: labels, units and display scale come from
    DISPLAY (e.g. soil.G is shown in MN/m^2). The first curve is black with '+' markers, the
    second red with circles, as in the paper.
    """
    xlabel, xf = axis_label(xkey, xunit)
    ylabel, yf = axis_label(ykey, yunit)
    if ax is None:
        fig, ax = new_figure(1, 1, height=3.8)
    else:
        fig = ax.figure
    for i, (label, values) in enumerate(curves.items()):
        if isinstance(values, tuple) and len(values) == 2:
            xs, ys = values
        else:
            xs, ys = x, values
        style = dict(color=COLORS[i % len(COLORS)], marker=MARKERS[i % len(MARKERS)], lw=1.2,
                     ms=6, mfc="none")
        ax.plot(np.asarray(xs, dtype=float) * xf, np.asarray(ys, dtype=float) * yf,
                label=label or None, **style)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    if any(curves):
        _legend(ax, loc="best")
    if title:
        fig.suptitle(title)
    return fig


def _value_text(v: float) -> str:
    return f"{v:g}"


def plot_table(table: Mapping[str, np.ndarray], x: str, y: str,
               group: Optional[Sequence[str] | str] = None,
               units: Optional[Mapping[str, str]] = None, title: Optional[str] = None,
               where: Optional[Mapping[str, float]] = None) -> Figure:
    """plot_sweep from a study table ({column: numeric values}, e.g. read_csv_columns of the
    CLI's sweep results): y against x, one curve per combination of the `group` columns, only
    rows whose `where` columns equal the given values (booleans as 1/0). Rows whose metric is
    missing (invalid or failed cases) leave gaps."""
    units = units or {}
    groups = [group] if isinstance(group, str) else list(group or [])
    xcol, ycol = resolve_column(table, x), resolve_column(table, y)
    xs, ys = np.asarray(table[xcol], dtype=float), np.asarray(table[ycol], dtype=float)
    keep = np.ones(len(xs), dtype=bool)
    for key, value in (where or {}).items():
        keep &= np.asarray(table[resolve_column(table, key)], dtype=float) == float(value)
    gcols = [resolve_column(table, g) for g in groups]
    keys = [tuple(float(table[c][i]) for c in gcols) for i in range(len(xs))]
    curves: Dict[str, Any] = {}
    for combo in dict.fromkeys(k for k, ok in zip(keys, keep) if ok):
        sel = keep & np.array([k == combo for k in keys])
        order = np.argsort(xs[sel])
        label = ", ".join(f"{c} = {_value_text(v)}" for c, v in zip(gcols, combo))
        curves[label] = (xs[sel][order], ys[sel][order])
    return plot_sweep(None, curves, xcol, ycol, title=title, xunit=units.get(xcol, ""),
                      yunit=units.get(ycol, ""))


def plot_case(data: Any, out_dir: str | os.PathLike, fmt: str = "png", label: str = "",
              periods: float = 2) -> List[Path]:
    """Every single-case figure of a steady state into out_dir: accelerations, figure_eight,
    spectra, delta_phi, forces (.png or .svg). Returns the paths written."""
    state = as_steady_state(data, label=label)
    out = Path(out_dir)
    title = state.label or None
    figures = {
        "accelerations": plot_accelerations(state, periods=periods, title=title),
        "figure_eight": plot_figure_eight(state, title=title),
        "spectra": plot_spectra(state, title=title),
        "delta_phi": plot_delta_phi(state, periods=periods, title=title),
        "forces": plot_forces(state, periods=periods, title=title),
    }
    return [save(fig, out / f"{name}.{fmt}", fmt) for name, fig in figures.items()]


def _parse(argv: Optional[Sequence[str]]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="python3 -m oscidrum.plot",
        description="Plot a steady state or a study written by the oscidrum CLI.")
    sub = parser.add_subparsers(dest="command", required=True)
    case = sub.add_parser("case", help="figures of one steady state (CSV of docs/csv-columns.md)")
    case.add_argument("--csv", required=True, help="steady-state CSV (oscidrum run --csv)")
    case.add_argument("--json", help="summary JSON (oscidrum run --json); optional")
    case.add_argument("--out", required=True, help="output directory")
    case.add_argument("--format", choices=("png", "svg"), default="png")
    case.add_argument("--label", default="", help="title of the figures")
    case.add_argument("--periods", type=float, default=2, help="periods shown in time plots")
    sweep = sub.add_parser("sweep", help="metric against parameter from a study's results CSV")
    sweep.add_argument("--csv", required=True, help="study results CSV (oscidrum sweep)")
    sweep.add_argument("--x", required=True, help="parameter column, e.g. soil.G")
    sweep.add_argument("--y", required=True, action="append",
                       help="metric column, e.g. area (repeat for several figures)")
    sweep.add_argument("--group", action="append", default=[],
                       help="one curve per value of this column, e.g. MMd_fraction (repeat for "
                       "combinations)")
    sweep.add_argument("--where", action="append", default=[], metavar="KEY=VALUE",
                       help="only rows with this value, e.g. contact.pure_rolling=true")
    sweep.add_argument("--out", required=True, help="output directory")
    sweep.add_argument("--format", choices=("png", "svg"), default="png")
    return parser.parse_args(argv)


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Entry point of ``python3 -m oscidrum.plot``; prints the files written."""
    args = _parse(argv)
    try:
        if args.command == "case":
            state = read_case(args.csv, args.json, label=args.label)
            paths = plot_case(state, args.out, args.format, periods=args.periods)
        else:
            table, units = read_csv_columns(args.csv)
            where = {}
            for item in args.where:
                key, sep, value = item.partition("=")
                if not sep:
                    raise ValueError(f"--where expects KEY=VALUE; got '{item}'")
                where[key] = {"true": 1.0, "false": 0.0}.get(value, None)
                if where[key] is None:
                    where[key] = float(value)
            paths = []
            for y in args.y:
                fig = plot_table(table, args.x, y, group=args.group, units=units, where=where)
                name = f"{split_header(y)[0]}_vs_{split_header(args.x)[0]}".replace("/", "_")
                paths.append(save(fig, Path(args.out) / f"{name}.{args.format}", args.format))
    except (OSError, ValueError, KeyError) as exc:
        print(f"oscidrum.plot: error: {exc}", file=sys.stderr)
        return 1
    for path in paths:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
