"""Surface finishes: how a finish meets the rarefied gas (:class:`GasSurface`), and a library of named
finishes with their solar-band optics and infrared emissivity (:data:`FINISHES`).

A materials file takes one with ``finish = "NAME"`` in a ``[materials.NAME]`` table (materials guide);
keys given beside it override the finish's. In Python: ``FINISHES["az-93"]`` or ``finish("az-93")``.

Sources, cited by short name in each finish's ``source``:

- *Gilmore*: D. G. Gilmore (ed.), Spacecraft Thermal Control Handbook, Vol. I, 2nd ed., The Aerospace
  Press, 2002, App. A (beginning-of-life values, mostly NASA/GSFC measurements);
- *Henninger*: J. H. Henninger, Solar Absorptance and Thermal Emittance of Some Common Spacecraft
  Thermal-Control Coatings, NASA RP-1121, 1984;
- *Fortescue*: P. Fortescue, G. Swinerd, J. Stark (eds), Spacecraft Systems Engineering, 4th ed., Wiley,
  2011, Table 11.3;
- *Lavochkin*: Ananyev and Chugunova, conductive coatings of the Elektro-L and Spektr-R spacecraft
  (Lavochkin Association journal), table 2: solar absorptance ``A_s`` and *normal* emissivity ``eps_n``
  of enamels, measured.

No source tabulates the specular share of the reflected sunlight: every ``specular_fraction`` here is
an engineering estimate from the kind of surface (matte paint, glossy film, mirror). Every finish is
opaque in both bands (``transmissivity`` 0).
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from sunwind.geometry.errors import MaterialError

#: Gas-surface interaction models (``gsi``), in the order of their codes in
#: :class:`~sunwind.geometry.materials.MaterialTable`.
GSI_MODELS = ("sentman", "dria", "schaaf-chambre", "cll", "specular")
#: Gas-surface keys of a ``[materials.NAME]`` table and their defaults (the materials guide).
GAS_DEFAULTS = {
    "gsi": "sentman",
    "energy_accommodation": 1.0,  # alpha_E (sentman, dria)
    "normal_accommodation": 1.0,  # sigma_n (schaaf-chambre), alpha_n (cll)
    "tangential_accommodation": 1.0,  # sigma_t (schaaf-chambre, cll)
    "wall_temperature": 300.0,  # T_w [K]
}

#: Hottest wall temperature a material may give [K]: above any surface a spacecraft keeps (tungsten melts
#: at 3695 K); a larger value is a unit slip, not a wall.
MAX_WALL_TEMPERATURE_K = 1e4


@dataclass(frozen=True)
class GasSurface:
    """How a surface finish meets the rarefied gas (METHOD.md "Free-molecular flow").

    Attributes
    ----------
    model : str
        One of :data:`GSI_MODELS`.
    energy_accommodation : float
        ``alpha_E`` [-] in [0, 1], of the diffuse models ``sentman`` and ``dria``.
    normal_accommodation : float
        ``sigma_n`` of ``schaaf-chambre``, normal energy accommodation ``alpha_n`` of ``cll`` [-].
    tangential_accommodation : float
        ``sigma_t`` [-] of ``schaaf-chambre`` and ``cll``.
    wall_temperature_K : float
        ``T_w`` [K], > 0.

    Examples
    --------
    >>> gas = GasSurface.checked("material 'foil'", {"gsi": "cll", "normal_accommodation": 0.5})
    >>> gas.model, gas.normal_accommodation, gas.wall_temperature_K, gas.code == GSI_MODELS.index("cll")
    ('cll', 0.5, 300.0, True)
    """

    model: str = GAS_DEFAULTS["gsi"]
    energy_accommodation: float = GAS_DEFAULTS["energy_accommodation"]
    normal_accommodation: float = GAS_DEFAULTS["normal_accommodation"]
    tangential_accommodation: float = GAS_DEFAULTS["tangential_accommodation"]
    wall_temperature_K: float = GAS_DEFAULTS["wall_temperature"]

    @classmethod
    def checked(cls, where: str, values: Mapping[str, object], source: str | None = None) -> GasSurface:
        """Gas-surface parameters from ``GAS_DEFAULTS`` keys (missing keys take their defaults).

        ``where`` names the owner in messages, e.g. "material 'white_paint'" or "command line".
        """
        unknown = sorted(set(values) - set(GAS_DEFAULTS))
        if unknown:
            raise MaterialError(f"{where} has unknown gas key '{unknown[0]}'", path=source)
        model = values.get("gsi", GAS_DEFAULTS["gsi"])
        if model not in GSI_MODELS:
            raise MaterialError(
                f"{where}: gsi = {model!r} is not a gas-surface model",
                path=source,
                hint=f"use one of {', '.join(GSI_MODELS)}",
            )
        numbers = {}
        for key in ("energy_accommodation", "normal_accommodation", "tangential_accommodation"):
            numbers[key] = checked_number(where, key, values.get(key, GAS_DEFAULTS[key]), source, 0.0, 1.0)
        wall = checked_number(
            where, "wall_temperature", values.get("wall_temperature", 300.0), source, 0.0, None, " K"
        )
        if wall > MAX_WALL_TEMPERATURE_K:
            raise MaterialError(
                f"{where}: wall_temperature = {wall:g} K is above {MAX_WALL_TEMPERATURE_K:g} K, hotter than "
                "any spacecraft wall",
                path=source,
                hint="give the surface temperature in kelvin",
            )
        return cls(model=str(model), wall_temperature_K=wall, **numbers)

    @property
    def code(self) -> int:
        """Index of :attr:`model` in :data:`GSI_MODELS`."""
        return GSI_MODELS.index(self.model)


def checked_number(
    where: str, key: str, value: object, source: str | None, low: float, high: float | None, unit: str = ""
) -> float:
    """Check that a value read from a file is a number in range.

    Parameters
    ----------
    where : str
        Owner of the value, for the message, e.g. "material 'white_paint'".
    key : str
        Name of the value, for the message.
    value : object
        The value read.
    source : str or None
        The file it was read from, named in the error.
    low : float
        Lower bound; inclusive when ``high`` is given, else exclusive.
    high : float or None
        Inclusive upper bound; None for none.
    unit : str
        Unit that follows the numbers of a lower-bound-only message, e.g. " K".

    Returns
    -------
    float
        ``value`` as a float.

    Raises
    ------
    MaterialError
        ``value`` is not a number (a bool is not), not finite, or out of range.

    Examples
    --------
    >>> checked_number("material 'm'", "reflectivity", 1, None, 0.0, 1.0)
    1.0
    >>> checked_number("material 'm'", "reflectivity", 1.5, None, 0.0, 1.0)
    Traceback (most recent call last):
    ...
    sunwind.geometry.errors.MaterialError: material 'm': reflectivity = 1.5 is outside [0, 1]...
    """
    hint = f"use a number in [{low:g}, {high:g}]" if high is not None else f"use a number above {low:g}{unit}"
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise MaterialError(f"{where}: {key} = {value!r} is not a number", path=source, hint=hint)
    if high is not None and not (math.isfinite(value) and low <= value <= high):
        raise MaterialError(
            f"{where}: {key} = {value} is outside [{low:g}, {high:g}]", path=source, hint=hint
        )
    if high is None and not (math.isfinite(value) and value > low):
        raise MaterialError(
            f"{where}: {key} = {value:g}{unit} is not above {low:g}{unit}", path=source, hint=hint
        )
    return float(value)


@dataclass(frozen=True)
class Finish:
    """One named finish: grey solar-band optics and grey infrared emissivity.

    Attributes
    ----------
    name : str
        Its name in :data:`FINISHES`.
    absorptance : float
        Solar absorptance ``alpha_s`` [-], in [0, 1].
    emissivity : float
        Hemispherical infrared emissivity ``eps`` [-], in [0, 1].
    specular_fraction : float
        ``beta`` [-], specular share of the reflected sunlight (an estimate for every finish).
    source : str
        Where ``absorptance`` and ``emissivity`` come from, and which numbers are estimates.
    transmissivity : float
        Solar ``sigma`` [-]; 0 (opaque).

    Examples
    --------
    >>> paint = Finish("paint", absorptance=0.285, emissivity=0.9, specular_fraction=0.1, source="made up")
    >>> paint.reflectivity
    0.715
    >>> sorted(paint.keys)
    ['emissivity', 'reflectivity', 'specular_fraction', 'transmissivity']
    """

    name: str
    absorptance: float
    emissivity: float
    specular_fraction: float
    source: str
    transmissivity: float = 0.0

    @property
    def reflectivity(self) -> float:
        """``rho = 1 - alpha_s - sigma`` [-], rounded to 1e-9 (0.285, not 0.28500000000000003)."""
        return round(1.0 - self.absorptance - self.transmissivity, 9)

    @property
    def keys(self) -> dict[str, float]:
        """The finish as ``[materials.NAME]`` keys: reflectivity, specular_fraction, transmissivity and
        emissivity."""
        return {
            "reflectivity": self.reflectivity,
            "specular_fraction": self.specular_fraction,
            "transmissivity": self.transmissivity,
            "emissivity": self.emissivity,
        }


_ENAMEL = (
    "Lavochkin table 2: A_s {a}, eps_n {e} (normal emissivity, measured), mid values taken; eps_n is used "
    "as the hemispherical emissivity unconverted (a dielectric paint's hemispherical value is about 0.95 "
    "of its normal one, {h:.2f} here: give emissivity = {h:.2f} to use it); specular_fraction estimated "
    "({what}, {b})"
)

#: The finishes library, by name (read-only).
FINISHES: Mapping[str, Finish] = MappingProxyType(
    {
        f.name: f
        for f in (
            Finish(
                "khs-973",
                0.715,
                0.725,
                0.05,
                "KhS-973 (ХС-973) grey conductive enamel; "
                + _ENAMEL.format(a="0.71-0.72", e="0.72-0.73", h=0.725 * 0.95, b=0.05, what="matte enamel"),
            ),
            Finish(
                "khs-928",
                0.925,
                0.815,
                0.10,
                "KhS-928 (ХС-928) black conductive enamel; "
                + _ENAMEL.format(a="0.92-0.93", e="0.81-0.82", h=0.815 * 0.95, b=0.10, what="flat black"),
            ),
            Finish(
                "ekom-1",
                0.275,
                0.91,
                0.05,
                "EKOM-1 (ЭКОМ-1) white enamel, three coats over a conductive primer; "
                + _ENAMEL.format(a="0.27-0.28", e="0.90-0.92", h=0.91 * 0.95, b=0.05, what="matte white")
                + "; after three months' corrosion test A_s 0.29-0.31, eps_n unchanged",
            ),
            Finish(
                "az-93",
                0.15,
                0.91,
                0.05,
                "AZ-93 white inorganic paint (zinc oxide in potassium silicate): alpha_s 0.15, eps 0.91 "
                "(Gilmore); specular_fraction estimated (matte, nearly Lambertian)",
            ),
            Finish(
                "s13g-lo",
                0.20,
                0.85,
                0.05,
                "S13G/LO white silicone paint: alpha_s 0.20, eps 0.85 (Henninger; Gilmore); darkens under UV "
                "(Fortescue: silicone white 0.26 -> 0.29 after 1000 h); specular_fraction estimated (matte)",
            ),
            Finish(
                "z-93",
                0.17,
                0.92,
                0.05,
                "Z-93 white inorganic paint (IITRI, zinc oxide in potassium silicate): alpha_s 0.17, "
                "eps 0.92 (Henninger; Gilmore); specular_fraction estimated (matte)",
            ),
            Finish(
                "z306",
                0.95,
                0.87,
                0.10,
                "Aeroglaze (Chemglaze) Z306 flat black polyurethane paint: alpha_s 0.95, eps 0.87 (Gilmore; "
                "Fortescue, black polyurethane: 0.95, 0.90); specular_fraction estimated (flat black)",
            ),
            Finish(
                "silver-teflon",
                0.08,
                0.78,
                0.90,
                "silvered Teflon (FEP), 5 mil, second-surface mirror: alpha_s 0.08, eps 0.78 (Gilmore; "
                "Fortescue: 0.08, 0.78; eps rises with film thickness); specular_fraction estimated "
                "(a mirror laid in sheets with some waviness)",
            ),
            Finish(
                "osr",
                0.07,
                0.80,
                0.95,
                "optical solar reflector, silvered fused silica: alpha_s 0.07, eps 0.80 (Gilmore; Fortescue "
                "0.07, 0.74); specular_fraction estimated (second-surface mirror tiles)",
            ),
            Finish(
                "aluminised-kapton",
                0.38,
                0.67,
                0.40,
                "aluminised Kapton, 1 mil, Kapton outward (an MLI outer layer): alpha_s 0.38, eps 0.67 "
                "(Gilmore; Fortescue: 0.40, 0.63; thicker film absorbs and emits more); specular_fraction "
                "estimated (glossy but wrinkled film)",
            ),
            Finish(
                "polished-aluminium",
                0.20,
                0.05,
                0.70,
                "polished aluminium alloy: handbook values spread with the polish, alpha_s about 0.10-0.25, "
                "eps 0.03-0.08 (Gilmore; Fortescue: 0.24, 0.08); 0.20 and 0.05 taken as typical (estimates "
                "within that spread); specular_fraction estimated (polished metal)",
            ),
            Finish(
                "gold",
                0.25,
                0.03,
                0.80,
                "vapour-deposited or plated gold: alpha_s 0.25, eps 0.03 (Gilmore; Fortescue: 0.25, 0.04); "
                "specular_fraction estimated (smooth metal film)",
            ),
            Finish(
                "gaas-cell",
                0.91,
                0.85,
                0.80,
                "GaAs (triple-junction) solar cells under cover glass: alpha_s 0.88-0.92, eps 0.80-0.85 "
                "(Gilmore; Fortescue: 0.88, 0.80), 0.91 and 0.85 taken (the emission is the cover glass's); "
                "specular_fraction estimated (the reflection is mostly the cover glass's)",
            ),
            Finish(
                "black-kapton",
                0.92,
                0.85,
                0.50,
                "black (carbon-loaded) Kapton film: alpha_s about 0.92, eps about 0.85 (handbook class "
                "values, Gilmore; to be checked against the film's data sheet); specular_fraction estimated "
                "(glossy film)",
            ),
            Finish(
                "ge-black-kapton",
                0.49,
                0.81,
                0.50,
                "germanium-coated black Kapton (antenna sunshields): alpha_s about 0.49, eps about 0.81 "
                "(vendor class values as quoted in thermal handbooks, Gilmore; to be checked against the "
                "film's data sheet); specular_fraction estimated (thin semiconductor film on glossy "
                "polyimide)",
            ),
            Finish(
                "cfrp",
                0.92,
                0.82,
                0.20,
                "bare carbon-fibre epoxy: alpha_s 0.90-0.93, eps 0.80-0.85 (Gilmore, graphite-epoxy), "
                "0.92 and 0.82 taken; specular_fraction estimated (resin-rich surface, mostly diffuse)",
            ),
        )
    }
)


def finish(name: object, where: str = "", source: str | None = None) -> Finish:
    """Look up a finish of the library :data:`FINISHES` by name.

    Parameters
    ----------
    name : str
        Its name, e.g. ``"az-93"``.
    where : str
        Who asks, for the message (e.g. "material 'radiator'"); empty for none.
    source : str, optional
        The file that names it.

    Returns
    -------
    Finish
        The finish.

    Raises
    ------
    MaterialError
        ``name`` is not a finish of the library; the message lists the closest names.

    Examples
    --------
    >>> white = finish("az-93")
    >>> white.absorptance, white.emissivity, white.reflectivity
    (0.15, 0.91, 0.85)
    """
    if isinstance(name, str) and name in FINISHES:
        return FINISHES[name]
    close = difflib.get_close_matches(str(name).lower(), FINISHES, n=4, cutoff=0.4)
    shown = ", ".join(f'"{c}"' for c in close) if close else "none"
    raise MaterialError(
        f"{where + ': ' if where else ''}finish = {name!r} is not in the finishes library",
        path=source,
        hint=f"the closest names: {shown}; the library: sunwind.geometry.finishes.FINISHES "
        f"({len(FINISHES)} finishes, the materials guide: docs/guides/meshes.md)",
    )
