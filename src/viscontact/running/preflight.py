"""The one preflight: every check made before a run computes its first step or writes its first byte.

:func:`preflight` is what the scripting API (:mod:`viscontact.running.api`), the command line
(``viscontact run``, its ``--dry-run``, ``viscontact steady``) and the sweeps' plans
(:func:`viscontact.sweep.spec.check_run`) call; each asks for the checks that apply to it. In order:

1. the case: a case file is read and validated (:func:`viscontact.io.case.load_case`);
2. the output (with ``out``): the result file may be written, and replaced only with ``force`` or
   ``resume``, never a file the case reads (:func:`viscontact.io.output_files.check_output_path`);
   for a transient run the streamed ``OUT.partial`` beside it must be a file
   (:func:`viscontact.io.streaming.check_partial_path`), and with ``interrupted`` an interrupted run's
   steps there are not thrown away unless forced or resumed;
3. the resources (with ``resources``): the material's creep spectrum is finite
   (:func:`viscontact.running.guards.check_material`), then the result's disk space, the peak memory and
   the run time against the machine, estimated from the case's outline before any n x n array
   (:func:`viscontact.running.resources.check_resources`);
4. the physics: can the answer be trusted (:func:`viscontact.running.guards.check_problem`);
5. the solver (with ``validate``): the transient solver's checks across the problem's parts
   (:func:`viscontact.solvers.transient.validate`) or the steady solver's
   (:func:`viscontact.solvers.steady.check_steady`);
6. the machine (with ``machine``): the case's settings describe a run, this machine must be able to
   make it: ``solver.device = "gpu"`` needs CuPy and a CUDA device
   (:func:`viscontact.numerics.arrays.array_backend`), ``solver.fft = "pyfftw"`` needs pyFFTW
   (:func:`viscontact.numerics.fftbackends.check_fft_backend`). A sweep's plan leaves this to each run
   (its runs may go to a cluster's workers); a case for a GPU loads, validates, is estimated and
   fingerprinted anywhere.

The first failed check raises, naming the key or the file; the command line prints it as one line
and exits with status 2 before anything is written. ``viscontact run --dry-run`` makes the same
checks as the run, the machine's included: on a machine without CuPy a GPU case's dry run is refused
in the same line as its run would be there.
"""
from __future__ import annotations

import errno
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from viscontact.errors import ViscontactWarning
from viscontact.problem.problem import Problem

if TYPE_CHECKING:  # pydantic loads only where a Case is built
    from viscontact.io.case import Case  # noqa: F401
    from viscontact.running.resources import Estimate

__all__ = ["Preflight", "check_machine", "preflight"]


@dataclass(frozen=True)
class Preflight:
    """What :func:`preflight` checked: the run is ready to start.

    Attributes
    ----------
    problem
        The problem to solve.
    text
        The case file's text ('' for a :class:`~viscontact.problem.problem.Problem`), kept in the result.
    transient
        Checked for the transient solver (else the steady one).
    estimate
        The resource estimate (:class:`~viscontact.running.resources.Estimate`) with ``resources``, else None.
    warnings
        The :class:`~viscontact.errors.ViscontactWarning` messages of the checks, with ``warn=False``
        (they were not shown); empty otherwise (they were issued as they arose).
    """

    problem: Problem
    text: str = ""
    transient: bool = True
    estimate: Estimate | None = None
    warnings: tuple[str, ...] = ()


def preflight(case: Any, *, transient: bool = True, out: str | Path | None = None, force: bool = False,
              resume: bool = False, checkpoints: bool = False, inputs: Sequence[str | Path] = (),
              interrupted: bool = False, resources: bool = False, validate: bool = True, machine: bool = True,
              warn: bool = True) -> Preflight:
    """Check a run before it starts (the module's steps 1-6) and return what it needs.

    Parameters
    ----------
    case
        Path of a TOML case file, a :class:`~viscontact.io.case.Case` or a
        :class:`~viscontact.problem.problem.Problem`.
    transient
        For the transient solver (also the time step and the steps' end); False: the steady solver.
    out
        The result file the run writes; None: no output checks (a run in memory).
    force, resume
        Replace an existing result ``out`` (``resume``: the one the interrupted run left); ``force``
        also turns the resource refusals into warnings.
    checkpoints
        The run writes checkpoints beside ``out`` (their disk space counted).
    inputs
        Files the result must not replace besides those the case reads (the case file of a
        :class:`Case`; a case file path given as ``case`` is counted itself).
    interrupted
        Refuse an ``OUT.partial`` left by an interrupted run unless ``force`` or ``resume`` (the
        command line; the API replaces it).
    resources
        Estimate the run's disk, memory and time and check them against the machine (needs ``out``).
    validate
        Make the solver's own checks (for the steady solver: at the case's sliding speed).
    machine
        Check that this machine can run it (the packages and the device of ``solver.device`` and
        ``solver.fft``); False for a plan whose runs may go elsewhere.
    warn
        Issue the checks' warnings (attributed to the caller's line); False: record them in
        :attr:`Preflight.warnings` only.

    Raises
    ------
    ParameterError
        Invalid input, naming the key to change.
    FileExistsError, IsADirectoryError, OSError
        The result file may not be written (:func:`viscontact.io.output_files.check_output_path`).
    """
    if warn:
        return _preflight(case, transient, out, force, resume, checkpoints, inputs, interrupted, resources, validate,
                          machine)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", ViscontactWarning)
        found = _preflight(case, transient, out, force, resume, checkpoints, inputs, interrupted, resources,
                           validate, machine)
    for w in caught:  # others pass on as they were
        if not issubclass(w.category, ViscontactWarning):
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, source=w.source)
    return Preflight(found.problem, found.text, found.transient, found.estimate,
                     tuple(str(w.message) for w in caught if issubclass(w.category, ViscontactWarning)))


