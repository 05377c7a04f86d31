"""The prescribed-history scheme: a*(t*), b*(t*) fed straight into the contact law, no dynamics.

The contact law alone, as in a displacement-controlled test: each sample advances the committed
history along a straight path and commits. The run returns the sampled forces and the dissipated
work, the integral of T* db* over the path (trapezoidal).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..contact.base import ContactModel
from ..contact.history import ContactHistory
from ..errors import NonFiniteStateError
from ..scene.parts import polyline
from ..scene.schema import Prescribed, Scene

if TYPE_CHECKING:
    import pandas as pd


def prescribed_history(drive: Prescribed) -> tuple[np.ndarray, np.ndarray]:
    """The sampled a*(k), b*(k) of a prescribed drive (see :class:`~sawdrift.scene.Prescribed`)."""

    def path(vertices: list[tuple[float, float]]) -> tuple[np.ndarray, np.ndarray]:
        return polyline(vertices, drive.samples_per_segment)

    if drive.waveform == "samples":
        return np.asarray(drive.a, dtype=float), np.asarray(drive.b, dtype=float)
    if drive.waveform == "proportional":
        return path([(0.0, 0.0), (drive.a_max, drive.slope * drive.a_max)])
    if drive.waveform == "mindlin_loop":
        am, bb = drive.a_max, drive.b_amplitude
        vertices = [(0.0, 0.0), (am, 0.0), (am, bb)]
        for _ in range(drive.cycles):
            vertices += [(am, -bb), (am, bb)]
        return path(vertices)
    rng = np.random.default_rng(drive.seed)
    m = 10 * drive.cycles
    a_v = drive.a_max * rng.uniform(-0.3, 1.5, size=m)
    b_v = np.cumsum(drive.a_max * rng.normal(0.0, 0.5, size=m))
    return path([(0.0, 0.0), *zip(a_v.tolist(), b_v.tolist(), strict=True)])


@dataclass
class PrescribedRun:
    """A prescribed history driven through the contact law (see :func:`run_prescribed`).

    Attributes
    ----------
    a, b
        The sampled a*(k), b*(k).
    frame
        Columns t (the sample index), a, b, N_star, T_star.
    dissipated_work
        The integral of T* db* over the path (trapezoidal).
    wall_time_s
        Driving the history.
    """

    a: np.ndarray
    b: np.ndarray
    frame: pd.DataFrame = field(repr=False)
    dissipated_work: float
    wall_time_s: float


def run_prescribed(scene: Scene, model: ContactModel, engine: str) -> PrescribedRun:
    """Drive ``model`` through the scene's prescribed history (see :func:`prescribed_history`)."""
    drive = scene.drive
    assert isinstance(drive, Prescribed)
    t0 = time.perf_counter()
    a, b = prescribed_history(drive)
    history = ContactHistory(model, engine)
    n_f, t_f = history.drive(a, b)
    bad = ~np.isfinite(n_f + t_f)
    if bad.any():
        k = int(np.argmax(bad))
        raise NonFiniteStateError(
            f"model {scene.model!r} returned a non-finite force at sample {k} "
            f"(a* = {a[k]:.6g}, b* = {b[k]:.6g})"
        )
    import pandas as pd

    # dissipated work: the integral of T* db*, trapezoidal over the sampled path
    work = float(np.sum(0.5 * (t_f[1:] + t_f[:-1]) * np.diff(b))) if a.size > 1 else 0.0
    frame = pd.DataFrame({"t": np.arange(a.size, dtype=float), "a": a, "b": b, "N_star": n_f, "T_star": t_f})
    return PrescribedRun(a=a, b=b, frame=frame, dissipated_work=work,
                         wall_time_s=time.perf_counter() - t0)
