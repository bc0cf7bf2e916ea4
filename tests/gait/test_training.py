"""Train and validate step models from files (mjwalk.gait.training): the checks before work."""

from __future__ import annotations

import pytest

from mjwalk.errors import InputError, MjwalkError
from mjwalk.gait.training import CaptureFiles, train_model_file, validate_model_file


def test_capture_files_of_a_glob():
    amc = CaptureFiles.of_glob("walks/*.AMC", asf="s.asf", skeleton="cmu")
    assert (amc.bvh, amc.amc, amc.asf, amc.skeleton) == (None, "walks/*.AMC", "s.asf", "cmu")
    bvh = CaptureFiles.of_glob("walks/*.bvh", asf="s.asf")
    assert (bvh.bvh, bvh.amc, bvh.asf) == ("walks/*.bvh", None, None)  # ASF for AMC only
    assert CaptureFiles().load() == []


def test_entry_points_errors(tmp_path):
    with pytest.raises(MjwalkError, match="give a BVH glob"):
        train_model_file(tmp_path / "m.npz")
    with pytest.raises(InputError, match=r"variance to keep must be in \(0, 1\]"):
        train_model_file(tmp_path / "m.npz", virtual=2, variance=1.5)
    with pytest.raises(MjwalkError, match="no BVH files match"):
        train_model_file(tmp_path / "m.npz", CaptureFiles(bvh=str(tmp_path / "*.bvh")))
    with pytest.raises(MjwalkError, match="no BVH files match"):
        validate_model_file(None, CaptureFiles.of_glob(str(tmp_path / "*.bvh")))
    assert not (tmp_path / "m.npz").exists()
