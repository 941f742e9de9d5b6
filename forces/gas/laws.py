"""Gas-surface interaction (GSI) laws: how a surface returns the molecules that strike it, one function
per law, and the pressure and shear coefficients that follow (METHOD.md "Free-molecular flow").

Notes
-----
**Conventions** (METHOD.md "Frames, units and signs"). For one species of number density ``n_k`` and
molecular mass ``m``, with speed ``V = |v_rel|``, free-stream temperature ``T``, speed ratio ``S = V /
sqrt(2 k T / m)`` and dynamic pressure ``q = rho V^2 / 2``, the force per unit area of an element of
outward normal ``n`` is::

    dF / dA = q (-c_n n + c_t t_hat),     t_hat = -(u - gamma n) / |u - gamma n|,

``c_n`` the pressure coefficient (pushing into the surface), ``c_t`` the shear coefficient, ``t_hat``
the direction of the molecules' tangential motion; the incident stream is :mod:`.incident`'s.

**The laws.** Each is linear in the incident distribution, so each is a :class:`Reemission`: a share
of the incident normal momentum returned specularly (``pressure_scale = 1 +`` that share), the
tangential momentum kept (``shear_scale``), and a share re-emitted diffusely at a temperature
``T_r`` (``tau_w = T_w / T``):

- :func:`sentman`: diffuse, full tangential accommodation, ``T_r / T = alpha_E tau_w + (1 - alpha_E)
  (2/3) S^2``: a re-emitted molecule carries ``(3/2) k T_r``, the incident one ``m V^2 / 2`` (Sentman
  1961). The default for orbit work.
- :func:`dria`: the same kernel with the other published energy balance, ``2 k T_r`` per re-emitted
  molecule (Doornbos; Moe & Moe): ``T_r / T = alpha_E tau_w + (1 - alpha_E) S^2 / 2``. At
  ``alpha_E = 0.9`` and LEO speed ratios the two differ by about 2 % in ``C_D`` (METHOD.md "The paper's
  misprints").
- :func:`schaaf_chambre`: normal and tangential momentum accommodation ``sigma_n``, ``sigma_t``, the
  accommodated share re-emitted diffusely at ``T_w``: ``c_n = (2 - sigma_n) c_n_inc + sigma_n * (diffuse
  term at T_w)``, ``c_t = sigma_t c_t_inc``.
- :func:`cll`: Cercignani-Lampis-Lord kernel with normal energy accommodation ``alpha_n`` and tangential
  momentum accommodation ``sigma_t`` (tangential energy accommodation ``sigma_t (2 - sigma_t)``). The
  tangential kernel's mean is ``(1 - sigma_t)`` times the incident tangential velocity, so ``c_t =
  sigma_t c_t_inc`` exactly; ``c_n = c_n_inc +`` the exact mean of the Rice-distributed reflected normal
  speed over the incident stream (:func:`~sunwind.forces.gas.incident.cll_reflected_normal`), not the
  fitted approximation of Walker et al. (2014).
- :func:`specular`: ``c_n = 2 c_n_inc``, ``c_t = 0``. For ``S -> inf`` the force per area is ``-4 q
  gamma^2 n``, the radiation law of a perfect mirror with ``P = 2 q`` (the paper's premise).

**Molecular exchange.** What a law re-emits diffusely travels on to other sides through the view
factors (:mod:`sunwind.forces.gas.exchange`), as :attr:`Reemission.emission_share` at
:attr:`Reemission.emission_temperature_K`: the diffuse share of sentman, dria and schaaf-chambre. What
it sends on unaccommodated (the specular law, Schaaf-Chambre's ``1 - sigma_n``, everything CLL sends
back, a lobe about the mirror direction) is followed by the chains of :mod:`sunwind.forces.gas.chains`.

:func:`panel_coefficients` evaluates laws mixed element by element (by model code), in numpy: the
reference the fast species sums (:func:`sunwind.forces.gas.sums.summed_coefficients`) are tested
against; both read the laws' :class:`Reemission`, so neither writes a law again.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sunwind.forces.gas.incident import (
    check_speed_ratio,
    check_stream,
    cll_reflected_normal,
    diffuse_normal,
    incident,
)
from sunwind.geometry.errors import InputError
from sunwind.geometry.materials import GSI_MODELS

#: Model name -> small integer code, for per-side ``int8`` arrays.
MODEL_CODES: dict[str, int] = {name: code for code, name in enumerate(GSI_MODELS)}
#: Parameters of each law, and the materials-file gas key (:class:`~sunwind.geometry.materials.GasSurface`
#: field) each is read from; a law ignores the other keys.
GSI_PARAMS: dict[str, dict[str, str]] = {
    "sentman": {"energy_accommodation": "energy_accommodation", "wall_temperature_K": "wall_temperature_K"},
    "dria": {"energy_accommodation": "energy_accommodation", "wall_temperature_K": "wall_temperature_K"},
    "schaaf-chambre": {
        "normal_accommodation": "normal_accommodation",
        "tangential_accommodation": "tangential_accommodation",
        "wall_temperature_K": "wall_temperature_K",
    },
    "cll": {
        "normal_energy_accommodation": "normal_accommodation",
        "tangential_accommodation": "tangential_accommodation",
        "wall_temperature_K": "wall_temperature_K",
    },
    "specular": {},
}


class Coefficients(NamedTuple):
    """Pressure and shear coefficients of elements: force per area over ``q`` is ``-c_n n_out + c_t t_hat``.

    Parameters
    ----------
    c_n : (n,) float64
        Pressure coefficient [-], pushing into the surface.
    c_t : (n,) float64
        Shear coefficient [-], along the molecules' tangential motion ``t_hat``.

    Examples
    --------
    >>> import numpy as np
    >>> Coefficients(c_n=np.array([2.0]), c_t=np.array([0.0])).c_n
    array([2.])
    """

    c_n: NDArray[np.float64]
    c_t: NDArray[np.float64]


@dataclass(frozen=True, eq=False, kw_only=True)
class Reemission:
    """How a gas-surface law returns the molecules that strike ``n`` elements, at one speed ratio.

    Built by the law functions (:func:`sentman`, :func:`dria`, :func:`schaaf_chambre`, :func:`cll`,
    :func:`specular`) and :func:`reemission`; keyword arguments only.

    Parameters
    ----------
    speed_ratio : float
        ``S`` of the species [-].
    pressure_scale : (n,) float64
        Factor of the incident normal momentum ``c_n_inc``: 1 plus the share returned specularly.
    shear_scale : (n,) float64
        Factor of the incident tangential momentum ``c_t_inc`` the surface takes.
    diffuse_share : (n,) float64
        Share of the incident molecules re-emitted as a Lambertian half-Maxwellian.
    temperature_ratio : (n,) float64
        ``T_r / T`` of that re-emission.
    cll_alpha_n : (n,) float64 or None
        CLL's normal energy accommodation where its exact normal kernel applies (NaN elsewhere), and
        ``tau_w = T_w / T`` beside it in ``cll_tau_w``; None where no element is CLL.
    cll_tau_w : (n,) float64 or None
        ``T_w / T`` of the CLL elements; None where no element is CLL.
    emission_share, emission_temperature_K : (n,) float64
        What the molecular exchange carries on as diffuse re-emission: share and temperature [K].
    wall_weight, energy_weight : (n,) float64
        The re-emission temperature of one molecule that arrives with speed ``v``: ``T_r = wall_weight
        T_w + energy_weight m v^2 / (2 k)`` [K] (the molecular chains'); at ``v = V`` it is the
        stream's ``temperature_ratio T``. Where nothing is re-emitted diffusely, 1 and 0.

    Examples
    --------
    >>> law = schaaf_chambre(7.0, 1000.0, normal_accommodation=0.8)
    >>> law.pressure_scale, law.diffuse_share
    (array([1.2]), array([0.8]))
    """

    speed_ratio: float
    pressure_scale: NDArray[np.float64]
    shear_scale: NDArray[np.float64]
    diffuse_share: NDArray[np.float64]
    temperature_ratio: NDArray[np.float64]
    emission_share: NDArray[np.float64]
    emission_temperature_K: NDArray[np.float64]
    wall_weight: NDArray[np.float64]
    energy_weight: NDArray[np.float64]
    cll_alpha_n: NDArray[np.float64] | None = None
    cll_tau_w: NDArray[np.float64] | None = None

    def coefficients(self, cos_incidence: ArrayLike, stream: str = "full") -> Coefficients:
        """Pressure and shear coefficients of the elements at incidence ``gamma = n_out . u``.

        Parameters
        ----------
        cos_incidence : (n,) array_like
            ``gamma`` [-] of each element, in [-1, 1] (one value per element, or one law for many
            values).
        stream : {"full", "directed", "thermal"}
            Incident stream (:mod:`sunwind.forces.gas.incident`).

        Returns
        -------
        Coefficients
            ``(c_n, c_t)``, each (n,).

        Raises
        ------
        InputError
            Unknown stream, non-finite cosines or a count that does not match the elements.

        Examples
        --------
        >>> law = specular(7.0, 1000.0)
        >>> law.coefficients([1.0, 0.5]).c_n.round(4)
        array([4.0408, 1.0408])
        """
        check_stream(stream)
        gamma = _cosines(cos_incidence, len(self.pressure_scale))
        law = self if len(self.pressure_scale) == len(gamma) else self.repeated(len(gamma))
        c_n_inc, c_t_inc, flux = incident(gamma, law.speed_ratio, stream)
        c_n = law.pressure_scale * c_n_inc + law.diffuse_share * diffuse_normal(
            flux, law.temperature_ratio, law.speed_ratio
        )
        if law.cll_alpha_n is not None:
            at = np.flatnonzero(np.isfinite(law.cll_alpha_n))
            normal = (gamma[at], law.cll_alpha_n[at], law.cll_tau_w[at], law.speed_ratio, stream)
            c_n[at] = c_n_inc[at] + cll_reflected_normal(*normal)
        return Coefficients(c_n, law.shear_scale * c_t_inc)

    def repeated(self, n: int) -> Reemission:
        """A law of one element (parameters given as scalars) for ``n`` elements.

        Parameters
        ----------
        n : int
            Elements wanted.

        Returns
        -------
        Reemission
            The same law, each array repeated ``n`` times.

        Examples
        --------
        >>> sentman(7.0, 1000.0).repeated(3).diffuse_share
        array([1., 1., 1.])
        """
        arrays = {
            name: np.repeat(getattr(self, name), n)
            for name in (*_REEMISSION_ARRAYS, "cll_alpha_n", "cll_tau_w")
            if getattr(self, name) is not None
        }
        return Reemission(speed_ratio=self.speed_ratio, **arrays)


def sentman(
    speed_ratio: float,
    temperature_K: float,
    *,
    energy_accommodation: ArrayLike = 1.0,
    wall_temperature_K: ArrayLike = 300.0,
) -> Reemission:
    """Sentman's diffuse law: every molecule re-emitted diffusely, full tangential accommodation.

    The re-emission temperature is ``T_r / T = alpha_E tau_w + (1 - alpha_E) (2/3) S^2`` (module Notes).

    Parameters
    ----------
    speed_ratio : float
        ``S`` of the species [-], > 0.
    temperature_K : float
        Free-stream temperature ``T`` [K], > 0.
    energy_accommodation : (n,) array_like
        ``alpha_E`` [-] in [0, 1].
    wall_temperature_K : (n,) array_like
        ``T_w`` [K], >= 0 (0: the cold-wall limit; a material's must be > 0).

    Returns
    -------
    Reemission
        The law of each element.

    Raises
    ------
    InputError
        A parameter out of range, or a speed ratio or temperature that is not finite and > 0.

    References
    ----------
    .. [1] Sentman, L. H. (1961). "Free molecule flow theory and its application to the determination of
       aerodynamic forces." Lockheed Missiles and Space Co., LMSC-448514.

    Examples
    --------
    >>> law = sentman(7.0, 1000.0, energy_accommodation=0.9, wall_temperature_K=300.0)
    >>> law.emission_temperature_K.round(2)
    array([3536.67])
    >>> law.coefficients([1.0]).c_n.round(4)
    array([2.4966])
    """
    return _diffuse_law(2.0 / 3.0, speed_ratio, temperature_K, energy_accommodation, wall_temperature_K)


def dria(
    speed_ratio: float,
    temperature_K: float,
    *,
    energy_accommodation: ArrayLike = 1.0,
    wall_temperature_K: ArrayLike = 300.0,
) -> Reemission:
    """The diffuse law with ``2 k T_r`` per re-emitted molecule (DRIA).

    The re-emission temperature is ``T_r / T = alpha_E tau_w + (1 - alpha_E) S^2 / 2``.

    Parameters
    ----------
    speed_ratio : float
        ``S`` of the species [-], > 0.
    temperature_K : float
        Free-stream temperature ``T`` [K], > 0.
    energy_accommodation : (n,) array_like
        ``alpha_E`` [-] in [0, 1].
    wall_temperature_K : (n,) array_like
        ``T_w`` [K], >= 0.

    Returns
    -------
    Reemission
        The law of each element.

    Raises
    ------
    InputError
        A parameter out of range, or a speed ratio or temperature that is not finite and > 0.

    Examples
    --------
    >>> dria(7.0, 1000.0, energy_accommodation=0.9).temperature_ratio.round(4)
    array([2.72])
    """
    return _diffuse_law(0.5, speed_ratio, temperature_K, energy_accommodation, wall_temperature_K)


def schaaf_chambre(
    speed_ratio: float,
    temperature_K: float,
    *,
    normal_accommodation: ArrayLike = 1.0,
    tangential_accommodation: ArrayLike = 1.0,
    wall_temperature_K: ArrayLike = 300.0,
) -> Reemission:
    """Schaaf & Chambre's law: ``sigma_n`` of the molecules re-emitted diffusely, the rest mirrored.

    The accommodated share ``sigma_n`` of the normal momentum is re-emitted diffusely at ``T_w``, the
    rest specularly; the share ``sigma_t`` of the tangential momentum is taken.

    Parameters
    ----------
    speed_ratio : float
        ``S`` of the species [-], > 0.
    temperature_K : float
        Free-stream temperature ``T`` [K], > 0.
    normal_accommodation : (n,) array_like
        ``sigma_n`` [-] in [0, 1].
    tangential_accommodation : (n,) array_like
        ``sigma_t`` [-] in [0, 1].
    wall_temperature_K : (n,) array_like
        ``T_w`` [K], >= 0.

    Returns
    -------
    Reemission
        The law of each element.

    Raises
    ------
    InputError
        A parameter out of range, or a speed ratio or temperature that is not finite and > 0.

    References
    ----------
    .. [1] Schaaf, S. A., Chambre, P. L. (1961). *Flow of Rarefied Gases*. Princeton University Press.

    Examples
    --------
    >>> law = schaaf_chambre(7.0, 1000.0, normal_accommodation=0.8, tangential_accommodation=0.9)
    >>> law.pressure_scale, law.shear_scale
    (array([1.2]), array([0.9]))
    """
    sigma_n, sigma_t, t_wall = _checked(
        speed_ratio,
        temperature_K,
        normal_accommodation=normal_accommodation,
        tangential_accommodation=tangential_accommodation,
        wall_temperature_K=wall_temperature_K,
    )
    ones, zeros = np.ones_like(t_wall), np.zeros_like(t_wall)
    return Reemission(
        speed_ratio=speed_ratio,
        pressure_scale=2.0 - sigma_n,
        shear_scale=sigma_t,
        diffuse_share=sigma_n,
        temperature_ratio=t_wall / temperature_K,
        emission_share=sigma_n,
        emission_temperature_K=t_wall.copy(),
        wall_weight=ones,
        energy_weight=zeros,
    )


def cll(
    speed_ratio: float,
    temperature_K: float,
    *,
    normal_energy_accommodation: ArrayLike = 1.0,
    tangential_accommodation: ArrayLike = 1.0,
    wall_temperature_K: ArrayLike = 300.0,
) -> Reemission:
    """The Cercignani-Lampis-Lord kernel, exact (module Notes).

    It re-emits nothing as a diffuse stream: the molecular chains follow its whole lobe.

    Parameters
    ----------
    speed_ratio : float
        ``S`` of the species [-], > 0.
    temperature_K : float
        Free-stream temperature ``T`` [K], > 0.
    normal_energy_accommodation : (n,) array_like
        ``alpha_n`` [-] in [0, 1] (a materials file's ``normal_accommodation`` key).
    tangential_accommodation : (n,) array_like
        ``sigma_t`` [-] in [0, 1].
    wall_temperature_K : (n,) array_like
        ``T_w`` [K], >= 0.

    Returns
    -------
    Reemission
        The law of each element.

    Raises
    ------
    InputError
        A parameter out of range, or a speed ratio or temperature that is not finite and > 0.

    References
    ----------
    .. [1] Cercignani, C., Lampis, M. (1971). "Kinetic models for gas-surface interactions." Transport
       Theory and Statistical Physics 1(2), 101-114.
    .. [2] Walker, A., Mehta, P., Koller, J. (2014). "Drag coefficient model using the
       Cercignani-Lampis-Lord gas-surface interaction model." Journal of Spacecraft and Rockets 51(5),
       1544-1563 (whose fitted normal coefficient this law does not use).

    Examples
    --------
    >>> law = cll(7.0, 1000.0, normal_energy_accommodation=0.5, tangential_accommodation=0.9)
    >>> law.coefficients([1.0, 0.5]).c_t.round(4)
    array([0.    , 0.7794])
    """
    alpha_n, sigma_t, t_wall = _checked(
        speed_ratio,
        temperature_K,
        normal_energy_accommodation=normal_energy_accommodation,
        tangential_accommodation=tangential_accommodation,
        wall_temperature_K=wall_temperature_K,
    )
    tau_w = t_wall / temperature_K
    ones, zeros = np.ones_like(tau_w), np.zeros_like(tau_w)
    return Reemission(
        speed_ratio=speed_ratio,
        pressure_scale=ones,
        shear_scale=sigma_t,
        diffuse_share=zeros,
        temperature_ratio=tau_w,
        emission_share=zeros.copy(),
        emission_temperature_K=t_wall.copy(),
        wall_weight=ones.copy(),
        energy_weight=zeros.copy(),
        cll_alpha_n=alpha_n,
        cll_tau_w=tau_w,
    )


def specular(speed_ratio: float, temperature_K: float, *, size: int = 1) -> Reemission:
    """Every molecule reflected as from a mirror: ``c_n = 2 c_n_inc``, ``c_t = 0``.

    Parameters
    ----------
    speed_ratio : float
        ``S`` of the species [-], > 0.
    temperature_K : float
        Free-stream temperature ``T`` [K], > 0.
    size : int
        Elements (the law has no parameters to give their number).

    Returns
    -------
    Reemission
        The law of each element.

    Raises
    ------
    InputError
        A parameter out of range, or a speed ratio or temperature that is not finite and > 0.

    Examples
    --------
    >>> specular(7.0, 1000.0, size=2).pressure_scale
    array([2., 2.])
    """
    _checked(speed_ratio, temperature_K)
    zeros = np.zeros(size)
    return Reemission(
        speed_ratio=speed_ratio,
        pressure_scale=np.full(size, 2.0),
        shear_scale=zeros,
        diffuse_share=zeros,
        temperature_ratio=zeros,
        emission_share=zeros,
        emission_temperature_K=zeros.copy(),
        wall_weight=np.ones(size),
        energy_weight=zeros,
    )


#: The law of each model name.
GSI_LAWS: dict[str, Callable[..., Reemission]] = {
    "sentman": sentman,
    "dria": dria,
    "schaaf-chambre": schaaf_chambre,
    "cll": cll,
    "specular": specular,
}


@dataclass(frozen=True, eq=False)
class GasSurfaces:
    """Gas-surface parameters of ``n`` elements, one array (n,) per ``GasSurface`` field.

    Parameters
    ----------
    code : (n,) int64
        Law of each element, into :data:`~sunwind.geometry.materials.GSI_MODELS` (:data:`MODEL_CODES`).
    energy_accommodation, normal_accommodation, tangential_accommodation : (n,) float64
        Accommodation coefficients [-], in [0, 1].
    wall_temperature_K : (n,) float64
        ``T_w`` [K].

    Examples
    --------
    >>> surfaces = GasSurfaces.of({"code": [0, 4], "energy_accommodation": 0.9,
    ...     "normal_accommodation": 1.0, "tangential_accommodation": 1.0, "wall_temperature_K": 300.0})
    >>> len(surfaces), surfaces.take([1]).code
    (2, array([4]))
    """

    code: NDArray[np.int64]
    energy_accommodation: NDArray[np.float64]
    normal_accommodation: NDArray[np.float64]
    tangential_accommodation: NDArray[np.float64]
    wall_temperature_K: NDArray[np.float64]

    @classmethod
    def of(cls, columns: Mapping[str, ArrayLike]) -> GasSurfaces:
        """From a mapping of the field names (e.g. ``Spacecraft.side_gas``), broadcast to one length.

        Parameters
        ----------
        columns : mapping of str to array_like
            One value or array per field.

        Returns
        -------
        GasSurfaces
            The arrays, 1-D and of one length.

        Raises
        ------
        InputError
            A model code outside :data:`MODEL_CODES`.

        Examples
        --------
        >>> GasSurfaces.of({"code": 0, "energy_accommodation": [0.8, 1.0], "normal_accommodation": 1.0,
        ...     "tangential_accommodation": 1.0, "wall_temperature_K": 300.0}).code
        array([0, 0])
        """
        arrays = np.broadcast_arrays(*(np.atleast_1d(np.asarray(columns[name])) for name in _FIELDS))
        code = np.ravel(arrays[0]).astype(np.int64)
        if np.any((code < 0) | (code >= len(GSI_MODELS))):
            raise InputError("unknown gas-surface model code", hint=f"codes are {MODEL_CODES} (MODEL_CODES)")
        floats = {
            name: np.ravel(a).astype(np.float64) for name, a in zip(_FIELDS[1:], arrays[1:], strict=True)
        }
        return cls(code=code, **floats)

    def __len__(self) -> int:
        return len(self.code)

    def take(self, rows: NDArray[np.int64]) -> GasSurfaces:
        """The elements ``rows``.

        Parameters
        ----------
        rows : (m,) int64
            Which elements, in order.

        Returns
        -------
        GasSurfaces
            Those elements.
        """
        return GasSurfaces(**{name: getattr(self, name)[rows] for name in _FIELDS})


_FIELDS = (
    "code",
    "energy_accommodation",
    "normal_accommodation",
    "tangential_accommodation",
    "wall_temperature_K",
)


def reemission(surfaces: GasSurfaces, speed_ratio: float, temperature_K: float) -> Reemission:
    """The :class:`Reemission` of elements of mixed laws, each its law with its parameters.

    Each element gets its law (:data:`GSI_LAWS`) with the parameters that law reads (:data:`GSI_PARAMS`).

    Parameters
    ----------
    surfaces : GasSurfaces
        Law and parameters of each element.
    speed_ratio : float
        ``S`` of the species [-], > 0.
    temperature_K : float
        Free-stream temperature ``T`` [K], > 0.

    Returns
    -------
    Reemission
        One entry per element.

    Raises
    ------
    InputError
        A parameter out of range, or a speed ratio or temperature that is not finite and > 0.

    Examples
    --------
    >>> surfaces = GasSurfaces.of({"code": [MODEL_CODES["sentman"], MODEL_CODES["specular"]],
    ...     "energy_accommodation": 1.0, "normal_accommodation": 1.0, "tangential_accommodation": 1.0,
    ...     "wall_temperature_K": 300.0})
    >>> reemission(surfaces, 7.0, 1000.0).pressure_scale
    array([1., 2.])
    """
    check_speed_ratio(speed_ratio)
    _check_temperature(temperature_K)
    n = len(surfaces)
    parts = {name: np.zeros(n) for name in _REEMISSION_ARRAYS}
    cll_alpha_n = cll_tau_w = None
    for code in np.unique(surfaces.code):
        model = GSI_MODELS[code]
        at = np.flatnonzero(surfaces.code == code)
        if model == "specular":
            law = specular(speed_ratio, temperature_K, size=len(at))
        else:
            given = {name: getattr(surfaces, column)[at] for name, column in GSI_PARAMS[model].items()}
            law = GSI_LAWS[model](speed_ratio, temperature_K, **given)
        for name in _REEMISSION_ARRAYS:
            parts[name][at] = getattr(law, name)
        if law.cll_alpha_n is not None:
            cll_alpha_n, cll_tau_w = np.full(n, np.nan), np.zeros(n)
            cll_alpha_n[at], cll_tau_w[at] = law.cll_alpha_n, law.cll_tau_w
    return Reemission(speed_ratio=speed_ratio, **parts, cll_alpha_n=cll_alpha_n, cll_tau_w=cll_tau_w)


_REEMISSION_ARRAYS = (
    "pressure_scale",
    "shear_scale",
    "diffuse_share",
    "temperature_ratio",
    "emission_share",
    "emission_temperature_K",
    "wall_weight",
    "energy_weight",
)


def panel_coefficients(
    surfaces: GasSurfaces | Mapping[str, ArrayLike],
    cos_incidence: ArrayLike,
    speed_ratio: float,
    temperature_K: float,
    stream: str = "full",
) -> Coefficients:
    """Pressure and shear coefficients ``(c_n, c_t)`` of surface elements for one species.

    Parameters
    ----------
    surfaces : GasSurfaces or mapping
        Law and parameters of each element (arrays broadcast to one length).
    cos_incidence : (n,) array_like
        ``gamma = n_out . u`` [-], in [-1, 1]; negative on lee faces.
    speed_ratio : float
        ``S = V / sqrt(2 k T / m)`` of the species [-], > 0.
    temperature_K : float
        Free-stream temperature ``T`` [K], > 0.
    stream : {"full", "directed", "thermal"}
        Incident stream (:mod:`sunwind.forces.gas.incident`); ``full = directed + thermal``.

    Returns
    -------
    Coefficients
        ``(c_n, c_t)``, each (n,).

    Raises
    ------
    InputError
        Unknown stream or model code, or a parameter out of range.

    Examples
    --------
    A Sentman element and a mirror, both at normal incidence:

    >>> columns = {"code": [MODEL_CODES["sentman"], MODEL_CODES["specular"]], "energy_accommodation": 1.0,
    ...     "normal_accommodation": 1.0, "tangential_accommodation": 1.0, "wall_temperature_K": 300.0}
    >>> panel_coefficients(columns, [1.0, 1.0], 7.0, 1000.0).c_n.round(4)
    array([2.1591, 4.0408])
    """
    check_stream(stream)
    surfaces = surfaces if isinstance(surfaces, GasSurfaces) else GasSurfaces.of(surfaces)
    gamma = _cosines(cos_incidence, len(surfaces))
    if len(surfaces) == 1 and len(gamma) > 1:
        surfaces = surfaces.take(np.zeros(len(gamma), dtype=np.int64))
    return reemission(surfaces, speed_ratio, temperature_K).coefficients(gamma, stream)


def _diffuse_law(
    incident_share: float,
    speed_ratio: float,
    temperature_K: float,
    energy_accommodation: ArrayLike,
    wall_temperature_K: ArrayLike,
) -> Reemission:
    """Sentman's or the DRIA law: ``T_r / T = alpha_E tau_w + (1 - alpha_E) incident_share S^2``."""
    alpha_e, t_wall = _checked(
        speed_ratio,
        temperature_K,
        energy_accommodation=energy_accommodation,
        wall_temperature_K=wall_temperature_K,
    )
    ratio = alpha_e * (t_wall / temperature_K) + (1.0 - alpha_e) * (incident_share * speed_ratio**2)
    ones = np.ones_like(ratio)
    return Reemission(
        speed_ratio=speed_ratio,
        pressure_scale=ones,
        shear_scale=ones,
        diffuse_share=ones,
        temperature_ratio=ratio,
        emission_share=ones,
        emission_temperature_K=temperature_K * ratio,
        wall_weight=alpha_e,
        energy_weight=(1.0 - alpha_e) * incident_share,
    )


def _checked(speed_ratio: float, temperature_K: float, **parameters: ArrayLike) -> list[NDArray[np.float64]]:
    """The parameters as float64 arrays broadcast to one 1-D shape, checked: accommodations in [0, 1],
    ``wall_temperature_K`` finite and >= 0; the speed ratio and temperature finite and > 0."""
    check_speed_ratio(speed_ratio)
    _check_temperature(temperature_K)
    arrays = [
        np.ravel(a)
        for a in np.broadcast_arrays(*(np.asarray(v, dtype=np.float64) for v in parameters.values()))
    ]
    for name, values in zip(parameters, arrays, strict=True):
        if name == "wall_temperature_K":
            if not np.all(np.isfinite(values) & (values >= 0.0)):
                raise InputError("wall_temperature_K must be finite and >= 0 K", parameters=(name,))
        elif not np.all((values >= 0.0) & (values <= 1.0)):
            raise InputError(
                f"{name} outside [0, 1]", hint="accommodation coefficients lie in [0, 1]", parameters=(name,)
            )
    return arrays


def _check_temperature(temperature_K: float) -> None:
    if not (math.isfinite(temperature_K) and temperature_K > 0.0):
        raise InputError(
            f"temperature_K {temperature_K!r} must be a finite number > 0", parameters=("temperature_K",)
        )


def _cosines(cos_incidence: ArrayLike, n: int) -> NDArray[np.float64]:
    """``gamma`` as finite float64 (m,) in [-1, 1], m = n or n broadcast to it."""
    gamma = np.atleast_1d(np.asarray(cos_incidence, dtype=np.float64)).reshape(-1)
    if not np.all(np.isfinite(gamma)):
        raise InputError("cos_incidence has non-finite values", parameters=("cos_incidence",))
    if len(gamma) != n and n != 1:
        raise InputError(
            f"cos_incidence has {len(gamma)} values for {n} elements", parameters=("cos_incidence",)
        )
    return np.clip(gamma, -1.0, 1.0)
