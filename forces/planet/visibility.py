"""What every side sees past the rest of the spacecraft along a fixed grid of directions, computed once
per model, so that each step's shadowed cap integral is a weighted sum (METHOD.md "Planet radiation",
its paragraph "Directional visibility").

The grid is an icosphere (:func:`direction_grid`): level ``k`` has ``10 4^k + 2`` nodes about
``63.4 / 2^k`` degrees apart, and the nodes of level ``k - 1`` are its first ones. Along each node
direction ``d_j`` one shadow pass gives each facing side's lit share ``f_ij`` and lit centroid; the
build keeps, per node,

* the shadow matrices ``S_ij = (n_i . d_j)(1 - f_ij)`` and ``S2_ij = (n_i . d_j)^2 (1 - f_ij)`` (sparse:
  only sides partly in shadow), which turn node irradiances ``W_j`` into what each side loses of the
  source, ``dI_0 = S W``, ``dI_1 = S (W d)``, ``dI_2 = S2 W``;
* per optics band (solar, infrared) the torque of moving each side's lit force to its lit centroid and the
  pass's estimated error, both per unit irradiance; and that torque per material and unit share of each
  way light leaves (:func:`~sunwind.forces.planet.lit_law.lit_share_torques`), whatever the optics: the
  basis of the derivatives with respect to the optics;
* with mirror or transmitted beams (solar band), each node's beam chains per unit irradiance
  (:func:`~sunwind.forces.reflection.follow_chains` is linear in the flux): their force and torque,
  the diffuse sources and arrivals they leave on each side (sparse) and their power split.

A step then needs no ray: the cap's radiance is spread on the nodes by :meth:`DirectionGrid.weights`
(linear interpolation on the grid's triangles, so the sum is the integral of the piecewise-linear
interpolant of the per-node losses: second order in the node spacing), and every quantity above is a
matrix-vector product. The build is sized before it starts (the worst case: every facing side partly
shadowed at every node) and refused when that exceeds the memory limit; it is kept in the model's cache
and on disk with the view factors, keyed by the geometry, the optics and the settings, and checked on
load.
"""

from __future__ import annotations

import functools
import hashlib
import time
from dataclasses import dataclass, fields, replace

import numpy as np
import scipy.sparse
import trimesh
from numpy.typing import NDArray
from scipy.spatial import cKDTree

from sunwind.forces.planet.lit_law import cell_error, law, lit_share_torques
from sunwind.forces.radiation.sensitivity import SHARES
from sunwind.forces.reflection import BeamChainTotals, ReflectionSettings, follow_chains
from sunwind.geometry.errors import InputError
from sunwind.geometry.memory import require
from sunwind.geometry.progress import advance, step
from sunwind.geometry.rays.hull import clearance
from sunwind.geometry.rays.sampling import ShadowSampling
from sunwind.geometry.rays.shadows import side_sampler
from sunwind.geometry.spacecraft import Spacecraft, infrared_optics
from sunwind.geometry.views.disk_cache import cache_directory, geometry_key, kept_on_disk

#: Finest grid level accepted (level 6: 40 962 nodes about 1 deg apart).
MOST_LEVEL = 6
#: The optics bands a grid keeps per-node values for, in order.
BANDS = ("solar", "infrared")
#: Nodes of the level-``k`` icosphere.
_NODES = [10 * 4**k + 2 for k in range(MOST_LEVEL + 1)]
#: Face centroids looked at per direction when it is located on the grid.
_CANDIDATES = 4


def level_for(cell_deg: float) -> int:
    """The coarsest grid level whose node spacing is at most ``cell_deg`` (at least 2, at most
    :data:`MOST_LEVEL`).

    Level ``k``'s mean spacing is about ``69 / 2^k`` degrees (8.6 at level 3).

    Parameters
    ----------
    cell_deg : float
        The spacing asked for [deg].

    Returns
    -------
    int
        The icosphere level.

    Examples
    --------
    >>> level_for(10.0), level_for(5.0), level_for(2.5), level_for(90.0)
    (3, 4, 5, 2)
    """
    level = 2
    while level < MOST_LEVEL and 69.0 / 2**level > cell_deg:
        level += 1
    return level


