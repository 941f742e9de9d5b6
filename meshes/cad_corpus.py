"""The CAD corpus: named models, each with one export defect or all of them, and a stepped closed bus.

:func:`corpus` lists the models the shadow pass must stay exact on: the small sample spacecraft
(:func:`sunwind.meshes.samples.sample_spacecraft`) re-exported with each defect of
:mod:`sunwind.meshes.cad` alone and with all of them at once, and :func:`stepped_bus`, a watertight
one-part body whose centimetre lips, risers, steps and skirt sit beside metre-sized faces, as low-orbit
satellite exports have. :func:`box_union` builds such bodies: the boundary of a union of boxes on the
rectilinear grid of their faces, watertight with outward winding by construction.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.geometry.errors import InputError
from sunwind.geometry.mesh_data import MeshData
from sunwind.meshes.arguments import check_positive
from sunwind.meshes.assembly import assemble
from sunwind.meshes.cad import (
    bolts,
    duplicate_layers,
    interpenetrating,
    mixed_winding,
    open_sheets,
    slivers,
    t_junctions,
    unwelded,
)
from sunwind.meshes.samples import sample_spacecraft

__all__ = ["CorpusEntry", "box_union", "corpus", "stepped_bus"]

#: Glob of the parts :func:`sunwind.meshes.cad.open_sheets` writes.
SHEET_GLOB = "*/sheet*"


@dataclass(frozen=True, eq=False)
class CorpusEntry:
    """One model of the CAD corpus.

    Attributes
    ----------
    name : str
        Short identifier, e.g. ``"unwelded"``.
    mesh : MeshData
        The model [m].
    two_sided : tuple of str
        Part globs to declare two-sided when loading (``build_spacecraft(..., two_sided=...)``): the open
        parts the defect made. The sample's own sheets are declared by the mesh (``two_sided_parts``).
    defect : str
        What is wrong with it, in one sentence.

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> entry = CorpusEntry("cube", box(), (), "none: a closed unit cube")
    >>> entry.name, entry.mesh.n_faces
    ('cube', 12)
    """

    name: str
    mesh: MeshData
    two_sided: tuple[str, ...]
    defect: str


def box_union(boxes: ArrayLike, max_cell_m: float | None = None, part: str = "body") -> MeshData:
    """The closed surface of a union of axis-aligned boxes: one part, watertight, wound outward.

    The boxes' faces set a rectilinear grid (intervals longer than ``max_cell_m`` cut into equal
    pieces); a cell is solid when its centre lies in a box. Every face between a solid cell and an
    empty one (or the outside) is two triangles on grid vertices, so neighbouring faces share whole
    edges and vertices: every edge has exactly two faces, the right-hand normals point out of the solid.

    Parameters
    ----------
    boxes : (n, 2, 3) float
        Low and high corner of each box [m].
    max_cell_m : float, optional
        Longest grid interval [m]; default no limit.
    part : str, optional
        Name of the one part.

    Returns
    -------
    MeshData
        The surface, on the grid's vertices, with ``metadata["shape"] == "box_union"``.

    Raises
    ------
    InputError
        Two solid cells meeting along an edge only (diagonal neighbours, a non-manifold edge), or an
        empty box.

    Examples
    --------
    >>> step = box_union([[[0, 0, 0], [2, 1, 1]], [[0, 0, 1], [1, 1, 1.5]]])
    >>> step.n_faces  # a 2 x 1 x 1 block with a 1 x 1 x 0.5 step on it: 14 cell faces
    28
    """
    boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 2, 3)
    if not len(boxes) or np.any(boxes[:, 1] <= boxes[:, 0]) or not np.isfinite(boxes).all():
        raise InputError("every box needs finite corners with low < high on each axis")
    if max_cell_m is not None:
        check_positive(max_cell_m=max_cell_m)
    lines = [_grid_lines(boxes[:, :, axis].ravel(), max_cell_m) for axis in range(3)]
    mids = np.meshgrid(*[(g[1:] + g[:-1]) / 2 for g in lines], indexing="ij")
    centre = np.stack(mids, axis=-1)[..., None, :]
    solid = np.any(np.all((centre > boxes[:, 0]) & (centre < boxes[:, 1]), axis=-1), axis=-1)
    _refuse_edge_contacts(solid)
    shape = np.array([len(g) for g in lines])  # lattice vertices per axis
    quads = []
    for axis in range(3):  # one pass per axis: the faces normal to it
        b, c = (axis + 1) % 3, (axis + 2) % 3  # b x c = +axis
        padded = np.pad(solid, [(1, 1) if k == axis else (0, 0) for k in range(3)])
        below = np.take(padded, np.arange(shape[axis]), axis=axis)
        above = np.take(padded, np.arange(1, shape[axis] + 1), axis=axis)
        for outward, mask in ((True, below & ~above), (False, above & ~below)):
            at = np.argwhere(mask)  # (plane along axis, cell indices along the others)
            corner = []
            for db, dc in ((0, 0), (1, 0), (1, 1), (0, 1)):  # counter-clockwise seen from +axis
                point = at.copy()
                point[:, b] += db
                point[:, c] += dc
                corner.append(np.ravel_multi_index(point.T, shape))
            quad = np.stack(corner, axis=1)
            quads.append(quad if outward else quad[:, ::-1])
    quad = np.concatenate(quads)
    faces = np.concatenate([quad[:, [0, 1, 2]], quad[:, [0, 2, 3]]])
    used, faces = np.unique(faces, return_inverse=True)
    faces = faces.reshape(-1, 3)
    grid = np.stack(np.meshgrid(*lines, indexing="ij"), axis=-1).reshape(-1, 3)
    metadata = {"shape": "box_union", "boxes": boxes.tolist(), "max_cell_m": max_cell_m}
    return assemble(grid[used], faces, np.zeros(len(faces)), [part], metadata)


def stepped_bus(
    size: Sequence[float] = (1.6, 1.4, 1.2),
    lip_m: float = 0.02,
    riser_m: float = 0.01,
    skirt_m: float = 0.02,
    step_m: float = 0.01,
    max_cell_m: float = 0.5,
) -> MeshData:
    """A closed one-part bus with centimetre features beside metre faces, as low-orbit exports have.

    A box of ``size`` [m] centred at the origin with: its upper two thirds (z above ``size[2] / 6``) set
    back by ``step_m`` on the -x side (a step); a lip ``lip_m`` wide and high round the top face; four
    tiles ``riser_m`` thick on the +x face (risers, 5 cm apart); and a skirt ``skirt_m`` thick
    sticking out ``skirt_m`` round the bottom edge. Built by :func:`box_union`, so it is watertight and
    wound outward; faces are cut into cells at most ``max_cell_m`` long.

    Parameters
    ----------
    size : sequence of float, optional
        Edge lengths of the box along x, y, z [m], shape (3,).
    lip_m : float, optional
        Width and height of the lip round the top face [m].
    riser_m : float, optional
        Thickness of the four tiles on the +x face [m].
    skirt_m : float, optional
        Thickness and overhang of the skirt round the bottom edge [m].
    step_m : float, optional
        Set-back of the upper two thirds on the -x side [m].
    max_cell_m : float, optional
        Longest grid interval [m].

    Returns
    -------
    MeshData
        One closed part ``bus``, watertight and wound outward.

    Raises
    ------
    InputError
        If a length is not a finite number > 0, or a feature is not small beside the bus (over an
        eighth of its smallest half-size, or no room for the risers).

    Examples
    --------
    >>> bus = stepped_bus()
    >>> bus.part_names, bus.n_faces > 300
    (('bus',), True)
    """
    x, y, z = (float(s) / 2 for s in size)
    check_positive(x=x, y=y, z=z, lip_m=lip_m, riser_m=riser_m, skirt_m=skirt_m, step_m=step_m)
    if max(lip_m, skirt_m, step_m, riser_m) * 8 > min(x, y, z) or 0.15 + 0.05 > min(y, z) / 2:
        raise InputError("the features must be small beside the bus", hint="give a larger size")
    joint, w = z / 3, lip_m
    boxes = [
        [[-x, -y, -z], [x, y, joint]],
        [[-x + step_m, -y, joint], [x, y, z]],
        [[-x + step_m, -y, z], [x, -y + w, z + w]],  # the lip, four sides
        [[-x + step_m, y - w, z], [x, y, z + w]],
        [[-x + step_m, -y, z], [-x + step_m + w, y, z + w]],
        [[x - w, -y, z], [x, y, z + w]],
        [[-x - skirt_m, -y - skirt_m, -z], [x + skirt_m, y + skirt_m, -z + skirt_m]],
    ]
    for ys in ((-y + 0.1, -0.025), (0.025, y - 0.1)):  # 2 x 2 tiles on the +x face
        for zs in ((-z + 0.15, -0.025), (0.025, z - 0.15)):
            boxes.append([[x, ys[0], zs[0]], [x + riser_m, ys[1], zs[1]]])
    bus = box_union(boxes, max_cell_m, "bus")
    parameters = {"size": (2 * x, 2 * y, 2 * z), "lip_m": lip_m, "riser_m": riser_m, "skirt_m": skirt_m}
    metadata = {"shape": "stepped_bus", **parameters, "step_m": step_m, "max_cell_m": max_cell_m}
    return MeshData(
        bus.vertices,
        bus.faces,
        bus.face_part,
        bus.part_names,
        bus.face_material,
        source="<stepped_bus>",
        metadata=metadata,
    )


def corpus(triangles: int = 2000, seed: int = 0) -> tuple[CorpusEntry, ...]:
    """The named CAD corpus: the sample with each export defect alone, with all of them, and a bus.

    The sample is re-exported once per defect and once with every defect; the last entry is
    :func:`stepped_bus`.

    Every entry loads with ``build_spacecraft(entry.mesh, uniform=..., two_sided=entry.two_sided)``.
    At the default 2000 (1884) triangles of the sample the models hold 1884 to about 4000 triangles.

    Parameters
    ----------
    triangles : int, optional
        Triangle count asked of :func:`sunwind.meshes.samples.sample_spacecraft` (>= 2000).
    seed : int, optional
        Seed of every random choice.

    Returns
    -------
    tuple of CorpusEntry
        ``unwelded``, ``mixed_winding``, ``open_sheets``, ``t_junctions``, ``coplanar_layer``,
        ``lifted_layer``, ``slivers``, ``bolts``, ``interpenetrating``, ``all_defects``,
        ``stepped_bus``.

    Examples
    --------
    >>> [entry.name for entry in corpus()][:3]
    ['unwelded', 'mixed_winding', 'open_sheets']
    """
    sample = sample_spacecraft(triangles)
    closed = tuple(part for part in sample.part_names if part not in sample.two_sided_parts)
    pierce = {"boom": (0.3, 0.0, 0.0), "boom_tip": (0.3, 0.0, 0.0)}
    every = interpenetrating(sample, moves=pierce, seed=seed)
    every = bolts(every, count=30, seed=seed)
    every = slivers(every, seed=seed)
    every = duplicate_layers(every, share=0.1, offset_m=0.0, part="mli", seed=seed)
    every = duplicate_layers(every, share=0.05, offset_m=0.004, part="decal", seed=seed + 1)
    every = t_junctions(every, seed=seed)
    every = unwelded(mixed_winding(open_sheets(every), seed=seed), seed=seed)
    entries = [
        (
            "unwelded",
            unwelded(sample, seed=seed),
            closed,
            "every face has its own vertex copies 1e-8 apart; closed bodies declared two-sided (the loader"
            " leaves them cracked)",
        ),
        ("mixed_winding", mixed_winding(sample, seed=seed), (), "half the faces wound the other way"),
        ("open_sheets", open_sheets(sample), (SHEET_GLOB,), "closed bodies written as flat open sheets"),
        ("t_junctions", t_junctions(sample, seed=seed), (), "a tenth of the edges split on one side only"),
        (
            "coplanar_layer",
            duplicate_layers(sample, share=0.2, part="mli", seed=seed),
            ("mli",),
            "a fifth of the faces copied onto themselves as a two-sided blanket",
        ),
        (
            "lifted_layer",
            duplicate_layers(sample, share=0.2, offset_m=0.005, part="decal", seed=seed),
            ("decal",),
            "a fifth of the faces copied 5 mm above themselves as a two-sided decal",
        ),
        (
            "slivers",
            slivers(sample, seed=seed),
            (),
            "large faces cut into 1000:1 slivers beside big triangles",
        ),
        (
            "bolts",
            bolts(sample, count=40, seed=seed),
            (),
            "40 boxes of 5 mm to 3 cm standing on or sunk into faces",
        ),
        (
            "interpenetrating",
            interpenetrating(sample, moves=pierce, yokes=2, seed=seed),
            (),
            "boom pushed 0.3 m into the bus, two beams through its walls",
        ),
        (
            "all_defects",
            every,
            (SHEET_GLOB,),
            "unwelded open sheets wound at random; pierced parts, layers, slivers, T-junctions, bolts",
        ),
        (
            "stepped_bus",
            stepped_bus(),
            (),
            "closed bus with 1-2 cm lip, step, tile risers and skirt on 1 m faces",
        ),
    ]
    return tuple(CorpusEntry(name, mesh, globs, defect) for name, mesh, globs, defect in entries)


def _grid_lines(values: NDArray[np.float64], max_cell_m: float | None) -> NDArray[np.float64]:
    """Sorted distinct ``values``, intervals longer than ``max_cell_m`` cut into equal pieces."""
    edges = np.unique(values)
    length = np.diff(edges)
    pieces = np.ones(len(length), np.int64)
    if max_cell_m is not None:
        pieces = np.maximum(1, np.ceil(length / max_cell_m)).astype(np.int64)
    start = np.repeat(edges[:-1], pieces)
    step = np.repeat(length / pieces, pieces)
    within = np.arange(pieces.sum()) - np.repeat(np.cumsum(pieces) - pieces, pieces)
    return np.r_[start + within * step, edges[-1]]


def _refuse_edge_contacts(solid: NDArray[np.bool_]) -> None:
    """Raise when two solid cells meet along a grid edge with the other two cells round it empty."""
    for axis in range(3):  # edges along this axis: the 2 x 2 cells round them in the other two axes
        b, c = [k for k in range(3) if k != axis]
        padded = np.pad(solid, [(0, 0) if k == axis else (1, 1) for k in range(3)])
        n_b, n_c = padded.shape[b], padded.shape[c]
        low_b, high_b = np.take(padded, range(n_b - 1), axis=b), np.take(padded, range(1, n_b), axis=b)
        quads = [np.take(half, range(n_c - 1), axis=c) for half in (low_b, high_b)]
        quads += [np.take(half, range(1, n_c), axis=c) for half in (low_b, high_b)]
        d00, d10, d01, d11 = quads
        if np.any((d00 == d11) & (d01 == d10) & (d00 != d01)):
            raise InputError("two solid cells meet along an edge only (a non-manifold edge)")
