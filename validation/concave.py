"""Concave validation cases, where light reflected by one facet strikes another, and the V-groove closed form.

The reference for these shapes is the Monte Carlo photon tracer of :mod:`sunwind.validation.photon_tracer`,
plus, for a mirror V-groove lit in the plane across its axis, the exact answer
:func:`v_groove_srp` derived below. :func:`compare` and :func:`reflection_table` put the solver
(``sunwind.forces.srp.srp`` with ``reflections="full"``) beside the tracer and return the numbers; they
print nothing.

Cases (:data:`CONCAVE_CASES`): a 90 deg V-groove of two long plates, an L of two unequal plates, a
cube open at the top, and the sample spacecraft's paraboloidal dish. Every plate is a two-sided sheet
meshed 8 x 8 cells or finer; each case is run with each of its finishes (:data:`FINISHES`) at each of
its Sun directions, given as azimuth/elevation (METHOD.md "Frames"), some off every symmetry plane.

Notes
-----
**V-groove of mirrors, lit across its axis.** Two plates of slant width ``w`` and length ``L`` meet
at 90 deg along the y axis (the apex, at the origin) and open toward +z; their inner normals are
``n_l = (1, 0, 1)/sqrt(2)`` (wall at x < 0) and ``n_r = (-1, 0, 1)/sqrt(2)``. The Sun is at
``psi`` from +z in the xz-plane, ``u = (sin psi, 0, cos psi)``, ``|psi| <= 45 deg``; photons travel
along ``s = -u`` and stay in their plane y = const, so the length ``L`` enters only as a factor.
Take ``psi >= 0`` (the other sign is the mirror image x -> -x) and write ``h = w / sqrt(2)``,
``c = cos psi``, ``sn = sin psi``, ``t = tan psi``.

*What enters.* The walls' outer sides face away from the Sun (``(+-1, 0, -1)/sqrt(2) . u <= 0``),
and the groove seen from the Sun spans exactly its aperture, the segment ``z = h``,
``-h <= x <= h``: all the light, power ``P_in = Phi A c`` with ``A = 2 h L = sqrt(2) w L``, enters
there, uniformly in the crossing abscissa ``x0``.

*First wall.* The ray ``(x0 - t' sn, h - t' c)`` meets the right wall (``z = x``) at
``t' = (h - x0)/(c - sn)`` and the left wall (``z = -x``) at ``t' = (h + x0)/(c + sn)``; the right
one is first exactly when ``x0 > h t``.

*Right wall first.* The mirror ``n_r`` maps ``(dx, dz)`` to ``(dz, dx)``, so the ray leaves along
``(-c, -sn)``, downward (``sn >= 0``), and must meet the left wall below the rim: two bounces.

*Left wall first.* It strikes at height ``z1 = (h sn - x0 c)/(c + sn)`` and leaves along
``(-dz, -dx) = (c, sn)``, upward; it meets the right wall at height ``z1 (c + sn)/(c - sn)``, which is
on the wall (``<= h``) when ``x0 >= h (2 t - 1)``: two bounces; else it leaves through the aperture
after one.

So one-bounce light enters on ``-h <= x0 < h (2 t - 1)``, a share ``t = tan psi`` of the aperture,
and leaves along ``e1 = s - 2 (s . n_A) n_A = (cos psi, 0, sin psi)``, the mirror image of ``s`` in
the wall ``A`` that faces the Sun more (the left one for ``psi > 0``). The rest, ``1 - t``, meets both
walls; two reflections in perpendicular mirrors reverse the ray, ``d -> -d``: it leaves along
``-s = u`` (a corner reflector). With reflectivity ``rho`` (specular, ``sigma = 0``) one-bounce light
leaves with ``rho P_in t`` and two-bounce light with ``rho^2 P_in (1 - t)``; momentum in minus momentum
out gives, with ``P = Phi / c_light``,

    F = P A cos(psi) [ (1 + rho^2 (1 - tan psi)) s - rho tan(psi) e1 ].

Limits: ``psi = 0``: everything is retro-reflected, ``F = -(1 + rho^2) P A u`` (``2 P A`` along
``-u`` for perfect mirrors). ``psi = 45 deg``: the left wall is at normal incidence and the right one
grazed; ``e1 = u`` and ``F = -(1 + rho) P A cos(psi) u``, a plain mirror of area ``w L``. ``rho = 0``:
``F = P A cos(psi) s``, an absorber.

*Torque about the apex.* A ray of power ``dW`` gives the impulse rate ``(dW / c_light)(d_in - d_out)``
at each bounce point, and ``r x d`` is the same at every point of a straight line, so its torque is
``(dW / c_light)(m_in - k m_out)`` with ``m = r x d`` of its incoming and outgoing lines and ``k`` the
share of its power that leaves. In the xz-plane ``m_y = z d_x - x d_z``; the incoming line through
``(x0, h)`` has ``m_in = x0 c - h sn``. A mirror through the apex maps a line to its mirror image,
which flips the sign of ``m``: one bounce gives ``m_out = -m_in`` (``k = rho``); two perpendicular
mirrors make a half-turn about the apex, which keeps it: ``m_out = m_in`` (``k = rho^2``). Over the
entry abscissae, ``int_{-h}^{h (2t - 1)} m_in dx0 = -2 h^2 sn`` (one bounce) and
``int_{h (2t - 1)}^{h} m_in dx0 = 0`` (two bounces). With ``dW = Phi c L dx0``,

    M_apex = -(1 + rho) P h^2 L sin(2 psi) e_y = -(1 + rho) P (w^2 / 2) L sin(2 psi) e_y,

and about a point ``r_ref``, ``M = M_apex - r_ref x F``. At ``psi = 45 deg`` with ``rho = 1`` this is
the force ``2 P A cos(psi)`` along ``s`` acting at the centre of the left wall, as it must be.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.geometry.materials import parse_materials
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.spacecraft import Spacecraft, build_spacecraft
from sunwind.meshes.primitives import grid_faces
from sunwind.meshes.samples import SAMPLE_OPTICS, sample_spacecraft
from sunwind.validation.analytic_srp import SOLAR_FLUX_1AU_W_M2, SPEED_OF_LIGHT_M_S, ForceTorque, Optics
from sunwind.validation.photon_tracer import TracerResult, trace_photons

__all__ = [
    "CONCAVE_CASES",
    "FINISHES",
    "MC_PHOTONS",
    "TOLERANCE",
    "TORQUE_LEVER",
    "ConcaveCase",
    "ReflectionRow",
    "compare",
    "dish_mesh",
    "finished_spacecraft",
    "l_mesh",
    "open_box_mesh",
    "reflection_table",
    "sheet",
    "sun_from_az_el",
    "torque_scale",
    "trace_case",
    "v_groove_mesh",
    "v_groove_srp",
]

#: Surface finishes of the concave cases, the same on both sides of every sheet unless a case says.
FINISHES: dict[str, Optics] = {
    "specular": Optics(0.9, 1.0, 0.0),
    "diffuse": Optics(0.9, 0.0, 0.0),
    "mixed": Optics(0.8, 0.5, 0.0),
}
#: A translucent film (sigma > 0) for the L's wall in its "translucent wall" finish.
TRANSLUCENT = Optics(0.5, 0.5, 0.3)
#: Solver against tracer: largest difference of force, torque and power, each over its scale [-].
TOLERANCE = 0.01
#: Torque scale where the torque is small: ``|F|`` times this share of the model size (:func:`torque_scale`).
TORQUE_LEVER = 0.25
#: Bundles the tracer launches per comparison; sets its standard error (see :func:`compare`).
MC_PHOTONS = 600_000

#: Part glob -> (front optics, back optics): the materials of one finish of a case.
PartOptics = Mapping[str, tuple[Optics, Optics]]


def sun_from_az_el(azimuth_deg: float, elevation_deg: float) -> NDArray[np.float64]:
    """Unit Sun vector from azimuth ``atan2(u_y, u_x)`` and elevation ``asin(u_z)`` [deg], body frame."""
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    return np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])


# ------------------------------------------------------------------------------------------ meshes


def sheet(
    corner: ArrayLike, edge_u: ArrayLike, edge_v: ArrayLike, divisions: tuple[int, int], part: str
) -> MeshData:
    """Flat parallelogram ``corner + a edge_u + b edge_v``, ``a, b`` in [0, 1], front along ``u x v``.

    Parameters
    ----------
    corner, edge_u, edge_v : (3,) array_like
        A corner and the two edges from it [m].
    divisions : (int, int)
        Cells along ``edge_u`` and ``edge_v``.
    part : str

    Returns
    -------
    MeshData
        ``2 nu nv`` triangles, no material.
    """
    nu, nv = divisions
    a, b = np.meshgrid(np.linspace(0, 1, nu + 1), np.linspace(0, 1, nv + 1), indexing="ij")
    vertices = (
        np.asarray(corner, dtype=np.float64)
        + a.reshape(-1, 1) * np.asarray(edge_u, dtype=np.float64)
        + b.reshape(-1, 1) * np.asarray(edge_v, dtype=np.float64)
    )
    faces = grid_faces(nu, nv)
    n = len(faces)
    return MeshData(vertices, faces, np.zeros(n, np.int32), (part,), np.full(n, -1, np.int32))


def v_groove_mesh(
    width_m: float = 1.0, length_m: float = 3.0, divisions: tuple[int, int] = (8, 16)
) -> MeshData:
    """90 deg V-groove: two plates ``width_m`` (slant) by ``length_m``, apex on the y axis, open to +z.

    The plates run from the apex (the y axis, ``|y| <= length / 2``) up to ``x = -+ w / sqrt(2)``,
    ``z = w / sqrt(2)``; fronts face into the groove. Parts ``"wall_left"`` (x < 0) and
    ``"wall_right"``; ``divisions`` cells across and along each.
    """
    h = width_m / math.sqrt(2)
    apex = (0.0, -length_m / 2, 0.0)
    along = (0.0, length_m, 0.0)
    left = sheet(apex, along, (-h, 0.0, h), divisions[::-1], "wall_left")
    right = sheet(apex, (h, 0.0, h), along, divisions, "wall_right")
    return MeshData.concatenate([left, right], source="<v-groove>")


def l_mesh(
    floor_m: tuple[float, float] = (1.0, 1.2), wall_height_m: float = 0.6, divisions: int = 8
) -> MeshData:
    """An L of two plates at 90 deg: a floor in z = 0 and a wall in x = 0 along its edge.

    The floor spans ``0 <= x <= floor_m[0]``, ``|y| <= floor_m[1] / 2``, front +z; the wall
    ``|y| <= floor_m[1] / 2``, ``0 <= z <= wall_height_m``, front +x. Parts ``"floor"``, ``"wall"``.
    """
    a, b = floor_m
    corner = (0.0, -b / 2, 0.0)
    floor = sheet(corner, (a, 0.0, 0.0), (0.0, b, 0.0), (divisions, divisions), "floor")
    wall = sheet(corner, (0.0, b, 0.0), (0.0, 0.0, wall_height_m), (divisions, divisions), "wall")
    return MeshData.concatenate([floor, wall], source="<L>")


def open_box_mesh(edge_m: float = 1.0, divisions: int = 8) -> MeshData:
    """A cube centred at the origin without its top face (z = +edge / 2): five sheets, fronts inward.

    Parts ``"floor"``, ``"wall_+x"``, ``"wall_-x"``, ``"wall_+y"``, ``"wall_-y"``.
    """
    e, g = edge_m / 2, (divisions, divisions)
    pieces = [sheet((-e, -e, -e), (edge_m, 0.0, 0.0), (0.0, edge_m, 0.0), g, "floor")]
    for axis, name in ((0, "x"), (1, "y")):
        other = 1 - axis
        for sign in (1.0, -1.0):
            corner = np.full(3, -e)
            corner[axis] = sign * e
            across = np.zeros(3)
            across[other] = edge_m
            up = np.array([0.0, 0.0, edge_m])
            # front = edge_u x edge_v must point inward, along -sign on this axis
            inward = np.cross(across, up)[axis] * sign < 0
            edges = (across, up) if inward else (up, across)
            pieces.append(sheet(corner, *edges, g, f"wall_{'+' if sign > 0 else '-'}{name}"))
    return MeshData.concatenate(pieces, source="<open box>")


@lru_cache(maxsize=2)
def dish_mesh(triangles: int = 20_000) -> MeshData:
    """The ``"dish"`` part of :func:`sunwind.meshes.samples.sample_spacecraft` alone, where it sits in the
    sample.

    A paraboloid of diameter 1.2 m and f/D 0.35, concave side +z (its front), vertex at z = 0.904 m.
    """
    sample = sample_spacecraft(triangles)
    keep = sample.face_part == sample.part_names.index("dish")
    used, faces = np.unique(sample.faces[keep], return_inverse=True)
    n = int(keep.sum())
    return MeshData(
        sample.vertices[used],
        faces.reshape(-1, 3),
        np.zeros(n, np.int32),
        ("dish",),
        np.full(n, -1, np.int32),
        source="<sample dish>",
    )


# ----------------------------------------------------------------------------------------- closed form


def v_groove_srp(
    width_m: float,
    length_m: float,
    angle_deg: float,
    rho: float = 1.0,
    *,
    flux_W_m2: float = SOLAR_FLUX_1AU_W_M2,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
) -> ForceTorque:
    """Exact SRP force and torque on a 90 deg V-groove of specular plates lit across its axis.

    Geometry as :func:`v_groove_mesh` (apex on the y axis at the origin, open to +z); the Sun at
    ``angle_deg`` from +z toward +x, ``u = (sin psi, 0, cos psi)``. Derivation in the module Notes.

    Parameters
    ----------
    width_m, length_m : float
        Slant width ``w`` of each plate and groove length ``L`` [m].
    angle_deg : float
        ``psi`` [deg], in [-45, 45]: the light enters through the aperture only.
    rho : float
        Reflectivity of the inner sides [-], all specular (``beta = 1``, ``sigma = 0``).
    flux_W_m2 : float
        Solar flux [W/m^2].
    ref_point_m : (3,) array_like
        Torque reference point [m].

    Returns
    -------
    ForceTorque
        Force [N] and torque [N m] about ``ref_point_m``, body frame.
    """
    if abs(angle_deg) > 45.0:
        raise ValueError(f"angle_deg = {angle_deg} outside [-45, 45]: light would strike the outer sides")
    psi = math.radians(angle_deg)
    u = np.array([math.sin(psi), 0.0, math.cos(psi)])
    s = -u
    n_a = np.array([math.copysign(1.0, psi), 0.0, 1.0]) / math.sqrt(2)  # inner normal of the wall facing u
    e1 = s - 2.0 * (s @ n_a) * n_a
    t = math.tan(abs(psi))
    pressure = flux_W_m2 / SPEED_OF_LIGHT_M_S
    aperture = math.sqrt(2) * width_m * length_m
    force = pressure * aperture * math.cos(psi) * ((1.0 + rho**2 * (1.0 - t)) * s - rho * t * e1)
    torque_apex = np.array(
        [0.0, -(1.0 + rho) * pressure * width_m**2 / 2 * length_m * math.sin(2 * psi), 0.0]
    )
    return ForceTorque(force, torque_apex - np.cross(np.asarray(ref_point_m, dtype=np.float64), force))


# --------------------------------------------------------------------------------------------- cases


def _both(optics: Optics) -> PartOptics:
    return {"*": (optics, optics)}


@dataclass(frozen=True, eq=False)
class ConcaveCase:
    """A concave model, its finishes and the Sun directions it is checked at.

    Attributes
    ----------
    name : str
    mesh : callable
        ``mesh()`` builds the geometry (every part a sheet).
    finishes : mapping of str -> PartOptics
        Finish name -> part glob -> (front, back) optics; the first matching glob wins.
    suns_deg : tuple of (float, float)
        Sun directions as (azimuth, elevation) [deg].
    size_m : float
        Largest extent of the model [m], for :func:`torque_scale`.
    notes : str
        Sizes and why these Sun directions.
    """

    name: str
    mesh: Callable[[], MeshData]
    finishes: Mapping[str, PartOptics]
    suns_deg: tuple[tuple[float, float], ...]
    size_m: float
    notes: str = ""

    def spacecraft(self, finish: str) -> Spacecraft:
        """The model with the materials of ``finish``; kept for reuse."""
        return _spacecraft(self, finish)


@lru_cache(maxsize=32)
def _spacecraft(case: ConcaveCase, finish: str) -> Spacecraft:
    return finished_spacecraft(case.mesh(), case.finishes[finish], f"{case.name}/{finish}")


def finished_spacecraft(mesh: MeshData, finish: PartOptics, source: str = "<concave>") -> Spacecraft:
    """``mesh`` built with ``finish`` (part glob -> (front, back) optics): every matched part a two-sided
    sheet. ``source`` names the model in messages."""
    materials, parts = {}, {}
    for k, (glob, (front, back)) in enumerate(finish.items()):
        for side, optics in (("front", front), ("back", back)):
            materials[f"{side}{k}"] = {
                "reflectivity": optics.rho,
                "specular_fraction": optics.beta,
                "transmissivity": optics.sigma,
            }
        parts[glob] = {"front": f"front{k}", "back": f"back{k}"}
    document = {"materials": materials, "parts": parts}
    return build_spacecraft(replace(mesh, source=source), parse_materials(document, source=source))


def _sample_optics(name: str) -> Optics:
    values = SAMPLE_OPTICS[name]
    return Optics(values["reflectivity"], values["specular_fraction"], values["transmissivity"])


_MLI = _sample_optics("mli")

#: Every concave case. Azimuth 0 / 180 with elevation 90 - |psi| light the V-groove across its axis.
CONCAVE_CASES: tuple[ConcaveCase, ...] = (
    ConcaveCase(
        name="v-groove",
        mesh=v_groove_mesh,
        finishes={name: _both(optics) for name, optics in FINISHES.items()},
        suns_deg=((0.0, 90.0), (0.0, 70.0), (180.0, 55.0), (35.0, 60.0)),
        size_m=3.0,
        notes="w 1 m, L 3 m; first three Suns across the axis (psi 0, 20, -35 deg), the last off it",
    ),
    ConcaveCase(
        name="L",
        mesh=l_mesh,
        finishes={
            **{name: _both(optics) for name, optics in FINISHES.items()},
            "translucent wall": {"wall": (TRANSLUCENT, TRANSLUCENT), "floor": (FINISHES["mixed"],) * 2},
        },
        suns_deg=((30.0, 50.0), (-60.0, 25.0), (150.0, 40.0), (20.0, -30.0)),
        size_m=1.2,
        notes="floor 1 x 1.2 m, wall 0.6 m high; Suns on both fronts, the wall's back, the floor's back",
    ),
    ConcaveCase(
        name="open box",
        mesh=open_box_mesh,
        finishes={name: _both(optics) for name, optics in FINISHES.items()},
        suns_deg=((0.0, 90.0), (20.0, 65.0), (200.0, 45.0), (70.0, 15.0)),
        size_m=1.0,
        notes="unit cube without its top, two-sided walls; from straight in to nearly edge-on",
    ),
    ConcaveCase(
        name="dish",
        mesh=dish_mesh,
        finishes={
            **{name: {"*": (optics, _MLI)} for name, optics in FINISHES.items()},
            "sample": {"*": (_sample_optics("reflector_paint"), _MLI)},
        },
        suns_deg=((0.0, 90.0), (25.0, 60.0), (140.0, 35.0), (260.0, 15.0)),
        size_m=1.2,
        notes="the sample's dish, back in its MLI; on axis (specular: no second bounce) to 75 deg off",
    ),
)


# ------------------------------------------------------------------------------------------ comparison


def torque_scale(force_N: ArrayLike, torque_Nm: ArrayLike, size_m: float) -> float:
    """Scale of a torque error [N m]: ``max(|M|, |F| size_m / 4)``.

    The torque's own size, unless symmetry makes it small; then a shift of the force's line of action
    by a quarter of the model size, so that 1 % of the scale is a shift of 0.25 % of the size.
    """
    return max(float(np.linalg.norm(torque_Nm)), float(np.linalg.norm(force_N)) * size_m * TORQUE_LEVER)


@dataclass(frozen=True)
class ReflectionRow:
    """Solver against tracer for one case, finish and Sun direction.

    Attributes
    ----------
    case, finish : str
    azimuth_deg, elevation_deg : float
        Sun direction [deg].
    force_solver_N, force_mc_N : float
        ``|F|`` from the solver and from the tracer [N].
    force_difference : float
        ``|F_solver - F_mc| / |F_mc|`` [-].
    force_mc_sigma : float
        Tracer's standard error of the force vector over ``|F_mc|`` [-].
    torque_scale_Nm : float
        :func:`torque_scale` of the tracer's loads [N m].
    torque_difference : float
        ``|M_solver - M_mc|`` over the torque scale [-].
    torque_mc_sigma : float
        Tracer's standard error of the torque vector over the torque scale [-].
    power_difference : float
        Largest difference of incident, absorbed and escaped power over the tracer's incident power [-].
    k_is : float
        The solver's interference criterion ``K_IS``, eq. (7) [-].
    photons : int
        Bundles the tracer launched.
    tracer_seconds, solver_seconds : float
        Wall-clock times [s].
    """

    case: str
    finish: str
    azimuth_deg: float
    elevation_deg: float
    force_solver_N: float
    force_mc_N: float
    force_difference: float
    force_mc_sigma: float
    torque_scale_Nm: float
    torque_difference: float
    torque_mc_sigma: float
    power_difference: float
    k_is: float
    photons: int
    tracer_seconds: float
    solver_seconds: float

    @property
    def passed(self) -> bool:
        """Force, torque and power within :data:`TOLERANCE`."""
        return max(self.force_difference, self.torque_difference, self.power_difference) <= TOLERANCE


def trace_case(
    case: ConcaveCase,
    finish: str,
    sun_deg: tuple[float, float],
    photons: int = MC_PHOTONS,
    seed: int = 0,
    max_bounces: int = 100,
) -> TracerResult:
    """The tracer's loads for one case, finish and (azimuth, elevation), about the model's default point.

    ``max_bounces`` as in :func:`sunwind.validation.photon_tracer.trace_photons`.
    """
    return trace_photons(
        case.spacecraft(finish),
        sun_from_az_el(*sun_deg),
        photons=photons,
        seed=seed,
        max_bounces=max_bounces,
    )


def compare(
    case: ConcaveCase,
    finish: str,
    sun_deg: tuple[float, float],
    photons: int = MC_PHOTONS,
    seed: int = 0,
) -> ReflectionRow:
    """Solver (``reflections="full"``) against the tracer (the physics) for one case, finish and Sun
    direction; both at 1361 W/m^2, torques about the model's default reference point (its area
    centroid)."""
    from sunwind.forces.srp import srp  # the solver under test; imported here so the tracer needs none of it

    craft = case.spacecraft(finish)
    mc = trace_case(case, finish, sun_deg, photons, seed)
    start = time.perf_counter()
    solver = srp(
        craft,
        sun_from_az_el(*sun_deg),
        flux_W_m2=mc.flux_W_m2,
        reference_point_m=mc.reference_point_m,
        reflections="full",
    )
    solver_seconds = time.perf_counter() - start
    f_mc = float(np.linalg.norm(mc.force_N))
    scale = torque_scale(mc.force_N, mc.torque_Nm, case.size_m)
    power = solver.power
    power_gaps = (
        power.incident_W - mc.incident_W,
        power.absorbed_W - mc.absorbed_W,
        power.escaped_W - (mc.escaped_W + mc.cut_W),
    )
    return ReflectionRow(
        case=case.name,
        finish=finish,
        azimuth_deg=sun_deg[0],
        elevation_deg=sun_deg[1],
        force_solver_N=float(np.linalg.norm(solver.force_N)),
        force_mc_N=f_mc,
        force_difference=float(np.linalg.norm(solver.force_N - mc.force_N)) / f_mc,
        force_mc_sigma=mc.force_error_N / f_mc,
        torque_scale_Nm=scale,
        torque_difference=float(np.linalg.norm(solver.torque_Nm - mc.torque_Nm)) / scale,
        torque_mc_sigma=mc.torque_error_Nm / scale,
        power_difference=max(abs(g) for g in power_gaps) / mc.incident_W,
        k_is=float(solver.k_is),
        photons=mc.photons,
        tracer_seconds=mc.seconds,
        solver_seconds=solver_seconds,
    )


def reflection_table(
    cases: tuple[ConcaveCase, ...] = CONCAVE_CASES,
    photons: int = MC_PHOTONS,
    seed: int = 0,
) -> list[ReflectionRow]:
    """:func:`compare` for every case, finish and Sun direction, in that order."""
    return [
        compare(case, finish, sun, photons, seed)
        for case in cases
        for finish in case.finishes
        for sun in case.suns_deg
    ]
