"""The normal/tangential coupling iteration of one transient step around a contact law.

A contact law (:mod:`viscontact.solvers.contact_laws`) solves one pass from an iterate (p, q); where the
normal and tangential components are coupled (IC_zx, IC_xz ~ (1 - 2 nu), seed Eqs. 9-12) a pass
depends on the previous iterate, and :func:`solve_coupled` iterates the passes as a fixed point,
under-relaxed (:func:`relaxation_weight`) or handed to the law's direct solve where it contracts too
slowly.
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from viscontact.errors import ConvergenceError
from viscontact.solvers.contact_laws import ContactLaw, StepContext, StepSolution


def _relative_change(new: np.ndarray, old: np.ndarray) -> float:
    scale = float(np.sum(np.abs(new)))
    return float(np.sum(np.abs(new - old))) / scale if scale > 0 else 0.0


#: smallest relaxation weight of the coupling iteration (:func:`relaxation_weight`)
MIN_RELAXATION = 0.02
#: a coupling pass whose change is above this fraction of the last pass's contracts too slowly for
#: the plain fixed point (:func:`solve_coupled`; the seed's cases shrink by about 0.1 a pass)
SLOW_CONTRACTION = 0.7


def relaxation_weight(weight: float, ratio: float) -> float:
    """Relaxation weight omega of the coupling iteration x <- (1 - omega) x + omega S(x) after a pass
    whose change shrank by ``ratio`` (>= 1: it did not shrink) under ``weight``.

    The coupling term mu_f K_zx is odd in x (a skew operator), so about the solution the map S acts
    on x through a matrix of imaginary eigenvalues +-i gamma, gamma ~ mu_f (1 - 2 nu) / (2 (1 - nu))
    relative to K_zz: the plain iteration (omega = 1) shrinks the change by gamma, diverging beyond 1.
    Relaxed, the change shrinks by |1 - omega -+ i omega gamma| = sqrt((1 - omega)^2 + omega^2 gamma^2),
    smallest, gamma / sqrt(1 + gamma^2) < 1, at omega = 1 / (1 + gamma^2). gamma is read off the
    observed ratio, gamma^2 = (ratio^2 - (1 - weight)^2) / weight^2; the weight never grows and
    stays above :data:`MIN_RELAXATION`.
    """
    gamma2 = max(ratio**2 - (1.0 - weight) ** 2, 0.0) / weight**2
    return max(min(weight, 1.0 / (1.0 + gamma2)), MIN_RELAXATION)


def solve_coupled(law: ContactLaw, ctx: StepContext, pressure: np.ndarray, shear: np.ndarray,
                  product: np.ndarray | None = None) -> StepSolution:
    """Fixed-point iteration of the contact ``law`` from (p, q) [Pa] until both change by less than
    ``solver.coupling_tolerance`` (one pass when it is not coupled); ``product``: the step's normal
    operator applied to p [m], where known (each pass hands its own on to the next). The solution's
    ``iterations`` are those of all passes, its ``coupling_iterations`` the passes.

    While the change shrinks from pass to pass, each pass starts from the last one's solution (the
    seed's cases: mu_f (1 - 2 nu) / (2 (1 - nu)) < 0.1). After a pass whose change did not shrink
    (a large mu_f (1 - 2 nu)), a law with a direct method for the coupled operator
    (``solve_direct``: gross sliding) solves the step with it; otherwise (partial slip)
    under-relaxation turns on (:func:`relaxation_weight`): the next pass starts from a weighted mean
    of its start and its solution (both satisfy the bounds and the load, so the mean does), which
    converges where the plain iteration diverges. A converged pass's own solution is returned."""
    settings = ctx.problem.solver
    iterations = 0
    change = previous = np.inf
    weight = 1.0
    for count in range(1, settings.max_coupling_iterations + 1):
        solved = law.solve(ctx, pressure, shear, product)
        p, q, solved_product = solved.pressure, solved.shear_x, solved.pressure_product
        iterations += solved.iterations
        change = _relative_change(p, pressure)
        if law.solves_shear:
            change = max(change, _relative_change(q, shear))
        if not law.coupled or change < settings.coupling_tolerance:
            return law.finish(ctx, replace(solved, iterations=iterations, coupling_iterations=count))
        if change >= SLOW_CONTRACTION * previous:
            if hasattr(law, "solve_direct"):  # the coupling is too strong for the fixed point
                direct = law.solve_direct(ctx, p)
                return law.finish(ctx, replace(direct, iterations=iterations + direct.iterations,
                                               coupling_iterations=count + 1))
            weight = relaxation_weight(weight, change / previous)
        previous = change
        if weight == 1.0:
            pressure, shear, product = p, q, solved_product
        else:
            pressure = (1.0 - weight) * pressure + weight * p
            shear = (1.0 - weight) * shear + weight * q
            product = (None if product is None or solved_product is None
                       else (1.0 - weight) * product + weight * solved_product)
    hint = ("raise solver.max_coupling_iterations" if weight == 1.0 else
            f"it converges slowly (under-relaxed by {weight:.2g}: a large mu_f (1 - 2 nu)); raise "
            "solver.max_coupling_iterations")
    raise ConvergenceError(f"normal/tangential coupling ({law.label})", settings.max_coupling_iterations,
                           change, settings.coupling_tolerance, hint=hint)


