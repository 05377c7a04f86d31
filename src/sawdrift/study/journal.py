"""Append-only JSON-lines journals: the records of a study that a kill may have cut short."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from typing import Any


def records(path: Path) -> Iterator[dict[str, Any]]:
    """The JSON objects of the journal at ``path``, in order; none if it does not exist.

    A line cut by a kill mid-write does not parse and is skipped: its cell is simply missing.
    """
    if not path.exists():
        return
    # a damaged byte makes its line no JSON (skipped), not the whole journal unreadable
    with path.open(encoding="utf-8", errors="replace") as fh:
        for line in fh:
            try:
                rec = json.loads(line)
            except json.JSONDecodeError:
                continue
            if isinstance(rec, dict):
                yield rec
