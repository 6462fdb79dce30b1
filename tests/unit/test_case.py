"""Case files: the shipped cases load; each kind of bad input is one ParameterError naming the key."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from viscontact.io.case import Case, load_case
from viscontact.errors import ParameterError
from viscontact.problem.problem import Problem, TangentialLoading

ROOT = Path(__file__).resolve().parents[2]
CASES = sorted((ROOT / "cases").glob("*.toml"))
BASE = (ROOT / "cases" / "creep_indentation.toml").read_text()


def parse(text: str, base_dir: Path = ROOT / "cases") -> Case:
    return Case.from_toml_text(text, base_dir)


@pytest.mark.parametrize("path", CASES, ids=[p.name for p in CASES])
def test_shipped_cases_load(path: Path) -> None:
    case = load_case(path)
    problem = case.to_problem()
    assert isinstance(problem, Problem)
    assert case.text == path.read_text()
    assert problem.gap.shape == problem.grid.shape == ((problem.grid.n, problem.grid.n) if case.grid.dimension == 2
                                                      else (1, problem.grid.n))
    assert problem.gap.min() >= 0


def test_seed_material_and_sphere() -> None:
    problem = load_case(ROOT / "cases" / "creep_indentation.toml").to_problem()
    mat = problem.material
    assert mat.shear_modulus_instantaneous == pytest.approx(1.93e6)
    assert mat.shear_modulus_long_term == pytest.approx(0.193e6)
    assert mat.creep.retardation_times[0] == pytest.approx(0.01)
    x, y = problem.grid.mesh()
    np.testing.assert_allclose(problem.gap, (x**2 + y**2) / (2 * 0.01))
    assert problem.normal.control == "load" and problem.normal.history(1.0) == pytest.approx(0.15)
    assert problem.time.dt == pytest.approx(2.5e-4) and problem.time.n_steps == 161


@pytest.mark.parametrize(
    ("old", "new", "key", "words"),
    [
        ("\nn = 128", '\nn = "big"', "grid.n", "integer"),                                   # wrong type
        ("poisson_ratio = 0.3", 'poisson_ratio = "0.3"', "material.poisson_ratio", "number"),
        ("poisson_ratio = 0.3", "poison_ratio = 0.3", "material.poison_ratio", "did you mean 'poisson_ratio'"),
        ("[grid]", "[grd]", "grd", "did you mean 'grid'"),                                # unknown section
        ("poisson_ratio = 0.3", "poisson_ratio = 0.7", "material.poisson_ratio", "<= 0.5"),  # out of range
        ("\nn = 128", "\nn = 4", "grid.n", ">= 8"),
        ("dt = 2.5e-4", "dt = -1.0", "time.dt", "> 0"),
        ("dt = 2.5e-4", "dt = inf", "time.dt", "finite"),
        ("shear_modulus_long_term = 0.193e6", "shear_modulus_long_term = 5e6",
         "material.shear_modulus_long_term", "<="),
        ('type = "zener"', 'type = "maxwell"', "material.type", "'zener', 'prony', 'elastic'"),
        ('mode = "none"', 'mode = "sliding"', "tangential.mode", "partial_slip"),
        ('mode = "none"', 'mode = "partial_slip"', "tangential.sliding_speed", "> 0"),
        ("value = 0.15 ", "value = 0.15\nhistory = [[0.0, 0.0], [0.01, 0.15]] ", "normal.value", "exactly one"),
        ("value = 0.15 ", "history = [[0.0, 0.0], [0.0, 0.15]] ", "normal.history", "increasing"),
        ("dt = 2.5e-4", "", "time.dt", "required"),
        ("[time]", "[time", "case file", "not valid TOML"),
    ],
)
def test_bad_input_names_the_key(old: str, new: str, key: str, words: str) -> None:
    assert old in BASE
    with pytest.raises(ParameterError) as info:
        parse(BASE.replace(old, new, 1))
    assert info.value.key == key
    assert words in info.value.message


def test_missing_file() -> None:
    with pytest.raises(ParameterError) as info:
        load_case(ROOT / "cases" / "no_such_case.toml")
    assert info.value.key == "case file" and "no such file" in info.value.message


def test_missing_section() -> None:
    start, end = BASE.index("[grid]"), BASE.index("[normal]")
    with pytest.raises(ParameterError) as info:
        parse(BASE[:start] + BASE[end:])
    assert info.value.key == "grid" and "missing" in info.value.message


def test_overrides() -> None:
    case = load_case(ROOT / "cases" / "creep_indentation.toml")
    fast = case.with_overrides({"grid.n": np.int64(32), "normal.history": [[0.0, 0.0], [0.01, 0.1]]})
    problem = fast.to_problem()
    assert problem.grid.n == 32
    assert problem.normal.history.reference == pytest.approx(0.1)
    assert case.to_problem().grid.n == 128          # the original is unchanged
    assert "grid.n" in fast.text
    with pytest.raises(ParameterError) as info:
        case.with_overrides({"grid.nn": 3})
    assert info.value.key == "grid.nn" and "did you mean 'n'" in info.value.message


def test_sliding_default_dt() -> None:
    case = load_case(ROOT / "cases" / "creep_indentation.toml").with_overrides(
        {"tangential.mode": "frictionless_sliding", "tangential.sliding_speed": 0.05,
         "tangential.steps_per_cell": 2, "time.dt": None})
    grid = case.to_problem().grid
    assert case.to_problem().time.dt == pytest.approx(grid.spacing / 0.05 / 2)


def test_surface_file(tmp_path: Path) -> None:
    n = 16
    x = (np.arange(n) + 0.5) / n - 0.5
    heights = 1e-6 + 1e-4 * np.add.outer(x**2, x**2)  # a relief of 50 um: rms slope about 0.02
    np.save(tmp_path / "h.npy", heights)
    text = (BASE.replace('shape = "sphere"', 'shape = "surface"\nfile = "h.npy"')
                .replace("radius = 0.01 ", "# no radius ").replace("\nn = 128", f"\nn = {n}"))
    problem = parse(text, tmp_path).to_problem()
    assert problem.radius is None
    np.testing.assert_allclose(problem.gap, heights - heights.min())
    with pytest.raises(ParameterError) as info:
        parse(text.replace("\nn = 16", "\nn = 32"), tmp_path).to_problem()
    assert info.value.key == "indenter.file" and "shape" in info.value.message
    with pytest.raises(ParameterError) as info:
        parse(text, tmp_path / "elsewhere").to_problem()
    assert info.value.key == "indenter.file" and "no such file" in info.value.message


def test_solver_coupling_is_a_case_key() -> None:
    case = load_case(ROOT / "cases" / "creep_indentation.toml")
    assert case.to_problem().solver.coupling is True
    assert case.with_overrides({"solver.coupling": False}).to_problem().solver.coupling is False
    with pytest.raises(ParameterError) as err:
        case.with_overrides({"solver.coupling": 0})
    assert err.value.key == "solver.coupling"


@pytest.mark.parametrize(("field", "value", "key"), [("friction_coefficient", 0.0, "tangential.friction_coefficient"),
                                                      ("displacement_rate", 0.0, "tangential.displacement_rate"),
                                                      ("sliding_speed", 0.0, "tangential.sliding_speed")])
def test_what_partial_slip_needs_is_decided_in_one_place(field: str, value: float, key: str) -> None:
    """The problem layer refuses partial slip with mu_f = 0 (and without a rate or speed); the case
    layer says the same, word for word."""
    good = {"friction_coefficient": 0.3, "displacement_rate": 0.01, "sliding_speed": 0.05}
    with pytest.raises(ParameterError) as direct:
        TangentialLoading("partial_slip", **{**good, field: value})
    case = load_case(ROOT / "cases" / "creep_indentation.toml")
    with pytest.raises(ParameterError) as from_case:
        case.with_overrides({"tangential.mode": "partial_slip",
                             **{f"tangential.{k}": v for k, v in {**good, field: value}.items()}})
    assert direct.value.key == from_case.value.key == key
    assert direct.value.message == from_case.value.message


def test_case_keys_list_every_material_type() -> None:
    """``case_keys()`` merged the material types' keys first come, first kept: ``material.type`` took
    only ``Literal["zener"]`` and nothing said which type a key belongs to. Now ``material.type``
    takes every type, every type's every key is listed, and a key some types lack names those that
    take it."""
    import typing

    from viscontact.io.case import MATERIALS, case_keys

    keys = case_keys()
    assert typing.get_args(keys["material.type"].annotation) == tuple(MATERIALS) == ("zener", "prony", "elastic")
    assert all(f"material.{name}" in keys for model in MATERIALS.values() for name in model.model_fields)
    for key, takers in {"material.shear_modulus": ['"elastic"'], "material.g": ['"prony"'],
                        "material.retardation_time": ['"zener"'],
                        "material.temperature": ['"zener"', '"prony"']}.items():
        description = keys[key].description
        assert description.endswith(f"(material.type = {' or '.join(takers)})"), (key, description)
        assert keys[key].json_schema_extra == MATERIALS[takers[0].strip('"')].model_fields[key[9:]].json_schema_extra
    assert keys["material.poisson_ratio"].description == MATERIALS["elastic"].model_fields["poisson_ratio"].description
    assert keys["grid.n"].description  # the other sections as they are



def test_case_keys_list_required_keys_first() -> None:
    """The case-key reference listed ``material.type`` after the optional keys every material inherits
    (poisson_ratio, temperature, ...). In :func:`case_keys` (and the reference built from
    :func:`required_first`) each section's required keys come first."""
    from viscontact.io.case import MATERIALS, case_keys, required_first

    keys = list(case_keys())
    material = [k for k in keys if k.startswith("material.")]
    assert material[:4] == ["material.type", "material.shear_modulus_instantaneous",
                            "material.shear_modulus_long_term", "material.retardation_time"]
    assert [k for k in keys if k.startswith("normal.")][0] == "normal.control"
    for model in MATERIALS.values():
        required = [info.is_required() for _, info in required_first(model)]
        assert required == sorted(required, reverse=True) and required[0]


