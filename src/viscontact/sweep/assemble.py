"""From runs to one Dataset: the final-state scalars (and time series) of each run along one
dimension per swept key (``.`` -> ``__``; the coordinate's ``key`` attribute holds the dotted key).

Per run: ``mu_app``, ``peak_pressure``, ``contact_area``, ``contact_shift``, ``delta_z``, ``load``,
``hysteresis_force``, ``friction_force``, ``wake_loss``, ``t_gross_sliding`` (NaN where not
defined), ``run_time``; transient sweeps add their time series (``mu_app_t`` ... along ``t``).
Failed runs are NaN and carry their message in the string variable ``error``; warnings go to
``warnings``.

The time axis ``t`` of a transient sweep is the union of the runs' record times. Runs of different
steps (``time.dt``, or a ``tangential.sliding_speed`` that sets it, ``output.every``) record
different times: each run's series is interpolated linearly onto the times it did not record inside
its own time range (NaN outside it). Those values were not computed: the attribute
``interpolated_runs`` lists such runs (JSON, their parameters) and :func:`assemble` warns once.
"""
from __future__ import annotations

import json
import math
from typing import TYPE_CHECKING, Any, Mapping, Sequence

import numpy as np

from viscontact.errors import warn_caller
from viscontact.io.case import case_keys
from viscontact.sweep.spec import Plan, format_value

if TYPE_CHECKING:  # xarray is imported where it is used
    import xarray as xr

__all__ = ["SERIES", "SUMMARIES", "assemble", "summarize"]

#: scalars kept of each run's final state (``t_gross_sliding`` and ``run_time`` are added)
SUMMARIES = ("mu_app", "peak_pressure", "contact_area", "contact_shift", "delta_z", "load",
             "hysteresis_force", "friction_force", "wake_loss")
#: the scalars whose time series a transient sweep keeps (as ``<name>_t``)
SERIES = ("mu_app", "peak_pressure", "contact_area", "contact_shift", "delta_z", "load")
_SUMMARY_UNITS = {"mu_app": "1", "peak_pressure": "Pa", "contact_area": "m2", "contact_shift": "m",
                  "delta_z": "m", "load": "N", "hysteresis_force": "N", "friction_force": "N",
                  "wake_loss": "1", "t_gross_sliding": "s", "run_time": "s"}


def summarize(ds: xr.Dataset, series: bool) -> dict[str, Any]:
    """Final-state scalars (and time series) of a run's Dataset."""
    nt = ds.sizes.get("t", 0)
    out: dict[str, Any] = {}
    for name in SUMMARIES:
        if name == "peak_pressure":
            value = float(ds["pressure"].isel(t=-1).max()) if "pressure" in ds and nt else math.nan
        else:
            value = float(ds[name].values[-1]) if name in ds and nt else math.nan
        out[name] = value
    out["t_gross_sliding"] = float(ds.attrs.get("t_gross_sliding", math.nan))
    out["complete"] = int(ds.attrs.get("complete", 0))
    if series:
        out["t"] = np.asarray(ds["t"].values, dtype=float)
        for name in SERIES:
            if name == "peak_pressure":
                data = ds["pressure"].max(("y", "x")).values if "pressure" in ds else np.full(nt, np.nan)
            else:
                data = ds[name].values if name in ds else np.full(nt, np.nan)
            out[f"{name}_t"] = np.asarray(data, dtype=float)
    return out


def _coordinate(values: Sequence[Any]) -> np.ndarray:
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return np.asarray(values, dtype=int if all(isinstance(v, int) for v in values) else float)
    if all(isinstance(v, (str, bool)) for v in values) and len({type(v) for v in values}) == 1:
        return np.asarray(values)
    return np.asarray([format_value(v) for v in values], dtype=object)


def _time_axis(results: Mapping[int, dict[str, Any]]) -> tuple[np.ndarray, float]:
    """Union of the runs' record times (equal within 1e-9 of the span merged) and that tolerance [s]."""
    times = [r["t"] for r in results.values() if not r["error"] and "t" in r and len(r["t"])]
    if not times:
        return np.zeros(0), 0.0
    t = np.unique(np.concatenate(times))
    tol = 1e-9 * max(float(t[-1] - t[0]), float(abs(t[-1])), 1e-300)
    keep = np.concatenate([[True], np.diff(t) > tol])
    return t[keep], tol


def _interpolated(t: np.ndarray, tr: np.ndarray, tol: float) -> bool:
    """Whether a run recording at ``tr`` is interpolated onto ``t``: some time of ``t`` inside the
    run's time range is none of its own (within ``tol``)."""
    inside = t[(t >= tr[0] - tol) & (t <= tr[-1] + tol)]
    nearest = np.clip(np.searchsorted(tr, inside), 1, tr.size - 1)
    gap = np.minimum(np.abs(inside - tr[nearest - 1]), np.abs(inside - tr[nearest]))
    return bool(np.any(gap > tol))


