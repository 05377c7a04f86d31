"""Force-velocity curves: each point a steady state under a load inside (-mu, mu) M g."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

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


def test_load_curve_refuses_a_load_and_an_incline_is_no_load(sawdrift_main):
    # load-curve ignored a --load without a word; force-velocity refused a device on an incline
    # (whose pull, particle.load -1.9e-4, is part of every force of the curve) as a given load
    from pathlib import Path

    motor = str(Path(__file__).resolve().parents[1] / "examples" / "saw_linear_motor.toml")
    bad = sawdrift_main("load-curve", "--model", "mmd", "--m-star", "1", "--load", "0.2")
    assert bad.returncode == 2 and "particle.load = 0.2" in bad.stderr and bad.stdout == ""
    bad = sawdrift_main("load-curve", motor, "--set", 'device.load="1 mN"')
    assert bad.returncode == 2 and "device.load" in bad.stderr
    ok = sawdrift_main("force-velocity", motor, "--set", 'device.incline="2 deg"', "--points",
                       "3", "--workers", "1", "--json")
    assert ok.returncode == 0, ok.stderr
    data = json.loads(ok.stdout)
    pull = sd.Scene.from_toml(motor).with_updates(**{"device.incline": "2 deg"}).particle.load
    # the unloaded point of the curve carries the incline's pull
    assert pull in [pytest.approx(f, abs=1e-12) for f in data["force"]]


CHAOTIC = ["--model", "mmd", "--m-star", "0.1", "--amplitude", "1"]


def _chaotic_scene() -> sd.Scene:
    """mmd at m* = 0.1, A* = 1, mu = 0.1: chaotic bouncing, a long-time mean with its error."""
    return sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 1.0})


def test_a_chaotic_curve_keeps_each_points_error_and_warnings(tmp_path, sawdrift_main):
    """Chaotic points used to lose their standard errors and warnings: the text, the JSON and
    the plot showed a bare mean, and the free drift was drawn as a firm point though it is zero
    within its error. Each point's error and warnings are those of its own run."""
    from matplotlib.container import ErrorbarContainer

    from sawdrift.report.force_velocity_plot import plot_force_velocity

    free = sd.run(_chaotic_scene())
    assert math.isfinite(free.drift_ratio_se)  # a long-time mean: the fact to carry
    curve = force_velocity(_chaotic_scene(), points=3, workers=1)
    data = curve.to_json()
    i = data["force"].index(0.0)
    speed = free.drift_velocity / free.drift_ratio
    assert data["drift_ratio_se"][i] == free.drift_ratio_se
    assert data["drift_velocity_se"][i] == pytest.approx(free.drift_ratio_se * speed, rel=1e-12)
    assert data["warnings"][i] == list(free.warnings)
    assert curve.free_drift_se == pytest.approx(free.drift_ratio_se * speed, rel=1e-12)
    zero_within = abs(free.drift_velocity) <= 3.0 * curve.free_drift_se
    assert data["free_drift_resolved"] is (not zero_within)
    for j, force in enumerate(data["force"]):  # every point: its own run's error
        run = sd.run(_chaotic_scene().with_updates(**{"particle.load": force}))
        se = data["drift_ratio_se"][j]
        assert se == (run.drift_ratio_se if math.isfinite(run.drift_ratio_se) else None)
    fig = plot_force_velocity(curve)
    bars = [c for c in fig.axes[0].containers if isinstance(c, ErrorbarContainer)]
    finite = sum(se is not None for se in data["drift_velocity_se"])
    assert finite >= 1 and len(bars) == finite + 1  # each point's, and the free drift's
    star = [t.get_text() for t in fig.axes[0].get_legend().get_texts() if "free drift" in t.get_text()]
    assert star and f"+- {curve.free_drift_se:.2g}" in star[0]
    assert ("zero within 3 errors" in star[0]) is zero_within
    done = sawdrift_main("force-velocity", *CHAOTIC, "--points", "3", "--workers", "1")
    assert done.returncode == 0, done.stderr
    assert f"free drift {free.drift_velocity:.6g} +- {curve.free_drift_se:.2g} a0 f" in done.stdout
    assert ("zero within 3 standard errors" in done.stdout) is zero_within


