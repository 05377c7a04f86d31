"""A snapshot of one integration, to continue it later bit for bit: what
:meth:`~sawdrift.dynamics.stepper.Stepper.save` keeps and
:meth:`~sawdrift.dynamics.stepper.Stepper.restore` puts back, and its text form for a JSON journal
(the bifurcation diagrams' resumable branches)."""

from __future__ import annotations

import base64
import io
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from . import evidence as ev

if TYPE_CHECKING:
    from .stepper import Stepper

__all__ = ["Checkpoint", "StepperState", "checkpoint", "put_back", "rewind", "snapshot"]

#: Keys of the contact history's snapshot in a :class:`StepperState`
#: (:meth:`~sawdrift.contact.history.ContactHistory.state`).
_HISTORY_KEYS = ("fs", "is", "ref")


@dataclass(frozen=True)
class StepperState:
    """A snapshot of one integration: what :meth:`Stepper.save` keeps and :meth:`Stepper.restore`
    puts back (mechanical state, step counters, Adams-Bashforth derivative history, contact memory).

    ``arrays`` holds ``y``, ``ctr``, with a compliant scheme ``fh``, and the contact history's
    snapshot (:meth:`~sawdrift.contact.history.ContactHistory.state`: ``fs``, ``is``; or ``ref``, the
    python reference pickled). :meth:`to_text` and :meth:`from_text` carry it through a JSON
    journal (base64 of an ``.npz``), bit for bit.
    """

    arrays: dict[str, np.ndarray]

    def to_text(self) -> str:
        """The snapshot as ASCII text (base64 of ``numpy.savez``)."""
        buf = io.BytesIO()
        np.savez(buf, **self.arrays)
        return base64.b64encode(buf.getvalue()).decode()

    @classmethod
    def from_text(cls, text: str) -> StepperState:
        """Inverse of :meth:`to_text`."""
        with np.load(io.BytesIO(base64.b64decode(text))) as data:
            return cls({key: data[key] for key in data.files})


def snapshot(stepper: Stepper) -> StepperState:
    """A snapshot of ``stepper`` (copies): its mechanical state, counters, the free flight's count
    and anchor, the Adams-Bashforth derivative history (compliant schemes) and the contact memory
    (:meth:`~sawdrift.contact.history.ContactHistory.state`)."""
    arrays: dict[str, np.ndarray] = {
        "y": stepper.y.copy(), "ctr": stepper.ctr.copy(),
        "flight": stepper.st[ev.S_FLY : ev.S_FLY + ev.N_FLIGHT].copy()}
    if not stepper.rigid:
        arrays["fh"] = stepper.fh.copy()
    if stepper.history is not None:
        arrays.update(stepper.history.state())
    return StepperState(arrays)


def put_back(stepper: Stepper, state: StepperState) -> None:
    """Put a :func:`snapshot` back into ``stepper`` (one of the same model and engine), in place."""
    data = state.arrays
    stepper.y[:] = data["y"]
    stepper.ctr[:] = data["ctr"]
    # a free flight's count and anchor (a snapshot without them: the flight counts afresh)
    stepper.st[ev.S_FLY : ev.S_FLY + ev.N_FLIGHT] = data.get("flight", 0.0)
    if "fh" in data:
        stepper.fh[:] = data["fh"]
    if stepper.history is not None:
        # in place: the loop stays bound to the history (ContactHistory.set_state)
        stepper.history.set_state({k: data[k] for k in _HISTORY_KEYS if k in data})


@dataclass(frozen=True)
class Checkpoint:
    """A point of a run to go back to within the run (:func:`checkpoint`): its snapshot, its
    window statistics and event log, and its recorded trajectory as far as it went."""

    state: StepperState
    stats: np.ndarray
    chunks: tuple[np.ndarray, ...]
    rows: int
    every: int
    keep_events: bool


def checkpoint(stepper: Stepper) -> Checkpoint:
    """A :class:`Checkpoint` of ``stepper``: what :func:`snapshot` keeps, and also the statistics
    and event log (``st``: the last lift-off, the contact and slip states the next step compares
    with) and the trajectory recorded so far, so that :func:`rewind` leaves no trace of the steps
    taken after it (a solved orbit that did not hold, :func:`~.direct.settle_direct`)."""
    return Checkpoint(snapshot(stepper), stepper.st.copy(), tuple(stepper.rec_chunks),
                      stepper.rec_rows, stepper.rec_every, stepper.keep_events)


def rewind(stepper: Stepper, point: Checkpoint) -> None:
    """Put ``stepper`` back at ``point``, in place: its state, statistics and event log, and its
    trajectory cut back to the rows recorded by then (time increasing along it)."""
    put_back(stepper, point.state)
    stepper.st = point.stats.copy()
    stepper.rec_chunks = list(point.chunks)
    stepper.rec_rows = point.rows
    stepper.rec_every = point.every
    stepper.keep_events = point.keep_events
