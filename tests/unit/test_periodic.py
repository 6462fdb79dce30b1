"""Periodic influence coefficients and the periodic convolver (viscontact.physics.periodic).

Independent truths:
* the Ewald split is exact only if its two halves (real-space closed form minus quadrature, and the
  screened Fourier series) are both right: the kernels must not depend on the screening parameter
  (round-off, 1e-13);
* a brute-force sum of the half-space compliance times the cell footprint over 401^2 aliases (no
  split, no real-space part) converges like 1/S^2: agreement to 1e-8 (even) and 1e-6 (odd kernels,
  slower) is what S = 200 allows;
* on a large period the periodic kernel near the origin tends to the non-periodic one of
  kernels.py: the difference is a constant (the images and the zero mean) of order dx/w plus a
  variation of order (d/w)^3 (even) or (d/w)^2 (odd kernels): its orders are measured;
* at low q the spectrum is Johnson's compliance (stiffness E*|q|/2 for zz) up to the cell
  footprint, 1 - (q dx)^2/24.
"""
from __future__ import annotations

import numpy as np
import pytest

from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import COMPONENTS, rectangle_influence
from viscontact.physics.periodic import PeriodicConvolver, half_space_compliance, periodic_influence_coefficients
from vc_testing import observed_order

NU = 0.3


@pytest.mark.parametrize("nu", [0.0, NU, 0.5])
def test_independent_of_the_ewald_screening(nu):
    grid = Grid(12, 0.7e-3)
    ref = periodic_influence_coefficients(grid, nu, screening=1.0)
    for screening in (0.5, 1.7):
        other = periodic_influence_coefficients(grid, nu, screening=screening)
        for c in COMPONENTS:
            scale = max(np.abs(ref["zz"]).max(), 1e-300)
            assert np.abs(other[c] - ref[c]).max() <= 1e-13 * scale, (c, screening)


def test_matches_brute_force_alias_sum():
    """The plain alias sum truncated at |s| <= S tends to our kernels as 1/S^3 (even kernels) and
    1/S^2 (odd kernels, slower): the observed orders show that the limit is ours, not a value
    near it."""
    grid = Grid(8, 0.5)
    n, dx = grid.n, grid.spacing
    spectra = {c: np.fft.fft2(v) for c, v in periodic_influence_coefficients(grid, NU).items()}
    ky = 2 * np.pi * np.fft.fftfreq(n, dx)[:, None]
    kx = 2 * np.pi * np.fft.fftfreq(n, dx)[None, :]
    cutoffs = np.array([50, 100, 200])
    errors = {c: [] for c in COMPONENTS}
    for cutoff in cutoffs:
        s = np.arange(-cutoff, cutoff + 1)
        total = {c: np.zeros((n, n), complex) for c in COMPONENTS}
        for sy in s:
            qy = (ky + 2 * np.pi * sy / dx)[None]
            qx = kx[None] + 2 * np.pi * s[:, None, None] / dx
            footprint = np.sinc(qx * dx / (2 * np.pi)) * np.sinc(qy * dx / (2 * np.pi))
            for c, v in half_space_compliance(qx, qy, NU).items():
                total[c] += (v * footprint).sum(axis=0)
        for c in COMPONENTS:
            errors[c].append(np.abs(spectra[c] - total[c]).max() / np.abs(spectra[c]).max())
    for c, order, last in (("zz", 3, 2e-8), ("xx", 3, 2e-8), ("xz", 2, 2e-6), ("zx", 2, 2e-6)):
        assert observed_order(1.0 / cutoffs, errors[c]) == pytest.approx(order, abs=0.1), (c, errors[c])
        assert errors[c][-1] < last, c


def test_zero_mean_and_symmetries():
    grid = Grid(10, 1.0)
    k = periodic_influence_coefficients(grid, NU)
    flip = -np.arange(grid.n)  # offset -i sits at index (-i) mod n
    for c in COMPONENTS:
        assert abs(k[c].mean()) <= 1e-15 * np.abs(k[c]).max()
    for c in ("zz", "xx"):
        np.testing.assert_allclose(k[c][:, flip], k[c], rtol=0, atol=1e-15 * np.abs(k[c]).max())
        np.testing.assert_allclose(k[c][flip, :], k[c], rtol=0, atol=1e-15 * np.abs(k[c]).max())
    np.testing.assert_allclose(k["xz"][:, flip], -k["xz"], atol=1e-15 * np.abs(k["xz"]).max())
    np.testing.assert_allclose(k["zx"], -k["xz"], atol=0)  # Betti: IC_xz(x) = IC_zx(-x)


