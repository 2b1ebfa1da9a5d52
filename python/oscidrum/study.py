"""Studies: many cases on all cores, or on any :class:`concurrent.futures.Executor` (Dask
distributed, mpi4py.futures, a process pool), with results as pandas and xarray objects.

>>> import oscidrum
>>> cases = [oscidrum.Case(table2_G=G, mu=mu) for G in (5e6, 25e6) for mu in (0.3, 0.5)]
>>> res = oscidrum.run_study(cases)                     # doctest: +SKIP
>>> res.to_dataframe()[["soil.G", "contact.mu", "area"]]   # [Pa], [-], [m^2/s^4]  # doctest: +SKIP
"""

from __future__ import annotations

import concurrent.futures as _cf
import copy
import math
import os
import sys
from typing import Any, Callable, Iterable, List, Optional, Sequence, Union

from . import _core
from ._checks import is_integer
from ._files import output_path

__all__ = ["run_study", "StudyResult", "Interrupted", "run_chunk"]

#: Default cases per executor task: large enough that scheduling costs little next to the
#: simulations (a case takes 4-15 ms), small enough to spread a study over the workers.
DEFAULT_CHUNK_SIZE = 500

_OUTCOME_COLUMNS = ("valid", "ok", "status", "error", "message")
_UNITS = {"periods_to_steady": "-", "multiplicity": "-"}


class Interrupted(KeyboardInterrupt):
    """Ctrl-C stopped a study. ``.result`` holds what was done: a :class:`StudyResult` whose
    cases not finished have ``valid=False`` and ``error='cancelled'``. Left uncaught, it ends a
    script as an uncaught KeyboardInterrupt does: killed by SIGINT (exit status 130 in a shell,
    which stops a shell loop over scripts), not with status 1."""

    def __init__(self, result: "StudyResult"):
        done = sum(1 for o in result if o.valid)
        super().__init__(f"study interrupted: {done} of {len(result)} cases done "
                         "(the exception's .result holds them)")
        self.result = result
        _end_by_sigint_if_uncaught()


# CPython ends an interpreter whose uncaught exception is KeyboardInterrupt by killing itself with
# SIGINT once it has finished (so that a shell sees the signal), but only for KeyboardInterrupt
# itself: a subclass such as Interrupted left status 1. Its first raise puts a hook in front of
# sys.excepthook (the hook that prints an uncaught exception's traceback in a script; Jupyter
# does not call it) that marks an uncaught Interrupted; the atexit handler registered when this
# module was imported, so after the handlers registered later, then ends the process by SIGINT.
_uncaught_interrupt = False


def _end_by_sigint_if_uncaught() -> None:
    hook = sys.excepthook
    if getattr(hook, "_oscidrum_interrupted", False):
        return

    def excepthook(kind, value, tb):
        global _uncaught_interrupt
        if isinstance(value, Interrupted):
            _uncaught_interrupt = True
        hook(kind, value, tb)

    excepthook._oscidrum_interrupted = True
    sys.excepthook = excepthook


def _exit_by_sigint() -> None:
    if not _uncaught_interrupt:
        return
    import signal
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except Exception:
            pass
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    os.kill(os.getpid(), signal.SIGINT)


import atexit  # noqa: E402

atexit.register(_exit_by_sigint)


def _metric_units():
    return dict(_core.Metrics.units)


