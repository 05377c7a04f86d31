"""Chains of touching beads: the common speed where every bead's horizontal and vertical balance
holds, and where a chain splits.

Beads in a lane along the wave (x) touch at rest on the plate: a bead of species s has its
centre at height z_s = R_s - a0_s, so two touching beads a (behind) and b (in front) have their
centres d = R_a + R_b apart along the contact normal

    n_ab = (cos phi, sin phi),   sin phi = (z_b - z_a) / d,   cos phi = sqrt(d^2 - (z_b - z_a)^2) / d,

inclined by phi from the plate (about 42 degrees for a 0.2 mm and a 1 mm bead: their centres are
0.8 mm apart in height and 0.89 mm along x). A compressive pair force P >= 0 acts on b as P n_ab
and on a as -P n_ab, so with pair forces P_e on the contacts e of a chain each bead j feels

    horizontal:  F_j = sum_e A_je P_e,   A_je = +cos phi_e (j in front of e), -cos phi_e (behind);
    normal load: N_j = W_j + sum_e B_je P_e,  B_je = +sin phi_e (j behind), -sin phi_e (in front):

the smaller bead of an inclined pair is pressed onto the plate, the larger one lifted.

A chain moving at the common drift V is steady when every bead's pair forces are the load that
holds it at V under its normal load: F_j = L_j(V, N_j) (the force-velocity curves of
:mod:`.curves`). The horizontal loads sum to zero (pair forces cancel), which fixes V; the pair
forces then follow from the horizontal balance (a tree of contacts: exactly), and the normal
loads from them. :func:`solve_chain` iterates this (normal loads -> V -> pair forces -> normal
loads) to a fixed point. A chain holds together only if every pair force is compressive; where
one would pull, the part in front would run ahead alone: the chain splits there
(:func:`split_chain`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .curves import SpeciesCurves

__all__ = ["Bead", "ChainState", "Edge", "contact_geometry", "solve_chain", "split_chain"]


@dataclass(frozen=True)
class Bead:
    """One species' geometry at rest: radius R, static compression a0, weight W (SI)."""

    radius: float
    a0: float
    weight: float

    @property
    def height(self) -> float:
        """Centre height above the plate's mean surface, R - a0."""
        return self.radius - self.a0


def contact_geometry(behind: Bead, front: Bead, dy: float = 0.0) -> tuple[float, float, float]:
    """(centre distance along x, cos phi, sin phi) of two touching beads at rest (docstring).

    ``dy`` is the offset of their centres across the wave: the distance along x is then
    sqrt(d^2 - dz^2 - dy^2) and the normal's x part dx / d (its y part, dy / d, is left out: the
    model is 1-D along the wave).
    """
    d = behind.radius + front.radius
    dz = front.height - behind.height
    dx = math.sqrt(max(d * d - dz * dz - dy * dy, 0.0))
    return dx, dx / d, dz / d


Edge = tuple[int, int] | tuple[int, int, float]


def _offset(edge: Edge) -> float:
    return float(edge[2]) if len(edge) > 2 else 0.0  # type: ignore[misc]


@dataclass
class ChainState:
    """A solved chain: its common drift ratio, pair forces (N) and normal loads N_j / W_j."""

    speed: float
    forces: np.ndarray
    normal: np.ndarray
    iterations: int
    saturated: bool = False  # the balance needed a load beyond the sampled curves
    loads: np.ndarray = field(default_factory=lambda: np.empty(0))  # L_j, N

    @property
    def holds(self) -> bool:
        """Every pair force compressive (within round-off)."""
        return bool(self.forces.size == 0 or self.forces.min() >= -1e-9 * _scale(self))


def _scale(state: ChainState) -> float:
    return float(np.abs(state.loads).max()) if state.loads.size else 1.0


def _matrices(beads: list[Bead], edges: list[Edge]) -> tuple[np.ndarray, np.ndarray]:
    n = len(beads)
    a = np.zeros((n, len(edges)))
    b = np.zeros((n, len(edges)))
    for e, edge in enumerate(edges):
        i, j = edge[0], edge[1]
        _, c, s = contact_geometry(beads[i], beads[j], _offset(edge))
        a[i, e], a[j, e] = -c, c
        b[i, e], b[j, e] = s, -s
    return a, b


