"""The ``scan`` and ``scene-import`` commands' arguments (mjwalk.cli.scenes)."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import pytest

from mjwalk.cli.scenes import (
    add_scan_parser,
    add_scene_import_parser,
    cmd_scan,
    cmd_scene_import,
)


def _parse(argv):
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers(dest="command", required=True)
    add_scan_parser(sub)
    add_scene_import_parser(sub)
    return parser.parse_args(argv)


def test_scan_parser():
    a = _parse(["scan", "a.ply", "b.ply", "-o", "s.xml", "--offset=-1,2,3.5"])
    assert a.scan == [Path("a.ply"), Path("b.ply")] and a.func is cmd_scan
    np.testing.assert_array_equal(a.offset, [-1.0, 2.0, 3.5])
    assert (a.resolution, a.units, a.up, a.voids) == (0.02, "m", "+z", "blocked")
    for bad in (["--offset", "1,2"], ["--offset=1,nan,2"], ["--resolution", "5"]):
        with pytest.raises(SystemExit):
            _parse(["scan", "a.ply", "-o", "s.xml", *bad])


def test_scene_import_parser():
    a = _parse(["scene-import", "part.stl", "-o", "s.xml", "--units", "mm"])
    # None: import_scene's defaults (0.02; 0.01 for a mesh with walk faces under its hull)
    assert (a.source, a.units, a.up, a.threshold) == (Path("part.stl"), "mm", "+z", None)
    assert a.func is cmd_scene_import
    assert _parse(["scene-import", "p.stl", "-o", "s.xml", "--threshold", "0.05"]).threshold == 0.05
