"""The compliance of a body: what its surface does under a traction history.

Words: the *body* is the whole compliant solid (:mod:`viscontact.bodies.base`); what lies under a
layer is its *base*; the *compliance* (a :class:`Compliance`, named before bodies had a word of
their own) is what a body gives the contact solvers.

Data model (linear viscoelasticity, seed Eqs. 5-6): the surface displacement u_i (i in z, x) is a
sum over TERMS,

    u_i = sum_terms K_term * (phi_term (*) dq_j),

a term being (displacement component i, traction component j, a real-space kernel K at unit
modulus, a time response phi(t) = J_0 + sum_m J_m (1 - exp(-t/lambda_m)) given as a
:class:`~viscontact.numerics.exponentials.CreepSpectrum`). Terms that read the same traction component through
the same time response share one hereditary history (:mod:`viscontact.numerics.history`): a history is
keyed by :attr:`Term.history` and carries one traction component.

One term, two stages, two types:

* :class:`ComplianceTerm` is a term as a body *builds* it: its kernel as an array and its time
  response as a spectrum (:func:`~viscontact.bodies.layer.rigid_base_terms`,
  :func:`~viscontact.bodies.bulk_elastic.half_space_terms`, ...);
* :class:`Term` is the same term once *placed* in a :class:`Compliance` (:meth:`ComplianceTerm.placed`):
  its kernel by name in the convolver, its response by the key of the history it reads (the
  compliance holds one response per history, shared by the terms that read it). Only the
  :class:`Compliance` and its subclasses (:class:`~viscontact.bodies.half_space.HalfSpace`, whose
  convolver is built from the kernels directly) deal in :class:`Term`.

:class:`Compliance` turns (terms, responses, a convolver, preconditioners) into what the contact
solvers use, and is all a new compliance has to provide:

* :meth:`~Compliance.elastic_operator`: the step's elastic operator for the normal (``zz``) or
  tangential (``xx``) solve: action, Fourier preconditioner, sparse action;
* :meth:`~Compliance.cross_displacement`: the step's instantaneous coupling (``zx``, ``xz``);
* :meth:`~Compliance.known_displacement`: (u_z, u_x) of the history state;
* :meth:`~Compliance.advanced`, :meth:`~Compliance.shifted`: the history after a step / a
  frame shift (new objects; nothing is mutated);
* :meth:`~Compliance.steady_convolver`: the effective kernel of steady sliding at a speed;
* :meth:`~Compliance.free_mean`: whether a uniform traction leaves the mean displacement
  undetermined (a periodic half-space);
* ``backend`` (:class:`~viscontact.numerics.arrays.ArrayBackend`: the array namespace ``xp`` and the FFT
  module ``fft`` of the fields, ``to_host`` for what the results keep).

:class:`HalfSpace` is the homogeneous half-space with constant Poisson ratio (Boussinesq-Cerruti
kernels of :mod:`viscontact.physics.kernels`, all four terms sharing the material's creep compliance, so
one history per traction component). Other substrates plug in by building other terms:

* a time-dependent Poisson ratio: the same kernels split into parts, each term its own computed
  spectrum (histories keyed e.g. ``"z:normal"``, ``"z:coupling"``);
* a layer on an elastic base: one kernel (and one single-mode term) per relaxation mode;
* a periodic domain: periodic kernels and a convolver with the same methods (``apply``,
  ``apply_sparse``, ``combine``, ``displacements``, ``spectrum``, ``inverse``) on unpadded
  transforms, and its own :meth:`~Compliance.steady_convolver`.

The contact solvers (:mod:`viscontact.solvers.transient`, :mod:`viscontact.solvers.steady`) see only this interface.
"""
from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass
from types import ModuleType
from typing import Callable, Iterable, Mapping, Sequence

import numpy as np

from viscontact.errors import ParameterError
from viscontact.numerics.arrays import CPU, ArrayBackend, array_backend, cpu_fast_length
from viscontact.numerics.convolution import Convolver, FourierPreconditioner
from viscontact.numerics.exponentials import CreepSpectrum
from viscontact.numerics.fftbackends import DCFFTTransforms, ZeroBlockTransforms, dcfft_transforms
from viscontact.numerics.grid import Grid
from viscontact.numerics.history import DirectHistory, History, PronyHistory
from viscontact.numerics.schemes import StepCoefficients, TimeScheme, get_scheme
from viscontact.physics.periodic import PeriodicConvolver
from viscontact.physics.steady_kernels import SteadyShape, steady_operator_spectrum

