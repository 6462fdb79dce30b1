"""Time schemes of the hereditary integral (seed Eq. 5), registered by name.

With the creep compliance J(t) = J_0 + sum_m J_m (1 - exp(-t/lambda_m)) (a
:class:`~viscontact.numerics.exponentials.CreepSpectrum`) and tractions discretised in time, the displacement
at step k is u_k = IC * sum_{n<=k} Phi(t_k, t_n) dp_n. A scheme says how an increment dp_n acts
within its step:

* ``"constant"`` (the seed's, first order): as a step at t_n, Phi = J(t_k - t_n);
* ``"linear"`` (second order): as a ramp over [t_{n-1}, t_n],
  Phi = (1/dt) int_{t_{n-1}}^{t_n} J(t_k - s) ds.

The increment at t = 0 is always a step. In the recursive form (:mod:`viscontact.numerics.history`) a
scheme is its step weights beta_m (H_m,k = A_m H_m,k-1 + beta_m dp_k, A_m = exp(-dt/lambda_m));
in the direct form it is Phi. Both come from the same :class:`TimeScheme` object, looked up by
name with :func:`get_scheme`; a new scheme is a subclass added with :func:`register_scheme`.

Stability (:meth:`TimeScheme.amplification`): a traction disturbance under a held displacement
obeys J_inst e_k + sum_m J_m (beta_m e_{k-1} - A_m H_m,k-1) = 0 with the H update above. Its
amplification per step is the spectral radius of that linear recursion's companion matrix, taken
with ``numpy.linalg.eigvals`` (well conditioned for Prony series over many decades, unlike the
roots of the expanded characteristic polynomial).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from viscontact.errors import ParameterError
from viscontact.numerics.exponentials import CreepSpectrum

_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(8)


@dataclass(frozen=True)
class StepCoefficients:
    """Per-step constants of one time response for one step of length ``dt`` [s].

    Attributes
    ----------
    decay
        A_m = exp(-dt/lambda_m) [-].
    weight
        beta_m [-]: 1 for a step increment, (lambda_m/dt)(1 - A_m) for a ramp.
    instantaneous
        J_inst = J_inf - sum_m J_m beta_m [1/Pa]: the compliance of the step's own increment.
    spectrum, scheme, dt, first
        What they were computed from (the direct history evaluates Phi from them).
    """

    decay: np.ndarray
    weight: np.ndarray
    instantaneous: float
    spectrum: CreepSpectrum | None = None
    scheme: "TimeScheme | None" = None
    dt: float = 0.0
    first: bool = False


class TimeScheme:
    """A time discretisation of the hereditary integral (subclass and :func:`register_scheme`).

    Attributes
    ----------
    name
        Registry name (the ``time.scheme`` case key).
    order
        Order of accuracy in dt.
    """

    name: ClassVar[str] = ""
    order: ClassVar[int] = 0

    def ramps(self, first: bool) -> bool:
        """Whether the increment of a step acts as a ramp over the step (else as a step at its end)."""
        raise NotImplementedError

    def weights(self, retardation_times: np.ndarray, dt: float, first: bool) -> np.ndarray:
        """beta_m for a step of length ``dt`` [s]: 1 for a step, (lambda_m/dt)(1 - A_m) for a ramp."""
        if not self.ramps(first) or not retardation_times.size:
            return np.ones_like(retardation_times)
        return -np.expm1(-dt / retardation_times) * retardation_times / dt

    def coefficients(self, spectrum: CreepSpectrum, dt: float, first: bool) -> StepCoefficients:
        """A_m, beta_m and J_inst of ``spectrum`` for a step of ``dt`` [s] (``first``: the step at t = 0)."""
        lam = spectrum.retardation_times
        decay = np.exp(-dt / lam) if lam.size else np.zeros(0)
        weight = self.weights(lam, dt, first)
        return StepCoefficients(decay, weight, float(spectrum.long_term - np.dot(spectrum.amplitudes, weight)),
                                spectrum, self, dt, first)

    def response(self, spectrum: CreepSpectrum, age: float, dt: float, ramp: bool) -> float:
        """Phi [1/Pa]: displacement at unit modulus-kernel per unit increment, ``age`` = t_k - t_n [s].

        A step increment gives J(age); a ramp over the step gives the mean of J over
        [age, age + dt] (8-point Gauss-Legendre, exact to ~1e-15 for dt <= lambda_min).
        """
        if not ramp:
            return float(spectrum.compliance(age))
        s = age + 0.5 * dt * (_GL_NODES + 1.0)
        return float(0.5 * np.sum(spectrum.compliance(s) * _GL_WEIGHTS))

    def amplification(self, spectrum: CreepSpectrum, dt: float) -> float:
        """Spectral radius [-] of the step-to-step amplification of a traction disturbance.

        State x_k = (e_k, H_1,k, ..., H_M,k) under a held displacement (module docstring):
        e_k = -(1/J_inst) sum_m J_m (beta_m e_{k-1} - A_m H_m,k-1) and
        H_m,k = A_m H_m,k-1 + beta_m (e_k - e_{k-1}), i.e. x_k = T x_{k-1}. Returns ``max |eig(T)|``
        (``numpy.linalg.eigvals``). For one mode (Zener) with the constant scheme the non-zero
        eigenvalue is z = A - J_1 (1 - A) / J_inst.
        """
        amps = spectrum.amplitudes
        if not amps.size:
            return 0.0
        coef = self.coefficients(spectrum, dt, first=False)
        m = amps.size
        row = np.empty(m + 1)
        row[0] = -float(np.dot(amps, coef.weight)) / coef.instantaneous
        row[1:] = amps * coef.decay / coef.instantaneous
        companion = np.empty((m + 1, m + 1))
        companion[0] = row
        companion[1:] = coef.weight[:, None] * row[None, :]
        companion[1:, 0] -= coef.weight
        companion[1:, 1:] += np.diag(coef.decay)
        return float(np.max(np.abs(np.linalg.eigvals(companion))))

    def stability_limit(self, spectrum: CreepSpectrum) -> float:
        """Largest dt [s] with :meth:`amplification` <= 1 (inf when stable for every dt)."""
        raise NotImplementedError


class ConstantScheme(TimeScheme):
    """The seed's scheme: tractions constant within a step, increments act at its start (order 1)."""

    name = "constant"
    order = 1

    def ramps(self, first: bool) -> bool:
        return False

    def stability_limit(self, spectrum: CreepSpectrum) -> float:
        """Bisection on :meth:`amplification` over (0, 1e3 lambda_max] [s] (60 halvings)."""
        if not spectrum.amplitudes.size:
            return float("inf")
        lo, hi = 0.0, float(spectrum.retardation_times.max()) * 1e3
        if self.amplification(spectrum, hi) <= 1.0:
            return float("inf")
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if self.amplification(spectrum, mid) <= 1.0 else (lo, mid)
        return lo


