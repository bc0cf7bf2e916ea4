"""The ``plan`` and ``render`` commands' arguments (mjwalk.cli.planning)."""

from __future__ import annotations

import argparse
from pathlib import Path

import pytest

from mjwalk.cli import main
from mjwalk.cli.planning import (
    VIDEO_SUFFIXES,
    add_plan_parser,
    add_render_parser,
    cmd_plan,
    cmd_render,
)
from mjwalk.conventions import BODY_RADIUS, DEFAULT_STATURE


def _parse(argv):
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers(dest="command", required=True)
    add_plan_parser(sub)
    add_render_parser(sub)
    return parser.parse_args(argv)


def test_plan_parser():
    a = _parse(["plan", "station", "--from", "stand_rack2", "--to", "1.5,2"])
    assert (a.scene, a.start, a.radius, a.n, a.cost, a.seed) == (
        Path("station"),
        "stand_rack2",
        BODY_RADIUS,
        15,
        "energy",
        0,
    )
    assert a.func is cmd_plan and a.walker is None and not a.footprints
    with pytest.raises(SystemExit):
        _parse(["plan", "station", "--from", "a"])  # --to is required


def test_render_parser():
    a = _parse(["render", "w.npz", "--scene", "station", "-o", "w.mp4"])
    assert (a.fps, a.width, a.height, a.stature, a.camera) == (
        30.0,
        640,
        480,
        DEFAULT_STATURE,
        "track",
    )
    assert a.func is cmd_render and VIDEO_SUFFIXES == (".mp4",)


def test_render_refuses_another_video_format_before_work(tmp_path, capsys):
    out = tmp_path / "w.avi"
    assert main(["render", "w.npz", "--scene", "station", "-o", str(out)]) == 2
    assert ".mp4" in capsys.readouterr().err and not out.exists()


def test_plan_over_levels_prints_the_grid_route_over_levels(scenes_dir, capsys):
    """A walk onto the platform gets its grid-A* baseline over levels, as a floor walk gets its
    grid A* (mjwalk.plan.levelgrid), even with no hybrid walks asked for."""
    scene = str(scenes_dir / "multilevel_station.xml")
    argv = ["plan", scene, "--from", "stand_rack1", "--to", "stand_platform2", "--n", "0"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "walk over levels  stand_rack1 (L0) -> stand_platform2 (L3)" in out
    assert "grid A*  stand_rack1 -> stand_platform2 over levels: length " in out
    assert out.rstrip().endswith("route L0 -> step up -> L3")
