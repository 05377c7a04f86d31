"""The reviewer's residue: bad input the command line accepted, and failures it exited 0 on."""

from __future__ import annotations

import re

import pytest

import sawdrift as sd

from .cli_call import call

# class names of Python exceptions must never reach the user
_EXC_NAME = re.compile(r"\b[A-Z][A-Za-z]*(Error|Exception)\b|Traceback")


def _one_line(code: int, err: str) -> str:
    """The one plain error line of a refused command (exit status 2)."""
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and lines[0].startswith("error: "), (code, err)
    assert not _EXC_NAME.search(lines[0]), lines[0]
    return lines[0]


@pytest.mark.parametrize(("args", "off"), [
    (["run", "--periods", "5", "--no-settle", "--max-periods", "100"], "--no-settle"),
    (["run", "--periods", "5", "--max-periods", "100", "--set", "numerics.settle=false"],
     "--set numerics.settle=false"),
    (["sweep", "--m-star", "0.1", "--amplitude", "0.3", "--periods", "5", "--no-settle",
      "--max-periods", "100", "-o", "{d}/t.parquet"], "--no-settle"),
])
def test_a_period_cap_given_to_a_fixed_run_is_refused(args, off, tmp_path, monkeypatch, capsys):
    """``run --no-settle --max-periods N`` ran its fixed periods and ignored the cap (it bounds
    the settling run only) without a word; the line names both options, and nothing is written."""
    code, _, err = call(monkeypatch, capsys, *(a.format(d=tmp_path) for a in args))
    line = _one_line(code, err)
    assert "--max-periods 100" in line and off in line, line
    assert not list(tmp_path.iterdir())


def test_a_period_cap_stays_accepted_where_it_is_read(tmp_path, monkeypatch, capsys):
    """The cap with a settling run is used; a scene (file or Python) with a cap and settle =
    false stays accepted (benchmarks/bench_audit.py builds such scenes), and so does a file's
    cap with --no-settle (examples/saw_linear_motor.toml has max_periods = 1e6)."""
    code, _, err = call(monkeypatch, capsys, "run", "--explain", "--settle", "--max-periods",
                        "100")
    assert code == 0, err
    fixed = sd.Scene(numerics={"settle": False, "periods": 200, "measure_periods": 100,
                               "max_periods": 200})
    assert fixed.numerics.max_periods == 200
    scene = tmp_path / "capped.toml"
    scene.write_text("[numerics]\nmax_periods = 1e6\n")
    code, _, err = call(monkeypatch, capsys, "run", str(scene), "--explain", "--no-settle")
    assert code == 0, err
