"""``viscontact`` command line: a thin shell over :mod:`viscontact.running.api`.

Bad input (an option, case file, missing file, existing result) prints one line
``viscontact: error: <key>: <message>`` and exits with status 2 (argparse's own errors too:
:class:`_Parser`; input found unsolvable during a run, such as partial slip reaching full contact
on a periodic domain, keeps the steps done and says where); a failed solve (no convergence,
numerical guard) exits with status 1, keeping the steps done in the result file (``complete = 0``).
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
"""
from __future__ import annotations

import argparse
import errno
import logging
import os
import shlex
import signal
import sys
import threading
import time
import warnings
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any, NoReturn

from viscontact.errors import (
    EXIT_INTERRUPTED,
    ConvergenceError,
    NumericalGuardError,
    OutputReplacedError,
    ParameterError,
    RunInterrupted,
    ViscontactWarning,
    raised_by_interrupt,
)

PROG = "viscontact"
EXIT_FAILED, EXIT_USAGE, EXIT_TERMINATED = 1, 2, 143
LOG_LEVELS = ("debug", "info", "warning", "error")
log = logging.getLogger("viscontact")


def _version() -> str:
    from viscontact.version import package_version

    return package_version()


# --- the parser: one ``_add_<command>`` per sub-command, each setting its ``_cmd_<command>`` handler --
class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line like every other bad input: argparse's own
    (a missing or unknown option, a value not among the choices, not a number) raise
    :class:`ParameterError` keyed by the option, pointing at the command's ``--help``, in place of its
    usage block. The sub-commands' parsers are of this class too (``add_subparsers`` makes its own)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.commands: dict[str, argparse.ArgumentParser] = {}  # the sub-commands' parsers (set by _parser)

    def error(self, message: str) -> NoReturn:
        key, message = _argparse_error(message)
        raise ParameterError(key, f"{message}; see {self.prog} --help")

    def parse_args(self, args: Any = None, namespace: Any = None) -> Any:
        """The arguments; those no parser knows are refused by the sub-command's parser (argparse
        refuses them at the top level, whose help does not list the sub-command's options)."""
        parsed, extra = self.parse_known_args(args, namespace)
        if extra:
            self.commands.get(getattr(parsed, "command", None) or "", self).error(
                f"unrecognized arguments: {' '.join(extra)}")
        return parsed


def _argparse_error(message: str) -> tuple[str, str]:
    """argparse's error ``message`` as (key, message): ``argument --format: invalid choice ...`` is
    keyed by ``--format``, ``the following arguments are required: --out`` by ``--out``."""
    required = "the following arguments are required: "
    if message.startswith(required):
        return message.removeprefix(required), "required"
    if message.startswith("argument ") and ": " in message:
        key, _, rest = message.removeprefix("argument ").partition(": ")
        return key, rest
    key, sep, rest = message.partition(": ")
    return (key, rest) if sep else ("command line", message)


def _set_argument(p: argparse.ArgumentParser, what: str = "a case-file key") -> None:
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="overrides",
                   help=f"override {what}, e.g. --set tangential.sliding_speed=0.1 (repeatable; "
                        "an empty VALUE removes the key)")


def _figure_arguments(p: argparse.ArgumentParser) -> None:
    """``--format`` and ``--dpi`` of the figures a command writes."""
    from viscontact.plotting.base import DPI, FORMATS

    p.add_argument("--format", default="png", choices=FORMATS, dest="fmt", help="file format of the figures")
    p.add_argument("--dpi", type=int, default=None, metavar="N", help=f"resolution of the figures (default {DPI})")


def _case_arguments(p: argparse.ArgumentParser) -> None:
    """Arguments of the commands that solve one case (``run``, ``steady``)."""
    p.add_argument("case", metavar="CASE.toml", help="case file")
    p.add_argument("--out", required=True, metavar="RESULT.nc", help="result file (netCDF-4)")
    p.add_argument("--plots", metavar="DIR", help="also write figures into DIR")
    _figure_arguments(p)
    p.add_argument("--force", action="store_true", help="overwrite an existing result file")
    _set_argument(p)
    _summary_argument(p)


