"""The default shadow pass on any model against the z-buffer reference, and its error estimate against
the error it made: the check behind the validation page (docs/validation.md) and its CAD exports.

At each Sun direction the default pass (``geometry.rays.shadows``) gives every side's lit share and lit
centroid; eq. (4) of METHOD.md at ``P = 1 Pa`` on them gives the direct force and torque, compared with
:func:`~sunwind.validation.shadow_reference.shadow_reference` (a z-buffer that shares no code with the
pass) at the same reference point. Errors are relative as the results report them: the force to
``|F|``, the torque to ``max(|M|, 0.01 |F| L)`` (``L`` the diagonal of the model's box); so are the
certificate's estimate (``ShadowCheck.loads_error``) and the reference's noise (``ERROR_SIGMAS``
standard errors).

Run it on the corpus or on a model of your own::

    python -m sunwind.validation.shadow_pass_check                      # the CAD corpus, 1 mm
    python -m sunwind.validation.shadow_pass_check model.obj --unit mm --pixel 0.0005

Only the direct law is compared: reflected light is computed from the same lit shares.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.error_estimate import ErrorEstimate
from sunwind.geometry.materials import Material
from sunwind.geometry.rays.certificate import LoadsError
from sunwind.geometry.rays.shadows import side_sampler
from sunwind.geometry.spacecraft import Spacecraft, build_spacecraft
from sunwind.validation.shadow_reference import ERROR_SIGMAS, projected_area_loads, shadow_reference

__all__ = ["PassComparison", "check_directions", "compare_pass", "unit_area_loads"]

#: The finish every model is given: a grey, partly specular surface (rho 0.4, beta 0.5).
GREY = Material("grey", 0.4, 0.5)


@dataclass(frozen=True)
class PassComparison:
    """The default pass against the reference at one Sun direction; errors relative (module docstring).

    Attributes
    ----------
    sun_vector : (3,) float64
        Unit vector toward the Sun, body frame.
    force_error, torque_error : float
        The pass's error against the reference.
    force_estimate, torque_estimate : float
        The certificate's estimate of that error.
    force_noise, torque_noise : float
        ``ERROR_SIGMAS`` standard errors of the reference: errors below them are not resolved.
    rays : int
        Rays the pass cast (its check's included).
    seconds : float
        Wall time of the pass.

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> craft = build_spacecraft(box(), uniform=GREY)
    >>> [row] = compare_pass(craft, np.array([[0.3, 0.4, 0.866]]), 0.05)
    >>> row.covered, row.rays > 0
    (True, True)
    """

    sun_vector: NDArray[np.float64]
    force_error: float
    torque_error: float
    force_estimate: float
    torque_estimate: float
    force_noise: float
    torque_noise: float
    rays: int
    seconds: float

    @property
    def covered(self) -> bool:
        """Whether the estimate is at least the error wherever the error shows above the noise."""
        return (
            self.force_estimate >= self.force_error - self.force_noise
            and self.torque_estimate >= self.torque_error - self.torque_noise
        )


def unit_area_loads(craft: Spacecraft, sun_vector: NDArray[np.float64]) -> NDArray[np.float64]:
    """Eq. (4) of METHOD.md on a unit lit area of each side at ``P = 1 Pa`` [N/m^2], (n_sides, 3).

    Parameters
    ----------
    craft : Spacecraft
        The model, with the optics of each side.
    sun_vector : (3,) float64
        Unit direction toward the Sun, body frame.

    Returns
    -------
    (n_sides, 3) float64
        Force on a unit lit area of each side [N/m^2] at 1 Pa.

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> black = build_spacecraft(box(), uniform=Material("black", 0.0, 0.0))
    >>> unit_area_loads(black, np.array([0.0, 0.0, 1.0]))[black.side_normals[:, 2] > 0.5][0] + 0.0
    array([ 0.,  0., -1.])
    """
    cosine = craft.side_normals @ sun_vector
    return cosine[:, None] * projected_area_loads(craft, sun_vector)


def compare_pass(craft: Spacecraft, sun_vectors: NDArray[np.float64], pixel_m: float) -> list[PassComparison]:
    """Compare the default pass of ``craft`` with the reference at each Sun direction.

    The reference has pixel ``pixel_m``; torques are about the mean vertex.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    sun_vectors : (k, 3) float64
        Directions toward the Sun, body frame (normalised here).
    pixel_m : float
        Pixel of the reference [m].

    Returns
    -------
    list of PassComparison
        One per Sun direction.

    Examples
    --------
    >>> from sunwind.meshes.primitives import box
    >>> craft = build_spacecraft(box(), uniform=GREY)
    >>> [c.force_error < 1e-3 for c in compare_pass(craft, np.array([[0.3, 0.4, 0.866]]), 0.01)]
    [True]
    """
    reference_m = craft.vertices.mean(axis=0)
    sampler = side_sampler(craft)
    out = []
    for u in np.asarray(sun_vectors, dtype=np.float64):
        u = u / np.linalg.norm(u)
        start = time.perf_counter()
        light = sampler.illuminate(u)
        seconds = time.perf_counter() - start
        load = unit_area_loads(craft, u)
        lit = (light.lit_fraction * craft.side_areas)[:, None] * load
        force, torque = lit.sum(axis=0), np.cross(light.lit_centroid - reference_m, lit).sum(axis=0)
        truth = shadow_reference(craft, u, pixel_m, reference_m)

        # the error, its estimate and the reference's noise, relative as results report their estimate
        error, estimate, noise = (
            ErrorEstimate.of(loads, truth.force_N, truth.torque_Nm, craft.diagonal_m)
            for loads in (
                LoadsError(
                    float(np.linalg.norm(force - truth.force_N)),
                    float(np.linalg.norm(torque - truth.torque_Nm)),
                ),
                light.check.loads_error(craft, load, reference_m),
                LoadsError(ERROR_SIGMAS * truth.force_sigma_N, ERROR_SIGMAS * truth.torque_sigma_Nm),
            )
        )
        out.append(
            PassComparison(
                sun_vector=u,
                force_error=error.force,
                torque_error=error.torque,
                force_estimate=estimate.force,
                torque_estimate=estimate.torque,
                force_noise=noise.force,
                torque_noise=noise.torque,
                rays=int(light.rays),
                seconds=seconds,
            )
        )
    return out


def check_directions(spread: int = 16) -> NDArray[np.float64]:
    """Give ``spread`` Sun directions over the sphere and four grazing the faces of an axis-aligned box.

    The ``spread`` directions are a Fibonacci lattice; the four graze the box's faces by 0.03 to 0.2
    degrees, from either side.

    Parameters
    ----------
    spread : int, optional
        Directions of the lattice over the sphere.

    Returns
    -------
    (spread + 4, 3) float64
        Unit directions, the grazing four last.

    Examples
    --------
    >>> check_directions(4).shape
    (8, 3)
    """
    k = np.arange(spread) + 0.5
    z = 1 - 2 * k / spread
    phi = np.pi * (1 + 5**0.5) * k
    lattice = np.c_[np.sqrt(1 - z * z) * np.cos(phi), np.sqrt(1 - z * z) * np.sin(phi), z]
    grazing = [[1, 0.003, 0.4], [0.3, 1, -0.002], [-0.001, -0.5, 1], [0.7, -0.7, 0.0005]]
    u = np.r_[lattice, grazing]
    return u / np.linalg.norm(u, axis=1)[:, None]


def _row(name: str, craft: Spacecraft, rows: list[PassComparison]) -> str:
    worst_f = max(rows, key=lambda r: r.force_error)
    worst_m = max(rows, key=lambda r: r.torque_error)
    covered = sum(r.covered for r in rows)
    return (
        f"{name:<18} {craft.n_facets:>7} {worst_f.force_error:>9.1e} {worst_f.force_noise:>8.1e} "
        f"{worst_f.force_estimate:>9.1e} {worst_m.torque_error:>9.1e} {worst_m.torque_noise:>8.1e} "
        f"{worst_m.torque_estimate:>9.1e} {covered:>3}/{len(rows):<3} "
        f"{1e3 * np.median([r.seconds for r in rows]):>7.0f} {np.median([r.rays for r in rows]):>9.0f}"
    )


def main(argv: list[str] | None = None) -> int:
    """Print, per model, the shadow pass's worst errors against the reference and their estimates.

    For the worst force and torque error over the directions: the reference's noise and the estimate
    at that direction; then at how many directions the estimate covers the error, and the median time
    and rays per direction.

    Parameters
    ----------
    argv : list of str, optional
        Command-line arguments: mesh files (default the CAD corpus), ``--unit``, ``--pixel`` [m] and
        ``--directions``; default ``sys.argv[1:]``.

    Returns
    -------
    int
        0.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from sunwind.geometry.io.obj import write_obj
    >>> from sunwind.meshes.primitives import box
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = Path(folder) / "cube.obj"
    ...     write_obj(box(), path)
    ...     main([str(path), "--directions", "2", "--pixel", "0.05"])  # doctest: +ELLIPSIS
    model               facets     force ...
    .../cube.obj      12 ...
    0
    """
    parser = argparse.ArgumentParser(prog="python -m sunwind.validation.shadow_pass_check")
    parser.add_argument("meshes", nargs="*", help="mesh files (default: the CAD corpus)")
    parser.add_argument(
        "--unit", default=None, help="length unit of the mesh files (default: the file's own, else m)"
    )
    parser.add_argument("--pixel", type=float, default=0.001, help="pixel of the reference [m]")
    parser.add_argument("--directions", type=int, default=16, help="directions over the sphere")
    args = parser.parse_args(argv)
    directions = check_directions(args.directions)
    print(
        f"{'model':<18} {'facets':>7} {'force':>9} {'noise':>8} {'estimate':>9} {'torque':>9} {'noise':>8} "
        f"{'estimate':>9} {'covered':>7} {'ms':>7} {'rays':>9}"
    )
    if args.meshes:
        from sunwind.forces.model import load

        models = [
            (path, load(path, unit=args.unit, uniform=GREY, two_sided=("*",)).craft) for path in args.meshes
        ]
    else:
        from sunwind.meshes.cad_corpus import corpus

        models = [(e.name, build_spacecraft(e.mesh, uniform=GREY, two_sided=e.two_sided)) for e in corpus()]
    for name, craft in models:
        print(_row(name, craft, compare_pass(craft, directions, args.pixel)), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
