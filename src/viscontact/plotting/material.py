"""Figure of a material (a :func:`viscontact.io.results.material_dataset`): G(t) and J(t), G'(omega)
and G''(omega), tan delta, so that an imported Prony series can be checked before a long run."""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from viscontact.plotting.base import FigureFiles, pyplot

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["material_figure", "plot_material"]


def plot_material(ds: xr.Dataset, out_dir: str | Path, *, fmt: str = "png", dpi: int | None = None) -> list[Path]:
    """``material.<fmt>`` in ``out_dir``: :func:`material_figure`. Returns the paths."""
    return [FigureFiles(Path(out_dir), fmt, dpi).save(material_figure(ds), "material")]


def material_figure(ds: xr.Dataset) -> Any:
    """Relaxation modulus and creep compliance against time (J(t) on a second axis), storage and loss
    moduli and tan delta against angular frequency (log axes); returns the Figure."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.4), layout="constrained")  # room for J(t)'s axis and the title
    fig.get_layout_engine().set(w_pad=0.1, wspace=0.06)
    t, omega = ds["t"].values, ds["omega"].values
    ax = axes[0]
    ax.loglog(t, ds["relaxation_modulus"].values, color="C0", label="G(t)")
    ax.set(xlabel="t [s]", ylabel="G(t) [Pa]", title="relaxation modulus and creep compliance")
    twin = ax.twinx()
    twin.loglog(t, ds["creep_compliance"].values, color="C1", label="J(t)")
    twin.set_ylabel("J(t) [1/Pa]")
    ax.legend(handles=ax.get_lines() + twin.get_lines(), loc="center left")
    ax = axes[1]
    ax.loglog(omega, ds["storage_modulus"].values, label=r"$G'(\omega)$")
    ax.loglog(omega, ds["loss_modulus"].values, label=r"$G''(\omega)$")
    ax.set(xlabel=r"$\omega$ [rad/s]", ylabel="G', G'' [Pa]", title="storage and loss moduli")
    ax.legend()
    ax = axes[2]
    ax.semilogx(omega, ds["tan_delta"].values)
    ax.set(xlabel=r"$\omega$ [rad/s]", ylabel=r"$\tan\delta = G''/G'$ [-]", title="loss factor")
    a_t = float(ds.attrs.get("a_T", 1.0))
    fig.suptitle(f"{ds.attrs.get('title') or 'material'}: G(0) = {ds.attrs['shear_modulus_instantaneous']:.4g} Pa, "
                 f"G(∞) = {ds.attrs['shear_modulus_long_term']:.4g} Pa, " + r"$a_T$" + f" = {a_t:.4g}")
    return fig
