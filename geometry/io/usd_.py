"""USD stages: each Mesh prim is a part, each bound Material a material key with sunwind optics.

sunwind's USD vocabulary, on top of plain ``UsdGeom``/``UsdShade``:

- ``float sunwind:reflectivity``, ``sunwind:specularFraction``, ``sunwind:transmissivity`` on a
  Material prim: its solar-band optics (all three or none);
- ``float sunwind:emissivity`` on a Material prim beside them (optional): its hemispherical infrared
  emissivity;
- ``doubleSided = true`` on a Mesh: a zero-thickness sheet lit on both sides;
- ``rel sunwind:backMaterial`` on a Mesh, targeting a Material: the material of its back side.
"""

from __future__ import annotations

import re
from dataclasses import replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from pxr import Gf, Sdf, Tf, Usd, UsdGeom, UsdShade, UsdUtils, Vt

from sunwind.geometry.errors import MeshError, combine
from sunwind.geometry.io.topology import bounds, check_transform, compact, fan_triangles, groups
from sunwind.geometry.mesh_data import OPTICS_KEYS, OPTIONAL_OPTICS_KEYS, MeshData

#: USD attribute on a Material prim holding each key of ``OPTICS_KEYS`` and ``OPTIONAL_OPTICS_KEYS``.
OPTICS_ATTRIBUTES = dict(
    zip(
        (*OPTICS_KEYS, *OPTIONAL_OPTICS_KEYS),
        ("sunwind:reflectivity", "sunwind:specularFraction", "sunwind:transmissivity", "sunwind:emissivity"),
        strict=True,
    )
)
#: C++ namespace that USD puts before every name in its messages.
PXR_NAMESPACE = re.compile(r"pxrInternal_v\w+?__pxrReserved__::")
#: Relationship on a Mesh prim targeting the Material of its back side.
BACK_MATERIAL = "sunwind:backMaterial"


def read_usd(path: Path) -> MeshData:
    """Read every active, non-guide Mesh prim of a USD stage at the default time.

    Parameters
    ----------
    path : Path
        A ``.usd``, ``.usda``, ``.usdc`` or ``.usdz`` file.

    Returns
    -------
    MeshData
        Vertices in stage units, world transforms applied; the stage's ``metersPerUnit``, when
        authored, is recorded in ``metadata["declared_unit"]``. Part name: the prim path.
        Polygons are fan-triangulated; ``leftHanded`` meshes and mirroring transforms have their
        winding reversed so triangles are counter-clockwise seen from the front. Material key:
        the name of the bound Material prim, per face where ``materialBind`` GeomSubsets say so.

    Raises
    ------
    MeshError
        A composition error (a missing referenced, payload or sublayer file: every problem USD
        reports), ``metersPerUnit`` not a positive finite number, a transform that is not finite or
        collapses a mesh (zero determinant), polygons with holes, inconsistent topology, or incomplete
        or non-numeric sunwind optics.

    Notes
    -----
    Instance proxies are read like ordinary prims. ``subdivisionScheme`` is ignored: the
    polygons themselves are the surface. ``upAxis`` is ignored: the body frame is the stage's.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.meshes import box
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_usd(box(), Path(folder) / "box.usda")
    ...     mesh = read_usd(Path(folder) / "box.usda")
    >>> mesh.n_faces, mesh.part_names, mesh.metadata["declared_unit"]
    (12, ('/box/box',), (1.0, 'USD metersPerUnit'))
    """
    held = Sdf.Layer.Find(str(path))
    if held and not held.dirty:  # a layer still open elsewhere in this process may be stale
        held.Reload(force=True)
    stage = Usd.Stage.Open(str(path))
    _check_composition(stage, path)
    materials = _Materials(path)
    xforms = UsdGeom.XformCache(Usd.TimeCode.Default())
    pieces = [
        _read_mesh(UsdGeom.Mesh(prim), xforms.GetLocalToWorldTransform(prim), materials, path)
        for prim in stage.Traverse(Usd.TraverseInstanceProxies(Usd.PrimDefaultPredicate))
        if prim.IsA(UsdGeom.Mesh) and UsdGeom.Imageable(prim).ComputePurpose() != UsdGeom.Tokens.guide
    ]
    mesh = MeshData.concatenate(pieces, source=str(path))
    declared = None
    if UsdGeom.StageHasAuthoredMetersPerUnit(stage):
        metres = UsdGeom.GetStageMetersPerUnit(stage)
        if not (np.isfinite(metres) and metres > 0):
            raise MeshError(
                f"metersPerUnit = {metres:g} is not a positive finite number",
                path=str(path),
                hint="author the stage's length unit in metres, e.g. metersPerUnit = 0.001 for mm, "
                "or remove it and give the unit with --unit (Python: unit=)",
            )
        declared = (metres, "USD metersPerUnit")
    return replace(
        mesh,
        file_optics=materials.optics,
        metadata={"declared_unit": declared} if declared else {},
    )