Array = np.ndarray
Operator = Callable[[Array], Array]
#: window sides whose convolvers a compliance keeps (:meth:`Compliance.elastic_operator`'s ``window``)
WINDOWS_KEPT = 3
#: retardation modes up to which the history displacement is carried in displacement space
#: (:meth:`Compliance.initial_response`): its 2 M field updates a step cost less than the transform
#: pair they spare up to about this many modes
RESPONSE_MODES = 8
#: a periodic kernel whose mean (its q = 0 spectral value) is below this fraction of its largest
#: spectral value has zero mean up to round-off (:meth:`Compliance.free_mean`)
FREE_MEAN_TOLERANCE = 1e-9


#: the kernel components, in the order a body builds them: u_z of p and of q_x, u_x of p and of q_x
COMPONENT_ORDER = ("zz", "zx", "xz", "xx")


def ordered_components(components: Iterable[str]) -> tuple[str, ...]:
    """``components`` and ``zz`` (always built) in :data:`COMPONENT_ORDER`."""
    wanted = set(components) | {"zz"}
    return tuple(c for c in COMPONENT_ORDER if c in wanted)


@dataclass(frozen=True)
class Term:
    """One term of the displacement as placed in a :class:`Compliance`:
    u_displacement += K_kernel * (phi_history (*) d traction), the kernel named in the convolver and
    the response keyed by its history (a body builds a :class:`ComplianceTerm`; module docstring).

    Attributes
    ----------
    displacement, traction
        Components ``"z"`` (normal; the traction is the pressure p) or ``"x"`` (the shear q_x).
    kernel
        Name of its unit-modulus kernel in the compliance's convolver.
    history
        Key of the hereditary history it reads (one traction component under one time response).
    """

    displacement: str
    traction: str
    kernel: str
    history: str


@dataclass(frozen=True)
class ElasticOperator:
    """The step's operator K = sum J_inst K_term for :func:`~viscontact.numerics.constrained.constrained_cg`.

    ``window``: m -> the same operator restricted to an m x m sub-box of the grid (tractions zero
    outside it; :mod:`viscontact.numerics.support_window`), or None where it has none (periodic grids);
    ``fast_length``: the padded window sides its backend transforms best
    (:attr:`~viscontact.numerics.arrays.ArrayBackend.fast_length`).
    ``apply_increment`` and ``single_preconditioner``: K and the preconditioner in single precision
    (float32 transforms), for the search directions of a mixed-precision solve; None where an
    operator has none (then every product is in double).
    ``sparse_limit``: the non-zeros up to which ``apply_sparse`` costs less than ``apply`` (its
    convolver's :attr:`~viscontact.numerics.convolution.Convolver.sparse_limit`); ``check_every``: its
    backend's (:attr:`~viscontact.numerics.arrays.ArrayBackend.check_every`: above 1, the solves keep
    their scalars on the device)."""

    apply: Operator
    preconditioner: Operator
    apply_sparse: Operator
    window: Callable[[int], "ElasticOperator"] | None = None
    apply_increment: Operator | None = None
    single_preconditioner: Operator | None = None
    fast_length: Callable[[int], int] = cpu_fast_length
    sparse_limit: int = Convolver.sparse_limit
    check_every: int = 1

    def cg_options(self, mixed_precision: bool = True) -> dict[str, Operator | None]:
        """Keyword arguments of :func:`~viscontact.numerics.constrained.constrained_cg` besides the action:
        with ``mixed_precision`` (``solver.mixed_precision``), the search directions and the
        preconditioner in single precision where this operator has them."""
        mixed = mixed_precision and self.apply_increment is not None
        return {"preconditioner": self.single_preconditioner if mixed else self.preconditioner,
                "apply_k_sparse": self.apply_sparse, "sparse_limit": self.sparse_limit,
                "apply_k_increment": self.apply_increment if mixed else None}


