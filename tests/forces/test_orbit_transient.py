"""The thermal transient along an orbit (``EarthTerms(thermal="transient")``, ``sunwind orbit --thermal
transient``): a black isothermal sphere on three orbits against ``solve_ivp`` of its heat balance with
the conical shadow at any time; a run stopped and resumed from its checkpoint gives bitwise the
uninterrupted run, hinged wings included; the per-side forcing is sized before the run; the command
line keeps ``--thermal`` alone the equilibrium and refuses a transient without heat capacity in one
line."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest
import xarray as xr
from scipy.integrate import solve_ivp

from helpers.planet import BLACK, write_sphere
from helpers.runs import stopped_then_resumed
from sunwind.forces import Model, load
from sunwind.forces.orbit import AttitudeLaw, Elements, Epoch, OrbitLoads, fly, propagate
from sunwind.forces.orbit.earth_terms import EarthTerms
from sunwind.forces.orbit.plots import plot_thermal
from sunwind.forces.orbit.sun import AU_M
from sunwind.forces.planet.shadow import sphere_visible
from sunwind.forces.tables import SweepRun
from sunwind.forces.tables.jobs import SrpSetup
from sunwind.forces.thermal import STEFAN_BOLTZMANN, integrate, thermal_model
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import Material, ThermalRule
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes.primitives import box_wing, sphere

EPOCH = Epoch.of("2024-06-01T00:00:00Z")
R_EARTH = 6_378_137.0
SOLAR_1AU = 1361.0
SUN = np.array([1.0, 0.0, 0.0])  # a fixed Sun along GCRF x, in the orbit's plane: the longest eclipses
CAPACITY = 20_000.0  # [J/K]
NONE = SrpSetup(reflections="none")
INERTIAL = AttitudeLaw.parse("inertial:1,0,0,0")  # the body frame is GCRF


@pytest.fixture(scope="module")
def black_sphere():
    """A black sphere of 0.5 m (88 triangles, one isothermal part of 20 kJ/K) fixed in GCRF on a
    circular 500 km orbit, three orbits at 30 s steps, the Sun fixed, no albedo and no Earth infrared:
    only sunlight in and its own emission out."""
    craft = build_spacecraft(sphere(0.5, 6), uniform=Material("black", 0.0, 0.0, emissivity=1.0))
    craft = replace(craft, thermal=(ThermalRule("sphere", isothermal=True, heat_capacity_J_K=CAPACITY),))
    model = Model(craft)
    orbit = Elements.circular(500.0, 51.6)
    times = np.arange(0.0, 3 * 5677.0, 30.0)
    path = propagate(orbit, EPOCH, times, "kepler")
    earth = EarthTerms(NONE, albedo=0.0, infrared_W_m2=0.0, thermal="transient")
    result = fly(model, path, INERTIAL, OrbitLoads(earth=earth), sun_eci=SUN)
    return model, path, result


def _circular(path):
    """The circular orbit in closed form from its first state: ``r(t) = r0 cos(n t) + (v0 / n) sin(n t)``."""
    r0, v0 = path.position_m[0], path.velocity_m_s[0]
    rate = np.linalg.norm(v0) / np.linalg.norm(r0)
    return lambda t: np.multiply.outer(np.cos(rate * t), r0) + np.multiply.outer(np.sin(rate * t), v0 / rate)


def _exact(model, path):
    """``C dT/dt = P(t) - sigma A T^4`` by Radau (rtol 1e-10, atol 1e-8), independent of the run: the
    circular orbit in closed form, the share of the Sun from ``sphere_visible``, the sunlight on the
    faceted sphere's projected area, at any time."""
    craft, position = model.craft, _circular(path)
    normals, areas, area = craft.side_normals, craft.side_areas, craft.side_areas.sum()
    sun_m = AU_M * SUN

    def power(t: float) -> float:
        r = position(t)
        to_sun = sun_m - r
        distance = np.linalg.norm(to_sun)
        projected = areas @ np.maximum(normals @ (to_sun / distance), 0.0)
        share = sphere_visible(r, sun_m, R_EARTH)[0]
        return SOLAR_1AU * (AU_M / distance) ** 2 * share * projected

    start = (power(0.0) / (STEFAN_BOLTZMANN * area)) ** 0.25  # the equilibrium of the first step
    solution = solve_ivp(
        lambda t, y: (power(t) - STEFAN_BOLTZMANN * area * y**4) / CAPACITY,
        (0.0, path.time_s[-1]),
        [start],
        method="Radau",
        t_eval=path.time_s,
        rtol=1e-10,
        atol=1e-8,
        jac=lambda t, y: [[-4 * STEFAN_BOLTZMANN * area * y[0] ** 3 / CAPACITY]],
    )
    assert solution.success
    return solution.y[0]


