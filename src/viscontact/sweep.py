"""Parameter sweeps on a dask.distributed cluster: ``viscontact sweep SWEEP.toml --out SWEEP.nc``.

A sweep file names a base case and lists values for any dotted case key; the sweep runs the
Cartesian product of those values, one simulation per task, on a local cluster of worker processes
or on an existing cluster (``--scheduler tcp://HOST:PORT``)::

    base = "../seed_table1_v0.8.toml"    # relative to this file's folder, else to the CWD
    solver = "steady"                    # or "transient"
    [overrides]                          # optional: fixed for every run
    "grid.n" = 64
    [parameters]                         # one dimension per key, in this order
    "tangential.sliding_speed" = [0.002, 0.005, 0.01]
    "material.shear_modulus_long_term" = [0.193e6, 0.386e6]

The result is one Dataset (and netCDF file) with one dimension per swept key (``.`` -> ``__``; the
coordinate's ``key`` attribute holds the dotted key) and, per run, the scalars of its final state:
``mu_app``, ``peak_pressure``, ``contact_area``, ``contact_shift``, ``delta_z``, ``load``,
``hysteresis_force``, ``friction_force``, ``wake_loss``, ``t_gross_sliding`` (NaN where not
defined), ``run_time``; transient sweeps add their time series (``mu_app_t`` ... along ``t``).
Failed runs are NaN and carry their message in the string variable ``error``; warnings go to
``warnings``.

Every run's full result is kept in ``SWEEP.runs/`` (named by its parameters) and is written
atomically (:func:`viscontact.results.write_netcdf`), so an interrupted sweep is resumed by running
the same command again: runs whose file opens, has ``complete == 1`` and was made from the same
case (attribute ``sweep_fingerprint``, a hash of the validated case and the solver) are not
recomputed. With ``--scheduler`` the workers write those files themselves, so they must see the
same file system (the usual case on a cluster).

dask, tqdm and matplotlib are imported inside the functions that use them.
"""
from __future__ import annotations

import argparse
import difflib
import hashlib
import itertools
import json
import math
import os
import re
import sys
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

import numpy as np
import tomllib

from .errors import ParameterError, ViscontactWarning

if TYPE_CHECKING:  # xarray is imported where it is used: ``viscontact --help`` stays fast
    import xarray as xr

__all__ = ["SweepSpec", "load_sweep", "sweep", "plot_sweep", "add_sweep_parser", "cli_sweep",
           "run_file_name", "local_cluster", "SOLVERS", "SUMMARIES"]

#: solvers a sweep may use: ``viscontact.api.run_steady`` or ``viscontact.api.run``
SOLVERS = ("steady", "transient")
#: scalars kept of each run's final state (``t_gross_sliding`` and ``run_time`` are added)
SUMMARIES = ("mu_app", "peak_pressure", "contact_area", "contact_shift", "delta_z", "load",
             "hysteresis_force", "friction_force", "wake_loss")
#: the scalars whose time series a transient sweep keeps (as ``<name>_t``)
SERIES = ("mu_app", "peak_pressure", "contact_area", "contact_shift", "delta_z", "load")
_SWEEP_KEYS = ("title", "base", "solver", "parameters", "overrides")
_SUMMARY_UNITS = {"mu_app": "1", "peak_pressure": "Pa", "contact_area": "m2", "contact_shift": "m",
                  "delta_z": "m", "load": "N", "hysteresis_force": "N", "friction_force": "N",
                  "wake_loss": "1", "t_gross_sliding": "s", "run_time": "s"}
_MAX_NAME = 200  # characters of a run file name before it is shortened with a hash


