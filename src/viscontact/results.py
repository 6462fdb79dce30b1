"""Results: solver records -> :class:`xarray.Dataset` -> netCDF-4 (:ref:`result-file`).

The Dataset is the only thing plots and users need: dimensions ``t`` [s], ``y``, ``x`` [m] (frame
moving with the indenter, origin under its centre), fields ``pressure``, ``shear_x``, ``stick``
(and ``displacement_z`` when recorded), the scalar histories of
:class:`~viscontact.records.StepRecord`, and attributes for normalisation (``a0``, ``p0``,
``retardation_time``; also scalar variables with units, :data:`SCALES`) and provenance (``case``,
``version``, ``source``, ``references``, ``history``). ``stick`` and ``phase`` carry the CF
``flag_values`` / ``flag_meanings``.
"""
from __future__ import annotations

import errno
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from datetime import datetime, timezone
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy import ndimage

from .errors import ParameterError
from .materials import Material
from .problem import PHASE_GROSS_SLIDING, PHASE_INDENTATION, PHASE_PARTIAL_SLIP, Problem
from .records import StepRecord
from .reference import hertz_from_approach, hertz_from_load

if TYPE_CHECKING:  # xarray (with pandas, ~60 MiB) loads only where a Dataset is built or read
    import xarray as xr

#: a variable in plain numpy, as :class:`xarray.Dataset` takes it: (dimensions, data, attributes)
VariableSpec = tuple[tuple[str, ...], Any, dict[str, Any]]

__all__ = [
    "REFERENCES",
    "SCALES",
    "VARIABLES",
    "completeness",
    "global_attrs",
    "hertz_scale",
    "material_dataset",
    "netcdf_encoding",
    "open_result",
    "result_layout",
    "scale_variables",
    "sweep_dataset",
    "t_gross_sliding",
    "to_dataset",
    "variable_encoding",
    "write_netcdf",
]

#: units and long names of every variable a result may hold
VARIABLES: dict[str, tuple[str, str]] = {
    "pressure": ("Pa", "contact pressure p"),
    "shear_x": ("Pa", "shear traction q_x on the half-space"),
    "stick": ("1", "node in contact and stuck (|q| < mu_f p)"),
    "displacement_z": ("m", "normal surface displacement u_z (positive into the half-space)"),
    "load": ("N", "normal load W = sum p dA"),
    "delta_z": ("m", "normal approach of the indenter"),
    "delta_x": ("m", "tangential rigid-body displacement of the indenter"),
    "sliding_distance": ("m", "distance slid since gross sliding began"),
    "contact_area": ("m2", "contact area"),
    "stick_ratio": ("1", "stick area / contact area (NaN where a partial-slip run has no contact)"),
    "phase": ("1", "phase: 0 indentation, 1 partial slip (until the stick zone of a contact vanishes), "
              "2 gross sliding"),
    "friction_force": ("N", "dry friction force sum q_x dA (positive when resisting the motion)"),
    "hysteresis_force": ("N", "hysteresis force F_T = -sum p du_z/dx dA (seed Eq. 15)"),
    "mu_app": ("1", "apparent friction coefficient F_T / W (seed Eq. 15): the hysteresis friction; with "
               "friction and nu < 0.5 it also holds the non-dissipative normal-tangential coupling term"),
    "contact_shift": ("m", "x-centroid of the pressure"),
    "frame_offset": ("m", "indenter centre on the grid (x - frame_offset is the indenter-frame coordinate)"),
    "wake_loss": ("1", "fraction of the history displacement load dropped at the trailing edge"),
    "iterations": ("1", "constrained-CG iterations of the step"),
    "coupling_iterations": ("1", "normal/tangential alternations of the step"),
    "peak_pressure": ("Pa", "largest contact pressure"),
    "contact_fraction": ("1", "real contact area / domain area"),
    "contact_patches": ("1", "number of contact patches (4-connected; merged across the edges of a periodic domain)"),
    "mean_gap": ("m", "mean deformed gap over the domain (mean separation)"),
    "mean_contact_pressure": ("Pa", "load / real contact area"),
    "stress_xx": ("Pa", "subsurface stress sigma_xx in the section y = 0 (tension positive)"),
    "stress_yy": ("Pa", "subsurface stress sigma_yy in the section y = 0 (tension positive)"),
    "stress_zz": ("Pa", "subsurface stress sigma_zz in the section y = 0 (tension positive)"),
    "stress_xz": ("Pa", "subsurface stress sigma_xz in the section y = 0"),
    "von_mises_stress": ("Pa", "von Mises stress sqrt(3 J2) in the section y = 0"),
    "max_shear_stress": ("Pa", "maximum shear stress (sigma_1 - sigma_3)/2 in the section y = 0"),
}
#: units and long names of the coordinates a result may hold ("": no units, an index)
COORDINATES: dict[str, tuple[str, str]] = {
    "t": ("s", "time"),
    "step": ("", "time-step index"),
    "y": ("m", "y in the frame of the indenter"),
    "x": ("m", "x in the frame of the indenter (sliding towards +x)"),
    "speed": ("m/s", "sliding speed v"),  # of a steady speed curve, and deborah along it
    "deborah": ("1", "Deborah number v tau / a0"),
    "t_sub": ("s", "time of the subsurface output"),
    "z": ("m", "depth below the surface"),
}
#: subsurface variables (dims t_sub, z, x)
SUBSURFACE_VARIABLES = ("stress_xx", "stress_yy", "stress_zz", "stress_xz", "von_mises_stress", "max_shear_stress")

