"""Array bookkeeping shared by the mesh readers and writers, vectorised over faces."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.geometry.errors import MeshError


def fan_triangles(counts: ArrayLike, indices: ArrayLike) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Split polygons into triangles fanning out from each polygon's first vertex.

    This is exact for convex polygons, which is what OBJ and USD exporters write; the winding
    of each triangle is that of its polygon.

    Parameters
    ----------
    counts : (n_polygons,) int
        Number of vertices of each polygon, each at least 3 (the caller checks).
    indices : (sum(counts),) int
        Vertex indices of all polygons, one after the other.

    Returns
    -------
    triangles : (n_triangles, 3) int64
        Vertex indices of the triangles, ``sum(counts - 2)`` of them, in polygon order.
    polygon : (n_triangles,) int64
        Polygon each triangle came from.

    Examples
    --------
    >>> triangles, polygon = fan_triangles([4, 3], [0, 1, 2, 3, 4, 5, 6])
    >>> triangles.tolist(), polygon.tolist()
    ([[0, 1, 2], [0, 2, 3], [4, 5, 6]], [0, 0, 1])
    """
    counts = np.asarray(counts, dtype=np.int64)
    indices = np.asarray(indices, dtype=np.int64)
    if np.all(counts == 3):
        return indices.reshape(-1, 3), np.arange(len(counts), dtype=np.int64)
    n_triangles = counts - 2
    polygon = np.repeat(np.arange(len(counts), dtype=np.int64), n_triangles)
    first = (np.cumsum(counts) - counts)[polygon]
    # corner j = 1 .. k-2 of the fan inside each polygon
    corner = np.arange(len(polygon)) - np.repeat(np.cumsum(n_triangles) - n_triangles, n_triangles)
    corner += 1
    triangles = np.stack([indices[first], indices[first + corner], indices[first + corner + 1]], axis=1)
    return triangles, polygon


def groups(labels: ArrayLike) -> list[tuple[int, NDArray[np.int64]]]:
    """Positions of each distinct label, in increasing label order and original order within.

    Parameters
    ----------
    labels : (n,) int
        A label per item, e.g. ``MeshData.face_part``.

    Returns
    -------
    list of (int, (k,) int64)
        Each label present and the positions holding it.

    Examples
    --------
    >>> [(label, where.tolist()) for label, where in groups([2, 0, 2, 1])]
    [(0, [1]), (1, [3]), (2, [0, 2])]
    """
    labels = np.asarray(labels)
    order = np.argsort(labels, kind="stable")
    values, starts = np.unique(labels[order], return_index=True)
    return [(int(value), chunk) for value, chunk in zip(values, np.split(order, starts[1:]), strict=True)]


def compact(faces: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Renumber a subset of faces to use only the vertices they touch.

    Parameters
    ----------
    faces : (n_faces, 3) int
        Indices into a larger vertex array.

    Returns
    -------
    used : (n_used,) int64
        Original indices of the touched vertices, ascending.
    faces : (n_faces, 3) int64
        The same faces as indices into ``used``.

    Examples
    --------
    >>> used, faces = compact(np.array([[4, 7, 9], [9, 7, 5]]))
    >>> used.tolist(), faces.tolist()
    ([4, 5, 7, 9], [[0, 2, 3], [3, 2, 1]])
    """
    used, inverse = np.unique(faces, return_inverse=True)
    return used, inverse.reshape(faces.shape).astype(np.int64)


def bounds(points: NDArray[np.floating]) -> tuple[NDArray[np.floating], NDArray[np.floating]]:
    """Lowest and highest coordinates of the finite points (zeros if there are none).

    Parameters
    ----------
    points : (n, 3) float
        Vertex positions, possibly with NaN or infinity (the model builder reports those).

    Returns
    -------
    low, high : (3,) float
        Per-axis bounds, in the dtype of ``points``.

    Examples
    --------
    >>> low, high = bounds(np.array([[0.0, 1.0, 2.0], [np.nan, 0.0, 0.0], [-1.0, 3.0, 0.5]]))
    >>> low.tolist(), high.tolist()
    ([-1.0, 1.0, 0.5], [0.0, 3.0, 2.0])
    """
    finite = points[np.isfinite(points).all(axis=1)]
    if not len(finite):
        finite = np.zeros((1, 3), dtype=points.dtype)
    return finite.min(axis=0), finite.max(axis=0)


def check_transform(linear: NDArray[np.float64], path: str, part: str) -> None:
    """Refuse a part's world transform that is not finite or collapses the part flat.

    Parameters
    ----------
    linear : (3, 3) float64
        The linear part of the transform.
    path : str
        The mesh file, named in the error.
    part : str
        The part the transform places, named in the error.

    Raises
    ------
    MeshError
        A NaN or infinite entry, or a determinant that is zero (to 1e-12 of the largest entry cubed):
        a scale of 0 somewhere in the part's transforms or its parents'.

    Examples
    --------
    >>> check_transform(np.eye(3), "craft.usda", "/bus")
    >>> check_transform(np.diag([1.0, 1.0, 0.0]), "craft.usda", "/bus")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.MeshError: ...collapses it flat...
    """
    if not np.isfinite(linear).all():
        raise MeshError(
            "has a transform (its own or a parent's) with values that are not finite",
            path=path,
            part=part,
            hint="give every transform of the part and its parents finite values",
        )
    determinant = float(np.linalg.det(linear))
    if abs(determinant) <= 1e-12 * max(float(np.abs(linear).max()), 1e-300) ** 3:
        raise MeshError(
            f"has a transform (its own or a parent's) that collapses it flat (determinant {determinant:g}: "
            "a scale of 0?)",
            path=path,
            part=part,
            hint="give every scale of the part and its parents non-zero factors",
        )
