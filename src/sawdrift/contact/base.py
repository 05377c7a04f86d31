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
integrator, a Newton iteration) uses :meth:`~sawdrift.contact.history.ContactHistory.trial`,
which evaluates on a copy, so a trial can never corrupt the committed history.

The committed history (:class:`~sawdrift.contact.history.ContactHistory`) and the python engine
of a kernel (:class:`~sawdrift.contact.history.KernelReference`) live in
:mod:`sawdrift.contact.history`; both are importable from here too.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar, Protocol

import numpy as np
from pydantic import BaseModel, ConfigDict

from ..codegen import refresh_stale_caches
from ..scene.profiles import Profile
from .history import ContactHistory, KernelReference

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

    def compiled_live_floats(self) -> Any:
        """The compiled twin of :meth:`live_sizes`' float count, ``live(fs, is_) -> int``
        (importable by name), for compiled loops that copy a history every period (the
        Lyapunov twin, :mod:`sawdrift.dynamics.stretching`); None: such a loop copies it whole,
        or, for a long memory, the copy stays in Python."""
        return None

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
            # the adhesive laws (effects.adhesion) the model takes, and what it assumes with them
            "adhesion": getattr(cls, "adhesive_summary", ""),
            "parameters": params,
        }

    def new_history(self, engine: str = "compiled") -> ContactHistory:
        """A committed contact history driven through this model (see :class:`ContactHistory`)."""
        return ContactHistory(self, engine)