class StudyResult(list):
    """The outcomes of a study, one :class:`oscidrum.CaseOutcome` per case in case order (a
    list), with the cases (``.cases``) and conversions to pandas and xarray."""

    def __init__(self, cases: Sequence[Any], outcomes: Iterable[Any]):
        super().__init__(outcomes)
        self.cases = list(cases)

    def to_dataframe(self, parameters: str = "varied"):
        """One row per case: parameters, outcome and metrics.

        Parameters
        ----------
        parameters : {'varied', 'all'}
            'varied': the dotted keys whose values differ between the cases (soil.G always when
            the soil varies); 'all': every key (soil values without effect included).

        Returns
        -------
        pandas.DataFrame
            Columns: the parameters (SI units), ``valid``, ``ok``, ``status``, ``error``, ``message``,
            ``periods_to_steady``, ``multiplicity`` and every scalar metric of
            :class:`oscidrum.Metrics` (``area`` [m^2/s^4], ``ddx_max`` [m/s^2], ...; NaN when a
            case has no steady state). ``df.attrs['units']`` maps columns to units.

        Examples
        --------
        >>> df = res.to_dataframe()                 # doctest: +SKIP
        >>> df.pivot(index="soil.G", columns="contact.mu", values="area")   # doctest: +SKIP
        """
        import numpy as np
        import pandas as pd

        if parameters not in ("varied", "all"):
            raise _core.Error(f"parameters must be 'varied' or 'all'; got {parameters!r}")
        params = [c.to_dict(all=True) for c in self.cases]
        keys = list(_core.Case.keys())
        if parameters == "varied" and params:
            keys = [k for k in keys if any(p[k] != params[0][k] for p in params)]
            if any(k.startswith("soil.") for k in keys) and "soil.G" not in keys:
                keys.insert(next(i for i, k in enumerate(keys) if k.startswith("soil.")),
                            "soil.G")
        names = list(_core.Metrics.scalar_names)
        rows = []
        for p, o in zip(params, self):
            row = {k: p[k] for k in keys}
            row["valid"] = o.valid
            row["ok"] = o.ok
            row["status"] = o.result.status.name  # invalid, or cancelled for a case never run
            # error: why a case was refused ('' for a case that ran, as CaseOutcome.error; it held
            # the result's message, so that every row had an "error"); message: the result's.
            row["error"] = o.error
            row["message"] = o.result.message if o.valid else o.error
            d = o.result.diagnostics
            row["periods_to_steady"] = d.periods_to_steady
            row["multiplicity"] = d.multiplicity
            has = o.ok  # metrics exist for a steady state only
            m = o.metrics.to_dict() if o.valid else {}
            for n in names:
                row[n] = m.get(n, np.nan) if has else np.nan
            rows.append(row)
        columns = keys + list(_OUTCOME_COLUMNS) + ["periods_to_steady", "multiplicity"] + names
        df = pd.DataFrame(rows, columns=columns)
        units = {k: _core.find_field(k).unit for k in keys}
        units.update(_UNITS)
        units.update(_metric_units())
        df.attrs["units"] = {k: v for k, v in units.items() if k in df.columns}
        return df

    def to_xarray(self, dims: Optional[Sequence[str]] = None):
        """The study as an :class:`xarray.Dataset` over its parameters.

        Parameters
        ----------
        dims : sequence of str, optional
            Dotted keys that span the study (default: every key that varies, in field-table
            order). The cases must form a grid over them with each point once (a product
            study); missing points are NaN.

        Returns
        -------
        xarray.Dataset
            Coordinates: the dims; data variables: ``status`` (str), ``ok`` (bool),
            ``periods_to_steady`` and every scalar metric, each with ``attrs['units']``.

        Raises
        ------
        oscidrum.Error
            If two cases share the same point, or a dim is not a key of the cases.

        Examples
        --------
        >>> ds = res.to_xarray()                                  # doctest: +SKIP
        >>> ds["area"].sel({"contact.mu": 0.5}).plot()            # doctest: +SKIP
        >>> res.to_netcdf("study.nc")                             # doctest: +SKIP
        """
        df = self.to_dataframe("all")
        if dims is None:
            # The varied keys, leaving out those that follow from the ones taken (the Table 2
            # coefficients follow soil.G).
            vary = self.to_dataframe("varied")
            dims = []
            for k in (k for k in vary.columns if k in df.columns and k in _core.Case.keys()):
                if not dims or (df.groupby(dims)[k].nunique() > 1).any():
                    dims.append(k)
        dims = list(dims)
        for d in dims:
            if d not in df.columns:
                raise _core.Error(f"to_xarray: {d!r} is not a key of the cases; the keys are "
                                  f"{', '.join(_core.Case.keys())}")
        if df.duplicated(subset=dims).any() if dims else len(df) > 1:
            raise _core.Error("to_xarray: the cases do not form a grid over "
                              f"{dims or 'no parameters'}: some points appear twice; pass dims=")
        units = df.attrs["units"]
        data = ["status", "ok", "periods_to_steady", "multiplicity"] + list(
            _core.Metrics.scalar_names)
        if dims:
            ds = df.set_index(dims)[data].to_xarray()
            # A varied key that is not a dim follows the dims (soil.ksh with soil.G under Table 2,
            # or mu varied together with G case by case): a coordinate over them, not dropped.
            varied = [k for k in self.to_dataframe("varied").columns
                      if k in df.columns and k in _core.Case.keys() and k not in dims]
            for k in varied:
                ds = ds.assign_coords({k: df.set_index(dims)[k].to_xarray()})
        else:  # one case: a Dataset of scalars (a Series' to_xarray is a DataArray)
            import xarray as xr
            ds = xr.Dataset({name: ((), df[name].iloc[0]) for name in data})
        for name in list(ds.variables):
            if name in units:
                ds[name].attrs["units"] = units[name]
        ds.attrs["source"] = f"oscidrum {_core.__version__}"
        return ds

    def to_netcdf(self, path: Union[str, os.PathLike], dims: Optional[Sequence[str]] = None):
        """Write :meth:`to_xarray` to a netCDF file (netCDF4 via python3-netcdf4). ``ok`` is
        stored as int8 (netCDF has no booleans)."""
        ds = self.to_xarray(dims)
        ds["ok"] = ds["ok"].fillna(False).astype("int8")
        ds["ok"].attrs["units"] = "-"
        with output_path(path, regular_only=True) as target:  # netCDF seeks: a regular file
            ds.to_netcdf(target)
        return path