def test_a_black_sphere_on_three_orbits_follows_solve_ivp(black_sphere):
    """Within 0.1 K of ``solve_ivp`` along three orbits of 35 min eclipses at 30 s steps (measured
    1.2e-3 K; the sphere swings from 212 K to 277 K), the eclipse edges resolved inside the steps; the
    integrator's estimate is of the size of the true error (1.4e-3 K)."""
    model, path, result = black_sphere
    s = result.series
    off = np.linalg.norm(_circular(path)(path.time_s) - path.position_m, axis=1)
    assert off.max() < 1e-3  # the closed-form orbit is the run's, to a millimetre
    exact = _exact(model, path)
    temperature = s["part_temperature_K"][:, 0]
    error = temperature - exact
    assert np.ptp(exact) > 40.0 and 0 < (s["solar_fraction"] == 0).sum() < len(exact)  # a real swing
    assert np.abs(error).max() < 0.1
    assert s["thermal_error_K"][0] == 0 and s["thermal_error_K"].max() < 0.1
    assert 0.2 < s["thermal_error_K"].max() / np.abs(error).max() < 5.0
    assert np.abs(s["thermal_force_body_N"]).max() < 1e-20  # one temperature: no net recoil
    assert result.terms == ("albedo", "infrared", "thermal")
    assert result.summary()["thermal_error_worst_K"] == s["thermal_error_K"].max()


def test_the_outputs_carry_the_mode_its_tolerance_and_start(black_sphere, tmp_path):
    _, _, result = black_sphere
    attributes = result.attributes
    assert attributes["thermal"] == "transient" and attributes["thermal_tolerance_K"] == 0.01
    assert attributes["thermal_initial_temperature_K"] == "equilibrium of the first step"
    result.to_dataset().to_netcdf(tmp_path / "run.nc")
    table = xr.open_dataset(tmp_path / "run.nc")
    assert table.attrs["thermal"] == "transient" and table.attrs["thermal_tolerance_K"] == 0.01
    assert table["thermal_error_K"].attrs["units"] == "K" and table["thermal_error_K"].dims == ("time",)
    assert "transient" in table["part_temperature_K"].attrs["long_name"]
    assert np.array_equal(table["part_temperature_K"].values, result.series["part_temperature_K"])
    document = result.to_json()
    assert document["attributes"]["thermal_initial_temperature_K"] == "equilibrium of the first step"
    assert len(document["thermal_error_K"]) == len(result.series["time_s"])
    assert "forcing_sun_side_W" not in result.series  # the integrator's inputs stay out of the output
    plot_thermal(result, tmp_path / "heat.png")
    assert (tmp_path / "heat.png").read_bytes()[:4] == b"\x89PNG"


HINGED = """[materials.cells]
reflectivity = 0.1
specular_fraction = 0.8
emissivity = 0.85

[materials.back]
reflectivity = 0.5
specular_fraction = 0.2
emissivity = 0.3

[materials.paint]
reflectivity = 0.3
specular_fraction = 0.1
emissivity = 0.8

[parts]
"wing*" = { front = "cells", back = "back" }
"*" = "paint"

[thermal."bus"]
isothermal = true
heat_capacity_J_K = 20000.0

[thermal."wing_left"]
isothermal = true
heat_capacity_J_K = 1500.0

[[conductance]]
parts = ["bus", "wing_left"]
conductance_W_K = 0.5

[articulation."wing*"]
axis = [0, 1, 0]
origin_m = [0, 0, 0]
schedule = [[0, 0], [1200, 90]]
"""


@pytest.fixture(scope="module")
def hinged(tmp_path_factory):
    """A box-wing whose wings turn on a schedule: an isothermal bus and left wing with heat capacities
    and a conductance between them, the right wing a node per facet in equilibrium; cells in front
    (eps 0.85) and a back of eps 0.3, so that the wings recoil."""
    folder = tmp_path_factory.mktemp("hinged")
    (folder / "hinged.toml").write_text(HINGED)
    return load(box_wing(facet_size=0.5), folder / "hinged.toml", threads=1)


