"""oscidrum: the oscillation roller drum on soil of Paulmichl, Adam & Adam (2019).

The compiled core (``oscidrum._core``, pybind11) holds the model; this package re-exports it and
adds plots (:mod:`oscidrum.plot`), the paper's studies (:mod:`oscidrum.paper`) and readers and
writers of the CLI's files (:mod:`oscidrum.data`). All quantities are SI; see docs/python.md.

>>> import oscidrum
>>> case = oscidrum.Case(soil=oscidrum.table2_soil(5e6), MMd=0.05 * 54947)
>>> case.set("contact.pure_rolling", True)
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
    "accelerations",
    "analyze_record",
    "analyze_windows",
    "compute_metrics",
    "contact_forces",
    "drum_motion",
    "enclosed_area",
    "estimate_frequency",
    "fields",
    "find_field",
    "harmonics",
    "identify_record",
    "kinematics",
    "make_trough_geometry",
    "paper_case",
    "paper_series",
    "phi_rolling",
    "run_case",
    "run_paper_studies",
    "run_study",
    "simulate",
    "slip_constraint_residual",
    "slip_velocity",
    "soil_coefficients",
    "synthetic_record",
    "table2",
    "table2_soil",
    "transmissibility",
    "validate",
    "validation_markdown",
    "wrap_pi",
)

if _core is not None:
    globals().update({name: getattr(_core, name) for name in _CORE_NAMES})


def __getattr__(name):
    # Only reached without a compiled core: oscidrum.data and oscidrum.plot still work on CSV
    # files, everything else explains what is missing.
    if name in _CORE_NAMES:
        raise ImportError(f"oscidrum.{name} needs the compiled module oscidrum._core, which "
                          f"could not be imported ({_core_error}); build it (cmake "
                          "-DOSCIDRUM_BUILD_PYTHON=ON) or install the package (pip install "
                          "--no-build-isolation .), see docs/python.md")
    raise AttributeError(f"module 'oscidrum' has no attribute '{name}'")


__all__ = [name for name in _CORE_NAMES if name != "__version__"]
