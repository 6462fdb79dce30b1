"""The homogeneous viscoelastic half-space with a constant Poisson ratio: every influence
coefficient (Boussinesq-Cerruti, Love 1929) times the shear creep compliance J(t).

:class:`HomogeneousHalfSpace` is the body (:class:`~viscontact.bodies.base.Body`), :class:`HalfSpace`
its compliance (a :class:`~viscontact.bodies.compliance.Compliance`).
"""
from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, Sequence

import numpy as np

from viscontact.bodies.base import ContactShape, half_space_contact_radius
from viscontact.bodies.compliance import COMPONENT_ORDER, Term, Compliance, grid_transforms, ordered_components
from viscontact.numerics.arrays import CPU, ArrayBackend
from viscontact.numerics.convolution import Convolver, FourierPreconditioner
from viscontact.numerics.exponentials import CreepSpectrum, complex_compliance
from viscontact.numerics.grid import Grid
from viscontact.numerics.schemes import TimeScheme
from viscontact.physics.kernels import influence_coefficients
from viscontact.physics.materials import Material
from viscontact.physics.periodic import PeriodicConvolver
from viscontact.physics.reference import contact_modulus
from viscontact.physics.steady_kernels import SteadyKernelBuilder

Array = np.ndarray


class HalfSpace(Compliance):
    """Homogeneous viscoelastic half-space with constant Poisson ratio (kernels x J(t)).

    Terms ``zz``, ``zx`` (u_z of p, q_x) and ``xz``, ``xx`` (u_x), the kernels of
    :func:`~viscontact.physics.kernels.influence_coefficients` at G = 1 (on a periodic grid those of
    :func:`~viscontact.physics.periodic.periodic_influence_coefficients`, with unpadded FFTs); every term's
    time response is the material's shear creep compliance, so the histories are ``"z"`` (of p) and
    ``"x"`` (of q_x).

    Parameters
    ----------
    material
        The material (creep spectrum and Poisson ratio).
    components
        Kernels to build among ``zz``, ``xx``, ``xz``, ``zx`` (``zz`` always).
    workers
        FFT worker threads (-1: all cores above 512^2 cells, one below: :func:`~viscontact.numerics.fftbackends.fft_threads`).
    fft
        DC-FFT transforms by backend name (:func:`~viscontact.numerics.fftbackends.dcfft_transforms`; on a device
        ``backend``, its own FFT module's zero-block transforms).
    grid, scheme, dt, direct, backend
        As for :class:`Compliance`.
    """

    ORDER = COMPONENT_ORDER

    def __init__(self, grid: Grid, material: Material, components: Sequence[str], scheme: str | TimeScheme,
                 dt: float, *, workers: int = -1, direct: bool = False, fft: str = "scipy",
                 backend: ArrayBackend = CPU) -> None:
        comps = list(ordered_components(components))
        if grid.periodic:
            conv = PeriodicConvolver.for_grid(grid, material.poisson_ratio, workers, comps, xp=backend.xp,
                                              fft=backend.fft)
            precond = {c: conv.preconditioner(c) for c in ("zz", "xx") if c in comps}
        else:
            ics = {c: backend.to_device(k) for c, k in influence_coefficients(grid, material.poisson_ratio, comps).items()}
            conv = Convolver.from_kernels(grid.n, {c: ics[c] for c in comps}, workers, xp=backend.xp,
                                          fft=backend.fft, transforms=grid_transforms(grid.n, workers, fft, backend, grid.rows))
            precond = {c: FourierPreconditioner.for_kernel(ics[c], 1.0, workers, fft=backend.fft)
                       for c in ("zz", "xx") if c in comps}
        terms = [Term(c[0], c[1], c, c[1]) for c in comps]
        creep = material.creep
        super().__init__(grid, terms, {t.history: creep for t in terms}, conv, precond, scheme, dt, direct,
                         periodic=grid.periodic, backend=backend)
        self.material = material
        self.workers = workers
        self._steady_builders: dict[tuple[str, ...], SteadyKernelBuilder] = {}

    def steady_convolver(self, speed: float, components: Sequence[str] = ("zz",)
                         ) -> tuple[Convolver, dict[str, Array]]:
        """K(d) = J_0 IC(d) + sum_m J_m F_m(d) with L_m = v lambda_m (see :mod:`viscontact.solvers.steady`),
        all modes in one pass (:class:`~viscontact.physics.steady_kernels.SteadyKernelBuilder`, kept for
        the next speed); ``apply("zz", p)`` is u_z [m] of p [Pa]."""
        if self.periodic:  # exact in Fourier space
            return super().steady_convolver(speed, components)
        comps = tuple(components)
        builder = self._steady_builders.get(comps)
        if builder is None:
            builder = self._steady_builders[comps] = SteadyKernelBuilder(self.grid, self.material.poisson_ratio, comps)
        c = self.material.creep
        kernels = builder.effective(c.instantaneous, c.amplitudes, c.retardation_times, speed)
        return Convolver.from_kernels(self.grid.n, kernels, self.workers, xp=self.xp, fft=self.fft,
                                      transforms=self.convolver.transforms), kernels

    def steady_preconditioner(self, speed: float, workers: int = -1, symmetric: bool = False
                              ) -> FourierPreconditioner | None:
        """The steady operator's Fourier symbol is known here: in the indenter's frame the material
        point at x + xi was at x a time xi/v ago, so the shift xi -> exp(i k_x xi) turns the hereditary
        integral of :mod:`viscontact.solvers.steady` into the complex compliance at the frequency k_x v,

            K^(k) = IC^_zz(k) J*(k_x),   J*(k_x) = J_0 + sum_m J_m / (1 - i k_x v lambda_m),

        with IC^_zz the elastic symbol at unit modulus (the periodic one of the n x n grid, as for the
        transient's preconditioner). It carries the phase of the viscous lag that the symmetric part
        misses: 2.5-3x fewer GMRES iterations. ``symmetric``: Re K^ = IC^ Re J*. None on a periodic
        grid (its steady state is exact in Fourier space)."""
        if self.periodic or "zz" not in self.preconditioners:
            return None
        elastic = self.preconditioners["zz"]
        k_x = 2.0 * np.pi * np.fft.rfftfreq(self.grid.n, self.grid.spacing)
        j_star = complex_compliance(self.material.creep, -k_x * speed)
        symbol = j_star.real if symmetric else j_star
        return FourierPreconditioner(elastic.inverse_symbol / self.backend.to_device(symbol[None, :]), workers,
                                     elastic.fft)


