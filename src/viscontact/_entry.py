"""The ``viscontact`` console command. Its first act is to make SIGINT during start-up (importing the
command line and its libraries takes a noticeable fraction of a second) one line and exit status
130 instead of a traceback; :func:`viscontact.cli.main` handles it from then on. Its second is the
allocator setting of :mod:`viscontact.numerics.allocator`."""
from __future__ import annotations

import os
import signal
import sys

from viscontact.errors import EXIT_INTERRUPTED, raised_by_interrupt


def _interrupted_at_start_up(signum: int, frame: object) -> None:  # noqa: ARG001
    """Say so and exit at once: nothing is written yet. No exception is raised: one raised where Python
    cannot propagate it (an import's module-lock callback) would be printed and dropped."""
    sys.stderr.write("viscontact: error: interrupted (no result file written)\n")
    sys.stderr.flush()
    os._exit(EXIT_INTERRUPTED)


def main() -> int:
    """Entry point of the ``viscontact`` console script."""
    previous = signal.signal(signal.SIGINT, _interrupted_at_start_up)
    from viscontact.numerics.allocator import tune_allocator

    tune_allocator()  # glibc settings for the solvers' temporaries (opt-out: VISCONTACT_MALLOC=default)
    try:
        from viscontact.cli import main as cli_main
    except ImportError as exc:  # an extension module's start-up interrupted: its ImportError is the SIGINT
        # (a guard: the handler above exits without raising, so this takes a handler that raises)
        if raised_by_interrupt(exc):
            raise SystemExit(EXIT_INTERRUPTED) from None
        raise

    signal.signal(signal.SIGINT, previous)
    return cli_main()
