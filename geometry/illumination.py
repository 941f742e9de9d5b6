"""Which share of each side a distant source lights, by shadow rays from quadrature points.

METHOD.md "Shadowing".

A side's sample points are the centroids of its ``level**2`` congruent sub-triangles
(:func:`geometry.triangles.subdivision_barycentric`). A point is lit when a ray from it toward the
source leaves the model. On a flat side under a uniform beam the force per unit lit area is the same
everywhere, so the lit share and the centroid of the lit points carry all that force and torque need.

Sampling is fixed (``level**2`` points on every side facing the source) or adaptive: every facing side
starts at ``BASE_LEVEL``; a side whose points disagree, or whose lit state differs from a neighbour
facing the same way, is refined by doubling ``level`` until it is either uniformly lit or dark at two
successive levels, or its lit share has changed by at most ``tolerance`` between levels while one
sub-triangle's share ``1 / level**2`` is also within ``tolerance`` (lit shares are quantised in steps
of ``1 / level**2``, so two coarse levels can agree by chance); ``MAX_LEVEL`` caps it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numba
import numpy as np
import scipy.sparse
from numpy.typing import NDArray

from . import triangles as tri
from .errors import InputError
from .spacecraft import Spacecraft

#: Level of the first pass of adaptive sampling: 4 points per side.
BASE_LEVEL = 2
#: Finest level of adaptive sampling: 4096 points per side.
MAX_LEVEL = 64
#: Default convergence threshold on a refined side's lit share between successive levels.
DEFAULT_TOLERANCE = 1e-3
#: Rays cast per batch when origins are made on the fly, to bound memory.
_BATCH_RAYS = 1 << 21
#: Largest origin array (points) kept per level for reuse across attitudes.
_KEEP_POINTS = 1 << 22


@dataclass(frozen=True, eq=False)
class Illumination:
    """The lit share of every side for one source direction.

    Attributes
    ----------
    direction : (3,) float64
        Unit vector toward the source, body frame (``u_sun``).
    cos_incidence : (n_sides,) float64
        ``n_out . direction`` of each side.
    facing : (n_facing,) int64
        Sides with ``cos_incidence > 0``; only these can be lit.
    lit_fraction : (n_sides,) float64
        Share of the side's area that is lit, in [0, 1]; 0 for sides facing away.
    lit_centroid : (n_sides, 3) float64
        Centroid of the side's lit sample points [m]; the facet centroid where nothing is lit.
    rays : int
        Shadow rays cast.
    sampling : str
        How sides were sampled, in words.
    """

    direction: NDArray[np.float64]
    cos_incidence: NDArray[np.float64]
    facing: NDArray[np.int64]
    lit_fraction: NDArray[np.float64]
    lit_centroid: NDArray[np.float64]
    rays: int
    sampling: str


def level_for_samples(samples: int) -> int:
    """Subdivision level whose ``level**2`` points per side are at least ``samples``."""
    if samples < 1:
        raise InputError(f"--samples {samples} must be at least 1", hint="give a positive count per facet")
    return math.isqrt(samples - 1) + 1


class SideSampler:
    """Shadow-ray sampling of one spacecraft's sides, with per-level ray origins kept for reuse."""

    def __init__(self, craft: Spacecraft) -> None:
        self.craft = craft
        self.scene = craft.scene
        self._origins: dict[int, NDArray[np.float32]] = {}

    def origins(self, level: int) -> NDArray[np.float32]:
        """Ray origins of every side at ``level`` in scene coordinates, (n_sides, level**2, 3); kept."""
        if level not in self._origins:
            self._origins[level] = self._origins_of(np.arange(self.craft.n_sides), level)
        return self._origins[level]

    def _keeps(self, level: int) -> bool:
        return self.craft.n_sides * level**2 <= _KEEP_POINTS

    def points(self, sides: NDArray[np.int64], level: int) -> NDArray[np.float64]:
        """Sample points [m] of ``sides`` at ``level``, (len(sides), level**2, 3)."""
        return tri.sample_points(self.craft.triangles[self.craft.side_facet[sides]], level)

    def _origins_of(self, sides: NDArray[np.int64], level: int) -> NDArray[np.float32]:
        normals = self.craft.side_normals[sides][:, None, :]
        return self.scene.origins(self.points(sides, level), normals)

    def _lit(self, origins: NDArray[np.float32], direction: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Lit flag of each origin, same leading shape as ``origins``."""
        flat = origins.reshape(-1, 3)
        directions = np.broadcast_to(direction.astype(np.float32), flat.shape)
        return ~self.scene.occluded(flat, directions).reshape(origins.shape[:-1])

    def _facing(
        self, direction: NDArray[np.float64], level: int
    ) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.float32] | None]:
        """Incidence cosine of every side, the sides facing ``direction`` and their kept ray origins."""
        if self._keeps(level):
            cos, facing, origins = _select_facing(self.craft.side_normals, direction, self.origins(level))
            return cos, facing, origins
        cos = self.craft.side_normals @ direction
        return cos, np.flatnonzero(cos > 0), None

    def illuminate(
        self, direction: NDArray[np.float64], samples: int | None = None, tolerance: float = DEFAULT_TOLERANCE
    ) -> Illumination:
        """Lit share and lit centroid of every side for a source along unit vector ``direction``.

        ``samples`` fixes the points per side (rounded up to a square, ``level**2``); None samples
        adaptively to ``tolerance`` on each refined side's lit share.
        """
        craft = self.craft
        cos = craft.side_normals @ direction
        facing = np.flatnonzero(cos > 0)
        fraction = np.zeros(craft.n_sides)
        level = BASE_LEVEL if samples is None else level_for_samples(samples)
        # the lit centroid differs from the side centroid only on partly lit sides, which level 1 has not
        centroid = craft.side_centroids if level == 1 else craft.side_centroids.copy()
        if not self._keeps(level):
            rays = self._sample(facing, level, direction, fraction, centroid)
            return Illumination(
                direction, cos, facing, fraction, centroid, rays, f"{level**2} points per side"
            )
        lit = self._lit(self.origins(level)[facing], direction)
        rays = lit.size
        self._store(facing, lit, level, fraction, centroid)
        if samples is None:
            rays += self._refine(direction, facing, lit, fraction, centroid, tolerance)
            sampling = f"adaptive, {BASE_LEVEL**2} to {MAX_LEVEL**2} points per side, tolerance {tolerance:g}"
        else:
            sampling = f"{level**2} points per side"
        return Illumination(direction, cos, facing, fraction, centroid, rays, sampling)

    def _store(
        self,
        sides: NDArray[np.int64],
        lit: NDArray[np.bool_],
        level: int,
        fraction: NDArray[np.float64],
        centroid: NDArray[np.float64],
    ) -> None:
        """Write lit share and lit-point centroid of ``sides`` from their lit flags (n, level**2).

        ``centroid`` must hold the facet centroid of sides not sampled before at a finer level.
        """
        count = lit.sum(axis=1)
        fraction[sides] = count / lit.shape[1]
        if level == 1:
            return
        partial = np.flatnonzero((count > 0) & (count < lit.shape[1]))
        if len(partial):
            points = self.points(sides[partial], level)
            centroid[sides[partial]] = np.einsum("ns,nsd->nd", lit[partial], points) / count[partial, None]

    @cached_property
    def _adjacency(self) -> scipy.sparse.csr_matrix:
        """Side adjacency (sides sharing an edge and facing the same way) as a sparse matrix."""
        a, b = self.craft.side_neighbours
        n = self.craft.n_sides
        return scipy.sparse.coo_matrix(
            (np.ones(2 * len(a)), (np.r_[a, b], np.r_[b, a])), shape=(n, n)
        ).tocsr()

    def _neighbours(self, sides: NDArray[np.int64]) -> NDArray[np.int64]:
        """Sides adjacent to any of ``sides``."""
        return np.unique(self._adjacency[sides].indices)

    def _refine(
        self,
        direction: NDArray[np.float64],
        facing: NDArray[np.int64],
        lit: NDArray[np.bool_],
        fraction: NDArray[np.float64],
        centroid: NDArray[np.float64],
        tolerance: float,
    ) -> int:
        """Refine the sides on a shadow edge in place; return the rays cast.

        Suspect at the base level: mixed sides, the sides sharing a vertex with them, and edge
        neighbours whose uniform states differ. Whenever refinement finds a side mixed, its
        unexamined facing vertex neighbours join.
        """
        craft = self.craft
        is_facing = np.zeros(craft.n_sides, dtype=bool)
        is_facing[facing] = True
        count = lit.sum(axis=1)
        state = np.full(craft.n_sides, -1)  # -1 facing away or mixed, 0 dark, 1 lit
        state[facing] = np.where(count == lit.shape[1], 1, np.where(count == 0, 0, -1))
        a, b = craft.side_neighbours
        differ = (state[a] >= 0) & (state[b] >= 0) & (state[a] != state[b])
        mixed = facing[(count > 0) & (count < lit.shape[1])]
        examined = np.zeros(craft.n_sides, dtype=bool)
        examined[np.r_[a[differ], b[differ], mixed, self._neighbours(mixed)]] = True
        examined &= is_facing
        active = np.flatnonzero(examined)
        level, rays = BASE_LEVEL, 0
        while len(active) and level < MAX_LEVEL:
            level *= 2
            previous = fraction[active].copy()
            centroid[active] = craft.side_centroids[active]
            rays += self._sample(active, level, direction, fraction, centroid)
            now = fraction[active]
            partly = (now > 0) & (now < 1)
            joining = self._neighbours(active[partly])
            joining = joining[is_facing[joining] & ~examined[joining]]
            examined[joining] = True
            uniform = ~partly & (now == previous)
            converged = (np.abs(now - previous) <= tolerance) & (level**-2 <= tolerance)
            active = np.r_[active[~(uniform | converged)], joining]
        return rays

    def _sample(
        self,
        sides: NDArray[np.int64],
        level: int,
        direction: NDArray[np.float64],
        fraction: NDArray[np.float64],
        centroid: NDArray[np.float64],
    ) -> int:
        """Sample ``sides`` at ``level`` in batches with origins made on the fly; return rays cast."""
        per_batch = max(1, _BATCH_RAYS // level**2)
        for start in range(0, len(sides), per_batch):
            batch = sides[start : start + per_batch]
            self._store(
                batch, self._lit(self._origins_of(batch, level), direction), level, fraction, centroid
            )
        return len(sides) * level**2


@numba.njit(cache=True, nogil=True)
def _select_facing(
    normals: NDArray[np.float64], direction: NDArray[np.float64], origins: NDArray[np.float32]
) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.float32]]:
    """``cos = normals . direction``, the sides with ``cos > 0`` and their ``origins``, in one pass."""
    n = normals.shape[0]
    cos = normals @ direction
    facing = np.empty(n, dtype=np.int64)
    count = 0
    for s in range(n):
        if cos[s] > 0.0:
            facing[count] = s
            count += 1
    facing = facing[:count]
    gathered = np.empty((count, origins.shape[1], 3), dtype=np.float32)
    for k in range(count):
        gathered[k] = origins[facing[k]]
    return cos, facing, gathered
