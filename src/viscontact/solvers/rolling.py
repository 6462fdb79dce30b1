"""Rolling with traction: the stick-slip contact law of a rolling indenter (Carter 1926; Kalker 1990).

The indenter's centre moves in +x at the rolling speed V; its surface turns at the circumferential
speed V_c, and the creepage xi = (V_c - V) / V is the relative rigid slip. In the frame of the
indenter (origin under its centre, :mod:`viscontact.solvers.sliding`) the body's material passes
through the contact at -V. The slip velocity of a body surface point relative to the indenter's
surface is the rigid creepage plus the material rate of the body's tangential displacement,

    s(x, t) = xi V + D u_x / D t,     D u_x / D t = d u_x / d t - V d u_x / d x

(Kalker 1990, *Three-dimensional elastic bodies in rolling contact*, ch. 5; the transient rolling of
Vollebregt's CONTACT). With the frame moving by one cell per step (V dt = dx) the material point at
x was at x + dx one step earlier, so over a step

    s dt = u_x(x, t) - u_x(x + dx, t - dt) + xi dx,

exact in the convection (no interpolation). Coulomb's law: stick where |q_x| < mu_f p and s = 0,
slip where q_x = -mu_f p s / |s|. Signs: q_x is the traction on the body (seed convention); with
xi < 0 (braking: the indenter's surface slips forward over the body) the traction points in +x and
the ``friction_force`` sum q_x dA is positive.

This is the incremental partial slip of :class:`~viscontact.solvers.contact_laws.PartialSlip` with the
reference displacement u_x(x + dx, t - dt) (the last step's total u_x convected by one cell,
:func:`convected`) in place of the last step's slip, and the step's rigid displacement -xi dx in
place of delta_x: :class:`Rolling` is that law, iterated over the normal-tangential coupling like
partial slip. Under a held ``tangential_force`` the step's rigid displacement c is the unknown of a
1-D root find (Illinois) on sum q_x(c) dA = F, monotone in c; the creepage is then -c / dx.

At the first step (t = 0) nothing has rolled yet: the rigid displacement is 0 under a held creepage
(the contact sticks where it touches), and under a held force it is found as in Cattaneo's problem
(the creepage is undefined there: NaN).
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np

from viscontact.errors import ConvergenceError, ParameterError
from viscontact.problem.problem import Problem
from viscontact.solvers.contact_laws import PartialSlip, StepContext, StepSolution, register_contact_law

#: the held force's root find: converged when sum q_x dA is within this fraction of mu_f W of the force
FORCE_TOLERANCE = 1e-9
#: ... or when its bracket on the rigid displacement c is narrower than this fraction of c's scale
#: (the displacement of the held force spread over the contact): c at round-off
ROOT_TOLERANCE = 1e-12
#: the most evaluations of the root find; Illinois' method converges superlinearly, in a few from the last step's c
MAX_ROOT_ITERATIONS = 100
#: doublings of the bracket of the rigid displacement before the held force is called unreachable
MAX_BRACKET_DOUBLINGS = 60


def convected(displacement_x: np.ndarray, periodic: bool) -> np.ndarray:
    """The field u(x + dx) [m] on the grid: ``displacement_x`` moved one cell towards -x, as the
    body's material moves through the rolling frame in one step. The column entering at the leading
    edge keeps the edge's value (far from the contact), or wraps around on a ``periodic`` grid."""
    if periodic:
        return np.roll(displacement_x, -1, axis=1)
    out = np.empty_like(displacement_x)
    out[:, :-1] = displacement_x[:, 1:]
    out[:, -1] = displacement_x[:, -1]
    return out


def rigid_step(problem: Problem, k: int) -> float:
    """The rigid tangential displacement [m] of step ``k`` under a held creepage: -xi V dt = -xi dx
    (the indenter's surface moves by it relative to the body's material), 0 at the first step (no
    rolling yet)."""
    tan = problem.tangential
    if k == 0 or tan.creepage is None:
        return 0.0
    return -tan.creepage * tan.rolling_speed * problem.time.dt


def step_creepage(problem: Problem, k: int, delta_x: float) -> float:
    """The creepage [-] of step ``k`` whose rigid displacement was ``delta_x`` [m]: the held one, or
    -delta_x / (V dt) found under a held force (NaN at the first step: nothing rolled)."""
    tan = problem.tangential
    if tan.creepage is not None:
        return float(tan.creepage)
    if k == 0:
        return float("nan")
    return -delta_x / (tan.rolling_speed * problem.time.dt)


