"""The scales of a problem: the contact radius and pressure that normalise its results (an analytic
shape's own, :mod:`viscontact.problem.shapes`), and the radius of the sphere that a gap's curvature
stands for (a rough or measured surface's lowest point's), on which the guards and the results'
``a0``, ``p0`` rest."""
from __future__ import annotations

import numpy as np

from viscontact.physics.reference import hertz_from_approach, hertz_from_load
from viscontact.problem.problem import Problem


def hertz_scale(problem: Problem) -> tuple[float, float]:
    """The results' scales a0 [m] and p0 [Pa] with G(0) at the reference (largest) normal value.

    An analytic shape's own (:meth:`viscontact.problem.shapes.Shape.scale`): a sphere's Hertz radius
    and peak pressure (load control: Hertz for the load; displacement control: a0 = sqrt(R delta),
    p0 from the Hertz load of that approach), an ellipsoid's, a roller's, a punch's, a cone's; on a line
    grid the shape's :meth:`~viscontact.problem.shapes.Shape.line_scale` (the infinite cylinder's Hertz
    line contact, a strip punch's), approaches relative to the grid's datum. A gap without a shape:
    Hertz for the sphere of the gap's :func:`equivalent_radius` (NaN where no
    curvature defines its lowest point: a plane, a cylinder, a flat punch, whose contact is its face
    at any load); NaN on a periodic domain.
    """
    mat = problem.material
    ref = problem.normal.history.reference
    if problem.shape is not None and problem.grid.dimension == 1:  # a line's shape: per unit length, datum
        return problem.shape.line_scale(ref, problem.normal.control, mat.shear_modulus_instantaneous,
                                        mat.poisson_ratio, problem.grid.datum_distance)
    if problem.shape is not None:
        return problem.shape.scale(ref, problem.normal.control, mat.shear_modulus_instantaneous, mat.poisson_ratio)
    if problem.grid.periodic:
        return float("nan"), float("nan")  # a periodic surface of many asperities has no Hertz scale
    radius = equivalent_radius(problem)
    if not np.isfinite(radius):
        return float("nan"), float("nan")
    build = hertz_from_load if problem.normal.control == "load" else hertz_from_approach
    h = build(ref, radius, mat.shear_modulus_instantaneous, mat.poisson_ratio)
    return float(h.radius), float(h.peak_pressure)


#: the curvature fit of :func:`equivalent_radius` starts on a disc of this fraction of the domain's
#: half-width (the scale of the contact the domain is sized for) ...
CURVATURE_FIT_FRACTION = 0.5
#: ... shrinks to this many Hertz radii of the fitted curvature (at G(inf), the largest contact) ...
CURVATURE_FIT_CONTACTS = 2.0
#: ... over at most this many rounds, and covers at least this many cells in radius
CURVATURE_FIT_ROUNDS, CURVATURE_FIT_CELLS = 4, 3
#: a fitted curvature whose rise over the disc, (c3 + c4) in the disc's scaled coordinates, is below
#: this fraction of the largest gap there is the fit's round-off: a plane (a tilted plane gave 2e-16 of
#: either sign, R = 9e14 m on one CPU); a sphere gives 2, and tilted by a slope s, reach / (R s)
CURVATURE_ROUNDOFF = 1e-10
#: a fit whose smaller principal curvature is below this fraction of the larger is a line contact
#: (a cylinder, whose curvature along its axis is 0; a valley) or a saddle, which no sphere's Hertz
#: scale describes: the contact is a strip whose width the sphere's radius does not estimate, and
#: which reaches the domain's edge. An ellipsoid of radii 1 : 100 has 0.01 (from about 1 : 80 the
#: flatness test below may find it already)
LINE_CURVATURE_RATIO = 0.01
#: the gap must rise from its lowest point no slower than its fitted paraboloid, whose cells within t
#: of its vertex cover 2 pi R t: the region about the lowest point within t of it, for every t from 0
#: to the Hertz approach at G(inf) (the largest contact), may cover this many cells (round-off ties
#: about a grid node: 4), plus this fraction of the Hertz contact's area at G(inf) (a flat tip, the
#: bottom level of quantised heights: small against the contact), plus this factor x 2 pi R t (a
#: noisy bottom; an ellipsoid's area is (sqrt(R1/R2) + sqrt(R2/R1)) / 2 x its fitted sphere's), no
#: more. A flat punch covers its face at t = 0, whatever the height of its walls
FLAT_CELLS, FLAT_CONTACT_FRACTION, FLAT_AREA_FACTOR = 9, 0.25, 4.0


def _fitted_paraboloid(gap: np.ndarray, dx: np.ndarray, dy: np.ndarray, reach: float) -> tuple[float, float]:
    """(2 / laplacian [m], smaller / larger principal curvature [-]) of the least-squares paraboloid
    h = c0 + c1 x + c2 y + c3 x^2 + c4 y^2 + c5 x y fitted to ``gap`` [m] over the cells within
    ``reach`` [m] of a point, (``dx``, ``dy``) [m] from it; NaN, NaN when not convex (a curvature at
    round-off, :data:`CURVATURE_ROUNDOFF`, is a plane's)."""
    near = dx**2 + dy**2 <= reach**2
    u, v = dx[near] / reach, dy[near] / reach  # scaled: a well-conditioned fit
    basis = np.column_stack([np.ones_like(u), u, v, u * u, v * v, u * v])
    if np.linalg.matrix_rank(basis) < basis.shape[1]:
        return float("nan"), float("nan")
    c = np.linalg.lstsq(basis, gap[near], rcond=None)[0]
    if not c[3] + c[4] > CURVATURE_ROUNDOFF * np.abs(gap[near]).max():
        return float("nan"), float("nan")
    spread = np.hypot(c[3] - c[4], c[5])  # eigenvalues of the Hessian: c3 + c4 +- spread (x 2 / reach^2)
    # 2 / laplacian, laplacian = 2 (c3 + c4) / reach^2
    return float(reach**2 / (c[3] + c[4])), float((c[3] + c[4] - spread) / (c[3] + c[4] + spread))


