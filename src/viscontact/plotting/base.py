"""What every figure shares: the pyplot helper, saving, the scales of a result and its profile along y = 0.

Figures are drawn from result Datasets only (never from solver objects). Matplotlib is imported by
:func:`pyplot` when a figure is drawn (Agg backend), so importing viscontact never pulls it in.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from viscontact.errors import ParameterError
from viscontact.problem.problem import PHASE_NAMES

if TYPE_CHECKING:  # xarray is imported where it is used
    import xarray as xr

__all__ = ["DPI", "FORMATS", "FigureFiles", "Scales", "cell_limits", "check_format", "contact_state",
           "draw_contact_maps", "draw_map", "fit_title", "format_duration", "is_periodic", "is_steady", "map_image",
           "nominal_pressure", "period", "phase_name", "positive_attr", "profile", "pyplot", "retardation_count",
           "save_figure", "scales_line", "set_title", "tau_line", "time_index", "compact_log_ticks", "integer_ticks", "legend_key"]

#: resolution of raster figures [dots per inch] unless asked otherwise
DPI = 150
#: file formats a figure may be written in
FORMATS = ("png", "pdf", "svg")


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


def check_format(fmt: str, dpi: int | None = None) -> None:
    """:class:`ParameterError` (``--format``, ``--dpi``) unless ``fmt`` is one of :data:`FORMATS` and
    ``dpi`` is None or an integer in [10, 2400]."""
    if fmt not in FORMATS:
        raise ParameterError("--format", f"must be one of {', '.join(FORMATS)}, got {fmt!r}")
    if dpi is not None and not (isinstance(dpi, int) and 10 <= dpi <= 2400):
        raise ParameterError("--dpi", f"must be an integer in [10, 2400] dots per inch, got {dpi!r}")


@dataclass(frozen=True)
class FigureFiles:
    """Where and how figures are written: ``folder``, format ``fmt`` (:data:`FORMATS`) and ``dpi``."""

    folder: Path
    fmt: str = "png"
    dpi: int | None = None

    def save(self, fig: Any, stem: str) -> Path:
        """Write ``fig`` as ``folder/stem.fmt`` and close it."""
        return save_figure(fig, self.folder / f"{stem}.{self.fmt}", dpi=self.dpi or DPI)

    def save_animation(self, fig: Any, frame: Callable[[int], Any], frames: int, stem: str, fps: int = 8) -> Path:
        """Write the animation of ``fig`` that ``frame(i)`` draws for i < ``frames`` as ``folder/stem.gif``
        (matplotlib's PillowWriter) and close ``fig``."""
        from matplotlib.animation import FuncAnimation, PillowWriter

        path = self.folder / f"{stem}.gif"
        path.parent.mkdir(parents=True, exist_ok=True)
        FuncAnimation(fig, frame, frames=frames).save(path, writer=PillowWriter(fps=fps), dpi=min(self.dpi or DPI, 100))
        pyplot().close(fig)
        return path


def check_drawable(ds: xr.Dataset, dim: str, names: Sequence[str]) -> None:
    """Refuse, before any figure is written, a result that has nothing to draw along ``dim`` (``t``
    or ``speed``): no record (a run killed before its first record was written leaves such a
    ``.partial`` file), or none of the variables ``names`` that its figures read (a file thinned
    or rewritten by another program).

    Raises
    ------
    ParameterError
        Keyed by the file the Dataset was read from (``result`` when it was not read from one).
    """
    from viscontact.errors import ParameterError

    where = str(ds.encoding.get("source") or "result")
    if not ds.sizes.get(dim, 0):
        raise ParameterError(where, f"holds no record (dimension {dim!r} is empty, as in the streamed file of "
                             "a run killed before its first record): nothing to draw")
    missing = [name for name in names if name not in ds.variables]
    if missing:
        raise ParameterError(where, f"has no variable {', '.join(map(repr, missing))}, which the figures of this "
                             "result draw: plot a result file as viscontact wrote it")


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


def is_line(ds: xr.Dataset) -> bool:
    """Whether ``ds`` is a line contact's result (``grid.dimension = 1``: one row, plane strain; its
    fields are drawn as profiles, not maps)."""
    return int(ds.attrs.get("grid_dimension", 2)) == 1


def is_periodic(ds: xr.Dataset) -> bool:
    """The result is one period of a periodic domain (``grid.periodic = true``)."""
    return bool(int(ds.attrs.get("grid_periodic", 0) or 0))


def period(ds: xr.Dataset) -> float | None:
    """Side L = 2 half_width [m] of the (square) domain, None when the result does not say."""
    half_width = positive_attr(ds, "grid_half_width")
    return 2.0 * half_width if half_width else None


def nominal_pressure(ds: xr.Dataset) -> float | None:
    """Nominal (mean) pressure W / L² [Pa] of a periodic result under a held load (``normal_control =
    "load"``, the reference load ``normal_reference`` [N] on one period of side L), else None."""
    side, load = period(ds), positive_attr(ds, "normal_reference")
    if not (is_periodic(ds) and side and load and ds.attrs.get("normal_control") == "load"):
        return None
    return load / side**2


def format_duration(seconds: float) -> str:
    """A duration in the unit that puts it in [1, 1000): ``10 ms``, ``136.8 ns``, ``2.5 s``."""
    for scale, unit in ((1.0, "s"), (1e-3, "ms"), (1e-6, "µs"), (1e-9, "ns")):
        if abs(seconds) >= scale:
            return f"{seconds / scale:.4g} {unit}"
    return f"{seconds / 1e-12:.4g} ps" if seconds else "0 s"


def retardation_count(ds: xr.Dataset) -> int:
    """How many retardation times the result's material has (as many as its Prony terms; 1 when the
    result does not keep them)."""
    return int(np.atleast_1d(ds.attrs["relaxation_times"]).size) if "relaxation_times" in ds.attrs else 1


def tau_line(ds: xr.Dataset) -> str:
    """``τ = 10 ms``, or ``τ = 136.8 ns (the shortest of 10 retardation times)``; empty without τ."""
    tau = positive_attr(ds, "retardation_time")
    if not tau:
        return ""
    count = retardation_count(ds)
    return f"τ = {format_duration(tau)}" + (f" (the shortest of {count} retardation times)" if count > 1 else "")


def scales_line(ds: xr.Dataset) -> str:
    """``a0 = 588.7 µm, p0 = 0.2067 MPa, τ = 10 ms``: the scales of a result (those it has; τ in the unit
    that suits it, and said to be the shortest retardation time where the material has several); a
    periodic result: ``period L = 1 mm, p̄ = W/L² = 10 kPa, τ = 10 ms``."""
    a0, p0 = positive_attr(ds, "a0"), positive_attr(ds, "p0")
    side, mean_p = (period(ds), nominal_pressure(ds)) if is_periodic(ds) else (None, None)
    parts = [f"period L = {side * 1e3:.4g} mm" if side else "",
             f"p̄ = W/L² = {mean_p * 1e-3:.4g} kPa" if mean_p else "",
             f"a0 = {a0 * 1e6:.4g} µm" if a0 else "", f"p0 = {p0 * 1e-6:.4g} MPa" if p0 else "",
             tau_line(ds)]
    return ", ".join(p for p in parts if p)


def set_title(fig: Any, ds: xr.Dataset, what: str) -> Any:
    """The figure's title: the result's title (or case), what is drawn, and its scales; returns the
    Text."""
    name = str(ds.attrs.get("title", "") or "")
    head = f"{name}: {what}" if name and what else name or what
    return fig.suptitle("\n".join(line for line in (head, scales_line(ds)) if line), fontsize=10)


def fit_title(fig: Any, title: Any, margin: float = 0.02) -> float:
    """Wrap the lines of the figure title ``title`` (a Text) until it fits the figure's width less
    ``margin`` on each side, for a figure saved at its own size (an animation's frames: nothing is
    cut by ``bbox_inches="tight"`` there); returns the height it takes, a fraction of the figure's."""
    import textwrap

    lines = title.get_text().split("\n")
    renderer = fig.canvas.get_renderer()
    for width in range(max(len(line) for line in lines), 9, -1):
        title.set_text("\n".join(textwrap.fill(line, width) for line in lines))
        if title.get_window_extent(renderer).width <= (1 - 2 * margin) * fig.bbox.width:
            break
    return title.get_window_extent(renderer).height / fig.bbox.height


def is_steady(ds: xr.Dataset) -> bool:
    """A single steady state (``viscontact steady`` at one speed): one record, nothing in time."""
    return ds.attrs.get("solver") == "steady" and ds.sizes.get("t", 1) == 1


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
    """``"indentation"``, ``"partial slip"``, ``"gross sliding"`` or ``"rolling"`` for a ``phase`` code."""
    return PHASE_NAMES[int(code)]


def contact_state(ds: xr.Dataset, k: int) -> np.ndarray:
    """0 open, 1 slip, 2 stick at record ``k`` (stick counts only where the result has ``stick``)."""
    state = (ds["pressure"].values[k] > 0).astype(int)
    if "stick" in ds:
        state = state + ds["stick"].values[k].astype(int)
    return state


def map_extent(ds: xr.Dataset, k: int, sc: Scales) -> tuple[float, float, float, float]:
    """imshow extent of the grid at record ``k`` in the indenter frame (x - frame_offset), scaled by ``sc``."""
    x = np.asarray(ds["x"].values, dtype=float)
    half = 0.5 * (x[1] - x[0])
    offset = float(ds["frame_offset"].values[k]) if "frame_offset" in ds else 0.0
    s = sc.length[0]
    return ((x[0] - half - offset) / s, (x[-1] + half - offset) / s, (x[0] - half) / s, (x[-1] + half) / s)


def map_image(ds: xr.Dataset, k: int, values: np.ndarray, sc: Scales) -> tuple[np.ndarray, tuple[float, ...]]:
    """(image, imshow extent) of the field ``values`` (y, x) of record ``k`` in the indenter frame.

    On a periodic domain the surface is the frame: the image is drawn over the period, its first
    column repeated after the last (the period wraps around), so that with the axes limited to the
    cell (:func:`cell_limits`) a sub-cell ``frame_offset`` leaves no empty strip.
    """
    extent = map_extent(ds, k, sc)
    if not is_periodic(ds):
        return values, extent
    dx = (extent[1] - extent[0]) / values.shape[1]
    return np.concatenate([values, values[:, :1]], axis=1), (extent[0], extent[1] + dx, extent[2], extent[3])


def cell_limits(ds: xr.Dataset, sc: Scales) -> tuple[float, float]:
    """Axis limits of the domain [-w, w] in the units of ``sc`` (the period of a periodic result)."""
    x = np.asarray(ds["x"].values, dtype=float)
    half = 0.5 * (x[1] - x[0])
    return (x[0] - half) / sc.length[0], (x[-1] + half) / sc.length[0]


def draw_map(ax: Any, ds: xr.Dataset, k: int, values: np.ndarray, sc: Scales, **imshow: Any) -> Any:
    """imshow of the field ``values`` of record ``k`` on ``ax`` (:func:`map_image`; a periodic
    result limited to its period); returns the image."""
    data, extent = map_image(ds, k, values, sc)
    image = ax.imshow(data, origin="lower", extent=extent, interpolation="nearest", **imshow)
    ax.locator_params(axis="x", nbins=3)  # no tick labels running into the next panel's (-0.4, -0.2 did)
    if is_periodic(ds):
        ax.set_xlim(*cell_limits(ds, sc))
    return image


def map_axes(n: int) -> tuple[Any, Any]:
    """A figure with ``n`` map panels in a row sharing both axes."""
    return pyplot().subplots(1, n, figsize=(3.2 * n + 0.8, 3.6), squeeze=False, sharex=True, sharey=True)


def draw_contact_maps(ds: xr.Dataset, picks: list[int], titles: list[str], what: str) -> Any:
    """One map per record in ``picks`` of the contact (white: open, orange: slip, blue: stick) in the
    indenter frame; returns the Figure."""
    from matplotlib.colors import ListedColormap

    sc = Scales(ds)
    fig, axes = map_axes(len(picks))
    colors = ["white", "tab:orange", "tab:blue"]
    cmap = ListedColormap(colors)
    for ax, k, title in zip(axes[0], picks, titles):
        draw_map(ax, ds, k, contact_state(ds, k), sc, cmap=cmap, vmin=0, vmax=2)
        ax.set(title=title, xlabel=sc.length[1])
    axes[0, 0].set_ylabel(sc.length[1].replace("x", "y"))
    set_title(fig, ds, what)
    fig.tight_layout()
    legend_key(fig, colors, ("no contact", "slip", "stick"))
    return fig


def legend_key(fig: Any, colors: Sequence[str], labels: Sequence[str]) -> Any:
    """A key of filled squares (``colors``, outlined) named ``labels``, in one row at the bottom of
    ``fig``, with the room it takes; returns the Legend."""
    from matplotlib.patches import Patch

    handles = [Patch(facecolor=c, edgecolor="0.4", label=label) for c, label in zip(colors, labels)]
    fig.subplots_adjust(bottom=fig.subplotpars.bottom + 0.45 / fig.get_size_inches()[1])  # its row, in inches
    return fig.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=9, frameon=False)