def solve_chain(beads: list[Bead], kinds: list[int], edges: list[Edge],
                curves: list[SpeciesCurves], *, tol: float = 1e-10,
                max_iter: int = 200) -> ChainState:
    """The common speed, pair forces and normal loads of a chain (module docstring).

    Parameters
    ----------
    beads
        The species' geometry, indexed by ``kinds``.
    kinds
        The species of each bead of the chain.
    edges
        Contacts ``(behind, front)`` or ``(behind, front, dy)`` as indices into ``kinds`` (dy:
        the offset of the centres across the wave); every bead connected.
    curves
        The force-velocity curves of each species.
    tol
        Convergence of the normal loads, relative to each bead's weight.
    """
    members = [beads[k] for k in kinds]
    w = np.array([b.weight for b in members])
    a, b = _matrices(members, edges)
    n_load = np.ones(len(kinds))
    kinds_a = np.asarray(kinds)
    used = [s for s in range(len(curves)) if (kinds_a == s).any()]
    grids = {s: curves[s].speed_grid() for s in used}
    common = np.unique(np.concatenate([grids[s][0] for s in used]))
    v, saturated, forces, it = 0.0, False, np.zeros(len(edges)), 0
    for it in range(1, max_iter + 1):
        basis = {s: curves[s].basis(n_load[kinds_a == s]) * w[kinds_a == s, None] for s in used}
        # the total load sum_j L_j(v): piecewise linear in v on each species' table
        total = np.zeros(common.size)
        for s in used:
            vs, table = grids[s]
            total += np.interp(common, vs, table @ basis[s].sum(axis=0))
        v, saturated = _first_zero(common, total)
        ell = np.empty(len(kinds))
        for s in used:
            ell[kinds_a == s] = basis[s] @ curves[s].rows_at(v)
        if edges:
            forces = np.linalg.lstsq(a, ell, rcond=None)[0]
        new = np.maximum((w + b @ forces) / w, 1e-3) if edges else n_load
        step = float(np.abs(new - n_load).max())
        # under-relaxed after a while: a steep curve in N can make the plain iteration overshoot
        n_load = n_load + (0.5 if it > 20 else 1.0) * (new - n_load)
        if step < tol:
            break
    return ChainState(speed=float(v), forces=forces, normal=n_load, iterations=it,
                      saturated=saturated, loads=ell)


def _first_zero(v: np.ndarray, total: np.ndarray) -> tuple[float, bool]:
    """(speed where the non-decreasing piecewise-linear ``total`` crosses 0, saturated?)."""
    if total[0] >= 0.0:
        return float(v[0]), total[0] > 0.0
    if total[-1] <= 0.0:
        return float(v[-1]), total[-1] < 0.0
    k = int(np.argmax(total >= 0.0))
    t0, t1 = total[k - 1], total[k]
    return float(v[k - 1] + (v[k] - v[k - 1]) * (-t0) / (t1 - t0)), False


def _components(n: int, edges: list[Edge]) -> list[list[int]]:
    """Connected components of ``n`` nodes under ``edges`` (sorted node lists)."""
    parent = list(range(n))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for edge in edges:
        parent[find(edge[0])] = find(edge[1])
    groups: dict[int, list[int]] = {}
    for i in range(n):
        groups.setdefault(find(i), []).append(i)
    return sorted(groups.values())


def split_chain(beads: list[Bead], kinds: list[int], edges: list[Edge],
                curves: list[SpeciesCurves]) -> list[tuple[list[int], list[Edge], ChainState]]:
    """The chain broken where it pulls: [(member indices, their edges, solution), ...].

    Solves the chain; while some pair force is tensile, the most tensile contact opens (the part
    in front runs ahead, or the part behind falls back) and each part is solved again. A split
    whose parts would close again at once (the part behind faster) is not made: the chain is kept
    with the small tension, which the slow model cannot resolve.
    """
    state = solve_chain(beads, kinds, edges, curves)
    if state.holds or not edges:
        return [(list(range(len(kinds))), list(edges), state)]
    worst = int(np.argmin(state.forces))
    rest = [e for k, e in enumerate(edges) if k != worst]
    parts = _components(len(kinds), rest)
    out = []
    for part in parts:
        index = {old: new for new, old in enumerate(part)}
        sub_edges: list[Edge] = [(index[e[0]], index[e[1]], _offset(e)) for e in rest
                                 if e[0] in index]
        for members, sub, sol in split_chain(beads, [kinds[i] for i in part], sub_edges, curves):
            out.append(([part[m] for m in members],
                        [(part[e[0]], part[e[1]], _offset(e)) for e in sub], sol))
    behind, front = edges[worst][0], edges[worst][1]
    v_of = {m: sol.speed for members, _, sol in out for m in members}
    if v_of[behind] > v_of[front] + 1e-12:
        return [(list(range(len(kinds))), list(edges), state)]
    return out
