"""Figures of result Datasets (never of solver objects): ``viscontact plot`` works on any saved file.

All plotting lives in this package: :mod:`.base` (the pyplot helper, scales, the profile along
y = 0), :mod:`.result` (one run or a speed curve), :mod:`.rolling` (a traction-creepage curve),
:mod:`.sweep` (parameter sweeps), :mod:`.material`
(a material's functions) and :mod:`.seed` (the seed's figures, for :mod:`viscontact.reproduce`).
Matplotlib is imported when a figure is drawn (Agg backend), so importing viscontact never pulls it in.
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from viscontact.plotting.base import (
    DPI,
    FORMATS,
    FigureFiles,
    Scales,
    check_format,
    phase_name,
    profile,
    pyplot,
    save_figure,
)
from viscontact.plotting.material import plot_material
from viscontact.plotting.result import plot_result, plot_speed_curve
from viscontact.plotting.rolling import plot_creep_curve
from viscontact.plotting.sweep import plot_sweep

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["DPI", "FORMATS", "FigureFiles", "Scales", "check_format", "phase_name", "plot_any", "plot_creep_curve",
           "plot_material",
           "plot_result", "plot_speed_curve", "plot_sweep", "profile", "pyplot", "save_figure"]


def plot_any(ds: xr.Dataset, out_dir: str | Path, *, times: Sequence[float] | None = None, fmt: str = "png",
             dpi: int | None = None) -> list[Path]:
    """:func:`plot_sweep` for a parameter sweep, :func:`plot_material` for a material,
    :func:`plot_speed_curve` for a steady speed curve, :func:`plot_creep_curve` for a steady
    traction-creepage curve, :func:`plot_result` (profiles and maps at
    ``times`` [s]) otherwise; files of format ``fmt``."""
    if ds.attrs.get("kind") == "sweep":
        return plot_sweep(ds, out_dir, fmt=fmt, dpi=dpi)
    if ds.attrs.get("kind") == "material":
        return plot_material(ds, out_dir, fmt=fmt, dpi=dpi)
    if "speed" in ds.dims:
        return plot_speed_curve(ds, out_dir, fmt=fmt, dpi=dpi)
    if "creepage" in ds.dims:
        return plot_creep_curve(ds, out_dir, fmt=fmt, dpi=dpi)
    return plot_result(ds, out_dir, times=times, fmt=fmt, dpi=dpi)
