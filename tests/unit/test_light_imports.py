"""A run imports what it uses (issue 35: peak memory): ``viscontact run`` of a creep case loads no
``scipy.optimize`` (nor ``scipy.linalg``, ``.sparse``, ``.spatial``, which it pulls in: about 23 MiB, a
fifth of the run's peak at 256^2), their users importing them where used; the creep spectrum's
roots (:func:`viscontact.physics.prony.secular_roots`, bisection) are those of scipy's ``brentq`` on
the same secular equations (an independent root finder) to 1e-13 (measured: at most 51 ulp in the
times, 73 in the amplitudes), over random
Prony series of up to 8 terms and 9 decades of relaxation times."""
from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from viscontact.physics.materials import Material

SRC = Path(__file__).resolve().parents[2] / "src"
NOT_LOADED = ("scipy.optimize", "scipy.linalg", "scipy.sparse", "scipy.spatial", "xarray", "matplotlib")


def test_a_creep_run_loads_no_scipy_optimize(tmp_path):
    script = textwrap.dedent(f"""
        import json, sys
        from viscontact.cli import main
        code = main(["run", sys.argv[1], "--out", sys.argv[2], "--quiet", "--set", "grid.n=32",
                     "--set", "time.t_end=0.001"])
        print(json.dumps([code, sorted(m for m in {NOT_LOADED} if m in sys.modules)]))
    """)
    out = subprocess.run([sys.executable, "-c", script, str(SRC / "viscontact" / "cases" / "creep_indentation.toml"),
                          str(tmp_path / "r.nc")], capture_output=True, text=True, timeout=300, check=False)
    assert out.returncode == 0, out.stderr
    code, loaded = json.loads(out.stdout.splitlines()[-1])
    assert code == 0 and loaded == [], loaded


def _brentq_spectrum(g_inf: float, g: np.ndarray, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Retardation times [s] and amplitudes [1/Pa] of G = g_inf + sum g_i exp(-t/tau_i) by scipy's brentq
    on the secular equation 1 - sum_i w_i / (r_i - x) = 0 (w_i = g_i r_i / G(0), r_i = 1/tau_i), each
    root sought as the offset from the nearer pole of its bracket (full relative precision)."""
    rates = np.sort(1.0 / tau)
    g = g[np.argsort(1.0 / tau)]
    g0 = g_inf + g.sum()
    weights = g * rates / g0
    roots, amplitudes = [], []
    for lo, hi in zip(np.concatenate([[0.0], rates[:-1]]), rates):
        mid = lo + 0.5 * (hi - lo)
        above = 1.0 - np.sum(weights / (rates - mid)) > 0  # decreasing: the root lies above mid
        origin = hi if above else lo
        diff = rates - origin

        def secular(delta, diff=diff):
            return 1.0 - float(np.sum(weights / (diff - delta)))

        span = mid - origin
        a, b = (span, -abs(span) * 1e-300) if above else (abs(span) * 1e-300 if origin > 0 else 0.0, span)
        with np.errstate(all="ignore"):
            delta = brentq(secular, a, b, xtol=abs(span) * 1e-300 + 1e-320, rtol=4 * np.finfo(float).eps,
                           maxiter=400) if secular(a) * secular(b) < 0 else span
        x = origin + delta
        roots.append(x)
        amplitudes.append(1.0 / (x * g0 * np.sum(weights / (diff - delta) ** 2)))
    order = np.argsort(1.0 / np.array(roots))
    return 1.0 / np.array(roots)[order], np.array(amplitudes)[order]


@pytest.mark.parametrize("seed", range(6))
def test_the_creep_spectrum_is_that_of_an_independent_root_finder(seed):
    rng = np.random.default_rng(seed)
    for _ in range(20):
        size = int(rng.integers(1, 9))
        tau = np.unique(10.0 ** rng.uniform(-5, 4, size))
        g = rng.uniform(0.05, 1.0, tau.size) * 1e6
        material = Material.prony(0.1e6, list(g), list(tau), 0.3)
        times, amplitudes = _brentq_spectrum(0.1e6, g, tau)
        creep = material.creep
        np.testing.assert_allclose(creep.retardation_times, times, rtol=1e-13, atol=0)
        np.testing.assert_allclose(creep.amplitudes, amplitudes, rtol=1e-13, atol=0)
        assert creep.instantaneous == pytest.approx(1 / (0.1e6 + g.sum()), rel=1e-14)
        assert creep.instantaneous + creep.amplitudes.sum() == pytest.approx(1 / 0.1e6, rel=1e-11)  # J(inf) = 1/G(inf)
