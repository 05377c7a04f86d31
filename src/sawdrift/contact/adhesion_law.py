"""The adhesive normal laws of a sphere, DMT and JKR, normalized, as plain Python.

Dimensional laws (a sphere of radius R on a flat, contact modulus E*, work of adhesion w, contact
radius c, overlap d; K. L. Johnson, *Contact Mechanics*, 1985, section 5.5; D. Maugis, *Contact,
Adhesion and Rupture of Elastic Solids*, 2000, chapter 5)::

    DMT (Derjaguin, Muller and Toporov 1975):  F = 4 E* c^3 / (3 R) - 2 pi w R,  d = c^2 / R
    JKR (Johnson, Kendall and Roberts 1971):   F = 4 E* c^3 / (3 R) - sqrt(8 pi w E* c^3),
                                               d = c^2 / R - sqrt(2 pi w c / E*)

In the scene's units (N* = F / (M g), a* = d / a0, a0 the Hertz compression under M g, so that
M g = (4/3) E* R^(1/2) a0^(3/2)) and with the contact radius c* = c / sqrt(R a0) (c*^2 = a* for
Hertz), both laws take one parameter, P = 2 pi R w / (M g), the DMT pull-off over the weight::

    DMT:  N* = a*^(3/2) - P,             c* = sqrt(a*)                     (in contact: a* > 0)
    JKR:  N* = c*^3 - 3 g c*^(3/2),       a* = c*^2 - 2 g c*^(1/2),  g = sqrt(P / 3)

The JKR pull-off force (load control) is 3 P / 4 = 1.5 pi R w / (M g), reached at
c*^(3/2) = 3 g / 2; the fixed-grip instability, da*/dc* = 0, is at c*^(3/2) = g / 2, the overlap
a*_c = -3 (g / 2)^(4/3) (in SI -(3/4) (pi^2 w^2 R / E*^2)^(1/3)); at zero load c*^3 = 3 P
(c^3 = 9 pi w R^2 / (2 E*)). A contact is made at a* = 0 on approach and broken on retraction at
the instability (or, as LAMMPS does, at the pull-off overlap): a hysteresis loop whose area,
:func:`jkr_hysteresis`, is the energy a cycle loses.

The descriptor ``ad`` (float64) of a law: ``[kind, P, a*_detach, F*_pull]`` with kind 1 (DMT)
or 2 (JKR), a*_detach the overlap at or below which a contact breaks (0 for DMT) and F*_pull the
law's pull-off force over M g (:func:`descriptor`).

The functions up to :data:`COMPILED` are written in the subset numba compiles and call each other
by their global names: :mod:`sawdrift.contact.adhesion` compiles these same functions for the
kernels, and the python engine runs them as they are.
"""

from __future__ import annotations

import math

import numpy as np

#: kinds of ``ad[0]``
DMT = 1.0
JKR = 2.0
#: Newton iterations of :func:`jkr_root` at most (from above the root it converges monotonically;
#: at the instability, a double root, linearly: 60 halvings reach the rounding)
NEWTON_MAX = 200


def jkr_root(a: float, g: float) -> float:
    """sqrt(c*) of the JKR contact at overlap ``a`` on its stable branch (a >= a*_c).

    s = sqrt(c*) is the largest root of f(s) = s^4 - 2 g s - a (module text). f is convex for
    s > 0 and increasing beyond the instability s_c = (g/2)^(1/3); from
    s_0 = |a|^(1/4) + (2 g)^(1/3), where f(s_0) >= 0, Newton's steps decrease monotonically to the
    root. Below a*_c there is no root: s_c is returned.
    """
    s_c = (0.5 * g) ** (1.0 / 3.0)
    s = abs(a) ** 0.25 + (2.0 * g) ** (1.0 / 3.0)
    for _ in range(NEWTON_MAX):
        s3 = s * s * s
        f = s3 * s - 2.0 * g * s - a
        fp = 4.0 * s3 - 2.0 * g
        if fp <= 0.0 or f <= 0.0:
            break
        step = f / fp
        s_new = s - step
        if s_new <= s_c:
            s = s_c
            break
        if not step > 1e-16 * s:
            s = s_new
            break
        s = s_new
    return s


