"""Contact slots: a contact composed of a normal law, an optional normal damping and a tangential law.

In the style of LAMMPS ``pair granular`` (a contact built from sub-models in fixed slots), a
compliant contact here is

* the **normal slot**: the profile's elastic law N*(a*) (power law or table,
  :mod:`sawdrift.contact.normal`), owned by the framework;
* the **normal-damping slot** (optional, :class:`NormalDamping`): one compiled function that turns
  the elastic N* into the total normal force, e.g. Tsuji's dashpot; empty means "not computed";
* the **tangential slot** (:class:`TangentialLaw`): one class and one compiled ``step`` function.

The framework owns what every law used to repeat: the committed (a*, b*), contact entry (a fresh
history that starts where the straight path crosses a* = 0), contact loss (the tangential
history is reset once, on the step that leaves contact), the normal force, and the state layout.
Every compliant built-in law (``mmd``, ``mdr``, ``jaeger``, ``hertz_mindlin_dem``) is a tangential
law here, so :func:`contact_force` is the only place where contact entry and loss are handled.
From the slots it generates the contact protocol of :mod:`sawdrift.contact.base`
(``reset``/``force``), so the integrators, the conformance suite and the python engine see an
ordinary contact model. The generated module is written to the cache folder of
:mod:`sawdrift.codegen` and compiled with numba's on-disk cache.

Tangential step protocol (numba ``@njit`` functions)::

    step(ts, is_, law, tp, a0, b0, a, b)  -> T*     # straight path (a0, b0) -> (a, b), commit
    reset(ts, is_, law, tp)               -> None   # optional; default: zero ts and is_

A step that computes N*(a*) anyway (``mmd``'s top kink stores it) may return ``(T*, N*)``
instead, N* bit for bit :func:`~sawdrift.contact.normal.law_normal`'s, if it is marked with
:func:`gives_normal`; the slots then take N* from it instead of evaluating the law again.
A step marked with :func:`takes_normal` is instead handed the total normal force N* (the normal
slot's, through the normal-damping slot if one is filled) as a last argument,
``step(ts, is_, law, tp, a0, b0, a, b, n)``, and bounds its stored force by it (the DEM spring
of ``hertz_mindlin_dem``, as LAMMPS bounds its tangential history by the total normal force).

``ts`` (float64) and ``is_`` (int64) are the law's own state (sizes from
:meth:`TangentialLaw.tangential_sizes`), ``law`` starts with the normal-law descriptor (read it
with :func:`~sawdrift.contact.normal.law_normal` / :func:`~sawdrift.contact.normal.law_slope` at
offset 0; the view runs on past it) and ``tp`` holds the law's parameters
(:meth:`TangentialLaw.tangential_params`). ``step`` is only called in contact (a > 0);
``a0 = 0`` exactly when the contact is new and the history has just been reset. ``reset`` is
called on a zeroed ``is_`` for a new history (:meth:`ContactHistory.reset
<sawdrift.contact.history.ContactHistory.reset>`) and on the live state, once, on the step that
loses contact, so a law can keep what outlives a contact (a high-water mark, a set-up grid).

The composition inlines ``step`` and ``damp`` (numba IR inlining, :data:`_INLINE`), so a law in
a slot costs what the same code written as one whole kernel does; numba copies an inlined body
once per call site, so a step should call its big helpers from few places (see
:mod:`sawdrift_builtin.mmd_kernel`) to keep compilation short.

Damping protocol: ``damp(dp, law, a, adot, n_elastic) -> N*`` with ``dp`` from
:meth:`NormalDamping.packed`.
"""

from __future__ import annotations

import copy
from typing import Any, ClassVar

import numpy as np
from pydantic import BaseModel, ConfigDict, create_model

from ..codegen import Generated, generate, rebind
from .base import ContactModel, KernelPair, LazyFunction, NoParams
from .history import KernelReference

#: Float entries the framework keeps in front of the law's state: committed a*, committed b*,
#: and 1.0 while the tangential history belongs to a contact (0.0: fresh).
HEADER = 3
#: where the normal-law descriptor starts in ``pp``
LAW = 2


def _load(func: Any) -> Any:
    return func.load() if isinstance(func, LazyFunction) else func


# -- the composition: one source, compiled for the kernel and run plainly for the python engine --


def contact_reset(fs, is_, pp):
    """Empty history, out of contact at (a*, b*) = (0, 0); the law's reset on a zeroed ``is_``."""
    fs[0] = 0.0
    fs[1] = 0.0
    fs[2] = 0.0
    for i in range(is_.shape[0]):
        is_[i] = 0
    tangential_reset(fs[HEADER:], is_, pp[LAW:], pp[int(pp[0]):int(pp[1])])  # noqa: F821


