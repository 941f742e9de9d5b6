"""The view factors a model's inter-reflection uses, kept with the model, and the interference
criterion ``K_IS`` of eq. (7) they give (METHOD.md "Inter-reflection")."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.reflection.settings import ReflectionSettings
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.view_factors import VIEW_SEED, ViewFactors, view_factors


def model_view_factors(craft: Spacecraft, settings: ReflectionSettings) -> ViewFactors:
    """View factors of ``craft`` sampled as ``settings`` say, from a cache where they are kept.

    From its cache, else the disk cache, else computed (and kept in both).

    Parameters
    ----------
    craft : Spacecraft
        The model.
    settings : ReflectionSettings
        Rays per side and disk cache of the view factors.

    Returns
    -------
    ViewFactors
        The view factors of ``craft``'s sides.

    Examples
    --------
    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> settings = ReflectionSettings(cache_dir=False, rays_per_side=16)
    >>> view = model_view_factors(craft, settings)
    >>> view.rays_per_side, model_view_factors(craft, settings) is view
    (16, True)
    """
    return craft.cache.get(
        ("view factors", *settings.view_key),
        lambda: view_factors(craft, settings.rays_per_side, VIEW_SEED, settings.cache_dir),
    )


def interference_criterion(
    craft: Spacecraft, view: ViewFactors, reflectivity: NDArray[np.float64] | float | None = None
) -> float:
    """Interference criterion ``K_IS`` of eq. (7): diffuse light meeting the spacecraft again over escaping.

    What the sides reflect (or re-emit) diffusely that meets the spacecraft again, over what escapes.

    ``Omega_inf / 2 pi`` is taken as the cosine-weighted open-sky share ``f_esc``, the share of a
    side's diffusely reflected light that escapes, which is the ratio eq. (7) describes. 0 for a
    convex body or a black one.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    view : ViewFactors
        The view factors of ``craft``'s sides (their ``escape_fraction``).
    reflectivity : (n_sides,) array_like or float, optional
        ``rho`` of each side; default the sides' optical reflectivity (light). Molecules take
        ``rho = 1``: every arriving molecule leaves again.

    Returns
    -------
    float
        ``K_IS`` >= 0 (inf when nothing escapes but something returns).

    Examples
    --------
    A convex box: nothing it reflects meets it again.

    >>> import sunwind as sw
    >>> model = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1)
    >>> view = model_view_factors(model.craft, ReflectionSettings(cache_dir=False, rays_per_side=16))
    >>> interference_criterion(model.craft, view, reflectivity=1.0)
    0.0

    References
    ----------
    Shmatov and Mordvinkin (2013), eq. (7).
    """
    rho = craft.side_optics[:, 0] if reflectivity is None else np.broadcast_to(reflectivity, craft.n_sides)
    rho_area = rho * craft.side_areas
    escaping = float(rho_area @ view.escape_fraction)
    returning = float(rho_area @ (1.0 - view.escape_fraction))
    if returning <= 0.0:
        return 0.0
    return returning / escaping if escaping > 0 else float("inf")


def interference(craft: Spacecraft, settings: ReflectionSettings, molecules: bool = False) -> float:
    """Interference criterion ``K_IS`` of ``craft`` (eq. 7) for light or molecules, kept in its cache.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    settings : ReflectionSettings
        Sampling and disk cache of the view factors.
    molecules : bool, optional
        False for light (the sides' reflectivity), True for molecules (``rho = 1``).

    Returns
    -------
    float
        ``K_IS`` >= 0 (:func:`interference_criterion`).

    References
    ----------
    Shmatov and Mordvinkin (2013), eq. (7).

    Examples
    --------
    A convex box: nothing it reflects meets it again.

    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> settings = ReflectionSettings(cache_dir=False, rays_per_side=16)
    >>> interference(craft, settings), interference(craft, settings, molecules=True)
    (0.0, 0.0)
    """
    return craft.cache.get(
        ("molecular K_IS" if molecules else "K_IS", *settings.view_key),
        lambda: interference_criterion(
            craft, model_view_factors(craft, settings), 1.0 if molecules else None
        ),
    )


def view_factor_summary(craft: Spacecraft, settings: ReflectionSettings) -> dict:
    """Interference criterion and the view factors' figures, JSON-ready.

    Parameters
    ----------
    craft : Spacecraft
        The model.
    settings : ReflectionSettings
        Sampling and disk cache of the view factors.

    Returns
    -------
    dict
        ``k_is`` and ``view_factors``: rays per side, where they came from, seconds, the area-weighted
        share of diffusely reflected light that escapes, and the reciprocity error.

    Examples
    --------
    >>> import sunwind as sw
    >>> craft = sw.load(sw.meshes.box(), uniform=sw.Material("white", 0.5, 0.5, 0.0), threads=1).craft
    >>> settings = ReflectionSettings(cache_dir=False, rays_per_side=16)
    >>> summary = view_factor_summary(craft, settings)
    >>> summary["k_is"], summary["view_factors"]["open_sky_share"], summary["view_factors"]["origin"]
    (0.0, 1.0, 'computed')
    """
    view = model_view_factors(craft, settings)
    return {
        "k_is": interference(craft, settings),
        "view_factors": {
            "rays_per_side": view.rays_per_side,
            "origin": view.origin,
            "seconds": view.seconds,
            "open_sky_share": float(craft.side_areas @ view.escape_fraction / craft.side_areas.sum()),
            "reciprocity_error": view.reciprocity_error(craft.side_areas),
        },
    }
