"""Shared conventions: side names and their one-letter MJCF prefixes."""

from __future__ import annotations

import pytest

from mjwalk.conventions import SIDES, other_side, side_of_prefix, side_prefix


def test_side_prefixes_round_trip():
    assert [side_prefix(s) for s in SIDES] == ["l", "r"]
    for s in SIDES:
        assert side_of_prefix(side_prefix(s)) == s
        assert other_side(other_side(s)) == s
    assert other_side("left") == "right"


@pytest.mark.parametrize("bad", ["Left", "l", ""])
def test_bad_side_names_are_refused(bad):
    with pytest.raises(ValueError, match="side must be 'left' or 'right'"):
        side_prefix(bad)
    with pytest.raises(ValueError, match="side prefix must be 'l' or 'r'"):
        side_of_prefix(bad.upper() or "x")
