"""LAMMPS pair granular jkr + mindlin_rescale/force in the wall frame against the native adhesive
DEM on the silica example: drift within 1 %, removal amplitude within 1 %."""

from __future__ import annotations

from pathlib import Path

import pytest

from sawdrift.lammps import available
from sawdrift.lammps.adhesion import compare, contact_string
from sawdrift.lammps.realize import realize
from sawdrift.scene.schema import Scene

HAVE_LAMMPS, WHY = available()
needs_lammps = pytest.mark.skipif(not HAVE_LAMMPS, reason=f"LAMMPS not installed: {WHY}")
EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "micro_silica_on_linbo3.toml"
#: the native removal amplitude of 60-period runs, located by bisection to 0.1 %
#: (validation/g14c_lammps_adhesion.py: native 0.1639 nm, LAMMPS 0.1646 nm)
NATIVE_REMOVAL = 0.1639e-9


def test_cohesion_is_half_the_work_of_adhesion():
    scene = Scene.from_toml(EXAMPLE)
    words = contact_string(scene, realize(scene, wall_frame=True)).split()
    assert words[0] == "jkr" and float(words[4]) == pytest.approx(0.025, rel=1e-9)


@needs_lammps
@pytest.mark.slow
def test_lammps_drift_and_removal_match_the_native_dem():
    base = Scene.from_toml(EXAMPLE)
    held = compare(base, periods=60)  # 0.01 nm
    assert not held["removed_lammps"] and not held["removed_native"]
    assert held["drift_lammps"] == pytest.approx(held["drift_native"], rel=0.01)
    for ratio, removed in ((0.99, False), (1.01, True)):
        got = compare(base.with_updates(**{"device.amplitude": ratio * NATIVE_REMOVAL}), periods=60)
        assert got["removed_lammps"] is removed and got["removed_native"] is removed, ratio
