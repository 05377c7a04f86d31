"""Tools for model authors: the conformance suite every contact model is held to.

``sawdrift.testing.check_model("mymodel", param=value)`` runs the same checks as
``sawdrift check-model`` (see :mod:`sawdrift.contact.conformance`) and returns a
:class:`~sawdrift.contact.conformance.Conformance` whose ``passed`` is False if a check fails.
"""

from .contact.conformance import Check, Conformance, check_model

__all__ = ["Check", "Conformance", "check_model"]
