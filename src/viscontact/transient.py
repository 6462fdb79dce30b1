"""Transient solver: indentation, partial slip and gross sliding (seed Sec. 2.2, Fig. 3).

Each time step is an elastic contact problem with the instantaneous compliance J_inst plus the
known hereditary displacement of all earlier increments (:mod:`viscontact.history`):

* normal (seed Eqs. 7-8, 10): Polonsky-Keer constrained CG under load or displacement control;
* partial slip (seed Eqs. 9, 11): bounded CG for q_x in [-mu_f p, mu_f p], alternated with the
  normal solve (semi-coupled: IC_zx, IC_xz ~ (1 - 2 nu)) until both change by less than
  ``coupling_tolerance``;
* gross sliding (seed Eq. 12): q_x = mu_f p, so u_z = J_inst (IC_zz + mu_f IC_zx) p + history. The
  operator is not symmetric; the coupling term is iterated as a fixed point around symmetric
  Polonsky-Keer solves (contraction factor about mu_f (1 - 2 nu) / (2 (1 - nu)) < 0.1 for the
  seed's case), each warm-started.

State is explicit: :func:`init` builds it, :func:`step` advances it by one time step and returns
the step's :class:`~viscontact.records.StepRecord`; :func:`simulate` loops and yields the records
the output settings ask for.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field, replace
from typing import Callable, Iterator

import numpy as np

from .constrained import constrained_cg
from .convolution import Convolver, FourierPreconditioner, coupled_displacements
from .kernels import influence_coefficients
from .errors import ConvergenceError, NumericalGuardError, ParameterError, ViscontactWarning
from .history import DirectHistory, PronyHistory, StepCoefficients, stable_step_limit, step_coefficients
from .problem import PHASE_GROSS_SLIDING, PHASE_INDENTATION, PHASE_PARTIAL_SLIP, Problem
from .records import StepRecord
from .sliding import Wake, hysteresis_force, pressure_centroid

#: relative margin under mu_f p below which a node counts as stuck
STICK_MARGIN = 1e-9
#: estimated relative error from the dropped wake above which a warning is issued
WAKE_WARNING = 0.01


@dataclass(frozen=True)
class Operators:
    """Per-problem constants: DC-FFT kernels and the step coefficients of the history."""

    conv: Convolver
    first: StepCoefficients
    regular: StepCoefficients
    preconditioners: dict[str, FourierPreconditioner] = field(default_factory=dict)


def operators(problem: Problem) -> Operators:
    """Kernel spectra (once per grid) and history coefficients (once per dt)."""
    nu = problem.material.poisson_ratio
    comps = ["zz"]
    if problem.tangential.mode == "partial_slip":
        comps += ["xx"]
    if nu < 0.5 and problem.solver.coupling and problem.tangential.mode in ("partial_slip", "gross_sliding"):
        comps += ["xz", "zx"]
    workers = problem.solver.workers
    ics = influence_coefficients(problem.grid, nu)
    conv = Convolver.from_kernels(problem.grid.n, {c: ics[c] for c in comps}, workers)
    precond = {c: FourierPreconditioner.for_kernel(ics[c], 1.0, workers) for c in ("zz", "xx") if c in comps}
    dt, scheme = problem.time.dt, problem.time.scheme
    return Operators(conv, step_coefficients(problem.material, dt, scheme, True),
                     step_coefficients(problem.material, dt, scheme, False), precond)


@dataclass
class State:
    """Everything that carries over from one step to the next (checkpointable)."""

    step: int
    t: float
    phase: int
    pressure: np.ndarray
    shear_x: np.ndarray
    history_p: PronyHistory | DirectHistory
    history_q: PronyHistory | DirectHistory
    delta_z: float = 0.0
    delta_x: float = 0.0
    sliding_distance: float = 0.0
    substep: int = 0
    t_gross_sliding: float | None = None
    wake: Wake = field(default_factory=Wake)
    pressure_previous: np.ndarray | None = None
    shear_previous: np.ndarray | None = None


def init(problem: Problem) -> State:
    """State before the first step (t = 0 is solved by the first call of :func:`step`)."""
    n = problem.grid.n
    m = problem.material.creep.retardation_times.size
    mode = problem.tangential.mode
    phase = {"none": PHASE_INDENTATION, "partial_slip": PHASE_PARTIAL_SLIP}.get(mode, PHASE_GROSS_SLIDING)
    if problem.solver.history == "direct":
        hp, hq = DirectHistory(n), DirectHistory(n)
    else:
        hp, hq = PronyHistory.zeros(m, n), PronyHistory.zeros(m, n)
    validate(problem)
    return State(step=-1, t=-problem.time.dt, phase=phase, pressure=np.zeros((n, n)),
                 shear_x=np.zeros((n, n)), history_p=hp, history_q=hq,
                 pressure_previous=np.zeros((n, n)), shear_previous=np.zeros((n, n)),
                 t_gross_sliding=0.0 if phase == PHASE_GROSS_SLIDING else None)


def validate(problem: Problem) -> None:
    """Checks that involve several parts of the problem (each part validated itself)."""
    tan = problem.tangential
    if tan.slides:
        if not tan.sliding_speed > 0:
            raise ParameterError("tangential.sliding_speed", f"must be > 0 m/s when sliding, got {tan.sliding_speed}")
        cell_dt = problem.grid.spacing / (tan.sliding_speed * tan.steps_per_cell)
        if abs(problem.time.dt - cell_dt) > 1e-6 * cell_dt:
            raise ParameterError(
                "time.dt", f"must equal (2*half_width/n)/sliding_speed/steps_per_cell = {cell_dt:.6g} s "
                f"so that the frame moves by whole cells, got {problem.time.dt:.6g}")
        if tan.steps_per_cell > 1 and problem.radius is None:
            raise ParameterError("tangential.steps_per_cell",
                                 "> 1 needs an analytic indenter (shape = \"sphere\"); use 1 with a height file")
    if tan.mode == "partial_slip" and not tan.displacement_rate > 0:
        raise ParameterError("tangential.displacement_rate", f"must be > 0 m/s for partial_slip, got {tan.displacement_rate}")
    limit = stable_step_limit(problem.material, problem.time.scheme)
    if problem.time.dt > limit:
        raise ParameterError(
            "time.dt", f"{problem.time.dt:.4g} s exceeds the stability limit {limit:.4g} s of the piecewise-constant "
            "(seed) scheme for this material: the result would oscillate and grow. Use time.scheme = \"linear\" "
            "(stable for any dt) or a smaller dt (with sliding: a larger grid.n or tangential.steps_per_cell)")
    ratio = problem.time.dt / problem.material.shortest_time
    if ratio > 1.0:
        warnings.warn(f"time.dt = {problem.time.dt:.3g} s is {ratio:.1f} x the shortest material time "
                      f"{problem.material.shortest_time:.3g} s: the transient is resolved coarsely "
                      "(reduce time.dt or raise grid.n when sliding)", ViscontactWarning, stacklevel=3)


def _gap(problem: Problem, offset: float) -> np.ndarray:
    """Undeformed gap with the indenter centre at x = offset [m] in the grid frame."""
    if offset == 0.0:
        return problem.gap
    x, y = problem.grid.mesh()
    return ((x - offset) ** 2 + y**2) / (2.0 * problem.radius)


def _history_traction(problem: Problem, coef: StepCoefficients, hist: PronyHistory | DirectHistory,
                      t: float) -> np.ndarray:
    if isinstance(hist, DirectHistory):
        return hist.traction(problem.material, t, problem.time.dt, coef.instantaneous)
    return hist.traction(problem.material, coef)


def _advance_history(hist: PronyHistory | DirectHistory, value: np.ndarray, coef: StepCoefficients,
                     t: float, first: bool, scheme: str) -> None:
    if isinstance(hist, DirectHistory):
        hist.advance(value, t, ramp=(not first and scheme == "linear"))
    else:
        hist.advance(value, coef)


def _elastic_operator(ops: Operators, kernel: str, j_inst: float) -> dict:
    """The step's elastic operator K = J_inst IC_kernel for :func:`constrained_cg`: its action, its
    Fourier preconditioner and its sparse action (for bound corrections)."""
    conv, precond = ops.conv, ops.preconditioners[kernel]
    return {"apply_k": lambda x: j_inst * conv.apply(kernel, x),
            "extra": {"preconditioner": lambda r: precond(r) / j_inst,
                      "apply_k_sparse": lambda x: j_inst * conv.apply_sparse(kernel, x)}}


def _solve_normal(problem: Problem, ops: Operators, j_inst: float, gap: np.ndarray,
                  known_uz: np.ndarray, warm: np.ndarray, value: float):
    """Polonsky-Keer solve of the normal problem with known displacement ``known_uz`` [m].

    Returns (pressure [Pa], approach delta_z [m], iterations, total u_z [m] at the solution)."""
    grid, s = problem.grid, problem.solver
    op = _elastic_operator(ops, "zz", j_inst)
    if problem.normal.control == "load":
        sol = constrained_cg(op["apply_k"], -(gap + known_uz), warm, 0.0, np.inf, total=value,
                             cell_area=grid.cell_area, tolerance=s.tolerance, max_iterations=s.max_iterations,
                             what="normal contact (load control)", **op["extra"])
        return sol.x, sol.multiplier, sol.iterations, sol.gradient + sol.multiplier - gap
    sol = constrained_cg(op["apply_k"], value - (gap + known_uz), warm, 0.0, np.inf, tolerance=s.tolerance,
                         max_iterations=s.max_iterations, what="normal contact (displacement control)", **op["extra"])
    return sol.x, value, sol.iterations, sol.gradient + value - gap


def _solve_tangential(problem: Problem, ops: Operators, j_inst: float, pressure: np.ndarray,
                      known_ux: np.ndarray, warm: np.ndarray, delta_x: float):
    """Bounded CG for q_x in [-mu p, mu p] with slip s = u_x - delta_x (seed Eqs. 9, 11)."""
    s = problem.solver
    bound = problem.tangential.friction_coefficient * pressure
    op = _elastic_operator(ops, "xx", j_inst)
    sol = constrained_cg(op["apply_k"], delta_x - known_ux, np.clip(warm, -bound, bound), -bound, bound,
                         tolerance=s.tolerance, max_iterations=s.max_iterations,
                         what="tangential contact (partial slip)", **op["extra"])
    return sol.x, sol.iterations


def _relative_change(new: np.ndarray, old: np.ndarray) -> float:
    scale = float(np.sum(np.abs(new)))
    return float(np.sum(np.abs(new - old))) / scale if scale > 0 else 0.0


def step(problem: Problem, ops: Operators, state: State) -> tuple[State, StepRecord]:
    """Advance ``state`` by one time step (in place) and return it with the step's record."""
    grid, tan, solver = problem.grid, problem.tangential, problem.solver
    k = state.step + 1
    t = k * problem.time.dt
    first = k == 0
    coef = ops.first if first else ops.regular
    j_inst = coef.instantaneous
    mu = tan.effective_friction

    # -- move the frame (gross sliding after the step at which it began)
    if state.phase == PHASE_GROSS_SLIDING and not first and state.t_gross_sliding is not None \
            and t > state.t_gross_sliding + 0.5 * problem.time.dt:
        state.sliding_distance += tan.sliding_speed * problem.time.dt
        state.delta_x += tan.sliding_speed * problem.time.dt
        state.substep += 1
        if state.substep == tan.steps_per_cell:
            state.substep = 0
            dropped = state.history_p.shift(1)
            state.history_q.shift(1)
            if dropped is not None and isinstance(state.history_p, PronyHistory):
                state.wake.drop(dropped)
        state.wake.tick(problem.material, problem.time.dt)
    elif state.phase == PHASE_PARTIAL_SLIP:
        state.delta_x = tan.displacement_rate * t
    offset = state.substep * grid.spacing / tan.steps_per_cell if tan.slides else 0.0
    gap = _gap(problem, offset)

    # -- known history displacements
    r_p = _history_traction(problem, coef, state.history_p, t)
    r_q = _history_traction(problem, coef, state.history_q, t)
    partial = state.phase == PHASE_PARTIAL_SLIP and mu > 0
    coupled = "zx" in ops.conv.spectra
    hist_uz, hist_ux = coupled_displacements(ops.conv, r_p, r_q if coupled or partial else None,
                                             need_x=partial)
    value = problem.normal.history(t)

    iterations = 0
    coupling_iterations = 0
    # warm start: linear extrapolation of the last two steps (frame fields), clipped by the solvers
    p = np.maximum(2.0 * state.pressure - state.pressure_previous, 0.0) if k > 1 else state.pressure
    q = 2.0 * state.shear_x - state.shear_previous if k > 1 else state.shear_x
    if state.phase == PHASE_PARTIAL_SLIP and mu > 0:
        for coupling_iterations in range(1, solver.max_coupling_iterations + 1):
            known_uz = hist_uz + (j_inst * ops.conv.apply("zx", q) if coupled else 0.0)
            p_new, delta_z, it_n, u_z = _solve_normal(problem, ops, j_inst, gap, known_uz, p, value)
            known_ux = hist_ux + (j_inst * ops.conv.apply("xz", p_new) if coupled else 0.0)
            q_new, it_t = _solve_tangential(problem, ops, j_inst, p_new, known_ux, q, state.delta_x)
            iterations += it_n + it_t
            change = max(_relative_change(p_new, p), _relative_change(q_new, q))
            p, q = p_new, q_new
            if change < solver.coupling_tolerance or not coupled:
                break
        else:
            raise ConvergenceError("normal/tangential coupling (partial slip)", solver.max_coupling_iterations,
                                   change, solver.coupling_tolerance, hint="raise solver.max_coupling_iterations")
    elif state.phase == PHASE_GROSS_SLIDING and mu > 0 and coupled:
        for coupling_iterations in range(1, solver.max_coupling_iterations + 1):
            known_uz = hist_uz + j_inst * mu * ops.conv.apply("zx", p)
            p_new, delta_z, it_n, u_z = _solve_normal(problem, ops, j_inst, gap, known_uz, p, value)
            iterations += it_n
            change = _relative_change(p_new, p)
            p = p_new
            if change < solver.coupling_tolerance:
                break
        else:
            raise ConvergenceError("normal/tangential coupling (gross sliding)", solver.max_coupling_iterations,
                                   change, solver.coupling_tolerance, hint="raise solver.max_coupling_iterations")
        q = mu * p
    else:
        p, delta_z, iterations, u_z = _solve_normal(problem, ops, j_inst, gap, hist_uz, p, value)
        coupling_iterations = 1
        q = mu * p if state.phase == PHASE_GROSS_SLIDING else np.zeros_like(p)

    # -- bookkeeping
    contact = p > 0
    n_contact = int(contact.sum())
    if state.phase == PHASE_PARTIAL_SLIP and mu > 0:
        stick = contact & (np.abs(q) < mu * p * (1 - STICK_MARGIN))
    else:
        stick = np.zeros_like(contact)
    stick_ratio = float(stick.sum()) / n_contact if n_contact else 0.0

    _advance_history(state.history_p, p, coef, t, first, problem.time.scheme)
    _advance_history(state.history_q, q, coef, t, first, problem.time.scheme)

    if state.phase == PHASE_PARTIAL_SLIP and mu > 0 and coupled:
        # the last tangential update changed the coupling term of u_z: recompute it
        u_z, _ = coupled_displacements(ops.conv, j_inst * p, j_inst * q, need_x=False)
        u_z += hist_uz
    phase_now = state.phase
    if state.phase == PHASE_PARTIAL_SLIP and (stick_ratio == 0.0 or mu == 0):
        phase_now = PHASE_GROSS_SLIDING
        state.t_gross_sliding = t
    state.phase = phase_now
    state.step, state.t = k, t
    state.pressure_previous, state.shear_previous = state.pressure, state.shear_x
    state.pressure, state.shear_x, state.delta_z = p, q, delta_z

    load = float(p.sum() * grid.cell_area)
    _guard(problem, p, load, value)
    f_t = hysteresis_force(p, u_z, grid) if tan.slides else 0.0
    wake = _wake_loss(problem, state, p, f_t / load if load > 0 else 0.0, float(delta_z))
    record = StepRecord(
        step=k, t=t, phase=phase_now, load=load, delta_z=float(delta_z), delta_x=state.delta_x,
        sliding_distance=state.sliding_distance, contact_area=n_contact * grid.cell_area,
        stick_ratio=stick_ratio, friction_force=float(q.sum() * grid.cell_area),
        hysteresis_force=f_t, mu_app=f_t / load if load > 0 else 0.0,
        contact_shift=pressure_centroid(p, grid) - offset, frame_offset=offset, wake_loss=wake,
        iterations=iterations, coupling_iterations=coupling_iterations,
        pressure=p, shear_x=q, stick=stick, displacement_z=u_z,
    )
    return state, record


