"""Terms of a surface compliance operator: a shape kernel and the time response it is multiplied by.

The surface displacement component i under the traction history of component j is a sum of terms

    u_i(x, t) = sum_terms  K_term * ( phi_term (*) dq_j )                                    [m]

where ``K_term`` is a real-space influence kernel on the DC-FFT offset grid (displacement per unit
cell traction, [m/Pa] x [Pa]; see :mod:`viscontact.kernels`), ``(*)`` the Stieltjes (hereditary)
convolution in time and ``phi_term(t) = J0 + sum_m J_m (1 - exp(-t/lambda_m))`` [1/Pa] a
:class:`~viscontact.materials.CreepSpectrum`. A homogeneous half-space with constant Poisson ratio
has one term per component pair, all sharing the shear creep compliance J(t); a time-dependent
Poisson ratio (:mod:`viscontact.poisson`) splits kernels into shape parts with their own computed
spectra; a layer (:mod:`viscontact.layers`) brings its own kernels.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Iterable

import numpy as np

from .materials import CreepSpectrum

if TYPE_CHECKING:
    from .steady_kernels import SteadyShape


@dataclass(frozen=True)
class ComplianceTerm:
    """One term of the compliance operator.

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
        (:class:`~viscontact.steady_kernels.SteadyShape`); None where it is not built (periodic
        grids need none: the periodic steady state is exact in Fourier space).

    On a periodic grid (``grid.periodic``) ``kernel`` is the periodic kernel on the n x n grid in
    wrap-around order (zero mean where the mean compliance is unbounded, :mod:`viscontact.periodic`).
    """

    displacement: str
    traction: str
    kernel: np.ndarray
    response: CreepSpectrum
    name: str = ""
    steady: SteadyShape | None = None


def carson_transform(spectrum: CreepSpectrum, s: np.ndarray | float) -> np.ndarray:
    """s phi^(s) = phi(inf) - sum_m J_m s / (s + 1/lambda_m) [1/Pa] at Laplace variables s [1/s]."""
    s = np.asarray(s, dtype=complex if np.iscomplexobj(s) else float)
    out = np.full(s.shape, spectrum.long_term, dtype=s.dtype)
    for jm, lm in zip(spectrum.amplitudes, spectrum.retardation_times):
        out = out - jm * s / (s + 1.0 / lm)
    return out


def linear_combination(parts: Iterable[tuple[float, CreepSpectrum]]) -> CreepSpectrum:
    """sum_k c_k phi_k as one spectrum (amplitudes of equal retardation times added, zeros dropped,
    times sorted ascending)."""
    inst = 0.0
    amps: list[np.ndarray] = []
    times: list[np.ndarray] = []
    for coef, spec in parts:
        if coef == 0.0:
            continue
        inst += coef * spec.instantaneous
        amps.append(coef * np.asarray(spec.amplitudes, dtype=float))
        times.append(np.asarray(spec.retardation_times, dtype=float))
    if not amps:
        return CreepSpectrum(0.0, np.zeros(0), np.zeros(0))
    a, lam = np.concatenate(amps), np.concatenate(times)
    uniq, inverse = np.unique(lam, return_inverse=True)
    summed = np.zeros(uniq.size)
    np.add.at(summed, inverse, a)
    keep = summed != 0.0
    return CreepSpectrum(float(inst), summed[keep], uniq[keep])


def complex_compliance(spectrum: CreepSpectrum, omega: np.ndarray | float) -> np.ndarray:
    """phi*(omega) = J_0 + sum_m J_m / (1 + i omega lambda_m) [1/Pa] at angular frequencies omega
    [rad/s] (exp(i omega t) convention): the Carson transform at s = i omega."""
    return carson_transform(spectrum, 1j * np.asarray(omega, dtype=float))


def history_key(term: ComplianceTerm) -> str:
    """Key of the hereditary history a term reads: its traction component and response label
    (``"zz:bulk"`` and ``"xz:bulk"`` both read p through L(t): ``"z:bulk"``; an unlabelled term
    ``"zz"``: ``"z:creep"``)."""
    label = term.name.split(":", 1)[1] if ":" in term.name else "creep"
    return f"{term.traction}:{label}"


def term_substrate(grid, terms: Iterable[ComplianceTerm], scheme, dt: float, *, workers: int = -1,
                   direct: bool = False, backend=None):
    """A :class:`~viscontact.substrate.TermSubstrate` of compliance terms: each term a kernel named
    after it, terms with the same :func:`history_key` sharing one history (they must share the
    response), Fourier preconditioners for the self (zz, xx) kernels, the terms' steady shapes. On
    a periodic grid the kernels are periodic (n x n) and the convolver is the unpadded
    :class:`~viscontact.periodic.PeriodicConvolver`; otherwise DC-FFT. For the solvers'
    ``substrate=`` argument (e.g. :func:`viscontact.transient.steps`). ``backend``: where the fields
    live (an :class:`~viscontact.arrays.ArrayBackend`; None: the CPU)."""
    from .arrays import CPU
    from .convolution import Convolver, FourierPreconditioner
    from .periodic import PeriodicConvolver
    from .substrate import Term, TermSubstrate

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
        conv = Convolver.from_kernels(grid.n, kernels, workers, xp=backend.xp, fft=backend.fft)
        precond = {name: FourierPreconditioner.for_kernel(kernels[name], 1.0, workers, fft=backend.fft)
                   for name in selves}
    core_terms = [Term(t.displacement, t.traction, t.name, history_key(t)) for t in terms]
    return TermSubstrate(grid, core_terms, responses, conv, precond, scheme, dt, direct, periodic=grid.periodic,
                         steady_shapes={t.name: t.steady for t in terms if t.steady is not None}, backend=backend)
