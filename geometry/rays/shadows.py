"""Which share of each side a distant source lights, and where: shadow rays toward the source.

METHOD.md "Shadowing and sampling".

By default every side facing the source casts one ray from its centroid, and the sides a shadow edge
crosses get their lit polygon from :mod:`.shadow_edges` (rays at the corners of a quadtree of nodes,
each cut along the shadow's outline or a bisected chord) to ``tolerance`` of their area. On a flat
side under a uniform beam the force per unit lit area is the same everywhere, so the lit share and
the centroid of the lit part carry all that force and torque need.

Fixed sampling (``samples``) instead puts one point in each of a side's ``level**2`` congruent
sub-triangles (the centroid at level 1, a seeded stratified point above:
:func:`sunwind.geometry.triangles.subdivision_barycentric`) and takes the lit share of its points.

Transmissive sheets cast full shadows here: light they transmit is not traced onward.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry import triangles as tri
from sunwind.geometry.errors import InputError
from sunwind.geometry.memory import count, require
from sunwind.geometry.parallel import map_ranges
from sunwind.geometry.rays.certificate import ShadowCheck
from sunwind.geometry.rays.crossings import crossings
from sunwind.geometry.rays.quadtree import uncovered
from sunwind.geometry.rays.shadow_edges import refine_edges
from sunwind.geometry.rays.shadow_kernels import (
    BLOCK,
    facing_origins,
    lit_centroids,
    lit_shares,
    sample_origins,
)
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.triangles import STRATIFIED_SEED

#: Default share of a refined side's area that its lit part is found to (:mod:`.shadow_edges`).
DEFAULT_TOLERANCE = 1e-3
#: Tightest tolerance: the quadtree's depth limits grow as log4(1 / tolerance), and below this the
#: nodes along a thin shadow would run to millions.
MIN_TOLERANCE = 1e-6
#: Rays cast per batch when origins are made on the fly, to bound memory.
_BATCH_RAYS = 1 << 21

#: Something summed over facing sides once their lit shares are final:
#: ``reduce(sides, lit_share, lit_centroid)``, ``lit_share[k]`` the share of side ``sides[k]`` and
#: ``lit_centroid`` indexed by side. It may be called from several threads at once, each time on
#: whole blocks of :attr:`SideSampler.side_block`, each block's sides in ascending order.
Reduction = Callable[[NDArray[np.int64], NDArray[np.float64], NDArray[np.float64]], None]
#: Fewest blocks in a chunk of an attitude's parallel work.
_MIN_BLOCKS_PER_CHUNK = 8
#: Largest origin array (points) kept per level for reuse across attitudes.
_KEEP_POINTS = 1 << 22
#: Peak bytes per point of a level's barycentric sample points while they are made (measured 178).
_BARYCENTRIC_BYTES = 180
#: Bytes per ray of a batch cast from origins made on the fly: origins, Embree's answers, lit flags.
_BATCH_BYTES = 21
#: Bytes per point of the lit flags of all facing sides (the batches' and their concatenation).
_LIT_BYTES = 2


@dataclass(frozen=True, eq=False)
class Illumination:
    """The lit share of every side for one source direction.

    Attributes
    ----------
    direction : (3,) float64
        Unit vector toward the source, body frame (``u_sun``).
    side_normals : (n_sides, 3) float64
        Outward normal of each side (the model's array, not a copy).
    facing_runs, share_runs : tuple of arrays
        The sides with ``cos_incidence > 0`` (only these can be lit), int64, and the share of the
        area of each that is lit, float64 (or bool with one point per side), in runs as the threads
        found them; joined on first use as :attr:`facing` and :attr:`facing_share`.
    lit_centroid : (n_sides, 3) float64
        Centroid of the side's lit part (of its lit points with fixed sampling) [m]; the facet centroid
        where nothing is lit.
    rays : int
        Shadow rays cast.
    sampling : str
        How sides were sampled, in words.
    level : int or None
        Subdivision level of fixed sampling (``level**2`` points on every facing side); None for the
        default pass.
    check : ShadowCheck or None
        What the default pass's check found (:mod:`.certificate`), from which
        :meth:`ShadowCheck.loads_error` estimates the error of any load summed over the lit sides; None
        for fixed sampling.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> light = side_sampler(craft).illuminate(direction)
    >>> light.sampling, light.level, round(float(light.lit_fraction.sum()), 3)
    ('shadow edges located, tolerance 0.001', None, 61.847)
    """

    direction: NDArray[np.float64]
    side_normals: NDArray[np.float64]
    facing_runs: tuple[NDArray[np.int64], ...]
    share_runs: tuple[NDArray[np.float64], ...]
    lit_centroid: NDArray[np.float64]
    rays: int
    sampling: str
    level: int | None = None
    check: ShadowCheck | None = None

    @cached_property
    def cos_incidence(self) -> NDArray[np.float64]:
        """Cosine of the incidence on each side, ``n_out . direction``; computed on first use.

        Returns
        -------
        (n_sides,) ndarray of float64
            Positive on the sides facing the source.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> light = side_sampler(craft).illuminate(direction)
        >>> light.cos_incidence[:2].round(4)
        array([-0.2996, -0.2996])
        """
        return self.side_normals @ self.direction

    @cached_property
    def facing(self) -> NDArray[np.int64]:
        """Sides facing the source, joined from :attr:`facing_runs` on first use.

        Returns
        -------
        (n_facing,) ndarray of int64
            The sides with ``cos_incidence > 0``.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> light = side_sampler(craft).illuminate(direction)
        >>> len(light.facing), bool((light.cos_incidence[light.facing] > 0).all())
        (72, True)
        """
        return _joined(self.facing_runs)

    @cached_property
    def facing_share(self) -> NDArray[np.float64]:
        """Lit share of each of :attr:`facing`, joined from :attr:`share_runs` on first use.

        Returns
        -------
        (n_facing,) ndarray of float64
            Share of each facing side's area that is lit, in [0, 1].

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> light = side_sampler(craft).illuminate(direction)
        >>> light.facing_share[:3]
        array([1., 1., 1.])
        """
        return _joined(self.share_runs).astype(np.float64, copy=False)

    @cached_property
    def lit_fraction(self) -> NDArray[np.float64]:
        """Lit share of every side, 0 for sides facing away; made on first use.

        Returns
        -------
        (n_sides,) ndarray of float64
            Share of each side's area that is lit.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> light = side_sampler(craft).illuminate(direction)
        >>> light.lit_fraction[[0, 8, 24, 26]].round(3)  # facing away, lit, partly shaded twice
        array([0. , 1. , 0.1, 0.4])
        """
        fraction = np.zeros(len(self.side_normals))
        fraction[self.facing] = self.facing_share
        return fraction


def _joined(runs: tuple[NDArray, ...]) -> NDArray:
    return runs[0] if len(runs) == 1 else np.concatenate(runs)


def level_for_samples(samples: int) -> int:
    """Find the subdivision level whose ``level**2`` points per side are at least ``samples``.

    Parameters
    ----------
    samples : int
        Points wanted per side.

    Returns
    -------
    int
        The smallest such level, at least 1.

    Raises
    ------
    InputError
        ``samples`` is not a whole number >= 1.

    Examples
    --------
    >>> level_for_samples(1), level_for_samples(10), level_for_samples(16)
    (1, 4, 4)
    """
    if isinstance(samples, bool) or not isinstance(samples, int | np.integer) or samples < 1:
        raise InputError(
            f"samples {samples!r} must be a whole number >= 1",
            hint="give a count of points per facet side",
            parameters=("samples",),
        )
    return math.isqrt(int(samples) - 1) + 1


def check_sampling(samples: int | None, tolerance: float) -> None:
    """Check the sampling arguments of :meth:`SideSampler.illuminate`.

    Parameters
    ----------
    samples : int or None
        Fixed shadow-ray points per side (None: the adaptive pass).
    tolerance : float
        The adaptive pass's tolerance, in [``MIN_TOLERANCE``, 1).

    Raises
    ------
    InputError
        ``samples`` refused by :func:`level_for_samples`, or ``tolerance`` outside
        [``MIN_TOLERANCE``, 1).

    Examples
    --------
    >>> check_sampling(None, 1e-3)
    >>> check_sampling(None, 5.0)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.InputError: tolerance 5.0 must lie in [1e-06, 1); default 1e-3
    """
    if samples is not None:
        level_for_samples(samples)
    number = not isinstance(tolerance, bool) and isinstance(tolerance, int | float)
    if not number or not MIN_TOLERANCE <= tolerance < 1:
        raise InputError(
            f"tolerance {tolerance!r} must lie in [{MIN_TOLERANCE:g}, 1)",
            hint="default 1e-3",
            parameters=("tolerance",),
        )


def side_sampler(craft: Spacecraft) -> SideSampler:
    """Get the :class:`SideSampler` of a model, made once and kept in its cache with the origins it keeps.

    Parameters
    ----------
    craft : Spacecraft
        The model.

    Returns
    -------
    SideSampler
        Its sampler.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> side_sampler(craft) is side_sampler(craft)
    True
    """
    return craft.cache.get("side sampler", lambda: SideSampler(craft))


class SideSampler:
    """Sample one spacecraft's sides with shadow rays, keeping the ray origins of each level for reuse.

    Parameters
    ----------
    craft : Spacecraft
        The model.

    Attributes
    ----------
    craft : Spacecraft
        The model.
    scene : RayScene
        Its ray scene.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.materials import Material
    >>> from sunwind.geometry.spacecraft import build_spacecraft
    >>> from sunwind.meshes import box_wing
    >>> craft = build_spacecraft(box_wing(facet_size=0.5),
    ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
    >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
    >>> sampler = SideSampler(craft)
    >>> sampler.illuminate(direction, samples=16).rays  # 72 facing sides, 16 points each
    1152
    """

    def __init__(self, craft: Spacecraft) -> None:
        self.craft = craft
        self.scene = craft.scene
        self._kept: dict[int, NDArray[np.float32]] = {}
        self._sized: set[int] = set()

    def check_memory(self, level: int) -> None:
        """Refuse fixed sampling at a level before allocating, when its peak memory is too large.

        The peak is that of the sample points, a batch of rays and the lit flags of every side, checked by
        :func:`sunwind.geometry.memory.require`.

        Parameters
        ----------
        level : int
            Subdivision level: ``level**2`` points per side.

        Raises
        ------
        InputError
            When the memory needed exceeds the limit.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> side_sampler(craft).check_memory(4)
        >>> side_sampler(craft).check_memory(10**6)
        Traceback (most recent call last):
        ...
        sunwind.geometry.errors.InputError: not enough memory: needs ... for 1e+12 points per side x 144 ...
        """
        if level in self._sized:
            return
        n, points = self.craft.n_sides, level**2
        if self._keeps(level):
            need = _BARYCENTRIC_BYTES * points + 3 * 4 * n * points
        else:
            batch = max(1, _BATCH_RAYS // points) * points
            need = _BARYCENTRIC_BYTES * points + _BATCH_BYTES * batch + _LIT_BYTES * n * points
        what = f"{count(points)} points per side x {n} sides"
        require(
            need,
            what,
            "lower samples (points per side), or leave it out for the default shadow pass",
            ("samples",),
        )
        self._sized.add(level)

    def origins(self, level: int) -> NDArray[np.float32]:
        """Make the ray origins of every side at a level, in scene coordinates.

        Parameters
        ----------
        level : int
            Subdivision level: ``level**2`` points per side.

        Returns
        -------
        (n_sides, level**2, 3) ndarray of float32
            The origins, pushed off their sides along the normals.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> side_sampler(craft).origins(2).shape
        (144, 4, 3)
        """
        return self._origins_of(np.arange(self.craft.n_sides), level)

    def _kept_origins(self, level: int) -> NDArray[np.float32]:
        """The origins of every side at ``level`` in the balanced order (row ``k`` belongs to side
        ``_balanced_order[k]``), so a block's rows are contiguous; made once and kept."""
        if level not in self._kept:
            self._kept[level] = self._origins_of(self._balanced_order, level)
        return self._kept[level]

    def _keeps(self, level: int) -> bool:
        return self.craft.n_sides * level**2 <= _KEEP_POINTS

    def _origins_of(self, sides: NDArray[np.int64], level: int) -> NDArray[np.float32]:
        """Ray origins of ``sides`` at ``level`` in scene coordinates, (len(sides), level**2, 3)."""
        scene = self.scene
        return sample_origins(
            self.craft.triangles,
            self.craft.side_facet,
            self.craft.side_normals,
            sides,
            tri.subdivision_barycentric(level),
            scene.centre,
            scene.half_size,
            scene.offset_m,
        )

    def _lit(self, origins: NDArray[np.float32], direction: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Lit flag of each origin, same leading shape as ``origins``."""
        flat = origins.reshape(-1, 3)
        directions = np.broadcast_to(direction.astype(np.float32), flat.shape)
        return self.scene.clear(flat, directions).reshape(origins.shape[:-1])

    def facing_rays(
        self, direction: NDArray[np.float64], level: int
    ) -> tuple[NDArray[np.int64], NDArray[np.float32] | None]:
        """Find the sides facing a direction and their ray origins at a level.

        Parameters
        ----------
        direction : (3,) ndarray of float64
            Unit vector toward the source, body frame.
        level : int
            Subdivision level: ``level**2`` points per side.

        Returns
        -------
        sides : (n_facing,) ndarray of int64
            The sides facing ``direction``.
        origins : (n_facing, level**2, 3) ndarray of float32 or None
            Their origins when kept for reuse, else None.

        Raises
        ------
        InputError
            When the memory needed exceeds the limit.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> sides, origins = side_sampler(craft).facing_rays(direction, 2)
        >>> sides.shape, origins.shape
        ((72,), (72, 4, 3))
        """
        self.check_memory(level)
        if not self._keeps(level):
            return np.flatnonzero(self.craft.side_normals @ direction > 0), None
        return self._facing_origins(direction, level, 0, self.n_blocks)

    def _facing_origins(
        self, direction: NDArray[np.float64], level: int, first: int, last: int
    ) -> tuple[NDArray[np.int64], NDArray[np.float32]]:
        """Sides of blocks ``first`` to ``last - 1`` facing ``direction``, and their kept origins."""
        low, high = self.block_normal_bounds
        return facing_origins(
            self.craft.side_normals,
            direction,
            self._kept_origins(level),
            self._balanced_order,
            low,
            high,
            first,
            last,
        )

    @cached_property
    def _balanced_order(self) -> NDArray[np.int64]:
        """All sides, in blocks of ``BLOCK`` consecutive sides taken in a seeded random order:
        equal runs of blocks hold about as many sides facing any direction, so threads given equal
        runs finish together. Block ``k`` of the order is ``order[k * BLOCK:(k + 1) * BLOCK]``."""
        n = self.craft.n_sides
        full = n // BLOCK  # the last, shorter block stays last so that every block stays whole
        blocks = np.random.default_rng(STRATIFIED_SEED).permutation(full)
        order = (blocks[:, None] * BLOCK + np.arange(BLOCK)).reshape(-1)
        return np.concatenate([order, np.arange(full * BLOCK, n)])

    @cached_property
    def block_normal_bounds(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Bound the normal components over each block of sides.

        A block whose bound on ``n . u`` is not positive has no side facing ``u`` and is skipped whole.

        Returns
        -------
        low, high : (n_blocks, 3) ndarray of float64
            Smallest and largest normal components of each block.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> low, high = side_sampler(craft).block_normal_bounds
        >>> low.tolist(), high.tolist()
        ([[-1.0, -1.0, -1.0]], [[1.0, 1.0, 1.0]])
        """
        normals = self.craft.side_normals[self._balanced_order]
        padded = np.concatenate([normals, np.repeat(normals[-1:], self.n_blocks * BLOCK - len(normals), 0)])
        blocks = padded.reshape(self.n_blocks, BLOCK, 3)
        return blocks.min(axis=1), blocks.max(axis=1)

    @property
    def n_blocks(self) -> int:
        """Number of blocks in :attr:`side_block`.

        Returns
        -------
        int
            ``ceil(n_sides / BLOCK)``.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> side_sampler(craft).n_blocks
        1
        """
        return -(-self.craft.n_sides // BLOCK)

    @cached_property
    def side_block(self) -> NDArray[np.int64]:
        """Give the block of the balanced order each side belongs to.

        A fixed grouping for sums whose result must not depend on how work was split over threads.

        Returns
        -------
        (n_sides,) ndarray of int64
            Block of each side, read-only.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> set(side_sampler(craft).side_block.tolist())
        {0}
        """
        block = np.empty(self.craft.n_sides, dtype=np.int64)
        block[self._balanced_order] = np.arange(self.craft.n_sides) // BLOCK
        block.flags.writeable = False
        return block

    def _cast_kept(
        self,
        direction: NDArray[np.float64],
        level: int,
        centroid: NDArray[np.float64],
        reduce: Reduction | None,
    ) -> tuple[tuple[NDArray[np.int64], ...], tuple[NDArray[np.float64], ...]]:
        """Cast every facing side's kept rays at ``level``; write lit centroids of part-lit sides.

        Threads take runs of whole blocks of :attr:`_balanced_order` through the facing test, Embree,
        the lit shares and ``reduce``, in one dispatch. Returns the facing sides and their lit shares,
        in runs.
        """

        def work(first: int, last: int) -> tuple:
            facing, mine = self._facing_origins(direction, level, first, last)
            lit = self._uncovered(facing, self._lit(mine, direction), level)
            share = self._shares(facing, lit, level, centroid)
            if reduce is not None:
                reduce(facing, share, centroid)
            return facing, share

        facing, share = zip(*map_ranges(work, self.n_blocks, _MIN_BLOCKS_PER_CHUNK), strict=True)
        return facing, share

    def illuminate(
        self,
        direction: NDArray[np.float64],
        samples: int | None = None,
        tolerance: float = DEFAULT_TOLERANCE,
        reduce: Reduction | None = None,
    ) -> Illumination:
        """Find the lit share and lit centroid of every side for a source along a direction.

        ``samples`` fixes the points per side (rounded up to a square, ``level**2``); None casts one
        ray per side and finds the lit part of each side a shadow edge crosses to ``tolerance`` of its
        area (:mod:`.shadow_edges`). ``reduce``, if given, is called on the facing sides once their lit
        shares are final (see ``Reduction``), in the worker threads where possible.

        Parameters
        ----------
        direction : (3,) ndarray of float64
            Unit vector toward the source, body frame.
        samples : int or None, optional
            Points per side for fixed sampling; None for the shadow-edge pass.
        tolerance : float, optional
            Share of a refined side's area its lit part is found to (shadow-edge pass only).
        reduce : callable or None, optional
            ``reduce(sides, lit_share, lit_centroid)``, called on whole blocks of facing sides.

        Returns
        -------
        Illumination
            Lit shares, lit centroids, rays cast and, for the shadow-edge pass, its check.

        Raises
        ------
        InputError
            ``samples`` not a whole number >= 1, or too many points for the memory.

        Examples
        --------
        >>> import numpy as np
        >>> from sunwind.geometry.materials import Material
        >>> from sunwind.geometry.spacecraft import build_spacecraft
        >>> from sunwind.meshes import box_wing
        >>> craft = build_spacecraft(box_wing(facet_size=0.5),
        ...     uniform=Material("m", reflectivity=0.5, specular_fraction=0.5))
        >>> direction = np.array([0.3, 0.95, 0.1]) / np.linalg.norm([0.3, 0.95, 0.1])  # the bus shades a wing
        >>> sampler = side_sampler(craft)
        >>> edges, fixed = sampler.illuminate(direction), sampler.illuminate(direction, samples=16)
        >>> edges.rays, round(float(edges.lit_fraction.sum()), 3), edges.check is not None
        (761, 61.847, True)
        >>> fixed.rays, fixed.level, round(float(fixed.lit_fraction.sum()), 3)
        (1152, 4, 61.75)
        """
        craft = self.craft
        fixed = samples is not None
        level = level_for_samples(samples) if fixed else 1
        self.check_memory(level)
        # the lit centroid differs from the side centroid only on partly lit sides, which one fixed
        # point per side has not
        centroid = craft.side_centroids if fixed and level == 1 else craft.side_centroids.copy()
        if self._keeps(level):
            facing, share = self._cast_kept(direction, level, centroid, reduce if fixed else None)
            reduce = None if fixed else reduce  # a fixed count reduces chunk by chunk as it goes
        else:
            sides, _ = self.facing_rays(direction, level)
            lit = self._cast(sides, level, direction)
            facing, share = (sides,), (self._shares(sides, lit, level, centroid),)
        rays = sum(map(len, facing)) * level**2
        sampling = f"{level**2} points per side"
        check = None
        if not fixed:
            sides, centre_lit = _joined(facing), _joined(share)
            fraction = np.zeros(craft.n_sides)
            fraction[sides] = centre_lit
            refined = refine_edges(craft, direction, sides, centre_lit, fraction, centroid, tolerance)
            rays += refined.rays
            check = refined.check
            share = tuple(fraction[run] for run in facing)
            sampling = f"shadow edges located, tolerance {tolerance:g}"
        if reduce is not None:  # each run is whole blocks: the threads sum them side by side
            map_ranges(
                lambda lo, hi: [reduce(facing[k], share[k], centroid) for k in range(lo, hi)], len(facing), 1
            )
        return Illumination(
            direction,
            craft.side_normals,
            facing,
            share,
            centroid,
            rays,
            sampling,
            level if fixed else None,
            check,
        )

    def _shares(
        self,
        sides: NDArray[np.int64],
        lit: NDArray[np.bool_],
        level: int,
        centroid: NDArray[np.float64],
    ) -> NDArray[np.float64]:
        """Lit share of each of ``sides`` from its lit flags (n, level**2); writes the centroid of the
        lit points of each part-lit side into ``centroid``, which holds the facet centroid elsewhere."""
        if level == 1:  # one point per side: its flag is its share, and no side is lit in part
            return lit.reshape(-1)
        craft = self.craft
        barycentric = tri.subdivision_barycentric(level)
        lit_centroids(sides, lit, barycentric, craft.triangles, craft.side_facet, centroid)
        return lit_shares(lit)

    def _cast(
        self, sides: NDArray[np.int64], level: int, direction: NDArray[np.float64]
    ) -> NDArray[np.bool_]:
        """Lit flags (len(sides), level**2) of ``sides`` at ``level``, origins made on the fly in batches."""
        per_batch = max(1, _BATCH_RAYS // level**2)
        batches = [sides[start : start + per_batch] for start in range(0, len(sides), per_batch)]
        if not batches:
            return np.zeros((0, level**2), dtype=bool)
        return np.concatenate(
            [
                self._uncovered(batch, self._lit(self._origins_of(batch, level), direction), level)
                for batch in batches
            ]
        )

    def _uncovered(self, sides: NDArray[np.int64], lit: NDArray[np.bool_], level: int) -> NDArray[np.bool_]:
        """Lit flags ``lit`` (len(sides), level**2) with the points a coplanar facet covers made dark."""
        if not len(crossings(self.craft).cover):  # most models: nothing to build the points for
            return lit
        points = tri.subdivision_barycentric(level)[:, 1:]
        n = len(sides)
        flat = uncovered(
            self.craft, np.repeat(sides, level**2), np.tile(points, (n, 1)), lit.reshape(-1).copy()
        )
        return flat.reshape(lit.shape)
