"""Adding an ergonomic method is one Score subclass and one registry entry: a toy method (the
share of time an upper arm is raised above the shoulder) registered at run time is scored with
a simulated cycle and lands in ergonomics.csv, report.json and report.md; removed, it is gone."""

from __future__ import annotations

import csv
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mjwalk.cycle.simulate import prepare, simulate_cycle
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.ergonomics.angles import BodyAngles
from mjwalk.ergonomics.registry import SCORES, ScoreRegistryError, register
from mjwalk.ergonomics.results import RunErgonomics
from mjwalk.ergonomics.score import Column, Score, ScoreContext, TaskSpan, fmt, percentiles
from mjwalk.ergonomics.summary import CSV_COLUMNS, csv_header
from mjwalk.report import write_report

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "benchmarks"))
import bench_heights  # noqa: E402

#: An upper arm elevated beyond this (deg) is above the shoulder (horizontal).
ABOVE_DEG = 90.0


class AboveShoulder(Score):
    """The share of frames with an upper arm raised above the horizontal (either arm)."""

    name = "above_shoulder"
    source = "toy: upper-arm elevation above 90 deg"
    columns = (Column("above_shoulder_share", lambda run, t: f"{t.extra['above_shoulder']:.3f}"),)
    table = (Column("above shoulder P95", lambda s: fmt(s["above_shoulder"]["p95"], 2)),)

    def per_frame(self, ang: BodyAngles, ctx: ScoreContext) -> np.ndarray:
        return (ang.upper_arm_elevation > ABOVE_DEG).any(axis=1)

    def per_task(self, frames: np.ndarray, span: TaskSpan, ctx: ScoreContext) -> dict[str, Any]:
        return {"above_shoulder": float(frames[span.start : span.end].mean())}

    def per_run(self, frames: np.ndarray, ang: BodyAngles, ctx: ScoreContext) -> dict[str, Any]:
        return {"above_shoulder": float(frames.mean())}

    def stats(self, runs: Sequence[RunErgonomics]) -> dict[str, Any]:
        return {"above_shoulder": percentiles([r.extra["above_shoulder"] for r in runs])}

    def notes(self, stats: dict[str, Any]) -> list[str]:
        return [f"Arms above the shoulder: P50 {fmt(stats['above_shoulder']['p50'], 2)}.", ""]


@pytest.fixture
def toy():
    score = register(AboveShoulder())
    try:
        yield score
    finally:
        SCORES.pop(score.name)


def test_a_registered_score_reaches_the_csv_and_the_report(tmp_path, toy):
    """A pick from a 1.85 m shelf (1.75 m operator): the reaching arm goes above the shoulder."""
    spec = load_cycle_spec(bench_heights.write_workplace(tmp_path, 1.85, "left"))
    res = simulate_cycle(prepare(spec), rng=0, collisions=False)
    ergo = res.ergonomics
    assert ergo is not None and list(SCORES)[-1] == "above_shoulder"
    (pick,) = [t for t in ergo.tasks if t.kind == "pick"]
    assert 0.0 < pick.extra["above_shoulder"] <= 1.0
    assert 0.0 < ergo.extra["above_shoulder"] <= pick.extra["above_shoulder"]
    assert 1 <= pick.rula <= 7 and ergo.rula.shape == ergo.reba.shape  # built-ins as before

    files = write_report([res], tmp_path / "out", baseline={})
    rows = list(csv.DictReader(files["ergonomics_csv"].open()))
    assert list(rows[0]) == [*CSV_COLUMNS, "above_shoulder_share"]
    cell = next(r for r in rows if r["kind"] == "pick")["above_shoulder_share"]
    assert cell == f"{pick.extra['above_shoulder']:.3f}"
    rep = json.loads(files["json"].read_text())["ergonomics"]
    assert rep["methods"]["above_shoulder"] == AboveShoulder.source
    assert rep["overall"]["above_shoulder"]["p50"] == pytest.approx(ergo.extra["above_shoulder"])
    md = files["markdown"].read_text()
    assert "| ISO 11226 not acc. | above shoulder P95 |" in md
    assert f"Arms above the shoulder: P50 {ergo.extra['above_shoulder']:.2f}." in md


def test_removed_it_is_gone_and_names_are_checked(toy):
    assert csv_header()[-1] == "above_shoulder_share"
    with pytest.raises(ScoreRegistryError, match="'above_shoulder' is empty or taken"):
        register(AboveShoulder())

    class Clash(Score):
        name = "clash"
        columns = (Column("rula_peak", lambda run, t: 0),)

    with pytest.raises(ScoreRegistryError, match=r"'clash': columns taken: \['rula_peak'\]"):
        register(Clash())
    assert "clash" not in SCORES
    SCORES.pop(toy.name)
    try:
        assert tuple(csv_header()) == CSV_COLUMNS and "above_shoulder" not in SCORES
    finally:
        SCORES[toy.name] = toy  # the fixture removes it
