"""One call writes any format: chosen by name or extension, refused where the table does not fit."""

import warnings

import pytest
import xarray as xr

from helpers.tables import grid_table, list_table
from sunwind.forces.export import (
    FORMATS,
    ReferencePointWarning,
    check_request,
    format_of,
    output_target,
    write,
)
from sunwind.forces.tables import direction_grid, open_table
from sunwind.forces.tables.attitudes import step_advice
from sunwind.geometry.errors import InputError


def test_every_format_has_its_extension_and_quantities():
    assert {name: spec.extension for name, spec in FORMATS.items()} == {
        "nc": ".nc",
        "csv": ".csv",
        "spad": ".spo",
        "basilisk": ".xml",
        "tudat": None,
    }
    assert FORMATS["basilisk"].kinds == ("srp",) and FORMATS["tudat"].kinds == ("drag",)
    assert format_of("a/b.SPO") == "spad" and format_of("t.dat", "csv") == "csv"
    with pytest.raises(InputError, match=r"cannot tell the format from the extension '\.dat'"):
        format_of("t.dat")
    with pytest.raises(InputError, match="format 'xls' is not a table format"):
        format_of("t.nc", "xls")


@pytest.mark.parametrize(
    ("name", "fmt", "written"),
    [
        ("t.nc", None, ["t.nc"]),
        ("t.csv", None, ["t.srp.csv", "t.drag.csv"]),
        ("t.spo", None, ["t.srp.spo", "t.drag.spo"]),
        ("aero", "tudat", [f"aero_C{k}{a}.txt" for k in "FM" for a in "xyz"]),
    ],
)
def test_a_grid_table_is_written_whole_in_every_format(tmp_path, name, fmt, written):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        if fmt == "tudat":
            warnings.simplefilter("ignore")  # a drag-only format: SRP is not written, and says so
        files = write(grid_table(15.0), tmp_path / name, fmt)
    assert sorted(files) == sorted(tmp_path / w for w in written)
    assert not list(tmp_path.glob(".*.tmp"))  # written under temporary names, renamed into place
    if fmt is None and name.endswith(".nc"):
        xr.testing.assert_identical(open_table(files[0]), grid_table(15.0).load())


def test_a_quantity_the_format_cannot_hold_is_said_and_none_at_all_is_refused(tmp_path):
    with (
        pytest.warns(UserWarning, match="basilisk holds srp only: drag is not written"),
        pytest.warns(ReferencePointWarning),  # and the torques were moved to the body origin
    ):
        write(grid_table(15.0), tmp_path / "t.xml")
    with pytest.raises(InputError, match="format tudat holds drag only, not srp"):
        write(grid_table(15.0, kinds=("srp",)), tmp_path / "aero", "tudat")
    with pytest.raises(InputError, match="grid"):
        write(list_table(kinds=("srp",)), tmp_path / "t.spo")


@pytest.mark.parametrize(
    ("name", "fmt", "target"),
    [
        ("t", "nc", ("nc", "t.nc")),
        ("t", "csv", ("csv", "t.csv")),
        ("t", "spad", ("spad", "t.spo")),
        ("t", "basilisk", ("basilisk", "t.xml")),
        ("aero", "tudat", ("tudat", "aero")),
        ("t.NC", None, ("nc", "t.NC")),
        ("t.txt", "csv", ("csv", "t.txt")),  # an extension of no format: the named format, as asked
    ],
)
def test_the_output_path_gets_the_extension_of_its_format(tmp_path, name, fmt, target):
    assert output_target(tmp_path / name, fmt) == (target[0], tmp_path / target[1])


@pytest.mark.parametrize(
    ("name", "fmt"), [("x.nc", "csv"), ("x.csv", "nc"), ("x.spo", "nc"), ("x.xml", "spad"), ("a.nc", "tudat")]
)
def test_an_extension_that_contradicts_the_format_is_refused(tmp_path, name, fmt):
    with pytest.raises(InputError, match=f"says .*, but the table is to be written as {fmt}"):
        write(grid_table(30.0), tmp_path / name, fmt)
    assert not list(tmp_path.iterdir())


def test_the_grid_checks_give_one_step_advice():
    """The sweep grid and SPAD refuse steps with the same advice, and every step advised is taken."""
    for step, whole in ((8.0, False), (7.0, False), (2.5, True), (0.7, False), (100.0, True)):
        with pytest.raises(InputError) as error:
            direction_grid(step) if not whole else check_request("spad", step)
        assert step_advice(step, whole) in str(error.value)
        advised = [float(s) for s in step_advice(step, whole).split("e.g. ")[1].split(", ")]
        assert len(advised) == 4
        for good in advised:
            direction_grid(good)
            if whole:
                check_request("spad", good)
    with pytest.raises(InputError, match="not an attitude list"):
        check_request("spad", None)
    with pytest.raises(InputError, match="not an attitude list"):
        check_request("tudat", None)
    check_request("nc", None), check_request("basilisk", None)
