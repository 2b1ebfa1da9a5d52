"""Studies from Python: DataFrames, xarray/netCDF, progress, Ctrl-C, and executors (a local
pool, Dask distributed, mpi4py.futures) giving results identical to a local run, in order."""

import math
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import oscidrum

G_VALUES = (5e6, 15e6, 25e6, 40e6)
MU_VALUES = (0.3, 0.5, 0.7)


def grid():
    # Independent cases (no continuation): an executor's chunks then give the local bits.
    return [oscidrum.Case(table2_G=G, mu=mu, continuation=False) for G in G_VALUES
            for mu in MU_VALUES]


@pytest.fixture(scope="module")
def local():
    return oscidrum.run_study(grid(), threads=2)


# Counters of the run's length: a case that keeps no samples integrates its steady period alone,
# one that samples integrates output_periods of them (the same orbit, the same metrics).
RUN_LENGTH = {"periods_simulated", "steps", "rejected_steps", "rhs_evaluations", "events",
              "switches", "period_equivalents"}


def same(a, b, sampled_differently=False):
    """Outcomes equal bit for bit (status, diagnostics, every scalar metric); with
    sampled_differently, the diagnostics but the run-length counters."""
    assert len(a) == len(b)
    for x, y in zip(a, b):
        assert (x.valid, x.error, x.result.status, x.result.message) == \
            (y.valid, y.error, y.result.status, y.result.message)
        assert same_values(x.metrics.to_dict(), y.metrics.to_dict())
        dx, dy = x.result.diagnostics.to_dict(), y.result.diagnostics.to_dict()
        if sampled_differently:
            dx = {k: v for k, v in dx.items() if k not in RUN_LENGTH}
            dy = {k: v for k, v in dy.items() if k not in RUN_LENGTH}
        assert same_values(dx, dy)


def same_values(a, b):
    """Dicts equal bit for bit, NaN equal to NaN (a ratio over a harmonic that vanishes by
    symmetry is NaN in both)."""
    def key(v):
        return "nan" if isinstance(v, float) and v != v else v
    return a.keys() == b.keys() and all(key(a[k]) == key(b[k]) for k in a)


def test_dataframe(local):
    df = local.to_dataframe()
    assert {"soil.G", "contact.mu"} <= set(df.columns) and "roller.m" not in df.columns
    assert len(df) == len(G_VALUES) * len(MU_VALUES) and df["ok"].all()
    assert df["area"].tolist() == [o.metrics.area for o in local]
    assert df.attrs["units"]["area"] == "m^2/s^4" and df.attrs["units"]["soil.G"] == "Pa"
    assert set(oscidrum.Case.keys()) <= set(local.to_dataframe("all").columns)


def test_xarray_and_netcdf(local, tmp_path):
    import xarray as xr
    ds = local.to_xarray()
    assert ds["area"].dims == ("soil.G", "contact.mu")
    assert ds["area"].attrs["units"] == "m^2/s^4"
    for o, case in zip(local, local.cases):
        assert ds["area"].sel({"soil.G": case.soil.G, "contact.mu": case.contact.mu}).item() == \
            o.metrics.area
    path = local.to_netcdf(tmp_path / "study.nc")
    back = xr.open_dataset(path)
    np.testing.assert_array_equal(back["area"].values, ds["area"].values)
    assert back["ok"].values.all() and back["area"].attrs["units"] == "m^2/s^4"
    back.close()
    with pytest.raises(oscidrum.Error, match="do not form a grid"):
        oscidrum.StudyResult(local.cases * 2, list(local) * 2).to_xarray()


def test_xarray_of_one_case_and_of_keys_varied_together(tmp_path):
    # One case raised AttributeError from inside the package (a Series' to_xarray is a
    # DataArray); mu varied together with G case by case was dropped without a word.
    one = oscidrum.run_study([oscidrum.Case()], progress=False)
    ds = one.to_xarray()
    assert ds["area"].item() == one[0].metrics.area and ds["status"].item() == "steady_state"
    one.to_netcdf(tmp_path / "one.nc")
    cases = [oscidrum.Case(table2_G=G, mu=mu) for G, mu in ((5e6, 0.3), (25e6, 0.5), (70e6, 0.7))]
    res = oscidrum.run_study(cases, progress=False)
    ds = res.to_xarray()
    assert ds["area"].dims == ("soil.G",)
    assert list(ds["contact.mu"].values) == [0.3, 0.5, 0.7]
    assert ds["contact.mu"].dims == ("soil.G",)
    res.to_netcdf(tmp_path / "two.nc")


