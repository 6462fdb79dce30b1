"""Results: fake solver records -> Dataset -> netCDF and back; plots from a Dataset."""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from vc_testing import SEED_A0, SEED_G0, SEED_LOAD, SEED_NU, SEED_P0, SEED_RADIUS, seed_material, sphere_problem

from viscontact.problem.problem import NormalLoading, PiecewiseLinear, Problem
from viscontact.problem.records import StepRecord
from viscontact.physics.reference import hertz_from_load
from viscontact.io.netcdf import open_result, write_netcdf
from viscontact.io.results import sweep_dataset, to_dataset

CONTRACT_VARIABLES = ("pressure", "shear_x", "stick", "load", "delta_z", "delta_x", "sliding_distance",
                      "contact_area", "stick_ratio", "phase", "friction_force", "hysteresis_force", "mu_app")
N = 32


def make_problem(mode: str = "partial_slip", fields: tuple[str, ...] = ("pressure", "shear_x", "stick")) -> Problem:
    return sphere_problem(seed_material(), N, 2e-3,  # holds and resolves the contact (viscontact.running.guards)
                          mode=mode, friction=0.3, rate=0.01, speed=0.05, t_end=0.004,
                          dt=1e-3, fields=fields, title="fake")


def fake_records(problem: Problem, phases: tuple[int, ...] = (0, 1, 1, 2, 2)) -> list[StepRecord]:
    rng = np.random.default_rng(0)
    out = []
    for k, phase in enumerate(phases):
        p = rng.random((N, N)) * 1e5
        out.append(StepRecord(step=k, t=k * problem.time.dt, phase=phase, load=SEED_LOAD, delta_z=3e-5 + k * 1e-6,
                              delta_x=k * 1e-6, sliding_distance=0.0, contact_area=1e-6 * (1 + k),
                              stick_ratio=0.5, friction_force=0.01, hysteresis_force=0.003, mu_app=0.02,
                              contact_shift=-1e-6 * k, pressure=p, shear_x=0.3 * p, stick=p > 5e4,
                              displacement_z=None))
    return out


def test_dataset_has_the_contract() -> None:
    problem = make_problem()
    records = fake_records(problem)
    ds = to_dataset(records, problem, case_text="title = 'x'", attrs={"extra": 7})
    assert dict(ds.sizes) == {"t": 5, "y": N, "x": N}
    for name in CONTRACT_VARIABLES + ("contact_shift", "frame_offset", "wake_loss", "iterations", "coupling_iterations"):
        assert name in ds, name
        assert ds[name].attrs["units"] and ds[name].attrs["long_name"], name
    assert ds["pressure"].dims == ("t", "y", "x") and ds["stick"].dtype == bool
    assert "displacement_z" not in ds                       # not requested
    np.testing.assert_array_equal(ds["x"].values, problem.grid.x)
    np.testing.assert_array_equal(ds["pressure"].values[2], records[2].pressure)
    hertz = hertz_from_load(SEED_LOAD, SEED_RADIUS, SEED_G0, SEED_NU)
    assert ds.attrs["a0"] == pytest.approx(hertz.radius) and ds.attrs["p0"] == pytest.approx(hertz.peak_pressure)
    assert ds.attrs["a0"] == pytest.approx(SEED_A0, rel=1e-3)
    assert ds.attrs["retardation_time"] == pytest.approx(0.01)
    assert ds.attrs["t_gross_sliding"] == pytest.approx(3e-3)   # first record in phase 2
    assert ds.attrs["complete"] == 1
    assert ds.attrs["case"] == "title = 'x'" and ds.attrs["extra"] == 7
    assert ds.attrs["tangential_mode"] == "partial_slip" and ds.attrs["version"]


def test_incomplete_and_undefined_quantities() -> None:
    problem = make_problem("none", fields=("pressure", "shear_x", "stick", "displacement_z"))
    ds = to_dataset(fake_records(problem, (0, 0)), problem)
    assert ds.attrs["complete"] == 0                        # 2 of 5 steps
    assert math.isnan(ds.attrs["t_gross_sliding"])
    assert "note" in ds["stick_ratio"].attrs and "note" in ds["shear_x"].attrs
    assert "note" not in ds["pressure"].attrs
    assert not ds["displacement_z"].values.any()            # requested but not recorded: zeros


def test_displacement_control_scale() -> None:
    problem = dataclasses.replace(make_problem(), normal=NormalLoading("displacement",
                                                                       PiecewiseLinear.constant(34.45e-6)))
    ds = to_dataset(fake_records(problem), problem)
    assert ds.attrs["a0"] == pytest.approx(math.sqrt(0.01 * 34.45e-6))
    assert ds.attrs["p0"] == pytest.approx(SEED_P0, rel=5e-3)  # delta 34.45 um is rounded


