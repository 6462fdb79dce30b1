"""An elastic layer on a rigid or elastic substrate: exact Fourier-space surface compliance and kernels.

Geometry: a layer 0 < z < h (shear modulus G, Poisson ratio nu) on a substrate z > h, rigid or an
elastic half-space (G_s, nu_s), the interface bonded (displacements and tractions continuous) or
frictionless (normal displacement and normal traction continuous, no shear traction). Surface
tractions p (into the solid) and q_x, q_y act at z = 0.

Fourier-space compliance. For a wavevector q = k e (k = |q|, e unit, e_perp = z x e) the response
splits into an in-plane (e, z) problem and an anti-plane one:

    u_z = A_zz(k) p + A_ze(k) t_e,   u_e = A_ez(k) p + A_ee(k) t_e,   u_perp = A_pp(k) t_perp

so that, with c = q_x/k, the components used by the contact solvers are

    M_zz = A_zz,   M_xz = c A_ez,   M_zx = c A_ze,   M_xx = c^2 A_ee + (1 - c^2) A_pp.

In-plane: in each material the displacement is given by Papkovich-Neuber potentials
phi = (alpha/k) E, psi = b E with E = exp(-s k (z - z0)) (2 G u = grad(phi + (z - z0) psi)
- 4 (1 - nu) psi e_z; Barber, *Elasticity*, ch. 20; the same representation as
:mod:`viscontact.physics.subsurface`): the layer has a family decaying from z0 = 0 (s = +1) and one decaying
from z0 = h (s = -1), the substrate one decaying from z0 = h (s = +1), so every basis function is
bounded by 1 and the 4 x 4 (rigid) or 6 x 6 (elastic) system of surface and interface conditions
stays well conditioned at large k h (at k h < 1e-2 the two layer families become alike and digits
are lost: 2e-7 relative at k h = 1e-3, nu = 0.5; the kernels sample k h >= 2 pi h / box). It is
solved for every distinct |q|. Anti-plane (closed form, with T = tanh(kh) and r = G_s/G):

    A_pp = T/(G k) (rigid, bonded),  (1 + r T)/((T + r) G k) (elastic, bonded),
           1/(T G k) (frictionless: no shear reaches the substrate).

Limits checked by the tests: k h -> inf gives the half-space (1 - nu)/(G k) etc.; a thin bonded
layer on a rigid base has A_zz -> h / M with the oedometric modulus M = 2 G (1 - nu)/(1 - 2 nu) and
A_pp, A_ee -> h/G; the rigid-bonded A_zz equals the closed form

    A_zz = (1 - nu)/(G k) [(3 - 4 nu) sinh 2kh - 2kh] / [(3 - 4 nu) cosh 2kh + 2 (kh)^2 + 5 - 12 nu + 8 nu^2].

On a frictionless interface A_ee and A_pp grow as 1/k^2 at small k (the layer slides as a plate):
the tangential kernels are then unbounded and only the periodic ones (mean displacement free) exist.

Kernels. Non-periodic (:func:`influence_coefficients`, the DC-FFT offset grid of
:mod:`viscontact.physics.kernels`): the
half-space kernels of the layer material (closed-form cell integrals) carry the 1/k behaviour at
large k; the long-wavelength 1/k behaviour (that of the substrate, or none on a rigid base) is
swapped in through kernels smoothed to depth H, whose real-space forms are

    e^{-kH}/k            ->  1 / (2 pi R),               R = sqrt(r^2 + H^2)
    e^{-kH} cos(2 theta_q)/k   ->  -cos(2 theta) (R - H)^2 / (2 pi r^2 R)
    i e^{-kH} cos(theta_q)/k   ->  -cos(theta) (R - H) / (2 pi r R)

(Hankel transforms of e^{-kH} J_n; Gradshteyn & Ryzhik 6.611.1), integrated over each cell by
Gauss-Legendre quadrature (smooth on the scale H >= 2 dx). The remainder spectrum is bounded at
q = 0 and decays as exp(-k min(H, 2h)); it is sampled on a periodic box of ``box`` x the domain
(at least 8 max(H, h)) with cells refined until its Nyquist wavenumber reaches 14/min(H, 2h),
multiplied by the footprint, folded onto the coarse wavevectors and transformed back. Its real-space
tail (~ m1/r^3, m1 the |k| coefficient of the remainder at small k) has periodic images whose sum
near the origin, -m1 Z/(2 pi P^3) (Z = sum of 1/|m|^3 over the square lattice = 9.0336), is removed, and
its q = 0 sample is extrapolated from the two smallest rings: measured against an independent
Hankel-quadrature kernel the error is a near-constant offset of ~1e-4 of the self-coefficient
(a rigid shift of the displacement under load control) falling as P^-3.6.

On a line grid (``grid.dimension = 1``, plane strain) a load uniform along y has its Fourier
transform at q_y = 0, so the plane-strain compliance is M(q_x, 0): c = +-1, M_xx = A_ee, and the
anti-plane part does not enter; the lattice is the row of wavevectors (q_x, 0) and the cell
footprint one sinc (:func:`_lattice_compliance`, :func:`_fourier_part`). The non-periodic line's
closed-form part is the strips' (:func:`_line_near`: the half-space strip kernels with their datum,
and the depth-smoothed line loads -(1/pi) ln(sqrt(x^2 + H^2)/b), -(1/pi) arctan(x/H)); its remainder's
real-space tail is m1/(pi x^2)-like, the images' sum near the origin -m1 pi/(3 P^2) removed, on a
box of at least :data:`LINE_BOX` domain widths.

Periodic (:func:`periodic_spectra`): no smoothing. The half-space part c_high/k is the exact
periodic half-space kernel of the layer material (:func:`viscontact.physics.periodic.periodic_influence_coefficients`,
Ewald, zero mean); the rest, M - c_high/k, decays as exp(-2kh) and is sampled on the periodic grid
refined until its Nyquist wavenumber reaches 7/h, times the footprint, and folded (no aliasing);
the mean (q = 0) is the uniform compliance (h/M on a rigid base, 0 where unbounded). Measured
against the alias sum of the exact compliance times the footprint at the lowest wavevectors (n = 16):
within 2e-8 (zz, xx) for h from 2 dx to a period, 6e-7 at h = 0.3 dx (the 7/h cut-off); a layer ten
periods thick is the periodic half-space plus h/M to round-off. (A depth-smoothed split, its near
part summed over a few periodic images in real space, is not exact for any h: the odd near part
decays only as H/r^2 and leaves a sawtooth along x, and for H above a period the even near part has
not decayed within the images. It was used before: 5e-4 to 2e-3 of the largest xz at n = 64 for
h <= 2 dx; 6e-4 (zz) and 2.4e-2 (xz) at h = 10 periods.)

Cost at 256^2 cells: ~15-25 s at h = 2 dx (non-periodic, the remainder on a 2048^2 refined box);
periodic 0.1-0.4 s for h >= dx (refined at most 3-fold), 2.5 s at h = 0.3 dx (8-fold), on this
2-core machine; the compliance is solved once per distinct i^2 + j^2 of the lattice.

Time response. With a rigid substrate and constant nu every A is 1/G times a function of (k h, nu),
so the kernels at unit modulus times the shear creep compliance J(t) are exact for a viscoelastic
layer (one term per component, as for the half-space). On an elastic substrate M depends on G/G_s
and does not factor: for each q the response to a traction step is a sum of exponentials whose rates
move with |q| (:func:`modulus_poles`: A(k; G) = alpha0/G + sum_j alpha_j/(G + shift_j(k)), so each
pole j brings the creep function of G(t) + shift_j(k)). :func:`viscoelastic_periodic_modes` gives
that data per wavevector and states the cost: one kernel (spectrum) and one history field per mode
and component, M (1 + number of poles) modes for an M-term Prony series. The solvers need fixed
times: :func:`elastic_base_terms` interpolates h = (s + G_ref)/(G + s) in u = G_ref/(G_ref + s)
at fixed nodes (:func:`shift_nodes`), so each node is a real-space kernel (DC-FFT or periodic) with
one creep function: D + 1 kernels per component and D M history fields per traction component for
D + 1 nodes.

Steady sliding (:func:`steady_shapes`): the near part through the product integration of
:class:`~viscontact.physics.steady_kernels.SteadyKernelBuilder`, the remainder sampled at sub-cell shifts
and integrated by the same recursion over its box.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np
import scipy.fft

from viscontact.bodies.base import ContactShape, TermBody
from viscontact.bodies.bulk_elastic import prony_creep_spectra, prony_creep_spectrum
from viscontact.bodies.compliance import ComplianceTerm
from viscontact.errors import ParameterError
from viscontact.numerics.exponentials import CreepSpectrum, linear_combination
from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import rectangle_influence, strip_influence
from viscontact.physics.materials import Material
from viscontact.physics.periodic import periodic_influence_coefficients
from viscontact.physics.reference import contact_modulus
from viscontact.physics.steady_kernels import SteadyKernelBuilder, SteadyShape, lagrange_basis, lobatto_nodes

if TYPE_CHECKING:  # the case's [layer], as the problem holds it (a layer above: for the reader only)
    from viscontact.problem.problem import LayerSettings

BASES = ("rigid", "elastic")
INTERFACES = ("bonded", "frictionless")
COMPONENTS = ("zz", "xx", "xz", "zx")
#: the least box of a line grid's non-periodic remainder, in domain widths (:func:`_box_cells`):
#: measured against the periodic line kernel (h = 0.3 of the half-width), the self-coefficient's
#: offset 1.6e-3 / 3.3e-5 / 6.3e-7 at boxes of 4 / 16 / 64
LINE_BOX = 64
#: sum over the square lattice Z^2 without 0 of 1/|m|^3 = 4 zeta(3/2) beta(3/2)
_LATTICE_ZETA3 = 9.033621683100950


@dataclass(frozen=True)
class Layer:
    """An elastic layer on a base (module docstring; the case keys, and the keys of its errors, call
    the base ``substrate``).

    Parameters
    ----------
    thickness
        h [m], > 0.
    shear_modulus, poisson_ratio
        G [Pa] and nu of the layer.
    base
        ``"rigid"`` or ``"elastic"`` (case key ``layer.substrate``).
    interface
        ``"bonded"`` or ``"frictionless"``.
    base_shear_modulus, base_poisson_ratio
        G_s [Pa] and nu_s (elastic base only; case keys ``layer.substrate_shear_modulus``,
        ``layer.substrate_poisson_ratio``).

    Examples
    --------
    A 0.1 mm layer (G = 1 MPa, nu = 0.3) bonded to a rigid base: at long wavelengths the oedometric
    compliance h/M, at short ones the half-space (1 - nu)/(G k):

    >>> import numpy as np
    >>> layer = Layer(1e-4, 1e6, 0.3)
    >>> a = in_plane_compliance(layer, np.array([1.0, 1e6]))["zz"]
    >>> round(float(a[0]) * layer.oedometric_modulus / layer.thickness, 6), round(float(a[1]) * 1e12 / 0.7, 6)
    (1.0, 1.0)
    """

    thickness: float
    shear_modulus: float
    poisson_ratio: float
    base: str = "rigid"
    interface: str = "bonded"
    base_shear_modulus: float = float("inf")
    base_poisson_ratio: float = 0.3

    def __post_init__(self) -> None:
        if not (np.isfinite(self.thickness) and self.thickness > 0):
            raise ParameterError("layer.thickness", f"must be > 0 m, got {self.thickness}")
        if not (np.isfinite(self.shear_modulus) and self.shear_modulus > 0):
            raise ParameterError("material.shear_modulus", f"must be > 0 Pa, got {self.shear_modulus}")
        if not 0.0 <= self.poisson_ratio <= 0.5:
            raise ParameterError("material.poisson_ratio", f"must be in [0, 0.5], got {self.poisson_ratio}")
        if self.base not in BASES:
            raise ParameterError("layer.substrate", f"must be one of {BASES}, got {self.base!r}")
        if self.interface not in INTERFACES:
            raise ParameterError("layer.interface", f"must be one of {INTERFACES}, got {self.interface!r}")
        if self.base == "elastic":
            gs, nus = self.base_shear_modulus, self.base_poisson_ratio
            if not (np.isfinite(gs) and gs > 0):
                raise ParameterError("layer.substrate_shear_modulus", f"must be > 0 Pa, got {gs}")
            if not 0.0 <= nus <= 0.5:
                raise ParameterError("layer.substrate_poisson_ratio", f"must be in [0, 0.5], got {nus}")

    @property
    def oedometric_modulus(self) -> float:
        """M = 2 G (1 - nu)/(1 - 2 nu) [Pa] (inf for nu = 0.5)."""
        nu = self.poisson_ratio
        return float("inf") if nu == 0.5 else 2 * self.shear_modulus * (1 - nu) / (1 - 2 * nu)

    @property
    def tangential_bounded(self) -> bool:
        """Whether the tangential compliance stays bounded as k -> 0 (bonded interface)."""
        return self.interface == "bonded"


# --- Fourier-space compliance -------------------------------------------------------------------

def _family_rows(kz: np.ndarray, s: float, shear_modulus: float, nu: float) -> dict[str, np.ndarray]:
    """Rows (..., 2) acting on (alpha, b) of one potential family at k (z - z0) = kz, k = 1:
    u_z, u_x / i, sigma_zz / k, sigma_xz / (i k) (module docstring)."""
    e = np.exp(-s * kz)
    inv2g = 0.5 / shear_modulus
    one = np.ones_like(kz)
    return {
        "uz": np.stack([-s * one, -s * kz - (3 - 4 * nu)], axis=-1) * (inv2g * e)[..., None],
        "ux": np.stack([one, kz], axis=-1) * (inv2g * e)[..., None],
        "szz": np.stack([one, kz + 2 * (1 - nu) * s], axis=-1) * e[..., None],
        "sxz": np.stack([-s * one, -s * kz - (1 - 2 * nu)], axis=-1) * e[..., None],
    }


def _in_plane_system(layer: Layer, kh: np.ndarray, modulus_ratio: float
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The interface-condition system at G = 1, k = 1 (module docstring) for k h = ``kh`` and
    G_s/G = ``modulus_ratio`` (inf: substrate displacement rows vanish). Returns the matrix
    (..., N, N), the right-hand sides (..., N, 2) for p = 1 and t_x = i (tau = 1), and the output
    rows (..., 2, N) giving (u_z, u_x / i) at the surface."""
    nu = layer.poisson_ratio
    zero = np.zeros_like(kh)
    top_near = _family_rows(zero, 1.0, 1.0, nu)      # layer family from z0 = 0, at z = 0
    top_far = _family_rows(-kh, -1.0, 1.0, nu)       # layer family from z0 = h, at z = 0
    bot_near = _family_rows(zero, -1.0, 1.0, nu)     # layer family from z0 = h, at z = h
    bot_far = _family_rows(kh, 1.0, 1.0, nu)         # layer family from z0 = 0, at z = h
    elastic = layer.base == "elastic"
    size = 6 if elastic else 4
    mat = np.zeros(kh.shape + (size, size))
    mat[..., 0, 0:2], mat[..., 0, 2:4] = -top_near["szz"], -top_far["szz"]   # -sigma_zz = p
    mat[..., 1, 0:2], mat[..., 1, 2:4] = top_near["sxz"], top_far["sxz"]     # sigma_xz/(ik) = -tau
    layer_at_h = {key: np.concatenate([bot_far[key], bot_near[key]], axis=-1) for key in bot_far}
    if elastic:
        sub = _family_rows(zero, 1.0, modulus_ratio, layer.base_poisson_ratio)
        keys = ("uz", "ux", "szz", "sxz") if layer.interface == "bonded" else ("uz", "szz")
        row = 2
        for key in keys:
            mat[..., row, 0:4], mat[..., row, 4:6] = layer_at_h[key], -sub[key]
            row += 1
        if layer.interface == "frictionless":
            mat[..., row, 0:4] = layer_at_h["sxz"]
            mat[..., row + 1, 4:6] = sub["sxz"]
    else:
        keys = ("uz", "ux") if layer.interface == "bonded" else ("uz", "sxz")
        for row, key in enumerate(keys, start=2):
            mat[..., row, 0:4] = layer_at_h[key]
    rhs = np.zeros(kh.shape + (size, 2))
    rhs[..., 0, 0] = 1.0   # p = 1
    rhs[..., 1, 1] = -1.0  # t_x = i tau, tau = 1: sigma_xz/(ik) = -1
    out = np.zeros(kh.shape + (2, size))
    out[..., 0, 0:4] = np.concatenate([top_near["uz"], top_far["uz"]], axis=-1)
    out[..., 1, 0:4] = np.concatenate([top_near["ux"], top_far["ux"]], axis=-1)
    return mat, rhs, out


