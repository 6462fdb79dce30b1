"""Signals during a command: SIGINT / SIGTERM stop a run after its current step
(:class:`StopSignals`), and a KeyboardInterrupt that Python had to drop is delivered again
(:func:`interrupts_redelivered`)."""
from __future__ import annotations

import os
import signal
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

__all__ = ["REDELIVERY_DELAY", "StopSignals", "interrupts_redelivered", "stop_on_signals"]


class StopSignals:
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
def stop_on_signals() -> Iterator[StopSignals]:
    """Handle SIGINT and SIGTERM with a :class:`StopSignals` while the body runs."""
    signals = StopSignals()
    previous = {sig: signal.signal(sig, signals.handle) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield signals
    finally:
        for sig, old in previous.items():
            signal.signal(sig, old)


#: seconds after which a KeyboardInterrupt that Python had to drop is delivered again
#: (:func:`interrupts_redelivered`)
REDELIVERY_DELAY = 0.005


@contextmanager
def interrupts_redelivered() -> Iterator[None]:
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
