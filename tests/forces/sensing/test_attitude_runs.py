"""Long attitude runs (METHOD.md "Attitude from heat fluxes"): the rows go through the sweep engine, so
finished chunks are kept in a checkpoint, an interrupted run says how to resume, the resumed output is the
uninterrupted one, and the rows' records read back to the very solutions."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import sunwind as sw
from sunwind.forces.planet.bodies import PlanetLight, planet
from sunwind.forces.sensing import AttitudeSolution, Minimum, attitude_from_fluxes, read_flux_rows
from sunwind.forces.sensing.tabulation import MINIMA, AttitudeSearch
from sunwind.forces.tables import SweepRun

DATA = sw.meshes.sample_path().parent
OPTICS = ["--reflectivity", "0.07", "--specular-fraction", "0", "--emissivity", "0.82"]
BLACK = sw.Material("black", 0.07, 0.0, emissivity=0.82)


def same(a, b) -> bool:
    """Whether two records (solutions, minima) hold equal values, arrays bit for bit (times apart)."""
    if dataclasses.is_dataclass(a):
        return type(a) is type(b) and all(
            same(getattr(a, f.name), getattr(b, f.name)) for f in dataclasses.fields(a) if f.compare
        )
    if isinstance(a, tuple):
        return (
            isinstance(b, tuple) and len(a) == len(b) and all(same(x, y) for x, y in zip(a, b, strict=True))
        )
    if isinstance(a, np.ndarray):
        return isinstance(b, np.ndarray) and np.array_equal(a, b)
    return a == b


def command(output, *extra):
    fluxes = DATA / "sensor_cube_fluxes.csv"
    return [
        "attitude",
        DATA / "sensor_cube.obj",
        *OPTICS,
        "--fluxes",
        fluxes,
        "--altitude",
        "500",
        "-o",
        output,
        *extra,
    ]


def test_records_read_back_to_every_kind_of_row():
    """A sunlit row with the most alternatives a row can have (quaternion and angles), and an eclipse with
    unobservable errors: records and back, equal field for field."""
    light = PlanetLight.of(planet("earth"), 1361.0)
    search = AttitudeSearch(("a", "b", "c"), 500.0, 0.01, 1.0, light)
    rng = np.random.default_rng(5)

    def minimum(k, sun=True):
        unit = rng.normal(size=(2, 3))
        unit /= np.linalg.norm(unit, axis=1)[:, None]
        return Minimum(
            unit[0] if sun else None, unit[1], 1.0 + k, 0.1 * k if sun else None, 0.2, rng.random(3), 4
        )

    minima = [minimum(k) for k in range(MINIMA)]
    sunlit = AttitudeSolution(
        1.0, minima[0], tuple(minima[1:]), False, rng.random(4), rng.random(3), rng.random(3), 0.5
    )
    dark = AttitudeSolution(2.0, minimum(0, sun=False), (), True, None, None, rng.random(3), 0.1)
    back = search.solutions(search.records([sunlit, dark]))
    assert same(back, (sunlit, dark))
    assert back[0].seconds == 0.5 and len(back[0].alternatives) == MINIMA - 1


@pytest.mark.slow
def test_chunked_runs_give_the_rows_of_one_pass_exactly(tmp_path):
    """The bundled rows (ten sunlit, two in eclipse) in chunks of 5 with a checkpoint, then all at once:
    the same solutions, bit for bit, and the checkpoint gone once done."""
    cube = sw.load(DATA / "sensor_cube.obj", uniform=BLACK, threads=1)
    rows = read_flux_rows(DATA / "sensor_cube_fluxes.csv")
    whole = attitude_from_fluxes(cube, rows, 500.0)
    checkpoint = tmp_path / "rows.checkpoint"
    done = []
    chunked = attitude_from_fluxes(
        cube, rows, 500.0, run=SweepRun(chunk=5, checkpoint=checkpoint, progress=done.append)
    )
    assert same(chunked.rows, whole.rows) and done == [0, 5, 10, 12] and not checkpoint.exists()
    assert sum(row.eclipse for row in whole.rows) == 2


def test_ctrl_c_keeps_the_finished_rows_and_the_resumed_file_is_the_uninterrupted_one(
    run_cli, tmp_path, monkeypatch
):
    import sunwind.forces.tables.engine as engine

    once = tmp_path / "once.csv"
    code, out, err = run_cli(*command(once))
    assert code == 0 and f"wrote {once}: 12 rows" in out, err
    output = tmp_path / "rows.csv"
    finished = engine._Finished.__call__

    def interrupt_after_one(self, job, lo, hi, values):
        finished(self, job, lo, hi, values)
        raise KeyboardInterrupt

    monkeypatch.setattr(engine._Finished, "__call__", interrupt_after_one)
    code, _, err = run_cli(*command(output, "--chunk", "4"))
    assert code == 130 and "Traceback" not in err and not output.exists()
    assert (
        "sunwind: notice: 1 finished chunks are kept in " in err and "resume with: sunwind attitude " in err
    )
    monkeypatch.undo()
    code, out, err = run_cli(*command(output, "--chunk", "4", "--resume"))
    assert code == 0 and "kept 1 chunks" in err, err
    assert output.read_text() == once.read_text().replace(str(once), str(output))
    lines = [line for line in output.read_text().splitlines() if not line.startswith("#")]
    assert lines[0].startswith("time_s,sun_body_x") and len(lines) == 13
    assert lines[-1].split(",")[1:4] == ["", "", ""]  # in eclipse: no Sun


@pytest.mark.slow
def test_rows_on_dask_workers_are_the_local_rows(tmp_path):
    """Workers load the model from its file and solve their chunks: the same solutions as here."""
    from dask.distributed import LocalCluster

    cube = sw.load(DATA / "sensor_cube.obj", uniform=BLACK, threads=1)
    rows = read_flux_rows(DATA / "sensor_cube_fluxes.csv")[:6]
    here = attitude_from_fluxes(cube, rows, 500.0)
    cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0")
    try:
        there = attitude_from_fluxes(
            cube, rows, 500.0, run=SweepRun(chunk=3, scheduler=cluster.scheduler_address)
        )
    finally:
        cluster.close()
    assert same(there.rows, here.rows) and there.model_error_W_m2 == here.model_error_W_m2
