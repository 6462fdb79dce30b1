"""Checkpoint and resume on the bodies built from compliance terms: nu(t) (``bulk_modulus``, two
histories per traction component), a layer on a rigid base and on an elastic substrate (one kernel
and history per shift node), on DC-FFT and periodic grids. A run stopped after a few steps (as
by a signal: its checkpoint written) and resumed gives the uninterrupted result bit for bit, as
the half-space's does (tests/unit/test_reliability.py); a checkpoint of another body is refused;
the memory estimate counts the body's extra histories and kernels."""
from __future__ import annotations

import warnings
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest

from viscontact.running import api
from viscontact.io.case import load_case
from viscontact.errors import ParameterError, RunInterrupted, ViscontactWarning

ROOT = Path(__file__).resolve().parents[2]
G0 = 1.93e6
SLIDING = {"grid.n": 16, "tangential.sliding_speed": 0.05, "tangential.friction_coefficient": 0.3, "time.dt": None,
           "time.scheme": "linear", "tangential.steps_per_cell": 4, "time.t_end": 10 * 2e-3 / 8 / 0.05 / 4}
BULK = {"material.poisson_ratio": None, "material.bulk_modulus": 2 * G0}
LAYER = {"layer.thickness": 0.5e-3}
ON_ELASTIC = {"layer.thickness": 0.5e-3, "layer.substrate": "elastic", "layer.substrate_shear_modulus": 5 * G0,
              "layer.substrate_poisson_ratio": 0.3}
FRETTING = [[0.0, 0.0], [0.5e-3, 5e-6], [1.5e-3, -5e-6], [2.5e-3, 5e-6]]  # [s, m]
BODIES = {
    "bulk_modulus gross sliding": {**SLIDING, "tangential.mode": "gross_sliding", **BULK},
    "bulk_modulus periodic": {**SLIDING, "tangential.mode": "gross_sliding", "grid.periodic": True, **BULK},
    "layer partial slip": {**SLIDING, "tangential.mode": "partial_slip", "tangential.displacement_rate": 0.01, **LAYER},
    # partial slip to step 6, then sliding: the checkpoint (step 3) holds s_x
    "incremental slip": {**SLIDING, "tangential.mode": "partial_slip", "tangential.displacement_rate": 0.004,
                         "tangential.slip": "incremental"},
    "layer, incremental slip": {**SLIDING, "tangential.mode": "partial_slip", "tangential.displacement_rate": 0.0025,
                                "tangential.slip": "incremental", **LAYER},
    # fretting: delta_x out to 5 um, back to -5 um and out again (below gross slip: 12.6 um), the
    # checkpoint (step 3, t = 0.75 ms) after the first reversal (0.5 ms): s_x holds the path's memory
    "fretting": {"grid.n": 16, "tangential.mode": "partial_slip", "tangential.friction_coefficient": 0.3,
                 "tangential.displacement_history": FRETTING, "time.t_end": 2.5e-3, "time.scheme": "linear"},
    # output.every = 3 keeps the turning points' steps (2 and 6 at 0.25 ms) beside 0, 3, ..., 18 and 20
    # (delta_x held after the history's end)
    "fretting, thinned output": {"grid.n": 16, "tangential.mode": "partial_slip", "tangential.friction_coefficient": 0.3,
                                 "tangential.displacement_history": FRETTING, "time.t_end": 5e-3,
                                 "time.scheme": "linear", "output.every": 3},
    "layer periodic": {**SLIDING, "tangential.mode": "frictionless_sliding", "grid.periodic": True, **LAYER},
    "layer on an elastic substrate": {**SLIDING, "tangential.mode": "gross_sliding", **ON_ELASTIC},
    "layer on an elastic substrate, periodic": {**SLIDING, "tangential.mode": "frictionless_sliding",
                                                "grid.periodic": True, **ON_ELASTIC},
}


def case(overrides):
    return load_case(ROOT / "cases" / "creep_indentation.toml").with_overrides(overrides)


@contextmanager
def quiet():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ViscontactWarning)  # dt above the shortest material time
        yield


def stopped(overrides, checkpoint: Path, after: int = 4) -> None:
    """Run ``overrides`` with checkpoints every 3 steps, stopped after step ``after`` (a signal)."""
    calls = []

    def stop() -> str | None:
        calls.append(1)
        return "SIGTERM" if len(calls) == after else None

    with quiet(), pytest.raises(RunInterrupted):
        api.run(case(overrides), checkpoint=checkpoint, checkpoint_every=3, should_stop=stop)
    assert checkpoint.exists()


@pytest.mark.parametrize("body", list(BODIES))
def test_stop_and_resume_equals_uninterrupted(tmp_path, body):
    overrides = BODIES[body]
    ckpt = tmp_path / "r.nc.checkpoint.npz"
    stopped(overrides, ckpt)
    with quiet():
        resumed = api.run(case(overrides), checkpoint=ckpt, resume=True)
        full = api.run(case(overrides))
    assert full["t"].size >= 8 and resumed.sizes == full.sizes
    for name in full.data_vars:
        np.testing.assert_array_equal(resumed[name].values, full[name].values, err_msg=name)


def test_resume_refuses_a_checkpoint_of_another_body(tmp_path):
    ckpt = tmp_path / "r.nc.checkpoint.npz"
    stopped(BODIES["layer periodic"], ckpt)
    other = {**BODIES["layer periodic"], "layer.thickness": 0.6e-3}
    with pytest.raises(ParameterError, match="^--resume: checkpoint .* different case"):
        api.run(case(other), checkpoint=ckpt, resume=True)


