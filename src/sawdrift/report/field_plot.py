"""Figures of drift fields: V(xi) with regimes, traps and repellers; direct runs beside them.

One panel shows the field of every species over one wavelength (two periods of the field), each
sample coloured by its regime (the colours of the regime diagrams), traps as filled triangles
and repellers as open circles on V = 0. With a direct run a second panel shows the particle's
position against time beside the field's prediction (dxi/dt = V(xi) / L*) and the traps
(moving with a phase ramp). Device scenes are drawn in um and mm/s when their wavelength is
known (:func:`sawdrift.study.field.wavelength_star`), else in wavelengths and mm/s.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..scene.device import normalized
from ..study.field import PERIOD, Field, FieldStudy, field_shift, wavelength_star  # noqa: E402
from .diagrams import COLOURS  # noqa: E402

__all__ = ["field_units", "plot_field"]

_MARK = {"trap": ("v", "k", "trap"), "repeller": ("o", "none", "repeller"),
         "one-sided": ("D", "0.5", "one-sided zero")}


def field_units(fld: Field) -> tuple[float, str, float, str]:
    """(position scale, its unit, velocity scale, its unit) of a field's figure.

    A device scene: positions in um (xi times the wavelength) when the wavelength is known, the
    drift velocity in mm/s (x* per period times a0 f); otherwise wavelengths and x* per period.
    """
    sc = fld.scene
    if sc.device is None:
        return 1.0, "xi = X / wavelength", 1.0, "V (x* per period)"

    norm = normalized(sc.device)
    v_scale = norm["a0_m"] * norm["frequency_hz"] * 1e3
    lstar = wavelength_star(sc)
    if lstar is None:
        return 1.0, "xi = X / wavelength", v_scale, "V (mm/s)"
    return lstar * norm["a0_m"] * 1e6, "X (um)", v_scale, "V (mm/s)"


def _draw_field(ax: Any, fld: Field, colour: str, label: str) -> None:
    if fld.positions.size == 0:
        return  # a species Ctrl-C stopped before any of its positions ended: nothing to draw
    xs, xu, vs, vu = field_units(fld)
    x = np.concatenate([fld.positions, fld.positions + PERIOD, [fld.positions[0] + 2 * PERIOD]])
    v = np.concatenate([fld.drift_velocity, fld.drift_velocity, fld.drift_velocity[:1]])
    regimes = list(fld.regimes) * 2 + fld.regimes[:1]
    ax.plot(x * xs, v * vs, "-", color=colour, lw=1.2, label=label or None, zorder=2)
    if fld.drift_velocity_se is not None and np.isfinite(fld.drift_velocity_se).any():
        # a long-time mean (irregular motion): its standard error as a bar
        se = np.concatenate([fld.drift_velocity_se, fld.drift_velocity_se,
                             fld.drift_velocity_se[:1]])
        ok = np.isfinite(se)
        ax.errorbar(x[ok] * xs, v[ok] * vs, yerr=se[ok] * vs, fmt="none", ecolor=colour,
                    elinewidth=1.0, capsize=2, zorder=2.5)
    for reg in dict.fromkeys(regimes):
        sel = [i for i, r in enumerate(regimes) if r == reg]
        ax.scatter(x[sel] * xs, v[sel] * vs, s=16, color=COLOURS.get(reg, "0.6"),
                   edgecolors=colour, linewidths=0.5, zorder=3, label=f"_{reg}")
    for z in fld.zeros:
        marker, face, _ = _MARK.get(z["kind"], _MARK["one-sided"])
        for k in range(3):
            pos = z["position"] + k * PERIOD
            if pos <= 2 * PERIOD + 1e-12:
                ax.scatter([pos * xs], [0.0], marker=marker, s=70, facecolors=face,
                           edgecolors=colour if face == "none" else "k", linewidths=1.4, zorder=4)
    ax.set_xlabel(xu)
    ax.set_ylabel(vu)


def plot_field(study: FieldStudy, path: str | Path, title: str = "") -> Path:
    """Write the field figure (and the direct run, if the study has one) as a PNG."""
    direct = study.direct
    ncols = 2 if direct is not None else 1
    fig, axes = plt.subplots(1, ncols, figsize=(7.5 * ncols, 4.6), constrained_layout=True,
                             squeeze=False)
    ax = axes[0][0]
    cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, fld in enumerate(study.fields):
        _draw_field(ax, fld, cycle[i % len(cycle)], fld.label)
    ax.axhline(0.0, color="0.4", lw=0.8, zorder=1)
    ax.grid(alpha=0.3)
    regimes = list(dict.fromkeys(r for f in study.fields for r in f.regimes))
    handles = [plt.Line2D([], [], ls="", marker="o", color=COLOURS.get(r, "0.6"), label=r)
               for r in regimes]
    kinds = list(dict.fromkeys(z["kind"] for f in study.fields for z in f.zeros))
    handles += [plt.Line2D([], [], ls="", marker=_MARK[k][0], markerfacecolor=_MARK[k][1],
                           markeredgecolor="k", markersize=8, label=_MARK[k][2]) for k in kinds]
    if study.axis is not None:
        handles += [plt.Line2D([], [], color=cycle[i % len(cycle)], label=f.label)
                    for i, f in enumerate(study.fields)]
    ax.legend(handles=handles, fontsize=8, loc="best")
    sc = study.fields[0].scene
    d = sc.drive
    ax.set_title(title or f"{sc.model}: drift field, s = {d.backward:g}, psi = "
                 f"{d.backward_phase:g} deg", fontsize=10)
    if direct is not None:
        _draw_direct(axes[0][1], direct, study.fields[0])
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _draw_direct(ax: Any, direct: dict[str, Any], fld: Field) -> None:
    """The direct run's xi(t*) beside the field's prediction and the traps."""
    t = np.asarray(direct["trajectory"]["t"])
    xi = np.asarray(direct["trajectory"]["position"])
    ax.plot(t, xi, color="k", lw=1.4, label="direct run")
    pred = direct.get("predicted")
    if pred is not None:
        ax.plot(t, pred["trajectory"]["position"], "--", color="tab:red", lw=1.2,
                label="field: dxi/dt = V(xi) / L*")
    rate = direct.get("backward_phase_rate", 0.0)
    lo = min(xi.min(), np.min(pred["trajectory"]["position"]) if pred else xi.min()) - 0.1
    hi = max(xi.max(), np.max(pred["trajectory"]["position"]) if pred else xi.max()) + 0.1
    shift = -field_shift(rate, t)  # the field's move, owned by the drive
    first = True
    for z in fld.zeros:
        if z["kind"] != "trap":
            continue
        for k in range(int(np.floor((lo - 2) / PERIOD)), int(np.ceil((hi + 2) / PERIOD)) + 1):
            path = z["position"] + k * PERIOD - shift
            if np.any((path >= lo) & (path <= hi)):
                ax.plot(t, path, ":", color="0.45", lw=0.9, label="traps" if first else None)
                first = False
    ax.set_ylim(lo, hi)
    ax.set_xlabel("t* (wave periods)")
    ax.set_ylabel("xi = X / wavelength")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    ax.set_title(f"direct run, L* = {direct['wavelength_star']:g}"
                 + (f", phase ramp {rate:g} deg/period" if rate else ""), fontsize=10)
