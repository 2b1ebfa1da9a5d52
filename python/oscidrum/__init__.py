"""oscidrum: the oscillation roller drum on soil of Paulmichl, Adam & Adam (2019).

The compiled core (``oscidrum._core``, pybind11) holds the model; this package re-exports it and
adds plots (:mod:`oscidrum.plot`), the paper's studies (:mod:`oscidrum.paper`) and readers and
writers of the CLI's files (:mod:`oscidrum.data`). All quantities are SI; see docs/python.md.

>>> import oscidrum
>>> case = oscidrum.Case(table2_G=5e6, MMd_fraction=0.05, pure_rolling=True)
>>> result = oscidrum.simulate(case)            # doctest: +SKIP
>>> result.samples.ddx_M                         # NumPy array [m/s^2]   # doctest: +SKIP
>>> oscidrum.compute_metrics(result).area        # [m^2/s^4]             # doctest: +SKIP
"""

import glob as _glob
import os as _os
import sys as _sys


def _find_core():
    """Import the compiled core. When the package is imported from the source tree
    (python/oscidrum, e.g. by the CLI's --plot with PYTHONPATH=<repo>/python), there is no
    _core next to it: then use the one of an installed copy on sys.path or of a CMake build tree
    (<repo>/build*/python/oscidrum), newest first. None if there is none."""
    try:
        from . import _core
        return _core, None
    except ImportError as exc:
        error = exc
    here = _os.path.realpath(_os.path.dirname(__file__))
    places = [_os.path.join(entry or ".", "oscidrum") for entry in _sys.path]
    repo = _os.path.dirname(_os.path.dirname(here))
    places += sorted(_glob.glob(_os.path.join(repo, "build*", "python", "oscidrum")),
                     key=_os.path.getmtime, reverse=True)
    for place in places:
        if _os.path.realpath(place) == here or not _glob.glob(_os.path.join(place, "_core*")):
            continue
        __path__.append(place)
        try:
            from . import _core
            return _core, None
        except ImportError:
            __path__.remove(place)
    return None, error


_core, _core_error = _find_core()

#: The compiled API, re-exported (see docs/python.md).
_CORE_NAMES = (
    "Accelerations",
    "Case",
    "CaseOutcome",
    "Contact",
    "ContactForces",
    "Diagnostics",
    "DrumMotion",
    "Error",
    "Event",
    "EventKind",
    "Field",
    "Harmonic",
    "Kinematics",
    "Metrics",
    "MotionAnalysis",
    "Model",
    "Numerics",
    "PaperSeries",
    "Phase",
    "RecordMetrics",
    "Result",
    "Roller",
    "Samples",
    "SeriesResult",
    "Soil",
    "SoilCoefficients",
    "SoilInput",
    "State",
    "Status",
    "Table2Row",
    "Transmissibility",
    "Trough",
    "TroughGeometry",
    "ValidationRow",
    "__version__",
    "absent_signals",
    "accelerations",
    "case_to_toml",
    "analyze_motion",
    "analyze_record",
    "analyze_windows",
    "bifurcation_diagram",
    "calibrate_records",
    "compute_metrics",
    "continue_branch",
    "contact_forces",
    "drum_motion",
    "enclosed_area",
    "estimate_frequency",
    "fields",
    "find_field",
    "gravity_points_up",
    "harmonics",
    "identify_record",
    "key_in_effect",
    "kinematics",
    "load_case",
    "make_trough_geometry",
    "paper_case",
    "paper_series",
    "phi_rolling",
    "read_record",
    "record_kb",
    "run_case",
    "run_paper_studies",
    "simulate",
    "slip_constraint_residual",
    "slip_velocity",
    "soil_coefficients",
    "soil_on_scale",
    "synthetic_record",
    "table2",
    "table2_soil",
    "transmissibility",
    "validate",
    "validation_markdown",
    "vibration_modulus",
    "wrap_pi",
)

