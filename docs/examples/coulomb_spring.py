"""A tangential law as a plugin: one class and one kernel function (docs/plugins.md).

An elastic spring of Mindlin's initial stiffness dN*/da*, capped by Coulomb's law, rescaled when
the contact shrinks (which keeps it passive). The framework owns the rest: the normal force, the
committed (a*, b*), contact entry (a new contact arrives with a0 = 0 and a zeroed state) and
contact loss.
"""

from numba import njit

from sawdrift import Capabilities, hookimpl
from sawdrift.contact.normal import law_normal, law_slope
from sawdrift.contact.slots import TangentialLaw


@njit(cache=True)
def spring_step(ts, is_, law, tp, a0, b0, a, b):
    t = ts[0]  # the stored T*, the law's only state
    k = law_slope(a, law, 0)  # Mindlin's stiffness N*'(a*) of the scene's normal law
    if a < a0:
        t *= k / law_slope(a0, law, 0)  # the stiffness shrinks with the contact
    n = law_normal(a, law, 0)
    ts[0] = t = min(max(t + k * (b - b0), -n), n)
    return t


class CoulombSpring(TangentialLaw):
    name = "coulomb_spring"
    summary = "Mindlin-stiffness spring with a Coulomb cap (plugin guide example)"
    capabilities = Capabilities(profiles=("sphere", "cone", "flat", "power", "table"))
    step = spring_step


@hookimpl
def sawdrift_contact_models():
    return [CoulombSpring]
