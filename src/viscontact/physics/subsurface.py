"""Subsurface stresses of an elastic half-space under the current surface tractions.

The stress field below the surface is computed for surface tractions given on the grid (pressure p
into the solid, shear q_x and optionally q_y acting on the solid), each uniform over its cell, in a
homogeneous isotropic half-space with Poisson ratio nu. The field does not depend on the shear
modulus, so for a viscoelastic half-space with constant nu it is the elastic field of the current
tractions (correspondence principle: the stresses are tied to the tractions at the same instant).

Method: Fourier transform in the surface plane. For a wavevector q = k e (|e| = 1, e_perp = z x e)
the problem splits into an in-plane (e, z) problem and an anti-plane one. With the Papkovich-Neuber
potentials phi = (alpha/k) E, psi = b E, E = exp(-k z) (2 G u = grad(phi + z psi) - 4 (1 - nu) psi e_z;
Barber, *Elasticity*, ch. 20; Johnson, *Contact Mechanics*, ch. 2-3), P = k b = -p + i t_e and
A = k alpha = -i t_e - (1 - 2 nu) P satisfy the surface conditions sigma_zz = -p, sigma_ez = -t_e, and

    sigma_zz = [ A + k z P + 2 (1 - nu) P ] E
    sigma_ee = [-A - k z P + 2 nu P ] E
    sigma_ez = i [-A - k z P - (1 - 2 nu) P ] E
    sigma_pp = 2 nu P E                               (plane strain along e_perp)
    sigma_zp = -t_p E,   sigma_ep = i t_p E          (anti-plane, t_p the traction along e_perp)

rotated back to x, y. Tension is positive; z > 0 is the depth [m]. Tractions are zero-padded to
``padding`` times the grid (the transform is periodic: images of the load sit at least
(padding - 1) x the domain width away) and multiplied by the cell footprint sinc(q_x dx/2) sinc(q_y dx/2).
The section y = 0 is obtained exactly (phase shift in q_y, sum over q_y) at the cell centres in x.
The transform resolves wavelengths down to 2 dx: fields closer to the surface than about 2 dx carry
the truncation of the cell footprint (at z = 0, sigma_zz = -p only to within that).

Von Mises: sqrt(3 J2); maximum shear (Tresca): (sigma_1 - sigma_3)/2 of the principal stresses.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.fft

from viscontact.numerics.grid import Grid

#: names of the stress components (tension positive) [Pa]
STRESS_COMPONENTS = ("xx", "yy", "zz", "xy", "xz", "yz")


@dataclass(frozen=True)
class SectionStresses:
    """Stresses in the section y = 0 at the depths ``depth`` [m] and the cell centres ``x`` [m].

    ``stress[c]`` has shape (len(depth), len(x)) [Pa] for c in :data:`STRESS_COMPONENTS`.
    """

    depth: np.ndarray
    x: np.ndarray
    stress: dict[str, np.ndarray]

    def tensor(self) -> np.ndarray:
        """The stress tensor, shape (depths, x, 3, 3) [Pa]."""
        s = self.stress
        rows = [[s["xx"], s["xy"], s["xz"]], [s["xy"], s["yy"], s["yz"]], [s["xz"], s["yz"], s["zz"]]]
        return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)

    @property
    def von_mises(self) -> np.ndarray:
        """sqrt(((s1-s2)^2 + (s2-s3)^2 + (s3-s1)^2)/2) [Pa], shape (depths, x)."""
        s = self.stress
        return np.sqrt(0.5 * ((s["xx"] - s["yy"]) ** 2 + (s["yy"] - s["zz"]) ** 2 + (s["zz"] - s["xx"]) ** 2)
                       + 3.0 * (s["xy"] ** 2 + s["xz"] ** 2 + s["yz"] ** 2))

    @property
    def max_shear(self) -> np.ndarray:
        """Tresca maximum shear stress (sigma_max - sigma_min)/2 [Pa], shape (depths, x)."""
        principal = np.linalg.eigvalsh(self.tensor())
        return 0.5 * (principal[..., -1] - principal[..., 0])


def _plane_mode_stresses(kx: np.ndarray, ky: np.ndarray, z: float, nu: float, p_hat: np.ndarray,
                         tx_hat: np.ndarray | None, ty_hat: np.ndarray | None,
                         periodic: bool = False, line: bool = False) -> dict[str, np.ndarray]:
    """Stress spectra at depth z [m] of surface traction spectra (module docstring); a shear spectrum
    ``None`` is a zero traction, its terms left out; ``periodic``: the q = 0 mode is the mean traction
    of a periodic surface, not the limit of an isolated load's; ``line``: tractions uniform along y
    (plane strain, q_y = 0), whose isolated load's q = 0 limit is that along e = x."""
    k = np.hypot(kx, ky)
    zero = k == 0
    k_safe = np.where(zero, 1.0, k)
    c, s = np.where(zero, 1.0, kx / k_safe), np.where(zero, 0.0, ky / k_safe)
    t_e = _sum_of_terms((c, tx_hat), (s, ty_hat))
    t_p = _sum_of_terms((-s, tx_hat), (c, ty_hat))
    decay = np.exp(-k * z)
    kz = k * z
    big_p = -p_hat if t_e is None else -p_hat + 1j * t_e
    big_a = -(1 - 2 * nu) * big_p if t_e is None else -1j * t_e - (1 - 2 * nu) * big_p
    s_zz = (big_a + kz * big_p + 2 * (1 - nu) * big_p) * decay
    s_ee = (-big_a - kz * big_p + 2 * nu * big_p) * decay
    s_ez = 1j * (-big_a - kz * big_p - (1 - 2 * nu) * big_p) * decay
    s_pp = 2 * nu * big_p * decay
    out = {
        "xx": s_ee * c**2 + s_pp * s**2,
        "yy": s_ee * s**2 + s_pp * c**2,
        "zz": s_zz,
        "xy": (s_ee - s_pp) * c * s,
        "xz": s_ez * c,
        "yz": s_ez * s,
    }
    if t_p is not None:  # the anti-plane part
        s_zp = -t_p * decay
        s_ep = 1j * t_p * decay
        out["xx"] -= 2 * s_ep * c * s
        out["yy"] += 2 * s_ep * c * s
        out["xy"] += s_ep * (c**2 - s**2)
        out["xz"] -= s_zp * s
        out["yz"] += s_zp * c
    # q = 0: a uniform traction; sigma_zz, sigma_xz, sigma_yz carry it at every depth (equilibrium).
    # periodic: the mean of a periodic traction, the half-space in uniaxial strain under its normal
    # part (sigma_xx = sigma_yy = nu/(1 - nu) sigma_zz) and in simple shear under its shear part.
    # isolated load (padded transform): the in-plane normal stresses take the average over the
    # directions of e of the k -> 0 limits (-p along e, -2 nu p across): -(1 + 2 nu) p / 2
    if np.any(zero):
        p0 = p_hat[zero]
        tx0, ty0 = (0.0 * p0 if t is None else t[zero] for t in (tx_hat, ty_hat))
        in_plane = -nu / (1 - nu) * p0 if periodic else -(1 + 2 * nu) * p0 / 2
        along, across = (-p0, -2 * nu * p0) if line and not periodic else (in_plane, in_plane)
        for name, value in (("zz", -p0), ("xz", -tx0), ("yz", -ty0), ("xx", along),
                            ("yy", across), ("xy", 0.0 * p0)):
            out[name][zero] = value
    return out


