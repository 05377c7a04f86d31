"""One integration of a wave or impact scene, advanced in segments, and its twin for Lyapunov.

The :class:`Stepper` holds the whole state of a run (mechanical state, Adams-Bashforth derivative
history, the contact history, the evidence vector) and advances it with the scheme the runner
assembled: the compliant loop of :mod:`.adams_bashforth` or the rigid scheme of :mod:`.rigid`.
:meth:`Stepper.twin` gives an independent copy, optionally perturbed, for the finite-time Lyapunov
estimate of the regime evidence.
"""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING

import numpy as np

from ..contact.adhesion import rest_compression
from ..contact.base import ContactModel
from ..contact.binding import model_for
from ..contact.history import ContactHistory
from ..contact.scene_damping import damped_law
from ..errors import NonFiniteStateError
from ..scene.schema import Scene
from . import adams_bashforth as ig
from . import evidence as ev
from . import rigid as rg
from . import rigid_bind
from .assembly import assemble
from .failure import failure
from .records import (
    MAX_TRAJECTORY_ROWS,
    NO_ROWS,
    RECORDS_PER_PERIOD,
    SEGMENT_ROWS,
    strobe_rows,
    thinned,
)
from .rolling import contact_point, integrates_psi, psi_from_rest
from .snapshot import StepperState, put_back, snapshot

if TYPE_CHECKING:
    import pandas as pd

    from .assembly import Assembly


#: Event rows reserved per period of the measurement window at the start (at most
#: :data:`INITIAL_EVENT_ROWS`); the log grows (doubling) whenever a loop finds it nearly full, up
#: to :data:`KEPT_EVENT_ROWS` (see :meth:`Stepper.advance`).
EVENTS_PER_PERIOD = 64

#: Most event rows a log starts with (7 floats a row: 3.7 MB), whatever the window's length
INITIAL_EVENT_ROWS = 1 << 16

#: Most event rows one window keeps (7 floats a row: 59 MB): where its log is full at this size,
#: its oldest half is shed (counted in the window's ``events_shed``), so the memory of a run does
#: not grow with its length (a fixed run's window is half of it)
KEPT_EVENT_ROWS = 1 << 20


#: what a long run tells of its progress: a callable taking the steps just taken, set by the
#: command line for the time of a run (:func:`sawdrift.study.progress.run_progress`); None: nothing
PROGRESS: list = [None]

#: steps an advance takes between two reports to :data:`PROGRESS`
REPORT_STEPS = 1 << 20