def composed_files(path: Path) -> list[Path]:
    """List the stage file and every file its composition reads: what a digest of the model must cover.

    Parameters
    ----------
    path : Path
        A USD stage file.

    Returns
    -------
    list of Path
        The stage and its sub-layers, references, payloads and the assets they name, resolved and sorted;
        files that do not exist are left out.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.meshes import box
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_usd(box(), Path(folder) / "box.usda")
    ...     [file.name for file in composed_files(Path(folder) / "box.usda")]
    ['box.usda']
    """
    layers, assets, _missing = UsdUtils.ComputeAllDependencies(str(path))
    found = {Path(layer.realPath) for layer in layers if layer.realPath} | {Path(a) for a in assets if a}
    return sorted({file.resolve() for file in found | {Path(path)} if file.is_file()})


def _check_composition(stage: Usd.Stage, path: Path) -> None:
    """Refuse a stage that USD could not compose completely (it only logs a warning and goes on)."""
    problems = [
        MeshError(f"the stage cannot be composed: {_composition_message(error)}", path=str(path))
        for error in stage.GetCompositionErrors()
    ]
    if problems:
        raise combine(
            problems,
            hint="put every file the stage refers to (references, payloads, subLayers) where it points, "
            "relative to the layer that names it, or remove the reference; or flatten the stage into "
            "one file (usdcat --flatten)",
        )


def _composition_message(error: object) -> str:
    """USD's text of a composition error, without its C++ namespace and its "skipping"."""
    text = PXR_NAMESPACE.sub("", str(error)).strip().rstrip(".")
    return text.removesuffix("; skipping").rstrip(".")


