"""The slow model of touching chains (sawdrift.mixture.chains, .events, .curves): closed forms of
a chain's balance, where it splits, contacts in slow time, and the dilute limit against single runs."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

import sawdrift as sd
from sawdrift.mixture.chains import Bead, contact_geometry, solve_chain, split_chain
from sawdrift.mixture.curves import SpeciesCurves, isotonic, species_curves
from sawdrift.mixture.events import SlowModel, lanes
from sawdrift.mixture.plane import PlaneModel

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def linear(v0: float, k: float, normal=(0.5, 1.0, 2.0), radius=1e-3, weight=1.0) -> SpeciesCurves:
    """Curves l = L / N = k (V - v0) at every normal load (l sampled in (-0.3, 0.3))."""
    ells = np.linspace(-0.29, 0.29, 31)
    v = v0 + ells / k
    rows = len(normal)
    return SpeciesCurves(radius=radius, weight=weight, normal=np.array(normal, dtype=float),
                         loads=np.tile(ells, (rows, 1)), speeds=np.tile(v, (rows, 1)),
                         raw=np.tile(v, (rows, 1)), regimes=(("x",) * 31,) * rows, mu=0.3,
                         wall_time_s=0.0)


def test_level_chain_moves_at_the_weighted_mean_speed():
    """Equal beads (horizontal contacts), linear curves L_j = k_j W_j (V - V_j): the balance
    sum L_j = 0 gives V = sum k_j W_j V_j / sum k_j W_j, and the pair force behind bead m is
    -sum_{j <= m} L_j (closed forms)."""
    beads = [Bead(1e-3, 1e-9, 1.0), Bead(1e-3, 1e-9, 2.0)]
    curves = [linear(0.3, 0.5, weight=1.0), linear(-0.2, 0.25, weight=2.0)]
    kinds = [0, 0, 1, 0]
    edges = [(0, 1), (1, 2), (2, 3)]
    state = solve_chain(beads, kinds, edges, curves)
    k = np.array([0.5, 0.5, 0.25, 0.5])
    w = np.array([1.0, 1.0, 2.0, 1.0])
    v0 = np.array([0.3, 0.3, -0.2, 0.3])
    v = float((k * w * v0).sum() / (k * w).sum())
    assert not state.saturated
    assert state.speed == pytest.approx(v, abs=1e-6)
    loads = k * w * (v - v0)
    assert state.forces == pytest.approx(-np.cumsum(loads)[:-1], abs=1e-5)
    assert state.normal == pytest.approx(1.0, abs=1e-12)  # level contacts press nobody


def test_inclined_pair_presses_the_small_bead_and_lifts_the_large():
    """A small bead behind a large one, curves L = k (V - V0) N: the pair force P along the
    normal inclined by phi gives -P cos phi = k_s (V - V_s) (W_s + P sin phi) and P cos phi =
    k_L (V - V_L) (W_L - P sin phi); solved here by elimination and a scalar root, independent of
    the chain's fixed point."""
    small, large = Bead(0.2e-3, 1.1e-10, 1.0), Bead(1e-3, 1.6e-9, 125.0)
    _, c, s = contact_geometry(small, large)
    assert math.degrees(math.asin(s)) == pytest.approx(41.8, abs=0.1)  # 0.8 mm up, 1.2 mm apart
    ks, vs, kl, vl = 0.2, 0.38, 1.0, -0.35
    curves = [linear(vs, ks, normal=(1.0, 4.0, 16.0), weight=1.0),
              linear(vl, kl, normal=(0.5, 1.0, 1.1), weight=125.0)]

    def force(v: float) -> float:
        return -ks * (v - vs) * 1.0 / (c + s * ks * (v - vs))

    def residual(v: float) -> float:
        p = force(v)
        return p * c - kl * (v - vl) * (125.0 - p * s)

    v = brentq(residual, vl, 0.0)
    state = solve_chain([small, large], [0, 1], [(0, 1)], curves)
    assert not state.saturated
    assert state.speed == pytest.approx(v, abs=1e-7)
    assert state.forces[0] == pytest.approx(force(v), rel=1e-5)
    assert state.normal[0] == pytest.approx(1.0 + force(v) * s, rel=1e-5)  # pressed
    assert state.normal[1] == pytest.approx(1.0 - force(v) * s / 125.0, rel=1e-7)  # lifted
    assert state.normal[0] > 1.0 > state.normal[1]


def test_chain_splits_where_the_front_runs_ahead():
    """A slow bead behind a fast one cannot pull it: the pair force would be tensile, the chain
    splits and each bead moves at its free speed; the other way round they hold together."""
    curves = [linear(0.3, 0.5), linear(-0.2, 0.25)]
    beads = [Bead(1e-3, 1e-9, 1.0), Bead(1e-3, 1e-9, 1.0)]
    parts = split_chain(beads, [1, 0], [(0, 1)], curves)
    assert [p[0] for p in parts] == [[0], [1]]
    assert [p[2].speed for p in parts] == pytest.approx([-0.2, 0.3], abs=1e-6)
    held = split_chain(beads, [0, 1], [(0, 1)], curves)
    assert len(held) == 1 and held[0][2].forces[0] > 0.0


