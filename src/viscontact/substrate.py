"""The substrate (compliance): what the surface does under a traction history.

Data model (linear viscoelasticity, seed Eqs. 5-6): the surface displacement u_i (i in z, x) is a
sum over TERMS,

    u_i = sum_terms K_term * (phi_term (*) dq_j),

a term being (displacement component i, traction component j, a real-space kernel K at unit
modulus, a time response phi(t) = J_0 + sum_m J_m (1 - exp(-t/lambda_m)) given as a
:class:`~viscontact.materials.CreepSpectrum`). Terms that read the same traction component through
the same time response share one hereditary history (:mod:`viscontact.history`): a history is
keyed by :attr:`Term.history` and carries one traction component.

:class:`TermSubstrate` turns (terms, responses, a convolver, preconditioners) into what the contact
solvers use, and is all a new substrate has to provide:

* :meth:`~TermSubstrate.elastic_operator`: the step's elastic operator for the normal (``zz``) or
  tangential (``xx``) solve: action, Fourier preconditioner, sparse action;
* :meth:`~TermSubstrate.cross_displacement`: the step's instantaneous coupling (``zx``, ``xz``);
* :meth:`~TermSubstrate.known_displacement`: (u_z, u_x) of the history state;
* :meth:`~TermSubstrate.advanced`, :meth:`~TermSubstrate.shifted`: the history after a step / a
  frame shift (new objects; nothing is mutated);
* :meth:`~TermSubstrate.steady_convolver`: the effective kernel of steady sliding at a speed;
* :meth:`~TermSubstrate.free_mean`: whether a uniform traction leaves the mean displacement
  undetermined (a periodic half-space);
* ``backend`` (:class:`~viscontact.arrays.ArrayBackend`: the array namespace ``xp`` and the FFT
  module ``fft`` of the fields, ``to_host`` for what the results keep).

:class:`HalfSpace` is the homogeneous half-space with constant Poisson ratio (Boussinesq-Cerruti
kernels of :mod:`viscontact.kernels`, all four terms sharing the material's creep compliance, so
one history per traction component). Other substrates plug in by building other terms:

* a time-dependent Poisson ratio: the same kernels split into parts, each term its own computed
  spectrum (histories keyed e.g. ``"z:normal"``, ``"z:coupling"``);
* a layer on an elastic substrate: one kernel (and one single-mode term) per relaxation mode;
* a periodic domain: periodic kernels and a convolver with the same methods (``apply``,
  ``apply_sparse``, ``combine``, ``displacements``, ``spectrum``, ``inverse``) on unpadded
  transforms, and its own :meth:`~TermSubstrate.steady_convolver`.

The contact solvers (:mod:`viscontact.transient`, :mod:`viscontact.steady`) see only this interface.
"""
from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass
from types import ModuleType
from typing import Callable, Mapping, Sequence

import numpy as np

from .arrays import CPU, ArrayBackend, array_backend, cpu_fast_length
from .convolution import Convolver, FourierPreconditioner
from .errors import ParameterError
from .fftbackends import ZeroBlockTransforms, dcfft_transforms
from .grid import Grid
from .history import DirectHistory, History, PronyHistory
from .kernels import influence_coefficients
from .materials import CreepSpectrum, Material
from .periodic import PeriodicConvolver
from .schemes import StepCoefficients, TimeScheme, get_scheme
from .steady_kernels import SteadyKernelBuilder, SteadyShape

Array = np.ndarray
Operator = Callable[[Array], Array]
#: window sides whose convolvers a substrate keeps (:meth:`TermSubstrate.elastic_operator`'s ``window``)
WINDOWS_KEPT = 3
#: retardation modes up to which the history displacement is carried in displacement space
#: (:meth:`TermSubstrate.initial_response`): its 2 M field updates a step cost less than the transform
#: pair they spare up to about this many modes
RESPONSE_MODES = 8
#: a periodic kernel whose mean (its q = 0 spectral value) is below this fraction of its largest
#: spectral value has zero mean up to round-off (:meth:`TermSubstrate.free_mean`)
FREE_MEAN_TOLERANCE = 1e-9


