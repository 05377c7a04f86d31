"""Beads in lanes along the wave, moved in slow time from event to event: contacts, merges, splits.

Between events every bead moves at the common drift of its chain (a lone bead: its free drift),
so positions are linear in time and the next event is the first contact between two beads of
different chains that approach each other (the one behind faster). At a contact the two chains
merge into one; the merged chain's balance (:func:`.chains.split_chain`) gives its common speed,
or splits it where a pair force would pull (the part in front runs ahead). Nothing else changes a
speed, so the cost grows with the number of contacts, not with the number of wave periods.

Geometry (1-D along the wave). Beads interact only with beads of their own *lane*: the beads whose
y-bands [y - R, y + R] overlap, linked (:func:`lanes`). Within a lane every contact is taken
head-on, in the x-z plane: the centre distance along x of two touching beads at rest is
sqrt((R_a + R_b)^2 - (z_b - z_a)^2) (:func:`.chains.contact_geometry`), and the order along x
never changes. A bead can touch its neighbour in the lane and, where a smaller bead fits
underneath, the bead beyond it (a 0.2 mm bead between two 1 mm beads lets them touch). The plate
is an open line: the bed is a piece of a plate larger than it, with free plate around it.

What 2-D (x and y) would add: contacts off the lane's axis, whose normal has a y part, so that a
small bead pushed by (or pushing) a large one is also pushed sideways and can go around it; beads
of neighbouring lanes that drift into each other; and the order along x of one lane could change.
In 1-D a small bead that meets a large one stays behind it for ever.
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
    edges: list[tuple[int, int]]
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
        """Candidate contacts (behind, front, centre distance along x) of each lane."""
        pi, pj, pd = [], [], []
        for ln in np.unique(self.lane):
            idx = np.flatnonzero(self.lane == ln)
            idx = idx[np.argsort(self.x[idx], kind="stable")]
            reach = [contact_geometry(self.beads[self.kinds[a]], self.beads[self.kinds[b]])[0]
                     for a, b in zip(idx[:-1], idx[1:], strict=True)]
            for k in range(idx.size - 1):
                for step in (1, 2, 3):
                    if k + step >= idx.size:
                        break
                    a, b = int(idx[k]), int(idx[k + step])
                    d = contact_geometry(self.beads[self.kinds[a]], self.beads[self.kinds[b]])[0]
                    # a bead beyond the neighbour matters only where it reaches past the chain of
                    # touching beads in between (a small bead under two large ones)
                    if step == 1 or d > sum(reach[k:k + step]) + TOUCH:
                        pi.append(a)
                        pj.append(b)
                        pd.append(d)
                gap = self.x[idx[k + 1]] - self.x[idx[k]] - reach[k]
                if gap < -1e-9 * reach[k]:
                    raise ValueError(f"beads {idx[k]} and {idx[k + 1]} overlap by {-gap:.3g} m")
        self.pi = np.array(pi, dtype=int)
        self.pj = np.array(pj, dtype=int)
        self.pd = np.array(pd, dtype=float)

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
        edges = sorted({(local[i], local[j]) for i, j in
                        [*ca.edges, *cb.edges, (int(self.pi[p]), int(self.pj[p]))]})
        kinds = [int(self.kinds[g]) for g in members]
        key = (tuple(kinds), tuple(edges))
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
            self.chains[cid] = _Chain(glob, [(members[i], members[j]) for i, j in e], v)
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
