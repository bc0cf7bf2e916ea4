"""The ``train`` and ``validate`` commands' arguments (mjwalk.cli.models)."""

from __future__ import annotations

import argparse

import pytest

from mjwalk.cli import main
from mjwalk.cli.models import (
    add_train_parser,
    add_validate_parser,
    cmd_train,
    cmd_validate,
    walker_from_args,
)
from mjwalk.gait.walker import WalkerError


def _parse(argv):
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers(dest="command", required=True)
    add_train_parser(sub)
    add_validate_parser(sub)
    return parser.parse_args(argv)


def test_train_and_validate_parsers():
    a = _parse(["train", "--virtual", "3", "--pca-variance", "0.95", "-o", "m.npz"])
    assert (a.virtual, a.pca_variance, a.seed, a.func) == (3, 0.95, 0, cmd_train)
    v = _parse(["validate", "--against", "x/*.bvh", "--walker", "brisk", "--speed", "1.5"])
    assert (v.model, v.against, v.walker, v.speed, v.func) == (
        None,
        "x/*.bvh",
        "brisk",
        1.5,
        cmd_validate,
    )
    with pytest.raises(SystemExit):
        _parse(["train", "--pca-variance", "1.5", "-o", "m.npz"])


def test_walker_from_args():
    a = _parse(["validate", "--against", "x.bvh"])
    assert walker_from_args(a) is None
    w = walker_from_args(_parse(["validate", "--against", "x.bvh", "--speed", "1.1"]))
    assert w is not None and w.speed == 1.1
    brisk = walker_from_args(_parse(["validate", "--against", "x.bvh", "--walker", "brisk"]))
    assert brisk is not None and brisk.group == "brisk"
    with pytest.raises(WalkerError):
        walker_from_args(_parse(["validate", "--against", "x.bvh", "--walker", "sprinter"]))


def test_amc_without_asf_is_refused(tmp_path, capsys):
    assert main(["train", "--amc", "*.amc", "-o", str(tmp_path / "m.npz")]) == 2
    assert "mjwalk: error: train: --amc needs --asf" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())
