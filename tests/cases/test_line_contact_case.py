"""The shipped line contact ``polymer_roller_line_contact``: from indentation through partial slip to
steady sliding, its apparent friction that of the steady state of the isolated cylinder.

Run at half its resolution (n = 512, a0 = 18 cells; dt doubles with the cell): measured mu_app at
t = 12 tau within 3e-4 of the steady solver's on the same grid, gross sliding from 1.7 ms, no wake
lost (wake_loss 0).
"""
import warnings

import pytest

from viscontact.errors import ViscontactWarning
from viscontact.io.case import load_case
from viscontact.io.shipped import shipped_case
from viscontact.running.api import run, run_steady


def test_polymer_roller_reaches_the_steady_state():
    case = load_case(shipped_case("polymer_roller_line_contact")).with_overrides({"grid.n": 512})
    assert case.grid.dimension == 1
    with warnings.catch_warnings():
        warnings.simplefilter("error", ViscontactWarning)  # no wake lost, no partial-slip warning
        ds = run(case)
        steady = run_steady(case)
    assert ds["pressure"].shape[1:] == (1, 512) and ds["load"].attrs["units"] == "N/m"
    assert 1e-3 < ds.attrs["t_gross_sliding"] < 3e-3
    assert float(ds["wake_loss"].max()) < 1e-3
    assert float(ds["mu_app"][-1]) == pytest.approx(float(steady["mu_app"].values.ravel()[0]), rel=2e-3)
    assert float(ds["contact_area"][-1]) == pytest.approx(float(steady["contact_area"].values.ravel()[0]),
                                                          abs=2 * 16e-3 / 512)


def test_the_command_line_runs_steadies_and_plots_a_line(tmp_path, capsys):
    """`viscontact run`, `steady` and `plot` on the shipped line case (n = 256): exit 0, the summary
    per unit length, a result with y of size 1, the line's figures (profiles, no maps)."""
    import xarray as xr

    from viscontact import cli

    case = str(shipped_case("polymer_roller_line_contact"))
    small = ["--set", "grid.n=256", "--set", "time.t_end=0.004"]
    assert cli.main(["run", case, "--out", str(tmp_path / "r.nc"), "--force", *small]) == 0
    said = capsys.readouterr()
    assert "2000 N/m" in said.out and "contact half-width A/2" in said.out
    with xr.open_dataset(tmp_path / "r.nc") as ds:
        assert ds.sizes["y"] == 1 and ds.sizes["x"] == 256 and ds.attrs["grid_dimension"] == 1
    assert cli.main(["steady", case, "--out", str(tmp_path / "s.nc"), "--force", *small]) == 0
    table = capsys.readouterr().out  # the steady table's column is the half-width A/2, not a radius
    assert "contact_half_width [m]" in table and "contact_radius" not in table
    assert cli.main(["plot", str(tmp_path / "r.nc"), "--out", str(tmp_path / "figs")]) == 0
    names = {p.name for p in (tmp_path / "figs").iterdir()}
    assert "pressure_profiles.png" in names and not any("map" in name or name.endswith(".gif") for name in names)
