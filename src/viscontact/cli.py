"""``viscontact`` command line: a thin shell over :mod:`viscontact.api`.

Bad input (case file, missing file, existing result) prints one line
``viscontact: error: <key>: <message>`` and exits with status 2; a failed solve (no convergence,
numerical guard) exits with status 1, keeping the steps done in the result file (``complete = 0``).
SIGINT / SIGTERM stop a run after its current step, write the steps done (``complete = 0``) and
exit with 130 / 143.
"""
from __future__ import annotations

import argparse
import signal
import sys
import time
import warnings
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import tomllib

from .errors import ConvergenceError, NumericalGuardError, ParameterError, RunInterrupted, ViscontactWarning

PROG = "viscontact"
EXIT_FAILED, EXIT_USAGE, EXIT_INTERRUPTED, EXIT_TERMINATED = 1, 2, 130, 143
#: sub-commands defined elsewhere: (module, function adding its parser; the parser sets ``handler``
#: or ``func`` to a callable taking the parsed arguments and returning the exit status)
def _version() -> str:
    from . import __version__

    return __version__


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog=PROG, description="Transient frictional sliding contact on a linear viscoelastic half-space.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    def common(p: argparse.ArgumentParser) -> None:
        p.add_argument("case", metavar="CASE.toml", help="case file")
        p.add_argument("--out", required=True, metavar="RESULT.nc", help="result file (netCDF-4)")
        p.add_argument("--plots", metavar="DIR", help="also write figures (PNG) into DIR")
        p.add_argument("--force", action="store_true", help="overwrite an existing result file")
        p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="overrides",
                       help="override a case-file key, e.g. --set tangential.sliding_speed=0.1 (repeatable; "
                            "an empty VALUE removes the key)")

    run = sub.add_parser("run", help="one transient simulation")
    common(run)
    run.add_argument("--quiet", action="store_true", help="no progress bar, no summary")
    run.add_argument("--checkpoint-every", type=int, default=0, metavar="N",
                     help="write the solver state every N steps to RESULT.nc.checkpoint.npz (atomic)")
    run.add_argument("--resume", action="store_true",
                     help="continue from RESULT.nc.checkpoint.npz (same case file) and overwrite RESULT.nc")
    run.add_argument("--dry-run", action="store_true",
                     help="validate the case and print the estimated result size and memory; run nothing")
    steady = sub.add_parser("steady", help="steady sliding state(s) (direct solver)")
    common(steady)
    steady.add_argument("--speeds", metavar="V1,V2,...", help="speed sweep [m/s], comma-separated")
    steady.add_argument("--quiet", action="store_true", help="no summary")
    plot = sub.add_parser("plot", help="figures of an existing result file")
    plot.add_argument("result", metavar="RESULT.nc")
    plot.add_argument("--out", required=True, metavar="DIR", help="folder for the PNG files")
    run.set_defaults(handler=_cmd_run)
    steady.set_defaults(handler=_cmd_steady)
    plot.set_defaults(handler=_cmd_plot)
    from .reproduce import add_reproduce_parser
    from .sweep import add_sweep_parser

    add_sweep_parser(sub)
    add_reproduce_parser(sub)
    return parser


def _say(line: str) -> None:
    """One line on stderr, without breaking a progress bar."""
    try:
        from tqdm import tqdm

        tqdm.write(line, file=sys.stderr)
    except ImportError:  # pragma: no cover - tqdm is a dependency
        print(line, file=sys.stderr)


@contextmanager
def _warnings_as_lines() -> Iterator[None]:
    """Show ViscontactWarning as ``viscontact: warning: ...`` (other warnings unchanged)."""
    previous = warnings.showwarning

    def show(message: Any, category: type, filename: str, lineno: int, file: Any = None, line: Any = None) -> None:
        if issubclass(category, ViscontactWarning):
            _say(f"{PROG}: warning: {message}")
        else:
            previous(message, category, filename, lineno, file, line)

    warnings.showwarning = show
    try:
        yield
    finally:
        warnings.showwarning = previous


@contextmanager
def _progress(enabled: bool) -> Iterator[Callable[[int, int], None] | None]:
    """A ``progress(done, total)`` callback drawing a tqdm bar on stderr, or None when disabled."""
    if not enabled:
        yield None
        return
    from tqdm import tqdm

    bar = tqdm(total=None, file=sys.stderr, unit="step", dynamic_ncols=True, leave=False)

    def update(done: int, total: int) -> None:
        if bar.total != total:
            bar.total = total
        bar.update(done - bar.n)

    try:
        yield update
    finally:
        bar.close()


def _parse_value(text: str) -> Any:
    """A ``--set`` value as TOML (number, boolean, array, quoted string), else the bare string;
    an empty value removes the key (``--set time.dt=``: its default applies)."""
    if not text:
        return None
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def _load(args: argparse.Namespace) -> Any:
    from .case import load_case

    case = load_case(args.case)
    overrides = {}
    for item in args.overrides:
        key, sep, value = item.partition("=")
        if not sep or not key.strip():
            raise ParameterError("--set", f"expected KEY=VALUE (e.g. tangential.sliding_speed=0.1), got {item!r}")
        overrides[key.strip()] = _parse_value(value.strip())
    return case.with_overrides(overrides) if overrides else case


