"""The text of ``sawdrift run``: a run's summary grouped, and several models side by side.

The summary (``Result.summary()``, also ``run --json``) is printed in five groups, in this order:
regime, drift, settled, evidence, provenance. A device's speed in m/s comes first, on a line of
its own. Fields that do not apply (None) are left out; nested values (a device's normalized
scene) are printed one field a line. A drift that has not settled says so beside the number; a
long-time mean (chaotic or irregular motion) is printed with its standard error, drift +- error.
"""

from __future__ import annotations

import math
from typing import Any

#: the groups of ``run``'s text output and the summary fields of each, in order; a field not
#: named here (a new model's or drive's extra output) goes to "evidence"
GROUPS: dict[str, tuple[str, ...]] = {
    "regime": ("regime", "direction", "hop_period", "liftoffs_per_hop", "liftoff_phases",
               "orbit_period", "chaotic", "contact_lost", "mean_acceleration", "detach_time",
               "detach_time_s", "detach_phase", "warnings"),
    "drift": ("drift_speed_m_s", "drift_velocity", "drift_ratio", "drift_ratio_se", "t90_s",
              "load_n", "power_w", "rebound_ratio", "contact_duration", "max_compression", "dissipated_work"),
    "settled": ("settled", "settle_method", "settle_periods", "t90_periods", "horizontal_inertia"),
    "evidence": ("out_of_contact_fraction", "min_compression", "gross_slip_fraction", "creep",
                 "liftoffs_per_period", "liftoff_phase", "liftoff_phase_spread", "lyapunov",
                 "periodicity", "spin_rate", "events_dropped"),
    "provenance": ("model", "engine", "version", "m_star", "amplitude", "mu", "nu",
                   "horizontal_ratio", "orbit", "profile", "steps_per_period", "periods",
                   "ramp_periods", "measure_periods", "steps", "wall_time_s", "compile_s",
                   "normalized"),
}

#: the drift fields that carry the NOT settled mark
DRIFTS = ("drift_speed_m_s", "drift_velocity", "drift_ratio")

#: units of fields that have them
UNITS = {"drift_speed_m_s": "m/s", "t90_s": "s", "detach_time_s": "s", "load_n": "N", "power_w": "W",
         "wall_time_s": "s", "compile_s": "s", "drift_velocity": "a0 f"}

#: rows of the side-by-side table of several models
TABLE_ROWS = ("regime", "drift_speed_m_s", "drift_velocity", "drift_ratio", "settled",
              "contact_lost", "gross_slip_fraction", "liftoffs_per_period", "hop_period", "lyapunov",
              "spin_rate", "steps_per_period", "periods", "wall_time_s")


def value_text(value: Any) -> str:
    """A value as printed: floats to 6 significant digits, booleans as yes / no."""
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, list):
        return ", ".join(value_text(v) for v in value)
    return str(value)


