"""Functions of triangle soups in (n, 3, 3) float form: normals, areas, centroids and quadrature points."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from numpy.typing import NDArray


def cross(triangles: NDArray[np.float64]) -> NDArray[np.float64]:
    """Edge cross products ``(v1 - v0) x (v2 - v0)``, (n, 3); twice the area along the normal."""
    return np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])


def areas(triangles: NDArray[np.float64]) -> NDArray[np.float64]:
    """Triangle areas [m^2], (n,)."""
    return 0.5 * np.linalg.norm(cross(triangles), axis=1)


def normals(triangles: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit normals by the right-hand rule on (v0, v1, v2), (n, 3); zero for a degenerate triangle."""
    c = cross(triangles)
    length = np.linalg.norm(c, axis=1)
    out = np.zeros_like(c)
    np.divide(c, length[:, None], out=out, where=length[:, None] > 0)
    return out


def centroids(triangles: NDArray[np.float64]) -> NDArray[np.float64]:
    """Triangle centroids [m], (n, 3)."""
    return triangles.mean(axis=1)


def signed_volume(triangles: NDArray[np.float64]) -> float:
    """Volume enclosed by a closed triangle set [m^3]; positive when the winding is outward."""
    return float(np.einsum("ij,ij->", triangles[:, 0], np.cross(triangles[:, 1], triangles[:, 2])) / 6)


def volume_centroid(triangles: NDArray[np.float64]) -> NDArray[np.float64]:
    """Centroid of the solid enclosed by a closed, outward-wound triangle set [m], (3,)."""
    tet_volume = np.einsum("ij,ij->i", triangles[:, 0], np.cross(triangles[:, 1], triangles[:, 2]))
    tet_centroid = triangles.sum(axis=1) / 4  # tetrahedra with the origin as fourth vertex
    return (tet_volume[:, None] * tet_centroid).sum(axis=0) / tet_volume.sum()


#: Seed of the stratified sample points: results are the same on every run and machine.
STRATIFIED_SEED = 20130101


def _sub_triangles(level: int) -> NDArray[np.float64]:
    """Barycentric corners of the ``level**2`` congruent sub-triangles, (level**2, 3 corners, 3)."""
    i, j = np.meshgrid(np.arange(level), np.arange(level), indexing="ij")
    up, down = (i + j) <= level - 1, (i + j) <= level - 2
    i_up, j_up, i_dn, j_dn = i[up], j[up], i[down], j[down]
    b1 = np.concatenate([np.stack([i_up, i_up + 1, i_up], 1), np.stack([i_dn + 1, i_dn, i_dn + 1], 1)])
    b2 = np.concatenate([np.stack([j_up, j_up, j_up + 1], 1), np.stack([j_dn, j_dn + 1, j_dn + 1], 1)])
    b1, b2 = b1 / level, b2 / level
    return np.stack([1 - b1 - b2, b1, b2], axis=-1)


@lru_cache(maxsize=16)
def subdivision_barycentric(level: int) -> NDArray[np.float64]:
    """Barycentric coordinates of one sample point in each of the ``level**2`` congruent sub-triangles.

    Splitting every edge into ``level`` equal parts cuts a triangle into ``level**2`` congruent
    sub-triangles, each standing for ``A / level**2`` of the area. At level 1 the point is the
    centroid (a midpoint rule, exact for linear integrands). From level 2 on it is a uniformly random
    point of its sub-triangle, drawn once with ``STRATIFIED_SEED`` (stratified sampling): for a lit
    region bounded by a shadow edge the estimate is unbiased and its error falls as ``level**-1.5``,
    whereas centroids lie in rows and an edge parallel to a row flips a whole row at once
    (error ``~1 / level``, common on boxes and panels whose shadow edges follow the mesh axes).

    Returns
    -------
    (level**2, 3) float64, read-only
        Weights ``(w0, w1, w2)`` on the vertices ``(v0, v1, v2)``; each row sums to 1.
    """
    if level < 1:
        raise ValueError("level must be at least 1")
    corners = _sub_triangles(level)
    if level == 1:
        bary = corners.mean(axis=1)
    else:
        r = np.random.default_rng([STRATIFIED_SEED, level]).random((level**2, 2))
        fold = r.sum(axis=1) > 1
        r[fold] = 1 - r[fold]
        bary = (
            corners[:, 0]
            + r[:, :1] * (corners[:, 1] - corners[:, 0])
            + r[:, 1:] * (corners[:, 2] - corners[:, 0])
        )
    bary.flags.writeable = False
    return bary


def sample_points(triangles: NDArray[np.float64], level: int) -> NDArray[np.float64]:
    """Sample points of :func:`subdivision_barycentric` on every triangle [m], (n, level**2, 3)."""
    return np.einsum("sk,nkd->nsd", subdivision_barycentric(level), triangles)
