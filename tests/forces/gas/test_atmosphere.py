"""The free stream: NRLMSIS pass-through, user-given atmospheres, speed ratios and orbital speeds."""

import math
import warnings
from datetime import datetime, timedelta, timezone

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sunwind.forces.gas.atmosphere import (
    SPECIES_MASS_KG,
    Atmosphere,
    AtmosphereWarning,
    explicit,
    species_name,
)
from sunwind.forces.gas.flow import circular_speed, corotation_speed, corotation_velocity
from sunwind.forces.gas.msis import nrlmsis, parse_time
from sunwind.geometry.errors import InputError

pymsis = pytest.importorskip("pymsis")

AMU = 1.66053906660e-27  # CODATA 2018 [kg]
K_B = 1.380649e-23  # [J/K]
#: Column of each species in pymsis.calculate's output, from pymsis's own Variable enum.
COLUMNS = {
    "N2": pymsis.Variable.N2,
    "O2": pymsis.Variable.O2,
    "O": pymsis.Variable.O,
    "He": pymsis.Variable.HE,
    "H": pymsis.Variable.H,
    "Ar": pymsis.Variable.AR,
    "N": pymsis.Variable.N,
    "O*": pymsis.Variable.ANOMALOUS_O,
}
#: The masses NRLMSIS 2.x uses for its total mass density (msis_constants.F90: CIPM 2007 molar masses
#: of N2, O2, Ar, halved for N and O; 4.0 for He, 1.0 for H) [g/mol].
MSIS_MOLAR_MASS = {
    "N2": 28.0134,
    "O2": 31.9988,
    "O": 31.9988 / 2,
    "He": 4.0,
    "H": 1.0,
    "Ar": 39.948,
    "N": 28.0134 / 2,
    "O*": 31.9988 / 2,
}
AVOGADRO = 6.02214076e23


def quiet_nrlmsis(*args, **kwargs) -> Atmosphere:
    """nrlmsis() with its coverage warnings silenced."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", AtmosphereWarning)
        return nrlmsis(*args, **kwargs)


def pymsis_row(
    altitude,
    latitude=0.0,
    longitude=0.0,
    time="2024-01-01T00:00",
    f107=150.0,
    f107a=150.0,
    ap=4.0,
    version=2.1,
):
    return pymsis.calculate(
        np.datetime64(time), longitude, latitude, altitude, f107, f107a, ap, version=version
    ).reshape(-1)


CASES = [
    dict(altitude=100.0),
    dict(altitude=400.0),
    dict(altitude=400.0, version=2.0),
    dict(altitude=400.0, version=0),
    dict(
        altitude=550.0,
        latitude=51.6,
        longitude=-120.0,
        time="2015-06-21T14:30:00",
        f107=210,
        f107a=180,
        ap=27,
    ),
    dict(altitude=1000.0),
    dict(
        altitude=1500.0,
        latitude=-80.0,
        longitude=300.0,
        time="1989-03-13T06:00:00",
        f107=250,
        f107a=230,
        ap=200,
    ),
    dict(altitude=2000.0),
]


@pytest.mark.parametrize("case", CASES)
def test_nrlmsis_passes_pymsis_output_through_unchanged(case):
    args = dict(case)
    time = args.pop("time", "2024-01-01T00:00:00")
    names = dict(latitude="latitude_deg", longitude="longitude_deg")
    kwargs = {names.get(k, k): v for k, v in args.items() if k != "altitude"}
    atm = quiet_nrlmsis(case["altitude"], time=time + "Z", **kwargs)
    row = pymsis_row(time=time, **args)
    assert atm.temperature_K == float(row[pymsis.Variable.TEMPERATURE])
    assert atm.model_density_kg_m3 == float(row[pymsis.Variable.MASS_DENSITY])
    for species, column in COLUMNS.items():
        expected = float(row[column])
        if math.isnan(expected) or expected == 0:
            assert species not in atm.number_density_m3
        else:
            assert atm.number_density_m3[species] == expected
    assert set(atm.number_density_m3) <= set(SPECIES_MASS_KG)
    assert atm.altitude_km == case["altitude"]
    assert atm.inputs["time_utc"] == time + "Z"


def test_absent_species_are_dropped():
    row = pymsis_row(50.0)
    assert math.isnan(row[pymsis.Variable.O]) and math.isnan(row[pymsis.Variable.H])
    atm = quiet_nrlmsis(50.0)
    assert "O" not in atm.number_density_m3 and "H" not in atm.number_density_m3
    assert set(atm.number_density_m3) == {"N2", "O2", "He", "Ar"}


@pytest.mark.parametrize("altitude", [100.0, 250.0, 400.0, 700.0, 1000.0, 1500.0, 2000.0])
@pytest.mark.parametrize("version", [2.1, 2.0])
def test_msis_total_density_includes_anomalous_oxygen_and_not_no(altitude, version):
    """NRLMSIS 2.x's total is sum n_k m_k over N2, O2, O, He, H, Ar, N and anomalous O with its masses."""
    atm = quiet_nrlmsis(altitude, version=version)
    msis_sum = math.fsum(n * MSIS_MOLAR_MASS[k] / 1e3 / AVOGADRO for k, n in atm.number_density_m3.items())
    assert msis_sum == pytest.approx(atm.model_density_kg_m3, rel=5e-7)  # pymsis gives single precision
    if altitude >= 700:
        without = msis_sum - atm.number_density_m3["O*"] * MSIS_MOLAR_MASS["O*"] / 1e3 / AVOGADRO
        assert without < atm.model_density_kg_m3 * (1 - 1e-3)