def contact_force(fs, is_, pp, a, b, adot, bdot):
    """Advance along the straight path from the committed (a*, b*) to (a, b), commit, (N*, T*).

    The one place of contact entry and loss (every tangential law runs inside it).
    """
    a0 = fs[0]
    b0 = fs[1]
    fs[0] = a
    fs[1] = b
    if not a > 0.0:
        if fs[2] != 0.0:
            # contact lost: the tangential history is forgotten, once
            tangential_reset(fs[HEADER:], is_, pp[LAW:], pp[int(pp[0]):int(pp[1])])  # noqa: F821
            fs[2] = 0.0
        return 0.0, 0.0
    if fs[2] == 0.0:
        # a fresh contact starts where the straight path crosses a* = 0
        if a0 < 0.0:
            b0 = b0 + (b - b0) * (-a0 / (a - a0))
        a0 = 0.0
        fs[2] = 1.0
    # STEP_NORMAL, TAKES_NORMAL, DAMPED and CAP are constants of the composition: numba prunes
    # the branches not taken before it inlines the step, so an empty slot is never computed
    if STEP_NORMAL:  # noqa: F821 - the step gives N*(a*) with T* (gives_normal)
        t, n = tangential_step(fs[HEADER:], is_, pp[LAW:], pp[int(pp[0]):int(pp[1])],  # noqa: F821
                               a0, b0, a, b)
        if DAMPED:  # noqa: F821 - a normal-damping slot is filled
            n = normal_damping(pp[int(pp[1]):], pp[LAW:], a, adot, n)  # noqa: F821
    else:
        n = law_normal(a, pp, LAW)  # noqa: F821
        if DAMPED:  # noqa: F821
            n = normal_damping(pp[int(pp[1]):], pp[LAW:], a, adot, n)  # noqa: F821
        if TAKES_NORMAL:  # noqa: F821 - the step bounds its stored force by N* (takes_normal)
            t = tangential_step(fs[HEADER:], is_, pp[LAW:], pp[int(pp[0]):int(pp[1])],  # noqa: F821
                                a0, b0, a, b, n)
        else:
            t = tangential_step(fs[HEADER:], is_, pp[LAW:], pp[int(pp[0]):int(pp[1])],  # noqa: F821
                                a0, b0, a, b)
    if CAP:  # noqa: F821 - a constant of the composition (TangentialLaw.coulomb_cap)
        t = coulomb_cap(t, n)  # noqa: F821 - |T*| <= N*, the total normal force (slot_kernels)
    return n, t


def contact_normal(fs, is_, pp, a, b, adot, bdot):
    """(N*, 0): the normal and normal-damping slots alone (friction off); no history."""
    if not a > 0.0:
        return 0.0, 0.0
    n = law_normal(a, pp, LAW)  # noqa: F821
    if DAMPED:  # noqa: F821
        n = normal_damping(pp[int(pp[1]):], pp[LAW:], a, adot, n)  # noqa: F821
    return n, 0.0


_TEMPLATES = (contact_reset, contact_force, contact_normal)


def gives_normal(step: Any) -> Any:
    """Mark a tangential step as returning ``(T*, N*)`` (module docstring); returns ``step``.

    N* must be the normal slot's N*(a*) bit for bit; the slots then skip evaluating the law.
    """
    return _mark(step, "gives_normal")


def _mark(step: Any, name: str) -> Any:
    """Set the flag ``name`` on ``step`` and on its plain-Python function (a compiled step's
    ``py_func``, which the python engine calls); returns ``step``."""
    setattr(step, name, True)
    py = getattr(step, "py_func", None)
    if py is not None:
        setattr(py, name, True)
    return step


def _gives_normal(step: Any) -> bool:
    return bool(getattr(step, "gives_normal", False))


def takes_normal(step: Any) -> Any:
    """Mark a tangential step as taking the total normal force N* as a last argument; returns it.

    The slots then compute N* (the normal slot, and the normal-damping slot if one is filled)
    before the step and pass it: ``step(ts, is_, law, tp, a0, b0, a, b, n) -> T*``. The law
    bounds its committed history by it (module docstring); the slots still cap the T* it
    returns. A step cannot both give and take N*.
    """
    if _gives_normal(step):
        raise ValueError("a tangential step cannot both give N* (gives_normal) and take it")
    return _mark(step, "takes_normal")


def _takes_normal(step: Any) -> bool:
    return bool(getattr(step, "takes_normal", False))


