"""The steady effective kernel of a many-term Prony material, built for all modes in one pass.

In the frame of an indenter sliding at speed v the steady hereditary kernel is (see
:mod:`viscontact.solvers.steady`)

    K(d) = J_0 IC(d) + sum_m J_m F_m(d),   F_m(d) = int_0^inf exp(-xi/L_m)/L_m IC(d + xi) dxi,

with decay lengths L_m = v lambda_m. Built mode by mode (``kernels.history_kernels``) every mode
evaluates the influence coefficients IC at its own quadrature nodes, so the cost grows with the
number of terms. Here the x-integral is done by *product integration*: on each interval of a fixed
partition of xi, IC(d + xi) is replaced by its polynomial interpolant at Chebyshev-Lobatto nodes
xi_q, and the exponential weight is integrated exactly against each Lagrange basis polynomial:

    int_I exp(-xi/L)/L IC(d + xi) dxi ~ sum_q c_q(L) IC(d + xi_q),
    c_q(L) = int_I exp(-xi/L)/L l_q(xi) dxi                     (1-D, cheap, any L).

The nodes, hence the costly IC evaluations on the (2n, 2n) offset grid, do not depend on L: they
are computed once per grid (and reused for every speed of a sweep), and each mode only costs its
1-D weights and a (modes x nodes) matrix product. The accuracy is that of the polynomial
interpolation of IC, uniform in L; both limits are exact: L << dx gives c -> (1, 0, ...), i.e.
F = IC(d) (the mode acts instantaneously), and L -> inf gives F -> 0.

As in ``kernels.history_kernels`` the whole past is covered by the exact backward recursion over
the offsets d = -(n-1) dx ... (n-1) dx,

    F(d) = int_0^dx exp(-xi/L)/L IC(d + xi) dxi + exp(-dx/L) F(d + dx),

started from a tail integral to infinity at the largest offset (geometrically growing intervals
up to 45 L_max, where exp(-45) ~ 3e-20). IC(d + xi) is analytic in xi on [0, dx] except, in the
row dy = 0 and the two columns next to d = 0, at the cell edge xi = dx/2 (an x log x point); the
partition of [0, dx] is graded geometrically towards dx/2 from both sides.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Iterable, Mapping, Sequence

import numpy as np

from viscontact.numerics.exponentials import CreepSpectrum, complex_compliance
from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import (
    cell_influence,
    influence_coefficients,
    lattice_rectangle_influence,
    offset_columns_to_kernels,
)

#: exp(-45) ~ 3e-20: beyond 45 decay lengths a mode's weight is below double precision
_DECAY_CUTOFF = 45.0
_FINE_NODES, _FINE_WEIGHTS = np.polynomial.legendre.leggauss(16)


def lobatto_nodes(degree: int) -> tuple[np.ndarray, np.ndarray]:
    """Chebyshev-Lobatto nodes on [0, 1] (ascending, ends included) and their barycentric weights."""
    j = np.arange(degree + 1)
    nodes = 0.5 * (1.0 - np.cos(np.pi * j / degree))
    bary = (-1.0) ** j
    bary[[0, -1]] *= 0.5
    return nodes, bary


def lagrange_basis(x: np.ndarray, nodes: np.ndarray, bary: np.ndarray) -> np.ndarray:
    """Lagrange basis polynomials l_q(x) of ``nodes`` (barycentric formula), shape (x.size, nodes.size)."""
    diff = x[:, None] - nodes[None, :]
    exact = diff == 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        terms = bary[None, :] / diff
        out = terms / terms.sum(axis=1, keepdims=True)
    hit = exact.any(axis=1)
    out[hit] = exact[hit].astype(float)
    return out


def _graded_unit_rule(levels: int = 10) -> tuple[np.ndarray, np.ndarray]:
    """Composite 16-point Gauss-Legendre on [0, 1] with breaks 2^-k, k = 0..levels (and 0)."""
    breaks = np.concatenate([[0.0], 0.5 ** np.arange(levels, -1, -1)])
    lo, hi = breaks[:-1], breaks[1:]
    nodes = ((0.5 * (hi - lo))[:, None] * (_FINE_NODES + 1.0) + lo[:, None]).ravel()
    weights = ((0.5 * (hi - lo))[:, None] * _FINE_WEIGHTS).ravel()
    return nodes, weights


#: in t = xi/L the weight is exp(-t) on [0, T], T <= 45: graded down to T/1024 < 1/16
_UNIT_NODES, _UNIT_WEIGHTS = _graded_unit_rule()


def product_weights(start: float, stop: float, degree: int, lengths: np.ndarray) -> np.ndarray:
    """c_mq = int_start^stop exp(-xi/L_m)/L_m l_q(xi) dxi for the Chebyshev-Lobatto basis of degree
    ``degree`` on [start, stop] [m]; ``lengths`` L_m [m]. Shape (modes, degree + 1), dimensionless.

    In t = (xi - start)/L the integral is exp(-start/L) int_0^beta exp(-t) l_q(t/beta) dt with
    beta = (stop - start)/L, cut at T = min(beta, 45) (the rest is below double precision) and
    done with one composite Gauss-Legendre rule graded towards t = 0, the same for every mode.
    """
    nodes, bary = lobatto_nodes(degree)
    lengths = np.asarray(lengths, dtype=float)
    out = np.zeros((lengths.size, degree + 1))
    live = start / lengths < 746.0  # exp(-746) underflows to 0
    if not live.any():
        return out
    lengths = lengths[live]
    beta = (stop - start) / lengths
    cut = np.minimum(beta, _DECAY_CUTOFF)
    t = cut[:, None] * _UNIT_NODES[None, :]
    w = cut[:, None] * _UNIT_WEIGHTS[None, :] * np.exp(-t - (start / lengths)[:, None])
    basis = lagrange_basis((t / beta[:, None]).ravel(), nodes, bary).reshape(*t.shape, degree + 1)
    out[live] = np.einsum("mf,mfq->mq", w, basis)
    return out


def _local_breaks(spacing: float, grading: int) -> np.ndarray:
    """Partition of [0, dx], graded geometrically towards the cell edge dx/2 from both sides."""
    h = 0.5 * spacing
    steps = h * 0.5 ** np.arange(1, grading + 1)  # h/2, h/4, ...
    left = h - steps
    right = h + steps
    return np.unique(np.concatenate([[0.0, h, spacing], left, right]))


@dataclass
class SteadyKernelBuilder:
    """Effective steady kernels of one grid for any creep spectrum and speed (product integration).

    Parameters
    ----------
    grid
        The grid (cell-centred, spacing dx [m]).
    poisson_ratio
        nu [-].
    components
        Influence components to build (``"zz"``, ``"zx"``, ...).
    degree
        Polynomial degree of the interpolation of IC on each interval.
    grading
        Geometric refinement levels towards the cell edge xi = dx/2 on each side.

    point_kernel
        Another kernel than the half-space's: ``point_kernel(dx, dy)`` gives the cell kernels (by
        component) at any offsets dx, dy [m] (broadcast arrays), e.g. the part of a layer's kernel
        known in closed form (:func:`viscontact.bodies.layer.steady_shapes`); ``poisson_ratio`` is then
        not used.
    smooth
        A further smooth part known only on a grid: ``smooth(shifts)`` gives its values at the
        x offsets -(n-1) dx + shift ... (-(n-1) + X - 1) dx + shift [m] for each shift in [0, dx],
        shape (shifts, components, 2n y offsets in wrap order, X), X >= 2n - 1, and nothing beyond
        (it must have decayed there). Its F_m are integrated over those X offsets only, by the same
        recursion, with product weights on a two-interval partition of [0, dx].

    The IC values at the local nodes (``len(components)`` x nodes x (2n)^2 doubles) are computed on
    first use and kept, so a speed sweep pays for them once.
    """

    grid: Grid
    poisson_ratio: float
    components: tuple[str, ...] = ("zz", "zx")
    degree: int = 6
    grading: int = 2
    point_kernel: Callable[[np.ndarray, np.ndarray], Mapping[str, np.ndarray]] | None = None
    smooth: Callable[[np.ndarray], np.ndarray] | None = None
    _local: tuple | None = field(default=None, init=False, repr=False)
    _tail_ic: dict = field(default_factory=dict, init=False, repr=False)
    _base_ic: dict | None = field(default=None, init=False, repr=False)
    _smooth_values: tuple | None = field(default=None, init=False, repr=False)

    # --- IC on the offset grid ------------------------------------------------------------
    def _ic(self, dx_offsets: np.ndarray, dy_offsets: np.ndarray) -> np.ndarray:
        if self.point_kernel is not None:
            res = self.point_kernel(dx_offsets, dy_offsets)
        else:
            res = cell_influence(self.grid, dx_offsets, dy_offsets, self.poisson_ratio, self.components)
        return np.stack([np.broadcast_to(res[c], np.broadcast(dx_offsets, dy_offsets).shape)
                         for c in self.components])

    @property
    def _x_offsets(self) -> np.ndarray:
        n = self.grid.n
        return self.grid.spacing * np.arange(-(n - 1), n)

    def _local_nodes(self) -> tuple[list[tuple[float, float]], list[np.ndarray], np.ndarray]:
        """(intervals of [0, dx], node indices of each interval's Lobatto nodes, IC at every node for
        every offset but the largest, shape (2n - 2, nodes, components * 2n))."""
        if self._local is None:
            dx = self.grid.spacing
            breaks = _local_breaks(dx, self.grading)
            unit, _ = lobatto_nodes(self.degree)
            positions: list[float] = []
            index: list[np.ndarray] = []
            for a, b in zip(breaks[:-1], breaks[1:]):
                idx = []
                for x in a + (b - a) * unit:
                    hit = [i for i, p in enumerate(positions) if abs(p - x) <= 1e-12 * dx]
                    if not hit:
                        positions.append(float(x))
                    idx.append(hit[0] if hit else len(positions) - 1)
                index.append(np.array(idx))
            dy = self.grid.row_offsets()[:, None]
            d = self._x_offsets[:-1]
            values = np.empty((d.size, len(positions), len(self.components) * dy.size))
            for q, x in enumerate(positions):
                # another kernel than the half-space's, at any offset, or the strips of a line grid
                if self.point_kernel is not None or self.grid.dimension == 1:
                    values[:, q, :] = self._ic(d[None, :] + x, dy).reshape(-1, d.size).T
                    continue
                ic = lattice_rectangle_influence(d[0] + x, d.size, dx, dy[:, 0], self.poisson_ratio, self.components)
                for ci, c in enumerate(self.components):  # [x offset, component * 2n + y offset]
                    values[:, q, ci * dy.size: (ci + 1) * dy.size] = ic[c]
            self._local = (list(zip(breaks[:-1], breaks[1:])), index, values)
        return self._local

    def _base(self) -> dict[str, np.ndarray]:
        """IC at the integer offsets (``kernels.influence_coefficients``), kept (half-space only)."""
        if self.point_kernel is not None or self.smooth is not None:
            raise ValueError("effective() is for the half-space kernels; add the term's own kernel to history()")
        if self._base_ic is None:
            ics = influence_coefficients(self.grid, self.poisson_ratio)
            self._base_ic = {c: ics[c] for c in self.components}
        return self._base_ic

    # --- the kernels ----------------------------------------------------------------------
    def history(self, amplitudes: Sequence[float], lengths: Sequence[float]) -> dict[str, np.ndarray]:
        """sum_m J_m F_m(d) on the (2n, 2n) DC-FFT offset grid (wrap order, row/column n zero).

        Parameters
        ----------
        amplitudes
            J_m [1/Pa] (or any weights).
        lengths
            Decay lengths L_m = v lambda_m [m], > 0.
        """
        amps = np.asarray(amplitudes, dtype=float)
        lengths = np.asarray(lengths, dtype=float)
        n, dx = self.grid.n, self.grid.spacing
        n_comp = len(self.components)
        rows = self.grid.row_offsets().size
        if amps.size == 0:
            return {c: np.zeros((rows, 2 * n)) for c in self.components}
        intervals, index, local_ic = self._local_nodes()
        weights = np.zeros((lengths.size, local_ic.shape[1]))
        for (a, b), idx in zip(intervals, index):
            np.add.at(weights, (slice(None), idx), product_weights(a, b, self.degree, lengths))
        running = self._tail(lengths)  # (M, C * 2n) at the largest offset
        decay = np.exp(-dx / lengths)[:, None]
        values = np.empty((2 * n - 1, n_comp * rows))
        values[-1] = amps @ running
        for i in range(2 * n - 3, -1, -1):
            running = weights @ local_ic[i] + decay * running
            values[i] = amps @ running
        if self.smooth is not None:
            values += self._smooth_history(amps, lengths)
        return offset_columns_to_kernels(values.T.reshape(n_comp, rows, 2 * n - 1), self.components)

    def _smooth_history(self, amps: np.ndarray, lengths: np.ndarray) -> np.ndarray:
        """sum_m J_m F_m of the ``smooth`` part at the offsets -(n-1) dx ... (n-1) dx, shape
        (2n - 1, C * 2n): the backward recursion from its last offset (F = 0 beyond it)."""
        n, dx = self.grid.n, self.grid.spacing
        if self._smooth_values is None:
            breaks = (0.0, 0.5 * dx, dx)
            unit, _ = lobatto_nodes(self.degree)
            shifts = np.unique(np.concatenate([a + (b - a) * unit for a, b in zip(breaks[:-1], breaks[1:])]))
            index = [np.searchsorted(shifts, a + (b - a) * unit) for a, b in zip(breaks[:-1], breaks[1:])]
            sampled = np.asarray(self.smooth(shifts), dtype=float)  # (S, C, 2n, X)
            sampled = sampled.reshape(shifts.size, -1, sampled.shape[-1]).transpose(2, 0, 1)  # (X, S, C * 2n)
            self._smooth_values = (list(zip(breaks[:-1], breaks[1:])), index, np.ascontiguousarray(sampled))
        intervals, index, sampled = self._smooth_values
        weights = np.zeros((lengths.size, sampled.shape[1]))
        for (a, b), idx in zip(intervals, index):
            np.add.at(weights, (slice(None), idx), product_weights(a, b, self.degree, lengths))
        decay = np.exp(-dx / lengths)[:, None]
        running = np.zeros((lengths.size, sampled.shape[2]))
        out = np.empty((2 * n - 1, sampled.shape[2]))
        for i in range(sampled.shape[0] - 1, -1, -1):
            running = weights @ sampled[i] + decay * running
            if i < 2 * n - 1:
                out[i] = amps @ running
        return out

    def _tail(self, lengths: np.ndarray) -> np.ndarray:
        """F_m at the largest offset d_max = (n-1) dx, shape (M, C * 2n): int_0^inf on intervals
        [s (1.5^k - 1), s (1.5^(k+1) - 1)], s = d_max, up to 45 L_max. IC at their nodes is kept."""
        d_max = self._x_offsets[-1]
        scale = max(d_max, self.grid.spacing)
        top = _DECAY_CUTOFF * float(lengths.max())
        unit, _ = lobatto_nodes(self.degree)
        dy = self.grid.row_offsets()[:, None]
        out = np.zeros((lengths.size, len(self.components) * dy.size))
        k = 0
        while True:
            a, b = scale * (1.5**k - 1.0), scale * (1.5 ** (k + 1) - 1.0)
            c = product_weights(a, b, self.degree, lengths)
            if k not in self._tail_ic:
                ic = self._ic(d_max + a + (b - a) * unit[None, :], dy)  # (C, 2n, q)
                self._tail_ic[k] = ic.transpose(2, 0, 1).reshape(unit.size, -1)
            out += c @ self._tail_ic[k]
            if b >= top:
                return out
            k += 1

    def effective(self, instantaneous: float, amplitudes: Sequence[float], retardation_times: Sequence[float],
                  speed: float) -> dict[str, np.ndarray]:
        """K = J_0 IC + sum_m J_m F_m with L_m = speed * lambda_m: the steady kernel [m/Pa per Pa of
        traction per cell... i.e. displacement = K (*) traction], J in 1/Pa, lambda in s, speed in m/s."""
        base = self._base()
        hist = self.history(amplitudes, speed * np.asarray(retardation_times, dtype=float))
        return {c: instantaneous * base[c] + hist[c] for c in self.components}


@dataclass(frozen=True)
class SteadyShape:
    """The kernel of a compliance term (:class:`~viscontact.bodies.compliance.ComplianceTerm`) as
    builders know it: K = sum_i factor_i K_i, K_i the kernel ``component_i`` of ``builder_i``, so
    that its steady history kernel is sum_i factor_i (sum_m J_m F_m[K_i]) with the term's own
    spectrum J_m (e.g. the nu = 0 and nu = 1 half-space kernels of :mod:`viscontact.bodies.bulk_elastic`, or a
    layer's kernel, :func:`viscontact.bodies.layer.steady_shapes`).

    Attributes
    ----------
    parts
        (builder, component, factor) triples; builders shared between shapes keep their node values
        for all of them.
    """

    parts: tuple[tuple[SteadyKernelBuilder, str, float], ...]

    def history(self, amplitudes: Sequence[float], lengths: Sequence[float]) -> np.ndarray:
        """sum_m J_m F_m[K](d) [m/Pa per Pa] on the (2n, 2n) DC-FFT offset grid; J_m [1/Pa], L_m [m]."""
        out = None
        for builder, component, factor in self.parts:
            part = factor * builder.history(amplitudes, lengths)[component]
            out = part if out is None else out + part
        return out


def steady_history_kernels(grid: Grid, poisson_ratio: float, amplitudes: Sequence[float],
                           lengths: Sequence[float], components: Sequence[str] = ("zz", "zx")
                           ) -> dict[str, np.ndarray]:
    """sum_m J_m F_m(d) for all modes at once (see :class:`SteadyKernelBuilder`); J_m [1/Pa],
    decay lengths L_m [m]."""
    return SteadyKernelBuilder(grid, poisson_ratio, tuple(components)).history(amplitudes, lengths)


def steady_operator_spectrum(grid: Grid, speed: float, parts: Iterable[tuple[np.ndarray, CreepSpectrum]]
                             ) -> np.ndarray:
    """Spectrum (n, n//2 + 1) of a steady operator p -> u_z [m per Pa] on a periodic grid: the sum over
    ``parts`` (a kernel spectrum K^ at unit modulus, its creep compliance) of K^ phi*(-k_x v), with
    phi*(omega) the complex compliance (:func:`~viscontact.numerics.exponentials.complex_compliance`): in
    the frame of the indenter sliding at ``speed`` v [m/s] a Fourier mode exp(i k.x) of the material
    is seen at the angular frequency -k_x v."""
    omega = -2 * np.pi * np.fft.rfftfreq(grid.n, grid.spacing)[None, :] * speed
    out = None
    for spectrum, compliance in parts:  # the compliance (host) moved to the spectrum's library
        part = spectrum * np.asarray(complex_compliance(compliance, omega), like=spectrum)
        out = part if out is None else out + part
    return out