def hertz_radius(load: float, sphere_radius: float, shear_modulus: float, poisson_ratio: float,
                 compliance_factor: float = 1.0) -> float:
    """Contact radius [m] of a rigid sphere (radius R [m]) on an elastic half-space (G [Pa], nu) under
    ``load`` W [N] (Hertz; Johnson, *Contact Mechanics*, 1985, Sec. 4.2): a^3 = 3 W R / (4 E*),
    E* = 2 G/(1 - nu); with every compliance ``compliance_factor`` c times larger (creep, Lee & Radok
    1960: a^3 ~ int J(t - s) dW(s)) a grows as c^(1/3)."""
    e_star = 2.0 * shear_modulus / (1.0 - poisson_ratio)
    return (3.0 * load * sphere_radius / (4.0 * e_star)) ** (1.0 / 3.0) * compliance_factor ** (1.0 / 3.0)


@dataclass(frozen=True)
class HomogeneousHalfSpace:
    """The homogeneous viscoelastic half-space of ``material`` with its constant Poisson ratio: a
    :class:`~viscontact.bodies.base.Body` whose compliance is :class:`HalfSpace` (one history per
    traction component, one kernel per component)."""

    material: Material

    #: the case adds no key for it
    description = MappingProxyType({})
    subsurface_stresses = True
    contact_model = "Lee & Radok creep"

    def compliance(self, grid: Grid, components: Sequence[str], scheme: str | TimeScheme, dt: float, *,
                   workers: int = -1, direct: bool = False, fft: str = "scipy",
                   backend: ArrayBackend | None = None) -> HalfSpace:
        """:class:`HalfSpace` of the material (``fft`` honoured on the CPU)."""
        return HalfSpace(grid, self.material, components, scheme, dt, workers=workers, direct=direct, fft=fft,
                         backend=backend or CPU)

    def stability_responses(self) -> list[CreepSpectrum]:
        """The shear creep compliance J(t) [1/Pa]."""
        return [self.material.creep]

    def size(self) -> tuple[int, int]:
        """M (retardation modes) history fields per traction component, one kernel per component."""
        return self.material.creep.retardation_times.size, 1

    def result_attributes(self) -> dict[str, Any]:
        """None beside the material's."""
        return {}

    def fingerprint(self) -> bytes:
        """Nothing: the half-space's fingerprint is what it was before bodies had one."""
        return b""

    def material_summary(self) -> str:
        return f"poisson_ratio = {self.material.poisson_ratio:g}"

    def contact_radius(self, load: float, shape: ContactShape, compliance_factor: float = 1.0) -> float:
        """The shape's elastic contact with E* = 2 G(0)/(1 - nu) (:func:`~viscontact.bodies.base.half_space_contact_radius`:
        Hertz for a sphere), crept as E*/``compliance_factor`` (Lee & Radok 1960)."""
        mat = self.material
        return half_space_contact_radius(load, shape, contact_modulus(mat.shear_modulus_instantaneous,
                                                                       mat.poisson_ratio), compliance_factor)

    def contact_radius_at_approach(self, approach: float, shape: ContactShape) -> float:
        """The shape's elastic relation, whatever the modulus (Hertz: a = sqrt(R delta) [m]; Johnson
        1985, Sec. 4.2)."""
        return shape.size_at_approach(approach)
