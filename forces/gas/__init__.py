"""The rarefied gas: the atmosphere (NRLMSIS or given), the flow speed, the drifting Maxwellian's
incident stream (closed forms and per direction), one function per gas-surface law and their species
sums, the panel law of an attitude, the stream integrated over each side's open sky, the chains of
unaccommodated molecules and the exchange of re-emitted ones (METHOD.md "Free-molecular flow", "The
open-sky integral", "Molecular chains", "Atmosphere")."""

from sunwind.forces.gas.atmosphere import (
    BOLTZMANN,
    SPECIES_MASS_KG,
    Atmosphere,
    AtmosphereWarning,
    explicit,
    parse_composition,
)
from sunwind.forces.gas.flow import circular_speed, corotation_speed, corotation_velocity
from sunwind.forces.gas.incident import STREAMS, incident_number_flux
from sunwind.forces.gas.laws import (
    GSI_LAWS,
    GSI_PARAMS,
    MODEL_CODES,
    Coefficients,
    GasSurfaces,
    Reemission,
    cll,
    dria,
    panel_coefficients,
    reemission,
    schaaf_chambre,
    sentman,
    specular,
)
from sunwind.forces.gas.msis import nrlmsis
from sunwind.forces.gas.sampling import GasSampling
from sunwind.forces.gas.sums import diffuse_emission, summed_coefficients

__all__ = [
    "BOLTZMANN",
    "GSI_LAWS",
    "GSI_PARAMS",
    "MODEL_CODES",
    "SPECIES_MASS_KG",
    "STREAMS",
    "Atmosphere",
    "AtmosphereWarning",
    "Coefficients",
    "GasSampling",
    "GasSurfaces",
    "Reemission",
    "circular_speed",
    "cll",
    "corotation_speed",
    "corotation_velocity",
    "diffuse_emission",
    "dria",
    "explicit",
    "incident_number_flux",
    "nrlmsis",
    "panel_coefficients",
    "parse_composition",
    "reemission",
    "schaaf_chambre",
    "sentman",
    "specular",
    "summed_coefficients",
]
