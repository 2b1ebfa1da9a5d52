"""Plots of steady states and studies (matplotlib, Agg: no display needed).

Every function takes steady states in any form :func:`oscidrum.data.as_steady_state` accepts (a
``Result``, a study's ``CaseOutcome``, a :class:`~oscidrum.data.SteadyState` read from the CLI's
CSV, or the CSV's path), or a ``(result, oscidrum.Case)`` pair that also gives the case's
parameters, and returns a :class:`matplotlib.figure.Figure`; :func:`save` writes it as PNG or
SVG. With ``ax=`` (an Axes, or a sequence of Axes for the two-panel plots) a function draws into
the caller's axes and returns them instead. Titles name the cases' key parameters (soil,
contact, driving torque, trough, f). Every function that draws a legend takes ``legend=``
(LEGEND_PLACES): by default it sits inside the axes where it hides no data, else beside them
when the figure has a layout engine (the figures made here have one), else inside at the best
place, so that in a user's figure it is never clipped.
Figures are built with the object-oriented API (no pyplot state), so they are safe in scripts,
tests and threads; in Jupyter, ``display(fig)`` shows them.

Command line (the C++ CLI's ``oscidrum run --plot DIR`` calls the first form and ``oscidrum
sweep --plot FILE`` the last; run it with the interpreter the package is installed for, on
Debian ``/usr/bin/python3``)::

    /usr/bin/python3 -m oscidrum.plot case --csv FILE [--json FILE] --out DIR [--format png|svg]
                                   [--spectra-units both|normalised|m/s^2]
    /usr/bin/python3 -m oscidrum.plot sweep --csv results.csv --x soil.G --y area [--y ddx_max]
                                   [--group MMd_fraction] [--where contact.pure_rolling=true]
                                   --out DIR [--format png|svg]
    /usr/bin/python3 -m oscidrum.plot map --csv results.csv --x soil.G --y roller.f [--z area]
                                   [--where KEY=VALUE] --out FILE.png
    /usr/bin/python3 -m oscidrum.plot study --csv results.csv [--metric area] --out FILE.png
"""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
import warnings
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from ._checks import is_integer, is_number
from ._files import output_path
from .data import (Error, SteadyState, as_steady_state, from_result, harmonic_amplitudes,
                   read_case, read_csv_columns, resolve_column, split_header)

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

#: Names and symbols (mathtext) of swept keys and metrics: key -> (name, symbol). Units and
#: display scales are not repeated here: those of a Case parameter come from the parameter table
#: (``oscidrum.find_field``: its display_unit and display_scale, e.g. MN/m^2 for soil.G), those
#: of a metric from the results' units (the CSV header, else ``oscidrum.Metrics.units``). Keys
#: not listed are named by the first words of their field's description.
NAMES: Dict[str, Tuple[str, str]] = {
    "soil.G": ("shear modulus", "$G$"),
    "soil.nu": ("Poisson's ratio", r"$\nu$"),
    "soil.rho": ("soil density", r"$\rho$"),
    "soil.ksh": ("horizontal soil spring", "$k_{sh}$"),
    "soil.ksv": ("vertical soil spring", "$k_{sv}$"),
    "soil.csh": ("horizontal soil dashpot", "$c_{sh}$"),
    "soil.csv": ("vertical soil dashpot", "$c_{sv}$"),
    "trough.a": ("trough radius", "$R$"),
    "trough.k": ("spiral parameter", "$k$"),
    "MMd": ("driving torque", "$M_{Md}$"),
    "MMd_fraction": ("driving torque", "$M_{Md}/M_0$"),
    "contact.pure_rolling": ("pure rolling", ""),
    "contact.unilateral": ("unilateral contact", ""),
    "contact.mu": ("friction coefficient", r"$\mu$"),
    "contact.mu_static": ("static friction coefficient", r"$\mu_s$"),
    "contact.v_eps": ("regularisation velocity", r"$v_\varepsilon$"),
    "roller.f": ("excitation frequency", "$f$"),
    "roller.M0": ("oscillation moment", "$M_0$"),
    "roller.unbalance": ("unbalance", "$m_u e_u e_w$"),
    "roller.m": ("drum mass", "$m$"),
    "roller.r": ("drum radius", "$r$"),
    "roller.P0": ("static axle load", "$P_0$"),
    "area": (r"area inside $\ddot{z}_M$-$\ddot{x}_M$", ""),
    "ddx_max": (r"peak $\ddot{x}_M$", ""),
    "ddx_min": (r"min $\ddot{x}_M$", ""),
    "ddz_max": (r"peak $\ddot{z}_M$", ""),
    "ddz_min": (r"min $\ddot{z}_M$", ""),
    "phi_lag": (r"phase lag $M_{Mu}$ to $\varphi$", ""),
    "phi_amplitude": (r"amplitude of $\varphi$", ""),
    "psi_xz": (r"phase lag $\psi$ between $\ddot{x}_M$ and $\ddot{z}_M$", ""),
    "stick_fraction": ("stick fraction", ""),
    "slip_positive_fraction": ("slip+ fraction", ""),
    "slip_negative_fraction": ("slip- fraction", ""),
}

#: Keys of the study files that are not Case parameters but stand for one (same unit and scale).
ALIASES = {"soil.table2_G": "soil.G"}

#: How a boolean parameter's values read in legends and panel titles: key -> (false, true).
BOOLEAN_TEXT = {"contact.pure_rolling": ("stick-slip", "pure rolling"),
                "contact.unilateral": ("permanent contact", "lift-off allowed")}

#: Colours of up to four cases (the paper's figures show four soils) and of more.
COLORS = ("black", "tab:red", "tab:blue", "tab:green", "tab:purple", "tab:orange", "tab:brown",
          "tab:pink", "tab:gray", "tab:olive", "tab:cyan")
MARKERS = ("+", "o", "s", "^", "v", "D", "x", "*", "<", ">", "p")
SLIP_COLORS = {1: ("tab:orange", "slip+ ($v_{rel} > 0$)"),
               -1: ("tab:cyan", "slip- ($v_{rel} < 0$)"),
               2: ("tab:purple", "flight (no contact)")}

#: A signal is absent as a whole when every component of its spectrum (mean included) is at most
#: this fraction of the largest component of x_M'' and z_M'' together, or at most
#: ROUND_OFF_ACCELERATION: the round-off of a motion that has none (the directed vertical
#: exciter's x_M''; both signals of a drum without friction; the metrics' rule, docs/outputs.md,
#: and ``oscidrum.absent_signals``). Plots draw it flat on zero with a note instead of scaling its
#: round-off up to look like a signal.
ABSENT_FRACTION = 1e-6
#: [m/s^2] 1e-12 g: below what the integration resolves or a logger measures.
ROUND_OFF_ACCELERATION = 1e-12 * 9.80665

#: The acceleration columns and their names in the notes.
_SIGNAL_NAMES = {"ddx_M": "x_M''", "ddz_M": "z_M''"}


def _field(name: str) -> Any:
    """The parameter table's field of a key (aliases resolved), or None (a metric)."""
    try:
        from . import _core
        return _core.find_field(ALIASES.get(name, name))
    except Exception:  # noqa: BLE001 - not a Case parameter
        return None


def unit_text(unit: str) -> str:
    """A unit as mathtext: 'MN/m^2' -> 'MN/m$^2$', 'pi rad' -> '$\\pi$ rad'."""
    unit = re.sub(r"\^(-?\d+)",
                  lambda m: f"$^{m.group(1)}$" if len(m.group(1)) == 1 else f"$^{{{m.group(1)}}}$",
                  unit)
    return re.sub(r"\bpi\b", r"$\\pi$", unit)


def key_display(key: str, unit: str = "") -> Tuple[str, str, str, float]:
    """(name, symbol, unit shown, factor from SI) of a swept key or a metric (a CSV header such
    as 'soil.G[Pa]' is accepted). A Case parameter is shown in its field's display unit (soil.G
    in MN/m^2); a metric in `unit` (from the CSV), else in oscidrum.Metrics.units; the name and
    symbol come from NAMES, else from the field's description."""
    name, csv_unit = split_header(key)
    field = _field(name)
    label, symbol = NAMES.get(name, NAMES.get(ALIASES.get(name, ""), ("", "")))
    if field is not None:
        if not label:
            label = re.split(r"[(;:,]", field.description)[0].strip() or name
        shown = field.display_unit or field.unit
        factor = 1.0 / float(field.display_scale or 1.0)
    else:
        shown = unit or csv_unit
        if not shown:
            try:
                from . import _core
                shown = dict(_core.Metrics.units).get(name, "")
            except Exception:  # noqa: BLE001 - no metric units: none shown
                shown = ""
        factor = 1.0
    return label or name, symbol, shown, factor


def axis_label(key: str, unit: str = "") -> Tuple[str, float]:
    """(axis label with unit, factor from SI) for a swept key or a metric name, e.g.
    ('shear modulus $G$ [MN/m$^2$]', 1e-6) for soil.G."""
    label, symbol, shown, factor = key_display(key, unit)
    text = f"{label} {symbol}".strip()
    return (f"{text} [{unit_text(shown)}]" if shown else text), factor


def value_label(key: str, value: float, unit: str = "") -> str:
    """A swept key's value as people read it in a legend or a panel title: booleans as what
    they mean ('pure rolling' / 'stick-slip' for contact.pure_rolling), choices by name, numbers
    with their symbol and display unit ('$G$ = 25 MN/m$^2$', '$M_{Md}/M_0$ = 0.05')."""
    name, _ = split_header(key)
    field = _field(name)
    label, symbol, shown, factor = key_display(key, unit)
    if field is not None and field.type == "boolean":
        off, on = BOOLEAN_TEXT.get(field.key, (f"{label}: no", f"{label}: yes"))
        return on if float(value) != 0 else off
    if field is not None and field.type == "choice" and field.choices:
        index = int(value)
        choice = field.choices[index] if 0 <= index < len(field.choices) else _value_text(value)
        return f"{symbol or label} = {choice}"
    text = f"{symbol or label} = {_value_text(float(value) * factor)}"
    return f"{text} {unit_text(shown)}" if shown and shown != "-" else text


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
        raise Error(f"format must be png or svg; got '{fmt}'")
    if path.suffix.lower() != "." + fmt:
        path = path.with_suffix("." + fmt)
    path.parent.mkdir(parents=True, exist_ok=True)
    with output_path(path) as target:
        fig.savefig(target, format=fmt, dpi=150)
    return path


