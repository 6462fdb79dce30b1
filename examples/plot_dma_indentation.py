"""
DMA-like oscillating indentation: storage and loss moduli
=========================================================

A rigid sphere (R = 10 mm) is pushed δ₀ = 34.45 µm into the seed's Zener half-space (G(0) = 1.93 MPa,
G(∞) = G(0)/10, retardation time 10 ms, hence relaxation time τ = 1 ms, ν = 0.3) and the approach
oscillates about that mean, ``[normal] oscillation = {mean, amplitude, frequency, cycles}`` under
displacement control: δ(t) = δ₀ + Δ sin(ωt), as a dynamic mechanical analyser would drive it.

Once the mean relaxation has settled, the force oscillates at the same frequency, ahead of the
displacement by the loss angle. For a small amplitude the contact radius stays close to its mean a,
and the contact answers like a flat punch of that radius (Johnson, *Contact Mechanics*, §3.8: the
stiffness of a circular contact is 2 a E*, whatever its pressure): with the complex modulus
G*(ω) = G′ + i G″ in place of G,

.. math:: K^*(\\omega) = \\frac{\\hat W}{\\hat\\delta} = 2 a E^*(\\omega), \\qquad
          E^*(\\omega) = \\frac{2 G^*(\\omega)}{1-\\nu}, \\qquad
          G' = \\frac{(1-\\nu)\\,\\mathrm{Re}\\,K^*}{4a}, \\quad G'' = \\frac{(1-\\nu)\\,\\mathrm{Im}\\,K^*}{4a},

where Ŵ and δ̂ are the complex amplitudes of the force and the approach at ω, fitted by least squares
on sin ωt and cos ωt over the last two cycles, and a = √(A/π) from the mean contact area A over the
same cycles.

*Small* is against the relaxed mean: the mean load has relaxed to G(∞), while the oscillation sees
:math:`|G^*(\\omega)|`, up to G(0) = 10 G(∞). The contact edge therefore swings by about
:math:`(\\Delta/\\delta_0)\\,|G^*|/G(\\infty)` of a, not Δ/δ₀, and the amplitude here is 0.5 %
of the mean: at 3 % the mean contact radius at the highest frequency is 5 % smaller than at 0.5 % and
tan δ is 2.5 % low there, against 0.6 %. The rest of the error, about 1 %, is the contact radius
counted in cells of a/12 on this 48² grid (it cancels in tan δ) and the 32 steps a cycle.
"""

import matplotlib.pyplot as plt
import numpy as np

import viscontact as vc

G0, G_INF, RETARDATION, NU = 1.93e6, 0.193e6, 0.01, 0.3  # Pa, Pa, s, -
TAU = RETARDATION * G_INF / G0  # relaxation time [s]
MEAN, AMPLITUDE = 34.45e-6, 0.005 * 34.45e-6  # m
F_PEAK = 1.0 / (2 * np.pi * np.sqrt(TAU * RETARDATION))  # tan(delta) peaks at omega = 1/sqrt(tau tau_creep)
FIT_CYCLES = 2


def dma_case(frequency: float) -> vc.Case:
    """The oscillation at ``frequency`` [Hz]: the mean relaxation settles over 15 relaxation times (or one
    cycle), then FIT_CYCLES cycles are fitted; steps of at most tau / 2 (the approach jumps to the mean at
    t = 0) and at least 32 a cycle, a multiple of 4 so that every peak and trough is a step."""
    period = 1.0 / frequency
    cycles = int(np.ceil(15 * TAU / period)) + FIT_CYCLES
    points = max(32, 4 * int(np.ceil(period / (4 * 0.5 * TAU))))
    return vc.Case.from_dict({
        "material": {"type": "zener", "shear_modulus_instantaneous": G0, "shear_modulus_long_term": G_INF,
                     "retardation_time": RETARDATION, "poisson_ratio": NU},
        "indenter": {"shape": "sphere", "radius": 0.01},
        "grid": {"n": 48, "half_width": 1.2e-3},
        "normal": {"control": "displacement",
                   "oscillation": {"mean": MEAN, "amplitude": AMPLITUDE, "frequency": frequency,
                                   "cycles": cycles, "points_per_cycle": points}},
        "tangential": {"mode": "none"},
        "time": {"t_end": cycles * period, "dt": period / points},
    })


def fitted(t: np.ndarray, frequency: float) -> np.ndarray:
    """The steps of the last FIT_CYCLES whole cycles, [t_end - FIT_CYCLES / frequency, t_end)."""
    eps = 1e-6 / frequency
    return (t > t[-1] - FIT_CYCLES / frequency - eps) & (t < t[-1] - eps)


def complex_amplitude(t: np.ndarray, x: np.ndarray, omega: float) -> complex:
    """X with x(t) ≈ c + Im(X exp(i omega t)) = c + Re X sin(omega t) + Im X cos(omega t), least squares."""
    basis = np.column_stack([np.ones_like(t), np.sin(omega * t), np.cos(omega * t)])
    _, s, c = np.linalg.lstsq(basis, x, rcond=None)[0]
    return complex(s, c)