@dataclass(frozen=True)
class Term:
    """One term of the displacement: u_displacement += K_kernel * (phi_history (*) d traction).

    Attributes
    ----------
    displacement, traction
        Components ``"z"`` (normal; the traction is the pressure p) or ``"x"`` (the shear q_x).
    kernel
        Name of its unit-modulus kernel in the substrate's convolver.
    history
        Key of the hereditary history it reads (one traction component under one time response).
    """

    displacement: str
    traction: str
    kernel: str
    history: str


@dataclass(frozen=True)
class ElasticOperator:
    """The step's operator K = sum J_inst K_term for :func:`~viscontact.constrained.constrained_cg`.

    ``window``: m -> the same operator restricted to an m x m sub-box of the grid (tractions zero
    outside it; :mod:`viscontact.support_window`), or None where it has none (periodic grids);
    ``fast_length``: the padded window sides its backend transforms best
    (:attr:`~viscontact.arrays.ArrayBackend.fast_length`).
    ``apply_increment`` and ``single_preconditioner``: K and the preconditioner in single precision
    (float32 transforms), for the search directions of a mixed-precision solve; None where the
    solves must reach round-off (periodic grids: their preconditioner is exact)."""

    apply: Operator
    preconditioner: Operator
    apply_sparse: Operator
    window: Callable[[int], "ElasticOperator"] | None = None
    apply_increment: Operator | None = None
    single_preconditioner: Operator | None = None
    fast_length: Callable[[int], int] = cpu_fast_length

    def cg_options(self, mixed_precision: bool = True) -> dict[str, Operator | None]:
        """Keyword arguments of :func:`~viscontact.constrained.constrained_cg` besides the action:
        with ``mixed_precision`` (``solver.mixed_precision``), the search directions and the
        preconditioner in single precision where this operator has them."""
        mixed = mixed_precision and self.apply_increment is not None
        return {"preconditioner": self.single_preconditioner if mixed else self.preconditioner,
                "apply_k_sparse": self.apply_sparse, "apply_k_increment": self.apply_increment if mixed else None}