# --- the sweep file ------------------------------------------------------------------------------
@dataclass(frozen=True)
class SweepSpec:
    """A sweep: the base case file, the swept keys with their values (in dimension order), the
    solver, and keys fixed for every run.

    ``base`` is taken relative to ``base_dir`` (the sweep file's folder) when it exists there, else
    relative to the current directory. Build one from a file with :func:`load_sweep`.
    """

    base: str | Path
    parameters: Mapping[str, Sequence[Any]]
    solver: str = "steady"
    overrides: Mapping[str, Any] = field(default_factory=dict)
    title: str = ""
    base_dir: Path | None = None
    text: str = ""
    source: str = "sweep"

    def base_path(self) -> Path:
        """The base case file; :class:`ParameterError` (key ``base``) when it is not found."""
        base = Path(self.base)
        candidates = [base] if base.is_absolute() else \
            ([self.base_dir / base] if self.base_dir is not None else []) + [Path.cwd() / base]
        for path in candidates:
            if path.is_file():
                return path
        where = " and ".join(dict.fromkeys(str(p.parent.resolve()) for p in candidates))
        raise ParameterError("base", f"no such case file: {str(self.base)!r} (looked in {where})")

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(self.parameters)

    @property
    def dims(self) -> tuple[str, ...]:
        """Dimension names of the swept keys: the dotted key with ``.`` -> ``__``."""
        return tuple(k.replace(".", "__") for k in self.parameters)

    @property
    def size(self) -> int:
        return math.prod(len(v) for v in self.parameters.values())


def load_sweep(path: str | Path) -> SweepSpec:
    """Read a sweep file (TOML). Its structure is checked here; the keys and values against the base
    case by :func:`sweep` (or :func:`plan`) before any run starts.

    Raises
    ------
    ParameterError
        Missing or unreadable file, not TOML, unknown top-level key, wrong types, empty list.
    """
    path = Path(path)
    from .case import read_input_file

    text = read_input_file(path, "sweep file")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError("sweep file", f"{path} is not valid TOML: {exc}") from None
    for key in data:
        if key not in _SWEEP_KEYS:
            raise ParameterError(key, f"unknown sweep-file key{_hint(key, _SWEEP_KEYS)}; "
                                 f"valid keys: {', '.join(_SWEEP_KEYS)}")
    if "base" not in data:
        raise ParameterError("base", f"required: the base case file (in {path})")
    if not isinstance(data["base"], str):
        raise ParameterError("base", f"must be a string (a case file path), got {data['base']!r}")
    if "parameters" not in data:
        raise ParameterError("parameters", "required: a [parameters] table of dotted case keys and value lists")
    for name in ("parameters", "overrides"):
        if name in data and not isinstance(data[name], dict):
            raise ParameterError(name, f"must be a table ([{name}]), got {data[name]!r}")
    for name in ("solver", "title"):
        if name in data and not isinstance(data[name], str):
            raise ParameterError(name, f"must be a string, got {data[name]!r}")
    return SweepSpec(base=data["base"], parameters=_flatten(data["parameters"]),
                     solver=data.get("solver", "steady"), overrides=_flatten(data.get("overrides", {})),
                     title=data.get("title", ""), base_dir=path.parent, text=text, source=str(path))


