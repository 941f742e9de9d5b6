"""The names, units and long names every result, batch, sweep table and orbit series shares (METHOD.md
"Outputs and tables"): one vocabulary, so ``force_N`` is the same quantity, with the same UDUNITS string,
in a result's :meth:`~sunwind.forces.result_base.LoadResult.to_dataset`, a batch's, a sweep table and an
orbit's dataset, and vectors always run along the dimension :data:`COMPONENT`.

>>> from sunwind.forces.vocabulary import units_of
>>> units_of("torque_Nm"), units_of("lit_area_m2"), units_of("CD")
('N m', 'm2', '1')
"""

from __future__ import annotations

#: The dimension every vector runs along, and its coordinate values.
COMPONENT = "component"
#: The coordinate of :data:`COMPONENT`.
COMPONENTS = ("x", "y", "z")
#: Attributes of the :data:`COMPONENT` coordinate.
COMPONENT_ATTRS = {"long_name": "vector component along the body-frame axis"}
#: The dimension a batch's results run along.
ATTITUDE = "attitude"
#: The dimensions an orbit's per-part and per-side series run along (besides ``time``).
PART, SIDE = "part", "side"
#: Sources of the power a part or a side absorbs, in order, with what each is: the first three as they
#: arrive, ``reflected`` after reflections off the spacecraft (of every band); the four add up to the
#: absorbed power.
ABSORBED_SOURCES = {
    "solar": "direct sunlight",
    "albedo": "sunlight the Earth reflects, as it arrives",
    "infrared": "the Earth's infrared, as it arrives",
    "reflected": "light of every band after reflection off the spacecraft's own surfaces",
}
#: Coordinates of the :data:`SIDE` dimension, what maps a side onto a mesh facet, with their long names.
SIDE_COORDINATES = {
    "side_part": "part the side belongs to",
    "side_facet": "facet of the side (index into the model's triangles)",
    "side_face": "front (along the facet normal) or back side of the facet",
    "side_area_m2": "area of the side",
}

#: UDUNITS strings of the unit suffixes names end in, longest first where one ends another.
SUFFIX_UNITS = (
    ("_W_m2", "W m-2"),
    ("_kg_m3", "kg m-3"),
    ("_m_s", "m s-1"),
    ("_Nms", "N m s"),
    ("_Nm", "N m"),
    ("_m2", "m2"),
    ("_m3", "m3"),
    ("_deg", "degree"),
    ("_rad", "radian"),
    ("_km", "km"),
    ("_Pa", "Pa"),
    ("_W", "W"),
    ("_K", "K"),
    ("_N", "N"),
    ("_s", "s"),
    ("_m", "m"),
)
#: Units of the names that carry no suffix.
UNITS = {
    "CD": "1",
    "CS": "1",
    "CL": "1",
    "CM": "1",
    "force_coefficients": "1",
    "speed_ratio": "1",
    "k_is": "1",
    "rays": "1",
    "solar_fraction": "1",
    "sun_vector": "1",
    "flow_vector": "1",
    "earth_vector": "1",
    "error_estimate_force": "1",
    "error_estimate_torque": "1",
}
#: Long names by field name.
LONG_NAMES = {
    "force_N": "force, body frame",
    "torque_Nm": "torque about the reference point, body frame",
    "direct_force_N": "force of the direct flux (panel law with shadowing)",
    "direct_torque_Nm": "torque of the direct flux",
    "reflected_force_N": "force added by inter-reflection (light) or re-emission exchange (molecules)",
    "reflected_torque_Nm": "torque added by inter-reflection or re-emission exchange",
    "lit_area_m2": "lit area (SRP), or area facing the flow and not shadowed from it (drag)",
    "projected_area_m2": "lit area projected normal to the Sun vector (SRP) or the flow vector u (drag)",
    "rays": "shadow rays cast",
    "k_is": "interference criterion K_IS of eq. (7)",
    "sun_vector": "unit vector toward the Sun",
    "flux_W_m2": "solar flux at the spacecraft",
    "pressure_Pa": "radiation pressure flux / c",
    "velocity_m_s": "velocity relative to the atmosphere v_rel, body frame",
    "speed_ratio": "speed ratio V / sqrt(2 k T / m_mean)",
    "dynamic_pressure_Pa": "dynamic pressure rho V^2 / 2",
    "CD": "drag coefficient F.(-u)/(q A_ref)",
    "CS": "side-force coefficient",
    "CL": "lift coefficient",
    "CM": "moment coefficients M/(q A_ref L_ref), body axes",
    "albedo_force_N": "force of the sunlight the Earth reflects, body frame",
    "albedo_torque_Nm": "torque of the Earth's albedo",
    "infrared_force_N": "force of the Earth's infrared, body frame",
    "infrared_torque_Nm": "torque of the Earth's infrared",
    "thermal_force_N": "recoil of each side's infrared at radiative equilibrium, body frame",
    "thermal_torque_Nm": "torque of the thermal recoil",
    "solar_fraction": "share of the solar disc in view (0: the Earth hides the Sun)",
    "error_estimate_force": "estimated relative error of the force left by the shadow pass",
    "error_estimate_torque": "estimated relative error of the torque left by the shadow pass",
    **SIDE_COORDINATES,
}


