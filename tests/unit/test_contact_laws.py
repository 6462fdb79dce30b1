"""The contact-law seam (viscontact.solvers.contact_laws) and the one measurement of a solved state
(viscontact.solvers.measure): every registered law is reachable by name, an unknown name is
refused with the names there are, each mode and phase gets its law from the one mapping, and a law
registered here (one class and its registration) is what the transient's stepper runs."""
from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np
import pytest
from vc_testing import SEED_A0, SEED_TAU, seed_material, sphere_problem

from viscontact.bodies.compliance import compliance_of
from viscontact.errors import ParameterError
from viscontact.problem.problem import PHASE_GROSS_SLIDING, PHASE_INDENTATION, PHASE_PARTIAL_SLIP
from viscontact.solvers.contact_laws import (
    CONTACT_LAWS,
    PHASE_LAWS,
    ContactLaw,
    NormalContact,
    PartialSlip,
    contact_law,
    first_phase,
    get_contact_law,
    law_name,
    register_contact_law,
)
from viscontact.solvers.measure import measure
from viscontact.solvers.transient import steps

MU = 0.3


def _sliding(mode: str = "gross_sliding", poisson_ratio: float = 0.5, **kw):
    v = 10 * SEED_A0 / SEED_TAU
    return sphere_problem(seed_material(poisson_ratio=poisson_ratio), 16, 2.6 * SEED_A0, mode=mode, friction=MU,
                          speed=v, t_end=0.3 * SEED_TAU, scheme="linear", **kw)


def test_the_shipped_laws_are_registered():
    assert {"normal_contact", "partial_slip"} <= set(CONTACT_LAWS)
    assert CONTACT_LAWS["normal_contact"] is NormalContact and CONTACT_LAWS["partial_slip"] is PartialSlip
    assert set(PHASE_LAWS.values()) <= set(CONTACT_LAWS)  # every phase's law is there


@pytest.mark.parametrize("name", sorted(CONTACT_LAWS))
def test_every_registered_law_is_reachable_by_name(name):
    law = get_contact_law(name)
    assert law is CONTACT_LAWS[name] and law.name == name and issubclass(law, ContactLaw)
    built = law.for_problem(_sliding(), compliance_of(_sliding()), PHASE_GROSS_SLIDING)
    assert isinstance(built, law) and built.friction == MU


def test_an_unknown_name_is_refused_with_the_registered_ones():
    with pytest.raises(ParameterError) as info:
        get_contact_law("adhesive")
    message = str(info.value)
    assert "'adhesive'" in message and "normal_contact" in message and "partial_slip" in message


def test_a_taken_or_missing_name_is_refused():
    @dataclasses.dataclass(frozen=True)
    class Impostor(NormalContact):
        name: ClassVar[str] = "normal_contact"

    @dataclasses.dataclass(frozen=True)
    class Nameless(ContactLaw):
        pass

    with pytest.raises(ValueError, match="registered already"):
        register_contact_law(Impostor)
    with pytest.raises(ValueError, match="no name"):
        register_contact_law(Nameless)
    assert CONTACT_LAWS["normal_contact"] is NormalContact
    assert register_contact_law(NormalContact) is NormalContact  # registering a law again changes nothing


@pytest.mark.parametrize("mode, phase, law, friction, coupled, label", [
    ("none", PHASE_INDENTATION, NormalContact, 0.0, False, "indentation"),
    ("frictionless_sliding", PHASE_GROSS_SLIDING, NormalContact, 0.0, False, "gross sliding"),
    ("gross_sliding", PHASE_GROSS_SLIDING, NormalContact, MU, True, "gross sliding"),
    ("partial_slip", PHASE_PARTIAL_SLIP, PartialSlip, MU, True, "partial slip"),
])
def test_each_mode_starts_with_its_law(mode, phase, law, friction, coupled, label):
    """The mode gives the first phase, the phase the law (nu = 0.3: the components are coupled
    where there is friction)."""
    problem = _sliding(mode, poisson_ratio=0.3, rate=1e-3 if mode == "partial_slip" else 0.0)
    assert first_phase(problem.tangential) == phase
    built = contact_law(problem, compliance_of(problem), phase)
    assert type(built) is law and built.name == law_name(problem, phase)
    assert (built.friction, built.coupled, built.label) == (friction, coupled, label)
    # partial slip ends in gross sliding, with the normal law and q_x = mu_f p
    if mode == "partial_slip":
        assert law_name(problem, PHASE_GROSS_SLIDING) == "normal_contact"


@dataclasses.dataclass(frozen=True)
class HalfFriction(NormalContact):
    """A toy law: gross sliding with half the friction coefficient, q_x = mu_f p / 2."""

    name: ClassVar[str] = "test_half_friction"

    @classmethod
    def for_problem(cls, problem, compliance, phase):
        law = super().for_problem(problem, compliance, phase)
        return dataclasses.replace(law, friction=0.5 * law.friction)


@pytest.fixture
def half_friction(monkeypatch):
    """:class:`HalfFriction` registered and chosen for gross sliding (both undone afterwards)."""
    register_contact_law(HalfFriction)
    monkeypatch.setitem(PHASE_LAWS, PHASE_GROSS_SLIDING, HalfFriction.name)
    yield HalfFriction
    del CONTACT_LAWS[HalfFriction.name]


def test_a_law_registered_here_is_what_the_stepper_runs(half_friction):
    """One class and its registration: the transient steps with it. Without coupling (nu = 0.5) the
    shear does not act on the pressure, which stays that of the shipped law bit for bit, while the
    friction force is halved."""
    problem = _sliding()
    assert get_contact_law("test_half_friction") is half_friction
    ours = [r for _, r in steps(problem)]
    with pytest.MonkeyPatch.context() as mp:
        mp.setitem(PHASE_LAWS, PHASE_GROSS_SLIDING, "normal_contact")
        shipped = [r for _, r in steps(problem)]
    assert len(ours) == len(shipped) == problem.time.n_steps
    for a, b in zip(ours, shipped):
        np.testing.assert_array_equal(a.pressure, b.pressure)
        assert a.load > 0
        assert a.friction_force == pytest.approx(0.5 * MU * a.load, rel=1e-12)
        assert b.friction_force == pytest.approx(MU * b.load, rel=1e-12)


def test_the_stick_ratio_of_a_measurement_without_contact():
    """No stick field: nothing sticks and the ratio is 0; a stick field without contact: NaN in
    partial slip (undefined), 0 in the other modes."""
    zeros = np.zeros((16, 16))
    kw = dict(delta_z=0.0, value=0.0, step=0, t=0.0, phase=PHASE_PARTIAL_SLIP)
    for mode, ratio in (("partial_slip", np.nan), ("gross_sliding", 0.0)):
        problem = _sliding(mode, rate=1e-3 if mode == "partial_slip" else 0.0)
        problem = dataclasses.replace(problem, normal=dataclasses.replace(problem.normal, control="displacement"))
        record = measure(problem, zeros, zeros, zeros, gap=problem.gap, **kw)
        assert record.stick_ratio == 0.0 and not record.stick.any() and record.load == 0.0 and record.mu_app == 0.0
        with_field = measure(problem, zeros, zeros, zeros, gap=problem.gap, stick=zeros > 0, **kw)
        np.testing.assert_equal(with_field.stick_ratio, ratio)