def _summary_argument(p: argparse.ArgumentParser) -> None:
    p.add_argument("--json", action="store_true", help="print the summary as one JSON object on stdout (even "
                   "with --quiet)")


def _add_run(sub: Any) -> None:
    p = sub.add_parser("run", help="one transient simulation")
    _case_arguments(p)
    p.add_argument("--quiet", action="store_true", help="no progress bar, no summary, no warnings")
    p.add_argument("--checkpoint-every", type=int, default=0, metavar="N",
                   help="write the solver state every N steps to RESULT.nc.checkpoint.npz (atomic); 0, the "
                        "default: no checkpoint")
    p.add_argument("--resume", action="store_true",
                   help="continue from RESULT.nc.checkpoint.npz (same case file) and the records streamed to "
                        "RESULT.nc.partial, and overwrite RESULT.nc")
    p.add_argument("--dry-run", action="store_true",
                   help="validate the case and print the estimated result size, peak memory and run time; "
                        "run nothing")
    p.set_defaults(handler=_cmd_run)


def _add_steady(sub: Any) -> None:
    p = sub.add_parser("steady", help="steady sliding state(s) (direct solver)")
    _case_arguments(p)
    p.add_argument("--speeds", metavar="V1,V2,...", help="speed sweep [m/s], comma-separated")
    p.add_argument("--quiet", action="store_true", help="no summary, no warnings")
    p.set_defaults(handler=_cmd_steady)


def _add_material(sub: Any) -> None:
    p = sub.add_parser("material", help="the case's material: moduli, retardation times, a_T (and figures)")
    p.add_argument("case", metavar="CASE.toml", help="case file")
    p.add_argument("--plots", metavar="DIR", help="also draw G(t), J(t), G'(omega), G''(omega), tan delta into DIR")
    _figure_arguments(p)
    _set_argument(p)
    p.set_defaults(handler=_cmd_material)


def _add_plot(sub: Any) -> None:
    p = sub.add_parser("plot", help="figures of an existing result file")
    p.add_argument("result", metavar="RESULT.nc", help="result file of viscontact run, steady or sweep")
    p.add_argument("--out", required=True, metavar="DIR", help="folder for the figures")
    p.add_argument("--times", metavar="T1,T2,...", help="times [s] of the profiles and the pressure and stick/slip "
                   "maps, t = 0 included (the nearest records; default: evenly spread)")
    _figure_arguments(p)
    p.set_defaults(handler=_cmd_plot)


def _add_export(sub: Any) -> None:
    p = sub.add_parser("export", help="tables of an existing result file (CSV)",
                       description="Write the scalar series of a result as a CSV table: of a run, one row per "
                       "record (t, load, delta_z, delta_x, contact_area, mu_app, friction_force, ...); of a steady "
                       "speed curve, one per speed; of a sweep, one per run. The first line names the columns "
                       "and their units.")
    p.add_argument("result", metavar="RESULT.nc", help="result file of viscontact run, steady or sweep")
    p.add_argument("--csv", required=True, metavar="OUT.csv", help="the table file to write")
    p.add_argument("--force", action="store_true", help="overwrite an existing table file")
    p.set_defaults(handler=_cmd_export)


