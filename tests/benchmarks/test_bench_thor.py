"""benchmarks/bench_thor.py: its measures on made-up walks, its options, and a short run on the
THÖR walks (skipped without the shared data)."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from mjwalk.world.footprint import Footprint

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
import bench_thor as bench


def test_a_straight_walk_measures_as_its_chord():
    lo, hi = np.array([0.0, 0.0]), np.array([6.0, 0.0])
    xy = np.column_stack([np.linspace(1.0, 5.0, 11), np.full(11, 0.3)])
    m = bench.measure(xy, lo, hi, obstacle=np.array([3.0, 0.0]))
    assert m["length"] == pytest.approx(4.0) and m["excess"] == pytest.approx(0.0, abs=1e-12)
    assert m["lateral"] == pytest.approx(0.3) and m["duration"] == pytest.approx(4.0)
    assert m["left"]  # passes the obstacle on its left (+y of lo -> hi)


def test_the_excess_is_split_by_thirds_of_the_chord_and_by_scale():
    """A walk with one sideways jog of 0.3 m in its first third: all its excess lies in that
    third, and a walk wavering 5 cm from sample to sample loses most of its excess to a
    further 1.2 s moving average, a single smooth bow little of it."""
    xy = np.column_stack([np.arange(0.0, 6.01, 0.5), np.zeros(13)])
    xy[2, 1] = 0.3  # x = 1.0 m of 6 m: the first third
    first, middle, last = bench.excess_thirds(xy)
    assert first == pytest.approx(2 * (np.hypot(0.5, 0.3) - 0.5))
    assert middle == pytest.approx(0.0, abs=1e-12) and last == pytest.approx(0.0, abs=1e-12)
    x = np.linspace(0.0, 6.0, 31)
    wavy = np.column_stack([x, 0.05 * (-1.0) ** np.arange(31)])
    wavy[[0, -1], 1] = 0.0
    bow = np.column_stack([x, 0.3 * np.sin(np.pi * x / 6.0)])
    for xy, kept in ((wavy, 0.2), (bow, 0.8)):
        whole = float(np.hypot(*np.diff(xy, axis=0).T).sum() - 6.0)
        share = bench.smoothed_excess(xy, 3) / whole
        assert share < kept if kept < 0.5 else share > kept


def test_a_walk_is_cut_from_its_last_sample_in_the_start_zone_to_its_first_in_the_goal():
    xy = np.column_stack([np.arange(-1.0, 8.01, 0.5), np.zeros(19)])
    out = bench.cut(xy, np.array([0.0, 0.0]), np.array([7.0, 0.0]), 1.25)
    assert out is not None and out[0, 0] == 1.0 and out[-1, 0] == 6.0


def test_the_crossing_duration_places_each_zone_crossing_between_its_samples():
    """A walk at 1 m/s sampled at 2.5 Hz (0.4 m apart) from 1.25 m zones about (0, 0) and
    (7, 0): it leaves the start zone at x = 1.25 and enters the goal zone at x = 5.75, 4.5 s
    apart, whatever the phase of its samples; the issue's whole-sample duration is 4.4 or
    4.8 s."""
    a, b = np.array([0.0, 0.0]), np.array([7.0, 0.0])
    for phase in (0.0, 0.13, 0.29):
        x = np.arange(-0.5 + phase, 8.0, 0.4)
        xy = bench.cut(np.column_stack([x, np.zeros_like(x)]), a, b, 1.25)
        assert xy is not None
        assert bench.crossing_duration(xy, a, b, 1.25) == pytest.approx(4.5, abs=1e-9)
        assert bench.measure(xy, a, b, np.array([3.0, 2.0]))["duration"] in (
            pytest.approx(4.4),
            pytest.approx(4.8),
        )


def test_a_chord_passing_the_obstacle_within_the_berth_counts_as_on_it():
    """A pillar of 0.2 m radius 0.5 m off a 6 m chord: its surface 0.3 m from it, within a
    walker's berth at 1.2 m/s (about 0.47 m: half of 0.45 m shoulders plus the speed-scaled
    0.30 m gap); 1.5 m off, beyond it."""
    s, g = np.array([0.0, 0.0]), np.array([6.0, 0.0])
    near = Footprint("p", 0, np.array([[3.0, 0.5], [3.0, 0.5]]), 0.2)
    far = Footprint("p", 0, np.array([[3.0, 1.5], [3.0, 1.5]]), 0.2)
    assert bench.on_chord(near, s, g, 1.2)
    assert not bench.on_chord(far, s, g, 1.2)


def test_the_guide_excess_is_nil_for_aligned_ends_and_grows_with_their_angle():
    """The minimum-jerk guide between ends heading along their chord is the chord (no
    excess); with both ends 10 deg off it in a bow, a few centimetres over the 5 m between
    the zones, more uncut between the same ends than cut at the 1.25 m zones."""
    a, b = np.array([0.0, 0.0]), np.array([7.5, 0.0])
    s, g = np.array([0.25, 0.0]), np.array([7.25, 0.0])
    along = np.array([1.0, 0.0])
    assert bench.guide_excess(s, g, along, along, 1.2, (a, b, 1.25)) == pytest.approx(0, abs=1e-9)
    t = np.radians(10.0)
    head, tail = np.array([np.cos(t), np.sin(t)]), np.array([np.cos(t), -np.sin(t)])
    cut = bench.guide_excess(s, g, head, tail, 1.2, (a, b, 1.25))
    whole = bench.guide_excess(s, g, head, tail, 1.2, None)
    assert 0.005 < cut < whole < 0.2, (cut, whole)


def test_bad_options_stop_with_status_2(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        bench.main(["--data", str(tmp_path)])
    assert exc.value.code == 2
    assert "no THÖR data" in capsys.readouterr().err


@pytest.mark.slow  # among the fast tier's 4 longest (84-222 s in a loaded run): its 5 min budget
def test_a_short_run_reproduces_the_real_figures(shared_data, capsys):
    """Pair 1-5's real walks measured as the data's README states (median path 4.07 m), and
    planned walks between their ends."""
    data = shared_data / "thor-exp12"
    if not data.is_dir():
        pytest.skip("no thor-exp12 in the shared data")
    assert bench.main(["--data", str(data), "--pairs", "1-5", "--walks-per", "1"]) == 0
    out = capsys.readouterr().out
    row = next(line for line in out.splitlines() if line.startswith("1-5 "))
    real_len, planned_len = (v.strip("|") for v in row.split()[1:3])
    assert float(real_len) == pytest.approx(4.07, abs=0.01)
    assert 3.0 < float(planned_len) < 5.0
    assert "1-5: 11 real, 11 planned, 0 failed" in out
