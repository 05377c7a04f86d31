"""Whether a folder can take the files a command or a study is about to write (light: the
command line imports it before any work)."""

from __future__ import annotations

import os
from pathlib import Path


def write_problem(folder: Path) -> str | None:
    """Why ``folder`` cannot take a file, or None: the folder is made if missing and a file is
    written in it and removed, so that a run or a sweep does not compute for minutes and then
    lose its results to a bad path."""
    import tempfile  # only where something is about to be written: not on every start-up

    try:
        folder.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".sawdrift-probe-")
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        return str(exc.strerror or exc)
    return None
