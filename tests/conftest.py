"""Shared fixtures, and the session summary's line about browser tests that could not run."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

#: Debian's headless browser and its WebDriver (packages chromium, chromium-driver)
CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
#: how the skip reasons of :func:`chromium` begin (the summary line finds them by these)
NO_SELENIUM, NO_CHROMIUM = "selenium is not installed", "headless Chromium is missing"


@pytest.fixture(scope="session")
def chromium() -> tuple[str, str]:
    """Paths of Chromium and chromedriver; skips, saying why, where they are missing.

    The tests never install system packages: ``.ci/run`` installs them (as root, with apt-get)
    before it runs the test command.
    """
    try:
        import selenium  # noqa: F401
    except ImportError:
        pytest.skip(f"{NO_SELENIUM} (pip install 'sawdrift[test]')")
    missing = [path for path in (CHROMIUM, CHROMEDRIVER) if not os.path.exists(path)]
    if missing:
        pytest.skip(f"{NO_CHROMIUM} ({', '.join(missing)}): .ci/run installs it "
                    "(apt-get install chromium chromium-driver)")
    return CHROMIUM, CHROMEDRIVER


@pytest.fixture
def sawdrift_main(monkeypatch, capsys):
    """``sawdrift ARGS`` run in this process: the console entry point
    (:func:`sawdrift.cli.main`) with ``sys.argv`` set, as tests/test_cli_errors.py runs it.

    Returns a function of the arguments giving a ``CompletedProcess`` (returncode, stdout,
    stderr), like ``subprocess.run(..., capture_output=True, text=True)``. For the paths that
    end in an error before any run: they then cost milliseconds instead of a new process's
    1-2 s of start-up (imports, the unit registry, numba's cache). An exception that escapes
    ``main`` (which a process would print as a traceback) fails the test.
    """
    from sawdrift.cli import main

    def call(*args: str) -> subprocess.CompletedProcess:
        monkeypatch.setattr(sys, "argv", ["sawdrift", *map(str, args)])
        capsys.readouterr()
        with pytest.raises(SystemExit) as exc:
            main()
        out = capsys.readouterr()
        code = exc.value.code
        return subprocess.CompletedProcess(["sawdrift", *args], 0 if code is None else code,
                                           out.out, out.err)

    return call


def _skip_reason(report: pytest.TestReport) -> str:
    """The reason of a skipped test's report ('' if it has none)."""
    longrepr = report.longrepr
    if isinstance(longrepr, tuple) and len(longrepr) == 3:
        return str(longrepr[2]).removeprefix("Skipped: ")
    return ""


def pytest_terminal_summary(terminalreporter, exitstatus, config) -> None:  # noqa: ARG001
    """One line naming the tests skipped for want of a browser, and why (pytest's own summary
    shows only a count of skips unless asked with -rs)."""
    skipped = [(r.nodeid, _skip_reason(r)) for r in terminalreporter.stats.get("skipped", [])
               if hasattr(r, "nodeid")]
    browser = [(node, why) for node, why in skipped if why.startswith((NO_SELENIUM, NO_CHROMIUM))]
    if not browser:
        return
    names = ", ".join(sorted(node.split("::", 1)[-1] for node, _ in browser))
    reasons = "; ".join(sorted({why for _, why in browser}))
    terminalreporter.write_line(f"{len(browser)} browser tests skipped ({names}): {reasons}",
                                yellow=True)