def _as_cases(cases: Any) -> List[Any]:
    if isinstance(cases, (str, bytes, dict, _core.Case)) or not hasattr(cases, "__iter__"):
        raise _core.Error("cases must be a list (or other iterable) of Case objects or "
                          f"{{key: value}} dicts; got {type(cases).__name__}")
    out = []
    for i, c in enumerate(cases):
        if isinstance(c, _core.Case):
            # A copy: the study runs, and its result's table describes, the case as it was given
            # (a caller who changed its Case objects for the next study had the first study's
            # table show the new parameters beside the old results).
            out.append(copy.copy(c))
        elif isinstance(c, dict):
            try:
                out.append(_core.Case.from_dict(c))
            except _core.Error as exc:
                error = _core.Error(f"cases[{i}]: {exc}")
                error.key, error.value = getattr(exc, "key", None), getattr(exc, "value", None)
                raise error from None
        else:
            text = repr(c)
            text = text if len(text) <= 60 else text[:60] + "..."
            raise _core.Error(f"cases[{i}] must be a Case or a {{key: value}} dict; got "
                              f"{type(c).__name__} ({text})")
    return out


def _check_options(threads, keep_samples, n_harmonics):
    if not is_integer(threads) or threads < 0:
        raise _core.Error(f"threads must be an integer >= 0 (0: all cores); got {threads!r}")
    if not isinstance(keep_samples, bool):
        raise _core.Error(f"keep_samples must be True or False; got {keep_samples!r}")
    if not is_integer(n_harmonics) or n_harmonics < 2:
        raise _core.Error(f"n_harmonics must be an integer >= 2; got {n_harmonics!r}")


class _Progress:
    """progress=None: a tqdm bar on stderr when it is a terminal; True/False; or a callable
    progress(done, total)."""

    def __init__(self, progress, total):
        self.call = None
        self.bar = None
        if callable(progress):
            self.call = progress
            return
        if progress is None:
            progress = sys.stderr is not None and sys.stderr.isatty()
        elif not isinstance(progress, bool):
            raise _core.Error("progress must be None (a bar on a terminal), True, False or a "
                              f"callable progress(done, total); got {progress!r}")
        if progress:
            try:
                from tqdm.auto import tqdm
            except ImportError:  # python3-tqdm missing: no bar
                return
            self.bar = tqdm(total=total, unit="case", desc="oscidrum", file=sys.stderr)

    def __call__(self, done, total):
        if self.call is not None:
            self.call(done, total)
        elif self.bar is not None:
            self.bar.update(done - self.bar.n)

    def close(self):
        if self.bar is not None:
            self.bar.close()


