"""Run the ``sawdrift`` entry point in the test process (shared by the CLI output tests)."""

from __future__ import annotations

import sys

import pytest

from sawdrift.cli import main


def call(monkeypatch, capsys, *args: str) -> tuple[int, str, str]:
    """Run ``sawdrift ARGS`` in this process: (exit status, stdout, stderr)."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", *args])
    with pytest.raises(SystemExit) as exc:
        main()
    out = capsys.readouterr()
    return int(exc.value.code or 0), out.out, out.err
