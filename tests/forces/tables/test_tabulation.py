"""Every setup the sweep engine runs is a Tabulation: the protocol Job.setup is typed with."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from sunwind.forces.gas import explicit
from sunwind.forces.orbit import OrbitLoads
from sunwind.forces.tables.earth_setup import EarthSetup
from sunwind.forces.tables.jobs import DragSetup, Job, PosedSetup, SrpSetup, Tabulation

AIR = explicit(1e-12, 900.0, "O:1")
SETUPS = {
    "srp": SrpSetup(),
    "drag": DragSetup(speed_m_s=7600.0, atmosphere=AIR),
    "posed": PosedSetup(SrpSetup(), (("wing_*", 30.0),), 0),
    "earth": EarthSetup(altitude_km=500.0, sun_vector=(1.0, 0.0, 0.0)),
    "orbit": OrbitLoads(SrpSetup()),
}


@pytest.mark.parametrize("name", SETUPS)
def test_each_setup_the_engine_runs_is_a_tabulation(name):
    setup = SETUPS[name]
    assert isinstance(setup, Tabulation)
    assert isinstance(setup.kind, str) and all(w >= 1 for w in setup.fields.values())
    assert isinstance(setup.describe(), dict)
    assert pickle.loads(pickle.dumps(setup)).kind == setup.kind  # Dask sends it to workers


def test_a_job_carries_its_inputs_by_that_name():
    job = Job(SETUPS["srp"], np.eye(3))
    assert job.inputs.shape == (3, 3) and not hasattr(job, "directions")
    assert not isinstance(object(), Tabulation)