def run_chunk(cases: Sequence[Any], threads: int = 0, keep_samples: bool = False,
              n_harmonics: int = 10) -> List[Any]:
    """Run one chunk of a study in this process on ``threads`` C++ threads (0: all cores, the
    GIL released): the task :func:`run_study` sends to an executor's workers."""
    return list(_core.run_study(list(cases), threads=threads, keep_samples=keep_samples,
                                n_harmonics=n_harmonics))


def run_study(cases: Iterable[Any], threads: int = 0, keep_samples: bool = False,
              n_harmonics: int = 10, progress: Union[None, bool, Callable[[int, int], Any]] = None,
              on_case_done: Optional[Callable[[int, Any], Any]] = None,
              executor: Optional[_cf.Executor] = None,
              chunk_size: Optional[int] = None,
              samples_in_callback: bool = False) -> StudyResult:
    """Run every case and return the outcomes in case order.

    Locally, the cases run on ``threads`` C++ threads with the GIL released. With an
    ``executor``, chunks of ``chunk_size`` cases go to its workers as tasks; each chunk runs on
    all cores of its worker; the outcomes are identical to a local run and in case order.

    Parameters
    ----------
    cases : iterable of Case or dict
        The cases ({key: value} dicts as for :meth:`Case.from_dict`).
    threads : int, default 0
        C++ worker threads per process (0: all cores).
    keep_samples : bool, default False
        Keep each steady state's samples (about 0.3 MB per case).
    n_harmonics : int, default 10
        Harmonics in the metrics.
    progress : None, bool or callable, default None
        None: a tqdm progress bar on stderr when it is a terminal, else none; True/False to
        force; or a callable ``progress(done, total)``.
    on_case_done : callable, optional
        ``on_case_done(index, outcome)`` after each case (locally) or each case of a finished
        chunk (executor). The outcome has samples only with ``keep_samples`` or
        ``samples_in_callback``.
    executor : concurrent.futures.Executor, optional
        E.g. ``distributed.Client(...).get_executor()``, ``mpi4py.futures.MPIPoolExecutor()``
        or ``ProcessPoolExecutor``. The workers must be able to import oscidrum.
    chunk_size : int, optional
        Cases per executor task (default 500, or fewer so that every worker gets work).
    samples_in_callback : bool, default False
        Give ``on_case_done`` each case's samples even without ``keep_samples`` (to write each
        steady state to disk while the study keeps only the metrics). Sampling costs about a
        fifth of a case; without it, and without ``keep_samples``, no case is sampled (every
        number of the outcomes is the same either way).

    Returns
    -------
    StudyResult
        A list of :class:`CaseOutcome` (invalid cases have ``valid=False`` and the message in
        ``error``), with ``.cases``, ``.to_dataframe()``, ``.to_xarray()``, ``.to_netcdf()``.

    Raises
    ------
    oscidrum.Error
        For a case that is neither a Case nor a valid dict, or a bad option.
    Interrupted
        On Ctrl-C (a KeyboardInterrupt): the running cases stop within about one excitation
        period; ``.result`` holds every case done.

    Examples
    --------
    >>> cases = [oscidrum.Case(table2_G=G) for G in (5e6, 10e6, 15e6)]
    >>> res = oscidrum.run_study(cases)                    # doctest: +SKIP
    >>> [round(o.metrics.area, 1) for o in res]            # [m^2/s^4]   # doctest: +SKIP
    """
    case_list = _as_cases(cases)
    _check_options(threads, keep_samples, n_harmonics)
    if on_case_done is not None and not callable(on_case_done):
        raise _core.Error(f"on_case_done must be callable or None; got {on_case_done!r}")
    if not isinstance(samples_in_callback, bool):
        raise _core.Error(f"samples_in_callback must be True or False; got {samples_in_callback!r}")
    # Samples for the callback only: taken, passed on, then dropped.
    sample = keep_samples or (samples_in_callback and on_case_done is not None)
    bar = _Progress(progress, len(case_list))
    try:
        if executor is None:
            return _run_local(case_list, threads, keep_samples, sample, n_harmonics, bar,
                              on_case_done)
        if not isinstance(executor, _cf.Executor) and not hasattr(executor, "submit"):
            raise _core.Error("executor must be a concurrent.futures.Executor; got "
                              f"{type(executor).__name__}")
        return _run_executor(case_list, executor, chunk_size, threads, keep_samples, sample,
                             n_harmonics, bar, on_case_done)
    finally:
        bar.close()


