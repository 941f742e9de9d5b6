"""The sunlight validation families: the solver against closed forms, the exact shadow and the photon tracer.

Each family function yields :class:`sunwind.validation.checks.Check` rows with the limits of
``tests/validation/test_srp_validation.py`` and ``test_reflection_validation.py``; ``quick`` keeps a
subset of the cases (the tracer at its full photon count, so that its own error stays in bounds).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from sunwind.forces.radiation.law import SOLAR_FLUX_1AU, SPEED_OF_LIGHT, radiation_pressure
from sunwind.forces.srp import srp
from sunwind.validation.analytic_srp_law import Optics
from sunwind.validation.analytic_v_groove import v_groove_srp
from sunwind.validation.cases import (
    LOW_POLY_CASE,
    REFINEMENT_CASES,
    SHADOW_CASE,
    SRP_CASES,
    ShadowCase,
    SrpCase,
)
from sunwind.validation.checks import Check, Measure
from sunwind.validation.concave import (
    CONCAVE_CASES,
    MC_PHOTONS,
    TOLERANCE,
    ReflectionRow,
    compare,
    finished_spacecraft,
    sun_from_az_el,
    torque_scale,
    trace_case,
)
from sunwind.validation.exact_shadow import exact_absorber_srp

#: The tracer's standard error may be at most this share of the tolerance.
SIGMA_SHARE = 0.25
#: Photon bundles of the single-interaction comparison of the direct law.
DIRECT_PHOTONS = 200_000
#: Mean observed order of the refinement study must lie in this range (two halvings of the facet size).
ORDER_RANGE = (1.3, 2.7)
#: Mirror V-groove lit across its axis: reflectivities and tilts psi [deg] of the closed-form checks.
V_GROOVE_RHO, V_GROOVE_PSI_DEG = (1.0, 0.9), (0.0, 20.0, -35.0)
#: The SRP closed-form cases of a quick run: the plates (exact) and one curved body.
QUICK_SRP = ("plate", "cone with base/mixed")


@dataclass(frozen=True)
class Row:
    """One SRP case at one Sun direction.

    Attributes
    ----------
    case : str
        ``body/finish``.
    sun : str
        The Sun direction, e.g. ``"alpha 30"``.
    reference, computed : float
        ``|F|`` of the closed form and of the solver [N].
    force_error : float
        ``|F_solver - F_ref| / |F_ref|`` [-].
    torque_error : float
        Torque error over the case's torque scale [-].
    tolerance : float
        Largest error that passes [-].

    Examples
    --------
    >>> row = Row("plate one-sided/absorbing", "alpha 0", 9.08e-06, 9.08e-06, 0.0, 0.0, 1e-3)
    >>> row.passed
    True
    """

    case: str
    sun: str
    reference: float
    computed: float
    force_error: float
    torque_error: float
    tolerance: float

    @property
    def passed(self) -> bool:
        """Whether the force and torque errors are both within the tolerance."""
        return self.force_error <= self.tolerance and self.torque_error <= self.tolerance


def run_srp_case(case: SrpCase, refinement: float = 1.0) -> list[Row]:
    """Solver against closed form at every direction of ``case``; torques about the origin.

    Parameters
    ----------
    case : SrpCase
        The body, its finish and its Sun directions.
    refinement : float, optional
        Mesh resolution relative to the case's default.

    Returns
    -------
    list of Row
        One row per Sun direction.

    Examples
    --------
    >>> from sunwind.validation.cases import SRP_CASES
    >>> rows = run_srp_case(SRP_CASES[0])
    >>> rows[0].case, rows[0].sun, all(row.passed for row in rows)
    ('plate one-sided/absorbing', 'alpha 0', True)
    """
    craft = case.spacecraft(refinement)
    scale = radiation_pressure(SOLAR_FLUX_1AU) * case.reference_area_m2
    rows = []
    for alpha, u in case.sun_vectors():
        exact = case.reference(u)
        result = srp(craft, u, reference_point_m=np.zeros(3))
        rows.append(
            Row(
                case=case.name,
                sun=f"alpha {alpha:g}",
                reference=float(np.linalg.norm(exact.force_N)),
                computed=float(np.linalg.norm(result.force_N)),
                force_error=float(np.linalg.norm(result.force_N - exact.force_N) / scale),
                torque_error=float(
                    np.linalg.norm(result.torque_Nm - exact.torque_Nm) / (scale * case.reference_length_m)
                ),
                tolerance=case.rel_tol,
            )
        )
    return rows


def run_shadow_case(case: ShadowCase = SHADOW_CASE) -> list[Row]:
    """Solver against the exact partial shadow; errors on plate A relative to its own loads.

    Parameters
    ----------
    case : ShadowCase, optional
        The plates, their finish and the Sun directions; default :data:`SHADOW_CASE`.

    Returns
    -------
    list of Row
        One row per Sun direction.

    Examples
    --------
    >>> rows = run_shadow_case()
    >>> rows[0].case, all(row.passed for row in rows)
    ('shadowed plates/mixed', True)
    """
    craft = case.spacecraft()
    on_a = craft.facet_part == craft.part_names.index("plate_a")
    rows = []
    for sun in case.sun_vectors:
        u = np.asarray(sun) / np.linalg.norm(sun)
        exact = case.reference(u)
        result = srp(craft, u, reference_point_m=np.zeros(3))
        force_a = result.facet_force_N[on_a].sum(axis=0)
        torque_a = result.facet_torque_Nm[on_a].sum(axis=0)
        rows.append(
            Row(
                case=case.name,
                sun="u " + " ".join(f"{x:+.2f}" for x in u),
                reference=float(np.linalg.norm(exact.plate_a.torque_Nm)),
                computed=float(np.linalg.norm(torque_a)),
                force_error=float(
                    np.linalg.norm(force_a - exact.plate_a.force_N) / np.linalg.norm(exact.plate_a.force_N)
                ),
                torque_error=float(
                    np.linalg.norm(torque_a - exact.plate_a.torque_Nm)
                    / np.linalg.norm(exact.plate_a.torque_Nm)
                ),
                tolerance=case.rel_tol,
            )
        )
    return rows


def refinement_study(case: SrpCase, refinements: tuple[float, ...] = (1 / 16, 1 / 8, 1 / 4)) -> list[float]:
    """Largest force error over the case's directions at each refinement (coarse to fine).

    Parameters
    ----------
    case : SrpCase
        A curved body (:data:`~sunwind.validation.cases.REFINEMENT_CASES`).
    refinements : tuple of float, optional
        Mesh resolutions relative to the case's default, coarse to fine.

    Returns
    -------
    list of float
        The largest relative force error at each refinement [-].

    Examples
    --------
    Halving the facets' size quarters the error of a cone (second order):

    >>> from sunwind.validation.cases import REFINEMENT_CASES
    >>> cone = REFINEMENT_CASES[3]
    >>> coarse, fine = refinement_study(cone, (1 / 16, 1 / 8))
    >>> cone.name, bool(3.0 < coarse / fine < 5.0)
    ('cone with base/mixed', True)
    """
    return [max(row.force_error for row in run_srp_case(case, f)) for f in refinements]


def _row_check(family: str, row: Row) -> Check:
    return Check(
        family,
        row.case,
        row.sun,
        (
            Measure("force", row.force_error, row.tolerance),
            Measure("torque", row.torque_error, row.tolerance),
        ),
    )


def srp_closed_form_checks(quick: bool) -> Iterator[Check]:
    """Check every convex body and finish of :data:`SRP_CASES` at every Sun angle.

    Parameters
    ----------
    quick : bool
        Run the quick subset (:data:`QUICK_SRP`).

    Yields
    ------
    Check
        One check per case and condition, computed when asked for.

    Examples
    --------
    >>> check = next(srp_closed_form_checks(quick=True))
    >>> check.case, check.at, check.passed
    ('plate one-sided/absorbing', 'alpha 0', True)
    """
    for case in SRP_CASES:
        if not quick or case.name.startswith(QUICK_SRP):
            yield from (_row_check("SRP closed forms", row) for row in run_srp_case(case))


def shadow_checks(quick: bool) -> Iterator[Check]:
    """Check plate A's force and torque under plate B's partial shadow, every Sun direction of the case.

    Parameters
    ----------
    quick : bool
        Unused: the case is quick.

    Yields
    ------
    Check
        One check per case and condition, computed when asked for.

    Examples
    --------
    >>> check = next(shadow_checks(quick=True))
    >>> check.case, check.passed
    ('shadowed plates/mixed', True)
    """
    yield from (_row_check("partial shadow", row) for row in run_shadow_case())


def low_poly_checks(quick: bool) -> Iterator[Check]:
    """Check the default shadow pass on :data:`LOW_POLY_CASE` against exact clipping.

    Lit area, force and torque, each relative to the exact value.

    Parameters
    ----------
    quick : bool
        Run the quick subset (its first Sun directions).

    Yields
    ------
    Check
        One check per case and condition, computed when asked for.

    Examples
    --------
    >>> check = next(low_poly_checks(quick=True))
    >>> check.case, check.passed
    ('bus, wing, 1 cm strut', True)
    """
    case = LOW_POLY_CASE
    craft = case.spacecraft()
    for sun in case.sun_vectors[: case.quick_suns if quick else None]:
        u = np.asarray(sun) / np.linalg.norm(sun)
        force, torque, lit = exact_absorber_srp(craft, u)
        # a flux of c W/m^2 is a pressure of 1 Pa, as the reference assumes
        result = srp(craft, u, flux_W_m2=SPEED_OF_LIGHT, reflections="none", reference_point_m=np.zeros(3))
        yield Check(
            "low-polygon shadows",
            case.name,
            "u " + " ".join(f"{x:+.2f}" for x in u),
            (
                Measure("lit area", abs(result.lit_area_m2 - lit) / lit, case.rel_tol),
                Measure("force", _relative(result.force_N, force), case.rel_tol),
                Measure("torque", _relative(result.torque_Nm, torque), case.rel_tol),
            ),
        )


def refinement_checks(quick: bool) -> Iterator[Check]:
    """Check that the force error falls at second order with mesh refinement (full run only).

    Parameters
    ----------
    quick : bool
        If True, yield nothing.

    Yields
    ------
    Check
        One check per case and condition, computed when asked for.

    Examples
    --------
    >>> list(refinement_checks(quick=True))
    []
    """
    for case in () if quick else REFINEMENT_CASES:
        errors = refinement_study(case)
        order = math.log2(errors[0] / errors[2]) / 2
        yield Check(
            "mesh refinement",
            case.name,
            "1/16, 1/8, 1/4",
            (
                Measure("error ratio 1/8 : 1/16", errors[1] / errors[0], 1.0),
                Measure("error ratio 1/4 : 1/8", errors[2] / errors[1], 1.0),
                Measure("observed order", order, ORDER_RANGE[1], low=ORDER_RANGE[0]),
            ),
        )


def v_groove_checks(quick: bool) -> Iterator[Check]:
    """Check the mirror V-groove lit across its axis against its closed form.

    The force error is over ``|F|``, the torque error over the torque scale.

    Parameters
    ----------
    quick : bool
        Run the quick subset.

    Yields
    ------
    Check
        One check per case and condition, computed when asked for.

    Examples
    --------
    >>> check = next(v_groove_checks(quick=True))
    >>> check.case, check.at, check.passed
    ('mirror rho 1', 'psi 0', True)
    """
    case = CONCAVE_CASES[0]
    for rho in V_GROOVE_RHO:
        mirror = Optics(rho, 1.0, 0.0)
        craft = finished_spacecraft(case.mesh(), {"*": (mirror, mirror)}, f"v-groove/mirror {rho}")
        ref = craft.default_reference[0]
        for psi in V_GROOVE_PSI_DEG:
            u = np.array([math.sin(math.radians(psi)), 0.0, math.cos(math.radians(psi))])
            exact = v_groove_srp(1.0, 3.0, psi, rho, ref_point_m=ref)
            result = srp(craft, u, reference_point_m=ref, reflections="full")
            scale = torque_scale(exact.force_N, exact.torque_Nm, case.size_m)
            force = np.linalg.norm(result.force_N - exact.force_N) / np.linalg.norm(exact.force_N)
            torque = np.linalg.norm(result.torque_Nm - exact.torque_Nm) / scale
            yield Check(
                "V-groove closed form",
                f"mirror rho {rho:g}",
                f"psi {psi:g}",
                (Measure("force", float(force), TOLERANCE), Measure("torque", float(torque), TOLERANCE)),
            )


def tracer_checks(quick: bool) -> Iterator[Check]:
    """Check full reflections against the photon tracer, every case, finish and Sun.

    Parameters
    ----------
    quick : bool
        Run the quick subset (the diffuse finish at each case's first Sun).

    Yields
    ------
    Check
        One check per case and condition, computed when asked for.

    Examples
    --------
    The first check (600 000 bundles, a few seconds):

    >>> check = next(tracer_checks(quick=True))
    >>> check.case, check.at, check.passed
    ('v-groove/diffuse', 'az 0 el 90', True)
    """
    for case in CONCAVE_CASES:
        for finish in ("diffuse",) if quick else case.finishes:
            for sun in case.suns_deg[:1] if quick else case.suns_deg:
                yield tracer_check(compare(case, finish, sun, photons=MC_PHOTONS))


def tracer_check(row: ReflectionRow) -> Check:
    """Turn one solver-against-tracer comparison into a check.

    Force, torque and power must lie within the tolerance, the tracer's own standard errors within
    :data:`SIGMA_SHARE` of it.

    Parameters
    ----------
    row : ReflectionRow
        The comparison.

    Returns
    -------
    Check
        Five measures: force, torque, power and the tracer's two standard errors.

    Examples
    --------
    >>> from sunwind.validation.concave import ReflectionRow
    >>> row = ReflectionRow(
    ...     "v-groove", "diffuse", 0.0, 90.0, 1e-5, 1e-5, 0.001, 0.001, 1e-5, 0.002, 0.001, 1e-4, 0.1,
    ...     600_000, 1.0, 0.5,
    ... )
    >>> check = tracer_check(row)
    >>> check.passed, [measure.name for measure in check.measures][:3]
    (True, ['force', 'torque', 'power'])
    """
    return Check(
        "photon tracer",
        f"{row.case}/{row.finish}",
        f"az {row.azimuth_deg:g} el {row.elevation_deg:g}",
        (
            Measure("force", row.force_difference, TOLERANCE),
            Measure("torque", row.torque_difference, TOLERANCE),
            Measure("power", row.power_difference, TOLERANCE),
            Measure("tracer sigma (force)", row.force_mc_sigma, SIGMA_SHARE * TOLERANCE),
            Measure("tracer sigma (torque)", row.torque_mc_sigma, SIGMA_SHARE * TOLERANCE),
        ),
    )


def direct_law_checks(quick: bool) -> Iterator[Check]:
    """Check ``reflections="none"`` against the tracer capped at one interaction, and the direct split.

    The mixed finish at every Sun direction (quick: each case's first), and the full result's split
    into direct and reflected parts.

    Parameters
    ----------
    quick : bool
        Run the quick subset.

    Yields
    ------
    Check
        One check per case and condition, computed when asked for.

    Examples
    --------
    >>> check = next(direct_law_checks(quick=True))
    >>> check.case, check.passed
    ('v-groove/mixed', True)
    """
    for case in CONCAVE_CASES:
        craft = case.spacecraft("mixed")
        for sun in case.suns_deg[:1] if quick else case.suns_deg:
            mc = trace_case(case, "mixed", sun, photons=DIRECT_PHOTONS, max_bounces=1)
            u, ref = sun_from_az_el(*sun), mc.reference_point_m
            none = srp(craft, u, reference_point_m=ref, reflections="none")
            full = srp(craft, u, reference_point_m=ref, reflections="full")
            f_mc = float(np.linalg.norm(mc.force_N))
            scale = torque_scale(mc.force_N, mc.torque_Nm, case.size_m)
            direct_gap = max(
                _relative(full.direct_force_N, none.force_N), _relative(full.direct_torque_Nm, none.torque_Nm)
            )
            split_gap = max(
                _relative(full.direct_force_N + full.reflected_force_N, full.force_N),
                _relative(full.direct_torque_Nm + full.reflected_torque_Nm, full.torque_Nm),
            )
            yield Check(
                "direct law",
                f"{case.name}/mixed",
                f"az {sun[0]:g} el {sun[1]:g}",
                (
                    Measure("force", float(np.linalg.norm(none.force_N - mc.force_N)) / f_mc, TOLERANCE),
                    Measure(
                        "torque", float(np.linalg.norm(none.torque_Nm - mc.torque_Nm)) / scale, TOLERANCE
                    ),
                    Measure("incident power", abs(none.power.incident_W / mc.incident_W - 1), TOLERANCE),
                    Measure("tracer sigma (force)", mc.force_error_N / f_mc, SIGMA_SHARE * TOLERANCE),
                    Measure("full's direct part", direct_gap, 1e-9),
                    Measure("direct + reflected", split_gap, 1e-12),
                ),
            )


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    """``|a - b| / |b|`` [-]."""
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))
