"""A seeded fuzz suite for the Python API: bad and extreme values in every field of Case and in
the size-like arguments of the analysis and identification functions are refused with
oscidrum.Error (a ValueError) or TypeError, never a crash, a hang or gigabytes of memory.

Fast by default; OSCIDRUM_FUZZ_SEED and OSCIDRUM_FUZZ_SCALE (scripts/fuzz.sh) make it longer.
Every failure names the seed and the call."""
import math
import os
import random
import resource

import numpy as np
import pytest

import oscidrum

SEED = int(os.environ.get("OSCIDRUM_FUZZ_SEED") or 20261126)
SCALE = float(os.environ.get("OSCIDRUM_FUZZ_SCALE") or 1)


def draws(base):
    return max(1, round(base * SCALE))


BAD = [float("nan"), float("inf"), -float("inf"), "abc", "", None, [1.0], {"a": 1}, b"1", 1e308,
       -1e308, 1e-320, -1.0, 0.0, 10**30, -(10**30), True]


@pytest.fixture(scope="module")
def record():
    out = oscidrum.run_case(oscidrum.Case(output_periods=24), keep_samples=True)
    s = out.result.samples
    return np.asarray(s.t), np.asarray(s.ddx_M), np.asarray(s.ddz_M)


def test_every_case_field_refuses_what_it_cannot_take():
    rng = random.Random(SEED)
    keys = oscidrum.Case.keys()
    for _ in range(draws(150)):
        key = rng.choice(keys)
        value = rng.choice(BAD)
        call = f"seed {SEED}: Case().set({key!r}, {value!r}); validate()"
        case = oscidrum.Case()
        try:
            case.set(key, value)
            case.validate()
        except (ValueError, TypeError) as e:
            assert str(e), call  # a message, naming what was wrong
            continue
        # Accepted: then the value is a legitimate one of the key's.
        got = case.get(key)
        if isinstance(got, float):
            assert math.isfinite(got), call


def test_size_like_arguments_are_bounded(record):
    t, ax, az = record
    rng = random.Random(SEED + 1)
    values = [1e-12, 1e-9, 0.0, -1.0, float("nan"), float("inf"), 1e9, 1e308]
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    for _ in range(draws(30)):
        name = rng.choice(["window", "hop", "f", "max_gap", "max_residual", "max_drift",
                           "clip_level"])
        value = rng.choice(values)
        call = f"seed {SEED + 1}: analyze_windows(..., {name}={value!r})"
        try:
            rows = oscidrum.analyze_windows(t, ax, az, **{name: value})
        except (ValueError, TypeError) as e:
            assert str(e), call
            continue
        assert len(rows) < 10**5, call
    for _ in range(draws(12)):
        name = rng.choice(["window", "hop", "f", "compare", "n_max"])
        value = rng.choice(values + [10**6, 10**12])
        if name in ("compare", "n_max") and isinstance(value, float) and math.isfinite(value):
            value = int(value)
        call = f"seed {SEED + 1}: identify_record(..., {name}={value!r})"
        try:
            oscidrum.identify_record(oscidrum.Case(), t, ax, az, **{name: value})
        except (ValueError, TypeError) as e:
            assert str(e), call
    # The cases: compare=0 or 10**6 are refused before any window, not failed per window.
    for compare in [0, -1, 10**6]:
        with pytest.raises(ValueError):
            oscidrum.identify_record(oscidrum.Case(), t, ax, az, compare=compare)
    for n in [0, -1, 10**7, 2**40]:
        with pytest.raises((ValueError, TypeError, OverflowError)):
            oscidrum.run_study([oscidrum.Case()], n_harmonics=n)
    # ru_maxrss is in KiB: the calls above may not have grown the process by a gigabyte.
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
    assert grown < 1024 * 1024, f"seed {SEED + 1}: memory grew by {grown} KiB"


def test_double_naming_is_refused():
    rng = random.Random(SEED + 2)
    aliases = oscidrum.Case.aliases()
    pairs = [(short, dotted) for short, dotted in aliases.items() if short != dotted]
    for _ in range(draws(10)):
        short, dotted = rng.choice(pairs)
        with pytest.raises(ValueError):
            oscidrum.Case(**{short: 0.5, dotted: 0.7})