def _constants(step: Any, damp: Any, cap: bool) -> dict[str, Any]:
    """The constants of a composition: layout, and which branches of the templates it takes."""
    from .slot_kernels import no_damping

    return {"HEADER": HEADER, "LAW": LAW, "CAP": cap, "STEP_NORMAL": _gives_normal(step),
            "TAKES_NORMAL": _takes_normal(step), "DAMPED": _py(damp) is not _py(no_damping)}


def _namespace(step: Any, reset: Any, damp: Any, law_normal: Any,
               consts: dict[str, Any]) -> dict[str, Any]:
    """The composition's templates bound to the given slot functions (the python engine)."""
    from .slot_kernels import coulomb_cap

    return rebind(_TEMPLATES, {"law_normal": law_normal, "tangential_step": step,
                               "tangential_reset": reset, "normal_damping": damp,
                               "coulomb_cap": coulomb_cap.py_func, **consts})


#: numba options of the step and damping functions as the composition sees them: inlined into
#: ``contact_force`` at numba's IR level, so a law in a slot costs what the same code written as
#: one whole kernel does (a called step kept its state arrays and parameters behind a call)
_INLINE = {"inline": "always", "_nrt": False}


def _compiled_namespace(step: Any, reset: Any, damp: Any, cap: bool) -> dict[str, Any]:
    """The generated, disk-cached module's namespace (or an in-memory compilation)."""
    from numba import njit

    from .normal import JIT_OPTIONS, law_normal
    from .slot_kernels import coulomb_cap

    # the code of every slot function and of all they call keys the module (an edited law
    # compiles anew), and numba's own caches of those functions are brought in line with it;
    # the step and the damping are inlined into the composition (numba IR inlining)
    consts = _constants(step, damp, cap)
    return generate(Generated(
        prefix="sawdrift_contact_",
        doc="a contact composed of slots",
        templates=_TEMPLATES,
        namespace={"law_normal": law_normal, "tangential_step": step, "tangential_reset": reset,
                   "normal_damping": damp, "coulomb_cap": coulomb_cap, **consts},
        imports=("from sawdrift.contact.normal import JIT_OPTIONS, law_normal  # noqa: F401\n"
                 "from sawdrift.contact.slots import HEADER, LAW  # noqa: F401\n"
                 "from sawdrift.contact.slot_kernels import coulomb_cap as _cap  # noqa: F401\n"),
        bind={"_step": step, "tangential_reset": reset, "_damp": damp},
        preamble=(f"tangential_step = njit(**{_INLINE!r})(_step.py_func)\n"
                  f"normal_damping = njit(**{_INLINE!r})(_damp.py_func)\n"
                  f"coulomb_cap = njit(**{_INLINE!r})(_cap.py_func)\n"
                  + "".join(f"{k} = {consts[k]!r}\n"
                            for k in ("CAP", "STEP_NORMAL", "TAKES_NORMAL", "DAMPED"))),
        decorator="njit(**JIT_OPTIONS)",
        memory_options={k: v for k, v in JIT_OPTIONS.items() if k != "cache"},  # source has no file
        memory_namespace={"law_normal": law_normal, "tangential_step": njit(**_INLINE)(_py(step)),
                          "tangential_reset": reset, "normal_damping": njit(**_INLINE)(_py(damp)),
                          "coulomb_cap": njit(**_INLINE)(coulomb_cap.py_func), **consts},
    ))


def _python_namespace(step: Any, reset: Any, damp: Any, cap: bool) -> dict[str, Any]:
    """The same composition run as plain Python (the python engine)."""
    from .normal import law_normal

    return _namespace(step, reset, damp, law_normal.py_func, _constants(step, damp, cap))


_COMPOSED: dict[tuple[Any, ...], dict[str, Any]] = {}


def _py(func: Any) -> Any:
    return getattr(func, "py_func", func)


class _SlotKernel:
    """The ``kernel`` of a :class:`TangentialLaw`: the :class:`KernelPair` composed from its slots.

    The composition depends on the class only (its step, reset and damping functions), so it is
    the same on the class and on every instance. The pair is looked up by the class and its raw
    slot attributes (the damping class's ``damp`` included), so an access costs a few attribute
    reads, not the loading of the slot functions (``ContactHistory.drive`` reads ``kernel`` on
    every call); replacing any slot function recomposes.
    """

    def __get__(self, obj: Any, owner: type[TangentialLaw]) -> KernelPair:
        damping = owner.damping
        raw = (owner.step, owner.reset_state, damping, owner.coulomb_cap,
               damping.damp if damping is not None else None)
        hit = _BY_CLASS.get(owner)
        if hit is not None and hit[0] == raw:  # identical objects: no __eq__ is called
            return hit[1]
        key = owner._key()
        pair = _PAIRS.get(key)
        if pair is None:
            ns = owner._compiled()
            pair = _PAIRS[key] = KernelPair(ns["contact_reset"], ns["contact_force"])
        _BY_CLASS[owner] = (raw, pair)
        return pair


