"""The array seam (viscontact.numerics.arrays): the transient on a device array library.

Every transient mode and body (half-space on DC-FFT and periodic grids, layers, nu(t)) runs on an
emulated device (tests/emulated_device.py: numpy behind CuPy's rules, so a host array leaking into
the device path raises) and must equal the numpy run bit for bit, its state held in device arrays.
Where CuPy finds a CUDA device, the same runs go on the GPU (equal to round-off: cuFFT's arithmetic
is not pocketfft's); VISCONTACT_TEST_DEVICE=gpu runs them there alone, each skipped with its reason
where there is none (benchmarks/device/check.sh), VISCONTACT_TEST_DEVICE=emulated on the emulation alone.
"""
from __future__ import annotations

import dataclasses
import os
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pytest
import scipy.fft

import emulated_device
from emulated_device import DeviceArray, HostArrayError
from viscontact.numerics.arrays import CPU, DEVICE_CHECK_EVERY, cupy_backend
from viscontact.numerics.constrained import constrained_cg
from viscontact.numerics.convolution import Convolver, FourierPreconditioner
from viscontact.errors import ParameterError
from viscontact.numerics.grid import Grid
from viscontact.physics.kernels import influence_coefficients
from viscontact.io.case import load_case
from viscontact.io.checkpoint import load_checkpoint, save_checkpoint
from viscontact.problem.problem import LayerSettings, SolverSettings, TangentialLoading, TimeStepping
from viscontact.problem.shapes import Cylinder
from viscontact.io.shipped import shipped_case
from viscontact.bodies.compliance import compliance_of
from viscontact.solvers import contact_laws
from viscontact.solvers.transient import steps
from vc_testing import SEED_A0, SEED_RADIUS, SEED_TAU, seed_material, sphere_problem


#: which backends the device tests run on: unset, the emulation and CuPy where it finds a CUDA device;
#: "gpu": CuPy alone (each test skipped with the reason where it finds none: benchmarks/device/check.sh);
#: "emulated": the emulation alone
DEVICE_VARIABLE = "VISCONTACT_TEST_DEVICE"


def _backends() -> list:
    chosen = os.environ.get(DEVICE_VARIABLE, "")
    if chosen not in ("", "gpu", "emulated"):
        raise ValueError(f"{DEVICE_VARIABLE} must be 'gpu' or 'emulated' (or unset), got {chosen!r}")
    out = [] if chosen == "gpu" else [pytest.param(emulated_device.BACKEND, id="emulated")]
    if chosen == "emulated":
        return out
    try:
        out.append(pytest.param(cupy_backend(), id="cupy"))
    except ImportError as exc:
        if chosen == "gpu":
            out.append(pytest.param(None, id="cupy", marks=pytest.mark.skip(reason=f"no CuPy GPU backend: {exc}")))
    return out


BACKENDS = _backends()
#: the emulation with the CG's scalars kept on the device (a GPU's :attr:`ArrayBackend.check_every`):
#: not numpy's sequence of iterates, so compared as a GPU is, both solved to round-off
RESIDENT = pytest.param(dataclasses.replace(emulated_device.BACKEND, name="emulated-resident",
                                            check_every=DEVICE_CHECK_EVERY), id="emulated-resident")


def _exact(backend) -> bool:
    """Whether the backend does numpy's arithmetic (the emulation): results equal bit for bit."""
    return backend is emulated_device.BACKEND


#: solver tolerances of a comparison on a device whose arithmetic is not numpy's (a GPU): both runs
#: solved to round-off. At the default 1e-8 (the relative change of p in a CG iteration) two runs
#: whose transforms round differently stop at different iterates, up to ~4e-8 of the peak pressure
#: apart (measured on an H200 against pocketfft, and on the CPU with transforms perturbed by 2 ulp:
#: tests/unit/test_array_seam.py::test_round_off_alone_moves_a_tightly_solved_run_by_round_off);
#: solved to 1e-13 they agree to ~1e-13.
ROUND_OFF_SOLVE = 1e-13
#: agreement of two runs solved to :data:`ROUND_OFF_SOLVE` whose transforms round differently,
#: relative to each field's (or scalar's) largest magnitude over the run: 1000 times what 2-ulp
#: perturbed transforms give, 100 times tighter than the default tolerance's spread
ROUND_OFF_AGREEMENT = 1e-10
#: record scalars that are lengths [m]: their scale is at least the grid spacing (a centroid offset
#: of a symmetric contact is round-off around zero)
LENGTHS = {"delta_z", "delta_x", "sliding_distance", "contact_shift", "frame_offset"}
#: record fields that count iterations: another sequence of iterates (a GPU's rounding, the resident
#: CG's checks every few iterations) may take more or fewer to the same tolerance
ITERATION_COUNTS = {"iterations", "coupling_iterations"}


