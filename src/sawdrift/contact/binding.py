"""A Scene bound to its contact model: the checks, the model instance and the body it names.

The scene layer (:mod:`sawdrift.scene`) describes the experiment and knows no contact model: a
``Scene`` holds ``model`` (a name) and ``model_params`` (a table) as given. This module, one
layer up, binds the two:

* :func:`bind` validates ``model_params`` against the model's own ``Params`` schema, checks
  what the model can do against the scene (its profiles; rigid or compliant against the drive
  and the effects) and returns the scene with the parameters' defaults filled in. Every path
  that runs a scene binds it first (:func:`sawdrift.run`, the sweeps and studies, the command
  line), so a wrong parameter is one line naming it before any work;
* :func:`model_for` gives the configured :class:`~sawdrift.contact.base.ContactModel`;
* :func:`describe_body` says what the particle is (``rigid point``, ``compliant sphere ...``);
* :func:`check_model_params` names a parameter the model does not take, with the nearest one.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from pydantic import BaseModel, ValidationError

from ..errors import SawdriftError, SceneError
from ..scene.bounds import NOT_A_NUMBER
from ..scene.messages import format_validation_error
from ..scene.overrides import nearest
from ..scene.parts import Impact, Prescribed
from ..scene.quoted import refuse_quoted_fields
from ..scene.schema import Scene
from .adhesion import adhesion_of, adhesive_model, supports_adhesion
from .base import ContactModel
from .registry import get_model

__all__ = ["bind", "check_model_params", "describe_body", "model_for"]


def _params(cls: type[ContactModel], scene: Scene, where: str) -> BaseModel:
    """The model's validated parameters, or one line naming the parameter and what it takes.

    A boolean given for a number is refused, as in the scene (:mod:`sawdrift.scene.bounds`):
    pydantic read ``--param restitution=true`` as e = 1."""
    known = ", ".join(cls.Params.model_fields) or "no parameters"
    for name, value in scene.model_params.items():
        field = cls.Params.model_fields.get(name)
        if isinstance(value, bool) and field is not None and field.annotation in (int, float):
            raise SceneError(f"{where}model_params.{name} = {value} {NOT_A_NUMBER} (model "
                             f"{scene.model!r} takes: {known})")
    try:
        return cls.Params.model_validate(scene.model_params)
    except ValidationError as exc:
        line = format_validation_error(exc)
        raise SceneError(f"{where}model_params.{line} (model {scene.model!r} takes: {known})") from None


def _capability_problem(cls: type[ContactModel], scene: Scene) -> str | None:
    """What ``scene`` asks of the model that it cannot do (one line), or None."""
    shape = scene.particle.profile.shape
    if shape not in cls.capabilities.profiles:
        return (f"model {scene.model!r} does not support profile {shape!r}; it supports "
                + ", ".join(cls.capabilities.profiles))
    rigid = cls.capabilities.rigid
    eff = scene.effects
    if isinstance(scene.drive, (Prescribed, Impact)) and rigid:
        return f"model {scene.model!r} is rigid: the {scene.drive.kind} drive needs a compliant model"
    if not eff.vertical_inertia and not rigid:
        return ("effects.vertical_inertia = false applies to a rigid point only; a compliant "
                f"model ({scene.model!r}) gets its normal force from the contact compression")
    if eff.normal_damping > 0.0 and rigid:
        return f"effects.normal_damping needs a compliant model; {scene.model!r} is rigid"
    if eff.adhesion != "none" and not supports_adhesion(cls):
        why = ("has a normal damping of its own, which the adhesive normal law would drop"
               if getattr(cls, "damping", None) is not None else "has none")
        return (f"effects.adhesion = {eff.adhesion!r} needs a compliant model with an adhesive "
                f"tangential law and no normal damping of its own (hertz_mindlin_dem, mmd); "
                f"{scene.model!r} {why}")
    if eff.rolling_resistance > 0.0 and (rigid or not eff.rotation):
        return ("effects.rolling_resistance needs effects.rotation = true and a compliant model"
                + (f"; {scene.model!r} is rigid" if rigid else ""))
    return None


def _checked(scene: Scene, source: str | None) -> tuple[type[ContactModel], BaseModel]:
    """The model class and its validated parameters, after every check of :func:`bind`."""
    cls = get_model(scene.model)
    where = f"{source}: " if source else ""
    # a number written as text ("64"), which pydantic's lax mode would read as 64
    refuse_quoted_fields(scene.model_params, cls.Params, source, "model_params.")
    params = _params(cls, scene, where)
    problem = _capability_problem(cls, scene)
    if problem is not None:
        raise SceneError(f"{where}scene: {problem}")
    return cls, params


def bind(scene: Scene, source: str | None = None) -> Scene:
    """Check ``scene`` against its contact model; the scene with the parameters' defaults filled.

    The checks the scene cannot make itself, since it knows no contact model: ``model_params``
    against the model's ``Params`` schema, the profile against the profiles the model supports,
    a rigid model against a prescribed or impact drive, ``effects.normal_damping`` and
    ``effects.rolling_resistance`` (compliant models only), ``effects.vertical_inertia = false``
    (rigid models only). Binding a bound scene returns it unchanged; the returned scene's
    ``model_params`` hold every parameter of the model (what ``Result.scene``, the sweep keys and
    the provenance record).

    Parameters
    ----------
    scene
        The scene, as validated by :class:`~sawdrift.scene.schema.Scene`.
    source
        Where the scene came from (a file name): the start of an error line.

    Returns
    -------
    Scene
        ``scene`` itself when its ``model_params`` are complete, else a copy holding them.

    Raises
    ------
    ModelNotFoundError
        No registered model has the scene's ``model`` name (one line listing the known ones).
    SceneError
        One line: ``model_params.NAME ...  (model 'mmd' takes: ...)`` for a parameter the model
        does not take or a value outside its range, ``scene: model ... `` for something the
        model cannot do.
    """
    if not isinstance(scene, Scene):
        raise SceneError(f"scene must be a sawdrift.Scene, not a {type(scene).__name__}: "
                         "Scene(**fields), Scene.model_validate(a dict) or Scene.from_toml(path)")
    _, params = _checked(scene, source)
    filled = params.model_dump()
    if filled == scene.model_params:
        return scene
    return scene.model_copy(update={"model_params": filled})


def model_for(scene: Scene) -> ContactModel:
    """The configured contact model of ``scene``: its class, parameters and profile.

    The scene is checked as by :func:`bind` (the same one-line errors).
    """
    cls, params = _checked(scene, None)
    adhesion = adhesion_of(scene)
    if adhesion is not None:
        return adhesive_model(cls)(params, scene.particle.profile, adhesion)
    return cls(params, scene.particle.profile)


def describe_body(scene: Scene) -> str:
    """What the particle is, in a few words: a rigid model with rotation is a rigid sphere.

    ``rigid point`` (a rigid model, not turning), ``rigid sphere, turning, kappa = ...``, or the
    compliant profile (``compliant sphere (N* = a*^p, p = 1.5), not turning``, ...).
    """
    kappa = scene.particle.gyration
    turning = f"turning, kappa = {kappa:g}" if scene.effects.rotation else "not turning"
    if get_model(scene.model).capabilities.rigid:
        return f"rigid sphere, {turning}" if scene.effects.rotation else "rigid point"
    profile = scene.particle.profile
    shape = "flat punch" if profile.shape == "flat" else profile.shape
    return f"compliant {shape} (N* = a*^p, p = {profile.p:g}), {turning}"


def check_model_params(model: str, params: Mapping[str, Any], source: str | None = None) -> None:
    """A one-line SceneError for a parameter ``model`` does not take, with the nearest name.

    Only the names are checked (the values are :func:`bind`'s); an unknown model is left to the
    registry's own error.
    """
    try:
        known = list(get_model(model).Params.model_fields)
    except (SawdriftError, ImportError, AttributeError):
        return
    where = f"{source}: " if source else ""
    for key in params:
        if key not in known:
            raise SceneError(f"{where}model_params.{key} is not a known parameter of model "
                             f"{model!r}{nearest(str(key), known, False)} (it takes: "
                             f"{', '.join(known) or 'none'})")
