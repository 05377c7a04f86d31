"""The docs say what the code does: the CLI reference is current, nothing points outside."""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_cli_reference_is_generated_from_the_program(tmp_path):
    # the command below (typer's own CLI, python -m typer), run in this process: it imports
    # sawdrift.cli afresh from its source either way
    from typer.cli import app
    from typer.testing import CliRunner

    out = tmp_path / "cli.md"
    res = CliRunner().invoke(app, ["sawdrift.cli", "utils", "docs", "--name", "sawdrift",
                                   "--output", str(out)], prog_name="typer")
    assert res.exit_code == 0, res.output
    assert out.read_text() == (ROOT / "docs" / "cli.md").read_text(), (
        "docs/cli.md is stale: regenerate it with "
        "python -m typer sawdrift.cli utils docs --name sawdrift --output docs/cli.md")


def test_no_user_facing_file_points_outside_the_repository():
    files = [ROOT / "README.md", *(ROOT / "docs").rglob("*.md"), *(ROOT / "src").rglob("*.py"),
             *(ROOT / "plugins").rglob("*.py"), *(ROOT / "validation").glob("*.py"),
             *(ROOT / "benchmarks").glob("*")]
    offenders = [str(f.relative_to(ROOT)) for f in files
                 if f.is_file() and "../shared" in f.read_text(errors="ignore")]
    assert not offenders, offenders
