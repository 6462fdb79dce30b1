"""Running a sweep on dask.distributed: one task per run, each run's result file kept, resume.

Every run's full result is kept in ``SWEEP.runs/`` (named by its parameters) and is written
atomically (:func:`viscontact.io.netcdf.write_netcdf`), so an interrupted sweep is resumed by running
the same command again: runs whose file opens, has ``complete == 1`` and was made from the same
case (attribute ``sweep_fingerprint``, a hash of the validated case and the solver) are not
recomputed. With an existing cluster the workers write those files themselves, so they must see
the same file system (the usual case on a cluster). dask is imported inside the functions.
"""
from __future__ import annotations

import json
import math
import time
import warnings
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable

from viscontact.errors import ParameterError, ViscontactWarning, warn_caller
from viscontact.io.output_files import check_output_path, remove_temporaries
from viscontact.running.resources import available_cores as default_workers
from viscontact.sweep.assemble import assemble, summarize
from viscontact.sweep.spec import Plan, Run, SweepSpec, load_sweep, plan

if TYPE_CHECKING:  # xarray is imported where it is used
    import xarray as xr

__all__ = ["cluster_client", "default_workers", "local_cluster", "runs_dir", "sweep"]


def _execute(task: dict[str, Any]) -> dict[str, Any]:
    """Run one case and write its result file; never raises for a failed run (the error is returned).

    ``task``: ``text``, ``base_dir``, ``source`` of the base case, ``overrides`` (all of them),
    ``solver``, ``path`` (result file or None), ``fingerprint``, ``parameters`` (JSON).
    """
    from viscontact.io.case import Case
    from viscontact.io.netcdf import write_netcdf
    from viscontact.running import api

    started = time.perf_counter()
    ds = None
    error = ""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ViscontactWarning)
        try:
            case = Case.from_toml_text(task["text"], task["base_dir"], source=task["source"])
            case = case.with_overrides(task["overrides"])
            ds = api.run_steady(case) if task["solver"] == "steady" else api.run(case)
        except Exception as exc:  # a failed run is a result of the sweep, not a crash of it
            error = " ".join(f"{type(exc).__name__}: {exc}".split())
            ds = getattr(exc, "partial", None)
    elapsed = time.perf_counter() - started
    notes = list(dict.fromkeys(" ".join(str(w.message).split()) for w in caught
                               if issubclass(w.category, ViscontactWarning)))
    if ds is not None and task["path"] is not None:
        ds.attrs.update({"sweep_fingerprint": task["fingerprint"], "sweep_parameters": task["parameters"],
                         "sweep_run_time": elapsed, "sweep_warnings": "\n".join(notes)})
        if error:
            ds.attrs["complete"] = 0
            ds.attrs["sweep_error"] = error
        write_netcdf(ds, task["path"], force=True)
    out = {"error": error, "warnings": notes, "run_time": elapsed}
    if not error:
        out.update(summarize(ds, task["solver"] == "transient"))
    return out


def _reuse(path: Path, fingerprint: str, series: bool) -> dict[str, Any] | None:
    """The summary of a complete result file made from the same case, else None."""
    import xarray as xr

    if not path.is_file():
        return None
    try:
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            if int(ds.attrs.get("complete", 0)) != 1 or ds.attrs.get("sweep_fingerprint") != fingerprint:
                return None
            out = summarize(ds, series)
            notes = str(ds.attrs.get("sweep_warnings", ""))
            out.update({"error": "", "warnings": notes.split("\n") if notes else [],
                        "run_time": float(ds.attrs.get("sweep_run_time", math.nan))})
            return out
    except Exception:  # unreadable: compute it again
        return None


def runs_dir(out: str | Path) -> Path:
    """Folder of the per-run result files of the sweep file ``out``: ``SWEEP.nc`` -> ``SWEEP.runs``."""
    out = Path(out)
    return out.with_name(out.stem + ".runs") if out.suffix else out.with_name(out.name + ".runs")


