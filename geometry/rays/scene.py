"""Ray casting against a spacecraft's triangles: an Embree scene built once, and a brute-force twin.

Both scenes take rays in scene coordinates: float32, the model recentred on its bounding-box centre
and divided by its half-size, so every coordinate lies in [-1, 1] and float32 keeps ~1e-7 of the
model size everywhere. :meth:`RayScene.to_scene` converts points in metres. Ray origins are pushed off
their surface along its normal by ``ORIGIN_OFFSET`` (a share of the model half-size), which clears
float32 round-off of the intersection test without stepping over any real feature of the model.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from sunwind.geometry.parallel import map_ranges, thread_count

#: Origin offset along the surface normal, as a share of the model half-size (5 um on a 10 m model).
ORIGIN_OFFSET = 1e-6
#: Rays per chunk of a batch of occlusion queries cast in parallel.
_RAYS_PER_CHUNK = 4_096
#: Rays per chunk of a batch of first-hit queries: they cost several times more per ray.
_HITS_PER_CHUNK = 1_024


class SceneFrame:
    """Map between metres (body frame) and float32 scene coordinates.

    The model is recentred on its bounding-box centre and divided by its half-size.

    Parameters
    ----------
    triangles : (n, 3, 3) ndarray of float64
        Triangle corners [m], body frame.

    Attributes
    ----------
    centre : (3,) ndarray of float64
        Centre of the bounding box [m].
    half_size : float
        Half the largest extent of the bounding box [m].
    offset_m : float
        How far ray origins are pushed off their surface [m]: ``ORIGIN_OFFSET * half_size``.

    Examples
    --------
    >>> import numpy as np
    >>> frame = SceneFrame(np.array([[[0.0, 0, 0], [4, 0, 0], [0, 2, 0]]]))
    >>> frame.centre, frame.half_size, frame.offset_m
    (array([2., 1., 0.]), 2.0, 2e-06)
    """

    def __init__(self, triangles: NDArray[np.float64]) -> None:
        lo = triangles.reshape(-1, 3).min(axis=0)
        hi = triangles.reshape(-1, 3).max(axis=0)
        self.centre = (lo + hi) / 2
        self.half_size = float(max((hi - lo).max() / 2, np.finfo(np.float64).tiny))
        self.offset_m = ORIGIN_OFFSET * self.half_size

    def to_scene(self, points_m: NDArray[np.float64]) -> NDArray[np.float32]:
        """Convert points [m] to scene coordinates.

        Parameters
        ----------
        points_m : (..., 3) ndarray of float64
            Points [m], body frame.

        Returns
        -------
        (..., 3) ndarray of float32
            ``(points_m - centre) / half_size``.

        Examples
        --------
        >>> import numpy as np
        >>> frame = SceneFrame(np.array([[[0.0, 0, 0], [4, 0, 0], [0, 2, 0]]]))
        >>> frame.to_scene(np.array([4.0, 1.0, 0.0]))
        array([1., 0., 0.], dtype=float32)
        """
        return ((points_m - self.centre) / self.half_size).astype(np.float32)

    def origins(self, points_m: NDArray[np.float64], normals: NDArray[np.float64]) -> NDArray[np.float32]:
        """Make ray origins in scene coordinates: points pushed off their surface along its normal.

        Parameters
        ----------
        points_m : (n, 3) ndarray of float64
            Points on the surface [m].
        normals : (n, 3) ndarray of float64
            Unit normal of the surface at each point, toward the side the rays leave.

        Returns
        -------
        (n, 3) ndarray of float32
            ``to_scene(points_m + offset_m * normals)``.

        Examples
        --------
        >>> import numpy as np
        >>> frame = SceneFrame(np.array([[[0.0, 0, 0], [4, 0, 0], [0, 2, 0]]]))
        >>> frame.origins(np.array([[2.0, 1.0, 0.0]]), np.array([[0.0, 0.0, 1.0]]))
        array([[0.e+00, 0.e+00, 1.e-06]], dtype=float32)
        """
        return self.to_scene(points_m + self.offset_m * normals)


class RayScene(SceneFrame):
    """Embree scene of a triangle set, built once; batched occlusion and first-hit queries.

    Large batches are split over the threads of :mod:`sunwind.geometry.parallel`.

    Parameters
    ----------
    triangles : (n, 3, 3) ndarray of float64
        Triangle corners [m], body frame.

    Examples
    --------

    >>> import numpy as np
    >>> from sunwind.meshes import box
    >>> scene = RayScene(box().vertices[box().faces])
    >>> origins = scene.to_scene(np.array([[2.0, 0.0, 0.0], [2.0, 2.0, 0.0]]))
    >>> toward = (np.array([[-1.0, 0.1, 0.1]] * 2) / np.linalg.norm([-1.0, 0.1, 0.1])).astype(np.float32)
    >>> scene.n_triangles, scene.half_size
    (12, 0.5)
    >>> scene.occluded(origins, toward)
    array([ True, False])
    """

    def __init__(self, triangles: NDArray[np.float64]) -> None:
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh

        super().__init__(triangles)
        self._scene = rtcore_scene.EmbreeScene()
        TriangleMesh(self._scene, np.ascontiguousarray(self.to_scene(triangles)))
        self.threads = thread_count()
        self.n_triangles = len(triangles)

    def _run(self, origins: NDArray[np.float32], directions: NDArray[np.float32], query: str) -> NDArray:
        parts = map_ranges(
            lambda lo, hi: self._scene.run(origins[lo:hi], directions[lo:hi], query=query),
            len(origins),
            _RAYS_PER_CHUNK if query == "OCCLUDED" else _HITS_PER_CHUNK,
        )
        return parts[0] if len(parts) == 1 else np.concatenate(parts)

    def occluded(self, origins: NDArray[np.float32], directions: NDArray[np.float32]) -> NDArray[np.bool_]:
        """Test whether each ray hits any triangle.

        Parameters
        ----------
        origins : (n, 3) float32
            Ray origins in scene coordinates (see :meth:`SceneFrame.origins`).
        directions : (n, 3) float32
            Unit directions, body frame.

        Returns
        -------
        (n,) ndarray of bool
            True where the ray hits a triangle.

        Examples
        --------

        >>> import numpy as np
        >>> from sunwind.meshes import box
        >>> scene = RayScene(box().vertices[box().faces])
        >>> origins = scene.to_scene(np.array([[2.0, 0.0, 0.0], [2.0, 2.0, 0.0]]))
        >>> toward = (np.array([[-1.0, 0.1, 0.1]] * 2) / np.linalg.norm([-1.0, 0.1, 0.1])).astype(np.float32)
        >>> scene.occluded(origins, toward)
        array([ True, False])
        """
        if not len(origins):
            return np.zeros(0, dtype=bool)
        return self._run(origins, directions, "OCCLUDED") != -1

    def clear(self, origins: NDArray[np.float32], directions: NDArray[np.float32]) -> NDArray[np.bool_]:
        """Test whether each ray meets no triangle: the opposite of :meth:`occluded`.

        Parameters
        ----------
        origins : (n, 3) float32
            Ray origins in scene coordinates (see :meth:`SceneFrame.origins`).
        directions : (n, 3) float32
            Unit directions, body frame.

        Returns
        -------
        (n,) ndarray of bool
            True where the ray escapes.

        Examples
        --------

        >>> import numpy as np
        >>> from sunwind.meshes import box
        >>> scene = RayScene(box().vertices[box().faces])
        >>> origins = scene.to_scene(np.array([[2.0, 0.0, 0.0], [2.0, 2.0, 0.0]]))
        >>> toward = (np.array([[-1.0, 0.1, 0.1]] * 2) / np.linalg.norm([-1.0, 0.1, 0.1])).astype(np.float32)
        >>> scene.clear(origins, toward)
        array([False,  True])
        """
        if not len(origins):
            return np.zeros(0, dtype=bool)
        return self._run(origins, directions, "OCCLUDED") == -1

    def first_hit(self, origins: NDArray[np.float32], directions: NDArray[np.float32]) -> NDArray[np.int32]:
        """Find the first triangle each ray hits.

        Parameters
        ----------
        origins : (n, 3) float32
            Ray origins in scene coordinates (see :meth:`SceneFrame.origins`).
        directions : (n, 3) float32
            Unit directions, body frame.

        Returns
        -------
        (n,) ndarray of int32
            Index of the triangle, -1 where the ray escapes.

        Examples
        --------

        >>> import numpy as np
        >>> from sunwind.meshes import box
        >>> scene = RayScene(box().vertices[box().faces])
        >>> origins = scene.to_scene(np.array([[2.0, 0.0, 0.0], [2.0, 2.0, 0.0]]))
        >>> toward = (np.array([[-1.0, 0.1, 0.1]] * 2) / np.linalg.norm([-1.0, 0.1, 0.1])).astype(np.float32)
        >>> hit = scene.first_hit(origins, toward)
        >>> int(hit[1]), bool(np.allclose(scene.to_scene(box().vertices)[box().faces[hit[0]], 0], 1.0))
        (-1, True)
        """
        if not len(origins):
            return np.zeros(0, dtype=np.int32)
        return self._run(origins, directions, "INTERSECT").astype(np.int32, copy=False)

    def intersect(
        self, origins: NDArray[np.float32], directions: NDArray[np.float32]
    ) -> tuple[NDArray[np.int32], NDArray[np.float32]]:
        """Find the first triangle each ray hits and the distance to it.

        Parameters
        ----------
        origins : (n, 3) float32
            Ray origins in scene coordinates (see :meth:`SceneFrame.origins`).
        directions : (n, 3) float32
            Unit directions, body frame.

        Returns
        -------
        facets : (n,) ndarray of int32
            Index of the triangle hit, -1 where the ray escapes.
        distance : (n,) ndarray of float32
            Distance to it in scene units (multiply by ``half_size`` for metres); meaningless where the ray
            escapes.

        Examples
        --------

        >>> import numpy as np
        >>> from sunwind.meshes import box
        >>> scene = RayScene(box().vertices[box().faces])
        >>> origins = scene.to_scene(np.array([[2.0, 0.0, 0.0], [2.0, 2.0, 0.0]]))
        >>> toward = (np.array([[-1.0, 0.1, 0.1]] * 2) / np.linalg.norm([-1.0, 0.1, 0.1])).astype(np.float32)
        >>> facets, distance = scene.intersect(origins, toward)
        >>> round(float(distance[0] * scene.half_size), 4)
        1.5149
        """
        if not len(origins):
            return np.zeros(0, dtype=np.int32), np.zeros(0, dtype=np.float32)
        parts = map_ranges(
            lambda lo, hi: self._scene.run(origins[lo:hi], directions[lo:hi], output=True),
            len(origins),
            _HITS_PER_CHUNK,
        )
        facets = np.concatenate([p["primID"] for p in parts]).astype(np.int32, copy=False)
        return facets, np.concatenate([p["tfar"] for p in parts])


class BruteForceScene(SceneFrame):
    """Answer the queries of :class:`RayScene` by testing every ray against every triangle in numpy.

    For tests on small meshes: it shares no code with Embree, so agreement is a real check.
    Möller-Trumbore intersection, in float64 on the same scene coordinates.

    Parameters
    ----------
    triangles : (n, 3, 3) ndarray of float64
        Triangle corners [m], body frame.

    Examples
    --------

    >>> import numpy as np
    >>> from sunwind.meshes import box
    >>> scene = BruteForceScene(box().vertices[box().faces])
    >>> origins = scene.to_scene(np.array([[2.0, 0.0, 0.0], [2.0, 2.0, 0.0]]))
    >>> toward = (np.array([[-1.0, 0.1, 0.1]] * 2) / np.linalg.norm([-1.0, 0.1, 0.1])).astype(np.float32)
    >>> bool(np.array_equal(scene.occluded(origins, toward), RayScene(box().vertices[box().faces]).occluded(
    ...     origins, toward)))
    True
    """

    def __init__(self, triangles: NDArray[np.float64]) -> None:
        super().__init__(triangles)
        self._corners = self.to_scene(triangles).astype(np.float64)
        self.n_triangles = len(triangles)

    def _distances(self, origins: NDArray, directions: NDArray) -> NDArray[np.float64]:
        """Hit distance of every ray on every triangle, inf where it misses, (n_rays, n_triangles)."""
        o = np.asarray(origins, dtype=np.float64)[:, None, :]
        d = np.asarray(directions, dtype=np.float64)[:, None, :]
        v0, e1, e2 = (
            self._corners[None, :, 0],
            (self._corners[:, 1] - self._corners[:, 0])[None],
            (self._corners[:, 2] - self._corners[:, 0])[None],
        )
        p = np.cross(d, e2)
        det = np.sum(e1 * p, axis=-1)
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = 1.0 / det
            s = o - v0
            u = np.sum(s * p, axis=-1) * inv
            q = np.cross(s, e1)
            v = np.sum(d * q, axis=-1) * inv
            t = np.sum(e2 * q, axis=-1) * inv
        hit = (np.abs(det) > 1e-14) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
        return np.where(hit, t, np.inf)

    def occluded(self, origins: NDArray, directions: NDArray) -> NDArray[np.bool_]:
        """Test whether each ray hits any triangle.

        Parameters
        ----------
        origins : (n, 3) float32
            Ray origins in scene coordinates (see :meth:`SceneFrame.origins`).
        directions : (n, 3) float32
            Unit directions, body frame.

        Returns
        -------
        (n,) ndarray of bool
            True where the ray hits a triangle.

        Examples
        --------

        >>> import numpy as np
        >>> from sunwind.meshes import box
        >>> scene = BruteForceScene(box().vertices[box().faces])
        >>> origins = scene.to_scene(np.array([[2.0, 0.0, 0.0], [2.0, 2.0, 0.0]]))
        >>> toward = (np.array([[-1.0, 0.1, 0.1]] * 2) / np.linalg.norm([-1.0, 0.1, 0.1])).astype(np.float32)
        >>> scene.occluded(origins, toward)
        array([ True, False])
        """
        return np.isfinite(self._distances(origins, directions)).any(axis=1)

    def clear(self, origins: NDArray, directions: NDArray) -> NDArray[np.bool_]:
        """Test whether each ray meets no triangle.

        Parameters
        ----------
        origins : (n, 3) float32
            Ray origins in scene coordinates (see :meth:`SceneFrame.origins`).
        directions : (n, 3) float32
            Unit directions, body frame.

        Returns
        -------
        (n,) ndarray of bool
            True where the ray escapes.

        Examples
        --------

        >>> import numpy as np
        >>> from sunwind.meshes import box
        >>> scene = BruteForceScene(box().vertices[box().faces])
        >>> origins = scene.to_scene(np.array([[2.0, 0.0, 0.0], [2.0, 2.0, 0.0]]))
        >>> toward = (np.array([[-1.0, 0.1, 0.1]] * 2) / np.linalg.norm([-1.0, 0.1, 0.1])).astype(np.float32)
        >>> scene.clear(origins, toward)
        array([False,  True])
        """
        return ~self.occluded(origins, directions)

    def first_hit(self, origins: NDArray, directions: NDArray) -> NDArray[np.int32]:
        """Find the first triangle each ray hits.

        Parameters
        ----------
        origins : (n, 3) float32
            Ray origins in scene coordinates (see :meth:`SceneFrame.origins`).
        directions : (n, 3) float32
            Unit directions, body frame.

        Returns
        -------
        (n,) ndarray of int32
            Index of the triangle, -1 where the ray escapes.

        Examples
        --------

        >>> import numpy as np
        >>> from sunwind.meshes import box
        >>> scene = BruteForceScene(box().vertices[box().faces])
        >>> origins = scene.to_scene(np.array([[2.0, 0.0, 0.0], [2.0, 2.0, 0.0]]))
        >>> toward = (np.array([[-1.0, 0.1, 0.1]] * 2) / np.linalg.norm([-1.0, 0.1, 0.1])).astype(np.float32)
        >>> int(scene.first_hit(origins, toward)[1])
        -1
        """
        return self.intersect(origins, directions)[0]

    def intersect(self, origins: NDArray, directions: NDArray) -> tuple[NDArray[np.int32], NDArray]:
        """Find the first triangle each ray hits and the distance to it, in scene units.

        Parameters
        ----------
        origins : (n, 3) float32
            Ray origins in scene coordinates (see :meth:`SceneFrame.origins`).
        directions : (n, 3) float32
            Unit directions, body frame.

        Returns
        -------
        facets : (n,) ndarray of int32
            Index of the triangle hit, -1 where the ray escapes.
        distance : (n,) ndarray of float64
            Distance to it in scene units; inf where the ray escapes.

        Examples
        --------

        >>> import numpy as np
        >>> from sunwind.meshes import box
        >>> scene = BruteForceScene(box().vertices[box().faces])
        >>> origins = scene.to_scene(np.array([[2.0, 0.0, 0.0], [2.0, 2.0, 0.0]]))
        >>> toward = (np.array([[-1.0, 0.1, 0.1]] * 2) / np.linalg.norm([-1.0, 0.1, 0.1])).astype(np.float32)
        >>> facets, distance = scene.intersect(origins, toward)
        >>> (distance * scene.half_size).round(4)
        array([1.5149,    inf])
        """
        t = self._distances(origins, directions)
        nearest = np.argmin(t, axis=1).astype(np.int32)
        distance = t.min(axis=1)
        return np.where(np.isfinite(distance), nearest, -1).astype(np.int32), distance
