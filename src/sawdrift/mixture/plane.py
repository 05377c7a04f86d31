"""Beads on the plate in 2-D (x along the wave, y across it), moved in slow time by their drifts
under the loads of the beads they touch.

Every bead of species s rests on the plate with its centre at the height z_s = R_s - a0_s and
moves at its steady drift under the loads on it (overdamped slow dynamics: a bead reaches its
steady drift within a few hundred periods, far less than it takes to move by a diameter):

* along the wave, V_x = V_s(L_x, N): the force-velocity curve of its species (:mod:`.curves`)
  read backwards at its tangential load L_x under its normal load N, the same curves and the same
  interpolation (linear in V, linear in log N at a fixed V) as the chains of :mod:`.chains`;
* across the wave, where nothing drives it, V_y = M_perp L_y with the transverse mobility

      M_perp = u / N * (v(l+) - v(l-)) / (l+ - l-),   l = L_x / N,  l+ = max(l, h), l- = min(l, -h),

  the secant of the same curve through the free drift (h: one sample of the curve's loads; the
  slope at zero load for small loads). This is an assumption: the single-bead engine is planar
  and cannot compute a sideways response. It says that the bead answers a sideways load as it
  answers a load along the wave of the same size near its present state: a bead that slides
  under a load slides sideways as easily, a bead pressed until it sticks does not. ``perp``
  scales it (the sensitivity of a result to it is measured in docs/mixtures.md).

Contacts. Two beads i, j whose centres (x, y, z) are closer than R_i + R_j overlap by delta and
push each other apart along the 3-D normal n (i -> j) with P = k delta, k = c W_min / delta_tol:
a stiff penalty spring whose overlap stays near delta_tol (a fraction ``tolerance`` of the
smallest radius) at a pair force of c = 4 weights of the lighter bead. The horizontal part of P n
is the pair's load on each bead (x and y), its vertical part presses the lower bead onto the plate
and lifts the higher one (N_j = W_j - P n_z, N_i = W_i + P n_z). A head-on contact (dy = 0) has no
y part: a line of beads along the wave stays a line, and moves as the 1-D chains do.

Time steps (:func:`.plane_step.integrate`). A bead that touches nothing moves at its free drift,
exactly, over any step. Beads that touch form clusters; each step is a backward Euler step,
d = dt V(x + d), solved by Newton's method per cluster from the linearly implicit step
(I - dt J) d = dt V, with J the derivative of the drifts with respect to the positions through
the pair forces: stable for any stiffness, and a chain moving at a common speed is an exact fixed
point (a translation changes no force). A step is accepted when Newton's method has converged
(no bead off by more than 5e-2 delta_tol), touching beads have moved by at most ``slide`` smallest
radii relative to each other (the resolution of sliding round a bead) and every bead by at most a
quarter of the neighbour list's skin (or of the nearest gap outside the list, when larger);
otherwise it is halved. Candidate pairs come from a sweep along x, rebuilt when a bead has moved
by that quarter.

Beyond the loads a species' curves sampled a bead slides (:data:`.plane_curves.SLIDE`), so that
no bead can hold more than its friction limit.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from . import plane_kernel as kernel
from .chains import Bead
from .curves import SpeciesCurves
from .plane_step import integrate

__all__ = ["PUSHED_APART", "TOLERANCE", "PlaneModel", "PlaneRun", "clusters", "curve_arrays", "free_speeds",
           "jitter", "worst_overlap"]

#: delta_tol over the smallest radius (:class:`PlaneModel`'s default ``tolerance``)
TOLERANCE = 1e-2

#: overlaps up to this many tolerances (delta_tol) are pushed apart in the first steps (a jitter
#: may press touching beads together); a larger one is refused
PUSHED_APART = 10.0


#: pair force (in weights of the lighter bead) at which the overlap is the tolerance
PRESS = 4.0


def curve_arrays(curves: list[SpeciesCurves]) -> tuple[np.ndarray, ...]:
    """The species' regular speed tables padded into arrays for the kernel (module docstring of
    :mod:`.plane_curves`): table, v0, dv, lo, hi, log n, curves per species, load step h."""
    grids = [c.speed_grid() for c in curves]
    ncurve = max(c.normal.size for c in curves)
    size = grids[0][0].size
    table = np.zeros((len(curves), size, ncurve))
    lo = np.zeros((len(curves), ncurve), dtype=np.int64)
    hi = np.zeros((len(curves), ncurve), dtype=np.int64)
    logn = np.zeros((len(curves), ncurve))
    v0 = np.array([g[0][0] for g in grids])
    dv = np.array([g[0][1] - g[0][0] for g in grids])
    for s, (c, (_, tab)) in enumerate(zip(curves, grids, strict=True)):
        m = c.normal.size
        table[s, :, :m] = tab
        logn[s, :m] = np.log(c.normal)
        for k in range(m):
            col = tab[:, k]
            above = np.flatnonzero(col > col[0])
            below = np.flatnonzero(col < col[-1])
            lo[s, k] = max(int(above[0]) - 1, 0) if above.size else 0
            hi[s, k] = min(int(below[-1]) + 1, size - 1) if below.size else size - 1
    nc = np.array([c.normal.size for c in curves], dtype=np.int64)
    hstep = np.array([float(np.min(np.diff(c.loads[0]))) for c in curves])
    return table, v0, dv, lo, hi, logn, nc, hstep


def clusters(x: np.ndarray, y: np.ndarray, kinds: np.ndarray, beads: list[Bead]) -> list[list[int]]:
    """Groups of beads that touch (overlap > 0), linked; lone beads are groups of one."""
    rad = np.array([b.radius for b in beads])
    hgt = np.array([b.height for b in beads])
    pi, pj = kernel.build_pairs(x, y, kinds.astype(np.int64), rad, hgt, 0.0)
    parent = np.arange(x.size)

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i, j in zip(pi, pj, strict=True):
        parent[root(int(i))] = root(int(j))
    groups: dict[int, list[int]] = {}
    for i in range(x.size):
        groups.setdefault(root(i), []).append(i)
    return sorted(groups.values())


@dataclass
class PlaneRun:
    """Positions at the sample times, the final drifts and the cost."""

    times: np.ndarray  # s
    x: np.ndarray  # (samples, beads), m
    y: np.ndarray  # (samples, beads), m
    kinds: np.ndarray
    speeds: np.ndarray  # drift ratio along the wave of each bead over the last sample interval
    speeds_y: np.ndarray  # the same across the wave
    steps: int
    rejected: int
    builds: int
    solves: int
    max_overlap: float  # largest overlap over the run, in units of the tolerance
    wall_time_s: float
    chains: list[list[int]] = field(default_factory=list)  # beads touching at the end, linked


class PlaneModel:
    """The 2-D slow motion of beads on the plate (module docstring).

    Parameters
    ----------
    x, y, kinds, beads, curves, surface_speed
        The placement, species and curves, as for the 1-D model (:class:`.events.SlowModel`).
    tolerance
        delta_tol over the smallest radius: the overlap at a pair force of 4 lighter weights.
    perp
        Factor on the transverse mobility (1: the assumption of the module docstring).
    slide
        Largest displacement of touching beads relative to each other per step, in smallest radii.
    skin
        Neighbour-list skin in smallest radii.
    """

    def __init__(self, x: np.ndarray, y: np.ndarray, kinds: np.ndarray, beads: list[Bead],
                 curves: list[SpeciesCurves], surface_speed: float, *, tolerance: float = TOLERANCE,
                 perp: float = 1.0, slide: float = 0.1, skin: float = 6.0) -> None:
        self.x = np.array(x, dtype=float)
        self.y = np.array(y, dtype=float)
        self.kinds = np.asarray(kinds, dtype=np.int64)
        self.beads, self.curves, self.u = beads, curves, surface_speed
        self.rad = np.array([b.radius for b in beads])
        self.hgt = np.array([b.height for b in beads])
        self.wgt = np.array([b.weight for b in beads])
        r_min = float(self.rad[np.unique(self.kinds)].min()) if self.kinds.size else 1.0
        self.tol = tolerance * r_min
        self.stiff = PRESS / self.tol
        self.perp, self.slide, self.skin = perp, slide * r_min, skin * r_min
        self.arrays = curve_arrays(curves)
        self.free = np.array([c.free for c in curves])
        self._check_overlap()

    def _check_overlap(self) -> None:
        ov, i, j = worst_overlap(self.x, self.y, self.kinds, self.rad, self.hgt)
        if ov > PUSHED_APART * self.tol:  # a jitter may press touching beads together
            raise ValueError(f"beads {i} and {j} overlap by {ov:.3g} m")

    def run(self, times: np.ndarray, max_steps: int = 20_000_000) -> PlaneRun:
        """Move the beads to every time of ``times`` (s, non-decreasing, from 0)."""
        t0 = time.perf_counter()
        times = np.asarray(times, dtype=float)
        n = self.x.size
        out_x, out_y = np.empty((times.size, n)), np.empty((times.size, n))
        out_u, stats = np.zeros((2, n)), np.zeros(5)
        status = integrate(self.x, self.y, self.kinds, self.rad, self.hgt, self.wgt,
                           *self.arrays, self.free, self.u, self.perp, self.stiff, self.tol,
                           self.skin, self.slide, times, out_x, out_y, out_u, stats,
                           max_steps)
        if status == 1:
            raise RuntimeError(f"more than {max_steps} steps: the beads are jammed")
        if status == 2:
            raise RuntimeError("a step could not be made small enough (the contacts chatter)")
        if times.size > 1 and times[-1] > times[-2]:
            span = (times[-1] - times[-2]) * self.u
            vx, vy = (out_x[-1] - out_x[-2]) / span, (out_y[-1] - out_y[-2]) / span
        else:
            vx, vy = out_u[0] / self.u, out_u[1] / self.u
        return PlaneRun(times=times, x=out_x, y=out_y, kinds=self.kinds.copy(), speeds=vx,
                        speeds_y=vy, steps=int(stats[0]), rejected=int(stats[1]),
                        builds=int(stats[2]), solves=int(stats[3]), max_overlap=float(stats[4]),
                        wall_time_s=time.perf_counter() - t0,
                        chains=clusters(self.x, self.y, self.kinds, self.beads))


def worst_overlap(x: np.ndarray, y: np.ndarray, kinds: np.ndarray, rad: np.ndarray,
                  hgt: np.ndarray) -> tuple[float, int, int]:
    """(largest overlap in m, bead i, bead j > i) over the touching pairs of a placement ((0, -1,
    -1) when none touch); ``rad`` and ``hgt`` per species, as :class:`PlaneModel` keeps them."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    pi, pj = kernel.build_pairs(x, y, kinds, rad, hgt, 0.0)
    worst = (0.0, -1, -1)
    for i, j in zip(pi, pj, strict=True):
        ov = float(kernel.pair_state(x, y, kinds, rad, hgt, i, j)[0])
        if ov > worst[0]:
            worst = (ov, int(min(i, j)), int(max(i, j)))
    return worst


def jitter(y: np.ndarray, size: float, seed: int) -> np.ndarray:
    """``y`` moved across the wave by ``size`` times a standard normal number (seeded)."""
    return y + size * np.random.default_rng([seed, 38]).standard_normal(y.size)


def free_speeds(curves: list[SpeciesCurves]) -> list[float]:
    """Each species' free drift ratio in the 2-D model (no load, N = W): the curves' own sample,
    as in the 1-D model, which the single-particle runs check."""
    return [c.free for c in curves]
