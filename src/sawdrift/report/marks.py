"""What every regime figure draws over its cells: creep markers, the contact resonances, device ticks.

* **Creep** (:func:`sawdrift.result.regimes.creep`): a drift in permanent contact with no gross
  slip in the measuring window. Its cells get a small open circle (:data:`CREEP_STYLE`), named in
  the legend.
* **Contact resonances** on an m* axis. Linearized about the static compression (a* = 1, b* = 0)
  of a profile with N*(a*) = a*^p, the normal equation m* y*'' = 1 - N*(a*) has the stiffness
  dN*/da* = p, so the free vertical oscillation has omega^2 = p / m* per unit t*; the tangential
  one, m* x*'' = -mu T* with b* = x* / (theta mu) and dT*/db* = p at b* = 0 (the memory law's
  initial slope, T* = N*(a*) - N*(a* - b*)), has omega^2 = p / (theta m*). The wave drives at
  omega = 2 pi, so the resonances lie at

      m*_N = p / (4 pi^2)            (sphere: 3 / (8 pi^2) = 0.0380)
      m*_T = p / (4 pi^2 theta)      (sphere, nu = 0.3, theta = 1.2143: 0.0313)

  and a sphere free to turn moves its contact point like a mass kappa / (1 + kappa) of the
  particle's, which multiplies m*_T by 1 + 1/kappa (3.5 for a solid sphere; kappa from a swept
  ``particle.gyration`` column, else the default 2/5). The normal one is
  a dashed line, the tangential one a dotted line, both named in the legend.
* **Device axes** (swept ``device.*`` fields, stored in SI units): engineering-prefixed tick
  labels (10 nm, 20 nm; 5 MHz) at 1-2-5 steps, instead of the colliding 2x10^-8 3x10^-8.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pandas as pd
from matplotlib.lines import Line2D
from matplotlib.ticker import EngFormatter, LogLocator, MaxNLocator, NullFormatter

from ..contact.registry import get_model
from ..result.regimes import creep
from ..scene.device import SHAPE_EXPONENT
from ..scene.rayleigh import theta as theta_of_nu
from ..study.axes import column_unit

#: marker of a creep cell (an open circle at the cell's centre)
CREEP_STYLE = {"marker": "o", "s": 18, "facecolors": "white", "edgecolors": "k", "linewidths": 0.8}
CREEP_LABEL = "creep: drift with no gross slip"

#: line styles of the normal and the tangential contact resonance
RESONANCE_STYLE = {"normal": {"ls": (0, (5, 3)), "color": "k", "lw": 1.1},
                   "tangential": {"ls": (0, (1, 2)), "color": "k", "lw": 1.3}}

def creep_cells(table: pd.DataFrame) -> np.ndarray:
    """True for each row that creeps: its ``creep`` column, or (older tables) its regime and
    ``gross_slip_fraction`` read by :func:`sawdrift.result.regimes.creep`."""
    if "creep" in table.columns:
        return table["creep"].astype("boolean").fillna(False).to_numpy(bool)
    if "gross_slip_fraction" not in table.columns:
        return np.zeros(len(table), dtype=bool)
    slip = pd.to_numeric(table["gross_slip_fraction"], errors="coerce").to_numpy(float)
    return np.array([creep(str(r), float(s)) for r, s in zip(table["regime"], slip, strict=True)],
                    dtype=bool)


def _single(rows: pd.DataFrame, column: str) -> Any:
    """The one value of ``column`` in ``rows`` (None if absent, missing, or several)."""
    if column not in rows.columns:
        return None
    values = rows[column].dropna().unique()
    return values[0] if len(values) == 1 else None


def _compliant(model: object) -> bool:
    """Whether ``model`` is a registered compliant contact law (a rigid one has no resonance)."""
    try:
        return not get_model(str(model)).capabilities.rigid
    except Exception:  # noqa: BLE001 - a model this installation does not know: draw nothing
        return False


def resonances(rows: pd.DataFrame) -> dict[str, float]:
    """m* of the normal and tangential contact resonances of a panel's rows (module docstring).

    Empty for a rigid model (the material point has no contact stiffness) and where the rows do
    not share one compliant model and one profile with a power law N*(a*) = a*^p; the tangential
    one is left out where they do not share one theta.
    """
    if not _compliant(_single(rows, "model")):
        return {}
    shape = _single(rows, "profile")
    p = SHAPE_EXPONENT.get(str(shape)) if shape is not None else None
    if p is None:
        return {}
    out = {"normal": p / (4.0 * math.pi**2)}
    theta = _single(rows, "material.theta")
    if theta is None and "material.theta" in rows.columns and rows["material.theta"].notna().any():
        return out  # several thetas
    if theta is None:
        nu = _single(rows, "nu")
        theta = theta_of_nu(float(nu)) if nu is not None else None
    if theta is None:
        return out
    turns = _turning(rows)
    if turns is None:
        return out  # some rows turn and some do not
    kappa = _single(rows, "particle.gyration") if turns else None
    gain = 1.0 + 1.0 / float(kappa if kappa is not None else 0.4) if turns else 1.0
    out["tangential"] = gain * p / (4.0 * math.pi**2 * float(theta))
    return out


def _turning(rows: pd.DataFrame) -> bool | None:
    """Whether the rows' sphere turns: a swept ``effects.rotation`` column, else the spin rate (a
    number only for a turning sphere, whatever the base scene set); None where they differ."""
    if "effects.rotation" in rows.columns:
        values = rows["effects.rotation"].dropna().unique()
        return bool(values[0]) if len(values) == 1 else None
    if "spin_rate" not in rows.columns:
        return False
    spins = pd.to_numeric(rows["spin_rate"], errors="coerce").notna()
    return bool(spins.iloc[0]) if spins.nunique() == 1 else None


def draw_resonances(ax, rows: pd.DataFrame, x: str, y: str) -> list[Line2D]:
    """Lines at the contact resonances across an m* axis that shows them; legend handles."""
    if "m_star" not in (x, y):
        return []
    lo, hi = ax.get_ylim() if y == "m_star" else ax.get_xlim()
    handles = []
    for kind, m in resonances(rows).items():
        if not min(lo, hi) < m < max(lo, hi):
            continue
        style = RESONANCE_STYLE[kind]
        (ax.axhline if y == "m_star" else ax.axvline)(m, **style, zorder=4)
        rolling = kind == "tangential" and bool(_turning(rows))
        handles.append(Line2D([], [], **style, label=resonance_label(kind, m, rolling)))
    return handles


def resonance_label(kind: str, m: float, rolling: bool = False) -> str:
    """The legend entry of a resonance line; a rolling sphere's tangential one says so (a
    comparison of rotation off and on showed two identical dotted entries, m* = 0.031 and
    0.11, with nothing to tell which was which)."""
    return f"{kind} contact resonance{' (rolling sphere)' if rolling else ''}, m* = {m:.2g}"


def mark_creep(ax, xs: np.ndarray, ys: np.ndarray, mask: np.ndarray) -> list[Any]:
    """Open circles at the centres of the creep cells (``mask`` [y, x] over ``xs``, ``ys``)."""
    if not mask.any():
        return []
    iy, ix = np.nonzero(mask)
    ax.scatter(np.asarray(xs)[ix], np.asarray(ys)[iy], **CREEP_STYLE, zorder=5)
    return [creep_handle()]


def creep_handle() -> Line2D:
    """The legend entry of the creep marker."""
    return Line2D([], [], ls="none", marker="o", mfc="white", mec="k", ms=5, mew=0.8,
                  label=CREEP_LABEL)


def device_unit(column: str) -> str:
    """SI unit of a device column (``device.amplitude`` -> ``m``), else ``""``
    (:func:`sawdrift.study.axes.column_unit`)."""
    return (column_unit(column) or "") if column.startswith("device.") else ""


def format_device_axes(ax, x: str, y: str) -> None:
    """Engineering tick labels with units on the device axes of ``ax`` (log or linear)."""
    for column, axis in ((x, ax.xaxis), (y, ax.yaxis)):
        unit = device_unit(column)
        if not unit:
            continue
        if axis.get_scale() == "log":
            lo, hi = sorted(ax.get_xlim() if axis is ax.xaxis else ax.get_ylim())
            decades = math.log10(hi / lo) if lo > 0 else math.inf
            subs = (1.0,) if decades > 2.5 else (1.0, 2.0, 5.0)
            axis.set_major_locator(LogLocator(base=10.0, subs=subs))
            axis.set_minor_formatter(NullFormatter())
        else:
            axis.set_major_locator(MaxNLocator(nbins=5, steps=[1, 2, 5, 10]))
        axis.set_major_formatter(EngFormatter(unit=unit, places=None, sep=" "))