@pytest.mark.parametrize("altitude", [100.0, 400.0, 1000.0, 2000.0])
@pytest.mark.parametrize("version", [2.1, 0])
def test_density_differs_from_msis_total_only_by_the_mass_table(altitude, version):
    """sum n_k m_k with standard atomic weights is the MSIS total times a mass-weighted mean mass ratio."""
    atm = quiet_nrlmsis(altitude, version=version)
    ratios = [SPECIES_MASS_KG[k] / (MSIS_MOLAR_MASS[k] / 1e3 / AVOGADRO) for k in atm.number_density_m3]
    msis_sum = math.fsum(n * MSIS_MOLAR_MASS[k] / 1e3 / AVOGADRO for k, n in atm.number_density_m3.items())
    assert min(ratios) - 1e-12 <= atm.density_kg_m3 / msis_sum <= max(ratios) + 1e-12
    assert atm.density_kg_m3 == pytest.approx(atm.model_density_kg_m3, rel=5e-3)
    if altitude <= 400:
        assert atm.density_kg_m3 == pytest.approx(atm.model_density_kg_m3, rel=1e-3)


def test_species_table():
    assert list(SPECIES_MASS_KG) == ["O", "N2", "O2", "He", "H", "N", "Ar", "O*"]
    assert SPECIES_MASS_KG["O"] == pytest.approx(15.999 * AMU, rel=1e-12)
    assert SPECIES_MASS_KG["N2"] == pytest.approx(28.014 * AMU, rel=1e-12)
    assert SPECIES_MASS_KG["He"] == pytest.approx(4.002602 * AMU, rel=1e-12)
    assert SPECIES_MASS_KG["O*"] == SPECIES_MASS_KG["O"]
    for typed, name in [("o2", "O2"), ("HE", "He"), ("ar", "Ar"), ("anomalous_O", "O*"), (" O* ", "O*")]:
        assert species_name(typed) == name
    with pytest.raises(InputError, match=r"unknown species 'CO2'.*O, N2, O2, He, H, N, Ar, O\*"):
        species_name("CO2")


def test_mole_fractions_and_mean_mass():
    atm = quiet_nrlmsis(400.0)
    fractions = atm.mole_fractions
    assert math.fsum(fractions.values()) == pytest.approx(1.0, abs=1e-15)
    total = math.fsum(atm.number_density_m3.values())
    assert atm.density_kg_m3 == pytest.approx(
        math.fsum(n * SPECIES_MASS_KG[k] for k, n in atm.number_density_m3.items()), rel=1e-15
    )
    assert atm.mean_mass_kg == pytest.approx(atm.density_kg_m3 / total, rel=1e-15)
    assert atm.mass_kg == {k: SPECIES_MASS_KG[k] for k in atm.number_density_m3}
    # at 400 km atomic oxygen dominates: mean mass between O and N2
    assert SPECIES_MASS_KG["O"] * 0.9 < atm.mean_mass_kg < SPECIES_MASS_KG["N2"]