def _read_mesh(mesh: UsdGeom.Mesh, world: Gf.Matrix4d, materials: _Materials, path: Path) -> MeshData:
    """One Mesh prim as a single-part MeshData in world coordinates."""
    prim = mesh.GetPrim()
    part = str(prim.GetPath())

    def error(message: str, hint: str) -> MeshError:
        return MeshError(message, path=str(path), part=part, hint=hint)

    if len(mesh.GetHoleIndicesAttr().Get() or []):
        raise error(
            "has polygons with holes (holeIndices), which sunwind does not read",
            "triangulate the mesh in the authoring tool and re-export",
        )
    points = np.asarray(mesh.GetPointsAttr().Get() or [], dtype=np.float64).reshape(-1, 3)
    counts = np.asarray(mesh.GetFaceVertexCountsAttr().Get() or [], dtype=np.int64)
    indices = np.asarray(mesh.GetFaceVertexIndicesAttr().Get() or [], dtype=np.int64)
    topology_hint = "re-export the mesh from the authoring tool"
    if np.any(counts < 3):
        face = int(np.argmax(counts < 3))
        raise error(
            f"has face {face} with {counts[face]} vertices, but a face needs at least 3", topology_hint
        )
    if counts.sum() != len(indices):
        raise error(
            f"has faceVertexCounts adding up to {counts.sum()} but {len(indices)} faceVertexIndices",
            topology_hint,
        )
    outside = indices[(indices < 0) | (indices >= len(points))]
    if len(outside):
        raise error(
            f"has faceVertexIndices referring to point {outside[0]} but only {len(points)} points",
            topology_hint,
        )
    triangles, polygon = fan_triangles(counts, indices)
    matrix = np.array(world, dtype=np.float64)  # row vectors: p_world = p @ M[:3, :3] + M[3, :3]
    check_transform(matrix[:3, :3], str(path), part)
    left_handed = mesh.GetOrientationAttr().Get() == UsdGeom.Tokens.leftHanded
    if left_handed != (np.linalg.det(matrix[:3, :3]) < 0):
        triangles = triangles[:, ::-1]

    material_names: list[str] = []
    polygon_material = np.full(len(counts), materials.index(mesh, material_names), dtype=np.int32)
    for subset in UsdShade.MaterialBindingAPI(prim).GetMaterialBindSubsets():
        if subset.GetElementTypeAttr().Get() != UsdGeom.Tokens.face:
            continue
        faces = np.asarray(subset.GetIndicesAttr().Get() or [], dtype=np.int64)
        if len(faces) and (faces.min() < 0 or faces.max() >= len(counts)):
            raise error(
                f"has GeomSubset '{subset.GetPrim().GetName()}' listing faces outside 0..{len(counts) - 1}",
                topology_hint,
            )
        polygon_material[faces] = materials.index(subset, material_names)

    two_sided = bool(mesh.GetDoubleSidedAttr().Get())
    back = materials.back_material(prim)
    return MeshData(
        vertices=points @ matrix[:3, :3] + matrix[3, :3],
        faces=triangles,
        face_part=np.zeros(len(triangles), dtype=np.int32),
        part_names=(part,),
        face_material=polygon_material[polygon],
        material_names=tuple(material_names),
        two_sided_parts=frozenset({part} if two_sided else ()),
        part_back_material={part: back} if back else {},
    )


