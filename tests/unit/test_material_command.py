"""``viscontact material``: the summary of an imported series and its figure; the material functions
it plots (results.material_dataset) against their closed forms."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from viscontact import cli
from viscontact.physics.materials import Material, wlf_shift_factor
from viscontact.io.results import material_dataset

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = Path(sys.executable).with_name("viscontact")
COMMAND = [str(SCRIPT)] if SCRIPT.exists() else [sys.executable, "-m", "viscontact.cli"]

CASE = """
[material]
type = "prony"
file = "terms.csv"
modulus = "tensile"
poisson_ratio = 0.5
temperature = 30.0
reference_temperature = 20.0
wlf_c1 = 17.44
wlf_c2 = 51.6

[indenter]
shape = "sphere"
radius = 0.01

[grid]
n = 16
half_width = 1e-3

[normal]
control = "load"
value = 0.15

[time]
t_end = 0.01
dt = 0.001
"""
TABLE = "i,tau_i,alpha_i,E_0,E_i\n-,s,-,MPa,MPa\n1,0.001,0.5,3.0,1.5\n2,0.1,0.25,3.0,0.75\n"


def test_material_command_prints_the_summary_and_draws(tmp_path: Path) -> None:
    (tmp_path / "case.toml").write_text(CASE)
    (tmp_path / "terms.csv").write_text(TABLE)
    proc = subprocess.run([*COMMAND, "material", "case.toml", "--plots", "figs"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=300, check=False)
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    # E_0 = 3 MPa, nu = 0.5: G(0) = 1 MPa, G(inf) = 1 MPa x (1 - 0.75) = 0.25 MPa
    assert "G(0) = 1e+06 Pa, G(inf) = 250000 Pa" in out, out
    a_t = wlf_shift_factor(30.0, 20.0, 17.44, 51.6)
    assert f"a_T = {a_t:.6g} at temperature = 30 degC" in out, out
    assert f"relaxation times [s]: {1e-3 * a_t:.4g} {0.1 * a_t:.4g}" in out, out
    assert (tmp_path / "figs" / "material.png").stat().st_size > 10_000


def test_material_dataset_against_closed_forms() -> None:
    m = Material.zener(1.93e6, 0.193e6, 0.01, 0.3)
    ds = material_dataset(m)
    t, w = ds["t"].values, ds["omega"].values
    g0, ginf, tau, lam = 1.93e6, 0.193e6, 1e-3, 0.01
    np.testing.assert_allclose(ds["relaxation_modulus"], ginf + (g0 - ginf) * np.exp(-t / tau), rtol=1e-13)
    np.testing.assert_allclose(ds["creep_compliance"], 1 / g0 + (1 / ginf - 1 / g0) * (1 - np.exp(-t / lam)),
                               rtol=1e-12)
    wt = w * tau
    np.testing.assert_allclose(ds["storage_modulus"], ginf + (g0 - ginf) * wt**2 / (1 + wt**2), rtol=1e-13)
    np.testing.assert_allclose(ds["tan_delta"], (g0 - ginf) * wt / (ginf + g0 * wt**2), rtol=1e-12)
    assert t[0] == pytest.approx(1e-6) and t[-1] == pytest.approx(10.0)
    assert ds.attrs["kind"] == "material" and ds.attrs["a_T"] == 1.0


def test_a_bulk_modulus_material_shows_its_poisson_ratio_in_time(capsys):
    """With bulk_modulus the command printed nu(0) as a constant poisson_ratio; it names K and nu(t)'s
    two ends (nu = (3K - 2G) / (2 (3K + G)) with G(0) and G(inf))."""
    g0, ginf, k = 1.93e6, 0.193e6, 5e6
    code = cli.main(["material", str(ROOT / "cases" / "creep_indentation.toml"), "--set", "material.bulk_modulus=5e6",
                     "--set", "material.poisson_ratio="])
    line = capsys.readouterr().out.splitlines()[0]
    nu = [(3 * k - 2 * g) / (2 * (3 * k + g)) for g in (g0, ginf)]
    assert code == 0 and "bulk_modulus K = 5e+06 Pa" in line
    assert f"from {nu[0]:.6g} (t = 0) to {nu[1]:.6g} (t = inf)" in line


def test_material_figure_takes_format_and_dpi(tmp_path: Path, capsys) -> None:
    """``material --plots`` takes ``--format`` and ``--dpi`` as every other command that draws (it had
    neither: "unrecognized arguments"); a bad one is refused in one line before anything is drawn."""
    case = str(ROOT / "cases" / "creep_indentation.toml")
    assert cli.main(["material", case, "--plots", str(tmp_path / "figs"), "--format", "svg", "--dpi", "50"]) == 0
    assert [p.name for p in (tmp_path / "figs").iterdir()] == ["material.svg"]
    capsys.readouterr()
    assert cli.main(["material", case, "--plots", str(tmp_path / "bad"), "--dpi", "5"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("viscontact: error: --dpi: "), err
    assert not (tmp_path / "bad").exists()