def _solved_to_round_off(problem, backend):
    """``problem`` as the comparison on ``backend`` solves it: unchanged on the emulation (the same
    arithmetic, bit for bit), to :data:`ROUND_OFF_SOLVE` elsewhere."""
    if _exact(backend):
        return problem
    solver = dataclasses.replace(problem.solver, tolerance=ROUND_OFF_SOLVE, coupling_tolerance=ROUND_OFF_SOLVE)
    return dataclasses.replace(problem, solver=solver)


def _host_twin(backend):
    """The CPU backend with ``backend``'s transform lengths (its support windows): the numpy run that
    ``backend``'s run must equal."""
    return dataclasses.replace(CPU, fast_length=backend.fast_length)


def _assert_same(ours, reference, backend, what: str) -> None:
    if _exact(backend):
        np.testing.assert_array_equal(ours, reference, err_msg=what)
    else:
        np.testing.assert_allclose(ours, reference, rtol=0,
                                   atol=ROUND_OFF_AGREEMENT * np.max(np.abs(reference)), err_msg=what)


def _assert_same_records(ours: list, reference: list, backend, spacing: float) -> None:
    """Every record of two transient runs equal: fields by :func:`_assert_same`, scalars bit for bit on
    the emulation, else to :data:`ROUND_OFF_AGREEMENT` of the scalar's largest magnitude over the run
    (:data:`LENGTHS`: at least the grid spacing); the iteration counts may differ off the emulation."""
    assert len(ours) == len(reference)
    scales: dict[str, float] = {}
    for record in reference:
        for f in dataclasses.fields(record):
            value = getattr(record, f.name)
            if isinstance(value, float):
                scales[f.name] = max(scales.get(f.name, spacing if f.name in LENGTHS else 0.0), abs(value))
    for record, expected in zip(ours, reference):
        for f in dataclasses.fields(record):
            value, want = getattr(record, f.name), getattr(expected, f.name)
            if isinstance(want, np.ndarray):
                assert isinstance(value, np.ndarray), f.name  # records are on the host
                _assert_same(value, want, backend, f"{f.name} at step {record.step}")
            elif isinstance(want, float) and want != want:  # NaN (rolling's creepage at t = 0 under a held force)
                assert value != value, f"{f.name} at step {record.step}"
            elif isinstance(want, float) and not _exact(backend):
                assert abs(value - want) <= ROUND_OFF_AGREEMENT * scales[f.name], f"{f.name} at step {record.step}"
            elif f.name not in ITERATION_COUNTS or _exact(backend):
                assert value == want, f"{f.name} at step {record.step}"


# --- the emulation itself refuses what a device library refuses ------------------------------------

def test_the_emulated_device_refuses_host_arrays_and_cpu_only_keywords():
    dev = emulated_device.xp.zeros((4, 4))
    with pytest.raises(HostArrayError):
        np.asarray(dev)
    with pytest.raises(HostArrayError):
        dev + np.ones((4, 4))
    with pytest.raises(HostArrayError):  # 0-d arrays too (scalars mix: np.float64(1.0) below)
        dev + np.array(1.0)
    with pytest.raises(HostArrayError):
        dev[np.zeros((4, 4), dtype=bool)] = 1.0
    with pytest.raises(HostArrayError):
        emulated_device.fft.rfft2(np.ones((4, 4)))
    with pytest.raises(TypeError, match="workers"):
        emulated_device.fft.rfft2(dev, workers=1)
    with pytest.raises(TypeError, match="where"):
        np.sum(dev, where=dev > 0)
    with pytest.raises(AttributeError):
        dev.flat  # noqa: B018
    # what is allowed: numpy's functions dispatched, scalars, explicit transfers
    out = np.maximum(dev + np.float64(1.0), 0.5)
    assert isinstance(out, DeviceArray) and float(out.sum()) == 16.0
    assert isinstance(np.zeros_like(dev), DeviceArray)
    assert isinstance(emulated_device.to_host(out), np.ndarray)
    with pytest.raises(HostArrayError):
        emulated_device.to_host(np.ones(3))


def test_the_gpu_selection_skips_each_device_test_with_its_reason_where_cupy_finds_no_device(tmp_path):
    """VISCONTACT_TEST_DEVICE=gpu (benchmarks/device/check.sh) without a CUDA device: the device tests
    are skipped, saying why, and the run succeeds; the emulated ones are left out."""
    try:
        cupy_backend()
        pytest.skip("CuPy finds a CUDA device here")
    except ImportError:
        pass
    out = subprocess.run([sys.executable, "-m", "pytest", "-q", "-rs", "-p", "no:cacheprovider", "-p", "no:xdist",
                          __file__, "-k", "dcfft or refuses_a_device"],
                         env={**os.environ, DEVICE_VARIABLE: "gpu"}, capture_output=True, text=True, timeout=120,
                         cwd=tmp_path)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "2 skipped" in out.stdout and "no CuPy GPU backend" in out.stdout and "emulated" not in out.stdout


