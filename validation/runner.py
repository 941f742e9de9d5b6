"""Run the validation cases through the solver and tabulate case, reference, computed and error.

``python -m sunwind.validation.runner`` (or ``sunwind validate``) prints the table the README quotes.
"""

from __future__ import annotations

import itertools
import sys
from dataclasses import dataclass

import numpy as np

from sunwind.forces.radiation.law import SOLAR_FLUX_1AU, radiation_pressure
from sunwind.forces.srp import srp
from sunwind.validation.cases import REFINEMENT_CASES, SHADOW_CASE, SRP_CASES, ShadowCase, SrpCase


@dataclass(frozen=True)
class Row:
    """One case at one Sun direction."""

    case: str
    sun: str
    reference: float
    computed: float
    force_error: float
    torque_error: float
    tolerance: float

    @property
    def passed(self) -> bool:
        return self.force_error <= self.tolerance and self.torque_error <= self.tolerance


def run_srp_case(case: SrpCase, refinement: float = 1.0) -> list[Row]:
    """Solver against closed form at every direction of ``case``; torques about the origin."""
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
    """Solver against the exact partial shadow; errors on plate A relative to its own loads."""
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
    """Largest force error over the case's directions at each refinement (coarse to fine)."""
    return [max(row.force_error for row in run_srp_case(case, f)) for f in refinements]


def main() -> int:
    """Print the validation table; exit non-zero if any case fails."""
    print(
        f"{'case':<34} {'worst Sun':<22} {'|F| ref [N]':>12} {'|F| [N]':>12} "
        f"{'F error':>9} {'M error':>9} {'tol':>7}"
    )
    failed = 0
    for rows in [run_srp_case(case) for case in SRP_CASES] + [run_shadow_case()]:
        worst = max(rows, key=lambda r: max(r.force_error, r.torque_error))
        failed += sum(not r.passed for r in rows)
        print(
            f"{worst.case:<34} {worst.sun:<22} {worst.reference:>12.5e} {worst.computed:>12.5e} "
            f"{worst.force_error:>9.2e} {worst.torque_error:>9.2e} {worst.tolerance:>7.0e}"
            f"{'' if all(r.passed for r in rows) else '  FAIL'}"
        )
    print("\nrefinement (force error at 1/16, 1/8, 1/4 of the default resolution; observed order):")
    for case in REFINEMENT_CASES:
        errors = refinement_study(case)
        orders = [np.log2(a / b) for a, b in itertools.pairwise(errors)]
        print(
            f"  {case.name:<32} "
            + "  ".join(f"{e:.2e}" for e in errors)
            + "   order "
            + "  ".join(f"{o:.2f}" for o in orders)
        )
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
