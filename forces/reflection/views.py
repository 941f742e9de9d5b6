"""The view factors a model's inter-reflection uses, kept with the model, and the interference
criterion ``K_IS`` of eq. (7) they give (METHOD.md "Inter-reflection")."""

from __future__ import annotations

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


def interference_criterion(craft: Spacecraft, view: ViewFactors) -> float:
    """``K_IS`` of eq. (7): reflected light that meets the spacecraft again over light that escapes.

    ``Omega_inf / 2 pi`` is taken as the cosine-weighted open-sky share ``f_esc``, the share of a
    side's diffusely reflected light that escapes, which is the ratio eq. (7) describes. 0 for a
    convex body or a black one.
    """
    rho_area = craft.side_optics[:, 0] * craft.side_areas
    escaping = float(rho_area @ view.escape_fraction)
    returning = float(rho_area @ (1.0 - view.escape_fraction))
    if returning == 0.0:
        return 0.0
    return returning / escaping if escaping > 0 else float("inf")


def interference(craft: Spacecraft, settings: ReflectionSettings) -> float:
    """``K_IS`` of ``craft`` (eq. 7) with its view factors for ``settings``; kept in its cache."""
    return craft.cache.get(
        ("K_IS", *settings.view_key),
        lambda: interference_criterion(craft, model_view_factors(craft, settings)),
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
