"""The report's figures (mjwalk.report.figures) on synthetic results with known walk lengths
and durations; the synthetic results are shared with the other report tests."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

from mjwalk.cycle.types import ArmRecord, CycleResult, CycleSpec, TaskRecord, WalkRecord
from mjwalk.errors import MjwalkError
from mjwalk.plan.walkpath import WalkPath
from mjwalk.report.figures import (
    CAPTURE_TABLE1,
    describe,
    over_takt,
    percentiles,
    report_dict,
    split_failed,
    walks_summary,
)
from mjwalk.report.files import write_report
from mjwalk.report.markdown import format_markdown, format_summary
from mjwalk.timeline import Contact
from mjwalk.world import load_workplace

SCENE = Path(__file__).resolve().parents[2] / "scenes" / "assembly_station.xml"
# (label, from, to, direction of the straight synthetic walk, mean length m, grid-A* length m)
LEGS = [
    ("T1", "stand_rack2", "stand_car1", (-0.6, 0.8), 2.4, 2.45),
    ("T2", "stand_car1", "stand_rack3", (0.6, -0.8), 2.3, 2.40),
    ("T2", "stand_rack3", "stand_car2", (-0.6, 0.8), 2.2, 2.30),
    ("T5", "stand_rack2", "stand_rack3", (1.0, 0.0), 1.1, 1.05),
]


@pytest.fixture(scope="module")
def workplace():
    return load_workplace(SCENE)


def _line(start, direction, length: float, duration: float, n: int = 40) -> WalkPath:
    s = np.linspace(0.0, length, n)
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    return WalkPath(
        t=np.linspace(0.0, duration, n),
        xy=np.asarray(start, float) + s[:, None] * d,
        yaw=np.full(n, np.arctan2(d[1], d[0])),
    )


def _results(workplace, runs: int = 12, seed: int = 3) -> list[CycleResult]:
    rng = np.random.default_rng(seed)
    spec = CycleSpec(path=Path("synthetic.toml"), scene=SCENE, start="stand_rack2", tasks=[])
    out = []
    for run in range(runs):
        t = 0.0
        tasks, walks, arms = [], [], []
        for k, (label, a, b, direction, mean, base) in enumerate(LEGS):
            length = mean + rng.normal(0.0, 0.1)
            duration = length / 1.2 + rng.normal(0.0, 0.05)
            path = _line(workplace.stations[a].xy, direction, length, duration)
            walks.append(WalkRecord(2 * k, label, a, b, path, base))
            tasks.append(TaskRecord(2 * k, "walk", b, t, t + duration, route=label))
            t += duration
            hold = 4.0 + rng.uniform(0.0, 1.0)
            tasks.append(TaskRecord(2 * k + 1, "fasten", "car_screw1", t, t + hold))
            arms.append(ArmRecord(2 * k + 1, "fasten", "car_screw1", "left", hold, 0.01 * k))
            t += hold
        contacts = [Contact(1.0, "hand_l", "car_body", 0.01, np.zeros(3)) for _ in range(run % 3)]
        out.append(CycleResult(spec, run, 100 + run, tasks, walks, arms, t, contacts))
    return out


def test_describe_matches_numpy():
    x = np.random.default_rng(0).normal(size=37)
    d = describe(x)
    q25, q50, q75 = np.percentile(x, [25, 50, 75])
    assert d["median"] == pytest.approx(q50) and d["iqr"] == pytest.approx(q75 - q25)
    assert d["sd"] == pytest.approx(np.std(x, ddof=1)) and d["n"] == 37
    assert describe([2.0])["sd"] == 0.0
    assert describe([])["n"] == 0


def test_report_figures(workplace):
    results = _results(workplace)
    rep = report_dict(results, reference=CAPTURE_TABLE1)
    assert list(rep["routes"]) == ["T1", "T2", "T5"]
    for label, e in rep["routes"].items():
        lengths = [w.length for r in results for w in r.walks if w.route == label]
        durations = [w.duration for r in results for w in r.walks if w.route == label]
        q = np.percentile(lengths, [25, 50, 75])
        assert e["length"]["median"] == pytest.approx(q[1], abs=1e-12)
        assert e["length"]["iqr"] == pytest.approx(q[2] - q[0], abs=1e-12)
        qd = np.percentile(durations, [25, 50, 75])
        assert e["duration"]["median"] == pytest.approx(qd[1], abs=1e-12)
        assert e["duration"]["iqr"] == pytest.approx(qd[2] - qd[0], abs=1e-12)
        assert e["reference"]["median"] == CAPTURE_TABLE1[label][0]
        assert e["median_error"] == pytest.approx(q[1] / CAPTURE_TABLE1[label][0] - 1)
    t2 = rep["routes"]["T2"]
    assert t2["walks"] == 24 and len(t2["directions"]) == 2
    assert t2["baseline_length"] == pytest.approx(2.35)  # median over both directions' routes
    # each direction on its own: its walks' length and duration median and IQR, its routes
    for d, (_, a, b, _, _, base) in zip(t2["directions"], LEGS[1:3], strict=True):
        assert (d["from"], d["to"], d["walks"]) == (a, b, 12)
        ws = [w for r in results for w in r.walks if (w.start_site, w.goal_site) == (a, b)]
        q = np.percentile([w.length for w in ws], [25, 50, 75])
        qd = np.percentile([w.duration for w in ws], [25, 50, 75])
        assert d["length"]["median"] == pytest.approx(q[1], abs=1e-12)
        assert d["length"]["iqr"] == pytest.approx(q[2] - q[0], abs=1e-12)
        assert d["duration"]["median"] == pytest.approx(qd[1], abs=1e-12)
        assert d["duration"]["iqr"] == pytest.approx(qd[2] - qd[0], abs=1e-12)
        assert d["baseline_length"] == pytest.approx(base)
        # its spread against the route's captured IQR (the source pools the directions)
        assert d["iqr_ratio"] == pytest.approx((q[2] - q[0]) / CAPTURE_TABLE1["T2"][1])
        # vs A*: the median of each walk's own ratio
        assert d["length_vs_baseline"] == pytest.approx(
            np.median([w.length / base - 1 for w in ws])
        )
    assert [len(e["directions"]) for e in rep["routes"].values()] == [1, 2, 1]
    md = format_markdown(rep)
    assert "| T2 | stand_car1 -> stand_rack3 | 12 | 2.40 |" in md
    assert "| T2 | stand_rack3 -> stand_car2 | 12 | 2.30 |" in md
    assert "| T2 | both | 24 | 2.35 |" in md  # the pooled line of a route walked both ways
    for d in t2["directions"]:  # a direction's own IQR ratio, in brackets on its row
        line = next(x for x in md.splitlines() if f"| {d['from']} -> {d['to']} |" in x)
        assert f"| ({100 * d['iqr_ratio']:.0f} %) |" in line
    assert "| T1 | both |" not in md  # a route walked one way has its one line
    assert rep["routes"]["T5"]["baseline_length"] == pytest.approx(1.05)
    cycle = [r.cycle_time for r in results]
    assert rep["cycle_time"]["median"] == pytest.approx(np.median(cycle))
    assert rep["cycle_time"]["sd"] == pytest.approx(np.std(cycle, ddof=1))
    assert rep["cycle_time"]["min"] == min(cycle) and rep["cycle_time"]["max"] == max(cycle)
    assert rep["collisions"]["total"] == sum(r % 3 for r in range(12)) == 12
    assert rep["collisions"]["runs_with_collisions"] == 8
    assert rep["collisions"]["by_pair"] == {"hand_l vs car_body": 12}
    assert set(rep["task_time"]) == {"walk", "fasten"}
    fasten = rep["task_time"]["fasten"]
    assert fasten["count_per_cycle"] == 4
    assert 4.0 <= fasten["task"]["min"] and fasten["task"]["max"] <= 5.0
    walk_total = [sum(w.duration for w in r.walks) for r in results]
    assert rep["task_time"]["walk"]["per_cycle"]["median"] == pytest.approx(np.median(walk_total))
    assert rep["arms"]["max_hand_error"] == pytest.approx(0.03)
    # hands 2 and 3 cm off (legs 2 and 3 of each run) are short of their target, 1 cm is on it
    short = rep["arms"]["short_of_target"]
    assert short["motions"] == 2 * 12 and short["sites"] == {"car_screw1": 24}
    assert short["max_error"] == pytest.approx(0.03)
    assert "WARNING: 24 of 48 arm motion(s) ended more than 10 mm" in format_summary(rep)
    assert "max 30 mm" in format_markdown(rep)


def test_no_results():
    with pytest.raises(MjwalkError, match="no cycle results"):
        report_dict([])


def _failed(spec: CycleSpec, run: int) -> CycleResult:
    return CycleResult(
        spec, run, 7, [], [], [], float("nan"), entropy=[7, run], error="PlanningError: boxed in"
    )


def test_failed_runs_are_listed_apart(tmp_path, workplace):
    ok = _results(workplace, runs=6)
    mixed = ok[:3] + [_failed(ok[0].spec, 6)] + ok[3:]
    rep = report_dict(mixed)
    # the figures are those of the simulated runs alone, the failure listed with its seed
    assert rep == {**report_dict(ok), "failed_runs": rep["failed_runs"]}
    assert rep["failed_runs"] == [
        {"run": 6, "entropy": [7, 6], "error": "PlanningError: boxed in", "operator": None}
    ]
    assert "FAILED run 6" in format_summary(rep)
    files = write_report(mixed, tmp_path, workplace=workplace, baseline={})
    assert "run 6: PlanningError: boxed in" in files["markdown"].read_text()
    rows = list(csv.DictReader(files["cycles"].open()))
    assert [r["run"] for r in rows] == [str(r.run) for r in ok]
    with pytest.raises(MjwalkError, match=r"all 2 run\(s\) failed.*run 6.*boxed in"):
        report_dict([_failed(ok[0].spec, 6), _failed(ok[0].spec, 7)])


def test_simulate_cycles_records_a_failed_run(monkeypatch, scenes_dir):
    """``on_error="record"`` (the CLI's choice) keeps a batch going past an unplannable run;
    the default re-raises it."""
    import mjwalk.cycle.simulate as sim
    from mjwalk.errors import PlanningError

    real = sim.simulate_cycle

    def flaky(ctx, rng, *, run=0, **kw):
        if run == 1:
            raise PlanningError("no walk from stand_car1 to stand_rack3")
        return real(ctx, rng, run=run, **kw)

    monkeypatch.setattr(sim, "simulate_cycle", flaky)
    spec = scenes_dir / "assembly_station.toml"
    res = sim.simulate_cycles(spec, runs=3, seed=5, collisions=False, on_error="record")
    assert [r.error is None for r in res] == [True, False, True]
    bad = res[1]
    assert bad.entropy == [5, 1] and np.isnan(bad.cycle_time) and not bad.walks
    assert "no walk from stand_car1" in bad.error
    # the failed run's operator is the one the run drew (same as its own simulation would)
    assert bad.operator is not None and bad.operator.group
    assert report_dict(res)["runs"] == 2
    with pytest.raises(PlanningError):
        sim.simulate_cycles(spec, runs=3, seed=5, collisions=False)
    with pytest.raises(MjwalkError, match="on_error"):
        sim.simulate_cycles(spec, runs=3, on_error="ignore")


def test_a_walk_shorter_than_the_grid_allows_is_counted(workplace):
    """A walk 20 % shorter than its own grid-A* route is below what the grid's
    discretisation allows (about -9 %): the report counts it and says so."""
    results = _results(workplace, runs=4)
    assert report_dict(results)["routes"]["T5"]["below_floor"] == 0
    walk = results[0].walks[3]
    results[0].walks[3] = WalkRecord(
        walk.task, walk.route, walk.start_site, walk.goal_site, walk.path, walk.length / 0.8
    )
    rep = report_dict(results)
    assert rep["routes"]["T5"]["directions"][0]["below_floor"] == 1
    assert rep["routes"]["T5"]["below_floor"] == 1
    assert rep["routes"]["T5"]["vs_baseline"]["min"] == pytest.approx(-0.2)
    below = sum(d["below_floor"] for e in rep["routes"].values() for d in e["directions"])
    assert f"{below} walk(s) below the bound" in format_markdown(rep)


def test_walks_summary_is_describe_of_each_figure(workplace):
    paths = [_line((0.0, 0.0), (1.0, 0.0), 1.0 + 0.1 * k, 1.0 + 0.2 * k) for k in range(5)]
    for k, p in enumerate(paths):
        p.meta["seconds"] = 0.01 * (k + 1)
    s = walks_summary(paths)
    assert s["length"] == describe([p.length for p in paths])
    assert s["length"]["median"] == pytest.approx(1.2, abs=0.02)
    assert s["duration"]["median"] == pytest.approx(1.4)
    assert s["planning_ms"]["median"] == pytest.approx(30.0) and s["planning_ms"]["iqr"] == 20.0


def test_percentiles_and_over_takt():
    x = np.arange(1.0, 101.0)
    p = percentiles(x)
    assert p["n"] == 100 and p["p50"] == pytest.approx(50.5) and p["p5"] < p["p95"]
    assert np.isnan(percentiles([])["p50"])
    o = over_takt(x, takt=90.0)
    assert (o["runs"], o["over"], o["share"]) == (100, 10, 0.1)
    assert o["ci_low"] < 0.1 < o["ci_high"] and o["confidence"] == 0.95
    assert np.isnan(over_takt([], 1.0)["share"])


def test_split_failed_keeps_order(workplace):
    ok = _results(workplace, runs=3)
    bad = _failed(ok[0].spec, 9)
    good, failed = split_failed([ok[0], bad, ok[1], ok[2]])
    assert [r.run for r in good] == [0, 1, 2] and failed == [bad]
