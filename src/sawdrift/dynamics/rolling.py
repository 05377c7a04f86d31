"""The rolling angle psi = R phi / a0: the one owner of its integration and of its conversions.

docs/physics.md, "Rotation" and "Loads, inclines and restitution". A sphere free to turn
(``effects.rotation``; I = kappa m R^2) has m* x*'' = -mu T* + L on its centre and
kappa m* psi'' = -mu T* + m_r on its rolling angle (m_r the rolling resistance's torque), and its
contact point is s* = x* + psi. With c = 1 + 1/kappa (the schemes' parameter ``roll``; 0 without
rotation):

* from rest, without a load or rolling resistance, psi = (c - 1) x* at all times
  (:func:`psi_from_rest`): psi is not integrated, s* = c x*;
* with rolling resistance, or under a load (which pulls the centre without turning it), psi is a
  state of its own, y[4] = psi and y[5] = psi', and stays one once it is apart from (c - 1) x*
  (:func:`integrates_psi`);
* the rigid scheme integrates the contact point within a step and carries the centre through the
  offset od = c x* - s* = (c - 1) x* - psi, whose second derivative is (c - 1) L/m* in every
  phase (:func:`centre_offset`, :func:`centre_at`, :func:`to_centre`).

Both schemes, the stepper and the measuring window call these functions: nothing else decides
whether psi is integrated or converts between the centre, the contact point and psi.
"""

from __future__ import annotations

import math

from numba import njit

#: Damping ratio eta_r of the rolling spring's viscous term (Ai, Chen, Rotter and Ooi 2011, Powder
#: Technol. 206, 269-282, eq. 15 and their recommended eta_r = 0.3): C_r = 2 eta_r sqrt(I_r K_r),
#: acting while the spring is elastic (their f = 0 at full mobilization).
ROLL_DAMPING = 0.3

#: numba options of the loops' helpers: inlined into the loop at numba's IR level (a call into
#: another compiled module is not inlined by LLVM), no reference counts (they allocate nothing;
#: see :data:`sawdrift.dynamics.rigid_bind._JIT`)
JIT = {"cache": True, "_nrt": False, "inline": "always"}


@njit(**JIT)
def integrates_psi(roll, rr, load, y, drag=0.0):
    """psi is integrated (y[4], y[5]): rotation with rolling resistance ``rr`` > 0, a load or air
    drag (forces on the centre without a moment about it: the contact point no longer stays at
    c x*; with drag alone a sphere was given the drift 0.134 of the from-rest shortcut, where
    it holds no drift at all), or once psi is apart from its value from rest (the state then
    carries it)."""
    return roll > 0.0 and (rr > 0.0 or load != 0.0 or drag > 0.0 or y[4] != 0.0 or y[5] != 0.0)


@njit(**JIT)
def contact_point(y, roll, spin):
    """(s*, s*') of the contact point: x* + psi where psi is integrated (``spin``), c x* from rest,
    x* itself without rotation (``roll`` = 0)."""
    if spin:
        return y[0] + y[4], y[1] + y[5]
    if roll > 0.0:
        return roll * y[0], roll * y[1]
    return y[0], y[1]


def psi_from_rest(x, roll):
    """psi = R phi / a0 = (c - 1) x* = x*/kappa of a sphere rolling from rest without load or
    rolling resistance (scalars or arrays; also psi' from x*')."""
    return (roll - 1.0) * x


@njit(**JIT)
def rotational_inertia(m_x, roll):
    """kappa m*_x = m*_x / (c - 1): the rotational inertia follows the horizontal one (0 without
    rotation)."""
    return m_x / (roll - 1.0) if roll > 0.0 else 0.0


#: relative distance below its cap at which the rolling spring's torque counts as the cap
CAP_RTOL = 1e-9


