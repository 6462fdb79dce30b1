"""Hereditary (Boltzmann) history of the surface tractions, seed Eqs. 5-6.

With tractions piecewise in time and the creep compliance J(t) = J_inf - sum_m J_m exp(-t/lambda_m)
(see :mod:`viscontact.materials`), the displacement at step k is

    u_k = IC * [ sum_{n<=k} Phi(t_k - t_n) (p_n - p_{n-1}) ]                     (seed Eq. 5)

where ``Phi = J`` when the increment acts as a step at t_n (``scheme="constant"``, the seed's) and
``Phi(t_k - t_n) = (1/dt) int_{t_{n-1}}^{t_n} J(t_k - s) ds`` when the traction is linear within the
step (``scheme="linear"``, second order). The increment at t = 0 is always a step.

Recursive form: with one internal field per retardation time, H_m,k = A_m H_m,k-1 + beta_m,k dp_k,
A_m = exp(-dt/lambda_m), beta_m = 1 (step) or (lambda_m/dt)(1 - A_m) (ramp),

    u_k = IC * [ J_inst,k p_k + r_k ],  J_inst,k = J_inf - sum_m J_m beta_m,k,
    r_k = sum_m J_m (beta_m,k p_{k-1} - A_m H_m,k-1),

so each step is an elastic problem with compliance J_inst plus the known history traction r_k.
Cost per step is independent of the number of past steps. :class:`DirectHistory` evaluates Eq. 5
literally (all past increments kept) and is the reference the recursive form is tested against.

Both live on the grid of the moving frame: :meth:`shift` moves the stored material fields by one
cell towards -x (the half-space moves in -x relative to the indenter), unloaded material entering
at the leading (+x) edge, and returns what left at the trailing edge.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .materials import Material


def shift_material(field_: np.ndarray, cells: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Move a material field (..., n, n) by ``cells`` towards -x. Returns (shifted, dropped columns)."""
    dropped = field_[..., :cells].copy()
    out = np.empty_like(field_)
    out[..., :-cells] = field_[..., cells:]
    out[..., -cells:] = 0.0
    return out, dropped


@dataclass(frozen=True)
class StepCoefficients:
    """Per-step constants of the recursive history: decay A_m, weight beta_m, J_inst [1/Pa]."""

    decay: np.ndarray
    weight: np.ndarray
    instantaneous: float


def step_coefficients(material: Material, dt: float, scheme: str, first: bool) -> StepCoefficients:
    """A_m = exp(-dt/lambda_m), beta_m and J_inst for a step of length ``dt`` [s].

    ``first``: the increment at t = 0, always a step (beta = 1, J_inst = J_0).
    """
    c = material.creep
    lam = c.retardation_times
    decay = np.exp(-dt / lam) if lam.size else np.zeros(0)
    if first or scheme == "constant" or not lam.size:
        weight = np.ones_like(lam)
    elif scheme == "linear":
        weight = -np.expm1(-dt / lam) * lam / dt
    else:
        raise ValueError(f"time.scheme must be 'constant' or 'linear', got {scheme!r}")
    return StepCoefficients(decay, weight, float(c.long_term - np.dot(c.amplitudes, weight)))


def amplification(material: Material, dt: float, scheme: str) -> float:
    """Spectral radius of the step-to-step amplification of a traction disturbance [-].

    A disturbance e_k = z^k of the traction under a held displacement satisfies (recursive form above)
    J_inst + sum_m J_m beta_m (1 - A_m) / (z - A_m) = 0. The scheme is stable when every root has
    |z| <= 1. For one mode (Zener) z = A - J_1 beta (1 - A) / J_inst; with the seed's constant scheme
    it falls below -1 once dt > -lambda ln(1 - 2 G(inf)/G(0)): the solution then oscillates with
    growing amplitude. The linear scheme is stable for any dt.
    """
    coef = step_coefficients(material, dt, scheme, first=False)
    amps = material.creep.amplitudes
    if not amps.size:
        return 0.0
    poly = coef.instantaneous * np.polynomial.polynomial.polyfromroots(coef.decay)
    for m in range(amps.size):
        others = np.polynomial.polynomial.polyfromroots(np.delete(coef.decay, m))
        poly = np.polynomial.polynomial.polyadd(poly, amps[m] * coef.weight[m] * (1 - coef.decay[m]) * others)
    return float(np.max(np.abs(np.polynomial.polynomial.polyroots(poly))))