def test_progress_bar_only_on_a_terminal(capsys):
    cases = [oscidrum.Case(pure_rolling=True)] * 3
    oscidrum.run_study(cases)  # stderr is not a terminal here: no bar
    assert "case" not in capsys.readouterr().err
    oscidrum.run_study(cases, progress=True)
    assert "3/3" in capsys.readouterr().err
    seen = []
    oscidrum.run_study(cases, progress=lambda d, t: seen.append((d, t)))
    assert seen[-1] == (3, 3)


@pytest.mark.parametrize("threads", [1, 2])
def test_ctrl_c_keeps_what_is_done(threads):
    # Pure rolling from rest by the transient method: ~60 ms a case, so that 400 of them are still
    # running when Ctrl-C arrives (by shooting they take ~2 ms and the study would be done). On
    # two threads no case runs on the main thread, the only one Python handles signals in: the
    # Ctrl-C waited for the whole study (about 12 s) before the main thread watched for it.
    slow = oscidrum.Case(table2_G=70e6, pure_rolling=True, method="transient")
    fast = [oscidrum.Case()] * 4
    timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(oscidrum.Interrupted) as info:
        oscidrum.run_study(fast + [slow] * 400, threads=threads)
    timer.join()
    assert time.perf_counter() - start < 5.0
    res = info.value.result
    assert isinstance(info.value, KeyboardInterrupt) and len(res) == 404
    assert all(o.ok for o in res[:4])  # done before Ctrl-C, kept
    assert res[-1].valid is False and res[-1].error == "cancelled"
    # Never run: no steady state (its result said steady_state with ok True before).
    assert res[-1].result.status == oscidrum.Status.cancelled and not res[-1].result.ok
    assert math.isnan(res[-1].result.diagnostics.final_change)



def test_thread_pool_executor_equals_local(local):
    from concurrent.futures import ThreadPoolExecutor
    with ThreadPoolExecutor(2) as pool:
        res = oscidrum.run_study(grid(), executor=pool, chunk_size=5, threads=1)
    same(res, local)
    assert res.cases == local.cases


def test_an_exception_of_the_callback_cancels_the_chunks_not_started():
    """An exception in on_case_done stops a local study; on an executor the chunks submitted ran
    on to the end (a Dask or MPI study kept the cluster busy for its whole length). They are
    cancelled, as on Ctrl-C. Every chunk after the first waits until the study has raised (else
    the one worker could run several chunks while the first case's callback is reported, however
    fast the cases are): the first ran, the second at most started, the other 18 are cancelled."""
    import threading
    from concurrent.futures import ThreadPoolExecutor

    raised = threading.Event()

    class Recording(ThreadPoolExecutor):
        futures = []

        def submit(self, fn, *args, **kwargs):
            first = not self.futures

            def gated(*a, **k):
                if not first:
                    raised.wait(30.0)  # a bound, so that a regression fails instead of hanging
                return fn(*a, **k)

            f = super().submit(gated, *args, **kwargs)
            self.futures.append(f)
            return f

    def fail(index, outcome):
        raise RuntimeError("stop here")

    cases = [oscidrum.Case(table2_G=G, continuation=False) for G in (5e6, 10e6, 15e6, 20e6) * 5]
    with Recording(1) as pool:
        with pytest.raises(RuntimeError, match="stop here"):
            oscidrum.run_study(cases, executor=pool, chunk_size=1, threads=1, on_case_done=fail)
        raised.set()
    assert len(pool.futures) == 20
    assert not pool.futures[0].cancelled()
    assert sum(f.cancelled() for f in pool.futures[2:]) == 18


def test_default_chunks_follow_the_executors_workers():
    """The default chunk size splits a study over the executor's workers: a pool's own count, a
    Dask ClientExecutor's cluster workers (not the client machine's cores)."""
    from concurrent.futures import ThreadPoolExecutor
    from oscidrum.study import _executor_workers

    class Client:
        def nthreads(self):
            return {f"tcp://w{k}": 1 for k in range(8)}

    class DaskLike:
        _client = Client()

    with ThreadPoolExecutor(3) as pool:
        assert _executor_workers(pool) == 3
    assert _executor_workers(DaskLike()) == 8
    assert _executor_workers(object()) == (os.cpu_count() or 1)


