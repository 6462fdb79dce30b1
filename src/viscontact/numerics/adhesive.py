"""The adhesive normal contact problem of a cell-by-cell Maugis-Dugdale law, solved by a sequence of
convex Polonsky-Keer problems that never increases the energy.

The law (Maugis 1992, on each cell): a tension sigma_0 [Pa] acts wherever the gap g is open but below
the range h_0 = w / sigma_0 [m]; beyond it nothing acts; the gap never closes below zero. With the
elastic operator K (p -> u_z) and the known gap h_k [m] (the undeformed gap plus the displacement of
the history, before the approach delta), g = K p + h_k - delta, the state minimises the energy

    Pi(p) = 1/2 p.K p + sum_cells phi(g) dA [- W delta under load control],
    phi(g) = min(sigma_0 g - w, 0) for g >= 0 (+inf for g < 0),

which is not convex (phi is concave beyond the kink at h_0): the problem has several solutions, jumps
in and off, and no plain bound-constrained method converges to it. The method here (a
majorise-minimise iteration; the fixed-point form of Rey, Anciaux & Molinari 2017, Comput. Mech. 60,
69, on the interaction zone) replaces phi on each cell by the convex function that touches it at the
current gap: sigma_0 g - w on the interaction zone I = {g < h_0} (tension allowed: p >= -sigma_0),
0 elsewhere (p >= 0). Each subproblem is Polonsky & Keer's (:func:`~viscontact.numerics.constrained.constrained_cg`
on x = p + sigma_0 1_I >= 0, load control included); then I is updated from the new gap. Both
majorants lie above phi and equal it at the current gap, so the energy of the iterates never
increases and the zone can never come back to a set it left: the iteration ends, at a state that
satisfies the law on every cell (up to the solve's tolerance). A step of the approach or of the load
beyond the last equilibrium makes the zone move by a ring of cells a round: the jump in, or, under
load control, the pull-off, where the required tension exceeds what the zone can carry
(:class:`NoEquilibriumError`).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Literal

import numpy as np

from viscontact.errors import ConvergenceError, ViscontactError
from viscontact.numerics.constrained import constrained_cg

Operator = Callable[[np.ndarray], np.ndarray]
#: a cell joins the interaction zone when its gap is below (1 - this) h_0 and leaves it above
#: (1 + this) h_0: the solves' round-off cannot toggle a cell at the edge of the range from round to round
RANGE_HYSTERESIS = 1e-9


class NoEquilibriumError(ViscontactError):
    """No adhesive equilibrium carries the load: the body lets go of the indenter (the pull-off under
    load control). ``load`` [N] is the load asked for, ``capacity`` [N] the most tension the last
    interaction zone could carry."""

    def __init__(self, load: float, capacity: float) -> None:
        super().__init__(f"no adhesive equilibrium carries the load {load:.6g} N (the interaction zone carries at "
                         f"most {capacity:.6g} N): the indenter comes off")
        self.load, self.capacity = load, capacity


@dataclass(frozen=True)
class AdhesiveSolution:
    """Result of :func:`adhesive_contact`.

    Attributes
    ----------
    pressure
        p [Pa] (negative where tension acts, >= -sigma_0).
    gap
        g [m] >= 0 (0 in contact).
    approach
        delta [m]: given under displacement control, found under load control.
    interaction
        The cells where the gap is below the range (bool): contact and cohesive zone.
    iterations
        Conjugate-gradient iterations, summed over the rounds.
    rounds
        Convex subproblems solved.
    """

    pressure: np.ndarray
    gap: np.ndarray
    approach: float
    interaction: np.ndarray
    iterations: int
    rounds: int


def adhesive_contact(apply_k: Operator, known_gap: np.ndarray, *, control: Literal["load", "displacement"],
                     value: float, cohesive_stress: float, work_of_adhesion: float, cell_area: float,
                     initial: np.ndarray | None = None, interaction: np.ndarray | None = None,
                     tolerance: float = 1e-10, max_iterations: int = 2000, max_rounds: int = 500,
                     preconditioner: Operator | None = None) -> AdhesiveSolution:
    """Solve the adhesive normal problem of the module docstring.

    Parameters
    ----------
    apply_k
        p [Pa] -> K p [m], symmetric positive definite (the step's instantaneous compliance).
    known_gap
        h_k [m]: the undeformed gap plus the known displacement, before the approach.
    control, value
        ``"displacement"``: the approach delta [m]; ``"load"``: the load W [N] (negative: a pull).
    cohesive_stress, work_of_adhesion
        sigma_0 [Pa] and w [J/m^2] (the range is h_0 = w / sigma_0).
    cell_area
        dA [m^2].
    initial, interaction
        A warm start: the last pressure [Pa] and interaction zone; None: from the rigid gap (the
        zone where h_k - delta < h_0 under displacement control, none under load control).
    tolerance, max_iterations
        Of each Polonsky-Keer solve.
    max_rounds
        Subproblems at most before :class:`~viscontact.errors.ConvergenceError`.
    preconditioner
        r -> approximate K^-1 r.

    Raises
    ------
    NoEquilibriumError
        Under load control, when no zone carries the load (the pull-off).
    ConvergenceError
        When the zone still moves after ``max_rounds`` subproblems, or a solve does not converge.
    """
    sigma, h0 = float(cohesive_stress), float(work_of_adhesion) / float(cohesive_stress)
    load_control = control == "load"
    if interaction is None:
        interaction = (known_gap - value < h0) if not load_control else np.zeros(known_gap.shape, dtype=bool)
    zone = np.asarray(interaction, dtype=bool)
    p = np.zeros_like(known_gap) if initial is None else np.asarray(initial, dtype=float)
    total_iterations = 0
    for rounds in range(1, max_rounds + 1):
        tension = np.where(zone, sigma, 0.0)
        shift = apply_k(tension)  # K sigma_0 1_I
        x0 = np.maximum(p + tension, 0.0)
        if load_control:
            capacity = sigma * cell_area * float(np.count_nonzero(zone))
            if value + capacity <= 0.0:
                raise NoEquilibriumError(value, -capacity)
            sol = constrained_cg(apply_k, shift - known_gap, x0, 0.0, np.inf, total=value + capacity,
                                 cell_area=cell_area, tolerance=tolerance, max_iterations=max_iterations,
                                 what="adhesive contact (load control)", preconditioner=preconditioner)
            approach = sol.multiplier
        else:
            sol = constrained_cg(apply_k, shift + value - known_gap, x0, 0.0, np.inf, tolerance=tolerance,
                                 max_iterations=max_iterations, what="adhesive contact (displacement control)",
                                 preconditioner=preconditioner)
            approach = float(value)
        total_iterations += sol.iterations
        p, gap = sol.x - tension, np.maximum(sol.gradient, 0.0)
        joins = ~zone & (gap < (1.0 - RANGE_HYSTERESIS) * h0)
        leaves = zone & (gap > (1.0 + RANGE_HYSTERESIS) * h0)
        if not (joins.any() or leaves.any()):
            return AdhesiveSolution(p, gap, approach, zone, total_iterations, rounds)
        zone = (zone | joins) & ~leaves
    raise ConvergenceError("adhesive interaction zone", max_rounds, float(np.count_nonzero(joins | leaves)), 0.0,
                           hint="cells still joining or leaving the zone; refine the step of the approach or load")
