"""Figures of a result Dataset (never of solver objects): ``viscontact plot`` works on any saved file.

Matplotlib is imported inside the functions (Agg backend), so importing viscontact never pulls it in.
Lengths are shown as x/a0, pressures as p/p0 and times as t/tau (tau = ``retardation_time``) when
the Dataset has those attributes, else in SI units.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

__all__ = ["plot_result", "plot_speed_curve"]

DPI = 150


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _finite(ds: xr.Dataset, name: str) -> float | None:
    value = ds.attrs.get(name)
    try:
        value = float(value)
    except (TypeError, ValueError):
        return None
    return value if np.isfinite(value) and value > 0 else None


class _Scales:
    """Normalisation of a Dataset: (scale, axis label) for lengths, pressures and times."""

    def __init__(self, ds: xr.Dataset) -> None:
        a0, p0, tau = _finite(ds, "a0"), _finite(ds, "p0"), _finite(ds, "retardation_time")
        self.length = (a0, "x / a0") if a0 else (1e-3, "x [mm]")
        self.pressure = (p0, "p / p0") if p0 else (1e6, "p [MPa]")
        self.shear = (p0, "q_x / p0") if p0 else (1e6, "q_x [MPa]")
        self.time = (tau, "t / τ") if tau else (1.0, "t [s]")
        self.radius = (a0, "a / a0") if a0 else (1e-3, "a [mm]")

    def t_label(self, t: float) -> str:
        scale, label = self.time
        return f"{label.split(' ')[0]}/τ = {t / scale:.3g}" if label.startswith("t /") else f"t = {t:.3g} s"


def _time_indices(nt: int, count: int = 6) -> np.ndarray:
    return np.unique(np.linspace(0, nt - 1, min(count, nt)).round().astype(int))


def _save(fig: Any, out_dir: Path, name: str) -> Path:
    path = out_dir / name
    fig.savefig(path, dpi=DPI, bbox_inches="tight")
    _pyplot().close(fig)
    return path


def _profiles(ds: xr.Dataset, sc: _Scales, out_dir: Path) -> Path:
    plt = _pyplot()
    shear = "shear_x" in ds and bool(np.any(ds["shear_x"].values != 0))
    fig, axes = plt.subplots(1, 2 if shear else 1, figsize=(11 if shear else 6, 4.2), squeeze=False)
    ax_p = axes[0, 0]
    row = ds.sel(y=0.0, method="nearest")
    x = ds["x"].values / sc.length[0]
    mu = float(ds.attrs.get("friction_coefficient", 0.0) or 0.0)
    for k in _time_indices(ds.sizes["t"]):
        label = sc.t_label(float(ds["t"].values[k]))
        line, = ax_p.plot(x, row["pressure"].values[k] / sc.pressure[0], label=label)
        if shear:
            ax_q = axes[0, 1]
            ax_q.plot(x, row["shear_x"].values[k] / sc.shear[0], color=line.get_color(), label=label)
            if mu > 0:
                ax_q.plot(x, mu * row["pressure"].values[k] / sc.shear[0], color=line.get_color(), ls=":", lw=0.8)
    ax_p.set(xlabel=sc.length[1], ylabel=sc.pressure[1], title="pressure along y ≈ 0")
    ax_p.legend(fontsize=8)
    if shear:
        ax_q = axes[0, 1]
        title = "shear traction (dotted: μ_f p)" if mu > 0 else "shear traction"
        ax_q.set(xlabel=sc.length[1], ylabel=sc.shear[1], title=title)
    return _save(fig, out_dir, "pressure_profiles.png")


def _contact_history(ds: xr.Dataset, sc: _Scales, out_dir: Path) -> Path:
    plt = _pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
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
    return _save(fig, out_dir, "contact_history.png")


def _friction(ds: xr.Dataset, sc: _Scales, out_dir: Path) -> Path:
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    t = ds["t"].values / sc.time[0]
    ax.plot(t, ds["mu_app"].values, label="μ_app = F_T / W (hysteresis)")
    if np.any(ds["friction_force"].values != 0):
        load = np.where(ds["load"].values > 0, ds["load"].values, np.nan)
        ax.plot(t, ds["friction_force"].values / load, ls="--", label="Σ q_x ΔA / W (dry)")
    t_gs = _finite(ds, "t_gross_sliding")
    if t_gs and ds.attrs.get("tangential_mode") == "partial_slip":
        ax.axvline(t_gs / sc.time[0], color="grey", lw=0.8, ls=":", label="gross sliding")
    ax.set(xlabel=sc.time[1], ylabel="friction coefficient [-]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, out_dir, "friction.png")


def _stick_map(ds: xr.Dataset, sc: _Scales, out_dir: Path) -> Path:
    plt = _pyplot()
    from matplotlib.colors import ListedColormap

    phase = ds["phase"].values
    sliding = np.flatnonzero(phase == 2)
    before = np.flatnonzero(phase <= 1)
    picks = before[_time_indices(before.size, 4 if sliding.size == 0 else 3)] if before.size else before
    picks = np.concatenate([picks, sliding[:1]]) if picks.size or sliding.size else np.array([0])
    fig, axes = plt.subplots(1, len(picks), figsize=(3.2 * len(picks), 3.4), squeeze=False)
    half = float(ds["x"].values[-1] + 0.5 * (ds["x"].values[1] - ds["x"].values[0])) / sc.length[0]
    cmap = ListedColormap(["white", "tab:orange", "tab:blue"])
    for ax, k in zip(axes[0], picks):
        state = (ds["pressure"].values[k] > 0).astype(int) + ds["stick"].values[k].astype(int)
        ax.imshow(state, origin="lower", extent=(-half, half, -half, half), cmap=cmap, vmin=0, vmax=2,
                  interpolation="nearest")
        title = sc.t_label(float(ds["t"].values[k])) + (" (gross sliding)" if phase[k] == 2 else "")
        ax.set(title=title, xlabel=sc.length[1], ylabel=sc.length[1].replace("x", "y"))
    fig.suptitle("contact: slip (orange), stick (blue)")
    fig.tight_layout()
    return _save(fig, out_dir, "stick_map.png")


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
    out_dir.mkdir(parents=True, exist_ok=True)
    sc = _Scales(ds)
    paths = []
    if "pressure" in ds:
        paths.append(_profiles(ds, sc, out_dir))
    paths.append(_contact_history(ds, sc, out_dir))
    if ds.attrs.get("tangential_mode", "none") != "none":
        paths.append(_friction(ds, sc, out_dir))
    if ds.attrs.get("tangential_mode") == "partial_slip" and "stick" in ds and "pressure" in ds:
        paths.append(_stick_map(ds, sc, out_dir))
    return paths


def plot_speed_curve(ds: xr.Dataset, out_dir: str | Path) -> list[Path]:
    """μ_app against the Deborah number v τ / a0 (log axis) of a steady speed sweep (dimension
    ``speed``), as ``speed_curve.png`` in ``out_dir``; against v [m/s] when τ or a0 is unknown."""
    plt = _pyplot()
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    order = np.argsort(ds["speed"].values)
    tau, a0 = _finite(ds, "retardation_time"), _finite(ds, "a0")
    if tau and a0:
        x, label = ds["speed"].values * tau / a0, "Deborah number v τ / a0"
    else:
        x, label = ds["speed"].values, "sliding speed v [m/s]"
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogx(x[order], ds["mu_app"].values[order], "o-")
    ax.set(xlabel=label, ylabel="μ_app = F_T / W [-]", title="steady sliding: hysteresis friction")
    ax.grid(alpha=0.3, which="both")
    return [_save(fig, out_dir, "speed_curve.png")]


def plot_any(ds: xr.Dataset, out_dir: str | Path) -> list[Path]:
    """:func:`viscontact.sweep.plot_sweep` for a parameter sweep, :func:`plot_speed_curve` for a steady
    speed curve, :func:`plot_result` otherwise."""
    if ds.attrs.get("kind") == "sweep":
        from .sweep import plot_sweep

        return plot_sweep(ds, out_dir)
    return plot_speed_curve(ds, out_dir) if "speed" in ds.dims else plot_result(ds, out_dir)
