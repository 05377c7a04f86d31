"""Shared fixtures."""

from __future__ import annotations

import os

import pytest

#: Debian's headless browser and its WebDriver (packages chromium, chromium-driver)
CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"


@pytest.fixture(scope="session")
def chromium() -> tuple[str, str]:
    """Paths of Chromium and chromedriver; skips, saying why, where they are missing.

    The tests never install system packages: ``.ci/run`` installs them (as root, with apt-get)
    before it runs the test command.
    """
    try:
        import selenium  # noqa: F401
    except ImportError:
        pytest.skip("selenium is not installed (pip install 'sawdrift[test]')")
    missing = [path for path in (CHROMIUM, CHROMEDRIVER) if not os.path.exists(path)]
    if missing:
        pytest.skip(f"headless Chromium is missing ({', '.join(missing)}): .ci/run installs it "
                    "(apt-get install chromium chromium-driver)")
    return CHROMIUM, CHROMEDRIVER