@dataclass(frozen=True, eq=False)
class DirectionGrid:
    """An icosphere of unit directions and its triangles, with the means to spread values on its nodes.

    Attributes
    ----------
    level : int
        Subdivision level.
    nodes : (n, 3) float64
        Unit node directions; the first ``10 4^(level-1) + 2`` are the nodes of the level below.
    faces : (m, 3) int64
        Node indices of each triangle.

    Examples
    --------
    >>> grid = direction_grid(3)
    >>> grid.nodes.shape, grid.faces.shape
    ((642, 3), (1280, 3))
    """

    level: int
    nodes: NDArray[np.float64]
    faces: NDArray[np.int64]

    @functools.cached_property
    def _locator(self) -> tuple[cKDTree, NDArray[np.float64], NDArray[np.float64]]:
        corners = self.nodes[self.faces]  # (m, 3 corners, 3)
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        normals /= np.linalg.norm(normals, axis=1, keepdims=True)
        offsets = np.einsum("ij,ij->i", normals, corners[:, 0])
        inverse = np.linalg.inv(np.transpose(corners, (0, 2, 1)))  # x = C^T b -> b = C^-T x
        return cKDTree(corners.mean(axis=1)), normals / offsets[:, None], inverse

    def locate(self, directions: NDArray[np.float64]) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """The triangle each unit direction crosses and its barycentric weights there.

        Parameters
        ----------
        directions : (p, 3) float64
            Unit directions.

        Returns
        -------
        faces : (p,) int64
            Triangle of each direction.
        weights : (p, 3) float64
            Barycentric weights on the triangle's nodes, each in [0, 1], summing to 1.

        Examples
        --------
        >>> grid = direction_grid(2)
        >>> faces, weights = grid.locate(grid.nodes[:2])
        >>> weights.max(axis=1).round(12)
        array([1., 1.])
        """
        tree, scaled_normals, inverse = self._locator
        _, near = tree.query(directions, k=_CANDIDATES)
        # the ray from the centre along w leaves the polyhedron through the face with the largest n.w / d
        reach = np.einsum("pkj,pj->pk", scaled_normals[near], directions)
        face = near[np.arange(len(directions)), np.argmax(reach, axis=1)]
        points = directions / np.einsum("pj,pj->p", scaled_normals[face], directions)[:, None]
        weights = np.clip(np.einsum("pij,pj->pi", inverse[face], points), 0.0, None)
        return face, weights / weights.sum(axis=1, keepdims=True)

    def weights(self, directions: NDArray[np.float64], values: NDArray[np.float64]) -> NDArray[np.float64]:
        """Spread ``values`` at ``directions`` on the nodes by linear interpolation on the triangles.

        ``sum_j g_j W_j`` is then ``sum_p values_p g(w_p)`` for the piecewise-linear interpolant ``g`` of
        any node values ``g_j``.

        Parameters
        ----------
        directions : (p, 3) float64
            Unit directions (quadrature points).
        values : (p,) or (p, b) float64
            A value at each (a quadrature weight times an integrand), or ``b`` of them.

        Returns
        -------
        (n,) or (n, b) float64
            The node weights; they sum to ``values.sum(axis=0)``.

        Examples
        --------
        >>> grid = direction_grid(2)
        >>> w = grid.weights(np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]), np.array([2.0, 3.0]))
        >>> w.shape, round(float(w.sum()), 12)
        ((162,), 5.0)
        """
        face, share = self.locate(directions)
        values = np.asarray(values, dtype=np.float64)
        columns = values.reshape(len(values), -1)
        node = self.faces[face].reshape(-1)
        out = np.stack(
            [np.bincount(node, (share * c[:, None]).reshape(-1), len(self.nodes)) for c in columns.T], axis=1
        )
        return out.reshape((len(self.nodes), *values.shape[1:]))


@functools.lru_cache(maxsize=MOST_LEVEL + 1)
def direction_grid(level: int) -> DirectionGrid:
    """The icosphere of subdivision ``level`` (made once per level; a pure function of it).

    Parameters
    ----------
    level : int
        0 (the icosahedron, 12 nodes) to :data:`MOST_LEVEL`.

    Returns
    -------
    DirectionGrid

    Examples
    --------
    >>> [len(direction_grid(k).nodes) for k in range(4)]
    [12, 42, 162, 642]
    """
    sphere = trimesh.creation.icosphere(subdivisions=level)
    nodes = np.asarray(sphere.vertices, dtype=np.float64)
    nodes /= np.linalg.norm(nodes, axis=1, keepdims=True)
    return DirectionGrid(level, nodes, np.asarray(sphere.faces, dtype=np.int64))


