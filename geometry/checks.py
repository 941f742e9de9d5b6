"""Mesh checks with clear outcomes: non-finite coordinates, degenerate triangles, open edges, winding."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse
from numpy.typing import NDArray
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from sunwind.geometry import triangles as tri
from sunwind.geometry.errors import MeshError, combine
from sunwind.geometry.io.units import UNITS
from sunwind.geometry.materials import toml_key
from sunwind.geometry.sides import SOLID

#: Vertices closer than this share of the model size are merged before connectivity is judged.
MERGE_TOLERANCE = 1e-9
#: A triangle whose area is below this share of its longest edge squared is degenerate (a needle or
#: a point); such triangles carry no area and are dropped and counted.
DEGENERATE_RATIO = 1e-10
#: Cracks of a closed body narrower than this share of the model size (largest bounding-box extent)
#: are closed on loading: boundary vertices this close are welded, and a boundary vertex this close
#: to another boundary edge of a closed body splits that edge (a T-junction).
CRACK_TOLERANCE = 1e-4
#: A model whose largest extent [m] is outside this range is probably in another unit: the largest
#: spacecraft flown (the ISS, 109 m across its trusses) and the smallest (3.5 cm chip satellites).
PLAUSIBLE_SIZE_M = (0.02, 120.0)
#: Extents [m] of most spacecraft (CubeSats to large buses with arrays): a unit that brings a model
#: of implausible size into this range is the one suggested.
TYPICAL_SIZE_M = (0.05, 30.0)
#: Most passes of T-junction splitting (each splits every open edge at one vertex at most).
_SPLIT_PASSES = 32


@dataclass(frozen=True, eq=False)
class MeshCheck:
    """What the checks found and the cleaned mesh.

    Attributes
    ----------
    vertices : (n_vertices, 3) float64
        Merged vertex positions [m].
    faces : (n_kept, 3) int64
        Kept faces, winding made outward on closed bodies.
    kept : (n_kept,) int64
        Index of each kept face in the input.
    dropped_degenerate : int
        Degenerate triangles removed.
    open_edges, nonmanifold_edges : dict of str -> int
        Per part, edges of closed-body (``SOLID``) faces used by one face, or by more than two. A closed
        body may be made of several parts (a cylinder's side and caps).
    open_alone : dict of str -> (int, tuple of str)
        Parts open on their own triangles whose boundary edges other parts' closed-body faces close:
        the number of those edges and the parts that close them.
    notices : tuple of str
        One line per repair made (faces dropped, winding fixed).

    Examples
    --------
    >>> from sunwind.meshes import box
    >>> mesh = box()
    >>> solid = np.full(mesh.n_faces, SOLID, dtype=np.int8)
    >>> check = check_mesh(mesh.vertices, mesh.faces, mesh.face_part, mesh.part_names, solid, "box")
    >>> check.closed, check.dropped_degenerate, len(check.kept)
    (True, 0, 12)
    """

    vertices: NDArray[np.float64]
    faces: NDArray[np.int64]
    kept: NDArray[np.int64]
    dropped_degenerate: int
    open_edges: dict[str, int]
    nonmanifold_edges: dict[str, int]
    open_alone: dict[str, tuple[int, tuple[str, ...]]]
    notices: tuple[str, ...]

    @property
    def closed(self) -> bool:
        """True when every closed-body edge is shared by exactly two faces."""
        return not self.open_edges and not self.nonmanifold_edges


def check_mesh(
    vertices: NDArray[np.float64],
    faces: NDArray[np.int64],
    face_part: NDArray[np.int32],
    part_names: tuple[str, ...],
    face_kind: NDArray[np.int8],
    source: str,
) -> MeshCheck:
    """Check a labelled triangle soup and repair what can be repaired without guessing.

    Non-finite coordinates are an error. Coincident vertices are merged. Faces of closed bodies
    (``face_kind == SOLID``) have their hair-line cracks closed (``CRACK_TOLERANCE``), with a notice.
    Triangles with a repeated vertex or (near) zero area are dropped and counted. Closed-body faces are
    checked for open and non-manifold edges, and each part on its own triangles (all reported, not
    raised: the caller decides); inconsistent winding is made consistent and a body wound inward
    (negative signed volume) is flipped, each with a notice.

    Parameters
    ----------
    vertices : (n_vertices, 3) float64
        Vertex positions [m].
    faces : (n_faces, 3) int64
        Vertex indices of the triangles.
    face_part : (n_faces,) int32
        Index into ``part_names`` of each face.
    part_names : tuple of str
        Part names, for the notices.
    face_kind : (n_faces,) int8
        ``SOLID``, ``ONE_SIDED`` or ``TWO_SIDED`` of each face.
    source : str
        The mesh file, named in errors.

    Returns
    -------
    MeshCheck
        The findings and the cleaned mesh.

    Raises
    ------
    MeshError
        Non-finite vertex coordinates, or no triangle left.

    Examples
    --------
    >>> from sunwind.meshes import box
    >>> mesh = box()
    >>> inward = mesh.faces[:, ::-1]
    >>> solid = np.full(mesh.n_faces, SOLID, dtype=np.int8)
    >>> check = check_mesh(mesh.vertices, inward, mesh.face_part, mesh.part_names, solid, "box")
    >>> check.notices  # doctest: +ELLIPSIS
    ('...',)
    >>> bool(np.array_equal(check.faces, mesh.faces))
    True
    """
    used = np.unique(faces)
    bad = used[~np.isfinite(vertices[used]).all(axis=1)]
    if len(bad):
        part = part_names[face_part[np.isin(faces, bad).any(axis=1)][0]]
        raise MeshError(
            f"has {len(bad)} vertices with NaN or infinite coordinates",
            path=source,
            part=part,
            hint="fix or remove them in the mesh file",
        )
    vertices, faces = _merge_vertices(vertices[used], np.searchsorted(used, faces))
    vertices, faces, origin, notices = _close_cracks(
        vertices, faces, face_part, face_kind == SOLID, part_names
    )
    face_part, face_kind = face_part[origin], face_kind[origin]
    repeated = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 0] == faces[:, 2])
    kept = np.flatnonzero(~repeated)
    solid = kept[face_kind[kept] == SOLID]
    open_edges, nonmanifold_edges, open_alone = _edge_defects(faces[solid], face_part[solid], part_names)
    faces = faces.copy()
    if not open_edges and not nonmanifold_edges and len(solid):
        faces[solid], winding_notices = _orient_outward(
            vertices, faces[solid], face_part[solid], part_names, source
        )
        notices += winding_notices
    corners = vertices[faces[kept]]
    longest = np.max(np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2), axis=1)
    kept = kept[tri.areas(corners) > DEGENERATE_RATIO * longest**2]
    dropped = len(faces) - len(kept)
    if dropped:
        lost = np.setdiff1d(np.arange(len(faces)), kept)
        names = sorted({part_names[p] for p in face_part[lost]})
        notices.append(f"dropped {dropped} degenerate triangles (parts: {', '.join(names)})")
    if not len(kept):
        raise MeshError("no triangle with non-zero area", path=source, hint="check the mesh file")
    return MeshCheck(
        vertices,
        faces[kept],
        origin[kept],
        dropped,
        open_edges,
        nonmanifold_edges,
        open_alone,
        tuple(notices),
    )


def size_notice(vertices: NDArray[np.float64], unit: str) -> str | None:
    """Warn when a model's size suggests its file is in another unit than the one it was read in.

    Parameters
    ----------
    vertices : (n_vertices, 3) float64
        Vertex positions [m].
    unit : str
        The unit it was read in; the first word counts (``"mm (--unit)"`` is mm).

    Returns
    -------
    str or None
        A notice naming the unit that would give the model a typical spacecraft's size (never the one it
        was read in), or None when its largest extent is plausible.

    Examples
    --------
    >>> print(size_notice(np.array([[0, 0, 0], [340.0, 100, 340]]), "m"))  # doctest: +ELLIPSIS
    the model is 340 m across (...unit m), outside 0.02-120 m: if the file is in mm, give --unit mm...
    >>> size_notice(np.array([[0, 0, 0], [2.0, 1, 1]]), "m") is None
    True
    """
    extent = float(np.ptp(vertices, axis=0).max()) if len(vertices) else 0.0
    low, high = PLAUSIBLE_SIZE_M
    if low <= extent <= high:
        return None
    read_in = unit.split()[0] if unit.split() and unit.split()[0] in UNITS else "m"
    written = extent / UNITS[read_in]  # the extent as the file writes it
    fits = [u for u in ("mm", "m", "cm", "in") if u != read_in and _typical(written * UNITS[u])]
    advice = (
        f"if the file is in {fits[0]}, give --unit {fits[0]} (Python: unit={fits[0]!r}; "
        f"{written * UNITS[fits[0]]:.3g} m across)"
        if fits
        else f"if the file is in another unit, give it with --unit (Python: unit=): one of {', '.join(UNITS)}"
    )
    return (
        f"the model is {extent:.4g} m across (largest extent of its bounding box; unit {unit}), "
        f"outside {low:g}-{high:g} m: {advice}"
    )


def _typical(extent_m: float) -> bool:
    return TYPICAL_SIZE_M[0] <= extent_m <= TYPICAL_SIZE_M[1]


def undeclared_sheets(check: MeshCheck, source: str) -> MeshError:
    """Gather one error for every part with open or non-manifold edges that is not declared a sheet.

    Parameters
    ----------
    check : MeshCheck
        The findings of :func:`check_mesh`, with at least one open or non-manifold part.
    source : str
        The mesh file, named in the errors.

    Returns
    -------
    MeshError
        The combined error, whose hint gives the choices and what each means for the physics.

    Examples
    --------
    >>> from sunwind.meshes import plate
    >>> mesh = plate(divisions=1)
    >>> solid = np.full(mesh.n_faces, SOLID, dtype=np.int8)
    >>> check = check_mesh(mesh.vertices, mesh.faces, mesh.face_part, mesh.part_names, solid, "plate.obj")
    >>> undeclared_sheets(check, "plate.obj").message
    'is an open surface (4 boundary edges)'
    """
    problems = [
        MeshError(f"is an open surface ({count} boundary edges)", path=source, part=part)
        for part, count in check.open_edges.items()
    ]
    problems += [
        MeshError(
            f"has {count} edges shared by more than two triangles (non-manifold)", path=source, part=part
        )
        for part, count in check.nonmanifold_edges.items()
    ]
    leaves = list(
        dict.fromkeys(
            part.rstrip("/").rsplit("/", 1)[-1] for part in [*check.open_edges, *check.nonmanifold_edges]
        )
    )
    leaf = leaves[0]
    flags = " ".join(f'--two-sided "{name}"' for name in leaves)
    hint = (
        "a solid body: close it in the mesh file (gaps narrower than "
        f"{CRACK_TOLERANCE:g} of the model size are closed on loading); a thin sheet lit from one side: "
        f'declare it one-sided ([parts] {toml_key(leaf)} = {{ front = "MATERIAL" }}; its back absorbs '
        "what reaches it); a sheet lit on both sides: declare it two-sided "
        f'([parts] {toml_key(leaf)} = {{ front = "...", back = "..." }}, two_sided={leaves!r} or '
        f"{flags}), a zero-thickness sheet lit and re-emitting on both faces, which turns the inside of a "
        "solid body into a cavity"
    )
    return combine(problems, hint=hint)


def _close_cracks(
    vertices: NDArray[np.float64],
    faces: NDArray[np.int64],
    face_part: NDArray[np.int32],
    solid: NDArray[np.bool_],
    part_names: tuple[str, ...],
) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.int64], list[str]]:
    """Close the hair-line cracks of closed bodies: weld boundary vertices closer than the tolerance and
    split boundary edges at the boundary vertices lying on them (T-junctions), of any part: a closed body
    may span parts, as the faces of a cube that are each a sensor.

    Returns the vertices, the faces (a split face becomes two), the input face of each face, and a
    notice per repair.
    """
    origin = np.arange(len(faces))
    scale = float(np.ptp(vertices, axis=0).max()) if len(vertices) else 0.0
    tolerance = CRACK_TOLERANCE * scale
    edges = _open_edges(faces, face_part, solid)
    if not len(edges) or tolerance <= 0:
        return vertices, faces, origin, []
    before = _length(vertices, edges)
    # weld: each boundary vertex joins its nearest boundary vertex when closer than the tolerance (one
    # neighbour each: the work stays linear however many vertices crowd together)
    boundary = np.unique(edges[:, :2])
    distance, nearest = cKDTree(vertices[boundary]).query(vertices[boundary], k=2)
    other = np.where(nearest[:, 0] == np.arange(len(boundary)), nearest[:, 1], nearest[:, 0])
    close = np.flatnonzero(
        np.where(nearest[:, 0] == np.arange(len(boundary)), distance[:, 1], distance[:, 0]) <= tolerance
    )
    welded = 0
    if len(close):
        graph = scipy.sparse.coo_matrix(
            (np.ones(len(close)), (close, other[close])), shape=(len(boundary), len(boundary))
        )
        label = connected_components(graph, directed=False)[1]
        target = np.arange(len(vertices))
        first = np.full(label.max() + 1, len(boundary))
        np.minimum.at(first, label, np.arange(len(boundary)))
        target[boundary] = boundary[first[label]]
        welded = int(np.count_nonzero(target[boundary] != boundary))
        faces = target[faces]
    split = 0
    for _ in range(_SPLIT_PASSES):
        faces, origin, count = _split_t_junctions(
            vertices, faces, origin, face_part[origin], solid[origin], tolerance
        )
        split += count
        if not count:
            break
    after = _open_edges(faces, face_part[origin], solid[origin])
    if not welded and not split:
        return vertices, faces, origin, []
    closed = before - _length(vertices, after)
    touched = sorted({part_names[p] for p in face_part[edges[:, 2]]})
    return (
        vertices,
        faces,
        origin,
        [
            f"closed hair-line cracks of closed bodies (parts: {', '.join(touched)}): welded {welded} "
            f"vertices and split {split} triangles at T-junctions, closing {closed:.4g} m of open edges; "
            f"gaps up to {tolerance:.3g} m ({CRACK_TOLERANCE:g} of the model size) count as cracks"
        ],
    )


def _open_edges(
    faces: NDArray[np.int64], face_part: NDArray[np.int32], solid: NDArray[np.bool_]
) -> NDArray[np.int64]:
    """Edges used once by the closed-body faces of their part: (n, 3) of vertex, vertex, face."""
    owner = np.flatnonzero(solid)
    keys, position = _edges(
        faces[solid], np.zeros(int(solid.sum()), np.int32)
    )  # closed bodies may span parts
    once = _uses(keys) == 1
    directed = faces[solid][:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    return np.column_stack([directed[once], owner[position[once]]]).astype(np.int64)


def _length(vertices: NDArray[np.float64], edges: NDArray[np.int64]) -> float:
    """Total length [m] of ``edges`` (rows of vertex, vertex, ...)."""
    return float(np.linalg.norm(vertices[edges[:, 0]] - vertices[edges[:, 1]], axis=1).sum())


def _junction_candidates(edges: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Pairs (open edge, boundary vertex) where the vertex may lie on the edge: the far end
    of an open edge that shares an end with it. A T-junction's vertex is found so (a chain of them one
    per pass), and the work is linear in the number of open edges."""
    n = len(edges)
    _, key = np.unique(np.r_[edges[:, 0], edges[:, 1]], return_inverse=True)
    incidence = scipy.sparse.csr_matrix((np.ones(2 * n), (key, np.r_[np.arange(n), np.arange(n)])))
    touching = (incidence.T @ incidence).tocoo()  # edges sharing an end (and each edge with itself)
    first, second = touching.row.astype(np.int64), touching.col.astype(np.int64)
    keep = first != second
    first, second = first[keep], second[keep]
    # the end of ``first`` that is not an end of ``second``
    shared_a = (edges[first, 0] == edges[second, 0]) | (edges[first, 0] == edges[second, 1])
    far = np.where(shared_a, edges[first, 1], edges[first, 0])
    return second, far