def _flatter_than_paraboloid(gap: np.ndarray, radius: float, depth: float, allowed: float,
                             cell_area: float) -> bool:
    """Whether the connected region about the lowest point of ``gap`` [m] where the gap is within t
    of its minimum covers more than ``allowed`` [m^2] plus :data:`FLAT_AREA_FACTOR` x 2 pi R t (the
    paraboloid of radius R's) for some t from 0 to ``depth`` [m]; cells of ``cell_area`` [m^2]."""
    low = gap - gap.min()
    from scipy import ndimage  # imported where used: scipy.ndimage weighs several MiB

    labels, _ = ndimage.label(low <= depth)
    j, i = np.unravel_index(np.argmin(low), low.shape)
    levels = np.sort(low[labels == labels[j, i]])
    area = np.arange(1, levels.size + 1) * cell_area
    return bool(np.any(area > allowed + FLAT_AREA_FACTOR * 2.0 * np.pi * radius * levels))


def equivalent_radius(problem: Problem) -> float:
    """Radius [m] of the sphere with the gap's mean curvature about its lowest point, on the scale of
    the contact; NaN where the gap has no lowest point that a curvature defines: not convex there (a
    plane), a line of minima (a cylinder) or a bottom flatter than its paraboloid (a flat punch).

    2 / laplacian of the least-squares paraboloid (:func:`_fitted_paraboloid`) over a disc about the
    lowest point: first :data:`CURVATURE_FIT_FRACTION` of the half-width, then
    :data:`CURVATURE_FIT_CONTACTS` Hertz radii of the fitted sphere under the run's largest load (or
    approach) at G(inf), refitted until the disc stops shrinking (at least
    :data:`CURVATURE_FIT_CELLS` cells). Exact for a paraboloid (centred on a grid node too: the fit
    about the first of the four tied cells has the same curvature); roughness on a smaller scale
    averages out (the curvature at one cell was the roughness's: a sphere of 10 mm with 1 um of
    roughness gave 0.2 mm); a tip or the lowest of several asperities is measured on its own
    contact's scale.

    That sphere is the contact's scale only where the gap rises from its lowest point as a
    paraboloid does. NaN, then:

    * a fit whose principal curvatures differ by more than 1 / :data:`LINE_CURVATURE_RATIO`: a
      cylinder (the fit gave 2 R, its laplacian's, for the strip contact of a line), a valley, a
      saddle;
    * a bottom flatter than the fitted paraboloid's (:func:`_flatter_than_paraboloid`): for some t
      from 0 to the Hertz approach at G(inf), the region about the lowest point within t of it
      covers more than :data:`FLAT_AREA_FACTOR` x 2 pi R t (a paraboloid's area) plus
      :data:`FLAT_CELLS` cells and :data:`FLAT_CONTACT_FRACTION` of the Hertz contact's. A flat punch covers
      its face at t = 0: its contact is the face, whatever the load and the height of its walls (the
      fit about the first cell of its rim took in the walls: R = 64 mm, 9.3 mm, 0.56 mm for walls
      of 20 um, 100 um, 1 mm about a 0.5 mm punch on +-2 mm). A flat with noise of rms s covers its
      face at t of a few s: found while 2 pi R s is small against its area (walls of 100 um about
      that punch: up to s = 1 um at least). A flat tip or a quantised bottom small against the
      contact keeps the sphere's radius.

    NaN gives no Hertz scale (the results' a0, p0) and no Hertz contact-size guard
    (:func:`viscontact.running.guards.contact_estimate`).
    """
    grid, h = problem.grid, problem.gap
    x, y = grid.mesh()
    j, i = np.unravel_index(np.argmin(h), h.shape)
    dx, dy = x - x[j, i], y - y[j, i]
    smallest = CURVATURE_FIT_CELLS * grid.spacing
    reach = max(CURVATURE_FIT_FRACTION * grid.half_width, smallest)
    mat, reference = problem.material, problem.normal.history.reference
    build = hertz_from_load if problem.normal.control == "load" else hertz_from_approach
    radius, ratio, depth, contact = float("nan"), float("nan"), 0.0, 0.0
    for _ in range(CURVATURE_FIT_ROUNDS):
        radius, ratio = _fitted_paraboloid(h, dx, dy, reach)
        if not (np.isfinite(radius) and reference > 0):
            break
        largest = build(reference, radius, mat.shear_modulus_long_term, mat.poisson_ratio)
        depth, contact = float(largest.approach), float(largest.radius)
        shrunk = max(CURVATURE_FIT_CONTACTS * contact, smallest)
        if shrunk >= 0.95 * reach:
            break
        reach = shrunk
    if not (np.isfinite(radius) and ratio >= LINE_CURVATURE_RATIO):
        return float("nan")
    allowed = FLAT_CELLS * grid.cell_area + FLAT_CONTACT_FRACTION * np.pi * contact**2
    return float("nan") if _flatter_than_paraboloid(h, radius, depth, allowed, grid.cell_area) else radius


def retardation_time(problem: Problem) -> float:
    """Shortest creep retardation time [s] of the material (NaN when elastic)."""
    lam = problem.material.creep.retardation_times
    return float(np.min(lam)) if lam.size else float("nan")
