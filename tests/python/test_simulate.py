"""simulate, metrics and studies through the bindings."""

import math
import re
import threading

import numpy as np
import pytest

import oscidrum
from oscidrum.data import COLUMNS


def test_result_arrays(slip_result):
    r = slip_result
    assert r.ok and r.status == oscidrum.Status.steady_state and r.status.name == "steady_state"
    assert r.frequency == 39.0 and r.period == pytest.approx(1 / 39.0)
    n = r.sample_periods * r.samples_per_period
    assert len(r.samples) == n > 0
    for name, _ in COLUMNS:
        a = getattr(r.samples, name)
        assert isinstance(a, np.ndarray) and a.shape == (n,)
    assert r.samples.ddx_M.dtype == np.float64 and not r.samples.ddx_M.flags.writeable
    assert r.samples.phase.dtype == np.int8
    assert set(np.unique(r.samples.phase)) <= {-1, 0, 1}  # no flight: permanent contact
    assert (r.samples.phase != 0).any()  # stick-slip
    dt = np.diff(r.samples.t)
    assert np.allclose(dt, 1 / (r.frequency * r.samples_per_period), rtol=1e-9)
    assert r.samples.columns == [name for name, _ in COLUMNS]
    assert r.samples.headers[0] == "t[s]" and r.samples.headers[-1] == "phase[-]"


def test_views_keep_the_result_alive():
    case = oscidrum.Case(soil=oscidrum.table2_soil(25e6))
    ddx = oscidrum.simulate(case).samples.ddx_M  # the Result is a temporary
    import gc

    gc.collect()
    assert np.isfinite(ddx).all() and np.abs(ddx).max() > 1.0


def test_events_and_diagnostics(slip_result):
    r = slip_result
    assert r.events and all(isinstance(e, oscidrum.Event) for e in r.events)
    kinds = {e.kind for e in r.events}
    assert oscidrum.EventKind.stick_to_slip in kinds
    times = [e.t for e in r.events]
    assert times == sorted(times)
    d = r.diagnostics
    assert d.periods_to_steady > 0 and d.multiplicity >= 1 and d.steps > 0
    assert d.to_dict()["steps"] == d.steps
    assert r.stick_time + r.slip_positive_time + r.slip_negative_time == pytest.approx(
        r.sample_periods / r.frequency, rel=1e-6)


def test_metrics(slip_result, rolling_result):
    m = oscidrum.compute_metrics(slip_result, n_max=10)
    assert m.ddx_amplitude.shape == (11,) and m.ddz_phase.shape == (11,)
    assert m.ddx_amplitude[1] == pytest.approx(m.ddx_harmonics[1].amplitude)
    assert m.ddx_max == pytest.approx(slip_result.samples.ddx_M.max())
    assert m.area > 0 and set(m.to_dict()) == set(oscidrum.Metrics.scalar_names)
    assert m.stick_fraction + m.slip_positive_fraction + m.slip_negative_fraction == \
        pytest.approx(1.0)
    # pure rolling at G = 5 (docs/validation.md, fig12.psi_G5: psi about 0.104 rad)
    mr = oscidrum.compute_metrics(rolling_result)
    assert mr.psi_xz == pytest.approx(0.104, abs=0.01)
    # the signal-level functions agree with the metrics
    s = rolling_result.samples
    amp, phase = oscidrum.harmonics(s.ddx_M, rolling_result.sample_periods,
                                    rolling_result.frequency, s.t[0], 10)
    assert np.allclose(amp, mr.ddx_amplitude) and np.allclose(phase, mr.ddx_phase)
    # a gap in the signal is named, not spread over every amplitude as NaN
    gap = np.array(s.ddx_M, dtype=float)
    gap[7] = np.nan
    with pytest.raises(oscidrum.Error, match=r"y\[7\] = nan: every sample must be finite"):
        oscidrum.harmonics(gap, rolling_result.sample_periods, rolling_result.frequency, s.t[0])
    n = rolling_result.samples_per_period  # the area of one steady period
    assert oscidrum.enclosed_area(s.ddx_M[:n], s.ddz_M[:n]) == pytest.approx(mr.area, rel=1e-6)