def _preflight(case: Any, transient: bool, out: str | Path | None, force: bool, resume: bool, checkpoints: bool,
               inputs: Sequence[str | Path], interrupted: bool, resources: bool, validate: bool,
               machine: bool) -> Preflight:
    """:func:`preflight`'s checks, its warnings issued as they arise."""
    from viscontact.running.guards import check_problem

    case, inputs = _load(case, inputs)
    written = _check_output(out, inputs, force=force, resume=resume, interrupted=interrupted, transient=transient)
    estimate = None
    if resources:
        from viscontact.running.guards import check_material
        from viscontact.running.resources import check_resources

        if out is None:
            raise TypeError("preflight: resources=True needs the result file out")
        outline = case if isinstance(case, Problem) else case.problem_outline()  # before any n x n array
        check_material(outline.material)  # the estimate reads its creep spectrum
        estimate = check_resources(outline, out, force=force, checkpoints=checkpoints, written_bytes=written)
    problem, text = (case, "") if isinstance(case, Problem) else (case.to_problem(), case.text)
    check_problem(problem, transient=transient)
    if validate:
        _check_solver(problem, transient)
    if machine:
        check_machine(problem)
    return Preflight(problem, text, transient, estimate)


def _load(case: Any, inputs: Sequence[str | Path]) -> tuple[Any, list[Path]]:
    """The :class:`Case` (read from its file) or :class:`Problem` of ``case``, and every file the result
    may not replace: ``inputs``, the case file, the files the case reads."""
    inputs = [Path(p) for p in inputs]
    if isinstance(case, Problem):
        return case, inputs
    from viscontact.io.case import Case, load_case  # pydantic: only for case files and Case objects

    if isinstance(case, (str, Path)):
        inputs.append(Path(case))
        case = load_case(case)
    if not isinstance(case, Case):
        raise TypeError(f"expected a case file path, a Case or a Problem, got {type(case).__name__}")
    return case, [*inputs, *case.input_files().values()]


def _check_output(out: str | Path | None, inputs: list[Path], *, force: bool, resume: bool, interrupted: bool,
                  transient: bool) -> int:
    """Step 2 of :func:`preflight`; returns the bytes a resumed run's streamed file holds already."""
    if out is None:
        return 0
    from viscontact.io.output_files import check_output_path

    check_output_path(out, force=force or resume, inputs=inputs)
    if not transient:
        return 0
    from viscontact.io.streaming import check_partial_path

    partial = check_partial_path(out)  # a folder there is in the way, not an interrupted run's steps
    if interrupted and partial.exists() and not (force or resume):
        raise FileExistsError(errno.EEXIST, "holds the steps of an interrupted run: --resume continues it (with its "
                              "checkpoint), --force starts over", str(partial))
    return partial.stat().st_size if resume and partial.exists() else 0  # a resume's records so far


def _check_solver(problem: Problem, transient: bool) -> None:
    """Step 5 of :func:`preflight`: the checks the solver makes before its first step."""
    if transient:
        from viscontact.running.guards import check_sliding_step
        from viscontact.solvers.transient import validate

        check_sliding_step(problem)  # a time.dt that sliding refuses: with the steps_per_cell that works
        validate(problem)
    else:
        from viscontact.solvers.steady import check_steady

        check_steady(problem)


def check_machine(problem: Problem) -> None:
    """Refuse a run that this machine cannot make (step 6 of :func:`preflight`): the array backend of
    ``solver.device`` (for ``"gpu"``: CuPy installed and a CUDA device found) and the FFT library of
    ``solver.fft`` (``"pyfftw"``: pyFFTW installed).

    Raises
    ------
    ParameterError
        One line naming ``solver.device`` or ``solver.fft``, what is missing and how to install it.
    """
    from viscontact.numerics.arrays import array_backend
    from viscontact.numerics.fftbackends import check_fft_backend

    array_backend(problem.solver.device)
    check_fft_backend(problem.solver.fft)