def test_explicit_recovers_density_and_fractions():
    atm = explicit(3.1e-12, 950.0, "O:0.7, N2:0.25, he:0.05")
    assert atm.density_kg_m3 == pytest.approx(3.1e-12, rel=1e-14)
    assert atm.temperature_K == 950.0
    assert atm.mole_fractions == pytest.approx({"O": 0.7, "N2": 0.25, "He": 0.05}, rel=1e-14)
    mean = 0.7 * SPECIES_MASS_KG["O"] + 0.25 * SPECIES_MASS_KG["N2"] + 0.05 * SPECIES_MASS_KG["He"]
    assert atm.number_density_m3["O"] == pytest.approx(0.7 * 3.1e-12 / mean, rel=1e-14)
    assert "mole fractions" in atm.source and atm.source.startswith("user:")
    assert explicit(3.1e-12, 950.0, {"he": 0.05, "N2": 0.25, "O": 0.7}) == atm
    assert explicit(3.1e-12, 950.0, "O=0.7;N2=0.25;He=0.05") == atm


def test_explicit_round_trips_an_nrlmsis_atmosphere():
    msis = quiet_nrlmsis(500.0)
    again = explicit(msis.density_kg_m3, msis.temperature_K, msis.mole_fractions)
    assert again.density_kg_m3 == pytest.approx(msis.density_kg_m3, rel=1e-14)
    assert again.number_density_m3 == pytest.approx(msis.number_density_m3, rel=1e-12)
    rebuilt = Atmosphere(msis.number_density_m3, msis.temperature_K, "copy")
    assert rebuilt.density_kg_m3 == msis.density_kg_m3


def test_explicit_normalise_rescales_and_zero_fractions_are_dropped():
    atm = explicit(1e-12, 1000.0, "O:70,N2:30,Ar:0", normalise=True)
    assert atm.mole_fractions == pytest.approx({"O": 0.7, "N2": 0.3}, rel=1e-14)
    assert "Ar" not in atm.number_density_m3
    within = explicit(1e-12, 1000.0, "O:0.7000004,N2:0.3")  # within 1e-6 of 1: accepted, rescaled
    assert math.fsum(within.mole_fractions.values()) == pytest.approx(1.0, abs=1e-15)


def test_speed_ratios():
    atm = explicit(1e-12, 1000.0, "O:0.5,N2:0.3,He:0.1,H:0.1")
    s = atm.speed_ratio(7500.0)
    assert s["O"] == pytest.approx(7500.0 / math.sqrt(2 * K_B * 1000.0 / (15.999 * AMU)), rel=1e-12)
    assert 7500.0 / s["O"] == pytest.approx(1019.5, abs=0.5)  # most probable speed of O at 1000 K
    for k in ("N2", "He", "H"):
        assert s[k] / s["O"] == pytest.approx(math.sqrt(SPECIES_MASS_KG[k] / SPECIES_MASS_KG["O"]), rel=1e-12)
    assert atm.speed_ratio(0.0) == {k: 0.0 for k in atm.number_density_m3}


def test_to_json():
    atm = quiet_nrlmsis(400.0)
    out = atm.to_json()
    assert out["density_kg_m3"] == atm.density_kg_m3
    assert out["temperature_K"] == atm.temperature_K
    assert out["number_density_m3"] == atm.number_density_m3
    assert out["model_density_kg_m3"] == atm.model_density_kg_m3
    assert out["altitude_km"] == 400.0
    assert out["inputs"]["f107_sfu"] == 150.0 and out["inputs"]["ap"] == 4.0
    assert out["source"].startswith(f"NRLMSIS 2.1 (pymsis {pymsis.__version__}): 400 km, lat 0, lon 0")
    assert "F10.7 150, F10.7a 150, Ap 4" in out["source"]
    assert "altitude_km" not in explicit(1e-12, 900.0, "O:1").to_json()


