"""Each bead's steady speed under a tangential and a normal load: tabulated force-velocity curves.

A bead of species s (radius R_s, weight W_s = m_s g) on the wave-driven plate, pushed along the
wave by a constant tangential force L and pressed onto the plate by a constant normal force N
(its weight plus what its neighbours press on it), reaches a steady drift V_s(L, N). Read the
other way, L_s(V, N) is the load that holds it at the speed V under N: the force-velocity curve
of the steady-drift study (:func:`sawdrift.study.force_velocity.force_velocity`), one curve per
normal load. Each point is a run at full inertia (the bead's fast oscillation and its contact
memory kept at its own m*), with the scene's damping.

The normal load enters through the bead's weight: the species' scene with gravity g N / W_s holds
the same bead (same mass) with N, so its static compression, m* and A* are those of a bead under
N. The table (:class:`SpeciesCurves`) samples

* l = L / N, the load over the normal load, strictly inside (-mu, mu) (beyond, no steady speed);
* n = N / W_s on a grid of normal loads (:func:`normal_grid`): a bead smaller than the other
  species is pressed by the inclined contact normals of a chain (n >= 1), a larger one lifted
  (n <= 1);
* V as the drift ratio (drift over the horizontal surface speed 2 pi f r A_y, the same for every
  species), made non-decreasing in l along each curve (isotonic fit) so that it can be read
  backwards.

L_s(V, N) interpolates l linearly in V on each curve and linearly in log n between curves;
outside the sampled speeds it is the end load (the bead cannot be held faster than the largest
load drives it), outside the grid the nearest curve.

The table is cached on disk (``cache_dir()/curves``), keyed by the species' scene, the grids,
the source of the runs and the sawdrift version.
"""

from __future__ import annotations

import hashlib
import json
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

import numpy as np

import sawdrift_builtin

from .._version import __version__
from ..codegen.modules import cache_dir
from ..errors import SceneError
from ..scene.device import normalized
from ..scene.schema import Scene

__all__ = ["SpeciesCurves", "curves_for", "isotonic", "normal_grid", "species_curves"]

#: normal loads N / W of a bead pressed by its neighbours (the smaller species)
PRESSED = (1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0, 24.0)
#: normal loads N / W of a bead lifted by its neighbours (the larger species)
LIFTED = (0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1)
#: loads per curve (odd: the unloaded run is one of them)
POINTS = 17

Source = Literal["native", "lammps_rule"]


def normal_grid(pressed: bool) -> tuple[float, ...]:
    """The normal loads N / W sampled for a species that chains press (True) or lift (False)."""
    return PRESSED if pressed else LIFTED


def isotonic(y: np.ndarray) -> np.ndarray:
    """The non-decreasing sequence closest to ``y`` in least squares (pool adjacent violators)."""
    vals: list[float] = []
    sizes: list[int] = []
    for v in np.asarray(y, dtype=float):
        vals.append(float(v))
        sizes.append(1)
        while len(vals) > 1 and vals[-2] > vals[-1]:
            n = sizes[-2] + sizes[-1]
            vals[-2] = (vals[-2] * sizes[-2] + vals[-1] * sizes[-1]) / n
            sizes[-2] = n
            vals.pop()
            sizes.pop()
    return np.repeat(vals, sizes)