def _flat_parameters(case: Any) -> Dict[str, Any]:
    """{dotted key: value} of an oscidrum.Case (its to_dict) or of a mapping."""
    if case is None:
        return {}
    if hasattr(case, "to_dict"):
        return dict(case.to_dict())
    return dict(case)


def _cases(cases: Any, labels: Optional[Sequence[str]]) -> List[SteadyState]:
    """Steady states from a case or a list of cases; a case may be a (result, oscidrum.Case)
    pair, which gives the plot its parameters (for the title and legend)."""
    if not isinstance(cases, list) and not (isinstance(cases, tuple) and not _is_pair(cases)):
        cases = [cases]
    # One label per case: a list one short labelled the last curve "case N", one long dropped its
    # last label, without a word.
    if labels is not None and len(labels) != len(cases):
        raise Error(f"labels: give one per case; got {len(labels)} for {len(cases)} case"
                    + ("" if len(cases) == 1 else "s"))
    out = []
    for i, case in enumerate(cases):
        label = labels[i] if labels is not None and i < len(labels) else ""
        if _is_pair(case):
            state = from_result(case[0], label=label, parameters=_flat_parameters(case[1]))
        else:
            state = as_steady_state(case, label=label)
        if label:
            state.label = label
        out.append(state)
    return out


def _is_pair(obj: Any) -> bool:
    return (isinstance(obj, tuple) and len(obj) == 2 and
            (hasattr(obj[1], "to_dict") or isinstance(obj[1], Mapping)) and
            not isinstance(obj[0], (str, os.PathLike)))


def _number(v: float) -> str:
    return f"{float(v):.4g}"


def _trough_text(params: Mapping[str, Any]) -> Optional[str]:
    """The trough as its shape describes itself ('circle, R = 0.606 m'), from the compiled
    module; without it (or for keys it refuses), the keys trough.k and trough.a as given."""
    k, a = params.get("trough.k"), params.get("trough.a")
    if a is None:
        return None
    try:
        from . import _core  # the compiled module
        return _core.make_trough_geometry(float(params.get("roller.r") or 0.6), float(k or 0.0),
                                          float(a)).summary
    except Exception:  # noqa: BLE001 - no compiled module or an invalid trough: the keys
        return f"trough k = {_number(float(k or 0.0))}, a = {_number(float(a))} m"


def case_parts(params: Mapping[str, Any], frequency: Optional[float] = None
               ) -> Dict[str, str]:
    """The key parameters of a case as {name: text} (soil, contact, torque, trough, excitation),
    from its {dotted key: value} parameters; names without a value are left out."""
    parts: Dict[str, str] = {}
    get = params.get
    # soil.input says how the soil is given (Table 2 is one of its values).
    source = {"modulus": "Appendix B soil", "table2": "Table 2 soil"}.get(get("soil.input"))
    if source and get("soil.G") is not None:
        parts["soil"] = f"G = {_number(float(get('soil.G')) * 1e-6)} MN/m$^2$"
        parts["soil source"] = source
    elif get("soil.ksh") is not None and get("soil.ksv") is not None:
        parts["soil"] = (f"$k_{{sh}}$ = {_number(float(get('soil.ksh')) * 1e-6)}, "
                         f"$k_{{sv}}$ = {_number(float(get('soil.ksv')) * 1e-6)} MN/m")
    pure = get("contact.pure_rolling")
    if pure in (True, 1, "true"):
        parts["contact"] = "pure rolling"
    elif get("contact.mu") is not None:
        parts["contact"] = rf"$\mu$ = {_number(get('contact.mu'))}"
    if get("MMd") is not None:
        mmd = float(get("MMd"))
        M0 = get("roller.M0")
        unbalance = float(get("roller.unbalance") or 0.0)
        f = float(get("roller.f") or frequency or 0.0)
        if unbalance > 0 and f > 0:
            M0 = 4.0 * unbalance * (2.0 * np.pi * f) ** 2
        if mmd == 0:
            parts["torque"] = "$M_{Md}$ = 0"
        elif M0 and get("roller.type") != "vibratory":  # (the vibratory drum has no M0)
            parts["torque"] = f"$M_{{Md}}$ = {_number(mmd / float(M0))} $M_0$"
        else:
            parts["torque"] = f"$M_{{Md}}$ = {_number(mmd * 1e-3)} kN m"
    trough = _trough_text(params)
    if trough:
        parts["trough"] = trough
    f = get("roller.f") or frequency
    if get("roller.type") == "vibratory":  # its excitation is a force, not M0 (and no M_Md / M0)
        parts["roller"] = "vibratory drum"
        if get("roller.static_moment") is not None:
            parts["static moment"] = (f"$m_u e_u$ = {_number(float(get('roller.static_moment')))}"
                                      " kg m")
    if f:
        parts["excitation"] = f"f = {_number(f)} Hz"
    return parts


def case_caption(state: SteadyState) -> str:
    """One line of the case's key parameters, e.g. 'G = 25 MN/m^2 (Table 2), mu = 0.5,
    M_Md = 0, R = 0.606 m, f = 39 Hz' (as far as the state knows them)."""
    return ", ".join(case_parts(state.parameters, state.frequency).values())


def _labels_and_title(states: List[SteadyState], title: Optional[str]
                      ) -> Tuple[List[str], Optional[str]]:
    """Legend labels and the title: what the cases share goes into the title, what differs into
    the labels (explicit labels and an explicit title win)."""
    parts = [case_parts(s.parameters, s.frequency) for s in states]
    names = list(dict.fromkeys(n for p in parts for n in p))
    common = [n for n in names if all(p.get(n) == parts[0].get(n) for p in parts)]
    labels = []
    for i, (state, p) in enumerate(zip(states, parts)):
        differ = ", ".join(p[n] for n in names if n not in common and n in p)
        labels.append(state.label or differ or (f"case {i + 1}" if len(states) > 1 else ""))
    shared = [parts[0][n] for n in common if n in parts[0]]
    if title is None:
        title = ", ".join(shared) or None
    else:  # an explicit title, with the shared parameters it does not state itself
        said = _plain(title)
        extra = [part for part in shared if _plain(part) not in said]
        if extra and len(states) > 0:
            title = f"{title}\n{', '.join(extra)}"
    # A run that is not a steady state (max_periods_reached, aperiodic, ...) is marked on every
    # figure, not only the figure eight: its traces and spectra look like a steady state's.
    unsteady = [s.status for s in states if s.status != "steady_state"]
    if unsteady and len(set(unsteady)) == 1 and len(unsteady) == len(states):
        note = f"{unsteady[0]}: not a steady state (the last periods, for inspection)"
        title = f"{title}\n{note}" if title else note
    elif unsteady:
        labels = [f"{label} ({s.status}: not a steady state)" if s.status != "steady_state"
                  else label for label, s in zip(labels, states)]
    return labels, title


def _plain(text: str) -> str:
    """Text without spaces and mathtext markup, to compare what two texts say
    ('G = 5 MN/m$^2$' and 'G = 5 MN/m²' agree)."""
    return re.sub(r"[\s${}\\]", "", text.replace("²", "^2")).lower()


def _window(state: SteadyState, periods: Optional[float]) -> np.ndarray:
    """Indices of the first `periods` excitation periods of the sampled window."""
    tau = state.tau()
    if periods is None:
        return np.arange(len(tau))
    if not (is_number(periods) and periods > 0):
        # 0 drew empty axes without a word; True drew one period
        raise Error(f"periods must be > 0 (excitation periods to show) or None (all); "
                    f"got {periods!r}")
    held = state.sample_periods
    if periods > max(held, 2) + 1e-9:
        # periods=10 of a result of 2 sampled periods drew 2 without a word (the default, 2,
        # shows what there is of a result of 1)
        warnings.warn(f"periods={periods:g}: {state.label or 'the result'} holds {held} sampled "
                      f"excitation period{'s' if held != 1 else ''}; all {held} drawn (sample "
                      "more with numerics.output_periods)", stacklevel=4)
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


#: The places of a legend (the ``legend=`` argument of every function that draws one):
#: "auto" (the default): inside the axes at matplotlib's best place if it hides no data there,
#: else beside the axes (right, or below for the square and twin-axis plots) when the figure
#: has a layout engine that makes room for it (the figures made here have one; so has a user's
#: figure made with layout="constrained"), else inside at the best place; "best" or "inside":
#: inside at matplotlib's best place; "outside": right of the axes, top-aligned; "below": under
#: the x axis' label; a matplotlib location inside the axes ("upper left", ...); None or False:
#: no legend. Outside and below need room in the figure: a layout engine, or
#: ``savefig(bbox_inches="tight")``.
LEGEND_PLACES = ("auto", "best", "inside", "outside", "below")


def _legend_place(legend: Any) -> Optional[str]:
    """The place of a legend= argument (None: no legend); refuses unknown places."""
    from matplotlib.legend import Legend
    if legend is None or legend is False:
        return None
    if legend is True:
        return "auto"
    if isinstance(legend, str):
        if legend == "inside":
            return "best"
        if legend in LEGEND_PLACES or legend in Legend.codes:
            return legend
    raise Error(f"legend must be one of {', '.join(LEGEND_PLACES)}, a matplotlib location "
                f"such as 'upper left', or None/False (no legend); got {legend!r}")