def _flat(summary: dict[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in summary.items():
        if key == "scene" or value is None or (isinstance(value, list) and not value):
            continue  # the whole scene is in --json and in -o DIR/scene.toml; [] does not apply
        if isinstance(value, dict):
            for sub, v in value.items():
                if v is not None:
                    out[f"{key}.{sub}"] = v
        else:
            out[key] = value
    return out


def unsettled_text(summary: dict[str, Any], mark: str = "NOT settled") -> str:
    """Why the drift is not the steady one, short enough to stand beside a number."""
    regime = summary.get("regime")
    if regime == "runaway":
        si = summary.get("mean_acceleration_m_s2")  # a device's, in m/s^2 beside a0 f^2
        return (f"{mark}: no steady state, the mean speed grows by "
                f"{value_text(summary.get('mean_acceleration'))} per period"
                + (f" ({value_text(si)} m/s^2)" if si is not None else ""))
    if regime == "ejected":
        return (f"{mark}: no steady state, out of contact since t* = "
                f"{value_text(summary.get('detach_time'))}")
    if drift_error(summary, "drift_ratio") is not None:
        kind = "chaotic" if summary.get("chaotic") else "irregular"
        return f"{mark}: {kind}, a long-time mean with its standard error"
    if summary.get("chaotic"):
        return f"{mark}: chaotic, an average over the window"
    if summary.get("settle_method") == "solved":
        # solved directly, its slow-cycle average uncertain under a load (the warning says how
        # much): it was said to be "still changing after 119 periods"
        return f"{mark}: solved directly, its average uncertain (see warnings)"
    return f"{mark} after {value_text(summary.get('periods'))} periods"


def drift_error(summary: dict[str, Any], key: str) -> float | None:
    """The standard error of the drift field ``key`` (``drift_ratio``, ``drift_velocity`` or
    ``drift_speed_m_s``) where the drift is a long-time mean (``drift_ratio_se`` finite, scaled
    by the field's ratio to the drift ratio); None otherwise."""
    se = summary.get("drift_ratio_se")
    ratio = summary.get("drift_ratio")
    value = summary.get(key)
    if not all(isinstance(v, float) and math.isfinite(v) for v in (se, ratio, value)):
        return None
    if key == "drift_ratio":
        return se
    return abs(value / ratio) * se if ratio != 0.0 else None


def pm_text(value: float | None, se: float | None, spec: str = ".6g") -> str:
    """``value +- se`` (the error to 2 significant digits), the value alone where it has no
    finite error, ``none`` for no value: a drift, speed or load as the curves print it."""
    if value is None or not math.isfinite(value):
        return "none"
    text = format(value, spec)
    return text if se is None or not math.isfinite(se) else f"{text} +- {se:.2g}"


def drift_text(summary: dict[str, Any], key: str) -> str:
    """A drift field as printed: its value, and +- its standard error for a long-time mean."""
    text = value_text(summary.get(key))
    err = drift_error(summary, key)
    return text if err is None else f"{text} +- {err:.2g}"


def _line(key: str, value: Any, summary: dict[str, Any], width: int) -> str:
    text = drift_text(summary, key) if key in DRIFTS else value_text(value)
    unit = UNITS.get(key)
    if unit is not None and not isinstance(value, bool):
        text += f" {unit}"
    if key in DRIFTS and summary.get("settled") is False:
        text += f"  <- {unsettled_text(summary)}"
    if key == "settled" and value is False:
        no_state = summary.get("regime") in ("runaway", "ejected")
        # a fixed run's one window cannot confirm a creep or a motion off any orbit: it may be
        # converged (hertz_mindlin_dem m* 50, A* 0.05 creeps at 0.00626318 after 22000 and 44000
        # periods alike), so "not confirmed", not "still changing"
        fixed = summary.get("settle_method") == "fixed"
        solved = summary.get("settle_method") == "solved"
        text = unsettled_text(summary, "NO" if no_state or solved else
                              "NO, not confirmed by its fixed window" if fixed else
                              "NO, still changing")
    return f"  {key:<{width}}  {text}"


def grouped(summary: dict[str, Any]) -> list[str]:
    """The lines of ``run``'s text output (see the module docstring)."""
    flat = _flat(summary)
    lines: list[str] = []
    speed = flat.get("drift_speed_m_s")
    if speed is not None:
        way = flat.get("direction")
        head = f"drift speed {speed:.4g} m/s" + (f", {way} the wave" if way in ("with", "against")
                                                  else "")
        if summary.get("settled") is False:
            head += f" ({unsettled_text(summary)})"
        lines.append(head)
    elif "drift_speed_m_s" in summary and summary.get("regime") in ("runaway", "ejected"):
        lines.append(unsettled_text(summary, "no drift speed"))  # a device run without one
    placed: dict[str, list[str]] = {group: [] for group in GROUPS}
    home = {key: group for group, keys in GROUPS.items() for key in keys}
    for key in flat:
        group = home.get(key, home.get(key.split(".")[0], "evidence"))
        placed[group].append(key)
    order = {key: i for keys in GROUPS.values() for i, key in enumerate(keys)}
    width = max((len(k) for k in flat), default=8)
    for group, keys in placed.items():
        if not keys:
            continue
        lines.append(f"{group}:")
        keys.sort(key=lambda k: order.get(k.split(".")[0], len(order)))
        lines.extend(_line(k, flat[k], summary, width) for k in keys)
    return lines


def side_by_side(summaries: list[dict[str, Any]]) -> list[str]:
    """Several runs of one scene as a table: one column per model, one row per field."""
    names = [str(s["model"]) for s in summaries]
    rows = [key for key in TABLE_ROWS if any(s.get(key) is not None for s in summaries)]
    cells = []
    for key in rows:
        row = []
        for s in summaries:
            value = s.get(key)
            text = "-" if value is None else drift_text(s, key) if key in DRIFTS else value_text(value)
            if key in DRIFTS and value is not None and s.get("settled") is False:
                text += " (NOT settled)"
            row.append(text)
        cells.append(row)
    width = max(len(k) for k in rows)
    cols = [max(len(n), *(len(r[i]) for r in cells)) for i, n in enumerate(names)]
    lines = [f"{'':<{width}}  " + "  ".join(f"{n:>{c}}" for n, c in zip(names, cols, strict=True))]
    for key, row in zip(rows, cells, strict=True):
        lines.append(f"{key:<{width}}  " + "  ".join(f"{v:>{c}}" for v, c in zip(row, cols,
                                                                                 strict=True)))
    return lines


def shared_warnings(summaries: list[dict[str, Any]]) -> list[str]:
    """The validity warnings of several runs, below their table: each warning once, with the
    models that carry it (all of them when every run does)."""
    holders: dict[str, list[str]] = {}
    for s in summaries:
        for warning in s.get("warnings") or ():
            holders.setdefault(str(warning), []).append(str(s["model"]))
    if not holders:
        return []
    lines = ["warnings:"]
    for warning, models in holders.items():
        who = "all models" if len(models) == len(summaries) else ", ".join(models)
        lines.append(f"  {who}: {warning}")
    return lines


#: distinct warnings of a curve's points printed in its text (the rest are counted)
SHOWN_WARNINGS = 3


def curve_warning_lines(per_point: list[Any], what: str, json_name: str) -> list[str]:
    """The stderr lines of a curve's point warnings (force-velocity, load-curve): each distinct
    text once with the number of points carrying it, at most :data:`SHOWN_WARNINGS`, then how
    many more. The note said "a lower-bound error, a motion still heating up" whatever the
    points carried (one said "the mean drift was still moving")."""
    counts: dict[str, int] = {}
    for texts in per_point:
        for text in dict.fromkeys(str(t) for t in (texts or ())):
            counts[text] = counts.get(text, 0) + 1
    if not counts:
        return []
    flagged = sum(1 for texts in per_point if texts)
    lines = [f"note: {flagged} of {len(per_point)} {what} carry warnings ({json_name} lists "
             "them by point):"]
    for text, n in list(counts.items())[:SHOWN_WARNINGS]:
        lines.append(f"warning ({n} {what if n > 1 else what.rstrip('s')}): {text}")
    if len(counts) > SHOWN_WARNINGS:
        lines.append(f"... and {len(counts) - SHOWN_WARNINGS} other warnings")
    return lines
