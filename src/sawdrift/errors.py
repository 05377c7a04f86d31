"""User-facing errors: one line, naming the field and what is allowed."""

from __future__ import annotations


class SawdriftError(Exception):
    """An error caused by the user's input or environment, reported as one line.

    The CLI prints ``str(error)`` and exits with status 2; it never shows a traceback.
    """


class SceneError(SawdriftError, ValueError):
    """A scene field has a value outside its allowed range."""


class ModelNotFoundError(SawdriftError, LookupError):
    """No registered contact model has the requested name."""


class PluginError(SawdriftError, RuntimeError):
    """Plugins disagree (for example two distributions claim one model name)."""


class NonFiniteStateError(SawdriftError, FloatingPointError):
    """The integration could not go on: a non-finite state, or a step it cannot resolve.

    The message names t*, the state and the cause (for example more events in one step than the
    rigid scheme resolves), and what to change.
    """


def first_line(exc: BaseException, most: int = 200) -> str:
    """``Type: first line of the message`` (at most ``most`` characters of it): what a one-line
    error says of an exception raised by code that is not sawdrift's (a plugin's kernel)."""
    text = (str(exc).strip().splitlines() or [""])[0][:most]
    return f"{type(exc).__name__}: {text}"