@njit(**JIT)
def rolling_torque(y, a, load_n, rr, p_exp, kappa_m):
    """(m_r, K_r, cap) of the elastic-plastic rolling spring with its viscous term.

    EPSD model of Ai, Chen, Rotter and Ooi (2011, Powder Technol. 206, 269-282): per R and per
    M g the torque is m_r = -K_r psi_e - C_r psi', |K_r psi_e| <= mu_r N*, with
    K_r = 2.25 mu_r^2 dN*/da* (their k_r = 2.25 k_n mu_r^2 R^2, N* = a*^p) and
    C_r = 2 eta_r sqrt(kappa m* K_r) while the spring is elastic, none at full mobilization
    (their f = 0); psi_e is y[6]. ``load_n`` is the normal force the cap is taken on, N*, or
    N* + 2 F*_pull with adhesion (as friction's), the cap none under a net pull. With ``rr`` = 0
    it is 0.

    The whole torque, the viscous term's included, is held to the cap, as LAMMPS's rolling
    model holds its spring and damper together: rolling friction resists with at most mu_r N*.
    Uncapped, C_r psi' of a fast-rolling sphere on a vibrating contact, whose cap grows faster
    than its spring's torque while the contact loads (the spring turns elastic again every
    period), was a drag growing with the spin: a sphere under a load twice mu_r reached a
    terminal speed (4.5 a0 f still, 10.9 at A* = 0.5, m* = 0.1) instead of rolling away. A
    spring held at its cap by :func:`slide_spring` counts as at the cap to rounding
    (:data:`CAP_RTOL`): a strict comparison took it for elastic and added the viscous term.
    """
    kr = 2.25 * rr * rr * p_exp * a ** (p_exp - 1.0) if a > 0.0 else 0.0
    cap = rr * max(load_n, 0.0)
    mr = -kr * y[6]
    if abs(mr) >= (1.0 - CAP_RTOL) * cap:
        mr = math.copysign(cap, mr)  # fully mobilized: the spring slides at its cap
    elif kr > 0.0:
        mr -= 2.0 * ROLL_DAMPING * math.sqrt(kappa_m * kr) * y[5]
        if abs(mr) > cap:
            mr = math.copysign(cap, mr)
    return mr, kr, cap


@njit(**JIT)
def slide_spring(y, psi_old, kr, cap):
    """The rolling spring takes the step's increment of psi, and slides (plastic) at its cap."""
    y[6] += y[4] - psi_old
    if kr > 0.0 and abs(kr * y[6]) > cap:
        y[6] = math.copysign(cap / kr, y[6])
    elif kr == 0.0:
        y[6] = 0.0


@njit(**JIT)
def centre_offset(y, roll, g_load):
    """(od, od', od'') of the offset od = c x* - s* = (c - 1) x* - psi (rigid scheme).

    The load's acceleration ``g_load`` = L/m* acts on c x* and L/(c m*) c on s*, so od'' =
    (c - 1) L/m* in contact, slip, flight and impacts alike (impulses change c x*' and s*' alike).
    """
    c1 = roll - 1.0
    return c1 * y[0] - y[4], c1 * y[1] - y[5], c1 * g_load


@njit(**JIT)
def centre_at(s, sv, frame, tc):
    """(x*, x*') of the centre at ``tc`` from the contact point's (s*, s*') there (rigid scheme).

    ``frame`` = (od, od', od'', c, t) holds the offset od = c x* - s* at the step's start t
    (:func:`centre_offset`), advanced here in closed form to ``tc``: x* = (s* + od(tc)) / c.
    """
    od, odv, gd, roll, t = frame
    dt = tc - t
    return (s + od + odv * dt + 0.5 * gd * dt * dt) / roll, (sv + odv + gd * dt) / roll


@njit(**JIT)
def to_contact_point(y, roll, turning, g_load):
    """Turn the state's centre (y[0], y[1]) into the contact point s* for the rigid scheme's step;
    the offset (od, od', od'') that :func:`to_centre` turns it back with (zeros from rest)."""
    if turning:
        od, odv, gd = centre_offset(y, roll, g_load)
        y[0] += y[4]
        y[1] += y[5]
        return od, odv, gd
    y[0] *= roll
    y[1] *= roll
    return 0.0, 0.0, 0.0


@njit(**JIT)
def to_centre(y, roll, turning, off, hh):
    """Turn the contact point in y[0], y[1] back into the centre and psi, ``hh`` after the step's
    start, with the offset ``off`` = (od, od', od'') of :func:`to_contact_point`."""
    xs = y[0]
    if turning:
        od, odv, gd = off
        od += odv * hh + 0.5 * gd * hh * hh
        odv += gd * hh
        y[0] = (xs + od) / roll
        y[4] = xs - y[0]
        vs = y[1]
        y[1] = (vs + odv) / roll
        y[5] = vs - y[1]
    else:
        y[0] = xs / roll
        y[1] /= roll
