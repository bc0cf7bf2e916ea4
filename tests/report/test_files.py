"""The report's files (mjwalk.report.files): all written, or none."""

from __future__ import annotations

import csv
import json

import imageio.v3 as iio
import numpy as np
import pytest
from test_figures import LEGS, _line, _results

from mjwalk.errors import MjwalkError
from mjwalk.report.figures import CAPTURE_TABLE1
from mjwalk.report.files import REPORT_FILES, write_report
from mjwalk.report.markdown import format_summary
from mjwalk.world import load_workplace


@pytest.fixture(scope="module")
def workplace():
    from test_figures import SCENE

    return load_workplace(SCENE)


def test_write_report_files(tmp_path, workplace):
    results = _results(workplace)
    baseline = {
        ("stand_rack2", "stand_car1"): _line(
            workplace.stations["stand_rack2"].xy, (-0.6, 0.8), 2.45, 1.0
        ),
        "T5": [_line(workplace.stations["stand_rack2"].xy, (1, 0), 1.05, 1.0)],
    }
    files = write_report(
        results, tmp_path / "out", workplace=workplace, baseline=baseline, reference=CAPTURE_TABLE1
    )
    assert set(files) == set(REPORT_FILES)
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == sorted(REPORT_FILES.values())
    rep = json.loads(files["json"].read_text())
    lengths = [w.length for r in results for w in r.walks if w.route == "T1"]
    q = np.percentile(lengths, [25, 50, 75])
    assert rep["routes"]["T1"]["length"]["median"] == pytest.approx(q[1], abs=1e-12)
    assert rep["routes"]["T1"]["length"]["iqr"] == pytest.approx(q[2] - q[0], abs=1e-12)
    with open(files["walks"]) as fh:
        walks = list(csv.DictReader(fh))
    assert len(walks) == 12 * len(LEGS)
    assert float(walks[0]["length_m"]) == pytest.approx(results[0].walks[0].length, abs=1e-4)
    with open(files["cycles"]) as fh:
        cycles = list(csv.DictReader(fh))
    assert len(cycles) == 12
    assert [int(c["collisions"]) for c in cycles] == [r % 3 for r in range(12)]
    assert float(cycles[5]["fasten_time_s"]) == pytest.approx(
        sum(t.duration for t in results[5].tasks if t.kind == "fasten"), abs=1e-4
    )
    md = files["markdown"].read_text()
    assert "| T1 | stand_rack2 -> stand_car1 | 12 | 2.45 |" in md
    assert "## Cycle time" in md and "capture 50th" in md
    for key in ("spaghetti", "histograms"):
        img = iio.imread(files[key])
        assert img.ndim == 3 and img.shape[0] > 200 and img.shape[1] > 300
        assert img[..., :3].std() > 10  # not blank
    summary = format_summary(rep)
    assert "T5" in summary and "cycle time" in summary and "12 run(s)" in summary


def test_no_half_written_files(tmp_path, workplace, monkeypatch):
    results = _results(workplace, runs=3)

    def broken(*args, **kwargs):
        raise RuntimeError("disk full")

    import mjwalk.render.plot

    monkeypatch.setattr(mjwalk.render.plot, "histograms_png", broken)
    out = tmp_path / "out"
    with pytest.raises(RuntimeError, match="disk full"):
        write_report(results, out, workplace=workplace)
    assert not out.exists() or list(out.iterdir()) == []  # neither targets nor temporary files


def test_baseline_must_be_paths(tmp_path, workplace):
    results = _results(workplace, runs=2)
    with pytest.raises(MjwalkError, match=r"baseline\[\('a', 'b'\)\] must be a WalkPath"):
        write_report(results, tmp_path / "out", workplace=workplace, baseline={("a", "b"): 2.4})
    assert not (tmp_path / "out").exists() or list((tmp_path / "out").iterdir()) == []


def test_station_walks_per_direction_against_their_own_grid_route(tmp_path, scenes_dir):
    """Three runs of the station's cycle: report.json gives each direction of a route its
    length and duration median and IQR (T2 and T3 are walked there and back, each pooled too);
    every walk is compared with the grid-A* route between its own two ends, and no walk reads
    lower than the grid's discretisation allows (:func:`~mjwalk.plan.grid.shortfall_bound`:
    about -9 % for these 1-4 m walks on 8 cm cells)."""
    from mjwalk.cycle.simulate import simulate_cycles
    from mjwalk.plan.grid import shortfall_bound

    results = simulate_cycles(
        scenes_dir / "assembly_station.toml", runs=3, seed=2, collisions=False
    )
    files = write_report(results, tmp_path / "out")
    rep = json.loads(files["json"].read_text())
    expected = {
        "T1": [("stand_rack2", "stand_car1")],
        "T2": [("stand_car1", "stand_rack3"), ("stand_rack3", "stand_car2")],
        "T3": [("stand_car2", "stand_rack1"), ("stand_rack1", "stand_car3")],
        "T4": [("stand_car3", "stand_rack2")],
        "T5": [("stand_rack2", "stand_rack3")],
    }
    assert {
        k: [(d["from"], d["to"]) for d in e["directions"]] for k, e in rep["routes"].items()
    } == expected
    for label, e in rep["routes"].items():
        assert e["walks"] == 3 * len(expected[label])
        for d in e["directions"]:
            assert d["walks"] == 3
            for key in ("length", "duration"):
                assert d[key]["median"] > 0 and d[key]["iqr"] >= 0
            assert d["without_baseline"] == 0 and d["below_floor"] == 0
            assert d["vs_baseline"]["min"] >= d["vs_baseline_floor"]
    assert rep["baseline"]["between"].startswith("each walk's own start and end")
    # the baseline joins the walk's own ends
    for r in results:
        for w in r.walks:
            assert w.baseline is not None
            np.testing.assert_array_equal(w.baseline.xy[0], w.path.xy[0])
            np.testing.assert_array_equal(w.baseline.xy[-1], w.path.xy[-1])
            assert w.baseline_length >= np.linalg.norm(w.path.xy[-1] - w.path.xy[0]) - 1e-9
    rows = list(csv.DictReader(files["walks"].open()))
    assert len(rows) == 3 * 7
    for row in rows:
        base, vs = float(row["baseline_length_m"]), float(row["vs_baseline"])
        assert vs == pytest.approx(float(row["length_m"]) / base - 1, abs=1e-4)
        assert vs >= shortfall_bound(base) - 1e-4, row  # within the grid's discretisation
    md = files["markdown"].read_text()
    assert "| T2 | both | 6 |" in md and "every walk within the grid's discretisation" in md


def test_a_report_given_its_figures_writes_the_same_files(tmp_path, workplace):
    """``mjwalk simulate`` computes report_dict once and hands it to write_report: the files
    are byte for byte those write_report writes computing it itself."""
    from mjwalk.report.figures import report_dict

    results = _results(workplace)
    own = write_report(results, tmp_path / "own", workplace=workplace, baseline={})
    given = write_report(
        results, tmp_path / "given", workplace=workplace, baseline={}, report=report_dict(results)
    )
    for key, path in own.items():
        assert path.read_bytes() == given[key].read_bytes(), key
