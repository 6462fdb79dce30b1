"""Hereditary (Boltzmann) history of one traction component under one time response, seed Eqs. 5-6.

With tractions piecewise in time and a time response (creep compliance)
J(t) = J_inf - sum_m J_m exp(-t/lambda_m) (a :class:`~viscontact.numerics.exponentials.CreepSpectrum`), the
displacement at step k is

    u_k = IC * [ sum_{n<=k} Phi(t_k - t_n) dp_n ]                                 (seed Eq. 5)

with Phi given by the time scheme (:mod:`viscontact.numerics.schemes`: a step or a ramp per increment).

Recursive form (:class:`PronyHistory`): with one internal field per retardation time,
H_m,k = A_m H_m,k-1 + beta_m,k dp_k, A_m = exp(-dt/lambda_m), beta_m from the scheme,

    u_k = IC * [ J_inst,k p_k + r_k ],  J_inst,k = J_inf - sum_m J_m beta_m,k,
    r_k = sum_m J_m (beta_m,k p_{k-1} - A_m H_m,k-1),

so each step is an elastic problem with compliance J_inst plus the known history traction r_k.
Cost per step is independent of the number of past steps. :class:`DirectHistory` evaluates Eq. 5
literally (all past increments kept) and is the reference the recursive form is tested against.

Both follow one protocol, driven by the step's :class:`~viscontact.numerics.schemes.StepCoefficients`
(which carry the spectrum, the scheme and dt):

* ``known(coef, t)``: r_k [m/Pa x Pa, to convolve with the unit-modulus kernel];
* ``advanced(p_k, coef, t)``: the history after step k (a new object: histories are immutable);
* ``shifted(cells, coef, wrap)``: the history after the frame moved, and the internal fields H_m of
  the columns that left at the trailing edge (for :class:`~viscontact.solvers.sliding.Wake`); with ``wrap``
  (a periodic domain) they re-enter at the leading edge.

Both live on the grid of the moving frame: a shift moves the stored material fields by whole cells
towards -x (the half-space moves in -x relative to the indenter), unloaded material entering at
the leading (+x) edge.
"""
from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType
from typing import Protocol

import numpy as np

from viscontact.numerics.schemes import StepCoefficients


