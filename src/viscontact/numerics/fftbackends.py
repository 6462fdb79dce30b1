"""FFT backends of the DC-FFT convolution: zero-block transforms, optionally planned with FFTW.

The DC-FFT (:mod:`viscontact.numerics.convolution`) transforms an (n, n) field zero-padded to (2n, 2n) and
keeps only the (n, n) physical block of the inverse transform. A full 2-D real transform does twice
the row work needed:

* forward: the real FFT along x (length 2n) of the n non-zero rows only, then the complex FFT along
  y (length 2n, the zero rows implied) of the n + 1 columns;
* inverse: the complex inverse FFT along y of the n + 1 columns, then the inverse real FFT along x
  of the n kept rows only.

That is half of the row transforms both ways, the same result to round-off (the same sums, in
another order). Backends, by name (``solver.fft``):

``"scipy"``
    :class:`ZeroBlockTransforms` with ``scipy.fft`` (pocketfft) and its ``workers`` threads; any
    module with numpy.fft's 1-D ``rfft``/``fft``/``ifft``/``irfft`` and an ``axis`` argument works
    (e.g. ``cupyx.scipy.fft``), so the array namespace can change without this code changing.
``"pyfftw"``
    :class:`FFTWTransforms`: the same scheme with FFTW plans made once per grid on pre-allocated
    aligned buffers (optional dependency ``pyFFTW``, extra ``fast``).

Every backend has ``forward(field) -> spectrum (2n, n+1)``, ``inverse(spectrum) -> (n, n)`` and
``convolve(kernel_spectrum, field) -> (n, n)``, the product of one forward and one inverse.

A line grid (one row of n cells, plane strain: ``rows = 1``) needs no padding along y: its fields
(1, n) are padded to (1, 2n) only, the spectrum is (1, n+1) and the transform along y (of length 1)
is the identity (:func:`padded_rows`).
"""
from __future__ import annotations

from types import ModuleType
from typing import Protocol

import numpy as np
import scipy.fft

__all__ = ["BACKENDS", "DCFFTTransforms", "FFTWTransforms", "SINGLE_THREAD_SIZE", "ZeroBlockTransforms",
           "check_fft_backend", "dcfft_transforms", "fft_keywords", "fft_threads", "padded_rows"]

#: grids of up to this many cells (n x n) transform on one thread when ``workers = -1``: a second pocketfft
#: thread costs more wall time than it saves below (2-core machine, quiet, padded pair of the DC-FFT:
#: n = 256 4.6 ms with one thread against 6.2-9.3 ms with two; n = 512 20.5 against 22.0 ms; n = 1024
#: 95 against 69 ms; the unpadded preconditioner pair: 256^2 2.2 against 2.5 ms CPU; BENCHMARKS.md)
SINGLE_THREAD_SIZE = 512 * 512


def padded_rows(rows: int) -> int:
    """Rows of the DC-FFT's padded field for a field of ``rows`` rows: 2 rows (the aperiodic
    convolution along y), or 1 for a single row (a line grid: the only y offset is 0)."""
    return 2 * rows if rows > 1 else 1


def fft_threads(workers: int, cells: int) -> int:
    """The threads of a transform on a grid of ``cells`` points (n x n) for the ``workers`` setting:
    ``-1`` (the default, "all cores where they win") is 1 up to :data:`SINGLE_THREAD_SIZE` cells and -1
    (all cores) above; an explicit count is used as given."""
    return 1 if workers == -1 and cells <= SINGLE_THREAD_SIZE else workers


def fft_keywords(fft: ModuleType, workers: int, cells: int) -> dict[str, int]:
    """The thread keyword of a transform by ``fft`` on ``cells`` points: ``workers`` (:func:`fft_threads`)
    for ``scipy.fft``; none for other modules (``cupyx.scipy.fft`` takes no ``workers``)."""
    return {"workers": fft_threads(workers, cells)} if fft is scipy.fft else {}


