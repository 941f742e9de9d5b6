"""Basilisk lookup XML: parsed as Basilisk's SRPLookupTableHandler does, one entry per distinct direction,
forces and torques at 1 au about the body origin, and nearest-entry lookup within h / sqrt(2)."""

from __future__ import annotations

import math
from xml.etree import ElementTree

import numpy as np
import pytest

from helpers.tables import ATTRS, REFERENCE_POINT_M, field, grid_table, list_table
from sunwind.forces.export.basilisk import ReferencePointWarning, write_basilisk
from sunwind.forces.radiation.law import SOLAR_FLUX_1AU
from sunwind.geometry.errors import InputError

BLOCKS = {"sHatBValues": "sHat_B", "forceBValues": "force_B", "torqueBValues": "torque_B"}


def load_lookup(path) -> dict[str, np.ndarray]:
    """The three (n, 3) arrays, read the way parseSRPLookup.parseAndLoadXML reads them."""
    root = ElementTree.parse(path).getroot()
    assert root.tag == "srp_values"
    out = {}
    for block, tag in BLOCKS.items():
        nodes = list(root.find(block))
        values = np.zeros((len(nodes), 3))
        for node in nodes:
            assert node.tag == tag
            index = int(node.attrib["index"])
            for child in node:
                values[index, int(child.tag.removeprefix("value_")) - 1] = float(child.text)
        assert [int(node.attrib["index"]) for node in nodes] == list(range(len(nodes)))
        out[tag] = values
    return out


def written(table, path):
    """``write_basilisk(table, path)`` of a table about ``REFERENCE_POINT_M``, which it says it moved the
    torques from (the warning's text: test_reference_point.py)."""
    with pytest.warns(ReferencePointWarning, match="were moved there"):
        return write_basilisk(table, path)


def expected_at_1au(sun: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    force, torque = field(sun, 1e-6)
    scale = SOLAR_FLUX_1AU / ATTRS["flux_W_m2"]
    return force * scale, (torque + np.cross(REFERENCE_POINT_M, force)) * scale


def test_grid_table_gives_one_entry_per_distinct_direction(tmp_path):
    lookup = load_lookup(written(grid_table(15.0), tmp_path / "srp.xml"))
    sun = lookup["sHat_B"]
    assert len(sun) == 24 * 11 + 2  # azimuths without +180, elevations without the poles, two poles
    np.testing.assert_allclose(np.linalg.norm(sun, axis=1), 1.0, rtol=1e-15)
    closest = (sun @ sun.T - 2 * np.eye(len(sun))).max()
    assert closest < math.cos(math.radians(1.0))  # no direction twice
    force, torque = expected_at_1au(sun)
    np.testing.assert_allclose(lookup["force_B"], force, rtol=0, atol=1e-12 * np.abs(force).max())
    np.testing.assert_allclose(lookup["torque_B"], torque, rtol=0, atol=1e-12 * np.abs(torque).max())


def test_nearest_entry_is_within_h_over_sqrt2(tmp_path):
    step = 15.0
    lookup = load_lookup(written(grid_table(step, kinds=("srp",)), tmp_path / "srp.xml"))
    queries = np.random.default_rng(2).normal(size=(3000, 3))
    queries /= np.linalg.norm(queries, axis=1, keepdims=True)
    nearest = np.argmax(queries @ lookup["sHat_B"].T, axis=1)  # RadiationPressure::computeLookupModel
    angle = np.degrees(np.arccos(np.clip(np.sum(queries * lookup["sHat_B"][nearest], axis=1), -1, 1)))
    assert angle.max() <= step / math.sqrt(2) * 1.001


def test_list_table_gives_one_entry_per_attitude(tmp_path):
    table = list_table(9)
    lookup = load_lookup(written(table, tmp_path / "srp.xml"))
    np.testing.assert_allclose(lookup["sHat_B"], table["sun_vector"].values, rtol=1e-15)
    force, torque = expected_at_1au(table["sun_vector"].values)
    np.testing.assert_allclose(lookup["force_B"], force, rtol=1e-15)
    np.testing.assert_allclose(lookup["torque_B"], torque, rtol=1e-14, atol=1e-20)


def test_bad_input(tmp_path):
    with pytest.raises(InputError) as error:
        write_basilisk(grid_table(15.0, kinds=("drag",)), tmp_path / "srp.xml")
    assert str(error.value) == (
        "cannot write a Basilisk SRP lookup: the table has no srp_force_N, srp_torque_Nm; "
        "run the sweep with SRP included"
    )
    table = grid_table(30.0)
    table.attrs["flux_W_m2"] = 0.0
    with pytest.raises(InputError, match="flux_W_m2 attribute is missing or not positive"):
        write_basilisk(table, tmp_path / "srp.xml")
