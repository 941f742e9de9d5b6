"""
A day in GEO with Sun-tracking arrays: the wheel-momentum budget
================================================================

A geostationary spacecraft that points at the Earth turns once a day in inertial space, and its solar
arrays turn once a day about their drive axis to keep the cells on the Sun. The solar pressure on an
asymmetric body (a dish on one side, a nozzle on another, the centre of pressure off the reference
point) then gives a torque that changes through the day; what the orbit average leaves over is
momentum the reaction wheels have to store, and in the end the thrusters have to dump.

This example flies the sample spacecraft for one day in GEO on the March equinox, Earth-pointing, with
both wings driven about body y to track the Sun, and adds up the body-frame angular impulse: the
momentum that body-fixed wheels absorb.
"""

# %%
# The spacecraft and its array drive
# ----------------------------------
# The sample spacecraft is built here at about 3 000 triangles (the shipped files have 20 000; the
# loads differ by well under one per cent, and this one keeps the page quick). Its materials file is
# the sample's own, with an ``[articulation]`` table added: both wings (parts ``wing_left`` and
# ``wing_right``, matched by the glob ``wing_*``) turn about the body y axis through the body origin,
# their cells as close to the Sun as the hinge allows. :meth:`~sunwind.Model.angles_at` gives the drive
# angle for a Sun direction, :meth:`~sunwind.Model.posed` the model at that angle.
#
# The torques are taken about the centre of the bus, on the array axis, standing for the centre of
# mass (a real budget takes it from the mass properties: a centre of mass a few centimetres off the
# array axis adds a daily torque about y of the wings' force times that offset).
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import sunwind as sw

ARRAY_DRIVE = """
[articulation."wing_*"]
axis = [0, 1, 0]
origin_m = [0, 0, 0]
track = "sun"
"""
mesh = sw.meshes.sample_spacecraft(triangles=3000)
workdir = tempfile.TemporaryDirectory(prefix="sunwind-geo-")  # removed when the script ends
folder = Path(workdir.name)
materials = folder / "sample_tracking.toml"
materials.write_text(sw.meshes.materials_toml(mesh) + ARRAY_DRIVE, encoding="utf-8")
model = sw.load(mesh, materials, reference_point_m=(0.0, 0.0, 0.0), threads=1)
point, where = model.reference()
print(model.craft)
print("hinges:", ", ".join(f"{h.pattern} ({h.law})" for h in model.hinges))
print(f"torque reference point: {np.round(point, 4)} m, body frame ({where})")
for sun in ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [-1.0, 0.0, -1.0]):
    print(f"  Sun along {sun} (body): wing drive at {model.angles_at(np.array(sun))['wing_*']:.1f} deg")

# %%
# The orbit and the attitude
# --------------------------
# A circular equatorial orbit 35 786 km above the equator, two-body motion, 73 steps of 20 minutes
# from 2024-03-20 00:00 UTC (the Sun's ephemeris from ERFA, so the spacecraft passes through the
# Earth's shadow near local midnight). The attitude law ``nadir`` holds the LVLH frame: body +z to the
# Earth's centre, +y along the negative orbit normal, so the wings' drive axis stays normal to the
# orbit plane and a drive turn a day keeps the cells on the Sun.
epoch = sw.orbit.Epoch.of("2024-03-20T00:00:00Z")
times_s = np.linspace(0.0, 86400.0, 73)
path = sw.orbit.propagate(sw.orbit.Elements.circular(35786.0, 0.0), epoch, times_s, "kepler")
attitude = sw.orbit.AttitudeLaw.parse("nadir")

# %%
# Flying it
# ---------
# :func:`sunwind.fly` poses the model at every step's drive angle (rounded here to 10 deg, so that
# steps share posed models), casts the shadows and applies the surface law at the flux of that step
# (distance from the Sun and eclipse). Inter-reflection between the wings and the bus is left out to
# keep this quick (``reflections="none"``); it changes the torque by a few per cent on this model.
loads = sw.orbit.OrbitLoads(srp=sw.SrpSetup(reflections="none"), hinge_step_deg=10.0)
result = sw.fly(model, path, attitude, loads)
summary = result.summary()
s = result.series
hours = s["time_s"] / 3600.0
print(
    f"{summary['steps']} steps over {summary['duration_s'] / 3600:.0f} h, period {summary['period_s']:.0f} s"
)
for start, end in summary["eclipses_s"]:
    print(f"eclipse from {start / 3600:.2f} h to {end / 3600:.2f} h (steps of 20 min)")
print(
    f"mean SRP force (GCRF): {np.array2string(np.array(summary['mean_force_eci_N']) * 1e6, precision=3)} uN"
)
print(f"effective SRP area C_R A = {summary['srp_area_m2']:.2f} m^2")
print(
    f"largest torque {summary['max_torque_Nm'] * 1e6:.2f} uN m at {summary['max_torque_time_s'] / 3600:.1f} h"
)
impulse = np.array(summary["angular_impulse_body_Nms"])
print(f"angular impulse after one day, body frame: {np.array2string(impulse * 1e3, precision=3)} mN m s")
swing = np.ptp(s["angular_impulse_body_Nms"], axis=0)
print(f"  swing of H through the day: {np.array2string(swing * 1e3, precision=2)} mN m s (x, y, z)")
print(f"momentum built per orbit in GCRF: {summary['momentum_per_orbit_Nms'] * 1e3:.2f} mN m s")

# %%
# The figure
# ----------
# Top, the body-frame SRP torque about the bus centre; middle, the wings' drive angle (a turn a day,
# shown within ±180 deg); bottom, the angular impulse the wheels absorb. At the equinox the Sun lies
# in the orbit plane, the body x-z plane, and the spacecraft is symmetric about that plane, so all the
# torque is about y, the orbit normal. It changes sign through the day as the Sun moves round the dish
# (+z), the nozzle (-z) and the boom (-x), and mostly cancels: the wheels must hold a cyclic swing of
# tens of mN m s, while what is left at the end of the day, a few mN m s, is the secular part that
# adds up day after day and must be dumped. In the Earth's shadow the torque is zero.
eclipsed = s["solar_fraction"] < 1.0
fig, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True, constrained_layout=True)
for k, axis in enumerate("xyz"):
    axes[0].plot(hours, s["torque_body_Nm"][:, k] * 1e6, label=f"$M_{axis}$")
    axes[2].plot(hours, s["angular_impulse_body_Nms"][:, k] * 1e3, label=f"$H_{axis}$")
axes[1].plot(hours, result.hinge_angles_deg["wing_*"], "k.", ms=4)
axes[0].set_ylabel("SRP torque [µN m]")
axes[1].set_ylabel("wing drive angle [deg]")
axes[2].set_ylabel("angular impulse [mN m s]")
axes[2].set_xlabel("hours after 2024-03-20 00:00 UTC")
axes[0].legend(ncol=3)
axes[2].legend(ncol=3)
for ax in axes:
    ax.fill_between(hours, 0, 1, where=eclipsed, color="0.85", transform=ax.get_xaxis_transform(), lw=0)
    ax.grid(alpha=0.3)
axes[0].set_title("Earth-pointing sample spacecraft in GEO, equinox (grey: the Earth's shadow)")
plt.show()
