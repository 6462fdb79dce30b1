"""``viscontact`` command line: a thin shell over :mod:`viscontact.running.api`.

Bad input (an option, case file, missing file, existing result) prints one line
``viscontact: error: <key>: <message>`` and exits with status 2 (argparse's own errors too:
:class:`~viscontact.cli.parser.Parser`; input found unsolvable during a run, such as partial slip reaching full contact
on a periodic domain, keeps the steps done and says where); a failed solve (no convergence,
numerical guard) exits with status 1, keeping the steps done in the result file (``complete = 0``); a run
out of memory (numpy's ``MemoryError``, CuPy's on the device) is one line and status 2, the steps done kept.
SIGINT / SIGTERM stop a run after its current step, keep the steps done (``complete = 0``) and
exit with 130 / 143. ``run`` streams its records to ``RESULT.nc.partial`` and renames it to
``RESULT.nc`` when it ends (:mod:`viscontact.io.streaming`); after a kill the steps done are in
``RESULT.nc.partial``. ``run``, ``steady`` and ``sweep`` lock their result file
(:func:`viscontact.io.output_files.output_lock`) before checking it: a second command writing the same
file is refused in one line (should the lock file be removed under a run and another run replace
its ``RESULT.nc.partial``, the first renames nothing, keeps its own file as
``RESULT.nc.orphan-PID.nc`` and exits with status 1). Every sub-command takes ``--quiet`` (no
progress bar, summary or warnings) and ``--log-level`` (the messages of the ``viscontact`` logger
shown on stderr; warnings are at level ``warning``).

This module holds :func:`main` (the one error path) and the sub-commands' handlers; beside it
:mod:`viscontact.cli.parser` (the argparse parser, light: ``viscontact --help`` loads no solver),
:mod:`viscontact.cli.arguments` (what the argument values mean), :mod:`viscontact.cli.output`
(messages, warnings and the progress bar on stderr) and :mod:`viscontact.cli.signals` (SIGINT / SIGTERM).
Every check before a run is the one preflight's (:func:`viscontact.running.preflight.preflight`).
"""
from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from viscontact.cli.arguments import check_result_name, command_line, parse_overrides, parse_positive
from viscontact.cli.output import PROG, configure_logging, error, log, progress_bar, say, warnings_as_lines
from viscontact.cli.parser import build_parser as _parser  # the name tests replace
from viscontact.cli.parser import cli_version
from viscontact.cli.signals import interrupts_redelivered, stop_on_signals
from viscontact.errors import (
    EXIT_INTERRUPTED,
    ConvergenceError,
    NumericalGuardError,
    OutputReplacedError,
    ParameterError,
    RunInterrupted,
    raised_by_interrupt,
)

__all__ = ["EXIT_FAILED", "EXIT_TERMINATED", "EXIT_USAGE", "PROG", "main"]

EXIT_FAILED, EXIT_USAGE, EXIT_TERMINATED = 1, 2, 143


def _check_figures(args: argparse.Namespace, option: str = "--plots", files: Sequence[str] | None = None) -> None:
    """Before any computing: the figure options are valid, matplotlib imports and the folder of the
    figures, given by ``option`` (``--plots`` of the commands that have one, ``--out`` of ``plot``),
    can be made and is none of ``files`` (default: the result file ``--out``)."""
    from viscontact.io.output_files import check_output_folder
    from viscontact.plotting import check_format, pyplot

    check_format(args.fmt, args.dpi)
    pyplot()
    folder = getattr(args, option.removeprefix("--"), None)
    if folder:
        check_output_folder(folder, option=option, files=[args.out] if files is None else files)


def _load(args: argparse.Namespace) -> Any:
    """The case file ``args.case`` with the ``--set`` overrides applied."""
    from viscontact.io.case import load_case

    case = load_case(args.case)
    overrides = parse_overrides(args.overrides)
    return case.with_overrides(overrides) if overrides else case


@contextmanager
def _writing(out: str, derived: Sequence[str] = ()) -> Iterator[None]:
    """While the body runs, this process alone writes the result file ``out`` (a ``*.nc`` name):
    :func:`viscontact.io.output_files.output_lock`, which first checks the names of the files
    ``derived`` (suffixes) written beside it. Enter it before ``out`` is checked."""
    from viscontact.io.output_files import output_lock

    check_result_name(out)
    with output_lock(out, derived):
        yield


