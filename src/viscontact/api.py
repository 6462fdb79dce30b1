"""The scripting API: what ``viscontact run`` and ``viscontact steady`` call.

>>> import viscontact as vc
>>> ds = vc.run("cases/creep_indentation.toml")                 # doctest: +SKIP
>>> ds.contact_area.plot()                                       # doctest: +SKIP
>>> sweep = vc.run_steady("cases/...toml", speeds=[0.01, 0.1, 1.0])  # doctest: +SKIP
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

import xarray as xr

from .case import Case, load_case
from .problem import Problem
from .results import sweep_dataset, to_dataset

__all__ = ["prepare", "run", "run_steady", "steady"]

CaseLike = Case | Problem | str | Path


def prepare(case: CaseLike) -> tuple[Problem, str]:
    """The problem and the case text of a case file path, a :class:`Case` or a :class:`Problem`."""
    if isinstance(case, (str, Path)):
        case = load_case(case)
    if isinstance(case, Case):
        return case.to_problem(), case.text
    if isinstance(case, Problem):
        return case, ""
    raise TypeError(f"expected a case file path, a Case or a Problem, got {type(case).__name__}")


def run(case: CaseLike, *, progress: Callable[[int, int], None] | None = None) -> xr.Dataset:
    """Run the transient simulation of ``case`` and return its result Dataset (SPEC §3).

    Parameters
    ----------
    case
        Path of a TOML case file, a :class:`~viscontact.case.Case` or a
        :class:`~viscontact.problem.Problem`.
    progress
        Called as ``progress(steps_done, steps_total)`` after each time step.

    Raises
    ------
    ParameterError
        Invalid input (before any step is computed).
    ConvergenceError, NumericalGuardError, KeyboardInterrupt
        The run stopped. When steps were recorded before, the exception carries the Dataset of
        those steps (attribute ``complete = 0``) as ``exc.partial``.
    """
    from .transient import simulate

    problem, text = prepare(case)
    records = []
    try:
        for record in simulate(problem, progress=progress):
            records.append(record)  # noqa: PERF402 - a loop keeps the steps done if one fails
    except BaseException as exc:
        if records:
            exc.partial = to_dataset(records, problem, case_text=text)  # type: ignore[attr-defined]
        raise
    return to_dataset(records, problem, case_text=text)


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

    problem, text = prepare(case)
    if speeds is None:
        record = solve_steady(problem)
        return to_dataset([record], problem, case_text=text, attrs={"solver": "steady", "complete": 1})
    speeds = [float(v) for v in speeds]
    return sweep_dataset(speed_sweep(problem, speeds), speeds, problem, case_text=text)


#: short alias of :func:`run_steady` inside this module (``viscontact.steady`` is the solver module)
steady = run_steady
