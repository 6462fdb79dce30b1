"""
Viscoelastic adhesion: hysteresis friction of a sticky sphere against speed
===========================================================================

The sphere and the PDMS-like Zener half-space of ``adhesive_pdms_retraction.toml`` (R = 10 mm,
G(0) = 1.05 MPa, G(∞) = 0.35 MPa, τ = 0.1 s, ν = 0.5; w = 50 mJ/m², σ₀ = 19 kPa), pressed with 1 mN and
slid frictionless (``tangential.mode = "frictionless_sliding"``) over 2 mm at speeds from a/(100 τ) to
100 a/τ, with and without ``[adhesion]``. The apparent friction coefficient μ_app = F_T / W is the
viscoelastic hysteresis alone (the resultant of the pressure on the slope of the deformed surface).

Without adhesion it is the bell of rolling/sliding hysteresis, largest where the contact is crossed in
about a retardation time. Adhesion adds a tensile ring whose trailing edge opens at a different
energy release rate than the leading edge closes (Carbone, Mandriota & Menga 2022, *Extreme Mech.
Lett.* 56, 101877): at this load the contact is about four times larger and the bell about ten times
taller, its peak still near v τ / a = 1; in both limits, relaxed and glassy, the body is elastic and
the friction vanishes. With ``tangential.mode = "gross_sliding"`` a Coulomb friction μ_f max(p, 0)
would add μ_f times the compressive load (docs: Numerics, section 10). 64² cells of 20 µm; at the
fastest speeds the material's memory still reaches past the trailing edge of the grid, which the run
warns about (a bias of about 2 %: ``wake_loss``). The lines are the steady states of the same cases
(``viscontact steady``, ``vc.run_steady`` with a list of speeds: the effective steady kernel
integrates the whole past, so it has no such bias), 25 speeds in a fraction of one transient run;
they peak at μ_app = 0.0041 (vτ/a = 0.56) without adhesion and 0.0545 (vτ/a = 0.63) with it, the
transient's points on them.
"""

import matplotlib.pyplot as plt
import numpy as np

import viscontact as vc

G0, G_INF, TAU, NU = 1.05e6, 0.35e6, 0.1, 0.5  # Pa, Pa, s, -
R, LOAD, DISTANCE = 0.01, 1e-3, 2e-3  # m, N, m
A_REF = 0.3e-3  # m, about the contact radius: speeds in units of A_REF / TAU


def sliding_case(speed: float, adhesive: bool) -> vc.Case:
    """Frictionless sliding at ``speed`` [m/s] over DISTANCE (one cell a step), with or without adhesion."""
    data = {
        "material": {"type": "zener", "shear_modulus_instantaneous": G0, "shear_modulus_long_term": G_INF,
                     "retardation_time": TAU, "poisson_ratio": NU},
        "indenter": {"shape": "sphere", "radius": R},
        "grid": {"n": 64, "half_width": 0.64e-3},
        "normal": {"control": "load", "value": LOAD},
        "tangential": {"mode": "frictionless_sliding", "sliding_speed": speed},
        "time": {"t_end": DISTANCE / speed, "scheme": "linear"},
    }
    if adhesive:
        data["adhesion"] = {"work_of_adhesion": 0.05, "law": "maugis_dugdale", "cohesive_stress": 1.9e4}
    return vc.Case.from_dict(data)


# %%
# Seven speeds, each run with and without adhesion; μ_app at the end of the slide (the last tenth
# averaged).
speeds = A_REF / TAU * np.logspace(-2, 2, 7)
mu = {True: [], False: []}
area = {True: [], False: []}
for v in speeds:
    for adhesive in (False, True):
        ds = vc.run(sliding_case(v, adhesive))
        last = slice(-max(1, ds.sizes["t"] // 10), None)
        mu[adhesive].append(float(ds["mu_app"][last].mean()))
        area[adhesive].append(float(ds["contact_area"][last].mean()))
print(" v tau / a    mu_app (no adhesion)   mu_app (adhesion)   contact area ratio")
for v, m0, m1, a0, a1 in zip(speeds, mu[False], mu[True], area[False], area[True]):
    print(f"{v * TAU / A_REF:9.2f}   {m0:18.4f}   {m1:17.4f}   {a1 / a0:18.2f}")

# %%
# The steady states on a finer sweep of speeds (each started from the last).
steady_speeds = A_REF / TAU * np.logspace(-2, 2, 25)
steady = {adhesive: vc.run_steady(sliding_case(steady_speeds[0], adhesive), speeds=list(steady_speeds))
          for adhesive in (False, True)}

# %%
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
for (adhesive, label), color in zip(((False, "no adhesion"), (True, "w = 50 mJ/m², λ = 1 (G(∞))")), ("C0", "C1")):
    ax1.semilogx(speeds * TAU / A_REF, mu[adhesive], "o", color=color, label=f"{label}, transient")
    ax1.semilogx(steady_speeds * TAU / A_REF, steady[adhesive]["mu_app"], "-", color=color, label=f"{label}, steady")
    ax2.semilogx(speeds * TAU / A_REF, np.array(area[adhesive]) * 1e6, "o", color=color, label=label)
    ax2.semilogx(steady_speeds * TAU / A_REF, steady[adhesive]["contact_area"] * 1e6, "-", color=color)
ax1.set(xlabel="speed v τ / a", ylabel="μ_app = F_T / W (hysteresis)")
ax2.set(xlabel="speed v τ / a", ylabel="contact area [mm²]")
ax1.legend(fontsize="small")
fig.suptitle(f"Frictionless sliding of a sphere on a Zener half-space under W = {LOAD * 1e3:g} mN")
fig.tight_layout()
plt.show()