def test_a_resumed_run_gives_the_uninterrupted_transient_bitwise(hinged, tmp_path, monkeypatch):
    """The integration runs after the chunks, over their records: stopped after the first chunk and
    resumed, the run ends with the same bits as one that was not stopped; a step posed by its hinges
    takes its recoil from its pose, at the integrated node temperatures."""
    path = propagate(Elements.circular(500.0, 51.6, 20.0), EPOCH, np.arange(0.0, 1800.0, 60.0), "kepler")
    earth = EarthTerms(NONE, cell_deg=30.0, thermal="transient", initial_temperature_K=290.0)
    loads, law = OrbitLoads(NONE, earth=earth), AttitudeLaw.parse("nadir")
    seen = {}
    original = EarthTerms.integrate_thermal

    def spy(self, model, times_s, records, solar_fraction, angles, **keywords):
        seen.update(records=records, solar_fraction=solar_fraction, angles=angles)
        return original(self, model, times_s, records, solar_fraction, angles, **keywords)

    monkeypatch.setattr(EarthTerms, "integrate_thermal", spy)
    whole = fly(hinged, path, law, loads)
    monkeypatch.undo()
    resumed, notices = stopped_then_resumed(
        lambda run: fly(hinged, path, law, loads, run=run), tmp_path / "run.checkpoint", 10
    )
    assert notices == ["checkpoint: kept 1 chunks, recomputing 2"]
    names = ("part_temperature_K", "thermal_error_K", "thermal_force_body_N", "thermal_torque_body_Nm")
    for name in (*names, "torque_body_Nm", "angular_impulse_eci_Nms"):
        assert np.array_equal(resumed.series[name], whole.series[name]), name
    s = whole.series
    assert np.all(s["part_temperature_K"][0] == 290.0) and s["thermal_error_K"].max() < 0.1
    assert np.linalg.norm(s["thermal_force_body_N"], axis=1).min() > 0  # the wings recoil
    assert whole.attributes["thermal_initial_temperature_K"] == 290.0
    # redone here: the nodes integrated as loaded, the recoil of a posed step from its pose
    records, share = seen["records"], seen["solar_fraction"]
    sun, rest = records["forcing_sun_side_W"], records["forcing_planet_side_W"]
    lumped = thermal_model(hinged.craft, "none")
    assert lumped.nodes.heat_capacity_J_K.tolist()[:2] == [20000.0, 1500.0]
    history = integrate(lumped, path.time_s, rest, initial=np.full(lumped.nodes.n_nodes, 290.0),
                        solar_W=sun, solar_fraction=share)  # fmt: skip
    assert np.array_equal(history.error_K, s["thermal_error_K"])
    done = []  # in blocks of 7 steps, told after each: the same bits
    again = earth.sized(hinged, 30).integrate_thermal(
        hinged, path.time_s, records, share, seen["angles"], block=7, progress=done.append
    )
    assert done == [8, 15, 22, 29, 30]
    assert all(np.array_equal(again[name], s[name].reshape(again[name].shape)) for name in names)
    for k in (0, 10, 25):
        posed = hinged.posed(seen["angles"][k])
        angle = whole.hinge_angles_deg["wing*"][k]
        assert (posed is hinged) == (k == 0) and seen["angles"][k]["wing*"] == angle
        q = rest[k] + s["solar_fraction"][k] * sun[k]
        state = thermal_model(posed.craft, "none").state_at(history.node_temperature_K[k], q)
        assert np.array_equal(state.force_N, s["thermal_force_body_N"][k])
        assert np.array_equal(state.torque_Nm, s["thermal_torque_body_Nm"][k])


def test_a_run_stopped_in_the_integration_keeps_its_checkpoint_and_resumes_without_a_step(
    hinged, tmp_path, monkeypatch
):
    """Ctrl-C while the transient is integrated, after every step is in: the checkpoint is still there
    (removed only once the integration is done), and the resumed run takes every step from it,
    computes none, and ends with the uninterrupted run's bits; then the checkpoint is gone."""
    path = propagate(Elements.circular(500.0, 51.6, 20.0), EPOCH, np.arange(0.0, 1200.0, 60.0), "kepler")
    earth = EarthTerms(NONE, cell_deg=30.0, thermal="transient", initial_temperature_K=290.0)
    loads, law = OrbitLoads(NONE, earth=earth), AttitudeLaw.parse("nadir")
    whole = fly(hinged, path, law, loads)
    original, stops = EarthTerms.integrate_thermal, []

    def stopped_once(self, *arguments, **keywords):
        if not stops:
            stops.append(True)
            raise KeyboardInterrupt
        return original(self, *arguments, **keywords)

    monkeypatch.setattr(EarthTerms, "integrate_thermal", stopped_once)
    checkpoint = tmp_path / "run.checkpoint"
    with pytest.raises(KeyboardInterrupt):
        fly(hinged, path, law, loads, run=SweepRun(chunk=8, checkpoint=checkpoint))
    assert stops and len(list(checkpoint.glob("*.npz"))) == 3  # every step kept
    told, notices = [], []
    run = SweepRun(chunk=8, checkpoint=checkpoint, resume=True, progress=told.append, notice=notices.append)
    resumed = fly(hinged, path, law, loads, run=run)
    assert notices == ["checkpoint: kept 3 chunks, recomputing 0"]
    assert told[0] == 20 and all(k >= 20 for k in told)  # no step computed, then the integration
    for name in ("part_temperature_K", "thermal_error_K", "thermal_force_body_N", "torque_body_Nm"):
        assert np.array_equal(resumed.series[name], whole.series[name]), name
    assert not checkpoint.exists()


