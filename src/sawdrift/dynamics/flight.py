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

Most of a high flight needs not even the surface. With |u_y| <= U at every t* and x* (the
drive's ``surface_bound``), a particle whose height on the parabola, y*(t*), stays below -U
cannot land (a* = y* - u_y < 0), and where moreover y* - U is not below the deepest a* seen so
far it cannot deepen that either: such steps only count as out of contact.
:func:`flight_skip` finds, from the parabola's roots, how many steps ahead are of that kind, and
the flight goes over them at once: the same state (every state is the parabola through the
anchor), the same counts (integers) and the same deepest a*, to the bit. A bouncer thrown high
(mmd m* = 0.1, A* = 1: 98.5 % of its steps in flight, a* down to -47) then pays for the steps
near the surface and near the top of its highest flight only.
"""

from __future__ import annotations

import math

from numba import njit

from .evidence import S_ANCHOR, S_FLY
from .rolling import JIT

#: flights skipped over fewer steps than this are stepped (:func:`flight_skip`)
MIN_SKIP = 4


@njit(**JIT)
def _roots(c2, c1, c0):
    """(r1, r2), r1 <= r2, of c2 t^2 + c1 t + c0 = 0 with c2 > 0; (nan, nan) without real roots
    (the stable form: no cancellation between -c1 and the square root)."""
    disc = c1 * c1 - 4.0 * c2 * c0
    if not disc >= 0.0:
        return math.nan, math.nan
    q = -0.5 * (c1 + math.copysign(math.sqrt(disc), c1))
    if q == 0.0:
        return 0.0, 0.0
    r1, r2 = q / c2, c0 / q
    return (r1, r2) if r1 <= r2 else (r2, r1)


@njit(**JIT)
def _steps_to(t, h, s, n_max):
    """The number of steps from step ``s`` to the last one at or before ``t`` (of ``h`` each),
    at most ``n_max``."""
    span = t / h - s
    return n_max if span >= n_max else int(math.floor(t / h)) - s


@njit(**JIT)
def flight_skip(s, n_max, parab, bound, deepest):
    """How many steps a flight may go over at once from the step ``s`` steps after its anchor
    (module docstring): the largest n <= ``n_max`` such that steps s + 1, ..., s + n cannot land
    and steps s + 1, ..., s + n - 1 cannot deepen the deepest a* so far (``deepest``), or 0 where
    that is fewer than :data:`MIN_SKIP` or ``bound`` < 0 (the drive gives none).
    ``parab`` = (h, y*, y*', y*'' at the anchor). The roots only propose n; the parabola itself
    is checked at the ends of the steps skipped (convex: between the ends it is lower than at
    one of them, and on one side of its vertex monotone), so rounding cannot let a landing or a
    deeper a* through."""
    if bound < 0.0 or n_max < MIN_SKIP:
        return 0
    h, y0, vy0, ay = parab
    thr = -bound - 1e-9 * (1.0 + bound)  # y* <= thr: a* <= -1e-9 (1 + U) < 0
    lo, hi = _roots(0.5 * ay, vy0, y0 - thr)
    t1 = (s + 1) * h
    if not hi == hi or t1 < lo:
        return 0
    n = _steps_to(hi, h, s, n_max)
    # where y* - U < deepest, a* may set a new deepest: those steps are stepped
    b_lo, b_hi = _roots(0.5 * ay, vy0, y0 - (deepest + bound))
    if b_hi == b_hi and t1 < b_hi:
        if t1 >= b_lo:
            return 0  # inside the band already
        n = min(n, _steps_to(b_lo, h, s, n_max) + 1)  # step s + n - 1 at the band's edge
    first = parabola(y0, vy0, ay, t1)
    if first > thr or first - bound < deepest:
        return 0
    for _ in range(3):
        if n < MIN_SKIP:
            return 0
        if (parabola(y0, vy0, ay, (s + n) * h) <= thr
                and parabola(y0, vy0, ay, (s + n - 1) * h) - bound >= deepest):
            return n
        n -= 1
    return 0


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
    without friction, the rolling factor c, whether x* moves, the drive's bound of |u_y| or -1
    where it gives none). Steps that can neither land nor deepen a* are gone over at once
    (:func:`flight_skip`). Returns the steps taken.
    """
    h, m, ax, k_ramp, scale_b, roll, move_x, bound = consts
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
    parab = (h, y0, vy0, ay)
    while j < k_end - k0:
        k = k0 + j
        n = flight_skip(k - ka, k_end - k if k_rec < 0 else min(k_end, k_rec) - k, parab, bound,
                        st[S_AMIN])  # noqa: F821
        if n > 0:
            # steps k + 1 .. k + n cannot land, k + 1 .. k + n - 1 cannot deepen a*: counted
            if k >= k_ramp:
                observe_step(st, 1.0, 0.0, a_j)  # noqa: F821
            counted = k + n - max(k + 1, k_ramp)
            if counted > 0:
                observe_flight_steps(st, counted)  # noqa: F821
            j += n
            tau = (k0 + j - ka) * h
            a_j = (parabola(y0, vy0, ay, tau)
                   - drive_surface((k0 + j) * h, parabola(x0, vx0, ax, tau), dp)[2])  # noqa: F821
            continue
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