def test_samples_reach_the_callback_only_when_asked(local):
    """Without keep_samples no case is sampled, unless samples_in_callback: then on_case_done
    sees each steady state's samples, and the outcomes returned (locally and from an executor)
    do not keep them. Every number is the same in all three runs (but the counters of the runs'
    lengths: the sampled periods beyond the steady one are integrated only for samples)."""
    from concurrent.futures import ThreadPoolExecutor
    seen = {}

    def record(index, outcome):
        seen[index] = len(outcome.result.samples)

    plain = oscidrum.run_study(grid(), threads=2, on_case_done=record)
    assert sorted(seen) == list(range(len(grid()))) and set(seen.values()) == {0}
    same(plain, local)
    seen.clear()
    streamed = oscidrum.run_study(grid(), threads=2, on_case_done=record,
                                  samples_in_callback=True)
    assert set(seen.values()) == {2 * 1024}  # 2 output periods of 1024 samples
    assert all(len(o.result.samples) == 0 for o in streamed)
    same(streamed, local, sampled_differently=True)
    seen.clear()
    with ThreadPoolExecutor(2) as pool:
        remote = oscidrum.run_study(grid(), executor=pool, chunk_size=5, threads=1,
                                    on_case_done=record, samples_in_callback=True)
    assert set(seen.values()) == {2 * 1024}
    assert all(len(o.result.samples) == 0 for o in remote)
    same(remote, local, sampled_differently=True)
    with pytest.raises(oscidrum.Error, match="samples_in_callback must be True or False"):
        oscidrum.run_study(grid(), samples_in_callback="yes")


def test_dask_distributed_executor(local):
    distributed = pytest.importorskip("distributed")
    env = {"PYTHONPATH": os.pathsep.join(sys.path)}
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None,
                                  worker_class=distributed.Nanny, env=env) as cluster, \
            distributed.Client(cluster) as client:
        res = oscidrum.run_study(grid(), executor=client.get_executor(), chunk_size=4)
        workers = client.run(os.getpid)
        from oscidrum.study import _executor_workers
        assert _executor_workers(client.get_executor()) == 2  # the cluster's, for chunk_size
    assert len(set(workers.values())) == 2
    same(res, local)


MPI_SCRIPT = """
import sys
from mpi4py.futures import MPIPoolExecutor
import oscidrum
cases = [oscidrum.Case(table2_G=G, mu=mu, continuation=False) for G in {G} for mu in {MU}]
local = oscidrum.run_study(cases, threads=1)
with MPIPoolExecutor() as pool:
    res = oscidrum.run_study(cases, executor=pool, chunk_size=4, threads=1)
# repr: exact for floats (shortest round trip) and NaN equal to NaN
assert repr([o.metrics.to_dict() for o in res]) == repr([o.metrics.to_dict() for o in local])
assert repr([o.result.diagnostics.to_dict() for o in res]) == \\
    repr([o.result.diagnostics.to_dict() for o in local])
print("identical", len(res))
"""


def test_mpi4py_futures_executor(tmp_path):
    pytest.importorskip("mpi4py")
    mpiexec = shutil.which("mpiexec")
    if mpiexec is None:
        pytest.skip("mpiexec (openmpi-bin) is not installed")
    script = tmp_path / "mpi_study.py"
    script.write_text(MPI_SCRIPT.format(G=G_VALUES, MU=MU_VALUES))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path),
               OMPI_MCA_btl="self,vader,tcp", OMPI_MCA_btl_tcp_if_include="lo",
               OMPI_MCA_oob_tcp_if_include="lo", OMPI_MCA_rmaps_base_oversubscribe="1",
               OMPI_MCA_plm_rsh_agent="", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", PRTE_MCA_rmaps_default_mapping_policy=":oversubscribe")
    args = [mpiexec, "-n", "3", "--oversubscribe"]
    if os.geteuid() == 0:
        args.append("--allow-run-as-root")
    args += [sys.executable, "-m", "mpi4py.futures", str(script)]
    p = subprocess.run(args, capture_output=True, text=True, env=env, timeout=120)
    assert p.returncode == 0, p.stdout + p.stderr
    assert f"identical {len(G_VALUES) * len(MU_VALUES)}" in p.stdout


def test_dataframe_has_no_metrics_without_a_steady_state():
    # the transient method's budget (shooting would find the orbit regardless)
    res = oscidrum.run_study([oscidrum.Case(max_periods=2, method="transient"),
                              oscidrum.Case(mu=-1.0 + 1.3)])
    df = res.to_dataframe()
    assert not df["ok"][0] and np.isnan(df["area"][0]) and df["status"][0] == "max_periods_reached"
    assert df["ok"][1] and df["area"][1] > 0


