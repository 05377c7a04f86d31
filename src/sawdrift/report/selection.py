"""Which rows of a sweep table a figure draws: a model's cells, the cells some columns fix
(``--where``), and the checks that a map's axes and rows make one map (one line each)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..errors import SceneError

#: the one line of a figure asked of an empty table
NO_CELLS = "the table holds no cells: sweep into it first"

def select(table: pd.DataFrame, model: str, where: dict | None = None) -> pd.DataFrame:
    """The rows of ``model`` (and of the column values in ``where``); a one-line error if none."""
    sub = table[table["model"] == model]
    if sub.empty:
        known = ", ".join(sorted(table["model"].dropna().unique()))
        if not known:  # an empty table was said to hold "" (nothing after the colon)
            raise SceneError(NO_CELLS)
        raise SceneError(f"model {model!r} is not in the table; it holds: {known}")
    for column, value in (where or {}).items():
        if column not in sub.columns:
            raise SceneError(f"column {column!r} is not in the table (sweep it with --axis)")
        sub = sub[sub[column] == value]
    return sub


def _value_text(value: object) -> str:
    """A column's value as the user types it (``0.2``, ``true``, ``a``)."""
    if isinstance(value, bool | np.bool_):
        return "true" if value else "false"
    if isinstance(value, float | np.floating):
        return f"{float(value):g}"
    return str(value)


def _values_text(values: pd.Series) -> str:
    return ", ".join(_value_text(v) for v in sorted(values.dropna().unique().tolist()))


def _matches(column: pd.Series, value: object) -> np.ndarray:
    """Which entries of ``column`` equal ``value`` (a string as typed, or a value)."""
    if not isinstance(value, str):
        return (column == value).fillna(False).to_numpy(bool)
    if pd.api.types.is_bool_dtype(column):
        word = value.strip().lower()
        if word not in ("true", "false"):
            return np.zeros(len(column), dtype=bool)
        return (column.astype("boolean") == (word == "true")).fillna(False).to_numpy(bool)
    if pd.api.types.is_numeric_dtype(column):
        try:
            number = float(value)
        except ValueError:
            return np.zeros(len(column), dtype=bool)
        values = column.to_numpy(float)
        exact = np.isclose(values, number, rtol=1e-9, atol=0.0)
        if exact.any():
            return exact
        # the value as this module prints it (six figures: 0.316228 for 0.31622776601683794),
        # which the error naming a table's values offered and then refused
        shown = f"{number:g}"
        return np.array([f"{v:g}" == shown for v in values], dtype=bool)
    return (column.astype(str) == value.strip()).to_numpy(bool)


def pick_rows(table: pd.DataFrame, where: dict | None) -> pd.DataFrame:
    """The rows with the value ``where`` gives each column (``--where FIELD=VALUE``).

    A column the table does not hold, or a value it does not hold, is a one-line SceneError
    naming what it holds.
    """
    for column, value in (where or {}).items():
        if column not in table.columns:
            swept = ", ".join(c for c in table.columns if "." in c and table[c].nunique() > 1)
            raise SceneError(f"--where {column}={_value_text(value)}: {column!r} is not a column of "
                             f"the table; its other swept columns: {swept or 'none'}")
        keep = _matches(table[column], value)
        if not keep.any():
            raise SceneError(f"--where {column}={_value_text(value)}: the table holds no cell with "
                             f"that value; its values of {column}: {_values_text(table[column])}")
        table = table[keep]
    return table


def where_label(table: pd.DataFrame, where: dict | None) -> str:
    """``", particle.load = 0.2"``: the values :func:`pick_rows` kept, for a figure's title."""
    return "".join(f", {c} = {_value_text(table[c].iloc[0])}" for c in (where or {})
                   if c in table.columns and len(table))


