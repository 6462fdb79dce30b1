"""
A polymer roller in line contact against Hunter's curve
=======================================================

The shipped case ``polymer_roller_line_contact``: a rigid steel roller (R = 10 mm, infinitely long:
``grid.dimension = 1``, plane strain) pressed with 2000 N/m on a Zener polymer (G(0) = 20 MPa,
G(∞) = 2 MPa, retardation time τ = 1 ms, ν = 0.5), then pushed along x until it slides at 0.5 m/s,
v τ / a0 = 0.89 (a0 = 564 µm, the Hertz half-width with G(0)).

Once sliding, the contact tends to the steady state of the isolated cylinder, the problem S. C. Hunter
solved in closed form (J. Appl. Mech. 28, 1961, 611-617):
:func:`viscontact.physics.reference.hunter_cylinder`. The apparent (hysteresis) friction
μ_app = ∫ p x dx / (R W) of the transient, of the steady solver (``viscontact steady``) and Hunter's;
then the steady solver's μ_app and contact edges against v τ / a0 from 0.01 to 1000, on Hunter's
curves. Slow and fast, the body is elastic (relaxed, glassy) and μ_app tends to 0.
"""

import matplotlib.pyplot as plt
import numpy as np

import viscontact as vc
from viscontact.physics.reference import contact_modulus, hertz_line_half_width, hunter_cylinder

case = vc.load_case(vc.shipped_case("polymer_roller_line_contact"))
m = case.material
tau, load, radius = m.retardation_time, case.normal.value, case.indenter.radius
a0 = hertz_line_half_width(load, radius, contact_modulus(m.shear_modulus_instantaneous, m.poisson_ratio))


def hunter(speed: float):
    return hunter_cylinder(load, radius, m.shear_modulus_instantaneous, m.shear_modulus_long_term, tau,
                           m.poisson_ratio, speed)


# %%
# From indentation through partial slip to steady sliding: μ_app against time.
ds = vc.run(case)
steady = vc.run_steady(case)
ref = hunter(case.tangential.sliding_speed)
print(f"mu_app: transient at 12 tau {float(ds['mu_app'][-1]):.5f}, steady solver "
      f"{float(steady['mu_app'][0]):.5f}, Hunter {ref.mu_app:.5f}")

fig, ax = plt.subplots(figsize=(6, 3.6))
ax.plot(ds["t"] / tau, ds["mu_app"], label="transient (n = 1024)")
ax.axhline(float(steady["mu_app"][0]), ls="--", c="C1", label="steady solver")
ax.axhline(ref.mu_app, ls=":", c="k", label="Hunter (1961)")
ax.set(xlabel="t / τ", ylabel="μ_app = F_T / W", title="roller: indentation to steady sliding")
ax.legend()
fig.tight_layout()

# %%
# The steady state against speed: μ_app from 0.01 to 1000 v τ / a0 on Hunter's curve, and the
# pressure at three speeds against Hunter's (the cylinder moves towards +x: the contact shifts ahead
# of the axis and narrows from the relaxed to the glassy Hertz width). The fresh material entering at the
# leading edge is glassy: the pressure rises there over a length v τ G(∞)/G(0), which below
# v τ / a0 ~ 0.03 is finer than a cell (μ_app 1.6 % low at 0.01).
deborahs = np.logspace(-2, 3, 11)
sweep = vc.run_steady(case, speeds=list(deborahs * a0 / tau))
for d, mu in zip(deborahs, sweep["mu_app"].values):
    print(f"v tau / a0 = {d:8.3f}: mu_app {mu:.5f}, Hunter {hunter(d * a0 / tau).mu_app:.5f}")
curve = np.logspace(-2, 3, 61)

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.6))
ax1.semilogx(curve, [hunter(d * a0 / tau).mu_app for d in curve], "k-", lw=1, label="Hunter (1961)")
ax1.semilogx(deborahs, sweep["mu_app"], "o", ms=4, label="viscontact steady, n = 1024")
ax1.set(xlabel="v τ / a0", ylabel="μ_app", title="apparent friction")
ax1.legend(loc="upper left")
for k, d in enumerate((0.1, 1.0, 10.0)):
    state = vc.run_steady(case.with_overrides({"tangential.sliding_speed": d * a0 / tau}))
    x = state["x"].values
    ax2.plot(x / a0, state["pressure"][0, 0] / 1e6, c=f"C{k}", label=f"v τ / a0 = {d:g}")
    ax2.plot(x / a0, hunter(d * a0 / tau).pressure(x) / 1e6, "k:", lw=1)
ax2.set(xlabel="x / a0", ylabel="p [MPa]", xlim=(-4, 4), title="pressure (dotted: Hunter)")
ax2.legend()
fig.tight_layout()
