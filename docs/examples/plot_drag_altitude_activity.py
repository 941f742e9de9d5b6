"""
Drag coefficient through the thermosphere and the solar cycle
=============================================================

The free-molecular drag coefficient of a body is not a constant: it depends on the speed ratio
``S = V / sqrt(2 k T / m)`` of the flow (how fast the spacecraft moves against the thermal speed of the
molecules) and on how the gas meets the wall. Both change with altitude and with solar activity: higher
up, the air is lighter (atomic oxygen, then helium and hydrogen) and hotter, and a more active Sun heats
the thermosphere further. Lower speed ratios mean more of the molecules strike the sides and the back
of the body, which raises ``C_D``.

This example takes a 1 m cube flying face-on, its walls re-emitting with the DRIA law (diffuse
reflection with incomplete energy accommodation, ``alpha_E = 0.9``, wall at 300 K), and computes
``C_D`` from 200 to 800 km in NRLMSIS 2.1 atmospheres for low, moderate and high solar activity
(F10.7 = 70, 150 and 250 sfu, daily and 81-day values equal, Ap = 4).
"""

# %%
# The model
# ---------
# A cube of 1 m edges from :mod:`sunwind.meshes`, loaded from memory with one material whose
# gas-surface law is DRIA. The reference area is the 1 m\ :sup:`2` face the flow meets, so ``C_D``
# reads as the usual coefficient of a face-on cube; the torque reference point is the cube's centre.
# A convex body sends no molecule back onto itself, so inter-reflection is switched off.
import matplotlib.pyplot as plt
import numpy as np

import sunwind as sw

cube = sw.meshes.box((1.0, 1.0, 1.0))
wall = sw.Material("anodised", reflectivity=0.2, specular_fraction=0.1)
model = sw.load(
    cube,
    uniform=wall,
    gas={"gsi": "dria", "energy_accommodation": 0.9, "wall_temperature": 300.0},
    reference_area_m2=1.0,
    reference_point_m=(0.0, 0.0, 0.0),
    threads=1,
)
print(model.craft)

# %%
# Drag at every altitude and activity level
# -----------------------------------------
# At each altitude the flow is ``v_rel = (V, 0, 0)`` in the body frame with ``V`` the circular-orbit
# speed, so the molecules arrive on the +x face. NRLMSIS is evaluated over the equator at 12:00 local
# time on the March equinox of 2024.
altitudes_km = np.arange(200.0, 801.0, 50.0)
activity = {"low (F10.7 = 70)": 70.0, "moderate (F10.7 = 150)": 150.0, "high (F10.7 = 250)": 250.0}
cd, ratio, density = {}, {}, {}
for name, f107 in activity.items():
    cd[name], ratio[name], density[name] = [], [], []
    for h in altitudes_km:
        air = sw.nrlmsis(h, 0.0, 0.0, "2024-03-20T12:00:00Z", f107=f107, f107a=f107, ap=4.0)
        speed = sw.circular_speed(h)
        result = sw.drag(model, [speed, 0.0, 0.0], air, reflections="none")
        cd[name].append(result.CD)
        ratio[name].append(result.speed_ratio)
        density[name].append(air.density_kg_m3)

print("C_D of the face-on 1 m cube (reference area 1 m^2, DRIA alpha_E = 0.9, T_wall = 300 K)")
print(f"{'altitude [km]':>14} " + " ".join(f"{name:>24}" for name in activity))
for k, h in enumerate(altitudes_km):
    cells = " ".join(f"{cd[name][k]:>10.3f} (S = {ratio[name][k]:4.2f})  " for name in activity)
    print(f"{h:>14.0f} {cells}")

# %%
# One attitude in full
# --------------------
# A single result carries the flow, the atmosphere and the coefficients; the force is in the body
# frame [N] and the torque about the cube's centre [N m] (zero here by symmetry).
air = sw.nrlmsis(400.0, 0.0, 0.0, "2024-03-20T12:00:00Z", f107=150.0, f107a=150.0, ap=4.0)
result = sw.drag(model, [sw.circular_speed(400.0), 0.0, 0.0], air, reflections="none")
print(f"400 km, moderate activity: rho = {air.density_kg_m3:.3e} kg/m^3, T = {air.temperature_K:.0f} K")
print(
    f"  V = {result.speed_m_s:.1f} m/s, q = {result.dynamic_pressure_Pa:.3e} Pa, S = {result.speed_ratio:.2f}"
)
print(f"  force (body frame) = {np.array2string(result.force_N * 1e3, precision=4)} mN")
print(f"  torque about the centre = {np.array2string(result.torque_Nm, precision=2)} N m")
print(f"  C_D = {result.CD:.3f}, C_L = {result.CL:.2e}")

# %%
# The figure
# ----------
# Left, ``C_D`` against altitude; right, the mean speed ratio ``S`` that drives it, and the density
# (dashed, right axis) that sets how much the drag matters at all. ``C_D`` rises with altitude as ``S``
# falls. Below about 600 km a hotter thermosphere (high activity) means a lower ``S`` and a higher
# ``C_D``; above, the order turns over: a quiet Sun leaves the upper thermosphere cold and thin, so
# light helium takes over from atomic oxygen at lower altitudes, and helium's small mass makes the
# speed ratio the lowest of the three. A coefficient held fixed through an orbit and a solar cycle is
# off by ten per cent or more.
fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.2), constrained_layout=True)
colours = ("tab:blue", "tab:orange", "tab:red")
for colour, name in zip(colours, activity, strict=True):
    left.plot(altitudes_km, cd[name], "o-", color=colour, ms=3, label=name)
    right.plot(altitudes_km, ratio[name], "o-", color=colour, ms=3, label=name)
left.set(xlabel="altitude [km]", ylabel="$C_D$ (reference area 1 m$^2$)", title="face-on 1 m cube, DRIA")
left.grid(alpha=0.3)
left.legend(title="solar activity")
right.set(xlabel="altitude [km]", ylabel="mean speed ratio $S$", title="speed ratio and density")
right.grid(alpha=0.3)
rho_axis = right.twinx()
for colour, name in zip(colours, activity, strict=True):
    rho_axis.semilogy(altitudes_km, density[name], "--", color=colour, lw=1)
rho_axis.set_ylabel("density [kg/m$^3$] (dashed)")
plt.show()
