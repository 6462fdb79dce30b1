"""The scripting API: what ``viscontact run`` and ``viscontact steady`` call.

A tiny creep indentation (from the repository's root folder; the shipped case runs at n = 128):

>>> import viscontact as vc
>>> case = vc.load_case("cases/creep_indentation.toml").with_overrides(
...     {"grid.n": 16, "grid.half_width": 1.6e-3, "time.t_end": 5e-4})
>>> ds = vc.run(case)
>>> ds.sizes["t"], int(ds.attrs["complete"]), bool(ds["delta_z"][-1] > ds["delta_z"][0])  # it creeps
(3, 1, True)

and steady frictionless sliding at two speeds [m/s]:

>>> sliding = case.with_overrides({"tangential.mode": "frictionless_sliding", "tangential.sliding_speed": 0.05})
>>> curve = vc.run_steady(sliding, speeds=[0.01, 0.1])
>>> curve["mu_app"].dims, bool(curve["mu_app"][1] > curve["mu_app"][0])
(('speed',), True)
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

import xarray as xr

from .case import Case, load_case
from .errors import ParameterError
from .problem import Problem
from .results import sweep_dataset, to_dataset

__all__ = ["checkpoint_path", "prepare", "run", "run_steady", "steady"]

CaseLike = Case | Problem | str | Path


def prepare(case: CaseLike, *, transient: bool = True) -> tuple[Problem, str]:
    """The problem and the case text of a case file path, a :class:`Case` or a :class:`Problem`,
    after the checks of :func:`viscontact.guards.check_problem` (``transient``: the time step too)."""
    from .guards import check_problem

    if isinstance(case, (str, Path)):
        case = load_case(case)
    if isinstance(case, Case):
        problem, text = case.to_problem(), case.text
    elif isinstance(case, Problem):
        problem, text = case, ""
    else:
        raise TypeError(f"expected a case file path, a Case or a Problem, got {type(case).__name__}")
    check_problem(problem, transient=transient)
    return problem, text


def checkpoint_path(out: str | Path) -> Path:
    """Where ``viscontact run --out OUT --checkpoint-every N`` keeps its checkpoint: ``OUT.checkpoint.npz``."""
    out = Path(out)
    return out.with_name(out.name + ".checkpoint.npz")


def run(case: CaseLike, *, progress: Callable[[int, int], None] | None = None,
        checkpoint: str | Path | None = None, checkpoint_every: int = 0, resume: bool = False,
        should_stop: Callable[[], str | None] | None = None) -> xr.Dataset:
    """Run the transient simulation of ``case`` and return its result Dataset (:ref:`result-file`).

    Parameters
    ----------
    case
        Path of a TOML case file, a :class:`~viscontact.case.Case` or a
        :class:`~viscontact.problem.Problem`.
    progress
        Called as ``progress(steps_done, steps_total)`` after each time step.
    checkpoint, checkpoint_every
        Write the complete solver state and the records so far to ``checkpoint`` (atomically)
        every ``checkpoint_every`` steps, and when the run is stopped.
    resume
        Continue from ``checkpoint`` (written for the same case) instead of starting at t = 0; the
        result equals that of an uninterrupted run.
    should_stop
        Called after every step; a non-empty return (the reason, e.g. ``"SIGINT"``) stops the run
        after that step with :class:`~viscontact.errors.RunInterrupted`.

    Raises
    ------
    ParameterError
        Invalid input (before any step is computed), or a checkpoint of another case.
    ConvergenceError, NumericalGuardError, RunInterrupted, KeyboardInterrupt
        The run stopped. When steps were recorded before, the exception carries the Dataset of
        those steps (attribute ``complete = 0``) as ``exc.partial``.
    """
    from . import transient
    from .checkpoint import load_checkpoint
    from .errors import RunInterrupted
    from .observers import Checkpointer, Recorder, StopRequest, WakeWarning
    from .records import records_from_arrays

    problem, text = prepare(case)
    start, kept = None, []
    if resume:
        if checkpoint is None:
            raise ParameterError("--resume", "needs a checkpoint file")
        start, extra = load_checkpoint(checkpoint, problem)
        kept = records_from_arrays(extra)
    recorder = Recorder(problem, kept)
    observers = [recorder, WakeWarning()]
    if checkpoint is not None:
        observers.append(Checkpointer(checkpoint, problem, recorder, checkpoint_every))
    if should_stop is not None:
        observers.append(StopRequest(should_stop))

    try:
        for state, record in transient.steps(problem, progress=progress, state=start):
            reasons = [r for r in (o.on_step(state, record) for o in observers) if r]
            if reasons:
                for o in observers:
                    o.on_stop(state, reasons[0])
                raise RunInterrupted(reasons[0])
    except BaseException as exc:
        if recorder.records:
            why = getattr(exc, "reason", None) or type(exc).__name__
            exc.partial = to_dataset(recorder.records, problem, case_text=text,  # type: ignore[attr-defined]
                                     attrs={"complete": 0, "stopped_by": why})
        raise
    return to_dataset(recorder.records, problem, case_text=text)


def run_steady(case: CaseLike, speeds: Sequence[float] | None = None) -> xr.Dataset:
    """Steady sliding state(s) of ``case`` (direct steady-state solver).

    Parameters
    ----------
    case
        As for :func:`run`; its tangential mode and friction coefficient apply.
    speeds
        ``None``: one state at ``tangential.sliding_speed``, returned with a ``t`` dimension of
        length 1 (same layout as :func:`run`). A sequence of speeds [m/s]: a Dataset along
        dimension ``speed`` with ``mu_app``, ``peak_pressure``, ``contact_area``,
        ``contact_shift``, ``delta_z``, ``load`` (see :func:`viscontact.results.sweep_dataset`).
    """
    from .steady import solve_steady, speed_sweep

    problem, text = prepare(case, transient=False)
    if speeds is None:
        record = solve_steady(problem)
        return to_dataset([record], problem, case_text=text, attrs={"solver": "steady", "complete": 1})
    speeds = [float(v) for v in speeds]
    return sweep_dataset(speed_sweep(problem, speeds), speeds, problem, case_text=text)


#: short alias of :func:`run_steady` inside this module (``viscontact.steady`` is the solver module)
steady = run_steady