def _explain(exc):
    """pybind11's "f(): incompatible function arguments. The following argument types are
    supported: 1. (x: float) -> ... Invoked with: 'a'" as one line naming the rule."""
    import re

    text = str(exc)
    head = text.split(":", 1)[0]
    # The numbered signatures lie between "supported:" and "Invoked with:" (the arguments'
    # printout after it may hold lines of numbers: a numpy array's).
    body = text.split("Invoked with:", 1)[0].split("supported:", 1)[-1]
    sigs = [s.strip().replace("oscidrum._core.", "")
            for s in re.findall(r"^\s*\d+\.\s+(.*)$", body, flags=re.M)]
    got = text.rsplit("Invoked with:", 1)[-1].strip() if "Invoked with:" in text else "?"
    got = re.sub(r"array\(\[.*?\]\)", "array(...)", got, flags=re.S)
    got = " ".join(got.split())
    if len(got) > 300:
        got = got[:300] + " ..."
    return f"{head}: arguments must be {' or '.join(sigs) or 'of other types'}; got {got}"


def _friendly(func):
    """Turn pybind11's TypeError for arguments of the wrong type into oscidrum.Error (only when
    raised by the compiled function itself, not by a Python callback it called)."""
    import functools

    @functools.wraps(func)
    def call(*args, **kwargs):
        try:
            return func(*args, **kwargs)
        except TypeError as exc:
            tb = exc.__traceback__
            if tb is not None and tb.tb_next is None and "incompatible" in str(exc):
                raise _core.Error(_explain(exc)) from None
            raise
    return call


def _friendly_class(cls):
    for name, attr in list(vars(cls).items()):
        if name.startswith("__") and name not in ("__init__", "__setstate__", "__call__"):
            continue
        if type(attr).__name__ == "instancemethod":
            setattr(cls, name, _friendly(attr.__func__))
        elif isinstance(attr, staticmethod):
            setattr(cls, name, staticmethod(_friendly(attr.__func__)))
        elif type(attr) is property and attr.fset is not None:
            setattr(cls, name, property(attr.fget, _friendly(attr.fset), attr.fdel, attr.__doc__))


def _result_to_dataframe(self):
    """The steady-state samples as a pandas DataFrame.

    Returns
    -------
    pandas.DataFrame
        One column per sample attribute (t [s], delta [rad], ..., ddx_M [m/s^2], ..., phase
        [-]: 0 stick, 1 slip+, -1 slip-, 2 flight), in the column order of the CLI's CSV;
        ``df.attrs['units']`` maps the columns to units.

    Examples
    --------
    >>> df = oscidrum.simulate(oscidrum.Case()).to_dataframe()    # doctest: +SKIP
    >>> df.plot(x="ddx_M", y="ddz_M")                            # doctest: +SKIP
    """
    import pandas as pd

    s = self.samples
    df = pd.DataFrame(s.to_dict(), columns=list(s.columns))
    units = {}
    for name, header in zip(s.columns, s.headers):
        units[name] = header[header.index("[") + 1:-1] if "[" in header else "-"
    df.attrs["units"] = units
    return df


if _core is not None:
    for _name in _CORE_NAMES:
        _obj = getattr(_core, _name)
        if isinstance(_obj, type) and not issubclass(_obj, BaseException):
            _friendly_class(_obj)
            globals()[_name] = _obj
        elif callable(_obj) and not isinstance(_obj, type):
            globals()[_name] = _friendly(_obj)
        else:
            globals()[_name] = _obj
    _core.Result.to_dataframe = _result_to_dataframe
    from .study import Interrupted, StudyResult, run_study  # noqa: E402


def __getattr__(name):
    # Only reached without a compiled core: every compiled name explains what is missing (as
    # importing oscidrum.data or oscidrum.plot does).
    if name in _CORE_NAMES or name in ("run_study", "StudyResult", "Interrupted"):
        raise ImportError(f"oscidrum.{name} needs the compiled module oscidrum._core, which "
                          f"could not be imported ({_core_error}); build it (cmake "
                          "-DOSCIDRUM_BUILD_PYTHON=ON) or install the package (pip install "
                          "--no-build-isolation .), see docs/python.md")
    raise AttributeError(f"module 'oscidrum' has no attribute '{name}'")


__all__ = [name for name in _CORE_NAMES if name != "__version__"] + [
    "run_study", "StudyResult", "Interrupted"]
