"""
Rough contact: an elastomer on a periodic self-affine surface
=============================================================

The shipped case ``rough_periodic_sliding``: the seed's Zener elastomer (G(0) = 1.93 MPa,
G(∞) = G(0)/10, τ = 10 ms, ν = 0.3) pressed by a mean pressure of 10 kPa onto one period
(1 mm × 1 mm) of a rigid, randomly rough surface (self-affine, Hurst exponent 0.8, rms slope 0.1,
shortest wavelength 125 µm), then pulled sideways. The domain is periodic (``[grid] periodic =
true``): the period repeats without end, the convolutions are periodic FFTs and the material that
leaves at −x re-enters at +x.

First partial slip at 0.2 mm/s: the real contact area grows by creep while stick islands shrink
inside the contact spots; when the last one slips (t ≈ 5.9τ, on this grid as on the case's: 5.94τ at
32², 5.86τ at 64²) the whole contact slides at 20 mm/s, the real contact area drops (the sliding
half-space responds stiffer than the creeping one) and the apparent friction μ_app = F_T/W, the
hysteresis friction of seed Eq. 15, rises to the steady state of ``viscontact steady``, which on a
periodic domain is exact (every Fourier mode of the surface through the complex modulus at its
frequency k_x v).

Here on a 32² grid instead of the case's 64²: a preview (about 100 steps).
"""


import matplotlib.pyplot as plt
import numpy as np

import viscontact as vc
from viscontact.plotting.result import pressure_maps_figure, stick_maps_figure

case = vc.load_case(vc.shipped_case("rough_periodic_sliding")).with_overrides({"grid.n": 32})
problem = case.to_problem()

# %%
# The rigid surface on the grid: heights h = max(h0) − h0 from the undeformed gap h0, z up. The
# generated realisation is scaled to its rms slope (the norm of the gradient by forward differences,
# wrapping around the period) on the grid it is sampled on: a coarser grid gives a smoother surface
# (smaller rms height), not the same surface resolved less.
grid = problem.grid
heights = problem.gap.max() - problem.gap
gradient = np.hypot(np.roll(heights, -1, axis=1) - heights, np.roll(heights, -1, axis=0) - heights) / grid.spacing
print(f"{grid.n}² points: rms height {heights.std() * 1e6:.2f} µm, rms slope {np.sqrt(np.mean(gradient**2)):.3f}")

w_mm = grid.half_width * 1e3
fig, ax = plt.subplots(figsize=(5, 4.2))
image = ax.imshow(heights * 1e6, origin="lower", extent=(-w_mm, w_mm, -w_mm, w_mm), cmap="cividis")
fig.colorbar(image, ax=ax, label="height h [µm]")
ax.set(xlabel="x [mm]", ylabel="y [mm]", title="one period of the rough surface")
fig.tight_layout()

# %%
# The transient run and the periodic steady state at the sliding speed.
ds = vc.run(case)
steady = vc.run_steady(case)
tau = float(ds["retardation_time"])
t_gross = float(ds["t_gross_sliding"])
print(f"{ds.sizes['t']} records; gross sliding from t = {t_gross / tau:.2f} τ")
print(f"mu_app at the end {float(ds['mu_app'][-1]):.4f}, periodic steady state {float(steady['mu_app'][0]):.4f}")

# %%
# Pressure maps at chosen times, over the period: at 1τ and half a τ before gross sliding, the
# contact spots grow by creep; half a τ after it and at the end they have shrunk to the faces of the
# asperities that meet the sliding elastomer.
times = [tau, t_gross - 0.5 * tau, t_gross + 0.5 * tau, float(ds["t"][-1])]
fig = pressure_maps_figure(ds, times)

# %%
# The same times as stick (blue) and slip (orange) maps: the stick islands shrink to nothing at the
# onset of gross sliding.
fig = stick_maps_figure(ds, times)

# %%
# The apparent friction μ_app and the real contact area fraction A_r/A_0 against time, with the
# periodic steady state (dashed). Before gross sliding μ_app is no hysteresis friction: it is small and
# negative, the tilt of the surface under the shear tractions (the normal displacement they cause
# when ν < 0.5). ``viscontact plot`` draws these with the number of contact patches and the mean gap
# as ``rough_contact``.
t = ds["t"].values / tau
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.8), sharex=True)
ax1.plot(t, ds["mu_app"], label="transient")
ax1.axhline(float(steady["mu_app"][0]), color="k", ls="--", lw=1, label="periodic steady state")
ax1.set(xlabel="t / τ", ylabel="μ_app = F_T / W [-]")
ax2.plot(t, ds["contact_fraction"])
ax2.axhline(float(steady["contact_fraction"][0]), color="k", ls="--", lw=1)
ax2.set(xlabel="t / τ", ylabel="real contact area fraction A_r / A_0 [-]")
for ax in (ax1, ax2):
    ax.axvline(t_gross / tau, color="grey", ls=":", lw=0.8)
    ax.grid(alpha=0.3)
ax1.legend()
fig.suptitle(f"{ds.attrs['title']}, 32² (dotted: gross sliding begins)", fontsize=10)
fig.tight_layout()
