"""JSON out of the command line: NaN and infinities as null (NaN is no JSON)."""

from __future__ import annotations

import math
from typing import Any

__all__ = ["json_nulls"]


def json_nulls(data: Any) -> Any:
    """``data`` with every NaN or infinite float replaced by None (JSON null: NaN is no JSON)."""
    if isinstance(data, dict):
        return {k: json_nulls(v) for k, v in data.items()}
    if isinstance(data, list | tuple):
        return [json_nulls(v) for v in data]
    if isinstance(data, float) and not math.isfinite(data):
        return None
    return data
