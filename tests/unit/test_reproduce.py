"""``viscontact reproduce``: the time scale comes from the material, and a figure is run, saved,
reused and drawn end to end (on tiny copies of the shipped cases)."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from viscontact import cli
from viscontact.io.case import load_case
from viscontact.errors import ParameterError
from viscontact.running.guards import TIME_WARNING_LIMIT
from viscontact.solvers.time_step_error import time_step_error
from viscontact.problem.problem import PHASE_GROSS_SLIDING
from viscontact.reproduce import FIGURES, find_cases_dir, load_seed_case, record_every, run_seed_cases, time_scale
from viscontact.io.netcdf import open_result
from viscontact.numerics.schemes import amplification, stable_step_limit

from vc_testing import SEED_G0, SEED_GINF, SEED_NU

CASES = Path(__file__).resolve().parents[2] / "cases"
LAMBDA = 4e-3  # s, a retardation time other than the seed's 0.01 s


def _zener_and_prony():
    """The seed's Table 1 case with the same Zener material (retardation time LAMBDA) written as a
    Zener and as its one-term Prony series (relaxation time LAMBDA G(inf)/G(0))."""
    base = load_case(CASES / "seed_table1_v0.8.toml").with_overrides({"grid.n": 64})
    zener = base.with_overrides({"material.retardation_time": LAMBDA})
    prony = base.with_overrides({"material": {
        "type": "prony", "g_inf": SEED_GINF, "g": [SEED_G0 - SEED_GINF], "tau": [LAMBDA * SEED_GINF / SEED_G0],
        "poisson_ratio": SEED_NU}})
    return zener, prony


def test_time_scale_is_the_materials_retardation_time_whatever_its_type():
    zener, prony = _zener_and_prony()
    assert time_scale(zener) == pytest.approx(LAMBDA, rel=1e-12)
    assert time_scale(prony) == pytest.approx(LAMBDA, rel=1e-9)
    times = FIGURES["fig4"].times
    assert record_every(prony, times) == record_every(zener, times)
    # the stride records every requested time exactly
    every, dt = record_every(prony, times), prony.default_dt()
    for t in times:
        assert (t * LAMBDA / dt) % every == pytest.approx(0, abs=1e-6)


def test_elastic_material_has_no_time_scale():
    elastic = load_case(CASES / "seed_table1_v0.8.toml").with_overrides({"material": {
        "type": "elastic", "shear_modulus": SEED_G0, "poisson_ratio": SEED_NU}})
    with pytest.raises(ParameterError) as err:
        time_scale(elastic)
    assert err.value.key == "material.type"


@pytest.fixture(scope="module")
def tiny_cases(tmp_path_factory) -> Path:
    """The cases of fig10 (and the marker case) at n = 16 with the linear scheme (the seed's constant
    scheme is unstable at the coarse dt = dx/v of so small a grid) and two steps per cell (one misses
    the creep by 23 %: refused by viscontact.running.guards)."""
    folder = tmp_path_factory.mktemp("cases")
    for name in ("seed_table1_v0.8", *FIGURES["fig10"].cases):
        text = (CASES / f"{name}.toml").read_text().replace("\nn = 256", "\nn = 16")
        assert '\nscheme = "constant"' in text  # the seed cases state the seed's scheme
        text = text.replace("[tangential]\n", "[tangential]\nsteps_per_cell = 2\n")
        (folder / f"{name}.toml").write_text(text.replace('\nscheme = "constant"', '\nscheme = "linear"'))
    return folder


def test_reproduce_runs_saves_reuses_and_draws(tiny_cases, tmp_path, capsys):
    out = tmp_path / "fig10"
    assert cli.main(["reproduce", "fig10", "--out", str(out), "--cases", str(tiny_cases), "--format", "svg",
                     "--set", "tangential.friction_coefficient=0.4", "--set", "tangential.displacement_rate=0.02"]) == 0
    paths = [Path(line) for line in capsys.readouterr().out.splitlines()[:-1]]
    assert [p.name for p in paths] == ["fig10.svg", "fig10_seed_fig10_case3_stick_map.svg",
                                       "seed_fig10_case1.nc", "seed_fig10_case2.nc", "seed_fig10_case3.nc"]
    assert all(p.stat().st_size > 1000 for p in paths)
    ds = open_result(out / "seed_fig10_case3.nc")
    assert ds.attrs["complete"] == 1 and ds.sizes["y"] == 16
    assert ds.attrs["friction_coefficient"] == 0.4 and ds.attrs["displacement_rate"] == 0.02   # --set
    assert ds["phase"].values[-1] == PHASE_GROSS_SLIDING                      # the partial-slip case slides
    # running the figure's cases again reuses every saved result (computed from the same case text)
    stamps = {p: p.stat().st_mtime_ns for p in paths if p.suffix == ".nc"}
    runs = run_seed_cases(FIGURES["fig10"].cases, out, times_tau=FIGURES["fig10"].times, cases_dir=tiny_cases,
                          overrides={"tangential.friction_coefficient": 0.4, "tangential.displacement_rate": 0.02})
    assert {p: p.stat().st_mtime_ns for p in stamps} == stamps
    assert float(runs["seed_fig10_case3"]["mu_app"][-1]) == float(ds["mu_app"][-1])


def test_reproduce_refuses_a_bad_grid_in_one_line(tiny_cases, tmp_path, capsys):
    assert cli.main(["reproduce", "fig10", "--out", str(tmp_path), "--n", "4", "--cases", str(tiny_cases)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("viscontact: error: --n: ")
    assert list(tmp_path.iterdir()) == []


def test_cases_dir_is_found_or_named():
    assert find_cases_dir(CASES) == CASES
    with pytest.raises(ParameterError) as err:
        find_cases_dir(CASES / "sweeps")
    assert err.value.key == "--cases"


SEED_CASES = sorted({name for spec in FIGURES.values() for name in spec.cases})


@pytest.mark.parametrize("n", [32, 64])
def test_previews_keep_the_seed_scheme_well_inside_its_stability_limit(n):
    """At --n 32 and 64 the grid's dt = dx/v is near or over the constant scheme's limit (2.23 ms
    for G(0)/G(inf) = 10; the Table 1 cases at n = 32: 4 ms). Each such case gets more steps per
    cell and is named. Then the scheme's factor per step on a disturbance of the seed's one-mode
    (Zener) materials, z = A (1 + r) - r with A = exp(-dt/lambda), r = G(0)/G(inf) - 1 (seed scheme,
    traction constant over the step), is > -0.5: an oscillation (z < 0) at least halves each step."""
    adapted = []
    for name in SEED_CASES:
        case, note = load_seed_case(name, CASES, n, ())
        material = case.material.build()
        dt = case.default_dt()
        assert dt <= 0.5 * stable_step_limit(material.creep, "constant") * (1 + 1e-9), name
        r = material.shear_modulus_instantaneous / material.shear_modulus_long_term - 1
        z = np.exp(-dt / material.creep.retardation_times[0]) * (1 + r) - r
        assert -0.5 < z < 1 and abs(z) == pytest.approx(amplification(material.creep, dt, "constant"), rel=1e-9), name
        if note:
            adapted.append(name)
            assert note.startswith("tangential.steps_per_cell = ") and (
                "stability limit" in note or "misses the material's response" in note)
            assert case.tangential.steps_per_cell > 1
        else:
            assert case.tangential.steps_per_cell == 1
        # and the time-step guard (viscontact.running.guards) neither refuses nor warns about the preview
        assert time_step_error(case.to_problem()) <= TIME_WARNING_LIMIT, name
    assert "seed_table1_v0.4" in adapted                        # dt = 4 ms (n = 32), 2 ms (n = 64)
    # the linear scheme is stable for any dt: only the accuracy of the step can adapt it
    case, note = load_seed_case("seed_table1_v0.4", CASES, 32, (), {"time.scheme": "linear"})
    assert "stability limit" not in note and time_step_error(case.to_problem()) <= TIME_WARNING_LIMIT


def test_set_reaches_every_case_and_names_a_bad_key():
    case, _ = load_seed_case("seed_fig10_case2", CASES, 32, (), {"material.shear_modulus_long_term": 0.643e6})
    assert case.material.shear_modulus_long_term == 0.643e6
    with pytest.raises(ParameterError) as err:
        load_seed_case("seed_fig10_case2", CASES, 32, (), {"material.shear_modulus_long_trem": 1.0})
    assert err.value.key == "material.shear_modulus_long_trem" and "seed_fig10_case2" in err.value.message


def test_reproduce_checks_every_result_path_before_the_first_case(tiny_cases, tmp_path, capsys):
    """Red team item 11: a foreign result in the way of the first case was replaced and the second
    refused only after the first was computed, with a message naming a --force reproduce lacks."""
    import xarray as xr

    first, second, third = (tmp_path / f"{name}.nc" for name in FIGURES["fig10"].cases)
    xr.Dataset({"load": ("t", [1.0])}, attrs={"case": "title = 'my own run'\n", "version": "0.1.0"}).to_netcdf(first)
    second.write_text("my notes")
    before = {path: path.read_bytes() for path in (first, second)}
    assert cli.main(["reproduce", "fig10", "--out", str(tmp_path), "--cases", str(tiny_cases), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"viscontact: error: {first}: exists and is not a result of the "
                                               "shipped case seed_fig10_case1") and "--force" not in err[0]
    assert {path: path.read_bytes() for path in before} == before and not third.exists()
    first.unlink()
    assert cli.main(["reproduce", "fig10", "--out", str(tmp_path), "--cases", str(tiny_cases), "--quiet"]) == 2
    assert str(second) in capsys.readouterr().err and not first.exists() and not third.exists()


def test_reproduce_replaces_its_own_results_at_any_grid(tiny_cases, tmp_path):
    """A result reproduce saved (attribute written_by) of the same shipped case (its case text,
    overrides appended) is reproduce's own."""
    import xarray as xr

    from viscontact.reproduce.runner import check_outputs

    name = "seed_fig10_case1"
    text = (tiny_cases / f"{name}.toml").read_text()
    case, _ = load_seed_case(name, tiny_cases, 24, ())
    assert case.text != text and case.text.startswith(text.rstrip("\n"))
    path = tmp_path / f"{name}.nc"
    xr.Dataset({"load": ("t", [1.0])}, attrs={"case": case.text, "version": "0.1.0",
                                              "written_by": "viscontact reproduce"}).to_netcdf(path)
    assert check_outputs(tmp_path, {name: text}, [tiny_cases / f"{name}.toml"]) == {name: path}
    with pytest.raises(FileExistsError, match="not a result of the shipped case seed_fig10_case1"):
        check_outputs(tmp_path, {name: "# another case file\n" + text}, [])