def _sum_of_terms(*terms: tuple[np.ndarray, np.ndarray | None]) -> np.ndarray | None:
    """The sum of the products ``factor * spectrum`` whose spectrum is not ``None`` (``None`` if none is)."""
    total = None
    for factor, spectrum in terms:
        if spectrum is not None:
            total = factor * spectrum if total is None else total + factor * spectrum
    return total


def _take(spectra: list[np.ndarray | None], index) -> list[np.ndarray | None]:
    """``spectrum[index]`` of each spectrum, ``None`` (a zero traction) kept."""
    return [None if sp is None else sp[index] for sp in spectra]


def _symmetric_mode_stresses(qx: np.ndarray, qy: np.ndarray, z: float, nu: float,
                             spectra: list[np.ndarray | None],
                             periodic: bool, nyquist: float | None, line: bool = False) -> dict[str, np.ndarray]:
    """:func:`_plane_mode_stresses` on the half plane ``qx`` (>= 0) x ``qy`` with each Nyquist wavevector
    component (+-``nyquist``, one mode of the transform) the average of its two signs: the spectra
    stay Hermitian, the stresses real and mirror-symmetric with the load."""
    fields = _plane_mode_stresses(qx[None, :], qy[:, None], z, nu, *spectra, periodic=periodic, line=line)
    if nyquist is None:
        return fields
    if qx[-1] == nyquist:
        other = _plane_mode_stresses(-qx[None, -1:], qy[:, None], z, nu, *_take(spectra, np.s_[:, -1:]),
                                     periodic=periodic, line=line)
        for c in fields:
            fields[c][:, -1:] = 0.5 * (fields[c][:, -1:] + other[c])
    row = qy == -nyquist
    if np.any(row):
        other = _symmetric_mode_stresses(qx, -qy[row], z, nu, _take(spectra, row), periodic, nyquist)
        for c in fields:
            fields[c][row] = 0.5 * (fields[c][row] + other[c])
    return fields


