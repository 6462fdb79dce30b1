"""
Flat-punch creep and conical indentation
========================================

Two indenters of indentation testing on the seed's Zener half-space (G(0) = 1.93 MPa,
G(∞) = G(0)/10, retardation time τ = 0.01 s, ν = 0.3), each a shipped case
(``indenter.shape = "flat_punch"`` and ``"cone"``).

A flat punch of radius a under a held load W keeps its face as its contact, and its pressure the
same (Boussinesq) field, so its approach creeps exactly as the creep compliance (Sneddon's
W = 2 a E* δ with 1/E* = (1 − ν) J(t)/2):

.. math:: \\delta(t) = \\frac{W (1-\\nu)}{4 a} J(t) .

A cone of semi-apex angle α pushed in at a constant rate and held: its contact radius follows the
depth, a = 2 δ tan α / π, and its load is Sneddon's made hereditary (Lee & Radok),

.. math:: W(t) = \\frac{4 \\tan\\alpha}{\\pi (1-\\nu)} \\int_0^t G(t-s)\\, \\mathrm{d}\\delta^2(s) .
"""

import math

import matplotlib.pyplot as plt
import numpy as np

import viscontact as vc
from viscontact.physics.reference import lee_radok_cone_load

punch_case = vc.load_case(vc.shipped_case("flat_punch_creep"))
punch = vc.run(punch_case)
cone_case = vc.load_case(vc.shipped_case("conical_indentation"))
cone = vc.run(cone_case)

# %%
# The punch's approach against the creep compliance, and the cone's load against Lee & Radok.
material = punch_case.to_problem().material
tau = 0.01
t = punch["t"].values
creep = material.creep.compliance(t)
delta = punch["delta_z"].values

problem = cone_case.to_problem()
history = problem.normal.history
t_cone = cone["t"].values
exact = lee_radok_cone_load(t_cone, history.times, history.values, math.radians(70.3), problem.material)

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.5))
ax1.plot(t / tau, delta * 1e6, "o", ms=3, label="viscontact, 64²")
ax1.plot(t / tau, delta[0] * creep / creep[0] * 1e6, "k-", lw=1, label="δ(0) J(t)/J(0)")
ax1.set(xlabel="t / τ", ylabel="approach δ [µm]", title="flat punch, 20 mN held")
ax1.legend()
ax2.plot(t_cone / tau, cone["load"] * 1e3, "o", ms=3, label="viscontact, 64²")
ax2.plot(t_cone / tau, exact * 1e3, "k-", lw=1, label="Sneddon + Lee & Radok")
ax2.set(xlabel="t / τ", ylabel="load W [mN]", title="cone 70.3°, ramp to 20 µm and hold")
ax2.legend()
fig.tight_layout()

print(f"punch: largest |δ(t)/δ(0) - J(t)/J(0)| = {np.max(np.abs(delta / delta[0] - creep / creep[0])):.1e}")
late = t_cone > 0.002
print(f"cone: largest relative load error = {np.max(np.abs(cone['load'].values[late] / exact[late] - 1)):.1e}")

# %%
# The pressure along y = 0: the punch's is singular at its rim, the cone's at its tip; on the grid
# both are cell averages there, while the load, the approach and the pressure a few cells away
# converge.
y0 = punch.sizes["y"] // 2
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.5))
for k in (0, -1):
    ax1.plot(punch["x"] * 1e3, punch["pressure"][k, y0] / 1e3, label=f"t = {t[k] / tau:.0f} τ")
ax1.set(xlabel="x [mm]", ylabel="p [kPa]", title="flat punch")
ax1.legend()
for k in (20, 40, -1):
    ax2.plot(cone["x"] * 1e6, cone["pressure"][k, y0] / 1e3, label=f"t = {t_cone[k] / tau:.1f} τ")
ax2.set(xlabel="x [µm]", ylabel="p [kPa]", title="cone")
ax2.legend()
fig.tight_layout()