#: (output row, right-hand side, factor) of each in-plane compliance in units 1/(G k)
_IN_PLANE = {"zz": (0, 0, 1.0), "ze": (0, 1, -1j), "ez": (1, 0, 1j), "ee": (1, 1, 1.0)}


def in_plane_compliance(layer: Layer, k: np.ndarray) -> dict[str, np.ndarray]:
    """A_zz, A_ze, A_ez, A_ee [m/Pa] at wavenumbers k [1/m] (> 0); A_ze, A_ez are imaginary."""
    k = np.asarray(k, dtype=float)
    mat, rhs, out = _in_plane_system(layer, k * layer.thickness, layer.base_shear_modulus / layer.shear_modulus)
    response = out @ np.linalg.solve(mat, rhs)  # (..., 2 outputs, 2 loads)
    scale = 1.0 / (layer.shear_modulus * k)
    return {key: factor * response[..., o, i] * scale for key, (o, i, factor) in _IN_PLANE.items()}


def anti_plane_compliance(layer: Layer, k: np.ndarray) -> np.ndarray:
    """A_pp [m/Pa] at wavenumbers k [1/m] (> 0) (module docstring)."""
    k = np.asarray(k, dtype=float)
    t = np.tanh(k * layer.thickness)
    if layer.interface == "frictionless":
        factor = 1.0 / t
    elif layer.base == "rigid":
        factor = t
    else:
        r = layer.base_shear_modulus / layer.shear_modulus
        factor = (1 + r * t) / (t + r)
    return factor / (layer.shear_modulus * k)


def fourier_compliance(layer: Layer, qx: np.ndarray, qy: np.ndarray,
                       components: tuple[str, ...] = COMPONENTS) -> dict[str, np.ndarray]:
    """M_zz, M_xx, M_xz, M_zx [m/Pa] at wavevectors (qx, qy) [1/m] (q != 0), u^ = M t^ with
    u(x) = int u^(q) exp(i q.x) d^2q / (2 pi)^2. Solves once per distinct |q|."""
    qx, qy = np.broadcast_arrays(np.asarray(qx, dtype=float), np.asarray(qy, dtype=float))
    k = np.hypot(qx, qy)
    uniq, inverse = np.unique(k, return_inverse=True)
    return _rotate(_layer_spectral(layer), qx / k, uniq, inverse.reshape(k.shape), components)


