"""The exponential adhesive law (``[adhesion] law = "exponential"``) on the array seam: its transient
on the emulated device (tests/emulated_device.py: numpy behind CuPy's rules, so a host array leaking
into the device path raises) equals the numpy run bit for bit, under displacement control (the shipped
approach-dwell-retraction, n = 32) and under load control to the pull-off."""
from __future__ import annotations

import dataclasses
import warnings

import emulated_device
import numpy as np
import pytest

from viscontact.bodies.compliance import compliance_of
from viscontact.errors import ViscontactWarning
from viscontact.io.case import load_case
from viscontact.io.shipped import shipped_case
from viscontact.numerics.arrays import CPU
from viscontact.solvers.transient import steps

EXPONENTIAL = {"grid.n": 32, "adhesion.law": "exponential", "adhesion.cohesive_stress": None,
               "adhesion.range": 2.6e-6}


@pytest.mark.parametrize("overrides", [{}, {"normal.control": "load",
                                            "normal.history": [[0.0, 0.0], [0.1, 2e-3], [0.6, 2e-3], [1.4, -5e-3]]}],
                         ids=["retraction", "load"])
def test_the_exponential_transient_on_the_device_equals_numpy(overrides):
    problem = load_case(shipped_case("adhesive_pdms_retraction")).with_overrides({**EXPONENTIAL, **overrides}
                                                                                  ).to_problem()
    backend = emulated_device.BACKEND
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ViscontactWarning)
        reference = list(steps(problem, compliance=compliance_of(
            problem, backend=dataclasses.replace(CPU, fast_length=backend.fast_length))))
        ours = list(steps(problem, compliance=compliance_of(problem, backend=backend)))
    assert len(ours) == len(reference) > 1
    if overrides:
        assert len(ours) < problem.time.n_steps  # the pull-off ended it
    for (state, record), (_, expected) in zip(ours, reference):
        for f in dataclasses.fields(record):
            value, wanted = getattr(record, f.name), getattr(expected, f.name)
            if isinstance(wanted, np.ndarray):
                np.testing.assert_array_equal(emulated_device.to_host(value) if not isinstance(value, np.ndarray)
                                              else value, wanted, err_msg=f.name)
            else:
                assert value == wanted or (np.isnan(value) and np.isnan(wanted)), f.name
    assert not isinstance(ours[-1][0].pressure, np.ndarray)  # the state stayed on the device