def planned(spec: SweepSpec | str | Path) -> Plan:
    """The checked plan :func:`sweep` runs (:func:`~viscontact.sweep.spec.plan`): each run on one
    thread (``solver.workers = 1``: the cluster's processes share the cores) unless the sweep sets
    ``solver.workers`` itself."""
    if not isinstance(spec, SweepSpec):
        spec = load_sweep(spec)
    user_set_workers = "solver.workers" in spec.parameters or "solver.workers" in spec.overrides
    return plan(spec, fixed={} if user_set_workers else {"solver.workers": 1})


def sweep(spec: SweepSpec | Plan | str | Path, client: Any = None, out: str | Path | None = None,
          progress: Callable[[int, int, int], None] | None = None, *, workers: int | None = None,
          force: bool = False) -> xr.Dataset:
    """Run every point of a sweep on a dask.distributed cluster and gather the results.

    Parameters
    ----------
    spec
        A sweep file path or a :class:`SweepSpec`, checked completely (keys, values, every run's
        case and the solver's pre-run checks: :func:`planned`) before anything is submitted; or the
        :class:`Plan` :func:`planned` made of it.
    client
        A ``distributed.Client``. None: a ``LocalCluster`` of ``workers`` processes (default one
        per core; one where a run has ``solver.device = "gpu"``: the runs share the first CUDA
        device) with one thread each is started for the call and closed after it.
    out
        The sweep's netCDF file; the runs' result files go to ``SWEEP.runs/`` beside it, and complete
        ones found there are reused (resume). An existing ``out`` is replaced when it holds this same
        sweep (resuming) or with ``force``; never the sweep file or the base case. Checked before any
        run, under a lock held until the end (:func:`viscontact.io.output_files.output_lock`: a sweep
        writing the same ``out`` in another process is refused). None: no files, nothing reused.
    progress
        Called as ``progress(done, failed, total)`` after each finished (or reused) run.
    workers
        Worker processes of the local cluster (ignored with ``client``).

    Returns
    -------
    xarray.Dataset
        One dimension per swept key; attributes ``kind = "sweep"``, ``solver``, ``swept_keys``
        (JSON), ``runs_computed``, ``runs_reused``, ``runs_failed``, ``complete`` (1 when no run
        failed), for a transient sweep ``time_axis`` and ``interpolated_runs`` (JSON: the runs whose
        series are interpolated onto the union time axis, :mod:`viscontact.sweep.assemble`; warned
        once), the base case's ``a0``, ``p0``, ``retardation_time``, ``case`` and ``sweep``
        (the sweep file's text).

    A failed run is NaN in the Dataset, its message is in ``error`` and it is reported with a
    :class:`~viscontact.errors.ViscontactWarning`; the other runs still finish.
    """
    the_plan = spec if isinstance(spec, Plan) else planned(spec)
    spec = the_plan.spec
    if workers is not None and workers < 1:
        raise ParameterError("--workers", f"must be >= 1, got {workers}")
    if out is None:
        return _sweep(the_plan, client, None, progress, workers)
    from viscontact.io.output_files import output_lock

    with output_lock(out):  # another sweep writing ``out`` (and its runs) is refused
        check_output_path(out, force=force or _holds_sweep(out, spec), inputs=the_plan.input_files())
        return _sweep(the_plan, client, out, progress, workers)


def _sweep(the_plan: Plan, client: Any, out: str | Path | None,
           progress: Callable[[int, int, int], None] | None, workers: int | None) -> xr.Dataset:
    """:func:`sweep` of the checked plan ``the_plan``, ``out`` (when given) checked and locked."""
    inputs = the_plan.input_files()
    folder = runs_dir(out) if out is not None else None
    transient = the_plan.spec.solver == "transient"
    total = len(the_plan.runs)
    results: dict[int, dict[str, Any]] = {}
    done = failed = 0

    def tick(k: int, result: dict[str, Any]) -> None:
        nonlocal done, failed
        results[k] = result
        if result["error"]:
            failed += 1
            warn_caller(f"run failed ({the_plan.runs[k].label}): {result['error']}")
        else:
            done += 1
        if progress is not None:
            progress(done, failed, total)

    todo = []
    for k, run in enumerate(the_plan.runs):
        if folder is not None:
            reused = _reuse(folder / run.name, run.fingerprint, transient)
            if reused is not None:
                tick(k, reused)
                continue
        todo.append(k)
    reused_count = total - len(todo)
    if progress is not None and reused_count == 0:
        progress(0, 0, total)
    if todo:
        if folder is not None:
            folder.mkdir(parents=True, exist_ok=True)
            for k in todo:  # temporary files of writes that were killed half way; a run file replaces
                remove_temporaries(folder / the_plan.runs[k].name)  # a result only, never an input
                check_output_path(folder / the_plan.runs[k].name, force=True, inputs=inputs)
        tasks = {k: _task(the_plan, the_plan.runs[k], folder) for k in todo}
        if client is None and workers is None and any(the_plan.runs[k].case.solver.device == "gpu" for k in todo):
            workers = 1  # every run on the one GPU: a process per core would each hold a CUDA context
        with cluster_client(client, workers) as cl:
            _submit_all(cl, tasks, tick)
    ds = assemble(the_plan, results, transient)
    ds.attrs.update({"runs_computed": len(todo), "runs_reused": reused_count, "runs_failed": failed,
                     "complete": int(failed == 0)})
    if folder is not None:
        ds.attrs["runs_dir"] = folder.name
    if out is not None:
        from viscontact.io.netcdf import write_netcdf

        write_netcdf(ds, out, force=True)
    return ds