def shift_material(field_: np.ndarray, cells: int = 1, wrap: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Move a material field (..., n, n) by ``cells`` towards -x. Returns (shifted, dropped columns).

    Unloaded material (zeros) enters at +x, or with ``wrap`` (a periodic domain) what left at -x."""
    dropped = field_[..., :cells].copy()
    out = np.empty_like(field_)
    out[..., :-cells] = field_[..., cells:]
    out[..., -cells:] = dropped if wrap else 0.0
    return out, dropped


def field_shape(n: int | tuple[int, int]) -> tuple[int, int]:
    """The shape of a field on n x n cells, or ``n`` itself when it is a shape (rows, cells)."""
    return (n, n) if isinstance(n, (int, np.integer)) else tuple(n)


class History(Protocol):
    """What the transient solver needs of a hereditary history (see the module docstring)."""

    def known(self, coef: StepCoefficients, t: float) -> np.ndarray: ...

    def advanced(self, current: np.ndarray, coef: StepCoefficients, t: float) -> "History": ...

    def shifted(self, cells: int, coef: StepCoefficients, wrap: bool = False) -> tuple["History", np.ndarray]: ...


@dataclass(frozen=True)
class PronyHistory:
    """Recursive hereditary state: internal fields H (M, n, n) and the previous traction (n, n)
    (fields of any grid's shape: (M, 1, n) and (1, n) on a line grid)."""

    internal: np.ndarray
    previous: np.ndarray

    @classmethod
    def zeros(cls, n_modes: int, n: int | tuple[int, int], xp: ModuleType = np) -> "PronyHistory":
        """The history before the first step on n x n cells (or fields of the shape ``n``, a grid's
        ``shape``), its fields made by the array namespace ``xp`` (:mod:`viscontact.numerics.arrays`)."""
        shape = field_shape(n)
        return cls(xp.zeros((n_modes, *shape)), xp.zeros(shape))

    def known(self, coef: StepCoefficients, t: float) -> np.ndarray:
        """r_k = sum_m J_m (beta_m p_{k-1} - A_m H_m,k-1) [m/Pa x Pa, to convolve with IC at G = 1]."""
        amps = coef.spectrum.amplitudes
        out = np.multiply(self.previous, float(np.dot(amps, coef.weight)))
        for m, d in enumerate(amps * coef.decay):
            out -= d * self.internal[m]
        return out

    def advanced(self, current: np.ndarray, coef: StepCoefficients, t: float) -> "PronyHistory":
        """H_m,k = A_m H_m,k-1 + beta_m (p_k - p_{k-1}); previous = p_k."""
        internal = self.internal
        if internal.shape[0]:
            inc = np.subtract(current, self.previous)
            internal = np.empty_like(self.internal)
            for m in range(internal.shape[0]):
                np.multiply(self.internal[m], coef.decay[m], out=internal[m])
                internal[m] += coef.weight[m] * inc
        return PronyHistory(internal, current.astype(float))  # a copy

    def shifted(self, cells: int, coef: StepCoefficients, wrap: bool = False) -> tuple["PronyHistory", np.ndarray]:
        """Moved with the frame; also returns the dropped internal columns (M, n, cells)."""
        internal, dropped = shift_material(self.internal, cells, wrap)
        return PronyHistory(internal, shift_material(self.previous, cells, wrap)[0]), dropped


@dataclass(frozen=True)
class DirectHistory:
    """Literal hereditary sum of seed Eq. 5: keeps every past increment (reference, O(k) per step).

    ``increments`` holds dp_n as material fields on the current frame grid, ``times`` their t_n,
    ``ramps`` whether each acted as a ramp over its step (from the scheme); ``n`` the cells per side,
    or the fields' shape (a line grid's (1, n)).
    """

    n: int | tuple[int, int]
    increments: tuple[np.ndarray, ...] = ()
    times: tuple[float, ...] = ()
    ramps: tuple[bool, ...] = ()
    previous: np.ndarray | None = None

    def known(self, coef: StepCoefficients, t: float) -> np.ndarray:
        """r_k = sum_{n<k} Phi(t_k, t_n) dp_n - J_inst p_{k-1}, Phi from the scheme and J(t) directly."""
        out = np.zeros(field_shape(self.n))
        for inc, tn, ramp in zip(self.increments, self.times, self.ramps):
            out += coef.scheme.response(coef.spectrum, t - tn, coef.dt, ramp) * inc
        if self.previous is not None:
            out -= coef.instantaneous * self.previous
        return out

    def advanced(self, current: np.ndarray, coef: StepCoefficients, t: float) -> "DirectHistory":
        prev = self.previous if self.previous is not None else np.zeros_like(current)
        return DirectHistory(self.n, self.increments + (current - prev,), self.times + (float(t),),
                             self.ramps + (coef.scheme.ramps(coef.first),), np.array(current, dtype=float, copy=True))

    def internal_fields(self, coef: StepCoefficients) -> np.ndarray:
        """H_m (M, n, n) of the equivalent recursive history after the last increment:
        sum_n exp(-(t_last - t_n)/lambda_m) beta_m,n dp_n (beta_m,n from the scheme)."""
        lam = coef.spectrum.retardation_times
        out = np.zeros((lam.size, *field_shape(self.n)))
        if not self.times:
            return out
        ramp_weight = coef.scheme.weights(lam, coef.dt, first=False) if lam.size else lam
        for inc, tn, ramp in zip(self.increments, self.times, self.ramps):
            weight = np.exp(-(self.times[-1] - tn) / lam) * (ramp_weight if ramp else 1.0)
            out += weight[:, None, None] * inc
        return out

    def shifted(self, cells: int, coef: StepCoefficients, wrap: bool = False) -> tuple["DirectHistory", np.ndarray]:
        """Moved with the frame; also returns the dropped columns of :meth:`internal_fields`."""
        dropped = self.internal_fields(coef)[..., :cells]
        previous = shift_material(self.previous, cells, wrap)[0] if self.previous is not None else None
        return DirectHistory(self.n, tuple(shift_material(f, cells, wrap)[0] for f in self.increments), self.times,
                             self.ramps, previous), dropped