def _split_t_junctions(
    vertices: NDArray[np.float64],
    faces: NDArray[np.int64],
    origin: NDArray[np.int64],
    face_part: NDArray[np.int32],
    solid: NDArray[np.bool_],
    tolerance: float,
) -> tuple[NDArray[np.int64], NDArray[np.int64], int]:
    """One pass: split each open edge that a boundary vertex lies on (within ``tolerance``,
    away from its ends) at that vertex; each face is split at most once. Returns faces, origin, count."""
    edges = _open_edges(faces, face_part, solid)
    if not len(edges):
        return faces, origin, 0
    edge, vertex = _junction_candidates(edges)
    a, b = vertices[edges[:, 0]], vertices[edges[:, 1]]
    half = np.linalg.norm(b - a, axis=1) / 2
    p, ea, eb = vertices[vertex], a[edge], b[edge]
    t = np.einsum("ij,ij->i", p - ea, eb - ea) / np.maximum(4 * half[edge] ** 2, 1e-300)
    gap = np.linalg.norm(ea + t[:, None] * (eb - ea) - p, axis=1)
    ends = np.minimum(np.linalg.norm(p - ea, axis=1), np.linalg.norm(p - eb, axis=1))
    ok = (
        (vertex != edges[edge, 0])
        & (vertex != edges[edge, 1])
        & (t > 0)
        & (t < 1)
        & (gap <= tolerance)
        & (ends > tolerance)
    )
    edge, vertex = edge[ok], vertex[ok]
    split_faces, first = np.unique(edges[edge, 2], return_index=True)
    if not len(split_faces):
        return faces, origin, 0
    # each split face's corners p, q, r with its open edge (x, y) as p -> q, and the vertex v on it
    x, y, v = edges[edge[first], 0], edges[edge[first], 1], vertex[first]
    corners = faces[split_faces]
    following = np.roll(corners, -1, axis=1)
    on_edge = ((corners == x[:, None]) & (following == y[:, None])) | (
        (corners == y[:, None]) & (following == x[:, None])
    )
    rows, at = np.arange(len(split_faces)), on_edge.argmax(axis=1)
    p, q, r = corners[rows, at], corners[rows, (at + 1) % 3], corners[rows, (at + 2) % 3]
    halves = np.stack([np.column_stack([p, v, r]), np.column_stack([v, q, r])], axis=1).reshape(-1, 3)
    keep = np.ones(len(faces), dtype=bool)
    keep[split_faces] = False
    faces = np.concatenate([faces[keep], halves.astype(np.int64)])
    origin = np.concatenate([origin[keep], np.repeat(origin[split_faces], 2)])
    return faces, origin, len(split_faces)


