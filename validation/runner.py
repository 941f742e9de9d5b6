"""Run every validation family and report each case's worst check against its limit.

``python -m sunwind.validation.runner [--quick] [--json] [--family NAME ...]`` (or ``sunwind validate``)
prints one line per
case (the family, the case, where its worst check is, that check's measure against its limit) and
ends with ``N passed, M failed`` over the checks; the exit status is 1 when any failed. ``--quick``
runs a subset of the cases, and the tracers at fewer particles, with the same limits.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections.abc import Callable, Sequence

from sunwind.geometry.errors import InputError
from sunwind.validation import gas_checks, light_checks
from sunwind.validation.checks import Check, Family, Measure

#: Every validation family, in the order they run.
FAMILIES: tuple[Family, ...] = (
    Family(
        "SRP closed forms", "analytic_srp: 7 convex bodies x 4 finishes", light_checks.srp_closed_form_checks
    ),
    Family(
        "partial shadow",
        "analytic_shadow: the exact shadow of one plate on another",
        light_checks.shadow_checks,
    ),
    Family(
        "low-polygon shadows",
        "exact_shadow: lit polygons of a 12-triangle bus, a wing and a 1 cm strut by clipping",
        light_checks.low_poly_checks,
    ),
    Family("mesh refinement", "second-order fall of the faceting error", light_checks.refinement_checks),
    Family(
        "V-groove closed form", "analytic_v_groove: mirror inter-reflection", light_checks.v_groove_checks
    ),
    Family("photon tracer", "photon_tracer: inter-reflection on concave shapes", light_checks.tracer_checks),
    Family("direct law", "photon_tracer capped at one interaction", light_checks.direct_law_checks),
    Family(
        "drag closed forms",
        "analytic_drag: 7 convex bodies x 3 gas-surface laws",
        gas_checks.drag_closed_form_checks,
    ),
    Family(
        "concave drag (TPMC)",
        "drag_matrix: 5 concave shapes x 5 laws x 5 speed ratios, and a mixture",
        gas_checks.concave_drag_checks,
    ),
    Family("TPMC closed forms", "the molecule tracer against plates and spheres", gas_checks.tpmc_checks),
)

Progress = Callable[[str], None]


def run(
    quick: bool = False, progress: Progress | None = None, families: Sequence[str] | None = None
) -> list[Check]:
    """Run every check of every family in :data:`FAMILIES` (or of those named).

    A family that raises ends with one failed check naming the error, and the run goes on.

    Parameters
    ----------
    quick : bool
        Run the subset of the cases, the tracers at fewer particles.
    progress : callable, optional
        ``progress(line)`` hears each family's start and end.
    families : sequence of str, optional
        Names of the families to run (:data:`FAMILIES`); default every one.

    Returns
    -------
    list of Check
        Every check, family by family.

    Raises
    ------
    InputError
        A family name that is not in :data:`FAMILIES`.

    Examples
    --------
    The whole quick run takes about half a minute on two cores; one family takes a second:

    >>> checks = run(quick=True, families=["V-groove closed form"])
    >>> summary(checks)  # doctest: +ELLIPSIS
    '... passed, 0 failed'
    """
    chosen = selected(families)
    checks: list[Check] = []
    for k, family in enumerate(chosen, start=1):
        start = time.perf_counter()
        if progress:
            progress(f"[{k}/{len(chosen)}] {family.name}: {family.reference} ...")
        done = _family_checks(family, quick)
        checks += done
        if progress:
            failed = sum(not c.passed for c in done)
            seconds = time.perf_counter() - start
            progress(
                f"[{k}/{len(chosen)}] {family.name}: {len(done)} checks, {failed} failed, {seconds:.1f} s"
            )
    return checks


def selected(families: Sequence[str] | None) -> tuple[Family, ...]:
    """The families of :data:`FAMILIES` named in ``families``, in their running order; all for None.

    Parameters
    ----------
    families : sequence of str or None
        Family names, as :data:`FAMILIES` spells them.

    Returns
    -------
    tuple of Family

    Raises
    ------
    InputError
        A name that is no family's.

    Examples
    --------
    >>> [family.name for family in selected(["photon tracer", "direct law"])]
    ['photon tracer', 'direct law']
    >>> selected(["drag"])
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: no validation family is called 'drag'; ...
    """
    if families is None:
        return FAMILIES
    names = [family.name for family in FAMILIES]
    unknown = [name for name in families if name not in names]
    if unknown:
        raise InputError(
            f"no validation family is called {unknown[0]!r}",
            hint="the families: " + ", ".join(names),
            parameters=("families",),
        )
    return tuple(family for family in FAMILIES if family.name in families)


def _family_checks(family: Family, quick: bool) -> list[Check]:
    """The family's checks; one that raises ends the family with a failed check naming the error."""
    done: list[Check] = []
    try:
        done.extend(family.checks(quick))
    except Exception as error:  # a family that breaks is a failed check, not a lost run
        stopped = Measure("family completed", 0.0, 1.0, low=1.0)
        done.append(Check(family.name, "(stopped)", f"{type(error).__name__}: {error}"[:60], (stopped,)))
    return done


