"""The command-line application: the Typer app, one-line errors, exit statuses, shared helpers.

Every user error (bad field, unknown model, malformed TOML or grid, broken plugin, an output path
that cannot be written) ends in one line on stderr and exit status 2, never a traceback. Exit
status 1 means a check failed (check-model, validate, bench speed); an internal failure (a bug:
please report it) exits with :data:`INTERNAL_FAILURE`.
"""

from __future__ import annotations

import inspect
import json
import sys
import warnings
from pathlib import Path
from typing import Annotated, Any

import typer
import typer.core

import sawdrift as sd

from .._paths import write_problem
from .._startup import stored_help
from ..study.executor import check_scheduler
from .interrupts import (  # noqa: F401 - the commands import them from here
    _INTERRUPT_SAID,
    _restore_interrupts,
    _say_interrupted,
    interrupted,
    interrupted_placements,
)
from .json_out import json_nulls  # noqa: F401 - the commands import it from here


def reflow(text: str | None) -> str | None:
    """A command's docstring as help: the lines of each paragraph joined (the help renderer keeps
    single line breaks, which a terminal narrower than the source wrapped again into ragged
    lines); a paragraph of list items or indented lines is kept as written."""
    if not text:
        return text
    paragraphs = inspect.cleandoc(text).split("\n\n")
    kept = ("- ", "* ", " ", "\b")  # list items and indented blocks (not a line on --an-option)
    return "\n\n".join(p if any(line.startswith(kept) for line in p.splitlines())
                       else " ".join(line.strip() for line in p.splitlines())
                       for p in paragraphs)


def _fold_help_tables() -> None:
    """Make the help's option tables fold what does not fit instead of cutting it: at 80 columns
    (a pipe, a standard terminal) 28 option and field names of ``run --help`` ended in an
    ellipsis (``--rolling-resista…``, ``material.restitut…``), the very names the help is read
    for. Rich's table columns cut a word longer than the column, and so do the grids a help
    cell's texts are laid out in (``Columns``); a folded word goes on below."""
    import rich.columns
    import rich.table
    import rich.text
    import typer.rich_utils as rich_utils

    if getattr(rich_utils.Table, "folds", False):
        return

    def fold(cell: Any) -> None:
        parts = cell.renderables if isinstance(cell, rich.columns.Columns) else [cell]
        for part in parts:
            if isinstance(part, rich.text.Text) and part.overflow in (None, "ellipsis"):
                part.overflow = "fold"

    class FoldingTable(rich.table.Table):
        folds = True

        def add_row(self, *renderables: Any, **kwargs: Any) -> None:
            for cell in renderables:
                fold(cell)
            super().add_row(*renderables, **kwargs)
            for column in self.columns:
                column.overflow = "fold"

    rich_utils.Table = FoldingTable


class _Command(typer.core.TyperCommand):
    """A command whose help folds long names (:func:`_fold_help_tables`) and that refuses an
    option given twice (:func:`_refuse_repeated`)."""

    def format_help(self, ctx: Any, formatter: Any) -> None:
        _fold_help_tables()
        super().format_help(ctx, formatter)

    def parse_args(self, ctx: Any, args: list[str]) -> list[str]:
        _refuse_repeated(self.params, args)
        return super().parse_args(ctx, args)


def _refuse_repeated(params: list[Any], args: list[str]) -> None:
    """One line, exit 2, for an option that takes one value given twice: ``--mu 0.2 --mu 0.3``
    ran at 0.3 without a word (the parser keeps the last), ``--settle ... --no-settle`` the
    same. Options that collect (``--param``, ``--set``) may repeat, and so may a flag (``--json
    --json`` asks nothing new); anything after ``--`` is not looked at."""
    names: dict[str, Any] = {}
    for param in params:
        if getattr(param, "param_type_name", "") == "option" and not (
                param.multiple or param.count):
            for opt in (*param.opts, *param.secondary_opts):
                names[opt] = param
    seen: dict[str, str] = {}
    i = 0
    while i < len(args) and args[i] != "--":
        name = args[i].split("=", 1)[0] if args[i].startswith("--") else args[i]
        param = names.get(name)
        if param is not None:
            first = seen.get(param.name)
            if first is not None and not (param.is_flag and first == name):
                _fail(f"{name} is given twice; give it once" if first == name else
                      f"{first} and {name} are both given; give one of them")
            seen[param.name] = name
            if not param.is_flag and "=" not in args[i]:
                i += param.nargs  # its value, even one that starts with '-' (--load -0.2)
        i += 1


