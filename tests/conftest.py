"""Shared fixtures and helpers for the test suite."""

from __future__ import annotations

import math

import pytest

import sawdrift as sd


def point_scene(gz: float, gx: float | None = None, m_star: float = 0.1, **numerics) -> sd.Scene:
    """A material-point wave scene with given Gz = 4 pi^2 m* A* and Gx = r Gz (mu = 0.1)."""
    amp = gz / (4.0 * math.pi**2 * m_star)
    drive = {"amplitude": amp}
    if gx is not None:
        drive["horizontal_ratio"] = gx / gz
    return sd.Scene(
        model="material_point", particle={"m_star": m_star}, drive=drive, numerics=numerics
    )


@pytest.fixture
def make_point_scene():
    return point_scene