def _prepare(args: argparse.Namespace) -> Any:
    """The :class:`~viscontact.running.preflight.Preflight` of the case with its overrides for the result
    file ``--out``, after checking that plotting is available (inside :func:`_writing`), before any
    computing: for ``run`` (its ``--dry-run`` too) with its resource estimate, refusing to throw away an
    interrupted run's steps; for ``steady`` the steady solver's checks."""
    from viscontact.running.preflight import preflight

    case = _load(args)
    if args.plots:
        _check_figures(args)
    checks: dict[str, bool] = ({"checkpoints": bool(args.checkpoint_every), "interrupted": True, "resources": True}
                               if args.command == "run" else  # steady: each speed of a curve checked by the solver
                               {"transient": False, "validate": args.speeds is None})
    return preflight(case, out=args.out, force=args.force, resume=getattr(args, "resume", False),
                     inputs=[args.case], **checks)


def _finish(ds: Any, args: argparse.Namespace, started: float) -> None:
    """Write the result ``ds`` of a command computed in memory, then :func:`_report`."""
    from viscontact.io.netcdf import write_netcdf

    ds.attrs["history"] = f"{ds.attrs.get('history', '')} {_history_note(args)}".strip()
    write_netcdf(ds, args.out, force=args.force)
    _report(ds, next((ds.sizes[d] for d in ("t", "speed", "creepage") if d in ds.sizes), 0), args, started)


def _history_note(args: argparse.Namespace) -> str:
    """``by the command: viscontact ...`` for the result's ``history`` attribute ('' when unknown)."""
    return f"by the command: {PROG} {command_line(args.argv)}" if getattr(args, "argv", None) is not None else ""


def _report(ds: Any, records: int, args: argparse.Namespace, started: float) -> None:
    """Draw the figures of the result ``ds`` (with ``--plots``) and print what was written."""
    written = [Path(args.out)]
    if args.plots:
        from viscontact.plotting import plot_any  # imported before the run by _check_figures when --plots is given

        written += plot_any(ds, args.plots, fmt=args.fmt, dpi=args.dpi)
    if args.json or not args.quiet:
        from viscontact.running.summary import print_summary

        print_summary(args.out if ds is None else ds, as_json=args.json, files=[str(p) for p in written],
                      note=f" ({records} records, {time.perf_counter() - started:.1f} s)")


def _cmd_run(args: argparse.Namespace) -> int:
    """The records are streamed to RESULT.nc.partial as the run goes and renamed to RESULT.nc at the
    end (:func:`viscontact.running.api.run_to_file`): memory does not grow with the number of steps."""
    from viscontact.io.checkpoint import check_checkpoint_every
    from viscontact.io.streaming import PARTIAL_SUFFIX
    from viscontact.running.api import CHECKPOINT_SUFFIX

    started = time.perf_counter()
    check_checkpoint_every(args.checkpoint_every, "--checkpoint-every")
    with _writing(args.out, (PARTIAL_SUFFIX, CHECKPOINT_SUFFIX)):
        return _run_locked(args, started)


def _run_locked(args: argparse.Namespace, started: float) -> int:
    """``viscontact run`` once this process alone writes ``--out`` (:func:`_writing`): an
    ``OUT.partial`` there is the steps of an interrupted run, not of a run going on."""
    from viscontact.io.netcdf import open_result
    from viscontact.running import api
    from viscontact.running.resources import describe

    checked = _prepare(args)
    if args.dry_run:  # the run's every check made, this machine's included
        print(describe(checked.problem, checked.estimate))
        return 0
    if args.resume:  # what the killed run's writes left half way
        from viscontact.io.output_files import remove_temporaries

        remove_temporaries(args.out)
        remove_temporaries(api.checkpoint_path(args.out))
    with progress_bar(args, "step") as bar, stop_on_signals() as signals:
        written = api.run_to_file(checked, args.out, progress=bar.update, checkpoint_every=args.checkpoint_every,
                                  resume=args.resume, should_stop=signals.should_stop, history=_history_note(args),
                                  require_space=not args.force, finishing=signals.finish, force=args.force)
    _report(open_result(written.path) if args.plots else None, written.records, args, started)
    if signals.received:
        reason = signals.received[0]
        return error(f"{reason} received while the result was written: the complete result is in {args.out} "
                      "(complete = 1)", EXIT_TERMINATED if reason == "SIGTERM" else EXIT_INTERRUPTED)
    return 0


def _cmd_steady(args: argparse.Namespace) -> int:
    from viscontact.running import api

    started = time.perf_counter()
    speeds = parse_positive(args.speeds, "--speeds", "m/s", "0.01,0.1,1") if args.speeds is not None else None
    creepages = (parse_positive(args.creepages, "--creepages", "(creepage, -)", "-0.01,-0.001,0.001", signed=True)
                 if args.creepages is not None else None)
    with _writing(args.out):
        checked = _prepare(args)
        _finish(api.run_steady(checked, speeds, creepages), args, started)
    return 0


