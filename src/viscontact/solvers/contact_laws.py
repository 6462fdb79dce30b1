"""Contact laws: what one time step of the transient solves at the surface, registered by name.

Each step of the transient (:func:`viscontact.solvers.transient.step`) is an elastic contact problem
with the instantaneous compliance J_inst plus the known hereditary displacement (seed Eq. 5). A
*contact law* says which tractions are unknown and what binds them:

* ``"normal_contact"`` (:class:`NormalContact`): p >= 0, gap >= 0, complementarity (seed Eqs. 7-8,
  10), solved by the Polonsky & Keer (1999) constrained conjugate gradient
  (:mod:`viscontact.numerics.constrained`), with q_x = mu_f p (gross sliding, seed Eq. 12; mu_f = 0
  for indentation and frictionless sliding);
* ``"partial_slip"`` (:class:`PartialSlip`): the normal problem alternated with the tangential one,
  q_x in [-mu_f p, mu_f p] with stick where the slip vanishes (seed Eqs. 9, 11; the bounded
  Polonsky & Keer CG).
* ``"rolling"`` (:class:`viscontact.solvers.rolling.Rolling`): partial slip in the rolling frame,
  the slip being the creepage plus the convected rate of u_x (Kalker 1990).

How a law is chosen from the problem (the one place: change it here, nowhere else): the tangential
mode gives the first phase (:func:`first_phase`), the phase gives the law's name
(:data:`PHASE_LAWS`, :func:`law_name`), the name gives the class (:func:`get_contact_law`) and the
class builds the step's law from the problem and the compliance (:meth:`ContactLaw.for_problem`;
:func:`contact_law` does all of it). Phases change in the stepper (partial slip turns into gross
sliding when the stick zone of a contact vanishes).

A new law (e.g. an adhesive normal law allowing tension, or a rolling law whose rigid slip comes
from the creepage) is one class and its registration::

    @register_contact_law
    @dataclass(frozen=True)
    class Adhesive(ContactLaw):
        name: ClassVar[str] = "adhesive"          # the registry name
        solves_shear: ClassVar[bool] = False      # whether q_x is an unknown of its own

        def solve(self, ctx, pressure, shear, product):   # one pass -> StepSolution
            ...

and its entry in :func:`law_name` (or :data:`PHASE_LAWS`). What it implements:

* :meth:`ContactLaw.solve` (required): one pass from the iterate (p, q) given the step's
  :class:`StepContext`, returning a :class:`StepSolution` (its ``iterations`` those of this pass);
* :meth:`ContactLaw.for_problem` (optional): the law's parameters from the problem (default: mu_f
  and whether the compliance couples the normal and tangential components);
* :meth:`ContactLaw.finish` (optional): the converged solution completed (default: as it is);
* :meth:`ContactLaw.stuck` (optional): the stuck points of a solution (default: none);
* ``solve_direct(ctx, pressure)`` (optional): a direct solve of a step whose coupling is too strong
  for the fixed point (:func:`viscontact.solvers.coupling.solve_coupled`).

A law holds only its parameters (a frozen dataclass, built anew each step): what carries over from
step to step is in :class:`viscontact.solvers.transient.State` and reaches the law through the
:class:`StepContext` (e.g. the incremental slip ``slip_x``). A line contact is a body and a grid
(:mod:`viscontact.bodies`), not a law: the laws see the body through the compliance only.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np

from viscontact.bodies.compliance import Compliance
from viscontact.errors import ParameterError
from viscontact.numerics.support_window import windowed_bounded_cg, windowed_cg
from viscontact.problem.problem import (
    PHASE_GROSS_SLIDING,
    PHASE_INDENTATION,
    PHASE_NAMES,
    PHASE_PARTIAL_SLIP,
    PHASE_ROLLING,
    Problem,
    TangentialLoading,
)

#: relative margin under mu_f p below which a node counts as stuck
STICK_MARGIN = 1e-9


@dataclass(frozen=True)
class StepContext:
    """What the contact law of step ``k`` at time ``t`` [s] sees (all given, nothing solved yet).

    Attributes
    ----------
    problem, compliance
        What is solved, and the body's operators (:class:`~viscontact.bodies.compliance.Compliance`).
    k, t, first
        Step index, time [s] and whether it is the step at t = 0.
    gap
        Undeformed gap at the frame offset [m], on the compliance's device.
    known_uz, known_ux
        History displacement [m] (seed Eq. 5 without the step's own increment); ``known_ux`` only
        for a law that solves the shear (:attr:`ContactLaw.solves_shear`), else None.
    value
        Normal condition: load [N] or approach [m].
    delta_x
        Tangential displacement [m] the contact sees (total slip: since it began).
    slip_x
        Incremental slip: s_x [m] of the last step, which a stuck point keeps; else None.
    interaction
        The adhesive interaction zone of the last step (:mod:`viscontact.solvers.adhesive_law`),
        which warm-starts this one; else None.
    """

    problem: Problem
    compliance: Compliance
    k: int
    t: float
    first: bool
    gap: np.ndarray
    known_uz: np.ndarray
    known_ux: np.ndarray | None
    value: float
    delta_x: float
    slip_x: np.ndarray | None = None
    interaction: np.ndarray | None = None


@dataclass(frozen=True)
class StepSolution:
    """Tractions [Pa], approach delta_z [m], total u_z [m] and the iteration counts of one step (or
    of one pass of a law); ``pressure_product``: the step's normal operator applied to the pressure
    [m], where the solve computed it in double precision (else None); ``slip``: partial slip's
    s_x - ``ctx.slip_x`` [m] at every point (the tangential solve's gradient: the slip, or with the
    incremental slip its change over the step), else None; ``interaction``: an adhesive law's
    interaction zone (contact and cohesive zone, boolean), else None; ``delta_x``: the step's rigid
    tangential displacement [m] where the law found it (rolling under a held tangential force:
    :mod:`viscontact.solvers.rolling`), else None (the context's)."""

    pressure: np.ndarray
    shear_x: np.ndarray
    delta_z: float
    displacement_z: np.ndarray
    iterations: int = 0
    coupling_iterations: int = 1
    pressure_product: np.ndarray | None = None
    slip: np.ndarray | None = None
    interaction: np.ndarray | None = None
    delta_x: float | None = None


@dataclass(frozen=True)
class ContactLaw:
    """A contact law: one step's surface problem, iterated by
    :func:`~viscontact.solvers.coupling.solve_coupled` as a fixed point on (p, q) (module docstring:
    what a new law implements).

    Attributes
    ----------
    name
        Registry name (class attribute; :func:`register_contact_law`).
    solves_shear
        Whether q_x is an unknown of its own (class attribute): the stepper then gives the law the
        history's u_x and the convergence test watches q too.
    friction
        mu_f [-] acting in the step.
    coupled
        Whether a pass depends on the previous iterate (normal/tangential coupling terms,
        IC_zx, IC_xz ~ (1 - 2 nu)); else one pass is the solution.
    label
        What errors call it (the phase's name, e.g. ``"gross sliding"``).
    """

    name: ClassVar[str] = ""
    solves_shear: ClassVar[bool] = False

    friction: float = 0.0
    coupled: bool = False
    label: str = ""

    @classmethod
    def for_problem(cls, problem: Problem, compliance: Compliance, phase: int) -> ContactLaw:
        """The law of a step of ``phase`` of ``problem``: mu_f the mode's effective friction, coupled
        where the compliance couples the components and mu_f > 0."""
        mu = problem.tangential.effective_friction
        return cls(mu, compliance.has_coupling() and mu > 0, PHASE_NAMES.get(phase, cls.name))

    def solve(self, ctx: StepContext, pressure: np.ndarray, shear: np.ndarray,
              product: np.ndarray | None) -> StepSolution:
        """One pass from the iterate (p [Pa], q [Pa]); ``product``: the step's normal operator applied
        to p [m] where known. Returns the pass's solution (its ``iterations`` those of this pass,
        ``pressure_product`` the operator applied to the new p or None)."""
        raise NotImplementedError

    def finish(self, ctx: StepContext, solution: StepSolution) -> StepSolution:
        """The converged solution, completed (e.g. u_z with the final coupling term)."""
        return solution

    def stuck(self, pressure: np.ndarray, shear: np.ndarray) -> np.ndarray:
        """The points that stick (a boolean field like ``pressure``): none, for a law without a
        tangential unknown."""
        return np.zeros(pressure.shape, dtype=bool)


#: the registered contact laws, by name
CONTACT_LAWS: dict[str, type[ContactLaw]] = {}


def register_contact_law(law: type[ContactLaw]) -> type[ContactLaw]:
    """Add the class ``law`` to :data:`CONTACT_LAWS` under its ``name``; returns it (a class
    decorator). A name already taken by another class is refused (:class:`ValueError`)."""
    if not law.name:
        raise ValueError(f"contact law {law.__qualname__} has no name")
    if CONTACT_LAWS.get(law.name, law) is not law:
        raise ValueError(f"a contact law named {law.name!r} is registered already "
                         f"({CONTACT_LAWS[law.name].__qualname__})")
    CONTACT_LAWS[law.name] = law
    return law


def get_contact_law(name: str) -> type[ContactLaw]:
    """The registered contact law of that name (:class:`~viscontact.errors.ParameterError` naming
    the registered ones otherwise)."""
    try:
        return CONTACT_LAWS[name]
    except KeyError:
        raise ParameterError("contact law", f"must be one of {sorted(CONTACT_LAWS)}, got {name!r}") from None


#: the law of every step of a problem with ``adhesion`` but those of partial slip with friction
#: (:mod:`viscontact.solvers.adhesive_law`)
ADHESIVE_LAW = "adhesive_normal"
#: the law of a partial-slip step with ``adhesion`` and friction (:mod:`viscontact.solvers.adhesive_law`)
ADHESIVE_PARTIAL_SLIP_LAW = "adhesive_partial_slip"

#: the law of each phase, by phase code (:data:`~viscontact.problem.problem.PHASE_NAMES`); the
#: tangential mode gives the first phase (:func:`first_phase`)
PHASE_LAWS: dict[int, str] = {PHASE_INDENTATION: "normal_contact", PHASE_PARTIAL_SLIP: "partial_slip",
                              PHASE_GROSS_SLIDING: "normal_contact", PHASE_ROLLING: "rolling"}


def first_phase(tangential: TangentialLoading) -> int:
    """The phase of a run's first step: indentation (``"none"``), partial slip (``"partial_slip"``),
    rolling (``"rolling"``, the run's only phase) or gross sliding (the sliding modes)."""
    return {"none": PHASE_INDENTATION, "partial_slip": PHASE_PARTIAL_SLIP,
            "rolling": PHASE_ROLLING}.get(tangential.mode, PHASE_GROSS_SLIDING)


def law_name(problem: Problem, phase: int) -> str:
    """The name of the contact law of a step of ``phase`` of ``problem`` (:data:`PHASE_LAWS`; partial
    slip and rolling without friction are the normal contact: frictionless rolling is frictionless
    sliding; with ``problem.adhesion``, :data:`ADHESIVE_LAW`, or :data:`ADHESIVE_PARTIAL_SLIP_LAW` in
    partial slip with friction)."""
    if problem.adhesion is not None:
        friction = problem.tangential.effective_friction > 0
        return ADHESIVE_PARTIAL_SLIP_LAW if phase == PHASE_PARTIAL_SLIP and friction else ADHESIVE_LAW
    if phase in (PHASE_PARTIAL_SLIP, PHASE_ROLLING) and not problem.tangential.effective_friction > 0:
        return PHASE_LAWS[PHASE_INDENTATION]
    return PHASE_LAWS[phase]


def contact_law(problem: Problem, compliance: Compliance, phase: int) -> ContactLaw:
    """The contact law of a step of ``phase`` of ``problem`` on ``compliance``, built from the
    problem (:func:`law_name`, :func:`get_contact_law`, :meth:`ContactLaw.for_problem`)."""
    return get_contact_law(law_name(problem, phase)).for_problem(problem, compliance, phase)


def solve_normal(ctx: StepContext, known_uz: np.ndarray, warm: np.ndarray, warm_product: np.ndarray | None
                 ) -> tuple[np.ndarray, float, int, np.ndarray, np.ndarray | None]:
    """Polonsky & Keer (1999) solve of the normal problem (seed Eqs. 7-8, 10) with known displacement
    ``known_uz`` [m], on a box around the warm start's support
    (:mod:`viscontact.numerics.support_window`).

    Parameters
    ----------
    ctx
        The step.
    known_uz
        Displacement [m] known before the solve (history, and coupling terms where iterated).
    warm, warm_product
        Start pressure [Pa], and the step's normal operator applied to it [m] where known.

    Returns
    -------
    tuple
        (pressure [Pa], approach delta_z [m], CG iterations, total u_z [m], the operator applied to
        the pressure [m] or None).
    """
    problem, s, gap = ctx.problem, ctx.problem.solver, ctx.gap
    op = ctx.compliance.elastic_operator("z", ctx.first)
    if problem.normal.control == "load":
        sol = windowed_cg(op, -(gap + known_uz), warm, total=ctx.value, cell_area=problem.grid.cell_area,
                          tolerance=s.tolerance, max_iterations=s.max_iterations, what="normal contact (load control)",
                          mixed_precision=s.mixed_precision, start_product=warm_product)
        return sol.x, sol.multiplier, sol.iterations, sol.gradient + sol.multiplier - gap, sol.product
    sol = windowed_cg(op, ctx.value - (gap + known_uz), warm, tolerance=s.tolerance, max_iterations=s.max_iterations,
                      what="normal contact (displacement control)", mixed_precision=s.mixed_precision,
                      start_product=warm_product)
    return sol.x, ctx.value, sol.iterations, sol.gradient + ctx.value - gap, sol.product


def _plus(known: np.ndarray, coupling: np.ndarray | None) -> np.ndarray:
    return known if coupling is None else known + coupling


@register_contact_law
@dataclass(frozen=True)
class NormalContact(ContactLaw):
    """Indentation, frictionless sliding and gross sliding (seed Eq. 12): q_x = mu_f p.

    With friction and coupling terms, u_z = J_inst (IC_zz + mu_f IC_zx) p + history is not
    symmetric; the coupling term is iterated as a fixed point around symmetric Polonsky-Keer solves
    (contraction factor about mu_f (1 - 2 nu) / (2 (1 - nu)) < 0.1 for the seed's case), or for a
    stronger coupling solved directly (:meth:`solve_direct`)."""

    name: ClassVar[str] = "normal_contact"

    def solve(self, ctx, pressure, shear, product):
        cross = ctx.compliance.cross_displacement("z", "x", pressure, ctx.first, self.friction) if self.coupled else None
        p, delta_z, its, u_z, product = solve_normal(ctx, _plus(ctx.known_uz, cross), pressure, product)
        return StepSolution(p, self.friction * p if self.friction else np.zeros_like(p), float(delta_z), u_z, its,
                            pressure_product=product)

    def solve_direct(self, ctx: StepContext, pressure: np.ndarray) -> StepSolution:
        """The step's normal problem with the coupling inside the operator, J_inst (K_zz + mu_f K_zx),
        which is not symmetric: the primal-dual active set with GMRES of the steady solver
        (:func:`viscontact.numerics.active_set.solve_contact_active_set`), from ``pressure`` [Pa]. For
        a coupling too strong for the fixed point. Its ``iterations`` are the Krylov iterations and
        its ``pressure_product`` K_zz p [m]."""
        from viscontact.numerics.active_set import solve_contact_active_set

        problem, s, sub = ctx.problem, ctx.problem.solver, ctx.compliance
        op = sub.elastic_operator("z", ctx.first)

        def apply_k(p: np.ndarray) -> np.ndarray:
            return op.apply(p) + sub.cross_displacement("z", "x", p, ctx.first, self.friction)

        p, delta_z, krylov, _ = solve_contact_active_set(
            apply_k, ctx.gap + ctx.known_uz, control=problem.normal.control, value=ctx.value,
            cell_area=problem.grid.cell_area, initial=pressure, tolerance=min(s.tolerance, 1e-10),
            max_iterations=s.max_iterations, preconditioner=op.preconditioner,
            what=f"{self.label} with the coupling in the operator")
        product = op.apply(p)
        u_z = product + sub.cross_displacement("z", "x", p, ctx.first, self.friction) + ctx.known_uz
        return StepSolution(p, self.friction * p, float(delta_z), u_z, krylov, pressure_product=product)


@register_contact_law
@dataclass(frozen=True)
class PartialSlip(ContactLaw):
    """Partial slip (seed Eqs. 9, 11): bounded CG for q_x in [-mu_f p, mu_f p] with slip
    s = u_x - delta_x, alternated with the normal solve (semi-coupled: IC_zx, IC_xz ~ (1 - 2 nu)).

    Total slip (the seed's): the CG's gradient is s itself, zero where stuck; delta_x is measured
    from the first step of the contact (:attr:`viscontact.solvers.transient.State.slip_origin`): the
    indenter that moved before it touched has dragged nothing. Incremental slip (``ctx.slip_x``, the
    last step's s): the right-hand side is delta_x + s_prev - u_known, so the gradient is the step's
    change of s, zero where stuck (a stuck point keeps its slip) and opposed to q where slipping
    (Mindlin-Deresiewicz); with nothing entering the contact and a monotonic loading both give the
    same solution. ``free_mean``: a uniform shear is in the null space of the tangential operator
    (:meth:`~viscontact.bodies.compliance.Compliance.free_mean`), so a contact over every cell is
    refused (:func:`check_not_full_contact`)."""

    name: ClassVar[str] = "partial_slip"
    solves_shear: ClassVar[bool] = True

    free_mean: bool = False

    @classmethod
    def for_problem(cls, problem, compliance, phase):
        law = super().for_problem(problem, compliance, phase)
        return replace(law, free_mean=compliance.free_mean("x"))

    def normal(self, ctx: StepContext, known_uz: np.ndarray, pressure: np.ndarray, product: np.ndarray | None
               ) -> tuple[np.ndarray, float, int, np.ndarray, np.ndarray | None, np.ndarray | None]:
        """The pass's normal problem with the known displacement ``known_uz`` [m] (:func:`solve_normal`;
        a law with another normal problem overrides it): (p [Pa], delta_z [m], iterations, u_z [m], the
        operator applied to p [m] or None, an adhesive interaction zone or None)."""
        return *solve_normal(ctx, known_uz, pressure, product), None

    def bound(self, pressure: np.ndarray) -> np.ndarray:
        """The friction bound |q_x| <= mu_f p [Pa] (p >= 0 here)."""
        return self.friction * pressure

    def solve(self, ctx, pressure, shear, product):
        p, delta_z, it_n, u_z, product, interaction = self.solve_normal(ctx, pressure, shear, product)
        q, slip, it_t = self.solve_tangential(ctx, p, shear, ctx.delta_x)
        return StepSolution(p, q, float(delta_z), u_z, it_n + it_t, pressure_product=product, slip=slip,
                            interaction=interaction)

    def solve_normal(self, ctx: StepContext, pressure: np.ndarray, shear: np.ndarray, product: np.ndarray | None
                     ) -> tuple[np.ndarray, float, int, np.ndarray, np.ndarray | None, np.ndarray | None]:
        """The pass's normal solve with the iterate's shear ``shear`` [Pa] in the coupling term
        (:meth:`normal`'s tuple)."""
        cross_z = ctx.compliance.cross_displacement("z", "x", shear, ctx.first) if self.coupled else None
        solved = self.normal(ctx, _plus(ctx.known_uz, cross_z), pressure, product)
        if self.free_mean:
            check_not_full_contact(solved[0], ctx.t)
        return solved

    def solve_tangential(self, ctx: StepContext, pressure: np.ndarray, shear: np.ndarray, delta_x: float
                         ) -> tuple[np.ndarray, np.ndarray, int]:
        """The bounded tangential solve for the pressure ``pressure`` [Pa] from ``shear`` [Pa], the
        stuck points at u_x = ``delta_x`` [m] (+ ``ctx.slip_x``): (q_x [Pa], the slip, CG iterations)."""
        sub, s = ctx.compliance, ctx.problem.solver
        cross_x = sub.cross_displacement("x", "z", pressure, ctx.first) if self.coupled else None
        bound = self.bound(pressure)
        op = sub.elastic_operator("x", ctx.first)
        target = delta_x - _plus(ctx.known_ux, cross_x)
        if ctx.slip_x is not None:
            target += ctx.slip_x
        sol = windowed_bounded_cg(op, target, np.clip(shear, -bound, bound),
                                  -bound, bound, tolerance=s.tolerance, max_iterations=s.max_iterations,
                                  what=f"tangential contact ({self.label or self.name})",
                                  mixed_precision=s.mixed_precision)
        return sol.x, sol.gradient, sol.iterations

    def finish(self, ctx, solution):
        if not self.coupled:
            return solution
        # the last tangential update changed the coupling term of u_z: recompute it
        u_z = ctx.compliance.instantaneous_displacement({"z": solution.pressure, "x": solution.shear_x}, ctx.first)
        return replace(solution, displacement_z=u_z + ctx.known_uz)

    def stuck(self, pressure, shear):
        """Points in contact whose |q_x| is under mu_f p by more than :data:`STICK_MARGIN`."""
        return (pressure > 0) & (np.abs(shear) < self.friction * pressure * (1 - STICK_MARGIN))


def check_not_full_contact(pressure: np.ndarray, t: float) -> None:
    """Raise :class:`~viscontact.errors.ParameterError` when the contact covers every cell of a
    periodic partial-slip problem whose tangential operator has a free mean: a uniform shear then
    moves the surface by an undetermined mean displacement, q = 0 pins it nowhere, and delta_x
    cannot fix the friction force (the solve returned any mean shear between 0 and mu_f min p:
    Q = 0 at every delta_x, or, on an earlier solver, mu_f min p everywhere at 5e-14 m). Under a
    prescribed delta_x nothing else determines it (a prescribed tangential force would); where part
    of the period is out of contact, q = 0 there does. Under displacement control the contact never
    covers the period (:func:`viscontact.physics.periodic.check_approach`)."""
    if bool((pressure > 0).all()):
        raise ParameterError(
            "tangential.mode", f"partial slip with the contact covering the whole period (t = {t:.6g} s): a uniform "
            "shear moves the periodic surface by an undetermined mean displacement, so delta_x cannot fix the "
            "friction force; use tangential.mode = 'gross_sliding', a normal load low enough to leave part of the "
            "period out of contact, or grid.periodic = false")
