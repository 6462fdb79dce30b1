"""Direct steady-state solver for sliding at constant speed v.

In the frame of the indenter the half-space moves at -v along x, so a material point now at x was
at x + xi a time xi/v ago. With the tractions steady in this frame, the hereditary integral of
seed Eq. 5 becomes (integration by parts, J(t) = J_0 + sum_m J_m (1 - exp(-t/lambda_m)))

    u(x) = J_0 [IC * p](x) + sum_m J_m int_0^inf exp(-xi/L_m)/L_m [IC * p](x + xi) dxi,  L_m = v lambda_m,

i.e. a convolution with the *effective steady kernel*

    K(d) = J_0 IC(d) + sum_m J_m F_m(d),   F_m(d) = int_0^inf exp(-xi/L_m)/L_m IC(d + xi) dxi.

F_m integrates the whole past of the material, far beyond the grid, so only the contact needs to
be on the grid (no wake truncation). It is built once per speed by the compliance
(:meth:`viscontact.bodies.half_space.HalfSpace.steady_convolver`, all modes in one pass by
:mod:`viscontact.physics.steady_kernels`).

The kernel is not symmetric, so the contact problem (p >= 0, gap >= 0, complementarity, load or
approach given) is solved by a primal-dual active-set method (Hintermueller, Ito & Kunisch 2002):
on the current contact set the linear system is solved with GMRES (:mod:`viscontact.numerics.krylov`, FFT
matrix-vector products), then points with negative pressure leave and points with negative gap
enter, until the set is stable. Each solve uses at most ``solver.max_iterations`` Krylov iterations.
What makes it fast:

* the Fourier preconditioner is the operator's own symbol, the elastic one times the complex
  compliance J*(k_x v) (:func:`steady_preconditioner`): ~20 GMRES iterations per solve to 1e-10
  instead of ~65 with the symmetric part alone;
* under load control a round is one solve of the bordered system for (p, delta), preconditioned by
  the same block system with the Fourier preconditioner (:func:`_solve_bordered`), not two solves;
* until the set first settles the solves stop at 1e-6 (:func:`solve_contact_active_set`), then the
  settled set is solved to the tolerance and checked again (the answer is that of exact rounds);
* the first set comes from the steady state on the grid with half the cells per side
  (:func:`coarse_start`, recursively down to 64^2), so the fine grid needs a few rounds, not ~10;
  a speed sweep starts each speed from the previous one instead (:func:`speed_sweep`).

For gross sliding (q_x = mu_f p) the operator is K_zz + mu_f K_zx.

With ``[adhesion]`` (a Maugis-Dugdale surface) the contact, the cohesive zone and the free surface
are found by :func:`viscontact.numerics.adhesive.adhesive_active_set` on K_zz (the same active set on
x = p + sigma_0 1_I for each interaction zone I, the zone moved to a fixed point), with q_x = mu_f
max(p, 0) whose displacement mu_f K_zx max(p, 0) enters the gap as a fixed point (:func:`_solve_adhesive`);
on a periodic grid with the period's exact steady operator (:func:`_periodic_adhesive`).

The fields are those of the compliance's array backend (:mod:`viscontact.numerics.arrays`); the record comes
back to the host, measured by :func:`viscontact.solvers.measure.measure` as a transient step is.
"""
from __future__ import annotations

from dataclasses import replace
from typing import Sequence

import numpy as np

from viscontact.bodies.compliance import compliance_of
from viscontact.bodies.compliance import Compliance
from viscontact.errors import ParameterError
from viscontact.numerics.active_set import solve_contact_active_set
from viscontact.numerics.adhesive import NoEquilibriumError, Operator, adhesive_active_set
from viscontact.numerics.convolution import Convolver, FourierPreconditioner
from viscontact.problem.problem import PHASE_GROSS_SLIDING, Problem
from viscontact.problem.records import StepRecord
from viscontact.solvers.measure import measure
from viscontact.solvers.sliding import check_speed


