"""Gas-surface kernels of the TPMC tracer: Maxwell and Cercignani-Lampis-Lord re-emission.

:class:`WallInteraction` names the kernel of a model's sides and holds its parameters, scalar or one
per side; :func:`maxwell_reemission` and :func:`cll_reemission` sample the re-emitted velocities for
:mod:`sunwind.validation.tpmc`. Like the tracer, the module imports nothing from ``forces``.

Notes
-----
**Maxwell kernel** (default). With probability ``diffuse_fraction`` of the struck side the molecule
is re-emitted diffusely, else specularly (``v_out = v_in - 2 (v_in . n) n``). Diffuse re-emission is
the flux-weighted half-range Maxwellian at rest at the temperature ``T_r`` about the side's outward
normal ``n`` (a cosine-law direction and a speed ``~ c^3 exp(-c^2 / c_r^2)``): normal component
``c_r sqrt(-ln U)``, tangential components ``c_r / sqrt(2) N(0, 1)``, ``c_r = sqrt(2 k T_r / m)``.
Energy accommodation is applied **per molecule**: a Maxwellian flux at ``T_r`` carries ``2 k T_r`` of
kinetic energy per molecule (the 2kT energy balance, ``dria`` in the solver; Sentman's own is 3/2 kT), so a
molecule arriving with ``E_in = m |v_in|^2 / 2`` is re-emitted at

    T_r = alpha_E T_w + (1 - alpha_E) E_in / (2 k),

and on average leaves with ``alpha_E 2 k T_w + (1 - alpha_E) E_in``. ``alpha_E = 1`` (default) is
full accommodation at the wall temperature ``T_w``. This is not quite the closed-form Sentman model
with ``alpha_E < 1``, which sets one ``T_r`` for a whole surface element from its *mean* incident
energy flux: the mean re-emission speed ``~ E[sqrt(T_r)]`` differs from ``sqrt(E[T_r])`` by the
spread of the incident energies (small at high ``S``).

**CLL kernel** (``kernel="cll"``; Cercignani-Lampis-Lord, sampled by Lord's algorithm, Lord 1991).
With ``c_w = sqrt(2 k T_w / m)``, the normal accommodation ``alpha_n`` and the tangential momentum
accommodation ``sigma_t`` (tangential energy accommodation ``alpha_t = sigma_t (2 - sigma_t)``), the
incident normal speed ``u_i = -v_in . n / c_w`` and tangential velocity ``v_t`` (direction ``t1``,
``t2 = n x t1``)::

    r = sqrt(-alpha_n ln U1),  th = 2 pi U2,  u_m = sqrt(1 - alpha_n) u_i,
    u_n = sqrt(r^2 + u_m^2 + 2 r u_m cos th)
    r = sqrt(-alpha_t ln U3),  th = 2 pi U4,
    u_t1 = (1 - sigma_t) |v_t| / c_w + r cos th,   u_t2 = r sin th
    v_out = c_w (u_n n + u_t1 t1 + u_t2 t2).

``alpha_n = sigma_t = 1`` is diffuse re-emission at ``T_w``, ``alpha_n = sigma_t = 0`` specular; the
mean tangential momentum out is exactly ``(1 - sigma_t)`` of the incident one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["KERNELS", "WallInteraction", "cll_reemission", "maxwell_reemission"]

#: Gas-surface kernels :class:`WallInteraction` offers.
KERNELS = ("maxwell", "cll")


@dataclass(frozen=True, eq=False, kw_only=True)
class WallInteraction:
    """The gas-surface kernel of a model's sides and its parameters, each a scalar or one per side.

    Attributes
    ----------
    diffuse_fraction : float or (n_sides,) array_like, or None
        Maxwell kernel: share of molecules each side re-emits diffusely [-], in [0, 1]; the rest are
        reflected specularly. Must be None for ``kernel="cll"``.
    wall_temperature_K : float or (n_sides,) array_like
        Wall temperature ``T_w`` of each side [K], > 0.
    energy_accommodation : float or (n_sides,) array_like
        Maxwell kernel: ``alpha_E`` [-] of the diffuse re-emission, in [0, 1], applied per molecule
        with 2 k T_r per re-emitted molecule (module Notes); default 1 (re-emission at ``T_w``).
    kernel : {"maxwell", "cll"}
        Gas-surface interaction kernel (module Notes).
    normal_accommodation, tangential_accommodation : float or (n_sides,) array_like, optional
        CLL kernel only (then required): normal energy accommodation ``alpha_n`` and tangential
        momentum accommodation ``sigma_t`` of each side [-], in [0, 1].

    Examples
    --------
    >>> walls = WallInteraction(diffuse_fraction=[1.0, 0.5], wall_temperature_K=300.0)
    >>> walls.per_side(2)["diffuse_fraction"].tolist()
    [1.0, 0.5]
    """

    diffuse_fraction: ArrayLike | None
    wall_temperature_K: ArrayLike
    energy_accommodation: ArrayLike = 1.0
    kernel: str = "maxwell"
    normal_accommodation: ArrayLike | None = None
    tangential_accommodation: ArrayLike | None = None

    def per_side(self, n_sides: int) -> dict[str, NDArray[np.float64]]:
        """The kernel's parameters as checked (n_sides,) float64 arrays, by name.

        Raises
        ------
        ValueError
            Unknown kernel, a parameter of the other kernel given, a required one missing, or a value
            out of range or of the wrong length.
        """
        if self.kernel not in KERNELS:
            raise ValueError(f"kernel must be one of {KERNELS}, not {self.kernel!r}")
        arrays = {
            "wall_temperature": _per_side(
                "wall_temperature_K", self.wall_temperature_K, n_sides, 1e-300, np.inf
            )
        }
        diffuse, normal, tangential = (
            self.diffuse_fraction,
            self.normal_accommodation,
            self.tangential_accommodation,
        )
        if self.kernel == "maxwell":
            if diffuse is None or normal is not None or tangential is not None:
                raise ValueError("the Maxwell kernel takes diffuse_fraction (and energy_accommodation) only")
            arrays["diffuse_fraction"] = _per_side("diffuse_fraction", diffuse, n_sides, 0.0, 1.0)
            arrays["energy_accommodation"] = _per_side(
                "energy_accommodation", self.energy_accommodation, n_sides, 0.0, 1.0
            )
            return arrays
        if diffuse is not None or normal is None or tangential is None:
            raise ValueError(
                "the CLL kernel takes normal_accommodation and tangential_accommodation, "
                "and diffuse_fraction=None"
            )
        if np.any(np.asarray(self.energy_accommodation) != 1.0):
            raise ValueError("energy_accommodation is for the Maxwell kernel; CLL uses normal_accommodation")
        arrays["normal_accommodation"] = _per_side("normal_accommodation", normal, n_sides, 0, 1)
        arrays["tangential_accommodation"] = _per_side(
            "tangential_accommodation", tangential, n_sides, 0.0, 1.0
        )
        return arrays


def _basis(normals: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Two unit tangents completing each unit normal (n, 3) to a right-handed orthonormal frame.

    Duff et al. (2017), "Building an orthonormal basis, revisited".
    """
    x, y, z = normals.T
    sign = np.where(z >= 0.0, 1.0, -1.0)
    a = -1.0 / (sign + z)
    b = x * y * a
    t1 = np.column_stack([1.0 + sign * x * x * a, sign * b, -sign * x])
    t2 = np.column_stack([b, sign + y * y * a, -y])
    return t1, t2