def _prepare(args: argparse.Namespace) -> Any:
    """The case with its overrides, after checking (before any computing) that the result file may
    be written and that plotting is available."""
    case = _load(args)
    if Path(args.out).exists() and not (args.force or getattr(args, "resume", False)):
        raise FileExistsError(17, "exists; refusing to overwrite it without --force", args.out)
    if args.plots:
        from . import plotting

        plotting._pyplot()
    return case


def _parse_speeds(text: str) -> list[float]:
    try:
        speeds = [float(s) for s in text.split(",") if s.strip()]
    except ValueError:
        raise ParameterError("--speeds", f"expected comma-separated speeds in m/s (e.g. 0.01,0.1,1), got {text!r}") from None
    if not speeds or any(not (v > 0 and v < float("inf")) for v in speeds):
        raise ParameterError("--speeds", f"every speed must be a finite number > 0 m/s, got {text!r}")
    return speeds


def _finish(ds: Any, args: argparse.Namespace, started: float) -> None:
    from .plotting import plot_any  # imported before the run by _prepare when --plots is given
    from .results import write_netcdf

    write_netcdf(ds, args.out, force=args.force)
    written = [Path(args.out)]
    if args.plots:
        written += plot_any(ds, args.plots)
    if not args.quiet:
        steps = ds.sizes.get("t", ds.sizes.get("speed", 0))
        print(f"wrote {', '.join(str(p) for p in written)} ({steps} records, {time.perf_counter() - started:.1f} s)")


def _cmd_run(args: argparse.Namespace) -> int:
    from . import api
    from .resources import check_resources, describe
    from .results import write_netcdf

    started = time.perf_counter()
    if args.checkpoint_every < 0:
        raise ParameterError("--checkpoint-every", f"must be >= 0 steps, got {args.checkpoint_every}")
    case = _prepare(args)
    problem, _ = api.prepare(case)
    estimate = check_resources(problem, args.out)
    if args.dry_run:
        from .transient import validate

        validate(problem)
        print(describe(problem, estimate))
        return 0
    checkpoint = api.checkpoint_path(args.out) if (args.checkpoint_every or args.resume) else None
    force = args.force or args.resume
    with _progress(not args.quiet and sys.stderr.isatty()) as progress, _stop_on_signals() as should_stop:
        try:
            ds = api.run(case, progress=progress, checkpoint=checkpoint, checkpoint_every=args.checkpoint_every,
                         resume=args.resume, should_stop=should_stop)
        except (ConvergenceError, NumericalGuardError, RunInterrupted, KeyboardInterrupt) as exc:
            partial = getattr(exc, "partial", None)
            if partial is not None:
                write_netcdf(partial, args.out, force=force)
                exc.saved = (args.out, partial.sizes["t"])  # type: ignore[attr-defined]
            raise
    args.force = force
    _finish(ds, args, started)
    if checkpoint is not None and checkpoint.exists():
        checkpoint.unlink()
    return 0


@contextmanager
def _stop_on_signals():
    """SIGINT and SIGTERM ask the run to stop after its current step (a second SIGINT interrupts at
    once). Yields the ``should_stop`` callable for :func:`viscontact.api.run`."""
    received: list[str] = []

    def handler(signum, frame):  # noqa: ARG001
        name = signal.Signals(signum).name
        if received and signum == signal.SIGINT:
            raise KeyboardInterrupt
        received.append(name)

    previous = {sig: signal.signal(sig, handler) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield lambda: received[0] if received else None
    finally:
        for sig, old in previous.items():
            signal.signal(sig, old)


def _cmd_steady(args: argparse.Namespace) -> int:
    from . import api

    started = time.perf_counter()
    speeds = _parse_speeds(args.speeds) if args.speeds else None
    case = _prepare(args)
    _finish(api.run_steady(case, speeds), args, started)
    return 0


def _cmd_plot(args: argparse.Namespace) -> int:
    from .plotting import plot_any
    from .results import open_result

    for path in plot_any(open_result(args.result), args.out):
        print(path)
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``viscontact`` command; returns the exit status."""
    args = _parser().parse_args(argv)
    command = getattr(args, "handler", None) or args.func
    try:
        with _warnings_as_lines():
            return command(args)
    except ParameterError as exc:
        return _error(f"{exc.key}: {exc.message}", EXIT_USAGE)
    except OSError as exc:  # missing file, existing result, permissions
        where = exc.filename if exc.filename is not None else "file"
        return _error(f"{where}: {exc.strerror or exc}", EXIT_USAGE)
    except (ConvergenceError, NumericalGuardError) as exc:
        return _error(f"{type(exc).__name__}: {exc}{_saved_note(exc)}", EXIT_FAILED)
    except RunInterrupted as exc:
        code = EXIT_TERMINATED if exc.reason == "SIGTERM" else EXIT_INTERRUPTED
        return _error(f"stopped by {exc.reason} after the current step{_saved_note(exc)}", code)
    except KeyboardInterrupt as exc:
        return _error(f"interrupted{_saved_note(exc)}", EXIT_INTERRUPTED)


def _saved_note(exc: BaseException) -> str:
    saved = getattr(exc, "saved", None)
    return f" (the {saved[1]} records done are in {saved[0]}, complete = 0)" if saved else " (no result file written)"


def _error(message: str, status: int) -> int:
    _say(f"{PROG}: error: {' '.join(message.split())}")
    return status


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