#: the padded period (padding x the domain width) is at least this many times the deepest depth
IMAGE_DISTANCE = 20.0
#: the largest padded transform side :func:`automatic_padding` chooses (spectra of up to 3 x 4096 x
#: 2049 complex values: 400 MB)
MAX_PADDED = 4096
#: on a line grid, the padded period is at least this many times the deepest depth and the domain's
#: half-width: a line load's images, a period D apart, add sigma_xx ~ -(2 pi/3) W z / D^2 at depth z,
#: (pi^2/3) a z / D^2 of Hertz's p0 (1.4 % measured at a = 0.3 half_width, z = 0.2 half_width, D = 4
#: half_width); at D = 60 max(z, half_width) below 0.1 % of p0 for any contact on the grid
LINE_IMAGE_DISTANCE = 60.0
#: the largest padded transform a line grid's :func:`automatic_padding` chooses (one row: 16 MiB a spectrum)
MAX_PADDED_LINE = 1 << 20


def automatic_padding(grid: Grid, deepest: float, *, warn: bool = True) -> int:
    """The zero-padding factor for an isolated load's stresses down to ``deepest`` [m]: the padded
    period (padding x 2 half_width) at least :data:`IMAGE_DISTANCE` x ``deepest``, 2 at least.

    The transform is periodic: the load's images, a padded period away, add a field that grows with
    depth relative to the load's own (~W/D^2 against ~W/z^2). Hertz tractions, a = 0.4 half_width,
    on the axis: the maximum shear is off by -3.4 % at z = 2 a with padding 2 (D = 10 a), and by
    about 40 (z/D)^2 at z >= a in general: 0.1 % at D = 20 z (0.2 % at z = 0.48 a when the contact
    fills the domain). Capped at a padded side of :data:`MAX_PADDED` (with ``warn``, a
    :class:`~viscontact.errors.ViscontactWarning` giving the depth that remains within 0.1 %).
    """
    width = 2.0 * grid.half_width
    if grid.dimension == 1:  # a line's transforms are one row: pad far (LINE_IMAGE_DISTANCE)
        reach = LINE_IMAGE_DISTANCE * max(deepest, grid.half_width)
        return min(max(2, int(np.ceil(reach / width - 1e-9))), max(2, MAX_PADDED_LINE // grid.n))
    padding = max(2, int(np.ceil(IMAGE_DISTANCE * deepest / width - 1e-9)))
    cap = max(2, MAX_PADDED // grid.n)
    if padding > cap and warn:
        from viscontact.errors import warn_caller

        warn_caller(f"subsurface stresses down to {deepest:.3g} m: the zero-padding is capped at {cap} x the "
                    f"domain ({cap * grid.n} points per side); the periodic images of the load bias the stresses "
                    f"below about {cap * width / IMAGE_DISTANCE:.3g} m by more than 0.1 % (about "
                    f"{40 * (deepest / (cap * width)) ** 2:.1%} at {deepest:.3g} m): widen grid.half_width")
    return min(padding, cap)


def working_bytes(grid: Grid, deepest: float, tractions: int = 3) -> int:
    """The memory :func:`section_stresses` allocates at its peak [bytes] for stresses down to
    ``deepest`` [m] (:func:`automatic_padding`) of ``tractions`` given tractions (1: the pressure
    alone, 2 or 3 with q_x and q_y; only the given ones are transformed): their padded spectra
    (m x (m/2 + 1) complex values, m the padded side) and, while one chunk of q_y rows is turned into
    stresses, :data:`CHUNK_TEMPORARIES` (:data:`PRESSURE_CHUNK_TEMPORARIES` for the pressure alone)
    arrays of that chunk's size; or the transforms' own peak, one spectrum more (the last one's
    zero-padded input), when it is higher. Within 4 % of the peak measured with ``tracemalloc`` for
    the shipped ``creep_subsurface_stress`` case (13 depths down to 1 mm, padding 5), pressure
    alone: 4.3, 16.8, 66.3, 93.0, 131 MiB at n = 32, 64, 128, 256, 512; with q_x: 5.7, 21.9, 86.7,
    127, 203 MiB (:data:`CHUNK_TEMPORARIES` measured with q_x and q_y: 5.9, 22.6, 89.8, 140, 253)."""
    if tractions not in (1, 2, 3):
        raise ValueError(f"tractions: the number of given surface tractions, 1 to 3; got {tractions}")
    m = grid.n if grid.periodic else automatic_padding(grid, deepest, warn=False) * grid.n
    half = m // 2 + 1
    rows = m if grid.dimension == 2 else 1  # a line's spectra: one row
    spectrum = 16 * rows * half
    chunk = 16 * half * min(rows, max(1, _CHUNK // half))
    temporaries = PRESSURE_CHUNK_TEMPORARIES if tractions == 1 else CHUNK_TEMPORARIES
    return max((tractions + 1) * spectrum, tractions * spectrum + temporaries * chunk)


def section_stresses(grid: Grid, poisson_ratio: float, depths: np.ndarray | list[float], pressure: np.ndarray,
                     shear_x: np.ndarray | None = None, shear_y: np.ndarray | None = None,
                     padding: int | None = None, workers: int = -1) -> SectionStresses:
    """Stresses [Pa] in the section y = 0 of the half-space at ``depths`` [m] (>= 0).

    Parameters
    ----------
    grid
        The surface grid; ``pressure`` etc. have shape ``grid.shape``, (n, n) indexed [y, x] [Pa]. On a
        line grid (``grid.dimension = 1``, (1, n)) the tractions are uniform along y and the field is
        plane strain (the modes q = (q_x, 0) only: sigma_yy = nu (sigma_xx + sigma_zz), no xy, yz
        shear; the McEwen (1949) field under Hertz's line pressure, Johnson 1985 Eq. 4.49). On a periodic grid
        (``grid.periodic``) the tractions are one period of a periodic surface load and the stresses
        are periodic: unpadded transforms over the period, the mean tractions carried to every depth
        (at depth the field tends to sigma_zz = -mean p, sigma_xz = -mean q_x, sigma_xx = sigma_yy =
        -nu/(1 - nu) mean p, with corrections ~exp(-2 pi z / period)).
    poisson_ratio
        nu of the half-space [-].
    pressure, shear_x, shear_y
        Surface tractions on the solid: p into the solid, q_x and q_y along +x, +y [Pa]. A shear
        ``None`` is zero and costs nothing: it is neither transformed nor carried through the
        stresses (the same stresses as a zero array, to the bit).
    padding
        Zero-padding factor of the transform of an isolated load (>= 2); default
        :func:`automatic_padding` of the deepest depth; none on a periodic grid (``None`` only).

    Examples
    --------
    Below a Hertz pressure (a = 1 mm, p0 = 1 MPa, nu = 0.3) the maximum shear is 0.31 p0 at 0.48 a:

    >>> import numpy as np
    >>> grid = Grid(65, 3e-3)
    >>> x, y = grid.mesh()
    >>> p = 1e6 * np.sqrt(np.clip(1 - (x**2 + y**2) / 1e-6, 0, None))
    >>> section = section_stresses(grid, 0.3, [0.48e-3], p)
    >>> round(float(section.max_shear.max()) / 1e6, 2)
    0.31
    """
    n, dx = grid.n, grid.spacing
    depths = np.atleast_1d(np.asarray(depths, dtype=float))
    if np.any(depths < 0) or not np.all(np.isfinite(depths)):
        raise ValueError(f"subsurface depths must be finite and >= 0 m, got {depths}")
    if grid.periodic:
        if padding is not None:
            raise ValueError(f"padding: a periodic grid's stresses are periodic, its transforms unpadded; got {padding}")
        m = n
    else:
        padding = automatic_padding(grid, float(depths.max(initial=0.0))) if padding is None else padding
        if padding < 2:
            raise ValueError(f"padding must be >= 2, got {padding}")
        m = padding * n
    # real tractions: half spectra along x (the stresses are real, their spectra Hermitian); a shear
    # not given (None) is zero: neither transformed nor carried through the stresses' terms
    line = grid.dimension == 1
    rows = 1 if line else m  # a line's tractions: one row, uniform along y (q_y = 0)
    spectra = [None if t is None else scipy.fft.rfft2(t, s=(rows, m), workers=workers)
               for t in (pressure, shear_x, shear_y)]
    qy = np.zeros(1) if line else 2.0 * np.pi * scipy.fft.fftfreq(m, dx)
    qx = 2.0 * np.pi * scipy.fft.rfftfreq(m, dx)
    footprint = np.sinc(qx[None, :] * dx / (2 * np.pi)) * np.sinc(qy[:, None] * dx / (2 * np.pi))
    for sp in spectra:  # in place: a product would hold six spectra at once
        if sp is not None:
            sp *= footprint
    del footprint
    # value at y = 0: the transform's row 0 is y_0 = grid.y[0]
    phase_y = np.exp(1j * qy * (0.0 - grid.y[0]))[:, None] / rows
    out = {c: np.empty((depths.size, n)) for c in STRESS_COMPONENTS}
    chunk = max(1, _CHUNK // qx.size)  # q_y rows at a time: the temporaries stay ~ _CHUNK values each
    for i, z in enumerate(depths):
        sums = {c: np.zeros(qx.size, dtype=complex) for c in STRESS_COMPONENTS}
        for j in range(0, rows, chunk):
            part = slice(j, j + chunk)
            fields = _symmetric_mode_stresses(qx, qy[part], float(z), poisson_ratio, _take(spectra, part),
                                              grid.periodic, np.pi / dx if m % 2 == 0 else None, line)
            for c in STRESS_COMPONENTS:
                sums[c] += np.sum(fields[c] * phase_y[part], axis=0)
        for c in STRESS_COMPONENTS:
            out[c][i] = scipy.fft.irfft(sums[c], m, workers=workers)[:n]
    return SectionStresses(depths, grid.x.copy(), out)


#: complex values per temporary array in :func:`section_stresses` (2^18: 4 MiB)
_CHUNK = 1 << 18
#: chunk-sized arrays alive at once while :func:`section_stresses` turns a chunk of spectra into
#: stresses (:func:`_plane_mode_stresses`: the rotation, the potentials, the components and the
#: expressions' temporaries; the real ones count half) with a shear traction: 25.7 measured, see
#: :func:`working_bytes`
CHUNK_TEMPORARIES = 26
#: the same for the pressure alone (no in-plane traction t_e, no anti-plane part): 20.2 measured
PRESSURE_CHUNK_TEMPORARIES = 21
