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


def test_validation_docs_name_every_group_of_the_report():
    """docs/validation.md's table has a row per report group; README's list covers adhesion."""
    from sawdrift.validation import GROUPS

    text = (ROOT / "docs" / "validation.md").read_text()
    for heading in GROUPS.values():
        number = heading.split(".", 1)[0]
        assert f"\n| {number}. " in text, heading
    assert "a figure per case" not in text
    assert "bisection to 1e-6" not in text
    readme = (ROOT / "README.md").read_text()
    cover = readme[readme.index("The cases cover:"):readme.index("Where a model is not exact")]
    assert "adhesion" in cover and "two-wave" in cover
