"""Checks of the closed-form SRP references against brute-force surface quadrature and known limits.

The brute-force route is written here from scratch: each smooth surface is parametrised, its
normals are the cross product of the parametric derivatives (complex-step, exact to rounding)
turned outward with an interior point, the terminator is located by root finding, and
METHOD.md's per-element law is summed at Gauss-Legendre nodes split at the terminator. None of
the closed forms' algebra is reused.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.spatial import ConvexHull

from sunwind.validation.analytic_srp import cone_srp, cylinder_srp, plate_srp, sphere_srp
from sunwind.validation.analytic_srp_law import SPEED_OF_LIGHT_M_S, ForceTorque, Optics, sun_vector_from_alpha

FLUX = 1361.0
PRESSURE = FLUX / SPEED_OF_LIGHT_M_S
REF = np.array([0.13, -0.21, 0.34])
QUADRATURE_TOL = 1e-9  # of P A_ref (force) and P A_ref L_ref (torque); the quadrature is spectral
EXACT_TOL = 1e-12  # same scales, for identities that hold to rounding

MATERIALS = {
    "absorbing": Optics(0.0, 0.0, 0.0),
    "specular": Optics(1.0, 1.0, 0.0),
    "diffuse": Optics(1.0, 0.0, 0.0),
    "mixed": Optics(0.6, 0.3, 0.1),
    "transmissive": Optics(0.2, 0.5, 0.5),
}
BACK = Optics(0.4, 0.8, 0.0)

_ALPHAS_DEG = [0, 10, 20, 30, 45, 60, 70, 89, 90, 91, 110, 120, 135, 150, 160, 170, 180]
_OFF_PLANE = np.random.default_rng(20240611).normal(size=(6, 3))
SUN_VECTORS = [sun_vector_from_alpha(a) for a in _ALPHAS_DEG] + list(
    _OFF_PLANE / np.linalg.norm(_OFF_PLANE, axis=1, keepdims=True)
)
SUN_IDS = [f"alpha{a}" for a in _ALPHAS_DEG] + [f"offplane{k}" for k in range(len(_OFF_PLANE))]

Surface = Callable[[np.ndarray, np.ndarray], np.ndarray]  # r(p, q): (n,), (n,) -> (n, 3)


class Piece(NamedTuple):
    """A smooth parametric surface piece: r(p, q) on a rectangle, and a point behind it."""

    surface: Surface
    p_range: tuple[float, float]
    q_range: tuple[float, float]
    interior: np.ndarray  # (3,) outward normals point away from it


# ------------------------------------------------------------------------ brute-force quadrature


def _xyz(x, y, z) -> np.ndarray:
    """Stack broadcast coordinates into (n, 3) rows."""
    return np.stack(np.broadcast_arrays(x, y, z), axis=-1)


def _geometry(piece: Piece, p: np.ndarray, q: np.ndarray):
    """Points (n, 3), outward unit normals (n, 3) and area Jacobians (n,) at (p, q)."""
    step = 1e-30
    points = piece.surface(p.astype(complex), q.astype(complex)).real
    d_p = piece.surface(p + 1j * step, q.astype(complex)).imag / step
    d_q = piece.surface(p.astype(complex), q + 1j * step).imag / step
    cross = np.cross(d_p, d_q)
    jacobian = np.linalg.norm(cross, axis=1)
    normals = cross / np.where(jacobian > 0.0, jacobian, 1.0)[:, None]
    outward = np.sign(np.einsum("ij,ij->i", normals, points - piece.interior))
    return points, normals * outward[:, None], jacobian


def _split(func: Callable[[np.ndarray], np.ndarray], lo: float, hi: float) -> list[float]:
    """[lo, ..., hi] with every sign change of the vectorised ``func`` between, by brentq."""
    grid = np.linspace(lo, hi, 1000)
    values = func(grid)
    changes = np.nonzero(values[:-1] * values[1:] < 0.0)[0]
    return [lo, *(_root(func, grid[k], grid[k + 1]) for k in changes), hi]


def _root(func: Callable[[np.ndarray], np.ndarray], a: float, b: float) -> float:
    """Zero of ``func`` in [a, b]; an end where func is ~0 (no clean sign change) is the zero."""

    def scalar(x: float) -> float:
        return float(func(np.array([x]))[0])

    f_a, f_b = scalar(a), scalar(b)
    if f_a * f_b >= 0.0:
        return a if abs(f_a) <= abs(f_b) else b
    return brentq(scalar, a, b, xtol=1e-15)


def _gauss(breaks: list[float], order: int) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss-Legendre nodes and weights over consecutive breakpoints."""
    x, w = np.polynomial.legendre.leggauss(order)
    lo, hi = np.array(breaks[:-1])[:, None], np.array(breaks[1:])[:, None]
    return (0.5 * (hi + lo) + 0.5 * (hi - lo) * x).ravel(), (0.5 * (hi - lo) * w).ravel()