def _legend(ax: Any, extra: Sequence[Any] = (), legend: Any = "auto", beside: str = "outside",
            under: Any = None, handles: Optional[Sequence[Any]] = None, **kwargs: Any) -> Any:
    """The legend of `ax` (its labelled artists and `extra` handles) at the place `legend`
    (LEGEND_PLACES); `beside` ("outside" or "below") is where "auto" puts it when inside it would
    hide data, `under` the Axes whose x label "below" goes under (default `ax`). The place is
    settled by _place_legends once the figure is complete. `handles`: these instead of the
    labelled artists of `ax`. Returns the Legend, or None."""
    place = _legend_place(legend)
    if handles is None:
        handles, _ = ax.get_legend_handles_labels()
    handles = list(handles) + list(extra)
    if ax.get_legend() is not None:
        ax.get_legend().remove()
    if place is None or not handles:
        return None
    kwargs.setdefault("fontsize", "small")
    kwargs.pop("loc", None)
    made = _draw_legend(ax, handles, "best" if place == "auto" else place, under or ax,
                        dict(kwargs))
    made._oscidrum_request = (place, beside, under or ax, handles, kwargs)
    return made


def _draw_legend(ax: Any, handles: List[Any], place: str, under: Any,
                 kwargs: Dict[str, Any]) -> Any:
    if place == "outside":
        kwargs.pop("ncol", None)
        return ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                         borderaxespad=0.0, **kwargs)
    if place == "below":  # anchored under the x label by _place_legends
        return ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, 0.0),
                         bbox_transform=under.transAxes, borderaxespad=0.0,
                         ncol=kwargs.pop("ncol", min(len(handles), 3)), **kwargs)
    kwargs.pop("ncol", None)  # inside or beside: one column
    return ax.legend(handles=handles, loc=place, **kwargs)


def _data_paths(fig: Figure, renderer: Any) -> Tuple[List[Any], List[Any]]:
    """Display-space paths of every plotted line (runs between gaps) and filled area
    (fill_between), and boxes of every bar, of the figure's axes: (paths as (path, filled),
    boxes). Reference lines (axhline, axvline) and shading spans are not data."""
    from matplotlib.path import Path as MplPath
    paths, boxes = [], []
    for ax in fig.axes:
        for line in ax.lines:
            if line.get_transform() != ax.transData or not line.get_visible():
                continue
            xy = np.column_stack([np.asarray(line.get_xdata(), dtype=float),
                                  np.asarray(line.get_ydata(), dtype=float)])
            if len(xy) == 0:
                continue
            pts = ax.transData.transform(xy)
            finite = np.isfinite(pts).all(axis=1)
            edges = np.diff(np.concatenate(([0], finite.astype(int), [0])))
            for start, end in zip(np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0]):
                paths.append((MplPath(pts[start:end]), False))
        for collection in ax.collections:
            if collection.get_transform() == ax.transData and collection.get_visible():
                paths += [(ax.transData.transform_path(path), True)
                          for path in collection.get_paths()]
        for patch in ax.patches:
            if patch.get_transform() == ax.transData and patch.get_visible():
                boxes.append(patch.get_window_extent(renderer))
    return paths, boxes


def _hides_data(legend: Any, paths: List[Any], boxes: List[Any], renderer: Any) -> bool:
    """Whether the legend's box covers a data point, crosses a curve or overlaps a bar."""
    box = legend.get_window_extent(renderer)
    for path, filled in paths:
        v = path.vertices
        if (((v[:, 0] > box.x0) & (v[:, 0] < box.x1) & (v[:, 1] > box.y0) &
             (v[:, 1] < box.y1)).any() or
                (len(v) > 1 and path.intersects_bbox(box, filled=filled))):
            return True
    return any(box.overlaps(b) for b in boxes)


def _layout_engine(fig: Figure) -> Any:
    getter = getattr(fig, "get_layout_engine", None)
    if getter is not None:
        return getter()
    return fig.get_constrained_layout() or fig.get_tight_layout() or None


def _place_legends(fig: Figure, axes: Sequence[Any]) -> None:
    """Settle the legends that _legend made on `axes` (and their twins): an "auto" legend that
    hides data inside the axes goes beside them when the figure's layout engine makes room; a
    "below" legend goes under its x axis' tick labels and label (an offset in points, so that it
    stays there whatever the figure's size)."""
    from matplotlib.transforms import ScaledTranslation
    legends = [(ax, ax.get_legend()) for ax in axes]
    legends = [(ax, leg) for ax, leg in legends
               if leg is not None and hasattr(leg, "_oscidrum_request")]
    if not any(leg._oscidrum_request[0] in ("auto", "below") for _, leg in legends):
        return
    fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    paths, boxes = _data_paths(fig, renderer)
    for ax, leg in legends:
        place, beside, under, handles, kwargs = leg._oscidrum_request
        if place == "auto":
            if not _hides_data(leg, paths, boxes, renderer) or _layout_engine(fig) is None:
                continue
            leg.remove()
            leg = _draw_legend(ax, handles, beside, under, dict(kwargs))
            leg._oscidrum_request = (beside, beside, under, handles, kwargs)
            place = beside
        if place == "below":
            axis_box = under.get_window_extent(renderer)
            tight = under.xaxis.get_tightbbox(renderer)
            drop = max(0.0, axis_box.y0 - tight.y0) if tight is not None else 0.0
            points = drop * 72.0 / fig.dpi + 4.0
            leg.set_bbox_to_anchor((0.5, 0.0), transform=under.transAxes + ScaledTranslation(
                0.0, -points / 72.0, fig.dpi_scale_trans))


def _axes(ax: Any, n: int, **figure_kwargs: Any) -> Tuple[Figure, List[Any], bool]:
    """(figure, n axes, made here): a new figure, or the caller's axes (one Axes, or a sequence of
    n Axes for the plots of n panels)."""
    if ax is None:
        fig, axes = new_figure(n, 1, **figure_kwargs)
        return fig, list(np.atleast_1d(axes)), True
    axes = list(np.atleast_1d(np.asarray(ax, dtype=object))) if not hasattr(ax, "plot") else [ax]
    if len(axes) != n:
        raise Error(f"ax: this plot draws {n} panel(s); pass {n} Axes (got {len(axes)})")
    return axes[0].figure, axes, False


def _finish(fig: Figure, axes: List[Any], made: bool, title: Optional[str],
            legend_axes: Sequence[Any] = ()) -> Any:
    """Title, the places of the legends on `axes` and `legend_axes` (twins), and the return
    value: the Figure when it was made here, else the caller's Axes."""
    if title:
        if made:
            fig.suptitle(title, fontsize="medium")
        else:
            axes[0].set_title(title, fontsize="medium")
    _place_legends(fig, list(axes) + list(legend_axes))
    if made:
        return fig
    return axes[0] if len(axes) == 1 else axes


def _time_panels(states: List[SteadyState], panels: Sequence[Tuple[str, str, float]],
                 periods: Optional[float], shade: Optional[bool], title: Optional[str],
                 ax: Any = None, transform: Optional[Dict[str, Any]] = None,
                 legend: Any = "auto") -> Any:
    fig, axes, made = _axes(ax, len(panels), width=8.4, sharex=True)
    shade = (len(states) == 1) if shade is None else shade
    labels, title = _labels_and_title(states, title)
    for k, (axis, (column, ylabel, factor)) in enumerate(zip(axes, panels)):
        handles: List[Any] = []
        for i, state in enumerate(states):
            idx = _window(state, periods)
            tau = state.tau()[idx]
            values = (transform[column](state) if transform and column in transform
                      else np.asarray(getattr(state.samples, column)))
            y = np.asarray(values)[idx] * factor
            axis.plot(tau, y, color=COLORS[i % len(COLORS)], lw=1.2,
                      label=labels[i] or None)
            if shade and i == 0:
                patches = shade_phases(axis, tau, np.asarray(state.samples.phase)[idx])
                handles = patches if k == 0 else []
        axis.set_ylabel(ylabel)
        if column in _SIGNAL_NAMES and _absent_everywhere(states, column):
            # Round-off, not a signal: flat on zero on the other signal's scale, with a note.
            axis.set_ylim(*_absent_range(states, column, lambda st: _window(st, periods),
                                         factor))
            _note_absent(axis, states, [column])
        axis.axhline(0.0, color="0.6", lw=0.5)
        axis.grid(alpha=0.3)
        if k == 0:  # one legend for the panels, which show the same cases
            _legend(axis, handles, legend, under=axes[-1])
    axes[-1].set_xlabel(TAU_LABEL)
    return _finish(fig, axes, made, title)


def plot_accelerations(cases: Any, labels: Optional[Sequence[str]] = None, periods: float = 2,
                       shade: Optional[bool] = None, title: Optional[str] = None,
                       ax: Any = None, legend: Any = "auto") -> Any:
    """x_M'' (a) and z_M'' (b) [m/s^2] over `periods` excitation periods against t/T (paper
    Figs. 7, 11, 17, 18). Slip phases are shaded when one case is shown (or shade=True: those
    of the first case). The title holds the parameters the cases share, the legend those that
    differ. ax: two Axes to draw into (then they are returned instead of a new Figure).
    legend: where the legend goes (LEGEND_PLACES: "auto" inside where it hides no data, else
    beside the axes; "best"/"inside", "outside", "below", a matplotlib location; None: none)."""
    states = _cases(cases, labels)
    return _time_panels(states, [("ddx_M", DDX_LABEL, 1.0), ("ddz_M", DDZ_LABEL, 1.0)], periods,
                        shade, title, ax, legend=legend)


def plot_delta_phi(cases: Any, labels: Optional[Sequence[str]] = None, periods: float = 2,
                   shade: Optional[bool] = None, title: Optional[str] = None,
                   ax: Any = None, legend: Any = "auto") -> Any:
    """Position angle delta (a) and drum rotation phi (b) [rad] against t/T (paper Figs. 8a,
    10a). phi is shown without its drift (the net slip per period, and its mean), so that its
    oscillation is visible. ax: two Axes to draw into. legend: as for plot_accelerations."""
    states = _cases(cases, labels)
    return _time_panels(states, [("delta", DELTA_LABEL, 1.0),
                                 ("phi", PHI_LABEL + " (drift removed)", 1.0)],
                        periods, shade, title, ax, transform={"phi": remove_drift},
                        legend=legend)


