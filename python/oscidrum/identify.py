"""The soil under the drum from measured accelerations (docs/identify.md).

:func:`identify` estimates G (or ksh, ksv), optionally mu and MMd, in each window of a record,
with the compiled core's Levenberg-Marquardt fit (the Python twin of ``oscidrum identify``).
:func:`plot_pass` draws G with its 95 % band against time or position; :func:`plot_fit` the
measured and the best-fitting simulated accelerations, spectra and z_M''-x_M'' figures of one
window (as the paper's Fig. 23), from the files ``oscidrum identify --plot DIR`` writes.

Command line (``oscidrum identify --plot DIR`` calls it)::

    python3 -m oscidrum.identify plot --dir DIR [--format png|svg]
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path
from collections.abc import Mapping
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from ._checks import is_integer, is_number
from ._files import output_path

#: The unknowns, their display unit and factor from SI.
_DISPLAY = {"G": (r"$G$", r"MN/m$^2$", 1e-6), "ksh": (r"$k_{sh}$", "MN/m", 1e-6),
            "ksv": (r"$k_{sv}$", "MN/m", 1e-6), "mu": (r"$\mu$", "-", 1.0),
            "MMd": (r"$M_{Md}$", "kN m", 1e-3)}


def _z_down(z: np.ndarray, z_positive: str, where: str) -> Tuple[np.ndarray, bool, bool]:
    """ddz_M positive down, whether its direction is open, and whether it was negated (read as
    pointing up): negated for 'up'; for 'auto' (the
    default), negated when its mean is about +1 g (within 0.15 g), which an accelerometer at rest
    reads along an axis pointing up, with a warning, as ``oscidrum identify --z-positive auto``
    reads a file; open when 'auto' finds no gravity either way (identify then fits ddz_M negated
    where that fits and as given does not)."""
    from . import Error, gravity_points_up
    if z_positive not in ("auto", "down", "up"):
        raise Error(f"z_positive must be 'auto', 'down' or 'up'; got {z_positive!r}")
    if z_positive == "up":
        return -z, False, True
    if z_positive != "auto":
        return z, False, False
    up, mean = gravity_points_up(z)
    if up:
        import warnings
        warnings.warn(f"{where}: ddz_M's mean is {mean:.6g} m/s^2, about +1 g, which an "
                      "accelerometer at rest reads along an axis pointing up: read as pointing up "
                      "(negated); give z_positive='down' to read it as it is", stacklevel=3)
        return -z, False, True
    down, _ = gravity_points_up(-z)
    return z, not down, False


# The options identify passes on to identify_record (its keyword arguments but the arrays, the
# position and z_open, which identify sets).
_IDENTIFY_OPTIONS = ("f", "window", "hop", "n_max", "estimate", "fit_mu", "fit_MMd", "compare",
                     "use_peaks", "use_area", "profile", "shooting", "soil_scale", "units_open",
                     "gain_uncertainty")

# What each option takes: "number" (window also None), "integer", "text" or "boolean".
_OPTION_KINDS = {"f": "number", "window": "number", "hop": "number", "gain_uncertainty": "number",
                 "n_max": "integer", "compare": "integer", "estimate": "text",
                 "soil_scale": "text", "fit_mu": "boolean", "fit_MMd": "boolean",
                 "use_peaks": "boolean", "use_area": "boolean", "profile": "boolean",
                 "shooting": "boolean", "units_open": "boolean"}


def _check_option_types(who: str, options: Dict[str, Any]) -> None:
    """One line naming the option and what it takes (pybind11's refusal dumped the binding's
    signature, with arguments identify does not have, and the value at its very end)."""
    from . import Error
    for name, value in options.items():
        kind = _OPTION_KINDS.get(name)
        ok = {"number": (value is None and name == "window") or is_number(value),
              "integer": is_integer(value),
              "text": isinstance(value, str),
              "boolean": isinstance(value, (bool, np.bool_))}.get(kind, True)
        if not ok:
            what = {"number": "a number" + (" or None" if name == "window" else ""),
                    "integer": "an integer", "text": "a string", "boolean": "True or False"}[kind]
            raise Error(f"{who}: {name} must be {what}; got {type(value).__name__} ({value!r})")


def identify(t: Sequence[float], ddx_M: Sequence[float], ddz_M: Sequence[float], case=None,
             position: Optional[Sequence[float]] = None, x_positive: str = "forward",
             z_positive: str = "auto", **options: Any) -> List[Dict[str, Any]]:
    """Identify the soil in each window of a record (t [s], ddx_M, ddz_M [m/s^2]).

    The model's axes: x_M'' positive forward (the direction of travel), z_M'' positive down.
    A record whose axes point the other way gives ``x_positive='backward'`` or
    ``z_positive='up'`` (most accelerometer mounts); the channel is negated. ``z_positive='auto'``
    (the default) is 'down' unless ddz_M's mean is about +1 g (gravity along an axis pointing
    up: then 'up', with a warning), as the CLI reads a file; without gravity in ddz_M, a window
    that fits poorly as given and well with ddz_M negated is fitted negated (its ``z_negated``
    true, with a warning). A poor fit that a negated axis or the other soil scale would fix
    says so in ``warnings``.

    ``case`` (an :class:`oscidrum.Case`, default the paper's roller) gives everything not
    estimated. Options as :func:`oscidrum.identify_record`: f (0: estimated), window (periods,
    default None: 40, or the whole record when it is shorter; 0: the whole record), hop, n_max, estimate ('G' or 'ks'), fit_mu, fit_MMd,
    compare (harmonics compared), use_peaks, use_area, profile, shooting (the model's steady
    states by shooting, default; False: by the transient from rest). Returns one dict per window with
    the keys of the CLI's CSV columns (G, G_u, G_lo, G_hi in Pa, ..., valid, reason, warnings).
    """
    from . import Case, Error, identify_record
    if x_positive not in ("forward", "backward"):
        raise Error(f"x_positive must be 'forward' or 'backward'; got {x_positive!r}")
    # A misspelled option or a case of another type: said in one line (pybind11's refusal named
    # identify_record and dumped its signature and the arrays, without the option's name).
    for name in options:
        if name not in _IDENTIFY_OPTIONS:
            import difflib
            near = difflib.get_close_matches(name, _IDENTIFY_OPTIONS, n=1)
            raise Error(f"identify: unknown option {name!r}" +
                        (f" (did you mean {near[0]!r}?)" if near else "") +
                        "; the options: " + ", ".join(_IDENTIFY_OPTIONS))
    _check_option_types("identify", options)
    if case is not None and not isinstance(case, Case):
        raise Error(f"identify: case must be an oscidrum.Case; got {type(case).__name__}")
    arrays = [np.asarray(a, dtype=float) for a in (t, ddx_M, ddz_M)]
    if x_positive == "backward":
        arrays[1] = -arrays[1]
    arrays[2], z_open, z_up = _z_down(arrays[2], z_positive, "identify")
    pos = None if position is None else np.asarray(position, dtype=float)
    return identify_record(case if case is not None else Case(), *arrays, position=pos,
                           z_open=z_open, x_read_backward=x_positive == "backward",
                           z_read_up=z_up, **options)


def identify_frame(t: Sequence[float], ddx_M: Sequence[float], ddz_M: Sequence[float], case=None,
                   position: Optional[Sequence[float]] = None, **options: Any):
    """:func:`identify` as a pandas DataFrame: one row per window, the scalar columns of the
    CLI's CSV (window, t_start, t_end, t [s], position [m], f [Hz], drift, change, valid, reason,
    G, G_u, G_lo, G_hi [Pa] or the unknowns estimated, tau [s], the residuals, iterations,
    simulations) and ``warnings`` (a list per window). :func:`to_geojson` maps it."""
    import pandas as pd
    rows = identify(t, ddx_M, ddz_M, case=case, position=position, **options)
    keep = [{k: v for k, v in row.items() if k not in ("metrics", "fitted")} for row in rows]
    return pd.DataFrame(keep)


def calibrate(references: Sequence[Dict[str, Any]], case=None,
              parameters: Sequence[str] = ("roller.M0",), soil_scale: str = "formulas",
              x_positive: str = "forward", z_positive: str = "auto",
              **options: Any) -> Dict[str, Any]:
    """Calibrate the roller on reference records of known soil (``oscidrum calibrate``).

    Each reference is a dict with ``t`` [s], ``ddx_M``, ``ddz_M`` [m/s^2] (the whole record is
    one window), the soil under it as ``G`` [Pa] on ``soil_scale`` ('formulas' or 'table2') or
    as ``soil`` (an :class:`oscidrum.Soil`; neither: the case's soil), and optionally ``name``.
    ``parameters`` are the case fields fitted (e.g. ``["roller.M0", "roller.P0"]``); ``case``
    (default the paper's roller) gives their start values and everything else. The axes as in
    :func:`identify`. Options: f (0: estimated per record), n_max (the gates' harmonics),
    compare, range, profile, shooting. Returns a dict with ``estimates`` (name, unit, value,
    standard_uncertainty, lower, upper, ...), ``references`` (how each fits), ``reduced_chi2``,
    ``warnings`` and ``calibrated``, the :class:`oscidrum.Case` to pass to :func:`identify`
    (``oscidrum.case_to_toml`` writes it as a case file)."""
    from . import Case, Error, calibrate_records, soil_on_scale
    if x_positive not in ("forward", "backward"):
        raise Error(f"x_positive must be 'forward' or 'backward'; got {x_positive!r}")
    if z_positive not in ("auto", "down", "up"):
        raise Error(f"z_positive must be 'auto', 'down' or 'up'; got {z_positive!r}")
    base = case if case is not None else Case()
    refs = []
    for k, ref in enumerate(references):
        if not isinstance(ref, Mapping):
            raise Error(f"reference {k} must be a dict with t, ddx_M, ddz_M and G or soil (as "
                        f"synthetic_record or read_record gives them); got "
                        f"{type(ref).__name__}")
        missing = [key for key in ("t", "ddx_M", "ddz_M") if key not in ref]
        if missing:
            raise Error(f"reference {k} has no {', '.join(missing)}")
        if "G" in ref and "soil" in ref:
            raise Error(f"reference {k}: give G or soil, not both")
        if "G" in ref:
            soil = soil_on_scale(float(ref["G"]), soil_scale, base.soil)
        else:
            soil = ref.get("soil", base.soil)
        x = np.asarray(ref["ddx_M"], dtype=float)
        z = np.asarray(ref["ddz_M"], dtype=float)
        z_down, z_open, _ = _z_down(z, z_positive, f"calibrate: reference {k}")
        entry = {"name": str(ref.get("name", f"reference {k}")), "soil": soil,
                 "t": np.asarray(ref["t"], dtype=float),
                 "ddx_M": -x if x_positive == "backward" else x,
                 "ddz_M": z_down, "z_open": z_open}
        if "G" in ref:  # a poor fit checks the other scale (and names it when that fits)
            entry.update(G=float(ref["G"]), soil_scale=soil_scale)
        refs.append(entry)
    return calibrate_records(base, refs, list(parameters), **options)


def _json_value(v: Any) -> Any:
    """A table cell as JSON: numpy scalars as Python numbers, NaN and infinities as null."""
    if isinstance(v, (list, tuple)):
        return [_json_value(x) for x in v]
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return float(v) if math.isfinite(v) else None
    if v is None or isinstance(v, str):
        return v
    return str(v)


def to_geojson(rows, t: Optional[Sequence[float]] = None, lat: Optional[Sequence[float]] = None,
               lon: Optional[Sequence[float]] = None, path: Optional[str | Path] = None,
               name: str = "") -> Dict[str, Any]:
    """The pass as GeoJSON (RFC 7946), in the layout of ``oscidrum identify --geojson``: a
    FeatureCollection with one Feature per window (``rows``: :func:`identify`'s list or
    :func:`identify_frame`'s DataFrame). With the record's times ``t`` [s] and GNSS ``lat``,
    ``lon`` [deg, WGS 84] (one per sample; NaN between a logger's fixes), each feature is the
    Point at its window's centre (interpolated linearly in time between the fixes, held beyond
    the first and last); without them, or without any fix, its geometry is null. The properties are the
    window's scalar columns as the rows name them (``G``, ``G_lo``, ``G_hi``, ... in SI units,
    G in Pa; NaN as null) and ``warnings`` -- not the CLI file's properties (``G`` in MN/m^2 with
    ``G_lower``, ``G_upper``, ``G_unit``): the two files' ``G`` differ by 1e6.
    ``path``: also write the file. Returns the GeoJSON as a dict."""
    from . import Error
    records = rows.to_dict("records") if hasattr(rows, "to_dict") else list(rows)
    have_points = lat is not None or lon is not None
    if have_points:
        if t is None or lat is None or lon is None:
            raise Error("to_geojson: give t, lat and lon together (one value per sample)")
        t_arr, lat_arr, lon_arr = (np.asarray(a, dtype=float) for a in (t, lat, lon))
        if not (t_arr.shape == lat_arr.shape == lon_arr.shape) or t_arr.ndim != 1:
            raise Error("to_geojson: t, lat and lon must be 1-D arrays of one length")
        if np.any(np.abs(lat_arr) > 90) or np.any(np.abs(lon_arr) > 180):
            raise Error("to_geojson: lat and lon must be in [-90, 90] and [-180, 180] degrees")
        # A logger's GNSS columns hold a fix every few rows, NaN between (empty cells): the
        # centres are interpolated between the fixes, as the CLI does (NaN coordinates were
        # written, which is no JSON); without any fix the geometry is null.
        fix = np.isfinite(t_arr) & np.isfinite(lat_arr) & np.isfinite(lon_arr)
        t_arr, lat_arr, lon_arr = t_arr[fix], lat_arr[fix], lon_arr[fix]
        have_points = t_arr.size > 0
    features = []
    for row in records:
        props = {k: _json_value(v) for k, v in row.items() if k not in ("metrics", "fitted")}
        geometry = None
        if have_points and props.get("t") is not None:
            centre = float(row["t"])
            if math.isfinite(centre):
                geometry = {"type": "Point",
                            "coordinates": [float(np.interp(centre, t_arr, lon_arr)),
                                            float(np.interp(centre, t_arr, lat_arr))]}
        features.append({"type": "Feature", "geometry": geometry, "properties": props})
    collection = {"type": "FeatureCollection", "name": name, "features": features}
    if path is not None:
        from ._files import write_file
        write_file(path, json.dumps(collection, indent=2) + "\n")
    return collection


def _figure(width: float = 7.0, height: float = 4.0):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(width, height), layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def read_csv(path: str | Path) -> Dict[str, np.ndarray]:
    """A CSV of the CLI as columns (names without their [unit]); text columns stay strings."""
    lines = Path(path).read_text().splitlines()
    import csv
    rows = list(csv.reader(lines))
    names = [h.split("[")[0] for h in rows[0]]
    out: Dict[str, np.ndarray] = {}
    for k, name in enumerate(names):
        cells = [r[k] for r in rows[1:]]
        try:
            out[name] = np.array([float(c) if c != "" else math.nan for c in cells])
        except ValueError:
            out[name] = np.array(cells, dtype=object)
    return out


def plot_pass(rows, x: str = "auto", parameter: str = "G", legend: Any = "auto"):
    """G (or another unknown) with its 95 % band against time or position (x = 't',
    'position' or 'auto': position if the rows have it). ``rows``: the result of
    :func:`identify` or the path of ``oscidrum identify --csv``. legend: where the legend goes,
    as in :mod:`oscidrum.plot` ("auto", "best"/"inside", "outside", "below", a matplotlib
    location, None/False). Returns a Figure."""
    from .plot import _legend, _place_legends
    if isinstance(rows, (str, Path)):
        cols = read_csv(rows)
        reasons, warnings = _text_columns(rows, ("reason", "warnings"))
    else:
        cols = {k: np.array([r.get(k, math.nan) for r in rows], dtype=float)
                for k in ("t", "position", parameter, parameter + "_lo", parameter + "_hi",
                          "valid")}
        reasons = [str(r.get("reason", "")) for r in rows]
        warnings = ["; ".join(r.get("warnings", [])) if isinstance(r.get("warnings"), list)
                    else str(r.get("warnings", "")) for r in rows]
    if x == "auto":
        x = "position" if np.isfinite(cols.get("position", np.array([np.nan]))).any() else "t"
    label, unit, k = _DISPLAY.get(parameter, (parameter, "", 1.0))
    fig = _figure()
    ax = fig.add_subplot()
    xs = cols[x]
    v, lo, hi = (cols[parameter] * k, cols[parameter + "_lo"] * k, cols[parameter + "_hi"] * k)
    ax.fill_between(xs, lo, hi, color="tab:blue", alpha=0.25, lw=0, label="95 % interval")
    ax.plot(xs, v, "-", color="tab:blue", lw=1)
    warned = np.array([bool(w) for w in warnings]) & np.isfinite(v)
    ax.plot(xs[~warned], v[~warned], "o", color="tab:blue", ms=3, label="estimate")
    if warned.any():
        ax.plot(xs[warned], v[warned], "o", mfc="white", mec="tab:orange", ms=5, mew=1.2,
                label="estimate with a warning (poor fit, ...)")
    # Failed windows: those over a change of soil (the change gate) apart from the other gates.
    bad = ~np.isfinite(v)
    changed = bad & np.array(["changes within the window" in r for r in reasons])
    for mask, style, text in ((changed, dict(color="tab:purple", ls="--", alpha=0.6),
                               "soil changes within the window"),
                              (bad & ~changed, dict(color="tab:red", ls="-", alpha=0.3),
                               "window failed a gate")):
        if mask.any():
            for xb in xs[mask]:
                if np.isfinite(xb):
                    ax.axvline(xb, lw=1.2, **style)
            ax.plot([], [], lw=1.2, label=text, **style)
    ax.set_xlabel("position [m]" if x == "position" else "time [s]")
    ax.set_ylabel(f"{label} [{unit}]")
    ax.set_title(f"identified {label} along the pass (lumped model, docs/identify.md)")
    ax.grid(alpha=0.3)
    _legend(ax, legend=legend)
    _place_legends(fig, [ax])
    return fig


def _text_columns(path, names):
    """The text columns `names` of a CSV of ``identify --csv`` (quoted cells kept whole), as
    lists of strings ('' for a missing column)."""
    import csv
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = [h.split("[")[0] for h in next(reader)]
        rows = list(reader)
    out = []
    for name in names:
        j = header.index(name) if name in header else None
        out.append([r[j] if j is not None and j < len(r) else "" for r in rows])
    return out


def plot_fit(directory: str | Path, legend: Any = "auto"):
    """Measured against simulated for one window, from the files of ``identify --plot DIR``
    (fit_measured.csv, fit_model.csv, fit_spectrum.csv, fit.json): three Figures (time
    histories over two periods, spectra, z_M''-x_M'' figure) with the estimates in the title.
    legend: as for plot_pass (one legend per figure)."""
    from .plot import _legend, _place_legends
    d = Path(directory)
    meas = read_csv(d / "fit_measured.csv")
    model = read_csv(d / "fit_model.csv")
    spec = read_csv(d / "fit_spectrum.csv")
    info = json.loads((d / "fit.json").read_text())
    parts = []
    for e in info["estimates"]:
        label, unit, k = _DISPLAY.get(e["name"], (e["name"], e["unit"], 1.0))
        parts.append(f"{label} = {e['value'] * k:.4g} ± {e['standard_uncertainty'] * k:.2g} {unit}")
    title = (", ".join(parts) + f"; f = {info['f']:.4g} Hz, window {info['window']}"
             f" (t = {info['t_start']:.3g}-{info['t_end']:.3g} s)")

    t0 = model["t"][0]
    figs = []
    fig = _figure(7.5, 5.0)
    axes = fig.subplots(2, 1, sharex=True)
    for ax, key, lab in ((axes[0], "ddx_M", r"$\ddot{x}_M$ [m/s$^2$]"),
                         (axes[1], "ddz_M", r"$\ddot{z}_M$ [m/s$^2$] (down +)")):
        ax.plot(meas["t"] - t0, meas[key], ".", ms=3, color="0.4", label="measured")
        ax.plot(model["t"] - t0, model[key], "-", color="tab:red", label="model, best fit")
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
    axes[1].set_xlabel(f"time from t = {t0:.4g} s [s]")
    fig.suptitle(title, fontsize="small")
    _legend(axes[0], legend=legend, under=axes[1])
    _place_legends(fig, [axes[0]])
    figs.append(("fit_accelerations", fig))

    fig = _figure(7.5, 4.0)
    axes = fig.subplots(1, 2)
    w = 0.38
    for ax, key, lab in ((axes[0], "ddx", r"$\ddot{x}_M$"), (axes[1], "ddz", r"$\ddot{z}_M$")):
        n = spec["n"]
        ax.bar(n - w / 2, spec[key + "_A_measured"], w, color="0.5", label="measured")
        ax.bar(n + w / 2, spec[key + "_A_model"], w, color="tab:red", label="model")
        ax.set_xlabel(r"harmonic $n$ ($n f$)")
        ax.set_ylabel(lab + r" amplitude $A_n$ [m/s$^2$]")
        ax.grid(alpha=0.3, axis="y")
    fig.suptitle(title, fontsize="small")
    _legend(axes[0], legend=legend)
    _place_legends(fig, [axes[0]])
    figs.append(("fit_spectra", fig))

    fig = _figure(5.5, 5.0)
    ax = fig.add_subplot()
    ax.plot(meas["ddx_M"], meas["ddz_M"], ".", ms=3, color="0.4", label="measured")
    ax.plot(np.append(model["ddx_M"], model["ddx_M"][:1]),
            np.append(model["ddz_M"], model["ddz_M"][:1]), "-", color="tab:red",
            label="model, best fit")
    ax.set_xlabel(r"$\ddot{x}_M$ [m/s$^2$]")
    ax.set_ylabel(r"$\ddot{z}_M$ [m/s$^2$] (down +)")
    ax.grid(alpha=0.3)
    fig.suptitle(title, fontsize="small")
    _legend(ax, legend=legend, beside="below")
    _place_legends(fig, [ax])
    figs.append(("fit_figure", fig))
    return figs


def plot_directory(directory: str | Path, fmt: str = "png") -> List[Path]:
    """Every plot of ``oscidrum identify --plot DIR``: pass_<unknown>.png from identify.csv,
    and fit_accelerations, fit_spectra, fit_figure from the fit files (if there are)."""
    d = Path(directory)
    written = []
    if (d / "identify.csv").exists():
        cols = read_csv(d / "identify.csv")
        for name in _DISPLAY:
            if name in cols and name + "_lo" in cols:
                fig = plot_pass(d / "identify.csv", parameter=name)
                path = d / f"pass_{name}.{fmt}"
                with output_path(path) as target:
                    fig.savefig(target, format=fmt, dpi=120)
                written.append(path)
    if (d / "fit.json").exists() and (d / "fit_model.csv").exists():
        for name, fig in plot_fit(d):
            path = d / f"{name}.{fmt}"
            with output_path(path) as target:
                fig.savefig(target, format=fmt, dpi=120)
            written.append(path)
    return written


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m oscidrum.identify",
                                     description="Plots of `oscidrum identify --plot DIR`.")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("plot", help="plot the files in DIR")
    p.add_argument("--dir", required=True)
    p.add_argument("--format", default="png", choices=["png", "svg"])
    args = parser.parse_args(argv)
    written = plot_directory(args.dir, args.format)
    if not written:
        print(f"oscidrum.identify: nothing to plot in {args.dir}", file=sys.stderr)
        from ._interrupt import EXIT_EXPLAINED
        return EXIT_EXPLAINED
    for path in written:
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    from ._interrupt import run_main

    sys.exit(run_main(main, "oscidrum.identify"))
