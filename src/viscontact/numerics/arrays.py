"""Array backends: where the solver's fields live and which library transforms them.

The solvers' numerics (:mod:`viscontact.numerics.constrained`, :mod:`viscontact.numerics.convolution`,
:mod:`viscontact.numerics.history`, :mod:`viscontact.numerics.support_window`, :mod:`viscontact.solvers.transient`,
:mod:`viscontact.numerics.krylov`, :mod:`viscontact.solvers.steady`, :mod:`viscontact.solvers.steady_periodic`) are
written against a numpy-compatible array namespace ``xp`` and a ``scipy.fft``-compatible FFT module,
which an :class:`ArrayBackend` names. The CPU backend :data:`CPU` is numpy and ``scipy.fft``; a
device library such as CuPy (with ``cupyx.scipy.fft``) follows numpy's API, and numpy's functions
dispatch to its arrays (``__array_function__``, ``__array_ufunc__``), so the same code carries its
fields if it keeps to these rules (the array seam):

* fields are made by the backend (``xp.zeros``) or from another field (``np.zeros_like(field)``,
  ``np.empty_like(field, shape=..., dtype=...)``: numpy hands those to the field's library), never by
  numpy from a shape;
* what is built once on the host (kernels, preconditioner symbols, the indenter's gap) moves to the
  device with :meth:`ArrayBackend.to_device`, once: a step copies no field to the device (the gap at
  each frame offset is shifted there, :meth:`~viscontact.problem.problem.Problem.frame_gaps`); what the
  results keep comes back with :attr:`ArrayBackend.to_host` (the record of each step: scalars and
  fields);
* no implicit conversion of a field (``np.asarray(field)``, ``np.array(field)``), no host array of
  one or more dimensions in an operation with fields, no ``.flat``;
* the FFT's ``workers`` only for ``scipy.fft`` (:func:`~viscontact.numerics.fftbackends.fft_keywords`),
  no ``where`` in reductions.

On the CPU backend every one of these is free: ``to_device`` and ``to_host`` return their argument,
and the arithmetic is the same. The test suite runs the transient and the steady solver on an
emulated device (numpy behind CuPy's rules, ``tests/emulated_device.py``) and checks that they equal
the numpy runs bit for bit and that a step after the first copies no field to the device; on a GPU
(CuPy, :func:`cupy_backend`: ``solver.device = "gpu"``) the same tests hold its runs to the numpy
runs to round-off (1e-10 of each field's peak, both solved to 1e-13: validated on an NVIDIA H200,
2026-11-28). Checkpoints save a device state through ``to_host`` and restore it to the device
(:mod:`viscontact.io.checkpoint`); the GMRES of the direct solve of strongly coupled gross sliding
(:meth:`~viscontact.solvers.contact_laws.NormalContact.solve_direct`) keeps its Krylov vectors on the device
and its small Hessenberg system on the host. The support windows of a device run take their padded
sides from :func:`device_fast_length`, whose few lengths keep cuFFT's plans (about 0.2 s each to
make) in use as a contact grows. CPU-only: the literal hereditary sum (the reference,
refused in one line on a device).
"""
from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType
from typing import Any, Callable

import numpy as np
import scipy.fft

__all__ = ["ArrayBackend", "CPU", "DEVICE_CHECK_EVERY", "array_backend", "cpu_fast_length", "cupy_backend", "device_fast_length",
           "device_free_memory"]


def cpu_fast_length(length: int) -> int:
    """``scipy.fft.next_fast_len(length, real=True)``: pocketfft's plans cost next to nothing, so every
    length with small prime factors will do (the tightest box)."""
    return scipy.fft.next_fast_len(length, real=True)


@dataclass(frozen=True)
class ArrayBackend:
    """An array namespace and its FFT module.

    Attributes
    ----------
    name
        Its name in messages (``"cpu"``).
    xp
        Array namespace with numpy's API (``numpy``, ``cupy``).
    fft
        FFT module with ``scipy.fft``'s 1-D and 2-D real and complex transforms (``scipy.fft``,
        ``cupyx.scipy.fft``).
    to_host
        A field of ``xp`` -> a numpy array (``numpy.asarray``: the same array; ``cupy.asnumpy``: a copy).
    """

    name: str
    xp: ModuleType
    fft: ModuleType
    to_host: Callable[[Any], np.ndarray]
    #: The smallest transform length >= its argument that this backend transforms fast and plans
    #: cheaply: the padded side 2m of a support window (:func:`viscontact.numerics.support_window.window_side`).
    #: On the CPU every 2^a 3^b 5^c length (:func:`cpu_fast_length`); on a GPU the coarse
    #: ladder of :func:`device_fast_length`, so that a creeping contact re-plans its transforms seldom.
    fast_length: Callable[[int], int] = cpu_fast_length
    #: Iterations of the constrained CG between two reads of its stopping test by the host: 1 on the
    #: CPU (:func:`~viscontact.numerics.constrained.constrained_cg` decides on the host every iteration, at
    #: no cost there); above 1 the solves of the support windows keep their scalars on the device
    #: (:func:`~viscontact.numerics.resident_cg.resident_cg`: no host round trip inside a block of
    #: ``check_every`` iterations).
    check_every: int = 1

    def to_device(self, array: Any) -> Any:
        """``array`` (numpy, built on the host) as a field of this backend (on the CPU: itself)."""
        return self.xp.asarray(array)

    @property
    def is_cpu(self) -> bool:
        """Whether the fields are numpy arrays."""
        return self.xp is np