class TermSubstrate:
    """A substrate given as terms (module docstring).

    Parameters
    ----------
    grid
        The surface grid.
    terms
        The displacement terms, in accumulation order.
    responses
        Time response (creep spectrum [1/Pa]) of each history key used by ``terms``.
    convolver
        Applies the terms' kernels (unit modulus).
    preconditioners
        Fourier preconditioners of the ``zz`` and ``xx`` kernels (unit factor), by kernel name.
    scheme, dt
        Time scheme and step [s] of the hereditary integral.
    direct
        Keep the literal hereditary sum (reference) instead of the recursion.
    periodic
        The domain is one period: a frame shift wraps the material history around (nothing is
        dropped, no wake) instead of losing it at the trailing edge.
    steady_shapes
        Steady shape (:class:`~viscontact.steady_kernels.SteadyShape`) of each kernel, by name, for
        :meth:`steady_convolver` on DC-FFT grids (kernels whose response has no retardation modes
        need none).
    backend
        Where the fields live (:mod:`viscontact.arrays`): ``convolver`` and ``preconditioners`` hold
        fields of it. The literal hereditary sum (``direct``) is CPU-only.
    """

    def __init__(self, grid: Grid, terms: Sequence[Term], responses: Mapping[str, CreepSpectrum],
                 convolver: Convolver, preconditioners: Mapping[str, FourierPreconditioner],
                 scheme: str | TimeScheme, dt: float, direct: bool = False, periodic: bool = False,
                 steady_shapes: Mapping[str, SteadyShape] | None = None, backend: ArrayBackend = CPU) -> None:
        if direct and not backend.is_cpu:
            raise ParameterError("solver.history", f"'direct' (the reference sum) runs on the CPU only, not on "
                                 f"{backend.name!r}")
        self.grid = grid
        self.terms = tuple(terms)
        self.responses = dict(responses)
        self.convolver = convolver
        self.preconditioners = dict(preconditioners)
        self.scheme = get_scheme(scheme)
        self.dt = float(dt)
        self.direct = direct
        self.periodic = periodic
        self.steady_shapes = dict(steady_shapes or {})
        self.backend = backend
        #: traction component each history carries
        self.history_traction = {t.history: t.traction for t in self.terms}
        #: the history of the normal self-term (what leaves the frame as the wake)
        self.normal_history = self._terms("z", "z")[0].history
        self._coefficients = {first: self._step_coefficients(first) for first in (True, False)}
        self._operators: dict[tuple[str, bool], ElasticOperator] = {}
        self._free_mean: dict[str, bool] = {}
        #: window side -> (convolver, preconditioners, operators by (component, first)), least recent first
        self._windows: OrderedDict[int, tuple[Convolver, dict[str, FourierPreconditioner],
                                              dict[tuple[str, bool], ElasticOperator]]] = OrderedDict()

    @property
    def xp(self) -> ModuleType:
        """Array namespace of the fields (:attr:`backend`'s: numpy on the CPU)."""
        return self.backend.xp

    @property
    def fft(self) -> ModuleType:
        """FFT module of the fields (:attr:`backend`'s: scipy.fft on the CPU)."""
        return self.backend.fft

    def _step_coefficients(self, first: bool) -> dict[str, StepCoefficients]:
        by_spectrum: dict[int, StepCoefficients] = {}
        out = {}
        for key, spectrum in self.responses.items():
            if id(spectrum) not in by_spectrum:
                by_spectrum[id(spectrum)] = self.scheme.coefficients(spectrum, self.dt, first)
            out[key] = by_spectrum[id(spectrum)]
        return out

    def coefficients(self, first: bool) -> Mapping[str, StepCoefficients]:
        """Step coefficients of each history (``first``: the step at t = 0)."""
        return self._coefficients[first]

    def _terms(self, displacement: str, traction: str) -> list[Term]:
        return [t for t in self.terms if t.displacement == displacement and t.traction == traction]

    def has_coupling(self) -> bool:
        """Whether any term couples normal and tangential components."""
        return any(t.displacement != t.traction for t in self.terms)

    # --- histories --------------------------------------------------------------------------------
    def initial_histories(self) -> dict[str, History]:
        """Histories before the first step (all zero), by key."""
        n = self.grid.n
        if self.direct:
            return {key: DirectHistory(n) for key in self.history_traction}
        return {key: PronyHistory.zeros(self.responses[key].retardation_times.size, n, self.xp)
                for key in self.history_traction}

    def advanced(self, histories: Mapping[str, History], tractions: Mapping[str, Array], t: float,
                 first: bool) -> dict[str, History]:
        """Histories after the step at ``t`` [s] with ``tractions`` {"z": p, "x": q} [Pa]."""
        coef = self.coefficients(first)
        return {key: h.advanced(tractions[self.history_traction[key]], coef[key], t) for key, h in histories.items()}

    def shifted(self, histories: Mapping[str, History], cells: int = 1
                ) -> tuple[dict[str, History], dict[str, Array]]:
        """Histories after the frame moved by ``cells`` towards -x, and the internal fields
        (M, n, cells) of each that left at the trailing edge, on the host (none when periodic: they
        wrap around)."""
        coef = self.coefficients(False)
        out, dropped = {}, {}
        for key, h in histories.items():
            out[key], dropped[key] = h.shifted(cells, coef[key], wrap=self.periodic)
        return out, ({} if self.periodic else {key: self.backend.to_host(d) for key, d in dropped.items()})

    def known_displacement(self, histories: Mapping[str, History], t: float, first: bool,
                           need_x: bool) -> tuple[Array, Array | None]:
        """(u_z, u_x) [m] at step time ``t`` [s] from the past increments only; u_x None unless ``need_x``."""
        coef = self.coefficients(first)
        outputs = ("z", "x") if need_x else ("z",)
        used = {t_.history for t_ in self.terms if t_.displacement in outputs}
        known = {key: histories[key].known(coef[key], t) for key in histories if key in used}
        u = self.convolver.displacements(
            [(t_.displacement, t_.kernel, known[t_.history]) for t_ in self.terms if t_.displacement in outputs],
            outputs)
        return u["z"], u.get("x")

    # --- the history displacement carried in displacement space ----------------------------------
    def response_term(self) -> Term | None:
        """The term whose history displacement can be carried in displacement space
        (:meth:`initial_response`), or None: the substrate's only u_z term, a self term (``zz``) on
        a support-window (DC-FFT) grid with the recursive history of at most
        :data:`RESPONSE_MODES` retardation modes."""
        z_terms = [t for t in self.terms if t.displacement == "z"]
        if self.direct or self.periodic or self.convolver.kernels is None or len(z_terms) != 1:
            return None
        term = z_terms[0]
        modes = self.responses[term.history].retardation_times.size
        return term if term.traction == "z" and modes <= RESPONSE_MODES else None

    def initial_response(self) -> PronyHistory | None:
        """The response history before the first step, or None where :meth:`response_term` is None.

        The hereditary recursion (:mod:`viscontact.history`) is linear and K is time-invariant, so
        fed with the displacements K p_k of the steps' pressures instead of p_k it carries
        K H_m and K p_k-1, and its ``known`` is the history displacement u_z = K r_k itself
        (:meth:`known_from_response`): no transform per step, M + 1 more fields. It holds while the
        frame stays put (a shift would need the displacement beyond the grid's edge: the transient
        drops it at the first shift)."""
        term = self.response_term()
        if term is None:
            return None
        return PronyHistory.zeros(self.responses[term.history].retardation_times.size, self.grid.n, self.xp)

    def known_from_response(self, response: PronyHistory, t: float, first: bool) -> Array:
        """u_z [m] of the past increments from the response history (:meth:`initial_response`)."""
        return response.known(self.coefficients(first)[self.response_term().history], t)

    def advanced_response(self, response: PronyHistory, pressure: Array, product: Array | None, t: float,
                          first: bool) -> PronyHistory:
        """The response history after the step at ``t`` [s] with ``pressure`` [Pa], ``product`` the
        step's normal operator applied to it (J_inst K p [m], where the solve computed it; else one
        product here)."""
        term = self.response_term()
        coef = self.coefficients(first)[term.history]
        if product is None:
            displacement = self.convolver.apply(term.kernel, pressure)
        else:
            displacement = product / coef.instantaneous
        return response.advanced(displacement, coef, t)

    # --- the step's elastic operators -------------------------------------------------------------
    def elastic_operator(self, component: str, first: bool) -> ElasticOperator:
        """K x = sum over the (component, component) terms of J_inst K_term x, for ``"z"`` or ``"x"``
        (made once per component and kind of step, then kept)."""
        key = (component, first)
        if key not in self._operators:
            self._operators[key] = self._elastic_operator(component, first)
        return self._operators[key]

    def _factors(self, component: str, first: bool) -> list[tuple[str, float]]:
        """(kernel name, J_inst [1/Pa]) of each (component, component) term of the step."""
        coef = self.coefficients(first)
        return [(t.kernel, coef[t.history].instantaneous) for t in self._terms(component, component)]

    def _elastic_operator(self, component: str, first: bool) -> ElasticOperator:
        windowed = not self.periodic and self.convolver.kernels is not None
        window = (lambda m: self._window_operator(component, first, m)) if windowed else None
        return _operator(self._factors(component, first), self.convolver, self.preconditioners, window,
                         single=not self.periodic, fast_length=self.backend.fast_length)

    def _window_operator(self, component: str, first: bool, m: int) -> ElasticOperator:
        """:meth:`elastic_operator` on an m x m window: a convolver of the kernels cropped to the window
        (:meth:`~viscontact.convolution.Convolver.window_kernels`) and their preconditioners, made once
        per side and kept for the :data:`WINDOWS_KEPT` sides used last (a growing contact walks
        through a sequence of sides; their kernels would otherwise pile up). Its transforms are the
        zero-block ``scipy.fft`` ones whatever ``solver.fft`` (FFTW plans per side would cost more
        planning than they save)."""
        if m not in self._windows:
            names = sorted({t.kernel for t in self.terms if t.displacement == t.traction})
            kernels = self.convolver.window_kernels(m, names)
            conv = Convolver.from_kernels(m, kernels, self.convolver.workers, xp=self.xp, fft=self.fft)
            precond = {k: FourierPreconditioner.for_kernel(kernels[k], 1.0, self.convolver.workers, fft=self.fft)
                       for k in names}
            self._windows[m] = (conv, precond, {})
            while len(self._windows) > WINDOWS_KEPT:
                self._windows.popitem(last=False)
        self._windows.move_to_end(m)
        conv, precond, operators = self._windows[m]
        key = (component, first)
        if key not in operators:
            operators[key] = _operator(self._factors(component, first), conv, precond, None, single=True)
        return operators[key]

    def free_mean(self, component: str) -> bool:
        """Whether a uniform traction of ``component`` (``"z"`` or ``"x"``) leaves the mean displacement
        undetermined: on a periodic grid whose (component, component) kernels have zero mean (the q = 0
        compliance of a periodic half-space is infinite: :mod:`viscontact.periodic`), the uniform
        traction is in the null space of :meth:`elastic_operator`. False on DC-FFT grids (a finite
        domain) and where the mean is bounded (a layer bonded to a rigid base: h/M normally, h/G
        tangentially). A kernel's mean counts as zero below :data:`FREE_MEAN_TOLERANCE` of its
        largest spectral value."""
        if component not in self._free_mean:
            spectra = [self.convolver.spectra[t.kernel] for t in self._terms(component, component)]
            self._free_mean[component] = self.periodic and all(
                abs(float(s[0, 0].real)) <= FREE_MEAN_TOLERANCE * float(self.xp.abs(s).max()) for s in spectra)
        return self._free_mean[component]

    def cross_displacement(self, displacement: str, traction: str, field: Array, first: bool,
                           factor: float = 1.0) -> Array | None:
        """(J_inst factor) K_term field summed over the (displacement, traction) terms of this step:
        the instantaneous coupling [m] of a traction [Pa]; None when the substrate has no such term."""
        terms = self._terms(displacement, traction)
        if not terms:
            return None
        coef = self.coefficients(first)
        out = None
        for t in terms:
            u = (coef[t.history].instantaneous * factor) * self.convolver.apply(t.kernel, field)
            out = u if out is None else out + u
        return out

    def instantaneous_displacement(self, tractions: Mapping[str, Array], first: bool) -> Array:
        """u_z [m] of the step's own tractions {"z": p, "x": q} [Pa] through every z term (J_inst K)."""
        coef = self.coefficients(first)
        scaled = {key: coef[key].instantaneous * tractions[self.history_traction[key]]
                  for key in {t.history for t in self.terms if t.displacement == "z"}}
        terms = [("z", t.kernel, scaled[t.history]) for t in self.terms if t.displacement == "z"]
        return self.convolver.displacements(terms, ("z",))["z"]

    # --- steady sliding ---------------------------------------------------------------------------
    def steady_convolver(self, speed: float, components: Sequence[str] = ("zz",)
                         ) -> tuple[Convolver, dict[str, Array]]:
        """Convolver of the effective steady kernels at ``speed`` [m/s] (1/Pa included) and the kernels,
        by component (``zz``, ``zx``, ...): the sum over the component's terms of

            K_term(d) = J_0 K(d) + sum_m J_m F_m(d),   F_m(d) = int_0^inf exp(-xi/L_m)/L_m K(d + xi) dxi,

        L_m = v lambda_m, each term with its own spectrum (J_0, J_m, lambda_m) and the F_m of its own
        kernel shape (:attr:`steady_shapes`, all modes in one pass: :mod:`viscontact.steady_kernels`);
        ``apply("zz", p)`` is u_z [m] of p [Pa]. DC-FFT grids; a periodic steady state is exact in
        Fourier space (:meth:`steady_spectrum`).
        """
        if self.periodic:
            raise NotImplementedError("a periodic steady state is exact in Fourier space: steady_spectrum")
        n = self.grid.n
        kernels: dict[str, Array] = {}
        for term in self.terms:
            name = term.displacement + term.traction
            if name not in components:
                continue
            spectrum = self.responses[term.history]
            # the convolver keeps its kernels centred (offset 0 at n - 1): back to wrap-around order
            kernel = spectrum.instantaneous * np.roll(self.convolver.kernels[term.kernel], (1 - n, 1 - n), axis=(0, 1))
            if np.any(spectrum.amplitudes):
                shape = self.steady_shapes.get(term.kernel)
                if shape is None:
                    raise ParameterError("steady", f"no steady kernel for the compliance term {term.kernel!r}; "
                                         "use `viscontact run` (transient)")
                kernel = kernel + self.backend.to_device(
                    shape.history(spectrum.amplitudes, speed * spectrum.retardation_times))
            kernels[name] = kernel if name not in kernels else kernels[name] + kernel
        return Convolver.from_kernels(n, kernels, self.convolver.workers, xp=self.xp, fft=self.fft,
                                      transforms=self.convolver.transforms), kernels

    def steady_spectrum(self, speed: float, friction: float = 0.0) -> Array:
        """Spectrum (n, n//2 + 1) of the steady operator p -> u_z [m per Pa] on a periodic grid: the sum
        over the ``zz`` terms (and ``friction`` x the ``zx`` terms: q_x = mu_f p) of K^_term
        phi*_term(-k_x v), each term with its own creep compliance
        (:func:`viscontact.steady_periodic.steady_operator_spectrum`)."""
        from .steady_periodic import steady_operator_spectrum

        if not self.periodic:
            raise NotImplementedError("steady_spectrum is for periodic grids: steady_convolver")
        terms = self._terms("z", "z") + (self._terms("z", "x") if friction > 0 else [])
        return steady_operator_spectrum(self.grid, speed, [
            ((1.0 if t.traction == "z" else friction) * self.convolver.spectra[t.kernel], self.responses[t.history])
            for t in terms])


