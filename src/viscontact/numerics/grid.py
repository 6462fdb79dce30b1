"""The surface grid: n x n square cells covering [-half_width, half_width]^2."""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np


@dataclass(frozen=True)
class Grid:
    """Uniform cell-centred grid in the frame of the indenter.

    Cell ``(j, i)`` (row ``j`` along y, column ``i`` along x) covers
    ``[x_i - dx/2, x_i + dx/2] x [y_j - dx/2, y_j + dx/2]`` with ``x_i = -half_width + (i + 1/2) dx``
    and ``dx = 2 half_width / n``. Arrays on the grid have shape ``(n, n)`` indexed ``[y, x]``.

    Parameters
    ----------
    n
        Cells per side.
    half_width
        Half the side of the square domain [m].
    periodic
        Whether the domain is one period of an infinitely repeated surface (periodic influence
        coefficients, unpadded FFTs, the moving frame wrapping around: :mod:`viscontact.physics.periodic`).
    """

    n: int
    half_width: float
    periodic: bool = False

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

    @property
    def spacing(self) -> float:
        """Cell side dx [m]."""
        return 2.0 * self.half_width / self.n

    @property
    def cell_area(self) -> float:
        """Cell area dx^2 [m^2]."""
        return self.spacing**2

    @cached_property
    def x(self) -> np.ndarray:
        """Cell-centre coordinates along x (= along y) [m], shape (n,)."""
        return -self.half_width + (np.arange(self.n) + 0.5) * self.spacing

    @property
    def y(self) -> np.ndarray:
        return self.x

    def mesh(self) -> tuple[np.ndarray, np.ndarray]:
        """(X, Y) [m], each of shape (n, n), indexed [y, x]."""
        return np.meshgrid(self.x, self.y, indexing="xy")

    def refined(self, factor: int = 2) -> "Grid":
        """A grid on the same domain with ``factor`` times more cells per side."""
        return Grid(self.n * factor, self.half_width, self.periodic)

    def offsets(self) -> np.ndarray:
        """Offsets between cell centres used by the DC-FFT kernel, shape (2n,) [m].

        Order: 0, dx, ..., (n-1) dx, (unused) n dx, -(n-1) dx, ..., -dx (FFT wrap-around order).
        """
        k = np.arange(2 * self.n)
        k = np.where(k <= self.n, k, k - 2 * self.n)
        return k * self.spacing


def mask_span(mask: np.ndarray, axis: int) -> tuple[int, int]:
    """[first, last + 1) of the rows (axis 0) or columns (axis 1) of a grid field where the boolean
    ``mask`` has a True (at least one)."""
    hit = np.flatnonzero(mask.any(axis=1 - axis))
    return int(hit[0]), int(hit[-1]) + 1
