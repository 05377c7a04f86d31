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
# -- damping and the Coulomb bound"): the slots' composition and the compliant loop call these;
# -- scene_damp is the same damping in the normal-damping slot (for a law that takes N*)


@njit(**JIT_OPTIONS, inline="always")
def coulomb_cap(t, n):
    """T* within the Coulomb bound |T*| <= N*, N* the total normal force (damping included).

    As DEM codes do: while the contact unloads fast, a dashpot lowers N* below the elastic force
    and with it the largest friction force. Only the transmitted force is capped here; a law
    whose step takes N* (:func:`~sawdrift.contact.slots.takes_normal`, the DEM spring) has
    already bounded its stored force by it, the others keep their history as they committed it.
    """
    if t > n:
        return n
    if t < -n:
        return -n
    return t


@njit(**JIT_OPTIONS, inline="always")
def damped_normal(n, a, adot, viscous, restitution, q):
    """The total normal force of the compliant loop's normal damping, N* >= 0 (a* > 0).

    N* = N*(a*) + c a*' with the viscous damping c = ``viscous`` (``effects.normal_damping``), else
    N* = N*(a*) + C a*^q a*' with the restitution damping C = ``restitution``, q = (p - 1)/2
    (:func:`~sawdrift.dynamics.adams_bashforth.restitution_damping`); then clamped at 0 (a
    contact does not pull).
    """
    if viscous > 0.0:
        n += viscous * adot
    else:
        n += restitution * a**q * adot
    if n < 0.0:
        n = 0.0
    return n


@njit(**JIT_OPTIONS, inline="always")
def damped_contact(n, t, a, adot, viscous, restitution, q):
    """(N*, T*) with the compliant loop's normal damping (:func:`damped_normal`) and the
    Coulomb cap (:func:`coulomb_cap`), a* > 0."""
    n = damped_normal(n, a, adot, viscous, restitution, q)
    return n, coulomb_cap(t, n)


@njit(**JIT_OPTIONS)
def scene_damp(dp, law, a, adot, n):  # noqa: ARG001 - the slot signature
    """The scene's normal damping as a normal-damping slot: :func:`damped_normal` with
    ``dp`` = [c, C, q] (:mod:`sawdrift.contact.scene_damping`)."""
    return damped_normal(n, a, adot, dp[0], dp[1], dp[2])
