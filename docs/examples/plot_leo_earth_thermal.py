"""
Earth albedo, infrared and thermal recoil in low orbit
======================================================

In low orbit the Earth is not a point: it fills a large part of the sky, reflects about 30 % of the
sunlight (albedo) and glows in the infrared. Both push on the spacecraft, from below, through a whole
cap of the Earth's surface; and the spacecraft, warmed by the Sun and the Earth, radiates its own heat
unevenly, which recoils (thermal re-emission). Next to direct solar pressure these are smaller terms,
but they do not switch off in eclipse as the Sun does.

This example flies a box-wing spacecraft through one orbit at 500 km, Earth-pointing with Sun-tracking
wings, and computes at every step the solar pressure, the Earth's albedo and infrared pressure over a
coarse grid of the visible cap, each face's radiative-equilibrium temperature and the recoil of the
heat it radiates.
"""

# %%
# The spacecraft
# --------------
# The bus is a 1.6 x 1.4 x 1.2 m box built from six plates of :func:`sunwind.meshes.plate`, turned
# and moved into place with :func:`~sunwind.meshes.transform` and named one part per face with
# :func:`~sunwind.meshes.label`, so that each face gets a temperature of its own. The two 3.2 x 1.1 m
# wings along ±y are sheets with cells in front; a hinge about y turns them to the Sun. Every
# material gives an infrared emissivity, which the Earth's infrared and the thermal balance need.
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import sunwind as sw

BUS = np.array([1.6, 1.4, 1.2])  # bus edges along x, y, z [m]
R = sw.meshes.rotation_matrix
# face name: (plate size along its own x and y, rotation taking the plate's +z to the face normal)
FACES = {
    "bus_+x": ((BUS[2], BUS[1]), R("y", 90.0)),
    "bus_-x": ((BUS[2], BUS[1]), R("y", -90.0)),
    "bus_+y": ((BUS[0], BUS[2]), R("x", -90.0)),
    "bus_-y": ((BUS[0], BUS[2]), R("x", 90.0)),
    "bus_+z": ((BUS[0], BUS[1]), None),
    "bus_-z": ((BUS[0], BUS[1]), R("x", 180.0)),
}
pieces = []
for name, ((a, b), rotation) in FACES.items():
    axis, sign = "xyz".index(name[-1]), 1.0 if name[-2] == "+" else -1.0
    offset = np.zeros(3)
    offset[axis] = sign * BUS[axis] / 2
    sheet = sw.meshes.plate(a, b, (4, 4))
    pieces.append(sw.meshes.label(sw.meshes.transform(sheet, rotation, offset), name, "mli"))
# the plate's x along body y (the span), its y along body z, its front +z along body +x
span_along_y = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
wing = sw.meshes.plate(3.2, 1.1, (8, 3))
for name, sign in (("wing_left", -1.0), ("wing_right", 1.0)):
    centre = (0.0, sign * (BUS[1] / 2 + 0.5 + 1.6), 0.0)
    pieces.append(sw.meshes.label(sw.meshes.transform(wing, span_along_y, centre), name))
mesh = sw.MeshData.concatenate(pieces, source="<box-wing by faces>")

MATERIALS = """
[materials.mli]          # aluminised Kapton, Kapton outward
reflectivity = 0.6
specular_fraction = 0.4
emissivity = 0.67
[materials.solar_cell]   # cells under cover glass
reflectivity = 0.09
specular_fraction = 0.8
emissivity = 0.85
[materials.cfrp]         # bare carbon fibre, the wings' backs
reflectivity = 0.08
specular_fraction = 0.2
emissivity = 0.82
[parts]
"wing_*" = { front = "solar_cell", back = "cfrp" }
[articulation."wing_*"]
axis = [0, 1, 0]
origin_m = [0, 0, 0]
track = "sun"
"""
workdir = tempfile.TemporaryDirectory(prefix="sunwind-leo-")  # removed when the script ends
folder = Path(workdir.name)
materials = folder / "box_wing.toml"
materials.write_text(MATERIALS, encoding="utf-8")
model = sw.load(mesh, materials, reference_point_m=(0.0, 0.0, 0.0), threads=1)
print(model.craft)
print("torque reference point: bus centre (0, 0, 0) m, body frame")

# %%
# The orbit
# ---------
# A circular orbit 500 km high, inclined 51.6 deg, over one period in 48 steps of about two minutes,
# from the June solstice of 2024 (ERFA's Sun; the conical shadow model gives the eclipse). The
# attitude law ``nadir`` holds body +z on the Earth's centre and +x along the velocity.
epoch = sw.orbit.Epoch.of("2024-06-21T00:00:00Z")
elements = sw.orbit.Elements.circular(500.0, 51.6)
times_s = np.linspace(0.0, elements.period_s, 48)
path = sw.orbit.propagate(elements, epoch, times_s, "kepler")

