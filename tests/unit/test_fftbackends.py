"""Zero-block DC-FFT transforms (viscontact.numerics.fftbackends) against independent truth.

* the literal O(n^4) aperiodic sum (``direct_convolution``): agreement to round-off, 1e-12
  relative to the largest value (a transform that dropped a non-zero block, or that wrapped the
  padding periodically, is off by O(1));
* the full 2-D real FFT of the zero-padded field (``numpy.fft.rfft2``, another implementation);
* odd n (the padded length 2n is then not a power of two) and fields non-zero up to every edge.
"""
from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest
from vc_testing import seed_material, sphere_problem

from viscontact.io.case import load_case
from viscontact.numerics.convolution import direct_convolution
from viscontact.errors import ParameterError
from viscontact.numerics.arrays import array_backend
from viscontact.numerics.fftbackends import BACKENDS, check_fft_backend, dcfft_transforms
from viscontact.problem.problem import SolverSettings
from viscontact.running.loop import simulate

ROOT = Path(__file__).resolve().parents[2]


def _backends() -> list:
    names = ["scipy"]
    try:
        import pyfftw  # noqa: F401
        names.append("pyfftw")
    except ImportError:
        pass
    return names


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


@pytest.mark.parametrize("name", _backends())
@pytest.mark.parametrize("n", [7, 12, 16])
def test_convolve_equals_direct_sum(name: str, n: int) -> None:
    rng = np.random.default_rng(n)
    kernel = rng.standard_normal((2 * n, 2 * n))
    field = rng.standard_normal((n, n))
    tr = dcfft_transforms(name, n, 1)
    kernel_hat = np.fft.rfft2(kernel)
    reference = direct_convolution(kernel, field)
    assert _rel(tr.convolve(kernel_hat, field), reference) < 1e-12
    # forward/inverse separately: the same convolution, and the caller owns the results
    spectrum = tr.forward(field)
    first = spectrum.copy()
    tr.forward(np.zeros((n, n)))
    assert np.array_equal(spectrum, first)
    assert _rel(tr.inverse(kernel_hat * spectrum), reference) < 1e-12
    # repeated convolutions: a second field (non-zero to every edge), then the first again, each
    # against its own direct sum; earlier results stay the caller's
    result = tr.convolve(kernel_hat, field)
    other = rng.standard_normal((n, n))
    assert _rel(tr.convolve(kernel_hat, other), direct_convolution(kernel, other)) < 1e-12
    assert _rel(result, reference) < 1e-12
    assert np.array_equal(tr.convolve(kernel_hat, field), result)


@pytest.mark.parametrize("name", _backends())
def test_forward_is_the_padded_real_fft(name: str) -> None:
    n = 10
    field = np.random.default_rng(3).standard_normal((n, n))
    spectrum = dcfft_transforms(name, n, 1).forward(field)
    assert spectrum.shape == (2 * n, n + 1)
    assert _rel(spectrum, np.fft.rfft2(field, s=(2 * n, 2 * n))) < 1e-13


@pytest.mark.parametrize("name", _backends())
def test_inverse_keeps_the_physical_block(name: str) -> None:
    n = 9
    big = np.random.default_rng(4).standard_normal((2 * n, 2 * n))
    block = dcfft_transforms(name, n, 1).inverse(np.fft.rfft2(big))
    assert block.shape == (n, n)
    assert _rel(block, big[:n, :n]) < 1e-13


def test_unknown_backend_is_refused() -> None:
    with pytest.raises(ValueError, match="unknown FFT backend 'fftx'"):
        dcfft_transforms("fftx", 8)
    assert set(BACKENDS) == {"scipy", "pyfftw"}


def test_solver_fft_is_a_case_key(monkeypatch: pytest.MonkeyPatch) -> None:
    case = load_case(ROOT / "cases" / "creep_indentation.toml")
    assert case.to_problem().solver.fft == "scipy"
    with pytest.raises(ParameterError) as err:
        case.with_overrides({"solver.fft": "fftx"})
    assert err.value.key == "solver.fft"
    real_find_spec = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "pyfftw" else real_find_spec(name, *a))
    assert SolverSettings(fft="pyfftw").fft == "pyfftw"  # the settings describe; the run decides
    with pytest.raises(ParameterError) as err:
        check_fft_backend("pyfftw")
    assert err.value.key == "solver.fft" and "viscontact[fast]" in err.value.message


@pytest.mark.skipif("pyfftw" not in _backends(), reason="pyFFTW not installed (extra 'fast')")
def test_pyfftw_run_equals_scipy_run() -> None:
    """The creep transient with FFTW plans against the one with pocketfft (another FFT library):
    the same pressures to round-off amplified by the iteration (1e-10), the same iterations. Both in
    double precision: FFTW's plans are double, so with mixed precision its single-precision increments
    would be computed in double and pocketfft's in float32, not the same arithmetic (the runs then
    differ by up to the CG tolerance, 6e-10 here)."""
    runs = {}
    for name in ("scipy", "pyfftw"):
        problem = sphere_problem(seed_material(), 24, 1.5e-3, t_end=0.01, dt=1e-3,
                                 solver=SolverSettings(workers=1, fft=name, mixed_precision=False))
        runs[name] = list(simulate(problem))
    for a, b in zip(runs["scipy"], runs["pyfftw"]):
        assert a.iterations == b.iterations
        assert _rel(b.pressure, a.pressure) < 1e-10


def test_default_workers_are_one_thread_up_to_512_squared() -> None:
    """workers = -1 is one thread up to SINGLE_THREAD_SIZE cells (threads are slower there), all cores
    above; an explicit count is kept; the transforms use the resolved count."""
    from viscontact.numerics.fftbackends import SINGLE_THREAD_SIZE, ZeroBlockTransforms, fft_threads

    assert SINGLE_THREAD_SIZE == 512 * 512
    assert fft_threads(-1, 256 * 256) == 1
    assert fft_threads(-1, 512 * 512) == 1
    assert fft_threads(-1, 1024 * 1024) == -1
    assert fft_threads(2, 64 * 64) == 2
    assert ZeroBlockTransforms(256, -1)._kw == {"workers": 1}
    assert ZeroBlockTransforms(1024, -1)._kw == {"workers": -1}


def test_solver_device_and_mixed_precision_are_case_keys() -> None:
    """``[solver] device`` is a contract key: "cpu" runs, "gpu" needs CuPy (refused with one line naming
    the key and the extra where it is missing), anything else is refused; ``mixed_precision`` reaches
    the problem."""
    case = load_case(ROOT / "cases" / "creep_indentation.toml")
    assert case.to_problem().solver.device == "cpu" and case.to_problem().solver.mixed_precision
    assert case.with_overrides({"solver.device": "cpu"}).to_problem().solver.device == "cpu"
    assert not case.with_overrides({"solver.mixed_precision": False}).to_problem().solver.mixed_precision
    with pytest.raises(ParameterError) as err:
        case.with_overrides({"solver.device": "tpu"}).to_problem()
    assert err.value.key == "solver.device"
    with pytest.raises(ParameterError) as err:
        SolverSettings(device="gpu", fft="pyfftw")
    assert err.value.key == "solver.fft" and "cuFFT" in err.value.message
    assert case.with_overrides({"solver.device": "gpu"}).to_problem().solver.device == "gpu"  # on any machine
    if importlib.util.find_spec("cupy") is None:  # the run decides: refused at its start
        with pytest.raises(ParameterError) as err:
            array_backend("gpu")
        assert err.value.key == "solver.device" and "viscontact[gpu]" in err.value.message