class _Materials:
    """Material keys of one stage and the sunwind optics their Material prims carry.

    Parameters
    ----------
    path : Path
        The stage's file, named in errors.

    Attributes
    ----------
    optics : dict of str -> dict of str -> float
        Optics by material key, for materials seen so far that carry them.
    """

    def __init__(self, path: Path) -> None:
        self.path = path
        self.optics: dict[str, dict[str, float]] = {}
        self._seen: dict[str, Sdf.Path] = {}

    def index(self, bound: UsdGeom.Mesh | UsdGeom.Subset, names: list[str]) -> int:
        """Index in ``names`` (appended to when new) of the material bound to a mesh or subset.

        Returns -1 when nothing is bound.
        """
        material, _ = UsdShade.MaterialBindingAPI(bound.GetPrim()).ComputeBoundMaterial()
        if not material:
            return -1
        name = self.key(material.GetPrim())
        if name not in names:
            names.append(name)
        return names.index(name)

    def back_material(self, prim: Usd.Prim) -> str | None:
        """Key of the Material that ``sunwind:backMaterial`` on a mesh prim targets, if any."""
        relationship = prim.GetRelationship(BACK_MATERIAL)
        if not relationship:
            return None
        targets = relationship.GetForwardedTargets()
        target = prim.GetStage().GetPrimAtPath(targets[0]) if len(targets) == 1 else None
        if not target or not target.IsA(UsdShade.Material):
            raise MeshError(
                f"has {BACK_MATERIAL} targeting {[str(t) for t in targets]}, not one Material prim",
                path=str(self.path),
                part=str(prim.GetPath()),
                hint="point it at a Material prim, e.g. </root/Looks/kapton>",
            )
        return self.key(target)

    def key(self, material: Usd.Prim) -> str:
        """The material key of a Material prim (its name); reads its optics on first sight."""
        name = material.GetName()
        first = self._seen.setdefault(name, material.GetPath())
        optics = self._read_optics(material)
        if first == material.GetPath():
            if optics:
                self.optics[name] = optics
        elif optics != self.optics.get(name, {}):
            raise MeshError(
                f"Materials {first} and {material.GetPath()} share the name '{name}' but carry "
                "different sunwind optics",
                path=str(self.path),
                hint="rename one of them: the prim name is the material key",
            )
        return name

    def _read_optics(self, material: Usd.Prim) -> dict[str, float]:
        """The sunwind optics authored on a Material prim: the three solar keys (and the emissivity when
        authored), or none."""
        optics = {}
        for key, attribute_name in OPTICS_ATTRIBUTES.items():
            attribute = material.GetAttribute(attribute_name)
            if not (attribute and attribute.HasAuthoredValue()):
                continue
            value = attribute.Get()
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise MeshError(
                    f"{attribute_name} on Material {material.GetPath()} is {value!r}, not a number",
                    path=str(self.path),
                    hint=f"author it as 'float {attribute_name} = 0.5'",
                )
            optics[key] = _shortest(value, attribute.GetTypeName())
        missing = [OPTICS_ATTRIBUTES[key] for key in OPTICS_KEYS if key not in optics]
        if optics and missing:
            raise MeshError(
                f"Material {material.GetPath()} has some sunwind optics but lacks {missing[0]}",
                path=str(self.path),
                hint="author all of "
                + ", ".join(OPTICS_ATTRIBUTES[key] for key in OPTICS_KEYS)
                + ", or none",
            )
        return optics


def _shortest(value: float, type_name: Sdf.ValueTypeName) -> float:
    """An attribute's value as the shortest decimal its type rounds to it (0.3, not 0.30000001)."""
    precision = {Sdf.ValueTypeNames.Float: np.float32, Sdf.ValueTypeNames.Half: np.float16}
    return float(str(precision.get(type_name, np.float64)(value)))


