"""A tangential law as a plugin: one class and one kernel (docs/plugins.md).

An elastic spring of Mindlin's initial stiffness dN*/da*, capped by Coulomb's law, rescaled when
the contact shrinks (which keeps it passive), forgetting everything when contact is lost.
"""

from numba import njit

from sawdrift import Capabilities, ContactModel, KernelPair, hookimpl


@njit(cache=True)
def reset(fs, is_, pp):
    fs[:] = 0.0  # committed a*, committed b*, stored T*


@njit(cache=True)
def force(fs, is_, pp, a, b, adot, bdot):
    a0, b0, t = fs[0], fs[1], fs[2]
    fs[0], fs[1] = a, b
    if a <= 0.0:  # contact lost: nothing remembered
        fs[2] = 0.0
        return 0.0, 0.0
    p = pp[0]  # the profile's exponent: N* = a*^p
    if a0 <= 0.0:
        t = 0.0
    elif a < a0:
        t *= (a / a0) ** (p - 1.0)  # the stiffness shrinks with the contact
    n = a**p
    fs[2] = t = min(max(t + p * a ** (p - 1.0) * (b - b0), -n), n)
    return n, t


class CoulombSpring(ContactModel):
    name = "coulomb_spring"
    summary = "Mindlin-stiffness spring with a Coulomb cap (plugin guide example)"
    capabilities = Capabilities(straight_path_exact=False)
    kernel = KernelPair(reset=reset, force=force)

    def state_sizes(self):
        return 3, 1


@hookimpl
def sawdrift_contact_models():
    return [CoulombSpring]
