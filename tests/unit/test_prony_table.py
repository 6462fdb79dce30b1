"""Prony tables from files (viscontact.io.prony_table) and the WLF shift (viscontact.physics.materials).

Truths: the same series typed in the case file (the reader must give the same material and the
same steady state, shear and tensile); G = E / (2 (1 + nu)) and G_inf = E_0 (1 - sum alpha_i)
worked by hand; the WLF formula worked by hand; and the shift identity of time-temperature
superposition: the steady state at temperature T and speed v is the one at T_ref and speed
v a_T, because the steady kernel only sees the decay lengths v lambda_m.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from viscontact.io.case import Case, load_case
from viscontact.errors import ParameterError
from viscontact.physics.materials import Material, wlf_shift_factor
from viscontact.io.results import global_attrs
from viscontact.solvers.steady import solve_steady

SCRIPT = Path(sys.executable).with_name("viscontact")
COMMAND = [str(SCRIPT)] if SCRIPT.exists() else [sys.executable, "-m", "viscontact.cli"]

# a 4-term series, tensile, in MPa (E_0 = 10 MPa); alpha_i = E_i / E_0
TAU = [1e-4, 1e-3, 1e-2, 1e-1]
ALPHA = [0.3, 0.2, 0.15, 0.1]
E0_MPA = 10.0
PYVISCO_E = ("i,tau_i,alpha_i,E_0,E_i\n-,s,-,MPa,MPa\n"
             + "".join(f"{k + 1},{t!r},{a!r},{E0_MPA!r},{a * E0_MPA!r}\n" for k, (t, a) in enumerate(zip(TAU, ALPHA))))

REST = """
[indenter]
shape = "sphere"
radius = 0.01

[grid]
n = 24
half_width = 1.2e-3

[normal]
control = "load"
value = 0.15

[tangential]
mode = "frictionless_sliding"
sliding_speed = 0.05

