"""Figures of one result file: a transient run, a single steady state, or a steady speed curve."""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..problem import PHASE_GROSS_SLIDING
from .base import Scales, draw_contact_maps, positive_attr, profile, pyplot, save_figure

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["plot_result", "plot_speed_curve", "profiles_figure"]


def _time_indices(nt: int, count: int = 6) -> np.ndarray:
    return np.unique(np.linspace(0, nt - 1, min(count, nt)).round().astype(int))


def profiles_figure(ds: xr.Dataset) -> Any:
    """Pressure (and shear, when nonzero) along y = 0 (:func:`~viscontact.plotting.base.profile`) at
    about six recorded times, against the distance from the indenter centre; returns the Figure."""
    plt = pyplot()
    sc = Scales(ds)
    shear = "shear_x" in ds and bool(np.any(ds["shear_x"].values != 0))
    fig, axes = plt.subplots(1, 2 if shear else 1, figsize=(11 if shear else 6, 4.2), squeeze=False)
    ax_p = axes[0, 0]
    mu = float(ds.attrs.get("friction_coefficient", 0.0) or 0.0)
    for k in _time_indices(ds.sizes["t"]):
        label = sc.t_label(float(ds["t"].values[k]))
        x, p = profile(ds, "pressure", k)
        line, = ax_p.plot(x / sc.length[0], p / sc.pressure[0], label=label)
        if shear:
            _, q = profile(ds, "shear_x", k)
            axes[0, 1].plot(x / sc.length[0], q / sc.shear[0], color=line.get_color(), label=label)
            if mu > 0:
                axes[0, 1].plot(x / sc.length[0], mu * p / sc.shear[0], color=line.get_color(), ls=":", lw=0.8)
    ax_p.set(xlabel=sc.length[1], ylabel=sc.pressure[1], title="pressure along y = 0")
    ax_p.legend(fontsize=8)
    if shear:
        title = "shear traction (dotted: μ_f p)" if mu > 0 else "shear traction"
        axes[0, 1].set(xlabel=sc.length[1], ylabel=sc.shear[1], title=title)
    return fig


def _contact_history(ds: xr.Dataset, sc: Scales) -> Any:
    fig, axes = pyplot().subplots(1, 3, figsize=(13, 3.8))
    t = ds["t"].values / sc.time[0]
    radius = np.sqrt(ds["contact_area"].values / np.pi) / sc.radius[0]
    axes[0].plot(t, radius)
    axes[0].set(xlabel=sc.time[1], ylabel=f"contact radius √(A/π), {sc.radius[1]}")
    axes[1].plot(t, ds["load"].values)
    axes[1].set(xlabel=sc.time[1], ylabel="load W [N]")
    axes[2].plot(t, ds["delta_z"].values * 1e6)
    axes[2].set(xlabel=sc.time[1], ylabel="approach δ_z [µm]")
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def _friction(ds: xr.Dataset, sc: Scales) -> Any:
    fig, ax = pyplot().subplots(figsize=(6, 4))
    t = ds["t"].values / sc.time[0]
    ax.plot(t, ds["mu_app"].values, label="μ_app = F_T / W (hysteresis)")
    if np.any(ds["friction_force"].values != 0):
        load = np.where(ds["load"].values > 0, ds["load"].values, np.nan)
        ax.plot(t, ds["friction_force"].values / load, ls="--", label="Σ q_x ΔA / W (dry)")
    t_gs = positive_attr(ds, "t_gross_sliding")
    if t_gs and ds.attrs.get("tangential_mode") == "partial_slip":
        ax.axvline(t_gs / sc.time[0], color="grey", lw=0.8, ls=":", label="gross sliding")
    ax.set(xlabel=sc.time[1], ylabel="friction coefficient [-]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def _stick_map(ds: xr.Dataset, sc: Scales) -> Any:
    phase = ds["phase"].values
    sliding = np.flatnonzero(phase == PHASE_GROSS_SLIDING)
    before = np.flatnonzero(phase < PHASE_GROSS_SLIDING)
    picks = before[_time_indices(before.size, 4 if sliding.size == 0 else 3)] if before.size else before
    picks = np.concatenate([picks, sliding[:1]]) if picks.size or sliding.size else np.array([0])
    titles = [sc.t_label(float(ds["t"].values[k])) + (" (gross sliding)" if phase[k] == PHASE_GROSS_SLIDING else "")
              for k in picks]
    return draw_contact_maps(ds, list(picks), sc, titles, "contact: slip (orange), stick (blue)")


def plot_result(ds: xr.Dataset, out_dir: str | Path) -> list[Path]:
    """Figures of a transient (or single steady) result, written as PNG into ``out_dir``.

    Always: pressure (and shear, when nonzero) along y = 0 at about six times
    (``pressure_profiles.png``) and contact radius, load and approach against time
    (``contact_history.png``). When sliding: apparent friction against time (``friction.png``).
    In partial slip: stick/slip maps (``stick_map.png``).

    Returns
    -------
    list of Path
        The files written.
    """
    out_dir = Path(out_dir)
    sc = Scales(ds)
    figures = {}
    if "pressure" in ds:
        figures["pressure_profiles.png"] = profiles_figure(ds)
    figures["contact_history.png"] = _contact_history(ds, sc)
    if ds.attrs.get("tangential_mode", "none") != "none":
        figures["friction.png"] = _friction(ds, sc)
    if ds.attrs.get("tangential_mode") == "partial_slip" and "stick" in ds and "pressure" in ds:
        figures["stick_map.png"] = _stick_map(ds, sc)
    return [save_figure(fig, out_dir / name) for name, fig in figures.items()]


def plot_speed_curve(ds: xr.Dataset, out_dir: str | Path) -> list[Path]:
    """μ_app against the Deborah number v τ / a0 (log axis) of a steady speed sweep (dimension
    ``speed``), as ``speed_curve.png`` in ``out_dir``; against v [m/s] when τ or a0 is unknown."""
    order = np.argsort(ds["speed"].values)
    tau, a0 = positive_attr(ds, "retardation_time"), positive_attr(ds, "a0")
    if tau and a0:
        x, label = ds["speed"].values * tau / a0, "Deborah number v τ / a0"
    else:
        x, label = ds["speed"].values, "sliding speed v [m/s]"
    fig, ax = pyplot().subplots(figsize=(6, 4))
    ax.semilogx(x[order], ds["mu_app"].values[order], "o-")
    ax.set(xlabel=label, ylabel="μ_app = F_T / W [-]", title="steady sliding: hysteresis friction")
    ax.grid(alpha=0.3, which="both")
    return [save_figure(fig, Path(out_dir) / "speed_curve.png")]
