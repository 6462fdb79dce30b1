"""Layer on a substrate (viscontact.bodies.layer): Fourier compliance and kernels against independent truths.

* Fourier space: the classical closed form of the bonded layer on a rigid base (A_zz), a substrate
  identical to the layer (exactly the half-space, every component), k h -> inf (half-space), k h -> 0
  (h/M with the oedometric modulus, h/G in shear), r = G_s/G -> inf (rigid). Tolerances are
  round-off (1e-9) except where a limit is approached at finite k h (stated).
* Kernels: an independent 1-D Hankel quadrature of the same compliance (composite Gauss-Legendre
  of (A - A_half-space) J_n(k r) k dk, integrated over the cell by Gauss-Legendre, plus the closed-form
  half-space cell integrals). The FFT kernels differ from it by a near-constant offset of ~1e-4 of the
  self-coefficient (periodic-image residue, module docstring); tolerance 3e-4 of the self-coefficient.
* Periodic kernels: on a rigid base the kernel decays exponentially, so the periodic kernel of a
  domain much wider than h equals the non-periodic one near the origin (two different splits). Their
  spectrum at low wavevectors is the alias sum of the exact compliance times the cell footprint
  (fourier_compliance, independent of the kernel construction); a layer many periods thick is the
  exact periodic half-space (viscontact.physics.periodic, Ewald) plus its uniform mode h/M.
"""
from __future__ import annotations

import numpy as np
import pytest
import scipy.fft
from scipy.special import jv

from viscontact.errors import ParameterError
from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import rectangle_influence
from viscontact.bodies.layer import (Layer, anti_plane_compliance, fourier_compliance, in_plane_compliance,
                               influence_coefficients, periodic_spectra)
from viscontact.physics.periodic import periodic_influence_coefficients

G, NU = 1.0e6, 0.3
K = np.logspace(-3, 1.5, 19)  # k h from 1e-3 to 30 with h = 1


def half_space(k: np.ndarray, g: float = G, nu: float = NU) -> dict[str, np.ndarray]:
    return {"zz": (1 - nu) / (g * k), "ee": (1 - nu) / (g * k), "ez": 1j * (1 - 2 * nu) / (2 * g * k),
            "ze": -1j * (1 - 2 * nu) / (2 * g * k)}


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_rigid_bonded_closed_form(nu):
    """Relative 1e-9 for k h >= 1e-2. (Incompressible, k h -> 0, A_zz ~ (k h)^3 comes out of a
    cancellation among O(1/(k h)) coefficients: 2e-7 at k h = 1e-3; kernels sample k h >= 2 pi h / box.)"""
    layer = Layer(1.0, G, nu)
    kh = K[K >= 1e-2]
    closed = ((1 - nu) / (G * kh) * ((3 - 4 * nu) * np.sinh(2 * kh) - 2 * kh)
              / ((3 - 4 * nu) * np.cosh(2 * kh) + 2 * kh**2 + 5 - 12 * nu + 8 * nu**2))
    np.testing.assert_allclose(in_plane_compliance(layer, kh)["zz"], closed, rtol=1e-9)


@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
def test_identical_bonded_substrate_is_the_half_space(interface):
    layer = Layer(1.0, G, NU, "elastic", "bonded", G, NU)
    a = in_plane_compliance(layer, K)
    for key, ref in half_space(K).items():
        np.testing.assert_allclose(a[key], ref, rtol=1e-12, atol=0, err_msg=key)
    np.testing.assert_allclose(anti_plane_compliance(layer, K), 1 / (G * K), rtol=1e-12)
    # thick layers on anything tend to the half-space of the layer material
    far = np.array([40.0, 200.0])
    thick = in_plane_compliance(Layer(1.0, G, NU, "elastic", interface, 5 * G, 0.1), far)
    for key, ref in half_space(far).items():
        np.testing.assert_allclose(thick[key], ref, rtol=1e-12, err_msg=key)


def test_thin_limits_rigid_bonded():
    """k h = 1e-4: A_zz -> h/M, A_ee, A_pp -> h/G, couplings -> 0 (relative corrections O((k h)^2))."""
    h = 2e-3
    layer = Layer(h, G, NU)
    k = np.array([1e-4 / h])
    a = in_plane_compliance(layer, k)
    assert a["zz"][0] == pytest.approx(h / layer.oedometric_modulus, rel=1e-7)
    assert a["ee"][0] == pytest.approx(h / G, rel=1e-7)
    assert anti_plane_compliance(layer, k)[0] == pytest.approx(h / G, rel=1e-7)
    assert abs(a["ez"][0]) < 1e-3 * h / G
    # frictionless base: no lateral constraint along e at long wavelengths -> plane-strain uniaxial
    assert in_plane_compliance(Layer(h, G, NU, interface="frictionless"), k)["zz"][0] == \
        pytest.approx(h * (1 - NU) / (2 * G), rel=1e-6)