@register_contact_law
@dataclass(frozen=True)
class Rolling(PartialSlip):
    """Rolling with Coulomb friction (module docstring): partial slip whose stuck points keep
    s dt = u_x - u_x(x + dx, t - dt) + xi dx = 0 (the context's ``slip_x`` is the convected u_x, its
    ``delta_x`` the rigid displacement -xi dx); ``tangential_force``: the held sum q_x dA [N] (the
    rigid displacement found), or None (the creepage held)."""

    name: ClassVar[str] = "rolling"

    tangential_force: float | None = None

    @classmethod
    def for_problem(cls, problem, compliance, phase):
        law = super().for_problem(problem, compliance, phase)
        return replace(law, tangential_force=problem.tangential.tangential_force)

    def solve(self, ctx, pressure, shear, product):
        if self.tangential_force is None:
            return super().solve(ctx, pressure, shear, product)
        p, delta_z, it_n, u_z, product, interaction = self.solve_normal(ctx, pressure, shear, product)
        c, q, slip, it_t = self.held_force(ctx, p, shear)
        return StepSolution(p, q, float(delta_z), u_z, it_n + it_t, pressure_product=product, slip=slip,
                            interaction=interaction, delta_x=c)

    def held_force(self, ctx: StepContext, pressure: np.ndarray, shear: np.ndarray
                   ) -> tuple[float, np.ndarray, np.ndarray, int]:
        """The rigid displacement c [m] for which the tangential solve carries the held force:
        (c, q_x [Pa], slip [m], CG iterations of every solve). sum q_x(c) dA rises monotonically
        from -mu_f W to mu_f W; the bracket grows from ``ctx.delta_x`` (the last step's c) by
        doublings of a scale from the contact's tangential compliance, then the Illinois method."""
        area = ctx.problem.grid.cell_area
        force = float(self.tangential_force)
        limit = self.friction * float(pressure.sum()) * area
        if not abs(force) < limit:
            raise ParameterError("tangential.tangential_force", f"|{force:g}| N must be below mu_f W = {limit:g} N "
                                 f"(t = {ctx.t:.6g} s): the contact would slide, not roll")
        iterations = 0
        last: dict[str, object] = {"q": shear}

        def excess(c: float) -> float:
            nonlocal iterations
            q, slip, its = self.solve_tangential(ctx, pressure, last["q"], c)
            iterations += its
            last.update(c=c, q=q, slip=slip)
            return float(q.sum()) * area - force

        # the scale of c: the mean displacement [m] of a uniform traction over the contact carrying
        # the larger of |F| and 1e-3 mu_f W
        contact = pressure > 0
        per_pascal = float(np.mean(ctx.compliance.elastic_operator("x", ctx.first).apply(
            contact.astype(float))[contact]))
        scale = max(abs(force), 1e-3 * limit) / (max(int(contact.sum()), 1) * area) * per_pascal
        a = b = float(ctx.delta_x)
        fa = fb = excess(a)
        step = scale
        for _ in range(MAX_BRACKET_DOUBLINGS):
            if fa * fb <= 0 and a != b:
                break
            if fb < 0:
                a, fa = b, fb
                b = b + step
                fb = excess(b)
            else:
                b, fb = a, fa
                a = a - step
                fa = excess(a)
            step *= 2.0
        else:
            raise ParameterError("tangential.tangential_force", f"{force:g} N was not bracketed (t = {ctx.t:.6g} s)")
        # Illinois (modified regula falsi) on the bracket, from the values already found: each evaluation
        # is a CG solve to a tolerance, so f is not re-evaluated at the ends (Brent's does, and near the
        # root the solve's tolerance can flip its sign there)
        tolerance = FORCE_TOLERANCE * limit
        for _ in range(MAX_ROOT_ITERATIONS):
            if abs(fa) <= tolerance or abs(fb) <= tolerance or abs(b - a) <= ROOT_TOLERANCE * scale:
                break
            c = b - fb * (b - a) / (fb - fa)
            fc = excess(c)
            if fc * fb < 0:
                a, fa = b, fb
            else:
                fa *= 0.5
            b, fb = c, fc
        else:
            raise ConvergenceError("rolling under a held tangential force", MAX_ROOT_ITERATIONS,
                                   min(abs(fa), abs(fb)) / limit, FORCE_TOLERANCE)
        c = b if abs(fb) <= abs(fa) else a
        if last["c"] != c:
            excess(c)
        return c, last["q"], last["slip"], iterations