def test_contact_in_slow_time_merges_at_the_closing_time():
    """Two beads a gap g apart, the one behind at v1 > v2: they touch at t = g / ((v1 - v2) u)
    and move on together at the common speed (closed form of the level chain)."""
    beads = [Bead(1e-3, 1e-9, 1.0), Bead(1e-3, 1e-9, 1.0)]
    curves = [linear(0.3, 0.5), linear(-0.2, 0.25)]
    u, gap = 2.0, 1e-3
    x = np.array([0.0, 2e-3 + gap])
    model = SlowModel(x, np.zeros(2), np.array([0, 1]), beads, curves, u)
    t_hit = gap / ((0.3 + 0.2) * u)
    v = (0.5 * 0.3 + 0.25 * -0.2) / 0.75
    run = model.run(np.array([0.5 * t_hit, t_hit, 3.0 * t_hit]))
    assert run.x[0] == pytest.approx([0.3 * u * 0.5 * t_hit, x[1] - 0.2 * u * 0.5 * t_hit], rel=1e-9)
    assert run.x[2, 0] == pytest.approx(0.3 * u * t_hit + v * u * 2.0 * t_hit, abs=1e-6 * gap)
    assert run.x[2, 1] - run.x[2, 0] == pytest.approx(2e-3, rel=1e-9)  # touching
    assert run.merges == 1 and run.splits == 0 and len(run.chains) == 1


def test_lanes_link_overlapping_bands_only():
    y = np.array([0.0, 0.5e-3, 5e-3, 10e-3, 11.5e-3])
    r = np.array([1e-3, 0.2e-3, 1e-3, 1e-3, 1e-3])
    assert lanes(y, r).tolist() == [0, 0, 1, 2, 2]


def test_isotonic_is_the_least_squares_monotone_fit():
    y = np.array([0.0, 2.0, 1.0, 3.0, 2.5, 2.5])
    fit = isotonic(y)
    assert fit.tolist() == pytest.approx([0.0, 1.5, 1.5, 2.5 + 1 / 6, 2.5 + 1 / 6, 2.5 + 1 / 6])
    assert (np.diff(fit) >= 0).all() and fit.sum() == pytest.approx(y.sum())


@pytest.mark.slow
def test_dilute_limit_is_each_single_bead_drift(tmp_path, monkeypatch):
    """Beads in lanes of their own move at their species' free drift: the slow model's
    displacement over 1e6 periods, 1-D and 2-D, equals the drift speed of an independent
    single-particle run of each species (the device in m/s) within 1e-9 relative."""
    import sawdrift.mixture.curves as curves_module

    monkeypatch.setattr(curves_module, "cache_dir", lambda: tmp_path)
    data = tomllib.loads((EXAMPLES / "mixture.toml").read_text())
    data.pop("particles")
    scene = sd.bind(sd.scene.build_scene(data))
    radii = (0.2e-3, 1e-3)
    curves = [species_curves(scene.with_updates(**{"device.particle.radius": r}), (1.0,), points=3)
              for r in radii]
    beads = [Bead(r, 0.0, 1.0) for r in radii]
    from sawdrift.lammps.realize import realize

    real = realize(scene)
    u = 2 * math.pi * real.frequency * real.ratio * real.amplitude * real.horizontal
    model = SlowModel(np.array([0.0, 0.0]), np.array([0.0, 0.01]), np.array([0, 1]), beads,
                      curves, u)
    t = 1e6 / real.frequency
    run = model.run(np.array([t]))
    plane = PlaneModel(np.array([0.0, 0.0]), np.array([0.0, 0.01]), np.array([0, 1]), beads,
                       curves, u).run(np.array([0.0, t]))
    for k, r in enumerate(radii):
        single = sd.run(scene.with_updates(**{"device.particle.radius": r,
                                              "numerics.settle": True}))
        speed = single.summary()["drift_speed_m_s"]
        assert run.x[0, k] / t == pytest.approx(speed, rel=1e-9)
        assert plane.x[1, k] / t == pytest.approx(speed, rel=1e-9)  # the 2-D model too


def test_offset_beads_meet_closer_or_pass():
    """Two equal beads approaching each other: offset across the wave by dy < 2R they touch at
    the centre distance sqrt(4 R^2 - dy^2) along x (Pythagoras), by dy >= 2R they pass freely."""
    beads = [Bead(1e-3, 1e-9, 1.0), Bead(1e-3, 1e-9, 1.0)]
    curves = [linear(0.3, 0.5), linear(-0.2, 0.25)]
    u = 1.0
    for dy, meets in ((1.2e-3, True), (2.0e-3, False)):
        model = SlowModel(np.array([0.0, 5e-3]), np.array([0.0, dy]), np.array([0, 1]), beads,
                          curves, u)
        run = model.run(np.array([0.1]))
        assert (run.merges == 1) == meets
        if meets:
            assert run.x[0, 1] - run.x[0, 0] == pytest.approx(math.sqrt(4e-6 - dy**2), rel=1e-9)
        else:
            assert run.x[0].tolist() == pytest.approx([0.3 * 0.1, 5e-3 - 0.2 * 0.1], rel=1e-12)
