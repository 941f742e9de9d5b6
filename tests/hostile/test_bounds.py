"""Finite but impossible values (issue 33's third sweep): space weather past any storm, a flux hotter
than the Sun, a subnormal reference area, rays and sizes without end. Each was a traceback, numpy
overflow warnings, hours of work or a meaningless answer; each is now one ``sunwind: error:`` line naming
the flag and its physical bound, and a value just inside the bound still runs."""

import pytest

OPTICS = ["--reflectivity", "0.3", "--specular-fraction", "0.5"]
SUN = ["--sun", "1", "0", "0"]
FLOW = ["--velocity", "7600", "0", "0", "--altitude", "400"]
SRP = ["srp", "{d}/box.obj", *OPTICS, *SUN]
FORCES = ["forces", "{d}/box.obj", *OPTICS, *SUN, *FLOW]
BELOW = ["--emissivity", "0.8", "--earth", "0", "0", "-1", "--altitude", "500"]
EARTH = ["earth", "{d}/box.obj", *OPTICS, *SUN, *BELOW]
SWEEP = ["sweep", "{d}/box.obj", *OPTICS, "--srp", "--step", "90", "-o", "{d}/t.nc"]


@pytest.fixture(scope="module")
def d(tmp_path_factory):
    """A folder holding a 1 m box of 12 triangles."""
    from sunwind.geometry.io import save_mesh
    from sunwind.meshes.primitives import box

    folder = tmp_path_factory.mktemp("bounds")
    save_mesh(box(), folder / "box.obj")
    return folder


#: name: (command line, {d} the folder of the box; the flag the error names; words of its bound)
REFUSED = {
    "--f107 1e308": ([*FORCES, "--f107", "1e308"], "--f107", "above 500 sfu"),
    "--f107a 1e308": ([*FORCES, "--f107a", "1e308"], "--f107a", "above 500 sfu"),
    "--f107a far above --f107": ([*FORCES, "--f107", "60", "--f107a", "450"], "--f107a 450",
                                 "outside its fit"),
    "--ap 1e308": ([*FORCES, "--ap", "1e308"], "--ap", "above 400 (the top of the Ap scale)"),
    "--lon 1e308": ([*FORCES, "--lon", "1e308"], "--lon", "is above 360"),
    "--lon -361": ([*FORCES, "--lon", "-361"], "--lon", "is below -360"),
    "srp --flux 1e308": ([*SRP, "--flux", "1e308"], "--flux", "the flux at the Sun's photosphere"),
    "forces --flux 1e308": ([*FORCES, "--flux", "1e308"], "--flux", "above 1e+09 W/m^2"),
    "earth --flux 1e308": ([*EARTH, "--flux", "1e308"], "--flux", "above 1e+09 W/m^2"),
    "sweep --flux 1e308": ([*SWEEP, "--flux", "1e308"], "--flux", "above 1e+09 W/m^2"),
    "--distance-au 1e-9": ([*SRP, "--distance-au", "1e-9"], "--distance-au", "inside the Sun"),
    "earth --earth-ir 1e308": ([*EARTH, "--earth-ir", "1e308"], "--earth-ir", "above 100000 W/m^2"),
    "--ref-area 1e-320": ([*FORCES, "--ref-area", "1e-320"], "--ref-area", "from 1e-12 to 1e+12 m^2"),
    "--ref-area 1e13": ([*FORCES, "--ref-area", "1e13"], "--ref-area", "from 1e-12 to 1e+12 m^2"),
    "--ref-length 1e-320": ([*FORCES, "--ref-length", "1e-320"], "--ref-length", "from 1e-06 to 1e+06 m"),
    "srp --view-rays 1e8": ([*SRP, "--view-rays", "100000000"], "--view-rays", "from 1 to 65536"),
    "forces --view-rays 1e8": ([*FORCES, "--view-rays", "100000000"], "--view-rays", "from 1 to 65536"),
    "--sun-azel 1e308 0": (["srp", "{d}/box.obj", *OPTICS, "--sun-azel", "1e308", "0"], "--sun-azel",
                           "azimuth 1e+308 deg is outside [-360, 360]"),
    "mesh box --size 1e308": (["mesh", "box", "--size", "1e308", "1", "1", "-o", "{d}/m.obj"], "--size",
                              "above 10000 m"),
    "mesh sphere --radius 2e4": (["mesh", "sphere", "--radius", "2e4", "-o", "{d}/m.obj"], "--radius",
                                 "above 10000 m"),
    "mesh cylinder --length 1e308": (["mesh", "cylinder", "--length", "1e308", "-o", "{d}/m.obj"],
                                     "--length", "above 10000 m"),
    "mesh dish --diameter 1e308": (["mesh", "dish", "--diameter", "1e308", "-o", "{d}/m.obj"],
                                   "--diameter", "above 10000 m"),
    "mesh box_wing --bus-size 1e308": (["mesh", "box_wing", "--bus-size", "1", "1e308", "1", "-o",
                                        "{d}/m.obj"], "--bus-size", "above 10000 m"),
    "mesh box_wing --wing-gap 1e308": (["mesh", "box_wing", "--wing-gap", "1e308", "-o", "{d}/m.obj"],
                                       "--wing-gap", "above 10000 m"),
}  # fmt: skip


@pytest.mark.parametrize("args, flag, bound", REFUSED.values(), ids=REFUSED.keys())
def test_a_value_past_its_physical_bound_is_one_error_line_naming_the_flag(run_cli, d, args, flag, bound):
    code, out, err = run_cli(*(a.format(d=d) for a in args))
    assert code == 1 and out == "", err
    assert err.startswith("sunwind: error: ") and err.count("\n") == 1, err
    assert flag in err and bound in err, err
    assert "encountered" not in err and "Traceback" not in err, err
    assert not (d / "m.obj").exists() and not (d / "t.nc").exists()


