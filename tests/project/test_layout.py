"""The package layout: stages import only downward and never in a circle; ``import mjwalk`` is
light and side-effect free; the top level exports the whole pipeline."""

from __future__ import annotations

import ast
import os
import re
import subprocess
import sys
from pathlib import Path

import mjwalk

PKG = Path(mjwalk.__file__).parent
#: The stages of the data flow, lowest first (ARCHITECTURE.md). Shared helpers (conventions,
#: errors, file I/O, numba set-up) sit below all of them; the report writers, the video and
#: plots (``render``) and the command line on top.
STAGES = (
    "_base", "mocap", "world", "scan", "gait", "plan", "body", "arms", "timeline", "ergonomics",
    "cycle", "top",
)  # fmt: skip
BASE = {
    "conventions",
    "anthropometry",
    "errors",
    "_io",
    "_buildonce",
    "_jit",
    "_args",
    "_version",
    "_log",
    "boundedmemo",
}
TOP = {"render", "report", "cli", "__main__", "shipped"}


def _module(path: Path) -> str:
    parts = path.relative_to(PKG.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _stage(module: str) -> str:
    parts = module.split(".")[1:]
    if not parts:
        return "top"
    head = parts[0]
    return "_base" if head in BASE else "top" if head in TOP else head


def _is_type_checking(node: ast.AST) -> bool:
    """Whether ``node`` is an ``if TYPE_CHECKING:`` block (imports for type checkers only)."""
    if not isinstance(node, ast.If):
        return False
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _targets(node: ast.AST) -> list[str]:
    """The mjwalk modules an import statement loads (``from mjwalk.cycle import reaching``
    loads the module ``mjwalk.cycle.reaching``)."""
    if isinstance(node, ast.Import):
        return [a.name for a in node.names if a.name.startswith("mjwalk.")]
    if not (isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("mjwalk")):
        return []
    if node.module == "mjwalk":  # the lazy top level: only its submodules count
        names = [f"mjwalk.{a.name}" for a in node.names]
        return [n for n in names if _exists(n)]
    subs = [f"{node.module}.{a.name}" for a in node.names if _exists(f"{node.module}.{a.name}")]
    return [node.module, *subs]


def _exists(module: str) -> bool:
    rel = Path(*module.split(".")[1:])
    return (PKG / rel).with_suffix(".py").is_file() or (PKG / rel / "__init__.py").is_file()


def _imports(path: Path, top_level_only: bool = False, type_checking: bool = True):
    """(module, line) of every mjwalk import in ``path``: at module level only, or everywhere
    (function-level imports too), with or without those under ``if TYPE_CHECKING:``."""
    out: list[tuple[str, int]] = []

    def visit(node: ast.AST) -> None:
        for child in ast.iter_child_nodes(node):
            if _is_type_checking(child) and not type_checking:
                for other in child.orelse:  # type: ignore[attr-defined]
                    visit_one(other)
                continue
            visit_one(child)

    def visit_one(node: ast.AST) -> None:
        out.extend((t, node.lineno) for t in _targets(node))  # type: ignore[attr-defined]
        if top_level_only and not _is_type_checking(node):
            return
        visit(node)

    visit(ast.parse(path.read_text()))
    return out


def _files() -> list[Path]:
    return sorted(PKG.rglob("*.py"))


def test_every_module_belongs_to_a_stage():
    for f in _files():
        assert _stage(_module(f)) in STAGES, f


def test_no_module_imports_upward():
    upward = []
    for f in _files():
        mod = _module(f)
        if mod == "mjwalk":  # the lazy top level names everything
            continue
        for target, line in _imports(f):
            if STAGES.index(_stage(target)) > STAGES.index(_stage(mod)):
                upward.append(f"{mod}:{line} imports {target}")
    assert upward == []


def _graph(type_checking: bool) -> dict[str, set[str]]:
    """Module -> the mjwalk modules it imports (at module level or inside a function), with or
    without the imports for type checkers only; the lazy top level is left out (it names
    everything)."""
    graph = {}
    for f in _files():
        mod = _module(f)
        if mod == "mjwalk":
            continue
        deps = {target for target, _ in _imports(f, type_checking=type_checking)}
        graph[mod] = deps - {mod, "mjwalk"}
    return graph


def test_no_import_cycles():
    """No module imports itself through others, counting every import a module runs (at module
    level or inside a function: both load the module when they run), not those for type
    checkers only."""
    graph = _graph(type_checking=False)
    state: dict[str, int] = {}
    cycles: list[str] = []

    def visit(m: str, trail: list[str]) -> None:
        if state.get(m) == 2 or m not in graph:
            return
        if state.get(m) == 1:
            cycles.append(" -> ".join([*trail[trail.index(m) :], m]))
            return
        state[m] = 1
        for d in sorted(graph[m]):
            visit(d, [*trail, m])
        state[m] = 2

    for m in sorted(graph):
        visit(m, [])
    assert cycles == []


#: Circles that only imports for type checkers (``if TYPE_CHECKING:``) close: known, issue 46,
#: to be removed. Each is the set of modules that import one another round a circle (a strongly
#: connected part of the import graph). A new circle, or a known one that grows, fails
#: :func:`test_no_import_cycles_counting_type_checking_imports`; a circle broken must be taken
#: off this list (the list only shrinks).
TYPING_CIRCLES_FOR_NOW: set[frozenset[str]] = set()


def test_no_import_cycles_counting_type_checking_imports():
    """A type annotation is a dependency too: counting the imports under ``if TYPE_CHECKING:``
    as well, the only circles are the known ones (:data:`TYPING_CIRCLES_FOR_NOW`). Two modules
    that need each other's names need a third home for what they share (a small module, a
    protocol), not an import hidden from the interpreter."""
    graph = _graph(type_checking=True)
    runtime = _graph(type_checking=False)
    reach: dict[str, set[str]] = {}
    for m in graph:  # every module reachable from m along imports
        seen: set[str] = set()
        todo = [d for d in graph[m] if d in graph]
        while todo:
            d = todo.pop()
            if d not in seen:
                seen.add(d)
                todo.extend(e for e in graph[d] if e in graph)
        reach[m] = seen
    circles = {
        frozenset({m, *(n for n in reach[m] if m in reach[n])}) for m in graph if m in reach[m]
    }
    typing_only = sorted(
        f"{m} -> {d}"
        for c in circles - TYPING_CIRCLES_FOR_NOW
        for m in sorted(c)
        for d in sorted((graph[m] & c) - runtime[m])
    )
    new = [sorted(c) for c in circles - TYPING_CIRCLES_FOR_NOW]
    assert new == [], f"new import circles {new}, closed by the typing-only imports {typing_only}"
    assert circles == TYPING_CIRCLES_FOR_NOW  # a circle broken is taken off the list


#: Private names a module still takes from another (each is to be made public in its owner).
PRIVATE_FOR_NOW: set[tuple[str, str, str]] = set()


def test_private_names_stay_in_their_module():
    """A name starting with an underscore is its module's own: another module that needs it
    needs a public name in the module that owns it."""
    crossing = set()
    for f in _files():
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("mjwalk"):
                for a in node.names:
                    private = a.name.startswith("_") and not a.name.startswith("__")
                    if private and not _exists(f"{node.module}.{a.name}"):  # a module is public
                        crossing.add((_module(f), node.module, a.name))
    assert crossing == PRIVATE_FOR_NOW


#: Tests that pin a compiled kernel to its pure-Python reference: they may import the private
#: kernels they pin (test file -> names). Every other test exercises public names.
KERNEL_PINNING_TESTS = {
    "tests/timeline/test_kernels.py": {"_end_slopes", "_hip_rotation_excess"},
    "tests/plan/test_planner_fastpaths.py": {"_rim", "_dijkstra_field"},
    "tests/plan/test_grid.py": {"_astar"},
    "tests/arms/test_chain.py": {"_shoulder_branch"},
    "tests/body/test_spin.py": {"_spin_rounds"},
}
#: Private names tests still import: each is to be made public in its module or tested through
#: public behaviour, then taken off this list.
TEST_PRIVATE_FOR_NOW = {("tests/scan/test_scene.py", "mjwalk.scan.scene", "_Site")}


def test_tests_import_no_private_names():
    """Tests assert public behaviour: a test file imports no private mjwalk name (a private
    module such as ``mjwalk._jit`` is a module like any other), except a kernel-pinning test
    importing the kernels it pins (:data:`KERNEL_PINNING_TESTS`)."""
    root = PKG.parent
    found = set()
    for f in sorted((root / "tests").rglob("*.py")):
        rel = f.relative_to(root).as_posix()
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("mjwalk"):
                for a in node.names:
                    private = a.name.startswith("_") and not a.name.startswith("__")
                    if not private or _exists(f"{node.module}.{a.name}"):
                        continue
                    if a.name not in KERNEL_PINNING_TESTS.get(rel, set()):
                        found.add((rel, node.module, a.name))
    assert found == TEST_PRIVATE_FOR_NOW


#: The longest a module may be (lines): one concept per module.
MAX_LINES = 600
#: Modules not yet split (each is to be split, then taken off this list).
TOO_LONG_FOR_NOW: set[str] = set()


def test_modules_are_short():
    long = {_module(f): n for f in _files() if (n := len(f.read_text().splitlines())) > MAX_LINES}
    assert {m: n for m, n in long.items() if m not in TOO_LONG_FOR_NOW} == {}
    assert set(long) == TOO_LONG_FOR_NOW  # the allow-list shrinks as modules are split


def test_import_is_light_and_changes_no_environment():
    code = (
        "import os, sys; env = dict(os.environ); import mjwalk; "
        "heavy = sorted(m for m in ('mujoco', 'numpy', 'numba', 'sklearn', 'scipy') "
        "if m in sys.modules); print(heavy, dict(os.environ) == env)"
    )
    env = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", "PYOPENGL_PLATFORM")}
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True
    ).stdout.strip()
    assert out == "[] True"