@dataclass(frozen=True, eq=False)
class NodeChains:
    """The beam chains of every node direction per unit irradiance (W/m^2), solar optics; body frame.

    Torques are about the body origin; a reference point ``r`` takes ``M - r x F``.

    Attributes
    ----------
    force_N, torque_Nm, open_sky_force_N, open_sky_torque_Nm : (n, 3) float64
        :class:`~sunwind.forces.reflection.BeamChainTotals` fields of each node.
    escaped_W, absorbed_W, truncated_W, first_W : (n,) float64
        The power split of each node's chains.
    depth : (n,) int64
        Most surfaces a chain of the node met.
    diffuse_source_W, arrived_W : scipy.sparse.csr_matrix, (n_sides, n)
        Per side and node: power handed to diffuse reflection, beam power arriving.

    Examples
    --------
    Made by :func:`visibility`; a convex model's beams all escape at once, and no node has chains:

    >>> import sunwind as sw
    >>> white = sw.Material("white", reflectivity=0.5, specular_fraction=0.5, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box(), uniform=white, threads=1).craft
    >>> visibility(craft, 2, sw.ShadowSampling(), sw.ReflectionSettings("full"), beams=True).chains is None
    True
    """

    force_N: NDArray[np.float64]
    torque_Nm: NDArray[np.float64]
    open_sky_force_N: NDArray[np.float64]
    open_sky_torque_Nm: NDArray[np.float64]
    escaped_W: NDArray[np.float64]
    absorbed_W: NDArray[np.float64]
    truncated_W: NDArray[np.float64]
    first_W: NDArray[np.float64]
    depth: NDArray[np.int64]
    diffuse_source_W: scipy.sparse.csr_matrix
    arrived_W: scipy.sparse.csr_matrix


@dataclass(frozen=True, eq=False)
class Visibility:
    """What every side sees along every node direction of a grid (module docstring); body frame, SI.

    Attributes
    ----------
    grid : DirectionGrid
        The directions.
    shadow : scipy.sparse.csr_matrix, (n_sides, n)
        ``(n_i . d_j)(1 - f_ij)`` for sides facing node ``j`` and partly shadowed; empty on a model no
        side of which can be shadowed.
    shadow2 : scipy.sparse.csr_matrix, (n_sides, n)
        ``(n_i . d_j)^2 (1 - f_ij)``.
    shift_torque_Nm : (2, n, 3) float64
        Per band of :data:`BANDS` and node, the torque of moving the lit forces to the lit centroids, per
        unit irradiance [N m / (W/m^2)] (a couple: the reference point does not enter).
    error_force_N, error_torque_Nm : (2, n) float64 or None
        Per band and node, the shadow pass's estimated error per unit irradiance (torque about the body
        origin); None with fixed sampling.
    chains : NodeChains or None
        The nodes' beam chains (solar optics), when beams were asked for and some side can be shadowed.
    lit_torque_Nm : (n, n_materials, 4, 3) float64
        Per node, material and share of :data:`~sunwind.forces.radiation.sensitivity.SHARES`, the torque of
        moving the lit forces of the material's sides to their lit centroids per unit irradiance and unit
        share; ``shift_torque_Nm`` of a band is its sum weighted by the band's shares.
    rays : int
        Rays the build cast.
    seconds : float
        Time the build took (0 when read from disk).
    origin : str
        "computed", or the disk entry it was read from.

    Examples
    --------
    >>> import numpy as np
    >>> import sunwind as sw
    >>> grey = sw.Material("grey", reflectivity=0.3, specular_fraction=0.0, emissivity=0.8)
    >>> craft = sw.load(sw.meshes.box_wing(), uniform=grey, threads=1).craft
    >>> seen = visibility(craft, 2, sw.ShadowSampling(), sw.ReflectionSettings("none"))
    >>> seen.shadow.shape == (craft.n_sides, 162), seen.shadow.nnz > 0  # the bus shades the wings
    (True, True)
    """

    grid: DirectionGrid
    shadow: scipy.sparse.csr_matrix
    shadow2: scipy.sparse.csr_matrix
    shift_torque_Nm: NDArray[np.float64]
    error_force_N: NDArray[np.float64] | None
    error_torque_Nm: NDArray[np.float64] | None
    chains: NodeChains | None
    lit_torque_Nm: NDArray[np.float64]
    rays: int
    seconds: float
    origin: str = "computed"

    @property
    def nbytes(self) -> int:
        """Bytes of the arrays kept.

        Examples
        --------
        >>> import sunwind as sw
        >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("m", 0.3, 0.0, 0.0, 0.8), threads=1).craft
        >>> visibility(craft, 2, sw.ShadowSampling(), sw.ReflectionSettings("none")).nbytes < 100_000
        True
        """
        return sum(value.nbytes for value in _arrays(self).values())