def _cmd_material(args: argparse.Namespace) -> int:
    from viscontact.io.results import material_dataset

    case = _load(args)
    if args.plots:
        _check_figures(args, files=[args.case])
    section = case.material
    problem = case.to_problem()
    material = problem.material
    c = material.creep
    print(f"material: {section.type}, {len(material.g)} Prony terms, {problem.body.material_summary()}")
    print(f"G(0) = {material.shear_modulus_instantaneous:.6g} Pa, G(inf) = {material.shear_modulus_long_term:.6g} Pa, "
          f"G(0)/G(inf) = {material.shear_modulus_instantaneous / material.shear_modulus_long_term:.6g}")
    temperature = getattr(section, "temperature", None)
    where = (f" at temperature = {temperature:g} degC (reference {section.reference_temperature:g} degC, "
             f"C1 = {section.wlf_c1:g}, C2 = {section.wlf_c2:g} degC)" if temperature is not None else
             " (reference temperature)")
    print(f"a_T = {material.shift_factor:.6g}{where}")
    print("relaxation times [s]: " + (" ".join(f"{x:.4g}" for x in sorted(material.tau)) or "none"))
    print("retardation times [s]: " + (" ".join(f"{x:.4g}" for x in c.retardation_times) or "none"))
    if args.plots:
        from viscontact.plotting import plot_material

        for path in plot_material(material_dataset(material), args.plots, fmt=args.fmt, dpi=args.dpi):
            print(f"wrote {path}")
    return 0


def _cmd_plot(args: argparse.Namespace) -> int:
    from viscontact.io.netcdf import open_result
    from viscontact.plotting import plot_any

    times = parse_positive(args.times, "--times", "s", "0,0.005,0.02", zero=True) if args.times is not None else None
    _check_figures(args, "--out", [args.result])
    for path in plot_any(open_result(args.result), args.out, times=times, fmt=args.fmt, dpi=args.dpi):
        if not args.quiet:
            print(path)
    return 0


def _cmd_export(args: argparse.Namespace) -> int:
    from viscontact.io.export import check_table_path, write_csv
    from viscontact.io.netcdf import open_result

    check_table_path(args.csv, force=args.force, inputs=[args.result])
    path = write_csv(open_result(args.result), args.csv, force=args.force)
    if not args.quiet:
        print(f"wrote {path}")
    return 0


def _cmd_sweep(args: argparse.Namespace) -> int:
    """0 when every run succeeded, 1 when some failed (the sweep file is written all the same), 130
    when interrupted (the finished runs are kept)."""
    from viscontact.sweep import load_sweep, planned, runs_dir, sweep

    started = time.perf_counter()
    if args.workers is not None and args.scheduler:
        raise ParameterError("--workers", "sets the size of a local cluster; leave it out with --scheduler")
    if args.workers is not None and args.workers < 1:
        raise ParameterError("--workers", f"must be >= 1, got {args.workers}")
    check_result_name(args.out)
    the_plan = planned(load_sweep(args.sweep))  # every run checked, before connecting to anything
    if args.plots:
        _check_figures(args)
    client = None
    try:
        if args.scheduler:
            from distributed import Client

            try:
                client = Client(args.scheduler, timeout="20s")
            except (OSError, TimeoutError) as exc:
                raise ParameterError("--scheduler", f"cannot connect to {args.scheduler}: {exc}") from None
        with progress_bar(args, "run") as bar:
            ds = sweep(the_plan, client=client, out=args.out, workers=args.workers, force=args.force,
                       progress=lambda done, failed, total: bar.update(done + failed, total, done=done, failed=failed))
    except KeyboardInterrupt as exc:
        exc.note = (f"; the finished runs are kept in {runs_dir(args.out)}/ - run the same "  # type: ignore[attr-defined]
                    "command again to resume")
        raise
    finally:
        if client is not None:
            client.close()
    written = [Path(args.out)]
    if args.plots:
        from viscontact.plotting import plot_sweep

        written += plot_sweep(ds, args.plots, fmt=args.fmt, dpi=args.dpi)
    if args.json or not args.quiet:
        from viscontact.running.summary import print_summary

        a = ds.attrs
        print_summary(ds, as_json=args.json, files=[str(p) for p in written],
                      note=f": {a['runs_computed'] + a['runs_reused']} runs ({a['runs_computed']} computed, "
                           f"{a['runs_reused']} reused, {a['runs_failed']} failed), {time.perf_counter() - started:.1f} s")
    return EXIT_FAILED if ds.attrs["runs_failed"] else 0


