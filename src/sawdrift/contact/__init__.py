"""The contact layer: the model interface, committed histories and the plugin registry."""

from .base import (
    Capabilities,
    ContactHistory,
    ContactModel,
    Kernel,
    KernelPair,
    NoParams,
    ReferenceContact,
)

__all__ = [
    "Capabilities", "ContactHistory", "ContactModel", "Kernel", "KernelPair", "NoParams",
    "ReferenceContact",
]
