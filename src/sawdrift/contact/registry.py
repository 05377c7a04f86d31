"""Model registry: plugins discovered lazily from the ``sawdrift.models`` entry points.

Pattern of tox 4 (one registration hook; built-ins load like third-party plugins) and xarray's
backend plugins (lazy discovery, a plugin that fails to import becomes a warning naming it).
"""

from __future__ import annotations

import importlib.metadata as im
import re
import warnings
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import pluggy

from .. import hookspecs
from ..errors import ModelNotFoundError, PluginError, SawdriftError, first_line
from .base import KERNEL_INTERFACE, ContactModel
from .slots import TangentialLaw

ENTRY_POINT_GROUP = "sawdrift.models"



#: the distribution of sawdrift's own models, which keep their names in a conflict
BUILTIN_DISTRIBUTION = "sawdrift"

class PluginWarning(UserWarning):
    """A plugin could not be loaded; the other models keep working."""


@dataclass(frozen=True)
class ModelEntry:
    """A registered model and where it came from."""

    cls: type[ContactModel]
    distribution: str
    entry_point: str


def _named_models(returned: Any) -> tuple[list[type[ContactModel]], str]:
    """Split what a plugin's hook returned into named ContactModel subclasses and the rest.

    Parameters
    ----------
    returned
        The value of ``sawdrift_contact_models()``: it should be an iterable of classes.

    Returns
    -------
    tuple
        The usable classes, and a short description of the unusable entries ('' if none).
    """
    if isinstance(returned, str | bytes) or not isinstance(returned, Iterable):
        return [], _short(returned)
    good: list[type[ContactModel]] = []
    bad: list[str] = []
    for cls in returned:
        if (isinstance(cls, type) and issubclass(cls, ContactModel)
                and isinstance(getattr(cls, "name", None), str) and cls.name):
            good.append(cls)
        else:
            bad.append(_short(cls))
    return good, ", ".join(bad)


#: what a model's name may hold: it is chosen on the command line, where "a,b" names two models
NAME = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.\-]*")


def model_fault(cls: type[ContactModel]) -> str:
    """What makes a model class unusable, found when it is registered ('' if nothing): a name
    the command line cannot choose, no profiles declared (check-model then passed it with no
    check run, and every run refused its sphere), or a tangential law without its step (listed
    as available, an internal failure when run)."""
    if not NAME.fullmatch(cls.name):
        return (f"model name {cls.name!r} is not usable: letters, digits, '_', '.' and '-' only "
                "(a model is chosen as --model NAME, and a comma separates models)")
    if not tuple(getattr(cls.capabilities, "profiles", ())):
        return f"model {cls.name!r} declares no profiles (Capabilities(profiles=...))"
    if issubclass(cls, TangentialLaw) and getattr(cls, "step", None) is None:
        return f"model {cls.name!r} is a TangentialLaw without a step function"
    return ""


def _short(obj: Any) -> str:
    """``repr(obj)`` on one line, cut to 60 characters."""
    text = " ".join(repr(obj).split())
    return text if len(text) <= 60 else text[:57] + "..."


