"""viscontact.numerics.allocator: the glibc settings for the solvers' temporaries, their opt-out and their effect
(page faults of repeated DC-FFT convolutions, counted by the kernel), each in a fresh interpreter."""
from __future__ import annotations

import os
import platform
import subprocess
import sys

import pytest

GLIBC = sys.platform.startswith("linux") and platform.libc_ver()[0] == "glibc"

# prints whether the settings are in effect, then the minor page faults of 50 convolutions at 128^2
# through forward and inverse (each allocates its 0.1-0.5 MiB results)
SCRIPT = """
import resource, sys
import numpy as np
from viscontact.numerics.allocator import tune_allocator
from viscontact.numerics.fftbackends import ZeroBlockTransforms
tuned = False
if sys.argv[1] == "tune":
    tuned = tune_allocator()
    assert tune_allocator() == tuned  # applied once, the same answer after
n = 128
transforms = ZeroBlockTransforms(n, 1)
kernel, field = transforms.forward(np.random.rand(n, n)), np.random.rand(n, n)
for _ in range(5):
    transforms.inverse(kernel * transforms.forward(field))
before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(50):
    u = transforms.inverse(kernel * transforms.forward(field)) * 2.0 + field
print(tuned, resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before)
"""


def _run(mode: str, **env: str) -> tuple[bool, int]:
    clean = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_") and k != "VISCONTACT_MALLOC"}
    out = subprocess.run([sys.executable, "-c", SCRIPT, mode], env={**clean, **env}, capture_output=True,
                         text=True, check=True).stdout.split()
    return out[0] == "True", int(out[1])


@pytest.mark.skipif(not GLIBC, reason="the settings apply to glibc only")
def test_settings_remove_the_page_faults_of_freed_temporaries():
    tuned, faults = _run("tune")
    untuned, faults_default = _run("plain")
    assert tuned and not untuned
    # glibc's defaults give back and fault in again every freed 0.1-0.5 MiB block (thousands of faults)
    assert faults_default > 1000
    assert faults < faults_default / 10


@pytest.mark.parametrize("env", [{"VISCONTACT_MALLOC": "default"}, {"VISCONTACT_MALLOC": "Off"},
                                 {"MALLOC_TOP_PAD_": "1048576"}, {"MALLOC_TRIM_THRESHOLD_": "131072"}])
def test_opt_out_and_the_users_own_settings_leave_the_allocator_alone(env):
    tuned, _ = _run("tune", **env)
    assert not tuned
