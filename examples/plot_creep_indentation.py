"""
Creep indentation against Lee & Radok
=====================================

A rigid sphere (R = 10 mm) is pressed into the seed's Zener half-space (G(0) = 1.93 MPa,
G(∞) = G(0)/10, retardation time τ = 0.01 s, ν = 0.3) by a load of 0.15 N applied at t = 0 and
held. The contact radius grows monotonically, so Lee & Radok's solution holds: the elastic Hertz
relations with the creep compliance J(t) in place of 1/G,

.. math:: a(t)^3 = \\frac{3 W R (1-\\nu)}{8} J(t), \\qquad \\delta(t) = a(t)^2 / R .

The shipped case runs on a coarser grid here (64² instead of 128²).
"""

import matplotlib.pyplot as plt
import numpy as np

import viscontact as vc
from viscontact.physics.reference import lee_radok_creep

case = vc.load_case(vc.shipped_case("creep_indentation")).with_overrides({"grid.n": 64})
ds = vc.run(case)
problem = case.to_problem()

# %%
# The approach δ(t) and the contact area against Lee & Radok's solution.
t = ds["t"].values
tau = float(ds["retardation_time"])
exact = lee_radok_creep(0.15, case.indenter.radius, problem.material, t)

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.5), sharex=True)
ax1.plot(t / tau, ds["delta_z"] * 1e6, "o", ms=3, label="viscontact, 64²")
ax1.plot(t / tau, exact.approach * 1e6, "k-", lw=1, label="Lee & Radok")
ax1.set(xlabel="t / τ", ylabel="approach δ [µm]")
ax1.legend()
ax2.plot(t / tau, ds["contact_area"] * 1e6, "o", ms=3)
ax2.plot(t / tau, np.pi * exact.radius**2 * 1e6, "k-", lw=1)
ax2.set(xlabel="t / τ", ylabel="contact area [mm²]")
fig.suptitle(f"Creep under a held load, a0 = {float(ds['a0']) * 1e6:.0f} µm, p0 = {float(ds['p0']) / 1e6:.3f} MPa")
fig.tight_layout()

error = np.max(np.abs(ds["delta_z"].values / exact.approach - 1))
print(f"largest relative error of the approach: {error:.1e}")

# %%
# The pressure along y = 0 at the first and the last step: the contact widens and the peak falls
# as the material creeps.
y0 = ds.sizes["y"] // 2
fig, ax = plt.subplots(figsize=(5, 3.5))
for k in (0, -1):
    ax.plot(ds["x"] / ds["a0"], ds["pressure"][k, y0] / ds["p0"], label=f"t = {t[k] / tau:.1f} τ")
ax.set(xlabel="x / a0", ylabel="p / p0")
ax.legend()
fig.tight_layout()