def absorbed_name(where: str, source: str) -> str:
    """The name of the power absorbed from ``source``, summed over each ``where``: ``{where}_{source}_W``.

    There is no CF standard name for absorbed power: its variables carry ``units``, ``long_name`` and a
    ``comment`` that spells this scheme out (:func:`variable_attrs`).

    Parameters
    ----------
    where : {"part", "side"}
        Per part (its sides summed) or per side (one side of a facet).
    source : str
        One of :data:`ABSORBED_SOURCES`.

    Returns
    -------
    str
        The field's name.

    Examples
    --------
    >>> absorbed_name(PART, "albedo"), absorbed_name(SIDE, "solar")
    ('part_albedo_W', 'side_solar_W')
    """
    return f"{where}_{source}_W"


_EACH = {PART: "each part (its sides summed)", SIDE: "each side of a facet"}
LONG_NAMES |= {
    absorbed_name(where, source): f"power absorbed by {_EACH[where]}: {words}"
    for where in (PART, SIDE)
    for source, words in ABSORBED_SOURCES.items()
} | {
    "part_temperature_K": "area-weighted mean of the sides' radiative-equilibrium temperatures of each part",
    PART: "part of the model (mesh part name)",
    SIDE: "side of a facet (index into the model's sides)",
}
_ABSORBED_COMMENT = (
    "no CF standard_name exists for absorbed power; sunwind names it {where}_{source}_W, where the power "
    "is summed (part: over a part's sides; side: one side of a facet) and what it comes from (solar, "
    "albedo, infrared as they arrive; reflected: after reflections off the spacecraft); the four sources "
    "add up to the absorbed power"
)
#: What the variables of some fields mean beyond their long names (attribute ``comment``).
COMMENTS = {
    "error_estimate_force": "|dF| / |F|: the shadow pass's check (rays at random points of a sample of "
    "the sides) and each side's load per unit lit area give the absolute error dF; 0 where nothing can be "
    "wrong; not written with fixed sampling (samples)",
    "error_estimate_torque": "|dM| / max(|M|, 0.01 |F| L), L the diagonal of the model's bounding box: "
    "against the torque, or where that is small against a torque the force could give",
} | {absorbed_name(where, source): _ABSORBED_COMMENT for where in (PART, SIDE) for source in ABSORBED_SOURCES}


def units_of(name: str) -> str | None:
    """The UDUNITS string of a quantity named ``name``, from :data:`UNITS` or the unit its name ends in.

    Parameters
    ----------
    name : str
        A field name, e.g. ``"force_N"``, ``"srp_torque_Nm"`` or ``"CD"``.

    Returns
    -------
    str or None
        Its units, ``"1"`` for a number without dimension, None when the name says nothing of them.

    Examples
    --------
    >>> units_of("srp_force_N"), units_of("velocity_m_s"), units_of("sampling")
    ('N', 'm s-1', None)
    """
    if name in UNITS:
        return UNITS[name]
    for suffix, units in SUFFIX_UNITS:
        if name.endswith(suffix):
            return units
    return None


def variable_attrs(name: str) -> dict[str, str]:
    """``units``, ``long_name`` and ``comment`` of a quantity named ``name``, those that are known.

    Parameters
    ----------
    name : str
        A field name of :data:`LONG_NAMES` or one whose units :func:`units_of` can tell.

    Returns
    -------
    dict
        The CF attributes of its variable.

    Examples
    --------
    >>> variable_attrs("lit_area_m2")["units"]
    'm2'
    """
    attrs = {}
    units = units_of(name)
    if units is not None:
        attrs["units"] = units
    if name in LONG_NAMES:
        attrs["long_name"] = LONG_NAMES[name]
    if name in COMMENTS:
        attrs["comment"] = COMMENTS[name]
    return attrs
