"""Bifurcation diagrams: located thresholds, slow transients, hysteresis, resume, bad input, panels.

The completely inelastic bouncing ball (material point, restitution 0, r = 0, Gamma = 4 pi^2 m* A*;
m* = 1/(4 pi^2) makes A* = Gamma): lift-off at Gamma = 1, loss of the sticking phase at
sqrt(1 + pi^2), first period doubling at sqrt(4 + pi^2) (Mehta and Luck 1990; docs/physics.md).
With restitution e the period-1 bounce exists from Gamma_1 = pi (1 - e)/(1 + e) and doubles at
sqrt(Gamma_1^2 + (2 (1 + e^2)/(1 + e)^2)^2) (Luck and Mehta 1993), while a particle at rest first
lifts off at Gamma = 1: between them the answer depends on the history.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest

import sawdrift as sd
from sawdrift.dynamics.window import orbit_period, state_scale
from sawdrift.errors import SceneError
from sawdrift.study.bifurcation import TABLE, bifurcation
from sawdrift.study.branch import Budget, attractor, continue_to, new_stepper
from sawdrift.study.orbits import classify
from sawdrift.study.provenance import TableProvenanceError

M_GAMMA = 1.0 / (4.0 * math.pi**2)  # m* at which A* = Gamma


def ball(restitution: float = 0.0) -> sd.Scene:
    return sd.Scene(model="material_point", particle={"m_star": M_GAMMA},
                    drive={"horizontal_ratio": 0.0}, model_params={"restitution": restitution})


def located(result, kind: str, direction: str = "up", model: str = "material_point") -> list[float]:
    return [b["value"] for b in result.bifurcations
            if b["kind"] == kind and b["direction"] == direction and b["model"] == model
            and b["located"]]


def test_inelastic_bouncing_ball_thresholds_are_located():
    res = bifurcation(ball(), "drive.amplitude", "lin:0.9:3.9:16", samples=16, locate=True,
                      tolerance=1e-4, workers=2, progress=False)
    (lift,) = located(res, "lift_off")
    (stick,) = located(res, "sticking_lost")
    (flip,) = located(res, "period_doubling")
    assert lift == pytest.approx(1.0, abs=1e-3)
    assert stick == pytest.approx(math.sqrt(1.0 + math.pi**2), abs=1e-3)
    assert flip == pytest.approx(math.sqrt(4.0 + math.pi**2), abs=1e-3)
    pts = res.summary["points"]["material_point"]["up"]
    assert all(p["period"] == 1 for p in pts if p["value"] < 3.7)
    assert all(p["period"] == 2 for p in pts if 3.75 < p["value"] < 3.9)
    # the period-1 orbit without a resting phase (docs/physics.md): take-off at the plate phase
    # tau = arccos(pi/Gamma), t* = (tau + pi/2)/(2 pi) mod 1, multiplier 1 - sqrt(Gamma^2 - pi^2)
    for gamma in (3.5, 3.7):
        rows = res.table[np.isclose(res.table["value"], gamma)]
        phase = (math.acos(math.pi / gamma) + 0.5 * math.pi) / (2 * math.pi)
        assert np.allclose(rows["liftoff_phase"], phase, atol=1e-6)
        lam = 1.0 - math.sqrt(gamma**2 - math.pi**2)
        assert rows["lyapunov"].iloc[0] == pytest.approx(math.log(abs(lam)), abs=0.01)


def test_slowly_decaying_alternation_is_period_one_with_the_map_multiplier():
    # Gamma = 3.72, just below the doubling: the period-1 orbit's multiplier is
    # 1 - sqrt(Gamma^2 - pi^2) = -0.99218. After 1600 periods the alternation is 4e-8 and
    # s_(n+2) - s_n = (1 + lambda)(s_(n+1) - s_n) is below the round-off test: the state
    # repeats after 2 periods, but its states 1 period apart differ by 4e-8 only, so it is no
    # orbit of 2 (window.DISTINCT): the motion converges to the period-1 orbit
    gamma = 3.72
    scene = ball().with_updates(**{"drive.amplitude": gamma})
    st = new_stepper(ball().with_updates(**{"drive.amplitude": 3.70}))
    st.advance(3000 * st.k_per)
    st = continue_to(st, scene)
    scale = state_scale(gamma, 0.0)
    rows = []
    for _ in range(1600):
        st.advance(st.k_per)
        rows.append(st.y[:4].copy())
    samples = np.array(rows[-64:])
    assert orbit_period(samples, scale) == 0  # was 2: the decaying alternation taken for an orbit
    cls = classify(samples[:, 1:4] / scale)
    assert cls.period == 1 and not cls.exact
    assert cls.multiplier == pytest.approx(1.0 - math.sqrt(gamma**2 - math.pi**2), abs=1e-4)
    point = attractor(continue_to(st, scene), scene, Budget.for_scene(scene, 16), gamma)
    assert point.period == 1 and point.exact
    # ln |lambda| per period, from the renormalized twin
    assert point.lyapunov == pytest.approx(math.log(0.99218), abs=2e-3)


@pytest.mark.slow
def test_hysteresis_of_the_bouncing_ball_with_restitution():
    e = 0.8
    res = bifurcation(ball(e), "drive.amplitude", "lin:0.25:1.45:13", samples=16,
                      direction="both", locate=True, workers=2, progress=False)
    gamma_1 = math.pi * (1 - e) / (1 + e)
    gamma_2 = math.sqrt(gamma_1**2 + (2 * (1 + e * e) / (1 + e) ** 2) ** 2)
    (up_lift,) = located(res, "lift_off", "up")
    (down_lift,) = located(res, "lift_off", "down")
    assert up_lift == pytest.approx(1.0, abs=1e-3)  # from rest: lifts when Gamma > 1
    assert down_lift == pytest.approx(gamma_1, abs=1e-3)  # the bounce dies at its saddle-node
    assert located(res, "period_doubling", "down")[0] == pytest.approx(gamma_2, abs=1e-3)
    spans = [(h["from"], h["to"]) for h in res.hysteresis]
    assert any(a <= 0.45 and b >= 0.95 for a, b in spans)
    table = res.table
    flagged = set(table[table["hysteresis"]]["value"].round(9))
    assert min(flagged) > gamma_1  # below the saddle-node both branches rest on the surface
    assert {round(v, 9) for v in np.linspace(0.25, 1.45, 13) if 0.4 < v < 1.0} <= flagged


def test_interrupted_run_resumes_with_the_same_table(tmp_path):
    axis = "lin:3.5:4.0:10"
    whole = bifurcation(ball(), "drive.amplitude", axis, samples=8, out=tmp_path / "a",
                        workers=1, progress=False)
    seen = []

    def stop(record):
        seen.append(record["i"])
        if len(seen) == 4:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        bifurcation(ball(), "drive.amplitude", axis, samples=8, out=tmp_path / "b", workers=1,
                    progress=False, on_value=stop)
    again = bifurcation(ball(), "drive.amplitude", axis, samples=8, out=tmp_path / "b",
                        workers=1, progress=False)
    assert whole.computed == 10 and again.computed == 6
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "a" / TABLE),
                                  pd.read_parquet(tmp_path / "b" / TABLE))
    done = bifurcation(ball(), "drive.amplitude", axis, samples=8, out=tmp_path / "b",
                       workers=1, progress=False)
    assert done.computed == 0


def test_a_folder_of_other_code_or_another_axis_is_refused(tmp_path):
    out = tmp_path / "d"
    bifurcation(ball(), "drive.amplitude", "3.5,3.6", samples=4, out=out, workers=1,
                progress=False)
    with pytest.raises(TableProvenanceError, match="another bifurcation diagram"):
        bifurcation(ball(), "drive.amplitude", "3.5,3.7", samples=4, out=out, workers=1,
                    progress=False)
    journal = out / "journal" / "material_point-up.jsonl"
    lines = journal.read_text().splitlines()
    head = json.loads(lines[0])
    head["code_hash"] = "0123456789ab"
    journal.write_text("\n".join([json.dumps(head), *lines[1:]]) + "\n")
    (out / TABLE).unlink()
    with pytest.raises(TableProvenanceError, match="other code"):
        bifurcation(ball(), "drive.amplitude", "3.5,3.6", samples=4, out=out, workers=1,
                    progress=False)
    res = bifurcation(ball(), "drive.amplitude", "3.5,3.6", samples=4, out=out, workers=1,
                      progress=False, force=True)
    assert res.computed == 0 and len(res.table) == 8


def test_a_run_with_fewer_branches_keeps_the_folders_other_branches(tmp_path):
    """A folder holding a --direction both diagram: an up run used to print "0 values computed"
    and rewrite the table with the up rows only (the down branch and the hysteresis lost)."""
    out = tmp_path / "both"
    kw = dict(samples=4, out=out, workers=1, progress=False)
    bifurcation(ball(), "drive.amplitude", "3.5,3.6", direction="both", **kw)
    before = pd.read_parquet(out / TABLE)
    assert set(before["direction"]) == {"up", "down"}
    for way in ("up", "down"):
        with pytest.raises(SceneError, match=rf"holds this diagram's material_point "
                           rf"{'down' if way == 'up' else 'up'} branch, .*direction='both'") as info:
            bifurcation(ball(), "drive.amplitude", "3.5,3.6", direction=way, **kw)
        assert "\n" not in str(info.value)
        pd.testing.assert_frame_equal(pd.read_parquet(out / TABLE), before)
    again = bifurcation(ball(), "drive.amplitude", "3.5,3.6", direction="both", **kw)
    assert again.computed == 0 and len(again.table) == len(before)
    # force replaces the table, as documented
    only_up = bifurcation(ball(), "drive.amplitude", "3.5,3.6", direction="up", force=True, **kw)
    assert set(pd.read_parquet(out / TABLE)["direction"]) == {"up"} and only_up.computed == 0


def test_a_run_with_fewer_branches_is_refused_in_one_line_on_the_command_line(tmp_path):
    from .cli_call import run_main

    args = ("bifurcation", "--model", "material_point", "--m-star", str(M_GAMMA),
            "--horizontal-ratio", "0", "--axis", "drive.amplitude=3.5,3.6", "--samples", "4",
            "--workers", "1", "--no-progress", "-o", tmp_path / "bif")
    run_main(*args, "--direction", "both", check=True)
    proc = run_main(*args, "--direction", "up")
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and "--direction both" in proc.stderr
    assert set(pd.read_parquet(tmp_path / "bif" / TABLE)["direction"]) == {"up", "down"}


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"values": "a,b"}, "not a number"),
    ({"values": "1.5"}, "at least two different values"),
    ({"values": [2.0, 2.0]}, "at least two different values"),
    ({"samples": 0}, "samples = 0 must be an integer from 1 to 1e\\+07"),
    ({"field": "drive.amplitud"}, "drive.amplitud is not a known field"),
    ({"field": "drive.orbit"}, "not a numeric scene field"),
    ({"direction": "sideways"}, "direction = 'sideways'"),
])
def test_bad_input_is_one_line(kwargs, match):
    args = {"field": "drive.amplitude", "values": "3.5,3.6", **kwargs}
    with pytest.raises(SceneError, match=match) as info:
        bifurcation(ball(), args.pop("field"), args.pop("values"), progress=False, **args)
    assert "\n" not in str(info.value)


@pytest.mark.slow
def test_two_models_side_by_side_on_one_axis():
    # a stiff compliant contact (m* = 1e-3, Tsuji damping) next to the rigid point: same values,
    # and below Gamma = 1 both stay in contact while the point's doubling is still located
    m = 1e-3
    k = 4 * math.pi**2 * m
    base = sd.Scene(model="material_point", particle={"m_star": m}, drive={"horizontal_ratio": 0.0})
    res = bifurcation(base, "drive.amplitude", f"lin:{0.6 / k}:{4.2 / k}:10",
                      models="material_point,hertz_tsuji", samples=8, locate=True, workers=2,
                      progress=False)
    t = res.table
    assert set(t["model"]) == {"material_point", "hertz_tsuji"}
    assert set(t[t.model == "material_point"]["value"]) == set(t[t.model == "hertz_tsuji"]["value"])
    (flip,) = located(res, "period_doubling")
    assert flip * k == pytest.approx(math.sqrt(4.0 + math.pi**2), abs=1e-3)
    (lift,) = located(res, "lift_off", model="hertz_tsuji")
    assert lift * k == pytest.approx(1.0, abs=0.05)
    from sawdrift.report.bifurcation_plot import plot_bifurcation

    fig = plot_bifurcation(res)
    assert len(fig.axes) == 2 * 4  # two columns: samples, lift-off phase, period, Lyapunov


def test_just_past_the_doubling_the_slow_alternation_is_followed_to_its_orbit_of_two():
    # Gamma = 3.7263, multiplier 1 - sqrt(Gamma^2 - pi^2) = -1.003: the alternation away from
    # the unstable period-1 orbit grows 4 % a 64-period window and never comes closer to
    # repeating on the way; the search gave up after two windows (356 periods) and reported
    # period 0 with the unstable orbit's exponent. The 2-cycle it reaches is stable.
    gamma = 3.7263
    res = bifurcation(ball(), "drive.amplitude", f"{gamma},{gamma + 1e-3}", samples=16,
                      workers=1, progress=False)
    for p in res.summary["points"]["material_point"]["up"]:
        assert p["period"] == 2, p
    rows = res.table[np.isclose(res.table["value"], gamma)]
    assert rows["lyapunov"].iloc[0] < 0.0


def test_a_failed_value_is_named_on_the_console(monkeypatch, capsys, tmp_path):
    # the ball at e = 0.8 collapses into more events than a step holds at Gamma = 1.01 on this
    # branch: the console said only 'no period: 18, period 1: 102', the failure in the table
    import sys

    from sawdrift.cli import main

    monkeypatch.setattr(sys, "argv", [
        "sawdrift", "bifurcation", "--model", "material_point", "--m-star",
        "0.025330295910584444", "--horizontal-ratio", "0", "--param", "restitution=0.8",
        "--axis", "drive.amplitude=lin:0.2:1.4:121", "-o", str(tmp_path / "b"), "--no-progress"])
    with pytest.raises(SystemExit):
        main()
    out = capsys.readouterr().out
    table = pd.read_parquet(tmp_path / "b" / TABLE)
    bad = table[table["error"].notna()]
    for value in bad["value"]:
        assert f"failed at drive.amplitude = {value:.6g}: " in out
    assert bad.empty or f"failed: {len(bad)}" in out
    assert "restitution below 1" not in out  # it is 0.8 already


def test_a_one_value_hysteresis_is_printed_as_such():
    # mmd's gallery diagram printed 'hysteresis from 0.87 to 0.87': at 1024 steps per period
    # the two branches agree there (the step's error on a compliant contact)
    from sawdrift.cli.study import hysteresis_line

    one = hysteresis_line({"model": "mmd", "from": 0.87, "to": 0.87, "values": 1})
    assert "hysteresis at 0.87 only" in one and "--steps-per-period" in one
    span = hysteresis_line({"model": "mmd", "from": 0.8, "to": 0.85, "values": 6})
    assert span.endswith("hysteresis from 0.8 to 0.85")


def test_a_device_axis_is_labelled_with_its_unit():
    """device.frequency was labelled bare, with ticks 0.5-3.0 and a '1e7' offset."""
    from pathlib import Path

    from sawdrift.report.bifurcation_plot import plot_bifurcation

    base = sd.Scene.from_toml(Path(__file__).resolve().parents[1] / "examples"
                              / "saw_linear_motor.toml")
    res = bifurcation(base, "device.frequency", "8 MHz:10 MHz:2", samples=4, workers=1,
                      progress=False)
    fig = plot_bifurcation(res)
    assert fig.axes[-1].get_xlabel() == "device.frequency (Hz)"
    fig.canvas.draw()
    assert any("MHz" in t.get_text() for t in fig.axes[-1].get_xticklabels())


def test_a_device_axis_list_takes_quantities_as_its_range_does():
    """'device.amplitude=5 nm:10 nm:2' ran; '5 nm,10 nm' was refused as not a number."""
    from sawdrift.study.bifurcation import _values

    assert _values("5 nm,10 nm", "device.amplitude") == pytest.approx([5e-9, 1e-8])
    with pytest.raises(sd.SceneError, match="is not a length"):
        _values("5 s,10 nm", "device.amplitude")


def test_the_size_line_says_what_locate_adds(monkeypatch, capsys):
    """--locate bisects at each bifurcation found, runs no estimate can count beforehand: the
    size line said 1.3 s for a run of 9 to 14 s as if it were the whole."""
    import importlib

    study = importlib.import_module("sawdrift.cli.study")
    base = sd.Scene(model="mmd", numerics={"periods": 10})
    study._bifurcation_size(base, "drive.amplitude", "lin:0.1:0.3:3", 1, "up", 8, 1, "compiled",
                            False, True, locate=True)
    assert "not counted: --locate's bisections" in capsys.readouterr().err
    study._bifurcation_size(base, "drive.amplitude", "lin:0.1:0.3:3", 1, "up", 8, 1, "compiled",
                            False, True, locate=False)
    assert "not counted" not in capsys.readouterr().err


def test_a_journal_row_that_is_not_its_axis_value_is_computed_again(tmp_path):
    """A journal row whose value is NaN (or another axis's) went into the table as it was."""
    out = tmp_path / "j"
    first = bifurcation(ball(), "drive.amplitude", "3.5,3.6", samples=4, out=out, workers=1,
                        progress=False)
    journal = out / "journal" / "material_point-up.jsonl"
    lines = journal.read_text().splitlines()
    row = json.loads(lines[1])
    row["value"] = float("nan")
    journal.write_text("\n".join([lines[0], json.dumps(row), *lines[2:]]) + "\n")
    (out / TABLE).unlink()
    again = bifurcation(ball(), "drive.amplitude", "3.5,3.6", samples=4, out=out, workers=1,
                        progress=False)
    assert again.computed == 1
    assert again.table["value"].notna().all()
    pd.testing.assert_frame_equal(again.table.reset_index(drop=True),
                                  first.table.reset_index(drop=True))


def test_a_finite_exponent_between_superstable_ones_is_marked():
    """The Lyapunov panel drew finite exponents as a line only: a value between two -inf ones
    (or a branch's only finite one) had no mark at all."""
    from sawdrift.report.bifurcation_plot import plot_bifurcation

    res = bifurcation(ball(), "drive.amplitude", "3.4,3.5,3.6", samples=4, workers=1,
                      progress=False)
    table = res.table.copy()
    table["lyapunov"] = table["index"].map({0: -math.inf, 1: -0.61, 2: -math.inf})
    fig = plot_bifurcation(table, summary=res.summary)
    lyap_ax = next(ax for ax in fig.axes if "Lyapunov" in ax.get_ylabel())
    marked = [ln for ln in lyap_ax.get_lines() if ln.get_marker() not in ("None", "", None)
              and np.any(np.isclose(np.asarray(ln.get_ydata(), float), -0.61))]
    assert marked


def test_the_figure_lists_only_what_it_draws_and_a_log_sweep_on_a_log_axis():
    """Without --locate the legend listed bifurcation lines no panel drew; an axis swept
    log-spaced (m* 0.01:1:5) was drawn on a linear axis, its low values crammed together."""
    from sawdrift.report.bifurcation_plot import plot_bifurcation

    res = bifurcation(ball(), "drive.amplitude", "3.5,3.6,3.7,3.8", samples=4, workers=1,
                      progress=False)
    assert res.summary.get("bifurcations")  # found between values, not located
    fig = plot_bifurcation(res)
    texts = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
    assert texts == ["sweep up"], texts
    assert fig.axes[-1].get_xscale() == "linear"  # evenly spaced values
    logs = bifurcation(sd.Scene(model="material_point", drive={"amplitude": 0.5}),
                       "particle.m_star", "0.01:1:3", samples=4, workers=1, progress=False)
    assert plot_bifurcation(logs).axes[-1].get_xscale() == "log"


def test_a_rigid_point_sliding_all_period_has_the_finite_exponent_of_heavy_sliding():
    """material_point m* = 1, Gz = 0.5, Gx = 10 Gz: it slides through the whole period and never
    lands. A velocity perturbation shifts the two reversals of the slip, where friction jumps
    by 2 mu N*, and decays by 4 mu (1 - Gz cos phi0) / (m* 2 pi U sin phi0) a period (heavy
    sliding, 2 phi0 - pi = 2 Gz sin phi0, U the surface speed): -0.0541 at mu = 0.05, -0.1082
    at mu = 0.1. The twin displaced along y*' alone was held to the surface at once, and the
    exponent said -inf."""
    from scipy.optimize import brentq

    amp = 0.5 / (2.0 * math.pi) ** 2
    scene = sd.Scene(model="material_point", particle={"m_star": 1.0},
                     drive={"amplitude": amp, "horizontal_ratio": 10.0})
    res = bifurcation(scene, "material.mu", "0.05,0.1", samples=16, workers=1, progress=False)
    phi0 = brentq(lambda p: 2.0 * p - math.pi - 2.0 * 0.5 * math.sin(p), 0.01, math.pi - 0.01)
    speed = 2.0 * math.pi * 10.0 * amp
    for mu in (0.05, 0.1):
        rows = res.table[np.isclose(res.table["value"], mu)]
        expected = -mu * 4.0 * (1.0 - 0.5 * math.cos(phi0)) / (2.0 * math.pi * speed * math.sin(phi0))
        assert rows["lyapunov"].iloc[0] == pytest.approx(expected, rel=2e-3)


def test_the_json_says_where_a_lyapunov_exponent_of_minus_inf_became_null():
    """JSON has no -inf: a ball resting on the plate (its perturbation erased by the landing,
    -inf in the table) and a value not computed both read lyapunov null; ``erased`` tells
    them apart."""
    res = bifurcation(ball(), "drive.amplitude", "0.5,3.5", samples=16, workers=1,
                      progress=False)
    table = res.table.groupby("value")["lyapunov"].first()
    points = {p["value"]: p for p in json.loads(json.dumps(res.summary))["points"]
              ["material_point"]["up"]}
    assert table[0.5] == -math.inf and points[0.5]["lyapunov"] is None and points[0.5]["erased"]
    assert math.isfinite(table[3.5]) and points[3.5]["erased"] is False


def test_a_located_change_takes_the_periods_met_beside_it_not_the_brackets_ends():
    """The inelastic ball on a coarse grid: the bracket [3.7, 3.9] holds the doubling (3.7242)
    and the sticking regained on the period-2 orbit (3.8569), and both took the bracket's end
    periods: "sticking_regained 1 -> 2". The orbits met beside the located value are period 2
    on both sides."""
    res = bifurcation(ball(), "drive.amplitude", "lin:3.7:3.9:2", samples=16, locate=True,
                      tolerance=1e-4, workers=1, progress=False)
    (regained,) = [b for b in res.bifurcations if b["kind"] == "sticking_regained"]
    assert regained["value"] == pytest.approx(3.85685, abs=2e-3)
    assert (regained["from_period"], regained["to_period"]) == (2, 2)
    (flip,) = [b for b in res.bifurcations if b["kind"] == "period_doubling"]
    assert (flip["from_period"], flip["to_period"]) == (1, 2)
