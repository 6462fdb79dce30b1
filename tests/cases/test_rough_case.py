"""The shipped rough case: an elastomer on a periodic self-affine surface, from partial slip to
gross sliding (cases/rough_periodic_sliding.toml).

What the case shows, checked on a 32^2 grid (about 60 steps; the default 64^2 run is ``slow``):
* partial slip first: stick islands inside the contact spots shrink (stick ratio from about 0.8
  to 0) while the real contact area grows by creep at constant load;
* gross sliding then: the real contact area drops (the sliding half-space responds stiffer than
  the creeping one) and mu_app rises to a plateau;
* on the periodic frame the transient reaches the exact periodic steady state of ``viscontact
  steady`` (every Fourier mode through G*(k_x v), no truncation) after 10 retardation times of
  sliding: mu_app within the time-step error, which falls with dt = dx / v (second order on the
  smooth sinusoid, tests/validation/test_periodic_transient.py; slower here, where contact edges
  cross cells): measured 2.2 % at 32^2 (dt = 1.6 ms, 1.6 x the material's shortest time), 1.5 % at
  64^2 (tolerances 3 % and 2 %);
* the speed curve of the steady state has the hysteresis peak of a viscoelastic solid.
"""
from __future__ import annotations

import functools
import warnings
from pathlib import Path

import numpy as np
import pytest

from viscontact.running.api import run, run_steady
from viscontact.io.case import load_case
from viscontact.errors import ViscontactWarning

CASE = Path(__file__).resolve().parents[2] / "cases" / "rough_periodic_sliding.toml"


@functools.cache
def transient(n: int):
    case = load_case(CASE).with_overrides({"grid.n": n})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ViscontactWarning)  # dt > the shortest material time at n = 32
        return run(case), run_steady(case)


def _check(n: int, tolerance: float) -> None:
    ds, steady = transient(n)
    phase = ds["phase"].values
    stick = ds["stick_ratio"].values
    area = ds["contact_fraction"].values
    mu = ds["mu_app"].values
    start = int(np.argmax(phase == 2))
    assert phase[0] == 1 and start > 5 and phase[-1] == 2
    assert stick[0] > 0.5 and stick[start - 1] < stick[0] and stick[start] == 0
    assert area[start - 1] > 1.5 * area[0]            # creep at constant load
    assert area[-1] < 0.7 * area[start - 1]           # sliding stiffens the response
    assert np.all(ds["contact_patches"].values >= 1)
    assert mu[-1] > 0.01 and abs(mu[-1] - mu[-5]) < 1e-3 * mu[-1]  # a plateau
    assert ds["load"].values == pytest.approx(0.01, rel=1e-9)
    mu_steady = float(steady["mu_app"].values[0])
    assert mu[-1] == pytest.approx(mu_steady, rel=tolerance)
    assert area[-1] == pytest.approx(float(steady["contact_fraction"].values[0]), abs=0.02)


def test_rough_case_partial_slip_to_gross_sliding():
    _check(32, 0.03)


@pytest.mark.slow
def test_rough_case_default_grid():
    _check(64, 0.02)


def test_periodic_steady_speed_curve():
    case = load_case(CASE).with_overrides({"grid.n": 32, "tangential.mode": "frictionless_sliding"})
    speeds = np.geomspace(1e-4, 10.0, 6)
    ds = run_steady(case, speeds=speeds)
    mu = ds["mu_app"].values
    assert np.all(mu > 0) and np.argmax(mu) not in (0, len(mu) - 1)  # the hysteresis peak
    assert mu[0] < 0.2 * mu.max() and mu[-1] < 0.2 * mu.max()
    assert np.all(ds["contact_fraction"].values > 0) and ds["contact_patches"].values.min() >= 1
    assert ds["load"].values == pytest.approx(0.01, rel=1e-9)
