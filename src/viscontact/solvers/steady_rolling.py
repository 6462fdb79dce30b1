"""Direct steady state of rolling with traction (Carter 1926; Kalker 1990, ch. 5).

In the steady state the tractions and displacements are fixed in the frame of the indenter, and the
material rate of the transient rolling law (:mod:`viscontact.solvers.rolling`) becomes a difference
along x on the grid: over the time dt = dx / V in which the material crosses one cell,

    s dt = u_x(x) - u_x(x + dx) + xi dx,

the transient's own discretisation at its fixed point (the transient tends to this state). u_x is
the effective steady convolution of the tractions (:meth:`~viscontact.bodies.compliance.Compliance.steady_convolver`:
the material's whole past at speed V), u_x = K_xx q + K_xz p. Coulomb: stick (s = 0, |q| <= mu_f p)
or slip (q = -mu_f p s / |s|) at every point in contact.

The tangential problem for a given pressure is a box-constrained linear complementarity problem with
the non-symmetric operator q -> D K_xx q (D the difference above), solved by a primal-dual active set
like the steady normal problem (:mod:`viscontact.numerics.active_set`): on the stick set the
linear system is solved with GMRES, with the slip points at their bound; stuck points beyond the
bound leave to slip on its side, slipping points whose slip does not oppose their traction join the
stick set, until no point changes. Under a held tangential force the rigid creep xi dx is one more
unknown, with the force as its equation (a bordered system).

The pressure is the steady sliding pressure at V (:func:`viscontact.solvers.steady.solve_steady`,
frictionless: with nu = 0.5, or without ``solver.coupling``, the tangential problem does not change
it). Where the normal and tangential problems couple (nu < 0.5) the two are alternated, the normal
one with the known displacement K_zx q, until both change by less than ``solver.coupling_tolerance``.
A frictionless rolling is a frictionless sliding (Hunter 1961).

On a periodic grid (a row of indenters, one per period) the steady operators are exact in Fourier
space, each mode through the complex compliance at -k_x V (the compliance's periodic
``steady_convolver``, :mod:`viscontact.solvers.steady_periodic`), the material difference wraps
around the period as the transient's frame does, and the normal problem of the coupling is the
periodic steady one (zero-mean displacements).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from functools import partial

import numpy as np

from viscontact.bodies.compliance import Compliance, compliance_of
from viscontact.errors import ConvergenceError, ParameterError
from viscontact.numerics.active_set import solve_contact_active_set
from viscontact.numerics.krylov import gmres
from viscontact.problem.problem import PHASE_ROLLING, Problem, TangentialLoading
from viscontact.problem.records import StepRecord
from viscontact.solvers.measure import measure
from viscontact.solvers.sliding import check_speed
from viscontact.solvers.steady import steady_preconditioner

#: active-set rounds of the tangential problem before it is declared not settled
MAX_ROUNDS = 200


def material_difference(displacement: np.ndarray, periodic: bool = False) -> np.ndarray:
    """u(x) - u(x + dx) [m] along x (axis 1): the change of a steady displacement over one cell of
    the material's passage; 0 in the last column (the leading edge of the grid), or wrapping around
    on a ``periodic`` grid (as the transient's :func:`~viscontact.solvers.rolling.convected`)."""
    if periodic:
        return displacement - np.roll(displacement, -1, axis=1)
    out = np.zeros_like(displacement)
    out[:, :-1] = displacement[:, :-1] - displacement[:, 1:]
    return out


def rolling_components(problem: Problem) -> list[str]:
    """The steady kernels rolling needs: ``zz``, ``xx``, and ``xz``, ``zx`` where the components
    couple (nu < 0.5 and ``solver.coupling``)."""
    coupled = problem.material.poisson_ratio < 0.5 and problem.solver.coupling
    return ["zz", "xx"] + (["xz", "zx"] if coupled else [])


def solve_tangential(apply_xx, pressure: np.ndarray, known_x: np.ndarray, friction: float, cell_area: float, *,
                     creep: float | None, force: float | None, initial: np.ndarray | None = None,
                     tolerance: float = 1e-10, max_iterations: int = 2000, periodic: bool = False
                     ) -> tuple[np.ndarray, float, np.ndarray, int]:
    """The steady tangential problem of rolling for the pressure ``pressure`` [Pa] (module docstring).

    Parameters
    ----------
    apply_xx
        q [Pa] -> K_xx q [m], the steady tangential operator.
    known_x
        u_x [m] of the pressure (K_xz p), zeros where uncoupled.
    friction
        mu_f [-].
    creep, force
        The rigid creep xi dx [m] held, or (``creep`` None) the traction force sum q dA [N] held.
    initial
        A traction [Pa] whose stick set (|q| < mu_f p in contact) starts the active set (default:
        the whole contact sticks).
    periodic
        Whether the grid is periodic (the material difference wraps around: :func:`material_difference`).

    Returns
    -------
    tuple
        (q_x [Pa], the rigid creep xi dx [m], the slip s dt [m], GMRES iterations of all rounds).
    """
    contact = pressure > 0
    bound = friction * pressure
    if force is not None and not abs(force) < float(bound.sum()) * cell_area:
        raise ParameterError("tangential.tangential_force", f"|{force:g}| N must be below mu_f W = "
                             f"{float(bound.sum()) * cell_area:g} N: the contact would slide, not roll")
    if initial is None:
        stick, side = contact.copy(), np.zeros_like(pressure)
    else:
        stick = contact & (np.abs(initial) < bound)
        side = np.where(contact & ~stick, np.sign(initial), 0.0)
    difference = partial(material_difference, periodic=periodic)
    known_slip = difference(known_x)
    c = 0.0 if creep is None else float(creep)
    q = np.zeros_like(pressure) if initial is None else np.where(contact, np.clip(initial, -bound, bound), 0.0)
    krylov = 0
    seen: list[np.ndarray] = []
    for _ in range(MAX_ROUNDS):
        fixed = side * bound  # the slipping points at their bound
        if stick.any() or creep is None:
            q_stick, c, its = _solve_stick_set(apply_xx, difference, stick, fixed, known_slip, q, c,
                                               force if creep is None else None, cell_area,
                                               tolerance, max_iterations, contact)
            krylov += its
            q = fixed + q_stick
        else:
            q = fixed
        slip = difference(apply_xx(q)) + known_slip + c
        leave = stick & (np.abs(q) > bound)
        join = contact & ~stick & (side * slip > 0)
        if not leave.any() and not join.any():
            return q, c, slip, krylov
        new_stick = (stick & ~leave) | join
        side = np.where(leave, np.sign(q), np.where(join, 0.0, side))
        if any(np.array_equal(new_stick, s) for s in seen):  # a cycle: keep the larger stick set
            new_stick = new_stick | stick
            side = np.where(new_stick, 0.0, side)
        seen.append(stick)
        stick = new_stick
    raise ConvergenceError("steady rolling active set", MAX_ROUNDS, float(np.sum(stick != new_stick)), 0.0,
                           hint="the stick set did not settle")


def _solve_stick_set(apply_xx, difference, stick: np.ndarray, fixed: np.ndarray, known_slip: np.ndarray,
                     q: np.ndarray, creep: float, force: float | None, cell_area: float, tolerance: float, max_iterations: int,
                     contact: np.ndarray) -> tuple[np.ndarray, float, int]:
    """One round's linear solve (GMRES) of the stick set ``stick``: s = 0 there, with the slipping points
    at ``fixed`` [Pa]; ``difference`` is :func:`material_difference` on the grid. Under a held ``force`` [N] (else None: ``creep`` [m] held) the bordered system of
    (q on the set, the rigid creep) with the force as its last row (scaled to a slip: ``row`` [m/Pa],
    the mean material difference of a unit traction over the contact). Returns (q_x on the set [Pa],
    zeros elsewhere; the rigid creep [m]; GMRES iterations), starting from ``q`` and ``creep``."""
    idx = np.flatnonzero(stick)
    m = idx.size
    rhs = -(known_slip + difference(apply_xx(fixed))).ravel()[idx]

    def full(v: np.ndarray) -> np.ndarray:
        out = np.zeros_like(fixed)
        out.ravel()[idx] = v[:m]
        return out

    def slip_of(v: np.ndarray) -> np.ndarray:
        return difference(apply_xx(full(v))).ravel()[idx]

    if force is None:
        sol = gmres(slip_of, rhs - creep, q.ravel()[idx], rtol=tolerance, max_iterations=max_iterations)
    else:
        row = float(np.mean(np.abs(difference(apply_xx(contact.astype(float)))[contact]))) or 1.0
        per_point = max(m, 1)

        def entry(value) -> np.ndarray:  # the one-element border, in the fields' library
            return np.full_like(fixed, value, shape=1)

        def bordered(v: np.ndarray) -> np.ndarray:
            return np.concatenate([slip_of(v) + v[m], entry(row * v[:m].sum() / per_point)])

        rhs = np.concatenate([rhs, entry(row * (force / cell_area - float(fixed.sum())) / per_point)])
        sol = gmres(bordered, rhs, np.concatenate([q.ravel()[idx], entry(creep)]), rtol=tolerance,
                    max_iterations=max_iterations)
        creep = float(sol.x[m])
    if not sol.converged:
        raise ConvergenceError("steady rolling GMRES", max_iterations, sol.residual, tolerance)
    return full(sol.x), creep, sol.iterations


def check_steady_rolling(problem: Problem, speed: float | None = None) -> None:
    """A steady rolling state needs ``tangential.mode = "rolling"`` at a speed > 0 m/s
    (:class:`~viscontact.errors.ParameterError` otherwise)."""
    if not problem.tangential.rolls:
        raise ParameterError("tangential.mode", f"must be 'rolling' for a steady rolling state, got "
                             f"{problem.tangential.mode!r}")
    if problem.rolls_rough:
        raise ParameterError("tangential.mode", "a steady rolling state on a rough or measured surface is not "
                             "supported: the roughness carried through the contact makes the state change "
                             "with time (a steady solver for it is missing); run the transient (viscontact run)")
    check_speed(problem.tangential.rolling_speed if speed is None else speed)


def solve_steady_rolling(problem: Problem, speed: float | None = None, *, creepage: float | None = None,
                         compliance: Compliance | None = None, initial: StepRecord | None = None) -> StepRecord:
    """Steady state of rolling at ``speed`` [m/s] (default: ``tangential.rolling_speed``) with the
    held ``creepage`` [-] (default: the problem's; or its held ``tangential_force``).

    Returns the record of the state (``phase`` rolling, ``creepage`` the held or found one, the
    ``stick`` field and ratio, ``friction_force`` sum q_x dA [N], ``hysteresis_force`` the rolling
    resistance F_T = -sum p du_z/dx dA [N]; ``iterations`` the GMRES iterations of the tangential
    problem). ``initial``: a neighbouring state (e.g. at a nearby creepage) whose stick set starts
    the active set.
    """
    from viscontact.solvers.steady import solve_steady

    check_steady_rolling(problem, speed)
    tan = problem.tangential
    v = tan.rolling_speed if speed is None else speed
    grid, settings = problem.grid, problem.solver
    xi = tan.creepage if creepage is None else creepage
    force = tan.tangential_force if creepage is None else None
    mu = tan.friction_coefficient
    components = rolling_components(problem)
    compliance = compliance or compliance_of(problem, components)
    conv, kernels = compliance.steady_convolver(v, components)
    coupled = "xz" in conv.spectra
    tolerance = min(settings.tolerance, 1e-10)
    value = problem.normal.history(problem.time.t_end)
    # the pressure of frictionless sliding at v (with nu = 0.5: the answer; else the first iterate)
    sliding = replace(problem, tangential=TangentialLoading("frictionless_sliding", sliding_speed=v))
    normal = solve_steady(sliding, v, compliance=compliance,
                          initial=None if initial is None else initial.pressure)
    to_device, to_host = compliance.backend.to_device, compliance.backend.to_host
    p, delta, gap = to_device(normal.pressure), normal.delta_z, to_device(problem.gap)
    krylov = 0
    q = to_device(initial.shear_x) if initial is not None else None
    creep = None if xi is None else xi * grid.spacing
    normal_with = _normal_solver(problem, compliance, conv, kernels, v, value, tolerance)
    periodic = grid.periodic
    for _ in range(settings.max_coupling_iterations if coupled else 1):
        known_x = conv.apply("xz", p) if coupled else np.zeros_like(p)
        if mu > 0:
            q, c, _, its = solve_tangential(lambda f: conv.apply("xx", f), p, known_x, mu, grid.cell_area,
                                               creep=creep, force=force, initial=q, tolerance=tolerance,
                                               max_iterations=settings.max_iterations, periodic=periodic)
            krylov += its
        else:
            q, c = np.zeros_like(p), creep
        if not coupled or mu == 0:
            break
        p_new, delta = normal_with(gap + conv.apply("zx", q), p)
        change = float(np.abs(p_new - p).sum()) / max(float(np.abs(p_new).sum()), 1e-300)
        p = p_new
        if change < settings.coupling_tolerance:
            break
    else:
        raise ConvergenceError("steady rolling normal/tangential coupling", settings.max_coupling_iterations,
                               change, settings.coupling_tolerance)
    if mu > 0 and coupled:  # the tangential state of the final pressure
        q, c, _, its = solve_tangential(lambda f: conv.apply("xx", f), p, conv.apply("xz", p), mu, grid.cell_area,
                                           creep=creep, force=force, initial=q, tolerance=tolerance,
                                           max_iterations=settings.max_iterations, periodic=periodic)
        krylov += its
    u_z = to_host(conv.apply("zz", p) + (conv.apply("zx", q) if coupled else 0.0))
    p, q = to_host(p), to_host(q)
    stick = (p > 0) & (np.abs(q) < mu * p * (1 - 1e-9)) if mu > 0 else np.zeros(p.shape, dtype=bool)
    record = measure(problem, p, q, u_z, delta_z=delta, value=value, gap=problem.gap, step=0, t=problem.time.t_end,
                     phase=PHASE_ROLLING, stick=stick, sliding_distance=float("inf"), iterations=krylov,
                     where=f" at V = {v:.4g} m/s")
    return replace(record, creepage=float(xi) if xi is not None else c / grid.spacing)


def _normal_solver(problem: Problem, compliance: Compliance, conv, kernels: dict[str, np.ndarray], speed: float,
                   value: float, tolerance: float):
    """The steady normal problem of the coupled alternation: (gap h0 + K_zx q [m], the last pressure
    [Pa]) -> (p [Pa], delta_z [m]) with the steady K_zz at ``speed`` [m/s] and the held normal
    ``value``: the active set of :mod:`viscontact.solvers.steady` on a DC-FFT grid, or that of
    :func:`~viscontact.solvers.steady_periodic.solve_periodic_steady` (zero-mean displacements) on a
    periodic one."""
    settings, grid, backend = problem.solver, problem.grid, compliance.backend
    if grid.periodic:
        from viscontact.solvers.steady_periodic import solve_periodic_steady

        spectrum = compliance.steady_spectrum(speed)

        def periodic(gap: np.ndarray, initial: np.ndarray) -> tuple[np.ndarray, float]:
            state = solve_periodic_steady(compliance.convolver, problem.material, grid, gap, speed=speed,
                                          control=problem.normal.control, value=value, initial=initial,
                                          tolerance=tolerance, max_iterations=settings.max_iterations,
                                          spectrum=spectrum, to_host=backend.to_host)
            return backend.to_device(state.pressure), state.delta_z

        return periodic
    precondition = steady_preconditioner(compliance, kernels, speed, settings.workers)

    def dc_fft(gap: np.ndarray, initial: np.ndarray) -> tuple[np.ndarray, float]:
        p, delta, _, _ = solve_contact_active_set(
            lambda f: conv.apply("zz", f), gap, control=problem.normal.control, value=value,
            cell_area=grid.cell_area, initial=initial, tolerance=tolerance, max_iterations=settings.max_iterations,
            preconditioner=precondition, what="steady rolling (normal)")
        return p, delta

    return dc_fft


def creepage_sweep(problem: Problem, creepages: Sequence[float], speed: float | None = None) -> list[StepRecord]:
    """Steady rolling states at each creepage [-] in the given order (the traction-creepage curve),
    each started from the previous one's stick set; one compliance serves them all."""
    check_steady_rolling(problem, speed)
    compliance = compliance_of(problem, rolling_components(problem))
    out: list[StepRecord] = []
    for xi in creepages:
        out.append(solve_steady_rolling(problem, speed, creepage=xi, compliance=compliance,
                                        initial=out[-1] if out else None))
    return out