@pytest.mark.parametrize("dry_run", [False, True])
def test_cupy_without_a_cuda_device_is_one_line_and_exit_2_before_anything_is_written(tmp_path, dry_run):
    """solver.device = "gpu" where CuPy is installed but finds no device (a stand-in CuPy whose runtime
    raises as CUDA's does): ``viscontact run`` and its ``--dry-run`` stop with one line naming the key,
    status 2, and write nothing."""
    fake = tmp_path / "fake"
    (fake / "cupyx" / "scipy").mkdir(parents=True)
    (fake / "cupy").mkdir()
    (fake / "cupy" / "__init__.py").write_text(
        "class _Runtime:\n"
        "    @staticmethod\n"
        "    def getDeviceCount():\n"
        "        raise RuntimeError('cudaErrorNoDevice: no CUDA-capable device is detected')\n"
        "class cuda:\n"
        "    runtime = _Runtime\n")
    for package in ("cupyx", "cupyx/scipy"):
        (fake / package / "__init__.py").write_text("")
    (fake / "cupyx" / "scipy" / "fft.py").write_text("")
    src = Path(__file__).resolve().parents[2] / "src"
    out_file = tmp_path / "r.nc"
    out = subprocess.run([sys.executable, "-m", "viscontact", "run", str(shipped_case("creep_indentation")),
                          "--out", str(out_file), "--set", 'solver.device="gpu"', "--set", "grid.n=512",
                          *(["--dry-run"] if dry_run else [])],
                         env={**os.environ, "PYTHONPATH": os.pathsep.join(  # the stand-in first, the rest kept
                             [str(fake), str(src), *filter(None, [os.environ.get("PYTHONPATH")])])},
                         capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 2, out.stdout + out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("viscontact: error: solver.device: 'gpu' needs CuPy and a CUDA device")
    assert "cudaErrorNoDevice" in lines[0]
    assert not list(tmp_path.glob("r.nc*"))


def test_the_cpu_backend_moves_nothing():
    field = np.ones((3, 3))
    assert CPU.to_device(field) is field and CPU.to_host(field) is field and CPU.is_cpu


# --- round-off: what a device whose transforms round differently may differ by ----------------------

class _RoundedFFT(types.ModuleType):
    """``scipy.fft`` whose every transform's output is perturbed by up to 2 units in the last place of
    its precision (seeded): another FFT library's round-off (cuFFT's), on the CPU."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.rng = np.random.default_rng(0)

    def __getattr__(self, name: str):
        attr = getattr(scipy.fft, name)
        if name == "next_fast_len" or not callable(attr):
            return attr

        def transform(*args, **kwargs):
            out = attr(*args, **kwargs)
            ulp = np.finfo(out.real.dtype).eps
            return (out * (1 + ulp * self.rng.uniform(-2, 2, out.shape))).astype(out.dtype)
        return transform


@pytest.mark.parametrize("mode", ["creep", "partial_slip"])
def test_round_off_alone_moves_a_tightly_solved_run_by_round_off(mode):
    """Why the comparisons off the emulation solve to :data:`ROUND_OFF_SOLVE`: with transforms rounded
    differently, runs at the default tolerance differ by more than :data:`ROUND_OFF_AGREEMENT` (they
    stop at different iterates: ~3e-8 of the peak for creep), runs solved to round-off agree within it."""
    rounded = dataclasses.replace(CPU, name="rounded", fft=_RoundedFFT("rounded_fft"))

    def both(problem):
        reference = [r for _, r in steps(problem)]
        return [r for _, r in steps(problem, compliance=compliance_of(problem, backend=rounded))], reference

    problem = _transient(mode)
    with pytest.raises(AssertionError):
        _assert_same_records(*both(problem), rounded, problem.grid.spacing)
    _assert_same_records(*both(_solved_to_round_off(problem, rounded)), rounded, problem.grid.spacing)


# --- the numerics on the device --------------------------------------------------------------------

@pytest.mark.parametrize("backend", BACKENDS)
def test_dcfft_preconditioned_cg_on_the_device_equals_numpy(backend):
    """Hertz contact (elastic, load control), mixed precision: convolver, preconditioner and CG."""
    grid = Grid(32, 1.5e-3)
    x, y = grid.mesh()
    gap = (x**2 + y**2) / (2 * 0.01)
    ics = influence_coefficients(grid, 0.3, ("zz",))

    def solve(xp, fft, to_device, to_host):
        kernel = to_device(ics["zz"])
        conv = Convolver.from_kernels(grid.n, {"zz": kernel}, xp=xp, fft=fft)
        precond = FourierPreconditioner.for_kernel(kernel, 1.0 / 1e6, fft=fft)
        sol = constrained_cg(lambda p: conv.apply("zz", p) / 1e6, -to_device(gap), xp.zeros((grid.n, grid.n)), 0.0,
                             np.inf, total=0.15, cell_area=grid.cell_area, tolerance=ROUND_OFF_SOLVE,
                             preconditioner=precond.single(), apply_k_sparse=lambda p: conv.apply_sparse("zz", p, 1e-6),
                             apply_k_increment=lambda p: conv.apply("zz", p, single=True) / 1e6)
        return sol, to_host(sol.x), to_host(sol.gradient)

    ref, p_ref, g_ref = solve(np, scipy.fft, np.asarray, np.asarray)
    sol, p, g = solve(backend.xp, backend.fft, backend.to_device, backend.to_host)
    assert not isinstance(sol.x, np.ndarray)
    _assert_same(p, p_ref, backend, "pressure")
    _assert_same(g, g_ref, backend, "gap")
    assert sol.iterations == ref.iterations if _exact(backend) else abs(sol.iterations - ref.iterations) <= 2
    assert sol.multiplier == ref.multiplier if _exact(backend) else \
        sol.multiplier == pytest.approx(ref.multiplier, rel=ROUND_OFF_AGREEMENT)


def _line(problem, load: float = 30.0):
    """``problem`` as a line contact (grid.dimension = 1, 4n cells on the same line; the cylinder's gap,
    ``load`` [N/m] under load control: a half-width of 0.45 a0 at G(0), 1.4 a0 at G(inf))."""
    grid = Grid(4 * problem.grid.n, problem.grid.half_width, dimension=1)
    x, _ = grid.mesh()
    normal = problem.normal
    if normal.control == "load":
        normal = dataclasses.replace(normal, history=type(normal.history).constant(load))
    dt = problem.time.dt / 4 if problem.tangential.frame_moves else problem.time.dt
    return dataclasses.replace(problem, grid=grid, gap=x**2 / (2 * SEED_RADIUS), normal=normal,
                               time=dataclasses.replace(problem.time, dt=dt), radius=None,
                               shape=Cylinder(SEED_RADIUS))


def _transient(mode: str):
    """A short run of every transient mode on the seed's material (n = 32)."""
    if mode.startswith("line_"):  # the same on a line contact
        return _line(_transient(mode[len("line_"):]))
    if mode.endswith("_incremental"):  # the incremental slip: s_x carried in the state
        base = _transient(mode[:-len("_incremental")])
        return dataclasses.replace(base, tangential=dataclasses.replace(base.tangential, slip="incremental"))
    if mode.startswith("sub_cell_"):  # two steps per cell: the indenter moves within a cell (frame_gap)
        base = _transient({"sub_cell_periodic": "rough_periodic"}.get(mode, "frictionless_sliding"))
        tangential = dataclasses.replace(base.tangential, steps_per_cell=2)
        time = dataclasses.replace(base.time, dt=base.time.dt / 2)
        if mode == "sub_cell_surface":  # a gap given as a surface on a DC-FFT grid: interpolated
            x, y = base.grid.mesh()
            base = dataclasses.replace(base, gap=(x**2 + y**2) / (2 * SEED_RADIUS), radius=None)
        return dataclasses.replace(base, tangential=tangential, time=time)
    if mode.startswith("adhesive"):
        return _adhesive_transient(mode)
    material = seed_material()
    if mode == "creep":
        return sphere_problem(material, 32, 2.5 * SEED_A0, t_end=10 * SEED_TAU / 20)
    if mode == "displacement":
        return sphere_problem(material, 32, 2.5 * SEED_A0, control="displacement", value=20e-6,
                              t_end=6 * SEED_TAU / 20, scheme="linear")
    if mode == "frictionless_sliding":  # frame shifts, the wake
        return sphere_problem(material, 32, 2.5 * SEED_A0, mode="frictionless_sliding", speed=0.05,
                              t_end=12 * 2.5 * SEED_A0 / 16 / 0.05)
    if mode == "gross_sliding":  # with the normal-tangential coupling
        return sphere_problem(material, 32, 2.5 * SEED_A0, mode="gross_sliding", friction=0.5, speed=0.05,
                              t_end=6 * 2.5 * SEED_A0 / 16 / 0.05)
    if mode == "strong_coupling":  # mu_f (1 - 2 nu) too large for the fixed point: the direct solve (GMRES)
        return sphere_problem(seed_material(poisson_ratio=0.0), 32, 6 * SEED_A0, mode="gross_sliding", friction=2.5,
                              speed=0.1, t_end=4 * 6 * SEED_A0 / 16 / 0.1)
    if mode == "partial_slip":  # 6 steps, then gross sliding (5)
        return sphere_problem(material, 32, 2.5 * SEED_A0, mode="partial_slip", friction=0.5, rate=0.003,
                              speed=0.02, t_end=10 * 2.5 * SEED_A0 / 16 / 0.02, scheme="linear")
    if mode == "rough_periodic":  # partial slip on a periodic self-affine surface, then sliding (total slip)
        case = load_case(shipped_case("rough_periodic_sliding")).with_overrides(
            {"grid.n": 32, "tangential.displacement_rate": 0.004, "time.t_end": 10 * 1e-3 / 32 / 0.02,
             "tangential.slip": "total"})
        return case.to_problem()
    if mode == "rolling_rough":  # rolling on a rough periodic surface: the roughness carried, its gap moved each step
        base = _transient("rolling")
        grid = dataclasses.replace(base.grid, periodic=True)
        x, y = grid.mesh()
        k = 2.0 * np.pi / (2.0 * grid.half_width)
        rough = 0.05 * SEED_A0**2 / SEED_RADIUS * (np.cos(3 * k * x + 5 * k * y) + np.sin(4 * k * x - 0.7))
        return dataclasses.replace(base, grid=grid, gap=base.shape.gap(grid) + rough, surface_topography=True)
    if mode.startswith("rolling"):  # rolling with the coupling: u_x convected in the state; a held force's root find
        held = {"creepage": -3e-3} if mode == "rolling" else {"tangential_force": 0.02}
        base = sphere_problem(material, 32, 2.5 * SEED_A0, t_end=8 * 2.5 * SEED_A0 / 16 / 0.05, dt=1.0)
        tangential = TangentialLoading("rolling", 0.5, rolling_speed=0.05, **held)
        return dataclasses.replace(base, tangential=tangential,
                                   time=TimeStepping(base.time.t_end, 2.5 * SEED_A0 / 16 / 0.05, "linear"))
    creep = _transient("creep")
    if mode == "layer":
        return dataclasses.replace(creep, layer=LayerSettings(0.3e-3))
    if mode == "layer_on_elastic":  # a kernel and a history per shift node
        return dataclasses.replace(creep, layer=LayerSettings(0.3e-3, substrate="elastic", substrate_shear_modulus=10e6))
    # nu(t): two histories per traction component, sliding with the coupling
    sliding = _transient("gross_sliding")
    return dataclasses.replace(sliding, material=seed_material(poisson_ratio=0.25), bulk_modulus=5e6)


def _adhesive_transient(mode: str):
    """The shipped adhesive case (n = 32): its approach-dwell-retraction (displacement control, past the
    jump-off), under load control to the pull-off, gross sliding with the coupling (nu = 0.3), partial
    slip, and on a periodic grid."""
    held = {"normal.history": [[0.0, 4e-6], [1.0, 4e-6]], "tangential.sliding_speed": 2.5e-3, "time.dt": None}
    overrides = {
        "adhesive_retraction": {},
        "adhesive_load": {"normal.control": "load",
                          "normal.history": [[0.0, 0.0], [0.1, 2e-3], [0.6, 2e-3], [1.4, -5e-3]]},
        "adhesive_sliding": {**held, "tangential.mode": "gross_sliding", "tangential.friction_coefficient": 0.3,
                             "material.poisson_ratio": 0.3, "time.t_end": 0.1},
        "adhesive_partial_slip": {**held, "tangential.mode": "partial_slip", "tangential.friction_coefficient": 0.5,
                                  "tangential.displacement_rate": 1e-4, "time.t_end": 0.2},
        "adhesive_periodic": {"grid.periodic": True, "time.t_end": 1.0},
    }[mode]
    return load_case(shipped_case("adhesive_pdms_retraction")).with_overrides({"grid.n": 32, **overrides}).to_problem()


TRANSIENT_MODES = ["creep", "displacement", "frictionless_sliding", "gross_sliding", "strong_coupling", "partial_slip",
                   "partial_slip_incremental", "rough_periodic", "rough_periodic_incremental", "layer",
                   "layer_on_elastic", "bulk_modulus", "sub_cell_sphere", "sub_cell_surface", "sub_cell_periodic",
                   "rolling", "rolling_force", "rolling_rough", "line_creep", "line_gross_sliding",
                   "line_partial_slip_incremental", "adhesive_retraction", "adhesive_load", "adhesive_sliding",
                   "adhesive_partial_slip", "adhesive_periodic"]
#: the modes run with the device-resident CG: each kind of solve it takes (load and displacement
#: control, windows, periodic, partial slip's array bounds, rolling, the adhesive rounds)
RESIDENT_MODES = ["creep", "displacement", "frictionless_sliding", "partial_slip_incremental", "rough_periodic",
                  "rolling", "adhesive_retraction"]


def _with_modes(backends: list, modes: list) -> list:
    """(backend, mode) parameters of each backend parameter (its id and marks kept) and mode."""
    return [pytest.param(b.values[0], m, id=f"{m}-{b.id}", marks=b.marks) for b in backends for m in modes]


@pytest.mark.parametrize("backend, mode", _with_modes(BACKENDS, TRANSIENT_MODES) + _with_modes([RESIDENT], RESIDENT_MODES))
def test_the_transient_on_the_device_equals_numpy(backend, mode, monkeypatch):
    problem = _solved_to_round_off(_transient(mode), backend)
    reference = list(steps(problem, compliance=compliance_of(problem, backend=_host_twin(backend))))
    direct_solves = []
    solve_direct = contact_laws.NormalContact.solve_direct
    monkeypatch.setattr(contact_laws.NormalContact, "solve_direct",
                        lambda self, ctx, p: direct_solves.append(ctx.k) or solve_direct(self, ctx, p))
    ours = list(steps(problem, compliance=compliance_of(problem, backend=backend)))
    assert len(ours) == (len(reference) if mode == "adhesive_load" else problem.time.n_steps)  # (the pull-off ends it)
    _assert_same_records([r for _, r in ours], [r for _, r in reference], backend, problem.grid.spacing)
    final = ours[-1][0]
    assert not isinstance(final.pressure, np.ndarray)  # the state stayed on the device
    assert all(not isinstance(h.internal, np.ndarray) for h in final.histories.values())
    if problem.tangential.slides and not problem.grid.periodic:
        assert final.wake.strips  # the frame moved and history left it (on the host)
    assert bool(direct_solves) == (mode == "strong_coupling")  # its steps ran the direct solve
    if problem.adhesion is not None:  # the interaction zone stayed on the device, and the run pulled on the body
        assert not isinstance(final.interaction, np.ndarray) and min(r.adhesive_force for _, r in ours) < 0
    if mode == "adhesive_load":
        assert len(ours) < problem.time.n_steps  # it came off before the end of the history
    if mode.startswith(("partial_slip", "rough_periodic", "line_partial_slip")):
        assert {r.phase for _, r in ours} == {1, 2} and max(r.stick_ratio for _, r in ours) > 0.5
        carried = [state.slip_x for state, r in ours if r.phase == 1]
        if mode.endswith("_incremental"):  # s_x, a field on the device, until gross sliding
            assert carried and all(not isinstance(s_x, np.ndarray) and s_x is not None for s_x in carried)
            assert final.slip_x is None
        else:
            assert all(s_x is None for s_x in carried)


@pytest.mark.parametrize("mode", ["creep", "frictionless_sliding", "gross_sliding", "strong_coupling",
                                  "partial_slip_incremental", "rough_periodic", "sub_cell_sphere", "sub_cell_surface",
                                  "sub_cell_periodic"])
def test_a_step_after_the_first_moves_no_field_to_the_device(mode):
    """The fields a step needs from the host (kernels, spectra, the gap at every frame offset) move to
    the device before the run or in its first step; a later step copies nothing as large as a grid
    row to it (the GMRES's small least-squares solution of the direct solve apart), only the record
    back (p, q, u_z). The emulation's copies are free, a GPU's are not (an n x n field crosses the bus)."""
    problem = _transient(mode)
    n = problem.grid.n
    run = steps(problem, compliance=compliance_of(problem, backend=emulated_device.BACKEND))
    next(run)
    offsets = set()
    while True:
        with emulated_device.transfers() as moved:
            try:
                _, record = next(run)
            except StopIteration:
                break
        offsets.add(record.frame_offset)
        fields = [t for t in moved if t.direction == "to_device" and np.prod(t.shape) >= n]
        assert not fields, f"step {record.step} copied {fields} to the device"
        assert sum(t.direction == "to_host" and t.shape == (n, n) for t in moved) >= 3  # the record
    assert len(offsets) == (2 if mode.startswith("sub_cell_") else 1)  # every frame offset was met


@pytest.mark.parametrize("body", ["half_space", "gross_sliding", "rough_periodic", "layer"])
def test_the_steady_active_set_moves_no_field_to_the_device(body, monkeypatch):
    """The steady solver moves its kernels and the gap once; its active set and Krylov iterations copy
    nothing as large as a grid row to the device."""
    from viscontact import steady
    from viscontact.solvers import steady_periodic
    from viscontact.bodies import compliance
    from viscontact.numerics import active_set
    from viscontact.solvers.steady import solve_steady

    problem = _steady(body)
    monkeypatch.setattr(compliance, "array_backend", lambda device: emulated_device.BACKEND)
    solves = []
    for module in (steady, steady_periodic, active_set):  # (the adhesive rounds call it from active_set)
        def counted(apply_k, gap, _solve=module.solve_contact_active_set, **kw):
            with emulated_device.transfers() as moved:
                out = _solve(apply_k, gap, **kw)
            solves.append(moved)
            return out
        monkeypatch.setattr(module, "solve_contact_active_set", counted)
    solve_steady(problem)
    assert solves
    n = problem.grid.n
    for moved in solves:
        assert not [t for t in moved if t.direction == "to_device" and np.prod(t.shape) >= n]


@pytest.mark.parametrize("backend", BACKENDS)
def test_the_reference_hereditary_sum_refuses_a_device_in_one_line(backend):
    problem = _transient("creep")
    with pytest.raises(ParameterError, match="solver.history: 'direct' .* CPU only"):
        compliance_of(dataclasses.replace(problem, solver=SolverSettings(history="direct")), backend=backend)


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_checkpoint_of_a_device_state_resumes_bit_exact(backend, tmp_path):
    """Sliding (histories shifted, a wake on the host): saved after step 5, resumed on the device."""
    problem = _transient("frictionless_sliding")
    compliance = compliance_of(problem, backend=backend)
    run = list(steps(problem, compliance=compliance))
    save_checkpoint(tmp_path / "c.npz", problem, run[5][0], backend=backend)
    state, _ = load_checkpoint(tmp_path / "c.npz", problem, backend=backend)
    assert not isinstance(state.pressure, np.ndarray) and state.wake.strips
    assert all(isinstance(strip, np.ndarray) for strip in state.wake.strips)  # the wake stays on the host
    resumed = list(steps(problem, state=state, compliance=compliance))
    assert len(resumed) == len(run) - 6
    for (_, ours), (_, want) in zip(resumed, run[6:]):
        np.testing.assert_array_equal(ours.pressure, want.pressure)
        assert ours.mu_app == want.mu_app and ours.wake_loss == want.wake_loss


@pytest.mark.parametrize("backend", BACKENDS)
def test_a_streamed_run_stopped_and_resumed_on_the_device_equals_the_cpu_run(backend, tmp_path, monkeypatch):
    """The command's path (run_to_file: streamed records, checkpoints, a stop, --resume) with the
    device as the backend of ``solver.device``."""
    import xarray as xr

    from viscontact.running import api
    from viscontact.io import checkpoint
    from viscontact.bodies import compliance
    from viscontact.errors import RunInterrupted

    problem = dataclasses.replace(_transient("frictionless_sliding"),  # a dt the command's guards accept
                                  time=dataclasses.replace(_transient("frictionless_sliding").time, scheme="linear"))
    problem = _solved_to_round_off(problem, backend)
    monkeypatch.setattr(compliance, "array_backend", lambda device: _host_twin(backend))
    api.run_to_file(problem, tmp_path / "cpu.nc")
    monkeypatch.setattr(compliance, "array_backend", lambda device: backend)
    monkeypatch.setattr(checkpoint, "array_backend", lambda device: backend)
    done = []
    with pytest.raises(RunInterrupted):
        api.run_to_file(problem, tmp_path / "dev.nc", checkpoint_every=2,
                        progress=lambda k, total: done.append(k),
                        should_stop=lambda: "test stop" if len(done) >= 7 else None)
    with np.load(api.checkpoint_path(tmp_path / "dev.nc")) as saved:  # the state was on the device
        assert saved["state.pressure.__device__"] and saved["state.histories.z.internal.__device__"]
    api.run_to_file(problem, tmp_path / "dev.nc", resume=True)
    with xr.open_dataset(tmp_path / "cpu.nc") as cpu, xr.open_dataset(tmp_path / "dev.nc") as dev:
        assert dev.attrs["complete"] == 1 and dev.sizes == cpu.sizes and "resumed" in dev.attrs["history"]
        assert set(dev.data_vars) == set(cpu.data_vars)
        for name in cpu.data_vars:
            if name != "iterations" or _exact(backend):  # the CG iterations may differ off the emulation
                _assert_same(dev[name].values.astype(float), cpu[name].values.astype(float), backend, name)


def _steady(body: str):
    """A steady sliding problem of each body (n = 32; 128 for the coarse-grid start)."""
    sliding = dict(mode="frictionless_sliding", speed=0.8 * SEED_A0 / SEED_TAU, t_end=SEED_TAU)
    if body == "line":  # the isolated cylinder, with the coarse-grid start
        return _line(sphere_problem(seed_material(), 64, 2.5 * SEED_A0, **sliding))
    if body == "rough_periodic":
        return load_case(shipped_case("rough_periodic_sliding")).with_overrides({"grid.n": 32}).to_problem()
    if body == "coarse_start":
        return sphere_problem(seed_material(), 128, 2.5 * SEED_A0, **sliding)
    if body == "adhesive":  # gross sliding with the coupling (nu = 0.3), started from the coarse grid's
        return load_case(shipped_case("adhesive_pdms_retraction")).with_overrides({
            "grid.n": 128, "normal.history": [[0.0, 4e-6], [1.0, 4e-6]], "tangential.mode": "gross_sliding",
            "tangential.friction_coefficient": 0.3, "material.poisson_ratio": 0.3, "tangential.sliding_speed": 2.5e-3,
            "time.dt": None}).to_problem()
    if body == "gross_sliding":
        return sphere_problem(seed_material(), 32, 2.5 * SEED_A0, **{**sliding, "mode": "gross_sliding"}, friction=0.5)
    problem = sphere_problem(seed_material(), 32, 2.5 * SEED_A0, **sliding)
    if body == "layer":
        return dataclasses.replace(problem, layer=LayerSettings(0.3e-3))
    if body == "bulk_modulus":
        return dataclasses.replace(problem, material=seed_material(poisson_ratio=0.25), bulk_modulus=5e6)
    return problem


@pytest.mark.parametrize("periodic", [False, True], ids=["dc_fft", "periodic"])
@pytest.mark.parametrize("held", [{"creepage": -3e-3}, {"tangential_force": 0.02}], ids=["creepage", "force"])
@pytest.mark.parametrize("backend", BACKENDS)
def test_the_steady_rolling_state_on_the_device_equals_numpy(backend, held, periodic, monkeypatch):
    """Coupled (nu = 0.3): the steady normal and tangential problems alternate on the device (on a
    periodic grid with the periodic steady operators and normal solver)."""
    from viscontact.bodies import compliance
    from viscontact.numerics.grid import Grid
    from viscontact.solvers.steady_rolling import solve_steady_rolling

    base = sphere_problem(seed_material(), 32, 2.5 * SEED_A0, t_end=SEED_TAU, dt=SEED_TAU / 20)
    if periodic:
        base = dataclasses.replace(base, grid=Grid(32, 2.5 * SEED_A0, periodic=True))
    problem = _solved_to_round_off(dataclasses.replace(base, tangential=TangentialLoading(
        "rolling", 0.5, rolling_speed=0.8 * SEED_A0 / SEED_TAU, **held)), backend)
    reference = solve_steady_rolling(problem)
    monkeypatch.setattr(compliance, "array_backend", lambda device: backend)  # solver.device -> the device
    ours = solve_steady_rolling(problem)
    for f in dataclasses.fields(ours):
        value, want = getattr(ours, f.name), getattr(reference, f.name)
        if isinstance(want, np.ndarray):
            assert isinstance(value, np.ndarray), f.name
            _assert_same(value, want, backend, f.name)
        elif isinstance(want, float) and not _exact(backend):
            scale = max(abs(want), problem.grid.spacing if f.name in LENGTHS else 0.0)
            assert value == want or abs(value - want) <= ROUND_OFF_AGREEMENT * scale, f.name
        elif f.name != "iterations" or _exact(backend):
            assert value == want, f.name


@pytest.mark.parametrize("body", ["half_space", "coarse_start", "gross_sliding", "rough_periodic", "layer",
                                  "bulk_modulus", "line", "adhesive"])
@pytest.mark.parametrize("backend", BACKENDS)
def test_the_steady_state_on_the_device_equals_numpy(backend, body, monkeypatch):
    from viscontact import steady
    from viscontact.solvers import steady_periodic
    from viscontact.bodies import compliance
    from viscontact.numerics import active_set
    from viscontact.solvers.steady import solve_steady

    problem = _solved_to_round_off(_steady(body), backend)
    reference = solve_steady(problem)
    monkeypatch.setattr(compliance, "array_backend", lambda device: backend)  # solver.device -> the device
    gaps = []
    for module in (steady, steady_periodic, active_set):  # (the adhesive rounds call it from active_set)
        solve = module.solve_contact_active_set
        monkeypatch.setattr(module, "solve_contact_active_set",
                            lambda apply_k, gap, _solve=solve, **kw: gaps.append(gap) or _solve(apply_k, gap, **kw))
    ours = solve_steady(problem)
    assert gaps and not any(isinstance(g, np.ndarray) for g in gaps)  # the active set ran on the device
    for f in dataclasses.fields(ours):
        value, want = getattr(ours, f.name), getattr(reference, f.name)
        if isinstance(want, np.ndarray):
            assert isinstance(value, np.ndarray), f.name
            _assert_same(value, want, backend, f.name)
        elif isinstance(want, float) and not _exact(backend):  # equal infinities too (sliding_distance)
            scale = max(abs(want), problem.grid.spacing if f.name in LENGTHS else 0.0)
            assert value == want or abs(value - want) <= ROUND_OFF_AGREEMENT * scale, f.name
        elif f.name != "iterations" or _exact(backend):
            assert value == want, f.name