def _operator(factors: Sequence[tuple[str, float]], conv: Convolver,
              preconditioners: Mapping[str, FourierPreconditioner],
              window: Callable[[int], ElasticOperator] | None, single: bool,
              fast_length: Callable[[int], int] = cpu_fast_length) -> ElasticOperator:
    """K x = sum over ``factors`` (kernel name, J_inst [1/Pa]) of J_inst K_name x through ``conv``, with
    the Fourier preconditioner of the summed symbols (:class:`ElasticOperator`); ``single``: with its
    single-precision variants as well; ``fast_length``: the backend's window sides."""
    if len(factors) == 1:
        (kernel, j_inst), = factors
        base = preconditioners[kernel]
        precond = FourierPreconditioner(base.inverse_symbol / j_inst, base.workers, base.fft)

        def product(x: Array, single: bool = False) -> Array:
            out = conv.apply(kernel, x, single=single)
            out *= j_inst
            return out

        def sparse(x: Array) -> Array:
            return conv.apply_sparse(kernel, x, j_inst)
    else:
        precond = FourierPreconditioner(1.0 / sum(j / preconditioners[k].inverse_symbol for k, j in factors),
                                        conv.workers, conv.fft)

        def product(x: Array, single: bool = False) -> Array:
            return conv.combine([(k, j, x) for k, j in factors], single=single)

        def sparse(x: Array) -> Array:
            return sum(conv.apply_sparse(k, x, j) for k, j in factors)

    if not single:
        return ElasticOperator(product, precond, sparse, window, fast_length=fast_length)
    return ElasticOperator(product, precond, sparse, window, lambda x: product(x, True), precond.single(),
                           fast_length)