def test_outcome_pickles_every_member():
    """A CaseOutcome crosses processes whole: samples, events, the Floquet multipliers of a
    shooting run, the method diagnostics and the metrics (every output-table member)."""
    import pickle
    case = oscidrum.Case(table2_G=25e6, mu=0.5, MMd_fraction=0.05, method="shooting")
    (o,) = oscidrum.run_study([case], threads=1, keep_samples=True)
    assert o.result.status == oscidrum.Status.steady_state and len(o.result.samples.t) > 0
    back = pickle.loads(pickle.dumps(o))
    assert same_values(back.metrics.to_dict(), o.metrics.to_dict())
    assert same_values(back.result.diagnostics.to_dict(), o.result.diagnostics.to_dict())
    assert back.result.diagnostics.method == o.result.diagnostics.method
    assert back.result.floquet_multipliers == o.result.floquet_multipliers
    assert len(o.result.floquet_multipliers) > 0
    for column in oscidrum.Samples.columns:
        np.testing.assert_array_equal(np.asarray(getattr(back.result.samples, column)),
                                      np.asarray(getattr(o.result.samples, column)))
    assert [(e.t, e.kind) for e in back.result.events] == [(e.t, e.kind) for e in o.result.events]
    with pytest.raises(oscidrum.Error, match="not one written by this build"):
        o.__setstate__(o.__getstate__()[:-3])


def test_result_metrics_diagnostics_samples_pickle_on_their_own(tmp_path):
    """What oscidrum.simulate and compute_metrics return crosses processes too (Dask,
    multiprocessing, a pickle cache): equal member by member in another interpreter; a state of
    another type or a cut one is refused by name."""
    import pickle
    import subprocess
    import sys
    case = oscidrum.Case(table2_G=25e6, mu=0.5, MMd_fraction=0.05)
    r = oscidrum.simulate(case)
    m = oscidrum.compute_metrics(r)
    assert r.ok and len(r.samples) > 0 and len(r.events) > 0 and len(r.floquet_multipliers) > 0
    path = tmp_path / "outputs.pickle"
    path.write_bytes(pickle.dumps((r, m, r.diagnostics, r.samples)))
    script = (
        "import pickle, sys\n"
        "import numpy as np\n"
        "import oscidrum\n"
        "r, m, d, s = pickle.loads(open(sys.argv[1], 'rb').read())\n"
        "case = oscidrum.Case(table2_G=25e6, mu=0.5, MMd_fraction=0.05)\n"
        "r0 = oscidrum.simulate(case)\n"
        "m0 = oscidrum.compute_metrics(r0)\n"
        "assert r.status == r0.status and r.message == r0.message\n"
        "assert r.frequency == r0.frequency and r.sample_periods == r0.sample_periods\n"
        "assert r.floquet_multipliers == r0.floquet_multipliers and r.stability == r0.stability\n"
        "assert [(e.t, e.kind) for e in r.events] == [(e.t, e.kind) for e in r0.events]\n"
        "assert r.stick_time == r0.stick_time and r.slip_positive_time == r0.slip_positive_time\n"
        "for c in oscidrum.Samples.columns:\n"
        "    np.testing.assert_array_equal(getattr(s, c), getattr(r0.samples, c))\n"
        "    np.testing.assert_array_equal(getattr(r.samples, c), getattr(r0.samples, c))\n"
        "a, b = m.to_dict(), m0.to_dict()\n"
        "assert a.keys() == b.keys()\n"
        "for k in a:\n"
        "    np.testing.assert_array_equal(a[k], b[k], err_msg=k)\n"
        "np.testing.assert_array_equal(m.ddx_amplitude, m0.ddx_amplitude)\n"
        "np.testing.assert_array_equal(m.ddz_phase, m0.ddz_phase)\n"
        "x, y = d.to_dict(), r0.diagnostics.to_dict()\n"
        "for k in x:\n"
        "    assert x[k] == y[k] or (x[k] != x[k] and y[k] != y[k]), k\n"
        "print('same')\n")
    p = subprocess.run([sys.executable, "-c", script, str(path)], capture_output=True, text=True,
                       timeout=120)
    assert p.returncode == 0 and p.stdout.strip() == "same", p.stdout + p.stderr
    with pytest.raises(oscidrum.Error, match="cannot restore a Result: the state is not one"):
        r.__setstate__(m.__getstate__())
    with pytest.raises(oscidrum.Error, match="cannot restore a Samples: the state is not one"):
        r.samples.__setstate__(r.samples.__getstate__()[:-1])
    with pytest.raises(oscidrum.Error, match="cannot restore a Metrics from"):
        pickle.loads(pickle.dumps(m)).__setstate__("garbage")


