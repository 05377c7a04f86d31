"""Writers of the validation report: figures, results.json and the HTML page."""

from __future__ import annotations

import base64
import html
import io
import json
from pathlib import Path
from typing import Any

from ..report.texts import asset
from .api import GROUPS, MU, NU, CaseResult, ValidationReport, _environment, _fmt, _one_line

# -- report writers ----------------------------------------------------------------------------


def _write_figures(report: ValidationReport) -> None:
    fig_dir = report.out / "figures"
    for res in report.results:
        if res.figure is None:
            continue
        try:
            png = figure_png(res.figure)
        except Exception as exc:  # noqa: BLE001 - a broken figure must not lose the report
            res.message += f" (figure failed: {_one_line(exc)})"
            res.figure = None
            continue
        fig_dir.mkdir(exist_ok=True)
        slug = "".join(c if c.isalnum() or c in "-_" else "_" for c in res.name)
        (fig_dir / f"{slug}.png").write_bytes(png)
        res.figure = png
        res.figure_file = f"figures/{slug}.png"


def figure_png(figure: Any, dpi: int = 96) -> bytes:
    """PNG bytes of a matplotlib figure (closed afterwards) or of PNG bytes as given."""
    if isinstance(figure, bytes | bytearray):
        return bytes(figure)
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    figure.savefig(buf, format="png", dpi=dpi)
    plt.close(figure)
    return buf.getvalue()


def write_json(report: ValidationReport, path: Path) -> None:
    """Write ``results.json``: summary, environment and one record per result."""
    data = {
        "passed": report.passed,
        "summary": report.summary(),
        "counts": {
            "passed": report.count("pass"),
            "failed": report.count("fail") + report.count("error"),
            "errors": report.count("error"),
            "expected_deviations": report.count("expected deviation"),
            "skipped": report.count("skipped"),
            "total": len(report.results),
        },
        "skipped": [{"name": r.name, "reason": r.skip_reason} for r in report.skipped],
        "expected_deviations": [{"name": r.name, "reason": _deviation_reason(r)}
                                for r in report.results if r.status == "expected deviation"],
        "quick": report.quick,
        "seconds": round(report.seconds, 3),
        "environment": _environment(),
        "groups": GROUPS,
        "cases": [r.to_json() for r in report.results],
    }
    path.write_text(json.dumps(data, indent=2, allow_nan=False) + "\n")


_SYMBOL = {"<=": "&le;", ">=": "&ge;"}


def _deviation_reason(res: CaseResult) -> str:
    """The declared reason of an expected deviation, or a note that the case gives none."""
    return res.deviation_reason or "no reason declared by the case"


def _message_cell(res: CaseResult) -> str:
    """The message cell of a row: an expected deviation states its reason before the numbers."""
    text = html.escape(res.message)
    if res.status != "expected deviation":
        return text
    return (f"<b>Not exact by design:</b> {html.escape(_deviation_reason(res))}"
            + (f"<br>{text}" if text else ""))

#: the skipped label's style (the page's stylesheet has the other statuses)
_SKIP_CSS = ".st-skip{background:#bdbdbd;color:#222}.skips{font-size:13px;color:#444}"


def write_html(report: ValidationReport, path: Path) -> None:
    """Write the self-contained ``index.html`` (figures inline as base64 PNG)."""
    esc = html.escape
    env = _environment()
    parts = [
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
        "<title>sawdrift validation</title>",
        f"<style>{asset('validation.css')}{_SKIP_CSS}</style></head><body>",
        "<h1>sawdrift validation report</h1>",
        f"<div class='meta'>sawdrift {esc(env['sawdrift'])}, Python {esc(env['python'])}, "
        f"numpy {esc(env['numpy'])}, numba {esc(env['numba'])}; {esc(env['date'])}; "
        f"{'quick subset' if report.quick else 'full run'}; mu = {MU}, nu = {NU} unless stated. "
        "Oracles: docs/physics.md.</div>",
        f"<div class='summary {'ok' if report.passed else 'bad'}'><b>{esc(report.summary())}</b></div>",
    ]
    if report.skipped:
        parts.append("<div class='skips'>Skipped (neither passed nor failed): <ul>" + "".join(
            f"<li><b>{esc(r.name)}</b>: {esc(r.skip_reason or '')}</li>" for r in report.skipped)
            + "</ul></div>")
    groups = list(GROUPS) + sorted({r.group for r in report.results} - set(GROUPS))
    for group in groups:
        rows = [r for r in report.results if r.group == group]
        if not rows:
            continue
        parts.append(f"<h2>{esc(GROUPS.get(group, group))}</h2>")
        parts.append("<table><tr><th>case</th><th>fact checked</th><th>model</th><th>status</th>"
                     "<th>value</th><th>tolerance</th><th>message</th><th>s</th></tr>")
        for k, r in enumerate(rows):
            cls, label = {
                "pass": ("st-pass", "PASS"),
                "fail": ("st-fail", "FAIL"),
                "expected deviation": ("st-dev", "expected deviation"),
                "skipped": ("st-skip", "SKIPPED"),
                "error": ("st-error", "ERROR"),
            }[r.status or "error"]
            first = k == 0 or rows[k - 1].case != r.case
            span = sum(1 for x in rows if x.case == r.case)
            shared_cells = f"<td rowspan='{span}'><b>{esc(r.case)}</b></td>" if first else ""
            title_cell = f"<td class='title' rowspan='{span}'>{esc(r.title)}</td>" if first else ""
            parts.append(
                f"<tr>{shared_cells}{title_cell}<td>{esc(r.model or '')}</td>"
                f"<td><span class='st {cls}'>{label}</span></td>"
                f"<td class='num'>{esc(_fmt(r.value))}</td>"
                f"<td class='num'>{_SYMBOL[r.compare]} {esc(_fmt(r.tolerance))}</td>"
                f"<td>{_message_cell(r)}</td><td class='num'>{r.seconds:.2f}</td></tr>"
            )
        parts.append("</table>")
        figs = [r for r in rows if isinstance(r.figure, bytes)]
        if figs:
            parts.append("<div class='figs'>")
            for r in figs:
                b64 = base64.b64encode(r.figure).decode("ascii")
                parts.append(
                    f"<figure><img alt='{esc(r.name)}' src='data:image/png;base64,{b64}'>"
                    f"<figcaption><b>{esc(r.name)}</b>: {esc(r.status)}"
                    + (f" ({esc(_deviation_reason(r))})" if r.status == "expected deviation" else "")
                    + "</figcaption></figure>"
                )
            parts.append("</div>")
    parts.append("</body></html>")
    path.write_text("\n".join(parts))