class Registry:
    """Contact models by name. Discovery runs once, on first use.

    ``entry_points`` (default: the installed ones of :data:`ENTRY_POINT_GROUP`, read by
    :func:`importlib.metadata.entry_points`) gives the entry points to load, objects with
    ``name``, ``value``, ``dist.name`` and ``load()``; the command line passes a stored copy of
    the installed ones (:func:`sawdrift._startup.skip_plugin_scans`), sparing a scan of every
    distribution.
    """

    def __init__(self, entry_points: Callable[[], Iterable[Any]] | None = None) -> None:
        self._models: dict[str, ModelEntry] | None = None
        self.failed: dict[str, str] = {}
        self.entry_points = entry_points

    def _discover(self) -> dict[str, ModelEntry]:
        pm = pluggy.PluginManager(hookspecs.PROJECT)
        pm.add_hookspecs(hookspecs)
        models: dict[str, ModelEntry] = {}
        clashes: dict[str, list[ModelEntry]] = {}
        found = self.entry_points() if self.entry_points else im.entry_points(group=ENTRY_POINT_GROUP)
        for ep in sorted(found, key=lambda e: e.name):
            dist = ep.dist.name if ep.dist is not None else "<unknown>"
            try:
                plugin = ep.load()
                pm.register(plugin, name=f"{dist}:{ep.name}")
                classes = plugin.sawdrift_contact_models()
            except Exception as exc:  # noqa: BLE001 - a broken plugin must not break the others
                msg = f"{type(exc).__name__}: {exc}".splitlines()[0]
                self.failed[ep.name] = msg
                warnings.warn(
                    f"sawdrift plugin {ep.name!r} from distribution {dist!r} failed to load "
                    f"and is skipped ({msg})",
                    PluginWarning,
                    stacklevel=3,
                )
                continue
            classes, bad = _named_models(classes)
            if bad:
                # a plugin handing back something else loses those entries, never the other models
                msg = (f"plugin {ep.name!r} from distribution {dist!r} returned {bad} from "
                       "sawdrift_contact_models(), not named ContactModel subclasses")
                self.failed[ep.name] = msg
                skipped = "those entries are skipped" if classes else "it is skipped"
                warnings.warn(f"sawdrift {msg}; {skipped}", PluginWarning, stacklevel=3)
            for cls in classes:
                name = cls.name
                fault = model_fault(cls)
                if fault:
                    self.failed[name] = fault
                    warnings.warn(f"sawdrift plugin {ep.name!r} from distribution {dist!r}: "
                                  f"{fault}; it is skipped", PluginWarning, stacklevel=3)
                    continue
                version = getattr(cls, "kernel_interface", None)
                if version != KERNEL_INTERFACE:
                    msg = (f"model {name!r} is written for kernel interface {version!r}; this "
                           f"sawdrift has {KERNEL_INTERFACE}")
                    self.failed[name] = msg
                    warnings.warn(f"sawdrift plugin {ep.name!r} from distribution {dist!r}: {msg}; "
                                  "it is skipped", PluginWarning, stacklevel=3)
                    continue
                entry = ModelEntry(cls, dist, ep.name)
                if name in clashes:
                    clashes[name].append(entry)
                elif name in models and models[name].cls is not cls:
                    clashes[name] = [models.pop(name), entry]
                else:
                    models[name] = entry
        for name, entries in clashes.items():
            # a duplicate disables only the name it duplicates: every other model keeps working;
            # sawdrift's own model keeps its name (a plugin called 'mmd' broke the default scene,
            # the demo and the validation report)
            who = " and ".join(f"{e.distribution!r} (entry point {e.entry_point!r})" for e in entries)
            own = [e for e in entries if e.distribution == BUILTIN_DISTRIBUTION]
            if len(own) == 1:
                models[name] = own[0]
                others = " and ".join(f"{e.distribution!r} (entry point {e.entry_point!r})"
                                      for e in entries if e is not own[0])
                warnings.warn(f"sawdrift plugin conflict: model name {name!r} is sawdrift's own; "
                              f"the one from {others} is skipped", PluginWarning, stacklevel=3)
                continue
            msg = f"model name {name!r} is claimed by {who}; neither is loaded"
            self.failed[name] = msg
            warnings.warn(f"sawdrift plugin conflict: {msg}", PluginWarning, stacklevel=3)
        return models

    @property
    def models(self) -> dict[str, ModelEntry]:
        if self._models is None:
            self._models = self._discover()
        return self._models

    def names(self) -> list[str]:
        """Sorted names of all loaded models."""
        return sorted(self.models)

    def get(self, name: str) -> type[ContactModel]:
        """The model class called ``name``; a one-line error lists the known names otherwise."""
        try:
            return self.models[name].cls
        except KeyError:
            if name in self.failed:
                raise ModelNotFoundError(f"model = {name!r} is unavailable: {self.failed[name]}") from None
            known = ", ".join(self.names()) or "none"
            raise ModelNotFoundError(
                f"model = {name!r} is not a registered contact model; known models: {known}"
            ) from None

    def register(self, cls: type[ContactModel], distribution: str = "<runtime>") -> None:
        """Register a model class at run time (tests, notebooks)."""
        fault = model_fault(cls)
        if fault:
            raise PluginError(fault)
        if cls.name in self.models and self.models[cls.name].cls is not cls:
            raise PluginError(f"model name {cls.name!r} is already registered")
        self.models[cls.name] = ModelEntry(cls, distribution, cls.name)

    def unregister(self, name: str) -> None:
        """Remove a model registered at run time."""
        self.models.pop(name, None)

    def reload(self) -> None:
        """Forget cached discovery (after installing a plugin in the same process): the next use
        scans the installed entry points again."""
        self._models = None
        self.failed = {}
        self.entry_points = None


registry = Registry()


def get_model(name: str) -> type[ContactModel]:
    """The registered contact model class called ``name``."""
    return registry.get(name)


@contextmanager
def plugin_failures(name: str) -> Iterator[None]:
    """Turn an exception out of a plugin model's code into a one-line :class:`PluginError`
    naming the model and its distribution (the command line's exit status 2): a kernel that
    raises, one numba cannot compile (a wrong signature, a tuple where T* is due) were an
    "internal failure, please report it", which blamed sawdrift. sawdrift's own models, and
    errors sawdrift raises itself, pass through as they are."""
    try:
        yield
    except SawdriftError:
        raise
    except Exception as exc:
        entry = registry.models.get(name)
        if entry is None or entry.distribution == BUILTIN_DISTRIBUTION:
            raise
        raise PluginError(f"model {name!r} from {entry.distribution!r} failed: "
                          f"{first_line(exc)}; `sawdrift check-model {name}` tests it") from None