def _holds_sweep(path: str | Path, spec: SweepSpec) -> bool:
    """Whether ``path`` is the result of a sweep file with the text of ``spec`` (resuming it)."""
    import xarray as xr

    try:
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            return ds.attrs.get("kind") == "sweep" and ds.attrs.get("sweep") == spec.text
    except (OSError, ValueError):
        return False


def _task(the_plan: Plan, run: Run, folder: Path | None) -> dict[str, Any]:
    base = the_plan.base
    return {"text": base.text, "base_dir": str(Path(base.base_dir).resolve()), "source": str(the_plan.base_path),
            "overrides": {**the_plan.fixed, **run.overrides}, "solver": the_plan.spec.solver,
            "path": None if folder is None else str((folder / run.name).resolve()),
            "fingerprint": run.fingerprint, "parameters": json.dumps(run.overrides)}


def local_cluster(workers: int | None = None) -> Any:
    """A ``distributed.LocalCluster`` of ``workers`` processes (default: one per core), one thread each,
    without dashboard or log chatter.

    Its workers keep glibc's adaptive memory trimming: distributed's default
    ``MALLOC_TRIM_THRESHOLD_ = 65536`` makes every temporary array of a 64 x 64 solve go back to the
    kernel and made the steady runs 1.7 times slower (measured, BENCHMARKS.md).
    """
    import logging

    import dask
    from distributed import LocalCluster

    with dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
        return LocalCluster(n_workers=workers or default_workers(), threads_per_worker=1, processes=True,
                            dashboard_address=":0", scheduler_kwargs={"dashboard": False},
                            silence_logs=logging.ERROR)


class cluster_client:
    """Context manager: the given client, or a client of a :func:`local_cluster` started and closed here."""

    def __init__(self, client: Any, workers: int | None) -> None:
        self.client, self.workers = client, workers
        self.own: list[Any] = []

    def __enter__(self) -> Any:
        if self.client is not None:
            return self.client
        from distributed import Client

        cluster = local_cluster(self.workers)
        client = Client(cluster)
        self.own = [client, cluster]
        return client

    def __exit__(self, *exc: object) -> None:
        for thing in self.own:
            thing.close()


def _submit_all(client: Any, tasks: dict[int, dict[str, Any]], tick: Callable[[int, dict], None]) -> None:
    """Submit one task per run; hand each result to ``tick`` as it arrives. A task the cluster could
    not run (worker died, ...) becomes a failed run. On interrupt, the unfinished tasks are cancelled."""
    from distributed import as_completed

    futures = {}
    for k, task in tasks.items():
        key = f"viscontact-sweep-{task['fingerprint']}-{k}"
        futures[client.submit(_execute, task, key=key, pure=False, retries=0)] = k
    try:
        for future in as_completed(futures):
            k = futures[future]
            try:
                result = future.result()
            except Exception as exc:
                result = {"error": " ".join(f"{type(exc).__name__}: {exc}".split()), "warnings": [],
                          "run_time": math.nan}
            tick(k, result)
    finally:
        pending = [f for f in futures if not f.done()]
        if pending:
            client.cancel(pending)