class Compliance:
    """A compliance given as terms (module docstring).

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
        Steady shape (:class:`~viscontact.physics.steady_kernels.SteadyShape`) of each kernel, by name, for
        :meth:`steady_convolver` on DC-FFT grids (kernels whose response has no retardation modes
        need none).
    backend
        Where the fields live (:mod:`viscontact.numerics.arrays`): ``convolver`` and ``preconditioners`` hold
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
        n = self.grid.shape
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
        (:meth:`initial_response`), or None: the compliance's only u_z term, a self term (``zz``) on
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

        The hereditary recursion (:mod:`viscontact.numerics.history`) is linear and K is time-invariant, so
        fed with the displacements K p_k of the steps' pressures instead of p_k it carries
        K H_m and K p_k-1, and its ``known`` is the history displacement u_z = K r_k itself
        (:meth:`known_from_response`): no transform per step, M + 1 more fields. It holds while the
        frame stays put (a shift would need the displacement beyond the grid's edge: the transient
        drops it at the first shift)."""
        term = self.response_term()
        if term is None:
            return None
        return PronyHistory.zeros(self.responses[term.history].retardation_times.size, self.grid.shape, self.xp)

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
        # a line grid's one row gains nothing from a window: its transforms are already 1-D
        windowed = not self.periodic and self.convolver.kernels is not None and self.grid.dimension == 2
        window = (lambda m: self._window_operator(component, first, m)) if windowed else None
        return _operator(self._factors(component, first), self.convolver, self.preconditioners, window,
                         self.backend)

    def _window_operator(self, component: str, first: bool, m: int) -> ElasticOperator:
        """:meth:`elastic_operator` on an m x m window: a convolver of the kernels cropped to the window
        (:meth:`~viscontact.numerics.convolution.Convolver.window_kernels`) and their preconditioners, made once
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
            operators[key] = _operator(self._factors(component, first), conv, precond, None, self.backend)
        return operators[key]

    def free_mean(self, component: str) -> bool:
        """Whether a uniform traction of ``component`` (``"z"`` or ``"x"``) leaves the mean displacement
        undetermined: on a periodic grid whose (component, component) kernels have zero mean (the q = 0
        compliance of a periodic half-space is infinite: :mod:`viscontact.physics.periodic`), the uniform
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
        the instantaneous coupling [m] of a traction [Pa]; None when the compliance has no such term."""
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
        kernel shape (:attr:`steady_shapes`, all modes in one pass: :mod:`viscontact.physics.steady_kernels`);
        ``apply("zz", p)`` is u_z [m] of p [Pa]. On a periodic grid the steady operator is exact in
        Fourier space: a :class:`~viscontact.physics.periodic.PeriodicConvolver` of the component
        spectra K^_term phi*_term(-k_x v) (:meth:`steady_spectrum`), and no real-space kernels.
        """
        if self.periodic:
            return self._periodic_steady_convolver(speed, components), {}
        n, rows = self.grid.n, self.grid.rows
        kernels: dict[str, Array] = {}
        for term in self.terms:
            name = term.displacement + term.traction
            if name not in components:
                continue
            spectrum = self.responses[term.history]
            # the convolver keeps its kernels centred (offset 0 at n - 1): back to wrap-around order
            kernel = spectrum.instantaneous * np.roll(self.convolver.kernels[term.kernel], (1 - rows, 1 - n), axis=(0, 1))
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

    def steady_preconditioner(self, speed: float, workers: int = -1, symmetric: bool = False
                              ) -> FourierPreconditioner | None:
        """The Fourier preconditioner of the steady operator K_zz at ``speed`` [m/s] from its known
        symbol (``symmetric``: of its symmetric part), or None where this compliance knows none (then
        :func:`viscontact.solvers.steady.steady_preconditioner` takes that of the effective kernel)."""
        return None

    def _periodic_steady_convolver(self, speed: float, components: Sequence[str]) -> PeriodicConvolver:
        """The periodic steady operators by component (``zz``, ``xx``, ``xz``, ``zx``: displacement,
        traction) at ``speed`` [m/s], each the sum over its terms of K^_term phi*_term(-k_x v)
        (:func:`viscontact.physics.steady_kernels.steady_operator_spectrum`, as :meth:`steady_spectrum`)."""
        spectra = {name: steady_operator_spectrum(self.grid, speed, [
            (self.convolver.spectra[t.kernel], self.responses[t.history]) for t in self._terms(name[0], name[1])])
            for name in components}
        return PeriodicConvolver(self.grid.n, spectra, self.convolver.workers, None, self.xp, self.fft)

    def steady_spectrum(self, speed: float, friction: float = 0.0) -> Array:
        """Spectrum (n, n//2 + 1) of the steady operator p -> u_z [m per Pa] on a periodic grid: the sum
        over the ``zz`` terms (and ``friction`` x the ``zx`` terms: q_x = mu_f p) of K^_term
        phi*_term(-k_x v), each term with its own creep compliance
        (:func:`viscontact.physics.steady_kernels.steady_operator_spectrum`)."""
        if not self.periodic:
            raise NotImplementedError("steady_spectrum is for periodic grids: steady_convolver")
        terms = self._terms("z", "z") + (self._terms("z", "x") if friction > 0 else [])
        return steady_operator_spectrum(self.grid, speed, [
            ((1.0 if t.traction == "z" else friction) * self.convolver.spectra[t.kernel], self.responses[t.history])
            for t in terms])


