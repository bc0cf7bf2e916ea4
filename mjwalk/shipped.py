"""The scenes and cycle specifications shipped with mjwalk, found by short name.

They live in the repository's top-level ``scenes/`` folder; a wheel (or ``pip install .``)
carries the same files as package data in ``mjwalk/scenes/`` (copied there by the build step
in ``setup.py``), so ``mjwalk simulate station`` and ``load_workplace(scene_file("corridor"))``
work from any folder whichever way mjwalk was installed.
"""

from __future__ import annotations

import os
from pathlib import Path

from mjwalk.errors import CycleSpecError, SceneError

#: Short names of the shipped MJCF scenes -> file names.
SCENES = {
    "station": "assembly_station.xml",
    "assembly_station": "assembly_station.xml",
    "corridor": "corridor.xml",
    "open_floor": "open_floor.xml",
    "multilevel": "multilevel_station.xml",
    "multilevel_station": "multilevel_station.xml",
    "pit": "pit_station.xml",
    "pit_station": "pit_station.xml",
}
#: Short names of the shipped cycle specifications -> file names.
CYCLES = {
    "station": "assembly_station.toml",
    "assembly_station": "assembly_station.toml",
    "multilevel": "multilevel_station.toml",
    "multilevel_station": "multilevel_station.toml",
    "multilevel_platform": "multilevel_platform.toml",
    "pit": "pit_station.toml",
    "pit_station": "pit_station.toml",
}


def scene_dir() -> Path:
    """The folder of the shipped scenes.

    Returns:
        ``mjwalk/scenes`` in an installed wheel, else the checkout's top-level ``scenes/`` (a
        source tree or an editable install).

    Raises:
        SceneError: when neither folder holds the shipped scenes.
    """
    here = Path(__file__).resolve().parent
    for folder in (here / "scenes", here.parent / "scenes"):
        if (folder / "assembly_station.xml").is_file():
            return folder
    raise SceneError(
        f"the shipped scenes are missing (looked in {here / 'scenes'} and "
        f"{here.parent / 'scenes'}): reinstall mjwalk"
    )


def _resolve(name: str | os.PathLike, table: dict[str, str], what: str, error) -> Path:
    path = Path(name)
    if path.is_file() or str(name) not in table:
        if not path.exists() and path.suffix == "" and path.parent == Path("."):
            raise error(
                f"{name}: no such {what} file, and not the name of a shipped {what} "
                f"({', '.join(table)})"
            )
        return path
    return scene_dir() / table[str(name)]


def scene_file(name: str | os.PathLike) -> Path:
    """An MJCF scene path from a path or a shipped scene's short name.

    Args:
        name: a file path, or a short name of :data:`SCENES` (``"station"``, ``"corridor"``...).

    Returns:
        ``name`` itself when such a file exists (or it looks like a path), else the shipped
        scene of that short name.

    Raises:
        SceneError: ``name`` is neither an existing file nor a shipped scene's name.
    """
    return _resolve(name, SCENES, "scene", SceneError)


def cycle_file(name: str | os.PathLike) -> Path:
    """A cycle specification path from a path or a shipped cycle's short name.

    Args:
        name: a file path, or a short name of :data:`CYCLES` (``"station"``).

    Returns:
        ``name`` itself when such a file exists (or it looks like a path), else the shipped
        cycle of that short name.

    Raises:
        CycleSpecError: ``name`` is neither an existing file nor a shipped cycle's name.
    """
    return _resolve(name, CYCLES, "cycle", CycleSpecError)
