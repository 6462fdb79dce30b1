"""Exceptions and warnings of viscontact. Each names its cause and, where there is one, the remedy."""
from __future__ import annotations

import os
import sys
import warnings


class ViscontactError(Exception):
    """Base class of every error viscontact raises on purpose."""


class ParameterError(ViscontactError, ValueError):
    """An input value is invalid. ``key`` is the dotted case-file key (``material.poisson_ratio``)."""

    def __init__(self, key: str, message: str) -> None:
        self.key = key
        self.message = message
        super().__init__(f"{key}: {message}")


class ConvergenceError(ViscontactError, RuntimeError):
    """An iterative solve did not reach its tolerance within its iteration cap."""

    def __init__(self, what: str, iterations: int, residual: float, tolerance: float, hint: str = "") -> None:
        self.what, self.iterations, self.residual, self.tolerance = what, iterations, residual, tolerance
        msg = (f"{what} did not converge: residual {residual:.3e} > tolerance {tolerance:.1e} "
               f"after {iterations} iterations")
        super().__init__(msg + (f"; {hint}" if hint else ""))


class NumericalGuardError(ViscontactError, RuntimeError):
    """The solution left its domain of validity (contact at the edge, NaN, load imbalance, ...)."""


class RunInterrupted(ViscontactError):
    """A run was asked to stop (SIGINT, SIGTERM) and did so after finishing its current step.
    ``reason`` says why; ``partial`` (set by :func:`viscontact.running.api.run`) holds the steps done."""

    def __init__(self, reason: str) -> None:
        self.reason = reason
        super().__init__(f"interrupted by {reason}")


class OutputReplacedError(ViscontactError, RuntimeError):
    """Another process replaced the file a run was writing, by its name (possible only when the run's
    lock file was removed under it): the run renames nothing. ``path`` is that file; ``kept`` is
    where this run's own result was saved instead, or None when it could not be saved."""

    def __init__(self, path: str, kept: str | None, why: str = "") -> None:
        self.path, self.kept = path, kept
        saved = (f"this run's result is kept in {kept}" if kept is not None
                 else f"this run's result could not be kept{f' ({why})' if why else ''} and is lost")
        super().__init__(f"{path}: another process replaced this file while this run was writing it (its lock "
                         f"file was removed); nothing was renamed, {saved}")


class ViscontactWarning(UserWarning):
    """A result is usable but something may bias it (history dropped, coarse time step, ...)."""


def check_type(value: object, expected: type | tuple[type, ...], what: str, described: str) -> None:
    """Raise :class:`TypeError` with a sentence (``"{what} must be {described}, got {type}"``) unless
    ``value`` is an instance of ``expected``: what the API says of a misused argument, in place of
    an AttributeError from deep inside.

    Parameters
    ----------
    value
        The argument given.
    expected
        The type, or types, it must have.
    what
        Its name in the sentence, e.g. ``"shipped_case's name"``.
    described
        What it must be, in words, e.g. ``"a str such as 'creep_indentation'"``.
    """
    if not isinstance(value, expected):
        raise TypeError(f"{what} must be {described}, got {type(value).__name__} {value!r:.60}")


#: the folder of the package's modules: :func:`warn_caller` skips the frames of files under it
_PACKAGE_PREFIX = os.path.dirname(os.path.abspath(__file__)) + os.sep


def warn_caller(message: str) -> None:
    """``warnings.warn(message, ViscontactWarning)`` attributed to the first frame outside the package: the
    user's line that called the API (:func:`viscontact.running.api.run`, :func:`~viscontact.running.api.run_to_file`, a
    generator such as :func:`viscontact.running.loop.simulate` where it is iterated), however deep in the
    package the warning is raised. A fixed ``stacklevel`` is right for one call path only. Python
    >= 3.12 skips the package's frames itself (``skip_file_prefixes``); before, they are counted here."""
    if sys.version_info >= (3, 12):
        warnings.warn(message, ViscontactWarning, skip_file_prefixes=(_PACKAGE_PREFIX,))
        return
    frame, level = sys._getframe(1), 2  # level 2: this function's caller
    while frame.f_back is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE_PREFIX):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, ViscontactWarning, stacklevel=level)


#: the exit status of a command stopped by SIGINT (128 + 2)
EXIT_INTERRUPTED = 130


def raised_by_interrupt(exc: BaseException | None) -> bool:
    """True when ``exc`` comes of a SIGINT: its chain of causes and contexts holds a KeyboardInterrupt
    or a SystemExit(:data:`EXIT_INTERRUPTED`) (a handler that exits by raising). An extension
    module interrupted while it initialises (pybind11's, such as scipy's HiGHS) raises
    ``ImportError: initialization failed`` from the interrupt instead of the interrupt itself."""
    seen: set[int] = set()
    while exc is not None and id(exc) not in seen:
        seen.add(id(exc))
        if isinstance(exc, KeyboardInterrupt) or (isinstance(exc, SystemExit) and exc.code == EXIT_INTERRUPTED):
            return True
        exc = exc.__cause__ or exc.__context__
    return False