def _nodes(piece: Piece, u: np.ndarray, order: int = 32):
    """Quadrature nodes of a piece whose lit set is a rectangle in (p, q), split at n . u = 0."""
    # probe lines off the middle: the sphere's equator about u is its terminator
    p_mid, q_mid = (lo + 0.3721 * (hi - lo) for lo, hi in (piece.p_range, piece.q_range))

    def cos_p(p: np.ndarray) -> np.ndarray:
        return _geometry(piece, p, np.full_like(p, q_mid))[1] @ u

    def cos_q(q: np.ndarray) -> np.ndarray:
        return _geometry(piece, np.full_like(q, p_mid), q)[1] @ u

    p_nodes, p_weights = _gauss(_split(cos_p, *piece.p_range), order)
    q_nodes, q_weights = _gauss(_split(cos_q, *piece.q_range), order)
    p, q = (grid.ravel() for grid in np.meshgrid(p_nodes, q_nodes, indexing="ij"))
    points, normals, jacobian = _geometry(piece, p, q)
    return points, normals, np.outer(p_weights, q_weights).ravel() * jacobian


def _brute_force(nodes: list[tuple[tuple, Optics]], u: np.ndarray) -> ForceTorque:
    """Sum METHOD.md's per-element force, and its torque about REF, over the lit nodes."""
    force, torque = np.zeros(3), np.zeros(3)
    for (points, normals, areas), (rho, beta, sigma) in nodes:
        c = normals @ u
        along_normal = 2.0 * rho * beta * c + (2.0 / 3.0) * rho * (1.0 - beta)
        bracket = (1.0 - sigma - rho * beta) * u + along_normal[:, None] * normals
        d_force = -PRESSURE * ((areas * c * (c > 0.0))[:, None] * bracket)
        force += d_force.sum(axis=0)
        torque += np.cross(points - REF, d_force).sum(axis=0)
    return ForceTorque(force, torque)


# ------------------------------------------------------------------ the bodies, parametrised


def _rectangle(size_x: float, size_y: float, back: float) -> Piece:
    """Rectangle in z = 0; ``back`` = -1 for the +z side, +1 for the -z side."""
    return Piece(
        lambda x, y: _xyz(x, y, 0.0 * x),
        (-size_x / 2, size_x / 2),
        (-size_y / 2, size_y / 2),
        np.array([0.0, 0.0, back]),
    )


def _disc(radius: float, z: float, back: float) -> Piece:
    """Disc in the plane z, facing away from (0, 0, z + back)."""
    return Piece(
        lambda phi, r: _xyz(r * np.cos(phi), r * np.sin(phi), z + 0.0 * r),
        (0.0, 2.0 * np.pi),
        (0.0, radius),
        np.array([0.0, 0.0, z + back]),
    )