def test_times_in_any_form_give_the_same_atmosphere():
    utc = datetime(2020, 3, 20, 12, 0, tzinfo=timezone.utc)
    same = [
        "2020-03-20T12:00:00Z",
        "2020-03-20T14:00:00+02:00",
        "2020-03-20 12:00",
        datetime(2020, 3, 20, 12, 0),
        utc.astimezone(timezone(timedelta(hours=-5))),
        np.datetime64("2020-03-20T12:00"),
    ]
    for time in same:
        assert parse_time(time) == utc
    assert parse_time("2020-03-20") == datetime(2020, 3, 20, tzinfo=timezone.utc)
    assert nrlmsis(400.0, time="2020-03-20T14:00:00+02:00") == nrlmsis(400.0, time=datetime(2020, 3, 20, 12))


def test_circular_speed():
    r = 6378.137e3 + 400e3
    assert circular_speed(400.0) == pytest.approx(math.sqrt(3.986004418e14 / r), rel=1e-15)
    assert circular_speed(400.0) == pytest.approx(7668.6, abs=1.0)  # e.g. Vallado: 7.6686 km/s at 400 km
    assert circular_speed(0.0) == pytest.approx(7905.4, abs=0.5)  # first cosmic velocity


def test_corotation_reduces_prograde_equatorial_speed_by_omega_r():
    omega_r = 7.292115e-5 * (6378.137e3 + 400e3)
    v = circular_speed(400.0)
    assert corotation_speed(400.0, 0.0, 90.0) == pytest.approx(v - omega_r, rel=1e-14)
    assert corotation_speed(400.0, 0.0, 90.0, 7700.0) == pytest.approx(7700.0 - omega_r, rel=1e-14)
    assert corotation_speed(400.0, 0.0, 270.0, 7700.0) == pytest.approx(7700.0 + omega_r, rel=1e-14)
    assert corotation_speed(400.0, 0.0, 0.0, 7700.0) == pytest.approx(math.hypot(7700.0, omega_r), rel=1e-14)
    assert corotation_speed(400.0, 90.0, 37.0, 7700.0) == pytest.approx(7700.0, rel=1e-12)  # at the pole


@settings(max_examples=50, deadline=None)
@given(
    st.floats(0, 2000),
    st.floats(-90, 90),
    st.floats(-360, 360),
    st.floats(0, 12000),
)
def test_corotation_matches_the_vector_form(altitude, latitude, heading, speed):
    """|v - omega x r| with explicit vectors in an Earth-centred frame, the spacecraft at longitude 0."""
    phi, psi = math.radians(latitude), math.radians(heading)
    r = (6378.137e3 + altitude * 1e3) * np.array([math.cos(phi), 0.0, math.sin(phi)])
    north = np.array([-math.sin(phi), 0.0, math.cos(phi)])
    east = np.array([0.0, 1.0, 0.0])
    v = speed * (math.cos(psi) * north + math.sin(psi) * east)
    expected = np.linalg.norm(v - np.cross([0.0, 0.0, 7.292115e-5], r))
    assert corotation_speed(altitude, latitude, heading, speed) == pytest.approx(
        expected, rel=1e-12, abs=1e-9
    )


def test_corotation_turns_v_rel_by_the_crosswind_a_hand_computation_gives():
    """Body frame x along the inertial velocity, z to the Earth's centre (y = z x x: east when
    heading north). Prograde equatorial: V - omega r along x only. Polar orbit at the equator heading
    north: the air moves east at omega r (~0.494 km/s at 400 km), so v_rel = (V, -omega r, 0)."""
    omega_r = 7.292115e-5 * (6378.137e3 + 400e3)
    v = circular_speed(400.0)
    x, z = [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]
    assert corotation_velocity(400.0, 0.0, 90.0, x) == pytest.approx([v - omega_r, 0.0, 0.0], rel=1e-14)
    polar = corotation_velocity(400.0, 0.0, 0.0, x, z)
    assert 490.0 < omega_r < 500.0
    assert polar == pytest.approx([v, -omega_r, 0.0], rel=1e-14, abs=1e-9)
    southbound = corotation_velocity(400.0, 0.0, 180.0, [0.0, 2.0, 0.0], [-3.0, 0.0, 0.0])  # any length
    assert southbound == pytest.approx([0.0, v, -omega_r], rel=1e-14, abs=1e-9)  # -z: west
    assert corotation_velocity(400.0, 90.0, 0.0, x) == pytest.approx([v, 0.0, 0.0])  # a pole: no wind
    with pytest.raises(InputError, match=r"crosses the track at 494\.3 m/s"):
        corotation_velocity(400.0, 0.0, 0.0, x)
    with pytest.raises(InputError, match="nadir is 45 deg off perpendicular"):
        corotation_velocity(400.0, 0.0, 0.0, x, [1.0, 0.0, 1.0])


