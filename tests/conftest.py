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


@pytest.fixture(scope="session", autouse=True)
def _click_commands_built_once():
    """Each Typer app's click command tree built once per test process, as in one ``sawdrift``
    process, instead of on every call of the app.

    typer rebuilds the tree (every command's options, from the function signatures) each time
    the app is called: about 65 ms of the 80 ms an in-process ``sawdrift run --m-star -1`` takes,
    paid by every test that runs the command line in this process. The tree is built again when
    the app's commands, groups or callback change. click runs a command tree any number of times
    (each call makes its own context).
    """
    import weakref

    import typer.main

    original = typer.main.get_command
    built: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()

    def shape(app) -> tuple:
        return (id(app.registered_callback), tuple(id(c.callback) for c in app.registered_commands),
                tuple((g.name, shape(g.typer_instance)) for g in app.registered_groups
                      if g.typer_instance is not None))

    def get_command(app):
        key = shape(app)
        hit = built.get(app)
        if hit is None or hit[0] != key:
            hit = built[app] = (key, original(app))
        return hit[1]

    typer.main.get_command = get_command
    yield
    typer.main.get_command = original


@pytest.fixture(autouse=True)
def _figures_closed_after_each_test():
    """Close the figures a test left open (many keep theirs to read them): a worker process
    otherwise gathers them from test to test, past matplotlib's warning at 20."""
    yield
    plt = sys.modules.get("matplotlib.pyplot")  # never imported just to close nothing
    if plt is not None:
        plt.close("all")


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


#: the test files that take longest, longest first (CPU seconds per file in the quick loop, measured
#: on a loaded 2-core machine: from 21 s for test_conformance.py down to 2.4 s), handed to the
#: pytest-xdist workers first. pytest-xdist would order files by their number of tests, which
#: leaves files of few but long tests (test_cold_start.py: 2 tests, 7 s) to the end, where one
#: worker runs them while the other waits; longest first, both end on short files together.
LONGEST_FIRST = (
    "tests/test_conformance.py", "tests/test_figures.py", "tests/test_cli_output.py",
    "tests/test_lammps.py", "tests/test_loads.py", "tests/test_explore.py",
    "tests/hard/test_hard_cases.py", "tests/test_steady.py", "tests/test_sweep.py",
    "tests/test_cold_start.py", "tests/test_cli_errors.py", "tests/test_progress.py",
    "tests/test_bench.py", "tests/test_cli.py", "tests/test_mixture_plane.py",
    "tests/test_plugin_example.py", "tests/test_adhesion_threshold.py", "tests/test_plugin_broken.py",
    "tests/test_provenance.py", "tests/test_batch_means.py",
)


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(session, config, items) -> None:  # noqa: ARG001
    """Files in the order :data:`LONGEST_FIRST`, then the others by their number of selected
    tests, most first (pytest-xdist's own order, turned off in pyproject's addopts by
    ``--no-loadscope-reorder``); the tests of a file keep their order. Runs after the ``-m``
    selection (trylast), so that the counts are of the tests that will run."""
    rank = {name: k for k, name in enumerate(LONGEST_FIRST)}
    files: dict[str, list[pytest.Item]] = {}
    for item in items:
        files.setdefault(item.nodeid.split("::", 1)[0], []).append(item)
    order = sorted(files, key=lambda name: (rank.get(name, len(rank)), -len(files[name])))
    items[:] = [item for name in order for item in files[name]]


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
