"""Rigid-surface topographies through SurfaceTopography: self-affine generation and measured files.

Heights h [m] are those of the rigid surface, z up (towards the half-space); the undeformed gap is
g0 = max(h) - h, so the highest summit touches first at delta_z = 0. SurfaceTopography indexes
heights [x, y]; viscontact's fields are [y, x] (the transposes are taken here, once).

* :func:`self_affine_heights`: Fourier synthesis (Ramisetti et al., J. Phys.: Condens. Matter 23,
  215004 (2011); Jacobs, Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001 (2017)) of a
  periodic surface with PSD C(q) ~ q^(-2-2H) between the long and short cut-offs, by
  ``SurfaceTopography.Generation.fourier_synthesis``.
* :func:`read_heights`: anything ``SurfaceTopography.read_topography`` reads (x3p, opd, sur, di,
  NetCDF, plain text with a header, ...), in its own physical size and units, converted to m; on the
  grid as it is, or resampled (cubic B-spline, periodic for a periodic topography) when asked.
* :func:`sphere_heights`: the parabolic sphere, to which roughness is added.

SurfaceTopography is imported when needed (it takes seconds to import).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy import ndimage

from .errors import ParameterError
from .grid import Grid


def gap_from_heights(heights: np.ndarray) -> np.ndarray:
    """Undeformed gap max(h) - h [m] of rigid-surface heights h [m] (z up)."""
    return heights.max() - heights


def sphere_heights(grid: Grid, radius: float) -> np.ndarray:
    """Heights -(x^2 + y^2) / (2 R) [m] of a rigid sphere of radius R [m] centred on the grid, [y, x]."""
    x, y = grid.mesh()
    return -(x**2 + y**2) / (2.0 * radius)


def self_affine_heights(grid: Grid, *, hurst: float, rms_height: float | None = None,
                        rms_slope: float | None = None, long_cutoff: float | None = None,
                        short_cutoff: float | None = None, seed: int = 0,
                        key: str = "indenter") -> np.ndarray:
    """A periodic self-affine surface on the grid's period, heights [m] indexed [y, x].

    Parameters
    ----------
    grid
        The grid; its domain is the period (2 half_width)^2.
    hurst
        Hurst exponent H, 0 < H <= 1.
    rms_height, rms_slope
        Exactly one of: root-mean-square height [m] or gradient [-] (SurfaceTopography's
        ``rms_gradient``: |grad h| by forward differences). The realisation is scaled to it exactly, so
        that seeds differ in their random phases and amplitudes, not in their rms.
    long_cutoff, short_cutoff
        Roll-off and cut-off wavelengths [m] (defaults: the period, and two cells).
    seed
        Seed of the random phases and amplitudes.
    key
        The case-file table these keys come from (in error messages).
    """
    from SurfaceTopography.Generation import fourier_synthesis

    if not 0 < hurst <= 1:
        raise ParameterError(f"{key}.hurst", f"must be in (0, 1], got {hurst}")
    if (rms_height is None) == (rms_slope is None):
        raise ParameterError(f"{key}.rms_height", "give exactly one of rms_height (m) or rms_slope (-)")
    amplitude, name = (rms_height, "rms_height") if rms_height is not None else (rms_slope, "rms_slope")
    if not amplitude > 0:
        raise ParameterError(f"{key}.{name}", f"must be > 0, got {amplitude}")
    period, dx = 2 * grid.half_width, grid.spacing
    if short_cutoff is not None and not 2 * dx <= short_cutoff <= period:
        raise ParameterError(f"{key}.short_cutoff", f"must be in [2 dx, period] = [{2 * dx:.6g}, {period:.6g}] m, "
                             f"got {short_cutoff}")
    lower = short_cutoff if short_cutoff is not None else 2 * dx
    if long_cutoff is not None and not long_cutoff > lower:
        raise ParameterError(f"{key}.long_cutoff", f"must be > the short cut-off {lower:.6g} m, got {long_cutoff}")
    topography = fourier_synthesis((grid.n, grid.n), (period, period), hurst=hurst, rms_height=rms_height,
                                   rms_slope=rms_slope, long_cutoff=long_cutoff, short_cutoff=short_cutoff,
                                   periodic=True, unit="m", rng=seed)
    heights = topography.heights()
    realised = np.sqrt(np.mean((heights - heights.mean()) ** 2)) if rms_height is not None \
        else topography.rms_gradient()
    return np.ascontiguousarray(heights.T) * (amplitude / realised)


def read_heights(path: str | Path, grid: Grid, *, resample: bool = False, physical_sizes: tuple | None = None,
                 unit: str | None = None, key: str = "indenter.file") -> np.ndarray:
    """Heights [m] of a measured topography file on the grid, indexed [y, x].

    Parameters
    ----------
    path
        Any file ``SurfaceTopography.read_topography`` reads.
    grid
        The grid. Without ``resample`` the file must hold grid.n x grid.n points over
        (2 half_width)^2 (relative tolerance 1e-6); its point (i, j) lands on cell (j, i).
    resample
        Interpolate (cubic B-spline) the file's heights at the grid's cell centres, the centres of the two
        point sets coinciding. A periodic topography wraps around; a non-periodic one must cover
        the grid.
    physical_sizes, unit
        Passed to ``read_topography`` for files that do not carry them.
    key
        The case-file key named in error messages.
    """
    import SurfaceTopography

    path = Path(path)
    if not path.is_file():
        raise ParameterError(key, f"no such file: {path}")
    extra = {k: v for k, v in (("physical_sizes", physical_sizes), ("unit", unit)) if v is not None}
    try:
        topography = SurfaceTopography.read_topography(str(path), **extra)
    except Exception as exc:  # readers raise anything from ValueError to struct.error
        message = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise ParameterError(key, f"cannot read {path} as a topography: {message}") from None
    if topography.dim != 2:
        raise ParameterError(key, f"{path} holds a line scan; a 2-D topography map is needed")
    if topography.unit is None:
        raise ParameterError(key, f"{path} does not give its length unit")
    if topography.has_undefined_data:
        raise ParameterError(key, f"{path} has undefined (missing) points; fill them before use")
    topography = topography.to_unit("m")
    heights = np.asarray(topography.heights(), dtype=float).T  # [y, x]
    if not np.all(np.isfinite(heights)):
        raise ParameterError(key, f"{path} must hold finite heights")
    (nx, ny), (lx, ly) = topography.nb_grid_pts, topography.physical_sizes
    period = 2 * grid.half_width
    same_points = (nx, ny) == (grid.n, grid.n)
    same_size = abs(lx - period) <= 1e-6 * period and abs(ly - period) <= 1e-6 * period
    if same_points and same_size:
        return np.ascontiguousarray(heights)
    described = (f"{path} holds {nx} x {ny} points over {lx:.6g} m x {ly:.6g} m; the grid has "
                 f"{grid.n} x {grid.n} points over {period:.6g} m x {period:.6g} m")
    if not resample:
        raise ParameterError(key, f"{described}: set resample = true to interpolate onto the grid")
    return _resample(heights, (lx, ly), topography.is_periodic, grid, key, described)


def _resample(heights: np.ndarray, sizes: tuple[float, float], periodic: bool, grid: Grid, key: str,
              described: str) -> np.ndarray:
    """Cubic B-spline interpolation (periodic or mirrored at the ends) of heights [y, x], sample
    spacing sizes/points, at the grid's cell centres."""
    ny, nx = heights.shape
    lx, ly = sizes
    sx, sy = lx / nx, ly / ny
    # cell centres in the file's frame (samples at i * s), the centres of both point sets coinciding
    x = grid.x + (lx - sx) / 2
    y = grid.y + (ly - sy) / 2
    if not periodic and (x.min() < 0 or x.max() > lx - sx or y.min() < 0 or y.max() > ly - sy):
        raise ParameterError(key, f"{described}: the surface is not periodic and does not cover the grid")
    yy, xx = np.meshgrid(y / sy, x / sx, indexing="ij")
    return ndimage.map_coordinates(heights, [yy, xx], order=3, mode="grid-wrap" if periodic else "mirror")