def _cmd_reproduce(args: argparse.Namespace) -> int:
    from viscontact.reproduce import reproduce

    started = time.perf_counter()
    _check_figures(args)
    with progress_bar(args, "step") as bar:
        paths = reproduce(args.figure, args.out, n=args.n, overrides=parse_overrides(args.overrides), cases_dir=args.cases,
                          progress=lambda name, done, total: bar.update(done, total, desc=name),
                          notify=None if args.quiet else lambda line: say(f"{PROG}: {line}"),
                          fmt=args.fmt, dpi=args.dpi)
    if not args.quiet:
        for path in paths:
            print(path)
        print(f"{args.figure}: {len(paths)} files in {args.out} ({time.perf_counter() - started:.1f} s)")
    return 0


#: the handler of each sub-command of :func:`viscontact.cli.parser.build_parser`
_HANDLERS = {"run": _cmd_run, "steady": _cmd_steady, "material": _cmd_material, "plot": _cmd_plot, "export": _cmd_export,
             "sweep": _cmd_sweep, "reproduce": _cmd_reproduce}


# --- the one error path ------------------------------------------------------------------------------
def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``viscontact`` command; returns the exit status.

    Every sub-command's handler raises; the errors become one line ``viscontact: error: ...`` here:
    bad input (:class:`ParameterError`, a missing or existing file) and a run out of memory
    (:class:`MemoryError`, the steps done kept) exit 2, a failed solve 1, a stop by SIGINT 130 and by
    SIGTERM 143.
    """
    try:
        with interrupts_redelivered():
            args = _parser().parse_args(argv)
            args.argv = list(sys.argv[1:] if argv is None else argv)
            configure_logging(args.log_level, args.quiet)
            log.debug("%s %s: %s", PROG, cli_version(), command_line(args.argv))
            with warnings_as_lines(args.quiet):
                return _HANDLERS[args.command](args)
    except ParameterError as exc:  # found during a run (partial slip in full periodic contact): the steps done kept
        saved = _saved_note(exc) if getattr(exc, "saved", None) else ""
        return error(f"{exc.key}: {exc.message}{saved}", EXIT_USAGE)
    except MemoryError as exc:  # the machine's (or, CuPy's OutOfMemoryError, the device's) memory ran out mid-run
        return error(_out_of_memory(exc), EXIT_USAGE)
    except OSError as exc:  # missing file, existing result, permissions
        where = exc.filename if exc.filename is not None else "file"
        saved = _saved_note(exc) if getattr(exc, "saved", None) else ""
        return error(f"{where}: {exc.strerror or exc}{saved}", EXIT_USAGE)
    except (ConvergenceError, NumericalGuardError) as exc:
        return error(f"{type(exc).__name__}: {exc}{_saved_note(exc)}", EXIT_FAILED)
    except OutputReplacedError as exc:  # the run's file was replaced under it: nothing renamed
        return error(str(exc), EXIT_FAILED)
    except RunInterrupted as exc:
        code = EXIT_TERMINATED if exc.reason == "SIGTERM" else EXIT_INTERRUPTED
        return error(f"stopped by {exc.reason} after the current step{_saved_note(exc)}", code)
    except KeyboardInterrupt as exc:
        return error(f"interrupted{_saved_note(exc)}", EXIT_INTERRUPTED)
    except ImportError as exc:  # a module the sub-command imports late, interrupted while it initialises
        if raised_by_interrupt(exc):
            return error("interrupted (no result file written)", EXIT_INTERRUPTED)
        raise


def _out_of_memory(exc: MemoryError) -> str:
    """The one line of a run that ran out of memory (``exc``: numpy's, or CuPy's on the device, whose
    message says how much it asked for), with what was kept of it."""
    detail = " ".join(str(exc).split())
    return (f"out of memory{f' ({detail})' if detail else ''}: the run needs more memory than this machine has free "
            f"(run --dry-run for its estimate); use a smaller grid.n, fewer recorded fields, or free memory"
            f"{_saved_note(exc)}")


def _saved_note(exc: BaseException) -> str:
    """What was kept of the run: the ``note`` or the ``saved`` (path, records) the handler attached."""
    if getattr(exc, "note", None):
        return exc.note  # type: ignore[attr-defined]
    saved = getattr(exc, "saved", None)
    return f" (the {saved[1]} records done are in {saved[0]}, complete = 0)" if saved else " (no result file written)"