class _Typer(typer.Typer):
    """A Typer app whose commands' help is their docstring reflowed (:func:`reflow`), with
    option tables that fold long names (:class:`_Command`)."""

    def command(self, name: str | None = None, **kwargs: Any) -> Any:  # type: ignore[override]
        """:meth:`typer.Typer.command`, the help taken from the docstring through :func:`reflow`."""
        def decorator(f: Any) -> Any:
            if kwargs.get("help") is None:
                kwargs["help"] = reflow(f.__doc__)
            kwargs.setdefault("cls", _Command)
            return typer.Typer.command(self, name, **kwargs)(f)
        return decorator


app = _Typer(
    add_completion=False,
    no_args_is_help=True,
    help="Compare frictional contact models on a particle driven by a Rayleigh wave.\n\n"
    "'The paper' (its equations, figures) is 'Particle manipulation with acoustic waves based on "
    "Hertz-Mindlin mechanics', which sawdrift implements; docs/physics.md explains each equation.",
    pretty_exceptions_enable=False,
)


#: options several commands share, declared once
Param = Annotated[list[str] | None, typer.Option("--param", help="model parameter NAME=VALUE")]
Workers = Annotated[int | None, typer.Option("--workers", help="local processes")]
def _scheduler_option(value: str | None) -> str | None:
    """``--scheduler``'s value checked before any work (:func:`~sawdrift.study.executor.check_scheduler`)."""
    if value is None:
        return None
    try:
        return check_scheduler(value)
    except sd.SawdriftError as exc:
        raise typer.BadParameter(str(exc).replace("scheduler = ", "", 1)) from None


Scheduler = Annotated[str | None, typer.Option("--scheduler", help="dask.distributed address "
                                               "([tcp://]host:port)", callback=_scheduler_option)]
Engine = Annotated[str, typer.Option("--engine", help="compiled or python")]
Progress = Annotated[bool, typer.Option("--progress/--no-progress", help="progress bars, notices "
                                        "and the size line on stderr")]
Yes = Annotated[bool, typer.Option("--yes", help="start even when the size estimate (printed "
                                   "before the work) is above 1 h")]

#: exit status of an unexpected internal failure (1 is a failed check, 2 bad input)
INTERNAL_FAILURE = 3


def _fail(message: str, code: int = 2) -> None:
    typer.echo(f"error: {message}", err=True)
    raise typer.Exit(code)


def _one_line_warnings(message, category, filename, lineno, file=None, line=None):  # noqa: ARG001
    sys.stderr.write(f"warning: {message}\n")


def new_folders(path: Path) -> list[Path]:
    """The folders among ``path`` and its parents that do not exist yet, innermost first: what
    writing to ``path`` makes (:func:`_writable` does), for :func:`remove_new` to take away
    again where a command ends with nothing written."""
    return [p for p in (path, *path.parents) if not p.exists()]


def remove_new(created: list[Path]) -> None:
    """Remove the folders :func:`new_folders` listed, innermost first, as long as each is empty
    (a refused or failed command leaves no folder of its own behind)."""
    for folder in created:
        try:
            folder.rmdir()
        except OSError:
            return


def _writable(path: Path, option: str = "-o", folder: bool = True) -> Path:
    """Check before any work that ``path`` (a folder, or a file's folder) can be written.

    A run or a sweep must not compute for minutes and then lose its results to a bad path.
    """
    where = path if folder else path.parent
    if not folder and path.is_dir():
        _fail(f"{option} {str(path)!r} is a directory; give a file name")
    if folder and path.exists() and not path.is_dir():
        _fail(f"{option} {str(path)!r} exists and is not a folder")
    blocker = next((p for p in (where, *where.parents) if p.exists() and not p.is_dir()), None)
    if blocker is not None:
        _fail(f"{option} {str(path)!r} cannot be written: {str(blocker)!r} is a file, not a folder")
    problem = write_problem(where)
    if problem is not None:
        _fail(f"{option} {str(path)!r} cannot be written ({problem})")
    return path


def _looks_like_file(path: Path) -> bool:
    """Whether ``path`` ends in a file suffix (``.csv``, ``.png``; not ``out_0.1``)."""
    import re

    return bool(re.fullmatch(r"\.[A-Za-z][A-Za-z0-9]{0,7}", path.suffix))


def out_kind(path: Path, files: tuple[str, ...], what: str, option: str = "-o") -> str:
    """``"folder"`` or the file suffix of an output path; one line and exit 2 for another suffix.

    A command that writes a folder of results may also write one file (``files``, e.g.
    ``(".csv",)``); ``what`` says what that file holds. An existing folder is a folder whatever
    its name; a name with another file suffix (``out.txt``, ``out.png``) is refused before any
    work, naming what is allowed.
    """
    if path.is_dir() or not _looks_like_file(path):
        return "folder"
    suffix = path.suffix.lower()
    if suffix in files:
        return suffix
    allowed = " or ".join(f"NAME{s}" for s in files)
    file_part = f", or {allowed} ({what})" if files else ""
    _fail(f"{option} {str(path)!r}: {suffix} files are not written here; give a folder{file_part}")
    return ""  # not reached


