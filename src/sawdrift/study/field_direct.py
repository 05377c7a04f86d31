"""A direct run through the drift field of two waves, and the field's prediction of it.

:func:`direct_run` integrates the particle with the drive at its own position (``drive.
wavelength`` = L*) and compares it with the field's prediction (:func:`predict_path`),
dxi/dt = V(xi + rate t*/720) / L*: a phase ramp of ``rate`` degrees per period moves the field
by -rate/720 wavelengths per period. :func:`direct_scenes` checks what a direct run can run
before any field is computed.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..dynamics.assembly import steps_per_period
from ..dynamics.drives.two_wave import field_shift
from ..errors import SceneError
from ..result.runner import run
from ..scene.schema import Scene
from .field import PERIOD, Field, wavelength_star

__all__ = ["MOST_PERIODS", "direct_run", "direct_scenes", "nearest_zero", "predict_path"]


def predict_path(fld: Field, start: float, times: np.ndarray, wavelength: float,
                 rate: float = 0.0) -> np.ndarray:
    """xi(t*) from dxi/dt* = V(xi + rate t*/720) / L*, xi(0) = ``start`` (the field's prediction).

    ``rate`` is the phase ramp in degrees per period: the field moves by -rate/720 wavelengths
    per period (every local quantity depends on 4 pi xi + psi). Integrated with scipy's RK45
    (rtol 1e-8) on the periodic linear interpolation of the sampled field.
    """
    from scipy.integrate import solve_ivp

    times = np.asarray(times, dtype=float)
    t_end = float(times[-1]) if times.size else 0.0
    if t_end <= 0.0:
        return np.full(times.shape, float(start))

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        return np.array([float(fld.velocity_at(y[0] - field_shift(rate, t))) / wavelength])

    step = PERIOD / max(len(fld.positions), 1) * wavelength / max(np.max(np.abs(fld.drift_velocity)),
                                                                     1e-300)
    sol = solve_ivp(rhs, (0.0, t_end), [float(start)], t_eval=times, rtol=1e-8, atol=1e-12,
                    max_step=max(step, 1e-3))
    return sol.y[0]


def nearest_zero(fld: Field, xi: float, kind: str = "trap") -> float | None:
    """The zero of ``kind`` nearest to ``xi`` on the unrolled line (a zero at z stands for z + k/2)."""
    best = None
    for z in fld.zeros:
        if z["kind"] != kind:
            continue
        cand = z["position"] + PERIOD * round((xi - z["position"]) / PERIOD)
        if best is None or abs(cand - xi) < abs(best - xi):
            best = cand
    return best


def _row_interval(total: int, samples: int) -> int:
    """Steps between trajectory rows: a divisor of ``total`` (so that a row falls at its end),
    the largest giving at least ``samples`` rows."""
    target = max(1, total // max(samples, 2))
    for every in range(target, 0, -1):
        if total % every == 0:
            return every
    return 1


#: the most periods a scene may run (``numerics.periods``)
MOST_PERIODS = 1e7


def direct_scenes(scene: Scene, start: float, periods: float, wavelength: float | None = None,
                  samples: int = 400) -> tuple[Scene, Scene, int, int]:
    """The direct run's scene, the one it runs (one row interval longer: rows are taken before
    each step, so the run goes on one interval past its end for a row to fall at t* = periods;
    the last one was up to an interval short of it, 2992.5 of 3000), its steps and its row
    interval; one-line SceneErrors for what it cannot run, checked before any field is computed
    (a run too long for ``numerics.periods`` failed after the field, naming a length the user
    had not given)."""
    lstar = wavelength if wavelength is not None else wavelength_star(scene)
    if lstar is None:
        raise SceneError("a direct run needs the wavelength: drive.wavelength = L* (wavelength / "
                         "a0, --wavelength), or a device with device.wavelength or "
                         "device.substrate.density")
    if not (math.isfinite(periods) and periods >= 1.0):
        raise SceneError(f"periods = {periods!r}: a direct run needs at least 1 period")
    window = max(1, min(20, int(periods) // 2))
    sc = scene.with_updates(**{"drive.wavelength": float(lstar), "drive.position": float(start),
                               "numerics.settle": False, "numerics.measure_periods": window,
                               "numerics.periods": min(float(periods), MOST_PERIODS)})
    k_per = steps_per_period(sc)
    total = int(round(k_per * periods))
    every = _row_interval(total, samples)
    length = (total + every) / k_per
    if length > MOST_PERIODS:
        most = math.floor(MOST_PERIODS * total / (total + every))
        raise SceneError(f"periods = {periods:g}: a direct run goes one row interval past its "
                         f"end ({length:.8g} periods), and a run takes at most {MOST_PERIODS:g}; "
                         f"give at most {most:g}")
    return sc, sc.with_updates(**{"numerics.periods": length}), total, every


def direct_run(scene: Scene, start: float, periods: float, fld: Field | None = None, *,
               wavelength: float | None = None, samples: int = 400,
               engine: str = "compiled") -> dict[str, Any]:
    """Integrate the particle with the drive at its own position and compare with the field.

    The run starts at xi = ``start`` (``drive.position``) with ``drive.wavelength`` = L*
    (``wavelength``, else the scene's or its device's, :func:`wavelength_star`) for ``periods``
    periods, no settle criterion. Returns ``{"start", "wavelength_star", "periods",
    "final_position", "trajectory": {"t", "position"}}`` (``samples`` points, xi in
    wavelengths) and, given the field ``fld`` of the same scene, ``"predicted"``: the path of
    :func:`predict_path` on the same times, its final position and the trap nearest to it.
    """
    sc, longer, total, every = direct_scenes(scene, start, periods, wavelength, samples)
    lstar = float(sc.drive.wavelength)
    k_per = steps_per_period(sc)
    res = run(longer, trajectory=True, engine=engine, record_every=every)  # type: ignore[arg-type]
    tr = res.trajectory
    tr = tr[tr["t"] <= total / k_per + 0.5 / k_per]
    t = tr["t"].to_numpy(dtype=float)
    xi = float(start) + tr["x"].to_numpy(dtype=float) / lstar
    out: dict[str, Any] = {
        "start": float(start), "wavelength_star": float(lstar), "periods": float(periods),
        "backward_phase_rate": sc.drive.backward_phase_rate,
        "final_position": float(xi[-1]), "regime": res.regime,
        "trajectory": {"t": t.tolist(), "position": xi.tolist()},
    }
    if fld is not None:
        rate = sc.drive.backward_phase_rate
        pred = predict_path(fld, start, t, lstar, rate)
        shift = field_shift(rate, float(t[-1]))
        trap = nearest_zero(fld, float(pred[-1]) - shift)
        out["predicted"] = {
            "final_position": float(pred[-1]),
            "trap": None if trap is None else trap + shift,
            "trajectory": {"t": t.tolist(), "position": pred.tolist()},
        }
    return out
