"""Surface influence coefficients of a uniformly loaded rectangle (a strip, in plane strain) on a
half-space, at G = 1.

Boussinesq (normal point force P into the solid) and Cerruti (tangential point force Q in +x)
surface displacements for shear modulus G and Poisson ratio nu (Johnson, *Contact Mechanics*,
Eqs. 3.19-3.20 and 3.86-3.87; Love 1929), u_z positive into the half-space::

    u_z = (1 - nu) / (2 pi G) P / r                     (zz)
    u_x = -(1 - 2 nu) / (4 pi G) P x / r^2              (xz)
    u_x = 1 / (2 pi G) [(1 - nu) / r + nu x^2 / r^3] Q  (xx)
    u_z = +(1 - 2 nu) / (4 pi G) Q x / r^2              (zx)

(the signs of xz and zx follow from each other by Betti's reciprocity: IC_xz(x) = IC_zx(-x)).

Integrating over a rectangle [x' in (xc - a, xc + a)] x [y' in (yc - b, yc + b)] gives closed forms
F(xi, eta) summed over the four corners with xi = x - x', eta = y - y'::

    int int 1/r        = xi asinh(eta/|xi|) + eta asinh(xi/|eta|)
    int int xi^2/r^3   = eta asinh(xi/|eta|)
    int int xi/r^2     = 1/2 eta ln(xi^2 + eta^2) + xi atan(eta/xi)   (up to terms linear in eta)

With a Prony compliance every coefficient is IC(x, y) J(t) (constant nu, correspondence principle),
so the kernels here are computed once per grid at unit shear modulus.

For steady sliding at speed v each retardation mode lambda also needs the kernel integrated over the
material's past, F(d) = int_0^inf exp(-xi/L)/L IC(d + xi) dxi with L = v lambda
(:func:`history_kernels`, used by :meth:`viscontact.bodies.half_space.HalfSpace.steady_convolver`): a tail
quadrature at the largest offset (composite Gauss-Legendre on geometrically growing intervals) and
the exact backward recursion F(d) = int_0^dx E(xi) IC(d + xi) dxi + exp(-dx/L) F(d + dx).

Plane strain (a line grid, ``grid.dimension = 1``): a line load (force per unit length) on the surface
of a half-space in plane strain (Flamant; Johnson, *Contact Mechanics*, Eqs. 2.19 and 2.20 with
(1 - nu^2)/E = (1 - nu)/(2 G), (1 - 2 nu)(1 + nu)/(2 E) = (1 - 2 nu)/(4 G)) displaces the surface by::

    u_z = -(1 - nu) / (pi G) P ln(|x| / b)          (zz)
    u_x = -(1 - 2 nu) / (4 G) P sgn(x)              (xz)
    u_x = -(1 - nu) / (pi G) Q ln(|x| / b)          (xx)
    u_z = +(1 - 2 nu) / (4 G) Q sgn(x)              (zx)

(the 3-D coefficients integrated along y: the coupling is again proportional to 1 - 2 nu). The
displacements of plane strain are defined up to a rigid-body constant (the log grows without bound):
here the normal and tangential displacements of a line load are zero at the datum, the surface points
at the distance b (``grid.datum_distance``, the domain's half-width) from it, as Johnson's constant C
of Eq. 2.19 leaves free. An approach delta is then the indenter's displacement relative to that datum
(:func:`viscontact.physics.reference.hertz_line` gives Hertz's for it). With b >= L/4, L the domain's
length, the discrete log operator stays positive definite (the logarithmic capacity L/4 of the
domain is below b). Integrated over a strip of width dx = 2h (:func:`strip_influence`), with
P(s) = s ln(|s|/b) - s::

    int ln(|s| / b) ds over [d - h, d + h] = P(d + h) - P(d - h),
    int sgn(s) ds over [d - h, d + h]       = |d + h| - |d - h|.
"""
from __future__ import annotations

from typing import Iterable, Mapping, Sequence

import numpy as np

from viscontact.numerics.convolution import Convolver
from viscontact.numerics.grid import Grid

COMPONENTS = ("zz", "xx", "xz", "zx")


