"""What the command line writes on stderr: one line per message (``viscontact: <level>: ...``), the
``viscontact`` logger's handler, warnings as lines, the progress bar, and the one error line."""
from __future__ import annotations

import argparse
import logging
import sys
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from viscontact.errors import ViscontactWarning

__all__ = ["PROG", "LineHandler", "ProgressBar", "configure_logging", "error", "log", "progress_bar", "say",
           "warnings_as_lines"]

PROG = "viscontact"
log = logging.getLogger("viscontact")


def say(line: str) -> None:
    """One line on stderr, without breaking a progress bar."""
    try:
        from tqdm import tqdm

        tqdm.write(line, file=sys.stderr)
    except ImportError:  # pragma: no cover - tqdm is a dependency
        print(line, file=sys.stderr)


class LineHandler(logging.Handler):
    """``viscontact: <level>: <message>`` on stderr, without breaking a progress bar."""

    def emit(self, record: logging.LogRecord) -> None:
        say(f"{PROG}: {record.levelname.lower()}: {' '.join(record.getMessage().split())}")


_HANDLER = LineHandler()


def configure_logging(level: str, quiet: bool) -> None:
    """The ``viscontact`` logger shows ``level`` and above on stderr; only errors when ``quiet``."""
    log.setLevel(logging.ERROR if quiet else getattr(logging, level.upper()))
    if _HANDLER not in log.handlers:
        log.addHandler(_HANDLER)
    log.propagate = False


@contextmanager
def warnings_as_lines(quiet: bool = False) -> Iterator[None]:
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


class ProgressBar:
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

    def __enter__(self) -> ProgressBar:
        return self

    def __exit__(self, *exc: object) -> None:
        if self.bar is not None:
            self.bar.close()


def progress_bar(args: argparse.Namespace, unit: str) -> ProgressBar:
    return ProgressBar(not args.quiet and sys.stderr.isatty(), unit)


def error(message: str, status: int) -> int:
    say(f"{PROG}: error: {' '.join(message.split())}")
    return status