def plot_forces(cases: Any, labels: Optional[Sequence[str]] = None, periods: float = 2,
                mu: Optional[float] = None, shade: Optional[bool] = None,
                title: Optional[str] = None, ax: Any = None, legend: Any = "auto") -> Any:
    """Normal force N (a) and tangential force T (b) [kN] against t/T, with +-mu N on (b)
    when mu is known (argument or the case's contact.mu). ax: two Axes to draw into. legend:
    as for plot_accelerations (the cases' legend on (a), +-mu N on (b))."""
    if mu is not None and not (is_number(mu) and np.isfinite(mu) and mu >= 0):
        # mu=-1 drew the limits upside down, True drew them at 1 N, without a word
        raise Error(f"mu must be a friction coefficient >= 0 or None (the case's contact.mu); "
                    f"got {mu!r}")
    states = _cases(cases, labels)
    result = _time_panels(states, [("N", "normal force $N$ [kN]", 1e-3),
                                   ("T", "tangential force $T$ [kN]", 1e-3)], periods, shade,
                          title, ax, legend=legend)
    axes = result.axes if isinstance(result, Figure) else list(result)
    axis = axes[1]
    limits: List[Any] = []
    for i, state in enumerate(states):
        m = mu if mu is not None else state.parameters.get("contact.mu")
        pure = state.parameters.get("contact.pure_rolling")
        if m is None or pure in (True, 1, "true"):
            continue
        idx = _window(state, periods)
        limit = float(m) * np.asarray(state.samples.N)[idx] * 1e-3
        axis.plot(state.tau()[idx], limit, color=COLORS[i % len(COLORS)], ls=":", lw=0.8)
        line, = axis.plot(state.tau()[idx], -limit, color=COLORS[i % len(COLORS)], ls=":",
                          lw=0.8, label=r"$\pm\mu N$")
        limits = limits or [line]
    # (b)'s legend says only what (a)'s does not: the friction limit.
    _legend(axis, legend=legend, handles=limits)
    _place_legends(axis.figure, [axis])
    return result


def remove_drift(state: SteadyState) -> np.ndarray:
    """phi [rad] without its net rotation per period (slip with a driving torque) and mean: the
    drift per period is phi(t + T) - phi(t), averaged over the window."""
    phi = np.asarray(state.samples.phi, dtype=float)
    n = state.samples_per_period
    slope = float(np.mean(phi[n:2 * n] - phi[:n])) if len(phi) >= 2 * n > 0 else 0.0
    phi = phi - slope * state.tau()
    return phi - np.mean(phi)


def plot_torque_phi(cases: Any, labels: Optional[Sequence[str]] = None,
                    title: Optional[str] = None, ax: Any = None, legend: Any = "auto") -> Any:
    """One excitation period of the drum rotation phi [rad] (solid) with the excitation torque
    M_M(t) [kN m] (dashed, right axis), as paper Fig. 10a. phi's drift (net slip) is removed.
    ax: the Axes to draw into (phi; the torque gets a twin axis). legend: as for
    plot_accelerations ("auto" goes below the plot, not beside the twin axis' labels, when
    inside it would hide data)."""
    states = _cases(cases, labels)
    fig, axes, made = _axes(ax, 1, height=3.6)
    axis = axes[0]
    right = axis.twinx()
    names, title = _labels_and_title(states, title)
    for i, state in enumerate(states):
        idx = _window(state, 1)
        tau = state.tau()[idx]
        phi = remove_drift(state)[idx]
        axis.plot(tau, phi, color=COLORS[i % len(COLORS)], lw=1.2, label=names[i] or r"$\varphi$")
        if i == 0:
            right.plot(tau, np.asarray(state.samples.torque)[idx] * 1e-3, color="0.4", ls="--",
                       lw=1.0, label=r"$M_M(t)$")
    axis.set_xlabel(TAU_LABEL)
    axis.set_ylabel(PHI_LABEL + " (drift removed)")
    right.set_ylabel(TORQUE_LABEL)
    axis.grid(alpha=0.3)
    handles, _ = axis.get_legend_handles_labels()
    right_handles, _ = right.get_legend_handles_labels()
    # On the twin axes, which are drawn over `axis`; beside them: below the plot.
    _legend(right, legend=legend, beside="below", under=axis, handles=handles + right_handles,
            ncol=min(4, len(handles) + 1))
    return _finish(fig, axes, made, title, legend_axes=[right])


def _area(state: SteadyState, x: np.ndarray, z: np.ndarray) -> Optional[float]:
    """The area inside the z_M''-x_M'' curve [m^2/s^4]: the case's metric, else computed by the
    compiled module (points of non-zero winding number), else None."""
    if state.metrics and state.metrics.get("area") is not None:
        return float(state.metrics["area"])
    try:
        from . import _core
        n = state.samples_per_period
        return float(_core.enclosed_area(np.ascontiguousarray(x[:n]),
                                         np.ascontiguousarray(z[:n])))
    except Exception:  # noqa: BLE001 - no compiled module: no area
        return None


