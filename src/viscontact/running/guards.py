"""Physical validity of a problem, checked before it is solved: can its answer be trusted?

Every check compares the discretisation with an estimate of the solution it must resolve, from
closed-form contact mechanics and from the time scheme applied to one point:

* **contact size** -- Hertz (Johnson, *Contact Mechanics*, Sec. 4.2) with the instantaneous and the
  long-term shear modulus: under load control the contact radius of a viscoelastic sphere creeps
  from a(G(0)) towards a(G(inf)) = a(G(0)) (G(0)/G(inf))^(1/3) as a^3 ~ int J(t - s) dW(s) (Lee &
  Radok 1960), for as long as the run lasts or, when sliding, a material point stays under the
  contact; under displacement control it is a = sqrt(R delta) whatever the modulus (a coarse grid
  there used to give zero load and zero contact). R is the sphere radius, or for a height file the
  equivalent radius of the gap, fitted about its lowest point (no estimate where no curvature defines
  that point: a plane, a cylinder's line, a flat punch's face; :func:`viscontact.problem.scales.equivalent_radius`).
* **resolution** -- cells across the smallest contact radius: on the cell-centred grid the node
  nearest the centre of the contact may lie dx/sqrt(2) from it, where the Hertz pressure is
  sqrt(1 - dx^2/(2 a^2)) of its peak (:func:`peak_pressure_error`; measured peak errors of the
  elastic Hertz case: 3.9 %, 2.6 %, 1.5 %, 0.6 % at a/dx = 2, 3, 4, 6 against 6.5 %, 2.8 %, 1.6 %,
  0.7 % estimated).
* **domain** -- the largest contact must fit in the domain with :data:`EDGE_CELLS` cells to spare.
* **small strain** -- the half-space and the paraboloidal gap are small-strain, small-slope
  approximations; the largest strain is about p0/E* = 2a/(pi R) (Hertz), so a/R above
  :data:`RADIUS_RATIO_ERROR` cannot be trusted and above :data:`RADIUS_RATIO_WARNING` is marginal.
* **time step** -- the time scheme (:mod:`viscontact.numerics.schemes`, :mod:`viscontact.numerics.history`) is run on
  one point of a contact whose area does not change: under displacement control the traction
  responds to the approach history delta(t) through the relaxation modulus G(t); under load control the displacement
  responds to the load history W(t) through the creep compliance J(t). Both are compared with the
  exact hereditary integrals of the piecewise-linear history (seed Eq. 5 with dt -> 0). This
  compares dt with the relaxation and retardation times and with the time scale of the loading.

An estimated error above the error limit raises :class:`~viscontact.errors.ParameterError` (the
answer cannot be trusted); above the warning limit a :class:`~viscontact.errors.ViscontactWarning`
gives the estimate. The limits are module constants.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from viscontact.errors import ParameterError, warn_caller
from viscontact.numerics.history import PronyHistory
from viscontact.numerics.schemes import stable_step_limit, step_coefficients
from viscontact.physics.materials import Material
from viscontact.problem.problem import PiecewiseLinear, Problem, is_number

__all__ = ["ContactEstimate", "check_material", "check_problem", "contact_estimate",
           "flat_face_cells", "flat_face_grid", "grid_suggestion", "peak_pressure_error", "time_step_error"]

#: estimated relative errors of the peak pressure above which a run is refused / warned about
ERROR_LIMIT, WARNING_LIMIT = 0.10, 0.05
#: the same for the one-point estimate of the time discretisation (:func:`time_step_error`). It
#: bounds the local pressure error of the transient (measured on the creep case at n = 64: estimate
#: 13.8 %, 3.1 %, 1.6 % against 16 %, 1 %, 1 % for constant dt = 1 ms, 0.25 ms and linear dt = 1 ms);
#: integral quantities (load, approach) are far more accurate (2e-4 under a held load).
TIME_ERROR_LIMIT, TIME_WARNING_LIMIT = 0.20, 0.07
#: cells kept between the largest contact (an upper bound: creep under a held load) and the edge
EDGE_CELLS = 1
#: contact radius / sphere radius: refused above, warned about above (strain ~ 2a/(pi R))
RADIUS_RATIO_ERROR, RADIUS_RATIO_WARNING = 0.5, 0.2
#: largest G(0)/G(inf) [-]: J_inst = J(inf) - sum_m J_m beta_m (viscontact.numerics.schemes) loses
#: log10(G(0)/G(inf)) of the 16 digits of float64; above 1e8 it is not known to the solver tolerance
MAX_MODULUS_RATIO = 1e8
#: shortfall of the last step's time under time.t_end, as a fraction of t_end, above which a run warns
END_SHORTFALL = 0.01
#: fraction of a history's largest absolute value (the displacement history's |delta_x|, the normal
#: history's load or approach) by which the time steps may miss one of its turning points
#: (:func:`turning_point_miss`); refused above
TURNING_POINT_MISS = 0.01
#: cells per side below which ``solver.device = "gpu"`` warns: its transforms are bound by their
#: launches there (seed Table 1 at 256^2 through the command line: 23.8 s on an H200 against 11.0 s
#: on its host's 16 cores; at 1024^2 the GPU steps 5.4 times as fast: BENCHMARKS.md)
GPU_SMALL_GRID = 512
#: the time-step check runs the scheme over at most this many steps (the response has settled by then
#: or the estimate is taken over the first part of the run)
MAX_CHECKED_STEPS = 4000


@dataclass(frozen=True)
class ContactEstimate:
    """Contact radii of a problem [m]: ``smallest`` (load control: Hertz with G(0)), ``largest``
    (after creeping, at most Hertz with G(inf)); ``sphere_radius`` R [m] of the (equivalent) sphere."""

    smallest: float
    largest: float
    sphere_radius: float


def contact_estimate(problem: Problem, *, transient: bool = True) -> ContactEstimate | None:
    """Hertz estimate of the contact radius at the largest load (or approach) of the run; None when
    the indenter has no curvature to estimate it from (a flat punch, whose contact is its face at any
    load; a cylinder; :func:`viscontact.problem.scales.equivalent_radius`), and for a surface other
    than a sphere on a periodic grid (a rough period): its load spreads over many asperities, so
    the one at the lowest point carrying it all is no estimate of the contact, and a period has no
    edge for a contact to reach.

    Under load control the radius creeps (Lee & Radok: a^3 ~ int J(t - s) dW(s)) for as long as a
    material point stays loaded: the run's duration, or when sliding at most 2 a(G(inf)) / v (the
    time to cross the widest contact; the steady state: that time). ``largest`` is the radius after
    that time, at most the Hertz radius with G(inf).
    """
    from viscontact.problem.scales import equivalent_radius

    if problem.grid.periodic and problem.radius is None:
        return None
    radius = problem.radius if problem.radius is not None else equivalent_radius(problem)
    reference = problem.normal.history.reference
    if not (np.isfinite(radius) and radius > 0 and reference > 0):
        return None
    mat = problem.material
    if problem.normal.control == "displacement":
        a = math.sqrt(radius * reference)
        return ContactEstimate(a, a, radius)
    e_star = 2.0 * mat.shear_modulus_instantaneous / (1.0 - mat.poisson_ratio)
    smallest = (3.0 * reference * radius / (4.0 * e_star)) ** (1.0 / 3.0)
    long_term = smallest * (mat.shear_modulus_instantaneous / mat.shear_modulus_long_term) ** (1.0 / 3.0)
    tan = problem.tangential
    duration = problem.time.t_end if transient else math.inf
    if tan.mode in ("frictionless_sliding", "gross_sliding") or (not transient and tan.sliding_speed > 0):
        duration = min(duration, 2.0 * long_term / tan.sliding_speed)
    return ContactEstimate(smallest, smallest * _creep_ratio(problem, duration) ** (1.0 / 3.0), radius)


def _creep_ratio(problem: Problem, duration: float) -> float:
    """max over 0 <= t <= duration of int J(t - s) dW(s) / (J(0) max W) [-] (1 for an elastic
    material, G(0)/G(inf) for a held load after a long time)."""
    mat = problem.material
    if mat.is_elastic or not math.isfinite(duration):
        return mat.shear_modulus_instantaneous / mat.shear_modulus_long_term
    creep = mat.creep
    t = np.linspace(0.0, duration, 1001)
    load = np.interp(t, problem.normal.history.times, problem.normal.history.values)  # history(t) at every t
    compliance = hereditary_integral(creep.long_term, -creep.amplitudes, creep.retardation_times, load, t[1] - t[0])
    return float(np.max(compliance) / (creep.instantaneous * problem.normal.history.reference))


def peak_pressure_error(cells_per_radius: float) -> float:
    """Estimated relative error [-] of the peak pressure with ``a / dx`` cells across the contact
    radius: 1 - sqrt(1 - 1/(2 (a/dx)^2)), the Hertz pressure dx/sqrt(2) from the centre."""
    return 1.0 - math.sqrt(max(1.0 - 0.5 / max(cells_per_radius, 1e-12) ** 2, 0.0))


def _grid_problems(est: ContactEstimate, n: int, half_width: float) -> list[tuple[str, str]]:
    """(key, message) for every way an n x n grid on +-half_width fails to resolve or hold ``est``."""
    dx = 2.0 * half_width / n
    found = []
    cells = est.smallest / dx
    if peak_pressure_error(cells) > ERROR_LIMIT:
        found.append(("grid.n", f"{n} cells of {dx:.3g} m resolve the contact radius {est.smallest:.3g} m "
                      f"with {cells:.2g} cells: the peak pressure would be off by about "
                      f"{100 * peak_pressure_error(cells):.0f} %"))
    if est.largest > half_width - EDGE_CELLS * dx:
        found.append(("grid.half_width", f"the contact radius reaches about {est.largest:.3g} m (Hertz, "
                      f"Lee & Radok creep): half_width = {half_width:.4g} m does not hold it with "
                      f"{EDGE_CELLS} cell{'s' if EDGE_CELLS > 1 else ''} to spare"))
    return found


def grid_suggestion(est: ContactEstimate, n: int, half_width: float) -> tuple[int, float]:
    """The smallest change of (n, half_width) that holds and resolves ``est`` (checked to pass)."""
    from viscontact.io.case import MAX_GRID_N

    if est.largest > half_width - EDGE_CELLS * 2.0 * half_width / n and 1.5 * est.largest > half_width:
        scale = 10.0 ** (math.floor(math.log10(1.5 * est.largest)) - 1)
        half_width = math.ceil(1.5 * est.largest / scale) * scale  # 1.5 a, rounded up to two digits
    cells_needed = 1.05 * math.sqrt(0.5 / (1.0 - (1.0 - WARNING_LIMIT) ** 2))  # 5 % margin under the warning
    n_needed = max(n, math.ceil(min(2.0 * half_width * cells_needed / est.smallest, 2.0 * MAX_GRID_N)))
    n = min(2 ** math.ceil(math.log2(n_needed)), MAX_GRID_N) if n_needed > n else n
    while _grid_problems(est, n, half_width) and n < MAX_GRID_N:
        n = min(2 * n, MAX_GRID_N)
    return n, half_width


def _normal_key(problem: Problem) -> str:
    return "normal.value" if len(problem.normal.history.times) == 1 else "normal.history"


#: measured load error of a flat circular punch per cell of dx/a: W / (2 a E* delta) - 1 = -0.12 dx/a
#: (tests/validation/test_flat_punch.py: -1.54 %, -0.75 %, -0.36 % at a/dx = 8, 16, 32), the rim's
#: singular pressure averaged over its cells
FLAT_FACE_LOAD_ERROR_PER_CELL = 0.12


def flat_face_cells(gap: np.ndarray) -> float | None:
    """Cells [-] across the half-width of the flat face of a gap (the cells at its lowest value, to
    1e-9 of its relief): half the smaller side of the face's bounding box, a disc's radius in cells.
    None where the lowest cells are no face: fewer than 4 of them, a line (a side of one cell: a
    cylinder's generator), or reaching the domain's edge (a plane, a cylinder across the domain)."""
    relief = float(gap.max() - gap.min())
    face = gap <= gap.min() + 1e-9 * relief
    rows, cols = np.flatnonzero(face.any(axis=1)), np.flatnonzero(face.any(axis=0))
    n_y, n_x = gap.shape
    if (np.count_nonzero(face) < 4 or rows.size < 2 or cols.size < 2 or rows[0] == 0 or cols[0] == 0
            or rows[-1] == n_y - 1 or cols[-1] == n_x - 1):
        return None
    return 0.5 * min(rows[-1] - rows[0] + 1, cols[-1] - cols[0] + 1)


def _check_flat_face(problem: Problem) -> None:
    """Warn where an indenter without a Hertz scale (:func:`contact_estimate` is None) has a flat face
    too coarse for its load: a flat punch carries its load on its face at any load, and the rim's
    singular pressure, a cell average on the grid, costs about
    :data:`FLAT_FACE_LOAD_ERROR_PER_CELL` dx/a of the load at a given approach (Boussinesq)."""
    if problem.grid.periodic or problem.radius is not None:
        return
    cells = flat_face_cells(problem.gap)
    if cells is None:
        return
    error = FLAT_FACE_LOAD_ERROR_PER_CELL / cells
    if error > WARNING_LIMIT:
        warn_caller(f"grid.n = {problem.grid.n}: the indenter's flat face is {2 * cells:.0f} cells across, so its "
                    f"rim (a singular pressure averaged over a cell) may put the load at a given approach off by "
                    f"about {100 * error:.0f} % (Boussinesq; grid.n = {flat_face_grid(problem.grid.n, cells)} would "
                    f"give less than {100 * WARNING_LIMIT:.0f} %)")


def flat_face_grid(n: int, cells: float) -> int:
    """The grid.n [-] at which a flat face ``cells`` across its half-width on n x n cells
    (:func:`flat_face_cells`) has a rim load error (:data:`FLAT_FACE_LOAD_ERROR_PER_CELL` dx/a) under
    :data:`WARNING_LIMIT`: the face's width in cells is quantised, one cell more than the error's share."""
    return math.ceil(n * (FLAT_FACE_LOAD_ERROR_PER_CELL / WARNING_LIMIT + 1.0) / cells)


def _check_device(problem: Problem) -> None:
    """Warn where ``solver.device = "gpu"`` runs a grid below :data:`GPU_SMALL_GRID` cells a side, on
    which the CPU is likely the faster device."""
    n = problem.grid.n
    if problem.solver.device == "gpu" and n < GPU_SMALL_GRID:
        warn_caller(f"solver.device = 'gpu' on {n} x {n} cells: below {GPU_SMALL_GRID} x {GPU_SMALL_GRID} the GPU's "
                    "transforms are bound by their launches and the CPU is likely faster (seed Table 1 at 256 x 256: "
                    "23.8 s on an H200 against 11.0 s on 16 CPU cores); solver.device = 'cpu' runs it there")


def _check_space(problem: Problem, transient: bool) -> None:
    grid = problem.grid
    est = contact_estimate(problem, transient=transient)
    if est is None:
        _check_flat_face(problem)
    else:
        ratio = est.largest / est.sphere_radius
        if ratio > RADIUS_RATIO_ERROR:
            raise ParameterError(_normal_key(problem), f"the contact radius reaches about {ratio:.2g} x the "
                                 "indenter radius "
                                 f"({est.largest:.3g} m against {est.sphere_radius:.3g} m): beyond the small-strain "
                                 f"half-space theory (a/R <= {RADIUS_RATIO_ERROR:g}); check the units "
                                 "(N, m) of the load and of indenter.radius")
        if ratio > RADIUS_RATIO_WARNING:
            warn_caller(f"the contact radius reaches about {ratio:.2g} x the indenter radius: strains of about "
                        f"{100 * 2 * ratio / math.pi:.0f} % exceed the small-strain theory's comfort "
                        f"(a/R <= {RADIUS_RATIO_WARNING:g})")
        found = _grid_problems(est, grid.n, grid.half_width)
        if found:
            from viscontact.io.case import MAX_GRID_N

            n, half_width = grid_suggestion(est, grid.n, grid.half_width)
            key, message = found[0]
            # a gap of no given radius whose lowest cells are tied in a face of a few cells (a coarse
            # flat punch, or a sphere's bottom on a grid node) was taken for the sphere of its curvature
            face = None if problem.radius is not None else flat_face_cells(problem.gap)
            punch = ""
            if face is not None:
                message = (f"the indenter's lowest cells are a flat face {2 * face:.0f} cells across, too few to "
                           "tell a flat punch from a sphere's bottom, so it is taken for the sphere of radius "
                           f"{est.sphere_radius:.3g} m that the gap's curvature gives (Hertz): {message}")
                punch = (f" (if it is a flat punch, its contact is its face at any load: grid.n = "
                         f"{flat_face_grid(grid.n, face)} resolves that face)")
            if _grid_problems(est, n, half_width):
                raise ParameterError(key, f"{message}; no grid of up to {MAX_GRID_N}^2 cells can hold and resolve "
                                     f"a contact of radius {est.smallest:.3g} to {est.largest:.3g} m: check the "
                                     f"units of the moduli (Pa), the load (N) and indenter.radius (m){punch}")
            raise ParameterError(key, f"{message}; use grid.half_width = {half_width:.2g} m and grid.n = {n}{punch}")
        cells = est.smallest / grid.spacing
        if peak_pressure_error(cells) > WARNING_LIMIT:
            n, _ = grid_suggestion(est, grid.n, grid.half_width)
            warn_caller(f"grid.n = {grid.n}: {cells:.2g} cells across the contact radius {est.smallest:.3g} m, "
                        f"the peak pressure may be off by about {100 * peak_pressure_error(cells):.0f} % "
                        f"(grid.n = {n} would give less than {100 * WARNING_LIMIT:.0f} %)")


# --- the time step -------------------------------------------------------------------------------
#: sub-steps per time step of the reference hereditary integrals
REFERENCE_REFINEMENT = 16
#: the time-step error of a step is relative to the exact value at that step, but not to less than this
#: fraction of the largest exact value (a value that passes through zero, e.g. an approach released)
RELATIVE_FLOOR = 0.05


def hereditary_integral(kernel_inf: float, amplitudes: np.ndarray, times: np.ndarray, f: np.ndarray,
                        h: float) -> np.ndarray:
    """y(t_j) = int_0^t_j K(t_j - s) df(s) [units of K x f] on the uniform times t_j = j h, for
    K(t) = kernel_inf + sum_i amplitudes_i exp(-t / times_i) and f linear between its samples ``f``
    with a step of f[0] at t = 0. Exact for that f (recursion over the exponentials, seed Eq. 6)."""
    y = kernel_inf * f
    slope = np.diff(f, prepend=f[0]) / h
    for amplitude, time in zip(np.atleast_1d(amplitudes), np.atleast_1d(times)):
        drive = slope * time * -math.expm1(-h / time)
        drive[0] = f[0]
        y = y + amplitude * _exponential_filter(drive, h / time)
    return y


def _exponential_filter(drive: np.ndarray, rate: float) -> np.ndarray:
    """y_j = exp(-rate) y_(j-1) + drive_j (y_(-1) = 0), vectorised in blocks short enough for
    exp(rate k) not to overflow: y_(s+k) = exp(-rate k) (exp(-rate) y_(s-1) + sum_i exp(rate i) drive_(s+i))."""
    out = np.empty_like(drive)
    block = max(1, min(drive.size, int(200.0 / max(rate, 1e-300))))
    carry = 0.0
    for start in range(0, drive.size, block):
        k = np.arange(min(block, drive.size - start))
        seg = np.exp(-rate * k) * (math.exp(-rate) * carry + np.cumsum(drive[start:start + k.size] * np.exp(rate * k)))
        out[start:start + k.size] = seg
        carry = seg[-1]
    return out


def _scheme_response(problem: Problem, driving: np.ndarray) -> np.ndarray:
    """The time scheme of :mod:`viscontact.solvers.transient` on one point: the traction under the
    displacements ``driving`` (displacement control) or the displacement under the tractions
    ``driving`` (load control), at the steps t_k = k dt."""
    spectrum, dt, scheme = problem.material.creep, problem.time.dt, problem.time.scheme
    first, regular = (step_coefficients(spectrum, dt, scheme, f) for f in (True, False))
    hist = PronyHistory.zeros(spectrum.retardation_times.size, 1)
    out = np.empty(driving.size)
    for k, value in enumerate(driving):
        coef = first if k == 0 else regular
        r = float(hist.known(coef, k * dt)[0, 0])
        if problem.normal.control == "displacement":
            p = out[k] = (value - r) / coef.instantaneous
        else:
            p, out[k] = value, coef.instantaneous * value + r
        hist = hist.advanced(np.full((1, 1), p), coef, k * dt)
    return out


def time_step_error(problem: Problem) -> float:
    """Estimated relative error [-] of the transient from the time discretisation alone.

    The scheme runs on one point of the Lee & Radok (1960) solution for a sphere, whose exact values
    are hereditary integrals of the normal history computed on a grid :data:`REFERENCE_REFINEMENT`
    times finer (:func:`hereditary_integral`):

    * displacement control: the contact radius is held by the approach, the traction at a point
      follows int G(t - s) d delta(s); the scheme is driven by delta(t_k) and returns the traction;
    * load control: a(t)^3 ~ int J(t - s) dW(s) grows, the centre pressure is ~ int G(t - s) da(s)
      and the centre displacement ~ a(t); the scheme is driven by the centre pressure and returns
      the displacement.

    Returns the largest difference over the run (at most :data:`MAX_CHECKED_STEPS` steps) relative to
    the largest exact value under load control; under displacement control relative to the exact
    value at its step, or to :data:`RELATIVE_FLOOR` of the largest where that is larger (the traction
    relaxes by G(0)/G(inf): relative to the largest value, the first, errors of 20 % and more late in
    the run passed unseen); 0 for an elastic material.
    """
    mat = problem.material
    if mat.is_elastic:
        return 0.0
    n_steps = min(problem.time.n_steps, MAX_CHECKED_STEPS)
    h = problem.time.dt / REFERENCE_REFINEMENT
    fine = np.arange((n_steps - 1) * REFERENCE_REFINEMENT + 1) * h
    history = np.array([problem.normal.history(t) for t in fine]) if len(problem.normal.history.times) > 1 \
        else np.full(fine.size, problem.normal.history.reference)
    relaxation = (mat.g_inf, np.array(mat.g), np.array(mat.tau))
    creep = mat.creep
    if problem.normal.control == "displacement":
        driving = history
        exact = hereditary_integral(*relaxation, history, h)
    else:
        compliance = hereditary_integral(creep.long_term, -creep.amplitudes, creep.retardation_times, history, h)
        exact = np.cbrt(np.maximum(compliance, 0.0))
        driving = hereditary_integral(*relaxation, exact, h)
    driving, exact = driving[::REFERENCE_REFINEMENT], exact[::REFERENCE_REFINEMENT]
    scale = float(np.max(np.abs(exact)))
    if not scale > 0:
        return 0.0
    # under a held approach the traction relaxes by G(0)/G(inf): each step against its own value; under
    # load control the contact only grows, and the largest value is the scale the limits were set on
    reference = (np.maximum(np.abs(exact), RELATIVE_FLOOR * scale) if problem.normal.control == "displacement"
                 else scale)
    return float(np.max(np.abs(_scheme_response(problem, driving) - exact) / reference))


def _check_time(problem: Problem) -> None:
    dt = problem.time.dt
    if dt > stable_step_limit(problem.material.creep, problem.time.scheme):
        return  # unstable: refused with its own message by viscontact.solvers.transient.validate
    err = time_step_error(problem)
    what = "relaxation" if problem.normal.control == "displacement" else "creep"
    if err > TIME_ERROR_LIMIT:
        key = "time.dt" if not problem.tangential.frame_moves else \
            ("grid.n" if problem.radius is None else "tangential.steps_per_cell")  # dt = dx / (v k) when sliding
        raise ParameterError(key, f"time.dt = {dt:.4g} s with the {problem.time.scheme} scheme misses the {what} of "
                             f"this material and loading by about {100 * err:.0f} % (one-point estimate against the "
                             f"exact hereditary integral); {_time_step_suggestion(problem)}")
    if err > TIME_WARNING_LIMIT:
        warn_caller(f"time.dt = {dt:.4g} s: the {problem.time.scheme} scheme misses the {what} by about "
                    f"{100 * err:.1f} % (one-point estimate); {_time_step_suggestion(problem)}")


def _check_end(problem: Problem) -> None:
    """Warn when the last step falls short of ``time.t_end`` by more than :data:`END_SHORTFALL` of it
    (the steps are t = k dt, k = 0 .. floor(t_end / dt))."""
    t_end, dt = problem.time.t_end, problem.time.dt
    last = (problem.time.n_steps - 1) * dt
    if t_end - last > END_SHORTFALL * t_end:
        warn_caller(f"time.t_end = {t_end:.4g} s is not a multiple of time.dt = {dt:.4g} s: the run ends at "
                    f"t = {last:.4g} s, {100 * (t_end - last) / t_end:.2g} % short; use time.t_end = "
                    f"{last + dt:.4g} s (one step more) or a time.dt that divides it")


def _histories(problem: Problem) -> dict[str, tuple[PiecewiseLinear, str, str]]:
    """The piecewise-linear histories the steps sample: case key -> (history, its symbol, unit)."""
    normal = problem.normal
    found = {"normal.history": (normal.history, "W" if normal.control == "load" else "delta_z",
                                "N" if normal.control == "load" else "m")}
    if problem.tangential.displacement_history is not None:
        found["tangential.displacement_history"] = (problem.tangential.displacement_history, "delta_x", "m")
    return found


def turning_point_miss(problem: Problem, dt: float | None = None,
                       key: str = "tangential.displacement_history") -> tuple[float, float, float, float] | None:
    """How far the time steps t = k ``dt`` (default ``time.dt``) miss the turning points that the run
    reaches of the history ``key`` (``tangential.displacement_history``, or ``normal.history``: a load
    or approach that rises and falls): the run's value is the history at the steps, so a reversal
    between two steps is cut to the nearer of them (a cycle faster than dt is aliased into another).
    Returns, for the first turning point missed by more than :data:`TURNING_POINT_MISS` of the
    history's largest absolute value (else the one missed most): (the miss, its time [s], its value,
    the extreme the steps reach), in the history's unit; None without that history or a reversal
    within the run. A turning point held over a plateau is met where a step falls on the plateau."""
    history = _histories(problem).get(key, (None,))[0]
    if history is None:
        return None
    dt = problem.time.dt if dt is None else dt
    limit = TURNING_POINT_MISS * float(np.max(np.abs(history.values)))
    worst = None
    # turning_steps lists the turning points the run reaches, in the same order
    for (first, _, value, _), (_, reached) in zip(history.turning_points(),
                                                   history.turning_steps(dt, problem.time.n_steps - 1)):
        found = (float(abs(value - reached)), first, value, float(reached))
        if found[0] > limit:
            return found
        if worst is None or found[0] > worst[0]:
            worst = found
    return worst


def _check_turning_points(problem: Problem) -> None:
    """Refuse a time step that misses a turning point of a history (the displacement history, the
    normal load's or approach's) by more than :data:`TURNING_POINT_MISS` of its largest absolute
    value (:func:`turning_point_miss`), suggesting the largest dt below it that meets every one."""
    dt = problem.time.dt
    for key, (history, symbol, unit) in _histories(problem).items():
        scale = max(abs(v) for v in history.values)
        worst = turning_point_miss(problem, key=key)
        if worst is None or not worst[0] > TURNING_POINT_MISS * scale:
            continue
        miss, t, value, reached = worst
        # the largest step below dt that meets them: dt / m, or the missed turning point's time / m
        first = int(np.ceil(t / dt))
        candidates = sorted({dt / m for m in range(2, 101)} | {t / m for m in range(first, first + 100)},
                            reverse=True)
        trial = next((c for c in candidates if all(
            not (turning_point_miss(problem, c, k) or (0.0,))[0] > TURNING_POINT_MISS * max(abs(v) for v in h.values)
            for k, (h, _, _) in _histories(problem).items())), candidates[-1])
        raise ParameterError("time.dt", f"{dt:.4g} s misses the turning point of {key} at t = {t:.6g} s ({symbol} = "
                             f"{value:.4g} {unit}) by {miss:.3g} {unit} ({100 * miss / scale:.2g} % of its largest "
                             f"|{symbol}|): the steps sample the history, and the run would turn at {reached:.4g} "
                             f"{unit}; use time.dt = {trial:.4g} s, or one that puts the turning points on steps")


def _time_step_suggestion(problem: Problem) -> str:
    """The step (halved until the estimate is under the warning limit) and the scheme to use."""
    from dataclasses import replace

    linear = " (or time.scheme = \"linear\")" if problem.time.scheme == "constant" else ""
    for halvings in range(1, 11):
        factor = 2**halvings
        trial = replace(problem, time=replace(problem.time, dt=problem.time.dt / factor))
        if time_step_error(trial) <= TIME_WARNING_LIMIT:
            if problem.tangential.frame_moves and problem.radius is None:  # dt = dx / v: a finer height file
                return f"use grid.n = {problem.grid.n * factor} (time.dt = {trial.time.dt:.3g} s){linear}"
            if problem.tangential.frame_moves:
                return (f"use tangential.steps_per_cell = {problem.tangential.steps_per_cell * factor} "
                        f"(time.dt = {trial.time.dt:.3g} s){linear}")
            return f"use time.dt = {trial.time.dt:.3g} s{linear}"
    return f"use a much smaller time.dt{linear}"


def check_material(material: Material) -> None:
    """Refuse (:class:`~viscontact.errors.ParameterError`) a material whose G(0)/G(inf) exceeds
    :data:`MAX_MODULUS_RATIO` or whose creep spectrum is not finite: the first check of
    :func:`check_problem`, and of anything that reads the creep spectrum before it (the resource estimate)."""
    ratio = material.shear_modulus_instantaneous / material.shear_modulus_long_term
    key = {"zener": "material.shear_modulus_long_term", "prony": "material.g_inf"}.get(material.name, "material")
    if not ratio <= MAX_MODULUS_RATIO:
        raise ParameterError(key, f"G(0)/G(inf) = {ratio:.3g} exceeds {MAX_MODULUS_RATIO:g}: the step compliance "
                             "J(inf) - sum J_m beta_m would lose every digit to cancellation; check the moduli (Pa)")
    with np.errstate(all="ignore"):
        c = material.creep
        values = np.concatenate([[c.instantaneous, c.long_term], c.amplitudes, c.retardation_times])
    if not np.all(np.isfinite(values)) or not np.all(values > 0):
        raise ParameterError(key, "the moduli and times give no finite creep compliance; check the moduli (Pa) "
                             "and times (s)")


def positive_values(values: object, key: str, unit: str, given: str | None = None, *,
                    zero: bool = False) -> list[float]:
    """``values`` (a sequence of numbers) as a list of floats after checking that it is not empty and
    that each is a finite number > 0 (``zero``: >= 0) given once (a coordinate along them, ``speed``
    or a time, would repeat a value): the speeds of a steady speed curve, the times of
    ``plot --times`` (t = 0 included).

    Raises
    ------
    ParameterError
        Naming ``key`` and ``unit``, quoting ``given`` (the text typed) or the values.
    """
    shown = given if given is not None else repr(values)
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise ParameterError(key, f"must be a list of numbers in {unit}, got {shown}")
    values = list(values)
    if not all(is_number(v) for v in values):
        raise ParameterError(key, f"must be a list of numbers in {unit}, got {shown}")
    values = [float(v) for v in values]
    if not values:
        raise ParameterError(key, f"must list at least one number in {unit}, got {shown}")
    if any(not (0 <= v if zero else 0 < v) or v == float("inf") for v in values):
        raise ParameterError(key, f"every value must be a finite number {'>=' if zero else '>'} 0 {unit}, got {shown}")
    twice = sorted({v for v in values if values.count(v) > 1})
    if twice:  # a result along them would have a coordinate with repeated values
        raise ParameterError(key, f"{', '.join(f'{v:g}' for v in twice)} {unit} is listed more than once, got {shown}")
    return values


def check_problem(problem: Problem, *, transient: bool = True) -> None:
    """Refuse a problem whose answer cannot be trusted, warn about a marginal one.

    Parameters
    ----------
    problem
        What is about to be solved.
    transient
        Also check the time step and that the steps reach ``time.t_end`` (not for the steady solver).

    Raises
    ------
    ParameterError
        Naming the key to change and a value that will work.
    """
    check_material(problem.material)
    _check_space(problem, transient)
    _check_device(problem)
    if transient:
        _check_time(problem)
        _check_end(problem)
        _check_turning_points(problem)
