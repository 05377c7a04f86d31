"""The contact-model interface every plugin implements.

A contact model turns the contact displacements (a*, b*) of docs/physics.md into the
normalized forces (N*, T*) and owns whatever history that takes. Two kinds exist:

* **compliant** models (``capabilities.rigid = False``) give (N*, T*) from (a*, b*) and their
  history. They provide a pure-Python reference (:meth:`ContactModel.reference`) and, where speed
  matters, a numba kernel (:attr:`ContactModel.kernel`). The runner integrates paper eq. 5 with
  them.
* **rigid** models (``capabilities.rigid = True``, the material point of paper section 4) have no
  displacement law: the runner uses a unilateral-constraint scheme with Coulomb friction.

Kernel protocol (numba ``@njit`` functions, both engines follow the same rules)::

    reset(fs, is_, pp)                          -> None        # empty history, no contact
    force(fs, is_, pp, a, b, adot, bdot)        -> (N, T)      # advance AND commit to (a, b)

``fs`` (float64) and ``is_`` (int64) are the model's state arrays, of the sizes
:meth:`ContactModel.state_sizes` returns; ``pp`` is the float64 vector from
:meth:`ContactModel.packed_params`. ``force`` treats the move from the previous committed (a*, b*)
to the new one as a straight path (the exact solution for piecewise-linear histories), commits it,
and returns the forces there. A fresh state is out of contact at (0, 0); the runner brings it to
the initial compression by calling ``force`` once.

The trial/commit rule: kernels always commit. Code that needs a trial evaluation (a multi-stage
integrator, a Newton iteration) uses :meth:`ContactHistory.trial`, which evaluates on a copy, so a
trial can never corrupt the committed history.
"""

from __future__ import annotations

import pickle
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, ClassVar, Protocol

import numpy as np
from pydantic import BaseModel, ConfigDict

from ..codegen import refresh_stale_caches
from ..scene.profiles import Profile

#: Version of the kernel protocol (the signatures and the trial/commit rule in the module
#: docstring). A change that breaks compiled plugins raises it; models declare the version they
#: were written for in ``ContactModel.kernel_interface``.
KERNEL_INTERFACE = 1


class NoParams(BaseModel):
    """Parameter schema of a model that takes none."""

    model_config = ConfigDict(frozen=True, extra="forbid")


@dataclass(frozen=True)
class Capabilities:
    """What a model can do, so the runner can refuse or adapt before anything runs.

    Attributes
    ----------
    rigid
        True for a material point (no contact compliance); the runner then uses the rigid scheme.
    profiles
        Profile shapes the model supports (``"power"`` means any power law p >= 1).
    compiled
        True if the model has a numba kernel.
    history
        True if the tangential force depends on the displacement history, not only on (a*, b*).
    uses_velocity
        True if the forces may depend on the velocities (a*', b*') (e.g. viscous damping).
        False is a promise the conformance suite holds the model to (check
        ``velocity_independence``: the same history driven with and without velocities gives the
        same forces); every check drives real, finite-difference velocities either way.
    straight_path_exact
        True if a straight move gives the same forces however it is split into steps (the
        conformance suite then checks it).
    deviations
        Known departures from a conformance check, as ``(check name, one-line reason)`` pairs:
        such a check is reported as ``declared`` instead of ``fail``, and listed by
        ``sawdrift models``.
    """

    rigid: bool = False
    profiles: tuple[str, ...] = ("sphere", "cone", "flat", "power")
    compiled: bool = True
    history: bool = True
    uses_velocity: bool = False
    straight_path_exact: bool = False
    deviations: tuple[tuple[str, str], ...] = ()


class Kernel(Protocol):
    """The pair of numba functions a compiled model provides."""

    reset: Callable[..., None]
    force: Callable[..., tuple[float, float]]