def visibility(
    craft: Spacecraft,
    level: int,
    sampling: ShadowSampling,
    settings: ReflectionSettings,
    *,
    beams: bool = False,
) -> Visibility:
    """The :class:`Visibility` of a model on the grid of ``level``: from the model's cache, from disk
    (where ``settings.cache_dir`` says, as the view factors), or built.

    Parameters
    ----------
    craft : Spacecraft
        The model (its solar and infrared optics enter the per-band values and the chains).
    level : int
        Grid level (:func:`level_for`), 0 to :data:`MOST_LEVEL`.
    sampling : ShadowSampling
        The shadow pass of each node.
    settings : ReflectionSettings
        ``cutoff`` and ``depth`` of the chains, and ``cache_dir``.
    beams : bool
        Follow each node's mirror and transmitted beams (the albedo with ``specular`` or ``full``
        reflections).

    Returns
    -------
    Visibility

    Raises
    ------
    InputError
        A level out of range, or a build that could need more memory than the limit (the estimate and the
        fix in the message).

    Examples
    --------
    A convex cube: no side can be shadowed, nothing is cast.

    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("m", 0.3, 0.0, 0.0, 0.8), threads=1).craft
    >>> seen = visibility(craft, 3, sw.ShadowSampling(), sw.ReflectionSettings("none"))
    >>> seen.rays, seen.shadow.nnz, len(seen.grid.nodes)
    (0, 0, 642)
    """
    if isinstance(level, bool) or not isinstance(level, int) or not 0 <= level <= MOST_LEVEL:
        raise InputError(f"grid level {level} is not in [0, {MOST_LEVEL}]", parameters=("level",))
    key = ("directional visibility", level, sampling.samples, sampling.tolerance, beams, settings.cutoff,
           settings.depth)  # fmt: skip
    if key not in craft.cache:  # built outside the cache's lock: its passes ask the cache from threads
        with step("directional visibility"):
            built = _kept(craft, level, sampling, settings, beams)
        return craft.cache.get(key, lambda: built)
    return craft.cache.get(key, lambda: _kept(craft, level, sampling, settings, beams))


def _kept(
    craft: Spacecraft, level: int, sampling: ShadowSampling, settings: ReflectionSettings, beams: bool
) -> Visibility:
    """Read from disk or build (and store)."""
    shadowing = not bool(np.all(clearance(craft).open_sky))
    grid = direction_grid(level)
    if not shadowing:
        return _empty(craft, grid, sampling)
    _check_memory(craft, grid, beams)
    directory = cache_directory(settings.cache_dir)
    build = functools.partial(_build, craft, grid, sampling, settings, beams)
    if directory is None:
        return build()
    optics = np.concatenate([craft.side_optics, infrared_optics(craft)])
    settings_key = {
        "kind": "directional visibility",
        "level": level,
        "samples": sampling.samples,
        "tolerance": sampling.tolerance,
        "beams": beams,
        "cutoff": settings.cutoff,
        "depth": settings.depth,
        "optics": hashlib.sha256(np.ascontiguousarray(optics, dtype="<f8").tobytes()).hexdigest(),
        "materials": [
            len(craft.materials),
            hashlib.sha256(np.ascontiguousarray(craft.side_material, dtype="<i4").tobytes()).hexdigest(),
        ],
    }
    return kept_on_disk(
        directory,
        "visibility",
        geometry_key(craft, settings_key),
        build,
        _arrays,
        lambda arrays, origin: _decoded(arrays, grid, (craft.n_sides, len(craft.materials)), origin),
    )


def _check_memory(craft: Spacecraft, grid: DirectionGrid, beams: bool) -> None:
    """Refuse a build whose worst case (every facing side partly shadowed at every node) exceeds the limit."""
    facing = craft.n_sides * len(grid.nodes) / 2
    per_entry = 2 * (8 + 4) + (2 * (8 + 4) if beams else 0)  # values and indices of the sparse matrices
    couples = len(grid.nodes) * len(craft.materials) * len(SHARES) * 3 * 8  # the lit couples per material
    require(
        facing * per_entry * 2 + couples,  # and the lists they are assembled from
        f"the directional visibility of {craft.n_sides} sides along {len(grid.nodes)} directions",
        "give a larger cell_deg (a coarser grid), or method cells (a shadow pass per cell at every call)",
        ("cell_deg", "method"),
    )


