"""Results: solver records -> :class:`xarray.Dataset` -> netCDF-4 (:ref:`result-file`).

The Dataset is the only thing plots and users need: dimensions ``t`` [s], ``y``, ``x`` [m] (frame
moving with the indenter, origin under its centre), fields ``pressure``, ``shear_x``, ``stick``
(and ``displacement_z`` when recorded), the scalar histories of
:class:`~viscontact.problem.records.StepRecord`, and attributes for normalisation (``a0``, ``p0``,
``retardation_time``; also scalar variables with units, :data:`SCALES`) and provenance (``case``,
``version``, ``source``, ``references``, ``history``). ``stick`` and ``phase`` carry the CF
``flag_values`` / ``flag_meanings``.
"""
from __future__ import annotations

from collections.abc import Sequence
from datetime import datetime, timezone
from typing import TYPE_CHECKING, Any

import numpy as np

from viscontact.errors import check_type
from viscontact.physics.materials import Material
from viscontact.problem.problem import (
    PHASE_GROSS_SLIDING,
    PHASE_INDENTATION,
    PHASE_PARTIAL_SLIP,
    PHASE_ROLLING,
    Problem,
)
from viscontact.problem.records import StepRecord
from viscontact.problem.scales import hertz_scale, retardation_time
from viscontact.version import package_version

if TYPE_CHECKING:  # xarray (with pandas, ~60 MiB) loads only where a Dataset is built or read
    import xarray as xr

#: a variable in plain numpy, as :class:`xarray.Dataset` takes it: (dimensions, data, attributes)
VariableSpec = tuple[tuple[str, ...], Any, dict[str, Any]]

__all__ = [
    "REFERENCES",
    "SCALES",
    "VARIABLES",
    "completeness",
    "cycle_variables",
    "energy_per_cycle",
    "fretting_cycles",
    "global_attrs",
    "material_dataset",
    "netcdf_encoding",
    "result_layout",
    "scale_variables",
    "sweep_dataset",
    "t_gross_sliding",
    "to_dataset",
    "variable_encoding",
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
    "creepage": ("1", "creepage (V_c - V) / V of the rolling indenter (V_c its circumferential speed, V that of "
                 "its centre): held, or found under a held tangential force (NaN at t = 0 there)"),
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
    "adhesive_force": ("N", "tensile part of the load, sum min(p, 0) dA (<= 0; with [adhesion])"),
    "adhesive_area": ("m2", "area where the gap is open and the adhesive tension acts (with [adhesion])"),
    "stress_xx": ("Pa", "subsurface stress sigma_xx in the section y = 0 (tension positive)"),
    "stress_yy": ("Pa", "subsurface stress sigma_yy in the section y = 0 (tension positive)"),
    "stress_zz": ("Pa", "subsurface stress sigma_zz in the section y = 0 (tension positive)"),
    "stress_xz": ("Pa", "subsurface stress sigma_xz in the section y = 0"),
    "von_mises_stress": ("Pa", "von Mises stress sqrt(3 J2) in the section y = 0"),
    "max_shear_stress": ("Pa", "maximum shear stress (sigma_1 - sigma_3)/2 in the section y = 0"),
    "energy_per_cycle": ("J", "energy dissipated in each full cycle of a tangential displacement history that "
                              "reverses: the area of the Q-delta_x loop, integral of friction_force d delta_x "
                              "(trapezoids over the records)"),
}
#: the units of a line contact's (``grid.dimension = 1``, plane strain) variables that are per unit length
#: along y: a force [N/m], an area [m], an energy [J/m]
LINE_UNITS = {"N": "N/m", "m2": "m", "J": "J/m"}

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
    "cycle": ("", "full cycle of the tangential displacement (from one turning point to the second after it)"),
    "t_cycle_start": ("s", "time the cycle starts (a turning point of delta_x)"),
    "t_cycle_end": ("s", "time the cycle ends (the second turning point after its start, or the last record)"),
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
    "rolling": ((), ""),
}
#: attributes of a variable that differ in one tangential mode: rolling's only phase code
_MODE_ATTRIBUTES: dict[str, dict[str, dict[str, Any]]] = {
    "rolling": {"phase": {"long_name": "phase: 3 rolling (the only phase of a rolling run)",
                          "flag_values": [PHASE_ROLLING], "flag_meanings": "rolling"},
                "sliding_distance": {"long_name": "distance rolled (the indenter's centre) since t = 0"},
                "delta_x": {"long_name": "position of the rolling indenter's centre (distance rolled)"}},
}
#: compression of the 3-D fields (chunks of one time step): byte shuffle, then zlib at level 1. 256^2
#: creep pressures on one core of the 2-core VM: a sparse one 2.9 ms and 4.7x smaller against 6.0 ms
#: and 4.0x for zlib at level 4 alone, a dense one (56 % in contact) 6.4 ms either way and 2.66x
#: against 2.32x; an all-zero field 0.75 ms against 2.4 ms (BENCHMARKS.md)
FIELD_COMPRESSION = {"zlib": True, "complevel": 1, "shuffle": True}
#: time steps per chunk of the 1-D series of a streamed result (:mod:`viscontact.io.streaming`)
SERIES_CHUNK = 512