_PAIRS: dict[tuple[Any, ...], KernelPair] = {}
#: class -> (its raw slot attributes, its pair): the fast path of :class:`_SlotKernel`
_BY_CLASS: dict[type, tuple[tuple[Any, ...], KernelPair]] = {}


class NormalDamping:
    """Base class of a normal-damping slot: one compiled ``damp`` function and its parameters.

    ``damp(dp, law, a, adot, n_elastic) -> N*`` receives the elastic normal force of the normal
    slot and returns the total one (clamping at 0 is the damping law's choice).
    """

    name: ClassVar[str]
    Params: ClassVar[type[BaseModel]] = NoParams
    damp: ClassVar[Any]

    @classmethod
    def packed(cls, params: BaseModel) -> np.ndarray:
        """The float64 vector ``dp`` that ``damp`` reads (default: the fields, in order)."""
        return np.array([float(v) for v in params.model_dump().values()], dtype=np.float64)


class TangentialLaw(ContactModel):
    """A contact model given as a tangential law in the tangential slot (module docstring).

    Subclasses set ``name``, ``summary``, ``capabilities``, optionally ``Params``, and ``step``
    (a numba function, or a :class:`LazyFunction`); optionally ``reset_state``, ``damping`` (a
    :class:`NormalDamping` subclass), and override :meth:`tangential_sizes` /
    :meth:`tangential_params`. The contact protocol (``kernel``, ``state_sizes``,
    ``packed_params``, ``normal_law``, ``reference``) is generated from the slots.
    """

    step: ClassVar[Any]
    reset_state: ClassVar[Any] = None
    damping: ClassVar[type[NormalDamping] | None] = None
    #: The slots cap |T*| by N* after the step (the law's committed history is left as it is).
    #: A law whose T* meets the Coulomb bound by construction (T* = N* in full sliding, as the
    #: memory diagram) may set False to get its own T* bit for bit; with a normal-damping slot
    #: the cap applies anyway, the total N* being one the law does not know (a step that takes
    #: it, :func:`takes_normal`, bounds its stored force by it as well).
    coulomb_cap: ClassVar[bool] = True

    # -- what a law provides ---------------------------------------------------------------
    def tangential_sizes(self) -> tuple[int, int]:
        """Sizes of the law's own float64 and int64 state (default: one of each)."""
        return 1, 1

    def tangential_params(self) -> np.ndarray:
        """The law's parameter vector ``tp`` (default: empty)."""
        return np.zeros(0, dtype=np.float64)

    def reference_step(self) -> Any:
        """Optional readable pure-Python step for the python engine.

        Either a ``(step, reset)`` pair of functions with the slot signatures, or an object with
        ``reset()`` and ``step(a0, b0, a, b) -> T*`` (it then keeps its state itself). The default,
        None, runs the kernel's own Python code uncompiled.
        """
        return None

    # -- what the framework derives ----------------------------------------------------------
    @classmethod
    def _functions(cls) -> tuple[Any, Any, Any]:
        # class access: a numba function would bind as a method on an instance
        step = _load(cls.step)
        reset = _load(cls.reset_state) if cls.reset_state is not None else None
        damp = _load(cls.damping.damp) if cls.damping is not None else None
        if reset is None or damp is None:
            from . import slot_kernels

            reset = reset if reset is not None else slot_kernels.zero_reset
            damp = damp if damp is not None else slot_kernels.no_damping
        return step, reset, damp

    @classmethod
    def _key(cls) -> tuple[Any, Any, Any, bool]:
        """What the composition is made of: the slot functions and whether T* is capped."""
        return (*cls._functions(), cls.damping is not None or cls.coulomb_cap)

    @classmethod
    def _compiled(cls) -> dict[str, Any]:
        key = cls._key()
        ns = _COMPOSED.get(key)
        if ns is None:
            ns = _COMPOSED[key] = _compiled_namespace(*key)
        return ns

    #: the contact protocol generated from the slots (also on the class: ``Law.kernel.force``)
    kernel = _SlotKernel()  # type: ignore[assignment]

    def state_sizes(self) -> tuple[int, int]:
        """The framework's header plus the law's own state."""
        nf, ni = self.tangential_sizes()
        return HEADER + int(nf), max(int(ni), 1)

    def damping_params(self) -> np.ndarray:
        """``dp`` of the normal-damping slot (empty if the slot is empty)."""
        if self.damping is None:
            return np.zeros(0, dtype=np.float64)
        fields = self.damping.Params.model_fields
        values = self.damping.Params(**{k: getattr(self.params, k) for k in fields})
        return self.damping.packed(values)

    def packed_params(self) -> np.ndarray:
        """``[start of tp, start of dp, law descriptor..., tp..., dp...]``."""
        law = np.asarray(self.profile.law(), dtype=np.float64)
        tp = np.asarray(self.tangential_params(), dtype=np.float64)
        dp = self.damping_params()
        it = LAW + law.size
        return np.concatenate([[float(it), float(it + tp.size)], law, tp, dp])

    def normal_law(self):
        """The normal and normal-damping slots alone (used when friction is off)."""
        return self._compiled()["contact_normal"], self.packed_params()

    def reference(self) -> SlotReference:
        """The slots composed in plain Python (the law's readable step if it has one)."""
        return SlotReference(self)

    @classmethod
    def with_damping(cls, damping: type[NormalDamping], name: str, summary: str) -> type[TangentialLaw]:
        """This law with ``damping`` in the normal-damping slot, as a new model ``name``.

        Its parameters are the law's and the damping's together.
        """
        fields = {k: (f.annotation, f) for k, f in cls.Params.model_fields.items()}
        fields.update({k: (f.annotation, f) for k, f in damping.Params.model_fields.items()})
        params = create_model(f"{name}_params", __config__=ConfigDict(frozen=True, extra="forbid"),
                              **fields)  # type: ignore[call-overload]
        from dataclasses import replace

        caps = replace(cls.capabilities, uses_velocity=True)
        # no adhesive variant: the DMT or JKR law would replace the normal slots, its damping
        # with them, without a word (hertz_tsuji gave the same drift at damping 0 and 2)
        return type(name, (cls,), {"name": name, "summary": summary, "Params": params,
                                   "damping": damping, "capabilities": caps,
                                   "adhesive_step": None, "adhesive_summary": "",
                                   "__module__": damping.__module__})


