"""The 2-D slow model (sawdrift.mixture.plane): a line along the wave against the 1-D chain
solver, the dilute limit, a small bead sliding round a large one, and sorting on a plate."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

import sawdrift as sd
import sawdrift.mixture.sort as sort_module
from sawdrift.mixture.chains import Bead, contact_geometry, solve_chain
from sawdrift.mixture.curves import SpeciesCurves
from sawdrift.mixture.events import SlowModel
from sawdrift.mixture.plane import PlaneModel, free_speeds
from sawdrift.mixture.sort import sort_mixture

from .cli_call import call

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

SMALL = Bead(0.2e-3, 1.1e-10, 2.58e-6)
LARGE = Bead(1e-3, 1.6e-9, 3.23e-4)


def curves(v0: list[float], k: list[float], normal: list[float], radius: float,
           weight: float) -> SpeciesCurves:
    """Curves l = L / N = k_i tanh(V - v0_i) / 0.3 on normal load i (non-linear, N-dependent)."""
    ells = np.linspace(-0.27, 0.27, 19)
    speeds = np.array([v + np.arctanh(np.clip(ells * 0.3 / kk, -0.99, 0.99))
                       for v, kk in zip(v0, k, strict=True)])
    return SpeciesCurves(radius=radius, weight=weight, normal=np.array(normal),
                         loads=np.tile(ells, (len(normal), 1)), speeds=speeds, raw=speeds,
                         regimes=(("x",) * ells.size,) * len(normal), mu=0.3, wall_time_s=0.0)


def plate_curves() -> list[SpeciesCurves]:
    """A light fast species that a pressing load slows down, and a heavy one that drifts back."""
    small = curves([0.38, 0.1, -0.02, -0.05], [0.1, 0.2, 0.3, 0.3], [1.0, 2.0, 4.0, 16.0],
                   SMALL.radius, SMALL.weight)
    large = curves([-0.40, -0.35, -0.32], [0.12, 0.1, 0.09], [0.5, 0.8, 1.1], LARGE.radius,
                   LARGE.weight)
    return [small, large]


def touching(kinds: list[int]) -> np.ndarray:
    """x of beads in a line along the wave, each touching the one before (no force)."""
    beads = [SMALL, LARGE]
    x = [beads[kinds[0]].radius]
    for a, b in zip(kinds[:-1], kinds[1:], strict=True):
        x.append(x[-1] + contact_geometry(beads[a], beads[b])[0])
    return np.array(x)


@pytest.mark.parametrize("kinds", [[0] * 10 + [1], [0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 0, 1]])
def test_line_along_the_wave_moves_as_the_1d_chains(kinds):
    """Beads on one line along the wave (dy = 0: no sideways force) end up at the speeds the
    1-D chain model gives them (the balance of :func:`solve_chain` and its splits), within 1 %
    of the speed scale."""
    beads, cv = [SMALL, LARGE], plate_curves()
    u = 4e-5
    x = touching(kinds)
    t = 0.5e-3 / u
    line = SlowModel(x, np.zeros(x.size), np.array(kinds), beads, cv, u).run(np.array([0.0, t]))
    plane = PlaneModel(x, np.zeros(x.size), np.array(kinds), beads, cv, u).run(
        np.array([0.0, 0.8 * t, t]))
    assert np.all(plane.y == 0.0)
    assert plane.speeds == pytest.approx(line.speeds, abs=0.01 * 0.4)
    if kinds[-1] == 1 and kinds.count(1) == 1:  # one chain: the closed balance
        edges = [(i, i + 1) for i in range(len(kinds) - 1)]
        common = solve_chain(beads, kinds, edges, cv).speed
        assert plane.speeds == pytest.approx(common, rel=1e-2)
        assert cv[1].free < common < 0.0  # small beads carried back, the large one slowed


def test_dilute_beads_move_at_their_free_drift_exactly():
    """Beads that never touch move on straight lines at their free drifts (no step error)."""
    beads, cv = [SMALL, LARGE], plate_curves()
    u = 4e-5
    x = np.array([0.0, 0.0, 10e-3, 10e-3])
    y = np.array([0.0, 5e-3, 10e-3, 15e-3])  # lanes of their own: they pass each other
    kinds = np.array([0, 1, 1, 0])
    t = np.array([0.0, 3.0, 100.0, 1e4])
    run = PlaneModel(x, y, kinds, beads, cv, u).run(t)
    free = np.array(free_speeds(cv))[kinds]
    assert free == pytest.approx([0.38, -0.32 - 0.0, -0.32, 0.38], abs=0.03)
    for k, tk in enumerate(t):
        assert run.x[k] == pytest.approx(x + free * u * tk, rel=1e-12, abs=1e-15)
        assert np.all(run.y[k] == y)
    assert run.speeds == pytest.approx(free, rel=1e-9)
    assert max(len(c) for c in run.chains) == 1


def test_small_bead_slides_round_a_large_one():
    """A small bead running into a large one a little off its centre line is pushed sideways by
    the y part of the contact normal, slides round it and leaves ahead of it, offset across the
    wave by the horizontal contact distance sqrt((R_s + R_L)^2 - dz^2) (the normal ends up
    across the wave), then moves at its free drift again."""
    beads, cv = [SMALL, LARGE], plate_curves()
    u = 4e-5
    reach = contact_geometry(SMALL, LARGE)[0]
    x = np.array([0.0, 3e-3])
    y = np.array([0.0, 1e-5])
    t = np.linspace(0.0, 0.2 / u, 41)
    run = PlaneModel(x, y, np.array([0, 1]), beads, cv, u).run(t)
    free = free_speeds(cv)
    assert run.x[-1, 0] > run.x[-1, 1] + reach  # ahead, clear of it
    dy = abs(run.y[-1, 0] - run.y[-1, 1])
    assert dy == pytest.approx(reach, rel=2e-2)
    assert run.speeds == pytest.approx(free, abs=1e-9)
    slowed = np.abs(np.diff(run.x[:, 0]) - free[0] * u * np.diff(t)) > 1e-9 * u * t[1]
    assert slowed.any()  # it did touch and was slowed on the way


def test_dy_zero_head_on_stays_behind():
    """Exactly head-on (dy = 0) the sideways force vanishes: the small bead stays behind the
    large one and is carried back with it, as in 1-D (the unstable equilibrium a placement's
    jitter breaks)."""
    beads, cv = [SMALL, LARGE], plate_curves()
    u = 4e-5
    run = PlaneModel(np.array([0.0, 3e-3]), np.zeros(2), np.array([0, 1]), beads, cv,
                     u).run(np.array([0.0, 0.1 / u, 0.2 / u]))
    assert run.speeds[0] == pytest.approx(run.speeds[1], abs=1e-6)
    assert run.speeds[0] < 0.0


def plate() -> tuple[sd.Scene, dict]:
    data = tomllib.loads((EXAMPLES / "mixture.toml").read_text())
    particles = data.pop("particles")
    return sd.bind(sd.scene.build_scene(data)), particles


def test_plane_sorts_rows_that_do_not_sort_in_1d(monkeypatch):
    """Rows of touching beads whose species drift in opposite directions: in 2-D the small beads
    get round the large ones and the purity of the best interface reaches 0.95 in every
    placement; in 1-D lanes the small beads behind a large one are carried back with it and
    the same rows stay mixed."""
    scene, particles = plate()
    monkeypatch.setattr(sort_module, "curves_for", lambda scene, radii, **kw: plate_curves())
    table = {**particles, "count": 24, "row": 6}
    plane = sort_mixture(scene, table, seeds=2, periods=1e8, samples=4, target=0.95)
    line = sort_mixture(scene, table, seeds=2, periods=1e8, samples=4, target=0.95,
                        geometry="line")
    assert np.isfinite(plane.times_to_target()).all()
    assert plane.measures["purity"][:, -1] == pytest.approx(1.0)
    assert line.measures["purity"][:, -1].max() < 0.95
    assert plane.summary()["geometry"] == "plane" and "assumed" in plane.summary()


def test_bad_geometry_is_a_scene_error():
    scene, particles = plate()
    with pytest.raises(sd.errors.SceneError, match="--geometry = 'disk'"):
        sort_mixture(scene, particles, seeds=1, geometry="disk")
    assert math.isfinite(LARGE.height)


@pytest.mark.parametrize("geometry", ["plane", "line"])
def test_sort_command_reports_and_plots_both_geometries(geometry, tmp_path, monkeypatch, capsys):
    """`sawdrift sort` prints the geometry, its assumption and the time to the purity, and
    writes sort.json and sort.png, for both geometries."""
    import json

    monkeypatch.setattr(sort_module, "curves_for", lambda scene, radii, **kw: plate_curves())
    text = (EXAMPLES / "mixture.toml").read_text().replace("count = 200", "count = 24")
    scene = tmp_path / "small.toml"
    scene.write_text(text.replace("row = 20", "row = 6"))
    status, out, _ = call(monkeypatch, capsys, "sort", str(scene), "--seeds", "2", "--until",
                          "1e8", "--geometry", geometry, "-o", str(tmp_path / "out"))
    assert status == 0
    assert ("in 2-D on the plate" in out) == (geometry == "plane")
    assert "model: " + ("2-D" if geometry == "plane" else "1-D") in out
    assert "time to purity 0.9:" in out
    data = json.loads((tmp_path / "out" / "sort.json").read_text())
    assert data["geometry"] == geometry
    assert (data["time_to_target"]["reached"] == 2) == (geometry == "plane")
    assert (tmp_path / "out" / "sort.png").stat().st_size > 10_000


def test_explicit_touching_positions_run_in_2d(monkeypatch):
    """Beads placed by hand touching off the axes (a small bead at 45 degrees to a large one):
    the jitter across the wave may press them together (by a fraction of a micrometre), which
    the 2-D model accepts and pushes apart; the small bead then slides off and runs ahead."""
    scene, particles = plate()
    monkeypatch.setattr(sort_module, "curves_for", lambda scene, radii, **kw: plate_curves())
    from sawdrift.lammps.placement import parse_particles, species_of

    small, large = (Bead(sp.radius, sp.a0, 1.0) for sp in species_of(scene, parse_particles(
        particles)))
    reach = contact_geometry(small, large)[0] / math.sqrt(2.0) * (1.0 + 1e-12)
    table = {k: v for k, v in particles.items() if k not in ("count", "packing", "row")}
    table["positions"] = [["5 mm", "5 mm", 1], [f"{5e-3 - reach} m", f"{5e-3 - reach} m", 0]]
    result = sort_mixture(scene, table, periods=1e7, samples=2)
    run = result.runs[0]
    assert run.x[-1, 1] > run.x[-1, 0]  # the small bead (index 1) ahead of the large one


def test_a_jitter_that_presses_rows_together_is_refused_before_the_curves(monkeypatch):
    """Rows 1.05 diameters apart moved across the wave by 0.3 small radii press neighbouring
    beads together by up to about half a small radius, five times what the 2-D model pushes
    apart (0.1): one line naming --jitter and particles.spacing, before any curve is computed
    (it ended in an internal failure, 'beads 20 and 40 overlap'); 0.01 small radii runs."""
    scene, particles = plate()
    computed = []

    def fake_curves(scene, radii, **kw):
        computed.append(radii)
        return plate_curves()

    monkeypatch.setattr(sort_module, "curves_for", fake_curves)
    with pytest.raises(sd.errors.SceneError, match=r"--jitter = 0.3: .*particles\.spacing"):
        sort_mixture(scene, {**particles, "spacing": 1.05}, seeds=2, periods=1e3, samples=2,
                     jitter_radii=0.3)
    assert computed == []
    table = {**particles, "count": 24, "row": 6, "spacing": 1.05}
    result = sort_mixture(scene, table, seeds=1, periods=1e3, samples=2, jitter_radii=0.01)
    assert result.runs[0].max_overlap < 10.0


@pytest.mark.parametrize("n", [1.0, 1.3, 2.0, 3.2, 9.0, 16.0])
def test_speed_is_the_inverse_of_load_between_the_sampled_normal_loads(n):
    """speed(l, n) reads back the drift ratio that load(v, n) was asked at, on a sampled normal
    load and between two (there it interpolated the two curves' speeds at a fixed load, where
    load interpolates their loads at a fixed speed: the small bead's curves here differ in
    slope and offset, and it read back speeds 0.02 to 0.1 off). Within 1e-5: load() reads the
    curves off a regular table of 2001 speeds."""
    small = plate_curves()[0]
    for v in (-0.3, -0.05, 0.0, 0.05, 0.2):
        ell = float(small.load(v, n)) / n
        assert small.speed(ell, n) == pytest.approx(v, abs=1e-5)


@pytest.mark.parametrize(("option", "value"), [("--jitter", "0.5"), ("--transverse", "3")])
def test_plane_only_options_with_lanes_are_refused(option, value, monkeypatch, capsys):
    """sort --geometry line took --jitter and --transverse and ignored them without a word."""
    code, _, err = call(monkeypatch, capsys, "sort", str(EXAMPLES / "mixture.toml"),
                        "--geometry", "line", option, value, "--seeds", "1", "--until", "1e3")
    assert code == 2 and f"{option} belongs to --geometry plane" in err


def test_a_fraction_rounded_to_one_bead_of_each_species_is_said(monkeypatch, capsys):
    """count 10, fraction 0.01 placed 1 small and 9 large beads without a word (round(0.1) = 0,
    each species keeps at least one); the command says so on stderr, and a fraction written as
    nan is not a finite number (it was "Input should be less than 1" alone)."""
    code, out, err = call(monkeypatch, capsys, "sort", str(EXAMPLES / "mixture.toml"),
                          "--seeds", "1", "--until", "1e3", "--set", "particles.count=10",
                          "--set", "particles.fraction=0.01")
    assert code == 0 and "0.1 of a bead of the first radius" in err and "1 and 9" in err, err
    assert "R = 0.2 mm (1)" in out and "R = 1 mm (9)" in out
    code, _, err = call(monkeypatch, capsys, "sort", str(EXAMPLES / "mixture.toml"),
                        "--set", "particles.fraction=nan")
    assert code == 2 and "particles.fraction = 'nan' is not a finite number" in err, err
    assert len(err.strip().splitlines()) == 1
