"""Exact steady sliding on a periodic domain: every Fourier mode through the complex modulus.

In the frame of the indenter the half-space moves at -v along x (as in :mod:`viscontact.solvers.steady`):
a material point now at x was at x + xi a time xi/v ago. For steady tractions, the hereditary
integral (seed Eq. 5) of a Fourier mode exp(i k.x) of the elastic displacement [IC * p] is

    J_0 + sum_m J_m int_0^inf exp(-xi/(v lambda_m)) / (v lambda_m) exp(i k_x xi) dxi
        = J_0 + sum_m J_m / (1 - i k_x v lambda_m) = J*(omega = -k_x v) = 1 / G*(-k_x v),

the complex creep compliance at the angular frequency -k_x v, with G*(omega) = G'(omega) + i G''(omega)
(exp(i omega t) convention; G' even, G'' odd in omega). So on a periodic domain the steady operator
is diagonal in Fourier space,

    u_z^(k) = [K^_zz(k) + mu_f K^_zx(k)] p^(k) / G*(-k_x v),

with the periodic influence coefficients K of :mod:`viscontact.physics.periodic` (unit modulus) and
q_x = mu_f p under gross sliding (mu_f = 0: frictionless). Nothing is truncated: the whole past of
the material is in G*. For a full-contact sinusoid h0 cos(kx) under the mean pressure p_mean this
gives the hysteresis friction mu_app = k^2 h0^2 E''(kv) / (4 p_mean), E* = 2 G* / (1 - nu)
(derivation in docs/numerics.md), positive: it resists the motion of the indenter in +x.

The contact problem (p >= 0, gap >= 0, complementarity; load on one period or approach given) has a
non-symmetric operator and is solved by the active-set method of :mod:`viscontact.solvers.steady`. The
periodic operator has no q = 0 mode (zero-mean displacement, see :mod:`viscontact.physics.periodic`): under
load control it is given the compliance c of the lowest non-zero mode there, which only shifts the
multiplier, and the approach is reported in the zero-mean convention, delta_z = delta_c - c mean(p).
A body whose uniform compliance is bounded (a layer on a rigid base, :mod:`viscontact.bodies.layer`) keeps
its own q = 0 mode, and its approach is the plain one, as in its transient.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from viscontact.numerics.active_set import solve_contact_active_set
from viscontact.numerics.constrained import constrained_cg
from viscontact.numerics.convolution import FourierPreconditioner
from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material
from viscontact.physics.periodic import PeriodicConvolver, check_approach
from viscontact.physics.steady_kernels import steady_operator_spectrum
from viscontact.solvers.sliding import check_speed, hysteresis_force


def steady_spectrum(conv: PeriodicConvolver, material: Material, grid: Grid, speed: float,
                    friction: float = 0.0) -> np.ndarray:
    """Spectrum (n, n//2 + 1) of the steady operator p -> u_z [m per Pa] of the half-space of
    ``material``: (K^_zz + mu_f K^_zx) J*(-k_x v) (:func:`steady_operator_spectrum`)."""
    parts = [(conv.spectra["zz"], material.creep)]
    if friction > 0 and "zx" in conv.spectra:
        parts.append((friction * conv.spectra["zx"], material.creep))
    return steady_operator_spectrum(grid, speed, parts)


@dataclass(frozen=True)
class PeriodicSteadyOperator:
    """The steady operator p [Pa] -> u_z [m] of one period, set up for an active-set solve.

    Attributes
    ----------
    conv
        The periodic convolver whose FFTs apply the spectra.
    spectrum
        The steady operator's spectrum (n, n//2 + 1) [m per Pa] (zero-mean u_z unless the body bounds
        its uniform compliance).
    solve_spectrum
        The same with the q = 0 entry the solve uses (module docstring): the body's own when
        ``bounded``, else the lowest non-zero mode's compliance c under load control, 0 under
        displacement control.
    bounded
        Whether the body keeps its own q = 0 mode (a layer on a rigid base).
    preconditioner
        The Fourier preconditioner of the symmetric part of ``solve_spectrum``.
    """

    conv: PeriodicConvolver
    spectrum: np.ndarray
    solve_spectrum: np.ndarray
    bounded: bool
    preconditioner: FourierPreconditioner

    @classmethod
    def of(cls, conv: PeriodicConvolver, spectrum: np.ndarray, control: str) -> PeriodicSteadyOperator:
        """Set up ``spectrum`` for a solve under ``control`` ("load" or "displacement")."""
        # q = 0 compliance (module docstring); a body with a bounded uniform compliance (a layer on a rigid
        # base: h/M) keeps its own and reports the approach in that convention, as its transient does
        bounded = abs(spectrum[0, 0].real) > 1e-9 * abs(spectrum[0, 1].real)
        offset = float(spectrum[0, 0].real) if bounded else float(spectrum[0, 1].real) if control == "load" else 0.0
        spec_solve = spectrum.copy()
        spec_solve[0, 0] = offset
        symmetric = np.abs(spec_solve.real)
        symmetric[0, 0] = symmetric[0, 1]
        return cls(conv, spectrum, spec_solve, bounded, FourierPreconditioner(1.0 / symmetric, conv.workers, conv.fft))

    def apply(self, spectrum: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
        """p [Pa] -> the inverse FFT of ``spectrum`` times p's [m]."""
        conv = self.conv
        return lambda p: conv.inverse(spectrum * conv.spectrum(p))

    def approach(self, solved: float, pressure: np.ndarray) -> float:
        """The approach delta_z [m] reported of the approach ``solved`` [m] with ``solve_spectrum``:
        delta_c - c mean(p) in the zero-mean convention, unchanged for a bounded body."""
        return solved - (0.0 if self.bounded else float(self.solve_spectrum[0, 0].real)) * float(pressure.mean())