def _merge_vertices(
    vertices: NDArray[np.float64], faces: NDArray[np.int64]
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Merge vertices that coincide to ``MERGE_TOLERANCE`` of the model size."""
    scale = float(np.ptp(vertices, axis=0).max()) if len(vertices) else 0.0
    quantum = MERGE_TOLERANCE * scale if scale > 0 else 1.0
    keys = np.round(vertices / quantum).astype(np.int64)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return vertices[first], inverse.reshape(-1)[faces]


def _edges(
    faces: NDArray[np.int64], face_part: NDArray[np.int32]
) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Undirected edge keys (3 n,), one per edge of each part (a part's edges are its own), and the
    face of each."""
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    lo, hi = directed.min(axis=1), directed.max(axis=1)
    part = np.repeat(np.asarray(face_part, dtype=np.int64), 3)
    n = int(faces.max()) + 1 if len(faces) else 1
    if (int(part.max()) + 1 if len(part) else 1) * n * n < 2**62:
        keys = (part * n + lo) * n + hi
    else:  # too many vertices and parts for one int64 key
        keys = np.unique(np.column_stack([part, lo, hi]), axis=0, return_inverse=True)[1].reshape(-1)
    return keys.astype(np.int64), np.repeat(np.arange(len(faces)), 3)


def _edge_defects(
    faces: NDArray[np.int64], face_part: NDArray[np.int32], part_names: tuple[str, ...]
) -> tuple[dict[str, int], dict[str, int], dict[str, tuple[int, tuple[str, ...]]]]:
    """Per part, the number of edges used by one face (open) and by more than two (non-manifold), over
    all closed-body faces; and for a part open on its own, its own boundary edges and the parts whose
    faces close them."""
    if not len(faces):
        return {}, {}, {}
    keys, owner = _edges(faces, np.zeros_like(face_part))
    own, _ = _edges(faces, face_part)
    per_edge, per_own = _uses(keys), _uses(own)

    def tally(mask: NDArray[np.bool_]) -> dict[str, int]:
        edge_part = np.unique(np.column_stack([keys[mask], face_part[owner[mask]]]), axis=0)
        parts, n = np.unique(edge_part[:, 1], return_counts=True)
        return {part_names[p]: int(c) for p, c in zip(parts, n, strict=True)}

    alone = (per_own == 1) & (per_edge == 2)
    edge_parts = np.unique(np.column_stack([keys, face_part[owner]]), axis=0)
    closed_by = {}
    for part, count in tally(alone).items():
        index = part_names.index(part)
        mine = np.unique(keys[alone & (face_part[owner] == index)])
        others = np.unique(edge_parts[np.isin(edge_parts[:, 0], mine), 1])
        closed_by[part] = (count, tuple(part_names[p] for p in others if p != index))
    return tally(per_edge == 1), tally(per_edge > 2), closed_by


def _uses(keys: NDArray[np.int64]) -> NDArray[np.int64]:
    """How many times each entry's key occurs in ``keys``."""
    _, inverse, counts = np.unique(keys, return_inverse=True, return_counts=True)
    return counts[inverse.reshape(-1)]


def _orient_outward(
    vertices: NDArray[np.float64],
    faces: NDArray[np.int64],
    face_part: NDArray[np.int32],
    part_names: tuple[str, ...],
    source: str,
) -> tuple[NDArray[np.int64], list[str]]:
    """Make the winding of each closed body consistent and outward; say what was flipped.

    Each face gets two states, kept and flipped. Two faces sharing an edge agree when they run the
    edge in opposite directions; agreeing states are joined in a graph of the 2 n states. On an
    orientable body the states then fall into two components; the one holding the first face's kept
    state is the consistent winding. A body whose signed volume is negative is then turned inside out.
    """
    notices = []
    n = len(faces)
    first, second, same_direction = _edge_pairs(faces, np.zeros_like(face_part))
    # agreeing states: (i kept, j kept) when the edge runs opposite ways, else (i kept, j flipped)
    a = np.r_[first, first + n]
    b = np.r_[second + n * same_direction, second + n * (1 - same_direction)]
    graph = scipy.sparse.coo_matrix((np.ones(len(a)), (a, b)), shape=(2 * n, 2 * n))
    labels = connected_components(graph, directed=False)[1]
    kept_label, flipped_label = labels[:n], labels[n:]
    if np.any(kept_label == flipped_label):
        part = part_names[face_part[np.argmax(kept_label == flipped_label)]]
        raise MeshError(
            "is not orientable (a Moebius-like surface)",
            path=source,
            part=part,
            hint="rebuild it as a closed body or declare it a sheet",
        )
    body_graph = scipy.sparse.coo_matrix((np.ones(len(first)), (first, second)), shape=(n, n))
    body = connected_components(body_graph, directed=False)[1]
    root = np.full(body.max() + 1, n)
    np.minimum.at(root, body, np.arange(n))
    flip = flipped_label == kept_label[root[body]]
    if flip.any():
        faces = faces.copy()
        faces[flip] = faces[flip][:, ::-1]
        names = sorted({part_names[p] for p in face_part[flip]})
        notices.append(
            f"made the winding of {int(flip.sum())} triangles consistent with their neighbours "
            f"(parts: {', '.join(names)})"
        )
    corners = vertices[faces]
    tet = np.einsum("ij,ij->i", corners[:, 0], np.cross(corners[:, 1], corners[:, 2]))
    inward = np.flatnonzero(np.bincount(body, weights=tet) < 0)
    if len(inward):
        turn = np.isin(body, inward)
        faces = faces.copy()
        faces[turn] = faces[turn][:, ::-1]
        names = sorted({part_names[p] for p in face_part[turn]})
        notices.append(
            f"{len(inward)} closed bodies were wound inward (negative signed volume); "
            f"flipped {int(turn.sum())} triangles to make normals point out (parts: {', '.join(names)})"
        )
    return faces, notices


def _edge_pairs(
    faces: NDArray[np.int64], face_part: NDArray[np.int32]
) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
    """Faces of one part sharing each manifold edge, and 1 where both run the edge in the same direction."""
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    keys, owner = _edges(faces, face_part)
    forward = (directed[:, 0] < directed[:, 1]).astype(np.int64)
    order = np.argsort(keys, kind="stable")
    paired = keys[order][1:] == keys[order][:-1]
    i, j = order[:-1][paired], order[1:][paired]
    return owner[i], owner[j], (forward[i] == forward[j]).astype(np.int64)