#: scales of a result: scalar variables with units (``a0`` and ``p0`` are also global attributes)
SCALES: dict[str, tuple[str, str]] = {
    "a0": ("m", "Hertz contact radius with G(0) at the reference normal value (sqrt(R delta) under "
                "displacement control); NaN without a curvature-defined lowest point (flat punch, cylinder)"),
    "p0": ("Pa", "Hertz peak pressure with G(0) at the reference normal value (NaN with a0)"),
    "retardation_time": ("s", "shortest creep retardation time tau of the material"),
    "t_gross_sliding": ("s", "first recorded time in gross sliding (0 when sliding from t = 0, NaN when never)"),
    "poisson_ratio_instantaneous": ("1", "Poisson ratio nu(0) from G(0) and the elastic bulk modulus K "
                                         "(material.bulk_modulus only)"),
    "poisson_ratio_long_term": ("1", "Poisson ratio nu(inf) from G(inf) and the elastic bulk modulus K "
                                     "(material.bulk_modulus only)"),
}

#: CF flags of the integer and boolean variables: (flag_values, flag_meanings)
_FLAGS: dict[str, tuple[list[int], str]] = {
    "stick": ([0, 1], "slip_or_no_contact stick"),
    "phase": ([PHASE_INDENTATION, PHASE_PARTIAL_SLIP, PHASE_GROSS_SLIDING], "indentation partial_slip gross_sliding"),
}

#: the ``references`` attribute of every result
REFERENCES = ("Wang et al., A numerical model to simulate the transient frictional viscoelastic sliding contact, "
              "Friction (2023); the viscontact documentation (physics, numerics, result files)")

# quantities that are zero by definition in a tangential mode, and why
_UNDEFINED = {
    "none": (("shear_x", "stick", "stick_ratio", "friction_force", "delta_x", "sliding_distance",
              "hysteresis_force", "mu_app"), "zero: no tangential motion (tangential.mode = 'none')"),
    "frictionless_sliding": (("shear_x", "stick", "stick_ratio", "friction_force"),
                             "zero: frictionless sliding (tangential.mode = 'frictionless_sliding')"),
    "gross_sliding": (("stick", "stick_ratio"),
                      "zero: no stick zone in gross sliding from t = 0 (tangential.mode = 'gross_sliding')"),
    "partial_slip": ((), ""),
}
#: compression of the 3-D fields (chunks of one time step): byte shuffle, then zlib at level 1. 256^2
#: creep pressures on one core of the 2-core VM: a sparse one 2.9 ms and 4.7x smaller against 6.0 ms
#: and 4.0x for zlib at level 4 alone, a dense one (56 % in contact) 6.4 ms either way and 2.66x
#: against 2.32x; an all-zero field 0.75 ms against 2.4 ms (BENCHMARKS.md)
FIELD_COMPRESSION = {"zlib": True, "complevel": 1, "shuffle": True}
#: time steps per chunk of the 1-D series of a streamed result (:mod:`viscontact.streaming`)
SERIES_CHUNK = 512


