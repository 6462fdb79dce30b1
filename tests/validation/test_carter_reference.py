"""Carter's plane-strain rolling (:class:`viscontact.physics.reference.Carter`) against its own
definition, by an independent quadrature: the traction integrates to Q', stays within mu_f p, and
the surface strain of the half-plane under it, du_x/dx = -(2 / (pi E*)) PV int q(s) / (x - s) ds
(Johnson, Contact Mechanics, Eq. 2.25b), is the creepage at every point of the stick zone (the stick
condition of steady rolling, du_x/dx = xi) and differs from it on the slip zone. The line-contact
transient and steady solvers are checked against it where the plane-strain grid exists."""
from itertools import pairwise

import numpy as np
import pytest
from scipy.integrate import quad

from viscontact.physics.reference import carter

G, NU, R, W, MU = 1.93e6, 0.5, 0.01, 100.0, 0.3  # Pa, -, m, N/m, -


def _strain(ref, force: float, x: float) -> float:
    """-(2 / (pi E*)) PV int_{-a}^{a} q(s) / (x - s) ds, the singularity subtracted:
    int (q(s) - q(x)) / (x - s) ds + q(x) ln((x + a) / (a - x))."""
    a = ref.half_width
    qx = float(ref.shear_traction(x, force))
    c = ref.stick_half_width(force)
    breaks = sorted({-a, a - 2 * c, x, a})
    smooth = sum(quad(lambda s: (float(ref.shear_traction(s, force)) - qx) / (x - s), lo, hi, limit=200,
                      epsabs=1e-12 * ref.peak_pressure)[0] for lo, hi in pairwise(breaks) if hi > lo)
    return -2.0 / (np.pi * ref.contact_modulus) * (smooth + qx * np.log((x + a) / (a - x)))


@pytest.mark.parametrize("share", [0.2, 0.6, -0.6])
def test_carter_traction_and_creepage(share):
    ref = carter(W, R, MU, G, NU)
    force = share * MU * W
    a, c = ref.half_width, ref.stick_half_width(force)
    x = np.linspace(-a, a, 200001)
    q = ref.shear_traction(x, force)
    assert np.trapezoid(q, x) == pytest.approx(force, rel=1e-6)
    assert np.all(np.abs(q) <= MU * ref.peak_pressure * np.sqrt(np.clip(1 - (x / a) ** 2, 0, None)) + 1e-9)
    xi = float(ref.creepage(force))
    assert np.sign(xi) == -np.sign(force)  # braking (Q' > 0): xi < 0
    for point in np.linspace(a - 2 * c, a, 7)[1:-1]:  # inside the stick zone
        assert _strain(ref, force, point) == pytest.approx(xi, rel=1e-6)
    assert abs(_strain(ref, force, a - 2 * c - 0.3 * (a - c)) - xi) > 1e-3 * abs(xi)  # on the slip zone
    assert float(ref.force(xi)) == pytest.approx(force, rel=1e-12)
