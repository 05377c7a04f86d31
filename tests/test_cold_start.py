"""Time to first answer: --help and models import neither numba, pandas nor matplotlib."""

from __future__ import annotations

import subprocess
import sys

import pytest

HEAVY = ("numba", "pandas", "matplotlib", "scipy")


@pytest.mark.parametrize("argv", [["--help"], ["models"], ["run", "--help"]])
def test_light_commands_do_not_import_heavy_libraries(argv):
    code = (
        "import sys\n"
        "from sawdrift.cli import main\n"
        f"sys.argv = ['sawdrift', *{argv!r}]\n"
        "try:\n    main()\nexcept SystemExit:\n    pass\n"
        f"print(sorted(m for m in {HEAVY!r} if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip().splitlines()[-1] == "[]", out.stdout[-400:]
