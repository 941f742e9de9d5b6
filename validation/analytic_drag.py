"""Closed-form free-molecular force and torque on convex bodies: flat plate, sphere, cylinder, cone.

These are independent references for the free-molecular solver: the local law
(:mod:`sunwind.validation.analytic_gas_law`) is derived again, each body's pieces are reduced to four
integrals of it (:mod:`sunwind.validation.analytic_drag_pieces`), and the modules import numpy and
scipy only, nothing from ``forces``. Everything is in the body frame and SI, one gas species, and the
bodies are convex, so every element sees only the free stream (no shadowing, no molecular
inter-reflection).

Notes
-----
**Bodies**, placed as in :mod:`sunwind.meshes.primitives`: the plate centred at the origin in
``z = 0`` with front normal +z; the sphere centred at the origin; the cylinder on the z axis from
``z = -L/2`` to ``L/2``; the cone with its base disc in ``z = 0`` (normal -z) and apex at
``(0, 0, R / tan(half_angle))``. The flow is a :class:`sunwind.validation.analytic_gas_law.AnalyticStream`.

**Cylinder torque and lift** (METHOD.md "The paper's misprints"). Take ``u = sin(alpha) e1 + cos(alpha) e_z``.
About its centre, the lateral surface's pressures have no moment (``r x n = z e_z x n`` integrates
to zero over ``z``), but its shear acts at ``R n``: ``M_0 / q = -R^2 L (int tau cos) e1 x u
= a_t pi R^2 L sin(alpha) cos(alpha) e2``, exact at every ``S`` because ``tau(gamma) - tau(-gamma) =
2 a_t gamma``. The caps' shear acts at ``+-L/2 e_z`` and gives ``-a_t pi R^2 L sin(alpha) cos(alpha)
e2``: the closed cylinder has no torque about its centre. Its lift is ``-q G . e_L`` with
``e_L = cos(alpha) e1 - sin(alpha) e_z``, and ``G . e_L = R L cos(alpha) int g cos - pi R^2 sin(alpha)
(g(cos alpha) - g(-cos alpha))`` depends only on the odd part of ``g`` (the even part cancels on a
body symmetric about its centre). If that odd part is linear, ``c gamma``, then ``G . e_L =
c pi R sin(alpha) cos(alpha) (L/2 - R)`` and ``C_L = -c sin(alpha) cos(alpha) (L / (2R) - 1)``
(``A_ref = pi R^2``): zero exactly when ``L = 2R``. That is the case of the directed (hyperthermal)
stream of any model with ``a_n = a_t`` (fully diffuse: sentman, dria at any ``alpha_E`` and ``T_w``;
schaaf-chambre with ``sigma_n = sigma_t = 1``), where ``g = kappa gamma`` on windward faces — the
Lambertian law of light, ``c = kappa``. At finite ``S`` the full stream adds the odd part
``erf(S gamma) / (2 S^2)`` of the incident pressure, which is not linear, so an
``L = D`` diffuse cylinder has a lift of order ``1/S^2`` (``S^2 C_L -> -(4 cos(alpha) - pi
sin(alpha)) / pi``); a specular one (``a_n != a_t``) has a lift of order 1.

**Coefficients.** ``C = F . e / (q A_ref)`` with the drag direction ``e_D = -u``, the lift direction
``e_L`` perpendicular to ``u`` in the plane of ``u`` and the body axis ``a = +z`` (plate normal,
cylinder and cone axis), pointing away from ``a``: ``e_L = -(a - (a.u) u) / |a - (a.u) u|``
(``e_L . a < 0``; a plate whose front faces the flow has positive lift), and the side direction
``e_S = e_L x e_D``, so ``(e_D, e_S, e_L)`` is right-handed. When ``u`` is along the axis the body
+x axis stands in for ``a`` (lift is then zero by symmetry). Default ``A_ref``: the plate's area
(one face), ``pi R^2`` for the sphere, the cylinder (its cross-section) and the cone (its base).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.validation.analytic_drag_pieces import Piece, flat_piece, frustum_piece, sphere_piece
from sunwind.validation.analytic_gas_law import AnalyticStream, GasLaw, SurfaceLaw, surface_law

__all__ = ["FmfLoad", "cone_drag", "cylinder_drag", "plate_drag", "sphere_drag"]

_UNIT_TOLERANCE = 1e-9

Vector = NDArray[np.float64]


@dataclass(frozen=True)
class FmfLoad:
    """Free-molecular force and torque on a body, with its coefficients; body frame, SI.

    Attributes
    ----------
    force_N : (3,) float64
        Force [N].
    torque_Nm : (3,) float64
        Torque [N m] about ``reference_point_m``.
    reference_point_m : (3,) float64
        Torque reference point [m].
    dynamic_pressure_Pa : float
        ``q = rho V^2 / 2`` [Pa].
    reference_area_m2 : float
        ``A_ref`` [m^2] of the coefficients.
    drag_direction, lift_direction, side_direction : (3,) float64
        Unit vectors ``e_D = -u``, ``e_L``, ``e_S`` (module Notes, "Coefficients").

    Examples
    --------
    >>> from sunwind.validation.analytic_gas_law import AnalyticStream, GasLaw, flow_vector_from_alpha
    >>> beam = AnalyticStream(flow_vector_from_alpha(0.0), 7.0, 900.0, stream="directed")
    >>> load = plate_drag(1.0, 1.0, beam, GasLaw("specular"))
    >>> load.force_N.tolist(), load.drag_coefficient
    ([0.0, 0.0, -4.0], 4.0)
    """

    force_N: Vector
    torque_Nm: Vector
    reference_point_m: Vector
    dynamic_pressure_Pa: float
    reference_area_m2: float
    drag_direction: Vector
    lift_direction: Vector
    side_direction: Vector

    def _coefficient(self, direction: Vector) -> float:
        return float(self.force_N @ direction) / (self.dynamic_pressure_Pa * self.reference_area_m2)

    @property
    def drag_coefficient(self) -> float:
        """``C_D = F . (-u) / (q A_ref)`` [-]."""
        return self._coefficient(self.drag_direction)

    @property
    def lift_coefficient(self) -> float:
        """``C_L = F . e_L / (q A_ref)`` [-]."""
        return self._coefficient(self.lift_direction)

    @property
    def side_coefficient(self) -> float:
        """``C_S = F . e_S / (q A_ref)`` [-]."""
        return self._coefficient(self.side_direction)


# ------------------------------------------------------------------------------------------- bodies


def plate_drag(
    size_x_m: float,
    size_y_m: float,
    flow: AnalyticStream,
    surface: GasLaw,
    *,
    one_sided: bool = True,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
    reference_area_m2: float | None = None,
) -> FmfLoad:
    """Free-molecular load on a flat rectangular plate centred at the origin in z = 0, front normal +z.

    Parameters
    ----------
    size_x_m, size_y_m : float
        Side lengths along x and y [m].
    flow : AnalyticStream
        Unit flow vector, speed ratio [-], temperature [K], dynamic pressure [Pa] and stream.
    surface : GasLaw
        Gas-surface interaction of both faces.
    one_sided : bool, optional
        If True (default) only the front face (normal +z) interacts; else both faces, the lee face
        included (struck by the thermal stream).
    ref_point_m : (3,) array_like, optional
        Torque reference [m], default the origin.
    reference_area_m2 : float, optional
        ``A_ref`` [m^2], default the plate area (one face).

    Returns
    -------
    FmfLoad
        Force [N] and torque [N m] about ``ref_point_m``, with the coefficient axes.

    Examples
    --------
    A specular plate face-on to the hyperthermal beam takes twice the momentum of the molecules it
    stops, ``C_D = 4`` over one face:

    >>> from sunwind.validation.analytic_gas_law import AnalyticStream, GasLaw, flow_vector_from_alpha
    >>> beam = AnalyticStream(flow_vector_from_alpha(0.0), 7.0, 900.0, stream="directed")
    >>> plate_drag(1.0, 1.0, beam, GasLaw("specular")).drag_coefficient
    4.0
    """
    u, law = _unit_flow(flow.flow_direction), _law(surface, flow)
    area = size_x_m * size_y_m
    normals = [np.array([0.0, 0.0, 1.0])] + ([] if one_sided else [np.array([0.0, 0.0, -1.0])])
    pieces = [flat_piece(area, np.zeros(3), n, u, law) for n in normals]
    return _load(pieces, u, flow.dynamic_pressure_Pa, ref_point_m, reference_area_m2 or area)


def sphere_drag(
    radius_m: float,
    flow: AnalyticStream,
    surface: GasLaw,
    *,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
    reference_area_m2: float | None = None,
) -> FmfLoad:
    """Free-molecular load on a sphere centred at the origin (force along ``-u``, no torque there).

    Parameters
    ----------
    radius_m : float
        Radius R [m].
    flow : AnalyticStream
        Unit flow vector, speed ratio [-], temperature [K], dynamic pressure [Pa] and stream.
    surface : GasLaw
        Gas-surface interaction of the whole sphere.
    ref_point_m : (3,) array_like, optional
        Torque reference [m], default the centre.
    reference_area_m2 : float, optional
        ``A_ref`` [m^2], default ``pi R^2``.

    Returns
    -------
    FmfLoad
        Force [N] and torque [N m] about ``ref_point_m``, with the coefficient axes.

    Raises
    ------
    ValueError
        If the flow vector is not a unit (3,) vector, the law's parameters are out of range or
        ``ref_point_m`` is not a (3,) point.

    Examples
    --------
    The hyperthermal specular sphere has ``C_D = 2``; a diffuse one (Sentman, full stream) a little more:

    >>> from sunwind.validation.analytic_gas_law import AnalyticStream, GasLaw, flow_vector_from_alpha
    >>> u = flow_vector_from_alpha(0.0)
    >>> beam = AnalyticStream(u, 7.0, 900.0, stream="directed")
    >>> sphere_drag(1.0, beam, GasLaw("specular")).drag_coefficient
    2.0
    >>> round(sphere_drag(1.0, AnalyticStream(u, 7.0, 900.0), GasLaw("sentman")).drag_coefficient, 4)
    2.1381

    References
    ----------
    .. [1] L. H. Sentman, "Free molecule flow theory and its application to the determination of
       aerodynamic forces", Lockheed Missiles and Space Co., LMSC-448514, 1961.
    """
    u, law = _unit_flow(flow.flow_direction), _law(surface, flow)
    return _load(
        [sphere_piece(radius_m, u, law)],
        u,
        flow.dynamic_pressure_Pa,
        ref_point_m,
        reference_area_m2 or math.pi * radius_m**2,
    )


def cylinder_drag(
    radius_m: float,
    length_m: float,
    flow: AnalyticStream,
    surface: GasLaw,
    *,
    caps: bool = True,
    lateral: str = "bessel",
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
    reference_area_m2: float | None = None,
) -> FmfLoad:
    """Free-molecular load on a circular cylinder on the z axis, centred at the origin.

    Parameters
    ----------
    radius_m, length_m : float
        Radius R and length L [m]; the cylinder spans ``z = -L/2 .. L/2``.
    flow : AnalyticStream
        As in :func:`plate_drag`.
    surface : GasLaw
        Gas-surface interaction of the whole body.
    caps : bool, optional
        Include the end discs (normals +-z); without them only the outer lateral surface interacts.
    lateral : {"bessel", "quad"}, optional
        Azimuth integrals of the lateral surface in closed form (default) or by adaptive quadrature.
    ref_point_m : (3,) array_like, optional
        Torque reference [m], default the origin (the centre).
    reference_area_m2 : float, optional
        Default ``pi R^2``.

    Returns
    -------
    FmfLoad
        Force [N] and torque [N m] about ``ref_point_m``, with the coefficient axes.

    Raises
    ------
    ValueError
        If ``lateral`` is neither ``"bessel"`` nor ``"quad"``, or as :func:`sphere_drag`.

    Examples
    --------
    A closed diffuse cylinder has no torque about its centre (module Notes):

    >>> from sunwind.validation.analytic_gas_law import AnalyticStream, GasLaw, flow_vector_from_alpha
    >>> flow = AnalyticStream(flow_vector_from_alpha(30.0), 7.0, 900.0)
    >>> load = cylinder_drag(0.5, 1.0, flow, GasLaw("sentman"))
    >>> round(load.drag_coefficient, 4), bool(abs(load.torque_Nm).max() < 1e-12)
    (3.2081, True)
    """
    if lateral not in ("bessel", "quad"):
        raise ValueError(f"lateral must be 'bessel' or 'quad', got {lateral!r}")
    u, law = _unit_flow(flow.flow_direction), _law(surface, flow)
    half = 0.5 * length_m
    pieces = [frustum_piece(radius_m, -half, radius_m, half, u, law, closed=lateral == "bessel")]
    if caps:
        disc = math.pi * radius_m**2
        for side in (1.0, -1.0):
            pieces.append(
                flat_piece(disc, np.array([0.0, 0.0, side * half * disc]), np.array([0.0, 0.0, side]), u, law)
            )
    area = reference_area_m2 or math.pi * radius_m**2
    return _load(pieces, u, flow.dynamic_pressure_Pa, ref_point_m, area)


def cone_drag(
    radius_m: float,
    flow: AnalyticStream,
    surface: GasLaw,
    *,
    half_angle_deg: float = 70.0,
    base: bool = True,
    ref_point_m: ArrayLike = (0.0, 0.0, 0.0),
    reference_area_m2: float | None = None,
) -> FmfLoad:
    """Free-molecular load on a right circular cone: base disc in z = 0 (normal -z), apex on +z.

    Parameters
    ----------
    radius_m : float
        Base radius R [m]; the apex is at ``(0, 0, R / tan(half_angle))``.
    flow : AnalyticStream
        As in :func:`plate_drag`.
    surface : GasLaw
        Gas-surface interaction of the whole body.
    half_angle_deg : float, optional
        Angle between the axis and a generator [deg], in (0, 90); default 70 as in the paper.
    base : bool, optional
        Include the base disc; without it only the outer lateral surface interacts.
    ref_point_m : (3,) array_like, optional
        Torque reference [m], default the origin (the base centre).
    reference_area_m2 : float, optional
        Default ``pi R^2`` (the base).

    Returns
    -------
    FmfLoad
        Force [N] and torque [N m] about ``ref_point_m``, with the coefficient axes.

    Notes
    -----
    The lateral full-stream azimuth integrals are adaptive quadratures
    (:mod:`sunwind.validation.analytic_drag_pieces`); the directed stream is closed.

    Raises
    ------
    ValueError
        If ``half_angle_deg`` lies outside (0, 90), or as :func:`sphere_drag`.

    Examples
    --------
    >>> from sunwind.validation.analytic_gas_law import AnalyticStream, GasLaw, flow_vector_from_alpha
    >>> flow = AnalyticStream(flow_vector_from_alpha(0.0), 7.0, 900.0)
    >>> round(cone_drag(1.0, flow, GasLaw("sentman")).drag_coefficient, 4)
    2.1578
    """
    if not 0.0 < half_angle_deg < 90.0:
        raise ValueError(f"cone half_angle_deg must lie in (0, 90), got {half_angle_deg}")
    u, law = _unit_flow(flow.flow_direction), _law(surface, flow)
    height = radius_m / math.tan(math.radians(half_angle_deg))
    pieces = [frustum_piece(radius_m, 0.0, 0.0, height, u, law, closed=False)]
    if base:
        pieces.append(flat_piece(math.pi * radius_m**2, np.zeros(3), np.array([0.0, 0.0, -1.0]), u, law))
    area = reference_area_m2 or math.pi * radius_m**2
    return _load(pieces, u, flow.dynamic_pressure_Pa, ref_point_m, area)


# --------------------------------------------------------------------------------------------- sums


def _unit_flow(flow_direction: ArrayLike) -> Vector:
    u = np.asarray(flow_direction, dtype=np.float64)
    if u.shape != (3,) or abs(np.linalg.norm(u) - 1.0) > _UNIT_TOLERANCE:
        raise ValueError(f"flow_direction must be a unit (3,) vector, got {flow_direction}")
    return u


def _law(surface: GasLaw, flow: AnalyticStream) -> SurfaceLaw:
    """The local law of ``surface`` in the species and stream of ``flow``."""
    return surface_law(surface, flow.speed_ratio, flow.temperature_K, flow.stream)


def _load(pieces: list[Piece], u: Vector, q: float, ref_point_m: ArrayLike, reference_area: float) -> FmfLoad:
    """Sum the pieces into force and torque about ``ref_point_m`` and set up the coefficient axes."""
    ref = np.asarray(ref_point_m, dtype=np.float64)
    if ref.shape != (3,):
        raise ValueError(f"ref_point_m must be a (3,) point [m], got {ref_point_m}")
    force, torque = np.zeros(3), np.zeros(3)
    for piece in pieces:
        force -= q * (piece.shear * u + piece.normal)
        torque -= q * (np.cross(piece.shear_moment, u) + piece.normal_moment)
    drag, lift, side = _wind_axes(u)
    return FmfLoad(
        force, torque - np.cross(ref, force), ref, float(q), float(reference_area), drag, lift, side
    )


def _wind_axes(u: Vector) -> tuple[Vector, Vector, Vector]:
    """``(e_D, e_L, e_S)`` of the module Notes for the body axis +z (+x when ``u`` is along z)."""
    for axis in (np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])):
        across = axis - (axis @ u) * u
        size = np.linalg.norm(across)
        if size > 1e-12:
            break
    lift = -across / size
    drag = -u
    return drag, lift, np.cross(lift, drag)