def global_attrs(problem: Problem, case_text: str = "") -> dict[str, Any]:
    """Attributes shared by transient and steady results (normalisation and provenance)."""
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
        **_rolling_attrs(tan),
        "shear_modulus_instantaneous": mat.shear_modulus_instantaneous,
        "shear_modulus_long_term": mat.shear_modulus_long_term,
        "poisson_ratio": mat.poisson_ratio,
        "a_T": mat.shift_factor,
        **_prony_attrs(mat),
        "radius": float("nan") if problem.radius is None else float(problem.radius),
        **({} if problem.shape is None else problem.shape.result_attributes()),
        **problem.body.result_attributes(),
        "dt": problem.time.dt,
        "time_scheme": problem.time.scheme,
        "grid_n": problem.grid.n,
        "grid_half_width": problem.grid.half_width,
        "grid_periodic": int(problem.grid.periodic),
        **({"grid_dimension": 1} if problem.grid.dimension == 1 else {}),
        "case": case_text,
        "version": package_version(),
        "Conventions": "CF-1.8",
        "source": f"viscontact {package_version()}: boundary elements with "
                  + ("periodic FFT convolutions" if problem.grid.periodic else "DC-FFT convolutions"),
        "references": REFERENCES,
        "history": history_stamp("created"),
    }


def history_stamp(action: str) -> str:
    """``<UTC time> <action> by viscontact <version>``: an entry of a result's ``history`` attribute."""
    return f"{datetime.now(timezone.utc).strftime('%Y-%m-%dT%H:%M:%SZ')} {action} by viscontact {package_version()}"


def _displacement_history_attrs(history) -> dict[str, Any]:
    """Partial slip's ``tangential.displacement_history`` as the run used it, where given (none for a
    ramp): ``displacement_history_times`` [s] and ``displacement_history_values`` [m], delta_x held at
    the last value after the last time; a result run from a Problem has no case text to hold it."""
    if history is None:
        return {}
    return {"displacement_history_times": np.asarray(history.times, dtype=float),
            "displacement_history_values": np.asarray(history.values, dtype=float)}


def _rolling_attrs(tangential) -> dict[str, Any]:
    """Rolling's settings, where it rolls: ``rolling_speed`` [m/s] and the held ``creepage`` [-] or
    ``tangential_force`` [N]; none in the other modes."""
    if not tangential.rolls:
        return {}
    held = ({"creepage": float(tangential.creepage)} if tangential.creepage is not None else
            {"tangential_force": float(tangential.tangential_force)})
    return {"rolling_speed": float(tangential.rolling_speed), **held}


def _prony_attrs(material) -> dict[str, Any]:
    """The terms of G(t) = G(inf) + sum_i g_i exp(-t / tau_i) as the run used them (WLF shift
    applied): ``relaxation_moduli`` g_i [Pa] and ``relaxation_times`` tau_i [s], so that a result
    holds its material whatever file or override it came from (none for an elastic material)."""
    if not material.g:
        return {}

    def attribute(values) -> np.ndarray | float:  # as netCDF reads it back: one value is a scalar
        return float(values[0]) if len(values) == 1 else np.asarray(values, dtype=float)
    return {"relaxation_moduli": attribute(material.g), "relaxation_times": attribute(material.tau)}


def subsurface_variables(records: Sequence[StepRecord], problem: Problem) -> tuple[dict, dict]:
    """Stresses in the section y = 0 (:func:`viscontact.physics.subsurface.section_stresses`) of the recorded
    tractions at ``problem.output.subsurface_depths`` [m], at the recorded steps nearest to
    ``subsurface_times`` [s] (default: the last one): variables on (``t_sub``, ``z``, ``x``) and
    their coordinates. Empty when no depths are asked for or nothing was recorded."""
    out = problem.output
    if not out.subsurface_depths or not records:
        return {}, {}
    from viscontact.physics.subsurface import section_stresses

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
    grid = problem.grid
    return {"y": _coordinate("y", grid.y), "x": _coordinate("x", grid.x)}