def test_equivalent_radius_without_sphere() -> None:
    problem = dataclasses.replace(make_problem(), radius=None)
    ds = to_dataset(fake_records(problem), problem)
    assert ds.attrs["a0"] == pytest.approx(SEED_A0, rel=1e-2)   # the gap is the R = 10 mm sphere


def test_round_trip(tmp_path: Path) -> None:
    problem = make_problem()
    ds = to_dataset(fake_records(problem), problem, case_text="# ü case\n")
    path = write_netcdf(ds, tmp_path / "sub" / "r.nc")
    assert sorted(p.name for p in path.parent.iterdir()) == ["r.nc"]     # no temporary file left
    back = open_result(path)
    for name in ds.variables:
        np.testing.assert_array_equal(back[name].values, ds[name].values, err_msg=name)
        assert back[name].dtype == ds[name].dtype, name
    assert back.attrs["case"] == "# ü case\n"
    assert back.attrs["a0"] == ds.attrs["a0"]
    import h5py

    with h5py.File(path) as f:
        assert f["pressure"].compression == "gzip"


def test_refuses_overwrite(tmp_path: Path) -> None:
    problem = make_problem()
    ds = to_dataset(fake_records(problem), problem)
    path = tmp_path / "r.nc"
    write_netcdf(ds.isel(t=[0]), path)
    kept = path.read_bytes()
    with pytest.raises(FileExistsError, match="--force"):
        write_netcdf(ds, path)
    assert path.read_bytes() == kept
    write_netcdf(ds, path, force=True)
    assert open_result(path).sizes["t"] == 5
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.nc"]
    path.write_bytes(b"keep me")  # not a result file: never replaced, even with force
    with pytest.raises(FileExistsError, match="not a netCDF result file"):
        write_netcdf(ds, path, force=True)
    assert path.read_bytes() == b"keep me"


def test_failed_write_leaves_nothing(tmp_path: Path) -> None:
    problem = make_problem()
    ds = to_dataset(fake_records(problem), problem)
    ds.attrs["bad"] = {"a dict": "cannot be an attribute"}
    with pytest.raises(TypeError):
        write_netcdf(ds, tmp_path / "r.nc")
    assert list(tmp_path.iterdir()) == []


def test_plots(tmp_path: Path) -> None:
    from viscontact.plotting import plot_result, plot_speed_curve

    problem = make_problem()
    records = fake_records(problem)
    paths = plot_result(to_dataset(records, problem), tmp_path / "figs")
    assert {p.name for p in paths} == {"pressure_profiles.png", "pressure_maps.png", "contact_history.png",
                                       "friction.png", "tangential_loop.png", "stick_map.png", "pressure.gif"}
    assert all(p.stat().st_size > 1000 for p in paths)
    sweep = sweep_dataset(records[:3], [0.01, 0.1, 1.0], problem)
    assert sweep["deborah"].values[1] == pytest.approx(0.1 * 0.01 / sweep.attrs["a0"])
    assert [p.name for p in plot_speed_curve(sweep, tmp_path)] == ["speed_curve.png"]


def test_every_coordinate_is_described() -> None:
    """The coordinates of a transient (with subsurface output) and of a speed curve are those of
    results.COORDINATES, which the documentation's result-variable table lists (``deborah`` was in
    no table), with its units and long names."""
    from viscontact.io.results import COORDINATES

    problem = make_problem()
    problem = dataclasses.replace(problem, output=dataclasses.replace(problem.output, subsurface_depths=(1e-4,)))
    records = fake_records(problem)
    fretting = [dataclasses.replace(r, delta_x=x) for r, x in zip(fake_records(problem, (1,) * 6), (0, 1, 0, -1, 0, 1))]
    seen = set()
    for ds in (to_dataset(records, problem), sweep_dataset(records[:2], [0.01, 0.1], problem),
               to_dataset(fretting, problem)):  # energy_per_cycle along cycle
        for name, coord in ds.coords.items():
            units, long_name = COORDINATES[name]
            assert coord.attrs["long_name"] == long_name and coord.attrs.get("units", "") == units, name
            seen.add(name)
    assert seen == set(COORDINATES)
    assert COORDINATES["deborah"] == ("1", "Deborah number v tau / a0")


def test_source_names_the_convolutions_of_the_domain() -> None:
    """A periodic result's ``source`` says periodic FFTs (it said DC-FFT, the zero-padded ones of an
    isolated contact, on every result)."""
    from viscontact.io.case import load_case
    from viscontact.io.results import global_attrs
    from viscontact.io.shipped import shipped_case

    for name, expected in (("rough_periodic_sliding", "periodic FFT convolutions"),
                           ("creep_indentation", "DC-FFT convolutions")):
        problem = load_case(shipped_case(name)).with_overrides({"grid.n": 16}).to_problem()
        assert global_attrs(problem)["source"].endswith(f": boundary elements with {expected}"), name


