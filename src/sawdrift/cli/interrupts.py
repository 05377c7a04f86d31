"""Ctrl-C on the command line: what a stopped command kept, said in one line, exit status 130.

A command that keeps what ended (run's models, a field's positions, an ensemble's placements, a
sweep's journal) says so with :func:`interrupted`; any other gets one line from
:func:`_say_interrupted` instead of typer's silent 130. After the first Ctrl-C a second is
ignored until the command has ended (:func:`_ignore_further_interrupts`, put back by
:func:`_restore_interrupts`), and a process pool shutting down around its killed workers prints
no traceback (:func:`_quiet_pool_shutdown`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import typer

from .json_out import json_nulls

__all__ = ["interrupted", "interrupted_curve", "interrupted_placements"]


#: whether a command already said what its Ctrl-C kept (:func:`interrupted`)
_INTERRUPT_SAID: list[bool] = [False]


def interrupted(message: str) -> None:
    """End a command stopped by Ctrl-C with ``message`` (what it kept, how to resume) on stderr
    and exit status 130."""
    _ignore_further_interrupts()
    _quiet_pool_shutdown()
    typer.echo(message, err=True)
    _INTERRUPT_SAID[0] = True
    raise typer.Exit(130)


def _quiet_pool_shutdown() -> None:
    """After a Ctrl-C, drop what a process pool's manager thread raises while the interpreter
    shuts down around its killed workers (an ``OSError: [Errno 9] Bad file descriptor`` from
    ``concurrent.futures.process``, printed as "Exception ignored in: <module 'threading'>" with
    its traceback after the "interrupted" line, 3 times in 20 resumed sweeps); anything else
    goes to the hook as before."""
    import sys

    if getattr(sys.unraisablehook, "sawdrift_quiet_pool", False):
        return  # installed by an earlier interrupt in this process
    previous = sys.unraisablehook

    def hook(unraisable: Any) -> None:
        exc = unraisable.exc_value
        tb = unraisable.exc_traceback
        frames = []
        while tb is not None:
            frames.append(tb.tb_frame.f_code.co_filename)
            tb = tb.tb_next
        if isinstance(exc, OSError) and any("concurrent" in f for f in frames):
            return
        previous(unraisable)

    hook.sawdrift_quiet_pool = True  # type: ignore[attr-defined]
    sys.unraisablehook = hook


def _ignore_further_interrupts() -> None:
    """Ignore Ctrl-C until the command has ended (:func:`_main` puts the handler back: a
    process that called the command line in-process, a test, kept ignoring it, and so did every
    process it started after)."""
    import signal

    try:
        previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    except ValueError:  # not the main thread: nothing to change there
        return
    if _SIGINT_BEFORE[0] is None:
        _SIGINT_BEFORE[0] = previous


#: the SIGINT handler :func:`_ignore_further_interrupts` replaced, put back when the command ends
_SIGINT_BEFORE: list[Any] = [None]


def _restore_interrupts() -> None:
    import signal

    if _SIGINT_BEFORE[0] is not None:
        signal.signal(signal.SIGINT, _SIGINT_BEFORE[0])
        _SIGINT_BEFORE[0] = None


def interrupted_placements(done: int, total: int, written: Path | None) -> None:
    """End an ensemble (sort, lammps --seeds) that Ctrl-C stopped after ``done`` of ``total``
    placements, whose numbers, printed and ``written`` (a file or folder, or None), are of the
    placements that ended (:func:`interrupted`)."""
    kept = f"; written to {written}" if written is not None else ""
    interrupted(f"interrupted (Ctrl-C) after {done} of {total} placements: the numbers are of "
                f"those{kept}")


def interrupted_curve(stop: Any, out: Path | None, command: str,
                      done: dict[str, Any] | None = None) -> None:
    """End a load or force-velocity curve that Ctrl-C stopped (``stop``: a
    :class:`~sawdrift.study.load_curve.CurveInterrupted`): the loaded runs that ended,
    printed on stderr (stdout stays the results': --json prints one object or nothing) and
    written as JSON (``partial_runs.json`` in an output folder, ``NAME.partial.json`` beside
    an output file), with ``done`` (the curves of an --axis that ended, written beside
    them), then :func:`interrupted`. Whole minutes of heavy runs were lost: "the command
    stopped before writing its results", an empty folder."""
    import json

    rows = []
    for load in sorted(stop.table):
        row = {"load": load, **stop.table[load]}
        if stop.newtons > 0.0:
            row["load_N"] = load * stop.newtons
        rows.append(row)
        typer.echo(f"L = {load:+.6g} M g: drift velocity {row.get('drift_velocity')} a0 f, "
                   f"{row.get('regime')}, settled {row.get('settled')}", err=True)
    written = ""
    curves = len(done["species"]) if done else 0
    if out is not None and (rows or curves):
        path = (out / "partial_runs.json" if out.suffix == "" or out.is_dir()
                else out.with_suffix(".partial.json"))
        path.parent.mkdir(parents=True, exist_ok=True)
        kept = {"command": command, "complete": False, "runs": rows, **(done or {})}
        path.write_text(json.dumps(json_nulls(kept), indent=1) + "\n")
        written = f", written to {path}"
    ended = f"{curves} curves and " if done else ""
    interrupted(f"interrupted (Ctrl-C): {command} stopped with {ended}{len(rows)} loaded runs "
                f"ended, printed above{written}; the curve needs the rest: run the command again")

def _say_interrupted(code: object) -> None:
    """Ctrl-C, which typer turns into exit status 130 with no word: one line, unless the command
    said what it kept (:func:`interrupted`). run, field, threshold, load-curve and bifurcation
    exited in silence."""
    if code == 130 and not _INTERRUPT_SAID[0]:
        typer.echo("interrupted (Ctrl-C): the command stopped before writing its results",
                   err=True)