def _wake_loss(problem: Problem, state: State, pressure: np.ndarray, mu_app: float, delta_z: float) -> float:
    """Estimated relative error of the result from the history dropped at the trailing edge:
    |d mu_app| / |mu_app| from the slope of the lost displacement, and under displacement control
    also the load error 3/2 u_lost / delta_z (W ~ delta^(3/2) for a sphere)."""
    if not state.wake.strips:
        return 0.0
    u_lost, slope = state.wake.lost_displacement(problem.material, problem.grid, problem.time.dt, pressure)
    err = abs(slope) / max(abs(mu_app), 1e-3)
    if problem.normal.control == "displacement" and delta_z > 0:
        err = max(err, 1.5 * abs(u_lost) / delta_z)
    return float(err)


def _guard(problem: Problem, pressure: np.ndarray, load: float, value: float) -> None:
    """Errors for results that cannot be trusted: NaN, contact at the domain edge, load imbalance."""
    if not np.all(np.isfinite(pressure)):
        raise NumericalGuardError("pressure has NaN or Inf values; check the inputs (material, load, grid)")
    edge = np.concatenate([pressure[0], pressure[-1], pressure[:, 0], pressure[:, -1]])
    peak = pressure.max()
    if peak > 0 and edge.max() > 1e-6 * peak:
        grid = problem.grid
        x, y = grid.mesh()
        r = np.sqrt(x**2 + y**2)[pressure > 1e-6 * peak].max()
        raise NumericalGuardError(
            f"the contact reaches the edge of the domain (pressure {edge.max() / peak:.1e} of its peak there); "
            f"enlarge grid.half_width to at least {1.5 * r:.4g} m (now {grid.half_width:.4g} m)")
    if problem.normal.control == "load" and value > 0 and abs(load - value) > 1e-6 * value:
        raise NumericalGuardError(f"load balance violated: sum p dA = {load:.6g} N for W = {value:.6g} N")


