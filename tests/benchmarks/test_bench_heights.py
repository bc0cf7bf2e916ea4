"""benchmarks/bench_heights.py: its workplaces load, its options are checked, and a pick from a
pallet with both hands ends on the grips without contact, bending for it."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
import bench_heights as bench


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--heights", "0.05"], "heights in metres between 0.1 and 2.5, got '0.05'"),
        (["--hands", "left,feet"], "hands out of left, right, both, got 'left,feet'"),
    ],
)
def test_bad_options_stop_with_status_2(capsys, args, message):
    with pytest.raises(SystemExit) as exc:
        bench.main(args)
    assert exc.value.code == 2
    assert message in capsys.readouterr().err


def test_a_two_handed_pick_from_a_pallet_bends_onto_the_grips(capsys):
    assert bench.main(["--heights", "0.45", "--hands", "both"]) == 0
    (row,) = capsys.readouterr().out.splitlines()[1:]
    height, hand, error, contacts, duration, posture, touching = row.split()
    assert (height, hand, posture, touching) == ("0.45", "both", "bend", "-")
    assert float(error) < 10.0 and int(contacts) == 0
    assert float(duration) > 2.2  # MTM-1's bend and arise (29 + 31.9 TMU) on top of the reach


def test_a_two_handed_pick_from_a_shelf_above_the_shoulder_is_clear(capsys):
    """Box on a shelf board at 1.45 m (grips 1.55 m, above a 1.75 m operator's shoulder): the
    hands lie flat on the box's sides pointing along their approach (in and down over the
    board's front edge), so the wrists and forearms stay above the edge. With the hands
    pointing where the reach model's trajectory left them (up, towards the raised target) the
    forearms went through the edge: 48 contact frames."""
    assert bench.main(["--heights", "1.55", "--hands", "both"]) == 0
    (row,) = capsys.readouterr().out.splitlines()[1:]
    height, hand, error, contacts, _, posture, touching = row.split()
    assert (height, hand, posture, touching) == ("1.55", "both", "stand", "-")
    assert float(error) < 10.0 and int(contacts) == 0
