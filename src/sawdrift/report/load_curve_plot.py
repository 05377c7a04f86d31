"""Figure of a load curve: drift speed and output power against the load, the stall load marked."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..study.load_curve import LoadCurve

__all__ = ["plot_load_curve", "plot_load_curves"]


def _zero_aligned(ax, twin, v: list[float], p: list[float]) -> None:
    """Limits of both axes with their zero at the same height and room for every point.

    The zero sits at the fraction z of the height that the two series need: a speed below zero
    (a particle drifting to -x) and a power above it share the panel at z = 1/2.
    """
    def need(values: list[float]) -> tuple[float, float, float, float]:
        lo, hi = min([0.0, *values]), max([0.0, *values])
        span = (hi - lo) or 1.0
        return lo, hi, -lo / span, hi / span

    (lo_v, hi_v, below_v, above_v), (lo_p, hi_p, below_p, above_p) = need(v), need(p)
    below, above = max(below_v, below_p, 0.05), max(above_v, above_p, 0.05)
    z = below / (below + above)
    for axis, lo, hi in ((ax, lo_v, hi_v), (twin, lo_p, hi_p)):
        height = 1.1 * max(-lo / z, hi / (1.0 - z), 1e-300)
        axis.set_ylim(-z * height, (1.0 - z) * height)


def plot_load_curve(curve: LoadCurve, path: str | Path | None = None, title: str = "") -> Figure:
    """Speed (left axis) and power F v (right axis) against the load; write a PNG if ``path``.

    The speed is signed along +x, as in :func:`plot_load_curves` (a particle that drifts to -x
    without load is drawn below zero); the power F v is positive while the particle advances
    against the load. Device scenes are drawn in mN, m/s and mW, normalized ones in M g, a0 f
    and M g a0 f. The stall load (the top of its bracket) and the largest sampled power are
    marked where they are known (not where the unloaded drift is zero within its error), and a
    speed that is a long-time mean carries its standard error as an error bar.
    """
    data = curve.to_json()
    dev = data.get("device")
    sign = curve.direction or 1
    if dev is not None:
        x, v, p, err = dev["loads_mN"], dev["speed_m_s"], dev["power_mW"], dev["speed_se_m_s"]
        labels = ("load F against the drift (mN)", "drift speed along +x (m/s)",
                  "output power F v (mW)")
        stall, p_max, at = dev["stall_load_mN"], dev["max_power_mW"], dev["load_at_max_power_mN"]
        unit = "mN"
    else:
        x, v, p, err = data["loads"], data["drift_velocity"], data["power"], data["drift_velocity_se"]
        labels = ("load F against the drift / (M g)", "drift velocity along +x / (a0 f)",
                  "output power F v / (M g a0 f)")
        stall, p_max, at = data["stall_load"], data["max_power"], data["load_at_max_power"]
        unit = "M g"
    v = [sign * s for s in v]
    fig, ax = plt.subplots(figsize=(6.4, 4.6), layout="constrained")
    ax.plot(x, v, "o-", color="#3182bd", ms=4, lw=1.2, label="drift speed")
    bars = [(xi, vi, e) for xi, vi, e in zip(x, v, err, strict=True) if e is not None]
    if bars:
        ax.errorbar([b[0] for b in bars], [b[1] for b in bars], yerr=[b[2] for b in bars],
                    fmt="none", ecolor="#3182bd", elinewidth=1.0, capsize=3,
                    label="+- 1 standard error (long-time mean)")
    ax.axhline(0.0, color="k", lw=0.6)
    if stall is not None:
        ax.axvline(stall, color="0.4", ls="--", lw=0.9, label=f"stall load {stall:.4g} {unit}")
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1], color="#3182bd")
    ax.grid(alpha=0.3)
    twin = ax.twinx()
    twin.plot(x, p, "s-", color="#e6550d", ms=3.5, lw=1.0, label="output power")
    if p_max is not None:
        twin.plot([at], [p_max], "*", color="#e6550d", ms=12,
                  label=f"largest power {p_max:.4g} at {at:.4g} {unit}")
    twin.set_ylabel(labels[2], color="#e6550d")
    ends = [b[1] + d * b[2] for b in bars for d in (-1.0, 1.0)]  # room for the error bars
    _zero_aligned(ax, twin, [*v, *ends], p)
    handles = ax.get_legend_handles_labels()[0] + twin.get_legend_handles_labels()[0]
    # below the panel: over it, the legend hid one series or the other (they cross)
    fig.legend(handles, [h.get_label() for h in handles], fontsize=8, ncol=2, frameon=False,
               loc="outside lower center")
    ax.set_title(title or _title(data), fontsize=9)
    if path is not None:
        fig.savefig(Path(path), dpi=120)
        plt.close(fig)
    return fig


def _title(data: dict) -> str:
    """What the unloaded run says, as the figure's title."""
    state = data["free_state"]
    if state == "zero_within_error":
        return ("load curve: the drift without load is zero within 3 standard errors:\n"
                "no direction to load against, no stall load")
    if state == "no_drift":
        return "load curve: no drift without load, so nothing to stall"
    if state == "no_steady_state":
        return "load curve: no steady drift without load"
    caveat = " (not settled)" if state == "not_settled" else ""
    return f"load curve: the particle drifts to {data['direction']} without load{caveat}"


def plot_load_curves(curves: list[tuple[str, LoadCurve]], path: str | Path | None = None,
                     title: str = "") -> Figure:
    """Several species' load curves on one figure: speed against load, stall loads marked.

    Speeds are signed along +x (a species that drifts to -x without load is drawn below zero),
    so species that go opposite ways, or stall at different loads, read at a glance. Device
    scenes in mN and m/s, normalized ones in M g and a0 f.
    """
    fig, ax = plt.subplots(figsize=(6.4, 4.2), layout="constrained")
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    unit = "M g"
    for k, (label, curve) in enumerate(curves):
        data = curve.to_json()
        dev = data.get("device")
        sign = curve.direction or 1
        if dev is not None:
            x, v, stall, unit = dev["loads_mN"], dev["speed_m_s"], dev["stall_load_mN"], "mN"
            ax.set_xlabel("load F against the drift (mN)")
            ax.set_ylabel("drift speed along +x (m/s)")
        else:
            x, v, stall = data["loads"], data["drift_velocity"], data["stall_load"]
            ax.set_xlabel("load F against the drift / (M g)")
            ax.set_ylabel("drift velocity along +x / (a0 f)")
        colour = colours[k % len(colours)]
        text = (f"to {data['direction']}, stall {stall:.4g} {unit}" if stall is not None
                else f"{data['free_state'].replace('_', ' ')} without load, no stall load")
        ax.plot(x, [sign * s for s in v], "o-", ms=3.5, lw=1.2, color=colour,
                label=f"{label}: {text}")
        if stall is not None:
            ax.axvline(stall, color=colour, ls="--", lw=0.8)
    ax.axhline(0.0, color="k", lw=0.6)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title or "load curves of the species", fontsize=9)
    if path is not None:
        fig.savefig(Path(path), dpi=120)
        plt.close(fig)
    return fig
