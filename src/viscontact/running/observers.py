"""Observers of a transient run: what is kept, warned, saved and when the run stops.

:func:`viscontact.running.api.run` is a plain loop over :func:`viscontact.solvers.transient.steps` that hands each
(state, record) to its observers in order. An observer has do-nothing defaults: ``on_step`` returns
``None`` to let the run go on, or a reason (e.g. ``"SIGINT"``) to stop it cleanly after this step;
``on_stop`` is then called on every observer with that reason before
:class:`~viscontact.errors.RunInterrupted` is raised; ``on_finish`` is called on every observer after
the last step of a run that went to its end.

* :class:`Recorder`: keeps every ``output.every``-th step, the last and the histories' turning points,
  with ``output.fields``, in memory (:func:`viscontact.running.api.run`);
* :class:`StreamWriter`: the same records, appended to a streamed result file instead of kept
  (:func:`viscontact.running.api.run_to_file`: memory does not grow with the number of steps);
* :class:`PullOff`: the pull-off force and time of a run with adhesion (result attributes);
* :class:`WakeWarning`: warns when the dropped wake biases the result by over 1 %, and again at the
  end when the bias has grown well beyond what the first warning said;
* :class:`ContactGrowthWarning`: warns once when the contact grows during partial slip under the
  seed's total slip, which has no memory there;
* :class:`Checkpointer`: saves the solver state (with the record count of a streamed run, or the
  records so far of an in-memory one) every N steps and on a stop;
* :class:`StopRequest`: asks a callable after each step whether to stop.
"""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Callable, Sequence

import numpy as np

from viscontact.errors import NumericalGuardError, warn_caller
from viscontact.problem.problem import PHASE_PARTIAL_SLIP, Problem
from viscontact.problem.records import StepRecord

#: estimated relative error from the dropped wake above which a warning is issued
WAKE_WARNING = 0.01
#: growth of that estimate, over the first warning's, above which the end of the run warns again
WAKE_GROWTH = 1.5
#: the same estimate above which the run is stopped (:class:`~viscontact.errors.NumericalGuardError`,
#: the steps done kept): a result that would be mostly the bias is not returned
WAKE_REFUSAL = 0.5
#: growth of the contact area during partial slip, relative to its first area, above which the total
#: slip warns (:class:`ContactGrowthWarning`)
CONTACT_GROWTH = 0.05


class Observer:
    """Do-nothing observer (subclass and override)."""

    def on_step(self, state, record: StepRecord) -> str | None:
        """Called after each step; a non-empty return stops the run with that reason."""
        return None

    def on_stop(self, state, reason: str) -> None:
        """The run stops cleanly after ``state`` (asked by an observer) for ``reason``."""

    def on_finish(self, state) -> None:
        """The run went to its end; ``state`` is the last step's."""


class Recorder(Observer):
    """Keeps the records the output settings ask for (:meth:`Problem.recorded`: step k when
    k % every == 0, the last step and the steps at the histories' turning points), with the fields
    not in ``output.fields`` dropped. ``records`` holds them (``initial`` first)."""

    def __init__(self, problem: Problem, initial: Sequence[StepRecord] = ()) -> None:
        self.problem = problem
        self.dropped = {name: None for name in StepRecord.FIELDS if name not in problem.output.fields}
        self.records: list[StepRecord] = list(initial)
        self.unkept: StepRecord | None = None  # the last step's record, when not kept

    def kept(self, record: StepRecord) -> StepRecord | None:
        """The record as kept, or None when this step is not recorded."""
        if not self.problem.recorded(record.step):
            return None
        return self.final(record)

    def final(self, record: StepRecord) -> StepRecord:
        """The record as kept, recorded or not (the last step of a run that a pull-off ended)."""
        return replace(record, **self.dropped) if self.dropped else record

    def keep(self, record: StepRecord) -> None:
        """Keep a record selected by :meth:`kept` (here: in :attr:`records`)."""
        self.records.append(record)

    def on_step(self, state, record: StepRecord) -> None:
        kept = self.kept(record)
        self.unkept = record if kept is None else None
        if kept is not None:
            self.keep(kept)

    def on_finish(self, state) -> None:
        """A run that a pull-off ended before its last step keeps its last equilibrium too."""
        if self.unkept is not None and getattr(state, "t_pull_off", None) is not None:
            self.keep(self.final(self.unkept))


