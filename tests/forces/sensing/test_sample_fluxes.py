"""The bundled example of ``sunwind attitude`` (docs/guides/attitude.md): ``meshes/data/sensor_cube.obj``
and ``meshes/data/sensor_cube_fluxes.csv``, twelve rows of a tumbling cube on a 500 km polar orbit, the
last two in the Earth's shadow, made here by the full forward model with 1 % noise."""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial.transform import Rotation

import sunwind as sw
from sunwind.forces.sensing import flux_model
from sunwind.geometry.io import load_mesh

DATA = sw.meshes.sample_path().parent
BLACK = sw.Material("black", 0.07, 0.0, emissivity=0.82)
#: The attitude's rate, body frame [rad/s], and the orbit's period [s].
RATE = np.array([0.002, -0.001, 0.003])
PERIOD_S = 5676.98


def make_rows() -> str:
    """The CSV text: times every 300 s, Sun along inertial +x, the cube turning at :data:`RATE`."""
    model = sw.load(sw.meshes.sensor_cube(), uniform=BLACK, threads=1)
    fluxes = flux_model(model, 500.0)
    names = model.craft.part_names
    rng = np.random.default_rng(37)
    header = ["time_s", *names] + [f"{g}_eci_{a}" for g in ("sun", "nadir", "velocity") for a in "xyz"]
    lines = [",".join(header)]
    sun = np.array([1.0, 0.0, 0.0])
    for k in range(12):
        t = 300.0 * k
        phase = 2 * math.pi * t / PERIOD_S - 1.2  # the last two rows in the umbra
        up = np.array([math.cos(phase), 0.0, math.sin(phase)])
        velocity = np.array([-math.sin(phase), 0.0, math.cos(phase)])
        body_to_inertial = Rotation.from_rotvec(RATE * t) * Rotation.from_euler(
            "xyz", [20.0, -35.0, 60.0], degrees=True
        )
        sun_body, nadir_body = body_to_inertial.inv().apply([sun, -up])
        place = sw.Place(
            nadir_body,
            500.0,
            sun_body,
            solar_fraction=float(fluxes.solar_fraction(sun_body[None], nadir_body[None])[0]),
        )
        result = sw.planet_radiation(model, place, reflections="none", cap=sw.CapSampling(5.0, "cells"))
        q = sum(result.part_absorbed_W().values()) / fluxes.response.areas_m2
        q = q * (1.0 + 0.01 * rng.normal(size=q.shape))
        values = [f"{t:g}", *(f"{v:.2f}" for v in q), *(f"{v + 0.0:.6f}" for v in (*sun, *-up, *velocity))]
        lines.append(",".join(values))
    return "\n".join(lines) + "\n"


def test_the_bundled_example_is_what_this_makes():
    """The files in meshes/data are this module's: the cube mesh and its fluxes (to the digits written)."""
    mesh = load_mesh(DATA / "sensor_cube.obj")
    assert mesh.part_names == sw.meshes.sensor_cube().part_names
    assert np.allclose(mesh.vertices, sw.meshes.sensor_cube().vertices)
    assert (DATA / "sensor_cube_fluxes.csv").read_text() == make_rows()


if __name__ == "__main__":  # python tests/forces/sensing/test_sample_fluxes.py: write the files again
    from sunwind.geometry.io import save_mesh

    save_mesh(sw.meshes.sensor_cube(), DATA / "sensor_cube.obj")
    (DATA / "sensor_cube_fluxes.csv").write_text(make_rows())