#: the figure formats a command writes to a file it is given (-o NAME.png, NAME.pdf, ...)
FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg", ".tif", ".tiff", ".webp", ".eps", ".ps")


def figure_path(path: Path, option: str = "-o") -> Path:
    """The file a figure given as ``path`` is written to, or one line and exit 2 before any work.

    A name without a file suffix gets ``.png`` (``-o phase`` writes ``phase.png``, and the
    command says so); a suffix that is not a figure format (:data:`FIGURE_SUFFIXES`) is refused,
    naming the allowed ones.
    """
    if not _looks_like_file(path):
        return path.with_name(path.name + ".png")
    if path.suffix.lower() not in FIGURE_SUFFIXES:
        allowed = ", ".join(FIGURE_SUFFIXES)
        _fail(f"{option} {str(path)!r}: {path.suffix} is not a figure format; give a name "
              f"ending in one of {allowed} (no suffix: .png)")
    return path


def _split_axis(item: str, form: str, example: str) -> tuple[str, str]:
    """``FIELD`` and ``SPEC`` of an ``--axis FIELD=SPEC`` option, or one line and exit 2."""
    from ..scene.schema import check_dotted

    field, sep, spec = item.partition("=")
    if not sep or not field.strip() or not spec.strip():
        _fail(f"--axis {item!r} must look like {form} (e.g. {example})")
    check_dotted(field.strip())  # a misspelled field: one line naming the nearest valid one
    return field.strip(), spec.strip()


def model_names(text: str | None, option: str = "--model") -> list[str]:
    """The names of a comma-separated model list ([] for None); one line for an empty name in
    it ('mmd,,mdr', 'mmd,' and '' were taken as the names that were there)."""
    if text is None:
        return []
    names = [m.strip() for m in text.split(",")]
    if not all(names):
        _fail(f"{option} {text!r} has an empty model name: give names separated by single "
              "commas (sawdrift models lists them)")
    return names


def _parse_param(items: list[str] | None) -> dict[str, Any]:
    params: dict[str, Any] = {}
    for item in items or []:
        if "=" not in item:
            _fail(f"--param {item!r} must look like NAME=VALUE")
        key, raw = item.split("=", 1)
        if not key.strip():
            _fail(f"--param {item!r} has no parameter name; it must look like NAME=VALUE")
        try:
            value: Any = json.loads(raw)
        except json.JSONDecodeError:
            value = raw
        if key.strip() in params:  # the last one won without a word
            _fail(f"--param {key.strip()} is given twice; give it once")
        params[key.strip()] = value
    return params


def _load_table(path: Path, needs: tuple[str, ...] = ("model", "regime")):
    """A sweep table read for a command, or a one-line error: missing, a folder, not Parquet, or
    without the columns ``needs`` (a trajectory or events file is Parquet too)."""
    import pandas as pd

    if not path.exists():
        _fail(f"table {str(path)!r} does not exist")
    if path.is_dir():
        _fail(f"table {str(path)!r} is a directory, not a Parquet file")
    try:
        frame = pd.read_parquet(path)
    except Exception as exc:  # noqa: BLE001
        _fail(f"table {str(path)!r} is not a readable Parquet file ({exc})".splitlines()[0])
    missing = [c for c in needs if c not in frame.columns]
    if missing:
        _fail(f"table {str(path)!r} is not a sweep table (no {', '.join(missing)} column): give "
              "the table `sawdrift sweep -o` writes")
    if "regime" in frame.columns:
        from ..result.regimes import check_table_regimes

        check_table_regimes(frame["regime"], str(path), "give the table `sawdrift sweep -o` writes")
    return frame


bench_app = _Typer(help="Performance: work-precision study and speed targets.", no_args_is_help=True)
app.add_typer(bench_app, name="bench")


#: every command (and command group) -> the module of this package that registers it, in the
#: order of ``--help``
COMMAND_MODULES: dict[str, str] = {
    "models": "run", "check-model": "run", "run": "run",
    "sweep": "study", "bifurcation": "study",
    "phase-diagram": "report", "compare": "report", "export": "report", "explore": "report",
    "demo": "report", "validate": "report", "bench": "report",
    "field": "field", "load-curve": "load_curve", "force-velocity": "force_velocity",
    "lammps": "lammps", "sort": "sort", "threshold": "threshold",
}