def test_stiff_elastic_substrate_tends_to_rigid():
    """(The substrate adds 1/(G_s k) ~ 1e-12 (k h)^-1 / G: below rtol 1e-6 for k h >= 1e-3.)"""
    rigid = in_plane_compliance(Layer(1.0, G, NU), K)
    stiff = in_plane_compliance(Layer(1.0, G, NU, "elastic", "bonded", 1e12 * G, 0.3), K)
    for key in rigid:
        np.testing.assert_allclose(stiff[key], rigid[key], rtol=1e-6, atol=1e-8 / G, err_msg=key)
    np.testing.assert_allclose(anti_plane_compliance(Layer(1.0, G, NU, "elastic", "bonded", 1e12 * G, 0.3), K),
                               anti_plane_compliance(Layer(1.0, G, NU), K), rtol=1e-8)


def test_fourier_compliance_rotation():
    """M_xx = c^2 A_ee + s^2 A_pp, M_xz = c A_ez: along x the in-plane values, along y the anti-plane."""
    layer = Layer(1.0, G, NU, "elastic", "bonded", 3 * G, 0.2)
    k = np.array([0.7])
    a, app = in_plane_compliance(layer, k), anti_plane_compliance(layer, k)
    along_x = fourier_compliance(layer, k, 0 * k)
    along_y = fourier_compliance(layer, 0 * k, k)
    assert along_x["xx"][0] == pytest.approx(a["ee"][0])
    assert along_y["xx"][0] == pytest.approx(app[0])
    assert along_x["xz"][0] == pytest.approx(a["ez"][0])
    assert along_y["xz"][0] == 0


def hankel_kernel(layer: Layer, name: str, offsets: list[tuple[int, int]], dx: float) -> np.ndarray:
    """Independent cell kernels at integer offsets: closed-form half-space cell integrals + 6 x 6
    Gauss-Legendre cell integral of the Hankel transform of (A - A_hs), order 0 for zz, order 1 for xz
    (M_xz = i cos(theta_q) beta(k) -> -cos(theta) int beta J_1(k r) k dk / (2 pi)), the k-integral by
    composite 8-point Gauss-Legendre on 1200 panels up to k h = 40."""
    key, order = {"zz": ("zz", 0), "xz": ("ez", 1)}[name]
    edges = np.linspace(0.0, 40.0 / layer.thickness, 1201)
    nodes, weights = np.polynomial.legendre.leggauss(8)
    width = np.diff(edges)[:, None]
    k = (edges[:-1, None] + 0.5 * width * (nodes + 1)).ravel()
    wk = (0.5 * width * weights).ravel()
    diff = in_plane_compliance(layer, k)[key] - half_space(k)[key]
    diff = diff.real if order == 0 else diff.imag
    gl, gw = np.polynomial.legendre.leggauss(6)
    gl, gw = 0.5 * dx * gl, 0.5 * dx * gw
    out = []
    for i, j in offsets:
        ox, oy = i * dx, j * dx
        hs = rectangle_influence(np.array(ox), np.array(oy), dx / 2, dx / 2, NU, (name,))[name] / G
        x = (ox + gl)[:, None] * np.ones(6)[None, :]
        y = np.ones(6)[:, None] * (oy + gl)[None, :]
        r = np.hypot(x, y)[..., None]
        value = np.sum(wk * diff * jv(order, k * r) * k, axis=-1) / (2 * np.pi)
        if order == 1:
            value = -value * x / r[..., 0]
        out.append(float(hs) + float(np.sum(gw[:, None] * gw[None, :] * value)))
    return np.array(out)


