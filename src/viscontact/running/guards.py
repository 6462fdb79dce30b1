"""Physical validity of a problem, checked before it is solved: can its answer be trusted?

Every check compares the discretisation with an estimate of the solution it must resolve, from
closed-form contact mechanics and from the time scheme applied to one point:

* **contact size** -- the indenter's shape (:mod:`viscontact.problem.shapes`: Hertz for a sphere, an
  ellipsoid, a roller; Boussinesq's punch; Sneddon's cone) on the body (its own estimate,
  :meth:`~viscontact.bodies.base.Body.contact_radius`) with the instantaneous and the
  long-term shear modulus; for a sphere (Johnson, *Contact Mechanics*, Sec. 4.2): under load control the contact radius of a viscoelastic sphere creeps
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
  0.7 % estimated). Other shapes estimate their own error (:meth:`~viscontact.problem.shapes.Shape.resolution_error`:
  a flat punch's and a cone's load at a given approach, the singular pressure at a rim or a tip
  averaged over its cells), and fewer than the shape's ``min_cells`` are refused (a punch's face, a
  cone's contact: :data:`~viscontact.problem.shapes.SINGULAR_MIN_CELLS`).
* **domain** -- the largest contact must fit in the domain with :data:`EDGE_CELLS` cells to spare.
* **small strain** -- the half-space and the paraboloidal gap are small-strain, small-slope
  approximations; the largest strain is about p0/E* = 2a/(pi R) (Hertz; a shape's contact size
  over its radius of curvature across it, :meth:`~viscontact.problem.shapes.Shape.strain_ratio`), so a/R above
  :data:`RADIUS_RATIO_ERROR` cannot be trusted and above :data:`RADIUS_RATIO_WARNING` is marginal.
* **time step** -- the time scheme (:mod:`viscontact.numerics.schemes`, :mod:`viscontact.numerics.history`) is run on
  one point of a contact whose area does not change: under displacement control the traction
  responds to the approach history delta(t) through the relaxation modulus G(t); under load control the displacement
  responds to the load history W(t) through the creep compliance J(t). Both are compared with the
  exact hereditary integrals of the piecewise-linear history (seed Eq. 5 with dt -> 0;
  :mod:`viscontact.solvers.time_step_error`). This compares dt with the relaxation and retardation
  times and with the time scale of the loading.

An estimated error above the error limit raises :class:`~viscontact.errors.ParameterError` (the
answer cannot be trusted); above the warning limit a :class:`~viscontact.errors.ViscontactWarning`
gives the estimate. The limits are module constants.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from viscontact.errors import ParameterError, warn_caller
from viscontact.numerics.hereditary import hereditary_integral
from viscontact.numerics.schemes import stable_step_limit
from viscontact.physics.adhesion import cohesive_zone_length
from viscontact.physics.materials import Material
from viscontact.problem.adhesion import ADHESION_LAWS
from viscontact.problem.problem import PiecewiseLinear, Problem
from viscontact.problem.shapes import FLAT_FACE_LOAD_ERROR_PER_CELL, Shape, Sphere, peak_pressure_error
from viscontact.solvers.time_step_error import time_step_error

__all__ = ["ContactEstimate", "check_material", "check_problem", "check_sliding_step", "contact_estimate",
           "flat_face_cells", "flat_face_grid", "grid_suggestion", "peak_pressure_error"]

#: cells across the adhesive cohesive zone (or the contact radius, when smaller) below which a run is
#: refused / warned about (:func:`_check_adhesion`): the cell-by-cell law knows the zone's edge to a cell
ADHESION_MIN_CELLS, ADHESION_WARN_CELLS = 2.0, 4.0
#: the tension at the domain's edge (the rigid gap's rise there) of a law whose tension reaches every cell
#: (the exponential), as a fraction of its peak, above which a warning says the grid cuts off its tail (the
#: Derjaguin force of a sphere loses that fraction: int 2 pi r sigma dr = 2 pi R w e^(-g_edge / rho))
EDGE_TAIL_FRACTION = 0.01
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
#: time.dt over time.t_end above which a run is refused, not warned: it would be its step at t = 0
#: alone, the time asked for a small part of one step (a sliding speed in the wrong unit sets the step)
END_REFUSAL = 10.0
#: fraction of a history's largest absolute value (the displacement history's |delta_x|, the normal
#: history's load or approach) by which the time steps may miss one of its turning points
#: (:func:`turning_point_miss`); refused above
TURNING_POINT_MISS = 0.01
#: cells per side below which ``solver.device = "gpu"`` warns: its transforms are bound by their
#: launches there (seed Table 1 at 256^2 through the command line: 23.8 s on an H200 against 11.0 s
#: on its host's 16 cores; at 1024^2 the GPU steps 5.4 times as fast: BENCHMARKS.md)
GPU_SMALL_GRID = 512


@dataclass(frozen=True)
class ContactEstimate:
    """Contact extents of a problem [m], from the body's own estimates of the shape's contact size
    (:meth:`~viscontact.bodies.base.Body.contact_radius`) and the shape's extents
    (:meth:`~viscontact.problem.shapes.Shape.extents`): ``smallest`` (the narrowest half-width to
    resolve; load control: with G(0)), ``largest`` (the farthest reach, after creeping, at most with
    G(inf)); ``sphere_radius`` R [m], the radius of curvature across the contact (a sphere's, an equivalent
    sphere's; NaN for a shape without one: a punch, a cone) and ``strain_ratio`` the largest contact
    size over it (Hertz strains ~ 2 a/(pi R)); ``model``: the closed forms of the estimate (in
    messages); ``shape``: what was estimated (its resolution error, :meth:`~viscontact.problem.shapes.Shape.resolution_error`)."""

    smallest: float
    largest: float
    sphere_radius: float
    model: str = "Lee & Radok creep; shape: Hertz"
    shape: Shape | None = None
    strain_ratio: float = float("nan")

    def resolution_error(self, cells: float) -> float:
        """The shape's estimated error [-] with ``cells`` across the narrowest half-width (a sphere's
        peak pressure, :func:`peak_pressure_error`, when no shape is known)."""
        return peak_pressure_error(cells) if self.shape is None else self.shape.resolution_error(cells)

    @property
    def resolved(self) -> str:
        """What :meth:`resolution_error` is the error of."""
        return "the peak pressure" if self.shape is None else self.shape.resolved


def contact_estimate(problem: Problem, *, transient: bool = True) -> ContactEstimate | None:
    """The body's estimate of the contact at the largest load (or approach) of the run for the
    problem's shape (:meth:`~viscontact.bodies.base.Body.contact_radius`: the shape's elastic contact
    on a half-space, a layer's own, thin or not), in the shape's extents. A gap without an analytic
    shape (a file) is estimated as the sphere of its :func:`viscontact.problem.scales.equivalent_radius`;
    None where it has no curvature to estimate it from (a flat punch, whose contact is its face at any
    load; a cylinder) and for such a gap on a periodic grid (a rough period): its load spreads over many
    asperities, so the one at the lowest point carrying it all is no estimate of the contact, and a
    period has no edge for a contact to reach.

    Under load control the contact creeps (Lee & Radok: a^3 ~ int J(t - s) dW(s) for a sphere; each
    shape's relation with E* / c) for as long as a material point stays loaded: the run's duration, or
    when sliding at most 2 a(G(inf)) / v (the time to cross the widest contact; the steady state:
    that time). ``largest`` is the reach after that time, at most the reach with G(inf).
    """
    from viscontact.problem.scales import equivalent_radius

    shape = problem.shape
    if shape is None:
        if problem.grid.periodic:
            return None
        radius = equivalent_radius(problem)
        if not (np.isfinite(radius) and radius > 0):
            return None
        shape = Sphere(radius)
    reference = problem.normal.history.reference
    if not reference > 0:
        return None
    mat, body = problem.material, problem.body
    model = f"{body.contact_model}; shape: {shape.model}"
    if problem.normal.control == "displacement":
        smallest = largest = body.contact_radius_at_approach(reference, shape)
    else:
        smallest = body.contact_radius(reference, shape)
        tan = problem.tangential
        duration = problem.time.t_end if transient else math.inf
        if tan.mode in ("frictionless_sliding", "gross_sliding") or (not transient and tan.sliding_speed > 0):
            long_term = body.contact_radius(reference, shape, mat.shear_modulus_instantaneous / mat.shear_modulus_long_term)
            duration = min(duration, 2.0 * long_term / tan.sliding_speed)
        largest = body.contact_radius(reference, shape, _creep_ratio(problem, duration))
    ratio, curvature = shape.strain_ratio(largest)
    return ContactEstimate(shape.extents(smallest)[0], shape.extents(largest)[1], curvature, model, shape, ratio)


def _creep_ratio(problem: Problem, duration: float) -> float:
    """max over 0 <= t <= duration of int J(t - s) dW(s) / (J(0) max W) [-] (1 for an elastic
    material, G(0)/G(inf) for a held load after a long time; 1 for a run of one step at t = 0, which
    has no time to creep)."""
    mat = problem.material
    if duration <= 0.0:
        return 1.0
    if mat.is_elastic or not math.isfinite(duration):
        return mat.shear_modulus_instantaneous / mat.shear_modulus_long_term
    creep = mat.creep
    t = np.linspace(0.0, duration, 1001)
    load = np.interp(t, problem.normal.history.times, problem.normal.history.values)  # history(t) at every t
    compliance = hereditary_integral(creep.long_term, -creep.amplitudes, creep.retardation_times, load, t[1] - t[0])
    return float(np.max(compliance) / (creep.instantaneous * problem.normal.history.reference))


def _grid_problems(est: ContactEstimate, n: int, half_width: float) -> list[tuple[str, str]]:
    """(key, message) for every way an n x n grid on +-half_width fails to resolve or hold ``est``."""
    dx = 2.0 * half_width / n
    found = []
    cells = est.smallest / dx
    error = est.resolution_error(cells)
    min_cells = 0.0 if est.shape is None else est.shape.min_cells
    if error > ERROR_LIMIT or cells < min_cells:
        singular = f" ({est.shape.singular})" if est.shape is not None and est.shape.singular else ""
        found.append(("grid.n", f"{n} cells of {dx:.3g} m resolve the contact radius {est.smallest:.3g} m "
                      f"with {cells:.2g} cells: {est.resolved} would be off by about {100 * error:.0f} %"
                      + (f" (at least {min_cells:g} cells are needed)" if error <= ERROR_LIMIT else "")
                      + singular))
    if est.largest > half_width - EDGE_CELLS * dx:
        found.append(("grid.half_width", f"the contact radius reaches about {est.largest:.3g} m ({est.model}): "
                      f"half_width = {half_width:.4g} m does not hold it with "
                      f"{EDGE_CELLS} cell{'s' if EDGE_CELLS > 1 else ''} to spare"))
    return found


def grid_suggestion(est: ContactEstimate, n: int, half_width: float) -> tuple[int, float]:
    """The smallest change of (n, half_width) that holds and resolves ``est`` (checked to pass)."""
    from scipy import optimize  # imported where used: a run that needs no suggestion loads no scipy.optimize

    from viscontact.io.case import MAX_GRID_N

    if est.largest > half_width - EDGE_CELLS * 2.0 * half_width / n and 1.5 * est.largest > half_width:
        scale = 10.0 ** (math.floor(math.log10(1.5 * est.largest)) - 1)
        half_width = math.ceil(1.5 * est.largest / scale) * scale  # 1.5 a, rounded up to two digits
    # cells under the warning, with 5 % margin: the shape's error falls as the cells grow
    cells_needed = 1.05 * max(optimize.brentq(lambda c: est.resolution_error(c) - WARNING_LIMIT, 1e-3, 1e6),
                              0.0 if est.shape is None else est.shape.min_cells)
    n_needed = max(n, math.ceil(min(2.0 * half_width * cells_needed / est.smallest, 2.0 * MAX_GRID_N)))
    n = min(2 ** math.ceil(math.log2(n_needed)), MAX_GRID_N) if n_needed > n else n
    while _grid_problems(est, n, half_width) and n < MAX_GRID_N:
        n = min(2 * n, MAX_GRID_N)
    return n, half_width


def _check_adhesion(problem: Problem, transient: bool) -> None:
    """With ``[adhesion]``: refuse a law the steady solver does not have (``transient`` False), and a grid whose cells are
    too coarse for the cohesive zone (:func:`cohesive_zone_estimate`) or for the contact radius
    (:func:`contact_estimate`) where that is smaller: fewer than :data:`ADHESION_MIN_CELLS` across is
    refused, fewer than :data:`ADHESION_WARN_CELLS` warned about, each with the grid.n that gives
    :data:`ADHESION_WARN_CELLS`."""
    adhesion = problem.adhesion
    if adhesion is None:
        return
    kind = adhesion.kind
    if not transient and not kind.steady:
        steady_laws = " or ".join(repr(name) for name, law in ADHESION_LAWS.items() if law.steady)
        raise ParameterError("adhesion.law", f"{adhesion.law!r} is not supported by `viscontact steady` yet: run the "
                             f"transient (`viscontact run`), or law = {steady_laws}")
    grid = problem.grid
    if kind.reaches_every_cell and not grid.periodic:
        rise = float(grid.edge_values(problem.gap).min() - problem.gap.min())
        tail = kind.tail(adhesion, rise)
        if tail > EDGE_TAIL_FRACTION:
            warn_caller(f"grid.half_width: the {kind.label} tension at the domain's edge (the gap {rise:.3g} m above "
                        f"its least, {rise / adhesion.range:.2g} ranges) is {tail:.2g} "
                        f"of its peak, cut off outside the grid; widen the domain to a rise of "
                        f"{kind.tail_gap(adhesion, EDGE_TAIL_FRACTION) / adhesion.range:.2g} ranges")
    est = contact_estimate(problem)
    length, what = cohesive_zone_estimate(problem, est)
    if est is not None and est.smallest < length:
        length, what = est.smallest, f"contact radius {est.smallest:.3g} m"
    cells = length / grid.spacing
    if cells >= ADHESION_WARN_CELLS:
        return
    from viscontact.io.case import MAX_GRID_N

    n = min(2 ** math.ceil(math.log2(ADHESION_WARN_CELLS * 2.0 * grid.half_width / length)), MAX_GRID_N)
    message = (f"{grid.n} cells of {grid.spacing:.3g} m resolve the {what} with {cells:.2g} cells; use "
               f"grid.n >= {n} (the pull-off converges at first order in the cell size)")
    if cells < ADHESION_MIN_CELLS:
        raise ParameterError("grid.n", message)
    warn_caller(f"grid.n: {message}")


def body_contact_modulus(problem: Problem, length: float) -> float:
    """The body's own contact modulus E* [Pa] at t = 0 at the scale ``length`` [m]: the Hertz modulus
    3 W R / (4 a^3) of the contact radius a = ``problem.body.contact_radius(W, Sphere(R))`` that the body
    gives for the load W at which a half-space of its material (E*_0 = 2 G(0) / (1 - nu)) would reach
    a = ``length`` (R = ``length``). The half-space's (and nu(t)'s, with nu(0)) is E*_0; a layer's is
    its compliance at that wavelength (stiffer than E*_0 beyond its thickness on a stiffer base)."""
    mat = problem.material
    e_star = 2.0 * mat.shear_modulus_instantaneous / (1.0 - mat.poisson_ratio)
    sphere = Sphere(length)
    load = sphere.load_at_size(length, e_star)
    a = problem.body.contact_radius(load, sphere)
    return 3.0 * load * length / (4.0 * a**3) if math.isfinite(a) and a > 0 else e_star


def cohesive_zone_estimate(problem: Problem, est: ContactEstimate | None) -> tuple[float, str]:
    """The length [m] of the adhesive cohesive zone a grid must resolve, and how it was found (for
    the guard's message): the smaller of

    * the Dugdale zone of a JKR-like contact, pi E* w / (4 sigma_0^2)
      (:func:`~viscontact.physics.adhesion.cohesive_zone_length`; the Maugis-Dugdale ring tends to it
      at a large Maugis parameter), with the body's own E* at the scale of that zone
      (:func:`body_contact_modulus`: a layer judged by its compliance there, not its material's);
      the exponential law is judged as the Maugis-Dugdale law of its peak, sigma_0 = w / rho and
      h_0 = rho (:attr:`~viscontact.problem.adhesion.AdhesionSettings.peak_stress`);
    * the width over which the rigid gap of the sphere (R, contact radius a: ``est``) opens to the
      range h_0 = w / sigma_0 beyond the contact's edge, sqrt(a^2 + 2 R h_0) - a: the zone of a small
      Maugis parameter (the DMT limit), which a stiff body (a thin layer on a rigid base) reaches.

    Measured at the largest approach of the shipped case at 128^2 (10 um cells): a half-space
    (lambda = 0.48 with G(0)) 128 um (estimate 104 um), a 50 um layer on a rigid base 48 um (104 um;
    the Dugdale zone with the layer's material 457 um, with its stiffness at that scale 3.4 mm)."""
    adhesion, mat = problem.adhesion, problem.material
    e_material = 2.0 * mat.shear_modulus_instantaneous / (1.0 - mat.poisson_ratio)
    w, sigma = adhesion.work_of_adhesion, adhesion.peak_stress
    e_star = body_contact_modulus(problem, cohesive_zone_length(e_material, w, sigma))
    length = cohesive_zone_length(e_star, w, sigma)
    what = f"cohesive zone pi E* w / (4 sigma_0^2) = {length:.3g} m (E* = {e_star:.3g} Pa, the body's at that scale)"
    if est is not None and math.isfinite(est.sphere_radius):  # (a punch, a cone: none)
        a, radius = est.smallest, est.sphere_radius
        opening = math.sqrt(a**2 + 2.0 * radius * adhesion.range) - a
        if opening < length:
            length = opening
            what = (f"cohesive zone sqrt(a^2 + 2 R h_0) - a = {length:.3g} m (where the indenter's gap opens to the "
                    f"range h_0 = w / sigma_0 = {adhesion.range:.3g} m beyond a = {a:.3g} m)")
    return length, what


def _normal_key(problem: Problem) -> str:
    return "normal.value" if len(problem.normal.history.times) == 1 else "normal.history"




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
    if problem.grid.periodic or problem.shape is not None:
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
    if problem.shape is not None:
        problem.shape.check_grid(grid)
        for caveat in problem.shape.caveats(grid):
            warn_caller(caveat)
    est = contact_estimate(problem, transient=transient)
    if est is None:
        _check_flat_face(problem)
    else:
        ratio = est.strain_ratio  # NaN (no check) for a shape without curvature: a punch, a cone
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
            face = None if problem.shape is not None else flat_face_cells(problem.gap)
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
        if est.resolution_error(cells) > WARNING_LIMIT:
            n, _ = grid_suggestion(est, grid.n, grid.half_width)
            singular = f"; {est.shape.singular}" if est.shape is not None and est.shape.singular else ""
            warn_caller(f"grid.n = {grid.n}: {cells:.2g} cells across the contact radius {est.smallest:.3g} m, "
                        f"{est.resolved} may be off by about {100 * est.resolution_error(cells):.0f} % "
                        f"(grid.n = {n} would give less than {100 * WARNING_LIMIT:.0f} %{singular})")


# --- the time step -------------------------------------------------------------------------------
def _check_time(problem: Problem) -> None:
    dt = problem.time.dt
    if dt > stable_step_limit(problem.material.creep, problem.time.scheme):
        return  # unstable: refused with its own message by viscontact.solvers.transient.validate
    err = time_step_error(problem)
    what = "relaxation" if problem.normal.control == "displacement" else "creep"
    if err > TIME_ERROR_LIMIT:
        key = "time.dt" if not problem.tangential.frame_moves else \
            ("grid.n" if problem.radius is None or problem.tangential.rolls  # rolling: one cell per step
             else "tangential.steps_per_cell")  # dt = dx / (v k) when sliding
        raise ParameterError(key, f"time.dt = {dt:.4g} s with the {problem.time.scheme} scheme misses the {what} of "
                             f"this material and loading by about {100 * err:.0f} % (one-point estimate against the "
                             f"exact hereditary integral); {_time_step_suggestion(problem)}")
    if err > TIME_WARNING_LIMIT:
        warn_caller(f"time.dt = {dt:.4g} s: the {problem.time.scheme} scheme misses the {what} by about "
                    f"{100 * err:.1f} % (one-point estimate); {_time_step_suggestion(problem)}")


def _check_end(problem: Problem) -> None:
    """Refuse (:class:`ParameterError`) a step more than :data:`END_REFUSAL` times ``time.t_end``;
    warn when the last step falls short of ``time.t_end`` by more than :data:`END_SHORTFALL` of it
    (the steps are t = k dt, k = 0 .. floor(t_end / dt))."""
    t_end, dt = problem.time.t_end, problem.time.dt
    last = (problem.time.n_steps - 1) * dt
    if dt > END_REFUSAL * t_end > 0:  # a unit slip: the run would be its step at t = 0 alone, refused
        why = (" (by default one cell of sliding per tangential.steps_per_cell steps: check "
               "tangential.sliding_speed)") if problem.tangential.mode != "none" else ""
        raise ParameterError("time.dt", f"time.dt = {dt:.4g} s: the run would end at t = {last:.4g} s, "
                             f"{100 * (t_end - last) / t_end:.3g} % short of time.t_end = {t_end:.4g} s (a step "
                             f"{dt / t_end:.3g} times the run); give a time.dt <= {t_end / 2:.4g} s{why}")
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
    # turning_reach lists the turning points the run reaches, in the same order (arrays: 20,000 points in ms)
    firsts, _, values, _ = history.turning_arrays()
    reached = history.turning_reach(dt, problem.time.n_steps - 1)[1]
    if reached.size == 0:
        return None
    miss = np.abs(values[:reached.size] - reached)
    over = np.flatnonzero(miss > limit)
    i = over[0] if over.size else int(np.argmax(miss))  # the first above the limit, else the first largest
    return float(miss[i]), float(firsts[i]), float(values[i]), float(reached[i])


def _check_turning_points(problem: Problem) -> None:
    """Refuse a time step that misses a turning point of a history (the displacement history, the
    normal load's or approach's) by more than :data:`TURNING_POINT_MISS` of its largest absolute
    value (:func:`turning_point_miss`), advising the change that meets every one
    (:func:`_turning_point_advice`): the largest ``time.dt`` below it, or, when sliding ties dt to
    the grid, the smallest ``tangential.steps_per_cell``."""
    for key, (history, symbol, unit) in _histories(problem).items():
        scale = max(abs(v) for v in history.values)
        worst = turning_point_miss(problem, key=key)
        if worst is None or not worst[0] > TURNING_POINT_MISS * scale:
            continue
        miss, t, value, reached = worst
        change, advice = _turning_point_advice(problem, t)
        step = f"{problem.time.dt:.4g} s" if change == "time.dt" else f"time.dt = {problem.time.dt:.4g} s"
        raise ParameterError(change, f"{step} misses the turning point of {key} at "
                             f"t = {t:.6g} s ({symbol} = {value:.4g} {unit}) by {miss:.3g} {unit} "
                             f"({100 * miss / scale:.2g} % of its largest |{symbol}|): the steps sample the "
                             f"history, and the run would turn at {reached:.4g} {unit}; {advice}")


def check_sliding_step(problem: Problem) -> None:
    """Refuse a ``time.dt`` given while sliding that is not the sliding's own step,
    :attr:`~viscontact.problem.problem.Problem.sliding_dt` (the frame moves by whole cells, so dt =
    (2 half_width / n) / sliding_speed / steps_per_cell), before the other guards judge it: the
    advice is the smallest ``tangential.steps_per_cell`` whose step is at most the one given and
    that every time-step guard accepts, with time.dt removed. The solver's own check
    (:func:`viscontact.solvers.transient.validate`, which cannot know the guards) with that advice:
    called before it by :func:`viscontact.running.preflight.preflight`."""
    dt, sliding_dt = problem.time.dt, problem.sliding_dt
    if sliding_dt is None or abs(dt - sliding_dt) <= 1e-6 * sliding_dt:
        return
    tan = problem.tangential
    cell = problem.grid.spacing / tan.sliding_speed
    start = max(1, math.ceil(cell / dt - 1e-6))
    k = next((k for k in range(start, start * MAX_STEPS_PER_CELL_FACTOR) if _accepted(_with_step(problem, cell / k, k))),
             start)
    raise ParameterError("time.dt", f"{dt:.6g} s is not the sliding's step: when sliding the frame moves by whole "
                         f"cells, so time.dt = (2 half_width / n) / sliding_speed / steps_per_cell = {sliding_dt:.6g} s; "
                         f"remove time.dt and use tangential.steps_per_cell = {k} (time.dt = {cell / k:.4g} s)")


def _with_step(problem: Problem, dt: float, steps_per_cell: int | None = None) -> Problem | None:
    """``problem`` with the time step ``dt`` [s] (and, when sliding, ``steps_per_cell``); None where
    that is more steps than a run may take."""
    from dataclasses import replace

    try:
        time = replace(problem.time, dt=dt)
    except ParameterError:
        return None
    if steps_per_cell is None:
        return replace(problem, time=time)
    return replace(problem, time=time, tangential=replace(problem.tangential, steps_per_cell=steps_per_cell))


def _meets_turning_points(problem: Problem) -> bool:
    """Whether the steps of ``problem`` meet every turning point of its histories to
    :data:`TURNING_POINT_MISS` (:func:`_check_turning_points` passes)."""
    return all(not (turning_point_miss(problem, key=key) or (0.0,))[0] > TURNING_POINT_MISS * max(
        abs(v) for v in history.values) for key, (history, _, _) in _histories(problem).items())


def _accepted(problem: Problem | None, time_limit: float = TIME_ERROR_LIMIT) -> bool:
    """Whether the time-step guards accept ``problem``: its turning points met, the one-point time
    error (:func:`~viscontact.solvers.time_step_error.time_step_error`) at most ``time_limit``."""
    return problem is not None and _meets_turning_points(problem) and time_step_error(problem) <= time_limit


#: largest tangential.steps_per_cell (times the case's) that an advice tries before giving up
MAX_STEPS_PER_CELL_FACTOR = 1000


def _turning_point_advice(problem: Problem, t_missed: float) -> tuple[str, str]:
    """(the key to change, the advice) that meets every turning point (:func:`_meets_turning_points`)
    and that the time-step guard still accepts. Sliding (dt = dx / (v k), so time.dt cannot be
    chosen): the smallest ``tangential.steps_per_cell`` k that does; otherwise the largest dt below
    ``time.dt`` among dt / m and ``t_missed`` / m (the missed turning point on a step)."""
    dt = problem.time.dt
    tan = problem.tangential
    if tan.frame_moves:
        cell = problem.grid.spacing / tan.sliding_speed  # one cell of sliding [s]
        for k in range(tan.steps_per_cell + 1, MAX_STEPS_PER_CELL_FACTOR * tan.steps_per_cell + 1):
            if _accepted(_with_step(problem, cell / k, k)):
                return "tangential.steps_per_cell", (
                    f"use tangential.steps_per_cell = {k} (time.dt = {cell / k:.4g} s: when sliding, time.dt "
                    "follows the grid and the speed, (2 half_width / n) / sliding_speed / steps_per_cell)")
        return "tangential.steps_per_cell", (
            f"no tangential.steps_per_cell up to {MAX_STEPS_PER_CELL_FACTOR * tan.steps_per_cell} meets them: put "
            f"the turning points on multiples of one cell of sliding, (2 half_width / n) / sliding_speed = "
            f"{cell:.4g} s")
    first = int(np.ceil(t_missed / dt))
    candidates = sorted({dt / m for m in range(2, 101)} | {t_missed / m for m in range(first, first + 100)},
                        reverse=True)
    trial = next((c for c in candidates if _accepted(_with_step(problem, c))), candidates[-1])
    return "time.dt", f"use time.dt = {trial:.4g} s, or one that puts the turning points on steps"


def _time_step_suggestion(problem: Problem) -> str:
    """The step (halved until the estimate is under the warning limit) and the scheme to use; when
    that step misses a turning point of a history (:func:`_check_turning_points`), the next one that
    meets them all, so that the advice is one the next run accepts: when sliding the smallest
    ``tangential.steps_per_cell`` from the halved one on, otherwise the largest ``time.dt`` below
    the halved one (:func:`_turning_point_advice`)."""
    linear = " (or time.scheme = \"linear\")" if problem.time.scheme == "constant" else ""
    tan = problem.tangential
    for halvings in range(1, 11):
        factor = 2**halvings
        trial = _with_step(problem, problem.time.dt / factor)
        if trial is None:
            break
        if time_step_error(trial) <= TIME_WARNING_LIMIT:
            if tan.frame_moves and (problem.radius is None or tan.rolls):  # dt = dx / v: a finer grid
                return f"use grid.n = {problem.grid.n * factor} (time.dt = {trial.time.dt:.3g} s){linear}"
            if tan.frame_moves:
                cell = problem.grid.spacing / tan.sliding_speed
                k = next((k for k in range(tan.steps_per_cell * factor, MAX_STEPS_PER_CELL_FACTOR * tan.steps_per_cell)
                          if _accepted(_with_step(problem, cell / k, k), TIME_WARNING_LIMIT)),
                         tan.steps_per_cell * factor)
                return f"use tangential.steps_per_cell = {k} (time.dt = {cell / k:.3g} s){linear}"
            missed = [turning_point_miss(trial, key=key) for key in _histories(trial)]
            missed = [m[1] for m, (h, _, _) in zip(missed, _histories(trial).values())
                      if m is not None and m[0] > TURNING_POINT_MISS * max(abs(v) for v in h.values)]
            if missed:  # the halved step misses a turning point: the step that meets them all
                return _turning_point_advice(trial, missed[0])[1] + linear
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
    _check_adhesion(problem, transient)
    if transient:
        _check_time(problem)
        _check_end(problem)
        _check_turning_points(problem)
