"""The adhesive normal contact problem of a smooth exponential traction-separation law, solved by the
majorise-minimise rounds of :mod:`viscontact.numerics.adhesive` with the tension of the last round's gap.

The law (on each cell): a tension sigma(g) = (w / rho) exp(-g / rho) [Pa] across an open gap g >= 0,
of peak w / rho at contact and work of separation int_0^inf sigma dg = w [J/m^2] (the Dupre work of
adhesion); the range rho [m] sets its reach: the adhesive potential -w exp(-g / rho) of the
exponential interaction used by Muser (2014, Beilstein J. Nanotechnol. 5, 419) for single-asperity
adhesion with a finite range. With
the elastic operator K (p -> u_z) and the known gap h_k [m], g = K p + h_k - delta, the state makes the
energy

    Pi(p) = 1/2 p.K p + sum_cells phi(g) dA [- W delta under load control],
    phi(g) = -w exp(-g / rho) for g >= 0 (+inf for g < 0),

stationary. phi is concave on g >= 0 (phi'' = -(w / rho^2) exp(-g / rho) < 0), the sum of a concave
function and the convex indicator of g >= 0: its tangent at the last gap g_k, phi(g_k) + sigma(g_k)
(g - g_k), majorises it and touches it at g_k. The majorant problem is the Maugis-Dugdale round of
:mod:`viscontact.numerics.adhesive` with sigma_0 1_I replaced by the fixed tension field sigma(g_k):
x = p + sigma(g_k) >= 0, complementary to the gap (Polonsky & Keer,
:func:`~viscontact.numerics.support_window.windowed_cg`, load control included). Each round therefore
never increases Pi (the majorise-minimise descent: Pi(p_k+1) <= M(p_k+1 | p_k) <= M(p_k | p_k) =
Pi(p_k)), the guarantee the Maugis-Dugdale rounds have; unlike them the tension changes continuously,
so the rounds end on a residual, max |sigma(g_k+1) - sigma(g_k)| <= :data:`ROUND_FACTOR` (the solve's
tolerance) w / rho, the last round solved to the full tolerance, after at most ``max_rounds`` rounds
(:class:`~viscontact.errors.ConvergenceError` beyond). Linearised about a stable equilibrium (on its open
cells) the rounds contract by the largest eigenvalue of K diag(sigma / rho) (< 1 where the equilibrium is
stable, positive: a monotone approach), which tends to 1 at a jump or a pull-off. Under load control a
round whose tension field cannot carry the load, W + sum sigma(g_k) dA <= 0, has no majorant
minimiser (the indenter would fly off): the pull-off,
:class:`~viscontact.numerics.adhesive.NoEquilibriumError`, as for the Maugis-Dugdale law. (Under a tensile
load Pi itself is unbounded below, the indenter pulled off to infinity: the descent says the rounds
never climb, not that they stay at a local equilibrium; near the pull-off they may drift off, and the
capacity test ends them.)
"""
from __future__ import annotations

from typing import Any, Literal

import numpy as np

from viscontact.errors import ConvergenceError
from viscontact.numerics.adhesive import AdhesiveSolution, FullDomain, NoEquilibriumError
from viscontact.numerics.support_window import windowed_cg

#: the rounds end when the tension of the new gap differs from the last round's by at most this multiple
#: of the solve's tolerance, as a fraction of the peak w / rho, on every cell (the solves' own error
#: sets a floor: with a relative tolerance of 1e-8, residuals of 5e-8 at a range of 0.9 um)
ROUND_FACTOR = 100.0
#: relative tolerance of the Polonsky-Keer solves of the rounds before the residual is met, at most
#: (the last round: the solve's own) ...
LOOSE_TOLERANCE = 1e-6
#: ... and at most this fraction of the last residual (a loose solve must not hide the residual)
LOOSE_FACTOR = 1e-2


def exponential_tension(gap: np.ndarray, work_of_adhesion: float, decay_length: float) -> np.ndarray:
    """sigma(g) = (w / rho) exp(-g / rho) [Pa] (tension positive) at the gaps g >= 0 [m]."""
    return (work_of_adhesion / decay_length) * np.exp(-np.maximum(gap, 0.0) / decay_length)


