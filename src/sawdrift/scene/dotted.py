"""Dotted paths into a scene's nested dictionary (``"drive.amplitude"``): how the CLI's options,
``--set`` and the sweeps' axes name a field."""

from __future__ import annotations

from typing import Any

__all__ = ["get_dotted", "set_dotted"]


def get_dotted(data: dict[str, Any], dotted: str) -> Any:
    """``data["a"]["b"]`` for ``dotted = "a.b"``; None where a level is missing."""
    node: Any = data
    for key in dotted.split("."):
        if not isinstance(node, dict):
            return None
        node = node.get(key)
    return node


def set_dotted(data: dict[str, Any], dotted: str, value: Any) -> None:
    """Set ``data["a"]["b"] = value`` for ``dotted = "a.b"``, creating levels as needed."""
    keys = dotted.split(".")
    node = data
    for key in keys[:-1]:
        node = node.setdefault(key, {})
    node[keys[-1]] = value