@settings(max_examples=50, deadline=None)
@given(
    st.floats(0, 2000),
    st.floats(-90, 90),
    st.floats(-360, 360),
    st.floats(100, 12000),
    st.floats(-math.pi, math.pi),
    st.floats(-1.5, 1.5),
)
def test_corotation_velocity_matches_the_vector_form_in_any_body_frame(
    altitude, latitude, heading, speed, yaw, pitch
):
    """v - omega x r in an Earth-centred frame, written in a body frame turned by (yaw, pitch)."""
    phi, psi = math.radians(latitude), math.radians(heading)
    r_hat = np.array([math.cos(phi), 0.0, math.sin(phi)])
    north = np.array([-math.sin(phi), 0.0, math.cos(phi)])
    east = np.array([0.0, 1.0, 0.0])
    v_hat = math.cos(psi) * north + math.sin(psi) * east
    relative = speed * v_hat - np.cross([0.0, 0.0, 7.292115e-5], (6378.137e3 + altitude * 1e3) * r_hat)
    basis = np.array([v_hat, np.cross(-r_hat, v_hat), -r_hat])  # velocity, y, nadir
    cy, sy, cp, sp = math.cos(yaw), math.sin(yaw), math.cos(pitch), math.sin(pitch)
    turn = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]]) @ np.array([[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]])
    expected = turn @ (basis @ relative)
    got = corotation_velocity(altitude, latitude, heading, turn[:, 0], turn[:, 2], speed)
    assert got == pytest.approx(expected, rel=1e-12, abs=1e-8)


@pytest.mark.parametrize(
    ("kwargs", "names"),
    [
        (dict(altitude_km=-1.0), "altitude_km"),
        (dict(altitude_km=2500.0), "altitude_km"),
        (dict(altitude_km=math.nan), "altitude_km"),
        (dict(altitude_km=400.0, latitude_deg=91.0), "latitude_deg"),
        (dict(altitude_km=400.0, latitude_deg=-90.5), "latitude_deg"),
        (dict(altitude_km=400.0, longitude_deg=math.inf), "longitude_deg"),
        (dict(altitude_km=400.0, time="2024-13-01"), "time"),
        (dict(altitude_km=400.0, time="yesterday"), "time"),
        (dict(altitude_km=400.0, time="1957-12-31"), "time year 1957"),
        (dict(altitude_km=400.0, time=datetime(2101, 1, 1)), "time year 2101"),
        (dict(altitude_km=400.0, f107=-1.0), "f107 "),
        (dict(altitude_km=400.0, f107=math.nan), "f107 "),
        (dict(altitude_km=400.0, f107a=-5.0), "f107a"),
        (dict(altitude_km=400.0, f107a=math.inf), "f107a"),
        (dict(altitude_km=400.0, ap=-1.0), "ap"),
        (dict(altitude_km=400.0, ap=math.inf), "ap"),
        (dict(altitude_km=400.0, version=3), "version"),
    ],
)
def test_nrlmsis_errors_name_the_parameter(kwargs, names):
    """Library errors name the Python parameter (the command line writes its flag instead)."""
    with pytest.raises(InputError) as error:
        nrlmsis(**kwargs)
    assert names in str(error.value)
    assert "\n" not in str(error.value)


def test_date_errors_say_why():
    with pytest.raises(InputError, match="space-age data"):
        nrlmsis(400.0, time="1900-01-01")
    with pytest.raises(InputError, match="ISO 8601"):
        nrlmsis(400.0, time="01/02/2024")