def _operator(factors: Sequence[tuple[str, float]], conv: Convolver,
              preconditioners: Mapping[str, FourierPreconditioner],
              window: Callable[[int], ElasticOperator] | None, backend: ArrayBackend = CPU) -> ElasticOperator:
    """K x = sum over ``factors`` (kernel name, J_inst [1/Pa]) of J_inst K_name x through ``conv``, with
    the Fourier preconditioner of the summed symbols and their single-precision variants
    (:class:`ElasticOperator`); ``backend``: where the fields live (its window sides, how often its
    CG reads its stopping test)."""
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

    return ElasticOperator(product, precond, sparse, window, lambda x: product(x, True), precond.single(),
                           backend.fast_length, conv.sparse_limit, backend.check_every)


@dataclass(frozen=True)
class ComplianceTerm:
    """One term of the compliance operator as a body builds it: kernel array and time response
    (placed in a :class:`Compliance` it becomes a :class:`Term`: :meth:`placed`; module docstring).

    Attributes
    ----------
    displacement
        Displacement component it produces, ``"z"`` (normal, into the solid) or ``"x"``.
    traction
        Traction component it acts on, ``"z"`` (pressure) or ``"x"`` (shear in +x).
    kernel
        Influence kernel at unit modulus on the (2n, 2n) DC-FFT offset grid [m] (displacement per
        unit cell traction times the modulus; multiply by the response [1/Pa]).
    response
        Time response phi(t) [1/Pa] of this term.
    name
        Label (e.g. ``"zz"``, ``"xx:poisson"``).
    steady
        How its kernel enters steady sliding on the DC-FFT grid
        (:class:`~viscontact.physics.steady_kernels.SteadyShape`); None where it is not built (periodic
        grids need none: the periodic steady state is exact in Fourier space).

    On a periodic grid (``grid.periodic``) ``kernel`` is the periodic kernel on the n x n grid in
    wrap-around order (zero mean where the mean compliance is unbounded, :mod:`viscontact.physics.periodic`).
    """

    displacement: str
    traction: str
    kernel: np.ndarray
    response: CreepSpectrum
    name: str = ""
    steady: SteadyShape | None = None

    def placed(self) -> Term:
        """The term as a :class:`Compliance` holds it: the kernel by its :attr:`name`, the response by
        its :func:`history_key`."""
        return Term(self.displacement, self.traction, self.name, history_key(self))


def history_key(term: ComplianceTerm) -> str:
    """Key of the hereditary history a term reads: its traction component and response label
    (``"zz:bulk"`` and ``"xz:bulk"`` both read p through L(t): ``"z:bulk"``; an unlabelled term
    ``"zz"``: ``"z:creep"``)."""
    label = term.name.split(":", 1)[1] if ":" in term.name else "creep"
    return f"{term.traction}:{label}"