def steady_convolver(problem: Problem, speed: float, compliance: Compliance | None = None
                     ) -> tuple[Convolver, dict[str, np.ndarray]]:
    """The compliance's effective steady kernels at ``speed`` [m/s] (``zz``, and ``zx`` when sliding with
    friction and coupling): ``apply("zz", p)`` is u_z [m] of the pressure p [Pa]."""
    components = steady_components(problem)
    compliance = compliance or compliance_of(problem, components)
    return compliance.steady_convolver(speed, components)


def steady_components(problem: Problem) -> list[str]:
    """Kernels of the steady operator: ``zz``, and ``zx`` when sliding with friction and coupling
    (nu < 0.5, ``solver.coupling``)."""
    mat = problem.material
    coupled = problem.tangential.effective_friction > 0 and mat.poisson_ratio < 0.5 and problem.solver.coupling
    return ["zz"] + (["zx"] if coupled else [])


def steady_preconditioner(compliance: Compliance, kernels: dict[str, np.ndarray], speed: float,
                          workers: int = -1, symmetric: bool = False) -> FourierPreconditioner:
    """Fourier preconditioner of the steady operator K_zz [m/Pa] at ``speed`` [m/s]: the compliance's
    own where it knows the operator's symbol
    (:meth:`~viscontact.bodies.compliance.Compliance.steady_preconditioner`: the
    :class:`~viscontact.bodies.half_space.HalfSpace`'s, with the phase of the viscous lag: 2.5-3x fewer
    GMRES iterations), else the symmetric part of the wrapped effective kernel (|Re K^|)."""
    known = compliance.steady_preconditioner(speed, workers, symmetric)
    if known is not None:
        return known
    return FourierPreconditioner.for_kernel(compliance.backend.to_device(kernels["zz"]), 1.0, workers, fft=compliance.fft)


def _symmetric_guess(conv: Convolver, problem: Problem, value: float, coupled: bool, mu: float,
                     preconditioner: FourierPreconditioner | None = None) -> np.ndarray:
    """Polonsky-Keer solution with the symmetric part of the steady operator (spectrum Re K^):
    the right contact size, a good first active set for the non-symmetric solve."""
    from viscontact.numerics.constrained import constrained_cg

    spec = conv.spectra["zz"].real.astype(complex)
    if coupled:
        spec = spec + mu * conv.spectra["zx"].real
    sym = Convolver(conv.n, {"s": spec}, conv.workers, xp=conv.xp, fft=conv.fft, rows=conv.rows)
    grid = problem.grid
    gap = conv.xp.asarray(problem.gap)
    b = -gap if problem.normal.control == "load" else value - gap
    sol = constrained_cg(lambda x: sym.apply("s", x), b, np.zeros_like(b), 0.0, np.inf,
                         total=value if problem.normal.control == "load" else None,
                         cell_area=grid.cell_area, tolerance=1e-6, max_iterations=problem.solver.max_iterations,
                         preconditioner=preconditioner)
    return sol.x


#: the coarsest grid of the coarse-grid start (:func:`coarse_start`): started from the symmetric guess
COARSEST = 64


def coarse_problem(problem: Problem) -> Problem:
    """The problem on the grid with half the cells per side (same domain, n even): the gap averaged
    over each 2 x 2 block of cells (its value at the coarse cell centre to O(dx^2))."""
    grid = problem.grid
    return replace(problem, grid=grid.coarsened(), gap=grid.block_mean(problem.gap), radius=None)


def coarse_start(problem: Problem, speed: float) -> np.ndarray:
    """First pressure [Pa] for the active set on ``problem``'s grid: the steady state at ``speed``
    [m/s] on the grid with half the cells per side (itself started the same way down to
    :data:`COARSEST` cells per side), each coarse cell's pressure on its 2 x 2 fine cells.

    The coarse contact set is right to about one coarse cell, so the fine active set needs a few
    rounds instead of the ~10 it needs from the symmetric guess; a coarse solve costs a quarter of
    a fine one per iteration (kernel build included)."""
    coarse = solve_steady(coarse_problem(problem), speed)
    return problem.grid.spread_blocks(coarse.pressure)