@pytest.mark.parametrize("layer_kind", ["rigid", "elastic"])
def test_kernels_against_hankel_quadrature(layer_kind):
    grid = Grid(24, 1.2e-3)
    dx = grid.spacing
    layer = Layer(2 * dx, G, NU) if layer_kind == "rigid" else Layer(2 * dx, G, NU, "elastic", "bonded", 3 * G, 0.2)
    kern = influence_coefficients(grid, layer, ("zz", "xz"))
    offsets = [(0, 0), (1, 0), (2, 3), (6, 1), (11, 0)]
    ref = hankel_kernel(layer, "zz", offsets, dx)
    got = np.array([kern["zz"][j, i] for i, j in offsets])
    np.testing.assert_allclose(got, ref, atol=3e-4 * ref[0])
    offsets = [(1, 0), (2, 1), (5, 3)]
    got = np.array([kern["xz"][j, i] for i, j in offsets])
    np.testing.assert_allclose(got, hankel_kernel(layer, "xz", offsets, dx), atol=3e-4 * ref[0])
    # the coupling kernels are odd in x and reciprocal: IC_xz(x) = IC_zx(-x)
    assert np.allclose(kern["xz"][:, 1:], -kern["xz"][:, :0:-1], atol=1e-12 * ref[0])


def test_periodic_matches_non_periodic_on_a_rigid_base():
    n = 24
    grid = Grid(n, 1.2e-3)
    dx = grid.spacing
    layer = Layer(1.5 * dx, G, NU)
    dc = influence_coefficients(grid, layer)
    per = periodic_spectra(Grid(3 * n, 3 * 1.2e-3), layer)
    for name, spec in per.items():
        real = scipy.fft.irfft2(spec, s=(3 * n, 3 * n))
        scale = np.abs(dc[name]).max()
        for i, j in ((0, 0), (1, 0), (0, 2), (3, 2), (-2, 1)):
            assert real[j, i] == pytest.approx(dc[name][j, i], abs=1e-4 * scale), (name, i, j)
    # the uniform mode of a rigid base: h/M
    assert per["zz"][0, 0].real == pytest.approx(layer.thickness / layer.oedometric_modulus, rel=1e-9)


def alias_sum_spectrum(grid: Grid, layer: Layer, wavevectors: list[tuple[int, int]], aliases: int
                       ) -> dict[str, np.ndarray]:
    """The periodic kernel's spectrum at lattice wavevectors (i, j) (q = 2 pi (i, j)/period), from the
    exact compliance alone: sum over |s_x|, |s_y| <= ``aliases`` of M(q + 2 pi s/dx) times the cell
    footprint sinc(q_x dx/2 pi) sinc(q_y dx/2 pi) (the sampled kernel's aliases, symmetric sum)."""
    dx, period = grid.spacing, 2 * grid.half_width
    s = np.arange(-aliases, aliases + 1)
    out = {c: [] for c in ("zz", "xx", "xz", "zx")}
    for i, j in wavevectors:
        qx = 2 * np.pi * (i / period + s[None, :] / dx) + 0 * s[:, None]
        qy = 2 * np.pi * (j / period + s[:, None] / dx) + 0 * s[None, :]
        m = fourier_compliance(layer, qx, qy, tuple(out))
        footprint = np.sinc(qx * dx / (2 * np.pi)) * np.sinc(qy * dx / (2 * np.pi))
        for name in out:
            out[name].append(np.sum(m[name] * footprint))
    return {name: np.array(v) for name, v in out.items()}


@pytest.mark.parametrize("layer_kind", ["rigid", "elastic", "frictionless", "thick"])
def test_periodic_spectra_are_the_alias_sum_of_the_compliance(layer_kind):
    """Periodic kernels (n = 16) of a layer 2 dx thick on a rigid base, L/4 on an elastic substrate or
    frictionless, and one period L thick: their spectrum at the lowest wavevectors against the alias
    sum of the exact compliance (alias_sum_spectrum, 100 aliases each way). Measured: zz, xx within
    1.4e-8 of the largest value, xz, zx 6.2e-6, the reference's own truncation (4x smaller with 200
    aliases). The former kernels, whose near part was summed over 3 periodic images in real space,
    were off by 4e-4 to 6e-3 (zz, xx) and 11-23 % (xz, zx: the odd near part's 1/r^2 tail left a
    sawtooth along x)."""
    grid = Grid(16, 1e-3, periodic=True)
    dx, period = grid.spacing, 2 * grid.half_width
    layer = {"rigid": Layer(2 * dx, G, NU), "elastic": Layer(period / 4, G, NU, "elastic", "bonded", 3 * G, 0.2),
             "frictionless": Layer(period / 4, G, NU, interface="frictionless"),
             "thick": Layer(period, G, NU)}[layer_kind]
    wavevectors = [(1, 0), (0, 1), (1, 1), (2, 1), (3, 0), (1, 3)]
    ref = alias_sum_spectrum(grid, layer, wavevectors, 100)
    spectra = periodic_spectra(grid, layer)
    for name, spec in spectra.items():
        got = np.array([spec[j % grid.n, i] for i, j in wavevectors])
        tolerance = 2e-5 if name in ("xz", "zx") else 1e-7
        assert np.abs(got - ref[name]).max() <= tolerance * np.abs(ref[name]).max(), name