def _empty(craft: Spacecraft, grid: DirectionGrid, sampling: ShadowSampling) -> Visibility:
    n, shape = len(grid.nodes), (craft.n_sides, len(grid.nodes))
    errors = np.zeros((2, n)) if sampling.estimates else None
    empty = scipy.sparse.csr_matrix(shape)
    lit = np.zeros((n, len(craft.materials), len(SHARES), 3))
    return Visibility(grid, empty, empty.copy(), np.zeros((2, n, 3)), errors, errors, None, lit, 0, 0.0)


def _build(
    craft: Spacecraft,
    grid: DirectionGrid,
    sampling: ShadowSampling,
    settings: ReflectionSettings,
    beams: bool,
) -> Visibility:
    """One shadow pass (and, with ``beams``, the chains) along every node direction."""
    start = time.perf_counter()
    sampler = side_sampler(craft)
    band_optics = (craft.side_optics, infrared_optics(craft))
    n, origin = len(grid.nodes), np.zeros(3)
    rows, cols, lost, lost2 = [], [], [], []
    shift = np.zeros((2, n, 3))
    lit_torque = np.zeros((n, len(craft.materials), len(SHARES), 3))
    errors = np.zeros((2, 2, n)) if sampling.estimates else None
    chain_list, rays = [], 0
    for j, direction in enumerate(grid.nodes):
        light = sampler.illuminate(direction, sampling.samples, sampling.tolerance)
        rays += light.rays
        facing, share = light.facing, light.facing_share.astype(np.float64)
        dark, dark_share = facing[share < 1.0], share[share < 1.0]
        cos = craft.side_normals[dark] @ direction
        rows.append(dark)
        cols.append(np.full(len(dark), j))
        lost.append(cos * (1.0 - dark_share))
        lost2.append(cos * cos * (1.0 - dark_share))
        offset = light.lit_centroid[dark] - craft.side_centroids[dark]
        normals, areas = craft.side_normals[dark], craft.side_areas[dark]
        torques = lit_share_torques(normals, areas, direction, (dark_share, offset))
        np.add.at(lit_torque[j], craft.side_material[dark], torques)
        for b, optics in enumerate(band_optics):
            lit = law(normals, areas, optics[dark], cos * dark_share, direction, cos)
            shift[b, j] = np.cross(offset, lit).sum(axis=0)
            if errors is not None and light.check is not None:
                error = cell_error(craft, optics, (direction, 1.0), light.check, origin)
                errors[b, :, j] = error.force_N, error.torque_Nm
        if beams:
            chains = follow_chains(craft, light, 1.0, origin, settings.cutoff, settings.depth, light.level)
            rays += chains.rays
            chain_list.append(_compact(chains))  # per-side arrays kept sparse from the start
        advance(j + 1, n)
    shape = (craft.n_sides, n)
    rows_all, cols_all = np.concatenate(rows), np.concatenate(cols)
    shadow = scipy.sparse.csr_matrix((np.concatenate(lost), (rows_all, cols_all)), shape=shape)
    shadow2 = scipy.sparse.csr_matrix((np.concatenate(lost2), (rows_all, cols_all)), shape=shape)
    return Visibility(
        grid=grid,
        shadow=shadow,
        shadow2=shadow2,
        shift_torque_Nm=shift,
        error_force_N=None if errors is None else errors[:, 0],
        error_torque_Nm=None if errors is None else errors[:, 1],
        chains=_stacked(chain_list, craft.n_sides) if beams else None,
        lit_torque_Nm=lit_torque,
        rays=rays,
        seconds=time.perf_counter() - start,
    )


def _compact(chains: BeamChainTotals) -> BeamChainTotals:
    """``chains`` with its per-side arrays as (indices, values) of their non-zero entries."""
    sparse = {}
    for name in _CHAIN_SPARSE:
        values = getattr(chains, name)
        kept = np.flatnonzero(values)
        sparse[name] = (kept, values[kept])
    return replace(chains, **sparse)