def test_tends_to_the_non_periodic_kernel_on_a_large_period():
    dx, nu = 1.0e-5, NU
    offsets = np.arange(-3, 4)
    ix, iy = np.meshgrid(offsets, offsets, indexing="xy")
    ref = rectangle_influence(ix * dx, iy * dx, dx / 2, dx / 2, nu)
    sizes = np.array([16, 32, 64, 128])
    raw = {c: [] for c in COMPONENTS}
    shape = {c: [] for c in COMPONENTS}
    for n in sizes:
        k = periodic_influence_coefficients(Grid(int(n), n * dx / 2), nu)
        for c in COMPONENTS:
            diff = k[c][iy % n, ix % n] - ref[c]
            scale = np.abs(ref[c]).max()
            raw[c].append(np.abs(diff).max() / scale)
            shape[c].append(np.abs(diff - diff.mean()).max() / scale)
    for c in ("zz", "xx"):
        assert observed_order(1.0 / sizes, raw[c]) == pytest.approx(1.0, abs=0.05), c   # constant ~ dx/w
        assert observed_order(1.0 / sizes, shape[c]) == pytest.approx(3.0, abs=0.1), c   # variation ~ (d/w)^3
        assert shape[c][-1] < 5e-6
    for c in ("xz", "zx"):
        assert observed_order(1.0 / sizes, raw[c]) == pytest.approx(2.0, abs=0.1), c     # odd: ~ d/w^2
        assert raw[c][-1] < 1e-3


def test_low_q_spectrum_is_the_half_space_compliance():
    """u^ = K^ p^ with K^_zz -> (1 - nu)/(G|q|) = 2/(E*|q|): stiffness E*|q|/2 (G = 1 here)."""
    grid = Grid(128, 2.0e-3)
    n, dx = grid.n, grid.spacing
    k = periodic_influence_coefficients(grid, NU)
    ky = 2 * np.pi * np.fft.fftfreq(n, dx)
    kx = 2 * np.pi * np.fft.fftfreq(n, dx)
    e_star = 2.0 / (1 - NU)
    for j, i in [(0, 1), (1, 0), (1, 1), (2, 3), (0, 5), (4, 2)]:
        qx, qy = kx[i], ky[j]
        q = np.hypot(qx, qy)
        bound = (q * dx) ** 2 / 8  # the cell footprint is 1 - (q dx)^2 / 24 + aliases
        spec = {c: np.fft.fft2(k[c])[j, i] for c in COMPONENTS}
        assert abs(spec["zz"] * e_star * q / 2 - 1) < bound
        assert abs(spec["xx"] / ((1 - NU * qx**2 / q**2) / q) - 1) < bound
        odd = (1 - 2 * NU) * 1j * qx / (2 * q**2)
        if qx == 0:
            assert abs(spec["xz"]) < 1e-12 * abs(spec["zz"])
        else:
            assert abs(spec["xz"] / odd - 1) < bound
            assert abs(spec["zx"] / -odd - 1) < bound


def _circular(kernel: np.ndarray, field: np.ndarray) -> np.ndarray:
    """Literal periodic sum u_i = sum_j K((i - j) mod n) f_j."""
    out = np.zeros_like(field)
    for jy, jx in zip(*np.nonzero(field)):
        out += field[jy, jx] * np.roll(kernel, (jy, jx), axis=(0, 1))
    return out


@pytest.mark.parametrize("component", COMPONENTS)
def test_convolver_is_the_circular_sum(component):
    grid = Grid(10, 1.0e-3)
    conv = PeriodicConvolver.for_grid(grid, NU, workers=1)
    k = periodic_influence_coefficients(grid, NU)
    rng = np.random.default_rng(4)
    field = rng.standard_normal((10, 10))
    ref = _circular(k[component], field)
    scale = np.abs(ref).max()
    assert np.abs(conv.apply(component, field) - ref).max() <= 1e-12 * scale
    sparse = np.zeros((10, 10))
    sparse[0, 9], sparse[7, 2], sparse[9, 0] = 1.0, -0.5, 2.0
    ref = _circular(k[component], sparse)
    assert np.abs(conv.apply_sparse(component, sparse) - ref).max() <= 1e-12 * np.abs(ref).max()
    both = conv.combine([(component, 2.0, field), ("zz", -1.0, sparse)])
    expect = 2.0 * _circular(k[component], field) - _circular(k["zz"], sparse)
    assert np.abs(both - expect).max() <= 1e-12 * np.abs(expect).max()


def test_preconditioner_inverts_the_operator_on_zero_mean_fields():
    grid = Grid(16, 1.0e-3)
    conv = PeriodicConvolver.for_grid(grid, NU, workers=1, components=("zz",))
    rng = np.random.default_rng(5)
    p = rng.standard_normal((16, 16))
    p -= p.mean()
    back = conv.preconditioner("zz", 3.0)(3.0 * conv.apply("zz", p))
    assert np.abs(back - p).max() <= 1e-10 * np.abs(p).max()