def test_progress_callback_and_cancel():
    # the transient method reports every period (shooting: a few periods and Newton steps)
    case = oscidrum.Case(soil=oscidrum.table2_soil(25e6), **{"numerics.method": "transient"})
    seen = []
    oscidrum.simulate(case, progress=lambda period, change: seen.append((period, change)))
    assert len(seen) > 10 and all(isinstance(p, int) for p, _ in seen)
    r = oscidrum.simulate(case, progress=lambda period, change: period < 5)
    assert r.status == oscidrum.Status.cancelled
    # By shooting each call counts on: the first Newton step repeated the transient's last
    # period (1, 2, 3, 3, 4, ...).
    for c in (oscidrum.Case(), oscidrum.Case(pure_rolling=True)):
        periods = []
        oscidrum.simulate(c, progress=lambda period, change: periods.append(period))
        assert periods == list(range(1, len(periods) + 1)), periods


def test_exception_in_progress_propagates():
    def boom(period, change):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        oscidrum.simulate(oscidrum.Case(), progress=boom)


def test_progress_that_is_not_callable_is_refused_before_integrating():
    # Python's own "'int' object is not callable" came from inside the first period
    for bad, shown in ((5, "got int (5)"), ("yes", "got str ('yes')")):
        with pytest.raises(oscidrum.Error, match=re.escape(
                "progress must be None or a callable progress(period: int, change: float); "
                + shown)):
            oscidrum.simulate(oscidrum.Case(), bad)


def test_simulate_releases_the_gil(ticking):
    """Another Python thread runs while simulate integrates."""
    # the transient method: long enough (~300 periods per case) for the other thread to tick
    case = oscidrum.Case(soil=oscidrum.table2_soil(70e6),
                         **{"contact.pure_rolling": True, "numerics.method": "transient"})
    with ticking() as ticks:
        for _ in range(3):
            oscidrum.simulate(case)
    assert len(ticks) > 3


def _cases():
    cases = []
    for G in (5e6, 25e6, 45e6, 70e6):
        for pure in (True, False):
            c = oscidrum.Case(soil=oscidrum.table2_soil(G), MMd=0.05 * 54947.0)
            c.contact.pure_rolling = pure
            c.numerics.continuation = False  # independent cases: each equals simulate(c)
            cases.append(c)
    return cases


def test_parallel_study_equals_serial():
    cases = _cases()
    parallel = oscidrum.run_study(cases, threads=4, keep_samples=True)
    serial = oscidrum.run_study(cases, threads=1, keep_samples=True)
    one_by_one = [oscidrum.simulate(c) for c in cases]
    assert len(parallel) == len(serial) == len(cases)
    for p, s, r, case in zip(parallel, serial, one_by_one, cases):
        assert p.ok and s.ok
        for name, _ in COLUMNS:
            a, b, c = (getattr(x.samples, name) for x in (p.result, s.result, r))
            assert np.array_equal(a, b) and np.array_equal(a, c), name
        # assert_equal: NaN (an undefined ratio) equals NaN
        np.testing.assert_equal(p.metrics.to_dict(), s.metrics.to_dict())
        np.testing.assert_equal(p.metrics.to_dict(),
                                oscidrum.compute_metrics(r, case=case).to_dict())


def test_study_options_and_invalid_cases():
    cases = [oscidrum.Case(), {"soil.ksh": 11.4e6, "contact.pure_rolling": True},
             oscidrum.Case(trough={"a": 0.5})]
    progress, done = [], []
    out = oscidrum.run_study(cases, threads=2, progress=lambda d, t: progress.append((d, t)),
                             on_case_done=lambda i, o: done.append(i))
    assert [o.valid for o in out] == [True, True, False]
    assert "trough.a must be > roller.r" in out[2].error and not out[2].ok
    assert len(out[0].result.samples) == 0  # keep_samples=False
    assert out[0].metrics.area > 0  # metrics are computed anyway
    assert sorted(progress) == [(1, 3), (2, 3), (3, 3)]
    assert sorted(done) == [0, 1, 2]
    single = oscidrum.run_case(oscidrum.Case())
    assert single.ok and len(single.result.samples) > 0
    np.testing.assert_equal(single.metrics.to_dict(), out[0].metrics.to_dict())