def adhesive_normal(a: float, ad) -> tuple[float, float]:
    """(N*, c*) of a contact in contact at overlap ``a`` (module text; descriptor ``ad``)."""
    p = ad[1]
    if ad[0] == DMT:
        if a > 0.0:
            c = math.sqrt(a)
            return a * c - p, c
        return -p, 0.0
    g = math.sqrt(p / 3.0)
    s = jkr_root(a, g)
    c = s * s
    return c * c * c - 3.0 * g * c * s, c


def entry_radius(ad) -> float:
    """c* of a contact just made at a* = 0: 0 for DMT, (2 g)^(2/3) for JKR."""
    if ad[0] == DMT:
        return 0.0
    return (2.0 * math.sqrt(ad[1] / 3.0)) ** (2.0 / 3.0)


#: The functions :mod:`sawdrift.contact.adhesion` compiles, callees first.
COMPILED = (jkr_root, adhesive_normal, entry_radius)


# -- closed forms (tests, oracles, the descriptor) ---------------------------------------------


def jkr_points(p: float) -> dict[str, tuple[float, float, float]]:
    """(a*, c*, N*) at the JKR instability, the pull-off and zero load, for P (module text)."""
    g = math.sqrt(p / 3.0)
    out = {}
    for name, s3 in (("instability", 0.5 * g), ("pulloff", 1.5 * g), ("zero_load", 3.0 * g)):
        c = s3 ** (2.0 / 3.0)
        out[name] = (c * c - 2.0 * g * math.sqrt(c), c, c**3 - 3.0 * g * c**1.5)
    return out


def jkr_hysteresis(p: float, detach: str = "instability") -> float:
    """The energy a JKR approach-retract cycle loses, normalized by M g a0.

    On approach N* = 0 until a* = 0; on retraction the contact pulls until it breaks at
    a*_detach < 0, so the loop work is -integral_{a*_detach}^{0} N* da*. With
    N* da* = (c^3 - 3 g c^(3/2)) (2 c - g c^(-1/2)) dc its primitive is
    W(c) = (2/5) c^5 - 2 g c^(7/2) + (3/2) g^2 c^2, and the loss is W(c_detach) - W(c(0)).
    """
    g = math.sqrt(p / 3.0)

    def prim(c: float) -> float:
        return 0.4 * c**5 - 2.0 * g * c**3.5 + 1.5 * g * g * c * c

    c0 = (2.0 * g) ** (2.0 / 3.0)
    cd = jkr_points(p)[detach][1]
    return prim(cd) - prim(c0)


def dmt_to_p(law: str, pulloff: float) -> float:
    """P = 2 pi R w / (M g) of a law whose pull-off force over M g is ``pulloff``."""
    return pulloff if law == "dmt" else pulloff / 0.75


def descriptor(law: str, pulloff: float, detach: str = "instability") -> np.ndarray:
    """``ad`` of the law ``"dmt"`` or ``"jkr"`` with the pull-off force ``pulloff`` over M g."""
    if law not in ("dmt", "jkr") or not pulloff > 0.0:
        raise ValueError(f"adhesive law {law!r} with pull-off {pulloff!r}: need 'dmt' or 'jkr' "
                         "and a pull-off > 0")
    p = dmt_to_p(law, pulloff)
    if law == "dmt":
        return np.array([DMT, p, 0.0, pulloff])
    where = jkr_points(p)[detach][0]
    return np.array([JKR, p, where, pulloff])


def rest_overlap(ad: np.ndarray, load: float = 1.0) -> float:
    """a* at which the contact carries N* = ``load`` (the static compression under M g: 1).

    DMT: (load + P)^(2/3); JKR: the stable-branch c* of c^3 - 3 g c^(3/2) = load (a quadratic in
    c^(3/2)), then its a*.
    """
    p = float(ad[1])
    if ad[0] == DMT:
        return (load + p) ** (2.0 / 3.0)
    g = math.sqrt(p / 3.0)
    x = 1.5 * g + math.sqrt(2.25 * g * g + load)  # c^(3/2), the larger root
    c = x ** (2.0 / 3.0)
    return c * c - 2.0 * g * math.sqrt(c)
