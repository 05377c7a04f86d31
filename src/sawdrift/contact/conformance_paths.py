"""The (a*, b*) paths the conformance suite drives a contact law through, and their loop work.

Each straight side is traversed in unit time; the velocities are the backward differences, so a
law that depends on velocities sees the velocity of the step it takes (see :class:`Path`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..scene.parts import polyline
from .base import ContactModel
from .history import ContactHistory

#: samples per straight side of a cycle
SIDE = 400
#: largest a* of the large random histories (the small ones stop at 3)
LARGE_A = 20.0


@dataclass(frozen=True)
class Path:
    """A sampled (a*, b*) history with the velocities passed at each step.

    Each straight side is traversed in unit time, ``dt`` = 1 / samples per side; the
    velocities are the backward differences (x_k - x_(k-1)) / dt, the velocity of the straight
    step that ends at sample k (the first sample is at rest).
    """

    a: np.ndarray
    b: np.ndarray
    adot: np.ndarray
    bdot: np.ndarray
    dt: float

    def __getitem__(self, sl: slice) -> Path:
        return Path(self.a[sl], self.b[sl], self.adot[sl], self.bdot[sl], self.dt)

    def still(self) -> Path:
        """The same samples at zero velocity (a quasi-static drive)."""
        return Path(self.a, self.b, np.zeros_like(self.a), np.zeros_like(self.b), self.dt)

    def drive(self, history: ContactHistory) -> tuple[np.ndarray, np.ndarray]:
        """Advance ``history`` through the samples; N*(k), T*(k)."""
        return history.drive(self.a, self.b, self.adot, self.bdot)


def path(vertices: list[tuple[float, float]], per_side: int = SIDE) -> Path:
    """The straight sides through ``vertices``, ``per_side`` samples each, in unit time each."""
    a, b = polyline(vertices, per_side)
    return Path(a, b, np.diff(a, prepend=a[0]) * per_side, np.diff(b, prepend=b[0]) * per_side,
                1.0 / per_side)


def cycles() -> dict[str, list[tuple[float, float]]]:
    """Closed (a*, b*) cycles of the passivity check, each as its vertices (first = last)."""
    theta = np.linspace(0.0, 2.0 * np.pi, 17)
    ellipse = [(1.5 + 0.5 * math.cos(t), 0.3 * math.sin(t)) for t in theta]
    return {
        "normal": [(0.5, 0.0), (2.5, 0.0), (0.5, 0.0)],
        "rectangle": [(1.0, 0.0), (1.0, 0.2), (2.0, 0.2), (2.0, 0.0), (1.0, 0.0)],
        "diamond": [(1.5, -0.3), (2.0, 0.0), (1.5, 0.3), (1.0, 0.0), (1.5, -0.3)],
        "ellipse": ellipse,
        "full_slip": [(1.0, 0.0), (1.0, 3.0), (2.0, 3.0), (2.0, -3.0), (1.0, -3.0), (1.0, 0.0)],
        "contact_loss": [(1.0, 0.0), (1.0, 0.5), (-0.2, 0.5), (-0.2, -0.5), (1.5, -0.5),
                         (1.0, 0.0)],
        "large": [(5.0, 0.0), (5.0, 1.5), (15.0, 1.5), (15.0, 0.0), (5.0, 0.0)],
        # in and out of contact along a* alone: an adhesive law's hysteresis (made at a* = 0,
        # broken below it) must lose energy here, not make it
        "normal_contact_loss": [(1.0, 0.0), (-0.4, 0.0), (1.0, 0.0)],
    }


def loop_work_parts(model: ContactModel, vertices: list[tuple[float, float]], laps: int = 10,
                    engine: str = "compiled") -> tuple[np.ndarray, ...]:
    """Normal and tangential loop work of each lap, its gross work and its quadrature error.

    Trapezoidal sums of N* da* and T* db* over each lap (the cycle driven at its velocities
    after a straight approach from (0, 0)), of |N*| |da*| + |T*| |db*|, and the rule's error
    estimate, sum of |da*| |d2 N*| / 12 + |db*| |d2 T*| / 12 (its local error h^3 f'' / 12, f''
    from the second differences d2).
    """
    start = vertices[0]
    approach, lap = path([(0.0, 0.0), start]), path(vertices)
    n0, per = approach.a.size - 1, lap.a.size - 1
    full = Path(*(np.concatenate([x, *[y[1:]] * laps]) for x, y in
                  ((approach.a, lap.a), (approach.b, lap.b), (approach.adot, lap.adot),
                   (approach.bdot, lap.bdot))), lap.dt)
    n, t = full.drive(ContactHistory(model, engine))
    out = np.empty((4, laps))
    for k in range(laps):
        sl = slice(n0 + k * per, n0 + (k + 1) * per + 1)
        da, db = np.diff(full.a[sl]), np.diff(full.b[sl])
        n_mid, t_mid = 0.5 * (n[sl][1:] + n[sl][:-1]), 0.5 * (t[sl][1:] + t[sl][:-1])
        quad = (np.sum(np.abs(da[1:] * np.diff(n[sl], 2))) + np.sum(np.abs(db[1:] * np.diff(t[sl], 2))))
        out[:, k] = (np.sum(n_mid * da), np.sum(t_mid * db),
                     np.sum(np.abs(n_mid * da)) + np.sum(np.abs(t_mid * db)), quad / 12.0)
    return out[0], out[1], out[2], out[3]


def loop_works(model: ContactModel, vertices: list[tuple[float, float]], laps: int = 10,
               engine: str = "compiled") -> tuple[np.ndarray, np.ndarray]:
    """Loop work (closed integral of N* da* + T* db*) of each lap, and each lap's gross work."""
    normal, tangential, gross, _ = loop_work_parts(model, vertices, laps, engine)
    return normal + tangential, gross


def random_history(seed: int, n: int = 600, a_max: float = 3.0) -> Path:
    """A random piecewise-linear (a*, b*) walk that loses and regains contact and reaches a_max.

    40 sides; a* walks in [-0.4, 3] and b* freely, both then scaled by a_max / 3.
    """
    rng = np.random.default_rng(seed)
    av = np.clip(np.cumsum(rng.normal(0.0, 0.25, 40)) + 1.0, -0.4, 3.0)
    av[int(np.argmax(av))] = 3.0
    bv = np.cumsum(rng.normal(0.0, 0.4, 40))
    s = a_max / 3.0
    av = np.clip(av * s, -0.4, a_max)
    return path([(0.0, 0.0), *zip(av.tolist(), (bv * s).tolist(), strict=True)], n // 40)


def histories(seeds: range | list[int]) -> list[Path]:
    """Random histories of each seed, one reaching a* = 3 and one reaching :data:`LARGE_A`."""
    return [random_history(s, a_max=a_max) for s in seeds for a_max in (3.0, LARGE_A)]
