"""The contact layer: the model interface, committed histories, the plugin registry, and the
binding of a Scene to its model (:mod:`sawdrift.contact.binding`)."""

from .base import (
    Capabilities,
    ContactModel,
    Kernel,
    KernelPair,
    NoParams,
    ReferenceContact,
)
from .binding import bind, check_model_params, describe_body, model_for
from .history import ContactHistory

__all__ = [
    "Capabilities", "ContactHistory", "ContactModel", "Kernel", "KernelPair", "NoParams",
    "ReferenceContact", "bind", "check_model_params", "describe_body", "model_for",
]
