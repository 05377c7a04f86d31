"""A contact model's committed history, and the python engine of a kernel.

The kernel protocol of :mod:`sawdrift.contact.base` always commits: ``force`` advances the
model's state arrays along a straight path to (a*, b*) and returns the forces there. This module
holds the objects that own such state and drive it:

* :class:`ContactHistory` - a model's committed history behind a trial/commit interface
  (``advance`` commits, ``trial`` evaluates on a copy), with snapshots (``state``,
  ``set_state``), checkpoints (``copy``), the kernel's call signature for an integrator loop
  (``kernel_call``) and whole sampled histories run in one compiled loop (``drive``);
* :class:`KernelReference` - the pure-Python engine of a kernel: its ``py_func`` run on its own
  state arrays (the default :meth:`~sawdrift.contact.base.ContactModel.reference`).

Both are re-exported by :mod:`sawdrift.contact.base`, where the model interface lives.
"""

from __future__ import annotations

import pickle
from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from ..codegen import Generated, generate

if TYPE_CHECKING:
    from .base import ContactModel, ReferenceContact


class KernelReference:
    """The pure-Python engine of a kernel: its ``py_func`` run on its own state arrays.

    ``reset`` and ``force`` default to the model's kernel functions (uncompiled); a caller with
    other Python functions of the same signatures passes them (the contact slots do).
    """

    def __init__(self, model: ContactModel, reset: Any = None, force: Any = None) -> None:
        nf, ni = model.state_sizes()
        if reset is None or force is None:
            reset = getattr(model.kernel.reset, "py_func", model.kernel.reset)
            force = getattr(model.kernel.force, "py_func", model.kernel.force)
        self._reset, self._force = reset, force
        self._model = model
        self.fs = np.zeros(nf, dtype=np.float64)
        self.is_ = np.zeros(ni, dtype=np.int64)
        self.pp = model.packed_params()
        self.reset()

    def reset(self) -> None:
        """Empty history."""
        self._reset(self.fs, self.is_, self.pp)

    def force(self, a: float, b: float, adot: float = 0.0, bdot: float = 0.0) -> tuple[float, float]:
        """Advance along a straight path to (a*, b*), commit, return (N*, T*)."""
        n, t = self._force(self.fs, self.is_, self.pp, float(a), float(b), float(adot), float(bdot))
        return float(n), float(t)

    def state(self) -> dict[str, Any]:
        """A snapshot of the committed history: copies of the live part of the state arrays.

        Returns
        -------
        dict
            ``{"fs": ..., "is": ...}``, the leading entries :meth:`ContactModel.live_sizes`
            counts (the rest is never read before it is written); picklable, :meth:`set_state`
            puts it back. A subclass whose functions keep state elsewhere adds it.
        """
        nf, ni = self._model.live_sizes(self.fs, self.is_)
        return {"fs": self.fs[:nf].copy(), "is": self.is_[:ni].copy()}

    def set_state(self, state: Mapping[str, Any]) -> None:
        """Put back a snapshot of :meth:`state` (same model), in place.

        Parameters
        ----------
        state
            What :meth:`state` returned on a reference of the same model.
        """
        fs, is_ = np.asarray(state["fs"]), np.asarray(state["is"])
        self.fs[: fs.size] = fs
        self.is_[: is_.size] = is_


