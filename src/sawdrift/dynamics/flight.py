"""A free flight in closed form: the steps of the wave loop out of contact, without the scheme.

Out of contact no contact force acts (the law returns N* = T* = 0 and holds no memory), so the
particle moves under constant accelerations, x*'' = L / m*_x and y*'' = 1 / m* (paper eq. 5
with N* = T* = 0), on a parabola. Adams-Bashforth integrates such a motion exactly once its
derivative history holds only flight steps: with a constant acceleration g the velocity
advances by h g (the coefficients sum to one) and the position by h v_n + h^2 g / 2 (for every
order from 2 up, sum_j j beta_j = -1/2), the Taylor step of a parabola. So the steps of a flight can be
taken in closed form from the state where the history became all flight, and they agree with
the scheme's to rounding.

What a flight step still costs is the surface: the loop must know at which step the particle
lands, and the window's evidence (the deepest flight, the steps out of contact) and the
trajectory's rows are per step. :func:`flight_body` therefore evaluates the drive at every step
but skips the contact law, the scheme and the bookkeeping of contact changes, and hands the
run back one step before the landing, so that the loop takes the last flight step (the law
sees the flight's last sample, as it would have) and the landing itself.
"""

from __future__ import annotations

from numba import njit

from .evidence import S_ANCHOR, S_FLY
from .rolling import JIT

#: consecutive flight steps after which the derivative history is that of a parabola: the
#: accelerations of the last 4 steps (the scheme's order at most) are the flight's after 4, the
#: velocities of the last 4 were themselves advanced by flight accelerations only after 4 more
FLIGHT_HISTORY = 8


@njit(**JIT)
def parabola(q0, v0, g, tau):
    """q0 + v0 tau + g tau^2 / 2: a coordinate of the flight, ``tau`` after its anchor."""
    return q0 + v0 * tau + 0.5 * g * tau * tau


@njit(**JIT)
def count_flight(st, y, k, out):
    """Count a step out of contact without force (``out``; any other resets the count) and
    whether the flight may now go in closed form: the count reached :data:`FLIGHT_HISTORY`, where
    the state ``y`` at step ``k`` becomes the flight's anchor (``st[S_FLY:]``,
    :mod:`~sawdrift.dynamics.evidence`)."""
    if not out:
        st[S_FLY] = 0.0
        return False
    st[S_FLY] += 1.0
    if st[S_FLY] == FLIGHT_HISTORY:
        st[S_ANCHOR] = k
        for c in range(4):
            st[S_ANCHOR + 1 + c] = y[c]
    return st[S_FLY] >= FLIGHT_HISTORY


def flight_body(y, fh, ctr, dp, k_end, rec, rec_every, st, consts):
    """Take the steps of a free flight in closed form (module docstring), from step ``ctr[0]``
    up to one step before the landing or ``k_end``.

    Every state is the parabola through the flight's anchor (``st[S_ANCHOR:]``, kept with the
    integration), not through the state at this call: the loop's segments, which end where a
    window, a period or a trajectory row asks, then give the same flight to the last bit. The
    window's statistics get each step's out-of-contact share and a* (``observe_step``), the
    trajectory its rows; ``y`` and the derivative history ``fh`` are put on the parabola at the
    step handed back (``ctr[0]``). ``drive_surface``, ``record``, ``next_record``, ``contact_point``,
    ``observe_step`` and the ``S_*`` indices are globals of the generated loop module.
    ``consts`` = (h, m*, x*'' of the flight, the first step after the ramp, 1 / (theta mu) or 0
    without friction, the rolling factor c, whether x* moves). Returns the steps taken.
    """
    h, m, ax, k_ramp, scale_b, roll, move_x = consts
    ka = st[S_ANCHOR]
    x0 = st[S_ANCHOR + 1]
    vx0 = st[S_ANCHOR + 2] if move_x else 0.0
    y0 = st[S_ANCHOR + 3]
    vy0 = st[S_ANCHOR + 4]
    ay = 1.0 / m
    k0 = ctr[0]
    j = 0
    tau = (k0 - ka) * h
    a_j = (parabola(y0, vy0, ay, tau)
           - drive_surface(k0 * h, parabola(x0, vx0, ax, tau), dp)[2])  # noqa: F821
    if a_j > 0.0:
        return 0  # this step lands already: the loop takes it
    k_rec = next_record(k0, rec_every)  # noqa: F821
    while j < k_end - k0:
        tau = (k0 + j + 1 - ka) * h
        a_next = (parabola(y0, vy0, ay, tau)
                  - drive_surface((k0 + j + 1) * h, parabola(x0, vx0, ax, tau), dp)[2])  # noqa: F821
        if a_next > 0.0:
            break  # the next step lands: the loop takes this one and the landing
        k = k0 + j
        if k >= k_ramp:
            observe_step(st, 1.0, 0.0, a_j)  # noqa: F821
        if k == k_rec:
            k_rec += rec_every
            on_parabola(y, fh, k - ka, (h, ax, ay, x0, vx0, y0, vy0, move_x))
            ux = drive_surface(k * h, y[0], dp)[0]  # noqa: F821
            b = (contact_point(y, roll, False)[0] - ux) * scale_b if scale_b != 0.0 else 0.0  # noqa: F821
            record(rec, ctr, k * h, y, a_j, b, 0.0, 0.0)  # noqa: F821
        a_j = a_next
        j += 1
    on_parabola(y, fh, k0 + j - ka, (h, ax, ay, x0, vx0, y0, vy0, move_x))
    ctr[0] = k0 + j
    return j


@njit(**JIT)
def on_parabola(y, fh, n, flight):
    """Put the state ``y`` and the derivative history ``fh`` (the 4 steps before) on the flight's
    parabola ``n`` steps after its anchor; ``flight`` = (h, x*'', y*'', and x*, x*', y*, y*' at
    the anchor, whether x* moves)."""
    h, ax, ay, x0, vx0, y0, vy0, move_x = flight
    tau = n * h
    y[0] = parabola(x0, vx0, ax, tau)
    y[2] = parabola(y0, vy0, ay, tau)
    if move_x:
        y[1] = vx0 + ax * tau
    y[3] = vy0 + ay * tau
    for r in range(4):
        s = (n - 1 - r) * h  # the derivative history: steps n - 1, ..., n - 4 after the anchor
        fh[r, 0] = vx0 + ax * s if move_x else 0.0
        fh[r, 1] = ax
        fh[r, 2] = vy0 + ay * s
        fh[r, 3] = ay