def _flatten(table: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """``{"a.b": v}`` and ``{"a": {"b": v}}`` (unquoted dotted TOML keys) both as ``{"a.b": v}``."""
    out: dict[str, Any] = {}
    for key, value in table.items():
        full = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(_flatten(value, full + "."))
        else:
            out[full] = value
    return out


def _hint(name: str, valid: Sequence[str]) -> str:
    close = difflib.get_close_matches(name, list(valid), n=1, cutoff=0.6)
    return f"; did you mean '{close[0]}'?" if close else ""


def case_keys() -> dict[str, Any]:
    """Every settable dotted case key -> its pydantic FieldInfo (all material types together)."""
    from pydantic import BaseModel

    from .case import _MATERIALS, Case, _model_of

    keys: dict[str, Any] = {}

    def walk(model: type[BaseModel], prefix: str) -> None:
        for name, info in model.model_fields.items():
            if model is Case and name == "material":
                for mat in _MATERIALS.values():
                    walk(mat, "material.")
                continue
            sub = _model_of(info.annotation)
            if sub is not None and issubclass(sub, BaseModel):
                walk(sub, f"{prefix}{name}.")
            else:
                keys.setdefault(f"{prefix}{name}", info)

    walk(Case, "")
    return keys


def _check_key(key: str, valid: Mapping[str, Any], where: str) -> None:
    if key in valid:
        return
    hint = _hint(key, list(valid))
    if not hint:  # a typo in the section or in the name alone
        section, _, name = key.rpartition(".")
        hint = _hint(name, [k for k in valid if k.startswith(section + ".")] or list(valid))
    raise ParameterError(key, f"unknown case key in [{where}]{hint}")


# --- the plan: every run, validated ----------------------------------------------------------------
@dataclass(frozen=True)
class Run:
    """One point of the sweep: its index along each dimension, its overrides and its case."""

    index: tuple[int, ...]
    overrides: dict[str, Any]
    case: Any  # viscontact.case.Case
    name: str
    fingerprint: str

    @property
    def label(self) -> str:
        return ", ".join(f"{k}={_fmt(v)}" for k, v in self.overrides.items())


@dataclass(frozen=True)
class Plan:
    spec: SweepSpec
    base: Any  # viscontact.case.Case
    base_path: Path
    runs: tuple[Run, ...]
    fixed: dict[str, Any]


def plan(spec: SweepSpec | str | Path, *, fixed: Mapping[str, Any] | None = None) -> Plan:
    """Check ``spec`` completely and build every run's validated case, computing nothing.

    ``fixed`` are overrides applied to every run after the sweep file's ``[overrides]`` (the sweep
    sets ``solver.workers = 1`` this way unless the sweep file sets it).

    Raises
    ------
    ParameterError
        Unknown solver, missing base case, unknown case key (with the closest valid one), a value
        list that is not a non-empty array of distinct values, or a run whose case is invalid
        (the message names the run's parameters).
    """
    from .case import load_case

    spec = load_sweep(spec) if isinstance(spec, (str, Path)) else spec
    if spec.solver not in SOLVERS:
        raise ParameterError("solver", f"must be one of {', '.join(repr(s) for s in SOLVERS)}, got {spec.solver!r}")
    if not spec.parameters:
        raise ParameterError("parameters", "empty: give at least one dotted case key with a list of values")
    valid = case_keys()
    for key in spec.overrides:
        _check_key(key, valid, "overrides")
    for key, values in spec.parameters.items():
        _check_key(key, valid, "parameters")
        if key in spec.overrides:
            raise ParameterError(key, "both swept in [parameters] and fixed in [overrides]; keep one")
        if not isinstance(values, (list, tuple)):
            raise ParameterError(key, f"must be an array of values to sweep, got {values!r}")
        if len(values) == 0:
            raise ParameterError(key, "empty list: give at least one value to sweep")
        seen = set()
        for v in values:
            token = json.dumps(v, sort_keys=True)
            if token in seen:
                raise ParameterError(key, f"value {v!r} is listed twice")
            seen.add(token)
    base_path = spec.base_path()
    try:
        base = load_case(base_path)
    except ParameterError as exc:
        raise ParameterError(exc.key, f"{exc.message} (in base case {base_path})") from None
    extra = {**spec.overrides, **{k: v for k, v in (fixed or {}).items()
                                  if k not in spec.overrides and k not in spec.parameters}}
    keys = list(spec.parameters)
    runs = []
    for index in itertools.product(*(range(len(v)) for v in spec.parameters.values())):
        combo = {k: spec.parameters[k][i] for k, i in zip(keys, index)}
        label = ", ".join(f"{k}={_fmt(v)}" for k, v in combo.items())
        try:
            case = base.with_overrides({**extra, **combo})
        except ParameterError as exc:
            raise ParameterError(exc.key, f"{exc.message} (in the run {label})") from None
        fp = hashlib.sha256(f"{spec.solver}\n{case.model_dump_json()}".encode()).hexdigest()[:16]
        runs.append(Run(index, combo, case, run_file_name(combo), fp))
    runs = _unique_names(runs)
    return Plan(spec, base, base_path, tuple(runs), extra)


def _fmt(value: Any) -> str:
    """A parameter value as written in run file names and messages (193000.0 -> 193000)."""
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e15:
        return str(int(value))
    if isinstance(value, (int, float, str)):
        return str(value) if isinstance(value, str) else repr(value)
    return json.dumps(value, separators=(",", ":"))


def run_file_name(overrides: Mapping[str, Any]) -> str:
    """``key=value__key=value.nc`` (characters outside ``[A-Za-z0-9._+=-]`` become ``_``; names
    over 200 characters are cut and end in a hash of the parameters)."""
    name = "__".join(f"{k}={_fmt(v)}" for k, v in overrides.items())
    name = re.sub(r"[^A-Za-z0-9._+=\-]", "_", name)
    if len(name) > _MAX_NAME:
        digest = hashlib.sha1(json.dumps(overrides, sort_keys=True, default=str).encode()).hexdigest()[:12]
        name = f"{name[:_MAX_NAME - 14]}__{digest}"
    return name + ".nc"


def _unique_names(runs: list[Run]) -> list[Run]:
    counts: dict[str, int] = {}
    for r in runs:
        counts[r.name] = counts.get(r.name, 0) + 1
    out = []
    for r in runs:
        if counts[r.name] > 1:  # two values that read the same once sanitised
            digest = hashlib.sha1(json.dumps(r.overrides, sort_keys=True, default=str).encode()).hexdigest()[:8]
            r = Run(r.index, r.overrides, r.case, f"{r.name[:-3]}__{digest}.nc", r.fingerprint)
        out.append(r)
    return out


# --- one run (on a worker) -------------------------------------------------------------------------
def _summarize(ds: xr.Dataset, series: bool) -> dict[str, Any]:
    """Final-state scalars (and time series) of a run's Dataset."""
    nt = ds.sizes.get("t", 0)
    out: dict[str, Any] = {}
    for name in SUMMARIES:
        if name == "peak_pressure":
            value = float(ds["pressure"].isel(t=-1).max()) if "pressure" in ds and nt else math.nan
        else:
            value = float(ds[name].values[-1]) if name in ds and nt else math.nan
        out[name] = value
    out["t_gross_sliding"] = float(ds.attrs.get("t_gross_sliding", math.nan))
    out["complete"] = int(ds.attrs.get("complete", 0))
    if series:
        out["t"] = np.asarray(ds["t"].values, dtype=float)
        for name in SERIES:
            if name == "peak_pressure":
                data = ds["pressure"].max(("y", "x")).values if "pressure" in ds else np.full(nt, np.nan)
            else:
                data = ds[name].values if name in ds else np.full(nt, np.nan)
            out[f"{name}_t"] = np.asarray(data, dtype=float)
    return out


def _execute(task: dict[str, Any]) -> dict[str, Any]:
    """Run one case and write its result file; never raises for a failed run (the error is returned).

    ``task``: ``text``, ``base_dir``, ``source`` of the base case, ``overrides`` (all of them),
    ``solver``, ``path`` (result file or None), ``fingerprint``, ``parameters`` (JSON).
    """
    from . import api
    from .case import Case
    from .results import write_netcdf

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
        out.update(_summarize(ds, task["solver"] == "transient"))
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
            out = _summarize(ds, series)
            notes = str(ds.attrs.get("sweep_warnings", ""))
            out.update({"error": "", "warnings": notes.split("\n") if notes else [],
                        "run_time": float(ds.attrs.get("sweep_run_time", math.nan))})
            return out
    except Exception:  # unreadable: compute it again
        return None


# --- the sweep -------------------------------------------------------------------------------------
def default_workers() -> int:
    """Cores available to this process."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def runs_dir(out: str | Path) -> Path:
    """Folder of the per-run result files of the sweep file ``out``: ``SWEEP.nc`` -> ``SWEEP.runs``."""
    out = Path(out)
    return out.with_name(out.stem + ".runs") if out.suffix else out.with_name(out.name + ".runs")


def sweep(spec: SweepSpec | str | Path, client: Any = None, out: str | Path | None = None,
          progress: Callable[[int, int, int], None] | None = None, *, workers: int | None = None) -> xr.Dataset:
    """Run every point of a sweep on a dask.distributed cluster and gather the results.

    Parameters
    ----------
    spec
        A sweep file path or a :class:`SweepSpec`. Checked completely (keys, values, every run's
        case) before anything is submitted.
    client
        A ``distributed.Client``. None: a ``LocalCluster`` of ``workers`` processes (default one
        per core) with one thread each is started for the call and closed after it.
    out
        The sweep's netCDF file (written, replacing an older one); the runs' result files go to
        ``SWEEP.runs/`` beside it, and complete ones found there are reused (resume). None: no
        files, nothing reused.
    progress
        Called as ``progress(done, failed, total)`` after each finished (or reused) run.
    workers
        Worker processes of the local cluster (ignored with ``client``).

    Returns
    -------
    xarray.Dataset
        One dimension per swept key; attributes ``kind = "sweep"``, ``solver``, ``swept_keys``
        (JSON), ``runs_computed``, ``runs_reused``, ``runs_failed``, ``complete`` (1 when no run
        failed), the base case's ``a0``, ``p0``, ``retardation_time``, ``case`` and ``sweep``
        (the sweep file's text).

    A failed run is NaN in the Dataset, its message is in ``error`` and it is reported with a
    :class:`~viscontact.errors.ViscontactWarning`; the other runs still finish.
    """
    if not isinstance(spec, SweepSpec):
        spec = load_sweep(spec)
    user_set_workers = "solver.workers" in spec.parameters or "solver.workers" in spec.overrides
    the_plan = plan(spec, fixed={} if user_set_workers else {"solver.workers": 1})
    if workers is not None and workers < 1:
        raise ParameterError("--workers", f"must be >= 1, got {workers}")
    folder = runs_dir(out) if out is not None else None
    transient = spec.solver == "transient"
    total = len(the_plan.runs)
    results: dict[int, dict[str, Any]] = {}
    done = failed = 0

    def tick(k: int, result: dict[str, Any]) -> None:
        nonlocal done, failed
        results[k] = result
        if result["error"]:
            failed += 1
            warnings.warn(f"run failed ({the_plan.runs[k].label}): {result['error']}", ViscontactWarning,
                          stacklevel=3)
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
            for k in todo:  # temporary files of writes that were killed half way
                for tmp in folder.glob(f"{glob_escape(the_plan.runs[k].name)}.tmp*"):
                    tmp.unlink(missing_ok=True)
        tasks = {k: _task(the_plan, the_plan.runs[k], folder) for k in todo}
        with _client(client, workers) as cl:
            _submit_all(cl, tasks, tick)
    ds = _assemble(the_plan, results, transient)
    ds.attrs.update({"runs_computed": len(todo), "runs_reused": reused_count, "runs_failed": failed,
                     "complete": int(failed == 0)})
    if folder is not None:
        ds.attrs["runs_dir"] = folder.name
    if out is not None:
        from .results import write_netcdf

        write_netcdf(ds, out, force=True)
    return ds


def glob_escape(name: str) -> str:
    return re.sub(r"([\[\]*?])", r"[\1]", name)


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


class _client:
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


def _coordinate(values: Sequence[Any]) -> np.ndarray:
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return np.asarray(values, dtype=int if all(isinstance(v, int) for v in values) else float)
    if all(isinstance(v, (str, bool)) for v in values) and len({type(v) for v in values}) == 1:
        return np.asarray(values)
    return np.asarray([_fmt(v) for v in values], dtype=object)


def _time_axis(results: Mapping[int, dict[str, Any]]) -> np.ndarray:
    """Union of the runs' record times (equal within 1e-9 of the span merged)."""
    times = [r["t"] for r in results.values() if not r["error"] and "t" in r and len(r["t"])]
    if not times:
        return np.zeros(0)
    t = np.unique(np.concatenate(times))
    tol = 1e-9 * max(float(t[-1] - t[0]), float(abs(t[-1])), 1e-300)
    keep = np.concatenate([[True], np.diff(t) > tol])
    return t[keep]


def _assemble(the_plan: Plan, results: Mapping[int, dict[str, Any]], transient: bool) -> xr.Dataset:
    from .results import VARIABLES, global_attrs

    spec = the_plan.spec
    dims, shape = spec.dims, tuple(len(v) for v in spec.parameters.values())
    names = list(SUMMARIES) + ["t_gross_sliding", "run_time"]
    arrays = {n: np.full(shape, np.nan) for n in names}
    error = np.full(shape, "", dtype=object)
    notes = np.full(shape, "", dtype=object)
    files = np.full(shape, "", dtype=object)
    t = _time_axis(results) if transient else None
    series = {f"{n}_t": np.full(shape + (t.size,), np.nan) for n in SERIES} if transient else {}
    for k, run in enumerate(the_plan.runs):
        files[run.index] = run.name
        r = results.get(k)
        if r is None:
            error[run.index] = "not run"
            continue
        error[run.index] = r["error"]
        notes[run.index] = "\n".join(r.get("warnings", []))
        arrays["run_time"][run.index] = r.get("run_time", math.nan)
        if r["error"]:
            continue
        for n in names[:-1]:
            arrays[n][run.index] = r[n]
        for n in series:
            tr, yr = r["t"], r[n]
            if tr.size == 1:
                series[n][run.index] = np.where(np.isclose(t, tr[0], rtol=1e-9, atol=0), yr[0], np.nan)
            elif tr.size:
                series[n][run.index] = np.interp(t, tr, yr, left=np.nan, right=np.nan)
    coords: dict[str, Any] = {}
    valid = case_keys()
    for key, dim in zip(spec.keys, dims):
        attrs = {"key": key, "long_name": key}
        extra = getattr(valid.get(key), "json_schema_extra", None) or {}
        if isinstance(extra, dict) and extra.get("unit"):
            attrs["units"] = extra["unit"]
        coords[dim] = (dim, _coordinate(spec.parameters[key]), attrs)
    variables: dict[str, Any] = {}
    for n in names:
        long_name = VARIABLES.get(n, ("", n))[1] if n in VARIABLES else {
            "t_gross_sliding": "time gross sliding began (0 when sliding from t = 0, NaN when never)",
            "run_time": "wall time of the run"}[n]
        variables[n] = (dims, arrays[n], {"units": _SUMMARY_UNITS[n], "long_name": f"{long_name}, final state"
                                          if n not in ("t_gross_sliding", "run_time") else long_name})
    variables["error"] = (dims, error.astype(str), {"long_name": "error of a failed run ('' when it succeeded)"})
    variables["warnings"] = (dims, notes.astype(str), {"long_name": "warnings of the run, one per line"})
    variables["run_file"] = (dims, files.astype(str), {"long_name": "result file of the run in the runs folder"})
    if transient:
        coords["t"] = ("t", t, {"units": "s", "long_name": "time (union of the runs' record times; each run "
                                "interpolated linearly, NaN outside its own time range)"})
        for n, data in series.items():
            base = n[:-2]
            long_name = VARIABLES[base][1] if base in VARIABLES else base
            variables[n] = (dims + ("t",), data, {"units": _SUMMARY_UNITS[base], "long_name": long_name})
    import xarray as xr

    ds = xr.Dataset(variables, coords=coords)
    base_attrs = global_attrs(the_plan.base.to_problem(), the_plan.base.text)
    for name in ("case", "a0", "p0", "retardation_time", "tangential_mode", "normal_control", "version",
                 "Conventions"):
        ds.attrs[name] = base_attrs[name]
    ds.attrs.update({"kind": "sweep", "solver": spec.solver, "title": spec.title or the_plan.base.title,
                     "swept_keys": json.dumps(list(spec.keys)), "fixed_overrides": json.dumps(the_plan.fixed),
                     "base": str(the_plan.base_path), "sweep": spec.text})
    return ds


# --- plots -----------------------------------------------------------------------------------------
_SPEED = "tangential.sliding_speed"
_LABELS = {"mu_app": "μ_app = F_T / W [-]", "peak_pressure": "peak pressure [MPa]",
           "contact_area": "contact area [mm²]"}
_SCALE = {"mu_app": 1.0, "peak_pressure": 1e-6, "contact_area": 1e6}


def _short(key: str) -> str:
    return key.rsplit(".", 1)[-1]


def plot_sweep(ds: xr.Dataset, out_dir: str | Path) -> list[Path]:
    """Figures of a sweep Dataset (``kind == "sweep"``) as PNG files in ``out_dir``.

    ``sweep_mu_app.png``: μ_app against the sliding speed (log axis; against the first swept key
    when the speed is not swept), one line per combination of the other swept keys; the top axis
    shows v τ / a0 when τ and a0 are the same for every run. ``sweep_peak_pressure.png`` and
    ``sweep_contact_area.png`` likewise. Failed runs are gaps.
    """
    from .plotting import _pyplot, _save

    plt = _pyplot()
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    keys = json.loads(ds.attrs.get("swept_keys", "[]")) or [ds[d].attrs.get("key", d) for d in _swept_dims(ds)]
    dims = [k.replace(".", "__") for k in keys]
    xdim = _SPEED.replace(".", "__") if _SPEED.replace(".", "__") in dims else dims[0]
    xkey = ds[xdim].attrs.get("key", xdim)
    others = [d for d in dims if d != xdim]
    xv = ds[xdim].values
    numeric = np.issubdtype(np.asarray(xv).dtype, np.number)
    order = np.argsort(xv) if numeric else np.arange(len(xv))
    logx = numeric and bool(np.all(xv > 0)) and (xdim == _SPEED.replace(".", "__") or xv.max() / xv.min() >= 10)
    # a0 (Hertz with G(0)) and the Zener retardation time do not depend on G(inf)
    scale_fixed = not any(k.startswith(("material.", "normal.", "indenter."))
                          and k != "material.shear_modulus_long_term" for k in keys)
    tau, a0 = ds.attrs.get("retardation_time"), ds.attrs.get("a0")
    deborah = (xdim == _SPEED.replace(".", "__") and scale_fixed and tau is not None and a0 is not None
               and np.isfinite(tau) and np.isfinite(a0) and a0 > 0)
    paths = []
    for name in ("mu_app", "peak_pressure", "contact_area"):
        if name not in ds:
            continue
        fig, ax = plt.subplots(figsize=(6.4, 4.3))
        combos = itertools.product(*(range(ds.sizes[d]) for d in others))
        for combo in combos:
            sel = dict(zip(others, combo))
            y = ds[name].isel(sel).values * _SCALE[name]
            label = ", ".join(_legend(ds[d], i) for d, i in sel.items())
            ax.plot(xv[order] if numeric else np.arange(len(xv)), y[order], "o-", ms=4, label=label or None)
        if logx:
            ax.set_xscale("log")
        if not numeric:
            ax.set_xticks(np.arange(len(xv)), [str(v) for v in xv])
        unit = ds[xdim].attrs.get("units", "")
        xlabel = "sliding speed v [m/s]" if xdim == _SPEED.replace(".", "__") else \
            f"{xkey}{f' [{unit}]' if unit else ''}"
        title = f"{ds.attrs.get('solver', '')} sweep: {_LABELS[name].split(' [')[0]}"
        ax.set(xlabel=xlabel, ylabel=_LABELS[name], title=title)
        if deborah:
            k = tau / a0
            top = ax.secondary_xaxis("top", functions=(lambda v, k=k: v * k, lambda d, k=k: d / k))
            top.set_xlabel("v τ / a0")
        ax.grid(alpha=0.3, which="both")
        if others:
            ax.legend(fontsize=7)
        fig.tight_layout()
        paths.append(_save(fig, out_dir, f"sweep_{name}.png"))
    return paths


def _legend(coord: Any, i: int) -> str:
    value = coord.values[i].item() if hasattr(coord.values[i], "item") else coord.values[i]
    text = f"{value:.4g}" if isinstance(value, float) else _fmt(value)
    unit = coord.attrs.get("units", "")
    return f"{_short(coord.attrs.get('key', coord.name))} = {text}{f' {unit}' if unit else ''}"


def _swept_dims(ds: xr.Dataset) -> list[str]:
    return [d for d in ds["mu_app"].dims if d != "t"]


# --- command line ----------------------------------------------------------------------------------
def add_sweep_parser(subparsers: Any) -> argparse.ArgumentParser:
    """Add ``sweep SWEEP.toml --out SWEEP.nc [--scheduler ADDRESS] [--workers N]`` to ``subparsers``."""
    p = subparsers.add_parser("sweep", help="a parameter sweep on a dask cluster (resumable)",
                              description="Run the Cartesian product of the values in SWEEP.toml. "
                              "Run files are kept in SWEEP.runs/; re-running the same command resumes.")
    p.add_argument("sweep", metavar="SWEEP.toml", help="sweep file")
    p.add_argument("--out", required=True, metavar="SWEEP.nc", help="sweep result file (netCDF-4)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="an existing dask scheduler, e.g. tcp://host:8786 "
                   "(default: a local cluster)")
    p.add_argument("--workers", type=int, metavar="N", help=f"local worker processes (default: one per core, "
                   f"{default_workers()} here)")
    p.add_argument("--plots", metavar="DIR", help="also write the sweep figures (PNG) into DIR")
    p.add_argument("--quiet", action="store_true", help="no progress bar, no summary")
    p.set_defaults(func=cli_sweep)
    return p


@dataclass
class _Bar:
    """A tqdm bar on stderr when it is a TTY (and not quiet); silent otherwise."""

    enabled: bool
    bar: Any = None

    def __call__(self, done: int, failed: int, total: int) -> None:
        if not self.enabled:
            return
        if self.bar is None:
            from tqdm import tqdm

            self.bar = tqdm(total=total, file=sys.stderr, unit="run", dynamic_ncols=True, desc="sweep")
        self.bar.set_postfix(done=done, failed=failed, total=total, refresh=False)
        self.bar.update(done + failed - self.bar.n)
        self.bar.refresh()

    def write(self, line: str) -> None:
        if self.bar is not None:
            self.bar.write(line, file=sys.stderr)
        else:
            print(line, file=sys.stderr)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def cli_sweep(args: argparse.Namespace) -> int:
    """``viscontact sweep``: 0 when every run succeeded, 1 when some failed (the sweep file is written
    all the same), 2 on a bad sweep file (one line), 130 when interrupted (finished runs are kept)."""
    started = time.perf_counter()
    bar = _Bar(enabled=not args.quiet and sys.stderr.isatty())
    failures: list[str] = []

    def show(message: Any, category: type, filename: str, lineno: int, file: Any = None, line: Any = None) -> None:
        text = str(message)
        if issubclass(category, ViscontactWarning) and text.startswith("run failed"):
            failures.append(text)
            bar.write(f"viscontact: {text}")
        elif issubclass(category, ViscontactWarning):
            bar.write(f"viscontact: warning: {text}")
        else:
            previous(message, category, filename, lineno, file, line)

    previous = warnings.showwarning
    client = None
    try:
        with warnings.catch_warnings():
            warnings.showwarning = show
            warnings.simplefilter("always", ViscontactWarning)
            if args.workers is not None and args.scheduler:
                raise ParameterError("--workers", "sets the size of a local cluster; leave it out with --scheduler")
            if args.workers is not None and args.workers < 1:
                raise ParameterError("--workers", f"must be >= 1, got {args.workers}")
            spec = load_sweep(args.sweep)
            plan(spec)  # every problem with the sweep file, before connecting to anything
            if args.plots:
                from .plotting import _pyplot

                _pyplot()
            if args.scheduler:
                from distributed import Client

                try:
                    client = Client(args.scheduler, timeout="20s")
                except (OSError, TimeoutError) as exc:
                    raise ParameterError("--scheduler", f"cannot connect to {args.scheduler}: {exc}") from None
            ds = sweep(spec, client=client, out=args.out, progress=bar, workers=args.workers)
    except ParameterError as exc:
        bar.close()
        return _error(f"{exc.key}: {exc.message}", 2)
    except KeyboardInterrupt:
        bar.close()
        return _error(f"interrupted; the finished runs are kept in {runs_dir(args.out)}/ - run the same "
                      "command again to resume", 130)
    except OSError as exc:
        bar.close()
        where = exc.filename if exc.filename is not None else "file"
        return _error(f"{where}: {exc.strerror or exc}", 2)
    finally:
        if client is not None:
            client.close()
    bar.close()
    written = [Path(args.out)]
    if args.plots:
        written += plot_sweep(ds, args.plots)
    if not args.quiet:
        a = ds.attrs
        total = a["runs_computed"] + a["runs_reused"]
        print(f"wrote {', '.join(str(p) for p in written)}: {total} runs ({a['runs_computed']} computed, "
              f"{a['runs_reused']} reused, {a['runs_failed']} failed), {time.perf_counter() - started:.1f} s")
    return 1 if ds.attrs["runs_failed"] else 0


def _error(message: str, status: int) -> int:
    print(f"viscontact: error: {' '.join(message.split())}", file=sys.stderr)
    return status


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m viscontact.sweep SWEEP.toml --out SWEEP.nc`` (the same as ``viscontact sweep``)."""
    parser = argparse.ArgumentParser(prog="viscontact")
    sub = parser.add_subparsers(dest="command", required=True)
    add_sweep_parser(sub)
    args = parser.parse_args(["sweep", *(sys.argv[1:] if argv is None else argv)])
    return cli_sweep(args)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
