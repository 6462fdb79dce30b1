"""Sweep files and plans: which runs a sweep makes, each checked against the case-file keys.

A sweep file names a base case and lists values for any dotted case key; the sweep runs the
Cartesian product of those values::

    base = "../seed_table1_v0.8.toml"    # relative to this file's folder, else to the CWD
    solver = "steady"                    # or "transient"
    [overrides]                          # optional: fixed for every run
    "grid.n" = 64
    [parameters]                         # one dimension per key, in this order
    "tangential.sliding_speed" = [0.002, 0.005, 0.01]
    "material.shear_modulus_long_term" = [0.193e6, 0.386e6]

:func:`load_sweep` reads the file, :func:`plan` validates every run's case and makes the solver's
pre-run checks on it (:func:`check_run`) before anything runs.
"""
from __future__ import annotations

import hashlib
import itertools
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, Sequence

import numpy as np
import tomllib

from viscontact.errors import ParameterError
from viscontact.io.case import case_keys, closest, load_case, read_input_file
from viscontact.io.safe_read import regular_input

__all__ = ["SOLVERS", "Plan", "Run", "SweepSpec", "check_run", "format_value", "load_sweep", "plan",
           "run_file_name"]

#: solvers a sweep may use: ``viscontact.running.api.run_steady`` or ``viscontact.running.api.run``
SOLVERS = ("steady", "transient")
_SWEEP_KEYS = ("title", "base", "solver", "parameters", "overrides")
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
    close = closest(name, valid)
    return f"; did you mean '{close}'?" if close else ""


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
    case: Any  # viscontact.io.case.Case
    name: str
    fingerprint: str

    @property
    def label(self) -> str:
        return ", ".join(f"{k}={format_value(v)}" for k, v in self.overrides.items())


@dataclass(frozen=True)
class Plan:
    spec: SweepSpec
    base: Any  # viscontact.io.case.Case
    base_path: Path
    runs: tuple[Run, ...]
    fixed: dict[str, Any]

    def input_files(self) -> list[Path]:
        """Every file the sweep reads: the sweep file (when read from one), the base case and the
        files any run's case reads (:meth:`viscontact.io.case.Case.input_files`)."""
        files = [Path(self.spec.source)] if self.spec.text else []
        files.append(self.base_path)
        for run in self.runs:
            files.extend(run.case.input_files().values())
        return list(dict.fromkeys(files))


def plan(spec: SweepSpec | str | Path, *, fixed: Mapping[str, Any] | None = None) -> Plan:
    """Check ``spec`` completely and build every run's validated case, computing nothing.

    ``fixed`` are overrides applied to every run after the sweep file's ``[overrides]`` (the sweep
    sets ``solver.workers = 1`` this way unless the sweep file sets it).

    Raises
    ------
    ParameterError
        Unknown solver, missing base case, unknown case key (with the closest valid one), a value
        list that is not a non-empty array of distinct values, or a run whose case is invalid or
        that the solver would refuse before its first step (:func:`check_run`; the message names
        the run's parameters); a steady sweep along a key that the steady solver ignores in every
        run (:func:`viscontact.solvers.steady.ignored_keys`: ``time.dt``, ``tangential.slip``, ...).
    """
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
    from viscontact.solvers.steady import ignored_keys

    keys = list(spec.parameters)
    runs = []
    idle: dict[str, str] | None = None  # the swept keys no run's solver reads so far -> why
    for index in itertools.product(*(range(len(v)) for v in spec.parameters.values())):
        combo = {k: spec.parameters[k][i] for k, i in zip(keys, index)}
        label = ", ".join(f"{k}={format_value(v)}" for k, v in combo.items())
        try:
            case = base.with_overrides({**extra, **combo})
            problem = check_run(case, spec.solver)
        except ParameterError as exc:
            raise ParameterError(exc.key, f"{exc.message} (in the run {label})") from None
        if spec.solver == "steady":
            ignored = ignored_keys(problem)
            idle = {k: ignored[k] for k in (keys if idle is None else idle) if k in ignored}
        runs.append(Run(index, combo, case, run_file_name(combo), run_fingerprint(spec.solver, case)))
    if idle:
        key, why = next(iter(idle.items()))
        raise ParameterError(key, f"the steady solver ignores it ({why}): every value would give the same "
                             "steady state; sweep it with solver = \"transient\", or drop it")
    runs = _unique_names(runs)
    return Plan(spec, base, base_path, tuple(runs), extra)


def check_run(case: Any, solver: str) -> Any:
    """The checks the solver makes before its first step (those of ``viscontact run`` or
    ``viscontact steady``), made here so that a sweep refuses a bad run before any run starts: the
    :func:`~viscontact.running.preflight.preflight` of the run, but this machine's (CuPy, pyFFTW: the
    runs may go to a cluster's workers, each checks its own at its start) and the output's (each run's
    file is the sweep's).

    About 1 ms per run for the steady solver and 6 ms for the transient (the time-step estimate)
    on a 64 x 64 grid. Warnings are not shown here: the run records them when it runs. Returns the
    run's :class:`~viscontact.problem.problem.Problem`.

    Raises
    ------
    ParameterError
        What the run would have been refused with.
    """
    from viscontact.running.preflight import preflight

    return preflight(case, transient=solver == "transient", machine=False, warn=False).problem


def run_fingerprint(solver: str, case: Any) -> str:
    """A hash of everything that shapes a run's result: the solver, the validated case and the
    content of every file it reads (a changed height file makes its runs stale)."""
    digest = hashlib.sha256(f"{solver}\n{case.model_dump_json()}".encode())
    for key, path in case.input_files().items():
        regular_input(path, key)  # a FIFO would block the read
        try:
            digest.update(Path(path).read_bytes())
        except OSError as exc:
            raise ParameterError(key, f"cannot read {path}: {exc.strerror}") from None
    return digest.hexdigest()[:16]


def format_value(value: Any) -> str:
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
    name = "__".join(f"{k}={format_value(v)}" for k, v in overrides.items())
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