#: the case keys a steady state never reads -> why (:func:`ignored_keys`: with those it ignores only
#: in some cases). Each was checked to leave every variable of a steady result bit for bit unchanged.
IGNORED_KEYS = {
    "time.dt": "a steady state has no time steps",
    "time.scheme": "a steady state has no time steps",
    "tangential.steps_per_cell": "it sets the default time.dt, and a steady state has no time steps",
    "tangential.displacement_rate": "it drives partial slip, and a steady state is gross sliding",
    "tangential.slip": "it is partial slip's stick condition, and a steady state is gross sliding",
    "output.every": "a steady state is one record",
    "output.subsurface_times": "a steady state is one record",
    "solver.coupling_tolerance": "the steady solver couples the normal and tangential tractions exactly, "
                                 "without alternations",
    "solver.max_coupling_iterations": "the steady solver couples the normal and tangential tractions exactly, "
                                      "without alternations",
    "solver.mixed_precision": "it sets the transient's conjugate gradient; the steady solver uses GMRES in double",
    "solver.history": "a steady state has no hereditary sum over past steps",
}


def ignored_keys(problem: Problem) -> dict[str, str]:
    """The case keys that cannot change ``problem``'s steady state -> why: :data:`IGNORED_KEYS`, and
    ``time.t_end`` under a held normal condition (its value at t_end is the one taken: only a
    ``normal.history`` reads it) and ``tangential.friction_coefficient`` without friction
    (``tangential.mode`` "none" or "frictionless_sliding")."""
    keys = dict(IGNORED_KEYS)
    if len(set(problem.normal.history.values)) == 1:
        keys["time.t_end"] = "the steady state takes the normal condition at time.t_end, and it is held"
    if problem.tangential.mode in ("none", "frictionless_sliding"):
        keys["tangential.friction_coefficient"] = f"tangential.mode = {problem.tangential.mode!r} has no friction"
    return keys


def check_steady(problem: Problem, speed: float | None = None) -> None:
    """What a steady state needs of ``problem`` besides the guards: an indenter that slides (a
    ``tangential.displacement_history`` never does: fretting has no steady sliding state) at a
    ``speed`` > 0 m/s (default: the problem's sliding speed; :func:`check_speed`)."""
    if problem.tangential.displacement_history is not None:
        raise ParameterError("tangential.displacement_history", "a displacement history (fretting) never slides, so "
                             "the case has no steady sliding state; run its transient (viscontact run), or drop "
                             "the history and give tangential.sliding_speed for a steady state of sliding")
    check_speed(problem.tangential.sliding_speed if speed is None else speed)