class StreamWriter(Recorder):
    """A :class:`Recorder` that appends each kept record to ``stream``
    (:class:`~viscontact.io.streaming.ResultStream`: written and flushed when the next one comes) and holds none."""

    def __init__(self, problem: Problem, stream) -> None:
        super().__init__(problem)
        self.stream = stream

    def keep(self, record: StepRecord) -> None:
        self.stream.append(record)


#: a load step at the pull-off above this fraction of the pull-off force is warned (:class:`PullOff`)
PULL_OFF_BRACKET = 0.05


class PullOff(Observer):
    """The pull-off of a run with adhesion (:mod:`viscontact.problem.adhesion`), from its last state:
    :attr:`attrs` are the result's attributes ``pull_off_force`` [N] and ``t_pull_off`` [s] (empty
    without adhesion).

    Under load control the pull-off is the first step no equilibrium carries (the run ends there):
    ``pull_off_force`` is the most tensile load carried (the last equilibrium's, within a load step of
    the pull-off), ``t_pull_off`` that step's time, and the result is ``complete`` (NaN for both when
    the load never pulled it off). Under displacement control the run goes on past the jump-off:
    ``pull_off_force`` is the most tensile load of the run and ``t_pull_off`` its time (NaN when no
    load was tensile)."""

    def __init__(self, problem: Problem) -> None:
        self.problem = problem
        self.attrs: dict[str, float | int] = {}

    def on_finish(self, state) -> None:
        if self.problem.adhesion is None:
            return
        nan = float("nan")
        if state.t_pull_off is not None:
            self.attrs = {"pull_off_force": state.most_tensile_load, "t_pull_off": state.t_pull_off, "complete": 1}
            self._check_bracket(state)
        elif self.problem.normal.control == "displacement" and state.most_tensile_load < 0:
            self.attrs = {"pull_off_force": state.most_tensile_load, "t_pull_off": state.t_most_tensile}
        else:
            self.attrs = {"pull_off_force": nan, "t_pull_off": nan}


    def _check_bracket(self, state) -> None:
        """Warn when the load step at the pull-off exceeds :data:`PULL_OFF_BRACKET` of the pull-off
        force (or the run came off before any tensile load): the pull-off lies anywhere between the
        last load carried and the first one not carried."""
        normal, dt = self.problem.normal, self.problem.time.dt
        carried, failed = float(normal.history(state.t_pull_off - dt)), float(normal.history(state.t_pull_off))
        if state.most_tensile_load < 0 and carried - failed <= PULL_OFF_BRACKET * -state.most_tensile_load:
            return
        unit = "N/m" if self.problem.grid.dimension == 1 else "N"  # the load's unit (per unit length on a line)
        warn_caller(f"time.dt: the run came off in a load step from {carried:.4g} to {failed:.4g} {unit} (t = "
                    f"{state.t_pull_off:.4g} s): the pull-off lies between them; refine the load steps near it "
                    "(a smaller time.dt, or more history points) for a sharper pull-off force")


