"""Shared fixtures of the Python tests.

Run from a CMake build tree (ctest sets PYTHONPATH=<build>/python and OSCIDRUM_CLI), or against
an installed package: ``/usr/bin/python3 -m pytest tests/python``.
"""

import contextlib
import glob
import os
import threading
from pathlib import Path

import pytest

import oscidrum

ROOT = Path(__file__).resolve().parents[2]


def find_cli():
    """The oscidrum CLI: $OSCIDRUM_CLI, else the newest build*/apps/cli/oscidrum."""
    path = os.environ.get("OSCIDRUM_CLI")
    if path and os.access(path, os.X_OK):
        return path
    found = [p for p in glob.glob(str(ROOT / "build*" / "apps" / "cli" / "oscidrum"))
             if os.access(p, os.X_OK)]
    return max(found, key=os.path.getmtime) if found else None


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def cli():
    path = find_cli()
    if path is None:
        pytest.skip("the oscidrum CLI is not built (set OSCIDRUM_CLI or build apps/cli)")
    return path


@pytest.fixture(scope="session")
def slip_case():
    """A stick-slip case of the paper (Table 2, G = 25 MN/m^2, mu = 0.5, MMd = 0.05 M0)."""
    case = oscidrum.Case(soil=oscidrum.table2_soil(25e6))
    case.MMd = 0.05 * case.roller.M0
    return case


@pytest.fixture(scope="session")
def slip_result(slip_case):
    return oscidrum.simulate(slip_case)


@pytest.fixture(scope="session")
def rolling_result():
    """Pure rolling at G = 5 MN/m^2, MMd = 0."""
    case = oscidrum.Case(soil=oscidrum.table2_soil(5e6))
    case.contact.pure_rolling = True
    return oscidrum.simulate(case)


@contextlib.contextmanager
def _ticking():
    """Run a Python thread beside the block that appends to the yielded list every millisecond:
    it only advances while the block's C++ code has released the GIL."""
    ticks = []
    done = threading.Event()

    def ticker():
        while not done.is_set():
            ticks.append(1)
            done.wait(0.001)

    thread = threading.Thread(target=ticker)
    thread.start()
    try:
        yield ticks
    finally:
        done.set()
        thread.join()


@pytest.fixture
def ticking():
    """The _ticking context manager, for tests that check the GIL is released."""
    return _ticking


@pytest.fixture(scope="session")
def paper_studies():
    """oscidrum.run_paper_studies() once (~3 s), with a progress callback and a Python thread
    ticking beside it: (results, [(done, total) per progress call], ticks)."""
    calls = []
    with _ticking() as ticks:
        results = oscidrum.run_paper_studies(progress=lambda d, t: calls.append((d, t)))
    return results, calls, ticks


@pytest.fixture(scope="session")
def paper_rows(paper_studies):
    """oscidrum.validate of paper_studies."""
    return oscidrum.validate(paper_studies[0])
