"""A free flight in closed form: the steps of the wave loop out of contact, without the scheme.

Out of contact no contact force acts (the law returns N* = T* = 0 and holds no memory), so the
particle moves under constant accelerations, x*'' = L / m*_x and y*'' = 1 / m* (paper eq. 5
with N* = T* = 0), on a parabola. Adams-Bashforth integrates such a motion exactly once its
derivative history holds only flight steps: with a constant acceleration g the velocity
advances by h g (the coefficients sum to one) and the position by h v_n + h^2 g / 2 (for every
order, sum_j j beta_j = -1/2), the Taylor step of a parabola. So the steps of a flight can be
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

#: consecutive flight steps after which the derivative history is that of a parabola: the
#: accelerations of the last 4 steps (the scheme's order at most) are the flight's after 4, the
#: velocities of the last 4 were themselves advanced by flight accelerations only after 4 more
FLIGHT_HISTORY = 8


def flight_body(y, fh, ctr, dp, k_end, rec, rec_every, st, consts):
    """Take the steps of a free flight in closed form (module docstring), from step ``ctr[0]``
    (its state in ``y``, not yet observed) up to one step before the landing or ``k_end - 2``.

    The window's statistics get each step's out-of-contact share and a* (``observe_step``), the
    trajectory its rows; ``y`` and the derivative history ``fh`` end at the step handed back,
    ``ctr[0]`` is set to it. ``drive_surface`` and ``record`` are globals of the generated
    loop module. ``consts`` = (h, m*, x*'' of the flight, the first step after the ramp, 1 /
    (theta mu) or 0 without friction, the rolling factor c, whether x* moves). Returns the steps
    taken.
    """
    h, m, ax, k_ramp, scale_b, roll, move_x = consts
    k0 = ctr[0]
    x0 = y[0]
    vx0 = y[1] if move_x else 0.0
    y0 = y[2]
    vy0 = y[3]
    ay = 1.0 / m
    last = k_end - 2 - k0  # the loop keeps the segment's last two steps
    j = 0
    a_j = y0 - drive_surface(k0 * h, x0, dp)[2]  # noqa: F821
    while j < last:
        tau = (j + 1) * h
        x1 = x0 + vx0 * tau + 0.5 * ax * tau * tau
        y1 = y0 + vy0 * tau + 0.5 * ay * tau * tau
        a_next = y1 - drive_surface((k0 + j + 1) * h, x1, dp)[2]  # noqa: F821
        if a_next > 0.0:
            break  # the next step lands: the loop takes this one and the landing
        k = k0 + j
        if k >= k_ramp:
            observe_step(st, 1.0, 0.0, a_j)  # noqa: F821
        if rec_every > 0 and k % rec_every == 0:
            tau0 = j * h
            y[0] = x0 + vx0 * tau0 + 0.5 * ax * tau0 * tau0
            y[1] = vx0 + ax * tau0 if move_x else y[1]
            y[2] = y0 + vy0 * tau0 + 0.5 * ay * tau0 * tau0
            y[3] = vy0 + ay * tau0
            ux = drive_surface(k * h, y[0], dp)[0]  # noqa: F821
            b = (contact_point(y, roll, False)[0] - ux) * scale_b if scale_b != 0.0 else 0.0  # noqa: F821
            record(rec, ctr, k * h, y, a_j, b, 0.0, 0.0)  # noqa: F821
        a_j = a_next
        j += 1
    if j == 0:
        return 0
    tau = j * h
    y[0] = x0 + vx0 * tau + 0.5 * ax * tau * tau
    y[2] = y0 + vy0 * tau + 0.5 * ay * tau * tau
    for r in range(4):
        s = (j - 1 - r) * h  # the derivative history: steps k0 + j - 1, ..., k0 + j - 4
        fh[r, 0] = vx0 + ax * s if move_x else 0.0
        fh[r, 1] = ax
        fh[r, 2] = vy0 + ay * s
        fh[r, 3] = ay
    if move_x:
        y[1] = vx0 + ax * tau
    y[3] = vy0 + ay * tau
    ctr[0] = k0 + j
    return j
