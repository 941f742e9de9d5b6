"""The shadow pass checks itself: rays at random points of random sides, asked of what the pass said,
sides found wrong resolved again by rays alone, and what was found turned into an error estimate.

METHOD.md "Shadowing and sampling", its certificate. The check shares no assumption with the
outline method: it needs no silhouette, neighbour, winding or crossing, only rays. Sides are drawn
with probability ``p`` in proportion to their area (an area-weighted Poisson sample, the same for a
model and direction: deterministic), each is asked at ``CHECK_POINTS`` stratified random points, and
each point's ray is compared with what the pass says there (a side's uniform state, or its leaves).
A side that disagrees is resolved again without trusting the outline (:func:`~.quadtree.resolve_sides`
with ``TRUST`` off and a floor depth), and its neighbours are checked next, as errors come in groups.
This is done in ``CHECK_ROUNDS`` independent rounds, each with its own sample; the errors the last
round finds, weighted by ``1 / p`` (each side stands for itself and the sides like it not drawn),
estimate the error the rounds before it left (a Horvitz-Thompson estimate; the last round's repairs
only lessen it), and the chords' bands bound the error of their resolution:
:meth:`ShadowCheck.loads_error` turns both into force and torque for any per-area load.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.rays.leaf_kernels import DARK, EITHER, LIT
from sunwind.geometry.rays.mesh_edges import side_corners
from sunwind.geometry.rays.quadtree import Caster, Leaves, Segments, resolve_sides
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.triangles import STRATIFIED_SEED

#: Points each checked side is asked at (stratified: one in each of the four quarters of the side).
CHECK_POINTS = 4
#: Rays the check's samples may cast, as a share of the pass's own (resolving sides again comes on top).
CHECK_SHARE = 0.15
#: Independent rounds of checking: each draws its own sample and repairs what it finds; the estimate
#: is the last round's, of the error the rounds before it left.
CHECK_ROUNDS = 2
#: Fewest sides checked per round (all of them on a model with fewer facing sides).
LEAST_CHECKED = 32
#: Depth a side found wrong is first split to, and most rounds of resolving it again (each two deeper).
FALLBACK_FLOOR, FALLBACK_ROUNDS = 2, 2
#: Rounds of checking the neighbours of sides found wrong.
NEIGHBOUR_ROUNDS = 2
#: Decimals a direction is rounded to before it seeds the check's draws.
DRAW_DIGITS = 9
#: How many standard deviations of the sample estimate the error estimate adds.
SPREAD = 2.0
_QUARTERS = np.array(
    [
        [[0, 0], [0.5, 0], [0, 0.5]],
        [[0.5, 0], [1, 0], [0.5, 0.5]],
        [[0, 0.5], [0.5, 0.5], [0, 1]],
        [[0.5, 0.5], [0, 0.5], [0.5, 0]],
    ]
)


@dataclass(frozen=True)
class LoadsError:
    """Estimated error of a force and torque summed over the lit parts of the sides (absolute).

    Attributes
    ----------
    force_N : float
        Error of the force [N].
    torque_Nm : float
        Error of the torque [N m].

    Examples
    --------
    >>> LoadsError(force_N=1e-9, torque_Nm=2e-9)
    LoadsError(force_N=1e-09, torque_Nm=2e-09)
    """

    force_N: float
    torque_Nm: float


@dataclass(frozen=True, eq=False)
class ShadowCheck:
    """What the shadow pass's check found, to estimate the pass's error for any load.

    Attributes
    ----------
    sides : (m,) int64
        Sides of the last round's random sample, checked at points.
    probability : (m,) float64
        Chance ``p`` each side had to be drawn: each stands for itself and ``1 / p - 1`` sides like it
        not drawn.
    area_m2 : (m,) float64
        Lit area the pass gave the side less the lit area its check points give it (signed) [m^2].
    moment_m3 : (m, 3) float64
        The first moment of that difference [m^3]: sum of ``+-dA x`` over the disagreeing points.
    band_sides : (k,) int64, band_m2 : (k,) float64
        Sides cut along chords and the area of their chords' bands [m^2], where a chord may be off.
    rays : int
        Rays the check cast, those resolving sides again included.
    wrong : int
        Sides found wrong and resolved again, in all rounds.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> from sunwind.geometry.rays.shadows import side_sampler
    >>> check = side_sampler(craft).illuminate(direction).check
    >>> len(check.sides), check.rays, check.wrong  # 29 sides checked, none found wrong
    (29, 268, 0)
    """

    sides: NDArray[np.int64]
    probability: NDArray[np.float64]
    area_m2: NDArray[np.float64]
    moment_m3: NDArray[np.float64]
    band_sides: NDArray[np.int64]
    band_m2: NDArray[np.float64]
    rays: int
    wrong: int

    @property
    def needed(self) -> NDArray[np.int64]:
        """The sides whose loads :meth:`loads_error` reads: the sample's and the chords'.

        Returns
        -------
        (k,) ndarray of int64
            The union of :attr:`sides` and :attr:`band_sides`, ascending.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> from sunwind.geometry.rays.shadows import side_sampler
        >>> check = side_sampler(craft).illuminate(direction).check
        >>> bool(np.array_equal(check.needed, np.union1d(check.sides, check.band_sides)))
        True
        """
        return np.union1d(self.sides, self.band_sides)

    def loads_error(
        self,
        craft: Spacecraft,
        load_per_area: NDArray[np.float64],
        reference_m: NDArray[np.float64],
    ) -> LoadsError:
        """Estimate the error of a force and torque summed over the lit parts of the sides.

        The estimate is ``sum |y| / p + SPREAD * sqrt(sum ((1 - p) / p^2 + 1 / p) |y|^2)`` over the last
        round's sample, ``y`` the errors its points found (the first term an unbiased estimate of the sum of
        the sides' error magnitudes that the rounds before it left, which bounds their sum and which its own
        repairs only lessen), plus the chords' bands times the load on them (their resolution).

        Parameters
        ----------
        craft : Spacecraft
            The model the pass ran on.
        load_per_area : (n_sides, 3) ndarray of float64
            Force on a unit lit area of each side [N/m^2]; only rows :attr:`needed` are read.
        reference_m : (3,) ndarray of float64
            Point the torques are about [m].

        Returns
        -------
        LoadsError
            Absolute error estimates [N, N m].

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> from sunwind.geometry.rays.shadows import side_sampler
        >>> check = side_sampler(craft).illuminate(direction).check
        >>> load = np.tile([0.0, 0.0, -4.5e-6], (craft.n_sides, 1))
        >>> check.loads_error(craft, load, np.zeros(3))
        LoadsError(force_N=0.0, torque_Nm=0.0)
        """
        f = load_per_area[self.sides]
        force = self.area_m2[:, None] * f
        torque = np.cross(self.moment_m3 - self.area_m2[:, None] * reference_m, f)
        p = np.maximum(self.probability, 1e-300)
        # the spread of drawing the sides, and of the few points on each (about the error found itself)
        spread = (1 - p) / p**2 + 1 / p
        out = []
        for y in (force, torque):
            total = (np.linalg.norm(y, axis=1) / p).sum()
            total += SPREAD * np.sqrt((spread * (y**2).sum(axis=1)).sum())
            out.append(float(total))
        band = np.linalg.norm(load_per_area[self.band_sides], axis=1) * self.band_m2
        arm = np.linalg.norm(craft.side_centroids[self.band_sides] - reference_m, axis=1)
        arm += np.sqrt(craft.side_areas[self.band_sides])
        return LoadsError(out[0] + float(band.sum()), out[1] + float((band * arm).sum()))


def check_pass(
    caster: Caster,
    leaves: Leaves,
    facing: NDArray[np.int64],
    fraction: NDArray[np.float64],
    segments: Segments,
    tolerance: float,
) -> tuple[Leaves, ShadowCheck]:
    """Check the shadow pass with rays at random points of an area-weighted sample of the facing sides.

    The sides found wrong are resolved again (and their neighbours checked), in ``CHECK_ROUNDS``
    independent rounds. The samples cast about ``CHECK_SHARE`` of the rays the pass did
    (``caster.rays`` so far).

    Parameters
    ----------
    caster : Caster
        Casts the rays and counts them.
    leaves : Leaves
        The leaves of the sides the pass refined.
    facing : (n_facing,) ndarray of int64
        The sides facing the source.
    fraction : (n_sides,) ndarray of float64
        The pass's lit shares by side: uniform sides 0 or 1, the sides of ``leaves`` by their leaves.
    segments : Segments
        The outline segments.
    tolerance : float
        Share of a side's area a side resolved again is found to.

    Returns
    -------
    leaves : Leaves
        ``leaves`` with the sides found wrong replaced.
    check : ShadowCheck
        What the last round's sample found.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> from sunwind.geometry.rays.quadtree import Caster, Leaves, Segments
    >>> facing = np.flatnonzero(craft.side_normals @ direction > 0)
    >>> all_lit = np.where(craft.side_normals @ direction > 0, 1.0, 0.0)  # a pass that missed every shadow
    >>> none = Segments.of(np.zeros(0, np.int64), np.zeros((0, 2, 2)))
    >>> leaves, check = check_pass(Caster(craft, direction), Leaves.empty(), facing, all_lit, none, 1e-2)
    >>> check.wrong, leaves.sides[:4]  # the shaded sides found and resolved again
    (14, array([24, 26, 28, 30]))
    """
    craft = caster.craft
    budget = max(LEAST_CHECKED, int(CHECK_SHARE * caster.rays / CHECK_POINTS / CHECK_ROUNDS))
    start_rays = caster.rays
    probability = _probabilities(craft, facing, budget)
    wrong_count = 0
    for round_ in range(CHECK_ROUNDS):
        drawn = _draw(craft, facing, caster.direction, round_, probability)
        sides, p = facing[drawn], probability[drawn]
        area, moment, points, truth = _ask(caster, leaves, sides, fraction, round_)
        sample = (sides, p, area, moment)
        checked = np.zeros(craft.n_sides, dtype=bool)
        checked[sides] = True
        for neighbour_round in range(NEIGHBOUR_ROUNDS + 1):
            wrong = np.flatnonzero(area != 0)
            if not len(wrong):
                break
            leaves = _resolve_again(
                caster, leaves, sides[wrong], points[wrong], truth[wrong], fraction, segments, tolerance
            )
            wrong_count += len(wrong)
            if neighbour_round == NEIGHBOUR_ROUNDS:
                break
            near = _neighbours(craft, sides[wrong], facing)
            sides = near[~checked[near]]
            checked[sides] = True
            area, moment, points, truth = _ask(caster, leaves, sides, fraction, round_)
    sides, p, area, moment = sample
    band = leaves.band_share()
    has_band = band > 0
    check = ShadowCheck(
        sides=sides,
        probability=p,
        area_m2=area,
        moment_m3=moment,
        band_sides=leaves.sides[has_band],
        band_m2=band[has_band] * craft.side_areas[leaves.sides[has_band]],
        rays=caster.rays - start_rays,
        wrong=wrong_count,
    )
    return leaves, check


def _probabilities(craft: Spacecraft, facing: NDArray[np.int64], budget: int) -> NDArray[np.float64]:
    """Chance of each facing side to be checked: in proportion to its area, ``budget`` sides in all
    expected (sides whose share would exceed 1 are checked for sure, the rest shared out again)."""
    if budget >= len(facing):
        return np.ones(len(facing))
    return _area_shares(craft.side_areas, facing, float(budget))


@numba.njit(cache=True, nogil=True)
def _area_shares(areas: NDArray[np.float64], facing: NDArray[np.int64], budget: float) -> NDArray[np.float64]:
    """:func:`_probabilities`: ``min(1, c a)`` for the areas ``a`` of ``facing``, ``c`` such that they
    sum to ``budget`` (found by raising to 1 the shares above 1 and sharing the rest again)."""
    n = facing.shape[0]
    p = np.empty(n)
    sure = np.zeros(n, dtype=np.bool_)
    n_sure = 0
    for _ in range(8):
        rest = 0.0
        for k in range(n):
            if not sure[k]:
                rest += areas[facing[k]]
        scale = (budget - n_sure) / max(rest, 1e-300)
        more = 0
        for k in range(n):
            if sure[k]:
                p[k] = 1.0
                continue
            p[k] = scale * areas[facing[k]]
            if p[k] > 1.0:
                sure[k] = True
                more += 1
        if more == 0:
            break
        n_sure += more
    for k in range(n):
        p[k] = min(p[k], 1.0)
    return p


def _draw(
    craft: Spacecraft,
    facing: NDArray[np.int64],
    direction: NDArray[np.float64],
    round_: int,
    probability: NDArray[np.float64],
) -> NDArray[np.int64]:
    """Rows of ``facing`` drawn, each with its ``probability``, fixed for the model, direction and
    round: a uniform number per side (the model's, drawn once from a fixed seed, turned by one drawn
    from the direction's bits) below its probability."""
    numbers = craft.cache.get(
        "check numbers", lambda: np.random.default_rng(STRATIFIED_SEED).random(craft.n_sides)
    )
    turn = np.random.default_rng([round_, *_bits(direction)]).random()
    return _below(numbers, facing, turn, probability)


@numba.njit(cache=True, nogil=True)
def _below(
    numbers: NDArray[np.float64], facing: NDArray[np.int64], turn: float, probability: NDArray[np.float64]
) -> NDArray[np.int64]:
    """:func:`_draw`: the rows ``k`` where ``(numbers[facing[k]] + turn) mod 1 < probability[k]``."""
    out = np.empty(facing.shape[0], dtype=np.int64)
    count = 0
    for k in range(facing.shape[0]):
        x = numbers[facing[k]] + turn
        if x >= 1.0:
            x -= 1.0
        if x < probability[k]:
            out[count] = k
            count += 1
    return out[:count]


def _bits(direction: NDArray[np.float64]) -> NDArray[np.uint32]:
    """Seed words of a direction, rounded to ``DRAW_DIGITS`` decimals first: the same draws for the
    same direction however it was computed (a frame rotated and back differs in the last bits)."""
    rounded = np.round(np.asarray(direction, dtype=np.float64), DRAW_DIGITS) + 0.0  # no -0.0
    return np.frombuffer(rounded.tobytes(), np.uint32)


def _points(sides: NDArray[np.int64], direction: NDArray[np.float64], round_: int) -> NDArray[np.float64]:
    """``CHECK_POINTS`` stratified random points (one in each quarter) of each side, (k, 4, 2), drawn
    from the direction and round (deterministic)."""
    rng = np.random.default_rng([STRATIFIED_SEED, round_, *_bits(direction)])
    r = rng.random((len(sides), CHECK_POINTS, 2))
    r = np.where(r.sum(axis=2, keepdims=True) > 1, 1 - r, r)
    q = _QUARTERS[None]
    return (
        q[..., 0, :] + r[..., :1] * (q[..., 1, :] - q[..., 0, :]) + r[..., 1:] * (q[..., 2, :] - q[..., 0, :])
    )


def _ask(
    caster: Caster,
    leaves: Leaves,
    sides: NDArray[np.int64],
    fraction: NDArray[np.float64],
    round_: int,
) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """Cast the check points of ``sides``; return per side the signed lit-area difference (pass less
    rays) [m^2], its first moment [m^3], the points (k, 4, 2) and their rays' flags (k, 4)."""
    craft = caster.craft
    points = _points(sides, caster.direction, round_)
    truth = caster.lit(np.repeat(sides, CHECK_POINTS), points.reshape(-1, 2)).reshape(-1, CHECK_POINTS)
    said = np.where(fraction[sides] > 0.5, LIT, DARK).astype(np.int8)[:, None].repeat(CHECK_POINTS, 1)
    index = leaves.find(sides)
    refined = index >= 0
    if refined.any():
        ask = np.repeat(index[refined], CHECK_POINTS)
        said[refined] = leaves.states(ask, points[refined].reshape(-1, 2)).reshape(-1, CHECK_POINTS)
    differ = np.where(said == EITHER, 0, (said == LIT).astype(int) - truth.astype(int))
    dA = craft.side_areas[sides] / CHECK_POINTS
    a, b, c = np.moveaxis(craft.triangles[craft.side_facet[sides]], 1, 0)
    x = a[:, None] + points[..., :1] * (b - a)[:, None] + points[..., 1:] * (c - a)[:, None]
    area = dA * differ.sum(axis=1)
    moment = dA[:, None] * (differ[..., None] * x).sum(axis=1)
    return area, moment, points, truth


def _resolve_again(
    caster: Caster,
    leaves: Leaves,
    sides: NDArray[np.int64],
    points: NDArray[np.float64],
    truth: NDArray[np.bool_],
    fraction: NDArray[np.float64],
    segments: Segments,
    tolerance: float,
) -> Leaves:
    """``leaves`` with ``sides`` resolved again by rays alone, deeper each round, until their leaves
    agree with the check rays ``truth`` at ``points`` (k, 4, 2) that found them out."""
    order = np.argsort(sides)
    sides, points, truth = sides[order], points[order], truth[order]
    floor = FALLBACK_FLOOR
    for _ in range(FALLBACK_ROUNDS):
        centre = fraction[sides] > 0.5
        again = resolve_sides(
            caster, sides, centre, np.zeros(len(sides), np.int8), floor, segments, tolerance
        )
        said = again.states(np.repeat(np.arange(len(sides)), CHECK_POINTS), points.reshape(-1, 2))
        said = said.reshape(-1, CHECK_POINTS)
        leaves = leaves.replaced(again)
        still = ((said == LIT) & ~truth | (said == DARK) & truth).any(axis=1)
        if not still.any():
            break
        sides, points, truth = sides[still], points[still], truth[still]
        floor += 2
    return leaves


def _neighbours(craft: Spacecraft, sides: NDArray[np.int64], facing: NDArray[np.int64]) -> NDArray[np.int64]:
    """The facing sides sharing a corner with any of ``sides``, those excluded."""
    ids, start, at = side_corners(craft)
    corners = np.unique(ids[sides].reshape(-1))
    count = start[corners + 1] - start[corners]
    rows = np.repeat(start[corners] - np.cumsum(count) + count, count) + np.arange(count.sum())
    near = np.unique(at[rows])
    is_facing = np.zeros(craft.n_sides, dtype=bool)
    is_facing[facing] = True
    near = near[is_facing[near]]
    return np.setdiff1d(near, sides)
