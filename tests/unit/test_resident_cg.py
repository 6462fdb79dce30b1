"""The constrained CG with device-resident scalars (viscontact.numerics.resident_cg) against the host
version and the contact conditions, and its reads of the device on the emulated device.

Truth: the Hertz contact (load and displacement control) and Cattaneo-Mindlin partial slip solved by
the host CG (constrained_cg, itself tested against the analytic solutions in tests/validation) to
1e-12, the Karush-Kuhn-Tucker conditions of the bound-constrained problem, and the count of host
reads of device values (the emulation counts every float/int/bool/tolist of a device array).
"""
from __future__ import annotations

import numpy as np
import pytest

import emulated_device
from viscontact.errors import ConvergenceError
from viscontact.numerics.constrained import constrained_cg
from viscontact.numerics.convolution import Convolver, FourierPreconditioner
from viscontact.numerics.grid import Grid
from viscontact.numerics.resident_cg import resident_cg
from viscontact.physics.kernels import influence_coefficients

G, NU, R = 1e6, 0.3, 0.01        # Pa, -, m
E_STAR = 2 * G / (1 - NU)
TIGHT = 1e-12


def _setup(n: int = 48, device: bool = False):
    """Grid, convolver, K (a factory: by kernel name, single or double), the Fourier preconditioners
    and the sphere's gap [m], on the host or the emulated device."""
    to_device = emulated_device.xp.asarray if device else (lambda a: a)
    grid = Grid(n, 0.4e-3)
    x, y = grid.mesh()
    kernels = influence_coefficients(grid, NU, ("zz", "xx"))
    conv = Convolver.from_kernels(n, {k: to_device(v) for k, v in kernels.items()},
                                  **({"xp": emulated_device.xp, "fft": emulated_device.fft} if device else {}))
    j = 1.0 / G

    def product(name, single=False):
        def apply(field):
            out = conv.apply(name, field, single=single)
            out *= j
            return out
        return apply

    precond = {k: FourierPreconditioner.for_kernel(kernels[k], j) for k in kernels}  # built on the host
    if device:
        precond = {k: FourierPreconditioner(to_device(p.inverse_symbol), p.workers, conv.fft) for k, p in precond.items()}
    gap = to_device((x**2 + y**2) / (2 * R))
    return grid, conv, product, precond, gap


@pytest.mark.parametrize("single", [False, True])
@pytest.mark.parametrize("check_every", [1, 4])
def test_hertz_under_load_and_approach_is_the_host_solution(single, check_every):
    grid, _, product, precond, gap = _setup()
    load = 0.02  # N: a / dx = 7
    host = constrained_cg(product("zz"), -gap, np.zeros_like(gap), 0.0, np.inf, total=load,
                          cell_area=grid.cell_area, tolerance=TIGHT, preconditioner=precond["zz"])
    options = {"preconditioner": precond["zz"].single() if single else precond["zz"],
               "apply_k_increment": product("zz", True) if single else None}
    ours = resident_cg(product("zz"), -gap, np.zeros_like(gap), 0.0, np.inf, total=load, cell_area=grid.cell_area,
                       tolerance=TIGHT, check_every=check_every, **options)
    scale = np.abs(host.x).max()
    assert np.abs(ours.x - host.x).max() <= 1e-9 * scale
    assert ours.x.sum() * grid.cell_area == pytest.approx(load, rel=1e-13)
    assert ours.multiplier == pytest.approx(host.multiplier, rel=1e-9)  # the approach
    assert ours.iterations % check_every == 0 or check_every == 1
    # KKT: no penetration outside, the gap closed inside
    contact = ours.x > 0
    assert ours.gradient[~contact].min() >= -1e-9 * gap.max()
    assert np.abs(ours.gradient[contact]).max() <= 1e-9 * gap.max()
    # displacement control at that approach (the multiplier: K p + gap = delta on the contact): the same pressure
    by_approach = resident_cg(product("zz"), host.multiplier - gap, np.zeros_like(gap), 0.0, np.inf, tolerance=TIGHT,
                              check_every=check_every, **options)
    assert np.abs(by_approach.x - host.x).max() <= 1e-8 * scale


def test_partial_slip_with_array_bounds_is_the_host_solution():
    """Cattaneo-Mindlin: q_x bounded by -/+ mu p of a Hertz pressure, a rigid shift of half the gross-slip
    one; the stick zone and the shear of the host solve."""
    grid, _, product, precond, _ = _setup()
    x, y = grid.mesh()
    a, mu = 0.2e-3, 0.3
    p = 1e5 * np.sqrt(np.clip(1 - (x**2 + y**2) / a**2, 0, None))
    b = np.where(p > 0, 2e-6, 0.0)
    host = constrained_cg(product("xx"), b, np.zeros_like(p), -mu * p, mu * p, tolerance=TIGHT,
                          preconditioner=precond["xx"])
    ours = resident_cg(product("xx"), b, np.zeros_like(p), -mu * p, mu * p, tolerance=TIGHT,
                       preconditioner=precond["xx"], check_every=4)
    assert np.abs(ours.x - host.x).max() <= 1e-9 * np.abs(host.x).max()
    stick = np.abs(host.x) < mu * p * (1 - 1e-9)
    assert 0 < stick.sum() < (p > 0).sum()  # partial slip
    assert np.abs(ours.gradient[stick & (p > 0)]).max() <= 1e-9 * b.max()


def test_a_solve_that_cannot_converge_says_so_and_nothing_loaded_is_zero():
    grid, _, product, precond, gap = _setup(24)
    with pytest.raises(ConvergenceError):
        resident_cg(product("zz"), -gap, np.zeros_like(gap), 0.0, np.inf, total=0.01, cell_area=grid.cell_area,
                    tolerance=1e-15, max_iterations=6, preconditioner=precond["zz"], check_every=4)
    nothing = resident_cg(product("zz"), -gap, np.ones_like(gap), 0.0, np.inf, total=0.0, cell_area=grid.cell_area)
    assert not nothing.x.any() and nothing.iterations == 0
    with pytest.raises(ValueError):
        resident_cg(product("zz"), -gap, np.zeros_like(gap), 0.0, np.inf, check_every=0)


def test_on_the_device_it_reads_three_numbers_every_check_and_the_host_cg_reads_every_iteration():
    """The point of the module: the host CG reads device values about a dozen times an iteration (its
    decisions), the resident one once every ``check_every`` iterations (plus a few reads to set up
    and to return)."""
    emu = emulated_device
    grid, _, product, precond, gap = _setup(48, device=True)
    b = -gap
    options = dict(total=0.02, cell_area=grid.cell_area, tolerance=TIGHT, preconditioner=precond["zz"])
    with emu.scalar_reads() as host_reads:
        host = constrained_cg(product("zz"), b, emu.xp.zeros(gap.shape), 0.0, np.inf, **options)
    with emu.scalar_reads() as ours_reads:
        ours = resident_cg(product("zz"), b, emu.xp.zeros(gap.shape), 0.0, np.inf, check_every=4, **options)
    assert len(host_reads) >= 8 * host.iterations
    checks = ours.iterations // 4
    assert ours_reads.count("tolist") == checks
    assert len(ours_reads) <= checks + 6  # the set-up (the load, the scale of b) and the result's sums
    np.testing.assert_allclose(emu.to_host(ours.x), emu.to_host(host.x), rtol=0,
                               atol=1e-9 * float(np.abs(host.x).max()))