@dataclass(frozen=True)
class _Spectral:
    """A Fourier-space surface compliance to turn into kernels (the layer's, or a part of it).

    ``planes(k)``: the in-plane A_zz, A_ze, A_ez, A_ee (coupling ones imaginary) and anti-plane
    A_pp [m/Pa] at wavenumbers k [1/m]; ``high``/``low``: its 1/k coefficients at large/small k by
    component and angular order (:func:`_half_space_coefficients`); ``half_space``: the large-k
    part is the half-space of the layer material (closed-form cell kernels in the near part);
    ``uniform``: the q = 0 compliance of the periodic kernels (0 where unbounded)."""

    planes: Callable[[np.ndarray], dict[str, np.ndarray]]
    high: dict[str, dict[int, float]]
    low: dict[str, dict[int, float]]
    uniform: dict[str, float]
    half_space: bool = True


def _layer_spectral(layer: Layer) -> _Spectral:
    """The layer's own compliance (:func:`in_plane_compliance`, :func:`anti_plane_compliance`)."""
    def planes(k: np.ndarray) -> dict[str, np.ndarray]:
        return {**in_plane_compliance(layer, k), "pp": anti_plane_compliance(layer, k)}

    return _Spectral(planes, _half_space_coefficients(layer.shear_modulus, layer.poisson_ratio),
                     _long_wave_coefficients(layer), uniform_compliance(layer))


def _rotate(spectral: _Spectral, cosine: np.ndarray, k_unique: np.ndarray, inverse: np.ndarray,
            components: tuple[str, ...]) -> dict[str, np.ndarray]:
    """M from the in-plane and anti-plane compliances at the distinct wavenumbers ``k_unique``
    (``inverse`` maps each wavevector to its |q|; ``cosine`` = q_x/|q|)."""
    a = {key: v[inverse] for key, v in spectral.planes(k_unique).items()}
    c = cosine
    out = {"zz": a["zz"], "xz": c * a["ez"], "zx": c * a["ze"]}
    if "xx" in components:
        out["xx"] = c**2 * a["ee"] + (1 - c**2) * a["pp"]
    return {name: out[name] for name in components}


def _lattice_compliance(spectral: _Spectral, size: int, spacing: float, components: tuple[str, ...],
                        dimension: int = 2) -> tuple[dict[str, np.ndarray], np.ndarray, np.ndarray]:
    """M on the wavevectors of a size x size transform with cells ``spacing`` [m] (fft order,
    q = 0 excluded: returned as 0), solving once per distinct i^2 + j^2 (|i| on a line; no sort); with
    ``dimension = 1`` on the (1, size) wavevectors (q_x, 0) of a line (plane strain: a load uniform
    along y sees the compliance at q_y = 0). Returns (M by component, q_x, |q|)."""
    idx = np.rint(scipy.fft.fftfreq(size) * size).astype(np.int64)
    # the key of a wavevector: i^2 + j^2 on a map, |i| on a line (|q| = dq sqrt(key), or dq key)
    keys = idx[None, :] ** 2 + idx[:, None] ** 2 if dimension == 2 else np.abs(idx)[None, :]
    radius = np.sqrt if dimension == 2 else np.asarray
    present = np.zeros(int(keys.max()) + 1, dtype=bool)
    present[keys] = True
    present[0] = False
    lookup = np.cumsum(present) - 1
    dq = 2 * np.pi / (size * spacing)
    k_unique = dq * radius(np.flatnonzero(present).astype(float))
    qx = np.broadcast_to(dq * idx[None, :].astype(float), keys.shape)
    k = dq * radius(keys.astype(float))
    k_safe = np.where(keys == 0, 1.0, k)
    m = _rotate(spectral, qx / k_safe, k_unique, np.where(keys == 0, 0, lookup[keys]), components)
    for name in m:
        m[name] = np.where(keys == 0, 0.0, m[name])
    return m, qx, k


def uniform_compliance(layer: Layer) -> dict[str, float]:
    """Displacement per uniform traction [m/Pa] (the q = 0 mode; 0 where unbounded, the mean
    displacement then being free): a rigid base gives h/M normally (lateral strain is zero in a
    uniformly loaded layer, bonded or not) and h/G tangentially when bonded."""
    h = layer.thickness
    rigid = layer.base == "rigid"
    nu = layer.poisson_ratio
    zz = h * (1 - 2 * nu) / (2 * layer.shear_modulus * (1 - nu)) if rigid else 0.0
    xx = h / layer.shear_modulus if rigid and layer.interface == "bonded" else 0.0
    return {"zz": zz, "xx": xx, "xz": 0.0, "zx": 0.0}


# --- kernel helpers -----------------------------------------------------------------------------

def _depth_smoothed(dx: np.ndarray, dy: np.ndarray, depth: float, order: int) -> np.ndarray:
    """Real-space form [1/m] of exp(-kH)/k times 1, i cos(theta_q), cos(2 theta_q) for order 0, 1, 2
    (module docstring), at offsets (dx, dy) [m]."""
    big_r = np.sqrt(dx**2 + dy**2 + depth**2)
    if order == 0:
        return 1.0 / (2 * np.pi * big_r)
    if order == 1:
        # -cos(theta) (R - H) / (r R) = -dx / (R (R + H))   (R - H = r^2 / (R + H))
        return -dx / (2 * np.pi * big_r * (big_r + depth))
    # -cos(2 theta) (R - H)^2 / (r^2 R) = -(dx^2 - dy^2) / ((R + H)^2 R)
    return -(dx**2 - dy**2) / (2 * np.pi * (big_r + depth) ** 2 * big_r)


def _cell_average(func, dx: np.ndarray, dy: np.ndarray, cell: float, points: int = 6) -> np.ndarray:
    """int over the cell of side ``cell`` centred at offset (dx, dy) of func(x, y), Gauss-Legendre."""
    nodes, weights = np.polynomial.legendre.leggauss(points)
    nodes, weights = 0.5 * cell * nodes, 0.5 * cell * weights
    out = np.zeros(np.broadcast(dx, dy).shape)
    for xi, wx in zip(nodes, weights):
        for yj, wy in zip(nodes, weights):
            out += wx * wy * func(dx + xi, dy + yj)
    return out


def _long_wave_coefficients(layer: Layer) -> dict[str, dict[int, float]]:
    """Coefficients [1/Pa] of the 1/k behaviour as k -> 0, by angular order: zz {0}, xx {0, 2},
    xz, zx {1} (M_xz ~ i c d/k, M_zx ~ -i c d'/k written as i c (-d')/k)."""
    if layer.base == "elastic":
        if layer.interface == "bonded":
            return _half_space_coefficients(layer.base_shear_modulus, layer.base_poisson_ratio)
    if layer.interface == "bonded":
        return {"zz": {0: 0.0}, "xx": {0: 0.0, 2: 0.0}, "xz": {1: 0.0}, "zx": {1: 0.0}}
    # frictionless: k A(k) extrapolated linearly to k = 0 from k h = 1e-4, 2e-4; the tangential
    # compliance grows as 1/k^2 (no 1/k coefficient: NaN, the non-periodic kernel refuses it)
    k = np.array([1e-4, 2e-4]) / layer.thickness
    lim = {key: 2 * (k * v)[0] - (k * v)[1] for key, v in in_plane_compliance(layer, k).items()}
    zz = float(lim["zz"].real) if layer.base == "elastic" else 0.0
    return {"zz": {0: zz}, "xz": {1: float(lim["ez"].imag)}, "zx": {1: float(lim["ze"].imag)},
            "xx": {0: np.nan, 2: np.nan}}


def _half_space_coefficients(shear_modulus: float, nu: float) -> dict[str, dict[int, float]]:
    """Half-space M = coefficient/k by angular order: zz (1-nu)/G; xx (1 - nu/2)/G, -nu/(2G);
    xz (1-2nu)/(2G) (M_xz = i c (1-2nu)/(2Gk)); zx -(1-2nu)/(2G)."""
    g = shear_modulus
    return {"zz": {0: (1 - nu) / g}, "xx": {0: (1 - nu / 2) / g, 2: -nu / (2 * g)},
            "xz": {1: (1 - 2 * nu) / (2 * g)}, "zx": {1: -(1 - 2 * nu) / (2 * g)}}


def _angular(order: int, qx: np.ndarray, k: np.ndarray) -> np.ndarray | float:
    """1, i cos(theta_q), cos(2 theta_q) for order 0, 1, 2."""
    if order == 0:
        return 1.0
    c = qx / k
    return 1j * c if order == 1 else 2 * c**2 - 1


# --- kernels ----------------------------------------------------------------------------------------

def _smoothing_depth(grid: Grid, layer: Layer, depth: float | None) -> float:
    """H [m]: max(2h, 2dx) unless given."""
    return max(2 * layer.thickness, 2 * grid.spacing) if depth is None else float(depth)


def _refinement(grid: Grid, layer: Layer, big_h: float) -> int:
    """Cells per grid cell of the refined transform: Nyquist wavenumber >= 14 / min(H, 2h)."""
    return max(1, int(np.ceil(14.0 * grid.spacing / (np.pi * min(big_h, 2 * layer.thickness)))))


def _half_space_near(ox: np.ndarray, oy: np.ndarray, cell: float, layer: Layer, big_h: float,
                     components: tuple[str, ...], coefficients: dict[str, dict[int, float]],
                     spectral: _Spectral | None = None) -> dict[str, np.ndarray]:
    """Cell-integrated real-space part [m/Pa] at offsets (ox, oy) [m] of the non-periodic kernels:
    the half-space kernels of the layer material plus, for each angular order, (c_low - c_high)
    times the kernels smoothed to depth H (module docstring; c_low from ``coefficients``), the cell
    integral by 6 x 6 Gauss-Legendre points (the smoothed kernels vary on the scale H >= 2 dx).
    ``spectral``: the compliance (default the layer's; without a half-space part, c_high = 0 and
    only the smoothed kernels)."""
    spectral = spectral or _layer_spectral(layer)
    high = spectral.high
    hs = rectangle_influence(ox, oy, cell / 2, cell / 2, layer.poisson_ratio, components) if spectral.half_space \
        else None
    out = {}
    for name in components:
        kern = hs[name] / layer.shear_modulus if hs is not None else np.zeros(np.broadcast(ox, oy).shape)
        for order, c_high in high[name].items():
            delta = coefficients[name][order] - c_high
            if delta != 0.0:
                kern = kern + delta * _cell_average(lambda x, y, o=order: _depth_smoothed(x, y, big_h, o), ox, oy, cell)
        out[name] = kern
    return out