# %%
# The loads
# ---------
# :class:`~sunwind.forces.orbit.earth_terms.EarthTerms` adds the Earth's radiation: a Lambertian
# Earth of Bond albedo 0.30 and uniform infrared exitance ``(1 - A) S / 4`` (about 238 W/m² at the
# surface), its visible cap cut into 20 deg cells, every cell's light shadowed and applied to every
# side; ``thermal=True`` adds each side's equilibrium temperature (absorbed Sun, albedo and infrared
# against its own emission, no conduction and no heat capacity) and the recoil of the heat it emits.
# Drag, by far the largest force at 500 km (about 0.1 mN on this craft), is left out to show these.
srp = sw.SrpSetup(reflections="none")
earth = sw.orbit.EarthTerms(srp, cell_deg=20.0, thermal=True)
loads = sw.orbit.OrbitLoads(srp=srp, earth=earth, hinge_step_deg=10.0)
result = sw.fly(model, path, sw.orbit.AttitudeLaw.parse("nadir"), loads)
s, summary = result.series, result.summary()
minutes = s["time_s"] / 60.0
(start, end), *_ = summary["eclipses_s"]
print(f"orbit period {summary['period_s'] / 60:.1f} min, eclipse from {start / 60:.1f} to {end / 60:.1f} min")
print("orbit-mean forces, body frame [uN] (x along the velocity, z to the Earth's centre):")
for term in ("srp", "albedo", "infrared", "thermal"):
    mean = np.trapezoid(s[f"{term}_force_body_N"], s["time_s"], axis=0) / (s["time_s"][-1] - s["time_s"][0])
    peak = np.linalg.norm(s[f"{term}_force_body_N"], axis=1).max()
    print(f"  {term:>9}: mean {np.array2string(mean * 1e6, precision=3)}, largest |F| {peak * 1e6:.2f}")

# %%
# Forces through the orbit
# ------------------------
# Direct solar pressure stops in eclipse (grey); the Earth's infrared does not, and it pushes along
# -z, away from the Earth, at about the same level all round; the albedo follows the sunlit part of
# the cap below and fades out before the eclipse begins. The thermal recoil is the smallest: the faces
# the Sun heats radiate more than the others, and the imbalance pushes away from them; in eclipse
# what is left is the pattern the Earth's infrared leaves.
eclipsed = s["solar_fraction"] < 1.0
fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7.5), sharex=True, constrained_layout=True)
for term, colour in (
    ("srp", "tab:orange"),
    ("albedo", "tab:blue"),
    ("infrared", "tab:red"),
    ("thermal", "k"),
):
    magnitude = np.linalg.norm(s[f"{term}_force_body_N"], axis=1) * 1e6
    top.plot(minutes, magnitude, ".-", color=colour, ms=3, label=term)
top.set(ylabel="|F| [µN]", title="box-wing, 500 km, 51.6 deg, nadir pointing, June solstice")
top.legend(ncol=4)

# %%
# Temperatures
# ------------
# Each part's temperature is the area-weighted mean of its sides' equilibrium temperatures; for the
# wings that means the cells and the backs together. The Earth-facing face (+z) stays warm from the
# Earth's infrared through the eclipse; the faces that see the Earth edge-on fall to about 180 K, and
# the face turned to the sky (-z) sees nothing at all in eclipse, so its equilibrium temperature falls
# to zero. That is the limit of faces without heat capacity or conduction, which is what an orbit
# step computes; a lumped transient model with both is in :mod:`sunwind.forces.thermal`.
temperatures = s["part_temperature_K"]
for k, name in enumerate(result.part_names):
    style = "--" if name.startswith("wing") else "-"
    bottom.plot(minutes, temperatures[:, k], style, label=name)
bottom.set(xlabel="minutes after 2024-06-21 00:00 UTC", ylabel="equilibrium temperature [K]")
bottom.legend(ncol=4, fontsize="small")
for ax in (top, bottom):
    ax.fill_between(minutes, 0, 1, where=eclipsed, color="0.85", transform=ax.get_xaxis_transform(), lw=0)
    ax.grid(alpha=0.3)
plt.show()

print("part temperatures over the orbit [K]:")
for name, part in summary["parts"].items():
    low, mean, high = part["min_temperature_K"], part["mean_temperature_K"], part["max_temperature_K"]
    print(f"  {name:>10}: min {low:6.1f}  mean {mean:6.1f}  max {high:6.1f}")
