"""The command line's parser: one ``_add_<command>`` per sub-command; :func:`build_parser` builds them all.
It loads no solver, case or sweep module (``viscontact --help`` stays light): the command's handler is
chosen by :func:`viscontact.cli.main` from ``args.command``."""
from __future__ import annotations

import argparse
from typing import Any, NoReturn

from viscontact.cli.output import PROG
from viscontact.errors import ParameterError

__all__ = ["LOG_LEVELS", "Parser", "build_parser", "cli_version"]

LOG_LEVELS = ("debug", "info", "warning", "error")


def cli_version() -> str:
    from viscontact.version import package_version

    return package_version()


class Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line like every other bad input: argparse's own
    (a missing or unknown option, a value not among the choices, not a number) raise
    :class:`ParameterError` keyed by the option, pointing at the command's ``--help``, in place of its
    usage block. The sub-commands' parsers are of this class too (``add_subparsers`` makes its own)."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.commands: dict[str, argparse.ArgumentParser] = {}  # the sub-commands' parsers (set by build_parser)

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
                   help="make every check of the run (this machine's too: a GPU case where CuPy or a CUDA device "
                        "is missing is refused as its run would be) and print the estimated result size, peak "
                        "memory and run time; run nothing")


def _add_steady(sub: Any) -> None:
    p = sub.add_parser("steady", help="steady sliding or rolling state(s) (direct solver)")
    _case_arguments(p)
    p.add_argument("--speeds", metavar="V1,V2,...", help="speed sweep [m/s], comma-separated")
    p.add_argument("--creepages", metavar="XI1,XI2,...", help="rolling: traction-creepage curve at the case's "
                   "rolling_speed, creepages [-] comma-separated (e.g. -0.01,-0.001,0,0.001)")
    p.add_argument("--quiet", action="store_true", help="no summary, no warnings")


def _add_material(sub: Any) -> None:
    p = sub.add_parser("material", help="the case's material: moduli, retardation times, a_T (and figures)")
    p.add_argument("case", metavar="CASE.toml", help="case file")
    p.add_argument("--plots", metavar="DIR", help="also draw G(t), J(t), G'(omega), G''(omega), tan delta into DIR")
    _figure_arguments(p)
    _set_argument(p)


def _add_plot(sub: Any) -> None:
    p = sub.add_parser("plot", help="figures of an existing result file")
    p.add_argument("result", metavar="RESULT.nc", help="result file of viscontact run, steady or sweep")
    p.add_argument("--out", required=True, metavar="DIR", help="folder for the figures")
    p.add_argument("--times", metavar="T1,T2,...", help="times [s] of the profiles and the pressure and stick/slip "
                   "maps, t = 0 included (the nearest records; default: evenly spread)")
    _figure_arguments(p)


def _add_export(sub: Any) -> None:
    p = sub.add_parser("export", help="tables of an existing result file (CSV)",
                       description="Write the scalar series of a result as a CSV table: of a run, one row per "
                       "record (t, load, delta_z, delta_x, contact_area, mu_app, friction_force, ...); of a steady "
                       "speed curve, one per speed; of a sweep, one per run. The first line names the columns "
                       "and their units.")
    p.add_argument("result", metavar="RESULT.nc", help="result file of viscontact run, steady or sweep")
    p.add_argument("--csv", required=True, metavar="OUT.csv", help="the table file to write")
    p.add_argument("--force", action="store_true", help="overwrite an existing table file")


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


def build_parser() -> Parser:
    parser = Parser(
        prog=PROG, description="Transient frictional contact of a rigid indenter on a linear viscoelastic body: "
        "indentation, partial slip, sliding, rolling and adhesion, in 3-D or as a line contact.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {cli_version()}")
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