def test_the_earth_radiation_of_forces_refuses_an_infrared_past_its_bound(run_cli, d):
    """``forces`` checks ``--earth-ir`` with its other flags, before any work: one line."""
    args = ["forces", d / "box.obj", *OPTICS, *SUN, "--earth-radiation", *BELOW, "--earth-ir", "1e308"]
    code, out, err = run_cli(*args)
    assert code == 1 and out == "" and err.count("\n") == 1, err
    assert err.startswith("sunwind: error: --earth-ir 1e+308 W/m^2 is above"), err
    assert "encountered" not in err and "Traceback" not in err, err


def test_view_rays_within_the_cap_still_meet_the_memory_limit(run_cli, d, monkeypatch):
    monkeypatch.setenv("SUNWIND_MAX_MEMORY", "10M")
    args = [*SRP, "--reflections", "full", "--view-rays", "65536", "--no-cache"]
    code, _, err = run_cli(*(str(a).format(d=d) for a in args))
    assert code == 1 and err.count("\n") == 1 and "lower --view-rays" in err, err


#: name: command line of values just inside their bounds, each run to the end
ACCEPTED = {
    "--flux 1e4": [*SRP, "--flux", "1e4"],
    "--distance-au 0.3, --sun-azel 359 10": ["srp", "{d}/box.obj", *OPTICS, "--sun-azel", "359", "10",
                                             "--distance-au", "0.3"],
    "--f107 300 --f107a 300 --ap 300 --lon -300": ["drag", "{d}/box.obj", *FLOW, "--reflections", "none",
                                                   "--f107", "300", "--f107a", "300", "--ap", "300",
                                                   "--lon", "-300"],
    "--earth-ir 1e4": [*EARTH, "--earth-ir", "1e4", "--plates"],
    "mesh box --size 1e4": ["mesh", "box", "--size", "1e4", "1", "1", "-o", "{d}/big.obj"],
}  # fmt: skip


@pytest.mark.parametrize("args", ACCEPTED.values(), ids=ACCEPTED.keys())
def test_a_value_just_inside_its_bound_still_runs(run_cli, d, args):
    code, out, err = run_cli(*(a.format(d=d) for a in args))
    assert code == 0 and out, err
    assert "error" not in err and "encountered" not in err, err


def test_the_library_takes_each_bound_itself_and_refuses_past_it():
    """The checks are the library's (Python users get them too), at the bounds exactly."""
    from sunwind.forces.gas.msis import nrlmsis
    from sunwind.forces.planet.bodies import PlanetLight, planet
    from sunwind.forces.radiation.law import PHOTOSPHERE_FLUX, SUN_RADIUS_AU, solar_flux
    from sunwind.forces.reflection import ReflectionSettings
    from sunwind.geometry.directions import azel_to_vector
    from sunwind.geometry.errors import InputError
    from sunwind.geometry.views.view_factors import resolve_rays_per_side
    from sunwind.meshes.primitives import box, sphere

    air = nrlmsis(400.0, longitude_deg=-360.0, f107=500.0, f107a=500.0, ap=400.0)
    assert 1000 < air.temperature_K < 3000 and air.inputs["ap"] == 400.0
    with pytest.raises(InputError, match=r"NRLMSIS gives .* outside its fit") as caught:
        nrlmsis(400.0, f107=60.0, f107a=450.0)  # a temperature of 1e11 K
    assert caught.value.parameters == ("f107", "f107a", "ap")
    assert solar_flux(PHOTOSPHERE_FLUX) == solar_flux(distance_au=SUN_RADIUS_AU) == PHOTOSPHERE_FLUX
    assert solar_flux(299_792_458.0) == 299_792_458.0  # c: the unit pressure of the closed forms
    assert abs(PHOTOSPHERE_FLUX / 6.29e7 - 1) < 1e-3  # sigma T^4 at 5772 K
    PlanetLight.of(planet("earth"), 1361.0, infrared_W_m2=1e5)
    assert azel_to_vector(-360.0, 0.0)[0] == 1.0
    assert ReflectionSettings(rays_per_side=65_536).rays_per_side == resolve_rays_per_side(65_536, 1)
    assert box((1e4, 1.0, 1.0)).vertices.max() == 5e3 and sphere(1e4, 2).n_faces > 0
    refused = [
        (lambda: nrlmsis(400.0, f107=500.5), "f107"),
        (lambda: nrlmsis(400.0, f107a=1e308), "f107a"),
        (lambda: nrlmsis(400.0, ap=400.5), "ap"),
        (lambda: nrlmsis(400.0, longitude_deg=360.5), "longitude_deg"),
        (lambda: solar_flux(1.001e9), "flux_W_m2"),
        (lambda: solar_flux(distance_au=SUN_RADIUS_AU * 0.999), "distance_au"),
        (lambda: PlanetLight.of(planet("earth"), 1361.0, infrared_W_m2=1.001e5), "infrared_W_m2"),
        (lambda: azel_to_vector(360.5, 0.0), "direction"),
        (lambda: ReflectionSettings(rays_per_side=65_537), "rays_per_side"),
        (lambda: resolve_rays_per_side(65_537, 1), "rays_per_side"),
        (lambda: box((1.0, 10_000.5, 1.0)), "size"),
        (lambda: sphere(1e308), "radius"),
    ]
    for call, name in refused:
        with pytest.raises(InputError) as caught:
            call()
        assert name in caught.value.parameters and str(caught.value).startswith(name), caught.value
