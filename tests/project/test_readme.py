"""The README's Python examples run as written: every ```python block, in order, in one namespace
(later blocks use earlier names), from the repository root; the test functions the examples
define are called. A block may be skipped only by a ``<!-- readme-test: skip (reason) -->`` line
right before it (the Dask example needs a running scheduler)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from mjwalk.cycle import types

ROOT = Path(__file__).parents[2]
SKIP = re.compile(r"<!-- readme-test: skip \((.+)\) -->\s*$")


def readme_blocks() -> list[tuple[int, str, str | None]]:
    """(line, code, skip reason or None) of every ```python block of README.md."""
    lines = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()
    out, i = [], 0
    while i < len(lines):
        if lines[i].strip() == "```python":
            m = SKIP.match(lines[i - 1]) if i else None
            j = next(k for k in range(i + 1, len(lines)) if lines[k].strip() == "```")
            out.append((i + 1, "\n".join(lines[i + 1 : j]), m.group(1) if m else None))
            i = j
        i += 1
    return out


def test_readme_has_examples_and_skips_only_the_cluster_and_scan_ones():
    """Only examples that need something a checkout lacks (a Dask scheduler, the user's own
    scan file) are skipped; tests/scan/test_scene.py runs scan_to_scene itself."""
    blocks = readme_blocks()
    assert len(blocks) >= 4
    reasons = [reason for _, _, reason in blocks if reason]
    assert len(reasons) == 2
    assert reasons[0].startswith("needs a scan file") or reasons[1].startswith("needs a scan file")
    assert "needs a running Dask scheduler" in reasons


@pytest.mark.slow
def test_readme_examples_run(monkeypatch):
    monkeypatch.chdir(ROOT)
    # the "Adding a task kind" example adds a kind to the table: gone again after this test
    kinds = dict(types.TASK_KINDS)
    try:
        _run_examples()
    finally:
        types.TASK_KINDS.clear()
        types.TASK_KINDS.update(kinds)


def _run_examples() -> None:
    namespace: dict = {"__name__": "readme"}
    for line, code, reason in readme_blocks():
        if reason:
            continue
        before = set(namespace)
        exec(compile(code, f"README.md:{line}", "exec"), namespace)
        for name in sorted(set(namespace) - before):
            if name.startswith("test_") and callable(namespace[name]):
                namespace[name]()  # the example's own test must pass
    assert "many" in namespace and len(namespace["many"]) == 4