def solve_steady(problem: Problem, speed: float | None = None, *, initial: np.ndarray | None = None,
                 compliance: Compliance | None = None) -> StepRecord:
    """Steady state of sliding at ``speed`` [m/s] (default: the problem's sliding speed).

    Frictionless (``frictionless_sliding``) or with q_x = mu_f p (``gross_sliding``,
    ``partial_slip`` once sliding). The normal condition is the history's final value. The record's
    ``iterations`` counts the GMRES (Krylov) iterations of all active-set rounds on this grid (not
    those of the coarse-grid start, a quarter the cost each). ``initial``: the pressure [Pa] to
    start the active set from (default: :func:`coarse_start` when n >= 2 :data:`COARSEST` is even,
    else the symmetric guess). On a periodic grid
    the steady state is exact in Fourier space (:mod:`viscontact.solvers.steady_periodic`).
    """
    v = problem.tangential.sliding_speed if speed is None else speed
    check_steady(problem, v)
    grid = problem.grid
    mu = problem.tangential.effective_friction if problem.tangential.mode != "none" else 0.0
    value = problem.normal.history(problem.time.t_end)
    tolerance = min(problem.solver.tolerance, 1e-10)
    compliance = compliance or compliance_of(problem, steady_components(problem))
    backend = compliance.backend
    if initial is not None:
        initial = backend.to_device(initial)
    if grid.periodic and problem.adhesion is not None:
        return _periodic_adhesive(problem, compliance, v, mu, value, initial, tolerance)
    if grid.periodic:
        from viscontact.solvers.steady_periodic import solve_periodic_steady

        state = solve_periodic_steady(compliance.convolver, problem.material, grid, problem.gap,
                                      speed=v, control=problem.normal.control, value=value, friction=mu,
                                      initial=initial, tolerance=tolerance,
                                      max_iterations=problem.solver.max_iterations,
                                      spectrum=compliance.steady_spectrum(v, mu), to_host=backend.to_host)
        p, delta, krylov, u_z = state.pressure, state.delta_z, state.iterations, state.displacement_z
    else:
        conv, kernels = steady_convolver(problem, v, compliance)
        coupled = "zx" in conv.spectra
        precondition = steady_preconditioner(compliance, kernels, v, problem.solver.workers)

        def apply_k(p: np.ndarray) -> np.ndarray:
            return conv.combine([("zz", 1.0, p)] + ([("zx", mu, p)] if coupled else []))

        if initial is None and grid.n >= 2 * COARSEST and grid.n % 2 == 0:
            initial = backend.to_device(coarse_start(problem, v))
        elif initial is None and problem.adhesion is None:
            initial = _symmetric_guess(conv, problem, value, coupled, mu,
                                       steady_preconditioner(compliance, kernels, v, problem.solver.workers, True))
        if problem.adhesion is not None:
            def apply_zz(p: np.ndarray) -> np.ndarray:
                return conv.apply("zz", p)

            def cross(p: np.ndarray) -> np.ndarray:
                return mu * conv.apply("zx", np.maximum(p, 0.0))

            p, delta, krylov, u_z, interaction = _solve_adhesive(apply_zz, cross if coupled and mu else None, problem,
                                                                 value, initial, tolerance, precondition, backend)
            return measure(problem, p, mu * np.maximum(p, 0.0), u_z, delta_z=delta, value=value, gap=problem.gap,
                           step=0, t=problem.time.t_end, phase=PHASE_GROSS_SLIDING, sliding_distance=float("inf"),
                           iterations=krylov, where=f" at v = {v:.4g} m/s", interaction=interaction)
        p, delta, krylov, _ = solve_contact_active_set(apply_k, backend.to_device(problem.gap),
                                                       control=problem.normal.control, value=value,
                                                       cell_area=grid.cell_area, initial=initial, tolerance=tolerance,
                                                       max_iterations=problem.solver.max_iterations,
                                                       preconditioner=precondition)
        p, u_z = backend.to_host(p), backend.to_host(apply_k(p))
    return measure(problem, p, mu * p, u_z, delta_z=delta, value=value, gap=problem.gap, step=0, t=problem.time.t_end,
                   phase=PHASE_GROSS_SLIDING, sliding_distance=float("inf"), iterations=krylov,
                   where=f" at v = {v:.4g} m/s")


