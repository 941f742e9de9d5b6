"""A survey of what a mesh's CAD export did that the shadow pass, reflections and drag care about.

CAD exports are not the meshes a solver is written for: borders left open, sheets of either winding,
faces written with their own copies of shared vertices or a hair apart, parts sunk into each other,
faces written twice or laid on one another, needle-thin triangles, and parts made of many loose
pieces. :func:`survey` counts each of these by part, with the edges and corners found by position
(:mod:`sunwind.geometry.rays.mesh_edges`) and the lines where facets cross
(:mod:`sunwind.geometry.rays.crossings`), the same as the shadow pass sees them; :func:`survey_mesh`
does so for a mesh as read, before the checks of loading (which it does not need to pass).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np
import scipy.sparse
from numpy.typing import NDArray
from scipy.sparse.csgraph import connected_components

from sunwind.geometry.checks import CRACK_TOLERANCE, DEGENERATE_RATIO, MERGE_TOLERANCE
from sunwind.geometry.errors import MeshError
from sunwind.geometry.materials import MaterialTable
from sunwind.geometry.mesh_data import MeshData
from sunwind.geometry.overlaps import box_pairs, stacked
from sunwind.geometry.rays.crossings import crossings
from sunwind.geometry.rays.mesh_edges import WELD_SHARE, MeshEdges, mesh_edges
from sunwind.geometry.rays.outline import SPACING_SHARE, WIDTH_PERCENTILE
from sunwind.geometry.rays.scene import ORIGIN_OFFSET
from sunwind.geometry.sides import SOLID, TWO_SIDED
from sunwind.geometry.spacecraft import Spacecraft

#: Open edges and layers this close, as a share of the model size (largest bounding-box extent), count
#: as a gap and as laid on one another.
NEAR_SHARE = 1e-3
#: A facet whose longest edge exceeds this many times its least altitude is a sliver.
SLIVER_ASPECT = 1000.0
#: Open edges across a gap run within this angle of each other (cosine of 15 deg).
GAP_PARALLEL = float(np.cos(np.radians(15.0)))
#: Layers are parallel to within this angle (cosine of 1 deg).
LAYER_PARALLEL = float(np.cos(np.radians(1.0)))


@dataclass(frozen=True)
class Tally:
    """Edges of one kind: how many, their total length, and how many touch each part.

    Attributes
    ----------
    count : int
        Edges.
    length_m : float
        Their total length [m].
    parts : dict of str -> int
        Edges with a facet of each part on them (an edge between two parts counts in both).

    Examples
    --------
    >>> from sunwind.meshes import box_wing
    >>> found = survey_mesh(box_wing(facet_size=0.5))
    >>> found.open_edges  # the borders of the two wings
    Tally(count=32, length_m=16.0, parts={'wing_left': 16, 'wing_right': 16})
    """

    count: int
    length_m: float
    parts: dict[str, int]


@dataclass(frozen=True)
class Crossing:
    """Two parts (or one part with itself) whose facets pass through each other.

    Attributes
    ----------
    parts : tuple of (str, str)
        The two parts' names.
    length_m : float
        Total length of the lines where their facets cross [m].
    facet_pairs : int
        Pairs of facets that cross.

    Examples
    --------
    >>> import numpy as np
    >>> from sunwind.geometry.mesh_data import MeshData
    >>> from sunwind.meshes import box
    >>> a, b = box(), box()
    >>> b = MeshData(b.vertices + 0.5, b.faces, b.face_part, ["other"], b.face_material)
    >>> survey_mesh(MeshData.concatenate([a, b])).crossings
    (Crossing(parts=('box', 'other'), length_m=3.0, facet_pairs=...),)
    """

    parts: tuple[str, str]
    length_m: float  # total length of the lines where their facets cross [m]
    facet_pairs: int  # pairs of facets that cross


@dataclass(frozen=True)
class Layers:
    """Facets laid on one another whose sides face the same way, and the area they share.

    Attributes
    ----------
    facets : int
        Facets with another on them.
    area_m2 : float
        Area shared, summed over the pairs [m^2].
    coplanar_area_m2 : float
        Of it, area whose layers are closer than the shadow rays' origin offset, one plane to the rays
        (neither shades the other by a ray) [m^2].
    parts : dict of str -> int
        Facets of each part.

    Examples
    --------
    >>> from sunwind.geometry.mesh_data import MeshData
    >>> from sunwind.meshes import plate
    >>> sheet = plate(divisions=1)
    >>> twice = MeshData.concatenate([sheet, sheet])  # a face written twice
    >>> found = survey_mesh(twice, [1, 1, 1, 1])
    >>> layers = found.coincident
    >>> layers.facets, round(layers.area_m2, 6), round(layers.coplanar_area_m2, 6), layers.parts
    (4, 1.0, 1.0, {'plate': 4})
    """

    facets: int
    area_m2: float
    coplanar_area_m2: float
    parts: dict[str, int]


@dataclass(frozen=True)
class Slivers:
    """Needle-thin facets, and the spread of facet sizes.

    Attributes
    ----------
    count : int
        Facets whose longest edge exceeds ``SLIVER_ASPECT`` times their least altitude.
    parts : dict of str -> int
        Of them, in each part.
    degenerate : int
        Facets without area by the loader's measure (dropped on loading), left out of everything else.
    area_min_m2, area_max_m2 : float
        Smallest and largest facet area [m^2].
    width_p10_m : float
        10th percentile of the facets' least altitudes [m].
    probe_spacing_m : float
        The shadow pass's spacing of outline probes drawn from it [m] (before widening for the budget).

    Examples
    --------
    >>> from sunwind.meshes import box_wing
    >>> slivers = survey_mesh(box_wing(facet_size=0.5)).slivers
    >>> slivers.count, slivers.area_min_m2, round(slivers.width_p10_m, 4)
    (0, 0.125, 0.3536)
    """

    count: int
    parts: dict[str, int]
    degenerate: int
    area_min_m2: float
    area_max_m2: float
    width_p10_m: float
    probe_spacing_m: float


@dataclass(frozen=True)
class Survey:
    """Hold what :func:`survey` found.

    Every edge and corner is found by position: corners within ``mesh_edges.WELD_SHARE`` of the
    half-size are one.

    Attributes
    ----------
    facets, corners : int
        Facets, and welded corners.
    size_m : float
        Largest extent of the bounding box [m].
    weld_m, merge_m, crack_m, offset_m : float
        Corners closer than ``weld_m`` are one here and in the shadow pass; loading merges vertices
        closer than ``merge_m`` and closes closed bodies' cracks narrower than ``crack_m``; shadow rays
        start ``offset_m`` off the surface [m].
    open_edges, nonmanifold_edges : Tally
        Edges with one facet, and with more than two.
    mixed_winding : Tally
        Edges with two facets that run them the same way (wound inconsistently).
    mixed_on_sheets : int
        Of them, edges with a sheet's facet: loading makes closed bodies' winding consistent, not sheets'.
    seams : Tally
        Edges whose facets meet at coinciding corners that are separate vertices.
    seams_unmerged : int
        Of them, edges whose corners lie farther apart than loading merges (``MERGE_TOLERANCE``).
    gaps : Tally
        Open edges within ``gap_m`` of another open edge across empty space.
    gap_m : float
        ``NEAR_SHARE`` of the size [m].
    crossings : tuple of Crossing
        Pairs of parts whose facets cross, longest crossing first.
    coincident, layered : Layers
        Facets on the same welded corners as another, and other facets laid within ``gap_m`` of another.
    slivers : Slivers
        Needle-thin facets and the spread of facet sizes.
    shells : dict of str -> int
        Pieces of each part that share no corner with each other.

    Examples
    --------
    >>> from sunwind.meshes import box_wing
    >>> found = survey_mesh(box_wing(facet_size=0.5))
    >>> found.facets, found.corners, found.size_m, found.shells
    (96, 68, 8.0, {'bus': 1, 'wing_left': 1, 'wing_right': 1})
    """

    facets: int
    corners: int
    size_m: float
    weld_m: float
    merge_m: float
    crack_m: float
    offset_m: float
    open_edges: Tally
    nonmanifold_edges: Tally
    mixed_winding: Tally
    mixed_on_sheets: int
    seams: Tally
    seams_unmerged: int
    gaps: Tally
    gap_m: float
    crossings: tuple[Crossing, ...]
    coincident: Layers
    layered: Layers
    slivers: Slivers
    shells: dict[str, int]

    def to_json(self) -> dict:
        """Convert the survey to JSON-ready nested dicts, keyed by the field names.

        Returns
        -------
        dict
            The fields; ``crossings`` as a list of dicts with ``parts`` as a list.

        Examples
        --------
        >>> from sunwind.meshes.primitives import box
        >>> found = survey_mesh(box()).to_json()
        >>> found["open_edges"], found["crossings"], found["shells"]
        ({'count': 0, 'length_m': 0.0, 'parts': {}}, [], {'box': 1})
        """
        out = asdict(self)
        out["crossings"] = [{**c, "parts": list(c["parts"])} for c in out["crossings"]]
        return out


def survey(craft: Spacecraft) -> Survey:
    """Survey a model's mesh for what CAD exports do (module docstring).

    Parameters
    ----------
    craft : Spacecraft
        The model; only its vertices, faces, parts and facet kinds are read.

    Returns
    -------
    Survey
        Counts and lengths by part of each thing found.

    Examples
    --------
    >>> from sunwind.geometry import build_spacecraft, Material
    >>> from sunwind.meshes.primitives import box
    >>> found = survey(build_spacecraft(box(), uniform=Material("paint", 0.5, 0.5, 0.0)))
    >>> found.open_edges.count, found.mixed_winding.count, found.shells
    (0, 0, {'box': 1})
    """
    edges = mesh_edges(craft)
    vertices, triangles = craft.vertices, craft.triangles
    size = float(np.ptp(triangles.reshape(-1, 3), axis=0).max())
    count = edges.edge_facet_count()
    length = np.linalg.norm(vertices[edges.ends[:, 1]] - vertices[edges.ends[:, 0]], axis=1)
    tally = _Tallier(edges, length, craft.facet_part, craft.part_names)
    two = np.flatnonzero(count == 2)
    first, second = edges.facet[edges.start[two]], edges.facet[edges.start[two] + 1]
    same_way = edges.way[edges.start[two]] == edges.way[edges.start[two] + 1]
    sheet = (craft.facet_kind[first] != SOLID) | (craft.facet_kind[second] != SOLID)
    seams, unmerged = _seams(craft, edges, MERGE_TOLERANCE * size)
    gap = NEAR_SHARE * size
    coincident, layered = _layers(craft, edges, gap, ORIGIN_OFFSET * size / 2)
    return Survey(
        facets=craft.n_facets,
        corners=len(np.unique(edges.corner[craft.faces])),
        size_m=size,
        weld_m=WELD_SHARE * size / 2,
        merge_m=MERGE_TOLERANCE * size,
        crack_m=CRACK_TOLERANCE * size,
        offset_m=ORIGIN_OFFSET * size / 2,
        open_edges=tally(count == 1),
        nonmanifold_edges=tally(count > 2),
        mixed_winding=tally(_mask(len(count), two[same_way])),
        mixed_on_sheets=int(np.count_nonzero(same_way & sheet)),
        seams=tally(seams),
        seams_unmerged=int(np.count_nonzero(unmerged)),
        gaps=tally(_mask(len(count), _gap_edges(craft, edges, gap))),
        gap_m=gap,
        crossings=_crossings(craft),
        coincident=coincident,
        layered=layered,
        slivers=_slivers(craft),
        shells=_shells(craft, edges),
    )


def survey_mesh(mesh: MeshData, facet_kind: NDArray[np.int8] | None = None) -> Survey:
    """Survey a mesh as read, before the checks of loading (:func:`survey`).

    An open part not declared a sheet, a part without material, or inconsistent winding do not stop it.

    Parameters
    ----------
    mesh : MeshData
        The mesh [m].
    facet_kind : (n_faces,) int8, optional
        ``SOLID``, ``ONE_SIDED`` or ``TWO_SIDED`` of each face, as declared
        (:func:`sunwind.geometry.sides.declared_kinds`); default all ``SOLID``.

    Returns
    -------
    Survey
        What :func:`survey` finds on the mesh.

    Raises
    ------
    MeshError
        No triangle, or coordinates that are NaN or infinite: nothing can be measured.

    Examples
    --------
    >>> from dataclasses import replace
    >>> from sunwind.meshes.primitives import box
    >>> mesh = box()
    >>> flipped = mesh.faces.copy()
    >>> flipped[:2] = flipped[:2, ::-1]  # one side of the box (two triangles) turned over
    >>> survey_mesh(replace(mesh, faces=flipped)).mixed_winding.count  # its four edges
    4
    """
    used = np.unique(mesh.faces)  # stray vertices no face uses are left out
    if not len(used):
        raise MeshError("has no triangle: nothing to survey", path=mesh.source, hint="check the mesh file")
    if not np.isfinite(mesh.vertices[used]).all():
        raise MeshError(
            "has vertices with NaN or infinite coordinates: nothing to survey",
            path=mesh.source,
            hint="fix or remove them in the mesh file",
        )
    n = mesh.n_faces
    kind = np.full(n, SOLID, dtype=np.int8) if facet_kind is None else np.array(facet_kind, dtype=np.int8)
    craft = Spacecraft(
        vertices=mesh.vertices[used],
        faces=np.searchsorted(used, mesh.faces),
        facet_part=mesh.face_part.copy(),
        part_names=mesh.part_names,
        facet_kind=kind,
        side_facet=np.arange(n),
        side_sign=np.ones(n),
        side_material=np.zeros(n, dtype=np.int32),
        materials=MaterialTable.from_materials([]),
        part_materials={},
        source=mesh.source,
    )
    return survey(craft)


class _Tallier:
    """Tallies of edge masks: count, length and edges per part (an edge counts once in each part on it)."""

    def __init__(self, edges: MeshEdges, length: NDArray, facet_part: NDArray, names: tuple[str, ...]):
        self.edge_of = np.repeat(np.arange(edges.n_edges), edges.edge_facet_count())
        self.part_of = facet_part[edges.facet].astype(np.int64)
        self.length, self.names = length, names

    def __call__(self, mask: NDArray[np.bool_]) -> Tally:
        on = mask[self.edge_of]
        pairs = np.unique(self.edge_of[on] * len(self.names) + self.part_of[on])
        return Tally(
            int(mask.sum()), float(self.length[mask].sum()), _by_part(pairs % len(self.names), self.names)
        )


def _mask(n: int, chosen: NDArray[np.int64]) -> NDArray[np.bool_]:
    out = np.zeros(n, dtype=bool)
    out[chosen] = True
    return out


def _by_part(part: NDArray[np.int64], names: tuple[str, ...]) -> dict[str, int]:
    """How many entries of ``part`` name each part, for the parts named at all."""
    counts = np.bincount(np.asarray(part, dtype=np.int64), minlength=len(names))
    return {names[p]: int(counts[p]) for p in np.flatnonzero(counts)}


def _seams(
    craft: Spacecraft, edges: MeshEdges, merge_m: float
) -> tuple[NDArray[np.bool_], NDArray[np.bool_]]:
    """Edges whose facets run them between different vertices (welded by position only), and those of
    them whose corners lie farther apart than ``merge_m``, (n_edges,) each."""
    slot = np.flatnonzero(edges.facet_edges.reshape(-1) >= 0)
    facet, k = slot // 3, slot % 3
    edge = edges.facet_edges.reshape(-1)[slot]
    a, b = craft.faces[facet, k], craft.faces[facet, (k + 1) % 3]
    forward = edges.corner[a] < edges.corner[b]
    a, b = np.where(forward, a, b), np.where(forward, b, a)  # a at end 0, b at end 1
    other = np.flatnonzero((a != edges.ends[edge, 0]) | (b != edges.ends[edge, 1]))  # not the edge's own
    v = craft.vertices
    apart = np.maximum(
        np.linalg.norm(v[a[other]] - v[edges.ends[edge[other], 0]], axis=1),
        np.linalg.norm(v[b[other]] - v[edges.ends[edge[other], 1]], axis=1),
    )
    seam = np.bincount(edge[other], minlength=edges.n_edges) > 0
    unmerged = np.bincount(edge[other[apart > merge_m]], minlength=edges.n_edges) > 0
    return seam, unmerged


def _gap_edges(craft: Spacecraft, edges: MeshEdges, gap_m: float) -> NDArray[np.int64]:
    """Open edges within ``gap_m`` of another open edge that shares no corner with them, runs within
    15 deg of them, lies beside them (the edge's midpoint falls between the other's ends) and across
    empty space (the edge's facet lies on its far side, so that a narrow strip's two borders are no gap)."""
    count = edges.edge_facet_count()
    open_ = np.flatnonzero(count == 1)
    ends = craft.vertices[edges.ends[open_]]
    near = box_pairs(ends, gap_m)
    i, j = near.first, near.second
    corner = edges.corner[edges.ends[open_]]
    apart = (corner[i][:, :, None] != corner[j][:, None, :]).all(axis=(1, 2))
    i, j = i[apart], j[apart]
    a, b = np.concatenate([i, j]), np.concatenate([j, i])  # each edge of a pair against the other
    along_a, along_b = ends[a, 1] - ends[a, 0], ends[b, 1] - ends[b, 0]
    size_a, size_b = np.linalg.norm(along_a, axis=1), np.linalg.norm(along_b, axis=1)
    middle = ends[a].mean(axis=1)
    t = np.einsum("nd,nd->n", middle - ends[b, 0], along_b) / size_b**2
    nearest = ends[b, 0] + t[:, None] * along_b
    centroid = craft.facet_centroids[edges.facet[edges.start[open_[a]]]]
    ok = (
        (np.abs(np.einsum("nd,nd->n", along_a, along_b)) >= GAP_PARALLEL * size_a * size_b)
        & (t > 0)
        & (t < 1)
        & (np.linalg.norm(nearest - middle, axis=1) <= gap_m)
        & (np.einsum("nd,nd->n", centroid - middle, nearest - middle) <= 0)
    )
    return open_[np.unique(a[ok])]


def _crossings(craft: Spacecraft) -> tuple[Crossing, ...]:
    """Pairs of parts whose facets cross (:func:`~sunwind.geometry.rays.crossings.crossings`), with the
    length of the lines where they do, longest first."""
    lines = crossings(craft)
    n_facets = craft.n_facets
    facet = np.repeat(np.arange(n_facets), np.diff(lines.start))
    key, reverse = facet * n_facets + lines.other, lines.other * n_facets + facet
    # a crossing line is listed on both facets (an outline a coplanar cover draws, on the covered one only)
    once = (facet < lines.other) & np.isin(key, reverse)
    facet, other, w = facet[once], lines.other[once], lines.segments[once]
    t = craft.triangles[facet]
    step = w[:, 1] - w[:, 0]
    length = np.linalg.norm(step[:, :1] * (t[:, 1] - t[:, 0]) + step[:, 1:] * (t[:, 2] - t[:, 0]), axis=1)
    n = len(craft.part_names)
    low = np.minimum(craft.facet_part[facet], craft.facet_part[other]).astype(np.int64)
    high = np.maximum(craft.facet_part[facet], craft.facet_part[other]).astype(np.int64)
    keys, which = np.unique(low * n + high, return_inverse=True)
    total = np.bincount(which, weights=length, minlength=len(keys))
    pairs = np.bincount(which, minlength=len(keys))
    found = [
        Crossing((craft.part_names[key // n], craft.part_names[key % n]), float(total[k]), int(pairs[k]))
        for k, key in enumerate(keys)
    ]
    return tuple(sorted(found, key=lambda c: -c.length_m))


def _layers(craft: Spacecraft, edges: MeshEdges, near_m: float, offset_m: float) -> tuple[Layers, Layers]:
    """Facets on the same welded corners as another (coincident) and other facets laid within
    ``near_m`` of another, parallel and overlapping it (layered), where sides of both face one way;
    the area of layers closer than ``offset_m``."""
    found = stacked(craft.triangles, near_m, LAYER_PARALLEL)
    i, j = found.first, found.second
    same_way = np.einsum("nd,nd->n", craft.facet_normals[i], craft.facet_normals[j]) > 0
    keep = same_way | (craft.facet_kind[i] == TWO_SIDED) | (craft.facet_kind[j] == TWO_SIDED)
    i, j, shared, height = i[keep], j[keep], found.area_m2[keep], found.height_m[keep]
    corners = np.sort(edges.corner[craft.faces], axis=1)
    same = (corners[i] == corners[j]).all(axis=1)
    close = np.abs(height) <= offset_m

    def layers(mask: NDArray[np.bool_]) -> Layers:
        facets = np.unique(np.concatenate([i[mask], j[mask]]))
        return Layers(
            len(facets),
            float(shared[mask].sum()),
            float(shared[mask & close].sum()),
            _by_part(craft.facet_part[facets], craft.part_names),
        )

    return layers(same), layers(~same)


def _slivers(craft: Spacecraft) -> Slivers:
    """Facets longer than ``SLIVER_ASPECT`` times their least altitude, degenerate facets (the loader's
    ``DEGENERATE_RATIO``), the facet areas' range and the width the shadow pass spaces its probes by."""
    triangles, area = craft.triangles, craft.facet_areas
    longest = np.linalg.norm(triangles - np.roll(triangles, 1, axis=1), axis=2).max(axis=1)
    proper = area > DEGENERATE_RATIO * longest**2
    width = 2 * area[proper] / longest[proper]
    sliver = np.flatnonzero(proper)[longest[proper] > SLIVER_ASPECT * width]
    p10 = float(np.percentile(width, WIDTH_PERCENTILE)) if len(width) else 0.0
    return Slivers(
        count=len(sliver),
        parts=_by_part(craft.facet_part[sliver], craft.part_names),
        degenerate=int(np.count_nonzero(~proper)),
        area_min_m2=float(area[proper].min()) if proper.any() else 0.0,
        area_max_m2=float(area[proper].max()) if proper.any() else 0.0,
        width_p10_m=p10,
        probe_spacing_m=SPACING_SHARE * p10,
    )


def _shells(craft: Spacecraft, edges: MeshEdges) -> dict[str, int]:
    """Pieces of each part: facets of the part joined through their welded corners."""
    n = craft.n_facets
    part = np.repeat(craft.facet_part.astype(np.int64), 3)
    _, node = np.unique(part * edges.n_corners + edges.corner[craft.faces].reshape(-1), return_inverse=True)
    size = n + int(node.max()) + 1
    graph = scipy.sparse.coo_matrix(
        (np.ones(3 * n), (np.repeat(np.arange(n), 3), n + node)), shape=(size, size)
    )
    label = connected_components(graph, directed=False)[1][:n]
    pieces = np.unique(craft.facet_part.astype(np.int64) * size + label) // size
    return _by_part(pieces, craft.part_names)