def test_reproduce_never_replaces_a_run_of_the_shipped_case_it_did_not_save(tiny_cases, tmp_path, capsys):
    """Red team round 2, item 4: the user's own `viscontact run` of a shipped case (a finer grid, hours
    at the seed's 256^2) at the path reproduce saves that case to is refused in one line before any
    case runs, and kept byte for byte; a result reproduce saved there itself is replaced."""
    first, second, third = (tmp_path / f"{name}.nc" for name in FIGURES["fig10"].cases)
    assert cli.main(["run", str(tiny_cases / f"{first.stem}.toml"), "--out", str(first), "--set", "grid.n=24",
                     "--quiet"]) == 0
    before = first.read_bytes()
    reproduce = ["reproduce", "fig10", "--out", str(tmp_path), "--cases", str(tiny_cases), "--quiet"]
    assert cli.main(reproduce) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"viscontact: error: {first}: exists and is not a result of the shipped case {first.stem} saved "
                   "by reproduce; reproduce replaces only its own results: move it or choose another --out"]
    assert first.read_bytes() == before and not second.exists() and not third.exists()
    first.unlink()
    assert cli.main(reproduce) == 0  # n = 16
    assert open_result(first).attrs["written_by"] == "viscontact reproduce"
    assert cli.main([*reproduce, "--set", "tangential.friction_coefficient=0.4"]) == 0  # its own, replaced
    for path in (first, second, third):
        ds = open_result(path)
        assert "friction_coefficient = 0.4" in ds.attrs["case"] and ds.attrs["written_by"] == "viscontact reproduce"


@pytest.mark.parametrize("value", ["abc", 48])
def test_a_grid_size_set_twice_is_refused(value):
    """``reproduce --n 32 --set grid.n=abc`` ran at 32 cells, the --set value ignored unchecked."""
    with pytest.raises(ParameterError, match="contradicts --n 32") as err:
        load_seed_case("seed_table1_v0.8", find_cases_dir(None), 32, (), {"grid.n": value})
    assert err.value.key == "--set"
    case, _ = load_seed_case("seed_table1_v0.8", find_cases_dir(None), 32, (), {"grid.n": 32})  # said twice alike
    assert case.grid.n == 32
