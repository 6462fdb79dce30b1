"""Small things a new user tripped over (issue 33): ``plot --times 0``, what ``reproduce --help``
and ``plot --help`` say, and the README's first screen."""
from __future__ import annotations

from pathlib import Path

import pytest

from test_results import fake_records, make_problem  # tests/unit is on sys.path

from viscontact import cli
from viscontact.io.netcdf import write_netcdf
from viscontact.io.results import to_dataset

ROOT = Path(__file__).resolve().parents[2]


def test_plot_takes_t_0_and_refuses_a_negative_time(tmp_path, capsys):
    problem = make_problem()
    write_netcdf(to_dataset(fake_records(problem), problem), tmp_path / "r.nc")
    assert cli.main(["plot", str(tmp_path / "r.nc"), "--out", str(tmp_path / "figs"), "--times", "0,0.002"]) == 0
    assert (tmp_path / "figs" / "pressure_maps.png").exists()
    capsys.readouterr()
    assert cli.main(["plot", str(tmp_path / "r.nc"), "--out", str(tmp_path / "figs"), "--times", "-0.001"]) == 2
    assert "--times: every value must be a finite number >= 0 s" in capsys.readouterr().err


@pytest.mark.parametrize("command, words", [
    ("reproduce", ["fig4   frictionless sliding at 0.4, 0.8, 1.2 a0/tau", "fig9 ", "fig10 ", "stick/slip"]),
    ("plot", ["RESULT.nc             result file of viscontact run, steady or sweep", "t = 0 included"]),
    ("export", ["--csv OUT.csv", "names the columns"]),
    ("run", ["--json"])])
def test_the_help_says_what_it_takes_and_shows(command, words, capsys):
    with pytest.raises(SystemExit):
        cli.main([command, "--help"])
    said = " ".join(capsys.readouterr().out.split(" \n"))
    for w in words:
        assert w in said, (w, said)


def test_the_readme_starts_with_its_title_and_the_two_commands_then_what_it_is():
    lines = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()
    assert lines[:6] == ["# viscontact", "", "```", "make demo", "make test", "```"]
    first_paragraph = lines[7]
    assert first_paragraph.startswith("**viscontact** computes"), first_paragraph
    assert len(lines) < 150  # a tour, not the reference: the details are in docs/