def compact_log_formatter(**kwargs: Any) -> Any:
    """A formatter of log-axis tick labels written short (``0.02``, ``3e-05``: three significant
    digits) on the ticks matplotlib's :class:`~matplotlib.ticker.LogFormatterSciNotation` (given
    ``kwargs``) labels, so that the labels of an axis spanning less than a decade (its minor ticks
    labelled ``2 x 10^-1``, ``3 x 10^-1`` ...) do not run into each other."""
    from matplotlib.ticker import LogFormatterSciNotation

    class CompactLogFormatter(LogFormatterSciNotation):
        def __call__(self, x: float, pos: Any = None) -> str:
            return f"{x:.3g}" if super().__call__(x, pos) else ""

    return CompactLogFormatter(**kwargs)


def integer_ticks(axis: Any) -> None:
    """Ticks of ``axis`` (an Axes' ``xaxis`` or ``yaxis``) on integers only: a count."""
    from matplotlib.ticker import MaxNLocator

    axis.set_major_locator(MaxNLocator(integer=True))


def compact_log_ticks(*axes: Any) -> None:
    """Label the log x axes ``axes`` (an Axes or a secondary axis) with :func:`compact_log_formatter`."""
    for ax in axes:
        ax.xaxis.set_major_formatter(compact_log_formatter())
        ax.xaxis.set_minor_formatter(compact_log_formatter(labelOnlyBase=False, minor_thresholds=(1, 0.4)))