def _dot(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.einsum("ij,ij->i", a, b)


def _per_side(name: str, value: ArrayLike, n_sides: int, low: float, high: float) -> NDArray[np.float64]:
    """``value`` (scalar or (n_sides,)) as a (n_sides,) float64 array, checked to lie in [low, high]."""
    array = np.asarray(value, dtype=np.float64)
    if array.ndim == 0:
        array = np.full(n_sides, float(array))
    if array.shape != (n_sides,):
        raise ValueError(f"{name} must be a scalar or have one value per side ({n_sides}), not {array.shape}")
    if not np.all(np.isfinite(array)) or np.any(array < low) or np.any(array > high):
        raise ValueError(f"{name} must lie in [{low}, {high}]")
    return array


def maxwell_reemission(
    v_in: NDArray[np.float64],
    normals: NDArray[np.float64],
    diffuse_fraction: NDArray[np.float64],
    wall_c2: NDArray[np.float64],
    energy_accommodation: NDArray[np.float64],
    rng: np.random.Generator,
) -> NDArray[np.float64]:
    """Maxwell kernel: velocities [m/s] of molecules re-emitted by walls (module Notes).

    Parameters
    ----------
    v_in : (k, 3) float64
        Incident velocities [m/s], toward the walls (``v_in . normals < 0``).
    normals : (k, 3) float64
        Outward unit normals of the struck sides.
    diffuse_fraction : (k,) float64
        Probability of diffuse re-emission [-]; else specular reflection.
    wall_c2 : (k,) float64
        ``c_w^2 = 2 k T_w / m`` [m^2/s^2].
    energy_accommodation : (k,) float64
        ``alpha_E`` [-]: diffuse re-emission at ``c_r^2 = alpha_E c_w^2 + (1 - alpha_E) |v_in|^2 / 2``,
        i.e. ``T_r = alpha_E T_w + (1 - alpha_E) E_in / (2 k)``.
    rng : numpy.random.Generator

    Returns
    -------
    (k, 3) float64

    Examples
    --------
    With no diffuse share the molecule is reflected specularly:

    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> v_in, normal = np.array([[0.0, 0.0, -7000.0]]), np.array([[0.0, 0.0, 1.0]])
    >>> maxwell_reemission(v_in, normal, np.array([0.0]), np.array([1e5]), np.array([1.0]), rng).tolist()
    [[0.0, 0.0, 7000.0]]

    References
    ----------
    .. [1] J. C. Maxwell, "On stresses in rarified gases arising from inequalities of temperature",
       Philosophical Transactions of the Royal Society of London 170, 231-256, 1879.
    """
    k = len(v_in)
    vn = _dot(v_in, normals)
    out = v_in - 2.0 * vn[:, None] * normals
    diffuse = rng.random(k) < diffuse_fraction
    alpha = energy_accommodation
    c_r = np.sqrt(alpha * wall_c2 + (1.0 - alpha) * 0.5 * _dot(v_in, v_in))
    t1, t2 = _basis(normals)
    normal = np.sqrt(-np.log1p(-rng.random(k)))
    tangent = rng.standard_normal((k, 2)) / math.sqrt(2.0)
    emitted = c_r[:, None] * (normal[:, None] * normals + tangent[:, :1] * t1 + tangent[:, 1:] * t2)
    out[diffuse] = emitted[diffuse]
    return out


def cll_reemission(
    v_in: NDArray[np.float64],
    normals: NDArray[np.float64],
    wall_c2: NDArray[np.float64],
    normal_accommodation: NDArray[np.float64],
    tangential_accommodation: NDArray[np.float64],
    rng: np.random.Generator,
) -> NDArray[np.float64]:
    """Cercignani-Lampis-Lord kernel by Lord's algorithm: re-emitted velocities [m/s] (module Notes).

    Parameters
    ----------
    v_in : (k, 3) float64
        Incident velocities [m/s], toward the walls (``v_in . normals < 0``).
    normals : (k, 3) float64
        Outward unit normals of the struck sides.
    wall_c2 : (k,) float64
        ``c_w^2 = 2 k T_w / m`` [m^2/s^2].
    normal_accommodation : (k,) float64
        ``alpha_n`` [-], normal kinetic-energy accommodation.
    tangential_accommodation : (k,) float64
        ``sigma_t`` [-], tangential momentum accommodation (energy: ``sigma_t (2 - sigma_t)``).
    rng : numpy.random.Generator

    Returns
    -------
    (k, 3) float64

    Examples
    --------
    With no accommodation at all (``alpha_n = sigma_t = 0``) the kernel is specular reflection:

    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> v_in, normal = np.array([[0.0, 0.0, -7000.0]]), np.array([[0.0, 0.0, 1.0]])
    >>> cll_reemission(v_in, normal, np.array([1e5]), np.array([0.0]), np.array([0.0]), rng).tolist()
    [[0.0, 0.0, 7000.0]]

    References
    ----------
    .. [1] C. Cercignani and M. Lampis, "Kinetic models for gas-surface interactions", Transport
       Theory and Statistical Physics 1, 101-114, 1971.
    .. [2] R. G. Lord, "Some extensions to the Cercignani-Lampis gas-surface scattering kernel",
       Physics of Fluids A 3, 706-710, 1991.
    """
    k = len(v_in)
    c_w = np.sqrt(wall_c2)
    alpha_n, sigma_t = normal_accommodation, tangential_accommodation
    alpha_t = sigma_t * (2.0 - sigma_t)
    vn = _dot(v_in, normals)
    r = np.sqrt(-alpha_n * np.log1p(-rng.random(k)))
    theta = 2.0 * math.pi * rng.random(k)
    u_m = np.sqrt(1.0 - alpha_n) * (-vn / c_w)
    u_n = np.sqrt(np.maximum(r * r + u_m * u_m + 2.0 * r * u_m * np.cos(theta), 0.0))
    vt = v_in - vn[:, None] * normals
    vt_norm = np.linalg.norm(vt, axis=1)
    along = vt_norm > 0.0
    e1 = np.where(along[:, None], vt / np.where(along, vt_norm, 1.0)[:, None], _basis(normals)[0])
    e2 = np.cross(normals, e1)
    r = np.sqrt(-alpha_t * np.log1p(-rng.random(k)))
    theta = 2.0 * math.pi * rng.random(k)
    u_t1 = (1.0 - sigma_t) * vt_norm / c_w + r * np.cos(theta)
    u_t2 = r * np.sin(theta)
    return c_w[:, None] * (u_n[:, None] * normals + u_t1[:, None] * e1 + u_t2[:, None] * e2)
