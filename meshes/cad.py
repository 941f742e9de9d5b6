"""CAD-like re-exports of a model: the same surfaces written with one defect each, as real exporters do.

Each generator takes a :class:`~sunwind.geometry.mesh_data.MeshData` and returns a new one (the input is
never modified) with one defect: vertices not shared between faces (:func:`unwelded`), faces wound
either way (:func:`mixed_winding`), closed bodies written as open surfaces (:func:`open_sheets`),
T-junctions (:func:`t_junctions`), coincident or lifted copies of faces (:func:`duplicate_layers`),
slivers beside large triangles (:func:`slivers`), small boxes standing on or sunk into faces
(:func:`bolts`) and parts passing through each other (:func:`interpenetrating`). Random choices come
from ``numpy.random.default_rng(seed)``: the same seed gives the same bits. Each appends its name and
parameters to ``metadata["cad_defects"]`` (STYLE.md §8). A watertight model with centimetre steps
beside metre faces, and the named corpus of all of them, are in :mod:`sunwind.meshes.cad_corpus`.

Faces are found adjacent through edges whose end points have equal coordinates (whatever their vertex
indices), so a generator works on welded and unwelded input alike.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
import scipy.sparse
from numpy.typing import NDArray
from scipy.sparse.csgraph import connected_components
from scipy.spatial.transform import Rotation

from sunwind.geometry import triangles as tri
from sunwind.geometry.errors import InputError
from sunwind.geometry.mesh_data import MeshData
from sunwind.meshes.arguments import check_count, check_positive

__all__ = [
    "UNWELD_JITTER",
    "bolts",
    "duplicate_layers",
    "interpenetrating",
    "mixed_winding",
    "open_sheets",
    "slivers",
    "t_junctions",
    "unwelded",
]

#: Default displacement of unwelded vertex copies, as a share of the model size (largest bounding-box
#: extent): above the loader's vertex merge (1e-9, ``sunwind.geometry.checks.MERGE_TOLERANCE``), below the
#: float32 scene's resolution (1e-6 of the half-size).
UNWELD_JITTER = 1e-8
#: Two faces sharing an edge belong to one flat sheet when their unit normals differ by less than this.
_FLAT = 1e-9
#: Corners of a unit cube centred at the origin and its 12 outward triangles.
_CUBE_CORNERS = np.array([[x, y, z] for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)])
_CUBE_FACES = np.array(
    [
        [[0, 1, 3], [0, 3, 2]],  # -x
        [[4, 6, 7], [4, 7, 5]],  # +x
        [[0, 4, 5], [0, 5, 1]],  # -y
        [[2, 3, 7], [2, 7, 6]],  # +y
        [[0, 2, 6], [0, 6, 4]],  # -z
        [[1, 5, 7], [1, 7, 3]],  # +z
    ]
).reshape(-1, 3)


def unwelded(mesh: MeshData, jitter: float = UNWELD_JITTER, seed: int = 0) -> MeshData:
    """Every face with its own copies of its corners, each moved a little: an exporter's split normals.

    Each copy moves by between 3/4 and all of ``jitter`` times the model size (largest bounding-box
    extent). The copies of one vertex take directions spread evenly over the sphere (a Fibonacci
    lattice of as many points as the most-used vertex has copies, turned at random per vertex), so they
    lie apart by more than the loader's vertex merge (1e-9 of the size) at the default jitter, and well
    inside its crack closing (1e-4).

    Parameters
    ----------
    mesh : MeshData
        The model; it is not modified.
    jitter : float, optional
        Largest displacement of a copy, as a share of the model size [-].
    seed : int, optional
        Seed of ``numpy.random.default_rng``: the same seed gives the same output.

    Returns
    -------
    MeshData
        ``3 n_faces`` vertices, face ``i`` using vertices ``3 i``, ``3 i + 1``, ``3 i + 2``.

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> soup = unwelded(box(), seed=1)
    >>> soup.vertices.shape, len(box().vertices)
    ((36, 3), 8)
    """
    check_positive(jitter=jitter)
    rng = np.random.default_rng(seed)
    corners = mesh.vertices[mesh.faces].reshape(-1, 3)
    vertex = mesh.faces.reshape(-1)
    order = np.argsort(vertex, kind="stable")
    copies = np.bincount(vertex, minlength=len(mesh.vertices))
    rank = np.empty_like(order)  # which copy of its vertex each corner is: 0, 1, ...
    rank[order] = np.arange(len(order)) - np.repeat(np.cumsum(copies) - copies, copies)
    n = int(copies.max())
    height = 1 - (2 * np.arange(n) + 1) / n
    turn = np.arange(n) * np.pi * (3 - np.sqrt(5))
    lattice = np.column_stack(
        [np.sqrt(1 - height**2) * np.cos(turn), np.sqrt(1 - height**2) * np.sin(turn), height]
    )
    spin = Rotation.random(len(mesh.vertices), random_state=rng).as_matrix()[vertex]
    direction = np.einsum("nij,nj->ni", spin, lattice[rank])
    reach = jitter * _size(mesh) * rng.uniform(0.75, 1.0, len(corners))
    faces = np.arange(len(corners)).reshape(-1, 3)
    moved = replace(mesh, vertices=corners + direction * reach[:, None], faces=faces)
    return _noted(moved, "unwelded", jitter=float(jitter), seed=seed)


def mixed_winding(mesh: MeshData, share: float = 0.5, seed: int = 0) -> MeshData:
    """The winding of ``round(share * n_faces)`` faces drawn at random reversed (their normals flip).

    The loader makes a closed body's winding consistent and outward again (with a notice); on a sheet a
    flipped face swaps its front and back.

    Parameters
    ----------
    mesh : MeshData
        The model; it is not modified.
    share : float, optional
        Share of the faces to reverse, in [0, 1].
    seed : int, optional
        Seed of ``numpy.random.default_rng``: the same seed gives the same output.

    Returns
    -------
    MeshData
        A new mesh with the defect, its name and parameters appended to ``metadata["cad_defects"]``.

    Raises
    ------
    InputError
        If ``share`` lies outside [0, 1].

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> mixed_winding(box(), share=0.25, seed=3).metadata["cad_defects"][-1]["flipped"]
    3
    """
    chosen = _draw(mesh.n_faces, share, seed)
    faces = mesh.faces.copy()
    faces[chosen] = faces[chosen, ::-1]
    return _noted(replace(mesh, faces=faces), "mixed_winding", share=share, seed=seed, flipped=len(chosen))


def open_sheets(mesh: MeshData) -> MeshData:
    """Every part the file does not declare two-sided cut into its flat regions, each an open part.

    As exporters that write each CAD face as a surface of its own: faces of a part joined through
    shared edges with the same normal direction form a sheet named ``<part>/sheet<k>`` (``k`` from 0 in
    order of first face), with its own copies of its vertices. Parts in ``two_sided_parts`` are kept
    whole. The sheets are open: declare them two-sided (glob ``*/sheet*``).

    Parameters
    ----------
    mesh : MeshData
        The model; it is not modified.

    Returns
    -------
    MeshData
        The mesh with one part per flat sheet (and the two-sided parts unchanged), its vertices
        duplicated between sheets; ``metadata["cad_defects"]`` notes the number of sheets.

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> open_sheets(box(divisions=2)).part_names
    ('box/sheet0', 'box/sheet1', 'box/sheet2', 'box/sheet3', 'box/sheet4', 'box/sheet5')
    """
    split = ~_declared(mesh)[mesh.face_part]
    normals = tri.normals(mesh.vertices[mesh.faces])
    face_a, _, face_b, _ = _shared_edges(mesh)
    flat = (
        (mesh.face_part[face_a] == mesh.face_part[face_b])
        & split[face_a]
        & split[face_b]
        & (np.einsum("ij,ij->i", normals[face_a], normals[face_b]) > 1 - _FLAT)
    )
    n = mesh.n_faces
    graph = scipy.sparse.coo_matrix((np.ones(int(flat.sum())), (face_a[flat], face_b[flat])), shape=(n, n))
    region = connected_components(graph, directed=False)[1]
    # one group per sheet (split faces) or per kept part, numbered in order of first face
    group_key = np.where(split, region, -1 - mesh.face_part.astype(np.int64))
    _, first, group = np.unique(group_key, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    group = rank[group.reshape(-1)]
    first = first[order]
    names, counter = [], dict.fromkeys(mesh.part_names, 0)
    for face in first:  # one name per group (sheets and parts, not faces)
        part = mesh.part_names[mesh.face_part[face]]
        names.append(f"{part}/sheet{counter[part]}" if split[face] else part)
        counter[part] += 1
    pairs = np.column_stack([np.repeat(group, 3), mesh.faces.reshape(-1)])
    unique, inverse = np.unique(pairs, axis=0, return_inverse=True)
    cut = replace(
        mesh,
        vertices=mesh.vertices[unique[:, 1]],
        faces=inverse.reshape(-1, 3),
        face_part=group.astype(np.int32),
        part_names=tuple(names),
    )
    return _noted(cut, "open_sheets", sheets=int(np.count_nonzero(split[first])))


def t_junctions(mesh: MeshData, share: float = 0.1, seed: int = 0) -> MeshData:
    """A random share of the shared edges split at their midpoint in one adjacent face only.

    That face becomes two triangles meeting at the new midpoint vertex; the neighbour across the edge
    keeps the whole edge, so the midpoint lies on its edge (a T-junction). Each face is split at most
    once: of edges drawn for the same face, the first wins.

    Parameters
    ----------
    mesh : MeshData
        The model; it is not modified.
    share : float, optional
        Share of the edges shared by two faces to split, in [0, 1].
    seed : int, optional
        Seed of ``numpy.random.default_rng``: the same seed gives the same output.

    Returns
    -------
    MeshData
        A new mesh with the defect, its name and parameters appended to ``metadata["cad_defects"]``.

    Raises
    ------
    InputError
        If ``share`` lies outside [0, 1].

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> cracked = t_junctions(box(), share=0.5, seed=2)
    >>> cracked.n_faces - 12 == cracked.metadata["cad_defects"][-1]["junctions"]
    True
    """
    face_a, edge_a, face_b, edge_b = _shared_edges(mesh)
    chosen = _draw(len(face_a), share, seed)
    other = np.random.default_rng([seed, 1]).integers(2, size=len(chosen)).astype(bool)
    face = np.where(other, face_b[chosen], face_a[chosen])
    edge = np.where(other, edge_b[chosen], edge_a[chosen])
    face, first = np.unique(face, return_index=True)
    points = mesh.vertices[_edge_ends(mesh.faces[face], edge[first])].mean(axis=1)
    split = _split_faces(mesh, face, edge[first], points)
    return _noted(split, "t_junctions", share=share, seed=seed, junctions=len(face))


def duplicate_layers(
    mesh: MeshData, share: float = 0.1, offset_m: float = 0.0, part: str = "mli", seed: int = 0
) -> MeshData:
    """Copy a random share of the bodies' faces into a new part: a blanket or a decal over the surface.

    The faces are drawn among those of the parts the file does not declare two-sided (a copy of a
    sheet's face would meet the sheet's back side in a tie of no physical meaning). Each copy has its
    own vertices and the face's winding and material key; it lies on its face (``offset_m = 0``,
    coincident faces with the same optics) or is lifted along the face's normal by ``offset_m`` [m].
    The layer is open: declare ``part`` two-sided (or one-sided).

    Parameters
    ----------
    mesh : MeshData
        The model; it is not modified.
    share : float, optional
        Share of the bodies' faces to copy, in [0, 1].
    offset_m : float, optional
        Lift of the copies along their face normals [m]; 0 gives coincident faces.
    part : str, optional
        Name of the new part holding the copies.
    seed : int, optional
        Seed of ``numpy.random.default_rng``: the same seed gives the same output.

    Returns
    -------
    MeshData
        A new mesh with the defect, its name and parameters appended to ``metadata["cad_defects"]``.

    Raises
    ------
    InputError
        If ``part`` names an existing part, ``offset_m`` is not finite or ``share`` lies outside [0, 1].

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> layered = duplicate_layers(box(), share=0.5, offset_m=0.005, part="decal")
    >>> layered.n_faces, layered.part_names
    (18, ('box', 'decal'))
    """
    if part in mesh.part_names:
        raise InputError(f"part '{part}' exists already", hint="name the layer another way")
    if not np.isfinite(offset_m):
        raise InputError(f"offset_m {offset_m!r} must be finite", parameters=("offset_m",))
    bodies = np.flatnonzero(~_declared(mesh)[mesh.face_part])
    chosen = bodies[np.sort(_draw(len(bodies), share, seed))]
    corners = mesh.vertices[mesh.faces[chosen]]
    corners = corners + offset_m * tri.normals(corners)[:, None, :]
    layer = MeshData(
        corners.reshape(-1, 3),
        np.arange(3 * len(chosen)).reshape(-1, 3),
        np.zeros(len(chosen), np.int32),
        (part,),
        mesh.face_material[chosen],
        mesh.material_names,
    )
    joined = _joined(mesh, layer)
    return _noted(joined, "duplicate_layers", share=share, offset_m=float(offset_m), part=part, seed=seed)


def slivers(mesh: MeshData, share: float = 0.25, ratio: float = 1000.0, seed: int = 0) -> MeshData:
    """Large faces re-triangulated with slivers of aspect about ``ratio`` beside big triangles.

    A random share of the faces at least as large as the median face is cut along its longest edge at
    ``1 / ratio`` of the way from the edge's start: the face becomes a sliver (``1 / ratio`` of its area)
    and a big triangle. The neighbour across that edge is cut at the same point, so the mesh stays
    conforming (no T-junction) and the total area is unchanged to round-off. Each face is cut at most
    once: a drawn face whose neighbour is already cut is skipped.

    Parameters
    ----------
    mesh : MeshData
        The model; it is not modified.
    share : float, optional
        Share of the faces at least as large as the median face to cut, in [0, 1].
    ratio : float, optional
        Length of the cut edge over the distance of the cut from its start [-]: the aspect of a sliver.
    seed : int, optional
        Seed of ``numpy.random.default_rng``: the same seed gives the same output.

    Returns
    -------
    MeshData
        A new mesh with the defect, its name and parameters appended to ``metadata["cad_defects"]``.

    Raises
    ------
    InputError
        If ``ratio`` is not a finite number > 0 or ``share`` lies outside [0, 1].

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> thin = slivers(box(), share=1.0)
    >>> round(float(tri.areas(thin.vertices[thin.faces]).sum()), 12)
    6.0
    """
    check_positive(ratio=ratio)
    areas = tri.areas(mesh.vertices[mesh.faces])
    large = np.flatnonzero(areas >= np.median(areas))
    face = large[_draw(len(large), share, seed)]
    corners = mesh.vertices[mesh.faces[face]]
    edge = np.argmax(np.linalg.norm(np.roll(corners, -1, axis=1) - corners, axis=2), axis=1)
    face_a, edge_a, face_b, edge_b = _shared_edges(mesh)
    # the neighbour across each chosen edge, -1 on an open border
    slot = np.full(3 * mesh.n_faces, -1)
    slot[3 * face_a + edge_a], slot[3 * face_b + edge_b] = 3 * face_b + edge_b, 3 * face_a + edge_a
    across = slot[3 * face + edge]
    # keep a pair only where neither face appeared in an earlier pair
    flat = np.column_stack([face, np.where(across >= 0, across // 3, -2 - np.arange(len(face)))]).ravel()
    _, seen = np.unique(flat, return_index=True)
    first = np.zeros(len(flat), bool)
    first[seen] = True
    keep = first[0::2] & first[1::2]
    face, edge, across = face[keep], edge[keep], across[keep]
    ends = mesh.vertices[_edge_ends(mesh.faces[face], edge)]
    points = ends[:, 0] + (ends[:, 1] - ends[:, 0]) / ratio
    both = across >= 0
    split = _split_faces(
        mesh,
        np.r_[face, across[both] // 3],
        np.r_[edge, across[both] % 3],
        np.r_[points, points[both]],
        shared=np.r_[np.arange(len(face)), np.flatnonzero(both)],
    )
    return _noted(split, "slivers", share=share, ratio=float(ratio), seed=seed, cut=len(face))


def bolts(
    mesh: MeshData, count: int = 20, size_m: tuple[float, float] = (0.005, 0.03), seed: int = 0
) -> MeshData:
    """Small closed boxes (bolts, brackets) on random large faces of bodies, each its own part ``bolt<k>``.

    Each box has edges drawn between ``size_m[0]`` and ``size_m[1]`` [m], stands upright on a face
    (its axis along the face normal, turned at random about it) and shares no vertex with it. Even
    ``k`` stand on the face (base in its plane), odd ``k`` are sunk halfway into it (interpenetrating
    the body). Faces are drawn in proportion to their area among the faces of parts the file does not
    declare two-sided (a base on a sheet would tie with the sheet's back) whose inscribed circle holds
    the largest footprint; the box sits at a random point of that circle, wholly over the face.

    Parameters
    ----------
    mesh : MeshData
        The model; it is not modified.
    count : int, optional
        Number of boxes, >= 1.
    size_m : tuple of float, optional
        Smallest and largest edge length of a box [m].
    seed : int, optional
        Seed of ``numpy.random.default_rng``: the same seed gives the same output.

    Returns
    -------
    MeshData
        A new mesh with the defect, its name and parameters appended to ``metadata["cad_defects"]``.

    Raises
    ------
    InputError
        If ``count`` < 1, a size is not a finite number > 0, or no face's inscribed circle holds the
        largest footprint.

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> bolted = bolts(box(), count=3, seed=1)
    >>> bolted.n_faces, bolted.part_names
    (48, ('box', 'bolt0', 'bolt1', 'bolt2'))
    """
    check_count(1, count=count)
    low, high = (float(s) for s in size_m)
    check_positive(smallest=low, largest=high)
    rng = np.random.default_rng(seed)
    corners = mesh.vertices[mesh.faces]
    lengths = np.linalg.norm(np.roll(corners, -1, axis=1) - corners, axis=2)  # edge k: corner k to k+1
    areas = tri.areas(corners)
    inradius = 2 * areas / lengths.sum(axis=1)
    reach = high / np.sqrt(2)  # half the diagonal of the largest footprint
    eligible = np.flatnonzero((inradius > reach) & ~_declared(mesh)[mesh.face_part])
    if not len(eligible):
        raise InputError(f"no face is large enough for a {high:g} m bolt", hint="give a smaller size_m")
    face = rng.choice(eligible, size=count, p=areas[eligible] / areas[eligible].sum())
    dims = rng.uniform(low, high, (count, 3))
    # incentre, plus a random shift that keeps the footprint inside the inscribed circle
    opposite = np.roll(lengths[face], -1, axis=1)  # the edge opposite corner k runs from k+1 to k+2
    centre = np.einsum("nk,nkd->nd", opposite, corners[face]) / opposite.sum(axis=1, keepdims=True)
    normal = tri.normals(corners[face])
    tangent = corners[face, 1] - corners[face, 0]
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    angle = rng.uniform(0, 2 * np.pi, (2, count))
    t1 = np.cos(angle[0])[:, None] * tangent + np.sin(angle[0])[:, None] * np.cross(normal, tangent)
    t2 = np.cross(normal, t1)
    room = (inradius[face] - np.hypot(dims[:, 0], dims[:, 1]) / 2) * np.sqrt(rng.uniform(0, 1, count))
    centre = centre + room[:, None] * (np.cos(angle[1])[:, None] * t1 + np.sin(angle[1])[:, None] * t2)
    sunk = np.arange(count) % 2 == 1
    centre = centre + np.where(sunk, 0.0, dims[:, 2] / 2)[:, None] * normal
    frame = np.stack([t1, t2, normal], axis=2)  # columns: the box's x, y, z axes
    boxes = _boxes(frame, dims, centre, [f"bolt{k}" for k in range(count)])
    return _noted(_joined(mesh, boxes), "bolts", count=count, size_m=(low, high), seed=seed)


def interpenetrating(
    mesh: MeshData,
    moves: Mapping[str, Sequence[float]] | None = None,
    yokes: int = 1,
    seed: int = 0,
) -> MeshData:
    """Make parts pass through each other: named parts moved, and box beams pushed through a wall.

    ``moves`` translates whole parts (e.g. the sample's boom into its bus, ``{"boom": (0.3, 0, 0)}``).
    Each of ``yokes`` beams (parts ``yoke<k>``) is a closed box half a target's extent long and a
    twentieth of it wide, along the normal of a face of the target drawn in proportion to area,
    centred on that face: half inside the target, half out. The target is the largest part (by area)
    the file does not declare two-sided.

    Parameters
    ----------
    mesh : MeshData
        The model; it is not modified.
    moves : mapping of str to sequence of float, optional
        Translation [m], shape (3,), of each named part.
    yokes : int, optional
        Number of box beams pushed through the largest body, >= 0.
    seed : int, optional
        Seed of ``numpy.random.default_rng``: the same seed gives the same output.

    Returns
    -------
    MeshData
        A new mesh with the defect, its name and parameters appended to ``metadata["cad_defects"]``.

    Raises
    ------
    InputError
        If ``moves`` names a part the mesh does not have, ``yokes`` < 0, or ``yokes`` > 0 and every part
        is declared two-sided.

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> pierced = interpenetrating(box(), yokes=2)
    >>> pierced.part_names, pierced.n_faces
    (('box', 'yoke0', 'yoke1'), 36)
    """
    unknown = sorted(set(moves or {}) - set(mesh.part_names))
    if unknown:
        raise InputError(f"no part '{unknown[0]}' to move", hint=f"parts: {', '.join(mesh.part_names)}")
    check_count(0, yokes=yokes)
    vertices = mesh.vertices.copy()
    for part, shift in (moves or {}).items():  # one step per moved part
        used = np.unique(mesh.faces[mesh.face_part == mesh.part_names.index(part)])
        vertices[used] += np.asarray(shift, dtype=np.float64)
    moved = replace(mesh, vertices=vertices)
    if yokes:
        corners = vertices[mesh.faces]
        areas = tri.areas(corners)
        part_area = np.bincount(mesh.face_part, weights=areas, minlength=len(mesh.part_names))
        part_area[_declared(mesh)] = 0.0
        if not part_area.any():
            raise InputError("no part to push a yoke through", hint="give yokes=0 for a model of sheets")
        target = np.flatnonzero(mesh.face_part == np.argmax(part_area))
        extent = float(np.ptp(vertices[np.unique(mesh.faces[target])], axis=0).max())
        rng = np.random.default_rng(seed)
        face = rng.choice(target, size=yokes, p=areas[target] / areas[target].sum())
        normal = tri.normals(corners[face])
        t1 = np.cross(normal, np.eye(3)[np.argmin(np.abs(normal), axis=1)])
        t1 /= np.linalg.norm(t1, axis=1, keepdims=True)
        frame = np.stack([t1, np.cross(normal, t1), normal], axis=2)
        dims = np.tile([extent / 20, extent / 20, extent / 2], (yokes, 1))
        beams = _boxes(frame, dims, corners[face].mean(axis=1), [f"yoke{k}" for k in range(yokes)])
        moved = _joined(moved, beams)
    moves_m = {part: tuple(float(x) for x in shift) for part, shift in (moves or {}).items()}
    return _noted(moved, "interpenetrating", moves_m=moves_m, yokes=yokes, seed=seed)


# ----------------------------------------------------------------------------------- helpers


def _size(mesh: MeshData) -> float:
    """Largest bounding-box extent of the mesh [m]."""
    return float(np.ptp(mesh.vertices[mesh.faces].reshape(-1, 3), axis=0).max())


def _declared(mesh: MeshData) -> NDArray[np.bool_]:
    """Whether each part is one the file declares two-sided, (n_parts,)."""
    return np.array([part in mesh.two_sided_parts for part in mesh.part_names], dtype=bool)


def _draw(n: int, share: float, seed: int) -> NDArray[np.int64]:
    """``round(share * n)`` distinct indices below ``n``, drawn at random."""
    if not 0 <= share <= 1:
        raise InputError(f"share {share!r} must lie in [0, 1]", parameters=("share",))
    return np.random.default_rng(seed).permutation(n)[: round(share * n)]


def _noted(mesh: MeshData, defect: str, **parameters: Any) -> MeshData:
    """``mesh`` with ``{"defect": defect, **parameters}`` appended to ``metadata["cad_defects"]``."""
    done = tuple(mesh.metadata.get("cad_defects", ()))
    return replace(mesh, metadata={**mesh.metadata, "cad_defects": (*done, {"defect": defect, **parameters})})


def _shared_edges(mesh: MeshData) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """Pairs of faces sharing an edge used by exactly two faces (end points compared by coordinates):
    ``face_a, edge_a, face_b, edge_b``, edge ``k`` of a face running from its corner ``k`` to ``k + 1``."""
    welded = np.unique(mesh.vertices, axis=0, return_inverse=True)[1].reshape(-1)[mesh.faces]
    ends = np.sort(np.stack([welded, np.roll(welded, -1, axis=1)], axis=2).reshape(-1, 2), axis=1)
    _, key, uses = np.unique(ends, axis=0, return_inverse=True, return_counts=True)
    key = key.reshape(-1)
    twice = np.flatnonzero(uses[key] == 2)
    order = twice[np.argsort(key[twice], kind="stable")]
    a, b = order[0::2], order[1::2]
    return a // 3, a % 3, b // 3, b % 3


def _edge_ends(faces: NDArray[np.int64], edge: NDArray[np.int64]) -> NDArray[np.int64]:
    """Vertex indices (n, 2) of edge ``edge[i]`` (corner k to k + 1) of each face ``faces[i]``."""
    rows = np.arange(len(faces))
    return np.column_stack([faces[rows, edge], faces[rows, (edge + 1) % 3]])


def _split_faces(
    mesh: MeshData,
    face: NDArray[np.int64],
    edge: NDArray[np.int64],
    points: NDArray[np.float64],
    shared: NDArray[np.int64] | None = None,
) -> MeshData:
    """Each ``face[i]`` (distinct) cut in two at a new vertex ``points[i]`` on its edge ``edge[i]``:
    corners (p, q, r) with the edge p -> q become (p, v, r) and (v, q, r), both in place of the face
    (each half keeps its part and material). ``shared[i]`` numbers the new vertex of cut ``i``, from 0
    up without gaps (cuts with one number share it, at the point of the first; default one per cut)."""
    shared = np.arange(len(face)) if shared is None else shared
    rows = np.arange(len(face))
    corners = mesh.faces[face]
    p, q, r = corners[rows, edge], corners[rows, (edge + 1) % 3], corners[rows, (edge + 2) % 3]
    v = len(mesh.vertices) + shared
    faces = mesh.faces.copy()
    faces[face] = np.column_stack([p, v, r])
    _, first = np.unique(shared, return_index=True)
    vertices = np.concatenate([mesh.vertices, points[first]])
    # the second halves go last; their faces keep the cut face's labels
    return replace(
        mesh,
        vertices=vertices,
        faces=np.concatenate([faces, np.column_stack([v, q, r])]),
        face_part=np.r_[mesh.face_part, mesh.face_part[face]],
        face_material=np.r_[mesh.face_material, mesh.face_material[face]],
    )


def _boxes(frame: NDArray, dims: NDArray, centre: NDArray, names: list[str]) -> MeshData:
    """Closed boxes, one part each: box ``k`` has edge lengths ``dims[k]`` along the columns of
    ``frame[k]`` (a proper rotation) and its centre at ``centre[k]``; outward winding, no material."""
    local = _CUBE_CORNERS[None, :, :] * dims[:, None, :]
    vertices = np.einsum("nij,nkj->nki", frame, local) + centre[:, None, :]
    n = len(dims)
    faces = (_CUBE_FACES[None, :, :] + 8 * np.arange(n)[:, None, None]).reshape(-1, 3)
    part = np.repeat(np.arange(n), len(_CUBE_FACES)).astype(np.int32)
    return MeshData(vertices.reshape(-1, 3), faces, part, tuple(names), np.full(len(faces), -1, np.int32))


def _joined(mesh: MeshData, extra: MeshData) -> MeshData:
    """``mesh`` with ``extra``'s faces and parts added, keeping ``mesh``'s labels, sheets and metadata."""
    joined = MeshData.concatenate([mesh, extra], source=mesh.source)
    return replace(
        joined,
        two_sided_parts=mesh.two_sided_parts,
        part_back_material=mesh.part_back_material,
        file_optics=mesh.file_optics,
        metadata=mesh.metadata,
    )
