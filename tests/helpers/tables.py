"""Synthetic sweep tables that follow the sweep contract, for the interpolation, export and plot tests."""

from __future__ import annotations

import numpy as np
import xarray as xr

from sunwind.forces.tables.interpolation import azel_directions

REFERENCE_POINT_M = (0.1, -0.2, 0.3)
ATTRS = {
    "frame": "body frame of the mesh",
    "reference_point_m": np.array(REFERENCE_POINT_M),
    "reference_point": "user",
    "flux_W_m2": 1000.0,
    "pressure_Pa": 1000.0 / 299_792_458.0,
    "density_kg_m3": 1e-12,
    "speed_m_s": 7500.0,
    "dynamic_pressure_Pa": 0.5e-12 * 7500.0**2,
    "temperature_K": 900.0,
    "reference_area_m2": 2.0,
    "reference_length_m": 1.5,
    "mesh": "/data/craft.obj",
    "mesh_sha256": "ab" * 32,
    "materials_sha256": "cd" * 32,
    "sunwind_version": "0.1.0",
    "conventions": "u_sun spacecraft->Sun; u = v_rel/|v_rel|; az = atan2(y, x), el = asin(z)",
}
UNITS = {"force_N": "N", "torque_Nm": "N m"}


def field(d: np.ndarray, scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """A smooth force (..., 3) and torque (..., 3) on the sphere: constant + linear + quadratic + more."""
    x, y, z = d[..., 0], d[..., 1], d[..., 2]
    force = np.stack(
        [
            1 + 0.5 * x - 0.3 * y + 0.2 * z + 0.7 * x * y - 0.4 * z * z,
            0.3 * y * z + x * x - 0.1,
            np.sin(2 * x),
        ],
        axis=-1,
    )
    torque = np.stack([0.2 * y - x * z, np.cos(y * z) - 0.5 * x, 0.1 + 0.6 * z * x + 0.3 * y * y], axis=-1)
    return scale * force, scale * torque


def _variables(kind: str, prefix: str, dims: tuple[str, ...], d: np.ndarray, scale: float) -> dict:
    force, torque = field(d, scale)
    vector = (*dims, "component")
    out = {
        f"{kind}_force_N": (vector, force, {"units": "N", "long_name": f"{kind} force"}),
        f"{kind}_torque_Nm": (vector, torque, {"units": "N m", "long_name": f"{kind} torque"}),
        f"{kind}_direct_force_N": (vector, 0.7 * force, {"units": "N", "long_name": "direct force"}),
        f"{kind}_direct_torque_Nm": (vector, 0.7 * torque, {"units": "N m", "long_name": "direct torque"}),
        f"{kind}_reflected_force_N": (vector, 0.3 * force, {"units": "N", "long_name": "reflected force"}),
        f"{kind}_reflected_torque_Nm": (
            vector,
            0.3 * torque,
            {"units": "N m", "long_name": "reflected torque"},
        ),
        f"{prefix}_vector": (vector, d, {"units": "1", "long_name": f"{prefix} direction"}),
    }
    if kind == "srp":
        area = 1.0 + d[..., 0] ** 2
        out["srp_lit_area_m2"] = (dims, area, {"units": "m^2", "long_name": "lit area"})
        out["srp_projected_area_m2"] = (dims, area, {"units": "m^2", "long_name": "projected area"})
    else:
        qa = ATTRS["dynamic_pressure_Pa"] * ATTRS["reference_area_m2"]
        for name, column in (("CD", 0), ("CS", 1), ("CL", 2)):
            out[f"drag_{name}"] = (dims, force[..., column] / qa, {"units": "1", "long_name": name})
        cm = torque / (qa * ATTRS["reference_length_m"])
        out["drag_CM"] = (vector, cm, {"units": "1", "long_name": "moment coefficients"})
    return out


def grid_table(
    step_deg: float = 15.0, kinds: tuple[str, ...] = ("srp", "drag"), el_step_deg: float | None = None
) -> xr.Dataset:
    """A grid sweep table of :func:`field` (SRP scaled by 1e-6, drag by 1e-3) on both direction grids."""
    el_step = step_deg if el_step_deg is None else el_step_deg
    az = np.linspace(-180.0, 180.0, round(360 / step_deg) + 1)
    el = np.linspace(-90.0, 90.0, round(180 / el_step) + 1)
    d = azel_directions(az[:, None], el[None, :])
    coords: dict = {"component": ["x", "y", "z"]}
    variables: dict = {}
    for kind, prefix, scale in (("srp", "sun", 1e-6), ("drag", "flow", 1e-3)):
        if kind in kinds:
            coords |= {f"{prefix}_azimuth": az, f"{prefix}_elevation": el}
            variables |= _variables(kind, prefix, (f"{prefix}_azimuth", f"{prefix}_elevation"), d, scale)
    return xr.Dataset(
        {name: xr.Variable(dims, values, attrs) for name, (dims, values, attrs) in variables.items()},
        coords=coords,
        attrs=dict(ATTRS),
    )


def list_table(n: int = 7, kinds: tuple[str, ...] = ("srp", "drag")) -> xr.Dataset:
    """A list sweep table of :func:`field` at ``n`` seeded random directions."""
    d = np.random.default_rng(5).normal(size=(n, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    variables: dict = {}
    for kind, prefix, scale in (("srp", "sun", 1e-6), ("drag", "flow", 1e-3)):
        if kind in kinds:
            variables |= _variables(kind, prefix, ("attitude",), d, scale)
    return xr.Dataset(
        {name: xr.Variable(dims, values, attrs) for name, (dims, values, attrs) in variables.items()},
        coords={"attitude": np.arange(n), "component": ["x", "y", "z"]},
        attrs=dict(ATTRS),
    )