def assemble(the_plan: Plan, results: Mapping[int, dict[str, Any]], transient: bool) -> xr.Dataset:
    from viscontact.io.results import LINE_UNITS, VARIABLES, global_attrs

    spec = the_plan.spec
    dims, shape = spec.dims, tuple(len(v) for v in spec.parameters.values())
    names = list(SUMMARIES) + ["t_gross_sliding", "run_time"]
    arrays = {n: np.full(shape, np.nan) for n in names}
    error = np.full(shape, "", dtype=object)
    notes = np.full(shape, "", dtype=object)
    files = np.full(shape, "", dtype=object)
    t, tol = _time_axis(results) if transient else (None, 0.0)
    interpolated = []
    series = {f"{n}_t": np.full(shape + (t.size,), np.nan) for n in SERIES} if transient else {}
    for k, run in enumerate(the_plan.runs):
        files[run.index] = run.name
        r = results.get(k)
        if r is None:
            error[run.index] = "not run"
            continue
        error[run.index] = r["error"]
        notes[run.index] = "\n".join(r.get("warnings", []))
        arrays["run_time"][run.index] = r.get("run_time", math.nan)
        if r["error"]:
            continue
        for n in names[:-1]:
            arrays[n][run.index] = r[n]
        for n in series:
            tr, yr = r["t"], r[n]
            if tr.size == 1:
                series[n][run.index] = np.where(np.isclose(t, tr[0], rtol=1e-9, atol=0), yr[0], np.nan)
            elif tr.size:
                series[n][run.index] = np.interp(t, tr, yr, left=np.nan, right=np.nan)
        if transient and r["t"].size > 1 and _interpolated(t, r["t"], tol):
            interpolated.append(run.label)
    coords: dict[str, Any] = {}
    valid = case_keys()
    for key, dim in zip(spec.keys, dims):
        attrs = {"key": key, "long_name": key}
        extra = getattr(valid.get(key), "json_schema_extra", None) or {}
        if isinstance(extra, dict) and extra.get("unit"):
            attrs["units"] = extra["unit"]
        coords[dim] = (dim, _coordinate(spec.parameters[key]), attrs)
    base_attrs = global_attrs(the_plan.base.to_problem(), the_plan.base.text)
    line = base_attrs.get("grid_dimension") == 1  # a line contact: forces per unit length (N/m), widths (m)

    def units(name: str) -> str:
        return LINE_UNITS.get(_SUMMARY_UNITS[name], _SUMMARY_UNITS[name]) if line else _SUMMARY_UNITS[name]

    variables: dict[str, Any] = {}
    for n in names:
        long_name = VARIABLES.get(n, ("", n))[1] if n in VARIABLES else {
            "t_gross_sliding": "time gross sliding began (0 when sliding from t = 0, NaN when never)",
            "run_time": "wall time of the run"}[n]
        variables[n] = (dims, arrays[n], {"units": units(n), "long_name": f"{long_name}, final state"
                                          if n not in ("t_gross_sliding", "run_time") else long_name})
    variables["error"] = (dims, error.astype(str), {"long_name": "error of a failed run ('' when it succeeded)"})
    variables["warnings"] = (dims, notes.astype(str), {"long_name": "warnings of the run, one per line"})
    variables["run_file"] = (dims, files.astype(str), {"long_name": "result file of the run in the runs folder"})
    if transient:
        coords["t"] = ("t", t, {"units": "s", "long_name": "time (union of the runs' record times; each run "
                                "interpolated linearly, NaN outside its own time range)"})
        if interpolated:
            warn_caller(f"{len(interpolated)} of {len(the_plan.runs)} runs recorded other times than the "
                        "sweep's time axis t (the union of the runs' record times): their time series "
                        f"(mu_app_t, ...) are interpolated linearly there, not computed (first: {interpolated[0]}; "
                        "all in the attribute interpolated_runs)")
        for n, data in series.items():
            base = n[:-2]
            long_name = VARIABLES[base][1] if base in VARIABLES else base
            variables[n] = (dims + ("t",), data, {"units": units(base), "long_name": long_name})
    import xarray as xr

    ds = xr.Dataset(variables, coords=coords)
    for name in ("case", "a0", "p0", "retardation_time", "tangential_mode", "normal_control", "version",
                 "Conventions", "source", "references", "history"):
        ds.attrs[name] = base_attrs[name]
    if line:
        ds.attrs["grid_dimension"] = 1
    ds.attrs.update({"kind": "sweep", "solver": spec.solver, "title": spec.title or the_plan.base.title,
                     "swept_keys": json.dumps(list(spec.keys)), "fixed_overrides": json.dumps(the_plan.fixed),
                     "base": str(the_plan.base_path), "sweep": spec.text})
    if transient:
        ds.attrs["time_axis"] = ("union of the runs' record times: the series of a run that did not record "
                                 "some of them inside its own time range are interpolated linearly there "
                                 "(interpolated_runs), NaN outside that range")
        ds.attrs["interpolated_runs"] = json.dumps(interpolated)
    return ds
