"""Run the ``sawdrift`` entry point in the test process (shared by the CLI output tests).

A new ``sawdrift`` process costs 1-2 s before it computes anything (imports, the unit registry,
loading numba's cached kernels); in the test process these are paid once per worker. The few
tests whose point is the process itself (the entry point and its plugin discovery, its exit
status, its start-up time) start one: tests/test_cold_start.py, tests/test_plugin_broken.py,
tests/test_cli.py::test_models_json_lists_material_point_with_distribution,
tests/test_conformance.py::test_cli_exit_status_is_1_for_a_failing_plugin_model.
"""

from __future__ import annotations

import io
import subprocess
import sys
from contextlib import redirect_stderr, redirect_stdout

import pytest

from sawdrift.cli import main


def call(monkeypatch, capsys, *args: str) -> tuple[int, str, str]:
    """Run ``sawdrift ARGS`` in this process: (exit status, stdout, stderr)."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", *args])
    with pytest.raises(SystemExit) as exc:
        main()
    out = capsys.readouterr()
    return int(exc.value.code or 0), out.out, out.err


def run_main(*args: object, check: bool = False) -> subprocess.CompletedProcess:
    """``sawdrift ARGS`` in this process, as ``subprocess.run([... "sawdrift", *ARGS],
    capture_output=True, text=True, check=check)`` would give it (stdout and stderr are not
    terminals, as in a captured process). An exception that escapes ``main`` (which a process
    would print as a traceback) fails the test.
    """
    argv = ["sawdrift", *map(str, args)]
    out, err = io.StringIO(), io.StringIO()
    saved = sys.argv
    sys.argv = argv
    try:
        with redirect_stdout(out), redirect_stderr(err):
            try:
                main()
                code = 0
            except SystemExit as exc:
                code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    finally:
        sys.argv = saved
    if check and code != 0:
        raise subprocess.CalledProcessError(code, argv, out.getvalue(), err.getvalue())
    return subprocess.CompletedProcess(argv, code, out.getvalue(), err.getvalue())


def kept_after_ctrl_c(monkeypatch, capsys, args: list[str], written, done: int,
                      total: int) -> None:
    """Run ``sawdrift ARGS`` in which a Ctrl-C comes after ``done`` placements of ``total``:
    exit 130, the JSON ``written`` (a path) holds those placements marked interrupted, and
    stderr says how many of how many ended."""
    import json

    code, _, err = call(monkeypatch, capsys, *args)
    assert code == 130
    data = json.loads(written.read_text())
    assert data["interrupted"] is True and data["seeds"] == list(range(done))
    assert f"after {done} of {total} placements" in err
