"""
Rolling with traction: a ball braking on a rubber
=================================================

The shipped case ``rolling_polymer_roller``: a rigid ball (R = 10 mm) rolls under 0.15 N over the
seed's Zener rubber (G(0) = 1.93 MPa, G(∞) = G(0)/10, τ = 10 ms, ν = 0.5) at V = a0/τ, braking with
a held creepage ξ = (V_c − V)/V = −0.5 % (its surface turns 0.5 % slower than it rolls). Signs: the
indenter rolls in +x; with ξ < 0 the traction on the body points in +x and ``friction_force`` > 0.

From standstill the traction builds as the body rolls, the contact passing from a Cattaneo-like state
(all stuck, slip spreading in from the edge) to the steady Carter–Kalker state: a stick zone
at the leading edge, a slip zone behind it. The steady rolling solver (``viscontact steady``) gives
that state directly, and a traction–creepage curve in one call (``--creepages``); here at three
speeds, where the body is relaxed (slow), in its transition and glassy (fast), with the rolling
resistance F_T/W, the body's hysteresis, against speed.

Here on a 32² grid instead of the case's 64²: a preview.
"""

import matplotlib.pyplot as plt
import numpy as np

import viscontact as vc

case = vc.load_case(vc.shipped_case("rolling_polymer_roller")).with_overrides({"grid.n": 32})

# %%
# The transient from standstill, and the steady state it tends to.
ds = vc.run(case)
steady = vc.run_steady(case)
tau, load = float(ds["retardation_time"]), float(ds["load"][-1])
print(f"traction at the end {float(ds['friction_force'][-1]) / load:.4f} W, "
      f"steady {float(steady['friction_force'][0]) / load:.4f} W")
print(f"rolling resistance at the end {float(ds['mu_app'][-1]):.4f}, steady {float(steady['mu_app'][0]):.4f}")

fig, ax = plt.subplots(figsize=(6, 3.6))
ax.plot(ds["t"] / tau, ds["friction_force"] / load, label="traction Σ q_x ΔA / W")
ax.plot(ds["t"] / tau, ds["stick_ratio"], label="stick ratio")
ax.axhline(float(steady["friction_force"][0]) / load, ls=":", c="k", label="steady rolling solver")
ax.set(xlabel="t / τ", ylabel="[-]", title="from standstill to steady rolling")
ax.legend()
fig.tight_layout()

# %%
# Stick maps (stuck points dark, slipping ones light) as the traction builds: the stick zone moves to
# the leading edge (+x).
a0 = float(ds["a0"])
fig, axes = plt.subplots(1, 3, figsize=(10, 3.4), sharey=True)
for ax, t in zip(axes, (2.0, 8.0, float(ds["t"][-1]) / tau)):
    k = int(np.argmin(np.abs(ds["t"].values - t * tau)))
    state = (ds["pressure"][k] > 0).astype(int) + ds["stick"][k].astype(int)
    ax.imshow(state, origin="lower", cmap="Greys", vmin=0, vmax=2,
              extent=[float(ds.x[0]) / a0, float(ds.x[-1]) / a0, float(ds.y[0]) / a0, float(ds.y[-1]) / a0])
    ax.set(xlabel="x / a0", title=f"t = {float(ds['t'][k]) / tau:.0f} τ")
axes[0].set_ylabel("y / a0")
fig.tight_layout()

# %%
# Traction–creepage curves of steady rolling at three speeds: relaxed (V τ = 0.01 a0), in the
# transition (a0) and glassy (100 a0). The stiffer the body, the steeper the curve at small creepage
# (Kalker's creep coefficient scales with the modulus), and each saturates at μ_f W.
creepages = [-0.04, -0.02, -0.01, -0.005, -0.002, -0.001, 0.0]
fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
for deborah in (0.01, 1.0, 100.0):
    curve = vc.run_steady(case.with_overrides({"tangential.rolling_speed": deborah * a0 / tau}),
                          creepages=creepages)
    axes[0].plot(-curve["creepage"], curve["traction_ratio"], "o-", ms=3, label=f"V τ / a0 = {deborah:g}")
    axes[1].plot(-curve["creepage"], curve["stick_ratio"], "o-", ms=3, label=f"V τ / a0 = {deborah:g}")
axes[0].set(xlabel="braking creepage −ξ [-]", ylabel="traction F / (μ_f W) [-]")
axes[1].set(xlabel="braking creepage −ξ [-]", ylabel="stick ratio [-]")
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend()
fig.tight_layout()

# %%
# Rolling resistance against speed (the hysteresis of the body, F_T / W of seed Eq. 15) at the held
# creepage: small where the body is relaxed or glassy, largest in between.
speeds = a0 / tau * np.logspace(-2, 2, 9)
resistance = [float(vc.run_steady(case.with_overrides({"tangential.rolling_speed": v}))["mu_app"][0]) for v in speeds]
fig, ax = plt.subplots(figsize=(5, 3.6))
ax.semilogx(speeds * tau / a0, resistance, "o-")
ax.set(xlabel="V τ / a0", ylabel="rolling resistance F_T / W [-]")
ax.grid(alpha=0.3, which="both")
fig.tight_layout()