class SlotReference(KernelReference):
    """The python engine of a :class:`TangentialLaw`: the composition source run uncompiled."""

    def __init__(self, model: TangentialLaw) -> None:
        step, reset, damp, cap = model._key()
        takes = _takes_normal(step)
        readable = model.reference_step()
        #: the law's readable reference, when it is an object with ``reset()`` and ``step()``
        self.readable = readable if hasattr(readable, "step") else None
        if self.readable is not None:
            obj = self.readable

            def step(ts, is_, law, tp, a0, b0, a, b, *n):  # noqa: ARG001 - the slot signature
                return obj.step(float(a0), float(b0), float(a), float(b), *n)

            def reset(ts, is_, law, tp):  # noqa: ARG001
                obj.reset()
        elif readable is not None:
            step, reset = readable
        if takes:
            takes_normal(step)  # the readable is handed N* as the kernel's step is
        ns = _python_namespace(_py(step), _py(reset), _py(damp), cap)
        super().__init__(model, ns["contact_reset"], ns["contact_force"])  # keeps the model

    def __deepcopy__(self, memo: dict) -> SlotReference:
        """An independent copy: its composed functions call its own readable reference.

        The composition's ``step`` and ``reset`` close over the readable object, and a function
        is copied by reference, so a plain deep copy would leave the copy driving the original's
        readable: a twin trajectory (a Lyapunov estimate, a checkpoint) and its base then shared
        one memory diagram. The copy is composed anew and given copies of the state.
        """
        new = type(self)(self._model)
        memo[id(self)] = new
        if self.readable is not None:
            new.readable.__dict__.update(copy.deepcopy(self.readable.__dict__, memo))
        new.fs[:] = self.fs
        new.is_[:] = self.is_
        new.pp = self.pp.copy()
        return new

    def state(self) -> dict[str, Any]:
        """A snapshot of the committed history: the state arrays and the readable's state.

        The readable reference's attributes are its state (as for :meth:`__deepcopy__`); the
        composed functions are not part of it, so the snapshot pickles.
        """
        out = super().state()
        if self.readable is not None:
            out["readable"] = copy.deepcopy(self.readable.__dict__)
        return out

    def set_state(self, state: dict[str, Any]) -> None:
        """Put back a snapshot of :meth:`state` in place (the composed functions call this
        reference's readable object, which therefore stays the same object)."""
        super().set_state(state)
        if self.readable is not None:
            self.readable.__dict__.update(copy.deepcopy(state["readable"]))