# --- self-describing result files (CF attributes, scales with units, provenance) -----------------------
def test_scales_are_variables_with_units(tmp_path: Path) -> None:
    """a0, p0, tau and the onset of gross sliding are scalar variables with units; a0 and p0 stay
    global attributes (public contract) with the same values."""
    problem = make_problem()
    ds = to_dataset(fake_records(problem), problem)
    hertz = hertz_from_load(0.15, 0.01, 1.93e6, 0.3)
    expected = {"a0": (hertz.radius, "m"), "p0": (hertz.peak_pressure, "Pa"), "retardation_time": (0.01, "s"),
                "t_gross_sliding": (3e-3, "s")}
    back = open_result(write_netcdf(ds, tmp_path / "r.nc"))
    for result in (ds, back):
        for name, (value, units) in expected.items():
            assert result[name].dims == () and result[name].attrs["units"] == units, name
            assert float(result[name]) == pytest.approx(value), name
        assert back.attrs["a0"] == float(result["a0"]) and back.attrs["p0"] == float(result["p0"])
    sweep = sweep_dataset(fake_records(problem)[:2], [0.01, 0.1], problem)
    assert float(sweep["a0"]) == pytest.approx(hertz.radius) and sweep["a0"].attrs["units"] == "m"


def test_cf_flags_on_stick_and_phase(tmp_path: Path) -> None:
    """CF flag_values / flag_meanings: one meaning per value, every stored value is a flag, and the
    meanings follow the phase numbering of the solver."""
    from viscontact.problem.problem import PHASE_GROSS_SLIDING, PHASE_INDENTATION, PHASE_PARTIAL_SLIP

    problem = make_problem()
    path = write_netcdf(to_dataset(fake_records(problem), problem), tmp_path / "r.nc")
    back = open_result(path)
    for name in ("stick", "phase"):
        values, meanings = back[name].attrs["flag_values"], back[name].attrs["flag_meanings"].split()
        assert len(values) == len(meanings), name
        assert set(np.unique(back[name].values.astype(int))) <= set(int(v) for v in values), name
    phase = dict(zip(back["phase"].attrs["flag_values"].tolist(), back["phase"].attrs["flag_meanings"].split()))
    assert phase == {PHASE_INDENTATION: "indentation", PHASE_PARTIAL_SLIP: "partial_slip",
                     PHASE_GROSS_SLIDING: "gross_sliding"}
    stick = dict(zip(back["stick"].attrs["flag_values"].tolist(), back["stick"].attrs["flag_meanings"].split()))
    assert stick[1] == "stick"
    import h5py

    with h5py.File(path) as f:  # stored with the type of the variable in the file
        assert f["stick"].attrs["flag_values"].dtype == f["stick"].dtype
        assert f["phase"].attrs["flag_values"].dtype == f["phase"].dtype


def test_coordinates_have_no_fill_value(tmp_path: Path) -> None:
    import h5py

    problem = make_problem()
    records = fake_records(problem)
    for name, ds in (("t.nc", to_dataset(records, problem)),
                     ("speed.nc", sweep_dataset(records[:2], [0.01, 0.1], problem))):
        path = write_netcdf(ds, tmp_path / name)
        with h5py.File(path) as f:
            for coord in ds.coords:
                assert "_FillValue" not in f[coord].attrs, (name, coord)
            assert "_FillValue" in f["mu_app"].attrs           # data variables keep theirs


def test_provenance_attributes() -> None:
    from datetime import datetime

    from viscontact import __version__

    problem = make_problem()
    ds = to_dataset(fake_records(problem), problem)
    assert "Friction (2023)" in ds.attrs["references"] and "transient frictional viscoelastic" in ds.attrs["references"]
    assert ds.attrs["source"].startswith(f"viscontact {__version__}")
    stamp, _, rest = ds.attrs["history"].partition(" ")
    assert datetime.strptime(stamp, "%Y-%m-%dT%H:%M:%SZ") and __version__ in rest
    assert ds.attrs["Conventions"] == "CF-1.8"


def test_open_result_refuses_what_is_not_a_result(tmp_path: Path) -> None:
    import xarray as xr

    from viscontact.errors import ParameterError

    text = tmp_path / "notes.nc"
    text.write_text("not HDF5 at all")
    foreign = tmp_path / "foreign.nc"
    xr.Dataset({"a": ("t", np.arange(3.0))}).to_netcdf(foreign, engine="h5netcdf")
    for path in (text, foreign):
        with pytest.raises(ParameterError, match="not a viscontact result file") as info:
            open_result(path)
        assert info.value.key == str(path)