def point_force_displacement(x: np.ndarray, y: np.ndarray, poisson_ratio: float) -> dict[str, np.ndarray]:
    """Surface displacements [m per N] at (x, y) [m] of unit point forces at the origin, G = 1 Pa."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    nu = poisson_ratio
    r2 = x**2 + y**2
    r = np.sqrt(r2)
    return {
        "zz": (1 - nu) / (2 * np.pi * r),
        "xx": ((1 - nu) / r + nu * x**2 / (r * r2)) / (2 * np.pi),
        "xz": -(1 - 2 * nu) / (4 * np.pi) * x / r2,
        "zx": (1 - 2 * nu) / (4 * np.pi) * x / r2,
    }


def _asinh_ratio(num: np.ndarray, den: np.ndarray) -> np.ndarray:
    """num * asinh(den / |num|), with the limit 0 at num = 0."""
    with np.errstate(divide="ignore", invalid="ignore"):
        out = num * np.arcsinh(den / np.abs(num))
    return np.where(num == 0, 0.0, out)


def _corner_primitives(xi: np.ndarray, eta: np.ndarray, odd: bool = True
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """(F_inv_r, F_xi2_r3, F_xi_r2): primitives of 1/r, xi^2/r^3 and xi/r^2 over (xi, eta); the
    last (the odd, coupling one) only when ``odd``."""
    a = _asinh_ratio(xi, eta)  # xi asinh(eta/|xi|)
    b = _asinh_ratio(eta, xi)  # eta asinh(xi/|eta|)
    if not odd:
        return a + b, b, None
    r2 = xi**2 + eta**2
    with np.errstate(divide="ignore", invalid="ignore"):
        log_term = np.where(r2 > 0, 0.5 * eta * np.log(np.where(r2 > 0, r2, 1.0)), 0.0)
        atan_term = np.where(xi != 0, xi * np.arctan(eta / np.where(xi != 0, xi, 1.0)), 0.0)
    return a + b, b, log_term + atan_term


def rectangle_influence(dx: np.ndarray, dy: np.ndarray, half_x: float, half_y: float,
                        poisson_ratio: float, components: tuple[str, ...] = COMPONENTS) -> dict[str, np.ndarray]:
    """Displacements [m per Pa of traction] at offsets (dx, dy) [m] from the centre of a rectangle
    of half-sides ``half_x``, ``half_y`` [m] loaded by a unit uniform traction, at G = 1 Pa.

    Returns the requested ``components`` among ``zz``, ``xx``, ``xz``, ``zx`` (first index:
    displacement, second: traction), each with the broadcast shape of ``dx`` and ``dy``.
    """
    dx = np.asarray(dx, dtype=float)
    dy = np.asarray(dy, dtype=float)
    nu = poisson_ratio
    odd = "xz" in components or "zx" in components
    inv_r = np.zeros(np.broadcast(dx, dy).shape)
    xi2_r3 = np.zeros_like(inv_r)
    xi_r2 = np.zeros_like(inv_r)
    for sx in (-1.0, 1.0):
        for sy in (-1.0, 1.0):
            f1, f2, f3 = _corner_primitives(dx + sx * half_x, dy + sy * half_y, odd)
            sign = sx * sy
            inv_r += sign * f1
            xi2_r3 += sign * f2
            if odd:
                xi_r2 += sign * f3
    return _components(inv_r, xi2_r3, xi_r2, nu, components)


def _components(inv_r: np.ndarray, xi2_r3: np.ndarray, xi_r2: np.ndarray, nu: float,
                components: tuple[str, ...]) -> dict[str, np.ndarray]:
    """The displacement components from the corner sums of the three primitives (at G = 1)."""
    out = {
        "zz": lambda: (1 - nu) / (2 * np.pi) * inv_r,
        "xx": lambda: ((1 - nu) * inv_r + nu * xi2_r3) / (2 * np.pi),
        "xz": lambda: -(1 - 2 * nu) / (4 * np.pi) * xi_r2,
        "zx": lambda: (1 - 2 * nu) / (4 * np.pi) * xi_r2,
    }
    return {c: out[c]() for c in components}


def lattice_rectangle_influence(x_first: float, count: int, spacing: float, dy: np.ndarray, poisson_ratio: float,
                                components: tuple[str, ...] = COMPONENTS) -> dict[str, np.ndarray]:
    """:func:`rectangle_influence` of a square cell of side ``spacing`` [m] at the x offsets
    ``x_first + k spacing`` (k < ``count``) and the y offsets ``dy`` (multiples of ``spacing``) [m],
    shape (count, dy.size), indexed [x offset, y offset] (the layout of the steady kernels' recursion
    over x offsets, :mod:`viscontact.physics.steady_kernels`).

    The corners of neighbouring cells coincide on these lattices, so each corner primitive is
    evaluated once, on the (count + 1) x (rows + 1) lattice of corners, and shared by the four cells
    around it: a quarter of the transcendental evaluations, the same sums (corner positions differ
    from :func:`rectangle_influence`'s by round-off in the offsets)."""
    dy = np.asarray(dy, dtype=float)
    half = 0.5 * spacing
    rows = np.rint(dy / spacing).astype(int)
    low = int(rows.min())
    xi = x_first - half + spacing * np.arange(count + 1)
    eta = spacing * (np.arange(low, int(rows.max()) + 2) - 0.5)  # the lower corner of row i is eta[i - low]
    odd = "xz" in components or "zx" in components
    prims = _corner_primitives(xi[:, None], eta[None, :], odd)
    top, bottom = rows - low + 1, rows - low

    def corner_sum(f: np.ndarray | None) -> np.ndarray:
        if f is None:
            return np.zeros((count, dy.size))
        across = f[1:] - f[:-1]  # the two x corners of every cell, then the two y corners
        return across[:, top] - across[:, bottom]

    return _components(*(corner_sum(f) for f in prims), poisson_ratio, components)


def strip_influence(offset: np.ndarray, half_x: float, poisson_ratio: float, datum: float,
                    components: tuple[str, ...] = COMPONENTS) -> dict[str, np.ndarray]:
    """Plane-strain displacements [m per Pa of traction] at the x offsets ``offset`` [m] from the centre
    of a strip of half-width ``half_x`` [m] loaded by a unit uniform traction, at G = 1 Pa, relative to
    the datum at ``datum`` b [m] from a line load (module docstring: Johnson 1985, Eqs. 2.19-2.20
    integrated over the strip). Returns the requested ``components`` among ``zz``, ``xx``, ``xz``, ``zx``."""
    d = np.asarray(offset, dtype=float)
    nu = poisson_ratio

    def primitive(s: np.ndarray) -> np.ndarray:  # P(s) = s ln(|s|/b) - s, P(0) = 0
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(s == 0, 0.0, s * np.log(np.abs(s) / datum) - s)

    log_integral = primitive(d + half_x) - primitive(d - half_x)
    sign_integral = np.abs(d + half_x) - np.abs(d - half_x)
    out = {
        "zz": lambda: -(1 - nu) / np.pi * log_integral,
        "xx": lambda: -(1 - nu) / np.pi * log_integral,
        "xz": lambda: -(1 - 2 * nu) / 4 * sign_integral,
        "zx": lambda: (1 - 2 * nu) / 4 * sign_integral,
    }
    return {c: out[c]() for c in components}


def cell_influence(grid: Grid, dx: np.ndarray, dy: np.ndarray, poisson_ratio: float,
                   components: tuple[str, ...] = COMPONENTS) -> dict[str, np.ndarray]:
    """Displacements [m per Pa] at offsets (dx, dy) [m] from a cell of ``grid`` under a unit traction
    at G = 1: :func:`rectangle_influence` of the square cell, or on a line grid (dy = 0)
    :func:`strip_influence` of the strip, relative to the grid's datum."""
    h = grid.spacing / 2.0
    if grid.dimension == 1:
        shape = np.broadcast(np.asarray(dx), np.asarray(dy)).shape
        return {c: np.broadcast_to(v, shape) for c, v in
                strip_influence(dx, h, poisson_ratio, grid.datum_distance, components).items()}
    return rectangle_influence(dx, dy, h, h, poisson_ratio, components)


def influence_coefficients(grid: Grid, poisson_ratio: float,
                           components: Sequence[str] = COMPONENTS) -> Mapping[str, np.ndarray]:
    """Influence coefficients on the DC-FFT offset grid, shape (2n, 2n) indexed [y, x] in FFT
    wrap-around order (see :meth:`Grid.offsets`), at unit shear modulus [m/Pa per Pa... i.e. m^3/N
    times traction: displacement = IC * traction / G]. Row/column n (offset n dx) is zeroed: it is
    never used by a linear convolution of two n x n arrays (Liu, Wang & Liu 2000, DC-FFT).
    ``components``: those to compute (the coupling ones cost a third of the time and memory).
    On a line grid: the plane-strain strip kernels (:func:`strip_influence`), shape (1, 2n).
    """
    if grid.dimension == 1:
        ics = cell_influence(grid, grid.offsets()[None, :], grid.row_offsets()[:, None], poisson_ratio,
                             tuple(components))
        ics = {name: np.array(k) for name, k in ics.items()}
        for k in ics.values():
            k[:, grid.n] = 0.0
        return ics
    off = grid.offsets()
    dx, dy = np.meshgrid(off, off, indexing="xy")
    h = grid.spacing / 2.0
    ics = rectangle_influence(dx, dy, h, h, poisson_ratio, tuple(components))
    n = grid.n
    for name in ics:
        ics[name][n, :] = 0.0
        ics[name][:, n] = 0.0
    return ics


_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(8)


def _integrate(fun, breaks: np.ndarray) -> np.ndarray:
    """Composite 8-point Gauss-Legendre of fun(xi) (returns arrays) over consecutive breaks."""
    a, b = breaks[:-1], breaks[1:]
    xi = (0.5 * (b - a))[:, None] * (_GL_NODES[None, :] + 1.0) + a[:, None]
    w = (0.5 * (b - a))[:, None] * _GL_WEIGHTS[None, :]
    xi, w = xi.ravel(), w.ravel()
    total = 0.0
    for chunk in range(0, xi.size, 64):
        vals = fun(xi[chunk:chunk + 64])  # (..., q)
        total = total + np.tensordot(vals, w[chunk:chunk + 64], axes=([-1], [0]))
    return total


def history_kernels(grid: Grid, poisson_ratio: float, length: float,
                    components: Sequence[str] = ("zz", "zx")) -> dict[str, np.ndarray]:
    """F(d) = int_0^inf exp(-xi/L)/L IC(d + xi) dxi on the (2n, 2n) DC-FFT offset grid [unit G].

    Parameters
    ----------
    grid
        The grid (cell-centred, spacing dx).
    poisson_ratio
        nu.
    length
        Decay length L = v lambda [m] of one retardation mode.
    """
    n, dx, h = grid.n, grid.spacing, grid.spacing / 2.0
    dy = grid.offsets()[:, None]  # (2n, 1): all y offsets, wrap order
    decay = np.exp(-dx / length)

    def ic(d: float):
        def f(xi: np.ndarray) -> dict:
            res = rectangle_influence(d + xi[None, :], dy, h, h, poisson_ratio, tuple(components))
            ex = np.exp(-xi / length) / length
            return np.stack([res[c] * ex[None, :] for c in components])  # (C, 2n, q)
        return f

    # local interval [0, dx], split at dx/2 (cell edge crossing) and graded when L < dx
    local = {0.0, 0.5 * dx, dx}
    s = min(length, dx) / 16.0
    while s < dx:
        local.add(s)
        s *= 2.0
    local_breaks = np.array(sorted(local))
    # tail from the largest offset to infinity
    tail = [0.0]
    s = min(length, dx) / 16.0
    while s < 60.0 * length + 4.0 * dx:
        tail.append(s)
        s *= 1.3
    tail.append(s)
    tail_breaks = np.array(tail)

    offsets = dx * np.arange(-(n - 1), n)
    values = np.empty((len(components), 2 * n, offsets.size))
    running = _integrate(ic(offsets[-1]), tail_breaks)
    values[:, :, -1] = running
    for idx in range(offsets.size - 2, -1, -1):
        running = _integrate(ic(offsets[idx]), local_breaks) + decay * running
        values[:, :, idx] = running
    return offset_columns_to_kernels(values, components)


def offset_columns_to_kernels(values: np.ndarray, components: Sequence[str]) -> dict[str, np.ndarray]:
    """Kernels (2n, 2n) in DC-FFT wrap order from ``values`` (components, 2n y offsets in wrap order,
    2n - 1 x offsets -(n-1) dx ... (n-1) dx); row and column n (offset n dx) zero. One y offset (a
    line grid): kernels (1, 2n)."""
    n = (values.shape[2] + 1) // 2
    rows = values.shape[1]
    k = np.arange(-(n - 1), n)
    cols = np.where(k >= 0, k, k + 2 * n)
    out = {}
    for ci, c in enumerate(components):
        kernel = np.zeros((rows, 2 * n))
        kernel[:, cols] = values[ci]
        if rows > 1:
            kernel[n, :] = 0.0
        kernel[:, n] = 0.0
        out[c] = kernel
    return out


def half_space_convolver(grid: Grid, poisson_ratio: float, workers: int = -1,
                         components: Iterable[str] = ("zz", "xx", "xz", "zx")) -> Convolver:
    """DC-FFT :class:`~viscontact.numerics.convolution.Convolver` of the half-space influence
    coefficients (:func:`influence_coefficients`) at unit shear modulus."""
    ics = influence_coefficients(grid, poisson_ratio)
    return Convolver.from_kernels(grid.n, {c: ics[c] for c in components}, workers)