def test_a_studys_table_describes_the_cases_as_they_ran():
    # The caller changes its Case objects for the next study: the first study's table keeps the
    # parameters its cases ran with (it showed the new G beside the old areas).
    cases = [oscidrum.Case(mu=m) for m in (0.3, 0.5)]
    res = oscidrum.run_study(cases, threads=1, progress=False)
    for c in cases:
        c.set("soil.G", 50e6)
    table = res.to_dataframe("all")
    assert list(table["soil.G"]) == [25e6, 25e6]
    assert [c.get("soil.G") for c in res.cases] == [25e6, 25e6]


def test_study_options_take_numpy_integers_and_errors_keep_their_key():
    out = oscidrum.run_study([oscidrum.Case()], threads=np.int64(1), n_harmonics=np.int64(10),
                             progress=False)
    assert out[0].ok
    with pytest.raises(oscidrum.Error, match="threads must be an integer"):
        oscidrum.run_study([oscidrum.Case()], threads=True, progress=False)
    # A dict case's error names its parameter, as Case's own does (docs/python.md, "Errors").
    with pytest.raises(oscidrum.Error) as e:
        oscidrum.run_study([{"soil.G": -5e6}], threads=1, progress=False)
    assert str(e.value).startswith("cases[0]: soil.G must be in")
    assert e.value.key == "soil.G" and e.value.value == -5e6


def test_exception_in_study_callback_propagates():
    def boom(done, total):
        raise KeyError("from the callback")

    with pytest.raises(KeyError, match="from the callback"):
        oscidrum.run_study([oscidrum.Case()] * 3, threads=2, progress=boom)


def test_ctrl_c_interrupts_a_study():
    import os
    import signal
    import time

    # the transient method: long enough (~300 periods per case) for the other thread to tick
    case = oscidrum.Case(soil=oscidrum.table2_soil(70e6),
                         **{"contact.pure_rolling": True, "numerics.method": "transient"})
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        oscidrum.run_study([case] * 400, threads=1)
    timer.join()
    assert time.perf_counter() - start < 5.0


def test_attributes_follow_the_output_table(slip_result, cli):
    """Every output of `oscidrum outputs` is an attribute with its documented name (the bindings
    are generated from the same table), and the pure-Python CSV contract agrees with it."""
    import json
    import subprocess

    table = json.loads(subprocess.run([cli, "outputs", "--format", "json"], capture_output=True,
                                      text=True, check=True).stdout)
    r = slip_result
    assert [s["name"] for s in table["statuses"]] == list(oscidrum.Status.__members__)
    assert [c["name"] for c in table["samples"]] == r.samples.columns
    assert [f"{c['name']}[{c['unit']}]" for c in table["samples"]] == r.samples.headers
    assert r.samples.headers == [f"{name}[{unit}]" for name, unit in COLUMNS]
    d = r.diagnostics
    # The table's diagnostics, the steady-state method's included (the method by its name).
    names = [x["name"] for x in table["diagnostics"]]
    assert list(d.to_dict()) == names
    assert names[-12:] == ["method", "newton_iterations", "jacobian_evaluations",
                           "period_equivalents", "phi_drift", "fallback", "contact_mode",
                           "operating_mode", "start_ramp_periods", "warm_start", "motion", "lyapunov_exponent"]
    assert d.motion == "" and d.lyapunov_exponent == 0.0  # a steady state: nothing to examine
    assert d.contact_mode == "permanent contact"  # a steady state of the paper's drum
    assert d.start_ramp_periods == 0  # the paper's start: all at once
    assert d.warm_start == 0  # a single run starts from rest
    assert d.method in ("transient", "shooting") and isinstance(d.fallback, str)
    assert d.inconsistent_slip_ends == 0  # was missing from Python before the table
    m = oscidrum.compute_metrics(r)
    for x in table["metrics"]:
        assert hasattr(m, x["name"]), x["name"]
    assert list(m.to_dict()) == [x["name"] for x in table["metrics"] if x["type"] != "array"]
    assert oscidrum.Metrics.units["friction_work"] == "J"
    t = r.samples.t
    rec = oscidrum.analyze_record(t, r.samples.ddx_M, r.samples.ddz_M, r.frequency)
    for x in table["record_metrics"]:
        assert hasattr(rec, x["name"]), x["name"]


