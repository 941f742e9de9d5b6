"""Monte Carlo sampling settings shared by the photon and molecule tracers."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Sampling"]


@dataclass(frozen=True)
class Sampling:
    """How a Monte Carlo tracer samples: particles launched, random seed, batches and bounce cap.

    Attributes
    ----------
    particles : int
        Photon bundles or molecules to launch in all; rounded up to a multiple of ``batches``.
    seed : int
        Seed of the random streams; the same seed gives the same result.
    batches : int
        Independent batches the standard errors come from (>= 2).
    max_bounces : int
        Most wall interactions a particle may have (>= 1); the tracer reports what it stopped.

    Examples
    --------
    >>> Sampling(10_000, seed=3)
    Sampling(particles=10000, seed=3, batches=20, max_bounces=100)
    """

    particles: int
    seed: int = 0
    batches: int = 20
    max_bounces: int = 100