class Stepper:
    """One integration, advanced in segments so that the state can be read between them.

    Parameters
    ----------
    scene, model, plan
        The scene, its model instance and the runner's :class:`~sawdrift.dynamics.assembly.Assembly`.
    record
        Record the trajectory (about :data:`RECORDS_PER_PERIOD` rows per period).
    preload
        Start at the static compression a* = 1 (wave scenes); an impact starts at a* = 0.
    event_periods
        Periods of the measurement window, which sizes the event buffer.
    """

    def __init__(
        self,
        scene: Scene,
        model: ContactModel,
        plan: Assembly,
        record: bool,
        preload: bool = True,
        event_periods: int = 1,
    ):
        self.scene = scene
        #: the substrate's motion (sawdrift.dynamics.drives): its functions are bound into the
        #: loops, its parameters are the vector dp
        self.drive = plan.drive
        engine = plan.engine
        self.k_per = plan.steps_per_period
        self.dp = self.drive.for_steps(self.drive.pack(scene), self.k_per)
        self.h = 1.0 / self.k_per
        self.rigid = model.capabilities.rigid
        named = dict(plan.params)  # the scheme's parameters, decided by the assembly
        contact_model = self._contact_model(model, plan, named)
        #: c = 1 + 1/kappa with rotation (contact point s = c x from rest), else 0: not computed
        self.roll = named["roll"]
        prm = ig.pack(named)
        self.y = np.zeros(ig.N_STATE)
        #: the rolling angle psi = R phi / a0 is integrated (state y[4], y[5]), as the loops
        #: decide it (:func:`~.rolling.integrates_psi`): with rolling resistance, or under a load
        #: (which turns the centre's motion away from s = c x)
        self.resist = self._integrates_psi(prm)
        self.ev_margin = rg.EV_MARGIN_RIGID if self.rigid else ev.EV_MARGIN
        self.st = ev.new_stats(max(min(EVENTS_PER_PERIOD * max(1, event_periods) + 64,
                                       INITIAL_EVENT_ROWS, KEPT_EVENT_ROWS), 2 * self.ev_margin))
        self.record = record
        #: keep every event (the measuring window); before it the log is emptied whenever full,
        #: so a run of any length holds at most one window's events (measure_window sets it)
        self.keep_events = False
        self.rec_every = max(1, self.k_per // RECORDS_PER_PERIOD) if record else 0
        self.rec_chunks: list[np.ndarray] = []
        self.rec_rows = 0  # rows in rec_chunks (thinned past MAX_TRAJECTORY_ROWS)
        self.compiled = engine == "compiled"
        self.history: ContactHistory | None = None
        if self.rigid:
            # the rigid scheme reads its own parameters, then the drive's, behind the common ones
            self.prm = np.concatenate([prm, ig.pack(named, rg.RIGID_PRM_NAMES), self.dp])
            self.ctr = np.zeros(5, dtype=np.int64)
            self.ctr[3] = 1  # starts stuck to the substrate at rest
            self.loop = (rigid_bind.rigid_loop_for(self.drive) if self.compiled
                         else rigid_bind.rigid_python_loop(self.drive))
        else:
            self.prm = prm
            self.ctr = np.zeros(3, dtype=np.int64)
            self.fh = np.zeros((4, 6))
            # a* = 1: static compression under M g (docs/physics.md); an impact starts at 0
            # (an adhesive contact rests where its law carries M g: sawdrift.contact.adhesion)
            rest = rest_compression(model)
            self.y[2] = rest if preload else 0.0
            if plan.tangential_law:
                self.history = ContactHistory(contact_model, engine)
                if preload:
                    self.history.advance(rest, 0.0)
                self._bind_history()
            else:
                # Friction off: the tangential slot is empty and never called; the loop calls
                # the model's normal law alone (its normal slot, e.g. with normal damping).
                normal, self.pp = model.normal_law()
                self.fs = np.zeros(1)
                self.is_ = np.zeros(1, dtype=np.int64)
                self.loop = ig.wave_loop(normal if self.compiled else normal.py_func, self.drive,
                                         self.compiled)

    @staticmethod
    def _contact_model(model: ContactModel, plan: Assembly, named: dict[str, float]) -> ContactModel:
        """The model the contact history runs: with the scene's normal damping in its slot for a
        law that bounds its stored force by the total N* (:mod:`sawdrift.contact.scene_damping`);
        ``named`` then loses the loop's damping (set to 0 in place), so it is added once."""
        if plan.scheme == "rigid" or not plan.tangential_law:
            return model
        damped = damped_law(model, named["damping"], named["restitution_damping"],
                            0.5 * (named["p"] - 1.0))  # q of the loop's q_rest
        if damped is None:
            return model
        named["damping"] = named["restitution_damping"] = 0.0
        return damped

    def _integrates_psi(self, prm: np.ndarray) -> bool:
        """Whether the loops integrate psi from the present state, with the parameters ``prm``
        (the common ones lead both schemes' vectors): :func:`~.rolling.integrates_psi`."""
        drag = 0.0 if self.rigid else float(prm[ig.P_DRAG])
        return bool(integrates_psi.py_func(self.roll, prm[ig.P_RR], prm[ig.P_LOAD], self.y, drag))

    def _bind_history(self) -> None:
        assert self.history is not None
        force, self.fs, self.is_, self.pp = self.history.kernel_call()
        self.loop = ig.wave_loop(force, self.drive, self.compiled)

    def warm_up(self) -> float:
        """Compile (or load from the disk cache) the loop with a call of zero steps; seconds."""
        import time

        t0 = time.perf_counter()
        rec = np.zeros((0, ig.N_REC))
        st = self.st.copy()
        if self.rigid:
            self.loop(self.y.copy(), self.ctr.copy(), self.prm, 0, rec, 0, st)
        else:
            self.loop(self.y.copy(), self.fh.copy(), self.ctr.copy(), (self.fs, self.is_, self.pp),
                      self.prm, self.dp, 0, rec, 0, st)
        return time.perf_counter() - t0

    @property
    def step(self) -> int:
        """Steps taken since t* = 0."""
        return int(self.ctr[0])

    def advance_periods(self, periods: int) -> np.ndarray:
        """Advance ``periods`` whole periods in one call of the loop and return the state
        (x*, x*', y*, y*') at the end of each, shape (periods, 4).

        The loop records the state at every period boundary itself (its trajectory row every
        ``k_per`` steps), so a window costs one call, not one per period. A run that records its
        trajectory, or one not at a period boundary, goes period by period.
        """
        samples = np.empty((periods, 4))
        if self.record or self.step % self.k_per != 0:
            for j in range(periods):
                self.advance(self.k_per)
                samples[j] = self.y[:4]
            return samples
        t0 = self.step // self.k_per
        self.advance(periods * self.k_per, strobe=(samples, t0))
        samples[periods - 1] = self.y[:4]
        return samples

    def advance(self, n_steps: int, strobe: tuple[np.ndarray, int] | None = None,
                rows: list[np.ndarray] | None = None) -> None:
        """Advance ``n_steps`` steps (:meth:`_recorded`), telling :data:`PROGRESS` the steps
        taken, in segments of at most :data:`REPORT_STEPS` where one is set (a long run was
        silent for minutes: the command line shows the steps as they go)."""
        report = PROGRESS[0]
        if report is None:
            self._recorded(n_steps, strobe, rows)
            return
        target = self.step + max(0, int(n_steps))
        while self.step < target:
            before = self.step
            segment = target - self.step if strobe is not None or rows is not None else min(
                target - self.step, REPORT_STEPS)
            self._recorded(segment, strobe, rows)
            report(self.step - before)

    def _recorded(self, n_steps: int, strobe: tuple[np.ndarray, int] | None = None,
                  rows: list[np.ndarray] | None = None) -> None:
        """Advance ``n_steps`` steps (:meth:`_advance`); a recorded trajectory in segments of at
        most :data:`~.records.SEGMENT_ROWS` rows, thinned past
        :data:`~.records.MAX_TRAJECTORY_ROWS` (:func:`~.records.thinned`): a 2e5-period run
        with ``-o`` asked 2.1 GiB for one buffer and lost the run, and its rows grew with its
        length."""
        if self.record and rows is not None and self.rec_every > 0:
            # every step's row is collected: the trajectory keeps every rec_every-th of them, as
            # the loop would have recorded (an irregular heavy bouncer's mean, .imposed, ran a
            # separate evidence window where it recorded a trajectory: run -o reported 935
            # periods and another Lyapunov exponent where --json said 535)
            first, start = len(rows), self.step
            self._advance(n_steps, strobe, rows)
            if len(rows) > first:
                kept = np.concatenate(rows[first:])[(-start) % self.rec_every::self.rec_every]
                self.rec_chunks.append(kept.copy())
                self.rec_rows += kept.shape[0]
                self._thin_trajectory()
            return
        if not (self.record and strobe is None and rows is None and self.rec_every > 0):
            self._advance(n_steps, strobe, rows)
            return
        target = self.step + max(0, int(n_steps))
        while self.step < target:
            self._advance(min(target - self.step, SEGMENT_ROWS * self.rec_every))
            self._thin_trajectory()

    def _thin_trajectory(self) -> None:
        """Thin the trajectory past :data:`~.records.MAX_TRAJECTORY_ROWS`
        (:func:`~.records.thinned`)."""
        if self.rec_rows > MAX_TRAJECTORY_ROWS:
            self.rec_chunks, self.rec_every = thinned(self.rec_chunks, self.h, self.rec_every)
            self.rec_rows = self.rec_chunks[0].shape[0]

    def _advance(self, n_steps: int, strobe: tuple[np.ndarray, int] | None = None,
                 rows: list[np.ndarray] | None = None) -> None:
        """Advance ``n_steps`` steps; raise a one-line error if the scheme cannot go on.

        The loops return early when the event log is nearly full; in the measuring window
        (:attr:`keep_events`) the log is then grown and the integration goes on, up to
        :data:`KEPT_EVENT_ROWS` rows, past which the window's oldest events are shed (counted);
        before the window the log is emptied (its events counted), so the memory of a run does
        not grow with its length. ``strobe`` = (samples, t0) takes the state at
        each period boundary (:meth:`advance_periods`); ``rows`` collects the trajectory row of
        every step (compliant scheme: the state before the step), whatever :attr:`record` says.
        """
        target = self.step + max(0, int(n_steps))
        every = 1 if rows is not None else self.k_per if strobe is not None else self.rec_every
        recording = self.record or strobe is not None or rows is not None
        # one buffer for the whole advance: a loop that returns early (its event log full)
        # goes on writing after the rows it has written
        buffer = (np.empty(((target - self.step) // every + 2, ig.N_REC)) if recording
                  else NO_ROWS)
        used = 0
        while self.step < target:
            n = target - self.step
            rec = buffer[used:]
            self.ctr[2] = 0
            if self.rigid:
                self.loop(self.y, self.ctr, self.prm, n, rec, every, self.st)
            else:
                self.loop(
                    self.y, self.fh, self.ctr, (self.fs, self.is_, self.pp), self.prm, self.dp, n,
                    rec, every, self.st,
                )
            used += int(self.ctr[2])
            if rows is not None:
                rows.append(rec[: self.ctr[2]])
            elif strobe is not None:
                strobe_rows(strobe, rec[: self.ctr[2]])
            elif self.record:
                self.rec_chunks.append(rec[: self.ctr[2]].copy())
                self.rec_rows += int(self.ctr[2])
            if self.st[ev.S_BAD] > 0.0:
                self._fail()
            if self.st[ev.S_EVDROP] > 0.0:
                raise NonFiniteStateError(
                    f"{int(self.st[ev.S_EVDROP])} events (lift-offs, landings, slip changes) "
                    f"did not fit in one step's room of the event log near t* = "
                    f"{self.step * self.h:.6g}; the regime evidence would be incomplete"
                )
            if ev.log_full(self.st, self.ev_margin):
                if not self.keep_events:
                    ev.forget_transient(self.st)  # before the window: counted, not kept
                    continue
                if self.st[ev.S_EVCAP] >= KEPT_EVENT_ROWS:
                    ev.shed_oldest(self.st, KEPT_EVENT_ROWS // 2)  # the newest half stays
                else:
                    self.st = ev.grown(self.st, 2 * self.ev_margin, KEPT_EVENT_ROWS)

    def _fail(self) -> None:
        """One line on why the state became non-finite (:func:`~.failure.failure`)."""
        raise failure(self)

    def continued(self, scene: Scene, model: ContactModel | None = None) -> Stepper:
        """A stepper for ``scene`` that starts from this one's state (warm start, continuation).

        The mechanical state, the contact history and the time carry over; the parameters are
        ``scene``'s. Use it between whole periods, after the ramp, for a scene of the same model
        and contact state layout (a parameter continuation: amplitude, m*, mu, ...). If the step
        changes, the Adams-Bashforth history restarts at order 1.
        """
        if scene.model != self.scene.model:
            raise ValueError(f"a continuation keeps the contact model ({self.scene.model!r}); "
                             f"got {scene.model!r}")
        model = model if model is not None else model_for(scene)
        engine = "compiled" if self.compiled else "python"
        new = Stepper(scene, model, assemble(scene, engine, model), record=False,
                      event_periods=max(1, int(self.st[ev.S_EVCAP]) // EVENTS_PER_PERIOD))
        if self.rigid != new.rigid:
            raise ValueError("a continuation keeps the scheme (rigid or compliant)")
        t = self.step * self.h
        new.y = self.y.copy()
        new.ctr = self.ctr.copy()
        new.ctr[0] = int(round(t * new.k_per))
        if new.resist and not self.resist and new.roll > 0.0:
            # the rolling angle starts being integrated: from rest it was psi = (c - 1) x
            new.y[4] = psi_from_rest(self.y[0], new.roll)
            new.y[5] = psi_from_rest(self.y[1], new.roll)
        # psi, once apart from (c - 1) x, stays integrated (the loops go on integrating it)
        new.resist = new._integrates_psi(new.prm)
        if self.rigid:
            return new
        if new.k_per == self.k_per:
            new.fh = self.fh.copy()
        else:
            new.ctr[1] = 0  # derivatives of another step: Adams-Bashforth starts again
        if self.history is None or new.history is None:
            return new
        old = self.scene
        same = (old.model_params == scene.model_params and old.particle.profile == scene.particle.profile
                and old.theta * old.material.mu == scene.theta * scene.material.mu)
        if same:
            # b* = (x* - u_x) / (theta mu) keeps its scale: the memory carries over exactly (into
            # the new history, whose parameters may hold another normal damping of the scene)
            new.history.set_state(self.history.state())
        else:
            # another scale of b* or another law layout: a fresh contact at the present (a*, b*)
            a, b = new.displacements()
            if a > 0.0:
                new.history.advance(a, b)
        return new

    def follow_surface(self, before: tuple[float, float, float, float]) -> None:
        """Shift the state by the surface's move from ``before`` (:meth:`surface` of the stepper
        this one continues) to now, so that a*, a*', b* and x*' - u_x' carry over unchanged.

        On a sphere rolling from rest (contact point at c x*, c = 1 + 1/kappa) the centre moves
        by 1/c of the shift, so that the contact point moves with the surface.
        """
        after = self.surface()
        share = 1.0 / self.roll if (self.roll > 0.0 and not self.resist) else 1.0
        self.y[0] += (after[0] - before[0]) * share
        self.y[1] += (after[1] - before[1]) * share
        self.y[2] += after[2] - before[2]
        self.y[3] += after[3] - before[3]
        self.moved()

    def moved(self) -> None:
        """After the state or the inertia was changed from outside the loop: a flight taken in
        closed form (:mod:`.flight`) counts afresh, or it would go on from its anchor, a state
        from before the change, until the landing and past it."""
        self.st[ev.S_FLY] = 0.0

    def save(self) -> StepperState:
        """A snapshot of the integration (copies): :meth:`restore` on a stepper of the same scene
        and engine continues from it bit for bit (the bifurcation journals, :mod:`sawdrift.study.
        branch`; :func:`~.snapshot.snapshot`)."""
        return snapshot(self)

    def restore(self, state: StepperState) -> None:
        """Put back a snapshot of :meth:`save` (taken on a stepper of the same model and engine;
        :func:`~.snapshot.put_back`)."""
        put_back(self, state)

    def set_horizontal_inertia(self, m_x: float) -> None:
        """Integrate the horizontal motion with the inertia ``m_x`` (the rotation's follows, kappa
        m_x): the separation of motions of :func:`~sawdrift.dynamics.steady.settle`. The rigid
        scheme keeps m* (its relaxation is already short); a no-op there."""
        if not self.rigid:
            self.prm[ig.P_MX] = m_x
            self.moved()  # a flight in closed form has its old x*'' since its anchor

    def surface(self) -> tuple[float, float, float, float]:
        """(u_x, u_x', u_y, u_y') of the drive now, at the particle's position."""
        ux, uxd, uy, uyd = self.drive.functions()[0](self.step * self.h, self.y[0], self.dp)
        return float(ux), float(uxd), float(uy), float(uyd)

    def displacements(self) -> tuple[float, float]:
        """(a*, b*) of the present state, as the compliant loop computes them."""
        prm = self.prm
        ux, _, uy, _ = self.surface()
        s, _ = contact_point.py_func(self.y, self.roll, self.resist)
        y = self.y
        return float(y[2] - uy), float((s - ux) / (prm[ig.P_THETA] * prm[ig.P_MU]))

    def twin(self, dy: np.ndarray | None = None) -> Stepper:
        """An independent copy of this integration (no trajectory recording), state + ``dy``."""
        new = copy.copy(self)
        new.y = self.y.copy()
        new.ctr = self.ctr.copy()
        new.st = self.st.copy()
        if dy is not None:
            new.y[: dy.size] += dy
            new.moved()  # displaced off its flight's parabola
        new.record = False
        new.rec_every = 0
        new.rec_chunks = []
        new.rec_rows = 0
        if not self.rigid:
            new.fh = self.fh.copy()
            if self.history is not None:
                new.history = self.history.copy()
                new._bind_history()
            else:
                new.fs, new.is_ = self.fs.copy(), self.is_.copy()
        return new

    def restart_from(self, other: Stepper, dy: np.ndarray | None = None) -> None:
        """Put this twin at ``other``'s state (+ ``dy``) in place, with an empty event log.

        What :meth:`twin` copies, without building a stepper: the mechanical state, the
        integrator's history, the counters and the contact memory (through
        :meth:`ContactHistory.state`), so advancing from here is bit for bit what advancing
        ``other.twin(dy)`` would be. The window statistics are ``other``'s; the event log starts
        empty (no event is read back from a twin). Both must be twins of one integration (the
        Lyapunov estimate restarts one twin this way every period).
        """
        np.copyto(self.y, other.y)
        if dy is not None:
            self.y[: dy.size] += dy
        np.copyto(self.ctr, other.ctr)
        self.st[: ev.N_ST] = other.st[: ev.N_ST]
        if dy is not None:
            self.moved()  # displaced off its flight's parabola
        self.st[ev.S_NEV] = 0.0
        self.st[ev.S_EVCAP] = (self.st.size - ev.N_ST) // ev.EV_W
        self.resist = other.resist
        if self.rigid:
            return
        np.copyto(self.fh, other.fh)
        if self.history is not None and other.history is not None:
            self.history.copy_from(other.history)
        else:
            np.copyto(self.fs, other.fs)
            np.copyto(self.is_, other.is_)

    def trajectory(self) -> pd.DataFrame:
        """The recorded rows (columns ``t, x, vx, y, vy, a, b, N_star, T_star``); x is the centre.

        With rotation also ``psi`` = R phi / a0 (the rolling angle in units of a0, from rest) and
        ``spin`` = psi' (R phi' / a0 per unit t*).
        """
        import pandas as pd

        data = np.concatenate(self.rec_chunks) if self.rec_chunks else np.zeros((0, ig.N_REC))
        if self.roll > 0.0 and not self.resist:
            # from rest R phi = x / kappa = (c - 1) x (docs/physics.md, Rotation)
            data[:, 9:11] = psi_from_rest(data[:, 1:3], self.roll)
        columns = list(ig.REC_COLUMNS)
        if self.roll <= 0.0:
            data = data[:, :9]
            columns = columns[:9]
        return pd.DataFrame(data, columns=columns)