class WakeWarning(Observer):
    """Stops the run when :attr:`StepRecord.wake_loss` exceeds :data:`WAKE_REFUSAL`; warns when it
    first exceeds :data:`WAKE_WARNING`, and at the end of
    the run with the largest estimate when it exceeds :data:`WAKE_GROWTH` times the first one's (the
    bias grows as the wake lengthens: one first warning of 1.2 % was followed by 12 % at the end)."""

    ADVICE = "enlarge grid.half_width (with grid.n) or use `viscontact steady`"

    def __init__(self) -> None:
        self.first: float | None = None
        self.largest, self.largest_t = 0.0, 0.0

    def on_step(self, state, record: StepRecord) -> None:
        if record.wake_loss > WAKE_REFUSAL:
            raise NumericalGuardError(
                f"history dropped at the trailing edge biases the result by about {100 * record.wake_loss:.2g}% "
                f"at t = {record.t:.4g} s (more than {100 * WAKE_REFUSAL:.0f}%: the result would be mostly that "
                f"bias); {self.ADVICE}")
        if record.wake_loss > self.largest:
            self.largest, self.largest_t = record.wake_loss, record.t
        if self.first is None and record.wake_loss > WAKE_WARNING:
            self.first = record.wake_loss
            warn_caller(
                f"history dropped at the trailing edge biases the result by about {100 * record.wake_loss:.2g}% "
                f"(t = {record.t:.4g} s, growing as the run goes on: see wake_loss); {self.ADVICE}")

    def on_finish(self, state) -> None:
        if self.first is not None and self.largest > WAKE_GROWTH * self.first:
            warn_caller(
                f"history dropped at the trailing edge biased the result by up to about {100 * self.largest:.2g}% "
                f"(t = {self.largest_t:.4g} s; wake_loss in the result); {self.ADVICE}")


class ContactGrowthWarning(Observer):
    """Warns once when, under the seed's total slip (``tangential.slip = "total"``), the contact area
    of a partial-slip step exceeds the first partial-slip contact's by more than
    :data:`CONTACT_GROWTH` (a rising load, creep under a held load; the contact of a held approach
    keeps its area). The total slip forces every point entering the contact to u_x = delta_x, as if
    it had stuck since the contact began: measured on Mindlin-Deresiewicz loadings (nu = 0.5, no
    slip in truth), Q 5-11 % high and a stick ratio of 0.75-0.9 for 1. The first area is that of the
    first step in contact this run saw (a resumed run: after the resume)."""

    def __init__(self, problem: Problem) -> None:
        tan = problem.tangential
        self.watching = tan.mode == "partial_slip" and tan.slip == "total"
        self.first: float | None = None

    def on_step(self, state, record: StepRecord) -> None:
        if not self.watching or record.phase != PHASE_PARTIAL_SLIP or not record.contact_area > 0:
            return
        if self.first is None:
            self.first = record.contact_area
        elif record.contact_area > (1.0 + CONTACT_GROWTH) * self.first:
            self.watching = False
            warn_caller(
                f"the contact grew by {100 * (record.contact_area / self.first - 1):.3g}% during partial slip "
                f"(t = {record.t:.4g} s): the seed's total slip condition (s_x = u_x - delta_x = 0 on the stuck "
                "points) has no memory there and sticks each point entering the contact at u_x = delta_x, "
                "overestimating the friction force and the slip; tangential.slip = \"incremental\" keeps the slip "
                "of each point (Mindlin-Deresiewicz)")


class Checkpointer(Observer):
    """Writes the solver state to ``path`` every ``every`` steps (0: never) and when the run stops
    cleanly (:func:`viscontact.io.checkpoint.save_checkpoint`, atomic), with the arrays ``extra()``
    returns then (how many records the streamed file holds, or the records so far)."""

    def __init__(self, path: str | Path, problem: Problem, every: int = 0,
                 extra: Callable[[], dict[str, np.ndarray]] | None = None) -> None:
        self.path, self.problem, self.every, self.extra = path, problem, every, extra

    def save(self, state) -> None:
        from viscontact.io.checkpoint import save_checkpoint

        save_checkpoint(self.path, self.problem, state, self.extra() if self.extra else None)

    def on_step(self, state, record: StepRecord) -> None:
        if self.every and (state.step + 1) % self.every == 0:
            self.save(state)

    def on_stop(self, state, reason: str) -> None:
        self.save(state)


class StopRequest(Observer):
    """Stops the run when ``should_stop()`` returns a reason (e.g. a signal handler's ``"SIGTERM"``)."""

    def __init__(self, should_stop: Callable[[], str | None]) -> None:
        self.should_stop = should_stop

    def on_step(self, state, record: StepRecord) -> str | None:
        return self.should_stop() or None