def steps(problem: Problem, *, progress: Callable[[int, int], None] | None = None,
          state: State | None = None, ops: Operators | None = None) -> Iterator[tuple[State, StepRecord, bool]]:
    """Run the transient one step at a time: yields (state after the step, its record, whether the
    output settings record it). Stopping the iteration between two steps leaves a consistent state
    (what checkpoints and interruptions rely on). Fields not in ``output.fields`` are dropped from
    the records.
    """
    ops = ops or operators(problem)
    state = state or init(problem)
    total = problem.time.n_steps
    every = problem.output.every
    dropped = {name: None for name in StepRecord.FIELDS if name not in problem.output.fields}
    warned = False
    while state.step + 1 < total:
        state, record = step(problem, ops, state)
        if not warned and record.wake_loss > WAKE_WARNING:
            warned = True
            warnings.warn(
                f"history dropped at the trailing edge biases the result by about {100 * record.wake_loss:.2g}% "
                f"(t = {record.t:.4g} s); enlarge grid.half_width (with grid.n) or use `viscontact steady`",
                ViscontactWarning, stacklevel=2)
        if progress is not None:
            progress(state.step + 1, total)
        recorded = state.step % every == 0 or state.step + 1 == total
        yield state, (replace(record, **dropped) if dropped else record), recorded


def simulate(problem: Problem, *, progress: Callable[[int, int], None] | None = None,
             state: State | None = None, ops: Operators | None = None) -> Iterator[StepRecord]:
    """Run the transient and yield a record every ``output.every`` steps and at the last step.

    Parameters
    ----------
    problem
        What to solve.
    progress
        Called as ``progress(steps_done, steps_total)`` after each step.
    state, ops
        Resume from a state (e.g. a checkpoint) / reuse operators.
    """
    for _, record, recorded in steps(problem, progress=progress, state=state, ops=ops):
        if recorded:
            yield record
