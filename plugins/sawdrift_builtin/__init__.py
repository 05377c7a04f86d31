"""Built-in sawdrift contact models, registered through the sawdrift.models entry points."""