@dataclass(frozen=True)
class SpeciesCurves:
    """The force-velocity curves of one species over normal loads (module docstring).

    ``loads[i, k]`` is l = L / N of point k on the curve at ``normal[i]`` = N / W, ``speeds[i, k]``
    its steady drift ratio (non-decreasing in k), ``raw[i, k]`` the drift ratio as run.
    """

    radius: float
    weight: float
    normal: np.ndarray
    loads: np.ndarray
    speeds: np.ndarray
    raw: np.ndarray
    regimes: tuple[tuple[str, ...], ...]
    mu: float
    wall_time_s: float
    source: str = "native"

    @property
    def free(self) -> float:
        """The free drift ratio (n = 1, l = 0), interpolated like every other value."""
        return float(self.speed(0.0, 1.0))

    #: speeds of the regular table behind :meth:`load` (drift ratio, over the sampled range)
    GRID = 2001

    def _table(self) -> tuple[float, float, np.ndarray, np.ndarray]:
        """(v0, dv, l[grid, curve], log n): l of every curve resampled on a regular speed grid.

        Resampled once (linear in v between the samples, the end loads outside), so that a load
        costs two array lookups: the chain balance evaluates it many times.
        """
        cached = self.__dict__.get("_table_cache")
        if cached is None:
            strict = self.speeds + 1e-12 * np.arange(self.speeds.shape[1])
            lo, hi = float(strict.min()), float(strict.max())
            grid = np.linspace(lo, hi, self.GRID)
            table = np.array([np.interp(grid, strict[i], self.loads[i])
                              for i in range(self.normal.size)]).T.copy()
            cached = (lo, (hi - lo) / (self.GRID - 1), table, np.log(self.normal))
            object.__setattr__(self, "_table_cache", cached)
        return cached

    def basis(self, n: np.ndarray) -> np.ndarray:
        """B[j, i]: L_j / W_j = sum_i B[j, i] l_i(v) for beads under N / W = ``n[j]``.

        The weights of linear interpolation in log n between the curves (the nearest curve
        outside the grid), times n (L = l N).
        """
        _, _, _, logn_grid = self._table()
        n = np.asarray(n, dtype=float)
        logn = np.log(np.clip(n, self.normal[0], self.normal[-1]))
        k = np.clip(np.searchsorted(logn_grid, logn, side="right") - 1, 0, max(logn_grid.size - 2, 0))
        out = np.zeros((n.size, logn_grid.size))
        if logn_grid.size == 1:
            out[:, 0] = n
            return out
        t = (logn - logn_grid[k]) / (logn_grid[k + 1] - logn_grid[k])
        rows = np.arange(n.size)
        out[rows, k] = (1.0 - t) * n
        out[rows, k + 1] += t * n
        return out

    def rows_at(self, v: float) -> np.ndarray:
        """l_i(v) of every curve i (linear on the regular table, the end loads outside)."""
        v0, dv, table, _ = self._table()
        u = min(max((v - v0) / dv, 0.0), self.GRID - 1.000001)
        k = int(u)
        t = u - k
        return table[k] * (1.0 - t) + table[k + 1] * t

    def speed_grid(self) -> tuple[np.ndarray, np.ndarray]:
        """(regular speeds, l on every curve there): the table behind :meth:`load`."""
        v0, dv, table, _ = self._table()
        return v0 + dv * np.arange(self.GRID), table

    def load(self, v: float, n: np.ndarray | float) -> np.ndarray:
        """L / W: the load (in weights) that holds beads under N / W = ``n`` at drift ratio v."""
        n_arr = np.atleast_1d(np.asarray(n, dtype=float))
        out = self.basis(n_arr) @ self.rows_at(v)
        return out if np.ndim(n) else out[0]

    def speed(self, ell: float, n: float) -> float:
        """The drift ratio under l = L / N = ``ell`` and N / W = ``n``: the inverse of
        :meth:`load` at that n.

        On a sampled normal load it is that curve read along the load. Between two, the load at
        a fixed speed is interpolated in log n (as :meth:`load` does, so that a chain steady in
        one model is steady in the other), and that blended curve is read along the load, not
        the two speeds at a fixed load interpolated (which read -0.2321 back for a load that
        :meth:`load` gave at -0.2707, at n = 3.2).
        """
        logn_grid = np.log(self.normal)
        logn = math.log(min(max(n, self.normal[0]), self.normal[-1]))
        k = int(np.clip(np.searchsorted(logn_grid, logn, side="right") - 1, 0,
                        max(self.normal.size - 2, 0)))
        t = 0.0 if self.normal.size == 1 else (logn - logn_grid[k]) / (logn_grid[k + 1]
                                                                       - logn_grid[k])
        if t <= 0.0 or t >= 1.0:
            i = k if t <= 0.0 else k + 1
            return float(np.interp(ell, self.loads[i], self.speeds[i]))
        # the blend is linear between the union of both curves' samples (strictly increasing
        # speeds, as in :meth:`_table`)
        strict = self.speeds[k:k + 2] + 1e-12 * np.arange(self.speeds.shape[1])
        knots = np.union1d(strict[0], strict[1])
        blend = ((1.0 - t) * np.interp(knots, strict[0], self.loads[k])
                 + t * np.interp(knots, strict[1], self.loads[k + 1]))
        return float(np.interp(ell, blend, knots))

    def to_json(self) -> dict[str, Any]:
        return {"radius": self.radius, "weight": self.weight, "normal": self.normal.tolist(),
                "loads": self.loads.tolist(), "speeds": self.speeds.tolist(),
                "raw": self.raw.tolist(), "regimes": [list(r) for r in self.regimes],
                "mu": self.mu, "wall_time_s": self.wall_time_s, "source": self.source}

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> SpeciesCurves:
        return cls(radius=data["radius"], weight=data["weight"], normal=np.array(data["normal"]),
                   loads=np.array(data["loads"]), speeds=np.array(data["speeds"]),
                   raw=np.array(data["raw"]), regimes=tuple(tuple(r) for r in data["regimes"]),
                   mu=data["mu"], wall_time_s=data["wall_time_s"], source=data["source"])


def _curve_native(scene: Scene, points: int) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    """(l, drift ratio, regimes) of one species' scene by the native force-velocity study."""
    from ..study.force_velocity import force_velocity

    fv = force_velocity(scene.with_updates(**{"numerics.settle": True}), points=points, workers=1)
    return fv.forces, fv.drift_ratios, fv.regimes