def test_the_transient_is_sized_before_the_run(black_sphere, monkeypatch):
    model, path, _ = black_sphere
    terms = EarthTerms(NONE, thermal="transient")
    assert terms.sized(model, 10).n_sides == model.craft.n_sides
    monkeypatch.setenv("SUNWIND_MAX_MEMORY", "1M")
    with pytest.raises(InputError, match=r"transient's forcing and history .* take thermal equilibrium"):
        terms.sized(model, 10**5)
    bare = Model(replace(model.craft, thermal=()))
    monkeypatch.delenv("SUNWIND_MAX_MEMORY")
    with pytest.raises(InputError, match=r"needs a node with a heat capacity.*heat_capacity_J_K = \.\.\."):
        fly(bare, path, INERTIAL, OrbitLoads(earth=terms))
    with pytest.raises(InputError, match="not one of equilibrium, transient"):
        EarthTerms(NONE, thermal="lumped")
    with pytest.raises(InputError, match="are the transient's"):
        EarthTerms(NONE, thermal=True, initial_temperature_K=280.0)
    with pytest.raises(InputError, match=r"initial_temperature_K -1\.0 is not a temperature"):
        EarthTerms(NONE, thermal="transient", initial_temperature_K=-1.0)


# --- the command line ------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("orbit_transient")
    write_sphere(folder / "sphere.obj", 6)
    (folder / "black.toml").write_text(BLACK)
    lumped = '[thermal."*"]\nisothermal = true\nheat_capacity_J_K = 9000.0\n'
    (folder / "lumped.toml").write_text(BLACK + lumped)
    return folder


def _orbit(folder, *extra):
    return [
        "orbit", folder / "sphere.obj", "--altitude", "500", "--inclination", "51.6", "--epoch",
        "2024-03-20T00:00:00Z", "--duration", "600", "--step", "60", "--srp", "--earth-radiation",
        "--reflections", "none", "--earth-step", "30", *extra,
    ]  # fmt: skip


def test_thermal_alone_is_still_the_equilibrium(run_cli, files):
    code, out, err = run_cli(*_orbit(files, "-m", files / "lumped.toml", "--thermal", "--json"))
    assert code == 0, err
    doc = json.loads(out)
    assert doc["attributes"]["thermal"] == "equilibrium" and "thermal_error_K" not in doc
    assert "notice: --thermal transient" not in err


def test_thermal_transient_runs_and_says_where_it_starts(run_cli, files):
    code, out, err = run_cli(*_orbit(files, "-m", files / "lumped.toml", "--thermal", "transient"))
    assert code == 0, err
    assert "sunwind: notice: --thermal transient starts from the equilibrium of the first step" in err
    assert "thermal    transient from the equilibrium of the first step, tolerance 0.01 K per step" in out
    code, out, err = run_cli(
        *_orbit(files, "-m", files / "lumped.toml", "--thermal", "transient", "--initial-temperature", "250",
                "--thermal-tolerance", "0.001", "--json")
    )  # fmt: skip
    assert code == 0, err
    doc = json.loads(out)
    assert doc["part_temperature_K"][0] == [250.0] and doc["attributes"]["thermal_tolerance_K"] == 0.001
    assert "notice: --thermal transient" not in err


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (("-m", "black.toml", "--thermal", "transient"), "transient needs a node with a heat capacity"),
        (("-m", "lumped.toml", "--thermal", "--initial-temperature", "250"), "needs --thermal transient"),
        (("-m", "lumped.toml", "--thermal", "transient", "--thermal-tolerance", "0"), "above 0 K"),
        (("-m", "lumped.toml", "--thermal", "lumped"), "'lumped' is not one of"),
    ],
)
def test_bad_transient_options_get_one_line(run_cli, files, extra, words):
    extra = tuple(files / e if e.endswith(".toml") else e for e in extra)
    code, _, err = run_cli(*_orbit(files, *extra))
    assert code != 0
    lines = [line for line in err.splitlines() if line.startswith("sunwind") and " error:" in line]
    assert len(lines) == 1 and words in lines[0], err
    assert "Traceback" not in err
    if "heat capacity" in words:  # names the materials file and the fix
        assert str(files / "black.toml") in lines[0] and '[thermal."GLOB"] isothermal = true' in lines[0]
