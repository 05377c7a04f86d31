"""pluggy hook specifications: the one registration hook every model plugin implements.

A plugin is a module (or object) named in the ``sawdrift.models`` entry-point group::

    [project.entry-points."sawdrift.models"]
    my_model = "my_package.my_module"

whose ``sawdrift_contact_models`` hook returns the :class:`~sawdrift.contact.ContactModel`
subclasses it provides. Built-in models go through exactly the same path.
"""

from __future__ import annotations

import pluggy

PROJECT = "sawdrift"

hookspec = pluggy.HookspecMarker(PROJECT)
hookimpl = pluggy.HookimplMarker(PROJECT)


@hookspec
def sawdrift_contact_models() -> list[type]:
    """Return the ContactModel subclasses this plugin provides."""
