"""A cached model is built by one process while the others wait and load it."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

from mjwalk._buildonce import built_once
from mjwalk.errors import ModelFileError

ROOT = Path(__file__).resolve().parents[1]

RACER = textwrap.dedent(
    """
    import sys, time
    from pathlib import Path
    sys.path.insert(0, {root!r})
    from mjwalk._buildonce import built_once

    path = Path(sys.argv[1])
    def build():
        with open(path.parent / "builds.txt", "a") as f:
            f.write("built\\n")
        time.sleep(1.0)  # long enough for the other process to reach the lock
        path.write_text("model")
        return "model"
    print(built_once(path, lambda p: p.read_text(), build))
    """
)


def test_two_processes_on_an_empty_cache_build_once(tmp_path):
    script = tmp_path / "racer.py"
    script.write_text(RACER.format(root=str(ROOT)))
    target = tmp_path / "cache" / "model.txt"
    procs = [
        subprocess.Popen([sys.executable, str(script), str(target)], stdout=subprocess.PIPE)
        for _ in range(2)
    ]
    outs = [p.communicate(timeout=60)[0].decode().strip() for p in procs]
    assert [p.returncode for p in procs] == [0, 0]
    assert outs == ["model", "model"]
    assert (tmp_path / "cache" / "builds.txt").read_text().splitlines() == ["built"]


def test_a_stale_file_is_rebuilt_and_reported(tmp_path):
    target = tmp_path / "model.txt"
    target.write_text("old")
    told = []

    def load(p: Path) -> str:
        text = p.read_text()
        if text == "old":
            raise ModelFileError("model.txt: version 1, this mjwalk reads version 2")
        return text

    def build() -> str:
        target.write_text("new")
        return "new"

    assert built_once(target, load, build, on_stale=told.append) == "new"
    assert [str(e) for e in told] == ["model.txt: version 1, this mjwalk reads version 2"]
    assert built_once(target, load, lambda: "never") == "new"  # now loaded, not built
