"""The bi-harmonic vibration drive (sawdrift.dynamics.drives.biharmonic) against closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

import sawdrift as sd
from sawdrift.scene.schema import Scene

PERIODS = 30


def _biharmonic(model: str, m_star: float = 0.1, **drive: float) -> Scene:
    return Scene.model_validate({"model": model, "particle": {"m_star": m_star},
                                 "numerics": {"periods": PERIODS},
                                 "drive": {"kind": "biharmonic", **drive}})


@pytest.mark.parametrize("model", ["mmd", "material_point"])
def test_without_second_harmonic_it_is_the_linear_orbit_wave_bit_for_bit(model):
    """X2 = Y2 = 0, X1 = r A*, Y1 = A*: the travelling wave with drive.phase = 0, to the last bit."""
    wave = Scene.model_validate({"model": model, "drive": {"phase": 0.0},
                                 "numerics": {"periods": PERIODS}})
    amp, r = wave.drive.amplitude, wave.horizontal_ratio
    plate = _biharmonic(model, amplitude=amp, horizontal=amp * r)
    a, b = sd.run(wave, trajectory=True), sd.run(plate, trajectory=True)
    skip = {"orbit", "wall_time_s", "compile_s", "scene"}
    sa, sb = a.summary(), b.summary()
    assert {k: v for k, v in sa.items() if k not in skip} == {k: v for k, v in sb.items() if k not in skip}
    assert a.drift_velocity.hex() == b.drift_velocity.hex()
    assert np.array_equal(a.trajectory.to_numpy(), b.trajectory.to_numpy(), equal_nan=True)


def _peak_downward_acceleration(y1: float, y2: float) -> float:
    """max over t* of u_y'' / (2 pi)^2 for u_y = Y1 cos(2 pi t*) + Y2 cos(4 pi t*), Y1, Y2 >= 0.

    -(Y1 c + 4 Y2 (2 c^2 - 1)) with c = cos(2 pi t*) in [-1, 1]: a downward parabola in c, its
    vertex c* = -Y1 / (16 Y2) inside [-1, 1] gives 4 Y2 + Y1^2 / (32 Y2), else c = -1 gives Y1 - 4 Y2.
    """
    if y2 > 0.0 and y1 <= 16.0 * y2:
        return 4.0 * y2 + y1 * y1 / (32.0 * y2)
    return y1 - 4.0 * y2 if y2 > 0.0 else y1


@pytest.mark.parametrize(("y1", "y2"), [(0.1, 0.05), (0.2, 0.0), (0.0, 0.03)])
def test_rigid_point_loses_contact_where_the_peak_downward_acceleration_exceeds_g(y1, y2):
    """N* = 1 - m* u_y'': contact is lost iff m* (2 pi)^2 peak > 1 (closed form above)."""
    m_c = 1.0 / ((2.0 * math.pi) ** 2 * _peak_downward_acceleration(y1, y2))
    below = sd.run(_biharmonic("material_point", 0.97 * m_c, amplitude=y1, second=y2))
    above = sd.run(_biharmonic("material_point", 1.03 * m_c, amplitude=y1, second=y2))
    assert not below.contact_lost
    assert above.contact_lost


def test_second_harmonic_transports_on_a_horizontal_vibration_alone():
    """A symmetric horizontal vibration (X2 = 0) gives no drift; the second harmonic breaks the
    symmetry t* -> t* + 1/2, x -> -x, and the sign of X2 sets the direction (Blekhman)."""
    base = {"amplitude": 0.0, "horizontal": 0.3}
    sym = sd.run(_biharmonic("mmd", 1.0, **base))
    plus = sd.run(_biharmonic("mmd", 1.0, **base, second_horizontal=0.1, second_horizontal_phase=90.0))
    minus = sd.run(_biharmonic("mmd", 1.0, **base, second_horizontal=-0.1,
                               second_horizontal_phase=90.0))
    # the mirror of ``plus`` shifted by half a period is ``minus``: opposite drifts once the
    # start-up (ramp, initial rest) is forgotten; the symmetric vibration only keeps its transient
    assert abs(sym.drift_velocity) < 0.01 * abs(plus.drift_velocity)
    assert plus.drift_velocity == pytest.approx(-minus.drift_velocity, rel=0.02)


def test_an_inclined_fundamental_transports_where_a_horizontal_one_does_not():
    """One harmonic, no second: along x alone the half-period shift with the mirror x -> -x maps
    the motion onto itself (no drift but the start-up's transient: 7e-6 a0 f over 30 periods),
    inclined (Y1 > 0) gravity breaks it and the point and mmd drift (the vibratory conveyor:
    -0.137 and -0.351 a0 f at m* = 0.1)."""
    for model in ("material_point", "mmd"):
        flat = sd.run(_biharmonic(model, 0.1, amplitude=0.0, horizontal=0.3))
        tilted = sd.run(_biharmonic(model, 0.1, amplitude=0.1, horizontal=0.3))
        assert abs(tilted.drift_velocity) > 0.1
        assert abs(flat.drift_velocity) < 1e-3 * abs(tilted.drift_velocity)