def _per_unit_length(variables: dict[str, VariableSpec], problem: Problem) -> dict[str, VariableSpec]:
    """``variables`` with the units of a line contact's per-unit-length quantities
    (:data:`LINE_UNITS`: forces in N/m, areas in m) on a line grid; as they are otherwise."""
    if problem.grid.dimension != 1:
        return variables
    out = {}
    for name, (dims, data, attrs) in variables.items():
        if attrs.get("units") in LINE_UNITS:
            attrs = {**attrs, "units": LINE_UNITS[attrs["units"]],
                     "long_name": attrs["long_name"] + " (per unit length of the line contact)"}
        out[name] = (dims, data, attrs)
    return out


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
    for key, value in _MODE_ATTRIBUTES.get(mode, {}).get(name, {}).items():
        attrs[key] = np.array(value, dtype=attrs["flag_values"].dtype) if key == "flag_values" else value
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


def _field_stack(records: Sequence[StepRecord], name: str, shape: tuple[int, int]) -> np.ndarray:
    dtype = bool if name == "stick" else float
    out = np.zeros((len(records), *shape), dtype=dtype)
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

    check_type(problem, Problem, "to_dataset's problem", "a viscontact Problem (Case.to_problem())")
    check_type(records, Sequence, "to_dataset's records", "a list of StepRecord (what viscontact.run returns)")
    for record in records:
        check_type(record, StepRecord, "each of to_dataset's records", "a StepRecord")
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
    writer (:mod:`viscontact.io.streaming`) writes a file's layout from it without loading xarray."""
    records = list(records)
    mode = problem.tangential.mode
    shape = problem.grid.shape
    t = np.array([r.t for r in records], dtype=float)
    variables: dict[str, VariableSpec] = {}
    for name in StepRecord.FIELDS:
        if name in problem.output.fields:
            variables[name] = _variable(name, ("t", "y", "x"), _field_stack(records, name, shape), mode)
    for name in StepRecord.scalars(problem.adhesion is not None, problem.tangential.rolls):
        dtype = int if name in ("phase", "iterations", "coupling_iterations", "contact_patches") else float
        data = np.array([getattr(r, name) for r in records], dtype=dtype)
        variables[name] = _variable(name, ("t",), data, mode)

    steps = np.array([r.step for r in records], dtype=int)
    coords = {"t": _coordinate("t", t), "step": _coordinate("step", steps, "t"), **_coords(problem)}
    sub_vars, sub_coords = subsurface_variables(records, problem)
    cycle_vars, cycle_coords = cycle_variables(t, variables["delta_x"][1], variables["friction_force"][1], mode)
    ds_attrs = global_attrs(problem, case_text)
    ds_attrs["t_gross_sliding"] = t_gross_sliding(mode, t, variables["phase"][1])
    ds_attrs["complete"] = completeness(coords["step"][1], problem)
    ds_attrs.update(attrs or {})
    return (_per_unit_length({**variables, **sub_vars, **cycle_vars}, problem), {**coords, **sub_coords, **cycle_coords},
            ds_attrs)


def completeness(steps: np.ndarray, problem: Problem) -> int:
    """Attribute ``complete``: 1 when the last of the recorded ``steps`` is the run's last step, else 0."""
    return int(len(steps) > 0 and int(steps[-1]) == problem.time.n_steps - 1)


def t_gross_sliding(mode: str, t: np.ndarray, phase: np.ndarray) -> float:
    """First recorded time [s] in gross sliding (partial slip), 0 (sliding modes), NaN (otherwise)."""
    if mode == "partial_slip":
        hits = np.flatnonzero(phase == PHASE_GROSS_SLIDING)
        return float(t[hits[0]]) if hits.size else float("nan")
    return 0.0 if mode in ("frictionless_sliding", "gross_sliding") else float("nan")


def fretting_cycles(delta_x: np.ndarray) -> list[tuple[int, int]]:
    """The full cycles of a tangential displacement ``delta_x`` (one value per record) that reverses:
    (first, last) record of each, from a turning point to the second turning point after it (or the
    last record, where ``delta_x`` is back at the value it started the cycle from, to 1e-6 of its
    amplitude); none when it never reverses twice. Held stretches do not turn."""
    x = np.asarray(delta_x, dtype=float)
    step = np.sign(np.diff(x))
    moving = np.flatnonzero(step)
    turns = [int(moving[i + 1]) for i in range(len(moving) - 1) if step[moving[i]] != step[moving[i + 1]]]
    points = turns + ([len(x) - 1] if x.size and (not turns or turns[-1] != len(x) - 1) else [])
    tol = 1e-6 * float(np.max(np.abs(x), initial=0.0))
    return [(points[i], points[i + 2]) for i in range(0, len(points) - 2, 2)
            if abs(x[points[i + 2]] - x[points[i]]) <= tol]