FRETTING = ROOT / "cases" / "fretting_zener.toml"


@pytest.mark.parametrize(("overrides", "key", "words"), [
    ({"tangential.displacement_rate": 1e-3}, "tangential.displacement_history", "exactly one of"),
    ({"tangential.displacement_history": None, "tangential.sliding_speed": 0.05}, "tangential.displacement_rate",
     "displacement_history instead"),
    ({"tangential.slip": "total"}, "tangential.slip", "no memory of the load path"),
    ({"tangential.mode": "gross_sliding", "tangential.sliding_speed": 0.05}, "tangential.displacement_history",
     "only with mode = 'partial_slip'"),
    ({"tangential.displacement_history": [[0.0, 1e-6], [0.01, 2e-6]]}, "tangential.displacement_history",
     "start at delta_x = 0 m"),
    ({"tangential.displacement_history": [[0.0, 0.0], [0.01, 1e-6], [0.01, -1e-6]]},
     "tangential.displacement_history", "strictly increasing"),
    ({"tangential.displacement_history": [[0.0, 0.0, 1.0]]}, "tangential.displacement_history", "[t, value] pairs"),
    ({"time.dt": None}, "time.dt", "required (> 0 s) with tangential.displacement_history"),
])
def test_displacement_history_errors_name_the_key(overrides, key, words) -> None:
    """A fretting case's bad input: one error naming the key and what is allowed (the history's
    list checks are the normal history's, one function)."""
    with pytest.raises(ParameterError) as info:
        load_case(FRETTING).with_overrides(overrides).to_problem()
    assert info.value.key == key, info.value
    assert words in info.value.message, info.value.message