def _curve_lammps_rule(scene: Scene, points: int) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    """(l, drift ratio, regimes) with LAMMPS's Coulomb rule (:mod:`sawdrift.lammps.damped`)."""
    from ..lammps.damped import cap_rule_drift

    mu = scene.material.mu
    ells = mu * np.linspace(-1.0, 1.0, points + 2)[1:-1]
    weight = _weight(scene)
    v = [cap_rule_drift(scene.with_updates(**{"device.load": float(e) * weight}), "total")
         for e in ells]
    return ells, np.array(v), tuple("lammps_rule" for _ in ells)


def _weight(scene: Scene) -> float:

    assert scene.device is not None
    return normalized(scene.device)["weight_n"]


def species_curves(scene: Scene, normal: tuple[float, ...], *, points: int = POINTS,
                   source: Source = "native",
                   progress: Callable[[str], None] | None = None) -> SpeciesCurves:
    """Run the curves of the single-bead device ``scene`` at the normal loads ``normal`` (N / W).

    Each curve is the species' scene with gravity g n (module docstring), sampled at ``points``
    loads strictly inside (-mu, mu) N. Cached on disk (:func:`_cache_path`).
    """
    if scene.device is None:
        raise SceneError("the slow model of chains needs a device scene (SI sizes and weights)")
    if source not in ("native", "lammps_rule"):
        raise SceneError(f"curve source {source!r}: use 'native' or 'lammps_rule'")
    path = _cache_path(scene, normal, points, source)
    if path.exists():
        return SpeciesCurves.from_json(json.loads(path.read_text()))
    t0 = time.perf_counter()
    g = scene.device.gravity
    weight = _weight(scene)
    loads, raw, regimes = [], [], []
    for n in normal:
        run = _curve_native if source == "native" else _curve_lammps_rule
        ell, v, reg = run(scene.with_updates(**{"device.gravity": g * n}), points)
        loads.append(np.asarray(ell, dtype=float))
        raw.append(np.asarray(v, dtype=float))
        regimes.append(tuple(reg))
        if progress is not None:
            progress(f"curve R = {scene.device.particle.radius * 1e3:g} mm, N/W = {n:g}: "
                     f"free drift ratio {float(np.interp(0.0, loads[-1], raw[-1])):+.4f}")
    raw_a = np.array(raw)
    if not np.isfinite(raw_a).all():
        raise SceneError("a force-velocity run found no steady drift (NaN); the slow model "
                         "needs a steady speed at every sampled load")
    curves = SpeciesCurves(
        radius=float(scene.device.particle.radius), weight=weight,
        normal=np.array(normal, dtype=float), loads=np.array(loads), raw=raw_a,
        speeds=np.array([isotonic(r) for r in raw_a]), regimes=tuple(regimes),
        mu=scene.material.mu, wall_time_s=time.perf_counter() - t0, source=source)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(curves.to_json()))
    except OSError:
        pass  # an unwritable cache costs a rerun, nothing else
    return curves


def _cache_path(scene: Scene, normal: tuple[float, ...], points: int, source: str) -> Path:
    """The cache file of a species' table: a hash of everything that sets its values."""
    key = json.dumps({"scene": scene.model_dump(mode="json"), "normal": list(normal),
                      "points": points, "source": source, "version": __version__,
                      "kernel": _kernel_digest()}, sort_keys=True, default=str)
    return cache_dir() / "curves" / f"{hashlib.sha256(key.encode()).hexdigest()[:24]}.json"


def _kernel_digest() -> str:
    """sha1 of the DEM law's source files (the plugin's kernel and law, and the contact slots and
    scene damping that hand it its normal force): an edited contact law invalidates the tables."""
    h = hashlib.sha1()
    builtin = Path(sawdrift_builtin.__file__).parent
    contact = Path(__file__).parents[1] / "contact"
    for p in (builtin / "dem_kernel.py", builtin / "hertz_mindlin_dem.py",
              contact / "slots.py", contact / "slot_kernels.py", contact / "scene_damping.py"):
        h.update(p.read_bytes() if p.exists() else b"")
    return h.hexdigest()


def curves_for(scene: Scene, radii: list[float], *, points: int = POINTS,
               source: Source = "native",
               progress: Callable[[str], None] | None = None) -> list[SpeciesCurves]:
    """The curves of each species of radius ``radii`` on the device ``scene``.

    The smallest species is sampled on the pressed grid, the others on the lifted grid (a chain's
    inclined contact normals press the smaller bead of a pair onto the plate and lift the larger).
    """
    if scene.device is None:
        raise SceneError("the slow model of chains needs a device scene (SI sizes and weights)")
    smallest = min(radii)
    out = []
    for r in radii:
        single = scene.with_updates(**{"device.particle.radius": r})
        out.append(species_curves(single, normal_grid(r == smallest and len(radii) > 1),
                                  points=points, source=source, progress=progress))
    return out
