"""A run imports what it uses (issue 35: peak memory): ``viscontact run`` of a creep case loads no
``scipy.optimize`` (nor ``scipy.linalg``, ``.sparse``, ``.spatial``, which it pulls in: about 23 MiB, a
fifth of the run's peak at 256^2), their users importing them where used; the creep spectrum's root
finder (:func:`viscontact.physics.prony.brent_root`) is scipy's ``brentq`` step for step: the same
roots to the last bit, on the secular equations of random Prony series and on plain functions, and
the same errors."""
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
from viscontact.physics.prony import brent_root

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


def _secular(rates: np.ndarray, weights: np.ndarray, origin: float):
    diff = rates - origin
    return lambda delta: 1.0 - float(np.sum(weights / (diff - delta)))


@pytest.mark.parametrize("seed", range(6))
def test_brent_root_is_scipys_brentq_to_the_last_bit(seed):
    rng = np.random.default_rng(seed)
    eps = 4 * np.finfo(float).eps
    compared = 0
    for _ in range(40):
        size = int(rng.integers(1, 9))
        rates = np.sort(10.0 ** rng.uniform(-3, 6, size))
        weights = rng.uniform(0.01, 1.0, size) * rates / size
        lows = np.concatenate([[0.0], rates[:-1]])
        for lo, hi in zip(lows, rates):
            for origin, a, b in ((lo, 1e-300 * (hi - lo), 0.5 * (hi - lo)), (hi, -0.5 * (hi - lo), -1e-300 * hi)):
                f = _secular(rates, weights, origin)
                with np.errstate(all="ignore"):
                    if not f(a) * f(b) < 0:
                        continue
                xtol = abs(b - a) * 1e-300 + 1e-320
                ours = brent_root(f, a, b, xtol=xtol, rtol=eps, maxiter=400)
                theirs = brentq(f, a, b, xtol=xtol, rtol=eps, maxiter=400)
                assert ours == theirs, (ours, theirs)
                compared += 1
    assert compared > 100
    for f, a, b in ((lambda x: x**3 - 2 * x - 5, 2.0, 3.0), (np.cos, 0.0, 3.0), (lambda x: np.exp(x) - 1e3, 0, 20)):
        for xtol in (2e-12, 1e-3):
            assert brent_root(f, a, b, xtol=xtol, rtol=eps) == brentq(f, a, b, xtol=xtol, rtol=eps)


def test_brent_root_refuses_what_brentq_refuses():
    with pytest.raises(ValueError, match="different signs"):
        brent_root(np.cos, 0.0, 1.0, xtol=1e-12, rtol=1e-15)
    with pytest.raises(RuntimeError, match="no convergence in 3 steps"):
        brent_root(lambda x: x**3 - 2 * x - 5, 2.0, 3.0, xtol=1e-15, rtol=1e-15, maxiter=3)


def test_a_material_creep_spectrum_is_unchanged(monkeypatch):
    """Material.creep (its retardation times and amplitudes) by brent_root equals brentq's: the spectrum
    computed with scipy's root finder swapped in."""
    from viscontact.physics import prony

    material = Material.prony(0.193e6, [1.0e6, 0.5e6, 0.237e6], [1e-4, 3e-3, 0.2], 0.3)
    ours = prony.retardation_spectrum(0.193e6, np.array([1.0e6, 0.5e6, 0.237e6]), np.array([1e-4, 3e-3, 0.2]))
    monkeypatch.setattr(prony, "brent_root", lambda f, a, b, **kw: brentq(f, a, b, **kw))
    theirs = prony.retardation_spectrum(0.193e6, np.array([1.0e6, 0.5e6, 0.237e6]), np.array([1e-4, 3e-3, 0.2]))
    assert np.array_equal(ours[0], theirs[0]) and np.array_equal(ours[1], theirs[1])
    assert material.creep.instantaneous == pytest.approx(1 / 1.93e6, rel=1e-12)