def test_compaction_indicators(slip_result, rolling_result):
    m = oscidrum.compute_metrics(slip_result)
    a = m.ddx_amplitude
    assert m.ddx_A3_A1 == pytest.approx(a[3] / a[1], rel=1e-12)
    assert m.ddx_thd > m.ddx_A3_A1  # the THD holds A_3 and more
    assert m.slip_fraction == pytest.approx(1 - m.stick_fraction, rel=1e-12)
    assert m.friction_work > 0
    mr = oscidrum.compute_metrics(rolling_result)
    assert mr.friction_work < 1e-9 * m.friction_work and mr.slip_fraction == 0  # stick only
    assert mr.mu_required > 0  # pure rolling: the friction rolling needs, |T|/N somewhere


def test_study_with_shooting_continues_from_the_neighbour():
    """Continuation (docs/periodic.md): with shooting, consecutive cases along G form a chain; every
    case after the first starts from its neighbour's steady state, whatever the thread count."""
    cases = []
    for G in (5e6, 10e6, 15e6, 20e6):
        c = oscidrum.Case(soil=oscidrum.table2_soil(G), **{"contact.pure_rolling": True})
        c.numerics.method = "shooting"
        c.numerics.samples_per_period = 256
        cases.append(c)
    one = oscidrum.run_study(cases, threads=1, progress=False)
    two = oscidrum.run_study(cases, threads=2, progress=False)
    assert [o.result.diagnostics.warm_start for o in one] == [0, 1, 1, 1]
    for a, b in zip(one, two):
        assert a.ok and b.ok
        assert a.metrics.area == b.metrics.area
    for c in cases:
        c.numerics.continuation = False
    cold = oscidrum.run_study(cases, threads=2, progress=False)
    assert [o.result.diagnostics.warm_start for o in cold] == [0, 0, 0, 0]


def test_vibratory_drum():
    # The vibratory drum (docs/model.md section 14) from Python: the example's roller lifts off
    # every period (partial uplift) and has a Kb-type stiffness below Table 2's ksv = 66.3 MN/m.
    c = oscidrum.Case(type="vibratory", static_moment=0.9, f=30.0, unilateral=True)
    r = oscidrum.simulate(c)
    assert r.status == oscidrum.Status.steady_state
    assert r.diagnostics.operating_mode == "partial uplift"
    kb = oscidrum.compute_metrics(r).kb
    assert 30e6 < kb < 66.3e6
    with pytest.raises(oscidrum.Error, match="roller.static_moment must be > 0"):
        oscidrum.simulate(oscidrum.Case(type="vibratory"))


def test_a_run_without_a_sampled_window_has_no_phase_times():
    # A spinning drum (gross slip) ends before its sampling: its phase times are unknown (NaN),
    # not 0 (which read as a drum that never slipped), and the JSON has null.
    r = oscidrum.simulate(oscidrum.Case(MMd_fraction=1.0))
    assert r.status == oscidrum.Status.gross_slip
    assert len(r.samples.t) == 0
    for value in (r.stick_time, r.slip_positive_time, r.slip_negative_time, r.flight_time):
        assert math.isnan(value)


def test_integer_arguments_refuse_a_bool(rolling_result):
    """pybind11 took True for an int: harmonics(y, True, f) ran over one cycle, a seed of True was
    seed 1, without a word. Every integer argument of the bindings now refuses a bool (NumPy's
    integers still pass)."""
    s = rolling_result.samples
    periods, f = rolling_result.sample_periods, rolling_result.frequency
    calls = [
        lambda b: oscidrum.harmonics(s.ddx_M, b, f),
        lambda b: oscidrum.harmonics(s.ddx_M, periods, f, 0.0, b),
        lambda b: oscidrum.compute_metrics(rolling_result, b),
        lambda b: oscidrum.synthetic_record([oscidrum.Case()], duration=0.1, seed=b),
        lambda b: oscidrum.analyze_record(s.t, s.ddx_M, s.ddz_M, f, b),
    ]
    for call in calls:
        for b in (True, False):
            with pytest.raises(oscidrum.Error, match="arguments must be"):
                call(b)
    amp, _ = oscidrum.harmonics(s.ddx_M, np.int64(periods), f, s.t[0], np.int32(3))
    assert len(amp) == 4
