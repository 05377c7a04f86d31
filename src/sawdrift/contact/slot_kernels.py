"""The compiled defaults of the empty slots (imported only when a contact is compiled)."""

from __future__ import annotations

from numba import njit

from .normal import JIT_OPTIONS


@njit(**JIT_OPTIONS)
def zero_reset(ts, is_, law, tp):  # noqa: ARG001 - the slot signature
    """Default tangential reset: every state entry zero."""
    for i in range(ts.shape[0]):
        ts[i] = 0.0
    for i in range(is_.shape[0]):
        is_[i] = 0


@njit(**JIT_OPTIONS)
def no_damping(dp, law, a, adot, n):  # noqa: ARG001 - the slot signature
    """The empty normal-damping slot: the elastic normal force as it is."""
    return n
