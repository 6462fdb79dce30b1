"""Every shipped case loads, and the seed's cases show the behaviour its text describes.

The seed is Wang et al., Friction 2023 (``/work/shared/seed``); its statements are quoted in the
test docstrings. The runs use reduced grids: ``grid.n = 64`` with ``tangential.steps_per_cell = 4``
so that the time step (one quarter cell of sliding per step) equals that of the seed's 256 x 256
runs (dt = 0.02-0.05 tau), only the space is coarser (dx = 0.08-0.12 a0). Each run takes 1-6 s; the
full-resolution checks are marked ``slow``.

Numbers measured with this file's settings (n = 64, 4 steps per cell) are quoted in comments as
"measured"; tolerances are set from them and from the grid (one cell = 0.08-0.12 a0; a contact of
radius a0 covers about 300 cells, so its area is quantised at about 2-3 %).
"""
from __future__ import annotations

import functools
import math
import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from viscontact.running.api import run
from viscontact.io.case import load_case
from viscontact.errors import ViscontactWarning
from viscontact.physics.reference import hertz_from_load

CASES = Path(__file__).resolve().parents[2] / "cases"
TAU = 0.01                   # s, the seed's tau (retardation time)
A0 = 588.7e-6                # m, the seed's a0 (Hertz with G(0) = 1.93 MPa, W = 0.15 N)
N_FAST, SPC_FAST = 64, 4     # reduced grid; 4 steps per cell keep the seed's dt


# --- helpers -----------------------------------------------------------------------------------------
@functools.cache
def simulate(name: str, n: int = N_FAST, steps_per_cell: int = SPC_FAST, **overrides) -> xr.Dataset:
    """Result of the shipped case ``name`` on an n x n grid (cached for the session).

    The wake warning (history dropped at the trailing edge, < 2 % of mu_app here) is expected: the
    domains are the seed's own."""
    case = load_case(CASES / f"{name}.toml")
    changes = {"grid.n": n, "tangential.steps_per_cell": steps_per_cell}
    changes.update({k.replace("__", "."): v for k, v in overrides.items()})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ViscontactWarning)
        return run(case.with_overrides(changes))


def at(ds: xr.Dataset, t_tau: float) -> int:
    """Index of the record nearest to t_tau [tau]."""
    return int(np.argmin(np.abs(ds["t"].values / TAU - t_tau)))


def shift(ds: xr.Dataset) -> np.ndarray:
    """Contact shift [a0 of the result]: pressure centroid relative to the indenter centre."""
    return ds["contact_shift"].values / ds.attrs["a0"]


def peak(ds: xr.Dataset) -> np.ndarray:
    """Peak pressure [p0 of the result] against time."""
    return ds["pressure"].max(("x", "y")).values / ds.attrs["p0"]


def area(ds: xr.Dataset) -> np.ndarray:
    """Contact area [pi a0^2 of the result] against time."""
    return ds["contact_area"].values / (math.pi * ds.attrs["a0"] ** 2)


