"""Steady-state data in one shape, whatever its source.

The plots take a :class:`SteadyState`: built from a :class:`oscidrum.Result` (or a study's
``CaseOutcome``) with :func:`from_result`, or read from the CLI's output with :func:`read_case`
(the steady-state CSV of ``docs/csv-columns.md`` plus, optionally, the ``oscidrum-case/1`` JSON
summary). The columns come from the compiled core's output table (the one description of every
output), so this module, and the plots, need it as the rest of the package does.

Also here: the CSV writer of the same contract (``%.17g``, round-trip exact) and a reader for
any ``name[unit]`` table such as the CLI's sweep results.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from . import _core, _core_error

if _core is None:
    raise ImportError("oscidrum.data and oscidrum.plot need the compiled module oscidrum._core "
                      "(its output table names the columns), which could not be imported "
                      f"({_core_error}); build it (cmake -DOSCIDRUM_BUILD_PYTHON=ON) or install "
                      "the package (pip install --no-build-isolation .), see docs/python.md")

from ._files import write_file  # noqa: E402

#: Every refusal of these modules is the library's oscidrum.Error (a ValueError), which
#: `except oscidrum.Error` catches (a plain ValueError escaped it).
Error = _core.Error

#: Columns of docs/csv-columns.md: (attribute, unit), in file order, from the library's output
#: table (the one description of every output).
COLUMNS: Tuple[Tuple[str, str], ...] = tuple(
    (name, unit) for name, unit in _core.sample_columns())

#: Columns that files written before they existed lack; read_case computes them (alpha = nu t).
_LATER_COLUMNS = ("alpha",)

#: The CSV header line of docs/csv-columns.md (without line break).
HEADER = ",".join(f"{name}[{unit}]" for name, unit in COLUMNS)


def split_header(cell: str) -> Tuple[str, str]:
    """Split a ``name[unit]`` header cell into (name, unit); unit '' if there is none."""
    cell = cell.strip()
    if cell.endswith("]") and "[" in cell:
        i = cell.index("[")
        return cell[:i], cell[i + 1:-1]
    return cell, ""


@dataclass
class SteadyState:
    """A sampled steady state, ready to plot.

    ``samples`` has one NumPy array per column of docs/csv-columns.md (``samples.t`` [s],
    ``samples.ddx_M`` [m/s^2], ..., ``samples.phase`` int8: 0 stick, 1 slip+, -1 slip-, 2 flight).
    """

    samples: Any
    frequency: float  #: excitation frequency f [Hz]
    sample_periods: int  #: excitation periods covered by the samples [-]
    label: str = ""
    status: str = "steady_state"
    metrics: Optional[Dict[str, Any]] = None  #: scalar metrics and harmonic arrays, if known
    parameters: Dict[str, Any] = field(default_factory=dict)  #: {dotted key: value}, if known
    multiplicity: int = 1  #: excitation periods after which the steady state repeats [-]

    @property
    def period(self) -> float:
        """Excitation period 1/f [s]."""
        return 1.0 / self.frequency

    @property
    def samples_per_period(self) -> int:
        """Samples per excitation period [-]."""
        return len(self.samples.t) // max(self.sample_periods, 1)

    @property
    def samples_per_orbit(self) -> int:
        """Samples of one steady period, multiplicity excitation periods (of all samples at
        most) [-]."""
        return min(len(self.samples.t), self.samples_per_period * max(self.multiplicity, 1))

    def tau(self) -> np.ndarray:
        """Time since the first sample in excitation periods, (t - t0) f [-]."""
        t = np.asarray(self.samples.t)
        return (t - t[0]) * self.frequency


def _metrics_dict(metrics: Any) -> Dict[str, Any]:
    out = dict(metrics.to_dict())
    out["ddx_amplitude"] = np.asarray(metrics.ddx_amplitude)
    out["ddz_amplitude"] = np.asarray(metrics.ddz_amplitude)
    out["ddx_phase"] = np.asarray(metrics.ddx_phase)
    out["ddz_phase"] = np.asarray(metrics.ddz_phase)
    return out


def from_result(result: Any, label: str = "", metrics: Any = None,
                parameters: Optional[Mapping[str, Any]] = None) -> SteadyState:
    """Wrap a :class:`oscidrum.Result` (or a ``CaseOutcome``; its metrics come along).

    The arrays are the Result's read-only NumPy views (no copy).
    """
    if hasattr(result, "result") and hasattr(result, "metrics"):  # a CaseOutcome
        if metrics is None and len(result.result.samples) > 0:
            metrics = result.metrics
        result = result.result
    if not (hasattr(result, "samples") and hasattr(result, "status")):
        # An AttributeError from inside the package ("'int' object has no attribute 'samples'").
        raise Error("a plot or a steady state takes a Result, a CaseOutcome, a SteadyState, a "
                    "steady-state CSV's path or a (result, case) pair; got "
                    f"{type(result).__name__}")
    if len(result.samples) == 0:
        # A study's case without keep_samples (these statuses sample their periods).
        if result.status.name in ("steady_state", "max_periods_reached", "aperiodic"):
            raise Error("the result holds no samples (run the study with keep_samples=True)")
        # A run that ended before anything was sampled (contact lost, gross slip, cancelled):
        # keep_samples would not help.
        raise Error(f"the result holds no samples: status {result.status.name} "
                    f"({result.message}); the run ended before a steady state or its last "
                    "periods were sampled, so there is nothing to plot")
    s = result.samples
    names = [name for name, _ in COLUMNS]
    ns = SimpleNamespace(**{name: getattr(s, name) for name in names})
    return SteadyState(samples=ns, frequency=result.frequency,
                       sample_periods=result.sample_periods, label=label,
                       status=result.status.name,
                       metrics=_metrics_dict(metrics) if metrics is not None else None,
                       parameters=dict(parameters or {}),
                       multiplicity=max(int(result.diagnostics.multiplicity), 1))


def as_steady_state(obj: Any, label: str = "") -> SteadyState:
    """A SteadyState from a SteadyState, Result, CaseOutcome or a path to a steady-state CSV."""
    if isinstance(obj, SteadyState):
        if label and not obj.label:
            obj.label = label
        return obj
    if isinstance(obj, (str, os.PathLike)):
        return read_case(obj, label=label)
    return from_result(obj, label=label)


def _infer_window(t: np.ndarray, torque: np.ndarray, signals: Sequence[np.ndarray]) -> Tuple[
        float, int]:
    """(f [Hz], periods) of a window that spans whole excitation periods.

    The samples are uniform over an integer number P of periods (end point not repeated), so the
    DFT of the excitation torque M0 sin(nu t) + MMd peaks exactly at bin P: f = P / (n dt).
    """
    n = len(t)
    if n < 4:
        raise Error("too few samples to infer the excitation frequency")
    dt = (t[-1] - t[0]) / (n - 1)
    for y in (torque, *signals):
        y = np.asarray(y, dtype=float) - np.mean(y)
        if np.max(np.abs(y)) == 0.0:
            continue
        spectrum = np.abs(np.fft.rfft(y))
        spectrum[0] = 0.0
        periods = int(np.argmax(spectrum))
        if periods > 0:
            return periods / (n * dt), periods
    raise Error("cannot infer the excitation frequency: the torque column is constant")


def _find(summary: Mapping[str, Any], *path: str) -> Any:
    node: Any = summary
    for key in path:
        if not isinstance(node, Mapping) or key not in node:
            return None
        node = node[key]
    return node


def _summary_metrics(summary: Mapping[str, Any]) -> Optional[Dict[str, Any]]:
    m = summary.get("metrics")
    if not isinstance(m, Mapping):
        return None
    out: Dict[str, Any] = {k: v for k, v in m.items() if not isinstance(v, (list, dict))}
    for signal in ("ddx", "ddz"):
        h = m.get(f"{signal}_harmonics")
        if isinstance(h, list) and h:
            if isinstance(h[0], Mapping):
                out[f"{signal}_amplitude"] = np.array([float(x["amplitude"]) for x in h])
                out[f"{signal}_phase"] = np.array([float(x["phase"]) for x in h])
            else:
                out[f"{signal}_amplitude"] = np.array([float(x) for x in h])
    return out


def read_csv_columns(path: str | os.PathLike) -> Tuple[Dict[str, np.ndarray], Dict[str, str]]:
    """Read a numeric ``name[unit]`` CSV into ({name: float array}, {name: unit}).

    Lines starting with '#' are skipped. Non-numeric cells become NaN.
    """
    table, units = read_table(path)
    numeric = {}
    for name, values in table.items():
        numeric[name] = np.array([_to_float(v) for v in values], dtype=float)
    return numeric, units


def read_case(csv_path: str | os.PathLike, json_path: str | os.PathLike | None = None,
              label: str = "") -> SteadyState:
    """Read a steady state written by ``oscidrum run --csv FILE [--json FILE]``.

    The JSON summary is optional: without it the excitation frequency and the number of periods
    are recovered exactly from the torque column (a whole number of periods is sampled).
    """
    columns, _ = read_csv_columns(csv_path)
    missing = [name for name, _ in COLUMNS if name not in columns and name not in _LATER_COLUMNS]
    if missing:
        raise Error(f"{csv_path}: missing steady-state columns {missing} "
                    "(see docs/csv-columns.md)")
    ns = SimpleNamespace(**{name: columns[name] for name, _ in COLUMNS if name in columns})
    ns.phase = np.rint(columns["phase"]).astype(np.int8)
    summary: Dict[str, Any] = {}
    if json_path is not None and os.path.exists(json_path):
        with open(json_path, encoding="utf-8") as fh:
            summary = json.load(fh)
    frequency = _find(summary, "sampling", "frequency")
    periods = _find(summary, "sampling", "sample_periods")
    if not frequency or not periods:
        frequency, periods = _infer_window(ns.t, ns.torque, (ns.ddx_M, ns.ddz_M))
    if "alpha" not in columns:  # a file of an oscidrum before the column: nu t, as run writes it
        ns.alpha = np.mod(2.0 * np.pi * float(frequency) * ns.t, 2.0 * np.pi)
    status = summary.get("status", "steady_state") if summary else "steady_state"
    multiplicity = _find(summary, "diagnostics", "multiplicity")
    if not multiplicity:  # no summary: the samples say after how many periods they repeat
        multiplicity = _repeats_after(ns.ddx_M, ns.ddz_M, int(periods))
    return SteadyState(samples=ns, frequency=float(frequency), sample_periods=int(periods),
                       label=label, status=str(status), metrics=_summary_metrics(summary),
                       parameters=dict(summary.get("parameters") or {}),
                       multiplicity=max(int(multiplicity or 1), 1))


def _repeats_after(x: np.ndarray, z: np.ndarray, periods: int) -> int:
    """The fewest excitation periods after which sampled accelerations repeat (to 1e-6 of their
    largest magnitude; a whole number of periods sampled), 1 when they never do within half the
    window: a steady state's multiplicity, for a CSV read without its summary (a period-2 orbit's
    figure eight was drawn over one period)."""
    n = len(x)
    if periods < 2 or n % periods:
        return 1
    per = n // periods
    for p in range(1, periods // 2 + 1):
        if periods % p:
            continue
        shift = p * per
        close = all(np.max(np.abs(a[shift:] - a[:-shift])) <= 1e-6 * max(np.max(np.abs(a)), 1e-300)
                    for a in (np.asarray(x, dtype=float), np.asarray(z, dtype=float)))
        if close:
            return p
    return 1


def format_double(value: float) -> str:
    """%.17g (round-trip exact, as the C++ writers); nan, inf, -inf for non-finite values."""
    if math.isnan(value):
        return "nan"
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    return "%.17g" % value


def write_case_csv(data: Any, path: str | os.PathLike) -> None:
    """Write a steady state (Result, CaseOutcome or SteadyState) in the docs/csv-columns.md
    format, byte-identical to ``oscidrum run --csv``."""
    state = as_steady_state(data)
    s = state.samples
    arrays = [np.asarray(getattr(s, name)) for name, _ in COLUMNS[:-1]]
    phase = np.asarray(s.phase).astype(int)
    lines = [HEADER + "\n"]
    for j in range(len(phase)):
        lines.append(",".join(format_double(float(a[j])) for a in arrays) + f",{phase[j]}\n")
    write_file(path, "".join(lines))


def write_table(path: str | os.PathLike, columns: Mapping[str, Sequence[Any]],
                units: Optional[Mapping[str, str]] = None) -> None:
    """Write {name: values} as a ``name[unit]`` CSV (numbers %.17g)."""
    units = units or {}
    names = list(columns)
    n = max((len(columns[c]) for c in names), default=0)
    fh = io.StringIO()
    writer = csv.writer(fh, lineterminator="\n")
    writer.writerow([f"{c}[{units.get(c, '-')}]" for c in names])
    for j in range(n):
        row = []
        for c in names:
            values = columns[c]
            v = values[j] if j < len(values) else ""
            if isinstance(v, (bool, np.bool_)):
                row.append("true" if v else "false")
            elif isinstance(v, (float, np.floating)):
                row.append(format_double(float(v)))
            else:
                row.append(str(v))
        writer.writerow(row)
    write_file(path, fh.getvalue())


def read_table(path: str | os.PathLike) -> Tuple[Dict[str, List[str]], Dict[str, str]]:
    """Read a ``name[unit]`` CSV (the CLI's sweep results, the paper's figure data) as text:
    ({name: [cell, ...]}, {name: unit}). Lines starting with '#' are skipped."""
    with open(path, encoding="utf-8", newline="") as fh:
        rows = [r for r in csv.reader(line for line in fh if not line.startswith("#"))]
    if not rows:
        raise Error(f"{path}: empty CSV")
    header = [split_header(c) for c in rows[0]]
    table: Dict[str, List[str]] = {name: [] for name, _ in header}
    for row in rows[1:]:
        if not row:
            continue
        for (name, _), cell in zip(header, row):
            table[name].append(cell)
        for name, _ in header[len(row):]:
            table[name].append("")
    return table, {name: unit for name, unit in header}


def _to_float(cell: str) -> float:
    cell = cell.strip()
    if cell in ("true", "false"):
        return 1.0 if cell == "true" else 0.0
    try:
        return float(cell)
    except ValueError:
        return math.nan


#: Other spellings of a key in sweep tables (the CLI writes soil.table2_G for Table 2 sweeps).
ALIASES: Dict[str, Tuple[str, ...]] = {
    "soil.G": ("soil.table2_G", "G"),
    "G": ("soil.G", "soil.table2_G"),
    "MMd_fraction": ("MMd/M0",),
}


def resolve_column(table: Mapping[str, Any], key: str) -> str:
    """The column of `table` that holds `key` (exact, unit stripped, or an alias)."""
    key = split_header(key)[0]
    if key in table:
        return key
    for alias in ALIASES.get(key, ()):
        if alias in table:
            return alias
    raise KeyError(f"no column '{key}'; columns: {', '.join(table)}")


def harmonic_amplitudes(y: Iterable[float], periods: int, n_max: int = 10) -> np.ndarray:
    """Amplitudes A_0 ... A_n_max of the harmonics of y sampled uniformly over exactly `periods`
    excitation periods (a DFT over whole periods, as oscidrum.harmonics; A_0 is |mean|)."""
    y = np.asarray(list(y) if not isinstance(y, np.ndarray) else y, dtype=float)
    spectrum = np.fft.rfft(y) / len(y)
    bins = np.arange(n_max + 1) * periods
    bins = bins[bins < len(spectrum)]
    amp = 2.0 * np.abs(spectrum[bins])
    amp[0] = abs(spectrum[0].real)
    return amp