@dataclass(frozen=True)
class PeriodicSteadyState:
    """Steady sliding on one period.

    Attributes
    ----------
    pressure
        p [Pa], (n, n) indexed [y, x].
    displacement_z
        u_z [m], zero mean over the period.
    delta_z
        Approach [m] from the mean plane of the deformed surface.
    load
        Force on one period [N].
    hysteresis_force
        F_T [N] (seed Eq. 15), > 0 when it resists the motion of the indenter in +x.
    mu_app
        F_T / load.
    contact_area
        Real contact area [m^2].
    iterations, active_sets
        Krylov (GMRES) iterations of all active-set rounds, and the rounds.
    """

    pressure: np.ndarray
    displacement_z: np.ndarray
    delta_z: float
    load: float
    hysteresis_force: float
    mu_app: float
    contact_area: float
    iterations: int
    active_sets: int


def solve_periodic_steady(conv: PeriodicConvolver, material: Material, grid: Grid, gap: np.ndarray, *,
                          speed: float, control: str, value: float, friction: float = 0.0,
                          initial: np.ndarray | None = None, tolerance: float = 1e-10,
                          max_iterations: int = 2000, spectrum: np.ndarray | None = None,
                          to_host: Callable[[np.ndarray], np.ndarray] = np.asarray) -> PeriodicSteadyState:
    """Steady state of sliding at ``speed`` [m/s] on a periodic domain.

    Parameters
    ----------
    conv
        Periodic convolver with at least ``zz`` (and ``zx`` for a coupled friction term).
    material, grid, gap
        The half-space, the grid (one period) and the undeformed gap h0 [m] (n, n).
    speed
        Sliding speed v [m/s], > 0.
    control, value
        ``"load"`` with the force on one period [N], or ``"displacement"`` with the approach [m].
    friction
        mu_f for gross sliding (q_x = mu_f p), 0 for frictionless sliding.
    initial
        Pressure to start the active set from (e.g. the previous speed's).
    spectrum
        The steady operator's spectrum when the body is not the half-space of ``material``
        (:meth:`viscontact.bodies.compliance.Compliance.steady_spectrum`; ``material`` is then not used).
    to_host
        The array backend's copy to the host (:mod:`viscontact.numerics.arrays`) for the fields returned, when
        ``conv`` holds device fields.
    """
    check_speed(speed)
    if control == "displacement":
        check_approach(value, gap)
    spec = steady_spectrum(conv, material, grid, speed, friction) if spectrum is None else spectrum
    load_control = control == "load"
    op = PeriodicSteadyOperator.of(conv, spec, control)
    apply, spec_solve, precondition = op.apply, op.solve_spectrum, op.preconditioner
    gap = conv.xp.asarray(gap)
    if initial is None:  # Polonsky-Keer with the symmetric part: the right contact size to start from
        b = -gap if load_control else value - gap
        initial = constrained_cg(apply(spec_solve.real.astype(complex)), b, np.zeros_like(gap), 0.0, np.inf,
                                 total=value if load_control else None, cell_area=grid.cell_area,
                                 tolerance=1e-6, max_iterations=max_iterations, preconditioner=precondition).x
    p, delta, krylov, sets = solve_contact_active_set(apply(spec_solve), gap, control=control, value=value,
                                                      cell_area=grid.cell_area, initial=initial, tolerance=tolerance,
                                                      max_iterations=max_iterations, preconditioner=precondition)
    p, u_z = to_host(p), to_host(apply(spec)(p))
    delta = op.approach(delta, p)
    load = float(p.sum() * grid.cell_area)
    f_t = hysteresis_force(p, u_z, grid, periodic=True)
    return PeriodicSteadyState(p, u_z, float(delta), load, f_t, f_t / load if load > 0 else 0.0,
                               float((p > 0).sum() * grid.cell_area), krylov, sets)
