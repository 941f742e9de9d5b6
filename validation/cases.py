"""The SRP validation cases, one table read by the runner, the tests and the validation page.

Each case is a meshed body with one material, a closed-form reference from
:mod:`sunwind.validation.analytic_srp`, the Sun directions it is checked at, and a tolerance with its reason.
Errors are measured on vectors against a physical scale, so components near zero do not inflate them:
``|F - F_ref| / (P A_ref)`` for force and ``|M - M_ref| / (P A_ref L_ref)`` for torque.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.materials import parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import Spacecraft, build_spacecraft
from sunwind.meshes import primitives
from sunwind.meshes.assembly import label, rotation_matrix, transform
from sunwind.validation.analytic_shadow import PlatePair, shadowed_plates_srp
from sunwind.validation.analytic_srp import cone_srp, cylinder_srp, plate_srp, sphere_srp
from sunwind.validation.analytic_srp_law import ForceTorque, Optics

#: Surface finishes every body is checked with.
OPTICS: dict[str, Optics] = {
    "absorbing": Optics(0.0, 0.0, 0.0),
    "specular": Optics(1.0, 1.0, 0.0),
    "diffuse": Optics(1.0, 0.0, 0.0),
    "mixed": Optics(0.6, 0.3, 0.1),
}
#: Back of the two-sided plate: a solar-cell-like finish, different from every front.
BACK_OPTICS = Optics(0.2, 0.8, 0.0)
#: Angles between the body axis (+z) and the Sun [deg].
ALPHAS_DEG = tuple(range(0, 181, 15))
#: Azimuth of the Sun about the axis [deg], off every symmetry plane of the meshes.
AZIMUTH_DEG = 17.0
#: Tolerance of the issue: 0.1 % of the force scale on the default primitive resolution.
REL_TOL = 1e-3
_REASON = (
    "faceting: default resolutions reproduce area and projected area to < 1e-4, so the force "
    "law on flat facets lands within 1e-3 of the smooth body"
)

CYLINDER = {"radius": 1.0, "length": 3.0}  # L = 1.5 D: a Lambertian cylinder has lift here
CONE = {"radius": 1.0, "half_angle_deg": 70.0}
PLATE = {"size_x": 2.0, "size_y": 1.0}


def sun_vector(alpha_deg: float, azimuth_deg: float = AZIMUTH_DEG) -> NDArray[np.float64]:
    """Make the unit Sun vector at an angle from +z and an azimuth about it, body frame.

    Parameters
    ----------
    alpha_deg : float
        Angle between +z (the body axis) and the Sun [deg].
    azimuth_deg : float
        Azimuth of the Sun about +z, from +x toward +y [deg]; default :data:`AZIMUTH_DEG`.

    Returns
    -------
    (3,) float64
        The unit vector toward the Sun.

    Examples
    --------
    >>> np.round(sun_vector(90.0, 0.0), 12) + 0.0
    array([1., 0., 0.])
    """
    a, p = np.radians(alpha_deg), np.radians(azimuth_deg)
    return np.array([np.sin(a) * np.cos(p), np.sin(a) * np.sin(p), np.cos(a)])


def _optics_table(optics: Optics) -> dict[str, float]:
    return {"reflectivity": optics.rho, "specular_fraction": optics.beta, "transmissivity": optics.sigma}


@dataclass(frozen=True, eq=False)
class SrpCase:
    """A meshed body checked against its closed form over Sun directions.

    Attributes
    ----------
    name : str
        ``body/finish``.
    mesh : callable
        ``mesh(refinement)`` builds the body; refinement 1 is the default resolution, 0.5 halves it.
    parts : mapping
        The materials file's ``[parts]`` table, naming materials "front" and "back".
    optics, back : Optics
        Finish of every lit surface, and of a two-sided plate's back.
    reference : callable
        ``reference(sun_vector)`` -> ForceTorque, torque about the origin, at 1361 W/m^2.
    reference_area_m2, reference_length_m : float
        Scales of the error measures [m^2, m].
    alphas_deg : tuple of float
        Angles between the axis and the Sun [deg].
    rel_tol : float
        Largest error allowed [-].
    reason : str
        Why ``rel_tol`` is what it is.

    Examples
    --------
    >>> case = next(c for c in SRP_CASES if c.name == "plate one-sided/specular")
    >>> case.spacecraft()
    <Spacecraft '<plate>': 2048 facets, 2048 sides, 1 parts, 1 materials>
    >>> print(f"{case.reference(sun_vector(0.0)).force_N[2]:.4e}")
    -1.8159e-05
    """

    name: str
    mesh: Callable[[float], MeshData]
    parts: Mapping[str, object]
    optics: Optics
    reference: Callable[[NDArray[np.float64]], ForceTorque]
    reference_area_m2: float
    reference_length_m: float
    back: Optics = BACK_OPTICS
    alphas_deg: tuple[float, ...] = ALPHAS_DEG
    rel_tol: float = REL_TOL
    reason: str = _REASON

    def spacecraft(self, refinement: float = 1.0) -> Spacecraft:
        """The meshed body with its materials; kept for reuse."""
        return _spacecraft(self, refinement)

    def sun_vectors(self) -> list[tuple[float, NDArray[np.float64]]]:
        """``(alpha, u)`` for every checked direction."""
        return [(alpha, sun_vector(alpha)) for alpha in self.alphas_deg]


@lru_cache(maxsize=8)
def _spacecraft(case: SrpCase, refinement: float) -> Spacecraft:
    document = {
        "materials": {"front": _optics_table(case.optics), "back": _optics_table(case.back)},
        "parts": dict(case.parts),
    }
    return build_spacecraft(case.mesh(refinement), parse_materials(document, source=case.name))


def _scaled(value: int, refinement: float, minimum: int = 3) -> int:
    return max(minimum, round(value * refinement))


def _bodies() -> list[tuple[str, Callable, Mapping, Callable, float, float]]:
    """(name, mesh(refinement), parts, reference(u, optics, back), A_ref, L_ref) for every body."""
    r, length = CYLINDER["radius"], CYLINDER["length"]
    rc = CONE["radius"]
    seg_cyl, seg_cone, sub = (
        primitives.CYLINDER_SEGMENTS,
        primitives.CONE_SEGMENTS,
        primitives.SPHERE_SUBDIVISIONS,
    )
    return [
        (
            "plate one-sided",
            lambda f: primitives.plate(**PLATE),
            {"plate": {"front": "front"}},
            lambda u, o, b: plate_srp(PLATE["size_x"], PLATE["size_y"], u, o),
            2.0,
            1.0,
        ),
        (
            "plate two-sided",
            lambda f: primitives.plate(**PLATE),
            {"plate": {"front": "front", "back": "back"}},
            lambda u, o, b: plate_srp(PLATE["size_x"], PLATE["size_y"], u, o, one_sided=False, back_optics=b),
            2.0,
            1.0,
        ),
        (
            "sphere",
            lambda f: primitives.sphere(1.0, _scaled(sub, f)),
            {"*": "front"},
            lambda u, o, b: sphere_srp(1.0, u, o),
            np.pi,
            1.0,
        ),
        (
            "cylinder with caps",
            lambda f: primitives.cylinder(r, length, _scaled(seg_cyl, f)),
            {"*": "front"},
            lambda u, o, b: cylinder_srp(r, length, u, o, caps=True),
            2 * r * length,
            length,
        ),
        (
            "cylinder without caps",
            lambda f: primitives.cylinder(r, length, _scaled(seg_cyl, f), caps=False),
            {"*": {"front": "front"}},
            lambda u, o, b: cylinder_srp(r, length, u, o, caps=False),
            2 * r * length,
            length,
        ),
        (
            "cone with base",
            lambda f: primitives.cone(segments=_scaled(seg_cone, f), **CONE),
            {"*": "front"},
            lambda u, o, b: cone_srp(rc, u, o, half_angle_deg=CONE["half_angle_deg"]),
            np.pi * rc**2,
            rc,
        ),
        (
            "cone without base",
            lambda f: primitives.cone(segments=_scaled(seg_cone, f), base=False, **CONE),
            {"*": {"front": "front"}},
            lambda u, o, b: cone_srp(rc, u, o, half_angle_deg=CONE["half_angle_deg"], base=False),
            np.pi * rc**2,
            rc,
        ),
    ]


def _srp_cases() -> tuple[SrpCase, ...]:
    cases = []
    for body, mesh, parts, reference, area, length in _bodies():
        for finish, optics in OPTICS.items():
            cases.append(
                SrpCase(
                    name=f"{body}/{finish}",
                    mesh=mesh,
                    parts=parts,
                    optics=optics,
                    reference=lambda u, r=reference, o=optics: r(u, o, BACK_OPTICS),
                    reference_area_m2=area,
                    reference_length_m=length,
                )
            )
    return tuple(cases)


#: Every convex-body case: 7 bodies x 4 finishes.
SRP_CASES: tuple[SrpCase, ...] = _srp_cases()
#: The bodies whose error must fall with mesh refinement (the plate is exact at any resolution).
REFINEMENT_CASES = tuple(c for c in SRP_CASES if c.name.endswith("/mixed") and not c.name.startswith("plate"))


@dataclass(frozen=True, eq=False)
class ShadowCase:
    """Plate B partly shadowing plate A (both one-sided, finish ``optics``), against the exact answer.

    Geometry as :class:`sunwind.validation.analytic_shadow.PlatePair`. The error measures are relative
    to the reference magnitude of A's force and of A's torque about A's centre, which the shadow's
    first moment alone sets: the sharp test of where the lit area is.

    Attributes
    ----------
    name : str
        Name of the case.
    side_a_m, side_b_m : float
        Side lengths of the square plates A and B [m].
    centre_b_m : (3,) tuple of float
        Centre of B [m]; A is centred at the origin in z = 0.
    gamma_deg : float
        Turn of B about z [deg].
    optics : Optics
        Finish of both plates.
    divisions : int
        Cells along each side of A.
    sun_vectors : tuple of (3,) tuple of float
        Directions toward the Sun, not normalised.
    rel_tol : float
        Largest error allowed [-].
    reason : str
        Why ``rel_tol`` is what it is.

    Examples
    --------
    >>> SHADOW_CASE.spacecraft().part_names
    ('plate_a', 'plate_b')
    """

    name: str = "shadowed plates/mixed"
    side_a_m: float = 1.0
    side_b_m: float = 0.4
    centre_b_m: tuple[float, float, float] = (0.13, -0.07, 0.3)
    gamma_deg: float = 23.0
    optics: Optics = OPTICS["mixed"]
    divisions: int = 20
    sun_vectors: tuple[tuple[float, float, float], ...] = (
        (0.35, 0.2, 1.0),
        (-0.5, 0.3, 1.0),
        (0.1, -0.6, 1.0),
        (0.7, 0.7, 1.0),
    )
    rel_tol: float = REL_TOL
    reason: str = field(
        default="the default shadow pass cuts the sides the shadow's straight outline crosses exactly"
    )

    def spacecraft(self) -> Spacecraft:
        """Plate A ('plate_a', 20 x 20 cells) and plate B ('plate_b'), both one-sided."""
        return _shadow_spacecraft(self)

    def reference(self, u: NDArray[np.float64]):
        """The exact loads, torques about the origin (A's centre)."""
        plates = PlatePair(self.side_a_m, self.side_b_m, self.centre_b_m, self.gamma_deg)
        return shadowed_plates_srp(plates, u, self.optics)


@lru_cache(maxsize=2)
def _shadow_spacecraft(case: ShadowCase) -> Spacecraft:
    a = label(primitives.plate(case.side_a_m, case.side_a_m, case.divisions), "plate_a")
    b = transform(
        label(primitives.plate(case.side_b_m, case.side_b_m, 4), "plate_b"),
        rotation=rotation_matrix("z", case.gamma_deg),
        translation=case.centre_b_m,
    )
    document = {
        "materials": {"finish": _optics_table(case.optics)},
        "parts": {"plate_*": {"front": "finish"}},
    }
    return build_spacecraft(MeshData.concatenate([a, b], source=case.name), parse_materials(document))


SHADOW_CASE = ShadowCase()

#: Sun directions of :class:`LowPolyCase`: four where the strut's and the wing's shadows fall across
#: the bus's large triangles (at the first the strut's touches none of their corners), then seeded
#: random ones (grazing shadows stretched over several sides, the bus's shadow across the strut), then
#: three along the axes.
LOW_POLY_SUNS: tuple[tuple[float, float, float], ...] = (
    (1.0, 0.05, 0.3),
    (1.0, 0.4, 0.1),
    (0.6, -0.2, 0.8),
    (1.0, -1.0, 0.2),
    *(tuple(float(x) for x in v) for v in np.random.default_rng(5).normal(size=(16, 3))),
    (1.0, 0.0, 0.0),  # along the axes: faces edge-on to the Sun, outlines along their planes
    (1.0, 0.0, 1.0),
    (0.0, -1.0, 0.0),
)


@dataclass(frozen=True)
class LowPolyCase:
    """A low-polygon model whose shadows fall across single large triangles, against exact clipping.

    The model: a 12-triangle 1 m box bus, a 1 cm x 1 cm x 1.6 m strut 0.2 m off its +x face, and a
    1 m x 2 m two-sided wing 5 cm off its +x face beside its -y face, all absorbing; the reference is
    :func:`sunwind.validation.exact_shadow.exact_absorber_srp`.

    Attributes
    ----------
    name : str
        Name of the case.
    sun_vectors : tuple of (3,) tuple of float
        Directions toward the Sun, not normalised (:data:`LOW_POLY_SUNS`).
    quick_suns : int
        How many of them a quick run checks.
    rel_tol : float
        Largest error allowed [-].
    reason : str
        Why ``rel_tol`` is what it is.

    Examples
    --------
    >>> craft = LOW_POLY_CASE.spacecraft()
    >>> craft.part_names, craft.n_sides
    (('bus', 'strut', 'wing'), 28)
    """

    name: str = "bus, wing, 1 cm strut"
    sun_vectors: tuple[tuple[float, float, float], ...] = LOW_POLY_SUNS
    quick_suns: int = 4
    rel_tol: float = 1e-4
    reason: str = field(
        default="the default shadow pass cuts sides along the shadow outline, exactly where it is found"
    )

    def spacecraft(self) -> Spacecraft:
        """Parts 'bus', 'strut' (closed) and 'wing' (two-sided)."""
        return _low_poly_spacecraft(self)


@lru_cache(maxsize=1)
def _low_poly_spacecraft(case: LowPolyCase) -> Spacecraft:
    bus = label(primitives.box((1.0, 1.0, 1.0)), "bus")
    strut = label(transform(primitives.box((0.01, 0.01, 1.6)), translation=(0.7, 0.0, 0.3)), "strut")
    wing = transform(primitives.plate(1.0, 2.0, 1), rotation_matrix("y", 90.0), translation=(0.55, -1.5, 0.0))
    black = {"front": "black"}
    document = {
        "materials": {"black": {"reflectivity": 0.0, "specular_fraction": 0.0}},
        "parts": {"bus": black, "strut": black, "wing": {"front": "black", "back": "black"}},
    }
    parts = MeshData.concatenate([bus, strut, label(wing, "wing")], source=case.name)
    return build_spacecraft(parts, parse_materials(document))


LOW_POLY_CASE = LowPolyCase()