def test_period_doubling_keeps_the_period_one_multipliers():
    """A steady state repeating every 2 periods (a period doubling, docs/periodic.md): the
    multipliers of the stable period-2 orbit, and those of the unstable period-1 orbit it
    replaced, through a process boundary too."""
    import pickle
    case = oscidrum.Case.from_dict({"soil.input": "modulus", "soil.G": 150e6,
                                    "roller.unbalance": 0.22877, "roller.f": 25.0,
                                    "trough.k": 0.002, "trough.a": 0.601, "contact.mu": 0.7})
    (o,) = oscidrum.run_study([case], threads=1)
    r = o.result
    assert o.ok and r.diagnostics.multiplicity == 2
    assert r.stability == "stable" and r.floquet_max_modulus < 1.0
    assert r.period1_stability == "period_doubling"
    assert len(r.period1_floquet_multipliers) == 7
    assert r.period1_floquet_multipliers[0].real < -1.0
    back = pickle.loads(pickle.dumps(o))
    assert back.result.period1_floquet_multipliers == r.period1_floquet_multipliers
    assert back.result.period1_stability == "period_doubling"
    plain = oscidrum.run_case(oscidrum.Case())
    assert plain.result.period1_stability == "unknown"
    assert plain.result.period1_floquet_multipliers == []


def test_harmonics_bounded_by_the_samples_nyquist_limit():
    # 10**7 harmonics once ran for minutes per case; the bound follows from the sampling.
    with pytest.raises(oscidrum.Error, match=r"n_harmonics must be < numerics.samples_per_period / 2 = 512"):
        oscidrum.run_study([oscidrum.Case()], n_harmonics=10**7)
    # run_case's argument, not its case, is wrong: an invalid outcome said "compute_metrics:
    # n_max must be < ...".
    for n in (10**7, 600, 512, -3):
        with pytest.raises(oscidrum.Error, match=r"^n_harmonics must be in \[0, 512\) "
                           r"\(numerics\.samples_per_period / 2, the samples' Nyquist limit\); "
                           rf"got {n}$"):
            oscidrum.run_case(oscidrum.Case(), n_harmonics=n)
    assert oscidrum.run_case(oscidrum.Case(), keep_samples=False, n_harmonics=511).ok


def test_an_invalid_case_has_no_steady_state_and_no_metrics():
    # It said status steady_state with every metric 0 (o.metrics.area read 0.0); the DataFrame's
    # "error" held the result's message for cases that ran ("periodic orbit by shooting ...").
    import math
    res = oscidrum.run_study([{"R": 0.59}, {"G": 30e6}])
    bad, good = res
    assert not bad.valid and bad.result.status.name == "invalid"
    assert math.isnan(bad.metrics.area) and math.isnan(bad.metrics.ddx_max)
    assert good.ok and good.error == ""
    df = res.to_dataframe()
    assert list(df["status"]) == ["invalid", "steady_state"]
    assert df["error"][1] == "" and "trough.a must be > roller.r" in df["error"][0]
    assert df["message"][1].startswith("periodic orbit")


def test_an_uncaught_interrupt_ends_a_script_by_sigint(tmp_path):
    """Ctrl-C during run_study in a script: the script dies by SIGINT as with a plain
    KeyboardInterrupt (exit status 130 in a shell), not with status 1 (a shell loop over study
    scripts went on after Ctrl-C); caught, it is an ordinary exception."""
    import signal
    import subprocess
    import sys
    import time
    script = tmp_path / "study.py"
    script.write_text("import sys\nimport oscidrum\n"
                      "cases = [oscidrum.Case(table2_G=25e6, mu=0.3 + 0.0001 * k) "
                      "for k in range(20000)]\n"
                      "print('started', flush=True)\n"
                      "oscidrum.run_study(cases, threads=1)\n")
    p = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "started"
    time.sleep(0.5)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    assert p.returncode == -signal.SIGINT, (p.returncode, err)
    assert "Interrupted: study interrupted" in err, err
    caught = tmp_path / "caught.py"
    caught.write_text("import os, signal, threading\nimport oscidrum\n"
                      "cases = [oscidrum.Case(table2_G=25e6, mu=0.3 + 0.0001 * k) "
                      "for k in range(20000)]\n"
                      "threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT)).start()\n"
                      "try:\n"
                      "    oscidrum.run_study(cases, threads=1)\n"
                      "except oscidrum.Interrupted as e:\n"
                      "    print('kept', sum(o.valid for o in e.result))\n")
    q = subprocess.run([sys.executable, str(caught)], capture_output=True, text=True, timeout=120)
    assert q.returncode == 0 and q.stdout.startswith("kept "), (q.returncode, q.stderr)
