"""Hostile input to sweeps, tables, checkpoints, exports and plots (issue 17, items 3, 4, 5, 9, 13, 14):
each command line gives its exit code and message, never a traceback, and leaves nothing half-made."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import pytest

from sunwind.forces.cli.app import main
from sunwind.geometry.errors import InputError

OPTICS = ("--reflectivity", "0.4", "--specular-fraction", "0.5", "--samples", "1", "--reflections", "none")
AIR = ("--density", "3e-12", "--temperature", "900", "--composition", "O:0.8,N2:0.2", "--speed", "7600")
#: Attitude lists by file name: (bytes of the file).
LISTS = {
    "dup.csv": b"sun_x,sun_y,sun_z,sun_z\n1,0,0,5\n0,1,0,7\n",
    "case_dup.csv": b"sun_x,SUN_X,sun_y,sun_z\n1,0,0,5\n",
    "extra.csv": b"sun_x,sun_y,sun_z,foo\n1,0,0,3\n",
    "missing.csv": b"sun_x,sun_y\n1,0\n",
    "bom.csv": b"\xef\xbb\xbfsun_x,sun_y,sun_z\n1,0,0\n",
    "latin1.csv": b"sun_x,sun_y,sun_z\n1,0,0\n# \xe9\n",
    "long_quaternion.csv": b"qw,qx,qy,qz,sun_x,sun_y,sun_z\n1,0,0,0,1,0,0\n2,0,0,0,1,0,0\n",
    "rounded_quaternion.csv": b"qw,qx,qy,qz,sun_x,sun_y,sun_z\n0.707107,0.707107,0,0,1,0,0\n",
}


@pytest.fixture(scope="module")
def box(tmp_path_factory) -> Path:
    """A 12-triangle box and the attitude lists, in one directory."""
    where = tmp_path_factory.mktemp("hostile_tables")
    main(["mesh", "box", "-o", str(where / "box.obj")])
    for name, data in LISTS.items():
        (where / name).write_bytes(data)
    return where / "box.obj"


# (id, arguments after `sweep MESH OPTICS`, exit code, words of stderr, files that must exist after)
SWEEPS = [
    (
        "csv-duplicated-column",
        ("--srp", "--attitudes", "dup.csv", "-o", "t.nc"),
        1,
        ["'sun_z' is given twice"],
        [],
    ),
    (
        "csv-duplicated-any-case",
        ("--srp", "--attitudes", "case_dup.csv", "-o", "t.nc"),
        1,
        ["given twice"],
        [],
    ),
    (
        "csv-unexpected-column",
        ("--srp", "--attitudes", "extra.csv", "-o", "t.nc"),
        1,
        ["unexpected column 'foo'", "sun_x,sun_y,sun_z and/or"],
        [],
    ),
    (
        "csv-missing-column",
        ("--srp", "--attitudes", "missing.csv", "-o", "t.nc"),
        1,
        ["lacks column sun_z", "sun_x,sun_y,sun_z"],
        [],
    ),
    ("csv-not-utf8", ("--srp", "--attitudes", "latin1.csv", "-o", "t.nc"), 1, ["not UTF-8"], []),
    (
        "csv-quaternion-not-unit",
        ("--srp", "--attitudes", "long_quaternion.csv", "-o", "t.nc"),
        1,
        ["row 3: the quaternion has length 2, not 1", "scalar first"],
        [],
    ),
    (
        "csv-quaternion-rounded",
        ("--srp", "--attitudes", "rounded_quaternion.csv", "-o", "q.nc"),
        0,
        [],
        ["q.nc"],
    ),
    ("csv-byte-order-mark", ("--srp", "--attitudes", "bom.csv", "-o", "t.nc"), 0, [], ["t.nc"]),
    (
        "nc-name-csv-format",
        ("--srp", "--step", "45", "-o", "x.nc", "--format", "csv"),
        1,
        ["extension .nc says nc", "as csv", "x.csv"],
        [],
    ),
    (
        "spo-name-nc-format",
        ("--srp", "--step", "45", "-o", "x.spo", "--format", "nc"),
        1,
        ["extension .spo says spad"],
        [],
    ),
    (
        "tudat-with-extension",
        ("--drag", *AIR, "--step", "45", "-o", "aero.nc", "--format", "tudat"),
        1,
        ["give a prefix without .nc"],
        [],
    ),
    (
        "format-adds-extension",
        ("--srp", "--step", "45", "-o", "noext", "--format", "nc"),
        0,
        [],
        ["noext.nc"],
    ),
    (
        "csv-format-adds-extension",
        ("--srp", "--step", "45", "-o", "noext", "--format", "csv"),
        0,
        [],
        ["noext.csv"],
    ),
    (
        "basilisk-drops-drag",
        ("--step", "45", *AIR, "-o", "b.xml"),
        0,
        ["warning: basilisk files hold srp only: drag is not tabulated"],
        ["b.xml"],
    ),
    (
        "tudat-drops-srp",
        ("--step", "45", *AIR, "--format", "tudat", "-o", "aero"),
        0,
        ["warning: tudat files hold drag only: srp is not tabulated"],
        ["aero_CFx.txt", "aero_CMz.txt"],
    ),
    (
        "basilisk-both-asked",
        ("--srp", "--drag", "--step", "45", *AIR, "-o", "b2.xml"),
        1,
        ["holds srp only, not drag"],
        [],
    ),
    (
        "spad-half-degree-step",
        ("--srp", "--step", "2.5", "-o", "x.spo"),
        1,
        ["SPAD grid step 2.5 deg is not a whole number", "e.g. 1, 2, 3, 4"],
        [],
    ),
    (
        "grid-step-8",
        ("--srp", "--step", "8", "-o", "x.spo"),
        1,
        ["--step 8 deg does not divide", "e.g. 6, 7.5, 9, 10"],
        [],
    ),
    (
        "spad-from-a-list",
        ("--srp", "--attitudes", "bom.csv", "-o", "x.spo"),
        1,
        ["needs an azimuth/elevation grid", "--attitudes"],
        [],
    ),
    (
        "tudat-from-a-list",
        ("--drag", *AIR, "--attitudes", "bom.csv", "--format", "tudat", "-o", "aero2"),
        1,
        ["need a grid of flow directions"],
        [],
    ),
]


@pytest.mark.parametrize(
    ("args", "code", "words", "made"), [case[1:] for case in SWEEPS], ids=[c[0] for c in SWEEPS]
)
def test_sweep_command_lines(box, run_cli, monkeypatch, args, code, words, made):
    monkeypatch.chdir(box.parent)
    with warnings.catch_warnings():
        warnings.simplefilter("default")
        got, out, err = run_cli("sweep", box, *OPTICS, *args)
    assert got == code, err
    assert "Traceback" not in err and "PosixPath" not in out and "{" not in out
    for word in words:
        assert word in err
    for name in made:
        assert (box.parent / name).stat().st_size > 0 and f"wrote {name}" in out
    if code:
        assert not list(box.parent.glob("*.checkpoint")) and "wrote" not in out


def test_scheduler_without_dask_is_one_line_and_leaves_nothing(box, run_cli, monkeypatch):
    monkeypatch.chdir(box.parent)
    monkeypatch.setitem(sys.modules, "dask", None)  # `import dask.distributed` now fails
    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    code, _, err = run_cli(
        "sweep", box, *OPTICS, "--srp", "--step", "45", "--scheduler", "tcp://h:8786", "-o", "d.nc"
    )
    assert code == 1 and "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert "--scheduler needs Dask distributed" in err and 'pip install "sunwind[dask]"' in err
    assert not (box.parent / "d.nc.checkpoint").exists()


def test_a_failed_scheduler_start_leaves_no_checkpoint(box, run_cli, monkeypatch):
    from sunwind.forces.tables import cluster

    def unreachable(scheduler, workers):
        raise InputError(f"cannot reach the Dask scheduler at {scheduler}: timed out")

    monkeypatch.chdir(box.parent)
    monkeypatch.setattr(cluster, "connect", unreachable)
    args = ("sweep", box, *OPTICS, "--srp", "--step", "45", "-o", "s.nc")
    code, _, err = run_cli(*args, "--scheduler", "tcp://127.0.0.1:9")
    assert code == 1 and "cannot reach the Dask scheduler" in err and "Traceback" not in err
    assert not (box.parent / "s.nc.checkpoint").exists()
    code, out, err = run_cli(*args)  # the next plain run is not blocked
    assert code == 0 and "wrote s.nc" in out, err


def test_a_failed_client_left_for_the_garbage_collector_does_not_leave_dask_asking_for_a_cluster(
    box, run_cli, monkeypatch
):
    """A client that failed to connect lives until the garbage collector runs; a default client closed
    meanwhile kept dask's global scheduler set to a closed cluster, and every later netCDF write in the
    process failed (CI, 28 tests). sunwind's clients are never dask's default."""
    import gc

    import dask
    from dask.distributed import LocalCluster

    from sunwind.forces.tables.cluster import connect

    gc.disable()
    try:
        with pytest.raises(InputError, match="cannot reach the Dask scheduler at nowhere://scheduler"):
            connect("nowhere://scheduler", None)
        cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0")
        try:
            client = connect(cluster.scheduler_address, None)
            assert len(client.scheduler_info()["workers"]) == 1
            client.close()
        finally:
            cluster.close()
        assert dask.config.get("scheduler", None) is None
    finally:
        gc.enable()
    monkeypatch.chdir(box.parent)
    code, out, err = run_cli("sweep", box, *OPTICS, "--srp", "--step", "90", "-o", "after.nc")
    assert code == 0 and "wrote after.nc" in out, err


def test_resume_says_what_it_kept_and_recomputes_a_damaged_chunk(box, run_cli, monkeypatch):
    monkeypatch.chdir(box.parent)
    (box.parent / "r.nc.checkpoint").mkdir()
    (box.parent / "r.nc.checkpoint" / "srp-00000000.npz").write_bytes(b"PK\x03\x04 not a chunk")
    code, out, err = run_cli(
        "sweep", box, *OPTICS, "--srp", "--step", "45", "--chunk", "5", "--resume", "-o", "r.nc"
    )
    assert code == 0 and "wrote r.nc" in out, err
    assert "notice: r.nc.checkpoint: checkpoint: kept 0 chunks, recomputing 6 (1 of them found" in err
    assert not (box.parent / "r.nc.checkpoint").exists()


def test_plot_refuses_a_mesh_edited_after_the_sweep(box, run_cli, monkeypatch, tmp_path):
    mesh = tmp_path / "box.obj"
    mesh.write_bytes(box.read_bytes())
    table = tmp_path / "p.nc"
    code, _, err = run_cli("sweep", mesh, *OPTICS, "--srp", "--step", "90", "-o", table)
    assert code == 0, err
    mesh.write_bytes(mesh.read_bytes().replace(b"v ", b"v  ", 1) + b"\n# edited\n")
    code, _out, err = run_cli("plot", table, "-o", tmp_path / "plots")
    assert code == 1 and "Traceback" not in err and not (tmp_path / "plots").exists()
    assert "mesh_sha256 differs" in err and "--no-view" in err
    code, _out, err = run_cli("plot", table, "--no-view", "-o", tmp_path / "plots")
    assert code == 0 and len(list((tmp_path / "plots").glob("*.png"))) == 2, err
    mesh.unlink()
    code, _out, err = run_cli("plot", table, "-o", tmp_path / "plots")
    assert code == 1 and "is not there for the 3-D view" in err and "--no-view" in err


@pytest.mark.parametrize(
    ("data", "reason"),
    [(bytes(range(256)) * 8, "it is not a netCDF file"), (b"CDF\x01\x00", "cannot read the table")],
    ids=["random-bytes", "truncated-netcdf"],
)
def test_plot_of_a_file_that_is_no_table_is_one_line(run_cli, tmp_path, data, reason):
    table = tmp_path / "garbage.nc"
    table.write_bytes(data)
    code, _out, err = run_cli("plot", table, "-o", tmp_path / "plots")
    assert code == 1 and err.count("\n") == 1 and reason in err and "give a .nc file sunwind wrote" in err


def test_plot_refuses_a_usd_stage_whose_referenced_file_was_edited(run_cli, tmp_path):
    """The table's mesh_sha256 covers every file a USD stage composes, not only the stage itself."""
    code, _out, err = run_cli("mesh", "box", "-o", tmp_path / "arm.usda")
    assert code == 0, err
    stage = tmp_path / "craft.usda"
    stage.write_text(
        '#usda 1.0\n(\n    defaultPrim = "craft"\n    metersPerUnit = 1\n)\n'
        'def Xform "craft" (references = @arm.usda@) {}\n'
    )
    table = tmp_path / "c.nc"
    code, _out, err = run_cli("sweep", stage, *OPTICS, "--srp", "--step", "90", "-o", table)
    assert code == 0, err
    arm = tmp_path / "arm.usda"
    arm.write_text(arm.read_text().replace("point3f[] points = [(-0.5,", "point3f[] points = [(-0.7,", 1))
    code, _out, err = run_cli("plot", table, "-o", tmp_path / "plots")
    assert code == 1 and "mesh_sha256 differs" in err and "Traceback" not in err
