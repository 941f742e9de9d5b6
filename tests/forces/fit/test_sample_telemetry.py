"""The calibration guide's telemetry, ``meshes/data/sample_telemetry.csv``: a day of the sample
spacecraft, made by the model with other coefficients than its materials file's, plus noise.

Regenerate it with ``python tests/forces/fit/test_sample_telemetry.py``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

import sunwind as sw
from sunwind.forces.fit.forward import with_optics

SAMPLE = Path(__file__).resolve().parents[3] / "meshes" / "data" / "sample_telemetry.csv"
#: The coefficients the "flight" had (the materials file says 0.09, 0.8, 0.6 and 0.8).
TRUTH = {
    "solar_cell.reflectivity": 0.12,
    "solar_cell.specular_fraction": 0.7,
    "mli.reflectivity": 0.55,
    "white_paint.reflectivity": 0.75,
}
ROWS, STEP_S, NOISE_NM = 144, 600.0, 2e-8


def sample_rows() -> dict[str, np.ndarray]:
    """A day of 10-minute samples: the Sun turns once about body z, 20 deg above the x-y plane
    (an Earth-pointing satellite in a high orbit), the wheels' torque with 2e-8 N m noise."""
    model = sw.load(sw.meshes.sample_path(), sw.meshes.sample_materials_path())
    table = model.craft.materials
    optics = np.stack([table.rho, table.beta, table.sigma], 1).astype(float)
    columns = ("reflectivity", "specular_fraction", "transmissivity")
    for name, value in TRUTH.items():
        material, _, coefficient = name.rpartition(".")
        optics[table.names.index(material), columns.index(coefficient)] = value
    time = STEP_S * np.arange(ROWS)
    phase, elevation = 2 * np.pi * time / 86400.0, np.radians(20.0)
    sun = np.stack(
        [
            np.cos(phase) * np.cos(elevation),
            np.sin(phase) * np.cos(elevation),
            np.full(ROWS, np.sin(elevation)),
        ],
        1,
    )
    torque = sw.srp(with_optics(model, optics), sun, reflections="none").torque_Nm
    rng = np.random.default_rng(36)
    torque = torque + rng.normal(scale=NOISE_NM, size=torque.shape)
    return {
        "time_s": time,
        **{f"sun_{a}": sun[:, k] for k, a in enumerate("xyz")},
        **{f"torque_{a}": torque[:, k] for k, a in enumerate("xyz")},
    }


def write(path: Path) -> None:
    rows = sample_rows()
    names = list(rows)
    lines = [
        "# sunwind calibration guide: a day of the sample spacecraft (meshes/data/sample_spacecraft.obj),",
        "# Sun direction body frame, wheel torque [N m] body frame about the area centroid, noise 2e-8 N m",
        ",".join(names),
    ]
    lines += [",".join(f"{rows[n][k]:.9g}" for n in names) for k in range(ROWS)]
    path.write_text("\n".join(lines) + "\n")


def test_the_shipped_telemetry_is_the_generators():
    from sunwind.forces.fit.telemetry import read_telemetry

    shipped = read_telemetry(SAMPLE)
    rows = sample_rows()
    assert np.allclose(shipped.time_s, rows["time_s"])
    made = np.stack([rows[f"torque_{a}"] for a in "xyz"], 1)
    assert np.allclose(shipped.measured["torque"], made, rtol=1e-6, atol=1e-12)


if __name__ == "__main__":
    write(Path(sys.argv[1]) if len(sys.argv) > 1 else SAMPLE)
