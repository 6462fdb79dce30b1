"""The adhesive normal contact law of a transient step: a cell-by-cell Maugis-Dugdale surface
(``[adhesion]``, :mod:`viscontact.problem.adhesion`).

Each step of the transient is an elastic problem with the instantaneous compliance J_inst and the
known hereditary displacement (seed Eq. 5); with adhesion that problem is the adhesive one of
:func:`viscontact.numerics.adhesive.adhesive_contact` (a tension sigma_0 wherever 0 < gap < w /
sigma_0; solved as a majorise-minimise sequence of Polonsky-Keer problems, Rey, Anciaux & Molinari
2017), with the step's operator K = J_inst K_zz and the known gap h_k = h_0(x, y) + u_z^history;
with the exponential law, :func:`viscontact.numerics.adhesive_exponential.exponential_contact`. Which
function solves a step, and how the contact and adhesive cells are measured, is one
:class:`AdhesiveSolver` per law, registered by the law's name in :data:`ADHESIVE_SOLVERS`.
Nothing else of the stepper changes: the pressure (now signed) enters the hereditary history as any
other. The step is warm-started with the last step's pressure and interaction zone (carried in
:class:`~viscontact.solvers.transient.State`), which makes the zone move by a ring of cells a round
at a jump-in, a jump-off or a pull-off. Under load control a step whose load no zone can carry
raises :class:`~viscontact.numerics.adhesive.NoEquilibriumError` (the pull-off: the run ends there,
:func:`viscontact.solvers.transient.steps`).

Friction (gross sliding, and the bound of partial slip; frictionless sliding and indentation: mu_f =
0): Coulomb's law on the compressive part of the normal traction, q_x = mu_f max(p, 0) in gross
sliding, |q_x| <= mu_f max(p, 0) in partial slip (:class:`AdhesivePartialSlip`). Where
the interface is in tension (the cohesive zone, and the tensile rim of the contact) it carries no
friction: the Coulomb bound mu_f p has no meaning for p < 0, and the interface's own shear strength
in tension is not modelled; sliding with adhesion then rubs with mu_f times the compressive load, the
rest of the resistance being the viscoelastic hysteresis of the adhesive contact (Carbone, Mandriota &
Menga 2022, Extreme Mech. Lett. 56, 101877, "Theory of viscoelastic adhesion and friction", whose
sliding interface carries no shear: the friction is the hysteresis alone, enhanced by adhesion;
``tangential.mode = "frictionless_sliding"`` here). Registered as
:data:`~viscontact.solvers.contact_laws.ADHESIVE_LAW` and
:data:`~viscontact.solvers.contact_laws.ADHESIVE_PARTIAL_SLIP_LAW`.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from viscontact.numerics.adhesive import AdhesiveSolution, adhesive_contact
from viscontact.numerics.adhesive_exponential import exponential_contact
from viscontact.problem.adhesion import AdhesionSettings, Exponential, MaugisDugdale
from viscontact.solvers.contact_laws import (
    ADHESIVE_LAW,
    ADHESIVE_PARTIAL_SLIP_LAW,
    ContactLaw,
    PartialSlip,
    StepContext,
    StepSolution,
    register_contact_law,
)

#: the adhesive area of the exponential law: the open cells whose tension exceeds this fraction of the
#: peak w / rho (the gap below rho ln 100 = 4.6 rho)
EXPONENTIAL_AREA_FRACTION = 0.01


@dataclass(frozen=True)
class AdhesiveSolver:
    """The solver side of one traction-separation law (:data:`ADHESIVE_SOLVERS`).

    Attributes
    ----------
    solve
        ``solve(operator, known_gap, adhesion, initial_product, **common)``: the step's adhesive problem
        with the operator [m/Pa] and the known gap [m] (the iterate's product [m] where known; the
        numerics' common arguments ``common``), an :class:`~viscontact.numerics.adhesive.AdhesiveSolution`.
    cells
        ``cells(adhesion, pressure, interaction)``: (the cells in contact, gap 0; the cells of the
        adhesive area) of a solution with the pressure [Pa] and the solver's ``interaction``.
    """

    solve: Callable[..., AdhesiveSolution]
    cells: Callable[[AdhesionSettings, np.ndarray, np.ndarray | None], tuple[np.ndarray, np.ndarray]]


def _maugis_dugdale_solve(op, known, adhesion: AdhesionSettings, product, **common) -> AdhesiveSolution:
    """:func:`~viscontact.numerics.adhesive.adhesive_contact` with sigma_0 [Pa], warm-started with the product."""
    return adhesive_contact(op, known, cohesive_stress=adhesion.cohesive_stress, initial_product=product, **common)


def _maugis_dugdale_cells(adhesion: AdhesionSettings, pressure: np.ndarray, interaction: np.ndarray | None
                          ) -> tuple[np.ndarray, np.ndarray]:
    """The contact of :func:`contact_cells`, the cohesive zone (the rest of the interaction zone: gap
    open, p = -sigma_0)."""
    contact = contact_cells(pressure, interaction, adhesion.cohesive_stress)
    return contact, (np.zeros_like(contact) if interaction is None else interaction & ~contact)


def _exponential_solve(op, known, adhesion: AdhesionSettings, product, **common) -> AdhesiveSolution:
    """:func:`~viscontact.numerics.adhesive_exponential.exponential_contact` with rho [m] (no product)."""
    return exponential_contact(op, known, decay_length=adhesion.decay_length, **common)


def _exponential_cells(adhesion: AdhesionSettings, pressure: np.ndarray, interaction: np.ndarray | None
                       ) -> tuple[np.ndarray, np.ndarray]:
    """The contact (the solver's ``interaction``), the open cells whose tension exceeds
    :data:`EXPONENTIAL_AREA_FRACTION` of the peak w / rho."""
    contact = pressure > 0 if interaction is None else interaction
    return contact, ~contact & (pressure < -EXPONENTIAL_AREA_FRACTION * adhesion.peak_stress)


#: the solver of each traction-separation law, by the law's name
#: (:data:`~viscontact.problem.adhesion.ADHESION_LAWS`)
ADHESIVE_SOLVERS: dict[str, AdhesiveSolver] = {
    MaugisDugdale.name: AdhesiveSolver(_maugis_dugdale_solve, _maugis_dugdale_cells),
    Exponential.name: AdhesiveSolver(_exponential_solve, _exponential_cells),
}


def adhesive_cells(adhesion: AdhesionSettings, pressure: np.ndarray, interaction: np.ndarray | None
                   ) -> tuple[np.ndarray, np.ndarray]:
    """(the cells in contact, gap 0; the cells of the adhesive area) of a solution of the law of
    ``adhesion`` with the pressure [Pa] and the solver's ``interaction``: its solver's
    :attr:`AdhesiveSolver.cells` (:data:`ADHESIVE_SOLVERS`)."""
    return ADHESIVE_SOLVERS[adhesion.law].cells(adhesion, pressure, interaction)


def contact_cells(pressure: np.ndarray, interaction: np.ndarray | None, cohesive_stress: float) -> np.ndarray:
    """The cells in contact (gap 0) of an adhesive solution: compressed, or pulled by less than
    sigma_0 [Pa] on the interaction zone (where the cohesive zone is at p = -sigma_0 exactly, its
    bound); outside the zone, p > 0. Without a zone: p > 0."""
    if interaction is None:
        return pressure > 0
    return np.where(interaction, pressure > -cohesive_stress, pressure > 0)


def solve_adhesive_normal(ctx: StepContext, known_uz: np.ndarray, pressure: np.ndarray, product: np.ndarray | None
                          ) -> tuple[np.ndarray, float, int, np.ndarray, np.ndarray, np.ndarray]:
    """The step's adhesive normal problem (module docstring) with the known displacement ``known_uz``
    [m], from the iterate ``pressure`` [Pa] (its ``product``, the step's operator applied to it [m],
    where known) and the last step's zone: (p [Pa], delta_z [m], iterations, u_z [m], the operator
    applied to p [m], the interaction zone). Under load control, a step before the first positive
    load with no interaction zone yet (the indenter not pressed on yet) holds the indenter just
    touching, without traction."""
    problem, settings = ctx.problem, ctx.problem.solver
    adhesion = problem.adhesion
    known = ctx.gap + known_uz
    zone = ctx.interaction
    control = problem.normal.control
    if control == "load" and ctx.value <= 0 and (zone is None or not zone.any()):
        p = np.zeros_like(known)
        return p, float(known.min()), 0, known_uz.copy(), np.zeros_like(p), np.zeros_like(p, dtype=bool)
    op = ctx.compliance.elastic_operator("z", ctx.first)
    common = {"control": control, "value": ctx.value, "work_of_adhesion": adhesion.work_of_adhesion,
              "cell_area": problem.grid.cell_area, "initial": pressure, "interaction": zone,
              "tolerance": settings.tolerance, "max_iterations": settings.max_iterations,
              "mixed_precision": settings.mixed_precision}
    sol = ADHESIVE_SOLVERS[adhesion.law].solve(op, known, adhesion, product, **common)
    return sol.pressure, float(sol.approach), sol.iterations, sol.product + known_uz, sol.product, sol.interaction


@register_contact_law
@dataclass(frozen=True)
class AdhesiveNormal(ContactLaw):
    """Adhesive indentation and sliding: the normal problem of a Maugis-Dugdale surface (module
    docstring), q_x = mu_f max(p, 0) (gross sliding; 0 otherwise); with the normal-tangential coupling
    (IC_zx ~ (1 - 2 nu)) its displacement J_inst K_zx q_x enters the known one, iterated as a fixed
    point by :func:`~viscontact.solvers.coupling.solve_coupled` (as
    :class:`~viscontact.solvers.contact_laws.NormalContact` does)."""

    name: ClassVar[str] = ADHESIVE_LAW

    def solve(self, ctx: StepContext, pressure: np.ndarray, shear: np.ndarray,
              product: np.ndarray | None) -> StepSolution:
        known_uz = ctx.known_uz
        if self.coupled:
            known_uz = known_uz + ctx.compliance.cross_displacement("z", "x", np.maximum(pressure, 0.0), ctx.first,
                                                                    self.friction)
        p, delta_z, iterations, u_z, product, zone = solve_adhesive_normal(ctx, known_uz, pressure, product)
        shear_x = self.friction * np.maximum(p, 0.0) if self.friction else np.zeros_like(p)
        return StepSolution(p, shear_x, delta_z, u_z, iterations, pressure_product=product, interaction=zone)


@register_contact_law
@dataclass(frozen=True)
class AdhesivePartialSlip(PartialSlip):
    """Partial slip with adhesion: :class:`~viscontact.solvers.contact_laws.PartialSlip` (the bounded
    tangential problem alternated with the normal one) with the adhesive normal problem and the
    friction bound on the compressive part, |q_x| <= mu_f max(p, 0): the cells in tension (the
    cohesive zone, the tensile rim of the contact) carry no shear and slip (module docstring)."""

    name: ClassVar[str] = ADHESIVE_PARTIAL_SLIP_LAW

    def normal(self, ctx, known_uz, pressure, product):
        return solve_adhesive_normal(ctx, known_uz, pressure, product)

    def bound(self, pressure):
        return self.friction * np.maximum(pressure, 0.0)
