"""What a run, a steady speed curve and a sweep print when they end (:mod:`viscontact.running.summary`)
and the tables of a result (:mod:`viscontact.io.export`, ``viscontact export``)."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from test_results import fake_records, make_problem  # tests/unit is on sys.path

from viscontact import cli
from viscontact.io.export import ResultFile, table, write_csv
from viscontact.io.netcdf import open_result, write_netcdf
from viscontact.io.results import sweep_dataset, to_dataset
from viscontact.running.summary import SETTLED, format_summary, steady_mu_app, summary, summary_of_file

CREEP = Path(__file__).resolve().parents[2] / "src" / "viscontact" / "cases" / "creep_indentation.toml"
SMALL = ["--set", "grid.n=16", "--set", "time.t_end=0.002"]


@pytest.fixture(scope="module")
def creep_result(tmp_path_factory):
    out = tmp_path_factory.mktemp("creep") / "r.nc"
    assert cli.main(["run", str(CREEP), "--out", str(out), "--quiet", *SMALL]) == 0
    return out


def test_run_prints_what_it_wrote_and_its_headline_numbers_with_units(tmp_path, capsys):
    out = tmp_path / "r.nc"
    assert cli.main(["run", str(CREEP), "--out", str(out), *SMALL]) == 0
    said = capsys.readouterr().out.splitlines()
    assert said[0].startswith(f"wrote {out} (") and "records" in said[0]
    text = "\n".join(said[1:])
    for words in ("final time", "approach delta_z", " m  (", "contact radius sqrt(A/pi)", "peak pressure", " Pa"):
        assert words in text, text
    assert "mu_app" not in text  # zero by definition without tangential motion


def test_json_is_one_object_on_stdout_even_quiet_and_quiet_alone_is_silent(tmp_path, capsys):
    out = tmp_path / "r.nc"
    assert cli.main(["run", str(CREEP), "--out", str(out), "--quiet", "--json", *SMALL]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["kind"] == "run" and s["complete"] and s["files"] == [str(out)]
    ds = open_result(out)
    assert s["values"]["delta_z"] == float(ds["delta_z"][-1]) and s["units"]["delta_z"] == "m"
    assert s["values"]["contact_radius"] == pytest.approx(math.sqrt(float(ds["contact_area"][-1]) / math.pi))
    assert s["values"]["peak_pressure"] == float(ds["pressure"][-1].max()) and s["units"]["peak_pressure"] == "Pa"
    assert cli.main(["run", str(CREEP), "--out", str(out), "--quiet", "--force", *SMALL]) == 0
    assert capsys.readouterr().out == ""


def test_the_summary_of_a_file_read_without_xarray_is_that_of_its_dataset(creep_result):
    from_file = summary_of_file(creep_result)
    assert from_file.pop("file") == str(creep_result)
    assert from_file == summary(open_result(creep_result))


def test_summary_of_a_partial_slip_run_and_of_a_steady_speed_curve(tmp_path):
    problem = make_problem()
    records = fake_records(problem)
    s = summary(to_dataset(records, problem))
    assert s["values"]["mu_app"] == 0.02 and s["values"]["friction_force"] == 0.01
    assert s["values"]["t_gross_sliding"] == records[3].t and s["units"]["t_gross_sliding"] == "s"
    assert "mu_app_steady" not in s["values"]  # 2 records of sliding: too few to say
    curve = summary(sweep_dataset(records[:2], [0.01, 0.1], problem))
    assert curve["kind"] == "steady" and [r["speed"] for r in curve["rows"]] == [0.01, 0.1]
    assert curve["units"]["speed"] == "m/s" and "mu_app" in format_summary(curve).splitlines()[1]


def test_steady_mu_app_is_the_mean_of_the_last_quarter_of_sliding_once_settled():
    t = np.arange(40.0)
    settled = 0.03 * (1 - np.exp(-t / 3))
    mean, change = steady_mu_app(t, settled, 8.0)
    assert change <= SETTLED and mean == pytest.approx(0.03, rel=1e-3)
    mean, change = steady_mu_app(t, 0.001 * t, 8.0)
    assert change > SETTLED
    assert math.isnan(steady_mu_app(t, settled, math.nan)[0])


def test_export_writes_the_series_with_names_and_units_and_refuses_to_overwrite(creep_result, tmp_path, capsys):
    pd = pytest.importorskip("pandas")
    out = tmp_path / "r.csv"
    assert cli.main(["export", str(creep_result), "--csv", str(out)]) == 0
    ds = open_result(creep_result)
    read = pd.read_csv(out)
    assert list(read.columns[:6]) == ["t [s]", "step", "load [N]", "delta_z [m]", "delta_x [m]",
                                      "sliding_distance [m]"]
    assert "mu_app [1]" in read.columns and "friction_force [N]" in read.columns
    np.testing.assert_array_equal(read["delta_z [m]"].to_numpy(), ds["delta_z"].values)  # exactly
    np.testing.assert_array_equal(read["t [s]"].to_numpy(), ds["t"].values)
    capsys.readouterr()
    assert cli.main(["export", str(creep_result), "--csv", str(out)]) == 2
    assert "--force" in capsys.readouterr().err
    assert cli.main(["export", str(creep_result), "--csv", str(out), "--force"]) == 0
    assert cli.main(["export", str(creep_result), "--csv", str(tmp_path / "r.txt")]) == 2
    assert "*.csv" in capsys.readouterr().err


def test_the_table_of_a_file_read_without_xarray_and_of_a_steady_curve(creep_result, tmp_path):
    with ResultFile(creep_result) as f:
        light, light_units = table(f)
    full, units = table(open_result(creep_result))
    assert set(light) == set(full) and light_units == units
    for name in full:
        np.testing.assert_array_equal(light[name], full[name])
    problem = make_problem()
    curve = sweep_dataset(fake_records(problem)[:2], [0.01, 0.1], problem)
    columns, units = table(curve)
    assert list(columns)[:2] == ["speed", "deborah"] and units["speed"] == "m/s" and "pressure" not in columns
    write_netcdf(curve, tmp_path / "c.nc")
    assert write_csv(open_result(tmp_path / "c.nc"), tmp_path / "c.csv").read_text().startswith(
        "speed [m/s],deborah [1],mu_app [1],")
