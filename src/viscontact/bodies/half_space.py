"""The homogeneous viscoelastic half-space with a constant Poisson ratio: every influence
coefficient (Boussinesq-Cerruti, Love 1929) times the shear creep compliance J(t)."""
from __future__ import annotations

from typing import Sequence

import numpy as np

from viscontact.bodies.compliance import Term, TermSubstrate
from viscontact.numerics.arrays import CPU, ArrayBackend
from viscontact.numerics.convolution import Convolver, FourierPreconditioner
from viscontact.numerics.fftbackends import ZeroBlockTransforms, dcfft_transforms
from viscontact.numerics.grid import Grid
from viscontact.numerics.schemes import TimeScheme
from viscontact.physics.kernels import influence_coefficients
from viscontact.physics.materials import Material
from viscontact.physics.periodic import PeriodicConvolver
from viscontact.physics.steady_kernels import SteadyKernelBuilder

Array = np.ndarray


class HalfSpace(TermSubstrate):
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
        As for :class:`TermSubstrate`.
    """

    ORDER = ("zz", "zx", "xz", "xx")

    def __init__(self, grid: Grid, material: Material, components: Sequence[str], scheme: str | TimeScheme,
                 dt: float, *, workers: int = -1, direct: bool = False, fft: str = "scipy",
                 backend: ArrayBackend = CPU) -> None:
        comps = [c for c in self.ORDER if c in set(components) | {"zz"}]
        if grid.periodic:
            conv = PeriodicConvolver.for_grid(grid, material.poisson_ratio, workers, comps, xp=backend.xp,
                                              fft=backend.fft)
            precond = {c: conv.preconditioner(c) for c in ("zz", "xx") if c in comps}
        else:
            ics = {c: backend.to_device(k) for c, k in influence_coefficients(grid, material.poisson_ratio, comps).items()}
            transforms = (dcfft_transforms(fft, grid.n, workers) if backend.is_cpu
                          else ZeroBlockTransforms(grid.n, workers, backend.fft))
            conv = Convolver.from_kernels(grid.n, {c: ics[c] for c in comps}, workers, xp=backend.xp,
                                          fft=backend.fft, transforms=transforms)
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
        if self.periodic:
            raise NotImplementedError("a periodic steady state is exact in Fourier space: viscontact.solvers.steady_periodic")
        comps = tuple(components)
        builder = self._steady_builders.get(comps)
        if builder is None:
            builder = self._steady_builders[comps] = SteadyKernelBuilder(self.grid, self.material.poisson_ratio, comps)
        c = self.material.creep
        kernels = builder.effective(c.instantaneous, c.amplitudes, c.retardation_times, speed)
        return Convolver.from_kernels(self.grid.n, kernels, self.workers, xp=self.xp, fft=self.fft,
                                      transforms=self.convolver.transforms), kernels
