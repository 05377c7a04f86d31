"""The drift field of two counter-propagating waves, its traps, and direct runs that test it.

With two waves (``drive.backward`` = s > 0) the local orbit depends on the place xi = X /
wavelength (:mod:`sawdrift.dynamics.drives.two_wave`), and so does the steady drift V(xi) of a
particle sitting there. A particle much smaller than the wavelength, whose drift per period is
much smaller than it, moves on the slow time as dX/dt = V(X) (docs/physics.md, "Two waves: the
local orbit and the drift field"): zeros with V' < 0 are traps, zeros with V' > 0 repellers.

* :func:`drift_field` runs the steady drift at N positions over one spatial period (1/2
  wavelength: every local quantity depends on 4 pi xi + psi), through the sweep's executors, for
  one scene or several species (an axis over a particle field), locates the zeros (sign changes,
  then regula falsi with more runs) and classifies them;
* :mod:`.field_direct` runs the particle through the field with the drive at its own position
  and compares it with the field's prediction;
* :func:`rayleigh_wavelength` and :func:`device_wavelength`: the wavelength of a device,
  lambda = c_R / f, c_R = xi_R sqrt(G / rho) with xi_R = c_R / c_S the root of the Rayleigh
  equation (:mod:`sawdrift.scene.rayleigh`).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..contact.binding import bind
from ..dynamics.drives.two_wave import TwoWaves, field_shift
from ..errors import SceneError
from ..scene.device import device_wavelength, normalized, rayleigh_wavelength
from ..scene.schema import Scene, Wave, build_scene, set_dotted
from .executor import Executor

__all__ = ["Field", "FieldInterrupted", "FieldStudy", "device_wavelength", "drift_field",
           "field_shift", "find_zeros", "rayleigh_wavelength", "wavelength_star"]

#: period of the field in wavelengths
PERIOD = 0.5
#: fewest positions of a field
MIN_POINTS = 4

#: most regula-falsi rounds per zero (``refine``): Illinois converges superlinearly, and a few
#: rounds reach the position's rounding; 99999999 ran for hours with no word
MAX_REFINE = 60

#: zeros per species a field's refinement is counted with in its size (a trap and a repeller per
#: period of the field, the usual two)
ZEROS_PER_FIELD = 2


def wavelength_star(scene: Scene) -> float | None:
    """L* = wavelength / a0: ``drive.wavelength``, else the device's (None if unknown)."""
    wave = scene.drive
    if isinstance(wave, Wave) and wave.wavelength is not None:
        return wave.wavelength
    if scene.device is not None:
        lam = device_wavelength(scene.device)
        if lam is not None:
            return lam / normalized(scene.device)["a0_m"]
    return None


@dataclass
class Field:
    """The drift field of one species: V(xi) over one period and its zeros."""

    label: str
    positions: np.ndarray
    drift_velocity: np.ndarray
    regimes: list[str]
    settled: list[bool | None]
    zeros: list[dict[str, Any]]
    scene: Scene
    #: one line: where it collects, or which way it goes
    summary: str = ""
    errors: list[str] = field(default_factory=list)
    #: standard error of each drift velocity that is a long-time mean (irregular motion; NaN
    #: for a steady drift), scaled from the run's ``drift_ratio_se``
    drift_velocity_se: np.ndarray | None = None
    #: the runs' warnings, each once (a device scene's validity warnings are every position's)
    warnings: list[str] = field(default_factory=list)

    def velocity_at(self, xi: np.ndarray | float) -> np.ndarray:
        """V at ``xi``: periodic linear interpolation of the samples and the zeros (period 1/2)."""
        x = np.append(self.positions, self.positions[0] + PERIOD)
        v = np.append(self.drift_velocity, self.drift_velocity[0])
        # the located zeros are knots too (V = 0 there), so that the path ends at them
        knots = [_wrap(z["position"], x[0]) for z in self.zeros if "values" in z]
        if knots:
            order = np.argsort(np.concatenate([x, knots]), kind="stable")
            x = np.concatenate([x, knots])[order]
            v = np.concatenate([v, np.zeros(len(knots))])[order]
        rel = np.mod(np.asarray(xi, dtype=float) - self.positions[0], PERIOD) + self.positions[0]
        return np.interp(rel, x, v)

    def to_json(self) -> dict[str, Any]:
        """``{"positions", "drift_velocity", "regimes", "zeros", ...}`` (positions in wavelengths)."""
        se = self.velocity_errors()
        out = {"label": self.label, "positions": self.positions.tolist(),
               "drift_velocity": self.drift_velocity.tolist(),
               "drift_velocity_se": [float(e) if np.isfinite(e) else None for e in se],
               "regimes": list(self.regimes),
               "settled": list(self.settled), "zeros": self.zeros, "summary": self.summary,
               "errors": self.errors, "warnings": self.warnings}
        scale = self.speed_scale()
        if scale is not None:  # a device: the speeds in m/s too, as the figure shows them
            out["drift_velocity_m_s"] = (self.drift_velocity * scale).tolist()
            out["drift_velocity_se_m_s"] = [float(e * scale) if np.isfinite(e) else None
                                            for e in se]
        return out

    def velocity_errors(self) -> np.ndarray:
        """Each drift velocity's standard error: a long-time mean's, NaN for a steady drift."""
        return (self.drift_velocity_se if self.drift_velocity_se is not None
                else np.full(self.drift_velocity.shape, np.nan))

    def speed_scale(self) -> float | None:
        """a0 f (m/s per x* a period) of a device scene's species, else None."""
        if self.scene.device is None:
            return None
        norm = normalized(self.scene.device)
        return float(norm["a0_m"] * norm["frequency_hz"])