def _solve_adhesive(apply_zz: Operator, cross: Operator | None, problem: Problem, value: float,
                    initial: np.ndarray | None, tolerance: float, preconditioner: FourierPreconditioner,
                    backend) -> tuple[np.ndarray, float, int, np.ndarray, np.ndarray]:
    """The steady Maugis-Dugdale contact (``[adhesion]``) on the effective steady kernel ``apply_zz``
    (p [Pa] -> u_z [m]; that of a DC-FFT grid, or a period's with the q = 0 entry of its solve,
    :class:`~viscontact.solvers.steady_periodic.PeriodicSteadyOperator`):
    :func:`~viscontact.numerics.adhesive.adhesive_active_set` (contact, cohesive zone and free surface),
    with q_x = mu_f max(p, 0) (no friction where the interface is in tension, as in the transient:
    :mod:`viscontact.solvers.adhesive_law`) whose displacement ``cross`` = mu_f K_zx max(p, 0) enters as
    a fixed point (the coupling; None: uncoupled). Returns (p [Pa], delta [m], GMRES iterations,
    u_z [m], the interaction zone), on the host. A tensile load that no zone carries (beyond the
    pull-off) raises :class:`~viscontact.errors.ParameterError` naming the normal key."""
    adhesion = problem.adhesion
    try:
        sol = adhesive_active_set(apply_zz, backend.to_device(problem.gap), control=problem.normal.control,
                                  value=value, cohesive_stress=adhesion.cohesive_stress,
                                  work_of_adhesion=adhesion.work_of_adhesion, cell_area=problem.grid.cell_area,
                                  initial=initial, cross=cross, tolerance=tolerance,
                                  max_iterations=problem.solver.max_iterations, preconditioner=preconditioner)
    except NoEquilibriumError as exc:  # a tensile load beyond the pull-off: the case asks for what cannot be
        key = "normal.value" if len(problem.normal.history.times) == 1 else "normal.history"
        raise ParameterError(key, f"{exc} (no steady sliding state: lower the tensile load)") from None
    u_z = sol.product + (cross(sol.pressure) if cross is not None else 0.0)
    return (backend.to_host(sol.pressure), sol.approach, sol.iterations, backend.to_host(u_z),
            backend.to_host(sol.interaction))


def _periodic_adhesive(problem: Problem, compliance: Compliance, speed: float, friction: float, value: float,
                       initial: np.ndarray | None, tolerance: float) -> StepRecord:
    """The steady adhesive state at ``speed`` [m/s] on a periodic grid: :func:`_solve_adhesive` on the
    period's steady operator (:class:`~viscontact.solvers.steady_periodic.PeriodicSteadyOperator`, the
    spectrum K^_zz J*(-k_x v)), with the coupling mu_f K^_zx J*(-k_x v) max(p, 0) for ``friction`` mu_f
    where the compliance has ``zx``; u_z [m] of zero mean and delta_z [m] in the zero-mean convention, as
    :func:`~viscontact.solvers.steady_periodic.solve_periodic_steady` reports them."""
    from viscontact.physics.periodic import check_approach
    from viscontact.solvers.steady_periodic import PeriodicSteadyOperator

    backend = compliance.backend
    if problem.normal.control == "displacement":
        check_approach(value, problem.gap)
    zz = compliance.steady_spectrum(speed)
    op = PeriodicSteadyOperator.of(compliance.convolver, zz, problem.normal.control)
    cross = None
    if friction > 0 and "zx" in compliance.convolver.spectra:
        apply_zx = op.apply(compliance.steady_spectrum(speed, friction) - zz)

        def cross(p: np.ndarray) -> np.ndarray:
            return apply_zx(np.maximum(p, 0.0))

    p, solved, krylov, _, interaction = _solve_adhesive(op.apply(op.solve_spectrum), cross, problem, value, initial,
                                                        tolerance, op.preconditioner, backend)
    u_z = backend.to_host(op.apply(zz)(backend.to_device(p)) + (cross(backend.to_device(p)) if cross else 0.0))
    return measure(problem, p, friction * np.maximum(p, 0.0), u_z, delta_z=op.approach(solved, p), value=value,
                   gap=problem.gap, step=0, t=problem.time.t_end, phase=PHASE_GROSS_SLIDING,
                   sliding_distance=float("inf"), iterations=krylov, where=f" at v = {speed:.4g} m/s",
                   interaction=interaction)


def speed_sweep(problem: Problem, speeds: Sequence[float]) -> list[StepRecord]:
    """Steady states at each speed [m/s], in the given order, each warm-started from the previous;
    one compliance serves them all (its kernel builder keeps what does not depend on the speed)."""
    out: list[StepRecord] = []
    previous = None
    compliance = compliance_of(problem, steady_components(problem))
    for v in speeds:
        rec = solve_steady(problem, v, initial=previous, compliance=compliance)
        previous = rec.pressure
        out.append(rec)
    return out