@dataclass(frozen=True)
class KernelPair:
    """Compiled ``reset`` and ``force`` functions of a model (see module docstring)."""

    reset: Any
    force: Any

    @staticmethod
    def lazy(module: str, reset: str = "reset", force: str = "force") -> LazyKernelPair:
        """A pair imported from ``module`` on first use (so that listing models needs no numba)."""
        return LazyKernelPair(module, reset, force)


class LazyFunction:
    """A compiled function named by module and attribute, imported on first use."""

    def __init__(self, module: str, name: str) -> None:
        self.module, self.name = module, name

    def __getstate__(self) -> dict[str, Any]:
        # a process that unpickles it imports (and checks) the function itself
        return {"module": self.module, "name": self.name}

    def load(self) -> Any:
        """The function itself.

        On the first load, numba's on-disk cache of it is brought in line with its code and the
        code it calls (:func:`sawdrift.codegen.refresh_stale_caches`), so a direct
        call (the conformance suite, ``ContactHistory``) never runs machine code of an older
        version of the kernel or of a helper in another file.
        """
        fn = self.__dict__.get("_fn")
        if fn is None:
            import importlib

            fn = getattr(importlib.import_module(self.module), self.name)
            if hasattr(fn, "py_func"):
                refresh_stale_caches([fn])
            self._fn = fn
        return fn


class LazyKernelPair:
    """A :class:`KernelPair` whose functions are imported from their module on first access."""

    def __init__(self, module: str, reset: str, force: str) -> None:
        self.module = module
        self._reset, self._force = LazyFunction(module, reset), LazyFunction(module, force)

    @property
    def reset(self) -> Any:
        """The compiled ``reset`` function."""
        return self._reset.load()

    @property
    def force(self) -> Any:
        """The compiled ``force`` function."""
        return self._force.load()


class ReferenceContact(Protocol):
    """Readable pure-Python implementation of a compliant model's contact law."""

    def reset(self) -> None:
        """Forget all history: out of contact at (a*, b*) = (0, 0)."""

    def force(self, a: float, b: float, adot: float = 0.0, bdot: float = 0.0) -> tuple[float, float]:
        """Advance along a straight path to (a*, b*), commit, and return (N*, T*)."""

    # Optional: ``state() -> picklable snapshot`` and ``set_state(snapshot)`` (in place), as
    # :class:`KernelReference` has; without them ContactHistory.state pickles the whole object.