def profile(ds: xr.Dataset, k: int, x_common: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Pressure along y = 0 [p0] against x - frame_offset [a0] (indenter frame); mean of the two
    middle rows. With ``x_common`` [a0], interpolated onto it (zero outside the grid)."""
    p = ds["pressure"].values[k]
    n = p.shape[0]
    row = 0.5 * (p[n // 2 - 1] + p[n // 2]) / ds.attrs["p0"]
    x = (ds["x"].values - ds["frame_offset"].values[k]) / ds.attrs["a0"]
    if x_common is None:
        return x, row
    return x_common, np.interp(x_common, x, row, left=0.0, right=0.0)


def time_to_steady(values: np.ndarray, t_tau: np.ndarray, tolerance: float) -> float:
    """First time [tau] after which ``values`` stay within ``tolerance`` (relative) of the last value."""
    off = np.flatnonzero(np.abs(values - values[-1]) > tolerance * abs(values[-1]))
    return float(t_tau[off[-1] + 1]) if off.size else float(t_tau[0])


# --- every shipped case ---------------------------------------------------------------------------------
ALL_CASES = sorted(CASES.glob("*.toml"))
SEED_CASES = sorted(CASES.glob("seed_*.toml"))


def test_the_seed_cases_are_shipped():
    names = {p.stem for p in SEED_CASES}
    expected = ({f"seed_table1_v{v}" for v in ("0.4", "0.8", "1.2")}
                | {f"seed_table2_ratio{r}_{c}" for r in (3, 5, 10) for c in ("load", "displacement")}
                | {f"seed_table3_case{c}" for c in (1, 2, 3, 4)} | {f"seed_fig10_case{c}" for c in (1, 2, 3)})
    assert expected <= names


@pytest.mark.parametrize("path", ALL_CASES, ids=lambda p: p.stem)
def test_case_loads_and_converts(path):
    case = load_case(path)
    problem = case.to_problem()
    assert problem.grid.n == case.grid.n
    assert problem.time.n_steps >= 2
    assert path.read_text().startswith("#"), "a shipped case starts with a comment block"
    if problem.tangential.frame_moves:  # the frame moves by whole cells (steps_per_cell steps each)
        cell_dt = problem.grid.spacing / problem.tangential.sliding_speed / problem.tangential.steps_per_cell
        assert problem.time.dt == pytest.approx(cell_dt, rel=1e-9)


@pytest.mark.parametrize("path", SEED_CASES, ids=lambda p: p.stem)
def test_seed_case_states_the_conversion(path):
    """Shipped cases state the modulus / time / load conversion of the seed in a comment."""
    text = path.read_text()
    for phrase in ("TWICE the shear modulus", "G(0) = 1.93 MPa", "RETARDATION", "0.148 N / 0.15 N"):
        assert phrase in text
    problem = load_case(path).to_problem()
    mat = problem.material
    assert mat.shear_modulus_instantaneous == pytest.approx(1.93e6)
    assert mat.creep.retardation_times.max() == pytest.approx(TAU)
    assert problem.grid.n == 256 and problem.radius == pytest.approx(0.01)


def test_seed_scales():
    """The seed's a0 = 588.7 um and p0 = 0.2067 MPa follow from G(0) = 1.93 MPa and W = 0.15 N."""
    h = hertz_from_load(0.15, 0.01, 1.93e6, 0.3)
    assert h.radius == pytest.approx(A0, rel=1e-3)
    assert h.peak_pressure == pytest.approx(0.2067e6, rel=1e-3)
    assert h.approach == pytest.approx(34.45e-6, rel=1e-2)
    speeds = {"seed_table1_v0.4": 0.4, "seed_table1_v0.8": 0.8, "seed_table1_v1.2": 1.2,
              "seed_table3_case1": 1.2, "seed_fig10_case1": 1.2, "seed_table2_ratio3_load": 0.8}
    for name, v in speeds.items():
        assert load_case(CASES / f"{name}.toml").tangential.sliding_speed == pytest.approx(v * A0 / TAU, rel=1e-6)
    widths = {"seed_table1_v0.4": 2.56, "seed_table1_v1.2": 3.84, "seed_table2_ratio3_displacement": 2.56,
              "seed_table3_case3": 3.07, "seed_fig10_case3": 3.84}
    for name, w in widths.items():
        assert load_case(CASES / f"{name}.toml").grid.half_width == pytest.approx(w * A0, rel=1e-6)
    for name, rate in (("seed_table3_case3", 0.17), ("seed_table3_case4", 0.017), ("seed_fig10_case3", 0.17)):
        assert load_case(CASES / f"{name}.toml").tangential.displacement_rate == pytest.approx(rate * A0 / TAU, rel=1e-5)


def test_table2_displacement_contact_fits_the_domain():
    """Shipped approach 34.45 um: a = sqrt(R delta) = a0 (the load case's contact) inside +-2.56 a0;
    the seed's literal 100 um would give 1 mm = 1.70 a0, which also fits (margin 0.86 a0)."""
    case = load_case(CASES / "seed_table2_ratio10_displacement.toml")
    a = math.sqrt(case.indenter.radius * case.normal.value)
    assert a == pytest.approx(A0, rel=5e-3)  # 586.9 um: the seed rounds (a0^2/R = 34.66 um)
    assert math.sqrt(case.indenter.radius * 100e-6) < 0.7 * case.grid.half_width


# --- Table 1 / Fig. 4: frictionless sliding under a held load ---------------------------------------------
SPEEDS = ("0.4", "0.8", "1.2")


def table1(v: str, n: int = N_FAST, spc: int = SPC_FAST) -> xr.Dataset:
    return simulate(f"seed_table1_v{v}", n, spc)


def _leading_peak(ds: xr.Dataset, k: int) -> tuple[float, float]:
    """(x of the pressure peak, middle of the contact) along y = 0 [a0]."""
    x, p = profile(ds, k)
    inside = x[p > 0]
    return float(x[np.argmax(p)]), 0.5 * float(inside.min() + inside.max())


@pytest.mark.parametrize("v", SPEEDS)
def test_table1_pressure_peak_on_the_leading_side(v):
    """Seed Fig. 4: "Compared with the pressure at the trailing edge of the contact area, that at the
    leading edge tends to be higher showing a sharp spike." Checked from 0.5 tau on (at t = 0 the
    contact is Hertzian, symmetric)."""
    ds = table1(v)
    for t in (0.5, 1.0, 2.0, 4.0):
        x_peak, middle = _leading_peak(ds, at(ds, t))
        assert x_peak > middle, f"t = {t} tau: peak at x = {x_peak:.3f} a0, contact middle {middle:.3f} a0"


def test_table1_contact_shift():
    """Seed Fig. 4: "the contact region shifts in the sliding direction with time" and the increase of
    the speed causes "a more pronounced contact shift phenomenon".

    Measured shift at 4 tau (n = 64): 0.317, 0.532, 0.701 a0 for v = 0.4, 0.8, 1.2 a0/tau."""
    final = []
    for v in SPEEDS:
        s = shift(table1(v))
        ds = table1(v)
        assert 0 < s[at(ds, 0.5)] < s[at(ds, 1.0)] < s[at(ds, 2.0)], f"v = {v}: shift {s[[at(ds, t) for t in (0.5, 1, 2)]]}"
        final.append(s[-1])
    assert 0 < final[0] < final[1] < final[2], final


def test_table1_peak_rises_and_area_falls_with_speed():
    """Seed Fig. 4: "the increase in the sliding velocity is found to cause an increase in the peak
    pressure, a decrease in the contacting area".

    Measured at 4 tau (n = 64): peak 0.277, 0.369, 0.435 p0; area 4.17, 3.72, 3.32 pi a0^2."""
    peaks = [peak(table1(v))[-1] for v in SPEEDS]
    areas = [area(table1(v))[-1] for v in SPEEDS]
    assert peaks[0] < peaks[1] < peaks[2], peaks
    assert areas[0] > areas[1] > areas[2], areas


def test_table1_apparent_friction_rises_with_speed_and_settles_by_3tau():
    """Seed Fig. 4(d): "the apparent friction coefficient tends to become steady when the simulation
    time reaches 3 tau ... a higher velocity leads to a higher apparent friction coefficient".

    Measured (n = 64): mu_app(4 tau) = 0.0184, 0.0310, 0.0407; change over the last tau 0.5, 1.0,
    0.7 %. Tolerance 3 %: the last tau must be flat to well within the spread between speeds (40 %)."""
    mu = [table1(v)["mu_app"].values for v in SPEEDS]
    assert 0 < mu[0][-1] < mu[1][-1] < mu[2][-1]
    for v, m in zip(SPEEDS, mu):
        ds = table1(v)
        change = abs(m[-1] - m[at(ds, 3.0)]) / m[-1]
        assert change < 0.03, f"v = {v}: mu_app changed by {100 * change:.1f} % between 3 and 4 tau"
    # monotonic in speed once sliding has built up (t >= 0.5 tau), not only at the end
    for t in (0.5, 1.0, 2.0, 3.0):
        values = [table1(v)["mu_app"].values[at(table1(v), t)] for v in SPEEDS]
        assert values[0] < values[1] < values[2], (t, values)


# --- Table 2 / Figs. 6-8: materials of G(0)/G(inf) = 3, 5, 10 ------------------------------------------------
RATIOS = (3, 5, 10)


def table2(ratio: int, control: str, **overrides) -> xr.Dataset:
    return simulate(f"seed_table2_ratio{ratio}_{control}", **overrides)


@pytest.mark.parametrize("control", ("displacement", "load"))
def test_table2_fluid_like_material_has_higher_apparent_friction(control):
    """Seed Fig. 8: "the more fluid-like material always shows a higher apparent friction coefficient
    regardless of the time and the experienced contact phenomenon". Checked at every record from
    0.25 tau on (mu_app starts at 0 for all).

    Measured mu_app(4 tau) (n = 64): relaxation (34.45 um) 0.0144, 0.0190, 0.0229; creep 0.0180, 0.0250, 0.0310."""
    runs = [table2(r, control) for r in RATIOS]
    t = runs[0]["t"].values / TAU
    mu = np.array([ds["mu_app"].values for ds in runs])
    late = t >= 0.25
    assert np.all(mu[0, late] < mu[1, late]) and np.all(mu[1, late] < mu[2, late]), mu[:, late][:, ::8]


def test_table2_creep_friction_higher_than_relaxation_for_the_seed_contact_size():
    """Seed Fig. 8: "the apparent friction coefficient is always higher when the creep phenomenon is
    experienced by the same viscoelastic material".

    Holds from 2 tau on when the held approach is about the Hertz approach of the held load
    (the seed's delta_z = 34.45 um; 34.66 um is Hertz's at 0.15 N: contact radius a0 within 0.3 %). Measured (n = 64), creep vs
    relaxation: ratio 3: 0.0169/0.0145 (2 tau), 0.0180/0.0144 (4 tau); ratio 5: 0.0236/0.0191,
    0.0250/0.0190; ratio 10: 0.0297/0.0230, 0.0310/0.0229. Before about 1 tau relaxation is
    higher (ratio 10 at 0.5 tau: 0.0146 creep vs 0.0228 relaxation): the relaxed contact reaches its
    steady state within about one tau, the creeping one needs about 3 tau (Fig. 7 text)."""
    for ratio in RATIOS:
        creep = table2(ratio, "load")
        relax = table2(ratio, "displacement")  # shipped: delta = 34.45 um
        t = creep["t"].values / TAU
        late = t >= 2.0
        assert np.all(creep["mu_app"].values[late] > relax["mu_app"].values[late]), ratio


@pytest.mark.parametrize("ratio", [
    pytest.param(3, marks=pytest.mark.xfail(strict=True, reason=(
        "seed Table 2 as stated (delta = 100 um, a = 1.7 a0): relaxation mu_app 0.0199 > creep 0.0180 at 4 tau "
        "(n = 64); holds with delta = 34.45 um, which we ship (see the test above)."))),
    pytest.param(5, marks=pytest.mark.xfail(strict=True, reason=(
        "seed Table 2 as stated (delta = 100 um): relaxation 0.0252 vs creep 0.0250 at 4 tau (n = 64)."))),
    10,
])
def test_table2_creep_friction_higher_than_relaxation_as_stated(ratio):
    """The same statement with the seed's Table 2 approach taken literally (delta = 100 um, not what
    we ship): the contact is then 1.7 times wider than in the load case, and the comparison holds at
    steady state only for the most fluid-like material. Measured mu_app(4 tau) creep / relaxation:
    ratio 3: 0.0180 / 0.0199, ratio 5: 0.0250 / 0.0252, ratio 10: 0.0310 / 0.0294."""
    literal = table2(ratio, "displacement", normal__value=100e-6)
    assert table2(ratio, "load")["mu_app"].values[-1] > literal["mu_app"].values[-1]


# --- Table 3 / Fig. 9: frictional sliding under a held approach --------------------------------------------
def table3(c: int, n: int = N_FAST, spc: int = SPC_FAST) -> xr.Dataset:
    return simulate(f"seed_table3_case{c}", n, spc)


def test_table3_onset_of_gross_sliding():
    """Seed §4.2: gross sliding "achieved at 0.1 tau" (case 3) and "at 0.6 tau" (case 4).

    Measured t_gross_sliding [tau]:        case 3   case 4
      n = 64,  1 step/cell  (dt 0.080 tau)  0.080    0.560
      n = 64,  4 steps/cell (dt 0.020 tau)  0.100    0.540
      n = 128, 1 step/cell  (dt 0.040 tau)  0.080    0.560
      n = 128, 2 steps/cell (dt 0.020 tau)  0.100    0.560
      n = 256, 1 step/cell  (dt 0.020 tau)  0.100    0.560   (the seed's grid)
    Bands: case 3 in [0.06, 0.14] tau and case 4 in [0.45, 0.70] tau, the seed's values with a margin
    of two steps (dt = 0.02 tau) plus the spread between grids; case 4 later than case 3."""
    t3, t4 = (table3(c).attrs["t_gross_sliding"] / TAU for c in (3, 4))
    assert 0.06 <= t3 <= 0.14, t3
    assert 0.45 <= t4 <= 0.70, t4
    assert t4 > t3
    for c in (3, 4):  # partial slip until the onset, gross sliding from then on
        ds = table3(c)
        phase = ds["phase"].values
        onset = at(ds, ds.attrs["t_gross_sliding"] / TAU)
        assert np.all(phase[:onset] == 1) and np.all(phase[onset:] == 2)
        assert ds["stick_ratio"].values[0] > 0.3  # Cattaneo-Mindlin stick zone at first touch


def test_table3_steady_state_peak_lower_and_contact_shifted_back_after_partial_slip():
    """Seed §4.2: "When the contact is in the steady regime, a slight difference can be observed ... a
    lower peak pressure is observed for the case where partial slip has been experienced. Besides, the
    contacting region is slightly shifted in the direction opposite to the sliding motion".

    Measured at 1.5 tau (n = 64): peak 0.289 (case 1), 0.278 (case 3), 0.270 (case 4) p0; shift 0.447,
    0.407, 0.410 a0 (n = 256: peak 0.283, 0.266, 0.266; shift 0.447, 0.408, 0.410). "Slightly": peaks within 15 % and shifts within 0.1 a0 of case 1."""
    c1, c3, c4 = table3(1), table3(3), table3(4)
    for ds in (c3, c4):
        assert 0.85 * peak(c1)[-1] < peak(ds)[-1] < peak(c1)[-1]
        assert shift(c1)[-1] - 0.1 < shift(ds)[-1] < shift(c1)[-1]


def test_table3_partial_slip_delays_the_steady_state():
    """Seed, Conclusions: the partial slip regime "delays the time required by the viscoelastic sliding
    surface to reach its steady state". Time after which mu_app stays within 5 % of its 1.5 tau value;
    measured (n = 64): 0.38 (case 1), 0.38 (case 3), 0.66 tau (case 4); n = 256: 0.38, 0.38, 0.68. Case 3 slides from 0.1 tau and
    the seed itself finds it steady with cases 1 and 2 by 0.5-1 tau; case 4 slides only from 0.54 tau."""
    steady = {}
    for c in (1, 3, 4):
        ds = table3(c)
        steady[c] = time_to_steady(ds["mu_app"].values, ds["t"].values / TAU, 0.05)
    assert steady[3] >= steady[1]
    assert steady[4] > steady[1] + 0.1 and steady[4] > steady[3] + 0.1, steady


def test_table3_cases_3_and_4_reach_the_same_pressure():
    """Seed Fig. 9(e): "The overlap of pressure distribution curves is found for cases 3 and 4" at
    1.5 tau, while case 1 (frictionless) stays visibly different.

    Profiles along y = 0 in the indenter frame, run with one step per cell (n = 64, dt = 0.08 tau) so
    that both frames sit on the grid: with sub-cell frame offsets (4 steps per cell) the sharp leading
    edge falls at a different place within its cell in each case, which alone makes 20 % pointwise
    differences on this grid. Measured (n = 64, 1 step/cell, seed scheme): |p3 - p4| at most 3.7 % of
    the peak, 0.9 % in L1, against 10.7 % in L1 between cases 1 and 3 (n = 128: 5.4 %, 0.7 %, 9.9 %);
    loads equal to 0.4 %, shifts to 0.004 a0. With the linear scheme, which the time-step guard
    requires at this dt: 3.1 %, 0.7 %, 9.5 %, loads to 0.35 %, shifts to 0.0024 a0. Tolerances: 10 % pointwise (one cell at the spike), 3 % L1, a
    fifth of the case 1-3 difference, 2 % in load, 0.02 a0 in shift."""
    # one step per cell is dt = 0.08 tau, at which the seed's first-order scheme misses the early
    # relaxation under the held approach by 47 % (refused): the second-order scheme (5 %) compares them
    c1, c3, c4 = (simulate(f"seed_table3_case{c}", N_FAST, 1, time__scheme="linear") for c in (1, 3, 4))
    x = np.linspace(-3.0, 3.0, 601)
    p1, p3, p4 = (profile(ds, -1, x)[1] for ds in (c1, c3, c4))

    def l1(a: np.ndarray, b: np.ndarray) -> float:
        return float(np.sum(np.abs(a - b)) / np.sum(b))

    assert np.max(np.abs(p3 - p4)) < 0.10 * p3.max()
    assert l1(p4, p3) < 0.03
    assert l1(p4, p3) < 0.2 * l1(p1, p3)
    assert c4["load"].values[-1] == pytest.approx(c3["load"].values[-1], rel=0.02)
    assert abs(shift(c3)[-1] - shift(c4)[-1]) < 0.02


# --- Fig. 10: frictional sliding under a held load -----------------------------------------------------------
def test_fig10_contact_areas_stay_almost_equal():
    """Seed §4.2 (Fig. 10): "the contacting areas of the three cases almost remain identical regardless
    of the sliding states". Tolerance: (max - min)/mean < 5 % at every record; measured (n = 64):
    largest spread 2.8 % (at 0.05 tau), 0.6 % at 4 tau. On this grid one ring of cells around a
    contact of radius a0 is about 7 % of its area, so 5 % is below one ring."""
    runs = [simulate(f"seed_fig10_case{c}") for c in (1, 2, 3)]
    areas = np.array([ds["contact_area"].values for ds in runs])
    spread = (areas.max(axis=0) - areas.min(axis=0)) / areas.mean(axis=0)
    assert spread.max() < 0.05, spread.max()
    t_gs = runs[2].attrs["t_gross_sliding"] / TAU
    assert 0.1 < t_gs <= 0.2, t_gs  # seed: partial slip at 0.1 tau, gross sliding "just achieved" at 0.2 tau


# --- full resolution (the seed's 256 x 256) -----------------------------------------------------------------
@pytest.mark.slow
def test_table3_onset_full_resolution():
    """As test_table3_onset_of_gross_sliding on the seed's grid (n = 256, dt = 0.02 tau)."""
    t3, t4 = (table3(c, 256, 1).attrs["t_gross_sliding"] / TAU for c in (3, 4))
    assert 0.06 <= t3 <= 0.14, t3
    assert 0.45 <= t4 <= 0.70, t4


@pytest.mark.slow
def test_table1_full_resolution():
    """Table 1 orderings on the seed's grid (n = 256)."""
    runs = [table1(v, 256, 1) for v in SPEEDS]
    mu = [ds["mu_app"].values[-1] for ds in runs]
    assert mu[0] < mu[1] < mu[2]
    assert [shift(ds)[-1] for ds in runs] == sorted(shift(ds)[-1] for ds in runs)
    assert peak(runs[0])[-1] < peak(runs[1])[-1] < peak(runs[2])[-1]
    assert area(runs[0])[-1] > area(runs[1])[-1] > area(runs[2])[-1]
    for ds in runs:
        x_peak, middle = _leading_peak(ds, at(ds, 2.0))
        assert x_peak > middle
        assert abs(ds["mu_app"].values[-1] - ds["mu_app"].values[at(ds, 3.0)]) < 0.03 * ds["mu_app"].values[-1]