def test_resume_of_the_incremental_slip_carries_its_slip_and_refuses_the_total_one(tmp_path):
    """The incremental slip's checkpoint holds s_x (State.slip_x, the run still in partial slip at
    its last save, step 3 of 4 here, gross sliding from step 7); a checkpoint of the total slip is refused by the incremental one
    and the other way round (tangential.slip enters the fingerprint away from its default, so the
    total slip's fingerprint, and the checkpoints written before the setting, stay as they were)."""
    from viscontact.io.checkpoint import load_checkpoint, problem_fingerprint

    incremental = BODIES["incremental slip"]
    total = {**incremental, "tangential.slip": "total"}
    ckpt = tmp_path / "r.nc.checkpoint.npz"
    stopped(incremental, ckpt)
    state, _ = load_checkpoint(ckpt, case(incremental).to_problem())
    assert state.phase == 1 and state.slip_x is not None and np.any(state.slip_x != 0)
    with pytest.raises(ParameterError, match="^--resume: checkpoint .* different case"):
        api.run(case(total), checkpoint=ckpt, resume=True)
    stopped(total, ckpt)
    assert load_checkpoint(ckpt, case(total).to_problem())[0].slip_x is None
    with pytest.raises(ParameterError, match="^--resume: checkpoint .* different case"):
        api.run(case(incremental), checkpoint=ckpt, resume=True)
    without = {k: v for k, v in total.items() if k != "tangential.slip"}
    assert problem_fingerprint(case(without).to_problem()) == problem_fingerprint(case(total).to_problem())
    # where there is no partial slip the setting changes nothing: the checkpoints stay each other's
    sliding = {**without, "tangential.mode": "gross_sliding"}
    assert (problem_fingerprint(case({**sliding, "tangential.slip": "incremental"}).to_problem())
            == problem_fingerprint(case(sliding).to_problem()))


def test_the_displacement_history_enters_the_fingerprint_and_leaves_the_others_alone(tmp_path):
    """A fretting checkpoint holds s_x after the reversal; one of another history (the amplitude
    changed) is refused; and the fingerprints of the problems without a history are those written
    before the key came (pinned: computed by the version before it for seed_fig10_case3 at n = 16,
    total and incremental slip), so their checkpoints still resume."""
    from viscontact.io.checkpoint import load_checkpoint, problem_fingerprint

    fretting = BODIES["fretting"]
    ckpt = tmp_path / "r.nc.checkpoint.npz"
    stopped(fretting, ckpt)
    state, _ = load_checkpoint(ckpt, case(fretting).to_problem())
    assert state.phase == 1 and state.delta_x < 5e-6 and np.any(state.slip_x != 0)
    other = {**fretting, "tangential.displacement_history": [[t, 0.8 * d] for t, d in FRETTING]}
    assert problem_fingerprint(case(other).to_problem()) != problem_fingerprint(case(fretting).to_problem())
    with pytest.raises(ParameterError, match="^--resume: checkpoint .* different case"):
        api.run(case(other), checkpoint=ckpt, resume=True)
    seed = load_case(ROOT / "cases" / "seed_fig10_case3.toml").with_overrides({"grid.n": 16})
    assert problem_fingerprint(seed.to_problem()) == \
        "740ba8c524dc6befa00da9d78b98a9dc45767aa2f5bfedfde3d821029fed2eae"
    assert problem_fingerprint(seed.with_overrides({"tangential.slip": "incremental"}).to_problem()) == \
        "baaf21299c44724bc5ce281db7a68a1872d411604035931e17de027f12e0887e"


def test_memory_estimate_counts_the_histories_and_kernels_of_the_body(monkeypatch):
    """A viscoelastic layer on an elastic substrate holds D M history fields and D + 1 kernels per
    component (D + 1 shift nodes, layers.shift_nodes), and its support windows keep the D + 1
    cropped kernels of each of the last WINDOWS_KEPT sides, and of one more being built beside them
    with its crops (and, with mixed precision, a complex64 spectrum of each kernel on the grid and
    on each side): the estimate of its solver state grows by that much over the half-space's
    (Zener: M = 1, 9 nodes at the default tolerance), less the half-space's response history
    (M + 1 fields in the old and the new state), which a body of several kernels does not carry
    (substrate.Compliance.initial_response). The layer's own contact estimate (its stiffer base
    narrows the contact) gives it smaller windows than the half-space's: both are counted here at the
    layer's side, so that the difference is the body's alone."""
    from viscontact.bodies.layer import shift_nodes
    from viscontact.running import resources
    from viscontact.running.resources import estimate, kernel_bytes, window_cells
    from viscontact.bodies.compliance import WINDOWS_KEPT

    half = case({"grid.n": 64}).to_problem()
    layer = case({"grid.n": 64, **ON_ELASTIC}).to_problem()
    nodes = shift_nodes(layer.material).nodes.size
    n, m = 64, window_cells(layer)
    assert window_cells(half) > m > 0
    monkeypatch.setattr(resources, "window_cells", lambda problem: m)
    assert resources.window_cells(half) == m > 0
    per_field = 2 * 2 * 8 * n * n
    single = 2 * n * (n + 1) * 8  # mixed precision: the complex64 spectrum of each self kernel
    per_kernel = kernel_bytes(n) + (1 + WINDOWS_KEPT) * (single + kernel_bytes(m)) + 4 * m * m * 8
    grown = estimate(layer).peak_memory_bytes - estimate(half).peak_memory_bytes
    assert nodes == 9
    response = 2 * (1 + 1) * 8 * n * n
    assert grown == (nodes - 2) * per_field + (nodes - 1) * per_kernel - response