def exponential_contact(operator: Any, known_gap: np.ndarray, *, control: Literal["load", "displacement"],
                        value: float, work_of_adhesion: float, decay_length: float, cell_area: float,
                        initial: np.ndarray | None = None, interaction: np.ndarray | None = None,
                        tolerance: float = 1e-10, max_iterations: int = 2000, max_rounds: int = 2000,
                        preconditioner: Any = None, mixed_precision: bool = True) -> AdhesiveSolution:
    """Solve the exponential adhesive problem of the module docstring.

    Parameters
    ----------
    operator
        K, symmetric positive definite: an :class:`~viscontact.bodies.compliance.ElasticOperator` or a
        plain action p [Pa] -> K p [m].
    known_gap
        h_k [m]: the undeformed gap plus the known displacement, before the approach.
    control, value
        ``"displacement"``: the approach delta [m]; ``"load"``: the load W [N] (negative: a pull).
    work_of_adhesion, decay_length
        w [J/m^2] and rho [m].
    cell_area
        dA [m^2].
    initial, interaction
        A warm start: the last pressure [Pa] and contact (gap 0, bool); the first tension field is w /
        rho on that contact and the last tension -p (0 to w / rho) elsewhere. None: the tension of the
        rigid gap h_k - delta under displacement control, none under load control.
    tolerance, max_iterations
        Of each Polonsky-Keer solve.
    max_rounds
        Rounds at most before :class:`~viscontact.errors.ConvergenceError`.
    preconditioner
        For a plain action: r -> approximate K^-1 r.
    mixed_precision
        Single-precision search directions where the operator has them.

    Returns
    -------
    AdhesiveSolution
        Its ``interaction`` is the contact (gap 0): the tension acts everywhere.

    Raises
    ------
    NoEquilibriumError
        Under load control, when the tension field cannot carry the load (the pull-off).
    ConvergenceError
        When the residual is not met after ``max_rounds`` rounds, or a solve does not converge.
    """
    op = operator if hasattr(operator, "apply") else FullDomain(operator, preconditioner)
    w, rho = float(work_of_adhesion), float(decay_length)
    peak = w / rho
    load_control = control == "load"
    if initial is not None:
        contact = np.zeros_like(known_gap, dtype=bool) if interaction is None else interaction.astype(bool)
        tension = np.where(contact, peak, np.clip(-initial, 0.0, peak))
        x = np.maximum(initial + tension, 0.0)
    else:
        rigid = known_gap - value
        tension = np.zeros_like(known_gap) if load_control else exponential_tension(rigid, w, rho)
        x = np.zeros_like(known_gap)
    iterations, tight, residual = 0, False, np.inf
    enough = ROUND_FACTOR * tolerance
    for rounds in range(1, max_rounds + 1):
        shift = op.apply(tension)
        total = None
        if load_control:
            capacity = float(tension.sum()) * cell_area
            if value + capacity <= 0.0:
                raise NoEquilibriumError(value, -capacity)
            total, b = value + capacity, shift - known_gap
        else:
            b = shift + value - known_gap
        loose = max(tolerance, min(LOOSE_TOLERANCE, LOOSE_FACTOR * residual))
        sol = windowed_cg(op, b, x, total=total, cell_area=cell_area, tolerance=tolerance if tight else loose,
                          max_iterations=max_iterations, what=f"exponential adhesive contact ({control} control)",
                          mixed_precision=mixed_precision)
        x = sol.x
        iterations += sol.iterations
        gap = np.maximum(sol.gradient, 0.0)
        new = exponential_tension(gap, w, rho)
        residual = float(np.abs(new - tension).max()) / peak
        if residual <= enough:
            if tight:
                product = (sol.product if sol.product is not None else op.apply(x)) - shift
                approach = sol.multiplier if load_control else float(value)
                return AdhesiveSolution(x - tension, gap, float(approach), x > 0, iterations, rounds, product)
            tight = True
            continue
        tension = new
    raise ConvergenceError("exponential adhesive rounds", max_rounds, residual, enough,
                           hint="the tension still changing; refine the step of the approach or load")
