"""What each side's diffuse emission meets: view factors and escape vectors by cosine-weighted rays, with
concave edges integrated, exchange factors through mirrors and sheets, and their verified disk cache
(METHOD.md "Inter-reflection"). The cached calls are ``view_factors.view_factors`` and
``exchange_factors.exchange_factors`` (their modules' own names, so not repeated here)."""

from sunwind.geometry.views.exchange_factors import ExchangeFactors, compute_exchange_factors
from sunwind.geometry.views.view_factors import VIEW_SEED, ViewFactors, compute_view_factors

__all__ = ["VIEW_SEED", "ExchangeFactors", "ViewFactors", "compute_exchange_factors", "compute_view_factors"]