def _line_coefficient(coefficients: dict[str, dict[int, float]], name: str) -> float:
    """The 1/|k| coefficient [1/Pa] of component ``name`` on a line (q = (k, 0): cos(theta_q) = sgn k,
    every angular order's factor 1, the odd one's i sgn k written as in :func:`_angular`)."""
    return float(sum(coefficients[name].values()))


def _line_near(ox: np.ndarray, grid: Grid, layer: Layer, big_h: float, components: tuple[str, ...],
               coefficients: dict[str, dict[int, float]], spectral: _Spectral | None = None) -> dict[str, np.ndarray]:
    """The closed-form part [m/Pa] of a line grid's non-periodic kernels (plane strain) at x offsets
    ``ox`` [m]: the half-space strip kernels of the layer material over G (datum b = ``grid.datum_distance``,
    :func:`viscontact.physics.kernels.strip_influence`: c_high/|k|) plus (c_low - c_high) times the
    strip integral of the depth-smoothed line load, whose real-space forms are

        e^{-|k|H}/|k|          ->  -(1/pi) ln(sqrt(x^2 + H^2) / b)   (even: zz, xx),
        i sgn(k) e^{-|k|H}/|k| ->  -(1/pi) arctan(x / H)             (odd: xz, zx),

    integrated over the cell in closed form (the even one with b, so that on a rigid base the datum
    cancels: the layer's displacement is then relative to the base)."""
    spectral = spectral or _layer_spectral(layer)
    half, datum = grid.spacing / 2, grid.datum_distance
    ox = np.asarray(ox, dtype=float)
    hs = strip_influence(ox, half, layer.poisson_ratio, datum, components) if spectral.half_space else None

    def even(s: np.ndarray) -> np.ndarray:  # int -(1/pi) ln(sqrt(s^2 + H^2)/b) ds
        return -(s * np.log((s * s + big_h * big_h) / datum**2) - 2 * s + 2 * big_h * np.arctan(s / big_h)) / (2 * np.pi)

    def odd(s: np.ndarray) -> np.ndarray:  # int -(1/pi) arctan(s/H) ds
        return -(s * np.arctan(s / big_h) - 0.5 * big_h * np.log(s * s + big_h * big_h)) / np.pi

    out = {}
    for name in components:
        kern = hs[name] / layer.shear_modulus if hs is not None else np.zeros(ox.shape)
        delta = _line_coefficient(coefficients, name) - _line_coefficient(spectral.high, name)
        if delta != 0.0:
            primitive = odd if name in ("xz", "zx") else even
            kern = kern + delta * (primitive(ox + half) - primitive(ox - half))
        out[name] = kern
    return out


def _near(grid: Grid, ox: np.ndarray, oy: np.ndarray, layer: Layer, big_h: float, components: tuple[str, ...],
          coefficients: dict[str, dict[int, float]], spectral: _Spectral) -> dict[str, np.ndarray]:
    """The closed-form part of the non-periodic kernels at offsets (ox, oy) [m]: the square cells'
    (:func:`_half_space_near`) or a line's strips (:func:`_line_near`, oy = 0)."""
    if grid.dimension == 1:
        shape = np.broadcast(np.asarray(ox), np.asarray(oy)).shape
        return {c: np.broadcast_to(v, shape) for c, v in
                _line_near(np.broadcast_to(ox, shape), grid, layer, big_h, components, coefficients, spectral).items()}
    return _half_space_near(ox, oy, grid.spacing, layer, big_h, components, coefficients, spectral=spectral)


def _fourier_part(grid: Grid, layer: Layer, components: tuple[str, ...], big_h: float, cells: int,
                  low: dict[str, dict[int, float]] | None, max_fine: int,
                  shifts: np.ndarray | None = None, spectral: _Spectral | None = None) -> dict[str, np.ndarray]:
    """Cell kernels [m/Pa] on a periodic box of ``cells`` x ``cells`` grid cells (real space,
    wrap-around order) of the spectrum M - c_high (1 - e^{-kH})/k - c_low e^{-kH}/k, sampled on a
    refined grid, times the cell footprint, folded onto the box wavevectors. ``shifts`` [m]: the
    same at the offsets moved by each shift along x (phase exp(i q_x shift) on the refined grid,
    before folding), shape (shifts, cells, cells). ``spectral``: the compliance (default the layer's).

    ``low`` None (periodic kernels, H = inf: the exact periodic half-space kernels carry the whole
    c_high/k, :func:`periodic_spectra`): the spectrum is M - c_high/k and its q = 0 term makes the
    kernel's mean the uniform compliance (0 where unbounded). Otherwise (non-periodic) the remainder is bounded at
    q = 0: its q = 0 sample and the periodic images of its |k| tail are handled as in the module
    docstring."""
    dx = grid.spacing
    refine = _refinement(grid, layer, big_h)
    fine = cells * refine
    if grid.dimension == 1:  # one row: the same number of samples as a max_fine^2 map
        max_fine = max_fine**2
    if fine > max_fine:
        raise ParameterError("layer.thickness", f"{layer.thickness:.4g} m needs a {fine}^2 transform for the layer "
                             f"kernels (limit {max_fine}^2) with cells of {dx:.4g} m: thinner than the cells "
                             "needs refinement, thicker than the domain a larger box; change grid.n or half_width")
    ds = dx / refine
    spectral = spectral or _layer_spectral(layer)
    m, qx, k = _lattice_compliance(spectral, fine, ds, components, grid.dimension)
    q1 = 2 * np.pi / (fine * ds)
    nonzero = k > 0
    m = {name: v[nonzero] for name, v in m.items()}
    kk, cx = k[nonzero], qx[nonzero]
    area = grid.cell_area  # dx^2, or dx on a line: one sinc per direction of the cell
    if grid.dimension == 2:
        qy = np.broadcast_to(2 * np.pi * scipy.fft.fftfreq(fine, ds)[:, None], k.shape)
        footprint = np.sinc(qx * dx / (2 * np.pi)) * np.sinc(qy * dx / (2 * np.pi)) * dx**2
    else:
        footprint = np.sinc(qx * dx / (2 * np.pi)) * area
    fold = (refine, cells, refine, cells) if grid.dimension == 2 else (1, 1, refine, cells)
    decay = np.exp(-kk * big_h)
    high, uniform = spectral.high, spectral.uniform
    out = {}
    for name in components:
        rem = m[name].astype(complex)
        for order, c_high in high[name].items():
            c_low = low[name][order] if low is not None else 0.0
            rem -= _angular(order, cx, kk) * (c_high * (1 - decay) + c_low * decay) / kk
        full = np.zeros(k.shape, dtype=complex)
        full[nonzero] = rem
        spec = full * footprint
        tail = 0.0
        if low is None:
            spec[0, 0] = uniform[name] * area  # the periodic half-space kernels have zero mean
        else:
            # bounded at q = 0 with an angle-independent part M0 + m1 |k| (orders 1, 2 average out
            # over the four axis wavevectors): M0 extrapolated from the rings q1, 2 q1; the -m1/(2 pi r^3)
            # tail's periodic images add -m1 Z/(2 pi P^3) near the origin, removed below
            if grid.dimension == 2:
                ring1 = 0.25 * (full[0, 1] + full[0, -1] + full[1, 0] + full[-1, 0]).real
                ring2 = 0.25 * (full[0, 2] + full[0, -2] + full[2, 0] + full[-2, 0]).real
                spec[0, 0] = (2 * ring1 - ring2) * dx**2
                tail = (ring2 - ring1) / q1 * _LATTICE_ZETA3 * dx**2 / (2 * np.pi * (cells * dx) ** 3)
            else:  # a line: m1 |k| is -m1/(pi x^2) in real space, its images -m1 pi/(3 P^2) near the origin
                ring1 = 0.5 * (full[0, 1] + full[0, -1]).real
                ring2 = 0.5 * (full[0, 2] + full[0, -2]).real
                spec[0, 0] = (2 * ring1 - ring2) * area
                tail = (ring2 - ring1) / q1 * np.pi * area / (3 * (cells * dx) ** 2)
        if shifts is None:
            folded = spec.reshape(fold).sum(axis=(0, 2))
            out[name] = scipy.fft.ifft2(folded).real / area + tail
            continue
        out[name] = np.stack([scipy.fft.ifft2((spec * np.exp(1j * qx * xi)).reshape(fold)
                                              .sum(axis=(0, 2))).real / area + tail for xi in shifts])
    return out


def _box_cells(grid: Grid, layer: Layer, big_h: float, box: int) -> int:
    """Cells per side of the periodic box of the non-periodic remainder: ``box`` domain widths (on a
    line at least :data:`LINE_BOX`: one row is cheap, and the images' offset falls as box^-2.8), at
    least 8 max(H, h)."""
    if grid.dimension == 1:
        box = max(box, LINE_BOX)
    return max(box * grid.n, 2 * int(np.ceil(4 * max(big_h, layer.thickness) / grid.spacing)))