def _not_run(cases, outcomes):
    """A StudyResult with the outcomes known and, for the rest, the runner's 'cancelled'."""
    return StudyResult(cases, [_core.CaseOutcome.not_run() if o is None else o
                               for o in outcomes])


def _run_local(cases, threads, keep_samples, sample, n_harmonics, bar, on_case_done):
    done = [None] * len(cases)  # for Interrupted: what is done, without the callback's samples

    def finished(index, outcome):
        if on_case_done is not None:
            on_case_done(index, outcome)
        done[index] = outcome if keep_samples or not sample else _core._without_samples(outcome)

    try:
        outcomes = _core.run_study(cases, threads=threads, keep_samples=keep_samples,
                                   n_harmonics=n_harmonics, progress=bar,
                                   on_case_done=finished, samples_in_callback=sample)
    except KeyboardInterrupt:
        raise Interrupted(_not_run(cases, done)) from None
    return StudyResult(cases, outcomes)


def _run_executor(cases, executor, chunk_size, threads, keep_samples, sample, n_harmonics, bar,
                  on_case_done):
    n = len(cases)
    if chunk_size is None:
        workers = _executor_workers(executor)
        chunk_size = max(1, min(DEFAULT_CHUNK_SIZE, math.ceil(n / workers))) if n else 1
    if not is_integer(chunk_size) or chunk_size < 1:
        raise _core.Error(f"chunk_size must be an integer >= 1; got {chunk_size!r}")
    starts = list(range(0, n, chunk_size))
    futures = {}
    outcomes = [None] * n
    done_count = 0
    try:
        for s in starts:
            f = executor.submit(run_chunk, cases[s:s + chunk_size], threads, sample,
                                n_harmonics)
            futures[f] = s
        pending = set(futures)
        while pending:
            finished, pending = _cf.wait(pending, return_when=_cf.FIRST_COMPLETED)
            for f in finished:
                s = futures[f]
                chunk = f.result()
                for i, o in enumerate(chunk):
                    if on_case_done is not None:
                        on_case_done(s + i, o)
                    outcomes[s + i] = o if keep_samples or not sample else _core._without_samples(o)
                done_count += len(chunk)
                bar(done_count, n)
    except KeyboardInterrupt:
        for f in futures:
            f.cancel()
        raise Interrupted(_not_run(cases, outcomes)) from None
    except BaseException:
        # An exception of on_case_done or progress (or a failed chunk): no new cases, as a local
        # study stops; the chunks not started yet are cancelled (they ran to the end before).
        for f in futures:
            f.cancel()
        raise
    return StudyResult(cases, outcomes)


def _executor_workers(executor) -> int:
    """How many workers an executor has, for the default chunk size: concurrent.futures' and
    mpi4py's pools say it (_max_workers); a Dask ClientExecutor's are its cluster's workers (not
    the cores of the machine running the client: a 2-core login node split a study into 2 tasks
    whatever the cluster's size); otherwise this machine's cores."""
    workers = getattr(executor, "_max_workers", None)
    if not workers:
        client = getattr(executor, "_client", None)
        try:
            workers = len(client.nthreads()) if client is not None else None
        except Exception:  # a client that cannot say (closed, not Dask's)
            workers = None
    return max(1, int(workers or os.cpu_count() or 1))
