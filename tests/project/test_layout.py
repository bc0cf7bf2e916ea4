"""The package layout: stages import only downward and never in a circle; ``import mjwalk`` is
light and side-effect free; the top level exports the whole pipeline."""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

import mjwalk

PKG = Path(mjwalk.__file__).parent
#: The stages of the data flow, lowest first (ARCHITECTURE.md). Shared helpers (conventions,
#: errors, file I/O, numba set-up, GL selection) sit below all of them; the report writers, the
#: video, the plots and the command line on top.
STAGES = (
    "_base", "mocap", "world", "gait", "plan", "body", "arms", "timeline", "ergonomics", "cycle",
    "top",
)  # fmt: skip
BASE = {"conventions", "anthropometry", "errors", "_io", "_jit", "_gl", "_args", "_version", "_log"}
TOP = {"render", "viewpoint", "plot", "report", "cli", "__main__", "shipped"}


def _module(path: Path) -> str:
    parts = path.relative_to(PKG.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _stage(module: str) -> str:
    parts = module.split(".")[1:]
    if not parts:
        return "top"
    head = parts[0]
    return "_base" if head in BASE else "top" if head in TOP else head


def _imports(path: Path, top_level_only: bool) -> list[tuple[str, int]]:
    tree = ast.parse(path.read_text())
    nodes = tree.body if top_level_only else ast.walk(tree)
    out = []
    for node in nodes:
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("mjwalk."):
            out.append((node.module, node.lineno))
        elif isinstance(node, ast.Import):
            out += [(a.name, node.lineno) for a in node.names if a.name.startswith("mjwalk.")]
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
        for target, line in _imports(f, top_level_only=False):
            if STAGES.index(_stage(target)) > STAGES.index(_stage(mod)):
                upward.append(f"{mod}:{line} imports {target}")
    assert upward == []


def test_no_import_cycles():
    graph = {}
    for f in _files():
        mod = _module(f)
        deps = {target for target, _ in _imports(f, top_level_only=True)}
        graph[mod] = deps - {mod}
    state: dict[str, int] = {}

    def visit(m: str, trail: list[str]) -> None:
        if state.get(m) == 2 or m not in graph:
            return
        assert state.get(m) != 1, " -> ".join([*trail, m])
        state[m] = 1
        for d in sorted(graph[m]):
            visit(d, [*trail, m])
        state[m] = 2

    for m in sorted(graph):
        visit(m, [])


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
