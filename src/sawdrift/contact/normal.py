"""The normal slot: a contact model's normal law alone, for runs with the tangential slot empty.

With friction off the integrator never calls the tangential law; it calls the model's normal law
(:meth:`sawdrift.contact.ContactModel.normal_law`) through the same kernel signature,
``(fs, is_, pp, a, b, adot, bdot) -> (N*, 0)``, so normal damping or any other normal physics of
the model stays in. The default is the power law of the profile, N*(a*) = a*^p for a* > 0
(Hertz for the sphere, p = 3/2; docs/physics.md, "Contact laws"), with p = ``pp[0]`` by the
packed-parameter convention.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True)
def power_normal(fs, is_, pp, a, b, adot, bdot):  # noqa: ARG001 - the kernel signature
    """(a*^p, 0) for a* > 0, else (0, 0): the elastic power-law normal force alone."""
    if a > 0.0:
        return a ** pp[0], 0.0
    return 0.0, 0.0