def energy_per_cycle(delta_x: np.ndarray, friction_force: np.ndarray) -> np.ndarray:
    """The energy [J] dissipated in each of the :func:`fretting_cycles` of ``delta_x`` [m]: the area
    of its loop of the tangential force ``friction_force`` [N] against ``delta_x``, by trapezoids."""
    x, q = np.asarray(delta_x, dtype=float), np.asarray(friction_force, dtype=float)
    return np.array([float(np.sum(0.5 * (q[a + 1:b + 1] + q[a:b]) * np.diff(x[a:b + 1])))
                     for a, b in fretting_cycles(x)], dtype=float)


def cycle_variables(t: np.ndarray, delta_x: np.ndarray, friction_force: np.ndarray, mode: str) -> tuple[dict, dict]:
    """``energy_per_cycle`` along ``cycle`` (with ``t_cycle_start``, ``t_cycle_end``) of partial slip
    whose ``delta_x`` goes through full cycles (:func:`fretting_cycles`); empty otherwise."""
    cycles = fretting_cycles(delta_x) if mode == "partial_slip" else []
    if not cycles:
        return {}, {}
    t = np.asarray(t, dtype=float)
    coords = {"cycle": _coordinate("cycle", np.arange(1, len(cycles) + 1)),
              "t_cycle_start": _coordinate("t_cycle_start", t[[a for a, _ in cycles]], "cycle"),
              "t_cycle_end": _coordinate("t_cycle_end", t[[b for _, b in cycles]], "cycle")}
    return {"energy_per_cycle": _variable("energy_per_cycle", ("cycle",), energy_per_cycle(delta_x, friction_force),
                                          mode)}, coords


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
    pressure = _field_stack(records, "pressure", problem.grid.shape)
    variables["peak_pressure"] = _variable("peak_pressure", ("speed",), pressure.max(axis=(1, 2)), mode)
    variables["pressure"] = _variable("pressure", ("speed", "y", "x"), pressure, mode)
    base = global_attrs(problem, case_text)
    deborah = speeds * base["retardation_time"] / base["a0"]
    coords = {"speed": _coordinate("speed", speeds), "deborah": _coordinate("deborah", deborah, "speed"),
              **_coords(problem)}
    ds = xr.Dataset(_per_unit_length(variables, problem), coords=coords)
    ds.attrs.update(base)
    ds.attrs.update({"solver": "steady", "complete": 1})
    ds.attrs.update(attrs or {})
    return _add_scales(ds)


def creepage_dataset(records: Sequence[StepRecord], creepages: Sequence[float], problem: Problem, *,
                     case_text: str = "") -> xr.Dataset:
    """Dataset of steady rolling states along dimension ``creepage`` [-] (the traction-creepage
    curve at the case's rolling speed): ``friction_force`` [N] (the traction), ``traction_ratio``
    = friction_force / (mu_f W) [-], ``stick_ratio``, ``hysteresis_force`` (the rolling resistance)
    and ``mu_app``, ``load``, ``delta_z``, ``contact_area``, and the fields ``pressure``, ``shear_x``
    and ``stick`` on (``creepage``, ``y``, ``x``)."""
    import xarray as xr

    records = list(records)
    mode = problem.tangential.mode
    along = ("creepage",)
    variables = {name: _variable(name, along, np.array([getattr(r, name) for r in records], dtype=float), mode)
                 for name in ("friction_force", "stick_ratio", "hysteresis_force", "mu_app", "load", "delta_z",
                              "contact_area")}
    limit = problem.tangential.friction_coefficient * variables["load"][1]
    variables["traction_ratio"] = (along, np.divide(variables["friction_force"][1], limit, out=np.zeros_like(limit),
                                                    where=limit > 0),
                                   {"units": "1", "long_name": "traction / (mu_f W)"})
    for name in ("pressure", "shear_x", "stick"):
        variables[name] = _variable(name, ("creepage", "y", "x"), _field_stack(records, name, problem.grid.shape), mode)
    coords = {"creepage": _coordinate_of_variable("creepage", np.asarray(creepages, dtype=float)), **_coords(problem)}
    ds = xr.Dataset(variables, coords=coords)
    ds.attrs.update(global_attrs(problem, case_text))
    ds.attrs.update({"solver": "steady", "complete": 1})
    return _add_scales(ds)


def _coordinate_of_variable(name: str, data: np.ndarray) -> VariableSpec:
    """A coordinate along itself with the units and long name of the variable ``name``."""
    units, long_name = VARIABLES[name]
    return (name,), data, {"units": units, "long_name": long_name}


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
    time step. ``streamed`` (``t`` unlimited, :mod:`viscontact.io.streaming`): also the 1-D series
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
