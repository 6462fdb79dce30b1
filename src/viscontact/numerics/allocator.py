"""The C allocator's settings for the solvers' short-lived arrays (glibc only; a no-op elsewhere).

A time step of the transient solver allocates and frees a few dozen arrays of 0.5-2 MiB (FFT
outputs, masked copies) per conjugate-gradient iteration. With glibc's defaults each of them is
either its own ``mmap`` or, once glibc's dynamic threshold has grown, heap memory that ``free``
trims back to the kernel at once: every iteration faults the same pages in again. At 256^2 that was
about 11 000 minor page faults per step and 22-28 % of the run's CPU time spent in the kernel
(BENCHMARKS.md). :func:`tune_allocator` raises the ``mmap`` threshold to 64 MiB and the trim
threshold to 256 MiB (``mallopt(M_MMAP_THRESHOLD)``, ``mallopt(M_TRIM_THRESHOLD)``: the same as the
environment variables ``MALLOC_MMAP_THRESHOLD_=67108864 MALLOC_TRIM_THRESHOLD_=268435456``), so the
freed blocks are reused from the heap. Both are needed: setting the ``mmap`` threshold alone turns
glibc's dynamic threshold off and trims as before. The price is that up to 256 MiB of freed heap
stay mapped to the process until it allocates again; the peak memory of a run does not change.

It is process-wide and applied once, when a transient run starts (:func:`viscontact.solvers.transient.steps`)
and when the ``viscontact`` command starts. It is skipped (the allocator keeps its settings):

* with the environment variable ``VISCONTACT_MALLOC=default`` (or ``off``, ``0``, ``no``, ``false``),
  the opt-out;
* when any of ``MALLOC_MMAP_THRESHOLD_``, ``MALLOC_TRIM_THRESHOLD_``, ``MALLOC_TOP_PAD_`` is set (the
  user's own settings win);
* on other platforms than Linux with glibc (macOS, Windows, musl), where it does nothing.
"""
from __future__ import annotations

import ctypes
import os
import sys

__all__ = ["OPT_OUT", "tune_allocator"]

#: environment variable of the opt-out
OPT_OUT = "VISCONTACT_MALLOC"
_OPT_OUT_VALUES = {"default", "off", "0", "no", "false"}
_USER_SETTINGS = ("MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_", "MALLOC_TOP_PAD_")
# mallopt parameters, glibc's <malloc.h>
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3
MMAP_THRESHOLD = 64 << 20  # bytes: blocks below it come from the heap
TRIM_THRESHOLD = 256 << 20  # bytes of free heap top kept before returning memory to the kernel

_applied: bool | None = None


def tune_allocator() -> bool:
    """Apply the allocator settings of the module docstring, once per process.

    Returns
    -------
    bool
        Whether they are in effect (applied now or by an earlier call); False when skipped.
    """
    global _applied
    if _applied is None:
        _applied = _apply()
    return _applied


def _apply() -> bool:
    if os.environ.get(OPT_OUT, "").strip().lower() in _OPT_OUT_VALUES:
        return False
    if any(name in os.environ for name in _USER_SETTINGS) or not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None)
        libc.gnu_get_libc_version  # noqa: B018 - glibc only (musl has mallopt as a stub)
        mallopt = libc.mallopt
    except (OSError, AttributeError):
        return False
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    mallopt.restype = ctypes.c_int
    # older glibc caps the mmap threshold at 32 MiB: fall back to the cap
    if not (mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD) or mallopt(_M_MMAP_THRESHOLD, 32 << 20)):
        return False
    return bool(mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD))