def _add_sweep(sub: Any) -> None:
    from viscontact.running.resources import (
        available_cores,  # not the sweep's modules: the parser is built for every command
    )

    p = sub.add_parser("sweep", help="a parameter sweep on a dask cluster (resumable)",
                       description="Run the Cartesian product of the values in SWEEP.toml. "
                       "Run files are kept in SWEEP.runs/; re-running the same command resumes.")
    p.add_argument("sweep", metavar="SWEEP.toml", help="sweep file")
    p.add_argument("--out", required=True, metavar="SWEEP.nc", help="sweep result file (netCDF-4)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="an existing dask scheduler, e.g. tcp://host:8786 "
                   "(default: a local cluster)")
    p.add_argument("--workers", type=int, metavar="N", help=f"local worker processes (default: one per core, "
                   f"{available_cores()} here; one where the runs use solver.device = \"gpu\")")
    p.add_argument("--plots", metavar="DIR", help="also write the sweep figures into DIR")
    _figure_arguments(p)
    p.add_argument("--force", action="store_true", help="replace an existing SWEEP.nc of another sweep")
    p.add_argument("--quiet", action="store_true", help="no progress bar, no summary, no warnings")
    _summary_argument(p)
    p.set_defaults(handler=_cmd_sweep)


def _add_reproduce(sub: Any) -> None:
    import textwrap

    from viscontact.reproduce.figures import FIGURES, SHOWS

    shows = "\n".join(textwrap.fill(SHOWS[name], 79, initial_indent=f"  {name:<6} ", subsequent_indent=" " * 9)
                      for name in FIGURES)
    p = sub.add_parser("reproduce", help="rerun the seed's cases and draw one of its figures",
                       formatter_class=argparse.RawDescriptionHelpFormatter,
                       description=f"Rerun the seed paper's cases (Wang et al., Friction 2023) and draw one of its "
                       f"figures:\n\n{shows}")
    p.add_argument("figure", choices=list(FIGURES), help="seed figure to reproduce (what each shows: above)")
    p.add_argument("--out", required=True, metavar="DIR", help="folder for the figures and the results (.nc)")
    p.add_argument("--n", type=int, default=None, metavar="N",
                   help="grid cells per side instead of the seed's 256 (quick preview; dt follows, and is cut "
                        "where the seed's scheme would be over half its stability limit or miss the material's "
                        "response by more than 7 %%, the time-step guard's warning limit: the cases are named)")
    _set_argument(p, "a key of every case of the figure")
    _figure_arguments(p)
    p.add_argument("--cases", default=None, metavar="DIR", help="folder of the seed_*.toml cases")
    p.add_argument("--quiet", action="store_true", help="no progress bar, no summary, no warnings")
    p.set_defaults(handler=_cmd_reproduce)


