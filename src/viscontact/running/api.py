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

import errno
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

from viscontact.errors import ParameterError
from viscontact.problem.problem import Problem

if TYPE_CHECKING:  # xarray, pandas and pydantic load only where a Dataset or a Case is built
    import xarray as xr

    from viscontact.io.case import Case  # noqa: F401 (CaseLike)
    from viscontact.running.preflight import Preflight

__all__ = ["Written", "checkpoint_path", "prepare", "run", "run_steady", "run_to_file", "steady"]

CaseLike = "Case | Problem | str | Path"


def __getattr__(name: str) -> Any:
    """``Case`` and ``load_case`` of :mod:`viscontact.io.case`, imported on first use (PEP 562): pydantic
    loads for case files, not for a :class:`Problem`."""
    if name in ("Case", "load_case"):
        from viscontact.io import case

        return getattr(case, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def prepare(case: CaseLike, *, transient: bool = True) -> tuple[Problem, str]:
    """The problem and the case text of a case file path, a :class:`Case` or a :class:`Problem`,
    after the checks of :func:`viscontact.running.guards.check_problem` (``transient``: the time step too):
    the :func:`~viscontact.running.preflight.preflight` of a problem to inspect, not yet of a run (neither the
    solver's nor the machine's checks)."""
    from viscontact.running.preflight import preflight

    checked = preflight(case, transient=transient, validate=False, machine=False)
    return checked.problem, checked.text


def _checked(case: CaseLike | Preflight, **checks: Any) -> Preflight:
    """``case`` after its :func:`~viscontact.running.preflight.preflight` with ``checks``, the machine's
    included; the solver's own checks are left to the solver, which makes them before its first step
    (:func:`viscontact.solvers.transient.init`, :func:`viscontact.solvers.steady.solve_steady`). A
    :class:`~viscontact.running.preflight.Preflight` is the caller's, made for this run: not repeated."""
    from viscontact.running.preflight import Preflight, preflight

    return case if isinstance(case, Preflight) else preflight(case, validate=False, **checks)


#: what :func:`checkpoint_path` adds to the result file's name
CHECKPOINT_SUFFIX = ".checkpoint.npz"


def checkpoint_path(out: str | Path) -> Path:
    """Where ``viscontact run --out OUT --checkpoint-every N`` keeps its checkpoint: ``OUT.checkpoint.npz``
    beside the file ``out`` names (beside its target when ``out`` is a symbolic link, as the streamed
    ``OUT.partial`` and the lock: the checks of the names written beside the result are the target's)."""
    from viscontact.io.output_files import link_target

    out = link_target(Path(out))
    return out.with_name(out.name + CHECKPOINT_SUFFIX)


def run(case: CaseLike | Preflight, *, progress: Callable[[int, int], None] | None = None,
        checkpoint: str | Path | None = None, checkpoint_every: int = 0, resume: bool = False,
        should_stop: Callable[[], str | None] | None = None) -> xr.Dataset:
    """Run the transient simulation of ``case`` and return its result Dataset (:ref:`result-file`),
    assembled in memory (every record is held until the end: for long runs :func:`run_to_file`
    streams them to the file instead).

    Parameters
    ----------
    case
        Path of a TOML case file, a :class:`~viscontact.io.case.Case` or a
        :class:`~viscontact.problem.problem.Problem`; or its :class:`~viscontact.running.preflight.Preflight`
        (checks made: not repeated).
    progress
        Called as ``progress(steps_done, steps_total)`` after each time step.
    checkpoint, checkpoint_every
        Write the complete solver state and the records so far to ``checkpoint`` (atomically)
        every ``checkpoint_every`` steps (an integer >= 0; > 0 needs ``checkpoint``), and when the
        run is stopped. An existing file there is
        replaced only when it is empty or a checkpoint (else an error before any step).
    resume
        Continue from ``checkpoint`` (written for the same case) instead of starting at t = 0; the
        result equals that of an uninterrupted run.
    should_stop
        Called after every step; a non-empty return (the reason, e.g. ``"SIGINT"``) stops the run
        after that step with :class:`~viscontact.errors.RunInterrupted`.

    Raises
    ------
    ParameterError
        Invalid input (before any step is computed: :func:`~viscontact.running.preflight.preflight`, the
        machine's checks included), or a checkpoint of another case; or input found unsolvable at a step (partial slip in full contact on a periodic domain:
        :func:`viscontact.solvers.contact_laws.check_not_full_contact`), with the steps done as below.
    FileExistsError, IsADirectoryError
        ``checkpoint`` names a folder or a file that is no checkpoint (a result, a case file).
    ConvergenceError, NumericalGuardError, RunInterrupted, KeyboardInterrupt
        The run stopped. When steps were recorded before, the exception carries the Dataset of
        those steps (attribute ``complete = 0``) as ``exc.partial``.
    """
    from viscontact.io.checkpoint import check_checkpoint_every, check_checkpoint_path, load_checkpoint
    from viscontact.io.results import to_dataset  # xarray: loaded here, not with the package
    from viscontact.problem.records import records_from_arrays, records_to_arrays
    from viscontact.running.loop import drive
    from viscontact.running.observers import Checkpointer, ContactGrowthWarning, PullOff, Recorder, WakeWarning

    check_checkpoint_every(checkpoint_every)
    if checkpoint_every and checkpoint is None:  # no checkpoint would ever be written
        raise ParameterError("checkpoint", f"checkpoint_every = {checkpoint_every} needs the checkpoint file to "
                             "write (checkpoint=PATH)")
    checked = _checked(case)
    problem, text = checked.problem, checked.text
    if checkpoint is not None and not resume:
        check_checkpoint_path(checkpoint)
    start, kept = None, []
    if resume:
        if checkpoint is None:
            raise ParameterError("--resume", "needs a checkpoint file")
        start, extra = load_checkpoint(checkpoint, problem)
        kept = records_from_arrays(extra)
    recorder, pull_off = Recorder(problem, kept), PullOff(problem)
    observers = [recorder, WakeWarning(), ContactGrowthWarning(problem), pull_off]
    if checkpoint is not None:
        observers.append(Checkpointer(checkpoint, problem, checkpoint_every,
                                      extra=lambda: records_to_arrays(recorder.records)))
    try:
        drive(problem, observers, start=start, progress=progress, should_stop=should_stop)
    except BaseException as exc:
        if recorder.records:
            exc.partial = to_dataset(recorder.records, problem, case_text=text,  # type: ignore[attr-defined]
                                     attrs={"complete": 0, "stopped_by": _reason(exc)})
        raise
    return to_dataset(recorder.records, problem, case_text=text, attrs=pull_off.attrs)


class Written(NamedTuple):
    """What :func:`run_to_file` wrote: the result file, how many records (time entries) it holds and,
    with adhesion, the pull-off attributes (:class:`~viscontact.running.observers.PullOff`)."""

    path: Path
    records: int
    pull_off: dict | None = None


def run_to_file(case: CaseLike | Preflight, out: str | Path, *, progress: Callable[[int, int], None] | None = None,
                checkpoint_every: int = 0, resume: bool = False,
                should_stop: Callable[[], str | None] | None = None, history: str = "",
                require_space: bool = True, finishing: Callable[[], None] | None = None,
                force: bool = False) -> Written:
    """Run the transient simulation of ``case``, streaming each record to the result file ``out``.

    Memory does not grow with the number of steps. The records go to ``OUT.partial`` as the run
    goes (valid netCDF after a kill at any moment, ``complete = 0``), renamed over ``out`` when the
    run is complete (:mod:`viscontact.io.streaming`). An existing ``out`` is replaced only with
    ``force`` (or ``resume``), and then only when it is a netCDF result, never a file the case reads
    (:func:`viscontact.io.output_files.check_output_path`, checked before any step).

    Parameters
    ----------
    case, progress, should_stop
        As for :func:`run`; a :class:`~viscontact.running.preflight.Preflight` made for ``out`` (with
        the same ``force`` and ``resume``).
    out
        The result file (netCDF-4).
    history
        Appended to the file's ``history`` attribute (e.g. the command that ran it).
    checkpoint_every
        Write the solver state to :func:`checkpoint_path` (atomically) every ``checkpoint_every``
        steps (0: never), and when the run is stopped. The checkpoint holds the solver state only;
        the records are in the streamed file.
    resume
        Continue from the checkpoint (written for the same case) and its streamed file (``OUT.partial``,
        or an incomplete ``out`` left by a clean stop; written for the same case too: its
        ``problem_fingerprint``), dropping the records after the checkpoint's step: the result
        equals that of an uninterrupted run, bit for bit. Without ``resume``, a checkpoint left by
        an earlier run is removed once this run's streamed file is created (it could only be
        resumed with the streamed file this run replaces).
    require_space
        The disk space of every record still to come is claimed before the first step
        (:class:`~viscontact.io.output_files.SpaceClaim`); True: a disk that cannot hold it is an
        error before any step, False (``--force``): run anyway. Either way a disk that fills stops
        the run between two records with one ``ENOSPC`` error, the steps done kept.
    finishing
        Called once the steps are done (or stopped), before the file is finished and renamed
        (the command line then only records signals, so that the write completes).
    force
        Replace an existing result ``out`` (``--force``); it is kept until the new result is
        complete.

    Returns
    -------
    Written
        ``out`` and the number of records. The checkpoint is removed once ``out`` is complete.

    Raises
    ------
    ParameterError
        Invalid input (before any step is computed), a checkpoint of another case, or a streamed
        file to resume that is missing, unreadable or written for another case
        (:func:`viscontact.io.streaming.check_resumable`; the file is left as it was); or input found
        unsolvable at a step (partial slip in full contact on a periodic domain:
        :func:`viscontact.solvers.contact_laws.check_not_full_contact`), with the steps done kept as below.
    BlockingIOError
        Another process writes ``out`` (:func:`viscontact.io.output_files.output_lock`, held for the
        whole run).
    FileExistsError, IsADirectoryError
        ``out`` exists and neither ``force`` nor ``resume`` is given, or it is a folder, a file that
        is no netCDF result or a file the case reads (even with ``force``); or ``OUT.partial`` is a
        folder or not a regular file (:func:`viscontact.io.streaming.check_partial_path`).
    OSError
        The result cannot be written: ``ENOSPC`` naming the file, the size needed and the space
        free (before the first step, or between two records with the steps done kept as below).
    OutputReplacedError
        Another process replaced ``OUT.partial`` under the run (its lock file was removed): nothing
        is renamed to ``out``; the run's own file is kept as ``OUT.orphan-PID.nc`` where it can be
        copied (``exc.kept``).
    ConvergenceError, NumericalGuardError, RunInterrupted, KeyboardInterrupt
        The run stopped. When steps were recorded, they are in the file (``complete = 0``,
        ``stopped_by``) named by ``exc.saved = (path, records)``: ``out``, or ``OUT.partial`` when
        ``out`` holds a complete result (never replaced by an incomplete one).
    """
    from viscontact.io.checkpoint import check_checkpoint_every, check_checkpoint_path, load_checkpoint
    from viscontact.io.output_files import link_target, output_lock
    from viscontact.io.streaming import ResultStream, is_complete_result, partial_path
    from viscontact.problem.records import records_from_arrays

    check_checkpoint_every(checkpoint_every)
    out = Path(out)
    with output_lock(out):
        checked = _checked(case, out=out, force=force, resume=resume)
        problem, text = checked.problem, checked.text
        partial, checkpoint = partial_path(out), checkpoint_path(out)
        if not resume:  # removed once the streamed file is created: only an earlier run's checkpoint
            check_checkpoint_path(checkpoint)
        start, extra = None, {}
        if resume:
            start, extra = load_checkpoint(checkpoint, problem)
        if resume and "records" in extra:  # the records so far are in the streamed file
            published = not partial.exists() and out.exists() and not is_complete_result(out)  # by a clean stop
            stream = ResultStream.reopen(partial, problem, int(extra["records"]), require_space=require_space,
                                         source=link_target(out) if published else None, history=history)
        else:
            stream = ResultStream.create(partial, problem, case_text=text, history=history,
                                         require_space=require_space)
            if not resume:  # a checkpoint of an earlier run: its streamed file was just replaced, or is stale
                checkpoint.unlink(missing_ok=True)
            for record in records_from_arrays(extra):  # resuming from a checkpoint of :func:`run`: its records
                stream.append(record)
        return _stream_run(problem, stream, out, checkpoint, checkpoint_every=checkpoint_every, resume=resume,
                           start=start, progress=progress, should_stop=should_stop, finishing=finishing)


def _stream_run(problem: Problem, stream: Any, out: Path, checkpoint: Path, *, checkpoint_every: int, resume: bool,
                start: Any, progress: Callable[[int, int], None] | None,
                should_stop: Callable[[], str | None] | None, finishing: Callable[[], None] | None) -> Written:
    """The steps of :func:`run_to_file` into the open ``stream``, its end (finished and renamed to
    ``out``, or stopped: :func:`_stopped`) and the removal of the checkpoint once ``out`` is complete."""
    import numpy as np

    from viscontact.running.loop import drive
    from viscontact.running.observers import Checkpointer, ContactGrowthWarning, PullOff, StreamWriter, WakeWarning

    pull_off = PullOff(problem)
    observers = [StreamWriter(problem, stream), WakeWarning(), ContactGrowthWarning(problem), pull_off]
    if checkpoint_every or resume:
        observers.append(Checkpointer(checkpoint, problem, checkpoint_every,
                                      extra=lambda: {"records": np.array(stream.drain())}))
    try:
        drive(problem, observers, start=start, progress=progress, should_stop=should_stop)
    except BaseException as exc:
        if finishing is not None:
            finishing()
        exc.saved = _stopped(stream, out, _reason(exc))  # type: ignore[attr-defined]
        raise
    if finishing is not None:
        finishing()
    stream.finish(pull_off.attrs)
    stream.publish(out)
    checkpoint.unlink(missing_ok=True)
    return Written(out, stream.count, pull_off.attrs or None)


def _stopped(stream: Any, out: Path, reason: str) -> tuple[Path, int] | None:
    """End the streamed file of a run stopped for ``reason`` (``complete = 0``, ``stopped_by``) and
    publish it as ``out`` unless ``out`` is a complete result. Returns (where, records), or None
    (and no file) when no record was written.

    Raises
    ------
    OutputReplacedError
        Another process replaced the streamed file (:meth:`~viscontact.io.streaming.ResultStream.publish`).
    """
    from viscontact.errors import OutputReplacedError
    from viscontact.io.streaming import is_complete_result

    if not stream.broken:
        try:
            stream.drain()  # the record still queued
        except Exception:  # noqa: BLE001 - its write failed: the file holds the records before it
            pass
    if stream.broken:  # a write failed and so did saving the file: it holds its last flush (complete = 0)
        return stream.path, stream.count
    if stream.count == 0:
        own = stream.owned()
        stream.close()
        if own:  # never another process's file renamed over it
            stream.path.unlink(missing_ok=True)
        return None
    try:
        stream.finish({"complete": 0, "stopped_by": reason})
    except OutputReplacedError:
        raise
    except Exception:  # noqa: BLE001 - interrupted inside a write: the file holds the last flush
        stream.close()
        return stream.path, stream.count
    if out.exists() and is_complete_result(out):
        stream.close()
        return stream.path, stream.count
    stream.publish(out)
    return out, stream.count


def _reason(exc: BaseException) -> str:
    """Attribute ``stopped_by`` of a run ended by ``exc``: its reason (a signal), the error's code
    (``ENOSPC``) or its type."""
    code = errno.errorcode.get(exc.errno, "") if isinstance(exc, OSError) and exc.errno else ""
    return getattr(exc, "reason", None) or code or type(exc).__name__


def run_steady(case: CaseLike | Preflight, speeds: Sequence[float] | None = None,
               creepages: Sequence[float] | None = None) -> xr.Dataset:
    """Steady sliding or rolling state(s) of ``case`` (direct steady-state solvers).

    Parameters
    ----------
    case
        As for :func:`run`; its tangential mode and friction coefficient apply.
    speeds
        ``None``: one state at ``tangential.sliding_speed``, returned with a ``t`` dimension of
        length 1 (same layout as :func:`run`). A sequence of speeds [m/s]: a Dataset along
        dimension ``speed`` with ``mu_app``, ``peak_pressure``, ``contact_area``,
        ``contact_shift``, ``delta_z``, ``load`` (see :func:`viscontact.io.results.sweep_dataset`).
    creepages
        Rolling (``tangential.mode = "rolling"``, :mod:`viscontact.solvers.steady_rolling`): a sequence
        of creepages [-], the traction-creepage curve at ``tangential.rolling_speed``: a Dataset along
        dimension ``creepage`` (:func:`viscontact.io.results.creepage_dataset`). ``None``: one rolling
        state at the case's creepage or tangential force.

    Raises
    ------
    ParameterError
        Invalid input, before any solve: the case's (:func:`~viscontact.running.preflight.preflight`), or ``speeds`` not a non-empty list of finite
        numbers > 0 m/s, each given once (key ``speeds``).
    """
    from viscontact.io.results import sweep_dataset, to_dataset
    from viscontact.io.values import positive_values
    from viscontact.solvers.steady import solve_steady, speed_sweep

    checked = _checked(case, transient=False)
    problem, text = checked.problem, checked.text
    if problem.tangential.rolls or creepages is not None:
        return _run_steady_rolling(problem, text, speeds, creepages)
    if speeds is None:
        record = solve_steady(problem)
        return to_dataset([record], problem, case_text=text, attrs={"solver": "steady", "complete": 1})
    speeds = positive_values(speeds, "speeds", "m/s")
    return sweep_dataset(speed_sweep(problem, speeds), speeds, problem, case_text=text)


def _run_steady_rolling(problem, text: str, speeds: Sequence[float] | None,
                        creepages: Sequence[float] | None) -> xr.Dataset:
    """:func:`run_steady` of a rolling case: one state, or the traction-creepage curve."""
    from viscontact.errors import ParameterError
    from viscontact.io.results import creepage_dataset, to_dataset
    from viscontact.io.values import positive_values
    from viscontact.solvers.steady_rolling import check_steady_rolling, creepage_sweep, solve_steady_rolling

    if speeds is not None:
        raise ParameterError("speeds", "a rolling case takes creepages (--creepages), not speeds: give "
                             "tangential.rolling_speed")
    check_steady_rolling(problem)
    if creepages is None:
        record = solve_steady_rolling(problem)
        return to_dataset([record], problem, case_text=text, attrs={"solver": "steady", "complete": 1})
    creepages = positive_values(creepages, "creepages", "(creepage, -)", signed=True)
    return creepage_dataset(creepage_sweep(problem, creepages), creepages, problem, case_text=text)


#: short alias of :func:`run_steady` inside this module (``viscontact.solvers.steady`` is the solver module)
steady = run_steady