def stable_step_limit(material: Material, scheme: str) -> float:
    """Largest dt [s] for which :func:`amplification` <= 1 (inf when stable for every dt)."""
    if scheme == "linear" or not material.creep.amplitudes.size:
        return float("inf")
    lo, hi = 0.0, float(material.creep.retardation_times.max()) * 1e3
    if amplification(material, hi, scheme) <= 1.0:
        return float("inf")
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if amplification(material, mid, scheme) <= 1.0 else (lo, mid)
    return lo


@dataclass
class PronyHistory:
    """Recursive hereditary state of one traction component: H (M, n, n) and the previous traction."""

    internal: np.ndarray
    previous: np.ndarray

    @classmethod
    def zeros(cls, n_modes: int, n: int) -> "PronyHistory":
        return cls(np.zeros((n_modes, n, n)), np.zeros((n, n)))

    def traction(self, material: Material, coef: StepCoefficients) -> np.ndarray:
        """r_k = sum_m J_m (beta_m p_{k-1} - A_m H_m,k-1) [m/Pa x Pa, to convolve with IC at G = 1]."""
        amps = material.creep.amplitudes
        out = np.multiply(self.previous, float(np.dot(amps, coef.weight)))
        for m, d in enumerate(amps * coef.decay):
            out -= d * self.internal[m]
        return out

    def advance(self, current: np.ndarray, coef: StepCoefficients) -> None:
        """H_m,k = A_m H_m,k-1 + beta_m (p_k - p_{k-1}); previous <- p_k (in place)."""
        if self.internal.shape[0]:
            inc = np.subtract(current, self.previous)
            for m in range(self.internal.shape[0]):
                h = self.internal[m]
                h *= coef.decay[m]
                h += coef.weight[m] * inc
        np.copyto(self.previous, current)

    def shift(self, cells: int = 1) -> np.ndarray:
        """Move with the frame; returns the dropped internal columns (M, n, cells)."""
        self.internal, dropped = shift_material(self.internal, cells)
        self.previous, _ = shift_material(self.previous, cells)
        return dropped

    def long_term_traction(self, material: Material) -> np.ndarray:
        """sum_m J_m H_m [1/Pa x Pa]: the part of the history still to be recovered."""
        amps = material.creep.amplitudes
        if not amps.size:
            return np.zeros_like(self.previous)
        return np.tensordot(amps, self.internal, axes=1)


def _ramp_average_compliance(material: Material, t_from: np.ndarray, dt: float) -> np.ndarray:
    """(1/dt) int_{t_from}^{t_from+dt} J(s) ds by 8-point Gauss-Legendre (J is smooth there)."""
    nodes, weights = np.polynomial.legendre.leggauss(8)
    s = t_from[..., None] + 0.5 * dt * (nodes + 1.0)
    return 0.5 * (material.creep_compliance(s) * weights).sum(axis=-1)


@dataclass
class DirectHistory:
    """Literal hereditary sum of seed Eq. 5: keeps every past increment (reference, O(k) per step).

    ``increments`` holds dp_n as material fields on the current frame grid, ``times`` their t_n,
    ``ramps`` whether each acted as a ramp (linear scheme, n > 0).
    """

    n: int
    increments: list[np.ndarray] = field(default_factory=list)
    times: list[float] = field(default_factory=list)
    ramps: list[bool] = field(default_factory=list)
    previous: np.ndarray | None = None

    def traction(self, material: Material, t_now: float, dt: float, instantaneous: float) -> np.ndarray:
        """r_k = sum_{n<k} Phi(t_k, t_n) dp_n - J_inst p_{k-1}, Phi from J(t) directly."""
        out = np.zeros((self.n, self.n))
        for inc, tn, ramp in zip(self.increments, self.times, self.ramps):
            if ramp:
                phi = float(_ramp_average_compliance(material, np.array(t_now - tn), dt))
            else:
                phi = float(material.creep_compliance(t_now - tn))
            out += phi * inc
        if self.previous is not None:
            out -= instantaneous * self.previous
        return out

    def advance(self, current: np.ndarray, t_now: float, ramp: bool) -> None:
        prev = self.previous if self.previous is not None else np.zeros_like(current)
        self.increments.append(current - prev)
        self.times.append(t_now)
        self.ramps.append(ramp)
        self.previous = current.copy()

    def shift(self, cells: int = 1) -> None:
        self.increments = [shift_material(f, cells)[0] for f in self.increments]
        if self.previous is not None:
            self.previous = shift_material(self.previous, cells)[0]