@dataclass
class FieldStudy:
    """The fields of every species of one study (one species without an axis)."""

    fields: list[Field]
    axis: str | None = None
    direct: dict[str, Any] | None = None
    #: (positions run, positions asked for) of a study Ctrl-C stopped: its fields hold the
    #: positions that ended, with no zeros located (None: the study ran to its end)
    interrupted: tuple[int, int] | None = None

    def to_json(self) -> dict[str, Any]:
        """The first species' field at the top level (the one-species form), all under "species"."""
        out = dict(self.fields[0].to_json())
        if self.axis is not None:
            out["axis"] = self.axis
            out["species"] = [f.to_json() for f in self.fields]
        if self.direct is not None:
            out["direct"] = self.direct
        if self.interrupted is not None:
            out["interrupted"] = {"positions_run": self.interrupted[0],
                                  "positions": self.interrupted[1]}
        return out


def find_zeros(positions: np.ndarray, velocity: np.ndarray,
               eps: float | np.ndarray = 0.0) -> list[dict[str, Any]]:
    """Zeros of a periodic field sampled at ``positions`` (period :data:`PERIOD`), classified.

    A sign change between neighbours is a zero at the linear interpolation, a *trap* where V
    falls through it (V' < 0: particles on both sides move towards it) and a *repeller* where V
    rises. Samples with |V| <= ``eps`` (a number, or one per sample: a long-time mean within two
    of its standard errors of zero has no known sign) form a zero band; its centre is the zero,
    classified by
    the signs beside the band (+ then -: trap, - then +: repeller, equal: ``one-sided``, a place
    where particles from one side stop). Each zero holds ``position``, ``kind`` and its
    ``bracket`` (the two neighbouring samples, or the band's ends, unwrapped: lo < hi).
    """
    x = np.asarray(positions, dtype=float)
    v = np.asarray(velocity, dtype=float)
    n = x.size
    gap = 2  # a sample with no drift (NaN: ejected, failed): no zero is read across it
    sign = np.where(~np.isfinite(v), gap,
                    np.where(np.abs(v) <= eps, 0, np.sign(np.nan_to_num(v)))).astype(int)
    moving = np.flatnonzero((sign == 1) | (sign == -1))
    if moving.size == 0:
        return []

    def at(idx: int) -> float:  # position of sample idx on the unrolled circle
        return float(x[idx % n] + PERIOD * (idx // n))

    zeros: list[dict[str, Any]] = []
    k = int(moving[0])  # walk the circle once from a sample that moves
    end = k + n
    while k < end:
        j = k + 1
        if sign[k % n] == gap:
            k = j
            continue
        if sign[j % n] == 0:
            m = j
            while sign[m % n] == 0:
                m += 1
            lo, hi = at(j), at(m - 1)
            pair = (sign[k % n], sign[m % n])
            if gap not in pair:
                kind = ("trap" if pair == (1, -1) else "repeller" if pair == (-1, 1)
                        else "one-sided")
                zeros.append({"position": _wrap(0.5 * (lo + hi), x[0]), "kind": kind,
                              "bracket": [lo, hi]})
            k = m
            continue
        if sign[j % n] != gap and sign[k % n] * sign[j % n] < 0:
            x0, x1, v0, v1 = at(k), at(j), float(v[k % n]), float(v[j % n])
            zeros.append({"position": _wrap(x0 + v0 / (v0 - v1) * (x1 - x0), x[0]),
                          "kind": "trap" if v0 > 0 else "repeller", "bracket": [x0, x1],
                          "values": [v0, v1]})
        k = j
    return sorted(zeros, key=lambda z: z["position"])


def _wrap(xi: float, origin: float) -> float:
    return float(np.mod(xi - origin, PERIOD) + origin)


def _field_base(scene: Scene) -> Scene:
    """The scene of the field's local orbits: no wavelength, no phase ramp (psi as given).

    Bound to its model (:func:`sawdrift.contact.binding.bind`): a wrong model parameter is one
    line before any position runs.
    """
    if not isinstance(scene.drive, Wave):
        raise SceneError(f"drive.kind = {scene.drive.kind!r}: a drift field needs a wave drive")
    data = json.loads(json.dumps(scene.model_dump(exclude_none=True)))
    data["drive"].pop("wavelength", None)
    data["drive"].update(backward_phase_rate=0.0, position=0.0)
    return bind(build_scene(data))


def species_scenes(base: Scene, axis: tuple[str, list[Any]] | None) -> list[tuple[str, Scene]]:
    """(label, scene) of every species: ``base`` with the axis field set to each value."""
    if axis is None:
        return [("", base)]
    name, values = axis
    out = []
    for value in values:
        cell = json.loads(json.dumps(base.model_dump(exclude_none=True)))
        set_dotted(cell, name, value)
        out.append((f"{name}={value}", bind(build_scene(cell))))
    return out


def _run_scenes(scenes: list[Scene], executor: Executor, engine: str) -> list[dict[str, Any]]:
    """Rows of :func:`sawdrift.study.sweep.run_cell` for ``scenes``, in order (the study executor)."""
    from functools import partial

    from .sweep import run_cell

    return executor.map(partial(run_cell, engine=engine), [s.model_dump_json() for s in scenes])


def drift_field(
    scene: Scene,
    points: int = 64,
    *,
    axis: tuple[str, list[Any]] | None = None,
    refine: int = 2,
    workers: int | None = None,
    scheduler: Any = None,
    progress: bool = False,
    engine: str = "compiled",
) -> FieldStudy:
    """The drift field V(xi) of ``scene`` at ``points`` positions over one period (1/2 wavelength).

    Parameters
    ----------
    scene
        A wave scene (``drive.backward``, ``drive.backward_phase`` set; ``numerics.settle`` for
        settled drifts); its wavelength, position and phase ramp are ignored here.
    points
        Positions xi = k / (2 points), k = 0 .. points - 1; at least :data:`MIN_POINTS`.
    axis
        ``(dotted particle field, values)``: one field per value (species to sort).
    refine
        Regula-falsi rounds per zero (each one more run per zero, all zeros at once).
    workers, scheduler, progress, engine
        As for :func:`sawdrift.study.sweep.sweep`, which runs the positions.

    Raises
    ------
    FieldInterrupted
        Ctrl-C after some positions had ended: a KeyboardInterrupt holding the study of those
        (``.study``, no zeros located unless every position had ended).
    """
    from .sweep import sweep

    if int(points) != points or points < MIN_POINTS:
        raise SceneError(f"points = {points!r}: a field needs at least {MIN_POINTS} positions "
                         "over its period (1/2 wavelength)")
    if not 0 <= refine <= MAX_REFINE:
        raise SceneError(f"refine = {refine!r}: give 0 to {MAX_REFINE} regula-falsi runs per zero "
                         "(Illinois converges superlinearly: a few reach the position's rounding)")
    base = _field_base(scene)
    positions = np.arange(int(points)) * (PERIOD / int(points))
    axes: dict[str, Any] = {"drive.position": positions.tolist()}
    if axis is not None:
        axes[axis[0]] = axis[1]
    ended: list[dict[str, Any]] = []
    try:
        with Executor(workers, scheduler) as executor:
            frame = sweep([base.model], axes=axes, base=base, progress=progress, engine=engine,
                          label=("field", "point"), executor=executor, on_row=ended.append)
            fields = _fields(frame, base, axis, positions)
            _refine(fields, refine, executor, engine)
    except KeyboardInterrupt:
        if not ended:
            raise
        # still an interrupt (a script's loop stops), carrying what ended (the command line
        # shows and writes it)
        raise FieldInterrupted(_interrupted(ended, base, axis, positions)) from None
    for f in fields:
        f.summary = _summarize(f)
    return FieldStudy(fields, axis[0] if axis is not None else None)


class FieldInterrupted(KeyboardInterrupt):
    """Ctrl-C stopped :func:`drift_field` after some positions had ended: a KeyboardInterrupt
    whose ``study`` holds them (:attr:`FieldStudy.interrupted`)."""

    def __init__(self, study: FieldStudy):
        super().__init__("drift field interrupted")
        self.study = study


def _interrupted(rows: list[dict[str, Any]], base: Scene, axis: tuple[str, list[Any]] | None,
                 positions: np.ndarray) -> FieldStudy:
    """The study Ctrl-C stopped, marked :attr:`FieldStudy.interrupted`: each species' field at
    the positions that ended (a field may have none), with no zeros located (a sign change
    between positions that ran may hide others between them); where every position had ended
    (stopped while refining), the zeros of the sign changes, not refined."""
    from .table import to_frame

    species = len(species_scenes(base, axis))
    complete = len(rows) == len(positions) * species
    fields = _fields(to_frame(rows), base, axis, positions, complete=complete)
    if complete:
        _place_zeros(fields)  # as a field of no refinement rounds places them
    for f in fields:
        if complete:
            f.summary = _summarize(f) + " (zeros not refined: interrupted)"
        else:
            f.zeros = []
            f.summary = (f"interrupted: {len(f.positions)} of {len(positions)} positions run, "
                         "no zeros located")
    return FieldStudy(fields, axis[0] if axis is not None else None,
                      interrupted=(len(rows), len(positions) * species))


def _fields(frame: Any, base: Scene, axis: tuple[str, list[Any]] | None,
            positions: np.ndarray, complete: bool = True) -> list[Field]:
    """The fields of every species from the sweep's rows, with their zeros (not yet refined);
    not ``complete``: at the positions that have a row (a study Ctrl-C stopped)."""
    from .table import distinct_warnings, drift_errors  # pandas, as the sweep's rows

    species = species_scenes(base, axis)
    fields = []
    for label, sp in species:
        rows = frame
        if axis is not None:
            from .sweep import get_dotted

            want = get_dotted(sp.model_dump(), axis[0])
            rows = frame[np.isclose(frame[axis[0]].astype(float), float(want), rtol=1e-12)]
        rows = rows.sort_values("drive.position")
        at = positions
        if not complete:
            at = rows["drive.position"].to_numpy(dtype=float) if len(rows) else positions[:0]
        elif len(rows) != len(positions):
            raise SceneError(f"field of {label or 'the scene'}: {len(rows)} of {len(positions)} "
                             "positions computed")
        v = rows["drift_velocity"].to_numpy(dtype=float)
        errors = [str(e) for e in rows["error"].dropna().unique()]
        warnings = distinct_warnings(rows["warnings"].dropna()) if "warnings" in rows else []
        fields.append(Field(label=label, positions=at.copy(), drift_velocity=v,
                            regimes=[str(r) for r in rows["regime"]],
                            settled=[None if s is None or s != s else bool(s)
                                     for s in rows["settled"]],
                            zeros=[], scene=sp, errors=errors, warnings=warnings,
                            drift_velocity_se=drift_errors(rows, "drift_velocity")))
    for f in fields:
        # a failed or ejected run (no drift) is a gap no zero is read across
        ok = np.isfinite(f.drift_velocity)
        f.zeros = (find_zeros(f.positions, f.drift_velocity, _zero_band(f))
                   if ok.sum() >= 2 else [])
    return fields


#: standard errors within which a long-time mean drift is taken as no known sign (a zero band)
SIGN_ERRORS = 2.0


def _zero_band(f: Field) -> np.ndarray:
    """|V| at or below which each sample counts as zero: the regimes' "no drift"
    (:func:`_zero_eps`), or :data:`SIGN_ERRORS` standard errors of a long-time mean (two noisy
    means of opposite signs are no trap: mmd 0.2 mm steel beads of examples/sorting.toml bounce
    from xi = 0.45 to 0.05 with means of 1 to 4.5 a0 f and errors of 3 to 12)."""
    eps = np.full(f.drift_velocity.shape, _zero_eps(f.scene))
    # a stuck contact's creep of 1e-7 a0 f is no direction
    eps[np.array([r == "stick" for r in f.regimes], dtype=bool)] = np.inf
    if f.drift_velocity_se is not None:
        se = np.where(np.isfinite(f.drift_velocity_se), f.drift_velocity_se, 0.0)
        eps = np.maximum(eps, SIGN_ERRORS * se)
    return eps


def _zero_eps(scene: Scene) -> float:
    """|V| at or below which a sample is a zero: the regimes' "no drift", ``numerics.
    drift_tolerance`` times the forward wave's horizontal speed 2 pi r A* (asked of the drive)."""
    return scene.numerics.drift_tolerance * TwoWaves.forward_speed(scene)


def _refine(fields: list[Field], rounds: int, executor: Executor, engine: str) -> None:
    """Regula falsi (Illinois) on every sign-change bracket, one run per zero and round."""
    jobs = [(f, z) for f in fields for z in f.zeros if "values" in z]
    for _ in range(rounds):
        if not jobs:
            return
        scenes = []
        for f, z in jobs:
            (x0, x1), (v0, v1) = z["bracket"], z["values"]
            z["position"] = x0 + v0 / (v0 - v1) * (x1 - x0)
            scenes.append(f.scene.with_updates(**{"drive.position": _wrap(z["position"], 0.0)}))
        rows = _run_scenes(scenes, executor, engine)
        for (_f, z), row in zip(jobs, rows, strict=True):
            vm = row["drift_velocity"]
            if vm is None or not math.isfinite(vm):
                continue
            (x0, x1), (v0, v1) = z["bracket"], z["values"]
            xm = z["position"]
            if vm == 0.0:
                z["bracket"], z["values"] = [xm, xm], [0.0, 0.0]
            elif (vm > 0.0) == (v0 > 0.0):  # keep the right end (halved if kept twice: Illinois)
                z["bracket"], z["values"] = [xm, x1], [vm, v1 * (0.5 if z.get("side") == 0 else 1.0)]
                z["side"] = 0
            else:
                z["bracket"], z["values"] = [x0, xm], [v0 * (0.5 if z.get("side") == 1 else 1.0), vm]
                z["side"] = 1
        jobs = [(f, z) for f, z in jobs if z["bracket"][0] != z["bracket"][1]]
    _place_zeros(fields)


def _place_zeros(fields: list[Field]) -> None:
    """Each bracketed zero at the secant through its bracket's ends (as far as the refinement
    took them), wrapped into the field's period; the zeros in order."""
    for f in fields:
        for z in f.zeros:
            if "values" in z:
                (x0, x1), (v0, v1) = z["bracket"], z["values"]
                z["position"] = _wrap(x0 if v0 == v1 else x0 + v0 / (v0 - v1) * (x1 - x0),
                                      f.positions[0])
                z.pop("side", None)
        f.zeros.sort(key=lambda z: z["position"])


def _summarize(f: Field) -> str:
    ejected = sum(r == "ejected" for r in f.regimes)
    if ejected == len(f.regimes):
        return "ejected at every position: the particle is thrown off, no drift field"
    if all(r == "stick" for r in f.regimes):
        return "stuck at every position: no drift"
    traps = [z["position"] for z in f.zeros if z["kind"] == "trap"]
    if traps:
        return "collects at xi = " + ", ".join(f"{t:.4f}" for t in traps) + " (+ k/2)"
    if not f.zeros:
        inside = np.abs(f.drift_velocity) <= _zero_band(f)
        if np.all(inside) and f.drift_velocity_se is not None and np.isfinite(
                f.drift_velocity_se).any():
            return "no known direction: every drift is within two errors of zero"
        mean = float(np.mean(f.drift_velocity))
        if np.all(f.drift_velocity > 0):
            return f"goes to +x everywhere (mean V = {mean:.4g})"
        if np.all(f.drift_velocity < 0):
            return f"goes to -x everywhere (mean V = {mean:.4g})"
        return "no drift"
    return "no trap: " + ", ".join(f"{z['kind']} at {z['position']:.4f}" for z in f.zeros)
