"""The surface grid: n x n square cells covering [-half_width, half_width]^2, or a line of n cells
along x (plane strain, ``dimension = 1``)."""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np


@dataclass(frozen=True)
class Grid:
    """Uniform cell-centred grid in the frame of the indenter.

    Cell ``(j, i)`` (row ``j`` along y, column ``i`` along x) covers
    ``[x_i - dx/2, x_i + dx/2] x [y_j - dx/2, y_j + dx/2]`` with ``x_i = -half_width + (i + 1/2) dx``
    and ``dx = 2 half_width / n``. Arrays on the grid have shape :attr:`shape`, ``(n, n)`` indexed ``[y, x]``.

    A line grid (``dimension = 1``, a plane-strain line contact) has one row at y = 0: its fields
    have shape ``(1, n)``, still indexed ``[y, x]``, depend on x only, and every area is per unit
    length along y (:attr:`cell_area` is dx [m], a force summed over it is in N/m).

    Parameters
    ----------
    n
        Cells per side.
    half_width
        Half the side of the square domain [m].
    periodic
        Whether the domain is one period of an infinitely repeated surface (periodic influence
        coefficients, unpadded FFTs, the moving frame wrapping around: :mod:`viscontact.physics.periodic`).
    dimension
        2: the square surface grid; 1: a line of cells along x (plane strain).
    """

    n: int
    half_width: float
    periodic: bool = False
    dimension: int = 2

    def __post_init__(self) -> None:
        """``grid.n`` an integer >= 2, ``grid.half_width`` a finite number > 0 m (else
        :class:`~viscontact.errors.ParameterError`, a ValueError)."""
        from viscontact.errors import ParameterError

        n, half_width = self.n, self.half_width
        if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)) or n < 2:
            raise ParameterError("grid.n", f"must be an integer >= 2, got {n!r}")
        if isinstance(half_width, (bool, np.bool_)) or not isinstance(half_width, (int, float, np.integer, np.floating)) \
                or not 0 < half_width < float("inf"):
            raise ParameterError("grid.half_width", f"must be a finite number > 0 m, got {half_width!r}")
        if self.dimension not in (1, 2) or isinstance(self.dimension, (bool, np.bool_)):
            raise ParameterError("grid.dimension", f"must be 1 (a line contact) or 2, got {self.dimension!r}")

    @property
    def rows(self) -> int:
        """Cells along y: n, or 1 on a line grid."""
        return self.n if self.dimension == 2 else 1

    @property
    def shape(self) -> tuple[int, int]:
        """Shape of a field on the grid, (rows, n) indexed [y, x]."""
        return (self.rows, self.n)

    @property
    def spacing(self) -> float:
        """Cell side dx [m]."""
        return 2.0 * self.half_width / self.n

    @property
    def cell_area(self) -> float:
        """Cell area dx^2 [m^2]; on a line grid the area per unit length, dx [m]."""
        return self.spacing**self.dimension

    @cached_property
    def x(self) -> np.ndarray:
        """Cell-centre coordinates along x (= along y) [m], shape (n,)."""
        return -self.half_width + (np.arange(self.n) + 0.5) * self.spacing

    @property
    def y(self) -> np.ndarray:
        """Cell-centre coordinates along y [m], shape (rows,): those of x, or (0,) on a line grid."""
        return self.x if self.dimension == 2 else np.zeros(1)

    def mesh(self) -> tuple[np.ndarray, np.ndarray]:
        """(X, Y) [m], each of shape :attr:`shape`, indexed [y, x]."""
        return np.meshgrid(self.x, self.y, indexing="xy")

    def refined(self, factor: int = 2) -> "Grid":
        """A grid on the same domain with ``factor`` times more cells per side."""
        return Grid(self.n * factor, self.half_width, self.periodic, self.dimension)

    def coarsened(self) -> "Grid":
        """The grid on the same domain with half the cells per side (n even)."""
        return Grid(self.n // 2, self.half_width, self.periodic, self.dimension)

    def block_mean(self, field: np.ndarray) -> np.ndarray:
        """``field`` (:attr:`shape`) averaged over each 2 x 2 block of cells (2 cells along x on a
        line grid): its values on :meth:`coarsened` (at the coarse cell centres to O(dx^2))."""
        coarse = self.coarsened()
        rows = 2 if self.dimension == 2 else 1
        return field.reshape(coarse.rows, rows, coarse.n, 2).mean(axis=(1, 3))

    def spread_blocks(self, coarse_field: np.ndarray) -> np.ndarray:
        """A field on :meth:`coarsened` spread on this grid: each coarse cell's value on its 2 x 2 fine
        cells (its 2 cells along x on a line grid)."""
        rows = 2 if self.dimension == 2 else 1
        return np.repeat(np.repeat(coarse_field, rows, axis=0), 2, axis=1)

    def offsets(self) -> np.ndarray:
        """Offsets between cell centres used by the DC-FFT kernel, shape (2n,) [m].

        Order: 0, dx, ..., (n-1) dx, (unused) n dx, -(n-1) dx, ..., -dx (FFT wrap-around order).
        """
        k = np.arange(2 * self.n)
        k = np.where(k <= self.n, k, k - 2 * self.n)
        return k * self.spacing

    def edge_values(self, field: np.ndarray) -> np.ndarray:
        """The values of ``field`` (:attr:`shape`) in the cells along the domain's boundary: its first and
        last rows and columns, or on a line grid its two end cells (y is unbounded there)."""
        if self.dimension == 1:
            return np.concatenate([field[:, 0], field[:, -1]])
        return np.concatenate([field[0], field[-1], field[:, 0], field[:, -1]])

    def row_offsets(self) -> np.ndarray:
        """Offsets along y of the DC-FFT kernel [m]: :meth:`offsets`, or (0,) on a line grid (one row:
        no other offset, no padding along y)."""
        return self.offsets() if self.dimension == 2 else np.zeros(1)

    @property
    def datum_distance(self) -> float:
        """Distance b [m] of the datum of a line grid's normal displacement from a line load: half the
        domain, ``half_width`` (plane strain defines displacements up to a constant;
        :func:`viscontact.physics.kernels.strip_influence`)."""
        return self.half_width


def mask_span(mask: np.ndarray, axis: int) -> tuple[int, int]:
    """[first, last + 1) of the rows (axis 0) or columns (axis 1) of a grid field where the boolean
    ``mask`` has a True (at least one)."""
    hit = np.flatnonzero(mask.any(axis=1 - axis))
    return int(hit[0]), int(hit[-1]) + 1


def shifted_periodic_x(field: np.ndarray, cells: float) -> np.ndarray:
    """The periodic grid field f(x + cells dx): ``field`` moved by ``cells`` (any real number of cells)
    towards -x, as its Fourier series along x (a mode exp(i k x) gains the phase exp(i k cells dx)).

    The whole cells are moved by :func:`numpy.roll` (exact, bit for bit); the fraction f of a cell
    multiplies each mode m of the real FFT along x by exp(2 pi i m f / n), exact for a field whose
    spectrum the grid holds (the Nyquist mode of an even n keeps its real part only, as the inverse
    real FFT does). A pure function: ``field`` is not changed.
    """
    whole = int(np.floor(cells))
    fraction = float(cells) - whole
    moved = np.roll(field, -whole, axis=1)
    if fraction == 0.0:
        return moved
    n = field.shape[1]
    phase = np.exp(2j * np.pi * np.fft.rfftfreq(n) * fraction)
    return np.fft.irfft(np.fft.rfft(moved, axis=1) * phase, n, axis=1)