def test_displacement_history_defaults_to_the_incremental_slip_and_needs_no_speed() -> None:
    """Under a displacement history the slip defaults to "incremental" (given or not); no sliding
    speed is needed and dt is free (the frame never moves); delta_x(t) is the history, piecewise
    linear, held after its last point. The ramp keeps its default, the total slip."""
    case = load_case(FRETTING)
    assert "slip =" not in case.text.split("[tangential]")[1].split("[time]")[0].replace("# slip =", "")
    problem = case.to_problem()
    tan = problem.tangential
    assert tan.slip == "incremental" and tan.incremental_slip and not tan.frame_moves and tan.sliding_speed == 0
    assert tan.delta_x(0.0) == 0 and tan.delta_x(0.00125) == pytest.approx(4e-6) and tan.delta_x(0.005) == \
        pytest.approx(0.0, abs=1e-20) and tan.delta_x(1.0) == pytest.approx(8e-6)
    assert case.with_overrides({"tangential.slip": "incremental"}).to_problem().tangential == tan
    ramp = case.with_overrides({"tangential.displacement_history": None, "tangential.displacement_rate": 1e-3,
                                "tangential.sliding_speed": 0.05, "time.dt": None}).to_problem().tangential
    assert ramp.slip == "total" and ramp.frame_moves and ramp.delta_x(0.01) == pytest.approx(1e-5)


def test_a_sliding_speed_beside_a_displacement_history_is_refused_by_the_run(tmp_path):
    """A displacement history never slides, so a sliding speed beside it is a contradiction: the run
    (transient.validate, what viscontact run and the sweeps' checks call) refuses it in one line keyed
    tangential.sliding_speed - before, it was accepted silently and written to the result's
    attributes as if the indenter had slid. (viscontact steady refuses the history itself.)"""
    from viscontact.io.shipped import shipped_case
    from viscontact.solvers.transient import validate

    case = load_case(shipped_case("fretting_zener")).with_overrides({"grid.n": 16})
    validate(case.to_problem())
    with pytest.raises(ParameterError, match=r"^tangential.sliding_speed: give none with "
                                             r"tangential.displacement_history.*got 0.01 m/s"):
        validate(case.with_overrides({"tangential.sliding_speed": 0.01}).to_problem())