# %%
# One run per frequency, from F_PEAK/8 to 8 F_PEAK (F_PEAK = 50 Hz); the moduli from the last two cycles.
frequencies = F_PEAK * 2.0 ** np.arange(-3, 4)
storage, loss, runs = [], [], {}
for f in frequencies:
    ds = vc.run(dma_case(f))
    t, omega = ds["t"].values, 2 * np.pi * f
    last = fitted(t, f)
    k_star = (complex_amplitude(t[last], ds["load"].values[last], omega)
              / complex_amplitude(t[last], ds["delta_z"].values[last], omega))
    a = np.sqrt(ds["contact_area"].values[last].mean() / np.pi)
    storage.append(k_star.real * (1 - NU) / (4 * a))
    loss.append(k_star.imag * (1 - NU) / (4 * a))
    runs[f] = ds

material = dma_case(F_PEAK).to_problem().material
omegas = 2 * np.pi * frequencies
exact_storage, exact_loss = material.storage_modulus(omegas), material.loss_modulus(omegas)
storage, loss = np.array(storage), np.array(loss)
print(" f [Hz]   G' [MPa] (exact)     error    G'' [MPa] (exact)    error   tan δ (exact)")
for row in zip(frequencies, storage, exact_storage, loss, exact_loss):
    f, gs, es, gl, el = row
    print(f"{f:7.1f}  {gs / 1e6:7.4f} ({es / 1e6:7.4f})  {gs / es - 1:+7.2%}   {gl / 1e6:7.4f} ({el / 1e6:7.4f})  "
          f"{gl / el - 1:+7.2%}   {gl / gs:.3f} ({el / es:.3f})")

# %%
# The run at the tan δ peak: at the mean approach the load relaxes from its instantaneous value to the
# relaxed one within a few relaxation times (the fit starts after 15), then oscillates ahead of the
# approach by the loss angle δ = arctan(G″/G′); over the fitted cycles load against approach is an
# ellipse whose area is the energy dissipated per cycle, π Im(K*) Δ².
ds = runs[F_PEAK]
t, load, approach = ds["t"].values, ds["load"].values, ds["delta_z"].values
print(f"load at the mean approach: {load[0] * 1e3:.1f} mN at t = 0, {load[t > 15 * TAU].mean() * 1e3:.2f} mN "
      f"on average after 15 τ")
last = fitted(t, F_PEAK)
load_hat = complex_amplitude(t[last], load[last], 2 * np.pi * F_PEAK)
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.5))
cycles = (t[last] - t[last][0]) * F_PEAK
ax1.plot(cycles, (approach[last] - MEAN) / AMPLITUDE, "k-", lw=1, label="approach (δ − δ₀) / Δ")
ax1.plot(cycles, (load[last] - load[last].mean()) / abs(load_hat), "C0-", lw=1, label="load (W − W̄) / |Ŵ|")
ax1.set(xlabel="cycles (of the fitted two)", ylabel="normalised", ylim=(-1.2, 1.6))
ax1.legend(loc="upper right", fontsize="small", ncols=2)
ax2.plot((approach[last] - MEAN) * 1e9, load[last] * 1e3, "-", lw=1)
ax2.set(xlabel="approach δ − δ₀ [nm]", ylabel="load W [mN]")
fig.suptitle(f"Oscillation at f = {F_PEAK:.1f} Hz (ωτ = {2 * np.pi * F_PEAK * TAU:.2f}, tan δ = "
             f"{loss[3] / storage[3]:.2f}), 48² grid")
fig.tight_layout()

# %%
# The recovered moduli (markers) against the material's own G′(ω), G″(ω) and tan δ (lines).
w = np.logspace(np.log10(omegas[0]) - 0.3, np.log10(omegas[-1]) + 0.3, 200)
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.5))
ax1.loglog(w * TAU, material.storage_modulus(w) / 1e6, "C0-", lw=1, label="G′, material")
ax1.loglog(w * TAU, material.loss_modulus(w) / 1e6, "C1-", lw=1, label="G″, material")
ax1.loglog(omegas * TAU, storage / 1e6, "C0o", label="G′, from the indentation")
ax1.loglog(omegas * TAU, loss / 1e6, "C1s", label="G″, from the indentation")
ax1.set(xlabel="ωτ", ylabel="modulus [MPa]")
ax1.legend(fontsize="small")
ax2.semilogx(w * TAU, material.loss_modulus(w) / material.storage_modulus(w), "k-", lw=1, label="material")
ax2.semilogx(omegas * TAU, loss / storage, "o", label="from the indentation")
ax2.set(xlabel="ωτ", ylabel="tan δ = G″ / G′")
ax2.legend(fontsize="small")
fig.suptitle("Storage and loss moduli from the force–approach phase lag")
fig.tight_layout()

print(f"largest relative error: G' {np.max(np.abs(storage / exact_storage - 1)):.1%}, "
      f"G'' {np.max(np.abs(loss / exact_loss - 1)):.1%}")
