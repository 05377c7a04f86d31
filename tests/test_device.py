"""Devices in physical units: conversion, orbit, two materials, sweeps over any field."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

import sawdrift as sd
from sawdrift.scene.device import Device, normalized

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
MOTOR = EXAMPLES / "saw_linear_motor.toml"


def _cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "sawdrift", *args], capture_output=True,
                          text=True, cwd=cwd)


def _hand(R, rho, E1, nu1, E2, nu2, f, A, F, g=9.81):
    # docs/physics.md, "Physical units": written out independently of sawdrift.scene.device
    m = rho * 4 / 3 * math.pi * R**3
    e_star = 1 / ((1 - nu1**2) / E1 + (1 - nu2**2) / E2)
    g1, g2 = E1 / (2 * (1 + nu1)), E2 / (2 * (1 + nu2))
    g_star = 1 / ((2 - nu1) / g1 + (2 - nu2) / g2)
    w = m * g + F
    a0 = (9 * w**2 / (16 * R * e_star**2)) ** (1 / 3)
    return {"m_star": a0 * m * f**2 / w, "amplitude": A / a0, "theta": e_star / (4 * g_star),
            "a0_m": a0}


def test_motor_normalized_block_matches_hand_computation():
    scene = sd.Scene.from_toml(MOTOR)
    want = _hand(0.5e-3, 7850, 210e9, 0.3, 170e9, 0.25, 9.6e6, 10e-9, 7.35e-3)
    got = normalized(scene.device)
    for key, value in want.items():
        assert got[key] == pytest.approx(value, rel=1e-12), key
    assert scene.particle.m_star == pytest.approx(want["m_star"], rel=1e-12)
    assert scene.theta == pytest.approx(want["theta"], rel=1e-12)
    assert scene.horizontal_ratio == 0.68 and scene.drive.orbit == "retrograde"


def test_identical_materials_give_the_textbook_theta():
    for nu in (0.2, 0.3, 0.45):
        dev = Device.model_validate({
            "frequency": "1 MHz", "amplitude": "1 nm", "friction": 0.1,
            "particle": {"radius": "1 mm", "density": 7800, "youngs_modulus": "200 GPa",
                         "poisson": nu},
            "substrate": {"youngs_modulus": "200 GPa", "poisson": nu}})
        assert normalized(dev)["theta"] == pytest.approx((2 - nu) / (2 * (1 - nu)), rel=1e-13)


def test_motor_settles_and_drifts_against_propagation():
    out = _cli("run", str(MOTOR), "--json")
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert d["orbit"] == "retrograde" and d["settled"] is True
    assert d["direction"] == "against" and d["drift_speed_m_s"] < 0.0
    n = d["normalized"]
    assert d["drift_speed_m_s"] == pytest.approx(d["drift_velocity"] * n["a0_m"] * 9.6e6, rel=1e-12)
    assert d["t90_s"] > 0.0


def test_retrograde_orbit_mirrors_the_drift_exactly():
    pro = _cli("run", "--model", "mmd", "--m-star", "0.1", "--amplitude", "0.316", "--json")
    retro = _cli("run", "--model", "mmd", "--m-star", "0.1", "--amplitude", "0.316",
                 "--orbit", "retrograde", "--json")
    p, r = json.loads(pro.stdout), json.loads(retro.stdout)
    assert r["drift_ratio"] == -p["drift_ratio"] and p["regime"] == "drift_with"
    assert r["regime"] == "drift_against" and r["orbit"] == "retrograde"
    point = dict(model="material_point", particle={"m_star": 0.01}, drive={"amplitude": 2.0})
    a = sd.run(sd.Scene(**point))
    b = sd.run(sd.Scene(**{**point, "drive": {"amplitude": 2.0, "orbit": "retrograde"}}))
    assert b.drift_ratio == -a.drift_ratio
    assert (a.regime, b.regime) == ("drift_against", "drift_with")


def test_sweep_over_material_mu(tmp_path):
    table = tmp_path / "t.parquet"
    out = _cli("sweep", "--model", "mmd", "--m-star", "0.1", "--amplitude", "0.316", "--axis",
               "material.mu=0.05,0.1,0.2", "-o", str(table), "--workers", "1", "--no-progress")
    assert out.returncode == 0, out.stderr
    frame = pd.read_parquet(table)
    assert sorted(frame["material.mu"]) == [0.05, 0.1, 0.2]
    assert sorted(frame["mu"]) == [0.05, 0.1, 0.2]


def test_sweep_over_a_device_field_with_units():
    base = sd.Scene.from_toml(MOTOR).with_updates(**{"numerics.settle": False,
                                                     "numerics.periods": 20})
    frame = sd.sweep(["mmd"], axes={"device.amplitude": "5 nm,10 nm"}, base=base, workers=1,
                     progress=False)
    assert sorted(frame["device.amplitude"]) == pytest.approx([5e-9, 10e-9])
    ratio = frame.sort_values("device.amplitude")["amplitude"].to_numpy()
    assert ratio[1] / ratio[0] == pytest.approx(2.0, rel=1e-12)


@pytest.mark.parametrize(
    "edit, needle",
    [
        ('amplitude = "10 kg"', "device.amplitude = '10 kg' is not a length"),
        ('amplitude = "ten"', "device.amplitude = 'ten' is not a quantity"),
        ('frequency = "3 m"', "device.frequency = '3 m' is not a frequency"),
        ('radius = "-0.5 mm"', "device.particle.radius = '-0.5 mm' is not > 0"),
        ('youngs_modulus = "210 m/s"', "is not a pressure"),
        ('youngs_modulus = None', "youngs_modulus is required: a pressure in Pa"),
    ],
)
def test_wrong_units_are_one_line_errors(tmp_path, edit, needle):
    key = edit.split(" = ")[0]
    lines = []
    done = False
    for line in MOTOR.read_text().splitlines():
        if not done and line.startswith(key + " ="):
            done = True
            if not edit.endswith("None"):
                lines.append(edit)
            continue
        lines.append(line)
    path = tmp_path / "bad.toml"
    path.write_text("\n".join(lines) + "\n")
    out = _cli("run", str(path), "--json")
    assert out.returncode == 2
    err = out.stderr.strip().splitlines()
    assert len(err) == 1 and needle in err[0], err


def test_explain_names_time_scales_and_limits():
    text = _cli("run", str(EXAMPLES / "silica_bead_on_quartz.toml"), "--explain").stdout
    assert "a0 < 1 nm" in text and "natural frequency" in text and "approach" in text
    motor = _cli("run", str(MOTOR), "--explain").stdout
    assert "retrograde orbit" in motor and "a0 < 1 nm" not in motor