def _parser() -> _Parser:
    parser = _Parser(
        prog=PROG, description="Transient frictional sliding contact on a linear viscoelastic half-space.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {_version()}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for add in (_add_run, _add_steady, _add_material, _add_plot, _add_export, _add_sweep, _add_reproduce):
        add(sub)
    parser.commands = sub.choices
    for command in sub.choices.values():  # options every sub-command shares
        _add_shared_option(command, "--quiet", action="store_true", help="no progress bar, no summary, no warnings")
        _add_shared_option(command, "--log-level", choices=LOG_LEVELS, default="warning", type=str.lower,
                           help="messages shown on stderr, from the most detailed (default: warning)")
    return parser


def _add_shared_option(parser: argparse.ArgumentParser, flag: str, **kwargs: Any) -> None:
    """Add ``flag`` to ``parser`` unless the sub-command defines it already."""
    try:
        parser.add_argument(flag, **kwargs)
    except argparse.ArgumentError:
        pass


# --- output on stderr -------------------------------------------------------------------------------
def _say(line: str) -> None:
    """One line on stderr, without breaking a progress bar."""
    try:
        from tqdm import tqdm

        tqdm.write(line, file=sys.stderr)
    except ImportError:  # pragma: no cover - tqdm is a dependency
        print(line, file=sys.stderr)


class _LineHandler(logging.Handler):
    """``viscontact: <level>: <message>`` on stderr, without breaking a progress bar."""

    def emit(self, record: logging.LogRecord) -> None:
        _say(f"{PROG}: {record.levelname.lower()}: {' '.join(record.getMessage().split())}")


_HANDLER = _LineHandler()


def _configure_logging(level: str, quiet: bool) -> None:
    """The ``viscontact`` logger shows ``level`` and above on stderr; only errors when ``quiet``."""
    log.setLevel(logging.ERROR if quiet else getattr(logging, level.upper()))
    if _HANDLER not in log.handlers:
        log.addHandler(_HANDLER)
    log.propagate = False


@contextmanager
def _warnings_as_lines(quiet: bool = False) -> Iterator[None]:
    """Log every ViscontactWarning as ``viscontact: warning: ...`` (other warnings unchanged); with
    ``quiet``, no warning at all."""
    previous = warnings.showwarning

    def show(message: Any, category: type, filename: str, lineno: int, file: Any = None, line: Any = None) -> None:
        if issubclass(category, ViscontactWarning):
            log.warning("%s", message)
        else:
            previous(message, category, filename, lineno, file, line)

    warnings.showwarning = show
    try:
        with warnings.catch_warnings():
            if quiet:
                warnings.simplefilter("ignore")
            yield
    finally:
        warnings.showwarning = previous


class _Bar:
    """A tqdm progress bar on stderr when ``enabled`` (a TTY and not ``--quiet``); silent otherwise.
    ``update(count, total, desc=..., **postfix)`` serves every command's progress callback."""

    def __init__(self, enabled: bool, unit: str) -> None:
        self.enabled, self.unit, self.bar, self.desc = enabled, unit, None, None

    def update(self, count: int, total: int, desc: str | None = None, **postfix: int) -> None:
        if not self.enabled:
            return
        if self.bar is None:
            from tqdm import tqdm

            self.bar = tqdm(total=total, file=sys.stderr, unit=self.unit, dynamic_ncols=True, leave=False)
        if self.bar.total != total or desc != self.desc:
            self.bar.reset(total=total)
            self.desc = desc
            self.bar.set_description(desc)
        if postfix:
            self.bar.set_postfix(**postfix, refresh=False)
        self.bar.update(count - self.bar.n)

    def __enter__(self) -> _Bar:
        return self

    def __exit__(self, *exc: object) -> None:
        if self.bar is not None:
            self.bar.close()


def _bar(args: argparse.Namespace, unit: str) -> _Bar:
    return _Bar(not args.quiet and sys.stderr.isatty(), unit)


def _parse_value(text: str) -> Any:
    """A ``--set`` value as TOML (number, boolean, array, quoted string), else the bare string;
    an empty value removes the key (``--set time.dt=``: its default applies)."""
    import tomllib

    if not text:
        return None
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def _overrides(items: Sequence[str]) -> dict[str, Any]:
    """``--set KEY=VALUE`` arguments as dotted keys and values."""
    overrides = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key.strip():
            raise ParameterError("--set", f"expected KEY=VALUE (e.g. tangential.sliding_speed=0.1), got {item!r}")
        try:  # a case file is UTF-8 text, and so is what the result stores of it (title, case text)
            item.encode("utf-8")
        except UnicodeEncodeError:
            raise ParameterError("--set", f"{item!r} holds bytes that are not UTF-8 text (shown as \\udcNN); "
                                 "type it in a UTF-8 terminal or put it in the case file") from None
        overrides[key.strip()] = _parse_value(value.strip())
    return overrides


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
    overrides = _overrides(args.overrides)
    return case.with_overrides(overrides) if overrides else case


@contextmanager
def _writing(out: str, derived: Sequence[str] = ()) -> Iterator[None]:
    """While the body runs, this process alone writes the result file ``out`` (a ``*.nc`` name):
    :func:`viscontact.io.output_files.output_lock`, which first checks the names of the files
    ``derived`` (suffixes) written beside it. Enter it before ``out`` is checked."""
    from viscontact.io.output_files import output_lock

    _check_result_name(out)
    with output_lock(out, derived):
        yield


def _prepare(args: argparse.Namespace) -> Any:
    """The case with its overrides, after checking (before any computing) that the result file may
    be written and that plotting is available (inside :func:`_writing`)."""
    from viscontact.io.output_files import check_output_path

    case = _load(args)
    check_output_path(args.out, force=args.force or getattr(args, "resume", False),
                      inputs=[args.case, *case.input_files().values()])
    if args.plots:
        _check_figures(args)
    return case


def _check_result_name(out: str) -> None:
    """A result file (``--out`` of run, steady, sweep) is netCDF-4: its name must end in ``.nc``."""
    if Path(out).suffix != ".nc":
        raise ParameterError("--out", f"must be a netCDF-4 result file named *.nc, got {out!r}")


def _parse_positive(text: str, option: str, unit: str, example: str, zero: bool = False) -> list[float]:
    """Comma-separated finite numbers > 0 (``zero``: >= 0), each once (``--speeds``, ``--times``)."""
    from viscontact.running.guards import positive_values

    try:
        values = [float(s) for s in text.split(",") if s.strip()]
    except ValueError:
        raise ParameterError(option, f"expected comma-separated numbers in {unit} (e.g. {example}), got {text!r}") from None
    return positive_values(values, option, unit, repr(text), zero=zero)


def _finish(ds: Any, args: argparse.Namespace, started: float) -> None:
    """Write the result ``ds`` of a command computed in memory, then :func:`_report`."""
    from viscontact.io.netcdf import write_netcdf

    ds.attrs["history"] = f"{ds.attrs.get('history', '')} {_history_note(args)}".strip()
    write_netcdf(ds, args.out, force=args.force)
    _report(ds, ds.sizes.get("t", ds.sizes.get("speed", 0)), args, started)


def _history_note(args: argparse.Namespace) -> str:
    """``by the command: viscontact ...`` for the result's ``history`` attribute ('' when unknown)."""
    return f"by the command: {PROG} {_command_line(args.argv)}" if getattr(args, "argv", None) is not None else ""


def _command_line(argv: Sequence[str]) -> str:
    """The arguments ``argv`` as one shell-quoted line of valid UTF-8 (what a result's ``history``
    and the log record): a byte of an argument that is not UTF-8 (which Python carries as a lone
    surrogate) is written ``\\xNN``."""
    line = shlex.join(argv)
    try:
        raw = line.encode("utf-8", "surrogateescape")
    except UnicodeEncodeError:  # a lone surrogate that is no escaped byte (an argv given in Python)
        raw = line.encode("utf-8", "backslashreplace")
    return raw.decode("utf-8", "backslashreplace")


def _report(ds: Any, records: int, args: argparse.Namespace, started: float) -> None:
    """Draw the figures of the result ``ds`` (with ``--plots``) and print what was written."""
    written = [Path(args.out)]
    if args.plots:
        from viscontact.plotting import plot_any  # imported before the run by _prepare when --plots is given

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
    from viscontact.io.streaming import check_partial_path
    from viscontact.running import api
    from viscontact.running.guards import check_material
    from viscontact.running.resources import check_resources, describe

    case = _prepare(args)
    partial = check_partial_path(args.out)  # a folder there is in the way, not an interrupted run's steps
    if partial.exists() and not (args.force or args.resume):
        raise FileExistsError(errno.EEXIST, "holds the steps of an interrupted run: --resume continues it (with its "
                              "checkpoint), --force starts over", str(partial))
    written = partial.stat().st_size if args.resume and partial.exists() else 0  # a resume's records so far
    outline = case.problem_outline()  # the estimate's sizes, before any n x n array
    check_material(outline.material)  # the estimate reads its creep spectrum
    estimate = check_resources(outline, args.out, force=args.force, checkpoints=bool(args.checkpoint_every),
                               written_bytes=written)  # the outline says whether SurfaceTopography makes its gap
    if args.dry_run:  # a run prepares its problem in run_to_file
        from viscontact.numerics.arrays import array_backend
        from viscontact.solvers.transient import validate

        problem, _ = api.prepare(case)
        validate(problem)
        array_backend(problem.solver.device)  # 'gpu' without a CUDA device: one line, as the run would
        print(describe(problem, estimate))
        return 0
    if args.resume:  # what the killed run's writes left half way
        from viscontact.io.output_files import remove_temporaries

        remove_temporaries(args.out)
        remove_temporaries(api.checkpoint_path(args.out))
    with _bar(args, "step") as bar, _stop_on_signals() as signals:
        written = api.run_to_file(case, args.out, progress=bar.update, checkpoint_every=args.checkpoint_every,
                                  resume=args.resume, should_stop=signals.should_stop, history=_history_note(args),
                                  require_space=not args.force, finishing=signals.finish, force=args.force)
    _report(open_result(written.path) if args.plots else None, written.records, args, started)
    if signals.received:
        reason = signals.received[0]
        return _error(f"{reason} received while the result was written: the complete result is in {args.out} "
                      "(complete = 1)", EXIT_TERMINATED if reason == "SIGTERM" else EXIT_INTERRUPTED)
    return 0


class _StopSignals:
    """SIGINT / SIGTERM during ``viscontact run``: while computing, the first asks the run to stop after
    its current step and a second SIGINT interrupts at once; once ``finishing`` (the result is being
    written) they are only recorded, so that the write completes."""

    def __init__(self) -> None:
        self.received: list[str] = []
        self.finishing = False

    def should_stop(self) -> str | None:
        """The ``should_stop`` callable of :func:`viscontact.running.api.run_to_file`."""
        return self.received[0] if self.received else None

    def finish(self) -> None:
        """The ``finishing`` callable of :func:`viscontact.running.api.run_to_file`: the result is being written."""
        self.finishing = True

    def handle(self, signum: int, frame: Any) -> None:  # noqa: ARG002
        if self.received and signum == signal.SIGINT and not self.finishing:
            raise KeyboardInterrupt
        self.received.append(signal.Signals(signum).name)


@contextmanager
def _stop_on_signals() -> Iterator[_StopSignals]:
    """Handle SIGINT and SIGTERM with a :class:`_StopSignals` while the body runs."""
    signals = _StopSignals()
    previous = {sig: signal.signal(sig, signals.handle) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield signals
    finally:
        for sig, old in previous.items():
            signal.signal(sig, old)


def _cmd_steady(args: argparse.Namespace) -> int:
    from viscontact.running import api

    started = time.perf_counter()
    speeds = _parse_positive(args.speeds, "--speeds", "m/s", "0.01,0.1,1") if args.speeds is not None else None
    with _writing(args.out):
        case = _prepare(args)
        _finish(api.run_steady(case, speeds), args, started)
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
    if problem.bulk_modulus is None:
        nu = f"poisson_ratio = {material.poisson_ratio:g}"
    else:  # nu(t) from G(t) and K
        from viscontact.bodies.bulk_elastic import BulkElasticMaterial

        bulk = BulkElasticMaterial(material, problem.bulk_modulus)
        nu = (f"bulk_modulus K = {problem.bulk_modulus:.6g} Pa: poisson ratio nu(t) from "
              f"{bulk.poisson_ratio_instantaneous:.6g} (t = 0) to {bulk.poisson_ratio_long_term:.6g} (t = inf)")
    print(f"material: {section.type}, {len(material.g)} Prony terms, {nu}")
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

    times = _parse_positive(args.times, "--times", "s", "0,0.005,0.02", zero=True) if args.times is not None else None
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
    _check_result_name(args.out)
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
        with _bar(args, "run") as bar:
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
    with _bar(args, "step") as bar:
        paths = reproduce(args.figure, args.out, n=args.n, overrides=_overrides(args.overrides), cases_dir=args.cases,
                          progress=lambda name, done, total: bar.update(done, total, desc=name),
                          notify=None if args.quiet else lambda line: _say(f"{PROG}: {line}"),
                          fmt=args.fmt, dpi=args.dpi)
    if not args.quiet:
        for path in paths:
            print(path)
        print(f"{args.figure}: {len(paths)} files in {args.out} ({time.perf_counter() - started:.1f} s)")
    return 0


# --- the one error path ------------------------------------------------------------------------------
def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``viscontact`` command; returns the exit status.

    Every sub-command's handler raises; the errors become one line ``viscontact: error: ...`` here:
    bad input (:class:`ParameterError`, a missing or existing file) exits 2, a failed solve 1, a
    stop by SIGINT 130 and by SIGTERM 143.
    """
    try:
        with _interrupts_redelivered():
            args = _parser().parse_args(argv)
            args.argv = list(sys.argv[1:] if argv is None else argv)
            _configure_logging(args.log_level, args.quiet)
            log.debug("%s %s: %s", PROG, _version(), _command_line(args.argv))
            with _warnings_as_lines(args.quiet):
                return args.handler(args)
    except ParameterError as exc:  # found during a run (partial slip in full periodic contact): the steps done kept
        saved = _saved_note(exc) if getattr(exc, "saved", None) else ""
        return _error(f"{exc.key}: {exc.message}{saved}", EXIT_USAGE)
    except OSError as exc:  # missing file, existing result, permissions
        where = exc.filename if exc.filename is not None else "file"
        saved = _saved_note(exc) if getattr(exc, "saved", None) else ""
        return _error(f"{where}: {exc.strerror or exc}{saved}", EXIT_USAGE)
    except (ConvergenceError, NumericalGuardError) as exc:
        return _error(f"{type(exc).__name__}: {exc}{_saved_note(exc)}", EXIT_FAILED)
    except OutputReplacedError as exc:  # the run's file was replaced under it: nothing renamed
        return _error(str(exc), EXIT_FAILED)
    except RunInterrupted as exc:
        code = EXIT_TERMINATED if exc.reason == "SIGTERM" else EXIT_INTERRUPTED
        return _error(f"stopped by {exc.reason} after the current step{_saved_note(exc)}", code)
    except KeyboardInterrupt as exc:
        return _error(f"interrupted{_saved_note(exc)}", EXIT_INTERRUPTED)
    except ImportError as exc:  # a module the sub-command imports late, interrupted while it initialises
        if raised_by_interrupt(exc):
            return _error("interrupted (no result file written)", EXIT_INTERRUPTED)
        raise


#: seconds after which a KeyboardInterrupt that Python had to drop is delivered again
#: (:func:`_interrupts_redelivered`)
REDELIVERY_DELAY = 0.005


@contextmanager
def _interrupts_redelivered() -> Iterator[None]:
    """While the body runs, a KeyboardInterrupt raised where Python cannot propagate it is delivered
    again. SIGINT landing in a weakref callback (an import's module lock) or a ``__del__`` raises there;
    Python prints "Exception ignored in ..." and drops it, and the command would go on as if never
    interrupted. ``sys.unraisablehook`` catches it instead and sends SIGINT to the process again from a
    timer thread a few milliseconds later, once the main thread has left the callback (sending it from
    the hook itself would raise inside the hook, dropped again)."""
    previous = sys.unraisablehook
    active = threading.Event()
    active.set()

    def resend() -> None:
        if active.is_set():
            os.kill(os.getpid(), signal.SIGINT)

    def hook(unraisable: Any) -> None:
        if isinstance(unraisable.exc_value, KeyboardInterrupt):
            threading.Timer(REDELIVERY_DELAY, resend).start()
        else:
            previous(unraisable)

    sys.unraisablehook = hook
    try:
        yield
    finally:
        active.clear()
        sys.unraisablehook = previous


def _saved_note(exc: BaseException) -> str:
    """What was kept of the run: the ``note`` or the ``saved`` (path, records) the handler attached."""
    if getattr(exc, "note", None):
        return exc.note  # type: ignore[attr-defined]
    saved = getattr(exc, "saved", None)
    return f" (the {saved[1]} records done are in {saved[0]}, complete = 0)" if saved else " (no result file written)"


def _error(message: str, status: int) -> int:
    _say(f"{PROG}: error: {' '.join(message.split())}")
    return status


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
