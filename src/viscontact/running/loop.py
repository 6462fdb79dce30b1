"""The run loop: one loop over the transient's steps that hands each step to observers.

:func:`observed_steps` is the loop; :func:`drive` runs it to the end for the API's runs (records
kept or streamed by the observers); :func:`simulate` yields the records the output settings keep,
for scripts and tests. Each step's physics is :func:`viscontact.solvers.transient.step`.
"""
from __future__ import annotations

from typing import Any, Callable, Iterator, Sequence

from viscontact.errors import RunInterrupted
from viscontact.problem.problem import Problem
from viscontact.problem.records import StepRecord
from viscontact.running.observers import ContactGrowthWarning, Observer, Recorder, StopRequest, WakeWarning
from viscontact.solvers import transient


def observed_steps(problem: Problem, observers: Sequence[Observer], *, start: Any = None,
                   progress: Callable[[int, int], None] | None = None,
                   should_stop: Callable[[], str | None] | None = None,
                   compliance: Any = None) -> Iterator[tuple[Any, StepRecord]]:
    """The run: each (state, record) of :func:`viscontact.solvers.transient.steps` handed to the
    ``observers`` (:mod:`viscontact.running.observers`) and then yielded; stops cleanly with
    :class:`~viscontact.errors.RunInterrupted` when one of them (or ``should_stop``) asks, and tells
    them when the run went to its end.

    Parameters
    ----------
    problem
        What to solve.
    observers
        Told of every step (:meth:`~viscontact.running.observers.Observer.on_step`), of a stop and of the end.
    start, compliance
        Resume from a state (a checkpoint's) / reuse a body's compliance.
    progress
        Called as ``progress(steps_done, steps_total)`` after each step.
    should_stop
        Asked after each step; a reason stops the run.

    Notes
    -----
    A run with adhesion under load control ends at the pull-off (the first step no equilibrium
    carries): the observers are told ``on_finish`` with the last equilibrium's state, whose
    ``t_pull_off`` is set (:func:`viscontact.solvers.transient.steps`).
    """
    if should_stop is not None:
        observers = [*observers, StopRequest(should_stop)]
    state = start
    run = transient.steps(problem, progress=progress, state=start, compliance=compliance)
    while True:
        try:
            state, record = next(run)
        except StopIteration as end:  # the end, or the pull-off (adhesion under load control)
            state = state if end.value is None else end.value
            break
        reasons = [r for r in (o.on_step(state, record) for o in observers) if r]
        if reasons:
            for o in observers:
                o.on_stop(state, reasons[0])
            raise RunInterrupted(reasons[0])
        yield state, record
    for o in observers:
        o.on_finish(state)


def drive(problem: Problem, observers: Sequence[Observer], *, start: Any = None,
          progress: Callable[[int, int], None] | None = None,
          should_stop: Callable[[], str | None] | None = None) -> None:
    """Run :func:`observed_steps` to its end (what is kept is the observers')."""
    for _ in observed_steps(problem, observers, start=start, progress=progress, should_stop=should_stop):
        pass


def simulate(problem: Problem, *, progress: Callable[[int, int], None] | None = None,
             state: Any = None, compliance: Any = None) -> Iterator[StepRecord]:
    """Run the transient and yield the records the output settings keep (every ``output.every``
    steps, the last and the histories' turning points, with the ``output.fields``), warning about a
    biasing wake (:class:`~viscontact.running.observers.WakeWarning`) and a contact growing under the
    total slip (:class:`~viscontact.running.observers.ContactGrowthWarning`).

    Parameters are those of :func:`viscontact.solvers.transient.steps`.
    """
    recorder = Recorder(problem)
    observers = [WakeWarning(), ContactGrowthWarning(problem)]
    record = kept = None
    for _, record in observed_steps(problem, observers, start=state, progress=progress, compliance=compliance):
        kept = recorder.kept(record)
        if kept is not None:
            yield kept
    if record is not None and kept is None:  # a pull-off ended the run: its last equilibrium is kept
        yield recorder.final(record)