def test_full_contact_by_constrained_cg_with_the_exact_preconditioner():
    """In full contact the periodic load-controlled problem is linear: p = p_mean + K^-1 (delta - h0)
    mode by mode (exact). With its exact Fourier preconditioner Polonsky-Keer converges in one
    iteration; the next one must not divide round-off by round-off (it used to return p = 0 for a
    few of these surfaces and warm starts)."""
    from viscontact.numerics.constrained import constrained_cg

    grid = Grid(16, 0.5e-3)
    x, y = grid.mesh()
    k = 2 * np.pi / (2 * grid.half_width)
    conv = PeriodicConvolver.for_grid(grid, NU, workers=1, components=("zz",))
    compliance = 1.0 / 1e6  # 1/G [1/Pa]
    p_mean = 2e5
    spec = compliance * conv.spectra["zz"].copy()
    spec[0, 0] = 1.0
    for seed in range(20):
        rng = np.random.default_rng(seed)
        gap = 1e-6 * (1 - np.cos(k * x)) + 0.3e-6 * (1 - np.cos(2 * k * y)) + 1e-8 * rng.random((16, 16))
        exact = p_mean + conv.inverse(-conv.spectrum(gap - gap.mean()) / spec)
        assert exact.min() > 0  # full contact
        for x0 in (np.zeros_like(gap), exact, exact * (1 + 1e-3 * np.cos(3 * k * x)),
                   exact * (1 + 1e-6 * rng.random((16, 16)))):
            sol = constrained_cg(lambda p: compliance * conv.apply("zz", p), -gap, x0, 0.0, np.inf,
                                 total=p_mean * (2 * grid.half_width) ** 2, cell_area=grid.cell_area,
                                 tolerance=1e-8, preconditioner=conv.preconditioner("zz", compliance))
            assert np.abs(sol.x - exact).max() <= 1e-9 * p_mean, seed
            assert sol.multiplier == pytest.approx(gap.mean(), rel=1e-9)


def test_a_step_along_the_null_space_ends_the_full_contact_solve(monkeypatch):
    """The periodic operator's constant mode is in its null space (its curvature is round-off, of
    either sign). In full contact under load control the gradient left once its mean (the load
    multiplier) is taken off is that mode times the mean's round-off, which depends on the CPU's
    summation order: 2e-14 of the approach at 64^2 on an AVX-512 Xeon, above the round-off test,
    and the transient of a full-contact sinusoid stepped 1e25 along the mode and lost every pressure.
    Here the gradient is exactly constant (dyadic values), each mean 1e-13 off and the mode's
    curvature 1e-12 of the compliance: the solve must stop at the solution (the old one ended 104 %
    off after 17 iterations)."""
    from viscontact.numerics import constrained

    grid = Grid(32, 0.5e-3)
    x, _ = grid.mesh()
    k = 2 * np.pi / (2 * grid.half_width)
    conv = PeriodicConvolver.for_grid(grid, NU, workers=1, components=("zz",))
    compliance = 1.0 / 1e6

    def apply_k(p):
        mean = p.mean()
        return compliance * conv.apply("zz", p - mean) + 1e-12 * compliance * mean

    gap = 1e-6 * (1 - np.cos(k * x))
    spec = compliance * conv.spectra["zz"].copy()
    spec[0, 0] = 1.0
    exact = 2e5 + conv.inverse(-conv.spectrum(gap - gap.mean()) / spec)
    product = np.round(apply_k(exact) * 2.0**62) / 2.0**62  # K x0 to 1e-12, multiples of 2^-62
    b = product - 2.0**-20
    assert np.all(product - b == 2.0**-20)  # the gradient: the approach, exactly, everywhere
    exact_mean = constrained._free_mean
    monkeypatch.setattr(constrained, "_free_mean", lambda f, m, n: exact_mean(f, m, n) * (1 - 1e-13))
    sol = constrained.constrained_cg(apply_k, b, exact, 0.0, np.inf, total=float(exact.sum()) * grid.cell_area,
                                     cell_area=grid.cell_area, tolerance=1e-10, start_product=product,
                                     preconditioner=conv.preconditioner("zz", compliance))
    assert np.abs(sol.x - exact).max() <= 1e-12 * exact.max()


def test_partial_contact_grows_from_a_warm_start_with_the_exact_preconditioner():
    """Warm-started from the contact of a smaller load, the free set converges at once (exact
    preconditioner) and the points outside it whose gap would be negative must still be released:
    the result is the cold-started one, with no interpenetration."""
    from viscontact.numerics.constrained import constrained_cg

    grid = Grid(16, 0.5e-3)
    _, y = grid.mesh()
    gap = 1e-6 * (1 - np.cos(2 * np.pi * y / (2 * grid.half_width)))
    conv = PeriodicConvolver.for_grid(grid, NU, workers=1, components=("zz",))
    compliance = 1.0 / 1e6
    area = (2 * grid.half_width) ** 2

    def solve(load, x0):
        return constrained_cg(lambda p: compliance * conv.apply("zz", p), -gap, x0, 0.0, np.inf, total=load,
                              cell_area=grid.cell_area, tolerance=1e-12,
                              preconditioner=conv.preconditioner("zz", compliance))

    small = solve(0.5e3 * area, np.zeros_like(gap))
    for load in (2e3 * area, 6e3 * area):
        cold = solve(load, np.zeros_like(gap))
        warm = solve(load, small.x)
        assert (cold.x > 0).sum() > (small.x > 0).sum()
        assert np.abs(warm.x - cold.x).max() <= 1e-8 * cold.x.max()
        deformed = gap + compliance * conv.apply("zz", warm.x) - warm.multiplier
        assert deformed.min() >= -1e-12 * gap.max()
