"""Attitude sweeps: grids, lists, the table against single attitudes, checkpoints, resume, Dask, bad input."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest
import xarray as xr

from sunwind.forces import export
from sunwind.forces.drag import drag
from sunwind.forces.model import Model, load
from sunwind.forces.reflection import ReflectionSettings
from sunwind.forces.srp import srp
from sunwind.forces.tables import (
    DragSetup,
    Job,
    SrpSetup,
    SweepRun,
    direction_grid,
    grid_table,
    open_table,
    read_attitude_csv,
    run_jobs,
    sweep,
)
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import Material
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes.primitives import sphere
from sunwind.validation.analytic_srp import sphere_srp
from sunwind.validation.analytic_srp_law import Optics

OPTICS = Material("paint", 0.4, 0.5, 0.1)
#: Meshed sphere against the analytic sphere: the inscribed mesh's area error, ~2.5 / bands^2.
SPHERE_BANDS, SPHERE_TOLERANCE = 48, 2e-3


@pytest.fixture(scope="module")
def model(tmp_path_factory) -> Model:
    """The box-wing written by ``sunwind mesh``, loaded with a uniform material and two-sided wings."""
    from sunwind.forces.cli.app import main

    path = tmp_path_factory.mktemp("sweep") / "box_wing.obj"
    main(["mesh", "box_wing", "-o", str(path)])
    return load(path, uniform=OPTICS, two_sided=("wing*",))


@pytest.fixture(scope="module")
def air():
    from sunwind.forces.gas import explicit

    return explicit(3e-12, 900.0, "O:0.8,N2:0.2")


def _setups(air, reflections="full"):
    settings = _settings(reflections)
    return (
        SrpSetup(flux_W_m2=1361.0, sampling=ShadowSampling(samples=4), reflections=settings),
        DragSetup(speed_m_s=7600.0, atmosphere=air, sampling=ShadowSampling(samples=4), reflections=settings),
    )


def _jobs(air, step=45.0, reflections="full"):
    grid = direction_grid(step)
    return grid, [Job(setup, grid.distinct[0]) for setup in _setups(air, reflections)]


def _settings(mode):
    return ReflectionSettings(mode, rays_per_side=64)


# ------------------------------------------------------------------------------------------ grids


def test_grid_has_both_ends_and_shares_directions_exactly():
    grid = direction_grid(30)
    assert grid.azimuth_deg[[0, -1]].tolist() == [-180.0, 180.0]
    assert grid.elevation_deg[[0, -1]].tolist() == [-90.0, 90.0]
    assert grid.vectors.shape == (13, 7, 3)
    np.testing.assert_array_equal(grid.vectors[0], grid.vectors[-1])  # az -180 is az 180
    assert (grid.vectors[:, -1] == [0.0, 0.0, 1.0]).all() and (grid.vectors[:, 0] == [0.0, 0.0, -1.0]).all()
    distinct, node = grid.distinct
    assert len(distinct) == 12 * 5 + 2
    np.testing.assert_array_equal(distinct[node], grid.vectors.reshape(-1, 3))
    assert direction_grid(5).vectors.shape[:2] == (73, 37)  # 2701 nodes


@pytest.mark.parametrize("step", [7.0, 0.0, -5.0, 100.0, math.nan])
def test_a_step_that_does_not_divide_the_range_is_refused(step):
    with pytest.raises(InputError, match="step_deg"):
        direction_grid(step)


@pytest.mark.parametrize(
    ("field", "value"), [("chunk", 0), ("chunk", 2.5), ("workers", 0), ("workers", True)]
)
def test_a_run_with_no_whole_chunk_or_worker_count_is_refused(field, value):
    with pytest.raises(InputError, match=f"^{field} {value!r} must be a whole number >= 1") as caught:
        SweepRun(**{field: value})
    assert caught.value.parameters == (field,)


# ----------------------------------------------------------------------------------- table entries


def test_every_table_entry_equals_the_single_attitude_result(model, air):
    light_setup, drag_setup = _setups(air)
    table = sweep(model, srp=light_setup, drag=drag_setup, step_deg=45.0, run=SweepRun(chunk=7))
    grid = direction_grid(45.0)
    for i, az in enumerate(grid.azimuth_deg):
        for j, el in enumerate(grid.elevation_deg):
            u = grid.vectors[i, j]
            light = srp(model, u, sampling=ShadowSampling(samples=4), reflections=_settings("full"))
            gas = drag(
                model, 7600.0 * u, air, sampling=ShadowSampling(samples=4), reflections=_settings("full")
            )
            at = {"sun_azimuth": az, "sun_elevation": el}
            np.testing.assert_array_equal(table.srp_force_N.sel(at).values, light.force_N)
            np.testing.assert_array_equal(table.srp_torque_Nm.sel(at).values, light.torque_Nm)
            np.testing.assert_array_equal(table.srp_reflected_force_N.sel(at).values, light.reflected_force_N)
            flow = {"flow_azimuth": az, "flow_elevation": el}
            np.testing.assert_array_equal(table.drag_force_N.sel(flow).values, gas.force_N)
            np.testing.assert_array_equal(table.drag_torque_Nm.sel(flow).values, gas.torque_Nm)
            assert table.drag_CD.sel(flow).item() == gas.force_coefficients[0]
    assert np.abs(table.srp_reflected_force_N.values).max() > 0  # the concave model does reflect
    for key in (
        "frame",
        "reference_point_m",
        "flux_W_m2",
        "mesh_sha256",
        "dynamic_pressure_Pa",
        "grid_step_deg",
    ):
        assert key in table.attrs  # the Python sweep carries the provenance the command line writes


def test_a_netcdf_table_states_its_coordinates_modes_and_atmosphere(model, air, tmp_path):
    """CF metadata, long names that say what a coordinate is, the mode ``auto`` resolved to, the
    atmosphere's source and altitude, and drag's projected area."""
    settings = _settings("auto")
    high = replace(air, altitude_km=400.0)
    light_setup = SrpSetup(flux_W_m2=1361.0, sampling=ShadowSampling(samples=4), reflections=settings)
    drag_setup = DragSetup(
        speed_m_s=7600.0, atmosphere=high, sampling=ShadowSampling(samples=4), reflections=settings
    )
    (path,) = export.write(sweep(model, srp=light_setup, drag=drag_setup, step_deg=90.0), tmp_path / "t.nc")
    table = open_table(path)
    u = np.array([0.0, 0.0, 1.0])
    light = srp(model, u, sampling=ShadowSampling(samples=4), reflections=settings)
    gas = drag(model, 7600.0 * u, high, sampling=ShadowSampling(samples=4), reflections=settings)
    assert table.attrs["Conventions"] == "CF-1.8" and "sun_vector points" in table.attrs["comment"]
    assert table.attrs["reflections_requested"] == "auto"
    assert table.attrs["srp_reflections"] == light.reflected.mode != "auto"
    assert table.attrs["drag_reflections"] == gas.reflected.mode != "auto"
    assert table.attrs["altitude_km"] == 400.0 and table.attrs["atmosphere_source"] == high.source
    assert table.sun_azimuth.attrs["long_name"].startswith("Sun azimuth in the body frame")
    assert table.flow_elevation.attrs["long_name"].startswith("flow (v_rel) elevation in the body frame")
    assert all("units" in table[name].attrs for name in (*table.data_vars, "sun_azimuth", "flow_azimuth"))
    assert all("long_name" in table[name].attrs for name in (*table.data_vars, *table.coords))
    at = {"flow_azimuth": 0.0, "flow_elevation": 90.0}
    assert table.drag_projected_area_m2.sel(at).item() == gas.projected_area_m2 > 0
    assert table.drag_lit_area_m2.sel(at).item() == gas.lit_area_m2 > 0


def test_table_entry_equals_the_command_line(model, run_cli, tmp_path):
    mesh = model.source.mesh
    table_path = tmp_path / "t.nc"
    flags = ["--reflectivity", "0.4", "--specular-fraction", "0.5", "--transmissivity", "0.1"]
    flags += ["--two-sided", "wing*", "--samples", "4", "--reflections", "full"]
    air_flags = ["--density", "3e-12", "--temperature", "900", "--composition", "O:0.8,N2:0.2"]
    code, out, err = run_cli(
        "sweep", mesh, *flags, *air_flags, "--speed", "7600", "--step", "45", "-o", table_path
    )
    assert code == 0, err
    table = open_table(table_path)
    code, out, err = run_cli("srp", mesh, *flags, "--sun-azel", "-135", "45", "--json")
    single = json.loads(out)
    value = table.srp_force_N.sel(sun_azimuth=-135, sun_elevation=45).values
    assert value.tolist() == single["force_N"]
    code, out, err = run_cli(
        "drag", mesh, *flags, *air_flags, "--speed", "7600", "--flow-azel", "90", "-45", "--json"
    )
    single = json.loads(out)
    value = table.drag_torque_Nm.sel(flow_azimuth=90, flow_elevation=-45).values
    assert value.tolist() == single["torque_Nm"]
    for key in (
        "frame",
        "reference_point_m",
        "flux_W_m2",
        "mesh_sha256",
        "sunwind_version",
        "dynamic_pressure_Pa",
    ):
        assert key in table.attrs
    assert table.srp_force_N.attrs["units"] == "N"


def test_sphere_table_equals_the_analytic_sphere():
    craft_optics = Optics(0.4, 0.5, 0.1)
    craft = build_spacecraft(sphere(1.0, SPHERE_BANDS), uniform=OPTICS)
    grid = direction_grid(30)
    setup = SrpSetup(
        flux_W_m2=1361.0,
        reference_point_m=(0.0, 0.0, 0.0),
        sampling=ShadowSampling(samples=1),
        reflections=_settings("none"),
    )
    table = sweep(craft, srp=setup, step_deg=30)  # a model built in memory
    forces = table.srp_force_N.values.reshape(-1, 3)
    expected = np.array([sphere_srp(1.0, u, craft_optics).force_N for u in grid.vectors.reshape(-1, 3)])
    error = np.linalg.norm(forces - expected, axis=1) / np.linalg.norm(expected, axis=1)
    assert error.max() < SPHERE_TOLERANCE


# -------------------------------------------------------------------------------- checkpoint, resume


class _Stop(Exception):
    pass


def test_an_interrupted_sweep_resumes_to_the_same_table(model, air, tmp_path):
    grid, jobs = _jobs(air, reflections="none")
    whole = run_jobs(model, jobs, SweepRun(chunk=5))
    checkpoint = tmp_path / "t.nc.checkpoint"
    seen = []

    def stop_after_two_chunks(done: int) -> None:
        seen.append(done)
        if len(seen) == 3:
            raise _Stop

    with pytest.raises(_Stop):
        run_jobs(model, jobs, SweepRun(chunk=5, checkpoint=checkpoint, progress=stop_after_two_chunks))
    assert len(list(checkpoint.glob("*.npz"))) == 2
    progress = []
    resumed = run_jobs(
        model, jobs, SweepRun(chunk=5, checkpoint=checkpoint, resume=True, progress=progress.append)
    )
    assert progress[0] == 10  # the two chunks kept are not recomputed
    for kind in whole:
        for name in whole[kind]:
            np.testing.assert_array_equal(resumed[kind][name], whole[kind][name])
    assert not checkpoint.exists()  # removed once finished
    (a,) = export.write(grid_table(whole, dict.fromkeys(whole, grid), {}), tmp_path / "a.nc")
    (b,) = export.write(grid_table(resumed, dict.fromkeys(whole, grid), {}), tmp_path / "b.nc")
    xr.testing.assert_identical(xr.load_dataset(a), xr.load_dataset(b))


def test_a_checkpoint_another_run_is_writing_is_refused_until_it_ends(model, air, tmp_path):
    _, jobs = _jobs(air, reflections="none")
    checkpoint = tmp_path / "t.nc.checkpoint"
    refused = []

    def second_run_meanwhile(done: int) -> None:
        if done == 5:  # the first chunk is kept on disk: a second run tries to take it up
            with pytest.raises(InputError, match="another sunwind run is writing this checkpoint now"):
                run_jobs(model, jobs, SweepRun(chunk=5, checkpoint=checkpoint, resume=True))
            refused.append(done)
            raise _Stop

    with pytest.raises(_Stop):
        run_jobs(model, jobs, SweepRun(chunk=5, checkpoint=checkpoint, progress=second_run_meanwhile))
    assert refused and len(list(checkpoint.glob("*.npz"))) == 1  # the second run deleted nothing
    run_jobs(model, jobs, SweepRun(chunk=5, checkpoint=checkpoint, resume=True))  # free once it ended
    assert not checkpoint.exists()


def test_a_checkpoint_of_another_sweep_is_refused(model, air, tmp_path):
    _, jobs = _jobs(air, reflections="none")
    checkpoint = tmp_path / "c"

    def stop(done: int) -> None:
        if done:
            raise _Stop

    with pytest.raises(_Stop):
        run_jobs(model, jobs, SweepRun(chunk=5, checkpoint=checkpoint, progress=stop))
    with pytest.raises(InputError, match="resume"):
        run_jobs(model, jobs, SweepRun(chunk=5, checkpoint=checkpoint))
    other = [Job(replace(j.setup, sampling=ShadowSampling(samples=9)), j.inputs) for j in jobs]
    with pytest.raises(InputError, match="srp_settings"):
        run_jobs(model, other, SweepRun(chunk=5, checkpoint=checkpoint, resume=True))
    paint = load(
        model.source.mesh, uniform=Material("paint", 0.2, 0.5, 0.1), two_sided=model.source.two_sided
    )
    with pytest.raises(InputError, match="model"):
        run_jobs(paint, jobs, SweepRun(chunk=5, checkpoint=checkpoint, resume=True))
    moved = replace(model, reference_point_m=np.array([0.0, 0.0, 0.5]))
    with pytest.raises(InputError, match="references"):
        run_jobs(moved, jobs, SweepRun(chunk=5, checkpoint=checkpoint, resume=True))


def _stopped_checkpoint(model, jobs, checkpoint, chunks: int = 2) -> None:
    """Run ``jobs`` with a checkpoint and stop after ``chunks`` chunks."""
    seen = []

    def stop(done: int) -> None:
        seen.append(done)
        if len(seen) == chunks + 1:
            raise _Stop

    with pytest.raises(_Stop):
        run_jobs(model, jobs, SweepRun(chunk=5, checkpoint=checkpoint, progress=stop))


def test_chunks_without_their_manifest_are_taken_only_by_their_own_sweep(model, air, tmp_path):
    _, jobs = _jobs(air, reflections="none")
    checkpoint = tmp_path / "c"
    _stopped_checkpoint(model, jobs, checkpoint)
    (checkpoint / "manifest.json").unlink()
    other = [Job(replace(j.setup, sampling=ShadowSampling(samples=9)), j.inputs) for j in jobs]
    lines, progress = [], []
    run = SweepRun(chunk=5, checkpoint=checkpoint, resume=True, progress=progress.append, notice=lines.append)
    resumed = run_jobs(model, other, run)
    fresh = run_jobs(model, other, SweepRun(chunk=5))
    for kind in fresh:
        for name in fresh[kind]:
            np.testing.assert_array_equal(resumed[kind][name], fresh[kind][name])
    assert progress[0] == 0 and lines == [
        "checkpoint: kept 0 chunks, recomputing 12 (2 of them found but of other settings or edited)"
    ]


def test_an_edited_chunk_is_computed_again(model, air, tmp_path):
    _, jobs = _jobs(air, reflections="none")
    checkpoint = tmp_path / "c"
    _stopped_checkpoint(model, jobs, checkpoint)
    first = checkpoint / "srp-00000000.npz"
    with np.load(first) as kept:
        edited = {name: kept[name] for name in kept.files}
    edited["force_N"] = edited["force_N"] * 2
    np.savez(first, **edited)
    lines = []
    resumed = run_jobs(
        model, jobs, SweepRun(chunk=5, checkpoint=checkpoint, resume=True, notice=lines.append)
    )
    whole = run_jobs(model, jobs, SweepRun(chunk=5))
    np.testing.assert_array_equal(resumed["srp"]["force_N"], whole["srp"]["force_N"])
    assert lines == [
        "checkpoint: kept 1 chunks, recomputing 11 (1 of them found but of other settings or edited)"
    ]


def test_a_failed_start_leaves_no_checkpoint(model, air, tmp_path, monkeypatch):
    from sunwind.forces.tables import engine

    _, jobs = _jobs(air, reflections="none")
    checkpoint = tmp_path / "c"

    def unreachable(*args) -> None:
        raise InputError("cannot reach the Dask scheduler")

    monkeypatch.setattr(engine, "run_on_dask", unreachable)
    with pytest.raises(InputError, match="cannot reach"):
        run_jobs(model, jobs, SweepRun(chunk=5, checkpoint=checkpoint, scheduler="tcp://127.0.0.1:9"))
    assert not checkpoint.exists()
    _stopped_checkpoint(model, jobs, checkpoint)  # but one that saved chunks is kept
    assert len(list(checkpoint.glob("*.npz"))) == 2


@pytest.mark.slow
def test_killed_command_line_sweep_resumes_to_the_same_file(model, tmp_path):
    """A real process killed after its first checkpoint chunk, then resumed, writes the same CSV."""
    import os
    import signal
    import subprocess
    import sys
    import time

    args = [
        sys.executable,
        "-m",
        "sunwind",
        "sweep",
        model.source.mesh,
        "--reflectivity",
        "0.4",
        "--specular-fraction",
        "0.5",
        "--two-sided",
        "wing*",
        "--srp",
        "--samples",
        "4",
        "--reflections",
        "none",
        "--step",
        "15",
        "--chunk",
        "8",
    ]
    reference = tmp_path / "whole.csv"
    subprocess.run([*args, "-o", reference], check=True, capture_output=True, env=os.environ.copy())
    target = tmp_path / "killed.csv"
    process = subprocess.Popen([*args, "-o", target], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    checkpoint = tmp_path / "killed.csv.checkpoint"
    deadline = time.monotonic() + 120
    while not list(checkpoint.glob("*.npz")) and time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.05)
    process.send_signal(signal.SIGKILL)
    process.wait()
    assert not target.exists() and list(checkpoint.glob("*.npz"))
    subprocess.run([*args, "-o", target, "--resume"], check=True, capture_output=True)
    assert target.read_bytes() == reference.read_bytes()


# ------------------------------------------------------------------------------------------- lists


def test_attitude_list_with_quaternions_turns_inertial_directions_into_the_body_frame(tmp_path):
    path = tmp_path / "a.csv"
    half = math.sqrt(0.5)
    # body turned +90 deg about z: the inertial +x Sun is at body -y
    path.write_text(f"qw,qx,qy,qz,sun_x,sun_y,sun_z\n1,0,0,0,2,0,0\n{half},0,0,{half},1,0,0\n")
    attitudes = read_attitude_csv(path)
    np.testing.assert_allclose(attitudes.sun_vectors, [[1, 0, 0], [0, -1, 0]], atol=1e-15)
    assert attitudes.flow_vectors is None and len(attitudes) == 2


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("sun_x,sun_y\n1,0\n", "sun_z"),
        ("a,b,c\n1,2,3\n", "unexpected column 'a'"),
        ("qw,qx,qy,qz\n1,0,0,0\n", "no direction columns"),
        ("sun_x,sun_y,sun_z,sun_z\n1,0,0,5\n", "column 'sun_z' is given twice"),
        ("sun_x,sun_y,Sun_Y,sun_z\n1,0,0,5\n", "column 'sun_y' is given twice"),
        ("sun_x,sun_y,sun_z,foo\n1,0,0,3\n", "unexpected column 'foo'"),
        ("sun_x,sun_y,sun_z,\n1,0,0,\n", "unexpected column ''"),
        ("\ufeffsun_x,sun_y\n1,0\n", "lacks column sun_z"),
        ("sun_x,sun_y,sun_z\n0,0,0\n", "zero"),
        ("sun_x,sun_y,sun_z\n1,nan,0\n", "NaN"),
        ("sun_x,sun_y,sun_z\n1,x,0\n", "not all numbers"),
        ("sun_x,sun_y,sun_z\n", "at least one"),
    ],
)
def test_bad_attitude_lists_are_refused(tmp_path, text, match):
    path = tmp_path / "a.csv"
    path.write_text(text)
    with pytest.raises(InputError, match=match):
        read_attitude_csv(path)


def test_an_attitude_list_with_a_byte_order_mark_is_read(tmp_path):
    path = tmp_path / "a.csv"
    path.write_bytes(b"\xef\xbb\xbfSun_X, sun_y ,sun_z\n0,3,4\n")
    np.testing.assert_allclose(read_attitude_csv(path).sun_vectors, [[0, 0.6, 0.8]])


def test_list_sweep_from_the_command_line(model, run_cli, tmp_path):
    path = tmp_path / "list.csv"
    path.write_text("sun_x,sun_y,sun_z,flow_x,flow_y,flow_z\n1,0,0,0,1,0\n0,0,1,-1,0,0\n")
    out_path = tmp_path / "list.csv.nc"
    code, _out, err = run_cli(
        "sweep",
        model.source.mesh,
        "--reflectivity",
        "0.4",
        "--specular-fraction",
        "0.5",
        "--transmissivity",
        "0.1",
        "--two-sided",
        "wing*",
        "--samples",
        "4",
        "--reflections",
        "none",
        "--attitudes",
        path,
        "--speed",
        "7600",
        "--density",
        "3e-12",
        "--temperature",
        "900",
        "--composition",
        "O:0.8,N2:0.2",
        "-o",
        out_path,
    )
    assert code == 0, err
    table = open_table(out_path)
    assert table.sizes["attitude"] == 2
    single = srp(model, [0, 0, 1], sampling=ShadowSampling(samples=4), reflections="none")
    np.testing.assert_array_equal(table.srp_force_N.values[1], single.force_N)


# --------------------------------------------------------------------------------------- bad input


def test_unwritable_output_is_refused_before_any_work(run_cli, tmp_path):
    code, _out, err = run_cli("sweep", tmp_path / "missing.obj", "--srp", "-o", tmp_path / "no" / "t.nc")
    assert code == 1 and "directory does not exist" in err and "Traceback" not in err


def test_unknown_extension_and_wrong_format_are_refused(run_cli, tmp_path):
    code, _, err = run_cli("sweep", tmp_path / "m.obj", "-o", tmp_path / "t.dat")
    assert code == 1 and "--format" in err
    code, _, err = run_cli("sweep", tmp_path / "m.obj", "--drag", "-o", tmp_path / "t.xml")
    assert code == 1 and "basilisk holds srp only" in err


@pytest.mark.slow
def test_unreachable_scheduler_is_reported(model, run_cli, tmp_path):
    pytest.importorskip("dask.distributed")
    code, _, err = run_cli(
        "sweep",
        model.source.mesh,
        "--reflectivity",
        "0.4",
        "--specular-fraction",
        "0.5",
        "--two-sided",
        "wing*",
        "--srp",
        "--step",
        "90",
        "--scheduler",
        "tcp://127.0.0.1:9",
        "-o",
        tmp_path / "t.nc",
    )
    assert code == 1 and "cannot reach the Dask scheduler" in err


@pytest.mark.slow
def test_dask_local_cluster_gives_the_local_result(model, air):
    pytest.importorskip("dask.distributed")
    _grid, jobs = _jobs(air, step=45.0)
    local = run_jobs(model, jobs, SweepRun(chunk=9))
    distributed = run_jobs(model, jobs, SweepRun(chunk=9, scheduler="local", workers=2))
    for kind in local:
        for name in local[kind]:
            np.testing.assert_array_equal(distributed[kind][name], local[kind][name])
    assert set(local["drag"]) >= {"force_N", "CD", "CM"}


# ----------------------------------------------------------------------------------- formats, plots

FLAGS = ("--reflectivity", "0.4", "--specular-fraction", "0.5", "--two-sided", "wing*", "--samples", "1")
AIR = ("--density", "3e-12", "--temperature", "900", "--composition", "O:0.8,N2:0.2", "--speed", "7600")


@pytest.mark.parametrize(
    ("name", "extra", "written"),
    [
        ("t.nc", (), ["t.nc"]),
        ("t.csv", (), ["t.srp.csv", "t.drag.csv"]),
        ("t.spo", (), ["t.srp.spo", "t.drag.spo"]),
        ("t.xml", (), ["t.xml"]),
        ("aero", ("--format", "tudat"), ["aero_CFx.txt", "aero_CMz.txt"]),
    ],
)
def test_every_format_is_written_and_named(model, run_cli, tmp_path, name, extra, written):
    code, out, err = run_cli(
        "sweep",
        model.source.mesh,
        *FLAGS,
        *AIR,
        "--reflections",
        "none",
        "--step",
        "45",
        "-o",
        tmp_path / name,
        *extra,
    )
    assert code == 0, err
    for file in written:
        assert (tmp_path / file).stat().st_size > 0
        assert str(tmp_path / file) in out


def test_plot_writes_maps_and_a_pressure_view(model, run_cli, tmp_path):
    table = tmp_path / "t.nc"
    code, _, err = run_cli(
        "sweep", model.source.mesh, *FLAGS, *AIR, "--reflections", "none", "--step", "45", "-o", table
    )
    assert code == 0, err
    code, _out, err = run_cli("plot", table, "-o", tmp_path / "plots")
    assert code == 0, err
    pngs = sorted((tmp_path / "plots").glob("*.png"))
    assert len(pngs) == 6  # SRP and drag force and torque maps (x, y, z panels each), two 3-D views
    assert {p.name.split(".")[1] for p in pngs if "pressure" in p.name} == {"srp", "drag"}
    assert all(p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for p in pngs)
