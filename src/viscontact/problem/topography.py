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
* :func:`check_surface`: what a surface on the grid must look like: slopes a half-space theory
  takes (an rms slope above :data:`MAX_RMS_SLOPE` is a unit slip and refused; above
  :data:`WARN_RMS_SLOPE` warned) and, on a periodic grid, edges that meet (a map that is not periodic
  over the grid's period has a cliff along the seams, warned).

SurfaceTopography is imported when needed (it takes seconds to import).
"""
from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from viscontact.errors import ParameterError, warn_caller
from viscontact.numerics.grid import Grid

#: an rms slope above this is refused: heights in the wrong unit (a half-space model of a surface
#: whose slopes average 84 degrees means nothing). Over the whole surface, what comes into contact or
#: not: a unit slip scales every slope, and what comes into contact is not known before the solve
#: under load control (under displacement control the part of a unit-slipped gap within the approach
#: of its lowest point shrinks to a few cells, whose slopes would hide the slip on a periodic grid,
#: where no Hertz guard runs). A step counts at its full height: a flat punch's wall of H on cells of dx is a ring of
#: slopes H/dx, an rms that grows as sqrt(n) (a 0.5 mm punch on +-2 mm with walls of 1 mm: 2.0 at
#: 64^2, 8.0 at 1024^2, 11.3 at 2048^2; with walls of 20 um, 0.04 to 0.23). Walls that stay out of
#: contact do not enter the solution (its load to 4e-14 for 20 um against 1 mm), so the messages say
#: to lower them to a few times the approach
MAX_RMS_SLOPE = 10.0
#: an rms slope above this is warned: beyond the small-slope theory of the half-space
WARN_RMS_SLOPE = 1.0
#: on a periodic grid, steps across the period's edges whose rms exceeds this times that of the steps
#: between neighbouring points are warned: the map is not periodic over the grid's period (a cropped
#: measurement: about 17; a periodic map: about 1)
SEAM_RATIO = 3.0
#: resampling that changes the point spacing by more than this factor either way is warned
RESAMPLE_RATIO = 4.0


def rms_slopes(gap: np.ndarray, spacing: float, periodic: bool) -> tuple[float, float]:
    """(rms |grad h| by forward differences over the interior, rms of the steps across the period's
    edges over rms of the interior steps) of a field [m] on a grid of ``spacing`` [m]; the second is 1
    when not ``periodic``. A line grid's one row has no step along y."""
    dx, dy = np.diff(gap, axis=1), np.diff(gap, axis=0)
    interior = float(np.sqrt(np.mean(dx**2) + (np.mean(dy**2) if dy.size else 0.0))) / spacing
    if not periodic or interior == 0:
        return interior, 1.0
    if not dy.size:  # a line: its one seam, across x
        return interior, float(np.sqrt(np.mean((gap[:, 0] - gap[:, -1])**2) / np.mean(dx**2)))
    seams = np.concatenate([gap[:, 0] - gap[:, -1], gap[0] - gap[-1]])
    step = float(np.sqrt((np.mean(dx**2) + np.mean(dy**2)) / 2))
    return interior, float(np.sqrt(np.mean(seams**2))) / step


_STEP_NOTE = ("a step such as a flat punch's wall counts at its full height: walls that stay out of contact can be "
              "lowered to a few times the approach without changing the solution")


def check_surface(gap: np.ndarray, grid: Grid, key: str) -> None:
    """Refuse a surface whose rms slope exceeds :data:`MAX_RMS_SLOPE` (heights in the wrong unit),
    warn above :data:`WARN_RMS_SLOPE`, and on a periodic grid warn when the steps across the period's
    edges exceed :data:`SEAM_RATIO` times the steps between neighbours (the map is not periodic over the
    grid's period: the contact piles up on the seams). ``gap`` [m] on ``grid``; ``key`` names the input."""
    slope, seam = rms_slopes(gap, grid.spacing, grid.periodic)
    if slope > MAX_RMS_SLOPE:
        raise ParameterError(key, f"the surface's rms slope is {slope:.3g} on this grid: heights in the wrong unit "
                             "(m expected), or a physical size that is too small? (" + _STEP_NOTE + ")")
    if slope > WARN_RMS_SLOPE:
        warn_caller(f"{key}: the surface's rms slope is {slope:.3g}, beyond the small-slope theory of the "
                    f"half-space (check the height unit; {_STEP_NOTE})")
    if seam > SEAM_RATIO:
        warn_caller(f"{key}: the surface is not periodic over the grid's period: its steps across the period's "
                    f"edges are {seam:.3g} x those between neighbouring points (rms), a cliff on which the contact "
                    "piles up; use a periodic map whose period the grid's is a multiple of, or grid.periodic = false")


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
    """A periodic self-affine surface on the grid's period, heights [m] indexed [y, x], of shape
    ``grid.shape``: on a line grid (``grid.dimension = 1``) a self-affine profile along x (a 1-D
    Fourier synthesis, PSD C(q) ~ q^(-1-2H)).

    Parameters
    ----------
    grid
        The grid; its domain is the period (2 half_width)^2, or 2 half_width on a line.
    hurst
        Hurst exponent H, 0 < H <= 1.
    rms_height, rms_slope
        Exactly one of: root-mean-square height [m] or gradient [-] (SurfaceTopography's
        ``rms_gradient``: |grad h| by forward differences; on a line its ``rms_slope_from_profile``,
        |dh/dx| by periodic forward differences). The realisation is scaled to it exactly, so
        that seeds differ in their random phases and amplitudes, not in their rms.
    long_cutoff, short_cutoff
        Roll-off and cut-off wavelengths [m] (defaults: the period, and two cells).
    seed
        Seed of the random phases and amplitudes. With a ``short_cutoff`` one seed gives one surface at
        every ``grid.n`` that holds its modes below the Nyquist frequency (they are drawn on the coarsest
        such grid and carried to the grid by their Fourier series: a grid refinement refines, it does
        not redraw); without one the cut-off, two cells, follows the grid and so does the surface.
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
    # with a short cut-off the modes are drawn on the coarsest grid that holds them below its Nyquist
    # frequency, whatever grid.n, and carried to the grid by their Fourier series (SurfaceTopography's
    # interpolate_fourier): one seed, one surface at every resolution (on a grid too coarse for that
    # draw, a cut-off within a mode of the grid's Nyquist wavelength, on the grid itself)
    points = grid.n if short_cutoff is None else 2 * math.ceil(period / short_cutoff) + 2
    points = min(points, grid.n)
    line = grid.dimension == 1
    topography = fourier_synthesis((points,) * grid.dimension, (period,) * grid.dimension, hurst=hurst,
                                   rms_height=rms_height, rms_slope=rms_slope, long_cutoff=long_cutoff,
                                   short_cutoff=short_cutoff, periodic=True, unit="m", rng=seed)
    if line:  # SurfaceTopography's interpolate_fourier is for maps: the profile's Fourier series here
        heights = _fourier_interpolated(topography.heights(), grid.n)
        slope = np.sqrt(np.mean((np.roll(heights, -1) - heights) ** 2)) / grid.spacing
    else:
        if points < grid.n:
            topography = topography.interpolate_fourier((grid.n, grid.n))
        heights = topography.heights()
    realised = np.sqrt(np.mean((heights - heights.mean()) ** 2)) if rms_height is not None \
        else slope if line else topography.rms_gradient()
    return np.ascontiguousarray(heights.T).reshape(grid.shape) * (amplitude / realised)


def _fourier_interpolated(profile: np.ndarray, n: int) -> np.ndarray:
    """A periodic profile of m <= n points [m] on n points by its Fourier series (zero padding of the
    spectrum; an even m's Nyquist mode split between +-k, as SurfaceTopography's ``interpolate_fourier``
    does on a map)."""
    m = profile.size
    if m == n:
        return np.asarray(profile, dtype=float)
    spectrum = np.fft.rfft(profile)
    if m % 2 == 0:
        spectrum[-1] /= 2
    return np.fft.irfft(spectrum, n) * (n / m)


def read_heights(path: str | Path, grid: Grid, *, resample: bool = False, physical_sizes: tuple | None = None,
                 unit: str | None = None, key: str = "indenter.file") -> np.ndarray:
    """Heights [m] of a measured topography file on the grid, indexed [y, x]: a 2-D map, or on a line
    grid (``grid.dimension = 1``) a line scan (a profile along x, SurfaceTopography's ``dim == 1``).

    Parameters
    ----------
    path
        Any file ``SurfaceTopography.read_topography`` reads.
    grid
        The grid. Without ``resample`` the file must hold grid.n x grid.n points over
        (2 half_width)^2 (relative tolerance 1e-6); its point (i, j) lands on cell (j, i). A line
        scan: grid.n points over 2 half_width, point i on cell (0, i).
    resample
        Interpolate (cubic B-spline) the file's heights at the grid's cell centres, the centres of the two
        point sets coinciding. A periodic topography wraps around; a non-periodic one must cover
        the grid.
    physical_sizes, unit
        Passed to ``read_topography`` for files that do not carry them (on a line grid only the
        width, the first of ``physical_sizes``, is passed).
    key
        The case-file key named in error messages.
    """
    import SurfaceTopography

    path = Path(path)
    if not path.is_file():
        raise ParameterError(key, f"{path} is not a regular file (a folder, FIFO, device or link loop): give a "
                             "topography file" if os.path.lexists(path) else f"no such file: {path}")
    if physical_sizes is not None:
        physical_sizes = tuple(physical_sizes)[:grid.dimension]
    extra = {k: v for k, v in (("physical_sizes", physical_sizes), ("unit", unit)) if v is not None}
    try:
        topography = SurfaceTopography.read_topography(str(path), **extra)
    except Exception as exc:  # readers raise anything from ValueError to struct.error
        message = " ".join(str(exc).split()) or type(exc).__name__
        if "physical_sizes" in message:
            message = ("its physical size is not in the file: give indenter.physical_size_m = [width, height] in "
                       "metres with the heights' indenter.unit (formerly physical_size = [width, height] and "
                       "indenter.unit, in that unit), or use a format that carries them (a text map with '# Width: 1 mm', "
                       "'# Height: 1 mm' and '# Value units: um' header lines, NetCDF, x3p, ...)")
        elif "already fixed by file" in message:
            message = "the file gives its own size and unit: remove indenter.physical_size_m and indenter.unit"
        raise ParameterError(key, f"cannot read {path} as a topography: {message[:300]}") from None
    if grid.dimension == 1:
        if topography.dim != 1:
            raise ParameterError(key, f"{path} holds a {topography.dim}-D map; a line contact (grid.dimension = 1) "
                                 "needs a line scan (a profile along x)")
    elif topography.dim != 2 or len(topography.nb_grid_pts) != 2 or len(topography.physical_sizes) != 2:
        raise ParameterError(key, f"{path} holds a line scan or gives one physical size "
                             f"({topography.physical_sizes}); a 2-D map with its width and height is needed "
                             "(a text map: '# Width:' and '# Height:' header lines)")
    if topography.unit is None:
        raise ParameterError(key, f"{path} does not give its length unit: give indenter.unit")
    if topography.has_undefined_data:
        raise ParameterError(key, f"{path} has undefined (missing) points; fill them before use")
    if min(topography.nb_grid_pts) < 2:
        raise ParameterError(key, f"{path} holds {topography.nb_grid_pts} points: a topography needs at least 2 "
                             "along each axis")
    topography = topography.to_unit("m")
    heights = np.asarray(topography.heights(), dtype=float).T.reshape(-1, topography.nb_grid_pts[0])  # [y, x]
    if not np.all(np.isfinite(heights)):
        raise ParameterError(key, f"{path} must hold finite heights")
    points, sizes = tuple(topography.nb_grid_pts), tuple(topography.physical_sizes)
    period = 2 * grid.half_width
    same_points = points == (grid.n,) * grid.dimension
    same_size = all(abs(length - period) <= 1e-6 * period for length in sizes)
    if same_points and same_size:
        return np.ascontiguousarray(heights)
    described = (f"{path} holds {' x '.join(map(str, points))} points over "
                 f"{' x '.join(f'{length:.6g} m' for length in sizes)}; the grid has "
                 f"{' x '.join([str(grid.n)] * grid.dimension)} points over "
                 f"{' x '.join([f'{period:.6g} m'] * grid.dimension)}")
    if not resample:
        raise ParameterError(key, f"{described}: set resample = true to interpolate onto the grid")
    return _resample(heights, sizes, topography.is_periodic, grid, key, described)


def _resample(heights: np.ndarray, sizes: tuple[float, float], periodic: bool, grid: Grid, key: str,
              described: str) -> np.ndarray:
    """Cubic B-spline interpolation (periodic or mirrored at the ends) of heights [y, x], sample
    spacing sizes/points, at the grid's cell centres; on a line grid, of the profile (1, nx) of
    length ``sizes[0]``."""
    ny, nx = heights.shape
    lx, ly = sizes if len(sizes) == 2 else (sizes[0], sizes[0] / nx)
    sx, sy = lx / nx, ly / ny
    # cell centres in the file's frame (samples at i * s), the centres of both point sets coinciding
    x = grid.x + (lx - sx) / 2
    y = grid.y + (ly - sy) / 2
    if not periodic and (x.min() < 0 or x.max() > lx - sx or y.min() < 0 or y.max() > ly - sy):
        # the grid's outermost cell centres, grid.half_width (1 - 1/n) from its centre, must lie within
        # the file's outermost samples, (l - s) / 2 from its centre
        widest = (min(lx - sx, ly - sy) if grid.dimension == 2 else lx - sx) / (2 * (1 - 1 / grid.n))
        raise ParameterError(key, f"{described}: the surface is not periodic and its outermost samples do not reach "
                             f"the grid's outermost cell centres; grid.half_width <= {widest:.6g} m keeps them inside")
    ratio = max(sx, sy) / grid.spacing
    if not 1 / RESAMPLE_RATIO <= ratio <= RESAMPLE_RATIO:
        warn_caller(f"{key}: resampling changes the point spacing {ratio:.3g}-fold ({max(sx, sy):.3g} m in the file, "
                    f"{grid.spacing:.3g} m on the grid): check the file's physical size"
                    + ("" if ratio > 1 else "; finer detail than the grid's is dropped, not averaged"))
    yy, xx = np.meshgrid(y / sy, x / sx, indexing="ij")
    from scipy import ndimage  # imported where used: scipy.ndimage weighs several MiB

    return ndimage.map_coordinates(heights, [yy, xx], order=3, mode="grid-wrap" if periodic else "mirror")