def test_thick_periodic_layer_is_the_periodic_half_space():
    """A layer h = 10 periods L thick on a rigid base samples k h >= 2 pi h/L = 63: it is the
    half-space to exp(-126), so its periodic kernels are the exact periodic half-space kernels of its
    material (viscontact.physics.periodic, Ewald) plus the uniform modes h/M and h/G. Measured (n = 32):
    within 4e-15 of the largest value, every component; tolerance 1e-12. (The former split smoothed
    the half-space to depth 2h, twenty periods, and summed its near part over 3 periodic images:
    1.2e-3 (zz, xx) and 4.6e-2 (xz, zx). At h = L the layer itself differs from the half-space by
    exp(-4 pi) times a polynomial in k h: test_periodic_spectra_are_the_alias_sum_of_the_compliance.)"""
    grid = Grid(32, 1e-3, periodic=True)
    layer = Layer(10 * 2 * grid.half_width, G, NU)
    hs = periodic_influence_coefficients(grid, NU)
    spectra = periodic_spectra(grid, layer)
    assert spectra["zz"][0, 0].real == pytest.approx(layer.thickness / layer.oedometric_modulus, rel=1e-12)
    assert spectra["xx"][0, 0].real == pytest.approx(layer.thickness / G, rel=1e-12)
    for name, spec in spectra.items():
        kernel = scipy.fft.irfft2(spec, s=(grid.n, grid.n))
        expected = hs[name] / G
        assert np.abs(kernel - kernel.mean() - expected).max() <= 1e-12 * np.abs(expected).max(), name


def test_frictionless_tangential_refused():
    with pytest.raises(ParameterError, match="layer.interface"):
        influence_coefficients(Grid(8, 1e-3), Layer(1e-4, G, NU, interface="frictionless"))
    # normal and coupling kernels exist, the periodic tangential ones too
    influence_coefficients(Grid(8, 1e-3), Layer(3e-4, G, NU, interface="frictionless"), ("zz", "xz"))
    periodic_spectra(Grid(8, 1e-3), Layer(3e-4, G, NU, interface="frictionless"), ("xx",))


@pytest.mark.parametrize("kwargs, key", [({"thickness": 0.0}, "layer.thickness"),
                                          ({"base": "soft"}, "layer.substrate"),
                                          ({"interface": "glued"}, "layer.interface"),
                                          ({"base": "elastic"}, "layer.substrate_shear_modulus"),
                                          ({"base": "elastic", "base_shear_modulus": 1e6,
                                            "base_poisson_ratio": 0.7}, "layer.substrate_poisson_ratio")])
def test_bad_layers(kwargs, key):
    base = {"thickness": 1e-4, "shear_modulus": G, "poisson_ratio": NU}
    with pytest.raises(ParameterError, match=key):
        Layer(**{**base, **kwargs})


def test_too_thin_for_the_grid():
    with pytest.raises(ParameterError, match="layer.thickness"):
        influence_coefficients(Grid(64, 1e-3), Layer(1e-7, G, NU), ("zz",))


@pytest.mark.parametrize("interface", ["bonded", "frictionless"])
@pytest.mark.parametrize("key", ["zz", "ze", "ez", "ee", "pp"])
def test_modulus_poles_reproduce_the_compliance(interface, key):
    """A(k; G) = alpha0/G + sum_j alpha_j/(G + shift_j) at G values not used to build it; shifts > 0.
    k h from 1e-2 to 100, relative 1e-8. (At k h = 1e-3 both this and the direct solve lose digits to
    the near-degenerate layer basis: they differ by up to 5e-6 there.)"""
    from dataclasses import replace

    from viscontact.bodies.layer import modulus_poles

    layer = Layer(1e-3, G, NU, "elastic", interface, 2 * G, 0.2)
    k = np.logspace(1, 5, 9)
    poles = modulus_poles(layer, k, key)
    assert np.all(poles.shift > 0)
    for g in (0.1 * G, 0.77 * G, 5 * G):
        lay = replace(layer, shear_modulus=g)
        ref = anti_plane_compliance(lay, k) if key == "pp" else in_plane_compliance(lay, k)[key]
        ref = ref.imag if key in ("ze", "ez") else ref.real
        rebuilt = poles.alpha0 / g + np.sum(poles.alpha / (g + poles.shift), axis=-1)
        np.testing.assert_allclose(rebuilt, ref, rtol=1e-8)


