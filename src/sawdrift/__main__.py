"""``python -m sawdrift`` runs the CLI."""

from .cli import main

main()
