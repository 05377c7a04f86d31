"""Energy balance of a run: the integrator's consistency check.

From paper eq. 5, m* x*'' = -mu T* and m* y*'' = 1 - N*, so the kinetic energy of the particle
changes by the work of friction, of the normal reaction and of gravity (the unit force M g):

    d/dt (m* (x*'^2 + y*'^2) / 2) = -mu T* x*' + (1 - N*) y*'.

A rolling sphere (I = kappa m R^2) also carries I phi'^2 / 2 = m* (x*'/kappa)^2 kappa / 2, since
R phi' = x*'/kappa from rest; friction then works on the contact point s*' = (1 + 1/kappa) x*':

    d/dt (m* ((1 + 1/kappa) x*'^2 + y*'^2) / 2) = -mu T* (1 + 1/kappa) x*' + (1 - N*) y*'.

The residual between the two sides, integrated along a recorded trajectory (trapezoidal rule),
measures the integration error; it must shrink as the step is refined.
"""

from __future__ import annotations

import numpy as np
import pandas as pd


def energy_residual(
    trajectory: pd.DataFrame, m_star: float, mu: float, gyration: float | None = None
) -> tuple[float, float]:
    """(largest |Delta KE - W|, total |work|) along a trajectory recorded at every step.

    Parameters
    ----------
    trajectory
        Columns t, vx, vy, N, T (as returned by ``run(..., trajectory=True, record_every=1)``).
    m_star, mu
        Normalized mass and friction coefficient of the scene.
    gyration
        kappa of a rolling sphere (rotation on), or None without rotation.
    """
    c = 1.0 + 1.0 / gyration if gyration is not None else 1.0
    t = trajectory["t"].to_numpy()
    vx = trajectory["vx"].to_numpy()
    vy = trajectory["vy"].to_numpy()
    power = -mu * trajectory["T_star"].to_numpy() * c * vx + (1.0 - trajectory["N_star"].to_numpy()) * vy
    dt = np.diff(t)
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * dt)])
    kinetic = 0.5 * m_star * (c * vx**2 + vy**2)
    residual = np.abs(kinetic - kinetic[0] - work)
    scale = float(np.sum(0.5 * (np.abs(power[1:]) + np.abs(power[:-1])) * dt))
    return float(residual.max()), scale