def write_usd(mesh: MeshData, path: Path) -> None:
    """Write the mesh as a USD stage in metres, Z up, with materials and sunwind optics.

    Layout: an Xform root prim named after the file stem (the default prim); one Mesh prim per
    part under it, named after the part (a prim-path part name keeps its leaf); one Material prim
    per material key under ``/<root>/Looks``, carrying ``sunwind:*`` float attributes when
    ``mesh.file_optics`` has the key. A part with one material is bound to it; a part with several
    gets a ``materialBind`` GeomSubset per material. Names are made valid USD identifiers
    (``"MLI-gold"`` becomes ``"MLI_gold"``, made unique with a suffix), and the keys read back
    are those names. Points are float32, the type USD gives them.

    Parameters
    ----------
    mesh : MeshData
        The mesh to write, in metres; every ``file_optics`` entry has all of ``OPTICS_KEYS`` and may
        have ``OPTIONAL_OPTICS_KEYS``.
    path : Path
        The ``.usd`` (binary), ``.usdc`` or ``.usda`` file to create or overwrite.

    Raises
    ------
    OSError
        The file cannot be written.

    Examples
    --------
    >>> import tempfile
    >>> from sunwind.meshes import plate
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     write_usd(plate(divisions=1), Path(folder) / "plate.usda")
    ...     "metersPerUnit = 1" in (Path(folder) / "plate.usda").read_text()
    True
    """
    stage = Usd.Stage.CreateInMemory()
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    root = Sdf.Path.absoluteRootPath.AppendChild(_identifier(path.stem))
    stage.SetDefaultPrim(UsdGeom.Xform.Define(stage, root).GetPrim())
    looks = UsdGeom.Scope.Define(stage, root.AppendChild("Looks")).GetPath()

    material_names = list(dict.fromkeys([*mesh.material_names, *mesh.part_back_material.values()]))
    material_prims = {}
    for name, identifier in zip(material_names, _identifiers(material_names), strict=True):
        material = UsdShade.Material.Define(stage, looks.AppendChild(identifier))
        for key, value in mesh.file_optics.get(name, {}).items():
            attribute = material.GetPrim().CreateAttribute(OPTICS_ATTRIBUTES[key], Sdf.ValueTypeNames.Float)
            attribute.Set(float(value))
        material_prims[name] = material

    leaves = [name.rsplit("/", 1)[-1] if name.startswith("/") else name for name in mesh.part_names]
    part_paths = [root.AppendChild(i) for i in _identifiers(leaves, reserved={"Looks"})]
    for part, face_ids in groups(mesh.face_part):
        used, faces = compact(mesh.faces[face_ids])
        points = mesh.vertices[used].astype(np.float32)
        usd_mesh = UsdGeom.Mesh.Define(stage, part_paths[part])
        usd_mesh.CreatePointsAttr(Vt.Vec3fArray.FromNumpy(points))
        usd_mesh.CreateExtentAttr(Vt.Vec3fArray.FromNumpy(np.stack(bounds(points))))
        usd_mesh.CreateFaceVertexCountsAttr(Vt.IntArray.FromNumpy(np.full(len(faces), 3, np.int32)))
        usd_mesh.CreateFaceVertexIndicesAttr(Vt.IntArray.FromNumpy(faces.astype(np.int32).ravel()))
        usd_mesh.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)
        name = mesh.part_names[part]
        if name in mesh.two_sided_parts:
            usd_mesh.CreateDoubleSidedAttr(True)
        if name in mesh.part_back_material:
            usd_mesh.GetPrim().CreateRelationship(BACK_MATERIAL).SetTargets(
                [material_prims[mesh.part_back_material[name]].GetPath()]
            )
        _bind(usd_mesh, mesh.face_material[face_ids], [material_prims[n] for n in material_names])
    if not stage.GetRootLayer().Export(str(path)):
        raise OSError(f"USD could not write {path}")


def _bind(
    usd_mesh: UsdGeom.Mesh, face_material: NDArray[np.int32], materials: list[UsdShade.Material]
) -> None:
    """Bind a part's materials: to the whole mesh when it has one, else per GeomSubset."""
    binding = UsdShade.MaterialBindingAPI.Apply(usd_mesh.GetPrim())
    keyed = [(m, faces) for m, faces in groups(face_material) if m >= 0]
    if len(keyed) == 1 and len(keyed[0][1]) == len(face_material):
        binding.Bind(materials[keyed[0][0]])
        return
    for m, faces in keyed:
        subset = binding.CreateMaterialBindSubset(
            materials[m].GetPrim().GetName(), Vt.IntArray.FromNumpy(faces.astype(np.int32))
        )
        UsdShade.MaterialBindingAPI.Apply(subset.GetPrim()).Bind(materials[m])
    if keyed and np.all(face_material >= 0):
        binding.SetMaterialBindSubsetsFamilyType(UsdGeom.Tokens.partition)


def _identifier(name: str) -> str:
    """``name`` as a valid USD prim name; a leading digit is kept behind an underscore."""
    return Tf.MakeValidIdentifier(f"_{name}" if name[:1].isdigit() else name)


def _identifiers(names: list[str], reserved: frozenset[str] | set[str] = frozenset()) -> list[str]:
    """Valid, distinct USD prim names for ``names``, avoiding ``reserved``; ``_2``, ``_3`` on clashes."""
    taken = set(reserved)
    result = []
    for name in names:
        base = candidate = _identifier(name)
        number = 1
        while candidate in taken:
            number += 1
            candidate = f"{base}_{number}"
        taken.add(candidate)
        result.append(candidate)
    return result