def hertz_scale(problem: Problem) -> tuple[float, float]:
    """Hertz radius a0 [m] and peak pressure p0 [Pa] with G(0) at the reference (largest) normal value.

    Load control: Hertz for the load. Displacement control: a0 = sqrt(R delta), p0 from the Hertz
    load of that approach. Without a sphere radius, R is the gap's :func:`equivalent_radius` (NaN where
    no curvature defines its lowest point: a plane, a cylinder, a flat punch, whose contact is its
    face at any load); NaN on a periodic domain without a sphere.
    """
    if problem.grid.periodic and problem.radius is None:
        return float("nan"), float("nan")  # a periodic surface of many asperities has no Hertz scale
    radius = problem.radius if problem.radius is not None else equivalent_radius(problem)
    if not np.isfinite(radius):
        return float("nan"), float("nan")
    mat = problem.material
    ref = problem.normal.history.reference
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
    (:func:`viscontact.guards.contact_estimate`).
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


def global_attrs(problem: Problem, case_text: str = "") -> dict[str, Any]:
    """Attributes shared by transient and steady results (normalisation and provenance)."""
    from . import __version__

    a0, p0 = hertz_scale(problem)
    mat, tan = problem.material, problem.tangential
    return {
        "title": problem.title,
        "a0": a0,
        "p0": p0,
        "retardation_time": retardation_time(problem),
        "tangential_mode": tan.mode,
        "normal_control": problem.normal.control,
        "normal_reference": problem.normal.history.reference,
        "friction_coefficient": tan.effective_friction,
        "sliding_speed": tan.sliding_speed,
        "displacement_rate": tan.displacement_rate,
        **_displacement_history_attrs(tan.displacement_history),
        "shear_modulus_instantaneous": mat.shear_modulus_instantaneous,
        "shear_modulus_long_term": mat.shear_modulus_long_term,
        "poisson_ratio": mat.poisson_ratio,
        "a_T": mat.shift_factor,
        **_prony_attrs(mat),
        "radius": float("nan") if problem.radius is None else float(problem.radius),
        **_substrate_attrs(problem),
        "dt": problem.time.dt,
        "time_scheme": problem.time.scheme,
        "grid_n": problem.grid.n,
        "grid_half_width": problem.grid.half_width,
        "grid_periodic": int(problem.grid.periodic),
        "case": case_text,
        "version": __version__,
        "Conventions": "CF-1.8",
        "source": f"viscontact {__version__}: boundary elements with "
                  + ("periodic FFT convolutions" if problem.grid.periodic else "DC-FFT convolutions"),
        "references": REFERENCES,
        "history": history_stamp("created"),
    }


def history_stamp(action: str) -> str:
    """``<UTC time> <action> by viscontact <version>``: an entry of a result's ``history`` attribute."""
    from . import __version__

    return f"{datetime.now(timezone.utc).strftime('%Y-%m-%dT%H:%M:%SZ')} {action} by viscontact {__version__}"


def _displacement_history_attrs(history) -> dict[str, Any]:
    """Partial slip's ``tangential.displacement_history`` as the run used it, where given (none for a
    ramp): ``displacement_history_times`` [s] and ``displacement_history_values`` [m], delta_x held at
    the last value after the last time; a result run from a Problem has no case text to hold it."""
    if history is None:
        return {}
    return {"displacement_history_times": np.asarray(history.times, dtype=float),
            "displacement_history_values": np.asarray(history.values, dtype=float)}


def _prony_attrs(material) -> dict[str, Any]:
    """The terms of G(t) = G(inf) + sum_i g_i exp(-t / tau_i) as the run used them (WLF shift
    applied): ``relaxation_moduli`` g_i [Pa] and ``relaxation_times`` tau_i [s], so that a result
    holds its material whatever file or override it came from (none for an elastic material)."""
    if not material.g:
        return {}

    def attribute(values) -> np.ndarray | float:  # as netCDF reads it back: one value is a scalar
        return float(values[0]) if len(values) == 1 else np.asarray(values, dtype=float)
    return {"relaxation_moduli": attribute(material.g), "relaxation_times": attribute(material.tau)}