@pytest.mark.parametrize(
    ("args", "kwargs", "pattern"),
    [
        ((1e-12, 1000.0, "O:0.5,CO2:0.5"), {}, r"unknown species 'CO2'; known species are O, N2, O2, He"),
        ((1e-12, 1000.0, "O:-0.1,N2:1.1"), {}, r"composition fraction of O is -0\.1"),
        ((1e-12, 1000.0, "O:nan,N2:1"), {}, r"composition fraction of O is nan"),
        ((1e-12, 1000.0, "O:inf"), {"normalise": True}, r"composition fraction of O is inf"),
        ((1e-12, 1000.0, "O:0.6,N2:0.3"), {}, r"sum to 0\.9, not 1.*set normalise"),
        ((1e-12, 1000.0, "O:0.7,N2:0.3000011"), {}, r"sum to 1\.0000011.*set normalise"),
        ((1e-12, 1000.0, "O:0,N2:0"), {"normalise": True}, r"composition fractions sum to 0"),
        ((1e-12, 1000.0, "O0.7,N2:0.3"), {}, r"composition entry 'O0\.7'"),
        ((1e-12, 1000.0, "O:lots"), {}, r"composition fraction of O 'lots' is not a number"),
        ((1e-12, 1000.0, "O:0.5,o:0.5"), {}, r"composition gives O twice"),
        ((1e-12, 1000.0, " , "), {}, r"composition is empty"),
        ((0.0, 1000.0, "O:1"), {}, r"density_kg_m3 0\.0 kg/m\^3 is not positive"),
        ((-1e-12, 1000.0, "O:1"), {}, r"density_kg_m3"),
        ((math.nan, 1000.0, "O:1"), {}, r"density_kg_m3 nan kg/m\^3 is not a finite number"),
        ((1e-12, 0.0, "O:1"), {}, r"temperature_K 0\.0 K is below 1"),
        ((1e-12, 1e300, "O:1"), {}, r"temperature_K 1e\+300 K is above 100000"),
        ((1e-12, math.inf, "O:1"), {}, r"temperature_K inf K is not a finite number"),
    ],
)
def test_explicit_errors(args, kwargs, pattern):
    with pytest.raises(InputError, match=pattern):
        explicit(*args, **kwargs)


def test_flow_errors_name_the_parameter():
    with pytest.raises(InputError, match="altitude_km"):
        circular_speed(-10.0)
    with pytest.raises(InputError, match="latitude_deg"):
        corotation_speed(400.0, 95.0, 90.0)
    with pytest.raises(InputError, match="heading_deg"):
        corotation_speed(400.0, 0.0, math.nan)
    with pytest.raises(InputError, match="inertial speed"):
        corotation_speed(400.0, 0.0, 90.0, -1.0)
    with pytest.raises(InputError, match="speed"):
        explicit(1e-12, 1000.0, "O:1").speed_ratio(math.inf)


def test_atmosphere_checks_its_fields():
    with pytest.raises(InputError, match=r"number density of O is 0\.0"):
        Atmosphere({"O": 0.0}, 1000.0, "test")
    with pytest.raises(InputError, match="species O is given twice"):
        Atmosphere({"O": 1.0, "o": 2.0}, 1000.0, "test")
    with pytest.raises(InputError, match=r"temperature_K -1\.0 K is below 1"):
        Atmosphere({"O": 1.0}, -1.0, "test")
    with pytest.raises(InputError, match="no species"):
        Atmosphere({}, 1000.0, "test")


def test_warning_above_the_fitted_altitude():
    with pytest.warns(AtmosphereWarning, match=r"1500 km is above 1000 km.*extrapolation"):
        nrlmsis(1500.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        nrlmsis(1000.0)
        nrlmsis(400.0)
        nrlmsis(150.0)


def test_warning_below_the_free_molecular_limit():
    with pytest.warns(AtmosphereWarning, match=r"120 km is below 150 km.*Knudsen number"):
        atm = nrlmsis(120.0)
    assert 0.5 < atm.mean_free_path_m < 20.0  # USSA 1976 gives about 3 m at 120 km
