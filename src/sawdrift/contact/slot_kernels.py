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


# -- the one owner of the Coulomb cap and of the loop's normal damping (docs/physics.md, "Normal
# -- damping and the Coulomb bound"): the slots' composition and the compliant loop call these


@njit(**JIT_OPTIONS, inline="always")
def coulomb_cap(t, n):
    """T* within the Coulomb bound |T*| <= N*, N* the total normal force (damping included).

    As DEM codes do: while the contact unloads fast, a dashpot lowers N* below the elastic force
    and with it the largest friction force. Only the transmitted force is capped; the tangential
    law's committed history is left as it is.
    """
    if t > n:
        return n
    if t < -n:
        return -n
    return t


@njit(**JIT_OPTIONS, inline="always")
def damped_contact(n, t, a, adot, viscous, restitution, q):
    """(N*, T*) with the compliant loop's normal damping, N* >= 0, and the Coulomb cap (a* > 0).

    N* = N*(a*) + c a*' with the viscous damping c = ``viscous`` (``effects.normal_damping``), else
    N* = N*(a*) + C a*^q a*' with the restitution damping C = ``restitution``, q = (p - 1)/2
    (:func:`~sawdrift.dynamics.adams_bashforth.restitution_damping`); then clamped at 0 (a contact
    does not pull) and T* capped by it (:func:`coulomb_cap`).
    """
    if viscous > 0.0:
        n += viscous * adot
    else:
        n += restitution * a**q * adot
    if n < 0.0:
        n = 0.0
    return n, coulomb_cap(t, n)
