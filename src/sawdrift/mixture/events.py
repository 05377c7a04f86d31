"""Beads in lanes along the wave, moved in slow time from event to event: contacts, merges, splits.

Between events every bead moves at the common drift of its chain (a lone bead: its free drift),
so positions are linear in time and the next event is the first contact between two beads of
different chains that approach each other (the one behind faster). At a contact the two chains
merge into one; the merged chain's balance (:func:`.chains.split_chain`) gives its common speed,
or splits it where a pair force would pull (the part in front runs ahead). Nothing else changes a
speed, so the cost grows with the number of contacts, not with the number of wave periods.

Geometry (1-D along the wave). Two beads meet only if their bands [y - R, y + R] across the wave
overlap; then they cannot pass each other, and they touch at the centre distance along x
sqrt((R_a + R_b)^2 - (z_b - z_a)^2 - (y_b - y_a)^2) (:func:`.chains.contact_geometry`). Beads
whose bands do not overlap pass each other freely. Every bead moves along x only, and a pair
force acts through the x and z parts of its contact normal (its y part is left out). A bead can
touch any bead it meets, not only its neighbour along x (a 0.2 mm bead between two 1 mm beads
lets them touch each other). The beads of one *lane* (:func:`lanes`: overlapping bands, linked)
are those that can interact at all, directly or through others. The plate is an open line: the
bed is a piece of a plate larger than it, with free plate around it.

What 2-D (x and y) would add: the y part of an off-centre contact's normal, which pushes the
two beads apart sideways, so that a small bead pushed by (or pushing) a large one slides around
it instead of staying behind it; beads then change lanes, and the order along x of beads that
meet could change. In 1-D a small bead that meets a large one stays behind it for ever.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .chains import Bead, contact_geometry, split_chain
from .curves import SpeciesCurves

__all__ = ["SlowRun", "SlowModel", "lanes"]

#: a gap below this (m) counts as touching
TOUCH = 1e-13


def lanes(y: np.ndarray, radius: np.ndarray) -> np.ndarray:
    """Lane index of each bead: beads whose bands [y - R, y + R] overlap, linked, share a lane."""
    order = np.argsort(y, kind="stable")
    lane = np.empty(y.size, dtype=int)
    current, top = -1, -math.inf
    for i in order:
        if y[i] - radius[i] >= top:
            current += 1
            top = -math.inf
        lane[i] = current
        top = max(top, y[i] + radius[i])
    return lane


@dataclass
class SlowRun:
    """Positions at the sample times, and what happened in between."""

    times: np.ndarray  # s
    x: np.ndarray  # (samples, beads), m
    kinds: np.ndarray
    lane: np.ndarray
    merges: int
    splits: int
    wall_time_s: float
    speeds: np.ndarray  # drift ratio of each bead at the end
    chains: list[list[int]] = field(default_factory=list)  # beads of each chain at the end
    saturated: int = 0  # chain balances that needed a load beyond the curves


@dataclass
class _Chain:
    members: list[int]
    edges: list[tuple[int, int, float]]  # (behind, front, offset across the wave)
    speed: float


class SlowModel:
    """The event-driven motion of beads in lanes (module docstring).

    Parameters
    ----------
    x, y
        Positions (m) of every bead's centre.
    kinds
        Species index of every bead.
    beads
        Geometry of each species.
    curves
        Force-velocity curves of each species (:mod:`.curves`).
    surface_speed
        The horizontal surface speed 2 pi f r A_y (m/s) that a drift ratio multiplies.
    cache
        Solved chains by composition, shared between runs on the same curves (optional).
    """

    def __init__(self, x: np.ndarray, y: np.ndarray, kinds: np.ndarray, beads: list[Bead],
                 curves: list[SpeciesCurves], surface_speed: float,
                 cache: dict[tuple, Any] | None = None) -> None:
        self.x = np.array(x, dtype=float)
        self.y = np.array(y, dtype=float)
        self.kinds = np.asarray(kinds, dtype=int)
        self.beads, self.curves, self.u = beads, curves, surface_speed
        radius = np.array([beads[k].radius for k in self.kinds])
        self.lane = lanes(np.asarray(y, dtype=float), radius)
        self._pairs()
        free = [c.free for c in curves]
        self.chain_of = np.arange(self.x.size)
        self.chains = {i: _Chain([i], [], free[k]) for i, k in enumerate(self.kinds)}
        self.speed = np.array([free[k] for k in self.kinds])
        self.merges = self.splits = self.saturated = 0
        self._cache: dict[tuple, Any] = {} if cache is None else cache

    def _pairs(self) -> None:
        """Candidate contacts (behind, front, centre distance along x, offset across the wave):
        every two beads whose bands [y - R, y + R] overlap, in their order along x."""
        y, radius = self.y, np.array([self.beads[k].radius for k in self.kinds])
        order = np.argsort(y, kind="stable")
        reach = 2.0 * float(radius.max()) if radius.size else 0.0
        pi, pj, pd, py = [], [], [], []
        for a_pos, a in enumerate(order):
            for b in order[a_pos + 1:]:
                dy = y[b] - y[a]
                if dy >= reach:
                    break
                if dy >= radius[a] + radius[b]:
                    continue
                i, j = (a, b) if (self.x[a], a) < (self.x[b], b) else (b, a)
                d = contact_geometry(self.beads[self.kinds[i]], self.beads[self.kinds[j]], dy)[0]
                gap = self.x[j] - self.x[i] - d
                if gap < -1e-9 * d:
                    raise ValueError(f"beads {min(i, j)} and {max(i, j)} overlap by {-gap:.3g} m")
                pi.append(int(i))
                pj.append(int(j))
                pd.append(d)
                py.append(abs(float(dy)))
        self.pi = np.array(pi, dtype=int)
        self.pj = np.array(pj, dtype=int)
        self.pd = np.array(pd, dtype=float)
        self.py = np.array(py, dtype=float)

    def _next_contact(self) -> tuple[float, int]:
        """(time to the next contact in s, its pair index), (inf, -1) if none."""
        if self.pi.size == 0:
            return math.inf, -1
        closing = (self.speed[self.pi] - self.speed[self.pj]) * self.u
        other = self.chain_of[self.pi] != self.chain_of[self.pj]
        ok = other & (closing > 0.0)
        if not ok.any():
            return math.inf, -1
        gap = self.x[self.pj] - self.x[self.pi] - self.pd
        dt = np.full(self.pi.size, math.inf)
        dt[ok] = np.maximum(gap[ok], 0.0) / closing[ok]
        p = int(np.argmin(dt))
        return float(dt[p]), p

    def _merge(self, p: int) -> None:
        """Join the chains of pair ``p`` and solve the merged chain (splitting where it pulls)."""
        a, b = self.chain_of[self.pi[p]], self.chain_of[self.pj[p]]
        ca, cb = self.chains.pop(a), self.chains.pop(b)
        members = sorted(ca.members + cb.members, key=lambda i: (self.x[i], i))
        local = {g: k for k, g in enumerate(members)}
        new = (int(self.pi[p]), int(self.pj[p]), float(self.py[p]))
        edges = sorted({(local[e[0]], local[e[1]], e[2]) for e in [*ca.edges, *cb.edges, new]})
        kinds = [int(self.kinds[g]) for g in members]
        key = (tuple(kinds), tuple((i, j, round(dy, 12)) for i, j, dy in edges))
        parts = self._cache.get(key)
        if parts is None:
            parts = [(m, e, s.speed, s.saturated)
                     for m, e, s in split_chain(self.beads, kinds, edges, self.curves)]
            self._cache[key] = parts
        self.merges += 1
        self.splits += len(parts) - 1
        for m, e, v, sat in parts:
            glob = [members[k] for k in m]
            cid = glob[0]
            self.chains[cid] = _Chain(glob, [(members[k[0]], members[k[1]], float(k[2]))
                                             for k in e], v)
            self.chain_of[glob] = cid
            self.speed[glob] = v
            self.saturated += int(sat)

    def run(self, times: np.ndarray, max_events: int = 10_000_000) -> SlowRun:
        """Move the beads to every time of ``times`` (s, non-decreasing, from 0)."""
        t0 = time.perf_counter()
        times = np.asarray(times, dtype=float)
        out = np.empty((times.size, self.x.size))
        t, events = 0.0, 0
        for k, target in enumerate(times):
            while True:
                dt, p = self._next_contact()
                if t + dt > target or p < 0:
                    break
                self.x += self.speed * self.u * dt
                t += dt
                self._merge(p)
                events += 1
                if events > max_events:
                    raise RuntimeError(f"more than {max_events} contacts: the chains chatter")
            self.x += self.speed * self.u * (target - t)
            t = target
            out[k] = self.x
        return SlowRun(times=times, x=out, kinds=self.kinds.copy(), lane=self.lane.copy(),
                       merges=self.merges, splits=self.splits,
                       wall_time_s=time.perf_counter() - t0, speeds=self.speed.copy(),
                       chains=[c.members for c in self.chains.values()],
                       saturated=self.saturated)
