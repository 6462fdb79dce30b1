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
(:class:`NoEquilibriumError`). Every cell whose gap falls in the range joins at once; the ring a round
is the iteration's own pace (the tension of the cells that joined pulls their neighbours into the
range), so the rounds a step needs grow with the cells the zone's edge travels: the default limit
(:data:`MIN_ROUNDS`, :data:`ROUNDS_PER_CELL_ACROSS` times the cells across the grid) covers a zone
that crosses the whole grid, on a fine grid as on a coarse one.

Cost. A step's rounds run on a box around the zone (and the start's support), with a margin
(:data:`ZONE_MARGIN_CELLS`, :data:`ZONE_MARGIN_FRACTION`): the operator cropped to the box (translation
invariance, as :mod:`~viscontact.numerics.support_window`); one product on the whole grid then gives the
gap outside it, and cells that join out there enlarge the box (:data:`MAX_ENLARGEMENTS`, then the whole
grid). Each subproblem is solved on the contact's box inside it
(:func:`~viscontact.numerics.support_window.windowed_cg`: x vanishes on the cohesive zone and outside
the zone, so its support is the contact, and the box's check gives the gap on the zone's box), with
single-precision search directions where the operator has them. Products are carried from round to
round: K x of the last solve starts the next (a cell that joins keeps x = 0, p = -sigma_0), K sigma_0 1_I
changes by sigma_0 K 1 on the cells that joined or left (direct sums while they are few,
:data:`SPARSE_LIMIT`), and the caller may give K p of the warm start (the last step's). The rounds whose
zone still moves are solved to :data:`LOOSE_TOLERANCE` and move only the cells whose gap is off the
range by more than :data:`LOOSE_HYSTERESIS`; the zone is accepted only after a round at the full
tolerance that moves nothing (the fixed point of the exact rounds: measured, the loads along the
shipped retraction at 128^2 and 256^2 equal those of exact rounds to 5e-10 of the peak, with the same
cells in contact and in the cohesive zone at every step).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any, ClassVar, Literal

import numpy as np

from viscontact.errors import ConvergenceError, ViscontactError
from viscontact.numerics.grid import mask_span
from viscontact.numerics.support_window import windowed_cg

Operator = Callable[[np.ndarray], np.ndarray]
#: a cell joins the interaction zone when its gap is below (1 - this) h_0 and leaves it above
#: (1 + this) h_0: the solves' round-off cannot toggle a cell at the edge of the range from round to round
RANGE_HYSTERESIS = 1e-9
#: cells joining or leaving the zone in a round whose product is taken by direct sums (more: one full
#: product; a direct sum over the grid per cell costs about a 48th of a product, as for
#: :func:`~viscontact.numerics.constrained.constrained_cg`'s bound corrections)
SPARSE_LIMIT = 48
#: relative tolerance of the rounds whose zone still moves (the last round: the solve's own)
LOOSE_TOLERANCE = 1e-3
#: the hysteresis of a loose round: a cell whose gap is that close to h_0 waits for a tight round
LOOSE_HYSTERESIS = 1e-4
#: rounds after which every round is tight
LOOSE_ROUNDS = 50
#: the default limit of rounds at least
MIN_ROUNDS = 500
#: the default limit of rounds per cell across the grid (the zone's edge moves by a cell or more each
#: round, both edges of a line's zone at once, and may cross the grid: joining, then leaving)
ROUNDS_PER_CELL_ACROSS = 2
#: margin [cells] at least around the zone's box (the zone moves by a few cells a step)
ZONE_MARGIN_CELLS = 4
#: margin as a fraction of the zone's extent
ZONE_MARGIN_FRACTION = 0.05
#: a zone's box above this fraction of the grid's side is not worth it: the rounds run on the grid
ZONE_FULL_FRACTION = 0.9
#: enlargements of the zone's box (cells outside it joined) before the rounds run on the whole grid
MAX_ENLARGEMENTS = 3


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
    product
        K p [m], from the last round's full-domain products (double precision).
    """

    pressure: np.ndarray
    gap: np.ndarray
    approach: float
    interaction: np.ndarray
    iterations: int
    rounds: int
    product: np.ndarray | None = None


@dataclass(frozen=True)
class FullDomain:
    """A plain action p -> K p as the operator :func:`windowed_cg` takes: no window, no single
    precision, no direct sums."""

    apply: Operator
    preconditioner: Operator | None = None
    window: None = None
    #: its "direct sums" are the action itself
    sparse_limit: ClassVar[int] = 0
    #: its solves decide on the host (:func:`~viscontact.numerics.constrained.constrained_cg`)
    check_every: ClassVar[int] = 1

    def apply_sparse(self, field: np.ndarray) -> np.ndarray:
        return self.apply(field)

    def cg_options(self, mixed_precision: bool = True) -> dict[str, Operator | None]:
        return {"preconditioner": self.preconditioner}


def adhesive_contact(operator: Any, known_gap: np.ndarray, *, control: Literal["load", "displacement"],
                     value: float, cohesive_stress: float, work_of_adhesion: float, cell_area: float,
                     initial: np.ndarray | None = None, interaction: np.ndarray | None = None,
                     initial_product: np.ndarray | None = None, tolerance: float = 1e-10,
                     max_iterations: int = 2000, max_rounds: int | None = None,
                     preconditioner: Operator | None = None, mixed_precision: bool = True) -> AdhesiveSolution:
    """Solve the adhesive normal problem of the module docstring.

    Parameters
    ----------
    operator
        K, symmetric positive definite (the step's instantaneous compliance): an
        :class:`~viscontact.bodies.compliance.ElasticOperator` (its windows, single-precision
        products and direct sums are used), or a plain action p [Pa] -> K p [m] (full-domain solves).
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
    initial_product
        K ``initial`` [m] in double precision where the caller knows it (spares a product).
    tolerance, max_iterations
        Of each Polonsky-Keer solve.
    max_rounds
        Subproblems at most before :class:`~viscontact.errors.ConvergenceError`; None: the larger of
        :data:`MIN_ROUNDS` and :data:`ROUNDS_PER_CELL_ACROSS` times the cells across the grid.
    preconditioner
        r -> approximate K^-1 r, for a plain action (an operator brings its own).
    mixed_precision
        Single-precision search directions where the operator has them
        (:meth:`~viscontact.bodies.compliance.ElasticOperator.cg_options`).

    Raises
    ------
    NoEquilibriumError
        Under load control, when no zone carries the load (the pull-off).
    ConvergenceError
        When the zone still moves after ``max_rounds`` subproblems, or a solve does not converge.
    """
    op = operator if hasattr(operator, "apply") else FullDomain(operator, preconditioner)
    h0 = float(work_of_adhesion) / float(cohesive_stress)
    if interaction is None:
        interaction = (known_gap - value < h0) if control != "load" else np.zeros(known_gap.shape, dtype=bool)
    zone = interaction.astype(bool, copy=False)
    if max_rounds is None:
        max_rounds = max(MIN_ROUNDS, ROUNDS_PER_CELL_ACROSS * max(known_gap.shape))
    pressure = np.zeros_like(known_gap) if initial is None else initial.astype(float, copy=False)
    product = None if initial is None else initial_product
    settings = _Rounds(control, float(value), float(cohesive_stress), h0, cell_area, tolerance, max_iterations,
                       max_rounds, mixed_precision)
    if control != "load" and not zone.any() and not pressure.any():
        gap = known_gap - value  # out of the range everywhere: nothing acts
        if not (gap < (1.0 - RANGE_HYSTERESIS) * h0).any():
            return AdhesiveSolution(pressure, gap, float(value), zone, 0, 0, np.zeros_like(pressure))
    iterations = rounds = 0
    for _ in range(MAX_ENLARGEMENTS + 1):
        box = _zone_box(zone | (pressure != 0), op)
        if box is None:
            break
        m, cells = box
        sol = settings.solve(_Boxed(op.window(m), op), known_gap[cells], zone[cells], pressure[cells],
                             None if product is None else product[cells], rounds)
        iterations, rounds = iterations + sol.iterations, sol.rounds
        # the zone's box solved: one product on the whole grid gives the gap outside it
        pressure = np.zeros_like(known_gap)
        pressure[cells] = sol.pressure
        product = op.apply(pressure)
        gap = product + known_gap - sol.approach
        zone = np.zeros_like(zone)
        zone[cells] = sol.interaction
        joins = ~zone & (gap < (1.0 - RANGE_HYSTERESIS) * h0)  # (outside the box: inside, none)
        if not joins.any():
            return AdhesiveSolution(pressure, np.maximum(gap, 0.0), sol.approach, zone, iterations, rounds, product)
        zone |= joins  # the next box covers them
    sol = settings.solve(op, known_gap, zone, pressure, product, rounds)
    return replace(sol, iterations=iterations + sol.iterations)


@dataclass(frozen=True)
class _Rounds:
    """The majorise-minimise rounds of :func:`adhesive_contact` on one box (its parameters)."""

    control: str
    value: float
    sigma: float
    h0: float
    cell_area: float
    tolerance: float
    max_iterations: int
    max_rounds: int
    mixed_precision: bool

    def solve(self, op: Any, known_gap: np.ndarray, zone: np.ndarray, pressure: np.ndarray,
              product: np.ndarray | None, rounds_before: int) -> AdhesiveSolution:
        """The rounds from the start (``pressure`` [Pa], its ``product`` K p [m] or None, ``zone``),
        on the grid of ``op`` (a box, or the whole grid), counting on from ``rounds_before``."""
        sigma, h0, load_control = self.sigma, self.h0, self.control == "load"
        tension = np.where(zone, sigma, 0.0)
        shift = op.apply(tension)  # K sigma_0 1_I, carried from round to round
        start = pressure + tension
        x0 = np.maximum(start, 0.0)
        # a start off the bound (a tension above sigma_0, or outside the zone): its product corrected
        kx0 = None if product is None else product + shift + _product(op, x0 - start)
        total_iterations, tight = 0, False
        for rounds in range(rounds_before + 1, self.max_rounds + 1):
            # a round whose zone may still move is solved to a loose tolerance, the last one to the full one
            tolerance = self.tolerance if tight else max(self.tolerance, LOOSE_TOLERANCE)
            total = None
            if load_control:
                capacity = sigma * self.cell_area * float(np.count_nonzero(zone))
                if self.value + capacity <= 0.0:
                    raise NoEquilibriumError(self.value, -capacity)
                total, b = self.value + capacity, shift - known_gap
            else:
                b = shift + self.value - known_gap
            sol = windowed_cg(op, b, x0, total=total, cell_area=self.cell_area, tolerance=tolerance,
                              max_iterations=self.max_iterations, what=f"adhesive contact ({self.control} control)",
                              mixed_precision=self.mixed_precision, start_product=kx0)
            x0 = sol.x
            kx0 = sol.product if sol.product is not None else op.apply(x0)
            approach = sol.multiplier if load_control else self.value
            total_iterations += sol.iterations
            gap = np.maximum(sol.gradient, 0.0)
            joins, leaves = _moved(zone, gap, h0, RANGE_HYSTERESIS if tight else LOOSE_HYSTERESIS)
            if not (joins.any() or leaves.any()):
                if tight:
                    return AdhesiveSolution(x0 - tension, gap, approach, zone, total_iterations, rounds, kx0 - shift)
                tight = True
                continue
            tight = rounds - rounds_before >= LOOSE_ROUNDS
            zone = (zone | joins) & ~leaves
            # the next round starts from x: a cell that joins (its gap open) starts in the cohesive zone
            # (x = 0, p = -sigma_0), one that leaves (x = 0) without traction
            shift += _product(op, np.where(joins, sigma, 0.0) - np.where(leaves, sigma, 0.0))
            tension = np.where(zone, sigma, 0.0)
        raise ConvergenceError("adhesive interaction zone", self.max_rounds, float(np.count_nonzero(joins | leaves)),
                               0.0, hint="cells still joining or leaving the zone; refine the step of the approach or load")


@dataclass(frozen=True)
class _Boxed:
    """The operator on the zone's m x m box (``box``: the full grid's ``window(m)``) as
    :func:`windowed_cg` takes it: its own windows, the contact's boxes inside this one, are the full
    grid's (translation invariance)."""

    box: Any
    full: Any

    @property
    def apply(self) -> Operator:
        return self.box.apply

    @property
    def apply_sparse(self) -> Operator:
        return self.box.apply_sparse

    @property
    def sparse_limit(self) -> int:
        return self.box.sparse_limit

    @property
    def check_every(self) -> int:
        return self.box.check_every

    @property
    def window(self) -> Callable[[int], Any]:
        return self.full.window

    @property
    def fast_length(self) -> Callable[[int], int]:
        return self.full.fast_length

    def cg_options(self, mixed_precision: bool = True) -> dict[str, Operator | None]:
        return self.box.cg_options(mixed_precision)


def _zone_box(cover: np.ndarray, op: Any) -> tuple[int, tuple[slice, slice]] | None:
    """(m, the m x m box) holding the True cells of ``cover`` (the zone and the start's support) with
    a margin of :data:`ZONE_MARGIN_CELLS` cells or :data:`ZONE_MARGIN_FRACTION` of its extent, 2m a
    fast transform length of the operator's backend; None where the operator has no windows, the
    zone is empty or the box would not be worth it (above :data:`ZONE_FULL_FRACTION` of the side)."""
    if getattr(op, "window", None) is None or not cover.any():
        return None
    n = cover.shape[0]
    rows, cols = mask_span(cover, 0), mask_span(cover, 1)
    extent = max(rows[1] - rows[0], cols[1] - cols[0])
    m = extent + 2 * max(ZONE_MARGIN_CELLS, math.ceil(ZONE_MARGIN_FRACTION * extent))
    while op.fast_length(2 * m) != 2 * m:
        m = (op.fast_length(2 * m) + 1) // 2
    if m > ZONE_FULL_FRACTION * n:
        return None
    r0 = min(max((rows[0] + rows[1] - m) // 2, 0), n - m)
    c0 = min(max((cols[0] + cols[1] - m) // 2, 0), n - m)
    return m, (slice(r0, r0 + m), slice(c0, c0 + m))


def _product(op: Any, field: np.ndarray) -> np.ndarray:
    """K ``field`` [m] in double precision: by direct sums for at most :data:`SPARSE_LIMIT` non-zeros
    and the operator's own ``sparse_limit`` (fewer on a periodic grid)."""
    points = int(np.count_nonzero(field))
    if not points:
        return np.zeros_like(field)
    limit = min(SPARSE_LIMIT, op.sparse_limit)
    return op.apply_sparse(field) if points <= limit else op.apply(field)


def _moved(zone: np.ndarray, gap: np.ndarray, h0: float, band: float) -> tuple[np.ndarray, np.ndarray]:
    """(the cells that join the zone, those that leave it) at ``gap`` [m], range ``h0`` [m]: below
    (1 - band) h0, above (1 + band) h0."""
    return ~zone & (gap < (1.0 - band) * h0), zone & (gap > (1.0 + band) * h0)


#: relative change of the normal-tangential cross displacement [of its largest value] below which the
#: rounds of :func:`adhesive_active_set` count it settled
CROSS_TOLERANCE = 1e-9


def adhesive_active_set(apply_k: Operator, known_gap: np.ndarray, *, control: Literal["load", "displacement"],
                        value: float, cohesive_stress: float, work_of_adhesion: float, cell_area: float,
                        initial: np.ndarray | None = None, cross: Operator | None = None,
                        tolerance: float = 1e-10, max_iterations: int = 2000, max_rounds: int = 200,
                        preconditioner: Operator | None = None, what: str = "steady adhesive contact"
                        ) -> AdhesiveSolution:
    """The Maugis-Dugdale problem of the module docstring with a non-symmetric operator K (the
    effective steady kernel of sliding, :mod:`viscontact.solvers.steady`): three sets, the contact
    (gap 0, p >= -sigma_0 unknown), the cohesive zone (0 < gap < h_0 = w / sigma_0, p = -sigma_0)
    and the free surface (p = 0).

    With the interaction zone I (contact and cohesive zone) fixed, x = p + sigma_0 1_I is the
    solution of a plain contact problem, x >= 0, K x + (h_k - sigma_0 K 1_I) - delta >= 0,
    complementarity (under load control sum x dA = W + sigma_0 |I|), solved by the primal-dual
    active set with GMRES of :func:`viscontact.numerics.active_set.solve_contact_active_set`; then
    the cells whose gap fell below h_0 join I and those whose gap rose above it leave, and the next
    round starts from x, until the zone stays (a fixed point; a non-symmetric K has no energy to
    decrease, so no monotone majorise-minimise: a zone still moving after ``max_rounds`` raises
    :class:`~viscontact.errors.ConvergenceError`).

    ``cross``: p [Pa] -> the displacement [m] of the tangential traction that p carries (gross
    sliding, q_x = mu_f max(p, 0): mu_f K_zx max(p, 0)), added to the known gap from the last
    round's p, the rounds going on until it changes by less than :data:`CROSS_TOLERANCE` of its
    largest value. ``initial``: a pressure [Pa] to start from (its non-zero cells the first zone);
    None: the zone where the rigid gap h_k - delta (under load control, h_k - min h_k) is below h_0.
    ``what`` names the problem in a :class:`~viscontact.errors.ConvergenceError`.

    Raises
    ------
    NoEquilibriumError
        Under load control, when the zone cannot carry the load (sigma_0 |I| < -W).
    """
    from viscontact.numerics.active_set import solve_contact_active_set

    sigma = float(cohesive_stress)
    h0 = float(work_of_adhesion) / sigma
    if initial is not None and np.any(initial != 0):
        zone = initial != 0
        x = np.maximum(initial + np.where(zone, sigma, 0.0), 0.0)
    else:
        zone = known_gap - (known_gap.min() if control == "load" else value) < h0
        x = np.zeros_like(known_gap)
    moved = np.zeros_like(zone)
    displaced = np.zeros_like(known_gap)
    krylov = 0
    for rounds in range(1, max_rounds + 1):
        tension = np.where(zone, sigma, 0.0)
        shift = apply_k(tension)
        shifted = known_gap - shift + displaced
        total = value
        if control == "load":
            capacity = sigma * cell_area * float(np.count_nonzero(zone))
            if value + capacity <= 0.0:
                raise NoEquilibriumError(value, -capacity)
            total = value + capacity
        x, approach, iterations, _ = solve_contact_active_set(
            apply_k, shifted, control=control, value=total, cell_area=cell_area,
            initial=x if np.any(x > 0) else None, tolerance=tolerance, max_iterations=max_iterations,
            preconditioner=preconditioner, what=what)
        krylov += iterations
        product = apply_k(x)
        gap = np.maximum(product + shifted - approach, 0.0)
        pressure = x - tension
        settled = True
        if cross is not None:
            new = cross(pressure)
            settled = float(np.abs(new - displaced).max()) <= CROSS_TOLERANCE * max(float(np.abs(new).max()), 1e-300)
            displaced = new
        joins, leaves = _moved(zone, gap, h0, RANGE_HYSTERESIS)
        moved = joins | leaves
        if settled and not moved.any():
            return AdhesiveSolution(pressure, gap, float(approach), zone, krylov, rounds, product - shift)
        zone = (zone | joins) & ~leaves
    raise ConvergenceError(f"{what} interaction zone", max_rounds, float(np.count_nonzero(moved)), 0.0,
                           hint="cells still joining or leaving the zone (or the normal-tangential coupling "
                                "still changing)")