def _stacked(chains: list[BeamChainTotals], n_sides: int) -> NodeChains:
    """The chains of each node (unit irradiance, per-side arrays compacted) as arrays."""

    def sparse(name: str) -> scipy.sparse.csr_matrix:
        parts = [getattr(c, name) for c in chains]
        columns = np.concatenate([np.full(len(kept), j) for j, (kept, _) in enumerate(parts)])
        rows, values = np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])
        return scipy.sparse.csr_matrix((values, (rows, columns)), shape=(n_sides, len(chains)))

    def rows(name: str) -> NDArray[np.float64]:
        return np.array([getattr(c, name) for c in chains], dtype=np.float64)

    return NodeChains(
        force_N=rows("force_N"),
        torque_Nm=rows("torque_Nm"),
        open_sky_force_N=rows("open_sky_force_N"),
        open_sky_torque_Nm=rows("open_sky_torque_Nm"),
        escaped_W=rows("escaped_W"),
        absorbed_W=rows("absorbed_W"),
        truncated_W=rows("truncated_W"),
        first_W=rows("first_W"),
        depth=np.array([c.depth for c in chains], dtype=np.int64),
        diffuse_source_W=sparse("diffuse_source_W"),
        arrived_W=sparse("arrived_W"),
    )


_SPARSE = ("shadow", "shadow2")
_CHAIN_SPARSE = ("diffuse_source_W", "arrived_W")


def _arrays(seen: Visibility) -> dict[str, NDArray]:
    """The arrays of a visibility, by name, for the disk entry."""
    out: dict[str, NDArray] = {
        "shift_torque_Nm": seen.shift_torque_Nm,
        "lit_torque_Nm": seen.lit_torque_Nm,
        "rays": np.array(seen.rays),
    }
    for name in _SPARSE:
        matrix = getattr(seen, name)
        out |= {
            f"{name}.data": matrix.data,
            f"{name}.indices": matrix.indices,
            f"{name}.indptr": matrix.indptr,
        }
    if seen.error_force_N is not None:
        out |= {"error_force_N": seen.error_force_N, "error_torque_Nm": seen.error_torque_Nm}
    if seen.chains is not None:
        for field in fields(NodeChains):
            value = getattr(seen.chains, field.name)
            if field.name in _CHAIN_SPARSE:
                out |= {f"chains.{field.name}.{part}": getattr(value, part) for part in ("data", "indices",
                        "indptr")}  # fmt: skip
            else:
                out[f"chains.{field.name}"] = value
    return out


def _decoded(
    arrays: dict[str, NDArray], grid: DirectionGrid, counts: tuple[int, int], origin: str
) -> Visibility:
    """A visibility from its disk entry (``counts``: the model's sides and materials), its shapes and
    values checked."""
    n_sides, n_materials = counts
    n, shape = len(grid.nodes), (n_sides, len(grid.nodes))

    def sparse(prefix: str) -> scipy.sparse.csr_matrix:
        parts = (arrays[f"{prefix}.data"], arrays[f"{prefix}.indices"], arrays[f"{prefix}.indptr"])
        matrix = scipy.sparse.csr_matrix(parts, shape=shape)
        matrix.check_format(full_check=True)
        if not np.all(np.isfinite(matrix.data)):
            raise ValueError(f"{prefix} holds values that are not finite")
        return matrix

    shift = np.asarray(arrays["shift_torque_Nm"], dtype=np.float64)
    if shift.shape != (2, n, 3):
        raise ValueError(f"shift_torque_Nm has shape {shift.shape}, not {(2, n, 3)}")
    lit = np.asarray(arrays["lit_torque_Nm"], dtype=np.float64)
    if lit.shape != (n, n_materials, len(SHARES), 3):
        raise ValueError(f"lit_torque_Nm has shape {lit.shape}, not {(n, n_materials, len(SHARES), 3)}")
    if not np.all(np.isfinite(lit)):
        raise ValueError("lit_torque_Nm holds values that are not finite")
    shadow, shadow2 = sparse("shadow"), sparse("shadow2")
    if shadow.nnz and not (shadow.data.min() >= 0.0 and shadow.data.max() <= 1.0 + 1e-9):
        raise ValueError("shadow holds losses outside [0, 1]")
    chains = None
    if "chains.force_N" in arrays:
        values = {
            field.name: sparse(f"chains.{field.name}")
            if field.name in _CHAIN_SPARSE
            else np.asarray(arrays[f"chains.{field.name}"])
            for field in fields(NodeChains)
        }
        chains = NodeChains(**values)
    return Visibility(
        grid=grid,
        shadow=shadow,
        shadow2=shadow2,
        shift_torque_Nm=shift,
        error_force_N=arrays.get("error_force_N"),
        error_torque_Nm=arrays.get("error_torque_Nm"),
        chains=chains,
        lit_torque_Nm=lit,
        rays=int(arrays["rays"]),
        seconds=0.0,
        origin=origin,
    )