def load_commands(command: str | None = None) -> typer.Typer:
    """Register the commands on :data:`app` and return it.

    With the name of a command, only the module that registers it is imported (and so only its
    commands are built when the application runs): ``sawdrift run`` does not pay for the
    other sixteen commands' imports and option parsing. Without one, every module is imported
    and the commands are put in the order of :data:`COMMAND_MODULES`, whatever order earlier
    calls imported them in, so ``--help`` always lists them the same way.
    """
    import importlib

    modules = [COMMAND_MODULES[command]] if command in COMMAND_MODULES else COMMAND_MODULES.values()
    for module in dict.fromkeys(modules):
        importlib.import_module(f"{__package__}.{module}")
    if command not in COMMAND_MODULES:
        order = {name: i for i, name in enumerate(COMMAND_MODULES)}
        app.registered_commands.sort(key=lambda info: order.get(info.name or "", len(order)))
    return app


def _command_of(argv: list[str]) -> str | None:
    """The command a command line names (its first word, if a command), else None."""
    return argv[0] if argv and argv[0] in COMMAND_MODULES else None


def main() -> None:
    """Console entry point: one-line errors and exit status 2 for user errors.

    The top-level ``--help`` is printed from its stored copy when there is one
    (:func:`sawdrift._startup.stored_help`).
    """
    warnings.showwarning = _one_line_warnings
    if sys.argv[1:] == ["--help"]:
        stored_help(_main)
    else:
        _main()


def _empty_output(argv: list[str]) -> str | None:
    """The output option given an empty path (``-o ""``), which the path type would read as the
    current folder and write into it, or None."""
    for i, arg in enumerate(argv):
        if arg in ("-o", "--out") and i + 1 < len(argv) and argv[i + 1].strip() == "":
            return arg
        if arg.startswith("--out=") and arg[len("--out="):].strip() == "":
            return "--out"
    return None


def _main() -> None:
    try:
        _run_main()
    finally:
        _restore_interrupts()


def _run_main() -> None:
    _INTERRUPT_SAID[0] = False  # one command line (tests call main several times in a process)
    try:
        empty = _empty_output(sys.argv[1:])
        if empty is not None:
            _fail(f"{empty} is an empty path; give a file or folder name (. for this folder)")
        load_commands(_command_of(sys.argv[1:]))
        # standalone_mode=False makes click return a typer.Exit's code instead of raising it
        code = app(standalone_mode=False)
        _say_interrupted(code)
        sys.exit(code if isinstance(code, int) else 0)
    except typer.Exit as exc:
        _say_interrupted(exc.exit_code)
        sys.exit(exc.exit_code)
    except KeyboardInterrupt:
        # a second Ctrl-C while the first was being handled (``timeout -s INT`` signals the
        # command and then its process group, so the command gets two): a traceback after the
        # "interrupted" line, once in eight sweeps on 2 workers
        _say_interrupted(130)
        sys.exit(130)
    except sd.SawdriftError as exc:
        typer.echo(f"error: {exc}", err=True)
        sys.exit(2)
    except MemoryError:
        # one line, not "internal failure": the work asked more memory than the machine has
        typer.echo("error: out of memory: the run asked for more than this machine has; give "
                   "fewer periods, cells or samples", err=True)
        sys.exit(2)
    except OSError as exc:
        # a path given on the command line (or a folder it names) cannot be read or written
        name = f" {str(exc.filename)!r}" if exc.filename else ""
        typer.echo(f"error: cannot use{name}: {exc.strerror or exc}", err=True)
        sys.exit(2)
    except Exception as exc:  # noqa: BLE001 - usage errors and anything unexpected
        # typer vendors click: its usage errors carry format_message() and an exit code
        if hasattr(exc, "format_message") and hasattr(exc, "exit_code"):
            message = exc.format_message()
            if message:  # no arguments: the help was the answer (an 'error: ' line followed it)
                typer.echo(f"error: {message}", err=True)
            sys.exit(exc.exit_code)
        if type(exc).__name__ == "Abort":  # end of input at a prompt
            typer.echo("interrupted", err=True)
            sys.exit(130)
        text = str(exc).splitlines()[0] if str(exc) else "no details"
        typer.echo(f"error: internal failure ({text}); please report it with the command line",
                   err=True)
        sys.exit(INTERNAL_FAILURE)



def check_engine(engine: str, lammps: bool = False) -> None:
    """One line, exit 2, for an engine that is neither compiled nor python (nor lammps, if allowed)."""
    allowed = ("compiled", "python", "lammps") if lammps else ("compiled", "python")
    if engine not in allowed:
        _fail(f"--engine = {engine!r} is not allowed; use " + ", ".join(repr(a) for a in allowed))


def write_outputs(out: Path, stem: str, data: dict[str, Any], plot: Any, scene: Any) -> None:
    """Write a study's ``STEM.json`` (NaN as null), its figure ``STEM.png`` (``plot(path)``)
    and its scene."""
    out.mkdir(parents=True, exist_ok=True)
    (out / f"{stem}.json").write_text(json.dumps(json_nulls(data), indent=1) + "\n")
    plot(out / f"{stem}.png")
    scene.to_toml(out / "scene.toml")