def test_viscoelastic_modes_on_an_elastic_substrate():
    """Per-q creep modes: t = 0 is the layer with G(0), t -> inf with G(inf), and the Carson transform
    at s is the elastic compliance with G~(s) (correspondence principle), every component."""
    from dataclasses import replace

    from viscontact.bodies.layer import viscoelastic_periodic_modes
    from viscontact.physics.materials import Material

    shear = Material.prony(1e5, [1e6, 4e5], [1e-3, 3e-2], NU)
    grid = Grid(12, 1e-3)
    layer = Layer(2e-4, G, NU, "elastic", "bonded", 3e5, 0.4)
    comps = ("zz", "xx", "xz", "zx")
    modes = viscoelastic_periodic_modes(grid, layer, shear, comps)
    assert modes["zz"].amplitudes.shape[0] == 2 * 3  # M (J) + 2 M (two poles per q)

    def elastic(g: float) -> dict[str, np.ndarray]:
        spec = periodic_spectra_plain(grid, replace(layer, shear_modulus=g), comps)
        return spec

    for name in comps:
        m = modes[name]
        t0 = elastic(shear.shear_modulus_instantaneous)[name]
        tinf = elastic(shear.shear_modulus_long_term)[name]
        scale = np.abs(tinf).max()
        np.testing.assert_allclose(m.instantaneous, t0, atol=1e-9 * scale, err_msg=name)
        np.testing.assert_allclose(m.instantaneous + m.amplitudes.sum(axis=0), tinf, atol=1e-9 * scale, err_msg=name)
        for s in (3.0, 300.0):
            g_s = shear.g_inf + sum(gi * s / (s + 1 / ti) for gi, ti in zip(shear.g, shear.tau))
            carson = m.instantaneous + np.sum(m.amplitudes / (1 + s * m.retardation_times), axis=0)
            np.testing.assert_allclose(carson, elastic(g_s)[name], atol=1e-9 * scale, err_msg=name)


def periodic_spectra_plain(grid: Grid, layer: Layer, components) -> dict[str, np.ndarray]:
    """M(q) times the cell footprint on the rfft2 wavevectors (q = 0 left at 0)."""
    n, dx = grid.n, grid.spacing
    qy = 2 * np.pi * scipy.fft.fftfreq(n, dx)[:, None]
    qx = 2 * np.pi * scipy.fft.rfftfreq(n, dx)[None, :]
    qx, qy = np.broadcast_arrays(qx, qy)
    nonzero = (qx != 0) | (qy != 0)
    m = fourier_compliance(layer, qx[nonzero], qy[nonzero], components)
    foot = (np.sinc(qx * dx / (2 * np.pi)) * np.sinc(qy * dx / (2 * np.pi)))[nonzero]
    out = {}
    for name in components:
        full = np.zeros(qx.shape, dtype=complex)
        full[nonzero] = m[name] * foot
        out[name] = full
    return out


def test_rigid_base_terms_factor_the_creep_compliance():
    """Unit-modulus kernels do not depend on the G the layer was given; the response is J(t)."""
    from dataclasses import replace

    from viscontact.bodies.layer import rigid_base_terms
    from viscontact.physics.materials import Material

    shear = Material.zener(2e6, 2e5, 0.01, NU)
    grid = Grid(8, 1e-3)
    layer = Layer(2e-4, G, NU)
    terms = rigid_base_terms(grid, layer, shear, ("zz", "xz"))
    other = rigid_base_terms(grid, replace(layer, shear_modulus=7 * G), shear, ("zz", "xz"))
    for a, b in zip(terms, other):
        np.testing.assert_allclose(a.kernel, b.kernel, rtol=1e-9, atol=1e-12 * np.abs(a.kernel).max())
        np.testing.assert_allclose(a.response.retardation_times, shear.creep.retardation_times, rtol=1e-10)
    with pytest.raises(ParameterError, match="layer.substrate"):
        rigid_base_terms(grid, Layer(2e-4, G, NU, "elastic", "bonded", G, NU), shear)


