"""The sum kernel of the direct pass, side by side and from block moments, against its numpy twin."""

import numpy as np
import pytest

from sunwind.forces.radiation.law import surface_forces
from sunwind.forces.radiation.moments import TOTALS, accumulate_forces, block_moments, weight_moments
from sunwind.geometry.rays.shadow_kernels import BLOCK


def _direct_sums_twin(u, spread, shares, flags, weighted):
    """The kernel's block sums and the numpy sums of eq. (4) over the same random sides.

    Normals of even blocks lie within ``spread`` of ``u`` (1 or more: any direction); each side is
    dark, wholly lit or lit in part with the probabilities ``shares``, a part-lit side's force acting
    at a point off its centroid. Blocks are runs of ``BLOCK`` sides, as the sampler's. With
    ``flags`` (and no part-lit side) the kernel gets lit flags instead of shares. ``weighted``: two
    random weights per side are summed with the lit projected area, as inter-reflection's channels are.
    """
    rng = np.random.default_rng(5)
    n_blocks = 10
    n = n_blocks * BLOCK - 7  # the last block is short, as the sampler's may be
    block = np.arange(n) // BLOCK
    # odd blocks take any direction, so blocks summed side by side come between the others
    normals = rng.normal(size=(n, 3)) + u / np.where(block % 2 == 0, spread, 10.0)[:, None]
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    state = rng.choice(3, size=n, p=shares)
    fraction = np.select([state == 0, state == 1], [0.0, 1.0], rng.random(n))
    areas, centroids = rng.random(n), rng.normal(size=(n, 3))
    lit_centroid = np.where((state == 2)[:, None], centroids + 0.1 * rng.normal(size=(n, 3)), centroids)
    material = rng.integers(0, 3, n)
    rho, beta, sigma = np.array([0.1, 0.6, 0.9]), np.array([0.0, 0.5, 1.0]), np.array([0.0, 0.1, 0.05])
    optics = np.stack([rho[material], beta[material], sigma[material]], axis=1)
    cos = normals @ u
    facing = np.flatnonzero(cos > 0)
    ref = np.array([0.1, 0.2, -0.3])
    low = np.array([normals[block == b].min(axis=0) for b in range(n_blocks)])
    high = np.array([normals[block == b].max(axis=0) for b in range(n_blocks)])
    moments = block_moments(normals, areas, optics, centroids, block, n_blocks)
    weights = rng.normal(size=(n, 2 if weighted else 0))
    partials = np.zeros((n_blocks, TOTALS + weights.shape[1]))
    accumulate_forces(
        facing,
        fraction[facing] > 0 if flags else fraction[facing],
        lit_centroid,
        centroids,
        normals,
        areas,
        optics,
        u,
        ref,
        block,
        low,
        high,
        moments,
        weights if weighted else None,
        weight_moments(weights, normals, areas, block, n_blocks) if weighted else None,
        partials,
    )
    lit = facing[fraction[facing] > 0]
    m = material[lit]
    lit_area = areas[lit] * fraction[lit]
    forces = surface_forces(normals[lit], lit_area, cos[lit], rho[m], beta[m], sigma[m], u, 1.0)
    twin = np.concatenate(
        [
            forces.sum(axis=0),
            np.cross(lit_centroid[lit] - ref, forces).sum(axis=0),
            [
                lit_area.sum(),
                (lit_area * cos[lit]).sum(),
                (lit_area * cos[lit] * (1 - rho[m] - sigma[m])).sum(),
            ],
            (lit_area * cos[lit]) @ weights[lit],
        ]
    )
    whole = np.minimum(low * u, high * u).sum(axis=1) > 0
    return partials.sum(axis=0), twin, whole


@pytest.mark.parametrize(
    "spread, shares, flags",
    [
        (10.0, (0.3, 0.4, 0.3), False),
        (0.2, (0.3, 0.4, 0.3), False),
        (0.2, (0.0, 1.0, 0.0), False),
        (0.2, (0.8, 0.1, 0.1), False),
        (0.2, (0.4, 0.6, 0.0), True),
    ],
    ids=["any-normals", "whole-blocks-mixed-light", "whole-blocks-all-lit", "whole-blocks-dark", "flags"],
)
@pytest.mark.parametrize("weighted", [False, True], ids=["", "weighted"])
def test_direct_sums_equal_their_numpy_twin(spread, shares, flags, weighted):
    """Side by side, and from block moments with corrections for sides not wholly lit: the same sums
    to round-off (1e-12 of the largest total of each kind)."""
    u = np.array([0.2, -0.5, 0.84])
    u /= np.linalg.norm(u)
    totals, twin, whole = _direct_sums_twin(u, spread, shares, flags, weighted)
    assert whole.any() == (spread < 1)  # the moment path is taken where it should be
    assert len(totals) == len(twin) == TOTALS + (2 if weighted else 0)
    for kind in (slice(0, 3), slice(3, 6), slice(6, 9), slice(9, 10), slice(10, 11))[: len(twin) - 6]:
        scale = np.abs(twin[kind]).max()
        assert np.allclose(totals[kind], twin[kind], rtol=0, atol=1e-12 * scale)