def mixed_columns(rows: pd.DataFrame, keys: list[str]) -> list[str]:
    """The swept (dotted) or scene columns (:data:`SCENE_COLUMNS`: a table forced to hold
    another base scene's cells) that take several values at one cell (the rows with equal
    ``keys``, e.g. model, x and y): one map of these rows would mix them."""
    repeated = rows[rows.duplicated(keys, keep=False)]
    if repeated.empty:
        return []
    groups = repeated.groupby(keys, dropna=False, sort=False)
    return [c for c in rows.columns if scene_column(c) and c not in keys
            and bool((groups[c].nunique(dropna=False) > 1).any())]


#: the scene columns a table holds for every cell besides the swept dotted fields: a map's axes
#: are drawn over these or over a swept field (``material.mu``), never over an output
SCENE_COLUMNS = ("m_star", "amplitude", "mu", "nu", "horizontal_ratio", "steps_per_period",
                 "periods", "ramp_periods", "measure_periods")


def scene_column(column: str) -> bool:
    """Whether a table's ``column`` is an input of its cells (a swept dotted field or one of
    :data:`SCENE_COLUMNS`), not an output of the runs (``drift_ratio``, ``lyapunov``)."""
    return "." in column or column in SCENE_COLUMNS


def check_axis(table: pd.DataFrame, column: str) -> None:
    """One line where ``column`` cannot be a map's axis: not in the table, an output of the runs
    (``drift_ratio``, ``lyapunov``: the table holds one cell per point of its swept fields, not
    of its results), or not numbers (``effects.rotation``, ``particle.profile.shape``: they
    ended in an internal failure of the plot)."""
    if column not in table.columns:
        raise SceneError(f"axis {column!r} is not a column of the table")
    if not scene_column(column):
        raise SceneError(f"axis {column!r} is an output of the runs, not a swept field: a map's "
                         "axes are two swept fields (amplitude, m_star, or an --axis field such "
                         "as material.mu)")
    values = table[column]
    if pd.api.types.is_bool_dtype(values) or not pd.api.types.is_numeric_dtype(values):
        raise SceneError(f"axis {column!r} holds no numbers: a map's axes are numeric swept fields; "
                         f"pick one of its values with --where {column}=VALUE")
    numbers = values.to_numpy(float)
    if not np.isfinite(numbers).all():
        # a NaN was reported as 'values <= 0 (0.1)', the smallest of the others
        raise SceneError(f"axis {column!r} holds {_value_text(numbers[~np.isfinite(numbers)][0])}"
                         " for some cells: a map's axes are numbers; the table is damaged (sweep "
                         "it again)")
    if not (numbers > 0.0).all():
        # the maps are drawn on log axes (a load of 0 ended in an internal failure of the plot)
        raise SceneError(f"axis {column!r} holds values <= 0 ({_value_text(values.min())}): a "
                         "map's axes are logarithmic; pick one of its values with --where "
                         f"{column}=VALUE, or draw the values above 0")
    if values.nunique() < 2:
        # one value spans no axis: a one-cell table was drawn on invented A* and m* ranges
        raise SceneError(f"axis {column!r} holds one value ({_value_text(values.iloc[0])}): a "
                         "map needs two swept fields (a sweep over one field is drawn as a line, "
                         "TABLE.png, by sawdrift sweep; one cell is a run)")


def one_map(rows: pd.DataFrame, keys: list[str], by: bool = False) -> None:
    """A one-line SceneError where one map of ``rows`` would hold several rows at a cell (rows of
    another swept column's values: a patchwork); it names the column, its values and the option
    to pick one (``by``: the figure also takes ``--by``)."""
    mixed = mixed_columns(rows, keys)
    if not mixed and not rows.duplicated(keys).any():
        return
    if not mixed:
        raise SceneError(f"the table holds several rows at one cell of {', '.join(keys)}; one map "
                         "would mix them: pick one with --where FIELD=VALUE")
    # a swept field before the scene columns it changes (effects.rotation sets the step: the
    # table's steps_per_period was named, and picking one of its values drew part of a map)
    column = next((c for c in mixed if "." in c), mixed[0])
    also = f", or draw a panel per value with --by {column}" if by else ""
    raise SceneError(f"the table holds several values of {column} ({_values_text(rows[column])}) "
                     f"and one map would mix them: pick one with --where {column}=VALUE{also}")