def device_fast_length(length: int) -> int:
    """The smallest 2^k or 3 x 2^k >= ``length`` (ratios 4/3 and 3/2 between rungs).

    On a GPU a new transform length costs new cuFFT plans: the first kernel spectrum and product of a
    new window side took 0.18-0.51 s on an H200 (``benchmarks/device/plan_cost.py``), against 0.6-0.7 ms
    for the same product afterwards. With ``scipy.fft``'s lengths a creeping contact, whose window
    grows by a few cells a step, planned at every step: seed creep at 1024^2 took 0.66 s a step on
    the GPU, no faster than 16 CPU cores; on this ladder it takes 0.072 s (BENCHMARKS.md). The window
    changes side only when the contact grows by a third or more; the larger box costs little on a
    GPU, whose small transforms are bound by their launches."""
    if length <= 1:
        return 1
    power = 1 << (int(length) - 1).bit_length()  # the smallest 2^k >= length
    three = 3 * power // 4                        # 3 x 2^(k-2), between power / 2 and power
    return three if three >= length and power % 4 == 0 else power


#: numpy and scipy.fft (pocketfft)
CPU = ArrayBackend("cpu", np, scipy.fft, np.asarray)
#: a GPU's :attr:`ArrayBackend.check_every`: one read of four numbers every four iterations instead of
#: about twenty reads an iteration (each waits for the device's queue to drain)
DEVICE_CHECK_EVERY = 4


def array_backend(device: str) -> ArrayBackend:
    """The backend of ``solver.device``: :data:`CPU` for ``"cpu"``, :func:`cupy_backend` for ``"gpu"``.

    The run decides here, not the case's settings: a ``"gpu"`` case loads, validates and is estimated
    on any machine; the run (its preflight, :func:`viscontact.running.preflight.check_machine`) is
    refused on one without CuPy or a CUDA device.

    Raises
    ------
    ParameterError
        ``"gpu"`` without CuPy installed (naming the extra to install) or without a CUDA device, or an
        unknown device.
    """
    import importlib.util

    from viscontact.errors import ParameterError

    if device == "cpu":
        return CPU
    if device == "gpu":
        if importlib.util.find_spec("cupy") is None:
            raise ParameterError("solver.device", "'gpu' needs the optional package CuPy for the machine's CUDA "
                                 "(pip install 'viscontact[gpu]' for CUDA 12, 'viscontact[gpu-cuda13]' for CUDA 13); "
                                 "use 'cpu'")
        try:
            return cupy_backend()
        except ImportError as exc:
            raise ParameterError("solver.device", f"'gpu' needs CuPy and a CUDA device ({exc})") from None
    raise ParameterError("solver.device", f"must be 'cpu' or 'gpu', got {device!r}")


def cupy_backend() -> ArrayBackend:
    """CuPy and ``cupyx.scipy.fft`` on the current CUDA device, its window sides on
    :func:`device_fast_length`'s ladder (``solver.device = "gpu"``).

    Validated on an NVIDIA H200 (CuPy 14.2, CUDA 13): the test suite's backend tests run on it where
    CuPy finds a device and hold it to the numpy runs to round-off; it pays off from about 1024^2
    cells (docs/gpu.md: 5-11 times the 16 CPU cores of its host there; slower than they at 256^2).

    Raises
    ------
    ImportError
        CuPy is not installed, finds no CUDA device, or its FFT (cuFFT) fails on a 4 x 4 transform
        (an install without cuFFT's library, or one for another CUDA).
    """
    import cupy
    import cupyx.scipy.fft

    try:
        devices = cupy.cuda.runtime.getDeviceCount()
    except Exception as exc:  # CUDA's own error types: no driver, no runtime
        raise ImportError(f"CuPy finds no CUDA device: {exc}") from exc
    if not devices:
        raise ImportError("CuPy finds no CUDA device")
    try:  # an install without a working cuFFT (its library missing or of another CUDA) fails at the first transform
        cupyx.scipy.fft.rfft2(cupy.zeros((4, 4)))
    except Exception as exc:  # CuPy's and CUDA's own error types
        raise ImportError(f"CuPy's FFT (cuFFT) does not work: {_one_line(exc)}") from exc
    return ArrayBackend("gpu", cupy, cupyx.scipy.fft, cupy.asnumpy, device_fast_length, DEVICE_CHECK_EVERY)


def device_free_memory() -> int | None:
    """Memory free on the current CUDA device [bytes] (``cupy.cuda.runtime.memGetInfo``), or None where
    CuPy is not installed or finds no device (the run's machine check then refuses the run:
    :func:`array_backend`)."""
    try:
        import cupy

        return int(cupy.cuda.runtime.memGetInfo()[0])
    except Exception:  # noqa: BLE001 - no CuPy, no driver, no device: nothing to say
        return None


def _one_line(exc: BaseException) -> str:
    """An exception's message on one line (CUDA's span several)."""
    return " ".join(str(exc).split()) or type(exc).__name__
