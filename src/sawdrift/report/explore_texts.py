"""The explorer's texts of each cell (numpy arrays of strings, one per row of a sweep table):
warnings, chaos, the "+- error" of a long-time mean, a runaway's or an ejection's note."""

from __future__ import annotations

import numpy as np
import pandas as pd

from .._texts import HEATING

#: the words of the warning of a long-time mean whose batch-means error still grew with the
#: batch length (:func:`sawdrift.result.runner._warnings`): its "+- error" is a lower bound
LOWER_BOUND = "is a lower bound"


def _flags(rows: pd.DataFrame, column: str) -> np.ndarray:
    """A boolean column of ``rows`` (missing: false)."""
    if column not in rows.columns:
        return np.zeros(len(rows), dtype=bool)
    return rows[column].astype("boolean").fillna(False).to_numpy(bool)


def _number(rows: pd.DataFrame, column: str) -> np.ndarray:
    if column not in rows.columns:
        return np.full(len(rows), np.nan)
    return pd.to_numeric(rows[column], errors="coerce").to_numpy(float)


def warning_texts(rows: pd.DataFrame) -> np.ndarray:
    """Each row's warnings (the table's ``warnings`` column, "; "-joined), "none" where it has none."""
    if "warnings" not in rows.columns:
        return np.full(len(rows), "none")
    text = rows["warnings"].astype(object).where(rows["warnings"].notna(), "").astype(str)
    return np.array([t.strip() or "none" for t in text])


def chaotic_cells(rows: pd.DataFrame) -> np.ndarray:
    """Whether each row's motion is chaotic: its ``chaotic`` column, else its ``resolved_as``."""
    if "chaotic" in rows.columns:
        return _flags(rows, "chaotic")
    if "resolved_as" in rows.columns:
        return (rows["resolved_as"].astype(str) == "chaotic_mean").to_numpy(bool)
    return np.zeros(len(rows), dtype=bool)


def drift_notes(rows: pd.DataFrame) -> np.ndarray:
    """What the tooltip and the click header print beside each row's drift ratio.

    A long-time mean: its "+- error" (:func:`error_text`, which says whether the motion is
    chaotic, whether the error is only a lower bound and whether the bounces heat up); a cell
    with no steady state: why there is no drift ratio, a runaway's mean acceleration (the growth
    of its mean speed per period) or an ejected cell's detach time; else empty.
    """
    warnings = warning_texts(rows)
    notes = list(error_text(_number(rows, "drift_ratio_se"), heating_cells(rows),
                            chaotic_cells(rows), np.array([LOWER_BOUND in w for w in warnings])))
    accel, detach = _number(rows, "mean_acceleration"), _number(rows, "detach_time")
    stored = {"mean_acceleration": "mean_acceleration" in rows.columns,
              "detach_time": "detach_time" in rows.columns}
    for k, regime in enumerate(rows["regime"].astype(str)):
        if regime == "runaway":
            notes[k] = ("(runaway, no steady state: the mean speed grows by "
                        f"{accel[k]:.4g} per period, its mean acceleration)" if np.isfinite(accel[k])
                        else "(runaway, no steady state; mean acceleration "
                        + ("not computed)" if stored["mean_acceleration"] else
                           "not stored in this table)"))
        elif regime == "ejected":
            notes[k] = (f"(ejected, no steady state: out of contact since t* = {detach[k]:.4g})"
                        if np.isfinite(detach[k]) else "(ejected, no steady state; detach time "
                        + ("not computed)" if stored["detach_time"] else "not stored in this table)"))
    return np.array(notes, dtype=str)


def error_text(se: np.ndarray, heating: np.ndarray | None = None,
               chaotic: np.ndarray | None = None, lower: np.ndarray | None = None) -> np.ndarray:
    """The "+- error" beside a long-time mean's drift ratio (its batch-means standard error):
    whether the motion is ``chaotic``, whether the error is only a ``lower`` bound (it still
    grew with the batch length) and whether the bounces heat up (``heating``: the mean depends
    on the run's length); empty where the drift is not a long-time mean."""
    none = np.zeros(len(se), dtype=bool)
    heating, chaotic, lower = (none if a is None else a for a in (heating, chaotic, lower))
    out = []
    for v, hot, chaos, low in zip(se, heating, chaotic, lower, strict=True):
        if not np.isfinite(v):
            out.append("")
            continue
        parts = ["chaotic, long-time mean" if chaos else "long-time mean"]
        if low:
            parts.append("error only a lower bound: it still grew with the batch length")
        if hot:
            parts.append("heating up: it depends on the run's length")
        out.append(f"+- {float(v):.2g} ({', '.join(parts)})")
    return np.array(out, dtype=object).astype(str)


def heating_cells(rows: pd.DataFrame) -> np.ndarray:
    """Whether each row's warnings say its bounces heat up (a long-time mean that depends on
    how long it was run)."""
    if "warnings" not in rows.columns:
        return np.zeros(len(rows), dtype=bool)
    return rows["warnings"].fillna("").astype(str).str.contains(HEATING, regex=False).to_numpy(bool)
