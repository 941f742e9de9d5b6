"""The default shadow pass on the CAD corpus (meshes.cad_corpus) against the z-buffer reference
(validation.shadow_reference, through validation.shadow_pass_check): within 2e-4 of the force and 1e-3
of the torque scale at Sun directions over the sphere and grazing ones, and its certificate's estimate
covering the error it makes wherever that error shows above the reference's noise."""

import pytest

from sunwind.geometry.rays.shadows import DEFAULT_TOLERANCE
from sunwind.geometry.spacecraft import build_spacecraft
from sunwind.meshes.cad_corpus import corpus
from sunwind.validation.shadow_pass_check import GREY, check_directions, compare_pass

#: Pixel of the reference [m]: its noise (``ERROR_SIGMAS`` standard errors) is added to each tolerance.
PIXEL_M = 0.002
FORCE, TORQUE = 2e-4, 1e-3


@pytest.mark.slow
@pytest.mark.parametrize("entry", corpus(), ids=lambda entry: entry.name)
def test_the_default_pass_is_exact_on_cad_exports_and_knows_its_error(entry):
    craft = build_spacecraft(entry.mesh, uniform=GREY, two_sided=entry.two_sided)
    for row in compare_pass(craft, check_directions(4), PIXEL_M):
        assert row.covered, row
        if max(row.force_estimate, row.torque_estimate) > DEFAULT_TOLERANCE:
            continue  # a result that says it is off by more than the tolerance, with a warning
        assert row.force_error <= FORCE + row.force_noise, row
        assert row.torque_error <= TORQUE + row.torque_noise, row