def cases(checks: Sequence[Check]) -> list[tuple[Check, int, int]]:
    """Group checks by (family, case), in order of first appearance.

    Parameters
    ----------
    checks : sequence of Check
        The checks, e.g. from :func:`run`.

    Returns
    -------
    list of (Check, int, int)
        Per case: its worst check (the one using most of a limit), its check count and its failures.

    Examples
    --------
    >>> a = Check("F", "case", "x", (Measure("m", 0.1, 1.0),))
    >>> b = Check("F", "case", "y", (Measure("m", 2.0, 1.0),))
    >>> [(worst.at, count, failed) for worst, count, failed in cases([a, b])]
    [('y', 2, 1)]
    """
    grouped: dict[tuple[str, str], list[Check]] = {}
    for check in checks:
        grouped.setdefault((check.family, check.case), []).append(check)
    return [
        (max(group, key=lambda c: c.worst.share), len(group), sum(not c.passed for c in group))
        for group in grouped.values()
    ]


def summary(checks: Sequence[Check]) -> str:
    """Count the passed and failed checks.

    Parameters
    ----------
    checks : sequence of Check
        The checks.

    Returns
    -------
    str
        ``"N passed, M failed"``.

    Examples
    --------
    >>> ok, bad = Measure("m", 0.1, 1.0), Measure("m", 2.0, 1.0)
    >>> summary([Check("F", "c", "x", (ok,)), Check("F", "c", "y", (bad,))])
    '1 passed, 1 failed'
    """
    failed = sum(not c.passed for c in checks)
    return f"{len(checks) - failed} passed, {failed} failed"


def table(checks: Sequence[Check]) -> list[str]:
    """Lay out the printed report: a header, one line per case (its worst check), the summary line.

    Parameters
    ----------
    checks : sequence of Check
        The checks.

    Returns
    -------
    list of str
        The lines, without line breaks.

    Examples
    --------
    >>> lines = table([Check("F", "c", "y", (Measure("m", 2.0, 1.0),))])
    >>> lines[1].endswith("FAIL (1)"), lines[-1]
    (True, '0 passed, 1 failed')
    """
    head = f"{'family':<21} {'case':<34} {'checks':>6}  {'worst at':<36} {'measure':<22}"
    lines = [f"{head} {'value':>9} {'limit':>9}"]
    for worst, count, failed in cases(checks):
        measure = worst.worst
        lines.append(
            f"{worst.family:<21} {worst.case:<34} {count:>6}  {worst.at:<36} {measure.name:<22} "
            f"{measure.value:>9.2e} {measure.limit:>9.3g}" + (f"  FAIL ({failed})" if failed else "")
        )
    return [*lines, summary(checks)]


def main(argv: Sequence[str] | None = None) -> int:
    """Run the validation from the command line and print the table (or ``--json``).

    Parameters
    ----------
    argv : sequence of str, optional
        ``[--quick] [--json] [--family NAME ...]``; default ``sys.argv[1:]``.

    Returns
    -------
    int
        The exit status: 1 if any check failed, else 0.

    Examples
    --------
    >>> main(["--quick", "--family", "V-groove closed form"])  # doctest: +ELLIPSIS
    family ... passed, 0 failed
    0
    """
    parser = argparse.ArgumentParser(prog="python -m sunwind.validation.runner", description=__doc__)
    parser.add_argument(
        "--quick", action="store_true", help="a subset of the cases, the tracers at fewer particles"
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument(
        "--family",
        action="append",
        default=None,
        choices=[family.name for family in FAMILIES],
        metavar="NAME",
        help="run this family only (repeatable)",
    )
    args = parser.parse_args(argv)
    return report(args.quick, args.json, args.family)


def report(quick: bool, as_json: bool, families: Sequence[str] | None = None) -> int:
    """Run the validation and print the table or a JSON object, with progress on stderr.

    Parameters
    ----------
    quick : bool
        Run the subset of the cases.
    as_json : bool
        Print one JSON object instead of the table.
    families : sequence of str, optional
        The families to run (:func:`run`); default every one.

    Returns
    -------
    int
        The exit status: 1 if any check failed, else 0.

    Examples
    --------
    >>> report(quick=True, as_json=True, families=["V-groove closed form"])  # doctest: +ELLIPSIS
    {...
    0
    """
    checks = run(quick, _to_stderr, families)
    if as_json:
        failed = sum(not c.passed for c in checks)
        document = {
            "quick": quick,
            "passed": len(checks) - failed,
            "failed": failed,
            "checks": [c.to_json() for c in checks],
        }
        print(json.dumps(document, indent=2))
    else:
        print("\n".join(table(checks)))
    return 1 if any(not c.passed for c in checks) else 0


if __name__ == "__main__":
    sys.exit(main())


def _to_stderr(line: str) -> None:
    """A progress line on standard error, prefixed ``validate:``."""
    print(f"validate: {line}", file=sys.stderr, flush=True)
