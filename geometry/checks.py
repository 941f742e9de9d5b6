"""Mesh checks with clear outcomes: non-finite coordinates, degenerate triangles, open edges, winding."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse
from numpy.typing import NDArray
from scipy.sparse.csgraph import connected_components

from sunwind.geometry import triangles as tri
from sunwind.geometry.errors import MeshError
from sunwind.geometry.sides import SOLID

#: Vertices closer than this share of the model size are merged before connectivity is judged.
MERGE_TOLERANCE = 1e-9
#: A triangle whose area is below this share of its longest edge squared is degenerate (a needle or
#: a point); such triangles carry no area and are dropped and counted.
DEGENERATE_RATIO = 1e-10


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
        Per part, edges of closed-body (``SOLID``) faces used by one face, or by more than two.
    notices : tuple of str
        One line per repair made (faces dropped, winding fixed).
    """

    vertices: NDArray[np.float64]
    faces: NDArray[np.int64]
    kept: NDArray[np.int64]
    dropped_degenerate: int
    open_edges: dict[str, int]
    nonmanifold_edges: dict[str, int]
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

    Non-finite coordinates are an error. Coincident vertices are merged. Triangles with a repeated
    vertex or (near) zero area are dropped and counted. Faces of closed bodies (``face_kind ==
    SOLID``) are checked for open and non-manifold edges (reported, not raised: the caller decides);
    inconsistent winding is made consistent and a body wound inward (negative signed volume) is
    flipped, each with a notice.

    Raises
    ------
    MeshError
        Non-finite vertex coordinates, or no triangle left.
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
    notices: list[str] = []
    repeated = (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 0] == faces[:, 2])
    kept = np.flatnonzero(~repeated)
    solid = kept[face_kind[kept] == SOLID]
    open_edges, nonmanifold_edges = _edge_defects(faces[solid], face_part[solid], part_names)
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
    return MeshCheck(vertices, faces[kept], kept, dropped, open_edges, nonmanifold_edges, tuple(notices))


def _merge_vertices(
    vertices: NDArray[np.float64], faces: NDArray[np.int64]
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Merge vertices that coincide to ``MERGE_TOLERANCE`` of the model size."""
    scale = float(np.ptp(vertices, axis=0).max()) if len(vertices) else 0.0
    quantum = MERGE_TOLERANCE * scale if scale > 0 else 1.0
    keys = np.round(vertices / quantum).astype(np.int64)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return vertices[first], inverse.reshape(-1)[faces]


def _edges(faces: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Undirected edge keys (3 n,) and the face of each."""
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    lo, hi = directed.min(axis=1), directed.max(axis=1)
    n = int(faces.max()) + 1 if len(faces) else 1
    return lo * n + hi, np.repeat(np.arange(len(faces)), 3)


def _edge_defects(
    faces: NDArray[np.int64], face_part: NDArray[np.int32], part_names: tuple[str, ...]
) -> tuple[dict[str, int], dict[str, int]]:
    """Per part, the number of edges used by one face (open) and by more than two (non-manifold)."""
    if not len(faces):
        return {}, {}
    keys, owner = _edges(faces)
    _, inverse, counts = np.unique(keys, return_inverse=True, return_counts=True)
    per_edge = counts[inverse]

    def tally(mask: NDArray[np.bool_]) -> dict[str, int]:
        edge_part = np.unique(np.column_stack([keys[mask], face_part[owner[mask]]]), axis=0)
        parts, n = np.unique(edge_part[:, 1], return_counts=True)
        return {part_names[p]: int(c) for p, c in zip(parts, n, strict=True)}

    return tally(per_edge == 1), tally(per_edge > 2)


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
    first, second, same_direction = _edge_pairs(faces)
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


def _edge_pairs(faces: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
    """Faces sharing each manifold edge, and 1 where both run the edge in the same direction."""
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    keys, owner = _edges(faces)
    forward = (directed[:, 0] < directed[:, 1]).astype(np.int64)
    order = np.argsort(keys, kind="stable")
    paired = keys[order][1:] == keys[order][:-1]
    i, j = order[:-1][paired], order[1:][paired]
    return owner[i], owner[j], (forward[i] == forward[j]).astype(np.int64)