class DCFFTTransforms(Protocol):
    """The transforms of the DC-FFT on an n x n grid (padded to 2n x 2n)."""

    n: int

    def forward(self, field: np.ndarray) -> np.ndarray:
        """Spectrum (2n, n+1) of ``field`` (n, n) zero-padded to (2n, 2n); a new array."""

    def inverse(self, spectrum: np.ndarray) -> np.ndarray:
        """The (n, n) block of the inverse transform of ``spectrum`` (2n, n+1), which it may
        overwrite."""

    def convolve(self, kernel_spectrum: np.ndarray, field: np.ndarray) -> np.ndarray:
        """inverse(kernel_spectrum * forward(field)): the aperiodic convolution, (n, n)."""


class ZeroBlockTransforms:
    """Zero-block DC-FFT transforms with a numpy.fft-like module (default ``scipy.fft``).

    Parameters
    ----------
    n
        Cells per side (along x).
    workers
        Threads of ``scipy.fft`` (-1: all cores above :data:`SINGLE_THREAD_SIZE` cells, one below:
        :func:`fft_threads`; ignored for modules without ``workers``).
    fft
        The 1-D transform module.
    rows
        Rows of the fields (along y): ``n`` (None) on the square grid, 1 on a line grid.
    """

    def __init__(self, n: int, workers: int = -1, fft: ModuleType = scipy.fft, rows: int | None = None) -> None:
        self.n = n
        self.rows = n if rows is None else rows
        self.workers = workers
        self.fft = fft
        self._kw = fft_keywords(fft, workers, n * self.rows)
        self._overwrite = {"overwrite_x": True} if fft is scipy.fft else {}

    def forward(self, field: np.ndarray) -> np.ndarray:
        """The (2n, n+1) real FFT of ``field`` (n, n) zero-padded to (2n, 2n): the real FFT of the n
        non-zero rows, then the column FFT, with the padding written into two work arrays instead of
        copied by the transforms and the column transforms in place in the second (scipy.fft's
        ``overwrite_x``): the spectrum returned is the only array that outlives the call. A single
        row: its (1, n+1) real FFT (:func:`padded_rows`)."""
        n, m, fft = self.n, self.rows, self.fft
        rows = np.empty_like(field, shape=(m, 2 * n))
        rows[:, :n] = field
        rows[:, n:] = 0.0
        if m == 1:
            return fft.rfft(rows, axis=1, **self._kw)
        spectrum = np.empty_like(field, shape=(2 * m, n + 1), dtype=np.result_type(field.dtype, np.complex64))
        spectrum[:m] = fft.rfft(rows, axis=1, **self._kw)          # (n, n+1): the non-zero rows
        spectrum[m:] = 0.0                                         # the zero rows
        return fft.fft(spectrum, axis=0, **self._kw, **self._overwrite)  # in place with scipy.fft

    def inverse(self, spectrum: np.ndarray) -> np.ndarray:
        n, m, fft = self.n, self.rows, self.fft
        columns = spectrum if m == 1 else fft.ifft(spectrum, axis=0, **self._kw, **self._overwrite)[:m]
        return fft.irfft(columns, n=2 * n, axis=1, **self._kw)[:, :n]

    def convolve(self, kernel_spectrum: np.ndarray, field: np.ndarray) -> np.ndarray:
        """:meth:`inverse` of ``kernel_spectrum * forward(field)``, the product in place: the (n, n)
        block returned is the only array that outlives the call."""
        spectrum = self.forward(field)
        spectrum *= kernel_spectrum
        return self.inverse(spectrum)


