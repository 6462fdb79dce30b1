"""Figures of a parameter sweep result (``kind == "sweep"``, see :mod:`viscontact.sweep`)."""
from __future__ import annotations

import itertools
import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from viscontact.plotting.base import FigureFiles, check_format, compact_log_ticks, positive_attr, pyplot, set_title

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["plot_sweep"]

_SPEED_DIM = "tangential__sliding_speed"
_LABELS = {"mu_app": "μ_app = F_T / W [-]", "peak_pressure": "peak pressure [MPa]",
           "contact_area": "contact area [mm²]"}
_SCALE = {"mu_app": 1.0, "peak_pressure": 1e-6, "contact_area": 1e6}
#: swept keys that leave a0 (Hertz with G(0)) and the retardation time unchanged
_SCALE_FREE = ("material.shear_modulus_long_term",)


def _legend(coord: Any, i: int) -> str:
    value = coord.values[i]
    value = value.item() if hasattr(value, "item") else value
    text = f"{value:.4g}" if isinstance(value, float) else str(value)
    unit = coord.attrs.get("units", "")
    key = str(coord.attrs.get("key", coord.name)).rsplit(".", 1)[-1]
    return f"{key} = {text}{f' {unit}' if unit else ''}"


def _what(ds: xr.Dataset, name: str) -> str:
    """What the figure of ``name`` adds to the sweep's title: the kind of sweep and the quantity,
    each unless the title says it already (``Steady mu_app vs speed``: nothing but ``sweep``)."""
    title = str(ds.attrs.get("title", "")).lower().replace("mu_app", "μ_app")
    quantity = _LABELS[name].split(" [")[0]
    solver = str(ds.attrs.get("solver", ""))
    kind = "" if "sweep" in title else "sweep" if solver.lower() in title else f"{solver} sweep".strip()
    return ": ".join(part for part in (kind, "" if quantity.split(" =")[0].lower() in title else quantity) if part)


def plot_sweep(ds: xr.Dataset, out_dir: str | Path, *, fmt: str = "png", dpi: int | None = None) -> list[Path]:
    """Figures of a sweep Dataset in ``out_dir`` (format ``fmt``: png, pdf or svg).

    ``sweep_mu_app.png``: μ_app against the sliding speed (log axis; against the first swept key
    when the speed is not swept), one line per combination of the other swept keys; the top axis
    shows v τ / a0 when τ and a0 are the same for every run. ``sweep_peak_pressure.png`` and
    ``sweep_contact_area.png`` likewise. Failed runs are gaps.
    """
    check_format(fmt, dpi)
    plt = pyplot()
    files = FigureFiles(Path(out_dir), fmt, dpi)
    keys = json.loads(ds.attrs.get("swept_keys", "[]")) or \
        [ds[d].attrs.get("key", d) for d in ds["mu_app"].dims if d != "t"]
    dims = [k.replace(".", "__") for k in keys]
    xdim = _SPEED_DIM if _SPEED_DIM in dims else dims[0]
    xkey = ds[xdim].attrs.get("key", xdim)
    others = [d for d in dims if d != xdim]
    xv = ds[xdim].values
    numeric = np.issubdtype(np.asarray(xv).dtype, np.number)
    order = np.argsort(xv) if numeric else np.arange(len(xv))
    logx = numeric and bool(np.all(xv > 0)) and (xdim == _SPEED_DIM or xv.max() / xv.min() >= 10)
    scale_fixed = not any(k.startswith(("material.", "normal.", "indenter.")) and k not in _SCALE_FREE for k in keys)
    tau, a0 = positive_attr(ds, "retardation_time"), positive_attr(ds, "a0")
    deborah = xdim == _SPEED_DIM and scale_fixed and tau is not None and a0 is not None
    paths = []
    for name in ("mu_app", "peak_pressure", "contact_area"):
        if name not in ds:
            continue
        fig, ax = plt.subplots(figsize=(6.4, 4.3))
        for combo in itertools.product(*(range(ds.sizes[d]) for d in others)):
            sel = dict(zip(others, combo))
            y = ds[name].isel(sel).values * _SCALE[name]
            label = ", ".join(_legend(ds[d], i) for d, i in sel.items())
            ax.plot(xv[order] if numeric else np.arange(len(xv)), y[order], "o-", ms=4, label=label or None)
        if logx:
            ax.set_xscale("log")
            compact_log_ticks(ax)
        if not numeric:
            ax.set_xticks(np.arange(len(xv)), [str(v) for v in xv])
        unit = ds[xdim].attrs.get("units", "")
        xlabel = "sliding speed v [m/s]" if xdim == _SPEED_DIM else f"{xkey}{f' [{unit}]' if unit else ''}"
        ax.set(xlabel=xlabel, ylabel=_LABELS[name])
        set_title(fig, ds, _what(ds, name))
        if deborah:
            k = tau / a0
            top = ax.secondary_xaxis("top", functions=(lambda v, k=k: v * k, lambda d, k=k: d / k))
            top.set_xlabel("v τ / a0")
            compact_log_ticks(top)
        ax.grid(alpha=0.3, which="both")
        if others:
            ax.legend(fontsize=7)
        fig.tight_layout()
        paths.append(files.save(fig, f"sweep_{name}"))
    return paths
