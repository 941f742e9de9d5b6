"""The matrix of issue 19: the drag solver against the TPMC tracer on concave shapes, every case, law,
speed ratio and flow direction, and the NRLMSIS mixture.

:func:`matrix` lists the points (:data:`SPEED_RATIOS` of atomic oxygen for every case and law of
:mod:`sunwind.validation.concave_drag`, and the open box in the 900 km NRLMSIS mixture with two laws);
:func:`run_point` compares solver and tracer at one, with the tracer's molecules chosen by
:func:`molecules_for`; :func:`markdown_table` sums the rows up for the validation page.
``python -m sunwind.validation.drag_matrix [--quick]`` prints that table and the times.

Notes
-----
**Molecule counts.** The tracer's standard error of a row must stay within ``SIGMA_SHARE`` of the
tolerance (0.5 %), and grows at low speed ratio, with specular walls and with many bounces, so each
row is first traced in a pilot of :data:`PILOT_MOLECULES` per species (its own seed), then once at the
count that brings the pilot's standard errors to :data:`SIGMA_AIM` of that limit, as
``sigma ~ 1 / sqrt(N)``. In a mixture the species share the budget: with ``a_k`` a species' pilot
standard error over the row's scale, ``N_k = N_0 a_k (sum_j a_j) / aim^2`` is the least total count
whose errors, added in quadrature, reach the aim (:func:`allocate`), taken for force and torque
alike. A standard error from :data:`~sunwind.validation.concave_drag.BATCHES` batches scatters by
11 %, the pilot's and the run's together by 16 %, so aiming at 0.6 of the limit leaves 3.2 of those
scatters before a row's run overshoots it. Measured over the full matrix (381 rows): runs of 0.11 to
0.96 million molecules (139 million in all, the pilots 17 million more), standard errors 0.30 % in the
median and 0.41 % at worst (0.82 of the limit), the torque's mostly the larger.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.validation.concave import torque_scale
from sunwind.validation.concave_drag import (
    BATCHES,
    DRAG_CASES,
    LAWS,
    SIGMA_SHARE,
    TOLERANCE,
    DragCase,
    DragRow,
    Gas,
    compare,
    msis_mixture,
    oxygen,
    run_key,
    seed_of,
    summed,
    trace_gas,
)
from sunwind.validation.sampling import Sampling

#: Speed ratios of the single-species rows, and those of the quick subset.
SPEED_RATIOS, QUICK_SPEED_RATIOS = (1.5, 3.0, 5.0, 8.0, 15.0), (1.5, 8.0)
#: The mixture rows: the case, its laws (quick: the first) and the NRLMSIS altitude [km].
MIXTURE_CASE, MIXTURE_LAWS, MIXTURE_ALTITUDE_KM = "open box", ("diffuse", "cll-0.8"), 900.0
#: Molecules of each species' pilot run.
PILOT_MOLECULES = 40_000
#: Share of the standard-error limit the runs aim at (module Notes).
SIGMA_AIM = 0.6
#: Fewest and most molecules of one species' run.
MOLECULE_RANGE = (2_000, 8_000_000)


@dataclass(frozen=True, eq=False)
class Point:
    """One row of the matrix: a case, a law, a flow direction and a gas.

    Attributes
    ----------
    case : DragCase
        The shape.
    law : str
        A key of :data:`LAWS`.
    flow_deg : (float, float)
        Azimuth and elevation of ``v_rel`` [deg].
    gas : Gas
        The free stream.

    Examples
    --------
    >>> from sunwind.validation.concave_drag import DragCase, oxygen
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> tiny = DragCase("tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), ((0.0, 90.0),), size_m=3.0)
    >>> point = Point(tiny, "diffuse", (0.0, 90.0), oxygen(8.0))
    >>> point.gas.name
    'O, S 8'
    """

    case: DragCase
    law: str
    flow_deg: tuple[float, float]
    gas: Gas


def matrix(quick: bool = False) -> list[Point]:
    """List the points: atomic oxygen at each speed ratio for every case, law and flow, then the mixture.

    ``quick``: each case once, at its last flow (off every symmetry plane), with a law of its own and
    the :data:`QUICK_SPEED_RATIOS` in turn, and the mixture with its first law.

    Parameters
    ----------
    quick : bool, optional
        Return the quick subset.

    Returns
    -------
    list of Point
        The points in the order they are run.

    Examples
    --------
    >>> len(matrix()), len(matrix(quick=True))
    (381, 6)
    >>> [(p.case.name, p.law, p.gas.name) for p in matrix(quick=True)][:2]
    [('v-groove', 'diffuse', 'O, S 1.5'), ('L', 'maxwell-0.5', 'O, S 8')]
    """
    if quick:
        points = [
            Point(case, law, case.flows_deg[-1], oxygen(QUICK_SPEED_RATIOS[i % 2]))
            for i, (case, law) in enumerate(zip(DRAG_CASES, LAWS, strict=True))
        ]
    else:
        points = [
            Point(case, law, flow, oxygen(ratio))
            for case in DRAG_CASES
            for law in LAWS
            for ratio in SPEED_RATIOS
            for flow in case.flows_deg
        ]
    mixture_case = next(case for case in DRAG_CASES if case.name == MIXTURE_CASE)
    mixture = msis_mixture(MIXTURE_ALTITUDE_KM)
    laws = MIXTURE_LAWS[:1] if quick else MIXTURE_LAWS
    return points + [
        Point(mixture_case, law, flow, mixture) for law in laws for flow in _flows(mixture_case, quick)
    ]


def _flows(case: DragCase, quick: bool) -> tuple[tuple[float, float], ...]:
    return case.flows_deg[-1:] if quick else case.flows_deg


def allocate(sigma_shares: ArrayLike, pilot_molecules: int, aim: float) -> list[int]:
    """Count the molecules of each species so that their standard errors, in quadrature, come to ``aim``.

    Parameters
    ----------
    sigma_shares : (n_species, n_measures) array_like
        Each species' pilot standard error of each measure (force, torque) over the row's scale [-].
    pilot_molecules : int
        Molecules of each species' pilot.
    aim : float
        Standard error aimed at over the row's scale [-].

    Returns
    -------
    list of int
        ``N_k = max over measures of N_0 a_k (sum_j a_j) / aim^2`` (module Notes), rounded up to a
        multiple of the batches and kept within :data:`MOLECULE_RANGE`.

    Examples
    --------
    Two species, the second half as noisy as the first:

    >>> allocate([[0.1, 0.2], [0.05, 0.1]], pilot_molecules=40_000, aim=0.05)
    [960000, 480000]
    """
    shares = np.asarray(sigma_shares, dtype=np.float64)
    needed = (pilot_molecules * shares * shares.sum(axis=0) / aim**2).max(axis=1)
    low, high = MOLECULE_RANGE
    return [min(high, max(low, BATCHES * math.ceil(n / BATCHES))) for n in needed]


def pilot_shares(point: Point) -> NDArray[np.float64]:
    """Each species' pilot standard errors of force and torque over the pilot's ``|F|`` and torque scale.

    Runs :data:`PILOT_MOLECULES` of each species.

    Parameters
    ----------
    point : Point
        The case, law, flow direction and gas.

    Returns
    -------
    (n_species, 2) float64
        Standard error of the force and of the torque of each species over the row's scales [-].

    Examples
    --------
    >>> from sunwind.validation.concave_drag import DragCase, oxygen
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> tiny = DragCase("tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), ((0.0, 90.0),), size_m=3.0)
    >>> point = Point(tiny, "diffuse", (0.0, 90.0), oxygen(8.0))
    >>> pilot_shares(point).shape
    (1, 2)
    """
    samplings = {
        k: Sampling(PILOT_MOLECULES, seed_of(_pilot_key(point, k)), BATCHES) for k in point.gas.streams()
    }
    runs = trace_gas(point.case, point.law, point.flow_deg, point.gas, samplings)
    total = summed(runs)
    force = float(np.linalg.norm(total.force_N))
    scale = torque_scale(total.force_N, total.torque_Nm, point.case.size_m)
    return np.array([[r.force_error_N / force, r.torque_error_Nm / scale] for r in runs])


def _pilot_key(point: Point, species: str) -> str:
    return run_key(point.case, point.law, point.flow_deg, point.gas, species) + "/pilot"


def molecules_for(point: Point) -> dict[str, int]:
    """Count the molecules of each species' run at ``point``, from its pilot (module Notes).

    Parameters
    ----------
    point : Point
        The case, law, flow direction and gas.

    Returns
    -------
    dict of str to int
        Molecules of each species, within :data:`MOLECULE_RANGE`.

    Examples
    --------
    >>> from sunwind.validation.concave_drag import DragCase, oxygen
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> tiny = DragCase("tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), ((0.0, 90.0),), size_m=3.0)
    >>> point = Point(tiny, "diffuse", (0.0, 90.0), oxygen(8.0))
    >>> molecules = molecules_for(point)
    >>> list(molecules), MOLECULE_RANGE[0] <= molecules["O"] <= MOLECULE_RANGE[1]
    (['O'], True)
    """
    counts = allocate(pilot_shares(point), PILOT_MOLECULES, SIGMA_AIM * SIGMA_SHARE * TOLERANCE)
    return dict(zip(point.gas.streams(), counts, strict=True))


def run_point(point: Point) -> DragRow:
    """Compare solver and tracer at ``point``, the tracer's molecules from :func:`molecules_for`.

    Parameters
    ----------
    point : Point
        The case, law, flow direction and gas.

    Returns
    -------
    DragRow
        The row; its ``tracer_seconds`` include the pilot's.

    Examples
    --------
    A tiny groove (a couple of seconds: a pilot and a run of some 200 000 molecules):

    >>> from sunwind.validation.concave_drag import DragCase, oxygen
    >>> from sunwind.validation.concave_meshes import v_groove_mesh
    >>> tiny = DragCase("tiny groove", lambda: v_groove_mesh(divisions=(1, 2)), ((0.0, 90.0),), size_m=3.0)
    >>> point = Point(tiny, "diffuse", (0.0, 90.0), oxygen(8.0))
    >>> row = run_point(point)
    >>> row.case, row.passed
    ('tiny groove', True)
    """
    start = time.perf_counter()
    molecules = molecules_for(point)
    pilot_seconds = time.perf_counter() - start
    row = compare(point.case, point.law, point.flow_deg, point.gas, molecules)
    return replace(row, tracer_seconds=row.tracer_seconds + pilot_seconds)


def run_matrix(
    quick: bool = False, progress: Callable[[DragRow], None] | None = None, first: int | None = None
) -> list[DragRow]:
    """Run :func:`run_point` at every point of :func:`matrix` (or at its first few).

    Parameters
    ----------
    quick : bool, optional
        Run the quick subset only.
    progress : callable, optional
        ``progress(row)`` hears each row as it is done.
    first : int, optional
        Run only the first ``first`` points (a check of the machinery; a point takes seconds).

    Returns
    -------
    list of DragRow
        One row per point, in the matrix's order.

    Examples
    --------
    The quick subset takes minutes and the whole matrix hours; its first point, seconds:

    >>> rows = run_matrix(quick=True, first=1)
    >>> len(rows), all(row.passed for row in rows)
    (1, True)
    """
    rows = []
    for row in map(run_point, matrix(quick)[:first]):
        rows.append(row)
        if progress:
            progress(row)
    return rows


def gas_label(row: DragRow) -> str:
    """The row's gas and speed ratio: ``"O, S 8"``, or a mixture's name with each species' ``S``.

    Parameters
    ----------
    row : DragRow
        A row of the matrix.

    Returns
    -------
    str
        The label.

    Examples
    --------
    >>> from sunwind.validation.concave_drag import DragRow
    >>> row = DragRow("groove", "diffuse", 0.0, 90.0, "O, S 8", (("O", 8.0),), 8e-3, 0.004, 0.014, 0.003,
    ...               0.003, 0.002, 0.003, 214_560, 1.0, 2.0)
    >>> gas_label(row)
    'O, S 8'
    """
    if len(row.speed_ratios) == 1:
        return row.gas
    return f"{row.gas}: " + ", ".join(f"{k} {s:.2f}" for k, s in sorted(row.speed_ratios, key=lambda p: p[1]))


def _groups(rows: Sequence[DragRow]) -> Iterator[list[DragRow]]:
    """The rows grouped by case, law and gas, in order of first appearance."""
    grouped: dict[tuple[str, str, str], list[DragRow]] = {}
    for row in rows:
        grouped.setdefault((row.case, row.law, row.gas), []).append(row)
    yield from grouped.values()


#: The row fields whose worst value over a group's flows the table shows.
_WORST = (
    "force_difference",
    "force_difference_none",
    "torque_difference",
    "torque_difference_none",
    "force_mc_sigma",
    "torque_mc_sigma",
)


def _percent(value: float) -> str:
    return f"{100 * value:.2f} %"


def markdown_table(rows: Sequence[DragRow]) -> str:
    """Write the rows as a Markdown table, one line per case, law and gas.

    Each line gives its flows, the worst force and torque differences over them (with and without
    exchange), the worst tracer standard error, the molecules and the verdict; then the rows passed
    and the times.

    Parameters
    ----------
    rows : sequence of DragRow
        The rows of the matrix.

    Returns
    -------
    str
        The table and its :func:`summary`.

    Examples
    --------
    >>> from sunwind.validation.concave_drag import DragRow
    >>> row = DragRow("groove", "diffuse", 0.0, 90.0, "O, S 8", (("O", 8.0),), 8e-3, 0.004, 0.014, 0.003,
    ...               0.003, 0.002, 0.003, 214_560, 1.0, 2.0)
    >>> print(markdown_table([row]))  # doctest: +ELLIPSIS
    | case | law | gas, speed ratio | flows | force | ...
    |---|...
    | groove | diffuse | O, S 8 | 1 | 0.40 % | 1.40 % | 0.30 % | 0.20 % | 0.30 % | 0.21-0.21 M | pass |
    <BLANKLINE>
    1 of 1 rows passed ...
    """
    lines = [
        "| case | law | gas, speed ratio | flows | force | force, no exchange | torque | torque, no exchange "
        "| tracer σ | molecules | |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for group in _groups(rows):
        first = group[0]
        worst = {name: max(getattr(r, name) for r in group) for name in _WORST}
        sigma = max(worst["force_mc_sigma"], worst["torque_mc_sigma"])
        counts = [r.molecules for r in group]
        lines.append(
            f"| {first.case} | {first.law} | {gas_label(first)} | {len(group)} "
            f"| {_percent(worst['force_difference'])} | {_percent(worst['force_difference_none'])} "
            f"| {_percent(worst['torque_difference'])} | {_percent(worst['torque_difference_none'])} "
            f"| {_percent(sigma)} | {min(counts) / 1e6:.2f}-{max(counts) / 1e6:.2f} M "
            f"| {'pass' if all(r.passed for r in group) else 'FAIL'} |"
        )
    return "\n".join([*lines, "", summary(rows)])


def summary(rows: Sequence[DragRow]) -> str:
    """Count the rows passed and failed; give the tolerance, and the tracer's and solver's seconds in all.

    Parameters
    ----------
    rows : sequence of DragRow
        The rows of the matrix.

    Returns
    -------
    str
        One line.

    Examples
    --------
    >>> from sunwind.validation.concave_drag import DragRow
    >>> row = DragRow("groove", "diffuse", 0.0, 90.0, "O, S 8", (("O", 8.0),), 8e-3, 0.004, 0.014, 0.003,
    ...               0.003, 0.002, 0.003, 214_560, 1.0, 2.0)
    >>> summary([row])
    '1 of 1 rows passed (force and torque within 2.00 %, tracer σ within 0.50 %); tracer 1 s, solver 2 s'
    """
    failed = sum(not r.passed for r in rows)
    tracer, solver = sum(r.tracer_seconds for r in rows), sum(r.solver_seconds for r in rows)
    return (
        f"{len(rows) - failed} of {len(rows)} rows passed (force and torque within {_percent(TOLERANCE)}, "
        f"tracer σ within {_percent(SIGMA_SHARE * TOLERANCE)}); tracer {tracer:.0f} s, solver {solver:.0f} s"
    )


def main(argv: Sequence[str] | None = None) -> int:
    """Run the matrix, print its table and the wall-clock time; progress on stderr.

    Parameters
    ----------
    argv : sequence of str, optional
        Command-line arguments (``--quick``: the subset; ``--first N``: its first ``N`` points);
        default ``sys.argv[1:]``.

    Returns
    -------
    int
        0 when every row passed, else 1.

    Examples
    --------
    The quick subset takes minutes; its first point, seconds:

    >>> main(["--quick", "--first", "1"])  # doctest: +ELLIPSIS
    | ...
    total ... s
    0
    """
    parser = argparse.ArgumentParser(prog="python -m sunwind.validation.drag_matrix", description=__doc__)
    parser.add_argument(
        "--quick", action="store_true", help="each case once, at one flow, with a law of its own, S 1.5 or 8"
    )
    parser.add_argument("--first", type=int, default=None, metavar="N", help="run only the first N points")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    rows = run_matrix(args.quick, progress=_print_progress, first=args.first)
    print(markdown_table(rows))
    print(f"total {time.perf_counter() - start:.0f} s")
    return 0 if all(r.passed for r in rows) else 1


def _print_progress(row: DragRow) -> None:
    print(
        f"{row.case}/{row.law} {gas_label(row)} az {row.azimuth_deg:g} el {row.elevation_deg:g}: "
        f"force {_percent(row.force_difference)}, torque {_percent(row.torque_difference)}, "
        f"σ {_percent(max(row.force_mc_sigma, row.torque_mc_sigma))}, {row.molecules} molecules, "
        f"{row.tracer_seconds:.1f} + {row.solver_seconds:.1f} s",
        file=sys.stderr,
        flush=True,
    )


if __name__ == "__main__":
    sys.exit(main())