[time]
t_end = 0.01
"""


def case_with(material: str, tmp_path: Path, files: dict[str, str] | None = None, rest: str = REST) -> Case:
    for name, text in (files or {}).items():
        (tmp_path / name).write_text(text)
    (tmp_path / "case.toml").write_text("[material]\n" + material + rest)
    return load_case(tmp_path / "case.toml")


def typed(moduli_pa: list[float], long_term_pa: float, modulus: str, nu: float) -> str:
    return (f'type = "prony"\nmodulus = "{modulus}"\npoisson_ratio = {nu}\ng_inf = {long_term_pa!r}\n'
            f"g = {moduli_pa!r}\ntau = {TAU!r}\n")


@pytest.mark.parametrize("modulus", ["tensile", "shear"])
def test_pyvisco_table_equals_the_typed_series(tmp_path: Path, modulus: str) -> None:
    letter = "E" if modulus == "tensile" else "G"
    table = PYVISCO_E.replace("E_0,E_i", f"{letter}_0,{letter}_i")
    from_file = case_with(f'type = "prony"\nfile = "terms.csv"\nmodulus = "{modulus}"\npoisson_ratio = 0.4\n',
                          tmp_path, {"terms.csv": table})
    moduli = [a * E0_MPA * 1e6 for a in ALPHA]
    by_hand = case_with(typed(moduli, E0_MPA * 1e6 * (1 - sum(ALPHA)), modulus, 0.4), tmp_path)
    m_file, m_hand = from_file.to_problem().material, by_hand.to_problem().material
    np.testing.assert_allclose(m_file.g, m_hand.g, rtol=1e-15)
    np.testing.assert_allclose(m_file.g_inf, m_hand.g_inf, rtol=1e-14)
    assert m_file.tau == m_hand.tau
    factor = 2 * (1 + 0.4) if modulus == "tensile" else 1.0
    assert m_file.g_inf == pytest.approx(E0_MPA * 1e6 * (1 - sum(ALPHA)) / factor, rel=1e-14)
    assert m_file.shear_modulus_instantaneous == pytest.approx(E0_MPA * 1e6 / factor, rel=1e-14)
    steady_file = solve_steady(from_file.to_problem())
    steady_hand = solve_steady(by_hand.to_problem())
    np.testing.assert_allclose(steady_file.pressure, steady_hand.pressure, rtol=1e-12, atol=1e-9)
    assert steady_file.mu_app == pytest.approx(steady_hand.mu_app, rel=1e-12)


def test_plain_table_and_zero_terms(tmp_path: Path) -> None:
    text = "tau,g\ninf,1.0e5\n1e-3,2.0e5\n1e-2,0\n1e-1,3.0e5\n"   # the zero term is dropped
    case = case_with('type = "prony"\nfile = "plain.csv"\npoisson_ratio = 0.3\n', tmp_path, {"plain.csv": text})
    assert case.to_problem().material == Material.prony(1e5, [2e5, 3e5], [1e-3, 1e-1], 0.3)


def bad_table(change: tuple[str, str]) -> str:
    old, new = change
    assert old in PYVISCO_E
    return PYVISCO_E.replace(old, new, 1)


BAD_TABLES = {  # name: (file text, words the one-line message must hold)
    "missing_column": (bad_table((",alpha_i", ",beta_i")), ["terms.csv", "missing column alpha_i"]),
    "unknown_unit": (bad_table(("-,s,-,MPa,MPa", "-,s,-,psi,MPa")), ["terms.csv", "column E_0", "line 2", "psi"]),
    "negative": (bad_table(("4,0.1,0.1,10.0,1.0", "4,-0.1,0.1,10.0,1.0")), ["terms.csv", "column tau_i", "line 6"]),
    "sum_alpha": (bad_table(("4,0.1,0.1,10.0,1.0", "4,0.1,0.35,10.0,3.5")), ["terms.csv", "column alpha_i", "sum"]),
    "not_a_number": (bad_table(("3,0.01,0.15", "3,0.01,abc")), ["terms.csv", "column alpha_i", "line 5", "'abc'"]),
    "empty": ("\n", ["terms.csv", "empty"]),
    "no_units_row": ("\n".join(PYVISCO_E.splitlines()[::2]) + "\n", ["terms.csv", "line 2", "units"]),
}


@pytest.mark.parametrize("name", sorted(BAD_TABLES))
def test_bad_table_is_one_parameter_error(tmp_path: Path, name: str) -> None:
    text, words = BAD_TABLES[name]
    with pytest.raises(ParameterError) as err:
        case_with('type = "prony"\nfile = "terms.csv"\nmodulus = "tensile"\npoisson_ratio = 0.3\n', tmp_path,
                  {"terms.csv": text})
    assert err.value.key == "material.file"
    assert "\n" not in str(err.value)
    for word in words:
        assert word in str(err.value), (word, str(err.value))


def test_tensile_columns_need_modulus_tensile(tmp_path: Path) -> None:
    with pytest.raises(ParameterError, match="set modulus = 'tensile'") as err:
        case_with('type = "prony"\nfile = "terms.csv"\npoisson_ratio = 0.3\n', tmp_path, {"terms.csv": PYVISCO_E})
    assert err.value.key == "material.modulus"


@pytest.mark.parametrize("name", ["unknown_unit", "sum_alpha", "missing_file"])
def test_bad_table_through_the_cli(tmp_path: Path, name: str) -> None:
    material = 'type = "prony"\nfile = "terms.csv"\nmodulus = "tensile"\npoisson_ratio = 0.3\n'
    if name != "missing_file":
        (tmp_path / "terms.csv").write_text(BAD_TABLES[name][0])
    (tmp_path / "case.toml").write_text("[material]\n" + material + REST)
    proc = subprocess.run([*COMMAND, "run", "case.toml", "--out", "out.nc"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=300, check=False)
    assert proc.returncode == 2, proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("viscontact: error: material.file: "), proc.stderr
    assert "terms.csv" in lines[0] and "Traceback" not in proc.stderr
    assert not (tmp_path / "out.nc").exists()


# --- WLF --------------------------------------------------------------------------------------
WLF = "temperature = {t}\nreference_temperature = 20.0\nwlf_c1 = 17.44\nwlf_c2 = 51.6\n"
SERIES = typed([2e5, 3e5, 1e5, 4e5], 1e5, "shear", 0.3)


def test_wlf_shift_factor_by_hand() -> None:
    assert wlf_shift_factor(20.0, 20.0, 17.44, 51.6) == 1.0
    assert wlf_shift_factor(30.0, 20.0, 17.44, 51.6) == pytest.approx(10 ** (-174.4 / 61.6), rel=1e-14)
    assert wlf_shift_factor(0.0, 20.0, 17.44, 51.6) == pytest.approx(10 ** (348.8 / 31.6), rel=1e-14)
    with pytest.raises(ParameterError, match="> -wlf_c2") as err:
        wlf_shift_factor(-31.6, 20.0, 17.44, 51.6)
    assert err.value.key == "material.temperature"


def test_wlf_below_the_divergence_is_a_case_error(tmp_path: Path) -> None:
    with pytest.raises(ParameterError, match="diverges") as err:
        case_with(SERIES + WLF.format(t=-40.0), tmp_path)
    assert err.value.key == "material.temperature"
    with pytest.raises(ParameterError, match="required with material.temperature") as err:
        case_with(SERIES + "temperature = 30.0\n", tmp_path)
    assert err.value.key == "material.reference_temperature"


def test_shift_scales_every_time_and_is_recorded(tmp_path: Path) -> None:
    warm = case_with(SERIES + WLF.format(t=35.0), tmp_path).to_problem()
    ref = case_with(SERIES, tmp_path).to_problem()
    a_t = wlf_shift_factor(35.0, 20.0, 17.44, 51.6)
    np.testing.assert_allclose(warm.material.tau, np.asarray(ref.material.tau) * a_t, rtol=1e-15)
    np.testing.assert_allclose(warm.material.creep.retardation_times, ref.material.creep.retardation_times * a_t,
                               rtol=1e-12)
    np.testing.assert_allclose(warm.material.creep.amplitudes, ref.material.creep.amplitudes, rtol=1e-12)
    assert global_attrs(warm)["a_T"] == pytest.approx(a_t, rel=1e-15)
    assert global_attrs(ref)["a_T"] == 1.0


def test_steady_state_shift_identity(tmp_path: Path) -> None:
    """Steady state at T and speed v == steady state at T_ref and speed v a_T, to round-off. The
    domain (+-3 mm) holds the slow contact (a(G_inf) = 1.7 mm): on +-1.2 mm it covered the grid."""
    rest = REST.replace("half_width = 1.2e-3", "half_width = 3.0e-3")
    warm = case_with(SERIES + WLF.format(t=26.0), tmp_path, rest=rest).to_problem()
    ref = case_with(SERIES, tmp_path, rest=rest).to_problem()
    a_t = warm.material.shift_factor
    assert 0.01 < a_t < 0.1  # a real shift: two orders of magnitude in speed between the two
    v = 0.05
    at_t = solve_steady(warm, v)
    at_ref = solve_steady(ref, v * a_t)
    at_ref_unshifted = solve_steady(ref, v)
    np.testing.assert_allclose(at_t.pressure, at_ref.pressure, rtol=1e-9, atol=1e-9 * at_ref.pressure.max())
    assert at_t.mu_app == pytest.approx(at_ref.mu_app, rel=1e-9)
    assert abs(at_ref_unshifted.mu_app - at_ref.mu_app) > 0.1 * at_ref.mu_app  # the shift matters


def test_rounded_alpha_that_shift_the_long_term_modulus_are_refused(tmp_path: Path) -> None:
    """E(0)/E(inf) = 1e5 with alpha_i written to 7 digits and E_i exact: E_0 (1 - sum alpha_i) was
    taken as E(inf), 0.5 % below E_0 - sum E_i (5 % at 1e6). The two must agree to 1e-3; the same
    table with alpha_i at full precision reads, E(inf) = 20000 Pa."""
    taus = [float(t) for t in np.logspace(-3, 6, 10)]
    e0, e_inf = 2000.0, 2000.0e-5  # MPa
    weights = np.random.default_rng(1).random(10) + 0.5  # their 7-digit roundings add up to 1e-7 of E_0
    moduli = [float(m) for m in (e0 - e_inf) * weights / weights.sum()]
    material_keys = 'type = "prony"\nfile = "terms.csv"\nmodulus = "tensile"\npoisson_ratio = 0.3\n'

    def table(alpha) -> str:
        rows = [f"{i + 1},{t!r},{alpha(m / e0)},{e0!r},{m!r}" for i, (t, m) in enumerate(zip(taus, moduli))]
        return "i,tau_i,alpha_i,E_0,E_i\n-,s,-,MPa,MPa\n" + "\n".join(rows) + "\n"

    with pytest.raises(ParameterError, match=r"E_0 \(1 - sum alpha_i\) = 19800 Pa and E_0 - sum E_i "
                                             r"= 20000 Pa differ by more than 0.001"):
        case_with(material_keys, tmp_path, {"terms.csv": table(lambda a: f"{a:.7f}")})
    material = case_with(material_keys, tmp_path, {"terms.csv": table(repr)}).to_problem().material
    assert material.shear_modulus_long_term == pytest.approx(e_inf * 1e6 / 2.6, rel=1e-9)  # G = E / (2 (1 + nu))


@pytest.mark.parametrize("text, words", [
    ("tau,g\ninf,0.193e6\n0.001,1_000\n", "'1_000' is not a number"),  # Python's float reads it as 1000
    ("tau,g\ninf,0.193e6\n1e400,1000\n", "'1e400' is out of range"),  # was a second long-term row (inf)
    ("tau,g,tau\ninf,0.193e6,1\n0.01,1000,2\n", "column tau appears 2 times"),  # the first was used
])
def test_numbers_and_columns_python_would_read_otherwise(tmp_path: Path, text: str, words: str) -> None:
    with pytest.raises(ParameterError, match=words):
        case_with('type = "prony"\nfile = "terms.csv"\npoisson_ratio = 0.3\n', tmp_path, {"terms.csv": text})


def test_a_row_with_an_extra_column_is_refused():
    """Issue 34 item 9: a Prony row with an extra column was accepted without a word."""
    import pytest

    from viscontact.errors import ParameterError
    from viscontact.io.prony_table import parse_prony_table

    with pytest.raises(ParameterError, match=r"line 3 has 3 columns, more than the 2 named in line 1"):
        parse_prony_table("tau,g\ninf,1e5\n0.1,2e5,7\n")
    assert parse_prony_table("tau,g\ninf,1e5\n0.1,2e5,\n").moduli == (2e5,)  # an empty trailing cell is none