def test_top_level_exports_the_pipeline():
    assert mjwalk.__version__
    assert len(set(mjwalk.__all__)) == len(mjwalk.__all__)
    assert set(mjwalk.__all__) <= set(dir(mjwalk))
    for name in (
        "load_workplace",
        "plan_walks",
        "legs_from_walk",
        "Timeline",
        "timeline_from_walk",
        "check_collisions",
        "simulate_cycles",
        "render_video",
        "write_report",
    ):
        assert name in mjwalk.__all__
    from mjwalk.timeline.collisions import check_collisions

    assert mjwalk.check_collisions is check_collisions
    assert not hasattr(mjwalk, "no_such_name")
    for name in mjwalk.__all__:  # every lazy name resolves
        assert getattr(mjwalk, name) is not None


# ------------------------------------------------------------------ small functions, tests, docs

#: The longest a function may be (lines from ``def`` to its end, its docstring not counted) and
#: the most parameters it may take (``self``/``cls`` not counted; ``*args``/``**kwargs`` count).
MAX_FUNCTION_LINES = 80
MAX_PARAMETERS = 8


def _is_kernel(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    """Whether ``fn`` is a compiled numba kernel (``@njit``, ``@jit(...)``, ``@vectorize``...):
    a kernel takes its arrays one by one and runs as one loop, so the size rules do not apply."""
    return any(
        re.search(r"\b(n?jit(_inline|_sum|_gil)?|vectorize|guvectorize|cfunc)\b", ast.unparse(d))
        for d in fn.decorator_list
    )


def _parameters(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> list[str]:
    a = fn.args
    names = [
        x.arg for x in (*a.posonlyargs, *a.args, *a.kwonlyargs) if x.arg not in ("self", "cls")
    ]
    if a.vararg:
        names.append(f"*{a.vararg.arg}")
    if a.kwarg:
        names.append(f"**{a.kwarg.arg}")
    return names


def _docstring_lines(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    first = fn.body[0]
    is_doc = isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
    return (
        first.end_lineno - first.lineno + 1 if is_doc and isinstance(first.value.value, str) else 0
    )  # type: ignore[union-attr, operator]


def _functions(tree: ast.AST):
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield node


def test_functions_are_short_and_take_few_parameters():
    """No ordinary function is longer than :data:`MAX_FUNCTION_LINES` or takes more than
    :data:`MAX_PARAMETERS` parameters: a longer one is several steps that want names, a wider
    one a record its values belong to. Compiled kernels are excepted (:func:`_is_kernel`)."""
    long, wide = [], []
    for f in _files():
        for fn in _functions(ast.parse(f.read_text())):
            if _is_kernel(fn):
                continue
            lines = fn.end_lineno - fn.lineno + 1 - _docstring_lines(fn)  # type: ignore[operator]
            if lines > MAX_FUNCTION_LINES:
                long.append(f"{_module(f)}.{fn.name} ({lines} lines)")
            if len(_parameters(fn)) > MAX_PARAMETERS:
                wide.append(f"{_module(f)}.{fn.name} ({len(_parameters(fn))} parameters)")
    assert long == []
    assert wide == []


def _public(f: Path) -> bool:
    """Whether ``f`` is a public module: no part of its path below ``mjwalk/`` is private."""
    return not any(p.startswith("_") and p != "__init__.py" for p in f.relative_to(PKG).parts)


def test_every_public_module_has_its_test_file():
    """``mjwalk/<stage>/.../<name>.py`` is tested in ``tests/<stage>/test_<name>.py`` (a top-level
    module in ``tests/test_<name>.py``), which imports it by name."""
    root = PKG.parent
    missing = []
    for f in _files():
        if not _public(f) or f.name == "__init__.py":
            continue
        rel = f.relative_to(PKG)
        test = root / "tests" / Path(*rel.parts[:-1][:1]) / f"test_{f.stem}.py"
        module = _module(f)
        parent, name = module.rsplit(".", 1)
        found = test.is_file() and any(
            (isinstance(n, ast.Import) and any(a.name == module for a in n.names))
            or (
                isinstance(n, ast.ImportFrom)
                and (
                    n.module == module
                    or (n.module == parent and any(a.name == name for a in n.names))
                )
            )
            for n in ast.walk(ast.parse(test.read_text()))
        )
        if not found:
            missing.append(f"{module}: {test.relative_to(root)}")
    assert missing == []


DEFERRED = "# deferred:"


def test_function_level_imports_say_why():
    """An import inside a function hides a dependency from the module's head: it is there only
    to break an import circle or to defer a heavy or optional dependency, and says which in a
    ``# deferred: <reason>`` comment on its line or the line above."""
    unexplained = []
    for f in _files():
        lines = f.read_text().splitlines()
        for fn in _functions(ast.parse("\n".join(lines))):
            for node in ast.walk(fn):
                if not isinstance(node, (ast.Import, ast.ImportFrom)):
                    continue
                near = lines[node.lineno - 2 : node.end_lineno]  # type: ignore[misc]
                if not any(DEFERRED in line for line in near):
                    unexplained.append(
                        f"{_module(f)}:{node.lineno} {lines[node.lineno - 1].strip()}"
                    )
    assert unexplained == []


def _section(doc: str, header: str) -> set[str] | None:
    """The names a Google docstring section lists (``name:`` or ``name (type):`` at the section's
    first indent), or None when there is no such section."""
    m = re.search(rf"^\s*{header}:\s*$", doc, re.M)
    if not m:
        return None
    names: set[str] = set()
    indent = None
    for line in doc[m.end() :].splitlines():
        if not line.strip():
            continue
        ind = len(line) - len(line.lstrip())
        if indent is not None and ind < indent:
            break
        indent = ind if indent is None else indent
        if ind == indent and (item := re.match(r"^\s*(\*{0,2}\w+)\s*(\([^)]*\))?\s*:", line)):
            names.add(item.group(1).lstrip("*"))
    return names


def _undocumented(fn: ast.FunctionDef | ast.AsyncFunctionDef, doc: str, init: bool) -> list[str]:
    problems = []
    params = [p.lstrip("*") for p in _parameters(fn)]
    if params:
        listed = _section(doc, "Args")
        if listed is None:
            problems.append("no Args:")
        elif missing := [p for p in params if p not in listed]:
            problems.append(f"Args: lacks {', '.join(missing)}")
    returns = fn.returns is not None and ast.unparse(fn.returns) not in ("None", "NoReturn")
    if returns and not init and not re.search(r"^\s*(Returns|Yields):", doc, re.M):
        problems.append("no Returns:")
    return problems


def _skipped(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> bool:
    decorators = [ast.unparse(d) for d in fn.decorator_list]
    return any(
        d in ("property", "overload", "typing.overload", "functools.cached_property")
        or d.endswith(".setter")
        for d in decorators
    )


def test_public_api_is_documented():
    """Every public function and method (and a public class's ``__init__``) of a public module
    documents its parameters in a Google ``Args:`` section and what it returns in ``Returns:``
    (or ``Yields:``); the texts state units and frames."""
    found = []
    for f in _files():
        if not _public(f):
            continue
        tree = ast.parse(f.read_text())
        for node in tree.body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                if not node.name.startswith("_") and not _skipped(node):
                    for p in _undocumented(node, ast.get_docstring(node) or "", init=False):
                        found.append(f"{_module(f)}.{node.name}: {p}")
            if isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
                for m in node.body:
                    if not isinstance(m, (ast.FunctionDef, ast.AsyncFunctionDef)) or _skipped(m):
                        continue
                    doc = ast.get_docstring(m) or ""
                    if m.name == "__init__":
                        doc = doc if "Args:" in doc else f"{ast.get_docstring(node) or ''}\n{doc}"
                    elif m.name.startswith("_"):
                        continue
                    for p in _undocumented(m, doc, init=m.name == "__init__"):
                        found.append(f"{_module(f)}.{node.name}.{m.name}: {p}")
    assert found == []


def test_architecture_lists_every_module():
    """ARCHITECTURE.md's module index names every module under its folder (a new module is
    placed in the map when it is made)."""
    text = (PKG.parent / "ARCHITECTURE.md").read_text()
    index = text[text.index("## Module index") :]
    listed: dict[str, set[str]] = {}
    folder = None
    for line in index.splitlines():
        if m := re.match(r"^\*\*`(.+)/`\*\*$", line):
            folder = m.group(1)
        elif (m := re.match(r"^- `([\w.]+\.py)`:", line)) and folder is not None:
            listed.setdefault(folder, set()).add(m.group(1))
    missing = [
        f"{f.parent.relative_to(PKG.parent).as_posix()}/{f.name}"
        for f in _files()
        if not (f.name == "__init__.py" and f.parent != PKG)
        and f.name not in listed.get(f.parent.relative_to(PKG.parent).as_posix(), set())
    ]
    assert missing == []
