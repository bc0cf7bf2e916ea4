"""Shipped scenes and cycles found by short name or by path."""

from __future__ import annotations

import pytest

from mjwalk.errors import CycleSpecError, SceneError
from mjwalk.shipped import CYCLES, SCENES, cycle_file, scene_dir, scene_file


def test_short_names_find_the_shipped_files():
    for name, file in SCENES.items():
        path = scene_file(name)
        assert path.name == file and path.is_file()
        assert path.parent == scene_dir()
    for name, file in CYCLES.items():
        assert cycle_file(name).name == file and cycle_file(name).is_file()


def test_paths_are_taken_as_they_are(tmp_path):
    own = tmp_path / "station.xml"
    own.write_text("<mujoco/>")
    assert scene_file(own) == own
    assert scene_file("some/dir/missing.xml").as_posix() == "some/dir/missing.xml"


def test_unknown_short_names_are_named_errors():
    with pytest.raises(SceneError, match=r"^stationn: no such scene file.*\(station, "):
        scene_file("stationn")
    with pytest.raises(CycleSpecError, match=r"^line: no such cycle file"):
        cycle_file("line")
