"""Sliding and removal thresholds of an adhesive particle against one device field (its radius).

For each value of the field (``device.particle.radius`` typically) the study locates two
amplitudes of the wave (``device.amplitude``):

* **sliding**: the smallest amplitude at which the contact slides as a whole (gross slip) in the
  measuring window, or loses contact;
* **removal**: the smallest amplitude at which the run ends ``ejected`` (out of contact through
  the whole window and not coming back).

Removal need not be monotonic in the amplitude (an undamped contact can be pumped near its
resonance, and a particle thrown off at one amplitude may hop on at a higher one), so each is a
*first crossing located from below*: amplitudes on a geometric grid from ``start`` times the
rigid removal amplitude upwards, until the first that crosses, then bisection between it and the
last that did not. The rigid removal amplitude is that of a particle that follows the surface
until its inertial force m (2 pi f)^2 A exceeds the pull-off force plus its weight:

    A_rigid = (F_pull + m g) / (m (2 pi f)^2)      (about F_pull / (m (2 pi f)^2) ~ 1 / R^2)

Every run is a fixed run (``numerics.settle = false``) of the scene's ``numerics.periods`` (or
``periods``): "removed" means thrown off and not back by the end of that run.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from functools import partial
from typing import Any

import numpy as np

from ..contact.binding import bind
from ..errors import SceneError
from ..result.runner import run
from ..scene.adhesion import normalized_adhesion
from ..scene.device import FIELD_KIND, field_si, normalized
from ..scene.schema import Scene, check_dotted
from ..scene.validity import device_warnings
from .progress import counter

#: how a threshold was found (``ThresholdRow.slide_found``, ``removal_found``): located by
#: bisection; already crossed at the scan's first amplitude (the threshold lies below
#: ``start`` times the rigid removal amplitude); not crossed up to ``stop``; not crossed up to the
#: largest amplitude the device may have (its wave's surface strain or speed bound, or the
#: largest A* the model integrates)
FOUND, BELOW_START, ABOVE_STOP, ABOVE_BOUND = "found", "below_start", "above_stop", "above_bound"


@dataclass(frozen=True)
class ThresholdRow:
    """The thresholds at one value of the field (SI units). An amplitude is NaN unless its
    ``*_found`` is :data:`FOUND`; then that field says on which side of the scan it lies."""

    value: float
    slide_amplitude_m: float
    removal_amplitude_m: float
    rigid_removal_m: float
    pulloff_n: float
    weight_n: float
    runs: int
    slide_found: str = FOUND
    removal_found: str = FOUND
    #: the scan's first amplitude (m): a threshold BELOW_START lies under it
    scan_start_m: float = math.nan
    #: where the scene at this value leaves the model's assumptions (as a Result's warnings)
    warnings: tuple[str, ...] = ()


@dataclass
class ThresholdStudy:
    """The rows of :func:`thresholds`, the field, and the fitted log-log slopes."""

    field: str
    rows: list[ThresholdRow] = field(default_factory=list)

    def table(self):
        """The rows as a pandas DataFrame (SI columns; the field's values in ``value``; the
        warnings of a row joined by '; ', empty for none)."""
        import pandas as pd

        rows = [{**asdict(r), "warnings": "; ".join(r.warnings)} for r in self.rows]
        return pd.DataFrame(rows)

    def slope(self, column: str, first: int | None = None) -> float:
        """The least-squares slope of log(column) against log(value), over the ``first`` rows."""
        rows = self.rows[:first] if first else self.rows
        x = np.log([r.value for r in rows])
        y = np.array([getattr(r, column) for r in rows], dtype=float)
        ok = np.isfinite(y) & (y > 0.0)
        # values that differ only by rounding ("1 um", "1000 nm", "1e-6 m") span nothing to fit
        # a slope over (polyfit warned it was poorly conditioned and gave 0.75 for an R^-2 law)
        if ok.sum() < 2 or np.ptp(x[ok]) <= SAME_VALUE:
            return math.nan
        return float(np.polyfit(x[ok], np.log(y[ok]), 1)[0])

    def to_json(self) -> dict[str, Any]:
        """The rows and the slopes (all rows, and the smallest third: the small-particle end)."""
        small = max(2, len(self.rows) // 3)
        return {"field": self.field,
                "rows": [{**asdict(r), "warnings": list(r.warnings)} for r in self.rows],
                "slopes": {c: {"all": self.slope(c), "small": self.slope(c, small)}
                           for c in ("slide_amplitude_m", "removal_amplitude_m",
                                     "rigid_removal_m")},
                "small_rows": small}


def parse_device_axis(spec: str) -> tuple[str, list[float]]:
    """``FIELD=START:STOP:N`` (log-spaced, ends with units, e.g. ``1 um:50 um:15``) or a comma list;
    values in SI. One line naming the axis on bad input."""
    if "=" not in spec:
        raise SceneError(f"--axis {spec!r} must be FIELD=START:STOP:N, e.g. "
                         "device.particle.radius=1 um:50 um:15")
    name, _, values = (part.strip() for part in spec.partition("="))
    check_dotted(name)
    if not name.startswith("device."):
        raise SceneError(f"--axis {name}: a threshold study sweeps a [device] field (in SI "
                         "units), e.g. device.particle.radius")
    kind = FIELD_KIND.get(name.rsplit(".", 1)[-1])

    def si(text: str) -> float:
        try:
            return field_si(name, text.strip()) if kind else float(text)
        except ValueError as exc:
            raise SceneError(f"--axis {name}: {text.strip()!r} {exc}") from None

    parts = values.split(":")
    if len(parts) == 3:
        # the ends first, in the order written ('a:b:c' was told that N = 'c' must be an
        # integer, not that 'a' is no length)
        lo, hi = si(parts[0]), si(parts[1])
        try:
            n = int(parts[2])
        except ValueError:
            raise SceneError(f"--axis {name}: N = {parts[2]!r} must be an integer") from None
        if not (lo > 0 and hi > 0 and 1 <= n <= 1000):
            raise SceneError(f"--axis {name}: START, STOP must be > 0 and 1 <= N <= 1000")
        if n == 1 and lo != hi:
            raise SceneError(f"--axis {name}: N = 1 cannot hold both ends {parts[0].strip()!r} "
                             f"and {parts[1].strip()!r}: give N >= 2, or one value")
        return name, np.geomspace(lo, hi, n).tolist() if n > 1 else [lo]
    out = [si(v) for v in values.split(",") if v.strip()]
    if not out:
        raise SceneError(f"--axis {name} must hold at least one value")
    return name, out


def rigid_removal(scene: Scene) -> tuple[float, float, float]:
    """(A_rigid in m, F_pull in N, M g in N) of a device scene with adhesion (module text)."""
    dev = scene.device
    n = normalized(dev)
    pull = normalized_adhesion(dev, scene.effects.adhesion) * n["weight_n"]
    omega = 2.0 * math.pi * n["frequency_hz"]
    return (pull + n["weight_n"]) / (n["mass_kg"] * omega**2), pull, n["weight_n"]


def stiff_removal_lost(law: str, ratio: float, m_star: float = 1e-5,
                       pulloff: float = 10.0) -> bool:
    """Whether a normalized adhesive DEM sphere loses contact at ``ratio`` times the rigid removal
    amplitude A* = (1 + F*_pull) / (4 pi^2 m*) (vertical vibration, a 100-period ramp, 12000
    steps a period): the stiff-contact oracle of the rigid limit (m* = 1e-5: the contact's
    natural frequency about 100 times the drive)."""
    amp = ratio * (1.0 + pulloff) / (4.0 * math.pi**2 * m_star)
    scene = Scene(model="hertz_mindlin_dem", particle={"m_star": m_star},
                  material={"adhesion": pulloff, "mu": 0.3},
                  effects={"adhesion": law, "horizontal_wave": False},
                  drive={"amplitude": amp, "ramp_periods": 100},
                  numerics={"periods": 104, "settle": False, "steps_per_period": 12000})
    return bool(run(scene).contact_lost)


#: log-values of the field closer than this are one value for a slope (:meth:`ThresholdStudy.slope`)
SAME_VALUE = 1e-9

#: halvings (in log) that locate the largest amplitude the device's wave may have
BOUND_HALVINGS = 40


def _allowed_top(refuses: Callable[[float], bool], ok: float, bad: float) -> float:
    """The largest amplitude in [``ok``, ``bad``) that ``refuses`` allows: ``ok`` is allowed,
    ``bad`` is not. Only the scenes are built (a scene beyond the bound is refused before it
    runs), so this costs no run."""
    for _ in range(BOUND_HALVINGS):
        mid = math.sqrt(ok * bad)
        ok, bad = (ok, mid) if refuses(mid) else (mid, bad)
    return ok


def first_crossing(crosses: Callable[[float], bool], start: float, factor: float,
                   stop: float, bisections: int,
                   refuses: Callable[[float], bool] | None = None) -> tuple[float, int, str]:
    """The smallest amplitude where ``crosses`` turns True, from below (module text), the runs it
    took and how it was found (:data:`FOUND`, or NaN and :data:`BELOW_START` where the first
    amplitude already crosses, :data:`ABOVE_STOP` where none up to ``stop`` does, the last
    grid point put at ``stop`` itself, :data:`ABOVE_BOUND` where none does up to the largest
    amplitude ``refuses`` allows: the grid's last point is put there too). ``crosses`` is asked
    only of allowed amplitudes; ``start`` must be allowed and not exceed ``stop``."""
    if start > stop:
        raise ValueError(f"the scan's start {start:g} is above its stop {stop:g}")
    lo, amp, runs, top = math.nan, start, 0, stop
    while True:
        amp = min(amp, top)
        if refuses is not None and refuses(amp):
            if math.isnan(lo):
                return math.nan, runs, ABOVE_BOUND  # nothing allowed to try
            top = _allowed_top(refuses, lo, amp)  # the grid's last point: the bound itself
            if top <= lo:
                return math.nan, runs, ABOVE_BOUND
            continue
        runs += 1
        if crosses(amp):
            break
        if amp >= top:
            return math.nan, runs, ABOVE_STOP if top >= stop else ABOVE_BOUND
        lo, amp = amp, amp * factor
    if math.isnan(lo):
        return math.nan, runs, BELOW_START  # crossed at the start: no bracket to bisect
    hi = amp
    for _ in range(bisections):
        mid = math.sqrt(lo * hi)
        runs += 1
        lo, hi = (lo, mid) if crosses(mid) else (mid, hi)
    return math.sqrt(lo * hi), runs, FOUND


def _refused(base: Scene, amp: float) -> bool:
    """Whether the device of ``base`` refuses the wave amplitude ``amp`` (:func:`_refusal`)."""
    return _refusal(base, amp) is not None


def _refusal(base: Scene, amp: float) -> str | None:
    """Why the device of ``base`` refuses the wave amplitude ``amp`` (its surface strain or
    speed bound, its range, or an A* beyond what the model integrates), or None."""
    try:
        base.with_updates(**{"device.amplitude": amp})
    except SceneError as exc:
        return str(exc).splitlines()[0]
    return None


def _check_start(base: Scene, name: str, value: float, start: float, stop: float) -> None:
    """One line where a value's scan cannot start: ``start`` times its rigid removal amplitude
    above ``stop``, or beyond the largest amplitude its wave may have (nothing would be run,
    and '> STOP' would claim what no run showed)."""
    first = start * rigid_removal(base)[0]
    where = f"at {name} = {value:g}"
    if first > stop:
        raise SceneError(f"--start {start:g} times the rigid removal amplitude is {first:.4g} m "
                         f"{where}, above --stop {stop:.4g} m: lower --start or raise --stop")
    why = _refusal(base, first)
    if why is not None:
        # the device's own reason (a strain or speed bound, or an A* above what the model
        # integrates: it blamed the strain bound for a 20 nm sphere 25 times below it)
        raise SceneError(f"--start {start:g} times the rigid removal amplitude is {first:.4g} m "
                         f"{where}, beyond the largest amplitude the device may have: "
                         f"{why.removeprefix('scene: ')}; lower --start")


def thresholds(scene: Scene, name: str, values: Sequence[float], *, start: float = 0.01,
               stop: float = 1e-8, per_decade: int = 4, bisections: int = 8,
               periods: float | None = None, engine: str = "compiled",
               show: bool = True) -> ThresholdStudy:
    """Sliding and removal amplitudes at each value of the device field ``name`` (module text).

    The scan starts at ``start`` times the rigid removal amplitude and ends at the amplitude
    ``stop`` (m; a threshold above it is NaN), ``per_decade`` grid points per decade, then
    ``bisections`` halvings (in log) of the bracket. ``periods`` replaces the scene's
    ``numerics.periods``: a particle counts as removed when it has not come back by the run's end,
    so a longer run removes at lower amplitudes where the contact is pumped slowly.
    """
    if scene.device is None or scene.effects.adhesion == "none":
        raise SceneError("sawdrift threshold needs a device scene with effects.adhesion = 'dmt' "
                         "or 'jkr' and device.adhesion > 0")
    if name == "device.amplitude":
        raise SceneError("--axis device.amplitude: the amplitude is what the study scans; sweep "
                         "another device field, e.g. device.particle.radius")
    factor = 10.0 ** (1.0 / per_decade)
    study = ThresholdStudy(name)
    fixed: dict[str, Any] = {"numerics.settle": False}
    if periods is not None:
        fixed["numerics.periods"] = periods
    # every value's scene first: a value outside its field's range, or whose scan would start
    # above --stop or beyond its wave's bound, is refused before any run
    bases = [bind(scene.with_updates(**{name: value, **fixed})) for value in values]
    for value, base in zip(values, bases, strict=True):
        _check_start(base, name, value, start, stop)
    bar = counter(len(values), "threshold", "value", enabled=show)
    for value, base in zip(values, bases, strict=True):
        a_rigid, pull, weight = rigid_removal(base)
        cache: dict[float, Any] = {}

        def result(amp: float, base: Scene = base, cache: dict = cache) -> Any:
            if amp not in cache:
                cache[amp] = run(base.with_updates(**{"device.amplitude": amp}), engine=engine)
            return cache[amp]

        def slides(amp: float, result: Callable[[float], Any] = result) -> bool:
            res = result(amp)
            return bool(res.contact_lost or res.gross_slip_fraction > 0.0)

        def removed(amp: float, result: Callable[[float], Any] = result) -> bool:
            return result(amp).regime == "ejected"

        refuses = partial(_refused, base)
        slide, _, slide_found = first_crossing(slides, start * a_rigid, factor, stop,
                                               bisections, refuses)
        removal, _, removal_found = first_crossing(removed, start * a_rigid, factor, stop,
                                                   bisections, refuses)
        study.rows.append(ThresholdRow(float(value), slide, removal, a_rigid, pull, weight,
                                       len(cache), slide_found, removal_found,
                                       start * a_rigid,
                                       tuple(device_warnings(base.device, base.effects.adhesion))))
        bar.update(1)
    bar.close()
    return study
