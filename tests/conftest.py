"""Shared fixtures: scene paths and the optional real-capture folder."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

os.environ.setdefault("MUJOCO_GL", "egl")

ROOT = Path(__file__).resolve().parents[1]
SCENES = ROOT / "scenes"
SHARED_DATA = ROOT.parent / "shared" / "data"


@pytest.fixture(scope="session")
def scenes_dir() -> Path:
    return SCENES


@pytest.fixture(scope="session")
def shared_data() -> Path:
    if not SHARED_DATA.is_dir():
        pytest.skip("../shared/data (real motion capture) is not present on this machine")
    return SHARED_DATA
