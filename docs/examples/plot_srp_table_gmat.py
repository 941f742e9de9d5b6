"""
An SRP table for GMAT
=====================

GMAT models solar-radiation pressure on a detailed spacecraft through a SPAD file: a table of area
vectors over the Sun's azimuth and elevation in the body frame, which it interpolates at every step
of a propagation. This example sweeps the sample spacecraft over Sun directions on a coarse 15 deg
grid with self-shadowing and inter-reflection, writes the table in GMAT's SPAD format with
:func:`sunwind.write`, shows the head of the file and maps the force over the grid.
"""

# %%
# The sweep
# ---------
# :func:`sunwind.sweep` evaluates :func:`sunwind.srp` at every grid direction and returns an
# ``xarray.Dataset`` with units, the body frame, the torque reference point and the provenance in its
# attributes. The sample spacecraft ships with the package: a bus with two solar wings along y (cells
# facing +x as drawn), a dish, a boom and an engine nozzle, about 20 000 triangles. Reflections are
# left at ``"auto"``, which follows diffuse and specular light between the parts when they can see
# each other enough to matter (they can here).
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import sunwind as sw

model = sw.load(
    sw.meshes.sample_path(), sw.meshes.sample_materials_path(), reference_point_m=(0.0, 0.0, 0.0), threads=1
)
table = sw.sweep(model, srp=sw.SrpSetup(), step_deg=15.0)
print(model.craft)
print(f"grid: {table.sizes['sun_azimuth']} azimuths x {table.sizes['sun_elevation']} elevations")
print(f"frame: {table.attrs['frame']}; reflections: {table.attrs['srp_reflections']}")
point, where = np.round(table.attrs["reference_point_m"], 4), table.attrs["reference_point"]
print(f"torque reference point: {point} m ({where})")
print(f"flux {table.attrs['flux_W_m2']:.0f} W/m^2, pressure {table.attrs['pressure_Pa'] * 1e6:.3f} uPa")

# %%
# Writing the SPAD file
# ---------------------
# The extension ``.spo`` chooses GMAT's format. A SPAD row holds the area vector ``A = F / P`` [m²]
# at 1 au, pointing along the force; GMAT turns it back into an acceleration ``P A / m`` with its own
# flux, distance and shadow model. SPAD files hold forces only, so the reference point does not enter
# (the header says so).
workdir = tempfile.TemporaryDirectory(prefix="sunwind-gmat-")  # removed when the script ends
folder = Path(workdir.name)
written = sw.write(table, folder / "sample_spacecraft.spo")
spad = written[0]
lines = spad.read_text(encoding="utf-8").splitlines()
print(f"{spad.name}: {len(lines)} lines")
print("\n".join(lines[:34]))

# %%
# In a GMAT script the file is named on the spacecraft and the SRP force chooses the SPAD model::
#
#     Create Spacecraft Sat;
#     Sat.SPADSRPFile = 'sample_spacecraft.spo';
#     Sat.SPADSRPScaleFactor = 1;
#     Create ForceModel FM;
#     FM.SRP = On;
#     FM.SRP.SRPModel = SPADFile;
#
# GMAT needs the spacecraft's attitude as well, since the table is looked up at the Sun's direction
# in the body frame. A finer grid (``step_deg=5``) is what one would hand over; 15 deg keeps this page
# quick.

# %%
# The force over the Sun's directions
# -----------------------------------
# The map shows ``|F|`` at 1 au, in µN, with the azimuth ``atan2(s_y, s_x)`` and the elevation
# ``asin(s_z)`` of the Sun direction ``s`` in the body frame. The force is largest with the Sun on the
# cells (+x, azimuth 0) or on the wings' backs (azimuth ±180), where the wings show their whole 7 m²
# of area, and smallest with the Sun in the plane of the wings (azimuth ±90, or elevation ±90), where
# they are edge-on and only the bus, the dish and the wings' edges are lit. The rows at elevation ±90
# are all the same direction, whatever their azimuth.
force = table["srp_force_N"]
magnitude = np.linalg.norm(force.values, axis=-1) * 1e6
azimuth, elevation = table["sun_azimuth"].values, table["sun_elevation"].values
fig, ax = plt.subplots(figsize=(8, 4.2), constrained_layout=True)
mesh = ax.pcolormesh(azimuth, elevation, magnitude.T, shading="nearest", cmap="viridis")
fig.colorbar(mesh, ax=ax, label="|F| at 1 au [µN]")
ax.set(
    xlabel="Sun azimuth [deg]", ylabel="Sun elevation [deg]", title="SRP on the sample spacecraft, body frame"
)
ax.set_xticks(np.arange(-180, 181, 60))
ax.set_yticks(np.arange(-90, 91, 30))
plt.show()

k_max = np.unravel_index(np.argmax(magnitude), magnitude.shape)
k_min = np.unravel_index(np.argmin(magnitude), magnitude.shape)
for what, (i, j) in (("largest", k_max), ("smallest", k_min)):
    print(f"{what} |F| {magnitude[i, j]:.1f} uN, azimuth {azimuth[i]:.0f}, elevation {elevation[j]:.0f} deg")
face_on = force.sel(sun_azimuth=0.0, sun_elevation=0.0).values
print(f"Sun on the cells (+x): F = {np.array2string(face_on * 1e6, precision=2)} uN, body frame")