def _basis_normal_to(u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors (3,) completing u to a right-handed orthonormal basis."""
    e_a = np.cross(u, [1.0, 0.0, 0.0] if abs(u[0]) < 0.9 else [0.0, 1.0, 0.0])
    e_a /= np.linalg.norm(e_a)
    return e_a, np.cross(u, e_a)


def _sphere_piece(radius: float, u: np.ndarray) -> Piece:
    """Sphere centred at the origin, polar angle q measured from u (the terminator is q = pi/2)."""
    e_a, e_b = _basis_normal_to(u)

    def surface(phi, theta):
        return radius * (
            (np.sin(theta) * np.cos(phi))[:, None] * e_a
            + (np.sin(theta) * np.sin(phi))[:, None] * e_b
            + np.cos(theta)[:, None] * u
        )

    return Piece(surface, (0.0, 2.0 * np.pi), (0.0, np.pi), np.zeros(3))


def _cylinder_side(radius: float, length: float) -> Piece:
    """Outer lateral surface of the cylinder on the z axis, z in [-L/2, L/2]."""
    return Piece(
        lambda phi, z: _xyz(radius * np.cos(phi), radius * np.sin(phi), z),
        (0.0, 2.0 * np.pi),
        (-length / 2, length / 2),
        np.zeros(3),
    )


def _cone_side(radius: float, height: float) -> Piece:
    """Lateral surface from the base rim (t = 1) to the apex (0, 0, height) (t = 0)."""
    return Piece(
        lambda phi, t: _xyz(t * radius * np.cos(phi), t * radius * np.sin(phi), height * (1 - t)),
        (0.0, 2.0 * np.pi),
        (0.0, 1.0),
        np.array([0.0, 0.0, height / 4]),
    )


class Body(NamedTuple):
    """A closed form, its brute-force surface pieces, and the scales of its tolerance."""

    closed_form: Callable[[np.ndarray, Optics], ForceTorque]
    pieces: Callable[[np.ndarray], list[tuple[Piece, Optics | None]]]  # None: the body's optics
    area: float  # A_ref [m^2]
    length: float  # L_ref [m]


_R, _L, _CONE_R = 0.5, 1.7, 0.9
_H70, _H30 = _CONE_R / np.tan(np.radians(70.0)), _CONE_R / np.tan(np.radians(30.0))

BODIES = {
    "plate_one_sided": Body(
        lambda u, m: plate_srp(1.2, 0.7, u, m, flux_W_m2=FLUX, ref_point_m=REF),
        lambda u: [(_rectangle(1.2, 0.7, -1.0), None)],
        0.84,
        1.4,
    ),
    "plate_two_sided": Body(
        lambda u, m: plate_srp(
            1.2, 0.7, u, m, one_sided=False, back_optics=BACK, flux_W_m2=FLUX, ref_point_m=REF
        ),
        lambda u: [(_rectangle(1.2, 0.7, -1.0), None), (_rectangle(1.2, 0.7, 1.0), BACK)],
        0.84,
        1.4,
    ),
    "sphere": Body(
        lambda u, m: sphere_srp(0.8, u, m, flux_W_m2=FLUX, ref_point_m=REF),
        lambda u: [(_sphere_piece(0.8, u), None)],
        np.pi * 0.64,
        1.6,
    ),
    "cylinder_caps": Body(
        lambda u, m: cylinder_srp(_R, _L, u, m, flux_W_m2=FLUX, ref_point_m=REF),
        lambda u: [
            (_cylinder_side(_R, _L), None),
            (_disc(_R, _L / 2, -1.0), None),
            (_disc(_R, -_L / 2, 1.0), None),
        ],
        2 * _R * _L,
        _L,
    ),
    "cylinder_open": Body(
        lambda u, m: cylinder_srp(_R, _L, u, m, caps=False, flux_W_m2=FLUX, ref_point_m=REF),
        lambda u: [(_cylinder_side(_R, _L), None)],
        2 * _R * _L,
        _L,
    ),
    "cone70_base": Body(
        lambda u, m: cone_srp(_CONE_R, u, m, flux_W_m2=FLUX, ref_point_m=REF),
        lambda u: [(_cone_side(_CONE_R, _H70), None), (_disc(_CONE_R, 0.0, 1.0), None)],
        np.pi * _CONE_R**2,
        2 * _CONE_R,
    ),
    "cone70_open": Body(
        lambda u, m: cone_srp(_CONE_R, u, m, base=False, flux_W_m2=FLUX, ref_point_m=REF),
        lambda u: [(_cone_side(_CONE_R, _H70), None)],
        np.pi * _CONE_R**2,
        2 * _CONE_R,
    ),
    "cone30_base": Body(
        lambda u, m: cone_srp(_CONE_R, u, m, half_angle_deg=30.0, flux_W_m2=FLUX, ref_point_m=REF),
        lambda u: [(_cone_side(_CONE_R, _H30), None), (_disc(_CONE_R, 0.0, 1.0), None)],
        _CONE_R * _H30,
        _H30,
    ),
}


def _assert_close(got: ForceTorque, want: ForceTorque, area: float, length: float, tol: float):
    """|dF| <= tol P A_ref and |dM| <= tol P A_ref L_ref."""
    force_err = np.linalg.norm(got.force_N - want.force_N) / (PRESSURE * area)
    torque_err = np.linalg.norm(got.torque_Nm - want.torque_Nm) / (PRESSURE * area * length)
    assert force_err <= tol, f"force error {force_err:.2e} of P A_ref"
    assert torque_err <= tol, f"torque error {torque_err:.2e} of P A_ref L_ref"


# ------------------------------------------------------------------------ closed form vs brute


@pytest.mark.parametrize("u", SUN_VECTORS, ids=SUN_IDS)
@pytest.mark.parametrize("name", list(BODIES))
def test_closed_form_matches_surface_quadrature(name: str, u: np.ndarray) -> None:
    body = BODIES[name]
    nodes = [(_nodes(piece, u), own) for piece, own in body.pieces(u)]
    for material_name, optics in MATERIALS.items():
        got = body.closed_form(u, optics)
        want = _brute_force([(n, optics if own is None else own) for n, own in nodes], u)
        try:
            _assert_close(got, want, body.area, body.length, QUADRATURE_TOL)
        except AssertionError as error:
            raise AssertionError(f"{material_name}: {error}") from None


# ---------------------------------------------------------------------------- limits


def _cylinder_silhouette(radius: float, length: float, u: np.ndarray) -> float:
    """Projected area along u of a closed cylinder [m^2].

    The silhouette is a 2R x L |u_xy| rectangle and two half ellipses of semi-axes R, R |u_z|.
    """
    return 2.0 * radius * length * np.hypot(u[0], u[1]) + np.pi * radius**2 * abs(u[2])


def _cone_silhouette(radius: float, height: float, u: np.ndarray) -> float:
    """Projected area along u of a closed cone: the hull of the base ellipse and the apex [m^2].

    In the plane normal to u the base is an ellipse of semi-axes R and R |u_z|, the apex lies on
    its minor axis at h |u_xy| from the centre. Scaled to the unit circle the apex is at
    d = h |u_xy| / (R |u_z|); if d > 1 the hull adds two tangents meeting the circle at
    +-beta = arccos(1/d) from that axis, and its area is pi - beta + tan(beta).
    """
    minor, apex = radius * abs(u[2]), height * np.hypot(u[0], u[1])
    if apex <= minor:
        return np.pi * radius * minor
    beta = np.arccos(minor / apex)
    return radius * minor * (np.pi - beta) + radius * np.sqrt(apex**2 - minor**2)


def _hull_area(points: np.ndarray, u: np.ndarray) -> float:
    """Area of the convex hull of points projected on the plane normal to u [m^2]."""
    e_a, e_b = _basis_normal_to(u)
    return ConvexHull(np.column_stack([points @ e_a, points @ e_b])).volume


def _rim(radius: float, z: float, n: int = 100_000) -> np.ndarray:
    """n points (n, 3) evenly round the circle of the given radius in the plane z [m]."""
    phi = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    return _xyz(radius * np.cos(phi), radius * np.sin(phi), np.full(n, z))


@pytest.mark.parametrize("u", SUN_VECTORS[::3], ids=SUN_IDS[::3])
def test_silhouette_areas_match_the_hull_of_sampled_rims(u: np.ndarray) -> None:
    """The silhouette formulas used below, against the hull of 1e5 points per rim."""
    cylinder = _hull_area(np.vstack([_rim(_R, _L / 2), _rim(_R, -_L / 2)]), u)
    cone = _hull_area(np.vstack([_rim(_CONE_R, 0.0), [[0.0, 0.0, _H70]]]), u)
    # an inscribed polygon of n sides misses (2 pi^2 / 3) / n^2 of an ellipse: ~7e-10
    assert cylinder == pytest.approx(_cylinder_silhouette(_R, _L, u), rel=1e-8)
    assert cone == pytest.approx(_cone_silhouette(_CONE_R, _H70, u), rel=1e-8)


@pytest.mark.parametrize("u", SUN_VECTORS, ids=SUN_IDS)
def test_absorbing_convex_bodies_feel_pressure_times_projected_area(u: np.ndarray) -> None:
    absorbing = MATERIALS["absorbing"]
    cases = [
        (sphere_srp(0.8, u, absorbing), np.pi * 0.64),
        (plate_srp(1.2, 0.7, u, absorbing, one_sided=False), 0.84 * abs(u[2])),
        (cylinder_srp(_R, _L, u, absorbing), _cylinder_silhouette(_R, _L, u)),
        (cone_srp(_CONE_R, u, absorbing), _cone_silhouette(_CONE_R, _H70, u)),
        (
            cone_srp(_CONE_R, u, absorbing, half_angle_deg=30.0),
            _cone_silhouette(_CONE_R, _H30, u),
        ),
    ]
    for load, area in cases:
        np.testing.assert_allclose(load.force_N, -PRESSURE * area * u, atol=EXACT_TOL * PRESSURE)


@pytest.mark.parametrize("u", SUN_VECTORS, ids=SUN_IDS)
def test_specular_sphere_feels_the_same_as_absorbing_sphere(u: np.ndarray) -> None:
    specular = sphere_srp(0.8, u, MATERIALS["specular"], ref_point_m=REF)
    absorbing = sphere_srp(0.8, u, MATERIALS["absorbing"], ref_point_m=REF)
    _assert_close(specular, absorbing, np.pi * 0.64, 1.6, EXACT_TOL)


@pytest.mark.parametrize("rho", [1.0, 0.5, 0.0])
def test_diffuse_sphere_force_is_one_plus_four_ninths_rho(rho: float) -> None:
    u = SUN_VECTORS[-1]
    load = sphere_srp(0.8, u, (rho, 0.0, 0.0))
    want = -(1.0 + 4.0 * rho / 9.0) * PRESSURE * np.pi * 0.64 * u
    np.testing.assert_allclose(load.force_N, want, rtol=0.0, atol=EXACT_TOL * PRESSURE)
    np.testing.assert_allclose(load.torque_Nm, 0.0, atol=EXACT_TOL * PRESSURE)


@pytest.mark.parametrize("u", SUN_VECTORS, ids=SUN_IDS)
def test_specular_plate_has_no_tangential_force(u: np.ndarray) -> None:
    load = plate_srp(1.2, 0.7, u, MATERIALS["specular"], one_sided=False)
    np.testing.assert_allclose(load.force_N[:2], 0.0, atol=EXACT_TOL * PRESSURE)
    # normal force is 2 P A cos^2(theta), pushing away from the Sun
    assert load.force_N[2] == pytest.approx(-2.0 * PRESSURE * 0.84 * u[2] * abs(u[2]), rel=1e-12)


def _lift(load: ForceTorque, u: np.ndarray) -> np.ndarray:
    """Force component (3,) normal to the Sun line [N]."""
    return load.force_N - (load.force_N @ u) * u


@pytest.mark.parametrize("rho", [1.0, 0.4])
@pytest.mark.parametrize("u", SUN_VECTORS, ids=SUN_IDS)
def test_lambertian_cylinder_of_length_equal_diameter_has_no_lift(u: np.ndarray, rho: float):
    load = cylinder_srp(0.5, 1.0, u, (rho, 0.0, 0.0))
    np.testing.assert_allclose(_lift(load, u), 0.0, atol=EXACT_TOL * PRESSURE)


@pytest.mark.parametrize("length_m", [0.5, 1.5, 3.0])
def test_lambertian_cylinder_of_other_length_has_lift(length_m: float) -> None:
    u = sun_vector_from_alpha(45.0)
    lift = _lift(cylinder_srp(0.5, length_m, u, MATERIALS["diffuse"]), u)
    # lift = -(2/3) P (pi/2) R sin(a) cos(a) (L - 2R) (cos(a), 0, -sin(a)), with R = 0.5
    want = -(2.0 / 3.0) * PRESSURE * (np.pi / 2) * 0.5 * 0.5 * (length_m - 1.0)
    assert np.linalg.norm(lift) > 0.01 * PRESSURE
    np.testing.assert_allclose(lift, want * np.array([0.5**0.5, 0.0, -(0.5**0.5)]), rtol=1e-12)


@pytest.mark.parametrize("u", SUN_VECTORS, ids=SUN_IDS)
def test_cylinder_caps_cancel_the_lateral_torque_about_the_centre(u: np.ndarray) -> None:
    for optics in MATERIALS.values():
        closed = cylinder_srp(_R, _L, u, optics)
        np.testing.assert_allclose(closed.torque_Nm, 0.0, atol=EXACT_TOL * PRESSURE * _L)
    lateral = cylinder_srp(_R, _L, u, MATERIALS["absorbing"], caps=False)
    s, u_z = np.hypot(u[0], u[1]), u[2]
    want = (np.pi / 2) * PRESSURE * _R**2 * _L * s * u_z  # along e_z x (u_xy / s)
    assert np.linalg.norm(lateral.torque_Nm) == pytest.approx(abs(want), rel=1e-12, abs=1e-22)
    assert abs(lateral.torque_Nm[2]) <= EXACT_TOL * abs(want)


AXISYMMETRIC = [name for name in BODIES if not name.startswith("plate")]


@pytest.mark.parametrize("name", AXISYMMETRIC)
@pytest.mark.parametrize("u", SUN_VECTORS, ids=SUN_IDS)
def test_rotating_sun_about_the_axis_rotates_the_loads(name: str, u: np.ndarray) -> None:
    chi = np.radians(37.0)
    rotation = np.array([[np.cos(chi), -np.sin(chi), 0.0], [np.sin(chi), np.cos(chi), 0.0], [0.0, 0.0, 1.0]])
    body = BODIES[name]

    def about_origin(load: ForceTorque) -> ForceTorque:  # the closed forms' torque is about REF
        return ForceTorque(load.force_N, load.torque_Nm + np.cross(REF, load.force_N))

    base = about_origin(body.closed_form(u, MATERIALS["mixed"]))
    turned = about_origin(body.closed_form(rotation @ u, MATERIALS["mixed"]))
    want = ForceTorque(rotation @ base.force_N, rotation @ base.torque_Nm)
    _assert_close(turned, want, body.area, body.length, EXACT_TOL)


def test_cone_side_is_fully_lit_up_to_the_half_angle_and_dark_beyond_its_supplement() -> None:
    """70 deg cone: side fully lit for alpha <= 70, partly lit between, dark for alpha >= 110."""
    absorbing = MATERIALS["absorbing"]

    def side(alpha_deg: float, optics: Optics = absorbing) -> ForceTorque:
        return cone_srp(_CONE_R, sun_vector_from_alpha(alpha_deg), optics, base=False)

    for alpha in (0.0, 30.0, 70.0):  # fully lit: its shadow is the base's, pi R^2 cos(alpha)
        want = -PRESSURE * np.pi * _CONE_R**2 * np.cos(np.radians(alpha)) * sun_vector_from_alpha(alpha)
        np.testing.assert_allclose(side(alpha).force_N, want, atol=EXACT_TOL * PRESSURE)
    for alpha in (110.0, 135.0, 180.0):  # at 110 exactly, rounding may leave a ~1e-30 N sliver
        np.testing.assert_allclose(side(alpha).force_N, 0.0, atol=EXACT_TOL * PRESSURE)
    assert np.linalg.norm(side(109.99).force_N) > 0.0
    for boundary in (70.0, 110.0):
        below, above = (side(boundary + step, MATERIALS["mixed"]) for step in (-1e-7, 1e-7))
        _assert_close(below, above, np.pi * _CONE_R**2, _CONE_R, 1e-8)


# ---------------------------------------------------------------------- input checks


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: sphere_srp(1.0, [0.0, 0.0, 2.0], (0.0, 0.0, 0.0)), "unit"),
        (lambda: plate_srp(1.0, 1.0, [0.0, 0.0, 1.0], (0, 0, 0), back_optics=(0, 0, 0)), "one_sided"),
        (lambda: sphere_srp(1.0, [0.0, 0.0, 1.0], (0.7, 0.0, 0.5)), "rho \\+ sigma"),
        (lambda: sphere_srp(1.0, [0.0, 0.0, 1.0], (1.2, 0.0, 0.0)), "\\[0, 1\\]"),
        (lambda: cone_srp(1.0, [0.0, 0.0, 1.0], (0, 0, 0), half_angle_deg=90.0), "half_angle"),
    ],
)
def test_bad_input_is_refused_with_the_reason(call, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        call()
