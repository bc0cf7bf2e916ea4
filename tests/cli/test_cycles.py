"""The ``simulate`` command's arguments (mjwalk.cli.cycles)."""

from __future__ import annotations

import argparse
from pathlib import Path

from mjwalk.cli import main
from mjwalk.cli.cycles import add_simulate_parser, cmd_simulate


def _parse(argv):
    parser = argparse.ArgumentParser()
    add_simulate_parser(parser.add_subparsers(dest="command", required=True))
    return parser.parse_args(argv)


def test_simulate_parser():
    a = _parse(["simulate", "station", "--export", "bvh", "--export", "csv"])
    assert (a.runs, a.out, a.seed, a.jobs, a.only_run) == (50, Path("out"), 0, -1, None)
    assert a.export == ["bvh", "csv"] and not a.video and a.func is cmd_simulate


def test_only_run_out_of_range_is_refused(tmp_path, capsys):
    out = tmp_path / "out"
    argv = ["simulate", "station", "--runs", "3", "--only-run", "3", "--out", str(out)]
    assert main(argv) == 2
    assert "--only-run 3: runs are numbered 0 to 2 (--runs 3)" in capsys.readouterr().err
    assert not out.exists()


def test_dry_run_checks_and_simulates_nothing(scenes_dir, tmp_path, capsys):
    out = tmp_path / "out"
    spec = scenes_dir / "assembly_station.toml"
    assert main(["simulate", str(spec), "--runs", "2", "--out", str(out), "--dry-run"]) == 0
    printed = capsys.readouterr().out
    assert "2 runs, seed 0" in printed and "nothing simulated (--dry-run)" in printed
    assert not out.exists() or not list(out.iterdir())
