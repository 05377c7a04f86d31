"""Dissipation in the LAMMPS bridge: material.restitution as LAMMPS damping coeff_restitution.

The free impact is the damping model's own check (the rebound ratio is the native e at any
speed); the drift of a damped bead on the wave is checked against an independent integrator of
the Coulomb rule both engines apply to the stored spring (its bound is the total normal force,
elastic plus damping; sawdrift.lammps.damped), and the two engines against each other.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

import sawdrift as sd
from sawdrift.lammps import available, input_script, refusal
from sawdrift.lammps.realize import MIN_LAMMPS_RESTITUTION, lammps_restitution

HAVE_LAMMPS, WHY = available()
needs_lammps = pytest.mark.skipif(not HAVE_LAMMPS, reason=f"LAMMPS not installed: {WHY}")
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def bead(radius: str, e: float | None, periods: float = 100.0) -> sd.Scene:
    """A bead of examples/mixture.toml alone on the plate (512 steps per period, fixed run)."""
    data = tomllib.loads((EXAMPLES / "mixture.toml").read_text())
    data.pop("particles")
    data["numerics"] = {"periods": periods, "steps_per_period": 512, "settle": False}
    data["device"]["particle"]["radius"] = radius
    data.setdefault("material", {})["restitution"] = e
    if e is None:
        data["material"].pop("restitution")
    return sd.bind(sd.scene.build_scene(data))


def test_lammps_restitution_is_the_unclamped_dashpot_of_the_same_damping():
    # e' = exp(-pi zeta / sqrt(1 - zeta^2)): below e (the unclamped dashpot rebounds lower), 1 at 1
    assert lammps_restitution(1.0) == 1.0
    for e in (0.3, 0.5, 0.8, 0.95):
        assert 0.0 < lammps_restitution(e) < e
    assert lammps_restitution(0.5) == pytest.approx(0.43629, rel=1e-4)
    assert MIN_LAMMPS_RESTITUTION == pytest.approx(0.135335, rel=1e-5)
    assert "above 0.1353" in refusal(bead("1 mm", 0.1))
    assert refusal(bead("1 mm", 0.5)) is None


def test_damped_input_clamps_the_normal_force():
    text = input_script(bead("1 mm", 0.5))
    model = text.split("pair_coeff * * ")[1].splitlines()[0].split()
    assert model[:1] == ["hertz/material"] and float(model[2]) == pytest.approx(0.43629, rel=1e-4)
    assert model[4:6] == ["damping", "coeff_restitution"] and model[-1] == "limit_damping"
    assert "damping" not in input_script(bead("1 mm", None)).split("pair_coeff * * ")[1].splitlines()[0]


@needs_lammps
@pytest.mark.parametrize("e", [0.5, 0.8])
def test_lammps_free_impact_rebounds_with_the_native_restitution(e):
    """A free impact in LAMMPS rebounds with e within 1e-3 at two speeds a decade apart (the
    native definition of e; measured 0.49999 and 0.80000)."""
    from sawdrift.lammps.damped import free_impact

    for speed in (1e-4, 1e-3):
        assert free_impact(bead("1 mm", e), speed) == pytest.approx(e, rel=1e-3)


BEADS = [("1 mm", 0.5), ("1 mm", 0.8), ("0.2 mm", 0.5), ("0.2 mm", 0.8)]


@pytest.mark.parametrize(("radius", "e"), BEADS)
def test_native_damped_bead_follows_the_total_coulomb_rule(radius, e):
    """The native DEM spring bounds its stored force by the total normal force: its drift agrees
    with an independent velocity-Verlet integrator of that rule within 1 % (measured -3.8e-3,
    -2.6e-3, -1.0e-3, -5e-4 for the four beads, 100 periods). The 1 mm bead (m* 0.067, A* 0.31,
    gross slip) tells the rules apart: the elastic bound gives a drift more than 20 % away
    (0.187 and -0.272 against 0.304 and -0.198)."""
    from sawdrift.lammps.damped import cap_rule_drift

    scene = bead(radius, e)
    total = cap_rule_drift(scene, "total")
    assert sd.run(scene).drift_ratio == pytest.approx(total, rel=1e-2)
    if radius == "1 mm":
        elastic = cap_rule_drift(scene, "elastic")
        assert abs(total - elastic) > 0.2 * abs(total)


@needs_lammps
def test_damped_bead_in_gross_slip_agrees_with_native():
    """The 1 mm bead at e = 0.5 (gross slip while loading, where the two Coulomb rules differ by
    64 %), 40 periods: LAMMPS and native within 1 % (measured +0.50 %)."""
    from sawdrift.lammps import run_scene

    scene = bead("1 mm", 0.5, periods=40.0)
    assert run_scene(scene).drift_ratio == pytest.approx(sd.run(scene).drift_ratio, rel=1e-2)


@pytest.mark.slow
@needs_lammps
@pytest.mark.parametrize(("radius", "e"), BEADS)
def test_damped_beads_agree_between_native_and_lammps(radius, e):
    """Issue 38's single-bead agreement: both beads of the mixture at e = 0.5 and 0.8, 100
    periods at 512 steps: LAMMPS within 1 % of native (measured +0.50 %, -0.16 %, +0.09 %,
    -0.00 %) and of the independent integrator of the total rule (within 1.2e-3)."""
    from sawdrift.lammps import run_scene
    from sawdrift.lammps.damped import cap_rule_drift

    scene = bead(radius, e)
    lammps = run_scene(scene).drift_ratio
    assert lammps == pytest.approx(sd.run(scene).drift_ratio, rel=1e-2)
    assert lammps == pytest.approx(cap_rule_drift(scene, "total"), rel=1e-2)