class HalfSpace(TermSubstrate):
    """Homogeneous viscoelastic half-space with constant Poisson ratio (kernels x J(t)).

    Terms ``zz``, ``zx`` (u_z of p, q_x) and ``xz``, ``xx`` (u_x), the kernels of
    :func:`~viscontact.kernels.influence_coefficients` at G = 1 (on a periodic grid those of
    :func:`~viscontact.periodic.periodic_influence_coefficients`, with unpadded FFTs); every term's
    time response is the material's shear creep compliance, so the histories are ``"z"`` (of p) and
    ``"x"`` (of q_x).

    Parameters
    ----------
    material
        The material (creep spectrum and Poisson ratio).
    components
        Kernels to build among ``zz``, ``xx``, ``xz``, ``zx`` (``zz`` always).
    workers
        FFT worker threads (-1: all cores above 512^2 cells, one below: :func:`~viscontact.fftbackends.fft_threads`).
    fft
        DC-FFT transforms by backend name (:func:`~viscontact.fftbackends.dcfft_transforms`; on a device
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
        """K(d) = J_0 IC(d) + sum_m J_m F_m(d) with L_m = v lambda_m (see :mod:`viscontact.steady`),
        all modes in one pass (:class:`~viscontact.steady_kernels.SteadyKernelBuilder`, kept for
        the next speed); ``apply("zz", p)`` is u_z [m] of p [Pa]."""
        if self.periodic:
            raise NotImplementedError("a periodic steady state is exact in Fourier space: viscontact.steady_periodic")
        comps = tuple(components)
        builder = self._steady_builders.get(comps)
        if builder is None:
            builder = self._steady_builders[comps] = SteadyKernelBuilder(self.grid, self.material.poisson_ratio, comps)
        c = self.material.creep
        kernels = builder.effective(c.instantaneous, c.amplitudes, c.retardation_times, speed)
        return Convolver.from_kernels(self.grid.n, kernels, self.workers, xp=self.xp, fft=self.fft,
                                      transforms=self.convolver.transforms), kernels


def substrate_for(problem, components: Sequence[str] | None = None,
                  backend: ArrayBackend | None = None) -> TermSubstrate:
    """The substrate of a :class:`~viscontact.problem.Problem` (the one place that chooses it).

    ``components``: the kernels to build; by default what the transient needs: ``zz``, ``xx`` for
    partial slip, and the coupling ``xz``, ``zx`` when sliding with friction, nu < 0.5 and
    ``solver.coupling``. The steady solver asks for ``("zz",)`` (it builds its own kernels).

    ``problem.layer``: the layer's terms (:func:`layer_terms`); ``problem.bulk_modulus``: the
    half-space with nu(t) (:func:`viscontact.poisson.half_space_terms`, two histories per traction
    component); else the :class:`HalfSpace` with constant nu.

    ``backend``: where the fields live (:mod:`viscontact.arrays`); None: that of ``solver.device``.
    """
    backend = backend or array_backend(problem.solver.device)
    if components is None:
        nu = problem.material.poisson_ratio
        mode = problem.tangential.mode
        components = ["zz"] + (["xx"] if mode == "partial_slip" else [])
        if nu < 0.5 and problem.solver.coupling and mode in ("partial_slip", "gross_sliding"):
            components += ["xz", "zx"]
    if problem.layer is None and problem.bulk_modulus is None:
        return HalfSpace(problem.grid, problem.material, components, problem.time.scheme, problem.time.dt,
                         workers=problem.solver.workers, direct=problem.solver.history == "direct",
                         fft=problem.solver.fft, backend=backend)
    from .compliance_terms import term_substrate

    comps = tuple(c for c in HalfSpace.ORDER if c in set(components) | {"zz"})
    if problem.layer is not None:
        terms = layer_terms(problem.grid, problem.layer, problem.material, comps)
    else:
        from .poisson import BulkElasticMaterial, half_space_terms

        terms = half_space_terms(problem.grid, BulkElasticMaterial(problem.material, problem.bulk_modulus), comps)
    return term_substrate(problem.grid, terms, problem.time.scheme, problem.time.dt,
                          workers=problem.solver.workers, direct=problem.solver.history == "direct", backend=backend)


def _shift_node_body(problem) -> bool:
    """Whether :func:`substrate_for` builds ``problem``'s body of shift-node terms: a viscoelastic layer
    on an elastic substrate (:func:`viscontact.layers.elastic_substrate_terms`)."""
    return problem.layer is not None and problem.layer.substrate == "elastic" and not problem.material.is_elastic


def body_size(problem) -> tuple[int, int]:
    """(history fields per traction component, kernels per kernel component) of the body that
    :func:`substrate_for` builds, for the memory estimate (:func:`viscontact.resources.estimate`):
    M (retardation modes) and 1 for the half-space and a layer on a rigid base; 2 M and 2 with
    ``bulk_modulus`` (J and L histories); D M and D + 1 for a viscoelastic layer on an elastic
    substrate with D + 1 shift nodes (:func:`viscontact.layers.shift_nodes`)."""
    modes = problem.material.creep.retardation_times.size
    if problem.bulk_modulus is not None:
        return 2 * modes, 2
    if _shift_node_body(problem):
        from .layers import shift_nodes

        nodes = shift_nodes(problem.material).nodes.size
        return (nodes - 1) * modes, nodes
    return modes, 1


def stability_responses(problem) -> list[CreepSpectrum]:
    """Time responses [1/Pa] whose step stability bounds dt (:func:`~viscontact.schemes.stable_step_limit`):
    the shear creep J(t), and with ``problem.bulk_modulus`` the normal (1 - nu)/G and tangential
    1/G factors of :class:`~viscontact.poisson.BulkElasticMaterial` (the normal one has the extra,
    shorter retardation time of G(t) + 3K); a viscoelastic layer on an elastic substrate adds the
    responses of its shift nodes (:func:`viscontact.layers.shift_nodes`, times of G(t) + s_p)."""
    out = [problem.material.creep]
    if problem.bulk_modulus is not None:
        from .poisson import BulkElasticMaterial

        bulk = BulkElasticMaterial(problem.material, problem.bulk_modulus)
        out += [bulk.factor("normal"), bulk.factor("tangential")]
    if _shift_node_body(problem):
        from .layers import shift_nodes

        nodes = shift_nodes(problem.material)
        out += [nodes.response(problem.material, p) for p in range(nodes.nodes.size)]
    return out


def layer_terms(grid: Grid, settings, material: Material, components: Sequence[str]) -> list:
    """Compliance terms of ``material`` as a layer (``settings``: a
    :class:`~viscontact.problem.LayerSettings`) on its substrate.

    Rigid base, or an elastic layer: one term per component, the unit-modulus kernel times the
    creep compliance (:func:`viscontact.layers.factored_terms`). A viscoelastic layer on an elastic
    substrate: the rigid-base terms and one kernel per shift node, each with its own creep function
    (:func:`viscontact.layers.elastic_substrate_terms`).
    """
    from .layers import Layer, elastic_substrate_terms, factored_terms, rigid_base_terms

    layer = Layer(settings.thickness, material.shear_modulus_instantaneous, material.poisson_ratio,
                  settings.substrate, settings.interface, settings.substrate_shear_modulus,
                  settings.substrate_poisson_ratio)
    comps = tuple(components)
    if layer.substrate == "rigid":
        return rigid_base_terms(grid, layer, material, comps)
    if not material.is_elastic:
        return elastic_substrate_terms(grid, layer, material, comps)
    return factored_terms(grid, layer, material.creep, comps)