@pytest.mark.parametrize("name", ["fv.csv", "fv.png", "fv.json"])
def test_an_output_with_a_file_suffix_is_refused_not_made_a_folder(name, tmp_path, sawdrift_main):
    """-o fv.csv used to create a folder named fv.csv; the command writes a folder only."""
    bad = sawdrift_main("force-velocity", *CHAOTIC, "--points", "3", "-o", str(tmp_path / name))
    lines = bad.stderr.strip().splitlines()
    assert bad.returncode == 2 and len(lines) == 1 and lines[0].startswith("error: -o"), bad.stderr
    assert "give a folder" in lines[0] and "Traceback" not in bad.stderr
    assert not any(tmp_path.iterdir())


def test_an_unwritable_output_is_refused_before_any_run(tmp_path, sawdrift_main, monkeypatch):
    """The output folder is checked before the size calibration and the runs, as sweep does."""
    import sawdrift.study.estimate as estimate
    import sawdrift.study.force_velocity as study

    def ran(*_args, **_kwargs):
        raise AssertionError("ran before checking -o")

    monkeypatch.setattr(estimate, "size_check", ran)
    monkeypatch.setattr(study, "force_velocity", ran)
    (tmp_path / "file").write_text("")
    bad = sawdrift_main("force-velocity", *CHAOTIC, "-o", str(tmp_path / "file" / "fv"))
    lines = bad.stderr.strip().splitlines()
    assert bad.returncode == 2 and len(lines) == 1 and "is a file, not a folder" in lines[0]


def test_a_refused_size_leaves_no_output_folder(tmp_path, sawdrift_main, monkeypatch):
    import sawdrift.study.estimate as estimate

    def refuse(*_args, **_kwargs):
        raise sd.SceneError("force-velocity: too big; give --yes to start it anyway")

    monkeypatch.setattr(estimate, "size_check", refuse)
    bad = sawdrift_main("force-velocity", *CHAOTIC, "-o", str(tmp_path / "a" / "fv"))
    assert bad.returncode == 2 and "too big" in bad.stderr
    assert not any(tmp_path.iterdir())


def test_adhesion_widens_the_loads_sampled_and_the_load_curve_to_its_friction_bound():
    # loads were sampled inside (-mu, mu) and the stall load bracketed below mu although an
    # adhesive contact holds up to mu (1 + 2 F*_pull): here the stall lies above mu = 0.3
    scene = sd.Scene(model="mmd", particle={"m_star": 0.2}, material={"mu": 0.3, "adhesion": 1.0},
                     effects={"adhesion": "jkr"}, drive={"amplitude": 0.3})
    curve = force_velocity(scene, points=5, workers=1)
    assert curve.friction_bound == pytest.approx(0.9, rel=1e-12)
    assert max(abs(curve.forces)) == pytest.approx(0.9 * 4 / 6, rel=1e-12)  # inside (-0.9, 0.9)
    free = sd.run(scene).drift_ratio
    lc = sd.load_curve(scene, loads=2, workers=1)
    # direct runs either side of the stall: the drift keeps its unloaded sign below it only
    below = sd.run(scene.with_updates(**{"particle.load": -math.copysign(0.98 * lc.stall_load,
                                                                          free)}))
    above = sd.run(scene.with_updates(**{"particle.load": -math.copysign(1.02 * lc.stall_load,
                                                                          free)}))
    assert lc.stall_load > 0.3
    assert below.drift_ratio * free > 0.0 and not above.drift_ratio * free > 0.0


def test_the_text_prints_each_points_own_warning(monkeypatch, capsys):
    """The note said "(a lower-bound error, a motion still heating up)" whatever the points
    carried (jaeger m* = 50, A* = 1.5, e = 0.5, whose free point's mean was then still moving;
    it is now solved, with no warning); it prints the warning itself, with the number of
    points carrying it. mmd m* = 0.1, A* = 1, mu = 0.1: the free point's bounces heat up."""
    from .cli_call import call

    code, _, err = call(monkeypatch, capsys, "force-velocity", "--model", "mmd", "--m-star",
                        "0.1", "--amplitude", "1", "--mu", "0.1",
                        "--points", "3", "--workers", "1", "--no-progress")
    results = sd.run(sd.Scene(model="mmd", particle={"m_star": 0.1}, drive={"amplitude": 1.0},
                              material={"mu": 0.1})).warnings
    assert code == 0 and results
    assert re.search(r"warning \((1 point|[2-9] points)\): " + re.escape(results[0]), err), err
    assert "a motion still heating up)" not in err