def _arrows(axis: Any, x: np.ndarray, z: np.ndarray, color: Any, count: int = 6) -> None:
    """Arrow heads along one period of the curve, in the direction of travel."""
    n = len(x)
    if n < 8:
        return
    step = max(1, n // 200)
    for k in range(count):
        i = int((k + 0.25) * n / count) % n
        j = (i + step) % n
        if x[i] == x[j] and z[i] == z[j]:
            continue
        axis.annotate("", xy=(x[j], z[j]), xytext=(x[i], z[i]),
                      arrowprops=dict(arrowstyle="-|>", color=color, lw=1.0,
                                      mutation_scale=14, shrinkA=0, shrinkB=0))


def plot_figure_eight(cases: Any, labels: Optional[Sequence[str]] = None,
                      title: Optional[str] = None, ax: Any = None, legend: Any = "auto") -> Any:
    """z_M'' over x_M'' [m/s^2] (paper Figs. 8b, 13, 21): one steady period per case as a closed
    curve, with arrow heads in the direction of travel, the slip phases as a coloured band under
    the curve (slip+ orange, slip- cyan; stick: the bare line) and the enclosed area (non-zero
    winding number, docs/model.md section 8) in the legend. ax: the Axes to draw into. legend:
    as for plot_accelerations ("auto" goes below the plot when inside it would hide data)."""
    states = _cases(cases, labels)
    fig, axes, made = _axes(ax, 1, width=6.4, height=6.0)
    axis = axes[0]
    names, title = _labels_and_title(states, title)
    slip_seen: Dict[int, bool] = {}
    for i, state in enumerate(states):
        # One steady period: multiplicity excitation periods (a period-2 orbit's figure was drawn
        # over its first period only, closed by a line that is not on it).
        n = state.samples_per_orbit
        x = np.asarray(state.samples.ddx_M, dtype=float)[:n]
        z = np.asarray(state.samples.ddz_M, dtype=float)[:n]
        phase = np.asarray(state.samples.phase).astype(int)[:n]
        color = COLORS[i % len(COLORS)]
        xc, zc = np.append(x, x[:1]), np.append(z, z[:1])
        for value, (slip_color, _) in SLIP_COLORS.items():
            mask = np.append(phase == value, phase[:1] == value)
            if mask.any():
                slip_seen[value] = True
                axis.plot(np.where(mask, xc, np.nan), np.where(mask, zc, np.nan),
                          color=slip_color, lw=6, alpha=0.45, solid_capstyle="round", zorder=1)
        # Not a steady state (max_periods_reached, aperiodic, ...): the last periods drawn are no
        # orbit, and their "area" is a number compute_metrics refuses; the label says the status.
        steady = state.status == "steady_state"
        area = _area(state, x, z) if steady else None
        label = names[i]
        if not steady:
            label = (f"{label}: " if label else "") + f"{state.status}, not a steady state"
        if area is not None:
            text = f"area {area:.4g} m$^2$/s$^4$"
            if any(absent_signals(state).values()):  # a curve of round-off in one coordinate
                text = f"area 0 (round-off {area:.2g} m$^2$/s$^4$)" if area != 0 else "area 0"
            label = (f"{label}: " if label else "") + text
        axis.plot(xc, zc, color=color, lw=1.2, label=label or None, zorder=2)
        _arrows(axis, x, z, color)
    handles = [Patch(color=SLIP_COLORS[v][0], alpha=0.45, label=SLIP_COLORS[v][1])
               for v in (1, -1, 2) if slip_seen.get(v)]
    if slip_seen:
        handles.insert(0, Patch(facecolor="none", edgecolor="none", label="stick: bare line"))
    axis.set_xlabel(DDX_LABEL)
    axis.set_ylabel(DDZ_LABEL)
    # A coordinate absent in every case spans the other's range: the curve is a line on zero.
    absent = []
    for column, set_lim in (("ddx_M", axis.set_xlim), ("ddz_M", axis.set_ylim)):
        if _absent_everywhere(states, column):
            set_lim(*_absent_range(states, column, lambda st: slice(None)))
            absent.append(column)
    if absent:
        _note_absent(axis, states, absent, bottom=True)
    axis.axhline(0.0, color="0.6", lw=0.5)
    axis.axvline(0.0, color="0.6", lw=0.5)
    axis.grid(alpha=0.3)
    _legend(axis, handles, legend, beside="below", ncol=2)
    return _finish(fig, axes, made, title)


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


def absent_signals(state: SteadyState) -> Dict[str, bool]:
    """Which of ddx_M and ddz_M is absent as a whole (ABSENT_FRACTION): from the case's spectra
    (its metrics, else a DFT of its samples), as the metrics judge it."""
    n_max = 10
    if state.metrics and "ddx_amplitude" in state.metrics and "ddz_amplitude" in state.metrics:
        n_max = min(len(state.metrics["ddx_amplitude"]), len(state.metrics["ddz_amplitude"])) - 1
    spectra = {c: spectrum(state, c, max(n_max, 1)) for c in _SIGNAL_NAMES}
    # The samples' peaks count too: with n_max = 1 (--harmonics 1) z_M'' of a drum without driving
    # torque, which has even harmonics only, read as absent and was drawn flat.
    peaks = {c: float(np.max(np.abs(getattr(state.samples, c)))) if len(state.samples.t) else 0.0
             for c in _SIGNAL_NAMES}
    level = max(ABSENT_FRACTION * max(max(float(np.max(a)) for a in spectra.values()),
                                      max(peaks.values())), ROUND_OFF_ACCELERATION)
    return {c: bool(np.all(a <= level)) and peaks[c] <= level for c, a in spectra.items()}


def _absent_everywhere(states: Sequence[SteadyState], column: str) -> bool:
    return bool(states) and all(absent_signals(st)[column] for st in states)


def _absent_range(states: Sequence[SteadyState], column: str, window: Any,
                  factor: float = 1.0) -> Tuple[float, float]:
    """The axis range of an absent signal: symmetric about zero, the other signal's largest
    |value| over window(state) (times factor) and 5 % more; +-1 where both are absent."""
    other = "ddz_M" if column == "ddx_M" else "ddx_M"
    top = 0.0 if _absent_everywhere(states, other) else max(
        float(np.max(np.abs(np.asarray(getattr(st.samples, other))[window(st)])))
        for st in states) * factor
    return (-1.05 * top, 1.05 * top) if top > 0 else (-1.0, 1.0)


def _note_absent(axis: Any, states: Sequence[SteadyState], columns: Sequence[str],
                 bottom: bool = False) -> None:
    """The note on a panel whose signals `columns` are absent in every case shown (at its top
    left, or at its bottom left where a legend may sit at the top)."""
    names = [_SIGNAL_NAMES[c] for c in columns]
    peaks = [max(float(np.max(np.abs(np.asarray(getattr(st.samples, c), dtype=float))))
                 for st in states) for c in columns]
    bounds = ", ".join(f"|{n}| <= {p:.2g}" for n, p in zip(names, peaks))
    verb = "is" if len(names) == 1 else "are"
    axis.text(0.01, 0.03 if bottom else 0.97,
              f"{' and '.join(names)} {verb} absent: round-off only ({bounds} m/s$^2$)",
              transform=axis.transAxes,
              va="bottom" if bottom else "top", ha="left",
              fontsize=8, color="0.25",
              bbox=dict(facecolor="white", edgecolor="0.8", alpha=0.9, pad=2))


#: The units of plot_spectra: "normalised" (A_n / max A_n, the paper's), "m/s^2" (A_n), "both"
#: (A_n on the left axis, A_n / max A_n on the right; one case only).
SPECTRUM_UNITS = ("normalised", "m/s^2", "both")


def plot_spectra(cases: Any, labels: Optional[Sequence[str]] = None, n_max: int = 10,
                 title: Optional[str] = None, ax: Any = None, units: str = "normalised",
                 legend: Any = "auto") -> Any:
    """Harmonic spectra of x_M'' (a) and z_M'' (b) against f / f_exc = 1 ... n_max, one bar
    group per harmonic (paper Figs. 14, 15, 19, 20). units: "normalised" (the paper's: each
    case's amplitudes / its largest, n >= 1), "m/s^2" (the amplitudes A_n, as in the metrics'
    ddx_amplitude, ddz_amplitude) or "both" (one case: A_n [m/s^2] on the left axis, A_n /
    max A_n on the right). ax: two Axes to draw into. legend: as for plot_accelerations (one
    legend, on (a))."""
    if not is_integer(n_max) or n_max < 1:  # -1 raised IndexError, 2.0 TypeError
        raise Error(f"n_max must be an integer >= 1 (the highest harmonic shown); got {n_max!r}")
    if units in ("m/s2", "m s^-2"):
        units = "m/s^2"
    if units not in SPECTRUM_UNITS:
        raise Error(f"units must be one of {', '.join(SPECTRUM_UNITS)}; got {units!r}")
    states = _cases(cases, labels)
    if units == "both" and len(states) != 1:
        raise Error("units='both' shows one case (its own normalisation on the right "
                    f"axis); got {len(states)} cases: use 'normalised' or 'm/s^2'")
    fig, axes, made = _axes(ax, 2, sharex=True)
    names, title = _labels_and_title(states, title)
    width = 0.8 / max(len(states), 1)
    for k, (axis, column, ylabel) in enumerate(zip(axes, ("ddx_M", "ddz_M"),
                                                   (DDX_LABEL, DDZ_LABEL))):
        peak = 0.0
        for i, state in enumerate(states):
            if units == "normalised":
                amp = normalised_spectrum(state, column, n_max)
            else:
                amp = spectrum(state, column, n_max)[1:]
            if absent_signals(state)[column]:  # round-off: no bars (normalised they would be 1)
                amp = np.zeros_like(amp)
            peak = max(peak, float(np.max(amp)) if len(amp) else 0.0)
            n = np.arange(1, len(amp) + 1)
            axis.bar(n - 0.4 + width * (i + 0.5), amp, width=width,
                     color=COLORS[i % len(COLORS)], label=names[i] or None)
        name = ylabel.split(" [")[0]
        if units == "normalised":
            axis.set_ylabel(f"{AMP_LABEL} of {name}")
            axis.set_ylim(0.0, 1.05)
        else:
            axis.set_ylabel(f"$A_n$ of {name} [m/s$^2$]")
            axis.set_ylim(0.0, 1.05 * peak if peak > 0 else 1.0)
            if units == "both" and peak > 0:
                right = axis.secondary_yaxis(
                    "right", functions=(lambda a, p=peak: a / p, lambda r, p=peak: r * p))
                right.set_ylabel(AMP_LABEL)
        if _absent_everywhere(states, column):
            _note_absent(axis, states, [column])
        axis.grid(alpha=0.3, axis="y")
        if k == 0:  # one legend for the panels, which show the same cases
            _legend(axis, legend=legend, under=axes[-1])
    axes[-1].set_xlabel(FREQ_LABEL)
    axes[-1].set_xticks(np.arange(1, n_max + 1))
    return _finish(fig, axes, made, title)


#: Above this many curves a study plot colours them by a colour map with a colour bar.
COLORMAP_FROM = 6


#: An "auto" y scale is logarithmic when the curves' typical values (medians) differ by more
#: than this factor (and all values are positive), so that the small curves are not squashed.
LOG_SCALE_FROM = 10.0


def plot_sweep(x: Optional[Sequence[float]], curves: Mapping[str, Any], xkey: str = "soil.G",
               ykey: str = "area", title: Optional[str] = None, xunit: str = "",
               yunit: str = "", ax: Any = None, color_values: Optional[Sequence[float]] = None,
               color_key: str = "", color_unit: str = "", legend: Any = "auto",
               yscale: str = "auto") -> Any:
    """Metric-versus-parameter curves (paper Figs. 9, 10b, 12, 16, 22).

    x: parameter values in SI units, shared by all curves; curves: {legend label: metric values}
    or {legend label: (x values, metric values)} for curves on their own x (then x may be None).
    xkey / ykey name the parameter and the metric: the label comes from NAMES, the unit and
    display scale from the parameter table (e.g. soil.G is shown in MN/m^2). The first curve is
    black with '+' markers, the second red with circles, as in the paper. color_values (one
    number per curve, SI, named by color_key): the curves are coloured by a colour map with a
    colour bar instead of a legend, for many curves. yscale: "linear", "log", or "auto" (log
    when the curves differ by more than LOG_SCALE_FROM and all values are positive). legend:
    as for plot_accelerations. ax: the Axes to draw into (returned instead of a new Figure).
    """
    fig, axes, made = _axes(ax, 1, height=3.8)
    _draw_sweep(axes[0], x, curves, xkey, ykey, xunit, yunit, color_values, color_key,
                color_unit, legend, yscale)
    return _finish(fig, axes, made, title)


def _auto_log(curves: Sequence[np.ndarray]) -> bool:
    """Whether curves of positive values differ by more than LOG_SCALE_FROM (their medians)."""
    values = [np.asarray(c, dtype=float) for c in curves]
    values = [v[np.isfinite(v)] for v in values]
    values = [v for v in values if len(v)]
    if len(values) < 2 or any((v <= 0).any() for v in values):
        return False
    medians = [float(np.median(v)) for v in values]
    return max(medians) > LOG_SCALE_FROM * min(medians)


def _draw_sweep(axis: Any, x: Optional[Sequence[float]], curves: Mapping[str, Any], xkey: str,
                ykey: str, xunit: str = "", yunit: str = "",
                color_values: Optional[Sequence[float]] = None, color_key: str = "",
                color_unit: str = "", legend: Any = "auto", yscale: str = "auto",
                styles: Optional[Sequence[int]] = None, ylabel: bool = True) -> None:
    """The curves of plot_sweep into `axis` (styles: the index of each curve's colour and
    marker, so that panels of one study draw a curve alike)."""
    if yscale not in ("auto", "linear", "log"):
        raise Error(f"yscale must be auto, linear or log; got {yscale!r}")
    xlabel, xf = axis_label(xkey, xunit)
    ytext, yf = axis_label(ykey, yunit)
    fig = axis.figure
    mappable = None
    if color_values is not None:
        from matplotlib.cm import ScalarMappable
        from matplotlib.colors import Normalize
        clabel, cf = axis_label(color_key, color_unit)
        cv = np.asarray(color_values, dtype=float) * cf
        norm = Normalize(vmin=float(np.nanmin(cv)), vmax=float(np.nanmax(cv)))
        mappable = ScalarMappable(norm=norm, cmap="viridis")
    drawn = []
    for i, (label, values) in enumerate(curves.items()):
        if isinstance(values, tuple) and len(values) == 2:
            xs, ys = values
        else:
            xs, ys = x, values
        j = styles[i] if styles is not None else i
        if mappable is not None:
            style = dict(color=mappable.to_rgba(cv[i]), marker="o", lw=1.2, ms=4)
        else:
            style = dict(color=COLORS[j % len(COLORS)], marker=MARKERS[j % len(MARKERS)],
                         lw=1.2, ms=6, mfc="none")
        y = np.asarray(ys, dtype=float) * yf
        drawn.append(y)
        axis.plot(np.asarray(xs, dtype=float) * xf, y,
                  label=(label or None) if mappable is None else None, **style)
    if yscale == "log" or (yscale == "auto" and _auto_log(drawn)):
        axis.set_yscale("log")
    axis.set_xlabel(xlabel)
    if ylabel:
        axis.set_ylabel(ytext)
    axis.grid(alpha=0.3)
    if mappable is not None:
        fig.colorbar(mappable, ax=axis, label=clabel)
    elif any(curves):
        _legend(axis, legend=legend)


def _value_text(v: float) -> str:
    return f"{v:g}"


def _as_table(table: Any, what: str) -> Mapping[str, Any]:
    """A study table as {column: values}: a mapping (read_csv_columns) as it is, a pandas
    DataFrame (StudyResult.to_dataframe) by its columns, choices (soil.input) as their indices
    as in the CLI's CSV. A DataFrame raised pandas' 'truth value ... is ambiguous'."""
    if isinstance(table, Mapping):
        return table
    if hasattr(table, "columns") and hasattr(table, "to_numpy"):
        out: Dict[str, Any] = {}
        for column in table.columns:
            values = np.asarray(table[column].to_numpy())
            field = _field(split_header(str(column))[0])
            if field is not None and field.type == "choice" and values.dtype == object:
                values = np.array([field.choices.index(v) if v in field.choices else np.nan
                                   for v in values], dtype=float)
            out[str(column)] = values
        return out
    raise Error(f"{what}: the table must be a {{column: values}} mapping (read_csv_columns of a "
                "study's results CSV) or a pandas DataFrame (StudyResult.to_dataframe()); got "
                f"{type(table).__name__}")


def _select(table: Mapping[str, np.ndarray], where: Optional[Mapping[str, float]]) -> np.ndarray:
    """The rows whose `where` columns hold the given values; an Error naming the column and the
    values it holds when none does (an empty plot was drawn without a word)."""
    n = len(next(iter(table.values()))) if table else 0
    keep = np.ones(n, dtype=bool)
    for key, value in (where or {}).items():
        column = resolve_column(table, key)
        values = np.asarray(table[column], dtype=float)
        if keep.any() and not (keep & (values == float(value))).any():
            held = np.unique(values[keep & np.isfinite(values)])
            shown = ", ".join(_value_text(v) for v in held[:12]) + (", ..." if len(held) > 12
                                                                     else "")
            raise Error(f"where: no row has {column} = {_value_text(float(value))}"
                        + (" among the rows kept so far" if not keep.all() else "")
                        + f"; {column} holds {shown or 'no values'}")
        keep &= values == float(value)
    return keep


def _check_one_case_per_point(table: Mapping[str, np.ndarray], rows: np.ndarray,
                               point: Sequence[str], what: str, plotted: str) -> None:
    """Raise when rows that would be drawn as one point (the same values of the `point` columns)
    are cases that differ in a swept column of the study (a parameter column, or a column
    between 'case' and 'status') that is neither grouped by nor selected: their values were
    joined into one zigzag curve, or all but the last cell of a map dropped, without a word."""
    if not rows.any():
        return
    keys = np.column_stack([np.asarray(table[c], dtype=float)[rows] for c in point])
    keys = np.where(np.isfinite(keys), keys, np.inf)
    _, index, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    index = np.asarray(index).reshape(-1)
    shared = counts[index] > 1
    if not shared.any():
        return
    swept = swept_columns(table)
    candidates = [c for c in table if c not in point and c != plotted and (
        c in swept or _field(split_header(c)[0]) is not None)]
    for column in candidates:
        values = np.asarray(table[column], dtype=float)[rows]
        if not np.isfinite(values).any():
            continue
        values = np.where(np.isfinite(values), values, np.inf)
        pairs = np.unique(np.column_stack([index[shared], values[shared]]), axis=0)
        if len(pairs) == len(np.unique(index[shared])):
            continue  # one value of the column at each point
        present = np.unique(values[shared])
        shown = ", ".join(_value_text(v) for v in present[:6]) + (", ..." if len(present) > 6
                                                                    else "")
        raise Error(f"{what}: rows with the same {' and '.join(point)} differ in {column} "
                    f"({shown}), which is neither a group column nor selected by where=: "
                    f"their cases would be drawn as one; add '{column}' to group= or give "
                    f"where={{'{column}': {_value_text(present[0])}}}")


def _is_regime(column: str) -> bool:
    """Whether a column is a boolean parameter (contact.pure_rolling: a regime of its own)."""
    field = _field(split_header(column)[0])
    return field is not None and field.type == "boolean"


def plot_table(table: Mapping[str, np.ndarray], x: str, y: str,
               group: Optional[Sequence[str] | str] = None,
               units: Optional[Mapping[str, str]] = None, title: Optional[str] = None,
               where: Optional[Mapping[str, float]] = None, ax: Any = None,
               panels: Optional[str] = "auto", legend: Any = "auto",
               yscale: str = "auto") -> Any:
    """plot_sweep from a study table ({column: numeric values}, e.g. read_csv_columns of the
    CLI's sweep results, or a pandas DataFrame of StudyResult.to_dataframe()): y against x, one
    curve per combination of the `group` columns, only rows whose `where` columns equal the
    given values (booleans as 1/0; oscidrum.Error when no row does). Rows whose metric is
    missing (invalid or failed cases) leave gaps. Curves are labelled as people read the values
    (value_label: '$M_{Md}/M_0$ = 0.05', 'pure rolling'). More than COLORMAP_FROM curves of one
    group column are coloured by a colour map with a colour bar.

    panels: a group column whose values get a panel each, side by side with their own y scale
    (titled with the value); "auto" (the default): a boolean group column such as
    contact.pure_rolling, whose regimes (pure rolling, stick-slip) differ by orders of magnitude
    in most metrics, when it takes both values; None: one panel. yscale: as for plot_sweep, per
    panel. legend: as for plot_accelerations (one legend, on the last panel). ax: the Axes to
    draw into (one per panel)."""
    table = _as_table(table, "plot_table")
    units = units or {}
    groups = [group] if isinstance(group, str) else list(group or [])
    xcol, ycol = resolve_column(table, x), resolve_column(table, y)
    xs, ys = np.asarray(table[xcol], dtype=float), np.asarray(table[ycol], dtype=float)
    keep = _select(table, where)
    gcols = [resolve_column(table, g) for g in groups]
    n_axes = None if ax is None else (1 if hasattr(ax, "plot") else len(np.atleast_1d(
        np.asarray(ax, dtype=object))))
    pcol = None
    if panels == "auto":
        for c in gcols:
            present = np.unique(np.asarray(table[c], dtype=float)[keep])
            if _is_regime(c) and len(present) > 1 and n_axes in (None, len(present)):
                pcol = c
                break
    elif panels is not None:
        pcol = resolve_column(table, panels)
        if pcol not in gcols:
            raise Error(f"panels: {panels} is not a group column ({', '.join(gcols)})")
    pvalues: List[Optional[float]] = [None]
    if pcol is not None:
        pv = np.asarray(table[pcol], dtype=float)
        pvalues = list(dict.fromkeys(float(v) for v, ok in zip(pv, keep) if ok))
    ccols = [c for c in gcols if c != pcol]
    _check_one_case_per_point(table, keep, [xcol] + gcols, "plot_table", ycol)
    keys = [tuple(float(table[c][i]) for c in ccols) for i in range(len(xs))]
    combos = list(dict.fromkeys(k for k, ok in zip(keys, keep) if ok))
    many = len(ccols) == 1 and len(combos) > COLORMAP_FROM
    if ax is None:
        n = len(pvalues)
        fig, axes = new_figure(1, n, width=7.0 if n == 1 else 3.9 * n + 0.4, height=3.8)
        axes, made = list(np.atleast_1d(axes)), True
    else:
        fig, axes, made = _axes(ax, len(pvalues))
    for p, (axis, value) in enumerate(zip(axes, pvalues)):
        rows = keep if pcol is None else keep & (np.asarray(table[pcol], dtype=float) == value)
        curves: Dict[str, Any] = {}
        styles: List[int] = []
        colours: List[float] = []
        for j, combo in enumerate(combos):
            sel = rows & np.array([k == combo for k in keys])
            if not sel.any():
                continue
            order = np.argsort(xs[sel])
            label = ", ".join(value_label(c, v, units.get(c, "")) for c, v in zip(ccols, combo))
            curves[label] = (xs[sel][order], ys[sel][order])
            styles.append(j)
            colours.append(combo[0] if combo else 0.0)
        _draw_sweep(axis, None, curves, xcol, ycol, units.get(xcol, ""), units.get(ycol, ""),
                    color_values=colours if many else None,
                    color_key=ccols[0] if many else "",
                    color_unit=units.get(ccols[0], "") if many else "",
                    legend=legend if p == len(pvalues) - 1 else None, yscale=yscale,
                    styles=styles, ylabel=p == 0)
        _note_missing(axis, xs[rows], ys[rows], xcol, ycol, units)
        if pcol is not None:
            axis.set_title(value_label(pcol, value, units.get(pcol, "")), fontsize="medium")
    return _finish(fig, axes, made, title)


def _note_missing(axis: Any, xs: np.ndarray, ys: np.ndarray, xcol: str, ycol: str,
                  units: Mapping[str, str]) -> None:
    """Cases of a panel without a value of the metric (failed, not a steady state) leave gaps:
    the x axis still spans every swept value (a failed case at the end of the range was outside
    it), and a note says how many there are."""
    finite_x = np.isfinite(xs)
    missing = int(np.sum(finite_x & ~np.isfinite(ys)))
    if not missing:
        return
    _, xf = axis_label(xcol, units.get(xcol, ""))
    lo, hi = float(np.min(xs[finite_x])) * xf, float(np.max(xs[finite_x])) * xf
    if hi > lo:
        left, right = axis.get_xlim()
        if axis.get_xscale() == "log":
            axis.set_xlim(min(left, lo / 1.1), max(right, hi * 1.1))
        else:
            pad = 0.05 * (hi - lo)
            axis.set_xlim(min(left, lo - pad), max(right, hi + pad))
    name = ycol.split("[")[0]
    axis.text(0.01, 0.99, f"{missing} of {int(np.sum(finite_x))} cases without {name} "
              "(not a steady state): gaps", transform=axis.transAxes, ha="left", va="top",
              fontsize="x-small", color="0.3")


def plot_map(table: Mapping[str, np.ndarray], x: str, y: str, z: str = "area",
             units: Optional[Mapping[str, str]] = None, title: Optional[str] = None,
             where: Optional[Mapping[str, float]] = None, ax: Any = None,
             annotate: Optional[bool] = None) -> Any:
    """A heat map of the metric z over two swept parameters x and y (a study table as for
    plot_table): one cell per (x, y) pair of the rows kept by `where`, coloured by z with a
    colour bar; missing cases (failed, invalid) stay blank. Cells are labelled with their values
    when there are at most 150 (annotate=True/False forces it). ax: the Axes to draw into."""
    table = _as_table(table, "plot_map")
    units = units or {}
    xcol, ycol, zcol = (resolve_column(table, c) for c in (x, y, z))
    keep = _select(table, where)
    _check_one_case_per_point(table, keep, [xcol, ycol], "plot_map", zcol)
    xs = np.asarray(table[xcol], dtype=float)[keep]
    ys = np.asarray(table[ycol], dtype=float)[keep]
    zs = np.asarray(table[zcol], dtype=float)[keep]
    xu, yu = np.unique(xs[np.isfinite(xs)]), np.unique(ys[np.isfinite(ys)])
    if len(xu) == 0 or len(yu) == 0:
        raise Error(f"plot_map: no rows with values of {xcol} and {ycol}")
    grid = np.full((len(yu), len(xu)), np.nan)
    for xv, yv, zv in zip(xs, ys, zs):
        if np.isfinite(xv) and np.isfinite(yv):
            grid[np.searchsorted(yu, yv), np.searchsorted(xu, xv)] = zv
    if not np.isfinite(grid).any():
        raise Error(f"plot_map: no case has a value of {zcol} (none is a steady state): "
                    "nothing to plot")
    xlabel, xf = axis_label(xcol, units.get(xcol, ""))
    ylabel, yf = axis_label(ycol, units.get(ycol, ""))
    zlabel, zf = axis_label(zcol, units.get(zcol, ""))
    fig, axes, made = _axes(ax, 1, width=6.4, height=4.8)
    axis = axes[0]
    axis.grid(False)
    mesh = axis.pcolormesh(xu * xf, yu * yf, np.ma.masked_invalid(grid * zf), shading="nearest",
                           cmap="viridis")
    fig.colorbar(mesh, ax=axis, label=zlabel)
    if annotate is None:
        annotate = grid.size <= 150
    if annotate:
        lo, hi = np.nanmin(grid * zf), np.nanmax(grid * zf)
        for r, yv in enumerate(yu):
            for c, xv in enumerate(xu):
                v = grid[r, c] * zf
                if np.isfinite(v):
                    light = hi > lo and (v - lo) / (hi - lo) < 0.6
                    axis.text(xv * xf, yv * yf, f"{v:.3g}", ha="center", va="center",
                              fontsize="x-small", color="white" if light else "black")
    axis.set_xlabel(xlabel)
    axis.set_ylabel(ylabel)
    blank = int(np.sum(~np.isfinite(grid)))
    if blank:
        name = zcol.split("[")[0]
        axis.set_title(f"blank: {blank} of {grid.size} cells without {name} (not a steady state)",
                       fontsize="x-small", color="0.3")
    if len(xu) <= 16:
        axis.set_xticks(xu * xf)
    if len(yu) <= 16:
        axis.set_yticks(yu * yf)
    return _finish(fig, axes, made, title)


def swept_columns(table: Mapping[str, Any]) -> List[str]:
    """The swept keys of a study results table (oscidrum sweep --out): the columns between
    'case' and 'status'."""
    names = list(table)
    if "case" in names and "status" in names:
        return names[names.index("case") + 1: names.index("status")]
    return []


def plot_study(table: Mapping[str, np.ndarray], metric: str = "area",
               units: Optional[Mapping[str, str]] = None, title: Optional[str] = None,
               ax: Any = None, legend: Any = "auto") -> Any:
    """The natural plot of a study's results (used by ``oscidrum sweep --plot``): one swept key:
    the metric against it; two numeric keys (each with several values): a heat map (plot_map)
    over them; otherwise the metric against the first numeric key, one curve per combination
    of the others, and a panel per regime when a boolean key (contact.pure_rolling) is swept
    (plot_table). legend: as for plot_accelerations."""
    table = _as_table(table, "plot_study")
    keys = [k for k in swept_columns(table)
            if np.isfinite(np.asarray(table[k], dtype=float)).any()]
    if not keys:
        raise Error("no swept numeric column between 'case' and 'status' "
                    "(a results CSV of oscidrum sweep --out)")
    column = resolve_column(table, metric)
    if not np.isfinite(np.asarray(table[column], dtype=float)).any():
        statuses = sorted(set(str(v) for v in table.get("status", [])) - {"nan"})
        raise Error(f"no case of the study has a value of {column}"
                    + (f" (statuses: {', '.join(statuses)})" if statuses else "")
                    + ": nothing to plot")
    varying = [k for k in keys if len(np.unique(np.asarray(table[k], dtype=float))) > 1]
    keys = varying or keys
    numeric = [k for k in keys if not _is_regime(k)]
    if len(keys) == 2 and len(numeric) == 2:
        return plot_map(table, keys[0], keys[1], metric, units=units, title=title, ax=ax)
    x = numeric[0] if numeric else keys[0]
    return plot_table(table, x, metric, group=[k for k in keys if k != x], units=units,
                      title=title, ax=ax, legend=legend)


BIFURCATION_STYLE = {"fold": ("o", "tab:red"), "branch_point": ("D", "tab:purple"),
                     "period_doubling": ("s", "tab:orange"), "neimark_sacker": ("^", "tab:green"),
                     "grazing": ("x", "tab:gray"), "lift_off": ("v", "tab:brown")}


def plot_branch(table: Mapping[str, np.ndarray], metric: str = "area",
                units: Optional[Mapping[str, str]] = None,
                bifurcations: Optional[Sequence[Tuple[Any, ...]]] = None,
                title: Optional[str] = None, ax: Any = None, legend: Any = "auto") -> Any:
    """A branch of periodic orbits (``oscidrum continue --csv``): `metric` against the continued
    parameter, stable orbits solid, unstable dashed, one colour per branch (the period-2p branches
    born at period doublings beside the first); `bifurcations` (kind, parameter[, branch]) marked
    on their branch, each kind with its marker (``oscidrum continue --bifurcations``). legend:
    as for plot_accelerations."""
    units = dict(units or {})
    names = list(table)
    if "arclength" not in names or names.index("arclength") < 1:
        raise Error("not a branch CSV (oscidrum continue --csv): no parameter column before "
                    "'arclength'")
    key = names[names.index("arclength") - 1]
    metric = resolve_column(table, metric)
    q_all = np.asarray(table[key], dtype=float)
    y_all = np.asarray(table[metric], dtype=float)
    stable_all = np.asarray(table["stable"], dtype=float) > 0.5
    branch_all = (np.asarray(table["branch"], dtype=float) if "branch" in table
                  else np.zeros(len(q_all)))
    period_all = (np.asarray(table["multiplicity"], dtype=float) if "multiplicity" in table
                  else np.ones(len(q_all)))
    xlabel, xf = axis_label(key, units.get(key, ""))
    ylabel, yf = axis_label(metric, units.get(metric, ""))
    fig, axes, made = _axes(ax, 1, width=7.0, height=4.2)
    ax = axes[0]
    labelled = set()
    for index in np.unique(branch_all):
        rows = branch_all == index
        q, y, stable = q_all[rows], y_all[rows], stable_all[rows]
        p = int(period_all[rows][0]) if rows.any() else 1
        color = COLORS[int(index) % len(COLORS)]
        # Runs of equal stability, unbroken: between the last point of one and the first of the
        # next the stability changes at a bifurcation of this branch there (or, where none is
        # given, half way), where the one style ends and the other begins (the stable line ran on
        # to the first unstable point, past the Neimark-Sacker point marked on it).
        crossings = [float(item[1]) for item in bifurcations or []
                     if (int(item[2]) if len(item) > 2 else 0) == int(index)
                     and item[0] in ("fold", "branch_point", "period_doubling", "neimark_sacker")]

        def change_between(i: int) -> Tuple[float, float]:
            lo, hi = q[i - 1], q[i]
            at = next((c for c in crossings if min(lo, hi) <= c <= max(lo, hi) and hi != lo),
                      0.5 * (lo + hi))
            w = (at - lo) / (hi - lo) if hi != lo else 0.5
            return at, y[i - 1] + w * (y[i] - y[i - 1])

        start, head = 0, None  # head: where this run begins, between points (None: at its first)
        for k in range(1, len(q) + 1):
            if k == len(q) or stable[k] != stable[start]:
                qs, ys = list(q[start:k]), list(y[start:k])
                if head is not None:
                    qs.insert(0, head[0])
                    ys.insert(0, head[1])
                head = change_between(k) if k < len(q) else None
                if head is not None:
                    qs.append(head[0])
                    ys.append(head[1])
                kind = f"period {p} T, {'stable' if stable[start] else 'unstable'}"
                ax.plot(np.asarray(qs) * xf, np.asarray(ys) * yf, color=color,
                        linestyle="-" if stable[start] else "--",
                        label=None if kind in labelled else kind)
                labelled.add(kind)
                start = k
    for item in bifurcations or []:
        kind, at = item[0], item[1]
        on = item[2] if len(item) > 2 else 0
        q, y = q_all[branch_all == on], y_all[branch_all == on]
        if len(q) == 0:
            continue
        marker, color = BIFURCATION_STYLE.get(kind, ("*", "black"))
        value = float(np.interp(at, q, y)) if q[0] <= q[-1] else float(np.interp(at, q[::-1], y[::-1]))
        ax.plot([at * xf], [value * yf], marker=marker, color=color, linestyle="none",
                markersize=8, label=None if kind in labelled else kind.replace("_", " "))
        labelled.add(kind)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    _legend(ax, legend=legend)
    return _finish(fig, axes, made, title)


def read_bifurcations(path: str | os.PathLike) -> List[Tuple[str, float, int]]:
    """(kind, parameter, branch) of every bifurcation in ``oscidrum continue --bifurcations
    FILE``."""
    from .data import read_table
    table, _ = read_table(path)
    names = list(table)
    if "kind" not in names or names.index("kind") + 1 >= len(names):
        raise Error(f"{path}: not a bifurcations CSV (oscidrum continue --bifurcations)")
    parameter = names[names.index("kind") + 1]
    branch = table.get("branch", ["0"] * len(table["kind"]))
    return [(kind, float(value), int(float(b)))
            for kind, value, b in zip(table["kind"], table[parameter], branch)]


def plot_diagram(table: Mapping[str, Sequence[str]], quantity: str = "ddx_M",
                 units: Optional[Mapping[str, str]] = None, title: Optional[str] = None,
                 ax: Any = None, legend: Any = "auto") -> Any:
    """A brute-force bifurcation diagram (``oscidrum diagram --csv``, read as text by
    oscidrum.data.read_table): the stroboscopic points of `quantity` against the parameter, the
    up sweep's in blue, the down sweep's in red (one point per period on a period-1 orbit, p
    points on a period-p orbit, a cloud on a torus or chaos). legend: as for
    plot_accelerations."""
    units = dict(units or {})
    names = list(table)
    if "value" not in names or "point" not in names or names.index("point") < 2:
        raise Error("not a diagram CSV (oscidrum diagram --csv): no parameter column between "
                    "'value' and 'point'")
    key = names[names.index("point") - 1]
    if quantity not in table:
        raise Error(f"no column '{quantity}' in the diagram CSV")
    q_all = np.asarray([float(c) for c in table[key]])
    y_all = np.asarray([float(c) if c else np.nan for c in table[quantity]])
    sweep = np.asarray(table["sweep"]) if "sweep" in table else np.full(len(q_all), "up")
    xlabel, xf = axis_label(key, units.get(key, ""))
    ylabel, yf = axis_label(quantity, units.get(quantity, ""))
    fig, axes, made = _axes(ax, 1, width=7.0, height=4.2)
    ax = axes[0]
    for direction, color, marker in (("up", "tab:blue", "."), ("down", "tab:red", "x")):
        rows = sweep == direction
        if rows.any():
            ax.plot(q_all[rows] * xf, y_all[rows] * yf, linestyle="none", marker=marker,
                    markersize=3, color=color, label=f"sweep {direction}")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"{ylabel} at t0 + k T")
    ax.grid(True, alpha=0.3)
    _legend(ax, legend=legend)
    return _finish(fig, axes, made, title)