@pytest.mark.parametrize("periodic", [False, True])
def test_elastic_base_terms_follow_the_correspondence_principle(periodic):
    """A viscoelastic layer on an elastic substrate (fixed-time terms, layers.elastic_base_terms):
    the Carson transform of the summed response, sum_t K_t s phi_t^(s), is the elastic layer's kernel
    at G~(s) (built independently, layers.unit_kernels), every component, at s = 0 (t -> inf),
    s -> inf (t = 0) and between (times of the material). The shift interpolation is within 1e-4
    (shift_nodes). Measured (of the kernel's largest value): periodic at most 1.3e-5, DC-FFT zz
    5.8e-6; the DC-FFT tangential and coupling kernels 2e-4 at G(0) = 5 G_s, where the elastic
    layer's own DC-FFT kernels (the reference) change by 3e-3 between a remainder box of 4 and 8
    domain widths: tolerance 5e-4 there, 2e-5 elsewhere."""
    from dataclasses import replace

    from viscontact.numerics.exponentials import carson_transform
    from viscontact.bodies.layer import elastic_base_terms, shift_nodes, unit_kernels
    from viscontact.physics.materials import Material

    shear = Material.prony(1e5, [1e6, 4e5], [1e-3, 3e-2], NU)
    grid = Grid(12, 1e-3, periodic)
    layer = Layer(2e-4, G, NU, "elastic", "bonded", 3e5, 0.4)
    comps = ("zz", "xx", "xz", "zx")
    terms = elastic_base_terms(grid, layer, shear, comps)
    nodes = shift_nodes(shear)
    assert nodes.error <= 1e-4
    assert len(terms) == len(comps) * nodes.nodes.size   # u = 1 merged into the rigid-base term
    for s in (0.0, 3.0, 300.0, np.inf):
        g_s = shear.g_inf + sum(gi * (1.0 if np.isinf(s) else s / (s + 1 / ti)) for gi, ti in zip(shear.g, shear.tau))
        ref = unit_kernels(grid, replace(layer, shear_modulus=g_s), comps)
        for name in comps:
            ours = sum(t.kernel * (t.response.instantaneous if np.isinf(s) else float(carson_transform(t.response, s)))
                       for t in terms if t.name.split(":")[0] == name)
            expected = ref[name] / g_s
            tolerance = 2e-5 if periodic or name == "zz" else 5e-4
            assert np.abs(ours - expected).max() <= tolerance * np.abs(expected).max(), (s, name)


def test_elastic_base_terms_of_a_thick_periodic_layer_are_the_half_space():
    """A viscoelastic layer 10 periods thick on an elastic substrate (layers.elastic_base_terms,
    periodic grid): the substrate and the shift nodes are invisible at k h >= 63 (the nodes' spectra
    vanish beyond k h = 18), so the Carson transform of the summed response is the periodic
    half-space kernel of the layer material at G~(s) (viscontact.physics.periodic), zero mean (the rigid-base
    term's h/M cancelled by the u = 1 node). Measured (n = 16): within 2e-15 of the largest value;
    tolerance 1e-12 (the former periodic kernels: 2.5e-3 (zz, xx), 8.7e-2 (xz, zx))."""
    from viscontact.numerics.exponentials import carson_transform
    from viscontact.bodies.layer import elastic_base_terms
    from viscontact.physics.materials import Material

    shear = Material.prony(1e5, [1e6, 4e5], [1e-3, 3e-2], NU)
    grid = Grid(16, 1e-3, True)
    layer = Layer(10 * 2 * grid.half_width, G, NU, "elastic", "bonded", 3e5, 0.4)
    comps = ("zz", "xx", "xz", "zx")
    terms = elastic_base_terms(grid, layer, shear, comps)
    hs = periodic_influence_coefficients(grid, NU, comps)
    for s in (0.0, 3.0, np.inf):
        g_s = shear.g_inf + sum(gi * (1.0 if np.isinf(s) else s / (s + 1 / ti)) for gi, ti in zip(shear.g, shear.tau))
        for name in comps:
            ours = sum(t.kernel * (t.response.instantaneous if np.isinf(s) else float(carson_transform(t.response, s)))
                       for t in terms if t.name.split(":")[0] == name)
            assert np.abs(ours - hs[name] / g_s).max() <= 1e-12 * np.abs(hs[name] / g_s).max(), (s, name)
