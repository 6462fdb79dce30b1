"""The traction-creepage curve of steady rolling (a Dataset along ``creepage``:
:func:`viscontact.io.results.creepage_dataset`, ``viscontact steady --creepages``)."""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from viscontact.plotting.base import FigureFiles, check_drawable, check_format, pyplot, set_title

if TYPE_CHECKING:
    import xarray as xr


def creep_curve_figure(ds: xr.Dataset) -> Any:
    """Traction F / (mu_f W), stick ratio and rolling resistance F_T / W against the creepage
    (V_c - V) / V [-] (signs: the result's, braking xi < 0 giving F > 0); returns the Figure."""
    order = np.argsort(ds["creepage"].values)
    creepage = ds["creepage"].values[order]
    load = ds["load"].values[order]
    panels = ((ds["traction_ratio"].values[order], "traction F / (μ_f W) [-]"),
              (ds["stick_ratio"].values[order], "stick area / contact area [-]"),
              (ds["hysteresis_force"].values[order] / load, "rolling resistance F_T / W [-]"))
    fig, axes = pyplot().subplots(1, 3, figsize=(13.0, 4.0), sharex=True)
    for ax, (values, label) in zip(axes, panels):
        ax.plot(creepage, values, "o-", ms=4)
        ax.set(xlabel="creepage ξ = (V_c − V) / V [-]", ylabel=label)
        ax.grid(alpha=0.3)
        ax.ticklabel_format(axis="y", useOffset=False)
    speed = ds.attrs.get("rolling_speed")
    set_title(fig, ds, f"steady rolling at V = {float(speed):.4g} m/s" if speed is not None else "steady rolling")
    fig.tight_layout()
    return fig


def plot_creep_curve(ds: xr.Dataset, out_dir: str | Path, *, fmt: str = "png", dpi: int | None = None) -> list[Path]:
    """:func:`creep_curve_figure` as ``creep_curve.<fmt>`` in ``out_dir``."""
    check_format(fmt, dpi)
    check_drawable(ds, "creepage", ("traction_ratio", "stick_ratio", "hysteresis_force"))
    return [FigureFiles(Path(out_dir), fmt, dpi).save(creep_curve_figure(ds), "creep_curve")]
