"""``python -m sawdrift`` runs the CLI.

The top-level ``--help`` is printed from its stored copy when there is one, before the command
line (Typer, Rich and every command) is imported (:func:`sawdrift._startup.replay_help`).
"""

import sys

from ._startup import replay_help

if sys.argv[1:] == ["--help"]:
    replay_help()  # exits when printed; otherwise main() below prints the help and stores it

from .cli import main  # noqa: E402

main()
