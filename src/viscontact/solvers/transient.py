"""Transient solver: indentation, partial slip and gross sliding (seed Sec. 2.2, Fig. 3).

Each time step is an elastic contact problem with the instantaneous compliance J_inst plus the
known hereditary displacement of all earlier increments (:mod:`viscontact.numerics.history`):

* normal (seed Eqs. 7-8, 10): Polonsky-Keer constrained CG under load or displacement control;
* partial slip (seed Eqs. 9, 11): bounded CG for q_x in [-mu_f p, mu_f p], alternated with the
  normal solve (semi-coupled: IC_zx, IC_xz ~ (1 - 2 nu)) until both change by less than
  ``coupling_tolerance``; the stick condition on the total slip (the seed's, s_x = 0) or, with
  ``tangential.slip = "incremental"``, on its change over the step (Mindlin-Deresiewicz: the state
  carries s_x, :attr:`State.slip_x`);
* gross sliding (seed Eq. 12): q_x = mu_f p, so u_z = J_inst (IC_zz + mu_f IC_zx) p + history. The
  operator is not symmetric; the coupling term is iterated as a fixed point around symmetric
  Polonsky-Keer solves (contraction factor about mu_f (1 - 2 nu) / (2 (1 - nu)) < 0.1 for the
  seed's case), each warm-started.

Each of these is a contact law, chosen by name from the problem and the phase
(:mod:`viscontact.solvers.contact_laws`) and iterated over the coupling by
:func:`viscontact.solvers.coupling.solve_coupled`; the solved state is measured into the step's record by
:func:`viscontact.solvers.measure.measure`.

State is explicit: :func:`init` builds it, :func:`step` advances it by one time step and returns
the step's :class:`~viscontact.problem.records.StepRecord`; :func:`simulate` loops and yields the records
the output settings ask for.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Callable, Generator

import numpy as np

from viscontact.bodies.compliance import Compliance, compliance_of
from viscontact.errors import ParameterError
from viscontact.numerics.adhesive import NoEquilibriumError
from viscontact.numerics.allocator import tune_allocator
from viscontact.numerics.history import History
from viscontact.numerics.schemes import stable_step_limit
from viscontact.physics.periodic import check_approach
from viscontact.problem.problem import PHASE_GROSS_SLIDING, PHASE_PARTIAL_SLIP, PHASE_ROLLING, FrameGaps, Problem
from viscontact.problem.records import StepRecord
from viscontact.solvers import adhesive_law  # noqa: F401 (registers the adhesive law)
from viscontact.solvers.contact_laws import (
    StepContext,
    contact_law,
    first_phase,
)
from viscontact.solvers.coupling import solve_coupled
from viscontact.solvers.measure import measure
from viscontact.solvers.rolling import convected, rigid_step, step_creepage
from viscontact.solvers.sliding import Wake


@dataclass(frozen=True)
class State:
    """Everything that carries over from one step to the next (checkpointable, never mutated:
    :func:`step` returns a new one).

    Attributes
    ----------
    step, t
        Index and time [s] of the last step done (-1 and -dt before the first).
    phase
        Phase code of the next step (:mod:`viscontact.problem.problem`).
    pressure, shear_x, pressure_previous, shear_previous
        Tractions [Pa] of the last two steps (frame fields; the warm start extrapolates them).
    histories
        Hereditary histories by key (:class:`~viscontact.bodies.compliance.Term`).
    delta_z, delta_x, sliding_distance
        Approach, tangential displacement and distance slid [m].
    pressure_product, pressure_product_previous
        The normal elastic operator of a regular step applied to ``pressure`` and to
        ``pressure_previous`` [m] (J_inst K p, from the full-domain check of the step's solve; None
        where that solve had none or the step was the first): with them the warm start's product
        costs no transform (:func:`_warm_start`).
    response
        The normal history in displacement space, which gives the history displacement without a
        transform (:meth:`~viscontact.bodies.compliance.Compliance.initial_response`); None where the
        compliance has none, from the first frame shift on, and from the first partial-slip step on.
    substep
        Steps since the last frame shift (0 .. steps_per_cell - 1).
    t_gross_sliding
        When gross sliding began [s] (None before).
    slip_origin
        Partial slip: ``delta_x`` [m] at the first step of the current contact, from which the
        displacement of the stuck points is measured; None after a step without contact (the
        indenter moves at ``displacement_rate`` without touching, which loads nothing): the next
        step that touches sets it. 0 before the first step (delta_x(0) = 0; also what a checkpoint
        written without it resumes with). Read by the total slip only: the incremental one's
        ``slip_x`` holds s_x = -delta_x at every point before the first contact, so the points
        that touch first stick where they are without an origin.
    slip_x
        Incremental slip (``tangential.slip = "incremental"``) during partial slip: the slip
        s_x = u_x - delta_x [m] at the end of the last step at every point of the grid (a frame
        field; in contact or not: a point entering the contact sticks at its own), which a stuck
        point keeps; zeros before the first step, None with the total slip and from gross sliding on.
    wake
        History that left the frame (:class:`~viscontact.solvers.sliding.Wake`).
    interaction
        With adhesion: the last step's interaction zone (contact and cohesive zone, boolean; the warm
        start of the next: :mod:`viscontact.solvers.adhesive_law`), else None.
    most_tensile_load, t_most_tensile
        With adhesion: the most tensile load of the steps done [N] (0 until one is tensile) and its
        time [s] (NaN until then).
    t_pull_off
        Under load control with adhesion: the time [s] of the first step no equilibrium carried (the
        pull-off, which ends the run: :func:`steps`); else None.
    displacement_x
        Rolling with friction: the total u_x [m] at the end of the last step at every point of the grid
        (a frame field; convected by a cell as the frame moves: :mod:`viscontact.solvers.rolling`);
        zeros before the first step, None in the other modes.
    rigid_x
        Rolling: the last step's rigid tangential displacement [m] (-creepage x dx; under a held
        force the start of the next step's root find), 0 before the first.
    """

    step: int
    t: float
    phase: int
    pressure: np.ndarray
    shear_x: np.ndarray
    histories: dict[str, History]
    delta_z: float = 0.0
    delta_x: float = 0.0
    sliding_distance: float = 0.0
    substep: int = 0
    t_gross_sliding: float | None = None
    wake: Wake = field(default_factory=Wake)
    pressure_previous: np.ndarray | None = None
    shear_previous: np.ndarray | None = None
    pressure_product: np.ndarray | None = None
    pressure_product_previous: np.ndarray | None = None
    response: History | None = None
    slip_origin: float | None = 0.0
    slip_x: np.ndarray | None = None
    interaction: np.ndarray | None = None
    most_tensile_load: float = 0.0
    t_most_tensile: float = float("nan")
    t_pull_off: float | None = None
    displacement_x: np.ndarray | None = None
    rigid_x: float = 0.0


def init(problem: Problem, compliance: Compliance | None = None) -> State:
    """State before the first step (t = 0 is solved by the first call of :func:`step`)."""
    validate(problem)
    compliance = compliance or compliance_of(problem)
    shape, xp = problem.grid.shape, compliance.xp
    phase = first_phase(problem.tangential)
    return State(step=-1, t=-problem.time.dt, phase=phase, pressure=xp.zeros(shape),
                 shear_x=xp.zeros(shape), histories=compliance.initial_histories(),
                 pressure_previous=xp.zeros(shape), shear_previous=xp.zeros(shape),
                 t_gross_sliding=0.0 if phase == PHASE_GROSS_SLIDING else None,
                 response=compliance.initial_response(),
                 slip_x=xp.zeros(shape) if problem.tangential.incremental_slip else None,
                 displacement_x=xp.zeros(shape) if problem.tangential.rolls and
                 problem.tangential.effective_friction > 0 else None)


def validate(problem: Problem) -> None:
    """Checks that involve several parts of the problem (each part validated itself)."""
    tan = problem.tangential
    if tan.frame_moves:
        if not tan.sliding_speed > 0:
            raise ParameterError("tangential.sliding_speed", f"must be > 0 m/s when sliding, got {tan.sliding_speed}")
        cell_dt = problem.sliding_dt
        if abs(problem.time.dt - cell_dt) > 1e-6 * cell_dt:
            raise ParameterError(
                "time.dt", f"must equal (2*half_width/n)/sliding_speed/steps_per_cell = {cell_dt:.6g} s "
                f"so that the frame moves by whole cells, got {problem.time.dt:.6g}")
    if problem.grid.periodic and problem.normal.control == "displacement":
        check_approach(problem.normal.history.reference, problem.gap,
                       "normal.value" if len(problem.normal.history.values) == 1 else "normal.history")
    if tan.displacement_history is not None and tan.sliding_speed != 0:
        raise ParameterError("tangential.sliding_speed", "give none with tangential.displacement_history: the "
                             "indenter never slides under a history (a vanished stick zone stops the run), got "
                             f"{tan.sliding_speed:g} m/s")
    if tan.tangential_force is not None and problem.normal.control == "load":
        limit = tan.friction_coefficient * min(problem.normal.history.values)
        if not abs(tan.tangential_force) < limit:
            raise ParameterError("tangential.tangential_force", f"|{tan.tangential_force:g}| N must be below mu_f W = "
                                 f"{limit:g} N (the smallest load of the run): the contact would slide, not roll")
    if tan.mode == "partial_slip" and tan.displacement_history is None and not tan.displacement_rate > 0:
        raise ParameterError("tangential.displacement_rate", f"must be > 0 m/s for partial_slip, got {tan.displacement_rate}")
    limit = min(stable_step_limit(r, problem.time.scheme) for r in problem.body.stability_responses())
    if problem.time.dt > limit:
        raise ParameterError(
            "time.dt", f"{problem.time.dt:.4g} s exceeds the stability limit {limit:.4g} s of the piecewise-constant "
            "(seed) scheme for this material: the result would oscillate and grow. Use time.scheme = \"linear\" "
            "(stable for any dt) or a smaller dt (with sliding: a larger grid.n or tangential.steps_per_cell)")
    # the accuracy of dt (against the material times and the loading) is checked by viscontact.running.guards


# --- one step: frame -> known displacement -> contact law -> commit -> record -------------------

def gross_slip_under_history(t: float, delta_x: float, force: float, load: float, mu: float) -> ParameterError:
    """The error that stops partial slip under ``tangential.displacement_history`` at the step ``t`` [s]
    whose contact has no stuck point left: the amplitude of delta_x [m] exceeds gross slip (the
    friction force ``force`` [N] has reached mu_f times the ``load`` [N]). The indenter does not slide
    on (nor back): the steps before are kept."""
    return ParameterError(
        "tangential.displacement_history", f"the stick zone vanished at t = {t:.6g} s (delta_x = {delta_x:.6g} m, "
        f"Q / (mu_f W) = {force / (mu * load) if load > 0 else float('nan'):.3g}): the amplitude exceeds gross slip, "
        "and a displacement history does not slide on; lower its amplitude, or use tangential.displacement_rate "
        "(a ramp into gross sliding)")


#: clipped points of the extrapolated warm start whose product is added by direct sums (fewer where the
#: operator's direct sums stop paying earlier: its ``sparse_limit``); more: one product of the warm
#: start instead (:func:`_warm_start`)
WARM_CLIP_POINTS = 24


def _warm_start(compliance: Compliance, state: State, k: int) -> tuple[np.ndarray, np.ndarray | None]:
    """The warm start of step ``k``'s pressure [Pa]: the linear extrapolation of the last two steps
    (frame fields) clipped at 0, or the last pressure at k <= 1; and the step's normal operator
    applied to it [m] where the state's products give it (J_inst K is linear: 2 K p_-1 - K p_-2, plus
    the direct sums of the clipped points, at most :data:`WARM_CLIP_POINTS` and the operator's
    ``sparse_limit``), else None."""
    if k <= 1:
        return state.pressure, None
    linear = 2.0 * state.pressure - state.pressure_previous
    warm = np.maximum(linear, 0.0)
    if state.pressure_product is None or state.pressure_product_previous is None:
        return warm, None
    clipped = np.subtract(warm, linear, out=linear)
    points = np.count_nonzero(clipped)
    op = compliance.elastic_operator("z", False)
    if points > min(WARM_CLIP_POINTS, op.sparse_limit):
        return warm, None
    product = 2.0 * state.pressure_product - state.pressure_product_previous
    if points:
        product += op.apply_sparse(clipped)
    return warm, product


def _advance_frame(problem: Problem, compliance: Compliance, state: State, k: int, t: float) -> State:
    """The state with the frame moved (gross sliding after the step at which it began, and rolling
    after the first step: v dt per step, the history shifted by a cell every steps_per_cell steps,
    rolling's u_x convected with it) or delta_x ramped or following its history (partial slip)."""
    tan, dt = problem.tangential, problem.time.dt
    sliding = (state.phase == PHASE_GROSS_SLIDING and state.t_gross_sliding is not None
               and t > state.t_gross_sliding + 0.5 * dt)
    if k > 0 and (sliding or state.phase == PHASE_ROLLING):
        histories, wake, substep = state.histories, state.wake, state.substep + 1
        displacement_x = state.displacement_x
        if substep == tan.steps_per_cell:
            substep = 0
            histories, dropped = compliance.shifted(histories, 1)
            if displacement_x is not None:
                displacement_x = convected(displacement_x, problem.grid.periodic)
            if compliance.normal_history in dropped:
                wake = wake.dropped(dropped[compliance.normal_history])
        wake = wake.ticked(compliance.responses[compliance.normal_history], dt)
        return replace(state, sliding_distance=state.sliding_distance + tan.sliding_speed * dt,
                       delta_x=state.delta_x + tan.sliding_speed * dt, substep=substep, histories=histories,
                       wake=wake, response=state.response if histories is state.histories else None,
                       displacement_x=displacement_x)
    if state.phase == PHASE_PARTIAL_SLIP:
        return replace(state, delta_x=tan.delta_x(t))
    return state


def step(problem: Problem, compliance: Compliance, state: State,
         frame_gaps: FrameGaps | None = None) -> tuple[State, StepRecord]:
    """Advance ``state`` by one time step; returns the new state and the step's record (``state``
    itself is left as it was). ``frame_gaps``: the gap's arrays on the compliance's device
    (:meth:`~viscontact.problem.problem.Problem.frame_gaps`; :func:`steps` moves them there once), else moved
    for this step."""
    grid, tan = problem.grid, problem.tangential
    k = state.step + 1
    t = k * problem.time.dt
    first = k == 0
    mu = tan.effective_friction

    state = _advance_frame(problem, compliance, state, k, t)
    offset = state.substep * grid.spacing / tan.steps_per_cell if tan.slides else 0.0
    law = contact_law(problem, compliance, state.phase)
    if law.solves_shear and state.response is not None:
        # partial slip needs u_x of the traction history anyway, and ends in sliding, whose first
        # frame shift would drop the response history: it is not kept up
        state = replace(state, response=None)
    if state.response is not None:
        known_uz, known_ux = compliance.known_from_response(state.response, t, first), None
    else:
        known_uz, known_ux = compliance.known_displacement(state.histories, t, first, need_x=law.solves_shear)
    # on the host, for the record; rolling on a rough surface: its roughness carried k steps on
    gap = problem.rolling_gap(k) if problem.rolls_rough else problem.frame_gap(offset)
    backend = compliance.backend
    if backend.is_cpu:
        device_gap = gap
    elif problem.rolls_rough:
        device_gap = backend.to_device(gap)
    else:
        device_gap = (frame_gaps or problem.frame_gaps(backend.to_device)).at(offset)
    # partial slip, total slip: the stuck points move with the indenter since the contact began (this
    # step, when the last one had none); incremental slip: they keep the slip of the last step
    origin = state.delta_x if state.slip_origin is None else state.slip_origin
    incremental = law.solves_shear and state.slip_x is not None
    rolling = state.displacement_x is not None
    if rolling:  # rolling with friction: the last step's u_x convected, and the step's rigid creep
        reference_x = rigid_step(problem, k) if tan.creepage is not None else state.rigid_x
        reference_slip = state.displacement_x
    elif incremental:
        reference_x, reference_slip = state.delta_x, state.slip_x
    else:
        reference_x, reference_slip = state.delta_x - origin, None
    ctx = StepContext(problem, compliance, k, t, first, device_gap, known_uz, known_ux,
                      problem.normal.history(t), reference_x, reference_slip, state.interaction)
    adhesive = problem.adhesion is not None
    # adhesion: the last pressure (its tensions kept: the extrapolation is clipped at 0), its product and zone
    p0, p0_product = (state.pressure, state.pressure_product) if adhesive else _warm_start(compliance, state, k)
    q0 = 2.0 * state.shear_x - state.shear_previous if k > 1 else state.shear_x
    sol = solve_coupled(law, ctx, p0, q0, p0_product)
    p, q = sol.pressure, sol.shear_x
    # what the record keeps, on the host (the same arrays on the CPU: :mod:`viscontact.numerics.arrays`)
    to_host = backend.to_host
    p_host, q_host, u_z = to_host(p), to_host(q), to_host(sol.displacement_z)

    n_contact = int((p_host > 0).sum())
    stick = law.stuck(p_host, q_host)

    # -- commit: gross sliding begins when the stick zone of a contact vanishes (no contact: the phase
    # stays; once sliding, it stays)
    phase, t_gross = state.phase, state.t_gross_sliding
    if phase == PHASE_PARTIAL_SLIP and n_contact and (not stick.any() or mu == 0):
        if tan.displacement_history is not None:
            raise gross_slip_under_history(t, state.delta_x, float(q_host.sum() * grid.cell_area),
                                           float(p_host.sum() * grid.cell_area), mu)
        phase, t_gross = PHASE_GROSS_SLIDING, t
    slip_x = None
    if incremental and phase == PHASE_PARTIAL_SLIP:
        # s_x at the end of the step: a stuck point keeps the last step's exactly (its change is zero
        # to the solve's tolerance), the others add the change the solve found
        slip_x = np.where(law.stuck(p, q), state.slip_x, state.slip_x + sol.slip)
    rigid_x = ctx.delta_x if sol.delta_x is None else sol.delta_x
    if rolling:  # the total u_x: the reference, the rigid displacement and the slip s dt
        state = replace(state, displacement_x=ctx.slip_x + rigid_x + sol.slip, rigid_x=rigid_x)
    state = replace(state, step=k, t=t, phase=phase, t_gross_sliding=t_gross,
                    slip_origin=origin if n_contact else None, slip_x=slip_x,
                    histories=compliance.advanced(state.histories, {"z": p, "x": q}, t, first),
                    pressure_previous=state.pressure, shear_previous=state.shear_x,
                    pressure=p, shear_x=q, delta_z=sol.delta_z,
                    pressure_product_previous=state.pressure_product,
                    pressure_product=None if first else sol.pressure_product,
                    response=None if state.response is None else
                    compliance.advanced_response(state.response, p, sol.pressure_product, t, first))
    interaction = None if sol.interaction is None else to_host(sol.interaction)

    # -- record
    record = measure(problem, p_host, q_host, u_z, delta_z=sol.delta_z, value=ctx.value, gap=gap, step=k, t=t,
                     phase=phase, stick=stick, slides=tan.slides, delta_x=state.delta_x,
                     sliding_distance=state.sliding_distance, frame_offset=offset, iterations=sol.iterations,
                     coupling_iterations=sol.coupling_iterations, interaction=interaction)
    if adhesive:
        state = replace(state, interaction=sol.interaction)
        if record.load < state.most_tensile_load:
            state = replace(state, most_tensile_load=record.load, t_most_tensile=t)
    if tan.rolls:
        record = replace(record, creepage=step_creepage(problem, k, rigid_x))
    return state, replace(record, wake_loss=_wake_loss(problem, compliance, state, p_host, record.mu_app, sol.delta_z))


def _wake_loss(problem: Problem, compliance: Compliance, state: State, pressure: np.ndarray, mu_app: float,
               delta_z: float) -> float:
    """Estimated relative error of the result from the history dropped at the trailing edge:
    |d mu_app| / |mu_app| from the slope of the lost displacement, and under displacement control
    also the load error 3/2 u_lost / delta_z (W ~ delta^(3/2) for a sphere)."""
    if not state.wake.strips:
        return 0.0
    u_lost, slope = state.wake.lost_displacement(compliance.responses[compliance.normal_history],
                                                 problem.material.poisson_ratio, problem.grid, problem.time.dt,
                                                 pressure)
    err = abs(slope) / max(abs(mu_app), 1e-3)
    if problem.normal.control == "displacement" and delta_z > 0:
        err = max(err, 1.5 * abs(u_lost) / delta_z)
    return float(err)


def steps(problem: Problem, *, progress: Callable[[int, int], None] | None = None,
          state: State | None = None, compliance: Compliance | None = None
          ) -> Generator[tuple[State, StepRecord], None, State | None]:
    """Run the transient one step at a time: yields (state after the step, its full record).

    Stopping the iteration between two steps leaves a consistent state (what checkpoints and
    interruptions rely on); what is kept, warned or saved is up to the caller's observers
    (:mod:`viscontact.running.observers`). With adhesion under load control, a step that no
    equilibrium carries (:class:`~viscontact.numerics.adhesive.NoEquilibriumError`: the indenter comes
    off) ends the run: the generator returns the last equilibrium's state with
    :attr:`State.t_pull_off` set (the value of its ``StopIteration``; None when the run went to its end).
    The first call sets the C allocator for the solver's temporaries
    (:func:`viscontact.numerics.allocator.tune_allocator`).

    Parameters
    ----------
    problem
        What to solve.
    progress
        Called as ``progress(steps_done, steps_total)`` after each step.
    state, compliance
        Resume from a state (e.g. a checkpoint) / reuse a compliance.
    """
    tune_allocator()  # reuse freed temporaries instead of faulting them in again (glibc; opt-out documented)
    compliance = compliance or compliance_of(problem)
    state = state or init(problem, compliance)
    total = problem.time.n_steps
    # the gap on the compliance's device, moved there once (each step shifts it there)
    frame_gaps = None if compliance.backend.is_cpu else problem.frame_gaps(compliance.backend.to_device)
    while state.step + 1 < total:
        try:
            state, record = step(problem, compliance, state, frame_gaps)
        except NoEquilibriumError:
            if problem.adhesion is None:
                raise
            return replace(state, t_pull_off=(state.step + 1) * problem.time.dt)
        if progress is not None:
            progress(state.step + 1, total)
        yield state, record
