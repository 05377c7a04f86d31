"""Shared fixtures."""

from __future__ import annotations

import os
import shutil
import subprocess

import pytest

#: Debian's headless browser and its WebDriver (packages chromium, chromium-driver)
CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"


@pytest.fixture(scope="session")
def chromium() -> tuple[str, str]:
    """Paths of Chromium and chromedriver, installed with apt-get (as root) when missing.

    Skips, saying why, only where they are absent and cannot be installed here.
    """
    try:
        import selenium  # noqa: F401
    except ImportError:
        pytest.skip("selenium is not installed (pip install 'sawdrift[test]')")
    if not (os.path.exists(CHROMIUM) and os.path.exists(CHROMEDRIVER)):
        if shutil.which("apt-get") is None or os.geteuid() != 0:
            pytest.skip("headless Chromium is missing and cannot be installed here (needs root and "
                        "apt-get: apt-get install chromium chromium-driver)")
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        for cmd in (["apt-get", "update"], ["apt-get", "install", "-y", "chromium", "chromium-driver"]):
            done = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=1800)
            if done.returncode != 0:
                last = (done.stderr.strip().splitlines() or ["no output"])[-1]
                pytest.skip(f"installing Chromium failed at {' '.join(cmd)!r}: {last}")
        if not (os.path.exists(CHROMIUM) and os.path.exists(CHROMEDRIVER)):
            pytest.skip(f"apt-get ran but {CHROMIUM} or {CHROMEDRIVER} is still missing")
    return CHROMIUM, CHROMEDRIVER