def influence_coefficients(grid: Grid, layer: Layer, components: tuple[str, ...] = COMPONENTS,
                           depth: float | None = None, box: int = 4, max_fine: int = 8192,
                           spectral: _Spectral | None = None) -> dict[str, np.ndarray]:
    """Influence coefficients [m per Pa of cell traction] of the layer on the DC-FFT offset grid
    (2n, 2n), wrap-around order, row/column n zeroed, like
    :func:`viscontact.physics.kernels.influence_coefficients` but in physical units (at the layer's G).

    ``depth`` is the smoothing depth H [m] (default max(2h, 2dx)); ``box`` the periodic box of
    the remainder in domain widths (at least 8 max(H, h)); ``max_fine`` caps the refined
    transform (ParameterError beyond it). ``spectral``: another compliance than the layer's (the
    parts of :func:`elastic_base_terms`).
    """
    n = grid.n
    spectral = spectral or _layer_spectral(layer)
    if not layer.tangential_bounded and "xx" in components:
        raise ParameterError("layer.interface", "a frictionless interface leaves the tangential compliance "
                             "unbounded at long wavelengths (the layer slides); use interface = \"bonded\"")
    big_h = _smoothing_depth(grid, layer, depth)
    low = spectral.low
    off = grid.offsets()
    ox, oy = np.meshgrid(off, grid.row_offsets(), indexing="xy")
    out = {c: np.array(v) for c, v in _near(grid, ox, oy, layer, big_h, components, low, spectral).items()}
    cells = _box_cells(grid, layer, big_h, box)
    remainder = _fourier_part(grid, layer, components, big_h, cells, low, max_fine, spectral=spectral)
    idx = np.concatenate([np.arange(0, n + 1), np.arange(cells - n + 1, cells)])
    rows = idx if grid.dimension == 2 else np.zeros(1, dtype=int)
    for name in components:
        out[name] = out[name] + remainder[name][np.ix_(rows, idx)]
        if grid.dimension == 2:
            out[name][n, :] = 0.0
        out[name][:, n] = 0.0
    return out


def periodic_spectra(grid: Grid, layer: Layer, components: tuple[str, ...] = COMPONENTS, max_fine: int = 8192,
                     spectral: _Spectral | None = None) -> dict[str, np.ndarray]:
    """Spectra (n, n//2 + 1) of the layer's kernels on the periodic n x n grid (rfft2 layout):
    u = irfft2(K^ rfft2(t)) [m] for cell tractions t [Pa].

    The half-space part of the compliance (c_high/k by angular order, that of the layer material)
    is the exact periodic half-space kernel (:func:`viscontact.physics.periodic.periodic_influence_coefficients`,
    Ewald, zero mean) over G; the rest, M - c_high/k, decays as exp(-2kh) and is sampled in Fourier
    space on a refined grid (Nyquist wavenumber >= 7/h, :func:`_refinement`) and folded (no
    aliasing). The mean (q = 0) is the uniform compliance (:func:`uniform_compliance`), 0 where
    unbounded. ``max_fine`` caps the refined transform (ParameterError beyond it). ``spectral``:
    another compliance than the layer's (the parts of :func:`elastic_base_terms`, without a
    half-space part: all of it in Fourier space).
    """
    n = grid.n
    spectral = spectral or _layer_spectral(layer)
    kernels = _fourier_part(grid, layer, components, np.inf, n, None, max_fine, spectral=spectral)
    if spectral.half_space:
        hs = periodic_influence_coefficients(grid, layer.poisson_ratio, components)
        kernels = {name: kernels[name] + hs[name] / layer.shear_modulus for name in components}
    out = {}
    for name in components:
        spec = scipy.fft.rfft2(kernels[name])
        if name in ("xz", "zx"):
            spec = 1j * spec.imag  # an odd real kernel has an imaginary spectrum
        out[name] = spec
    return out


def unit_kernels(grid: Grid, layer: Layer, components: tuple[str, ...] = COMPONENTS,
                 spectral: _Spectral | None = None) -> dict[str, np.ndarray]:
    """The layer's kernels at unit modulus (times G [Pa]: displacement = kernel * traction / G for an
    elastic layer) on ``grid``: DC-FFT (2n, 2n) (:func:`influence_coefficients`) or, on a periodic
    grid, the periodic n x n kernels in wrap-around order (:func:`periodic_spectra`)."""
    if grid.periodic:
        spectra = periodic_spectra(grid, layer, components, spectral=spectral)
        return {c: scipy.fft.irfft2(spectra[c], s=grid.shape) * layer.shear_modulus for c in components}
    kernels = influence_coefficients(grid, layer, components, spectral=spectral)
    return {c: kernels[c] * layer.shear_modulus for c in components}


