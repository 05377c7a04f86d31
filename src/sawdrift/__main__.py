"""``python -m sawdrift`` runs the CLI.

The top-level ``--help`` is printed from its stored copy when there is one, before the command
line (Typer, Rich and every command) is imported (:func:`sawdrift._startup.replay_help`), and
the process ends without the interpreter's teardown (:func:`sawdrift._startup.skip_teardown`).
:func:`console` is the same for an entry point.
"""

import sys

from ._startup import replay_help, skip_teardown

if __name__ == "__main__" and sys.argv[1:] == ["--help"]:
    replay_help()  # exits when printed; otherwise main() below prints the help and stores it

from .cli import main  # noqa: E402


def console() -> None:
    """The command line as its process's entry point: :func:`sawdrift.cli.main`, then the end
    of the process without the interpreter's teardown."""
    try:
        main()
    except SystemExit as done:
        skip_teardown(done.code)
        raise


if __name__ == "__main__":
    console()
