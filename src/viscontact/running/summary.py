"""The headline numbers of a result, as a dict with units and as a few lines of text.

What ``viscontact run``, ``steady`` and ``sweep`` print when they end (``--json``: one JSON object),
computed from the result alone, so that scripts and figures can use it too::

    import viscontact as vc
    from viscontact.running.summary import format_summary, summary
    print(format_summary(summary(vc.open_result("r.nc"))))

Of a transient run (``kind = "run"``): the final time, load, approach ``delta_z``, contact radius
sqrt(A/pi), peak pressure (with the field ``pressure`` recorded), the last ``mu_app`` and, once
sliding, its steady state (:func:`steady_mu_app`), the onset of gross sliding ``t_gross_sliding``,
the friction force and, under a cyclic displacement, the energy dissipated in the last cycle. Of a
steady speed curve (``kind = "steady"``): one row per speed. Of a sweep (``kind = "sweep"``): one row
per run with its swept values and ``mu_app``. Quantities a tangential mode defines as zero (the
variable's ``note``) are left out.
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["SETTLED", "UNITS", "format_summary", "print_summary", "steady_mu_app", "summary", "summary_of_file"]

#: units (SI) of every quantity of a summary ('1': a ratio)
UNITS: dict[str, str] = {
    "t_end": "s", "load": "N", "delta_z": "m", "contact_radius": "m", "peak_pressure": "Pa", "mu_app": "1",
    "mu_app_steady": "1", "t_gross_sliding": "s", "friction_force": "N", "energy_last_cycle": "J",
    "pull_off_force": "N", "t_pull_off": "s", "creepage": "1", "stick_ratio": "1",
    "speed": "m/s", "deborah": "1", "run_time": "s",
}
#: numbers that are result attributes, not variables, with the variable whose unit is theirs (a line
#: contact's forces: N/m)
UNIT_OF = {"pull_off_force": "load"}
#: how each quantity is named in the text
LABELS: dict[str, str] = {
    "t_end": "final time", "load": "normal load W", "delta_z": "approach delta_z", "contact_radius":
    "contact radius sqrt(A/pi)", "peak_pressure": "peak pressure", "mu_app": "mu_app (last record)",
    "mu_app_steady": "mu_app (steady state)", "t_gross_sliding": "gross sliding from t", "friction_force":
    "friction force Q", "energy_last_cycle": "energy dissipated, last cycle",
    "creepage": "creepage (last record)", "stick_ratio": "stick ratio (last record)",
}
#: the relative change of ``mu_app`` over the last quarter of sliding below which it is steady
SETTLED = 0.01
#: rows of a sweep's table printed at most (all are in ``--json`` and ``viscontact export``)
MAX_ROWS = 20


def summary(ds: Any) -> dict[str, Any]:
    """The headline numbers of the result ``ds``.

    Parameters
    ----------
    ds
        A result :class:`xarray.Dataset` of ``run``, ``steady`` or ``sweep``
        (:func:`viscontact.io.netcdf.open_result`), or a :class:`viscontact.io.export.ResultFile`.

    Returns
    -------
    dict
        ``kind`` (``"run"``, ``"steady"`` or ``"sweep"``), ``title``, ``complete`` (bool), ``values``
        (name -> number, None where not reached, e.g. ``t_gross_sliding`` of a run that never slid),
        ``rows`` (steady: one dict per speed; sweep: one per run, with ``error``; run: none) and
        ``units`` (name -> SI unit of every number in ``values`` and ``rows``) and ``scales``
        (the result's Hertz ``a0`` [m] and ``p0`` [Pa], None where undefined).
    """
    attrs = ds.attrs
    kind = "sweep" if attrs.get("kind") == "sweep" else "steady" if attrs.get("solver") == "steady" else "run"
    out: dict[str, Any] = {"kind": kind, "title": str(attrs.get("title", "")),
                           "complete": bool(int(attrs.get("complete", 1))), "values": {}, "rows": [], "units": {}}
    if kind == "run":
        out["values"] = _run_values(ds)
    elif kind == "steady":
        rolling = ("creepage", "friction_force", "stick_ratio") if "creepage" in ds.variables else ("friction_force",)
        out["rows"] = _rows(ds, ("speed", "deborah", "mu_app", "delta_z", "contact_radius", "peak_pressure", *rolling))
    else:
        out["rows"] = _rows(ds, (*_swept(ds), "mu_app", "t_gross_sliding", "error"))
        if not any(row.get("t_gross_sliding") for row in out["rows"]):  # steady, or sliding from t = 0
            for row in out["rows"]:
                row.pop("t_gross_sliding", None)
        out["values"] = {key: int(attrs[key]) for key in ("runs_computed", "runs_reused", "runs_failed")
                         if key in attrs}
    names = set(out["values"]) | {name for row in out["rows"] for name in row}
    out["units"] = {name: _unit(ds, name) for name in sorted(names) if _unit(ds, name) is not None}
    out["scales"] = {name: _plain(float(attrs.get(name, math.nan))) for name in ("a0", "p0")}
    if _line(ds):
        out["labels"] = LINE_LABELS
    return out


#: the labels of a line contact's (``grid.dimension = 1``) numbers where they differ from :data:`LABELS`
LINE_LABELS = {"contact_radius": "contact half-width A/2", "load": "normal load W per unit length"}
#: the column headers of a line contact's tables where they differ from the names (the names, e.g. of
#: ``--json``'s rows, stay those of the result)
LINE_COLUMNS = {"contact_radius": "contact_half_width"}


def _line(ds: Any) -> bool:
    """Whether ``ds`` is a line contact's result (plane strain: forces per unit length)."""
    return int(ds.attrs.get("grid_dimension", 2)) == 1


def _contact_radius(ds: Any, area: Any) -> Any:
    """sqrt(A/pi) [m] of the contact area A [m^2], or a line contact's half-width A/2 [m] (A per unit
    length [m])."""
    area = np.maximum(area, 0.0)
    return area / 2.0 if _line(ds) else np.sqrt(area / math.pi)


def summary_of_file(path: str | Path) -> dict[str, Any]:
    """:func:`summary` of the result file ``path``, read with h5netcdf (no xarray: what ``viscontact
    run`` prints); ``file`` is added."""
    from viscontact.io.export import ResultFile

    with ResultFile(path) as f:
        return {**summary(f), "file": str(path)}


def steady_mu_app(t: np.ndarray, mu_app: np.ndarray, t_gross_sliding: float) -> tuple[float, float]:
    """``mu_app`` sliding has settled to, and how much it changes on the way there.

    Over the last quarter of the records since gross sliding began (at least 4 records): their
    mean, and the relative change (max - min) / |mean|. The mean is the steady state when that
    change is at most :data:`SETTLED`.

    Returns
    -------
    (mean, change)
        NaN, NaN when the run has not slid over 4 records.
    """
    sliding = np.flatnonzero(np.asarray(t) >= t_gross_sliding) if math.isfinite(t_gross_sliding) else []
    if len(sliding) < 4:
        return math.nan, math.nan
    last = np.asarray(mu_app, dtype=float)[sliding[-max(len(sliding) // 4, 4):]]
    mean = float(np.mean(last))
    spread = float(np.max(last) - np.min(last))
    return mean, (spread / abs(mean) if mean else (0.0 if spread == 0 else math.inf))


def _defined(ds: Any, name: str) -> bool:
    """``name`` is in ``ds`` and not zero by definition (its ``note``)."""
    return name in ds.variables and "note" not in ds[name].attrs


def _last(ds: Any, name: str) -> float:
    return float(ds[name][-1]) if _defined(ds, name) and ds[name].shape[0] else math.nan


def _run_values(ds: Any) -> dict[str, Any]:
    """The headline numbers of a transient result."""
    if not ds["t"].shape[0]:
        return {}
    t = np.asarray(ds["t"].values, dtype=float)
    values: dict[str, Any] = {"t_end": float(t[-1])}
    for name in ("load", "delta_z"):
        values[name] = _last(ds, name)
    values["contact_radius"] = float(_contact_radius(ds, _last(ds, "contact_area")))
    if "pressure" in ds.variables:
        values["peak_pressure"] = float(np.max(ds["pressure"][-1]))
    if _defined(ds, "mu_app"):
        values["mu_app"] = _last(ds, "mu_app")
        onset = float(ds.attrs.get("t_gross_sliding", math.nan))
        mean, change = steady_mu_app(t, ds["mu_app"].values, onset)
        if math.isfinite(mean):
            values["mu_app_steady"] = mean if change <= SETTLED else None
    if ds.attrs.get("tangential_mode") == "partial_slip":
        onset = float(ds.attrs.get("t_gross_sliding", math.nan))
        values["t_gross_sliding"] = onset if math.isfinite(onset) else None
    if _defined(ds, "friction_force"):
        values["friction_force"] = _last(ds, "friction_force")
    if "creepage" in ds.variables:  # rolling: its creepage and stick ratio
        values["creepage"], values["stick_ratio"] = _last(ds, "creepage"), _last(ds, "stick_ratio")
    if "energy_per_cycle" in ds.variables and ds["energy_per_cycle"].shape[0]:
        values["energy_last_cycle"] = float(ds["energy_per_cycle"][-1])
    if "pull_off_force" in ds.attrs:  # an adhesive run (NaN: no tensile load in it)
        values["pull_off_force"] = float(ds.attrs["pull_off_force"])
        values["t_pull_off"] = float(ds.attrs["t_pull_off"])
    return {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in values.items()}


def _swept(ds: Any) -> list[str]:
    """The dimensions a sweep's runs vary along (the swept keys, ``.`` written ``__``)."""
    return [dim for dim in ds["mu_app"].dims if dim != "t"]


def _rows(ds: Any, names: tuple[str, ...]) -> list[dict[str, Any]]:
    """One dict per element of ``mu_app`` (a speed, a run) of the ``names`` in ``ds``."""
    from viscontact.io.export import table

    columns, _ = table(ds)
    rows = len(columns["mu_app"])
    if "contact_area" in columns:
        columns["contact_radius"] = _contact_radius(ds, columns["contact_area"])
    if "speed" in names and "speed" not in columns:  # one steady state (along t): its speed, its peak
        columns["speed"] = np.full(rows, float(ds.attrs.get("sliding_speed", math.nan)))
        if "pressure" in ds.variables:
            columns["peak_pressure"] = np.array([float(np.max(ds["pressure"][k])) for k in range(rows)])
    keep = [name for name in names if name in columns and (name not in ds.variables or _defined(ds, name)
                                                           or name == "contact_radius")]
    return [{name: _plain(columns[name][k]) for name in keep} for k in range(rows)]


def _plain(value: Any) -> Any:
    """A table cell as JSON takes it: NaN as None, numpy scalars as Python's."""
    if isinstance(value, (np.integer, int)):
        return int(value)
    if isinstance(value, (np.floating, float)):
        return float(value) if math.isfinite(value) else None
    return str(value)


def _unit(ds: Any, name: str) -> str | None:
    """The unit of ``name``: the result variable's own (a line contact's forces are per unit length,
    N/m), else :data:`UNITS`'."""
    variable = name if name in ds.variables else UNIT_OF.get(name)
    if variable in ds.variables and ds[variable].attrs.get("units"):
        return str(ds[variable].attrs["units"])
    return UNITS.get(name)


def format_summary(s: dict[str, Any]) -> str:
    """:func:`summary` ``s`` as lines of text: one line per number of a run (lengths and pressures
    also in the result's a0 and p0 where defined), a table of a steady speed curve or a sweep."""
    head = f"summary of {s['title']!r}" + ("" if s["complete"] else " (incomplete: the steps done)")
    lines = [head + ":"]
    scales = {k: v for k, v in s.get("scales", {}).items() if v}
    if s["kind"] == "run":
        values = dict(s["values"])
        pull_off = {k: values.pop(k) for k in ("pull_off_force", "t_pull_off") if k in values}
        labels = {**LABELS, **s.get("labels", {})}
        width = max((len(labels.get(k, k)) for k in values), default=0)
        for name, value in values.items():
            lines.append(f"  {labels.get(name, name):<{width}}  {_quantity(name, value, s['units'], scales)}")
        if pull_off:  # an adhesive run: its own line, last
            force, t = pull_off["pull_off_force"], pull_off["t_pull_off"]
            lines.append("pull-off: none (no tensile load in the run)" if force is None else
                         f"pull-off force {force:.6g} {s['units'].get('pull_off_force', 'N')} at t = {t:.6g} s")
    else:
        rows = s["rows"]
        if s["kind"] == "sweep" and s["values"]:
            v = s["values"]
            lines[0] = head + f": {sum(v.get(k, 0) for k in ('runs_computed', 'runs_reused'))} runs, " \
                              f"{v.get('runs_failed', 0)} failed"
        lines += _table(rows[:MAX_ROWS], s["units"], LINE_COLUMNS if "labels" in s else {})
        if len(rows) > MAX_ROWS:
            lines.append(f"  ... {len(rows) - MAX_ROWS} more (all: --json, or viscontact export RESULT.nc --csv)")
    return "\n".join(lines)


def _quantity(name: str, value: Any, units: dict[str, str], scales: dict[str, float]) -> str:
    """``value`` with its unit, and in a0 or p0 where given."""
    if value is None:
        return "not reached" if name in ("t_gross_sliding", "mu_app_steady") else "-"
    unit = units.get(name, "")
    text = f"{value:.4g}" + ("" if unit in ("", "1") else f" {unit}")
    scale = {"m": ("a0", "a0"), "Pa": ("p0", "p0")}.get(unit)
    if scale and scale[0] in scales:
        text += f"  ({value / scales[scale[0]]:.4g} {scale[1]})"
    return text


def _table(rows: list[dict[str, Any]], units: dict[str, str], columns: dict[str, str] | None = None) -> list[str]:
    """``rows`` as an aligned text table, a header of names (or their ``columns`` header) and units first."""
    if not rows:
        return ["  (no rows)"]
    columns = columns or {}
    names = [name for name in rows[0] if name != "error" or any(row["error"] for row in rows)]
    header = [columns.get(name, name).replace("__", ".")
              + (f" [{units[name]}]" if units.get(name) not in (None, "1", "") else "")
              for name in names]
    cells = [[_cell(row[name]) for name in names] for row in rows]
    widths = [max(len(h), *(len(c[i]) for c in cells)) for i, h in enumerate(header)]
    return ["  " + "  ".join(f"{h:>{w}}" for h, w in zip(header, widths)),
            *("  " + "  ".join(f"{c:>{w}}" for c, w in zip(cell, widths)) for cell in cells)]


def _cell(value: Any) -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value) if value != "" else "-"


def print_summary(source: Any, *, as_json: bool = False, files: list[str] | None = None, note: str = "") -> None:
    """Print the summary of ``source`` (a result Dataset, or the path of a result file) on stdout:
    with ``as_json`` one JSON object (``files`` added), else ``wrote FILES NOTE`` and the text of
    :func:`format_summary`."""
    s = summary_of_file(source) if isinstance(source, (str, Path)) else summary(source)
    if as_json:
        print(json.dumps({**s, "files": list(files or [])}, allow_nan=False))
        return
    if files:
        print(f"wrote {', '.join(files)}{note}")
    print(format_summary(s))
