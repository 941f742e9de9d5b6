"""Per-part and per-side absorbed powers along an orbit, the product for thermal models: the sides add up
to their parts, a black cube's sides take the closed-form sunlight and none in eclipse, the netCDF
round-trips with CF time, units, long names and the sides' coordinates, the per-side records are refused
before the run when they would not fit, and the heat plot is written."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from sunwind.forces import Model
from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, OrbitLoads, fly, propagate
from sunwind.forces.orbit.earth_terms import PART_SOURCES, EarthTerms
from sunwind.forces.orbit.plots import plot_thermal
from sunwind.forces.orbit.sun import AU_M, sun_position
from sunwind.forces.tables.jobs import SrpSetup
from sunwind.forces.vocabulary import SIDE, absorbed_name
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import Material
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes.primitives import box, box_wing

EPOCH = Epoch.of("2024-06-01T00:00:00Z")
TIMES = np.arange(0.0, 5700.0, 600.0)  # one orbit at 500 km, through the Earth's shadow
PAINT = Material("paint", 0.5, 0.4, 0.0, emissivity=0.85)
BLACK = Material("black", 0.0, 0.0, 0.0, emissivity=1.0)


def _fly(craft, law, reflections, thermal=False):
    model = Model(craft)
    path = propagate(Elements.circular(500.0, 51.6, 20.0), EPOCH, TIMES, "kepler")
    surface = SrpSetup(reflections=reflections)
    earth = EarthTerms(surface, cell_deg=15.0, thermal=thermal, per_side=True).sized(model, len(TIMES))
    return model, path, fly(model, path, AttitudeLaw.parse(law), OrbitLoads(surface, earth=earth))


@pytest.fixture(scope="module")
def wing_run():
    """A box-wing with inter-reflection (every source non-zero), thermal."""
    craft = build_spacecraft(box_wing(facet_size=0.5), uniform=PAINT, two_sided=["wing*"])
    return _fly(craft, "lvlh:5,-10,3", "full", thermal=True)


@pytest.fixture(scope="module")
def cube_run():
    """A black 1 m cube fixed in GCRF: no shadow of its own, no reflection."""
    return _fly(build_spacecraft(box(), uniform=BLACK), "inertial:1,0,0,0", "none")


def test_the_sides_of_each_part_add_up_to_its_powers(wing_run):
    model, _, result = wing_run
    craft = model.craft
    s = result.series
    part_of_side = craft.facet_part[craft.side_facet]
    assert [*np.unique(result.sides["side_part"])] == sorted(result.part_names)
    assert np.array_equal(result.sides["side_part"], np.asarray(craft.part_names)[part_of_side])
    for source in PART_SOURCES:
        sides = s[absorbed_name(SIDE, source)]
        assert sides.shape == (len(TIMES), craft.n_sides)
        summed = np.stack([np.bincount(part_of_side, row, len(craft.part_names)) for row in sides])
        assert np.allclose(s[f"part_{source}_W"], summed, rtol=1e-12, atol=1e-12)
        assert s[f"part_{source}_W"].max() > 0  # every source is there
    assert np.all(np.isfinite(s["part_temperature_K"]))


def test_a_black_cube_takes_the_closed_form_sunlight_and_none_in_eclipse(cube_run):
    model, path, result = cube_run
    s, craft = result.series, model.craft
    sun = sun_position(EPOCH, path.time_s) - path.position_m  # inertial attitude: the body frame is GCRF
    flux = 1361.0 * (AU_M / np.linalg.norm(sun, axis=1)) ** 2
    cos = np.maximum(craft.side_normals @ (sun / np.linalg.norm(sun, axis=1, keepdims=True)).T, 0.0).T
    expected = craft.side_areas * cos * (flux * s["solar_fraction"])[:, None]
    assert np.allclose(s["side_solar_W"], expected, rtol=1e-10, atol=0)
    dark = s["solar_fraction"] == 0
    assert 0 < dark.sum() < len(TIMES)
    assert np.all(s["side_solar_W"][dark] == 0) and np.all(s["part_solar_W"][dark] == 0)
    assert np.all(s["side_infrared_W"][dark].sum(axis=1) > 0)  # the Earth still warms it
    assert np.all(s["side_reflected_W"] == 0)  # black


def test_the_netcdf_round_trips_with_cf_time_units_names_and_side_coordinates(wing_run, tmp_path):
    model, _, result = wing_run
    result.to_dataset().to_netcdf(tmp_path / "run.nc")
    raw = xr.open_dataset(tmp_path / "run.nc", decode_times=False)
    time = raw["time"].attrs
    assert time["units"] == "seconds since 2024-06-01T00:00:00.000Z" and time["calendar"] == "standard"
    assert time["standard_name"] == "time" and "_FillValue" not in raw["time"].encoding
    for where, dim in (("part", "part"), ("side", "side")):
        for source in PART_SOURCES:
            variable = raw[f"{where}_{source}_W"]
            assert variable.dims == ("time", dim)
            assert variable.attrs["units"] == "W"
            assert source in variable.attrs["comment"] and "standard_name" not in variable.attrs
            assert variable.attrs["long_name"].startswith("power absorbed by each")
            assert np.array_equal(variable.values, result.series[f"{where}_{source}_W"])
    assert list(raw["part"].values) == list(result.part_names)
    craft = model.craft
    assert np.array_equal(raw["side_facet"].values, craft.side_facet)
    assert list(raw["side_face"].values) == ["front" if s > 0 else "back" for s in craft.side_sign]
    assert np.array_equal(raw["side_area_m2"].values, craft.side_areas)
    assert raw["side_area_m2"].attrs["units"] == "m2" and raw["part_temperature_K"].attrs["units"] == "K"
    decoded = xr.open_dataset(tmp_path / "run.nc")
    assert decoded["time"].values[1] - decoded["time"].values[0] == np.timedelta64(600, "s")
    assert str(decoded["time"].values[0]).startswith("2024-06-01T00:00:00")


def test_csv_and_json_name_each_side_by_part_facet_and_face(cube_run, tmp_path):
    _, _, result = cube_run
    result.write_csv(tmp_path / "run.csv")
    header = next(line for line in (tmp_path / "run.csv").read_text().splitlines() if line[0] != "#")
    assert "side_solar_W[box:0:front]" in header.split(",")
    document = result.to_json()
    assert document["sides"]["side_facet"] == list(range(12)) and len(document["side_albedo_W"][0]) == 12


def test_fly_sizes_the_per_side_terms_to_the_model_it_flies(cube_run, wing_run):
    """``fly`` sizes the terms itself (unsized, or sized to another model); the setup alone refuses
    records of unknown or other width before any step."""
    model, path, whole = cube_run
    surface = SrpSetup(reflections="none")
    terms = EarthTerms(surface, per_side=True)
    law = AttitudeLaw.parse("inertial:1,0,0,0")
    for earth in (terms, terms.sized(wing_run[0], len(TIMES))):
        result = fly(model, path, law, OrbitLoads(surface, earth=earth))
        assert np.array_equal(result.series["side_solar_W"], whole.series["side_solar_W"])
    with pytest.raises(InputError, match=r"sized\(model, steps\)"):
        terms.fields(n_parts=1)
    with pytest.raises(InputError, match="sized to 144 sides fly a model of 12"):
        terms.sized(wing_run[0], len(TIMES)).precompute(model)


def test_the_heat_plot_is_written_and_needs_the_earth(wing_run, cube_run, tmp_path):
    _, path, result = wing_run
    plot_thermal(result, tmp_path / "heat.png")
    assert (tmp_path / "heat.png").read_bytes()[:4] == b"\x89PNG"
    no_earth = fly(cube_run[0], path, AttitudeLaw.parse("nadir"), OrbitLoads(SrpSetup(reflections="none")))
    with pytest.raises(InputError, match="no absorbed powers"):
        plot_thermal(no_earth, tmp_path / "none.png")


@pytest.fixture(scope="module")
def wing_file(tmp_path_factory):
    from sunwind.geometry.io import save_mesh

    path = tmp_path_factory.mktemp("orbit-powers") / "box_wing.obj"
    save_mesh(box_wing(facet_size=0.5), path)  # 144 sides
    return [
        str(path),
        "--reflectivity",
        "0.3",
        "--specular-fraction",
        "0.5",
        "--emissivity",
        "0.8",
        "--two-sided",
        "wing*",
    ]


ORBIT = ["--altitude", "500", "--inclination", "51.6", "--epoch", "2024-06-01T00:00:00Z", "--srp"]


def test_the_command_writes_the_sides_and_the_heat_plot(run_cli, wing_file, tmp_path):
    args = [*ORBIT, "--duration", "1200", "--step", "600", "--reflections", "none", "--earth-step", "20"]
    code, out, err = run_cli(
        "orbit", *wing_file, *args, "--earth-radiation", "--thermal", "--per-side",
        "-o", tmp_path / "run.nc", "--plot-thermal", tmp_path / "heat.png",
    )  # fmt: skip
    assert code == 0, err
    assert f"wrote {tmp_path / 'heat.png'}" in out
    assert (tmp_path / "heat.png").read_bytes()[:4] == b"\x89PNG"
    table = xr.open_dataset(tmp_path / "run.nc")
    assert table["side_infrared_W"].dims == ("time", "side") and table.sizes["side"] == 144
    assert set(table["side_part"].values) == {"bus", "wing_left", "wing_right"}


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (("--per-side", "-o", "run.nc"), "--per-side needs --earth-radiation"),
        (("--plot-thermal", "heat.png"), "--plot-thermal needs --earth-radiation"),
        (("--earth-radiation", "--per-side"), "without -o or --json they would be lost"),
        (("--earth-radiation", "--per-side", "-o", "run.nc"), "not enough memory"),
    ],
)
def test_bad_heat_outputs_get_one_line_before_the_run(
    run_cli, wing_file, tmp_path, monkeypatch, extra, words
):
    # 11 steps: ~22 KiB of steps, 11 x 144 x 4 x 8 = ~50 KiB of per-side records
    monkeypatch.setenv("SUNWIND_MAX_MEMORY", "40K")
    extra = [tmp_path / e if e.endswith((".nc", ".png")) else e for e in extra]
    code, _, err = run_cli("orbit", *wing_file, *ORBIT, "--duration", "600", "--step", "60", *extra)
    assert code != 0
    lines = [line for line in err.splitlines() if line.startswith("sunwind: error:")]
    assert len(lines) == 1 and words in lines[0], err
    assert "Traceback" not in err and not (tmp_path / "run.nc").exists()
    if words == "not enough memory":
        assert "--per-side" in lines[0] and "11 steps x 144 sides" in lines[0]