class LinearScheme(TimeScheme):
    """Tractions linear within a step, exact integration of the exponentials (order 2).

    Unconditionally stable: the ramp-averaged compliance is a positive mixture of the exponentials."""

    name = "linear"
    order = 2

    def ramps(self, first: bool) -> bool:
        return not first

    def stability_limit(self, spectrum: CreepSpectrum) -> float:
        return float("inf")


#: the registered schemes, by name
SCHEMES: dict[str, TimeScheme] = {}


def register_scheme(scheme: TimeScheme) -> TimeScheme:
    """Add ``scheme`` to :data:`SCHEMES` under its name; returns it."""
    SCHEMES[scheme.name] = scheme
    return scheme


register_scheme(ConstantScheme())
register_scheme(LinearScheme())


def get_scheme(scheme: str | TimeScheme) -> TimeScheme:
    """The registered scheme of that name (a scheme object is returned as is)."""
    if isinstance(scheme, TimeScheme):
        return scheme
    try:
        return SCHEMES[scheme]
    except KeyError:
        raise ParameterError("time.scheme", f"must be one of {sorted(SCHEMES)}, got {scheme!r}") from None


def step_coefficients(spectrum: CreepSpectrum, dt: float, scheme: str | TimeScheme, first: bool) -> StepCoefficients:
    """A_m, beta_m and J_inst of ``spectrum`` for a step of ``dt`` [s] with the named scheme."""
    return get_scheme(scheme).coefficients(spectrum, dt, first)


def amplification(spectrum: CreepSpectrum, dt: float, scheme: str | TimeScheme) -> float:
    """:meth:`TimeScheme.amplification` of the named scheme."""
    return get_scheme(scheme).amplification(spectrum, dt)


def stable_step_limit(spectrum: CreepSpectrum, scheme: str | TimeScheme) -> float:
    """:meth:`TimeScheme.stability_limit` of the named scheme [s]."""
    return get_scheme(scheme).stability_limit(spectrum)
