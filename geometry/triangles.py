"""Functions of triangle soups in (n, 3, 3) float form: normals, areas, centroids and quadrature points."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from numpy.typing import NDArray


def cross(triangles: NDArray[np.float64]) -> NDArray[np.float64]:
    """Compute the edge cross products ``(v1 - v0) x (v2 - v0)``: twice the area along the normal.

    Parameters
    ----------
    triangles : (n, 3, 3) float64
        Corners ``(v0, v1, v2)`` of each triangle [m].

    Returns
    -------
    (n, 3) float64
        The cross products [m^2].

    Examples
    --------
    >>> tri = np.array([[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])
    >>> cross(tri)
    array([[0., 0., 2.]])
    """
    return np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])


def areas(triangles: NDArray[np.float64]) -> NDArray[np.float64]:
    """Compute triangle areas.

    Parameters
    ----------
    triangles : (n, 3, 3) float64
        Corners of each triangle [m].

    Returns
    -------
    (n,) float64
        Areas [m^2].

    Examples
    --------
    >>> tri = np.array([[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])
    >>> areas(tri)
    array([1.])
    """
    return 0.5 * np.linalg.norm(cross(triangles), axis=1)


def normals(triangles: NDArray[np.float64]) -> NDArray[np.float64]:
    """Compute unit normals by the right-hand rule on ``(v0, v1, v2)``; zero for a degenerate triangle.

    Parameters
    ----------
    triangles : (n, 3, 3) float64
        Corners of each triangle [m].

    Returns
    -------
    (n, 3) float64
        Unit normals.

    Examples
    --------
    >>> tri = np.array([[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])
    >>> normals(tri)
    array([[0., 0., 1.]])
    """
    c = cross(triangles)
    length = np.linalg.norm(c, axis=1)
    out = np.zeros_like(c)
    np.divide(c, length[:, None], out=out, where=length[:, None] > 0)
    return out


def centroids(triangles: NDArray[np.float64]) -> NDArray[np.float64]:
    """Compute triangle centroids.

    Parameters
    ----------
    triangles : (n, 3, 3) float64
        Corners of each triangle [m].

    Returns
    -------
    (n, 3) float64
        Centroids [m].

    Examples
    --------
    >>> tri = np.array([[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])
    >>> np.round(centroids(tri), 4)
    array([[0.6667, 0.3333, 0.    ]])
    """
    return triangles.mean(axis=1)


def signed_volume(triangles: NDArray[np.float64]) -> float:
    """Compute the volume enclosed by a closed triangle set; positive when the winding is outward.

    Parameters
    ----------
    triangles : (n, 3, 3) float64
        Corners of the triangles of a closed surface [m].

    Returns
    -------
    float
        Signed volume [m^3].

    Examples
    --------
    >>> from sunwind.meshes import box
    >>> cube = box((1.0, 2.0, 3.0))
    >>> signed_volume(cube.vertices[cube.faces])
    6.0
    """
    return float(np.einsum("ij,ij->", triangles[:, 0], np.cross(triangles[:, 1], triangles[:, 2])) / 6)


def volume_centroid(triangles: NDArray[np.float64]) -> NDArray[np.float64]:
    """Compute the centroid of the solid enclosed by a closed, outward-wound triangle set.

    Parameters
    ----------
    triangles : (n, 3, 3) float64
        Corners of the triangles of a closed surface [m].

    Returns
    -------
    (3,) float64
        The centroid [m].

    Examples
    --------
    >>> from sunwind.meshes import box, transform
    >>> cube = transform(box(), translation=(1.0, 0.0, -2.0))
    >>> np.round(volume_centroid(cube.vertices[cube.faces]), 12) + 0.0
    array([ 1.,  0., -2.])
    """
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

    Parameters
    ----------
    level : int
        Edge divisions, >= 1.

    Raises
    ------
    ValueError
        ``level`` below 1.

    Examples
    --------
    >>> subdivision_barycentric(1)
    array([[0.33333333, 0.33333333, 0.33333333]])
    >>> bary = subdivision_barycentric(3)
    >>> bary.shape, bool(np.allclose(bary.sum(axis=1), 1.0))
    ((9, 3), True)
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
    """Place the sample points of :func:`subdivision_barycentric` on every triangle.

    Parameters
    ----------
    triangles : (n, 3, 3) float64
        Corners of each triangle [m].
    level : int
        Edge divisions, >= 1; ``level**2`` points per triangle.

    Returns
    -------
    (n, level**2, 3) float64
        The points [m].

    Examples
    --------
    >>> tri = np.array([[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0]]])
    >>> sample_points(tri, 2).shape
    (1, 4, 3)
    """
    return np.einsum("sk,nkd->nsd", subdivision_barycentric(level), triangles)
