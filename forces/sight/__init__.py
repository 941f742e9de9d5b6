"""Lines of sight from points of a spacecraft: which directions each sensor, antenna or
retroreflector sees past the rest of the model, the blocked share of its field of view, what it sees
along an orbit, and retroreflector range offsets (METHOD.md "Lines of sight").

Modules, each importing only those before it: :mod:`.points` (the points file), :mod:`.cast`
(Embree lines lifted off the surface), :mod:`.lines` (:func:`lines_of_sight`), :mod:`.sky_map`
(azimuth-elevation maps and blocked fractions), :mod:`.ranging` (retroreflector range offsets),
:mod:`.passes` (the Sun, the Earth or a station along an orbit, with intervals) and :mod:`.plots`.

Examples
--------
>>> import sunwind as sw
>>> model = sw.load(sw.meshes.box(), uniform=sw.Material("black", 0.0, 0.0), threads=1)
>>> points = SightPoints.of(["camera"], [[0.0, 0.0, 0.5]], [[0.0, 0.0, 1.0]], [30.0])
>>> sw.lines_of_sight(model, points, [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]).visible.tolist()
[[True, False]]
"""

from sunwind.forces.sight.lines import FRAME, LinesOfSight, lines_of_sight
from sunwind.forces.sight.passes import SightPasses, Station, visibility_along
from sunwind.forces.sight.points import SightPoints, read_points
from sunwind.forces.sight.ranging import RangeOffsets, range_offsets
from sunwind.forces.sight.sky_map import SightMap, blocked_map

__all__ = [
    "FRAME",
    "LinesOfSight",
    "RangeOffsets",
    "SightMap",
    "SightPasses",
    "SightPoints",
    "Station",
    "blocked_map",
    "lines_of_sight",
    "range_offsets",
    "read_points",
    "visibility_along",
]
