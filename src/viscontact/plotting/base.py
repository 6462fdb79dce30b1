"""What every figure shares: the pyplot helper, saving, the scales of a result and its profile along y = 0.

Figures are drawn from result Datasets only (never from solver objects). Matplotlib is imported by
:func:`pyplot` when a figure is drawn (Agg backend), so importing viscontact never pulls it in.
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..problem import PHASE_NAMES

if TYPE_CHECKING:  # xarray is imported where it is used
    import xarray as xr

__all__ = ["DPI", "Scales", "contact_state", "draw_contact_maps", "phase_name", "positive_attr", "profile", "pyplot",
           "save_figure", "time_index"]

#: resolution of the PNG files [dots per inch]
DPI = 150


def pyplot() -> Any:
    """``matplotlib.pyplot`` on the non-interactive Agg backend, imported on first use.

    Raises ImportError when matplotlib is missing: call it before a long computation whose figures
    are wanted, so that the run fails first.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig: Any, path: str | Path, *, dpi: int = DPI) -> Path:
    """Write ``fig`` to ``path`` (its folder created) and close it; returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi, bbox_inches="tight")
    pyplot().close(fig)
    return path


def positive_attr(ds: xr.Dataset, name: str) -> float | None:
    """The attribute ``name`` of ``ds`` as a finite positive float, else None."""
    value = ds.attrs.get(name)
    try:
        value = float(value)
    except (TypeError, ValueError):
        return None
    return value if np.isfinite(value) and value > 0 else None


class Scales:
    """Normalisation of a result: (scale, axis label) for lengths, pressures and times.

    Lengths are shown as x/a0, pressures as p/p0 and times as t/tau (tau = the ``retardation_time``
    attribute) when the Dataset has those attributes, else in mm, MPa and s.
    """

    def __init__(self, ds: xr.Dataset) -> None:
        a0, p0, tau = positive_attr(ds, "a0"), positive_attr(ds, "p0"), positive_attr(ds, "retardation_time")
        self.length = (a0, "x / a0") if a0 else (1e-3, "x [mm]")
        self.pressure = (p0, "p / p0") if p0 else (1e6, "p [MPa]")
        self.shear = (p0, "q_x / p0") if p0 else (1e6, "q_x [MPa]")
        self.time = (tau, "t / τ") if tau else (1.0, "t [s]")
        self.radius = (a0, "a / a0") if a0 else (1e-3, "a [mm]")

    def t_label(self, t: float) -> str:
        """``t/τ = 0.5`` (or ``t = 0.005 s`` without a time scale) for a time t [s]."""
        scale, label = self.time
        return f"t/τ = {t / scale:.3g}" if label.startswith("t /") else f"t = {t:.3g} s"


def profile(ds: xr.Dataset, name: str, k: int) -> tuple[np.ndarray, np.ndarray]:
    """The field ``name`` along y = 0 at record ``k``, against the indenter coordinate.

    Returns (x - frame_offset [m], values): on an even grid y = 0 falls between the two middle rows
    (y = +-dx/2) and the profile is their mean; on an odd grid it is the middle row. x - frame_offset
    is the distance from the indenter centre (``frame_offset`` = 0 when the result has none).
    """
    field = np.asarray(ds[name].values[k], dtype=float)
    n = field.shape[0]
    row = field[n // 2] if n % 2 else 0.5 * (field[n // 2 - 1] + field[n // 2])
    offset = float(ds["frame_offset"].values[k]) if "frame_offset" in ds else 0.0
    return np.asarray(ds["x"].values, dtype=float) - offset, row


def time_index(ds: xr.Dataset, t: float) -> int:
    """Index of the record nearest to the time t [s]."""
    return int(np.argmin(np.abs(ds["t"].values - t)))


def phase_name(code: int) -> str:
    """``"indentation"``, ``"partial slip"`` or ``"gross sliding"`` for a ``phase`` code."""
    return PHASE_NAMES[int(code)]


def contact_state(ds: xr.Dataset, k: int) -> np.ndarray:
    """0 open, 1 slip, 2 stick at record ``k`` (stick counts only where the result has ``stick``)."""
    state = (ds["pressure"].values[k] > 0).astype(int)
    if "stick" in ds:
        state = state + ds["stick"].values[k].astype(int)
    return state


def draw_contact_maps(ds: xr.Dataset, picks: list[int], sc: Scales, titles: list[str], suptitle: str) -> Any:
    """One map per record in ``picks`` of the contact (white: open, orange: slip, blue: stick) in the
    grid frame, axes scaled by ``sc``; returns the Figure."""
    plt = pyplot()
    from matplotlib.colors import ListedColormap

    x = ds["x"].values
    half = float(x[-1] + 0.5 * (x[1] - x[0])) / sc.length[0]
    fig, axes = plt.subplots(1, len(picks), figsize=(3.2 * len(picks), 3.4), squeeze=False)
    cmap = ListedColormap(["white", "tab:orange", "tab:blue"])
    for ax, k, title in zip(axes[0], picks, titles):
        ax.imshow(contact_state(ds, k), origin="lower", extent=(-half, half, -half, half), cmap=cmap, vmin=0, vmax=2,
                  interpolation="nearest")
        ax.set(title=title, xlabel=sc.length[1], ylabel=sc.length[1].replace("x", "y"))
    fig.suptitle(suptitle)
    fig.tight_layout()
    return fig