def _substrate_attrs(problem: Problem) -> dict[str, Any]:
    """nu(0), nu(inf) and K [Pa] with a bulk modulus; the layer's keys with a [layer]."""
    out: dict[str, Any] = {}
    if problem.bulk_modulus is not None:
        from .poisson import BulkElasticMaterial

        nu = BulkElasticMaterial.poisson_ratio_of
        k, mat = problem.bulk_modulus, problem.material
        out.update(bulk_modulus=float(k), poisson_ratio_instantaneous=nu(mat.shear_modulus_instantaneous, k),
                   poisson_ratio_long_term=nu(mat.shear_modulus_long_term, k))
    if problem.layer is not None:
        lay = problem.layer
        out.update(layer_thickness=float(lay.thickness), layer_substrate=lay.substrate,
                   layer_interface=lay.interface, layer_substrate_shear_modulus=float(lay.substrate_shear_modulus),
                   layer_substrate_poisson_ratio=float(lay.substrate_poisson_ratio))
    return out


def subsurface_variables(records: Sequence[StepRecord], problem: Problem) -> tuple[dict, dict]:
    """Stresses in the section y = 0 (:func:`viscontact.subsurface.section_stresses`) of the recorded
    tractions at ``problem.output.subsurface_depths`` [m], at the recorded steps nearest to
    ``subsurface_times`` [s] (default: the last one): variables on (``t_sub``, ``z``, ``x``) and
    their coordinates. Empty when no depths are asked for or nothing was recorded."""
    out = problem.output
    if not out.subsurface_depths or not records:
        return {}, {}
    from .subsurface import section_stresses

    t = np.array([r.t for r in records])
    wanted = [t[-1]] if out.subsurface_times is None else out.subsurface_times
    picks = [int(np.argmin(np.abs(t - w))) for w in wanted]
    depths = np.asarray(out.subsurface_depths, dtype=float)
    stacks: dict[str, list[np.ndarray]] = {name: [] for name in SUBSURFACE_VARIABLES}
    for k in picks:
        rec = records[k]
        sec = section_stresses(problem.grid, problem.material.poisson_ratio, depths, rec.pressure,
                               rec.shear_x if problem.tangential.has_shear else None, workers=problem.solver.workers)
        for c in ("xx", "yy", "zz", "xz"):
            stacks[f"stress_{c}"].append(sec.stress[c])
        stacks["von_mises_stress"].append(sec.von_mises)
        stacks["max_shear_stress"].append(sec.max_shear)
    mode = problem.tangential.mode
    variables = {name: _variable(name, ("t_sub", "z", "x"), np.stack(v), mode) for name, v in stacks.items()}
    coords = {"t_sub": _coordinate("t_sub", t[picks]), "z": _coordinate("z", depths)}
    return variables, coords


def _coords(problem: Problem) -> dict[str, Any]:
    x = problem.grid.x
    return {"y": _coordinate("y", x), "x": _coordinate("x", x)}


def _coordinate(name: str, data: np.ndarray, dim: str | None = None) -> VariableSpec:
    """The coordinate ``name`` along ``dim`` (its own name by default) with the attributes of
    :data:`COORDINATES`."""
    units, long_name = COORDINATES[name]
    return (dim or name,), data, ({"units": units} if units else {}) | {"long_name": long_name}


def _variable(name: str, dims: tuple[str, ...], data: np.ndarray, mode: str) -> VariableSpec:
    units, long_name = VARIABLES[name]
    attrs = {"units": units, "long_name": long_name}
    names, why = _UNDEFINED.get(mode, ((), ""))
    if name in names:
        attrs["note"] = why
    if name in _FLAGS:
        values, meanings = _FLAGS[name]
        stored = np.int8 if data.dtype == bool else data.dtype  # a boolean is stored as int8 in the file
        attrs.update(flag_values=np.array(values, dtype=stored), flag_meanings=meanings)
    return dims, data, attrs


def scale_variables(attrs: dict[str, Any]) -> dict[str, VariableSpec]:
    """The :data:`SCALES` among the global attributes ``attrs`` as scalar variables with units."""
    return {name: ((), float(attrs[name]), {"units": units, "long_name": long_name})
            for name, (units, long_name) in SCALES.items() if name in attrs}


