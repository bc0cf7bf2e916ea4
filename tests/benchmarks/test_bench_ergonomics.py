"""benchmarks/bench_ergonomics.py: its measures on made-up reaches, its options, and a short
run on the shared raise-hand clips (skipped without the shared data)."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
bench = pytest.importorskip("bench_ergonomics")


def _reach(elevation, trunk):
    e = np.asarray(elevation, dtype=float)
    return bench.Reach(3, 2, e, e.copy(), np.asarray(trunk, dtype=float))


def test_the_reach_ends_at_the_first_frame_of_the_hold():
    out = np.linspace(0.0, 1.0, 7)[:, None] * np.ones((1, 4))
    frames = np.vstack([out, np.repeat(out[-1:], 6, axis=0), out[::-1]])
    assert bench.reach_end(frames, 6) == 6


def test_reaches_of_other_lengths_are_compared_at_equal_steps_of_their_time():
    """A capture of 31 frames and a reproduction of 11 along the same ramp 0-90 deg agree at
    every step; a reproduction 5 deg higher differs by 5 deg everywhere."""
    cap = _reach(np.linspace(0.0, 90.0, 31), np.zeros(31))
    same = _reach(np.linspace(0.0, 90.0, 11), np.full(11, 2.0))
    d = bench.differences(cap, same)
    assert np.allclose(d["elevation reach"], 0.0) and d["elevation end"] == pytest.approx(0.0)
    assert np.allclose(d["trunk_flexion reach"], 2.0) and len(d["elevation reach"]) == 21
    higher = _reach(np.linspace(5.0, 95.0, 11), np.zeros(11))
    a = bench.agreement([bench.differences(cap, higher), bench.differences(cap, same)])
    assert a["elevation end"]["median"] == pytest.approx(2.5)  # |5| and |0|
    assert a["elevation reach"]["p25"] == pytest.approx(0.0)
    assert a["elevation reach"]["p75"] == pytest.approx(5.0) and a["elevation reach"]["n"] == 42


def test_bad_options_stop_with_status_2(tmp_path, capsys):
    assert bench.main(["--data", str(tmp_path), "--stride", "0"]) == 2
    assert "--stride and --max-clips must be >= 1" in capsys.readouterr().err


def test_a_short_run_measures_the_angles_on_capture_and_reproduction(shared_data, capsys):
    """Every 32nd clip of each arm (all four styles): the upper arm's elevation at the reach's
    end within the issue's 10 deg (median |difference|; 5.9 deg on all 512 clips) and the trunk's
    flexion within 5 deg (2.6 deg on all clips: the actors lean back a little, the humanoid
    stands upright)."""
    if not (shared_data / "bandai-raise-hand").is_dir():
        pytest.skip("no bandai-raise-hand in the shared data")
    assert bench.main(["--data", str(shared_data), "--stride", "32"]) == 0
    out = capsys.readouterr().out

    def median(what: str) -> float:
        m = re.search(rf"{what}: ([\d.]+) \(([\d.]+)-([\d.]+)\)", out)
        assert m, out
        lo, hi = float(m.group(2)), float(m.group(3))
        assert lo <= float(m.group(1)) <= hi, out  # the IQR holds the median
        return float(m.group(1))

    assert median(r"elevation \(from the vertical\), at the reach's end") <= 10.0, out
    assert median(r"trunk flexion, at the reach's end") <= 5.0, out
    assert median(r"elevation \(from the vertical\), over the whole reach") > 0.0, out
    assert "target <= 10: met" in out and "by style" in out
