"""Force-velocity curves: each point a steady state under a load inside (-mu, mu) M g."""

from __future__ import annotations

import json
import math

import numpy as np

import sawdrift as sd
from sawdrift.study.force_velocity import force_velocity


def test_a_still_substrate_holds_every_load_below_friction_at_rest():
    """Material point, no wave: any |L| < mu is held by static friction (v = 0, stick): the curve
    is the vertical segment of Coulomb's law."""
    scene = sd.Scene(model="material_point", particle={"m_star": 0.1}, material={"mu": 0.2},
                     drive={"amplitude": 0.0})
    curve = force_velocity(scene, points=5, workers=1)
    assert np.allclose(curve.forces, 0.2 * np.array([-2, -1, 0, 1, 2]) / 3.0, atol=1e-15)
    assert np.all(curve.velocities == 0.0)
    assert set(curve.regimes) == {"stick"}


def test_the_steady_speed_grows_with_the_load_and_the_zero_is_the_free_drift():
    """mmd, m* = 0.1, A* = 0.316, mu = 0.1: a steady state is stable only where the mean friction
    grows with the speed, so the sampled speeds increase with the load; the zero crossing,
    interpolated between the two loads around it (without the unloaded run), is within 5 % of
    the free drift 0.479 a0 f."""
    scene = sd.Scene(model="mmd", particle={"m_star": 0.1}, material={"mu": 0.1},
                     drive={"amplitude": 0.316})
    curve = force_velocity(scene, points=8, workers=1)
    v = curve.velocities
    assert np.all(np.isfinite(v)) and np.all(np.diff(v) > 0.0)
    loaded = curve.forces != 0.0
    f, vv = curve.forces[loaded], v[loaded]
    i = int(np.nonzero(f > 0.0)[0][0])
    zero = vv[i - 1] - f[i - 1] * (vv[i] - vv[i - 1]) / (f[i] - f[i - 1])
    assert abs(zero - curve.free_drift) <= 0.05 * abs(curve.free_drift), (zero, curve.free_drift)
    assert abs(curve.free_drift - sd.run(scene).drift_velocity) == 0.0


def test_the_command_writes_the_curve_and_refuses_too_few_points(tmp_path, sawdrift_main):
    out = tmp_path / "fv"
    cmd = ["force-velocity", "--model", "material_point",
           "--m-star", "0.1", "--amplitude", "0", "--points", "3", "--workers", "1", "--json",
           "-o", str(out)]
    done = sawdrift_main(*cmd)  # in this process (tests/conftest.py)
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    assert len(data["force"]) == 3 and all(v == 0.0 for v in data["drift_velocity"])
    assert (out / "force_velocity.png").is_file() and (out / "force_velocity.json").is_file()
    bad = sawdrift_main(*cmd[:-7], "--points", "2")  # refused before any run
    assert bad.returncode == 2 and "at least 3" in bad.stderr and "Traceback" not in bad.stderr
    assert math.isfinite(data["mu"])


def test_the_command_refuses_a_load_it_would_replace(sawdrift_main):
    """The curve samples its own loads: a --load given to it used to be ignored without a word
    (the same curve as without it); it is refused in one line, before any run."""
    bad = sawdrift_main("force-velocity", "--model", "mmd", "--m-star", "1", "--load", "0.2")
    assert bad.returncode == 2 and "particle.load = 0.2" in bad.stderr
    assert "Traceback" not in bad.stderr and bad.stdout == ""