class FFTWTransforms:
    """Zero-block DC-FFT transforms with FFTW plans (pyFFTW) on buffers allocated once.

    ``convolve`` runs entirely in the plans' buffers (one copy in, one copy out); ``forward`` and
    ``inverse`` copy their result out as well, so every returned array is the caller's.

    Parameters
    ----------
    n
        Cells per side.
    threads
        FFTW threads (1 unless the machine has idle cores: threads cost more than they save for
        these sizes on a loaded machine, see BENCHMARKS.md).
    planner
        FFTW planner effort (``"FFTW_ESTIMATE"``, ``"FFTW_MEASURE"``...).
    rows
        Rows of the fields (along y): ``n`` (None) on the square grid, 1 on a line grid.
    """

    def __init__(self, n: int, threads: int = 1, planner: str = "FFTW_MEASURE", rows: int | None = None) -> None:
        import pyfftw  # optional dependency (extra "fast")

        self.n = n
        self.rows = m = n if rows is None else rows
        self._rows = pyfftw.empty_aligned((m, 2 * n), dtype="float64")
        self._spectrum = pyfftw.empty_aligned((padded_rows(m), n + 1), dtype="complex128")
        flags = (planner,)
        head = self._spectrum[:m]
        self._rows_forward = pyfftw.FFTW(self._rows, head, axes=(1,), direction="FFTW_FORWARD", flags=flags,
                                         threads=threads)
        self._columns_forward = pyfftw.FFTW(self._spectrum, self._spectrum, axes=(0,), direction="FFTW_FORWARD",
                                            flags=flags, threads=threads)
        self._columns_inverse = pyfftw.FFTW(self._spectrum, self._spectrum, axes=(0,), direction="FFTW_BACKWARD",
                                            flags=flags, threads=threads)
        self._rows_inverse = pyfftw.FFTW(head, self._rows, axes=(1,), direction="FFTW_BACKWARD",
                                         flags=flags + ("FFTW_DESTROY_INPUT",), threads=threads)
        self._scale = 1.0 / (4.0 * n * n) if m == n else 1.0 / (2.0 * n * padded_rows(m))
        self._rows[:] = 0.0  # planning may have written to the buffers

    def _forward_in_place(self, field: np.ndarray) -> None:
        n = self.n
        self._rows[:, :n] = field
        self._rows[:, n:] = 0.0
        self._rows_forward()
        self._spectrum[self.rows:] = 0.0
        self._columns_forward()

    def _inverse_in_place(self) -> np.ndarray:
        self._columns_inverse(normalise_idft=False)
        self._rows_inverse(normalise_idft=False)
        return self._rows[:, : self.n] * self._scale

    def forward(self, field: np.ndarray) -> np.ndarray:
        self._forward_in_place(field)
        return self._spectrum.copy()

    def inverse(self, spectrum: np.ndarray) -> np.ndarray:
        self._spectrum[:] = spectrum
        return self._inverse_in_place()

    def convolve(self, kernel_spectrum: np.ndarray, field: np.ndarray) -> np.ndarray:
        self._forward_in_place(field)
        np.multiply(self._spectrum, kernel_spectrum, out=self._spectrum)
        return self._inverse_in_place()


#: backend name -> constructor(n, workers[, rows]) (rows only for a grid that is not square: a line's 1)
BACKENDS = {
    "scipy": lambda n, workers, rows=None: ZeroBlockTransforms(n, workers, rows=rows),
    "pyfftw": lambda n, workers, rows=None: FFTWTransforms(n, threads=max(workers, 1), rows=rows),
}


def dcfft_transforms(name: str, n: int, workers: int = -1, rows: int | None = None) -> DCFFTTransforms:
    """The DC-FFT transforms of backend ``name`` (see :data:`BACKENDS`) for an n x n grid (``rows`` x n:
    a line grid's one row).

    Raises
    ------
    ValueError
        Unknown backend.
    ImportError
        ``"pyfftw"`` without pyFFTW installed.
    """
    if name not in BACKENDS:
        raise ValueError(f"unknown FFT backend {name!r}; expected one of {sorted(BACKENDS)}")
    return BACKENDS[name](n, workers) if rows in (None, n) else BACKENDS[name](n, workers, rows)


def check_fft_backend(name: str) -> None:
    """Refuse the backend ``name`` (``solver.fft``) where its library is not installed: ``"pyfftw"``
    without pyFFTW (checked at the start of a run, :func:`viscontact.running.preflight.check_machine`:
    the case's setting is valid on any machine).

    Raises
    ------
    ParameterError
        Key ``solver.fft``, naming the extra to install.
    """
    import importlib.util

    from viscontact.errors import ParameterError

    if name == "pyfftw" and importlib.util.find_spec("pyfftw") is None:
        raise ParameterError("solver.fft", "'pyfftw' needs the optional package pyFFTW "
                             "(pip install 'viscontact[fast]'); use 'scipy'")
