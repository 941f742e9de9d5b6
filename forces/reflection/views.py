"""The view factors a model's inter-reflection uses, kept with the model, and the interference
criterion ``K_IS`` of eq. (7) they give (METHOD.md "Inter-reflection")."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from sunwind.forces.reflection.settings import ReflectionSettings
from sunwind.geometry.spacecraft import Spacecraft
from sunwind.geometry.views.view_factors import VIEW_SEED, ViewFactors, view_factors


def model_view_factors(craft: Spacecraft, settings: ReflectionSettings) -> ViewFactors:
    """View factors of ``craft`` sampled as ``settings`` say: from its cache, else the disk cache,
    else computed (and kept in both)."""
    return craft.cache.get(
        ("view factors", *settings.view_key),
        lambda: view_factors(craft, settings.rays_per_side, VIEW_SEED, settings.cache_dir),
    )


def interference_criterion(
    craft: Spacecraft, view: ViewFactors, reflectivity: NDArray[np.float64] | float | None = None
) -> float:
    """``K_IS`` of eq. (7): what the sides reflect (or re-emit) diffusely that meets the spacecraft
    again, over what escapes.

    ``Omega_inf / 2 pi`` is taken as the cosine-weighted open-sky share ``f_esc``, the share of a
    side's diffusely reflected light that escapes, which is the ratio eq. (7) describes. 0 for a
    convex body or a black one.

    Parameters
    ----------
    craft : Spacecraft
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
    """
    rho = craft.side_optics[:, 0] if reflectivity is None else np.broadcast_to(reflectivity, craft.n_sides)
    rho_area = rho * craft.side_areas
    escaping = float(rho_area @ view.escape_fraction)
    returning = float(rho_area @ (1.0 - view.escape_fraction))
    if returning <= 0.0:
        return 0.0
    return returning / escaping if escaping > 0 else float("inf")


def interference(craft: Spacecraft, settings: ReflectionSettings, molecules: bool = False) -> float:
    """``K_IS`` of ``craft`` (eq. 7) with its view factors for ``settings``, of light (the sides'
    reflectivity) or of ``molecules`` (``rho = 1``); kept in its cache."""
    return craft.cache.get(
        ("molecular K_IS" if molecules else "K_IS", *settings.view_key),
        lambda: interference_criterion(
            craft, model_view_factors(craft, settings), 1.0 if molecules else None
        ),
    )


def view_factor_summary(craft: Spacecraft, settings: ReflectionSettings) -> dict:
    """``K_IS`` and the view factors' figures, JSON-ready: rays per side, where they came from, seconds,
    the area-weighted share of diffusely reflected light that escapes, and the reciprocity error."""
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