def _add_scales(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with the :data:`SCALES` among its attributes also as scalar variables with units."""
    for name, var in scale_variables(ds.attrs).items():
        ds[name] = var
    return ds


def _field_stack(records: Sequence[StepRecord], name: str, n: int) -> np.ndarray:
    dtype = bool if name == "stick" else float
    out = np.zeros((len(records), n, n), dtype=dtype)
    for k, rec in enumerate(records):
        value = getattr(rec, name)
        if value is not None:
            out[k] = value
    return out


def to_dataset(records: Sequence[StepRecord], problem: Problem, *, case_text: str = "",
               attrs: dict[str, Any] | None = None) -> xr.Dataset:
    """Dataset of a transient (or single steady) run (:ref:`result-file`).

    Parameters
    ----------
    records
        Recorded steps in time order (possibly none, or only the steps done before a failure).
    problem
        The problem they solve (grid, normalisation, requested output fields).
    case_text
        The case file's text (stored as attribute ``case``).
    attrs
        Extra global attributes; they override the computed ones.

    Returns
    -------
    xarray.Dataset
        Dimensions ``t`` [s], ``y``, ``x`` [m]. The fields in ``problem.output.fields`` (missing
        ones written as zeros), every scalar of :class:`StepRecord`; attributes ``a0`` [m],
        ``p0`` [Pa], ``retardation_time`` [s], ``t_gross_sliding`` [s], ``complete`` (1 when the
        last step of the run is in it), ``case``, ``version``, ...
    """
    import xarray as xr

    variables, coords, ds_attrs = result_layout(records, problem, case_text=case_text, attrs=attrs)
    ds = xr.Dataset(variables, coords=coords)
    ds.attrs.update(ds_attrs)
    return _add_scales(ds)


def result_layout(records: Sequence[StepRecord], problem: Problem, *, case_text: str = "",
                  attrs: dict[str, Any] | None = None
                  ) -> tuple[dict[str, VariableSpec], dict[str, VariableSpec], dict[str, Any]]:
    """What :func:`to_dataset` holds, in plain numpy (no xarray): its data variables and coordinates
    as (dimensions, data, attributes), in the Dataset's order, and its global attributes; the
    :data:`SCALES` variables follow from the attributes (:func:`scale_variables`). The streamed
    writer (:mod:`viscontact.streaming`) writes a file's layout from it without loading xarray."""
    records = list(records)
    mode = problem.tangential.mode
    n = problem.grid.n
    t = np.array([r.t for r in records], dtype=float)
    variables: dict[str, VariableSpec] = {}
    for name in StepRecord.FIELDS:
        if name in problem.output.fields:
            variables[name] = _variable(name, ("t", "y", "x"), _field_stack(records, name, n), mode)
    for name in StepRecord.SCALARS:
        dtype = int if name in ("phase", "iterations", "coupling_iterations", "contact_patches") else float
        data = np.array([getattr(r, name) for r in records], dtype=dtype)
        variables[name] = _variable(name, ("t",), data, mode)

    steps = np.array([r.step for r in records], dtype=int)
    coords = {"t": _coordinate("t", t), "step": _coordinate("step", steps, "t"), **_coords(problem)}
    sub_vars, sub_coords = subsurface_variables(records, problem)
    ds_attrs = global_attrs(problem, case_text)
    ds_attrs["t_gross_sliding"] = t_gross_sliding(mode, t, variables["phase"][1])
    ds_attrs["complete"] = completeness(coords["step"][1], problem)
    ds_attrs.update(attrs or {})
    return {**variables, **sub_vars}, {**coords, **sub_coords}, ds_attrs


def completeness(steps: np.ndarray, problem: Problem) -> int:
    """Attribute ``complete``: 1 when the last of the recorded ``steps`` is the run's last step, else 0."""
    return int(len(steps) > 0 and int(steps[-1]) == problem.time.n_steps - 1)


def t_gross_sliding(mode: str, t: np.ndarray, phase: np.ndarray) -> float:
    """First recorded time [s] in gross sliding (partial slip), 0 (sliding modes), NaN (otherwise)."""
    if mode == "partial_slip":
        hits = np.flatnonzero(phase == PHASE_GROSS_SLIDING)
        return float(t[hits[0]]) if hits.size else float("nan")
    return 0.0 if mode in ("frictionless_sliding", "gross_sliding") else float("nan")


def sweep_dataset(records: Sequence[StepRecord], speeds: Sequence[float], problem: Problem, *,
                  case_text: str = "", attrs: dict[str, Any] | None = None) -> xr.Dataset:
    """Dataset of steady states along dimension ``speed`` [m/s].

    Holds ``mu_app``, ``peak_pressure``, ``contact_area``, ``contact_shift``, ``delta_z``,
    ``load``, ``hysteresis_force``, ``friction_force``, the rough-contact outputs
    (``contact_fraction``, ``contact_patches``, ``mean_gap``, ``mean_contact_pressure``),
    ``pressure(speed, y, x)`` and the coordinate ``deborah`` = v tau / a0 [-].
    """
    import xarray as xr

    records = list(records)
    mode = problem.tangential.mode
    speeds = np.asarray(speeds, dtype=float)
    variables = {
        name: _variable(name, ("speed",), np.array([getattr(r, name) for r in records], dtype=float), mode)
        for name in ("mu_app", "contact_area", "contact_shift", "delta_z", "load", "hysteresis_force",
                     "friction_force", "contact_fraction", "contact_patches", "mean_gap", "mean_contact_pressure")
    }
    pressure = _field_stack(records, "pressure", problem.grid.n)
    variables["peak_pressure"] = _variable("peak_pressure", ("speed",), pressure.max(axis=(1, 2)), mode)
    variables["pressure"] = _variable("pressure", ("speed", "y", "x"), pressure, mode)
    base = global_attrs(problem, case_text)
    deborah = speeds * base["retardation_time"] / base["a0"]
    coords = {"speed": _coordinate("speed", speeds), "deborah": _coordinate("deborah", deborah, "speed"),
              **_coords(problem)}
    ds = xr.Dataset(variables, coords=coords)
    ds.attrs.update(base)
    ds.attrs.update({"solver": "steady", "complete": 1})
    ds.attrs.update(attrs or {})
    return _add_scales(ds)


def material_dataset(material: Material, *, points: int = 200) -> xr.Dataset:
    """The material functions of ``material`` on log-spaced times and angular frequencies.

    Time t [s] from 1e-3 x the shortest to 1e3 x the longest relaxation or retardation time (1e-3
    to 1e3 s for an elastic material), omega = 1/t [rad/s]: G(t) [Pa], J(t) [1/Pa], G'(omega),
    G''(omega) [Pa], tan delta = G''/G' [-]. Attributes: G(0), G(inf) [Pa], nu, a_T, the
    relaxation and retardation times [s] and ``kind = "material"``.
    """
    import xarray as xr

    creep = material.creep
    times = np.concatenate([np.asarray(material.tau, dtype=float), creep.retardation_times])
    lo, hi = (float(times.min()), float(times.max())) if times.size else (1.0, 1.0)
    t = np.geomspace(1e-3 * lo, 1e3 * hi, points)
    omega = 1.0 / t[::-1]
    storage, loss = material.storage_modulus(omega), material.loss_modulus(omega)
    ds = xr.Dataset(
        {"relaxation_modulus": ("t", material.relaxation_modulus(t), {"units": "Pa", "long_name": "G(t)"}),
         "creep_compliance": ("t", material.creep_compliance(t), {"units": "1/Pa", "long_name": "J(t)"}),
         "storage_modulus": ("omega", storage, {"units": "Pa", "long_name": "G'(omega)"}),
         "loss_modulus": ("omega", loss, {"units": "Pa", "long_name": "G''(omega)"}),
         "tan_delta": ("omega", loss / storage, {"units": "1", "long_name": "tan delta = G''/G'"})},
        coords={"t": ("t", t, {"units": "s", "long_name": "time"}),
                "omega": ("omega", omega, {"units": "rad/s", "long_name": "angular frequency"})})
    ds.attrs.update({"kind": "material", "title": material.name,
                     "shear_modulus_instantaneous": material.shear_modulus_instantaneous,
                     "shear_modulus_long_term": material.shear_modulus_long_term,
                     "poisson_ratio": material.poisson_ratio, "a_T": material.shift_factor,
                     "relaxation_times": np.sort(np.asarray(material.tau, dtype=float)),
                     "retardation_times": creep.retardation_times})
    return ds


def netcdf_encoding(ds: xr.Dataset, *, streamed: bool = False) -> dict[str, dict[str, Any]]:
    """How a result is stored: 3-D fields compressed (:data:`FIELD_COMPRESSION`) in chunks of one
    time step. ``streamed`` (``t`` unlimited, :mod:`viscontact.streaming`): also the 1-D series
    along ``t`` in chunks of :data:`SERIES_CHUNK` steps, uncompressed (rewritten in place).
    Coordinates have no fill value."""
    encoding = {name: variable_encoding(var.dims, var.shape, coordinate=name in ds.coords, streamed=streamed)
                for name, var in ds.variables.items()}
    return {name: enc for name, enc in encoding.items() if enc}


def variable_encoding(dims: Sequence[str], shape: Sequence[int], *, coordinate: bool,
                      streamed: bool = False) -> dict[str, Any]:
    """The encoding of one variable of dimensions ``dims`` and ``shape`` (:func:`netcdf_encoding`),
    as xarray takes it (netCDF4-python's keys: ``zlib``, ``complevel``, ``shuffle``, ``chunksizes``,
    ``_FillValue``); empty when xarray's defaults apply."""
    if len(shape) == 3:
        if shape[0] or streamed:
            return {**FIELD_COMPRESSION, "chunksizes": (1, *shape[1:])}
        return dict(FIELD_COMPRESSION)
    encoding: dict[str, Any] = {"_FillValue": None} if coordinate else {}
    if streamed and tuple(dims) == ("t",):
        encoding["chunksizes"] = (SERIES_CHUNK,)
    return encoding


def write_netcdf(ds: xr.Dataset, path: str | Path, *, force: bool = False) -> Path:
    """Write ``ds`` to ``path`` as netCDF-4 (h5netcdf), atomically.

    The file is encoded in memory, then written under a temporary name in the same folder with its
    size claimed first, flushed to disk and renamed over ``path``
    (:func:`viscontact.output_files.write_atomically`): readers see the old file, or the complete
    new one, never a partial one; a full disk is one error naming the size needed; SIGINT / SIGTERM
    arriving meanwhile are delivered once the file is complete. 3-D fields are zlib-compressed in
    chunks of one time step; coordinates have no ``_FillValue``.

    Raises
    ------
    FileExistsError
        ``path`` exists and ``force`` is false (``--force`` on the command line), or it is not a
        regular netCDF file (never replaced).
    OSError
        The file cannot be written (no space left, read-only folder, ...); nothing is left behind.
    """
    from .output_files import check_output_path, signals_deferred, write_atomically

    check_output_path(path, force=force)
    with signals_deferred(), _local_scheduler():
        data = ds.to_netcdf(engine="h5netcdf", encoding=netcdf_encoding(ds))
        write_atomically(path, data, hint="free some space or write elsewhere (--out)")
    return Path(path)


@contextmanager
def _local_scheduler() -> Iterator[None]:
    """Encode in this process even inside a dask worker: xarray would otherwise ask the distributed
    scheduler for a lock named after the in-memory buffer, which it does not know."""
    try:
        import dask
    except ImportError:  # pragma: no cover - dask is a dependency
        yield
        return
    with dask.config.set(scheduler="synchronous"):
        yield


def open_result(path: str | Path) -> xr.Dataset:
    """Load a result file fully into memory (the file is closed on return). Of a streamed file left
    incomplete by a kill, only the records whole at its last flush (attribute
    :data:`viscontact.streaming.FLUSHED`): a kill inside HDF5's flush can tear the last one.

    Raises
    ------
    FileNotFoundError
        ``path`` does not exist.
    ParameterError
        ``path`` is not a netCDF-4 file written by viscontact (``run``, ``steady`` or ``sweep``).
    """
    import xarray as xr

    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(errno.ENOENT, "no such file", str(path))
    not_a_result = ParameterError(str(path), "is not a viscontact result file (a netCDF-4 file written by "
                                  "viscontact run, steady or sweep)")
    try:
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            ds = ds.load()
    except (OSError, ValueError, KeyError, TypeError):  # not HDF5, not netCDF, or unreadable layout
        raise not_a_result from None
    if not {"version", "case"} <= set(ds.attrs):
        raise not_a_result
    from .streaming import FLUSHED

    flushed = ds.attrs.get(FLUSHED)  # a streamed file left by a kill: its whole records
    if flushed is not None and int(ds.attrs.get("complete", 1)) == 0 and ds.sizes.get("t", 0) > int(flushed):
        ds = ds.isel(t=slice(0, int(flushed)))
    return ds
