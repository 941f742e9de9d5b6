"""Fly Basilisk's ``RadiationPressure`` effector in lookup-table mode through given states.

:func:`basilisk_srp` answers what Basilisk itself computes from a lookup XML (such as
``sunwind sweep --format basilisk`` writes) for a sequence of positions, Sun positions and attitudes, so a
test can hold sunwind's orbit mode against it. Basilisk is imported inside the function only: this module
imports without it, and a test that calls the function starts with ``pytest.importorskip("Basilisk")``.

How Basilisk is driven. No simulation, spacecraft or integrator is built: the effector reads its inputs
from two ``StateData`` objects and one message, which are made stand-alone. A ``DynParamManager`` (the class
the spacecraft hub registers its states in) gets a 3x1 ``hubPosition`` (r_BN_N) and a 3x1 ``hubSigma``
(sigma_BN); the effector is given those state names (a ``Spacecraft`` would do so in
``addDynamicEffector``) and linked with ``linkInStates``. The Sun's ``SpicePlanetStateMsg`` is subscribed to
``sunEphmInMsg``; no ``sunEclipseInMsg`` is linked, so the illumination factor stays at the constructor's
1.0 (fully lit). Per state: write the two states and the Sun message, ``UpdateState`` (reads the message,
sets ``stateRead``), ``computeForceTorque``, then read ``forceExternal_B`` and ``torqueExternalPntB_B``.
The table is loaded as Basilisk's unit test does: ``SRPLookupTableHandler().parseAndLoadXML`` (the python
of ``parseSRPLookup.py``, appended to the ``Basilisk.simulation.radiationPressure`` module by SWIG), then
``addSHatLookupBEntry`` / ``addForceLookupBEntry`` / ``addTorqueLookupBEntry`` row by row, after
``setUseFacetedCPUModel()``.

What Basilisk computes (``RadiationPressure::computeForceTorque`` and ``computeLookupModel``):

- ``s_N = r_Sun_N - r_BN_N``; ``dcm_BN`` from the MRP state (``sigma.toRotationMatrix().transpose()``);
  ``s_B = dcm_BN s_N``; ``sHat_B = s_B / |s_B|`` (normalised; the table's ``sHat_B`` are used as stored);
- nearest entry: the first index with the largest ``lookupSHat_B[i] . sHat_B``. The search starts from
  index 0 with a best dot product of 0 and needs a strictly larger one, so ties go to the lower index and,
  if no entry has a positive dot product, entry 0 is returned;
- ``force_B = lookupForce_B[i] (AU / |s_B|)^2``, ``torque_B = lookupTorque_B[i] (AU / |s_B|)^2`` with
  ``AU`` = 149597870.693 km (``astroConstants.h``; :data:`BASILISK_AU_M` here), the distance being the
  spacecraft-to-Sun one; both then times the eclipse illumination factor (1 here);
- the torque is the table's, unchanged: about the body-frame origin B (``torqueExternalPntB_B``); no
  centre-of-mass shift is applied. ``forceExternal_N`` stays zero in this mode.

Basilisk sources read (AVSLab/basilisk, as installed as ``bsk`` 2.12.1 and on GitHub):
``src/simulation/dynamics/RadiationPressure/radiationPressure.cpp``, ``radiationPressure.h``,
``radiationPressure.i``, ``parseSRPLookup.py``, ``_UnitTest/test_radiationPressure.py``;
``src/simulation/dynamics/_GeneralModuleFiles/dynamicEffector.h``;
``src/architecture/utilities/astroConstants.h``.

Quirk of bsk 2.12.1: ``linkInStates`` raises "Did not find a valid sun ephemeris message connection" unless
``sunEphmInMsg`` is already subscribed, so the message is linked first.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

#: Basilisk's astronomical unit [m]: ``AU`` = 149597870.693 km in ``astroConstants.h`` (times 1000 in
#: ``computeLookupModel``). Not the IAU 2012 value 149597870700 m.
BASILISK_AU_M = 149597870693.0

_POSITION = "hubPosition"
_SIGMA = "hubSigma"


def basilisk_srp(
    lookup_xml: str | Path,
    position_eci_m: NDArray,
    sun_eci_m: NDArray,
    body_to_eci: NDArray,
) -> tuple[NDArray, NDArray]:
    """SRP force and torque Basilisk's lookup-table ``RadiationPressure`` gives at each state, fully lit.

    Parameters
    ----------
    lookup_xml
        Basilisk SRP lookup table (``sHatBValues``, ``forceBValues``, ``torqueBValues``).
    position_eci_m
        (n, 3) spacecraft position r_BN_N in the inertial frame N [m].
    sun_eci_m
        (n, 3) Sun position in N [m], same origin as ``position_eci_m``.
    body_to_eci
        (n, 3, 3) rotations R with v_N = R v_B (Basilisk's [NB]; its dcm_BN is R^T).

    Returns
    -------
    tuple of NDArray
        force_B [N] and torque_B [N m] about the body origin B, each (n, 3), in the body frame.

    Raises
    ------
    ValueError
        Shapes disagree, or a matrix is not a proper rotation.
    """
    from Basilisk.architecture import messaging
    from Basilisk.simulation import radiationPressure
    from Basilisk.utilities import RigidBodyKinematics

    position = np.asarray(position_eci_m, dtype=np.float64).reshape(-1, 3)
    sun = np.asarray(sun_eci_m, dtype=np.float64).reshape(-1, 3)
    rotation = np.asarray(body_to_eci, dtype=np.float64).reshape(-1, 3, 3)
    n = len(position)
    if len(sun) != n or len(rotation) != n:
        raise ValueError(f"{n} positions, {len(sun)} Sun positions and {len(rotation)} rotations differ")
    gram = np.einsum("nji,njk->nik", rotation, rotation)
    if not (np.allclose(gram, np.eye(3), atol=1e-9) and np.allclose(np.linalg.det(rotation), 1.0, atol=1e-9)):
        raise ValueError("body_to_eci holds a matrix that is not a proper rotation")

    handler = radiationPressure.SRPLookupTableHandler()
    handler.parseAndLoadXML(str(lookup_xml))
    srp = radiationPressure.RadiationPressure()
    srp.ModelTag = "sunwindLookupSRP"
    srp.setUseFacetedCPUModel()
    for s_hat, force, torque in zip(
        handler.sHatBLookup, handler.forceBLookup, handler.torqueBLookup, strict=True
    ):
        srp.addSHatLookupBEntry(s_hat.tolist())
        srp.addForceLookupBEntry(force.tolist())
        srp.addTorqueLookupBEntry(torque.tolist())

    # Every object the effector points into (message, states, their manager) stays referenced here
    # until the loop ends.
    sun_payload = messaging.SpicePlanetStateMsgPayload()
    sun_msg = messaging.SpicePlanetStateMsg().write(sun_payload)
    srp.sunEphmInMsg.subscribeTo(sun_msg)
    states = radiationPressure.DynParamManager()
    position_state = states.registerState(3, 1, _POSITION)
    sigma_state = states.registerState(3, 1, _SIGMA)
    srp.setStateNameOfPosition(_POSITION)
    srp.setStateNameOfSigma(_SIGMA)
    srp.linkInStates(states)
    srp.Reset(0)

    force_b = np.empty((n, 3))
    torque_b = np.empty((n, 3))
    for k in range(n):
        sigma_bn = RigidBodyKinematics.C2MRP(rotation[k].T)
        position_state.setState([[value] for value in position[k].tolist()])
        sigma_state.setState([[float(value)] for value in sigma_bn])
        sun_payload.PositionVector = sun[k].tolist()
        sun_msg.write(sun_payload)
        srp.UpdateState(0)
        srp.computeForceTorque(0.0, 0.0)
        force_b[k] = np.asarray(srp.forceExternal_B, dtype=np.float64).ravel()
        torque_b[k] = np.asarray(srp.torqueExternalPntB_B, dtype=np.float64).ravel()
    return force_b, torque_b
