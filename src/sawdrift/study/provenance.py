"""Provenance of computed results: a hash of the code that computed them.

``__version__`` stays the same through commits that change results, so a version alone cannot
tell a table's old rows from new ones. :func:`code_hash` is the sha1 of the source of the sawdrift
package (every ``.py`` file, by relative path and content) and, for each model named, of the
package its class comes from (and those of its base classes: a plugin that extends a built-in
model depends on it). It works the same in a git checkout, an installed wheel or an editable
install, and is computed once per process (a few milliseconds).
"""

from __future__ import annotations

import hashlib
import sys
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from .._version import __version__
from ..errors import SawdriftError

#: the hex digits of a code hash kept in tables and identifiers
LENGTH = 12

_TREES: dict[Path, str] = {}
_CODES: dict[tuple[str, ...], str] = {}


def tree_hash(root: Path) -> str:
    """sha1 of every ``.py`` file under ``root`` (a package folder) or of ``root`` (a module file).

    Files are taken in sorted order of their path relative to ``root``, each as its path and its
    bytes; ``__pycache__`` is skipped. Cached per process.
    """
    root = root.resolve()
    done = _TREES.get(root)
    if done is not None:
        return done
    h = hashlib.sha1()
    files = [root] if root.is_file() else sorted(
        p for p in root.rglob("*.py") if "__pycache__" not in p.parts)
    for path in files:
        rel = path.name if path == root else path.relative_to(root).as_posix()
        h.update(rel.encode() + b"\0")
        h.update(path.read_bytes() + b"\0")
    _TREES[root] = h.hexdigest()
    return _TREES[root]


def _package_root(module_name: str) -> Path | None:
    """The folder of the top-level package of ``module_name`` (or its file if it is a module)."""
    top = sys.modules.get(module_name.split(".")[0])
    path = getattr(top, "__file__", None)
    if path is None:
        return None
    path = Path(path)
    return path.parent if path.name == "__init__.py" else path


def model_roots(model: str) -> list[Path]:
    """Source roots a model's results depend on, besides sawdrift: its class's packages.

    A model that is not registered gives ``[]`` (its cells are errors; sawdrift alone computed them).
    """
    from ..contact.registry import get_model

    try:
        cls = get_model(model)
    except SawdriftError:
        return []
    roots = []
    for klass in cls.__mro__:
        module = getattr(klass, "__module__", "")
        if module.split(".")[0] in ("sawdrift", "builtins", "abc", "typing", "pydantic"):
            continue
        root = _package_root(module)
        if root is not None and root not in roots:
            roots.append(root)
    return roots


def code_hash(models: Iterable[str] = ()) -> str:
    """The hash of the code behind results of ``models``: sawdrift's source and the models' packages.

    Returns the first :data:`LENGTH` hex digits of the sha1 of the tree hashes (:func:`tree_hash`)
    of the sawdrift package and of each model's packages (:func:`model_roots`), in a fixed order.
    """
    key = tuple(sorted(set(models)))
    done = _CODES.get(key)
    if done is not None:
        return done
    roots = [Path(__file__).resolve().parent.parent]
    for model in key:
        roots += [r for r in model_roots(model) if r not in roots]
    text = "\n".join(f"{r.name}:{tree_hash(r)}" for r in roots)
    _CODES[key] = hashlib.sha1(text.encode()).hexdigest()[:LENGTH]
    return _CODES[key]


# -- resuming a table -----------------------------------------------------------------------------


class TableProvenanceError(SawdriftError):
    """A sweep would add to a table computed by other code or from another base scene."""


def _flat(data: Any, prefix: str = "") -> dict[str, Any]:
    """``{"a.b": value}`` for a nested dict."""
    if not isinstance(data, dict):
        return {prefix: data}
    out: dict[str, Any] = {}
    for key, value in data.items():
        out.update(_flat(value, f"{prefix}.{key}" if prefix else str(key)))
    return out


def base_differences(stored: dict[str, Any], current: dict[str, Any]) -> list[str]:
    """The dotted fields where two base scenes differ, as ``field: table X, this sweep Y``.

    ``model`` is not compared (a table may hold several models); ``model_params`` only when both
    scenes name the same model.
    """
    a, b = _flat(stored), _flat(current)
    skip = ("model",) if stored.get("model") == current.get("model") else ("model", "model_params")
    out = []
    for key in sorted(set(a) | set(b)):
        if key.split(".")[0] in skip or a.get(key) == b.get(key):
            continue
        out.append(f"{key}: table {a.get(key)!r}, this sweep {b.get(key)!r}")
    return out


#: the base scene :func:`~sawdrift.study.table.stored_base` gives for a journal whose header
#: (its first line) cannot be read: its rows cannot be checked against a sweep (tested by
#: identity, in :func:`check_resume`)
UNREADABLE_BASE: dict[str, Any] = {"unreadable": True}


def check_resume(table: Path, rows: Iterable[dict[str, Any]], stored_base: dict[str, Any] | None,
                 base: dict[str, Any], force: bool, engine: str | None = None) -> None:
    """Refuse to add to ``table`` when its rows come from other code or another base scene.

    ``rows`` are the table's (and its journal's) rows, each with ``model``, ``version`` and
    ``code_hash`` (None in tables written before the hash existed); a row is from other code when
    its hash is not :func:`code_hash` of its model now. ``stored_base`` is the base scene the
    table was swept from (its metadata, or its journal's header), ``base`` this sweep's;
    ``engine`` this sweep's engine, which the rows must share (None: not checked). With
    ``force`` nothing is refused: the table then mixes, and each row names its own code.

    Raises
    ------
    TableProvenanceError
        One line naming the table, what differs, and the two ways out.
    """
    if force:
        return
    rows = list(rows)
    engines = sorted({str(r["engine"]) for r in rows if r.get("engine")} - {engine})
    if engine is not None and engines:
        # a cell is one scene: the other engine's row was reused as this engine's, without a word
        # (a cross-check of the two engines compared identical rows)
        raise TableProvenanceError(
            f"table {str(table)!r} holds rows of the {' and '.join(engines)} engine; this sweep "
            f"runs {engine}: write a new table, or force it (--force; force=True in Python) to "
            "keep those rows")
    other = [r for r in rows if r.get("code_hash") != code_hash([str(r.get("model"))])]
    if other:
        theirs = sorted({f"sawdrift {r.get('version')} code {r.get('code_hash') or 'unrecorded'}"
                         for r in other})
        raise TableProvenanceError(
            f"table {str(table)!r} holds {len(other)} rows computed by other code "
            f"({'; '.join(theirs[:3])}; this is sawdrift {__version__} code "
            f"{code_hash(sorted({str(r.get('model')) for r in other}))}): write a new table, or "
            "force it (--force; force=True in Python) to add rows of this code to it")
    if stored_base is UNREADABLE_BASE:
        raise TableProvenanceError(
            f"table {str(table)!r}: the base scene its rows were swept from (in its metadata, or "
            "the first line of its journal) cannot be read, so its rows cannot be checked "
            "against this sweep: write a new table, or force=True (--force) to keep them")
    if stored_base is not None:
        diffs = base_differences(stored_base, base)
        if diffs:
            more = f" and {len(diffs) - 3} more" if len(diffs) > 3 else ""
            raise TableProvenanceError(
                f"table {str(table)!r} was swept from another base scene ({'; '.join(diffs[:3])}"
                f"{more}): write a new table, or force=True (--force) to mix them")