class ContactModel:
    """Base class of every contact model plugin.

    Subclasses set the class attributes and implement the methods their kind needs. They are
    registered by returning the class from the ``sawdrift_contact_models`` hook of a module named
    in the ``sawdrift.models`` entry-point group.

    Parameters
    ----------
    params
        An instance of the model's :attr:`Params` schema.
    profile
        The particle's profile.
    """

    name: ClassVar[str]
    summary: ClassVar[str]
    Params: ClassVar[type[BaseModel]] = NoParams
    capabilities: ClassVar[Capabilities] = Capabilities()
    kernel: ClassVar[KernelPair | None] = None
    #: The kernel protocol version the model was written for (see :data:`KERNEL_INTERFACE`);
    #: the registry refuses a model written for another one, with a warning naming it.
    kernel_interface: ClassVar[int] = 1

    def __init__(self, params: BaseModel | None = None, profile: Profile | None = None) -> None:
        self.params = params if params is not None else self.Params()
        self.profile = profile if profile is not None else Profile()

    # -- compliant models -------------------------------------------------------------------
    def state_sizes(self) -> tuple[int, int]:
        """Sizes of the float64 and int64 state arrays the kernel works on."""
        raise NotImplementedError(f"model {self.name!r} has no kernel state")

    def live_sizes(self, fs: np.ndarray, is_: np.ndarray) -> tuple[int, int]:
        """How many leading entries of ``fs`` and ``is_`` hold the current history.

        A copy (checkpoint, trial) needs only these; the default is everything.
        """
        return fs.size, is_.size

    def packed_params(self) -> np.ndarray:
        """Float64 vector of everything the kernel needs.

        The default is the profile's normal-law descriptor (:mod:`sawdrift.contact.normal`):
        ``[p]`` for a power law, so the exponent comes first by convention.
        """
        return self.profile.law()

    def reference(self) -> ReferenceContact:
        """A fresh pure-Python reference contact (empty history).

        The default runs the kernel's own Python code uncompiled (``py_func`` of ``reset`` and
        ``force``) on fresh state arrays; a model with a separate readable implementation
        overrides this.
        """
        if self.kernel is None:
            raise NotImplementedError(f"model {self.name!r} has no pure-Python reference")
        return KernelReference(self)

    def normal_law(self) -> tuple[Callable[..., tuple[float, float]], np.ndarray]:
        """The model's normal law alone: a compiled kernel and the ``pp`` it reads.

        The kernel has the signature ``(fs, is_, pp, a, b, adot, bdot)``, returns ``(N*, 0)`` and
        keeps no history; the integrator calls it instead of the tangential law when friction
        is off. The default is the profile's law
        (:func:`sawdrift.contact.normal.profile_normal`); a model with its own normal physics (normal
        damping, a tabulated law) overrides this. ``.py_func`` of the result is the python engine's.
        """
        from .normal import profile_normal

        return profile_normal, self.profile.law()

    def declared_deviations(self) -> tuple[tuple[str, str], ...]:
        """Known conformance deviations of this configured model (default: the capabilities').

        A model whose deviation depends on its parameters overrides this.
        """
        return self.capabilities.deviations

    # -- shared -----------------------------------------------------------------------------
    @classmethod
    def describe(cls) -> dict[str, Any]:
        """Name, summary, capabilities and parameter schema with defaults (for ``models --json``)."""
        schema = cls.Params.model_json_schema()
        params = {
            key: {
                "default": prop.get("default"),
                "type": prop.get("type", prop.get("anyOf")),
                "description": prop.get("description", ""),
            }
            for key, prop in schema.get("properties", {}).items()
        }
        caps = cls.capabilities
        return {
            "name": cls.name,
            "summary": cls.summary,
            "rigid": caps.rigid,
            "compiled": caps.compiled,
            "history": caps.history,
            "profiles": list(caps.profiles),
            "deviations": {check: reason for check, reason in cls().declared_deviations()},
            "parameters": params,
        }

    def new_history(self, engine: str = "compiled") -> ContactHistory:
        """A committed contact history driven through this model (see :class:`ContactHistory`)."""
        return ContactHistory(self, engine)


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
            self._fs = np.zeros(nf, dtype=np.float64)
            self._is = np.zeros(ni, dtype=np.int64)
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


_DRIVERS: dict[Any, Callable[..., None]] = {}


def _drive_compiled(force, fs, is_, pp, a, b, adot, bdot, n_out, t_out,
                    quasi_static: bool = False) -> None:
    """Run a kernel over a sampled history inside one compiled loop (one per kernel, cached);
    ``quasi_static`` passes zero velocities without reading ``adot``, ``bdot``."""
    fn = _DRIVERS.get((force, quasi_static))
    if fn is None:
        from numba import njit

        if quasi_static:
            def loop(fs, is_, pp, a, b, adot, bdot, n_out, t_out):
                for k in range(a.size):
                    n, t = force(fs, is_, pp, a[k], b[k], 0.0, 0.0)
                    n_out[k] = n
                    t_out[k] = t
        else:
            def loop(fs, is_, pp, a, b, adot, bdot, n_out, t_out):
                for k in range(a.size):
                    n, t = force(fs, is_, pp, a[k], b[k], adot[k], bdot[k])
                    n_out[k] = n
                    t_out[k] = t

        fn = njit(loop)
        _DRIVERS[(force, quasi_static)] = fn
    fn(fs, is_, pp, a, b, adot, bdot, n_out, t_out)