def steady_shapes(grid: Grid, layer: Layer, components: tuple[str, ...] = ("zz", "zx"), box: int = 4,
                  max_fine: int = 8192, spectral: _Spectral | None = None) -> dict[str, SteadyShape]:
    """Steady shapes (:class:`~viscontact.physics.steady_kernels.SteadyShape`) of the layer's unit-modulus
    DC-FFT kernels (:func:`unit_kernels`), by component: for steady sliding at speed v each
    retardation mode needs F_m(d) = int_0^inf exp(-xi/L_m)/L_m K(d + xi) dxi, L_m = v lambda_m,
    over the whole past of the material, far beyond the grid.

    The kernel is split as in :func:`influence_coefficients`: the near part (half-space kernels of
    the layer material and the depth-smoothed kernels, closed form at any offset, long-range tail
    included) goes through the product integration of
    :class:`~viscontact.physics.steady_kernels.SteadyKernelBuilder` (``point_kernel``); the remainder,
    smooth and decaying as 1/r^3, is sampled on its periodic box at the sub-cell shifts of the
    integration nodes (phase exp(i q_x xi) before folding) and integrated by the same recursion
    from half a box ahead of the domain (``smooth``), where it has decayed. Empty on a periodic
    grid (the periodic steady state is exact in Fourier space)."""
    if grid.periodic:
        return {}
    n = grid.n
    spectral = spectral or _layer_spectral(layer)
    big_h = _smoothing_depth(grid, layer, None)
    low = spectral.low
    cells = _box_cells(grid, layer, big_h, box)
    g = layer.shear_modulus
    rows = np.concatenate([np.arange(0, n + 1), np.arange(cells - n + 1, cells)]) if grid.dimension == 2 \
        else np.zeros(1, dtype=int)
    cols = np.concatenate([np.arange(cells - n + 1, cells), np.arange(0, cells // 2)])
    out = {}
    for comp in components:
        def point(ox: np.ndarray, oy: np.ndarray, comp: str = comp) -> dict[str, np.ndarray]:
            return {comp: g * _near(grid, ox, oy, layer, big_h, (comp,), low, spectral)[comp]}

        def smooth(shifts: np.ndarray, comp: str = comp) -> np.ndarray:
            box_values = _fourier_part(grid, layer, (comp,), big_h, cells, low, max_fine, shifts, spectral)[comp]
            return g * box_values[:, rows][:, :, cols][:, None]

        builder = SteadyKernelBuilder(grid, layer.poisson_ratio, (comp,), point_kernel=point, smooth=smooth)
        out[comp] = SteadyShape(((builder, comp, 1.0),))
    return out


# --- viscoelastic layer on a rigid base: one term per component ---------------------------------

def rigid_base_terms(grid: Grid, layer: Layer, shear: Material, components: tuple[str, ...] = ("zz", "xx", "xz", "zx")
                     ) -> list[ComplianceTerm]:
    """Compliance terms (:class:`~viscontact.bodies.compliance.ComplianceTerm`) of a viscoelastic
    layer (Prony shear modulus ``shear``, a :class:`~viscontact.physics.materials.Material`, constant
    nu = ``layer.poisson_ratio``) on a rigid base: every compliance is 1/G times a function of
    (k h, nu), so each component is its unit-modulus kernel (:func:`influence_coefficients` times G)
    times the shear creep compliance J(t): one history per traction component, as for the
    half-space. (On an elastic substrate the response does not factor: see
    :func:`viscoelastic_periodic_modes`.)"""
    if layer.base != "rigid":
        raise ParameterError("layer.substrate", "kernel x J(t) terms exist for a rigid substrate only; an elastic "
                             "substrate needs one term per relaxation mode (viscoelastic_periodic_modes)")
    return factored_terms(grid, layer, prony_creep_spectrum(shear.g_inf, shear.g, shear.tau), components)


def factored_terms(grid: Grid, layer: Layer, response: CreepSpectrum, components: tuple[str, ...] = COMPONENTS
                   ) -> list[ComplianceTerm]:
    """One term per component: the unit-modulus kernel (:func:`unit_kernels`, periodic on a periodic
    grid) times ``response`` [1/Pa], with its steady shape (:func:`steady_shapes`, DC-FFT grids):
    exact wherever the layer's compliance is 1/G times a function of the geometry (a rigid base, or
    an elastic layer whose response is 1/G)."""
    kernels = unit_kernels(grid, layer, components)
    shapes = steady_shapes(grid, layer, components)
    return [ComplianceTerm(c[0], c[1], kernels[c], response, c, shapes.get(c)) for c in components]


# --- viscoelastic layer on an elastic substrate: modes per wavevector -----------------------------

@dataclass(frozen=True)
class ModulusPoles:
    """Partial fractions of a compliance A(k; G) in the layer's shear modulus G (nu, substrate fixed):

        A(k; G) = alpha0(k) / G + sum_j alpha_j(k) / (G + shift_j(k))                     [m/Pa]

    ``alpha0`` (nk,) [m], ``alpha`` (nk, J) [m], ``shift`` (nk, J) [Pa] (> 0). J = 0 on a rigid
    substrate (A proportional to 1/G), 2 for the in-plane and 1 for the anti-plane compliance on a
    bonded elastic substrate, 1 in-plane and 0 anti-plane on a frictionless one.
    """

    alpha0: np.ndarray
    alpha: np.ndarray
    shift: np.ndarray


def _pole_count(layer: Layer, key: str) -> int:
    if layer.base == "rigid":
        return 0
    if key == "pp":
        return 1 if layer.interface == "bonded" else 0
    return 2 if layer.interface == "bonded" else 1


def _refined_eigentriple(s0: np.ndarray, s1: np.ndarray, rho: float, right: np.ndarray, left: np.ndarray
                         ) -> tuple[float, np.ndarray, np.ndarray]:
    """One step of inverse iteration on the pencil S0 + rho S1 at its eigenvalue ``rho``: the right and
    left eigenvectors from (S0 + rho S1) v' = S1 v (and the adjoint), rho from their Rayleigh quotient
    -w^H S0 v / w^H S1 v.

    At small k h the finite eigenvalue is far out (|rho| ~ 1e7 at k h = 1e-2: the substrate barely
    matters) and LAPACK's eigenvectors of the pencil carry relative errors of about 1e-7 into the
    residue; one step brings them to about 1e-9, the limit the rounded matrix entries set (checked
    against a 50-digit solve). A matrix singular to working precision keeps the vectors given."""
    shifted = s0 + rho * s1
    try:
        v = np.linalg.solve(shifted, s1 @ right)
        w = np.linalg.solve(shifted.conj().T, s1.conj().T @ left)
    except np.linalg.LinAlgError:
        return rho, right, left
    v, w = v / np.linalg.norm(v), w / np.linalg.norm(w)
    return float((-(w.conj() @ s0 @ v) / (w.conj() @ s1 @ v)).real), v, w


def modulus_poles(layer: Layer, k: np.ndarray, key: str) -> ModulusPoles:
    """Poles and residues in G of A_key(k; G), key in zz, ze, ez, ee (in-plane; the coupling ones as
    their imaginary parts) or pp (anti-plane), at wavenumbers k [1/m].

    In-plane: only the substrate's displacement rows of the interface system depend on G, linearly
    in rho = G/G_s, so the system is S0 + rho S1 and G k A = o^T (S0 + rho S1)^-1 b. Its poles are
    the finite generalised eigenvalues rho_j of (S0, -S1) (scipy.linalg.eig, left and right
    eigenvectors w, v, refined by one step of inverse iteration: :func:`_refined_eigentriple`), with
    residues c_j = (o.v)(w^H b)/(w^H S1 v); hence
    A = A(rho -> 0) + sum_j c_j/(k rho_j) / (G - rho_j G_s) (:class:`ModulusPoles`, shift = -rho_j G_s).
    Anti-plane (bonded): A = (1 + r T)/((T + r) G k), r = G_s/G, T = tanh(kh), has the single pole
    G = -G_s/T: A = T/(G k) + (1 - T^2)/(T k (G + G_s/T)).
    """
    import scipy.linalg  # imported where used: with scipy.optimize, a third of a run's imports (BENCHMARKS.md)

    k = np.asarray(k, dtype=float)
    count = _pole_count(layer, key)
    if key == "pp":
        t = np.tanh(k * layer.thickness)
        if count == 0:
            return ModulusPoles(layer.shear_modulus * anti_plane_compliance(layer, k), np.zeros(k.shape + (0,)),
                                np.zeros(k.shape + (0,)))
        gs = layer.base_shear_modulus
        return ModulusPoles(t / k, ((1 - t**2) / (t * k))[..., None], (gs / t)[..., None])
    o_row, i_col, factor = _IN_PLANE[key]
    sign = (factor / 1j).real if key in ("ze", "ez") else 1.0
    kh = k * layer.thickness
    mat0, rhs, out = _in_plane_system(layer, kh, np.inf)
    alpha0 = sign * (out @ np.linalg.solve(mat0, rhs))[..., o_row, i_col] / k
    if count == 0:
        return ModulusPoles(alpha0, np.zeros(k.shape + (0,)), np.zeros(k.shape + (0,)))
    mat1 = _in_plane_system(layer, kh, 1.0)[0] - mat0
    alpha = np.zeros(k.shape + (count,))
    shift = np.full(k.shape + (count,), np.inf)
    for idx in np.ndindex(k.shape):
        rho, left, right = scipy.linalg.eig(mat0[idx], -mat1[idx], left=True, right=True)
        finite = np.flatnonzero(np.isfinite(rho))
        if finite.size != count or np.any(np.abs(rho[finite].imag) > 1e-9 * np.abs(rho[finite])):
            raise ValueError(f"layer compliance: expected {count} real poles in G at k = {k[idx]:.4g} 1/m")
        for j, e in enumerate(finite[np.argsort(rho[finite].real)]):
            r, v, w = _refined_eigentriple(mat0[idx], mat1[idx], rho[e].real, right[:, e], left[:, e])
            c = (out[idx][o_row] @ v) * (w.conj() @ rhs[idx][:, i_col]) / (w.conj() @ mat1[idx] @ v)
            alpha[idx + (j,)] = sign * c.real / (k[idx] * r)
            shift[idx + (j,)] = -r * layer.base_shear_modulus
    return ModulusPoles(alpha0, alpha, shift)


@dataclass(frozen=True)
class SpectralModes:
    """Time response of one kernel component in Fourier space, per wavevector q:

        u^(q, t) = [instantaneous(q) + sum_m amplitudes_m(q) (1 - exp(-t / retardation_times_m(q)))] t^(q)

    for a traction step t^ at t = 0. ``instantaneous`` has the shape of the wavevector grid,
    ``amplitudes`` and ``retardation_times`` one more leading axis (modes) [m per Pa of cell
    traction; s]. Modes whose time does not depend on q (those of J(t)) have constant rows.
    """

    component: str
    instantaneous: np.ndarray
    amplitudes: np.ndarray
    retardation_times: np.ndarray


def viscoelastic_periodic_modes(grid: Grid, layer: Layer, shear: Material, components: tuple[str, ...] = ("zz",)
                                ) -> dict[str, SpectralModes]:
    """Per-wavevector creep modes of a viscoelastic layer (Prony shear modulus ``shear``, a
    :class:`~viscontact.physics.materials.Material`; constant nu = ``layer.poisson_ratio``; ``layer``'s own
    shear modulus is not used) on its substrate, on the periodic n x n grid (rfft2 layout, cell
    footprint applied, q = 0 left at zero).

    By the correspondence principle A(k; G) -> A(k; G~(s)) in the Carson domain, and with the
    partial fractions of :func:`modulus_poles` the creep response at each q is

        alpha0(k) J(t) + sum_j alpha_j(k) L_j(k, t),   L_j: Carson transform 1/(G~(s) + shift_j(k)),

    J the shear creep compliance and L_j the creep function of the Prony modulus G(t) + shift_j(k)
    (:func:`viscontact.bodies.bulk_elastic.prony_creep_spectra`): M retardation times shared by every q and
    J_poles x M more whose times move with |q|.

    Cost (the design): where the time response does not factor (elastic substrate) each mode is its
    own kernel. Per traction component and kernel component the hereditary history holds one field
    per mode, here a spectrum updated per q (H_m <- exp(-dt/lambda_m(q)) H_m + beta_m(q) dt^): with an
    M-term Prony series that is M (1 + J_poles) fields per component (3M for zz on a bonded elastic
    substrate, 3M + 3M c^2 / s^2 parts for xx), against M on a rigid substrate; each costs one
    multiply-add per wavevector and step, no extra transforms. This is exact on a periodic domain. For
    the non-periodic DC-FFT domain the same spectra on the 2n x 2n padded grid give the convolution
    with period 2 x domain (error: the kernel's tail beyond one domain width); the solvers use
    instead fixed-time terms that interpolate the pole shifts (:func:`elastic_base_terms`),
    on both grids.
    """
    n, dx = grid.n, grid.spacing
    qy = 2 * np.pi * scipy.fft.fftfreq(n, dx)[:, None]
    qx = 2 * np.pi * scipy.fft.rfftfreq(n, dx)[None, :]
    qx, qy = np.broadcast_arrays(qx, qy)
    k = np.hypot(qx, qy)
    nonzero = k > 0
    uniq, inverse = np.unique(k[nonzero], return_inverse=True)
    cx = (qx[nonzero] / k[nonzero])
    footprint = (np.sinc(qx * dx / (2 * np.pi)) * np.sinc(qy * dx / (2 * np.pi)))[nonzero]
    j_inst, j_amp, j_time = prony_creep_spectra(shear.g_inf, shear.g, shear.tau, np.array([0.0]))
    # angular weights of the in-plane / anti-plane compliances in each component (k-scaled: A ~ 1/k)
    parts = {"zz": [("zz", 1.0, 1.0)], "xz": [("ez", 1j, cx)], "zx": [("ze", 1j, cx)],
             "xx": [("ee", 1.0, cx**2), ("pp", 1.0, 1 - cx**2)]}
    out = {}
    for name in components:
        inst = np.zeros(inverse.size, dtype=complex)
        alpha0_total = np.zeros(inverse.size, dtype=complex)
        amps, times = [], []
        for key, phase, weight in parts[name]:
            poles = modulus_poles(layer, uniq, key)
            factor = phase * weight * footprint
            alpha0_total += factor * poles.alpha0[inverse]
            for j in range(poles.shift.shape[1]):
                l_inst, l_amp, l_time = prony_creep_spectra(shear.g_inf, shear.g, shear.tau, poles.shift[:, j])
                coef = factor * poles.alpha[inverse, j]
                inst = inst + coef * l_inst[inverse]
                for m in range(l_amp.shape[1]):
                    amps.append(coef * l_amp[inverse, m])
                    times.append(l_time[inverse, m])
        inst = inst + alpha0_total * j_inst[0]
        for m in range(j_amp.shape[1]):
            amps.append(alpha0_total * j_amp[0, m])
            times.append(np.full(inverse.size, j_time[0, m]))

        def place(values: np.ndarray, fill: float) -> np.ndarray:
            full = np.full(k.shape, fill, dtype=complex if np.iscomplexobj(values) else float)
            full[nonzero] = values
            return full

        out[name] = SpectralModes(name, place(inst, 0.0),
                                  np.array([place(a, 0.0) for a in amps]).reshape((len(amps),) + k.shape),
                                  np.array([place(t, 1.0) for t in times]).reshape((len(times),) + k.shape))
    return out


# --- viscoelastic layer on an elastic substrate: terms with fixed retardation times ---------------

def _shift_factor(u: np.ndarray, modulus: np.ndarray, reference: float) -> np.ndarray:
    """h(u; G) = (s + G_ref)/(G + s) written in u = G_ref/(G_ref + s) in [0, 1]: G_ref/(G_ref + u (G - G_ref))."""
    return reference / (reference + u * (modulus - reference))


@dataclass(frozen=True)
class ShiftNodes:
    """Interpolation nodes in the pole shift s of an elastic-substrate layer (:func:`shift_nodes`).

    Attributes
    ----------
    nodes
        u_p = G_ref/(G_ref + s_p) [-], Chebyshev-Lobatto on [0, 1] (u = 0: s = inf, u = 1: s = 0).
    reference
        G_ref = sqrt(G(0) G(inf)) [Pa].
    error
        Largest relative interpolation error of (s + G_ref)/(G + s) over u in [0, 1] and G on the
        complex modulus curve G*(omega) [-].
    """

    nodes: np.ndarray
    reference: float
    error: float

    @property
    def shifts(self) -> np.ndarray:
        """s_p = G_ref (1 - u_p)/u_p [Pa] (inf at u = 0)."""
        with np.errstate(divide="ignore"):
            return np.where(self.nodes > 0, self.reference * (1 - self.nodes) / self.nodes, np.inf)

    def response(self, shear: Material, p: int) -> CreepSpectrum:
        """Time response [1/Pa] of node p: the creep function whose Carson transform is
        (s_p + G_ref) / (G_ref (G~(s) + s_p)); 1/G_ref (elastic) at u = 0, J(t) at u = 1."""
        u, ref = float(self.nodes[p]), self.reference
        if u == 0.0:
            return CreepSpectrum(1.0 / ref, np.zeros(0), np.zeros(0))
        shift = ref * (1 - u) / u
        spectrum = prony_creep_spectrum(shear.g_inf, shear.g, shear.tau, shift)
        return linear_combination([((shift + ref) / ref, spectrum)])


def shift_nodes(shear: Material, tolerance: float = 1e-4, max_degree: int = 40) -> ShiftNodes:
    """The fewest Chebyshev-Lobatto nodes u_p in [0, 1] (u = G_ref/(G_ref + s)) for which
    h(u; G) = (s + G_ref)/(G + s) is interpolated within ``tolerance`` (relative) for every u and every
    G = G~(s) on the right half-plane: an analytic function of G there (its pole G = G_ref (1 - 1/u)
    is negative), so the error is largest on the boundary, the complex modulus curve G*(omega),
    sampled from omega = 0 (G(inf)) to infinity (G(0)). Wide spectra (G(0)/G(inf) >> 10) need more
    nodes. ParameterError when ``max_degree`` is not enough."""
    g0, ginf = shear.shear_modulus_instantaneous, shear.shear_modulus_long_term
    reference = float(np.sqrt(g0 * ginf))
    tau = np.asarray(shear.tau, dtype=float)
    omega = np.logspace(np.log10(1e-3 / tau.max()), np.log10(1e3 / tau.min()), 60 * max(1, int(np.log10(
        tau.max() / tau.min())) + 6))
    moduli = np.concatenate([[ginf, g0], shear.storage_modulus(omega) + 1j * shear.loss_modulus(omega)])
    u = np.linspace(0.0, 1.0, 801)
    exact = _shift_factor(u[:, None], moduli[None, :], reference)
    for degree in range(2, max_degree + 1):
        nodes, bary = lobatto_nodes(degree)
        approx = lagrange_basis(u, nodes, bary) @ _shift_factor(nodes[:, None], moduli[None, :], reference)
        error = float(np.max(np.abs(approx - exact) / np.abs(exact)))
        if error <= tolerance:
            return ShiftNodes(nodes, reference, error)
    raise ParameterError("material", f"a layer on an elastic substrate needs more than {max_degree + 1} shift "
                         f"nodes for this material (G(0)/G(inf) = {g0 / ginf:.3g}); use layer.substrate = 'rigid'")


class _LogInterpolant:
    """f(k) from samples: a cubic spline of k f(k) in log k; below the samples k f = a + b k through
    the two smallest (a: the 1/k coefficient at k -> 0), above them f = 0 (decayed)."""

    def __init__(self, k: np.ndarray, values: np.ndarray) -> None:
        from scipy.interpolate import CubicSpline

        scaled = k * values
        self.k_min, self.k_max = float(k[0]), float(k[-1])
        self.spline = CubicSpline(np.log(k), scaled, axis=-1)
        self.slope = (scaled[..., 1] - scaled[..., 0]) / (k[1] - k[0])
        self.limit = scaled[..., 0] - self.slope * k[0]

    def __call__(self, k: np.ndarray) -> np.ndarray:
        k = np.asarray(k, dtype=float)
        inside = self.spline(np.log(np.clip(k, self.k_min, self.k_max)))
        below = self.limit[..., None] + self.slope[..., None] * k
        return np.where(k < self.k_min, below, np.where(k > self.k_max, 0.0, inside)) / k


def _node_spectra(layer: Layer, nodes: ShiftNodes, samples_per_decade: int = 40) -> list[_Spectral]:
    """The compliance of each node (:func:`elastic_base_terms`) as a :class:`_Spectral` at the
    layer's G: c_p(k)/G with c_p = G_ref sum_j beta_j(k) l_p(u_j(k)), beta_j = alpha_j/(shift_j + G_ref)
    (:func:`modulus_poles`), sampled at k h from 1e-2 to 18 (beyond, alpha_j < exp(-36)) and
    interpolated (:class:`_LogInterpolant`)."""
    h, g = layer.thickness, layer.shear_modulus
    kh = np.logspace(-2, np.log10(18.0), int(samples_per_decade * np.log10(1800)) + 1)
    k = kh / h
    bary = lobatto_nodes(nodes.nodes.size - 1)[1]
    ref = nodes.reference
    tables = {}
    for key in ("zz", "ze", "ez", "ee", "pp"):
        poles = modulus_poles(layer, k, key)
        u = ref / (ref + poles.shift)
        beta = poles.alpha / (poles.shift + ref)
        basis = lagrange_basis(u.ravel(), nodes.nodes, bary).reshape(u.shape + (nodes.nodes.size,))
        tables[key] = _LogInterpolant(k, ref * np.einsum("kj,kjp->pk", beta, basis) / g)
    zero = {"zz": {0: 0.0}, "xx": {0: 0.0, 2: 0.0}, "xz": {1: 0.0}, "zx": {1: 0.0}}
    # periodic kernels: the rigid-base term's bounded mean (h/M, h/G) is cancelled by the node it is
    # merged with (u = 1, the same J(t)): on an elastic substrate the mean compliance is unbounded (0)
    rigid_mean = {c: -v for c, v in uniform_compliance(replace(layer, base="rigid")).items()}
    no_mean = {"zz": 0.0, "xx": 0.0, "xz": 0.0, "zx": 0.0}
    out = []
    for p in range(nodes.nodes.size):
        def planes(kq: np.ndarray, p: int = p) -> dict[str, np.ndarray]:
            vals = {key: table(kq)[p] for key, table in tables.items()}
            return {"zz": vals["zz"], "ze": 1j * vals["ze"], "ez": 1j * vals["ez"], "ee": vals["ee"], "pp": vals["pp"]}

        a = {key: float(table.limit[p]) for key, table in tables.items()}
        low = {"zz": {0: a["zz"]}, "xx": {0: 0.5 * (a["ee"] + a["pp"]), 2: 0.5 * (a["ee"] - a["pp"])},
               "xz": {1: a["ez"]}, "zx": {1: a["ze"]}}
        out.append(_Spectral(planes, zero, low, rigid_mean if p == nodes.nodes.size - 1 else no_mean, half_space=False))
    return out


def elastic_base_terms(grid: Grid, layer: Layer, shear: Material, components: tuple[str, ...] = ("zz",),
                            tolerance: float = 1e-4) -> list[ComplianceTerm]:
    """Compliance terms of a viscoelastic layer (Prony shear modulus ``shear``, constant
    nu = ``layer.poisson_ratio``) on an elastic substrate, on DC-FFT or periodic grids.

    With the partial fractions of :func:`modulus_poles`,

        A(k; G) = alpha0(k)/G + sum_j beta_j(k) h(u_j(k); G),   h(u; G) = (s + G_ref)/(G + s),

    u = G_ref/(G_ref + s) in (0, 1) for the shifts s = shift_j(k) > 0 and beta_j = alpha_j/(s + G_ref).
    The shifts move with |q|, so the creep functions of G(t) + shift_j(k) have |q|-dependent times
    (exact per wavevector: :func:`viscoelastic_periodic_modes`) and no real-space kernel. Here h is
    interpolated in u at fixed nodes u_p (:func:`shift_nodes`, relative error <= ``tolerance`` for
    every G on the material's complex modulus curve, hence for the whole time response):

        A(k; G) ~ alpha0(k)/G + sum_p c_p(k) h(u_p; G)/G_ref,   c_p = G_ref sum_j beta_j l_p(u_j),

    so that every term has a kernel of q and a response of t with fixed times: alpha0 G is the
    layer on a rigid base (same interface) with J(t) (:func:`factored_terms`); node p has the kernel
    of c_p (built like the layer's, :func:`unit_kernels` with its own compliance: no
    half-space part, the substrate's 1/k at small k) and the creep function whose Carson transform is
    h(u_p; G~(s))/G_ref (:meth:`ShiftNodes.response`): 1/G_ref (elastic) at u = 0 (s = inf, the
    substrate), J(t) at u = 1 (merged into the rigid-base term), the creep function of G(t) + s_p
    scaled in between.

    Cost: with D + 1 nodes (D = 4 to 8 for G(0)/G(inf) = 10 at 1e-4; more for wider spectra) and M
    Prony terms, each component has D + 1 kernels instead of one and each traction component D
    histories of M fields each (D M fields against M on a rigid base); every kernel costs one layer
    kernel build, and every step one more spectrum product per kernel.
    """
    nodes = shift_nodes(shear, tolerance)
    creep = prony_creep_spectrum(shear.g_inf, shear.g, shear.tau)
    rigid = factored_terms(grid, replace(layer, base="rigid"), creep, components)
    terms: list[ComplianceTerm] = []
    last = nodes.nodes.size - 1
    for p, spectral in enumerate(_node_spectra(layer, nodes)):
        kernels = unit_kernels(grid, layer, components, spectral)
        shapes = steady_shapes(grid, layer, components, spectral=spectral)
        if p == last:  # u = 1: the response is J(t), that of the rigid-base terms
            rigid = [replace(t, kernel=t.kernel + kernels[t.name],
                             steady=None if t.steady is None else SteadyShape(t.steady.parts + shapes[t.name].parts))
                     for t in rigid]
            continue
        response = nodes.response(shear, p)
        label = "elastic" if p == 0 else f"node{p}"
        terms += [ComplianceTerm(c[0], c[1], kernels[c], response, f"{c}:{label}", shapes.get(c)) for c in components]
    return rigid + terms


# --- the body ------------------------------------------------------------------------------------

#: k a of the wavenumber whose compliance stands for a contact of radius a in :meth:`LayerOnBase.contact_radius`:
#: 32/(3 pi) makes the estimate the thin-layer (Winkler) limit exactly
CONTACT_WAVENUMBER = 32.0 / (3.0 * math.pi)
#: k h below which :meth:`LayerOnBase.contact_radius` takes the compliance at this k h (the layer's
#: system loses digits below it; the thin limit h/M is reached to ~(k h)^2 there)
THIN_KH = 1e-3


@dataclass(frozen=True)
class LayerOnBase(TermBody):
    """A viscoelastic layer (``material``, constant nu) on a rigid or elastic base (``settings``, the
    case's ``[layer]``: a :class:`~viscontact.problem.problem.LayerSettings`, whose field names are the
    case keys: ``substrate`` there is the base here): a :class:`~viscontact.bodies.base.Body`.

    Its compliance: on a rigid base, or for an elastic layer, the layer's unit-modulus kernels times
    the creep compliance (:func:`rigid_base_terms`, :func:`factored_terms`: one term per component);
    a viscoelastic layer on an elastic base, the rigid-base terms and one kernel per shift node,
    each with its own creep function (:func:`elastic_base_terms`). Its fingerprint part:
    {"bulk_modulus": None, "layer": LayerSettings(...)}.
    """

    material: Material
    settings: LayerSettings

    subsurface_stresses = False
    contact_model = "layer compliance at k = 32/(3 pi a): Winkler when thin, the half-space when thick; Lee & Radok creep"

    @property
    def layer(self) -> Layer:
        """The elastic layer at G(0) on its base (checks the settings)."""
        return self.layer_at(self.material.shear_modulus_instantaneous)

    def layer_at(self, shear_modulus: float) -> Layer:
        """The elastic layer of shear modulus ``shear_modulus`` [Pa] on the base."""
        s = self.settings
        return Layer(s.thickness, shear_modulus, self.material.poisson_ratio, s.substrate, s.interface,
                     s.substrate_shear_modulus, s.substrate_poisson_ratio)

    @property
    def _shift_nodes(self) -> ShiftNodes | None:
        """The shift nodes of a viscoelastic layer on an elastic base (:func:`shift_nodes`); None when
        the time response factors (rigid base, elastic layer)."""
        if self.settings.substrate == "elastic" and not self.material.is_elastic:
            return shift_nodes(self.material)
        return None

    @property
    def description(self) -> Mapping[str, Any]:
        return {"layer": self.settings}

    def terms(self, grid: Grid, components: tuple[str, ...]) -> list[ComplianceTerm]:
        """The terms of the class docstring."""
        layer = self.layer
        if layer.base == "rigid":
            return rigid_base_terms(grid, layer, self.material, components)
        if not self.material.is_elastic:
            return elastic_base_terms(grid, layer, self.material, components)
        return factored_terms(grid, layer, self.material.creep, components)

    def stability_responses(self) -> list[CreepSpectrum]:
        """J(t), and on an elastic base the responses of the shift nodes (times of G(t) + s_p) [1/Pa]."""
        nodes = self._shift_nodes
        extra = [] if nodes is None else [nodes.response(self.material, p) for p in range(nodes.nodes.size)]
        return [self.material.creep] + extra

    def size(self) -> tuple[int, int]:
        """M history fields and one kernel per component; D M and D + 1 for a viscoelastic layer on an
        elastic base with D + 1 shift nodes."""
        modes = self.material.creep.retardation_times.size
        nodes = self._shift_nodes
        return (modes, 1) if nodes is None else ((nodes.nodes.size - 1) * modes, nodes.nodes.size)

    def result_attributes(self) -> dict[str, Any]:
        """The ``[layer]`` keys, prefixed ``layer_``."""
        s = self.settings
        return {"layer_thickness": float(s.thickness), "layer_substrate": s.substrate,
                "layer_interface": s.interface, "layer_substrate_shear_modulus": float(s.substrate_shear_modulus),
                "layer_substrate_poisson_ratio": float(s.substrate_poisson_ratio)}

    def material_summary(self) -> str:
        return f"poisson_ratio = {self.material.poisson_ratio:g}"

    def contact_radius(self, load: float, shape: ContactShape, compliance_factor: float = 1.0) -> float:
        """Contact size a [m] of the rigid ``shape`` (load W [N]) on the layer with G(0)/c
        (c = ``compliance_factor``; the base does not creep).

        The shape's elastic relation W = W(a, E*) (:meth:`~viscontact.bodies.base.ContactShape.load_at_size`)
        in terms of the compliance: a half-space has A_zz(k) = (1 - nu)/(G k) = 2/(E* k), so its E* is
        2/(k A_zz(k)) for any k. Here A_zz is the layer's (:func:`in_plane_compliance`) at the
        wavenumber k = kappa/a of the contact, and a solves

            W = W(a, 2 / (k A_zz(k))),   k = kappa/a,   kappa = 32/(3 pi) (:data:`CONTACT_WAVENUMBER`).

        For a sphere (Hertz, W = 4 E* a^3/(3 R)) that is a^3 = 3 W R (kappa/a) A_zz(kappa/a) / 8. A
        shape whose contact does not grow (a flat punch's face) keeps its size.

        Limits (a sphere): a thick layer (k h >> 1) is the half-space, Hertz for any kappa. A thin bonded
        compressible layer on a rigid base has A_zz -> h/M (oedometric M = 2 G (1 - nu)/(1 - 2 nu)),
        a Winkler foundation of stiffness M/h: p(r) = (M/h)(delta - r^2/2R), zero at r = a, so
        delta = a^2/2R and W = pi M a^4/(4 R h) (:func:`viscontact.physics.reference.winkler_sphere`);
        the equation gives a^4 = 3 kappa W R h/(8 M), the same for this kappa. A thin incompressible
        layer (A_zz -> h^3 k^2/(3 G): squeeze flow; exact a^6 = 32 W R h^3/(pi G), cf. Jaffar 1989;
        tests/validation/test_layer_contact.py) comes out 11-14 % small. On a softer elastic base the
        compliance at long wavelengths is the base's (1 - nu_s)/(G_s k), so the estimate moves from
        the layer's to the base's half-space as the contact outgrows h: the layer and its base are
        judged together, by the one compliance, rather than by the smaller or larger of two Hertz
        radii. Below k h = :data:`THIN_KH` the compliance at that k h is used.
        """
        if not shape.grows:
            return shape.size_at_load(load, math.nan)
        if not math.isfinite(compliance_factor):  # a fluid's unbounded creep (inf), no estimate (NaN)
            return math.inf if compliance_factor > 0 else math.nan
        layer = self.layer_at(self.material.shear_modulus_instantaneous / compliance_factor)
        h, k_floor = layer.thickness, THIN_KH / layer.thickness

        def excess(log_a: float) -> float:
            a = math.exp(log_a)
            k = max(CONTACT_WAVENUMBER / a, k_floor)
            modulus = 2.0 / (k * float(in_plane_compliance(layer, np.array([k]))["zz"][0].real))
            return math.log(load) - math.log(shape.load_at_size(a, modulus))

        # the size on the half-space of the layer's material brackets it within a few decades (a thin
        # layer on a rigid base is stiffer, on a softer base softer)
        scale = shape.size_at_load(load, contact_modulus(layer.shear_modulus, layer.poisson_ratio))
        low, high = math.log(1e-3 * min(h, scale)), math.log(1e3 * max(h, scale))
        if excess(low) <= 0.0 or excess(high) >= 0.0:
            return math.exp(low if excess(low) <= 0.0 else high)
        from scipy.optimize import brentq  # imported where used (see modulus_poles)

        return math.exp(brentq(excess, low, high, xtol=1e-12))

    def contact_radius_at_approach(self, approach: float, shape: ContactShape) -> float:
        """The half-space's relation of the shape (Hertz: a = sqrt(R delta) [m]): a thin compressible
        layer on a rigid base reaches sqrt(2 R delta) (Winkler), a thin incompressible one 2 sqrt(R
        delta); this estimate takes the half-space's (a known shortfall for thin layers under an approach)."""
        return shape.size_at_approach(approach)