def plot_case(data: Any, out_dir: str | os.PathLike, fmt: str = "png", label: str = "",
              periods: float = 2, spectra_units: str = "both") -> List[Path]:
    """Every single-case figure of a steady state into out_dir: accelerations, figure_eight,
    spectra, delta_phi, forces (.png or .svg), titled with the case's key parameters. The
    spectra in `spectra_units` (plot_spectra's units; "both": A_n in m/s^2 with A_n / max A_n
    on the right axis). Returns the paths written. `data` as for the other plots, a (result,
    case) pair included."""
    if _is_pair(data):
        state = from_result(data[0], label=label, parameters=_flat_parameters(data[1]))
    else:
        state = as_steady_state(data, label=label)
    out = Path(out_dir)
    title = state.label or None
    figures = {
        "accelerations": plot_accelerations(state, periods=periods, title=title),
        "figure_eight": plot_figure_eight(state, title=title),
        "spectra": plot_spectra(state, title=title, units=spectra_units),
        "delta_phi": plot_delta_phi(state, periods=periods, title=title),
        "forces": plot_forces(state, periods=periods, title=title),
    }
    return [save(fig, out / f"{name}.{fmt}", fmt) for name, fig in figures.items()]


def _periods(text: str) -> float:
    """--periods: a finite number of excitation periods > 0 (0 would draw empty time plots)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expects a number of periods > 0; got '{text}'")
    if not (value > 0.0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(f"must be a finite number of periods > 0; got '{text}'")
    return value


def _parse(argv: Optional[Sequence[str]]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="python3 -m oscidrum.plot",
        description="Plot a steady state or a study written by the oscidrum CLI. Run it with the "
        "interpreter the package is installed for (on Debian /usr/bin/python3; see "
        "docs/python.md).")
    sub = parser.add_subparsers(dest="command", required=True)
    case = sub.add_parser("case", help="figures of one steady state (CSV of docs/csv-columns.md)")
    case.add_argument("--csv", required=True, help="steady-state CSV (oscidrum run --csv)")
    case.add_argument("--json", help="summary JSON (oscidrum run --json); optional")
    case.add_argument("--out", required=True, help="output directory")
    case.add_argument("--format", choices=("png", "svg"), default="png")
    case.add_argument("--label", default="", help="title of the figures")
    case.add_argument("--periods", type=_periods, default=2,
                      help="excitation periods shown in the time plots (> 0; default 2)")
    case.add_argument("--spectra-units", choices=SPECTRUM_UNITS, default="both",
                      help="spectra.png: A_n / max A_n (normalised, the paper's), A_n in m/s^2, "
                      "or both (m/s^2 on the left axis, normalised on the right; the default)")
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
    heat = sub.add_parser("map", help="heat map of a metric over two swept parameters")
    heat.add_argument("--csv", required=True, help="study results CSV (oscidrum sweep)")
    heat.add_argument("--x", required=True, help="parameter column on the x axis, e.g. soil.G")
    heat.add_argument("--y", required=True, help="parameter column on the y axis, e.g. roller.f")
    heat.add_argument("--z", default="area", help="metric column (default area)")
    heat.add_argument("--where", action="append", default=[], metavar="KEY=VALUE",
                      help="only rows with this value, e.g. contact.pure_rolling=true")
    heat.add_argument("--out", required=True, help="output file (.png or .svg)")
    study = sub.add_parser("study", help="the natural plot of a study (oscidrum sweep --plot): "
                           "a curve for one swept key, a heat map for two")
    study.add_argument("--csv", required=True, help="study results CSV (oscidrum sweep)")
    study.add_argument("--metric", default="area", help="metric column (default area)")
    study.add_argument("--out", required=True, help="output file (.png or .svg)")
    branch = sub.add_parser("branch", help="a branch of periodic orbits (oscidrum continue "
                            "--plot): a metric against the parameter, stable solid, unstable "
                            "dashed, bifurcations marked")
    branch.add_argument("--csv", required=True, help="branch CSV (oscidrum continue --csv)")
    branch.add_argument("--metric", default="area", help="metric column (default area)")
    branch.add_argument("--bifurcations", help="bifurcations CSV (oscidrum continue "
                        "--bifurcations); optional")
    branch.add_argument("--out", required=True, help="output file (.png or .svg)")
    diagram = sub.add_parser("diagram", help="a brute-force bifurcation diagram (oscidrum "
                             "diagram --plot): the stroboscopic points against the parameter")
    diagram.add_argument("--csv", required=True, help="diagram CSV (oscidrum diagram --csv)")
    diagram.add_argument("--quantity", default="ddx_M", help="output column (default ddx_M)")
    diagram.add_argument("--out", required=True, help="output file (.png or .svg)")
    return parser.parse_args(argv)


def _where(items: Sequence[str]) -> Dict[str, float]:
    where: Dict[str, float] = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep:
            raise Error(f"--where expects KEY=VALUE; got '{item}'")
        flag = {"true": 1.0, "false": 0.0}.get(value)
        where[key] = flag if flag is not None else float(value)
    return where


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Entry point of ``python3 -m oscidrum.plot``; prints the files written."""
    args = _parse(argv)
    try:
        if args.command == "case":
            if args.json is not None and not os.path.exists(args.json):
                print(f"warning: --json {args.json}: no such file; the frequency and the periods "
                      "are inferred from the CSV, the summary's status and metrics are not shown",
                      file=sys.stderr)
            state = read_case(args.csv, args.json, label=args.label)
            paths = plot_case(state, args.out, args.format, periods=args.periods,
                              spectra_units=args.spectra_units)
        elif args.command == "sweep":
            table, units = read_csv_columns(args.csv)
            where = _where(args.where)
            paths = []
            for y in args.y:
                fig = plot_table(table, args.x, y, group=args.group, units=units, where=where)
                name = f"{split_header(y)[0]}_vs_{split_header(args.x)[0]}".replace("/", "_")
                paths.append(save(fig, Path(args.out) / f"{name}.{args.format}", args.format))
        elif args.command == "map":
            table, units = read_csv_columns(args.csv)
            fig = plot_map(table, args.x, args.y, args.z, units=units, where=_where(args.where))
            paths = [save(fig, args.out)]
        elif args.command == "branch":
            table, units = read_csv_columns(args.csv)
            bifs = read_bifurcations(args.bifurcations) if args.bifurcations else None
            fig = plot_branch(table, args.metric, units=units, bifurcations=bifs)
            paths = [save(fig, args.out)]
        elif args.command == "diagram":
            from .data import read_table
            text, units = read_table(args.csv)
            fig = plot_diagram(text, args.quantity, units=units)
            paths = [save(fig, args.out)]
        else:
            table, units = read_csv_columns(args.csv)
            fig = plot_study(table, args.metric, units=units)
            paths = [save(fig, args.out)]
    except (OSError, ValueError, KeyError) as exc:
        print(f"oscidrum.plot: error: {exc}", file=sys.stderr)
        from ._interrupt import EXIT_EXPLAINED
        return EXIT_EXPLAINED
    for path in paths:
        print(path)
    return 0


if __name__ == "__main__":
    from ._interrupt import run_main

    sys.exit(run_main(main, "oscidrum.plot"))