def grid_transforms(n: int, workers: int, fft: str = "scipy", backend: ArrayBackend = CPU,
                    rows: int | None = None) -> DCFFTTransforms:
    """The DC-FFT transforms of an n x n grid's fields (``rows`` x n: a line grid's one row): those of
    ``solver.fft`` by name on the CPU (:func:`~viscontact.numerics.fftbackends.dcfft_transforms`), on a
    device ``backend`` its own FFT module's zero-block transforms (``fft`` must then be ``"scipy"``, as
    :class:`~viscontact.problem.problem.SolverSettings` checks)."""
    if backend.is_cpu:
        return dcfft_transforms(fft, n, workers, rows)
    return ZeroBlockTransforms(n, workers, backend.fft, rows=rows)


def term_substrate(grid, terms: Iterable[ComplianceTerm], scheme, dt: float, *, workers: int = -1,
                   direct: bool = False, backend=None, fft: str = "scipy"):
    """A :class:`~viscontact.bodies.compliance.Compliance` of compliance terms: each term a kernel named
    after it, terms with the same :func:`history_key` sharing one history (they must share the
    response), Fourier preconditioners for the self (zz, xx) kernels, the terms' steady shapes. On
    a periodic grid the kernels are periodic (n x n) and the convolver is the unpadded
    :class:`~viscontact.physics.periodic.PeriodicConvolver`; otherwise DC-FFT. For the solvers'
    ``compliance=`` argument (e.g. :func:`viscontact.solvers.transient.steps`). ``backend``: where the fields
    live (an :class:`~viscontact.numerics.arrays.ArrayBackend`; None: the CPU). ``fft``: the DC-FFT
    transforms by name (``solver.fft``, :func:`grid_transforms`); a periodic grid's unpadded
    transforms are its backend's FFT module's whatever the name, as for every body."""
    terms = list(terms)
    responses: dict[str, CreepSpectrum] = {}
    for term in terms:
        key = history_key(term)
        if key in responses and responses[key] is not term.response:
            raise ValueError(f"terms reading history {key!r} have different responses")
        responses[key] = term.response
    backend = backend or CPU
    kernels = {t.name: backend.to_device(t.kernel) for t in terms}
    selves = [t.name for t in terms if t.displacement == t.traction]
    if grid.periodic:
        conv = PeriodicConvolver.from_kernels(grid.n, kernels, workers, xp=backend.xp, fft=backend.fft)
        precond = {name: conv.preconditioner(name) for name in selves}
    else:
        conv = Convolver.from_kernels(grid.n, kernels, workers, xp=backend.xp, fft=backend.fft,
                                      transforms=grid_transforms(grid.n, workers, fft, backend, grid.rows))
        precond = {name: FourierPreconditioner.for_kernel(kernels[name], 1.0, workers, fft=backend.fft)
                   for name in selves}
    core_terms = [t.placed() for t in terms]
    return Compliance(grid, core_terms, responses, conv, precond, scheme, dt, direct, periodic=grid.periodic,
                         steady_shapes={t.name: t.steady for t in terms if t.steady is not None}, backend=backend)


def compliance_of(problem, components: Sequence[str] | None = None,
                  backend: ArrayBackend | None = None) -> Compliance:
    """The compliance of ``problem``'s body (:meth:`~viscontact.bodies.base.Body.compliance`).

    ``components``: the kernels to build; by default what the transient needs: ``zz``, ``xx`` for
    partial slip and rolling, and the coupling ``xz``, ``zx`` when sliding with friction, nu < 0.5 and
    ``solver.coupling``. The steady solver asks for ``("zz",)`` (it builds its own kernels).

    ``backend``: where the fields live (:mod:`viscontact.numerics.arrays`); None: that of ``solver.device``.
    """
    backend = backend or array_backend(problem.solver.device)
    if components is None:
        nu = problem.material.poisson_ratio
        mode = problem.tangential.mode
        components = ["zz"] + (["xx"] if mode in ("partial_slip", "rolling") else [])
        if nu < 0.5 and problem.solver.coupling and mode in ("partial_slip", "gross_sliding", "rolling"):
            components += ["xz", "zx"]
    solver = problem.solver
    return problem.body.compliance(problem.grid, components, problem.time.scheme, problem.time.dt,
                                   workers=solver.workers, direct=solver.history == "direct", fft=solver.fft,
                                   backend=backend)
