"""Inter-reflection of light: the settings, mirror and transmitted beam chains with their kernels and
escape test, the diffuse balance and its adjoint, and what they add to the direct result
(METHOD.md "Inter-reflection")."""

from sunwind.forces.reflection.beams import BeamChainTotals, follow_chains
from sunwind.forces.reflection.diffuse import DiffuseExchange, DiffuseTotals, diffuse_exchange
from sunwind.forces.reflection.plan import (
    PowerBalance,
    Reflected,
    ReflectionPlan,
    reflected_part,
    reflection_plan,
)
from sunwind.forces.reflection.settings import AUTO_THRESHOLD, MODES, ReflectionSettings, resolved_mode
from sunwind.forces.reflection.views import interference, interference_criterion, model_view_factors

__all__ = [
    "AUTO_THRESHOLD",
    "MODES",
    "BeamChainTotals",
    "DiffuseExchange",
    "DiffuseTotals",
    "PowerBalance",
    "Reflected",
    "ReflectionPlan",
    "ReflectionSettings",
    "diffuse_exchange",
    "follow_chains",
    "interference",
    "interference_criterion",
    "model_view_factors",
    "reflected_part",
    "reflection_plan",
    "resolved_mode",
]
