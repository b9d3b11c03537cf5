"""A result whose complex-conjugate power bound does not exist (two PTOs on one joint: the Hermitian part of the PTO
admittance is singular) still stands: the run's own numbers are kept and the notes say why the bound is missing."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np

from wecss.sim import Scene, simulate

FLOAT = Path(__file__).parents[1] / "control" / "heaving_float.toml"


def test_a_singular_power_bound_is_noted_not_fatal(tmp_path):
    text = FLOAT.read_text() + '\n[[ptos]]\nname = "pto_2"\nkind = "joint"\njoint = "slider"\n'
    assert len(tomllib.loads(text)["ptos"]) == 2
    path = tmp_path / "two-ptos.toml"
    path.write_text(text)
    ds = simulate(
        Scene.from_dict(
            {
                "device": {"name": str(path)},
                "sea": {"kind": "regular", "height": 0.02, "period": 1.2, "duration": 12.0, "ramp": 2.0},
                "controller": {"name": "damping", "parameters": {"damping": 40.0}},
                "radiation": {"method": "convolution"},
                "outputs": {"variables": ["pto"]},
            }
        )
    )
    assert "no complex-conjugate power bound" in ds.attrs["notes"]
    assert "power_bound" not in ds
    assert np.all(ds.mean_pto_power.values > 0)  # the run's own result is there