class ContactHistory:
    """A model's committed history with a safe trial/commit interface.

    ``advance`` moves the history to (a*, b*) and commits; ``trial`` evaluates the forces that
    ``advance`` would give without touching the committed state (it works on a copy).

    Parameters
    ----------
    model
        A compliant contact model.
    engine
        ``"compiled"`` (numba kernel) or ``"python"`` (the reference implementation).
    """

    def __init__(self, model: ContactModel, engine: str = "compiled") -> None:
        if model.capabilities.rigid:
            raise ValueError(f"model {model.name!r} is rigid: it has no displacement history")
        self.model = model
        self.engine = engine
        if engine == "compiled":
            if model.kernel is None:
                raise ValueError(f"model {model.name!r} has no compiled kernel")
            nf, ni = model.state_sizes()
            # the float state uninitialised but for the part a reset history holds (its live
            # part, :meth:`ContactModel.live_sizes`): the rest is never read before written (as
            # in :meth:`copy`), and zeroing a memory diagram's whole capacity (65536 kinks,
            # 3 MB) cost 0.1 ms a history, 0.4 s of a 41 x 41 sweep on the 2-core machine
            self._is = np.zeros(ni, dtype=np.int64)
            self._fs = np.empty(nf, dtype=np.float64)
            self._fs[: model.live_sizes(self._fs, self._is)[0]] = 0.0
            self._pp = model.packed_params()
            model.kernel.reset(self._fs, self._is, self._pp)
            self._ref = None
        elif engine == "python":
            self._ref = model.reference()
            self._ref.reset()
        else:
            raise ValueError(f"engine = {engine!r}; allowed: 'compiled', 'python'")

    def reset(self) -> None:
        """Forget the history (out of contact at (0, 0)) without reallocating the state."""
        if self._ref is not None:
            self._ref.reset()
        else:
            self.model.kernel.reset(self._fs, self._is, self._pp)

    def advance(self, a: float, b: float, adot: float = 0.0, bdot: float = 0.0) -> tuple[float, float]:
        """Move the history along a straight path to (a*, b*), commit, return (N*, T*)."""
        if self._ref is not None:
            return self._ref.force(a, b, adot, bdot)
        n, t = self.model.kernel.force(self._fs, self._is, self._pp, a, b, adot, bdot)
        return float(n), float(t)

    @property
    def reference(self) -> ReferenceContact | None:
        """The python engine's live reference contact (its readable state); None when compiled."""
        return self._ref

    def kernel_call(self) -> tuple[Callable[..., tuple[float, float]], np.ndarray, np.ndarray, np.ndarray]:
        """``(force, fs, is_, pp)``: this history behind the kernel's call signature.

        An integrator loop calls ``force(fs, is_, pp, a, b, adot, bdot)`` and thereby advances
        this history. For the python engine ``force`` drives the reference and the arrays are
        placeholders. The call stays bound to this history across :meth:`set_state`.
        """
        if self._ref is None:
            return self.model.kernel.force, self._fs, self._is, self._pp
        history = self

        def force(fs, is_, pp, a, b, adot, bdot):
            # the reference this history holds at the call (set_state may replace it)
            return history._ref.force(a, b, adot, bdot)

        return force, np.zeros(1), np.zeros(1, dtype=np.int64), np.zeros(1)

    def kernel_reset(self) -> Callable[..., None]:
        """``reset``: :meth:`reset` behind the kernel's call signature ``reset(fs, is_, pp)``.

        Called with :meth:`kernel_call`'s arrays it empties this history, so that a loop bound
        to both starts from an empty memory without returning to Python: the kernel's own
        compiled ``reset``, or for the python engine a function that resets the reference.
        """
        if self._ref is None:
            return self.model.kernel.reset
        history = self

        def reset(fs, is_, pp):  # noqa: ARG001 - the kernel's signature
            history.reset()

        return reset

    def state(self) -> dict[str, np.ndarray]:
        """A snapshot of the committed history, as arrays (copies): :meth:`set_state` puts it back.

        Returns
        -------
        dict of str to numpy.ndarray
            For the compiled engine ``{"fs": ..., "is": ...}``, the live part of the float64 and
            int64 state arrays (:meth:`ContactModel.live_sizes`); for the python engine
            ``{"ref": ...}``, as uint8 the pickle of the reference contact's own snapshot
            (its ``state()``, which :class:`KernelReference` has) or, for a reference without
            one, of the reference itself. Either goes through ``numpy.savez`` and back bit for
            bit (the bifurcation journals keep it as text).
        """
        if self._ref is None:
            nf, ni = self.model.live_sizes(self._fs, self._is)
            return {"fs": self._fs[:nf].copy(), "is": self._is[:ni].copy()}
        own = getattr(self._ref, "state", None)
        snapshot = own() if callable(own) else self._ref
        return {"ref": np.frombuffer(pickle.dumps(snapshot), dtype=np.uint8)}

    def set_state(self, state: Mapping[str, np.ndarray]) -> None:
        """Put back a snapshot of :meth:`state`, taken on a history of the same model and engine.

        The compiled engine's arrays and the python engine's reference (by its ``set_state``)
        are written in place; a reference without one is replaced. A :meth:`kernel_call` taken
        before thus goes on driving this history, and advancing from here continues bit for bit
        as the history the snapshot was taken of would have.

        Parameters
        ----------
        state
            The mapping :meth:`state` returned (or its arrays read back from ``numpy.savez``).

        Raises
        ------
        ValueError
            If the snapshot is of the other engine, or larger than this history's state arrays.
        """
        if self._ref is None:
            if "fs" not in state or "is" not in state:
                raise ValueError("a compiled contact history needs a snapshot with 'fs' and 'is' "
                                 f"(got {sorted(state)})")
            fs, is_ = np.asarray(state["fs"]), np.asarray(state["is"])
            if fs.size > self._fs.size or is_.size > self._is.size:
                raise ValueError(f"a contact snapshot of sizes ({fs.size}, {is_.size}) does not fit "
                                 f"the state arrays ({self._fs.size}, {self._is.size}) of "
                                 f"model {self.model.name!r}")
            self._fs[: fs.size] = fs
            self._is[: is_.size] = is_
            return
        if "ref" not in state:
            raise ValueError("a python-engine contact history needs a snapshot with 'ref' "
                             f"(got {sorted(state)})")
        snapshot = pickle.loads(np.asarray(state["ref"]).tobytes())  # noqa: S301 - our snapshot
        own = getattr(self._ref, "set_state", None)
        if callable(own):
            own(snapshot)  # in place: the reference's composed functions stay bound to it
        else:
            self._ref = snapshot

    def trial(self, a: float, b: float, adot: float = 0.0, bdot: float = 0.0) -> tuple[float, float]:
        """The forces ``advance`` would return, computed on a copy: the history is unchanged."""
        clone = self.copy()
        return clone.advance(a, b, adot, bdot)

    def copy_from(self, other: ContactHistory) -> None:
        """Take ``other``'s committed history in place (a history of the same model and engine):
        what ``set_state(other.state())`` does, without the snapshot in between (the Lyapunov
        twin is put back on its base this way every period)."""
        if self._ref is not None or other._ref is not None:
            self.set_state(other.state())
            return
        nf, ni = other.model.live_sizes(other._fs, other._is)
        self._fs[:nf] = other._fs[:nf]
        self._is[:ni] = other._is[:ni]

    def copy(self) -> ContactHistory:
        """An independent copy (checkpoint) of this history."""
        import copy as _copy

        new = object.__new__(ContactHistory)
        new.model, new.engine = self.model, self.engine
        if self._ref is not None:
            new._ref = _copy.deepcopy(self._ref)
        else:
            new._ref = None
            # only the live part is copied: the rest of the capacity is never read before written
            nf, ni = self.model.live_sizes(self._fs, self._is)
            new._fs = np.empty_like(self._fs)
            new._fs[:nf] = self._fs[:nf]
            new._is = np.empty_like(self._is)
            new._is[:ni] = self._is[:ni]
            new._pp = self._pp
        return new

    def drive(self, a: np.ndarray, b: np.ndarray, adot: np.ndarray | None = None,
              bdot: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Advance through sampled histories a*(k), b*(k); return arrays N*(k), T*(k).

        ``adot``, ``bdot`` are the velocities a*'(k), b*'(k) passed with each step (default:
        zero, a quasi-static drive).
        """
        a = np.asarray(a, dtype=np.float64)
        b = np.asarray(b, dtype=np.float64)
        quasi_static = adot is None and bdot is None
        if quasi_static:
            adot = bdot = a  # placeholders of the right shape: the quasi-static loop passes 0.0
        else:
            adot = np.zeros_like(a) if adot is None else np.asarray(adot, dtype=np.float64)
            bdot = np.zeros_like(a) if bdot is None else np.asarray(bdot, dtype=np.float64)
        if not a.shape == b.shape == adot.shape == bdot.shape:
            raise ValueError("a, b, adot and bdot must have the same length")
        n_out = np.empty_like(a)
        t_out = np.empty_like(a)
        if self._ref is None:
            _drive_compiled(self.model.kernel.force, self._fs, self._is, self._pp, a, b, adot, bdot,
                            n_out, t_out, quasi_static)
        elif quasi_static:
            for k in range(a.size):
                n_out[k], t_out[k] = self._ref.force(a[k], b[k], 0.0, 0.0)
        else:
            for k in range(a.size):
                n_out[k], t_out[k] = self._ref.force(a[k], b[k], adot[k], bdot[k])
        return n_out, t_out


_DRIVERS: dict[Any, dict[str, Any]] = {}


def drive_body(fs, is_, pp, a, b, adot, bdot, n_out, t_out):
    """The contact law ``force`` (a global, bound per kernel) along sampled a*, b* and their
    rates: N*, T* of every step into ``n_out``, ``t_out``."""
    for k in range(a.size):
        n, t = force(fs, is_, pp, a[k], b[k], adot[k], bdot[k])  # noqa: F821
        n_out[k] = n
        t_out[k] = t


def drive_body_quasi_static(fs, is_, pp, a, b, adot, bdot, n_out, t_out):
    """:func:`drive_body` at zero rates (``adot``, ``bdot`` are not read)."""
    for k in range(a.size):
        n, t = force(fs, is_, pp, a[k], b[k], 0.0, 0.0)  # noqa: F821
        n_out[k] = n
        t_out[k] = t


def _drive_compiled(force, fs, is_, pp, a, b, adot, bdot, n_out, t_out,
                    quasi_static: bool = False) -> None:
    """Run a kernel over a sampled history inside one compiled loop; ``quasi_static`` passes
    zero velocities without reading ``adot``, ``bdot``.

    The loops (:func:`drive_body`, :func:`drive_body_quasi_static`) are bound to the kernel's
    ``force`` once per kernel and process, in a module generated and cached on disk across
    processes (:mod:`sawdrift.codegen`, as the wave loop): a second process loads their machine
    code instead of compiling it. A kernel that cannot be imported by name is compiled in memory.
    """
    loops = _DRIVERS.get(force)
    if loops is None:
        loops = generate(Generated(
            prefix="sawdrift_loop_", doc="the contact law driven along a prescribed history",
            templates=(drive_body, drive_body_quasi_static), namespace={"force": force},
            bind={"force": force}, decorator="njit(cache=True, _nrt=False)",
            memory_options={"_nrt": False},
        ))
        _DRIVERS[force] = loops
    fn = loops["drive_body_quasi_static" if quasi_static else "drive_body"]
    fn(fs, is_, pp, a, b, adot, bdot, n_out, t_out)
