"""mjwalk.cycle.specfile: the lines of a cycle file's keys and tables, the checker's errors
that cite them, and the size limits read before anything else."""

from __future__ import annotations

from pathlib import Path

import pytest

from mjwalk.cycle.specfile import MAX_LABEL_CHARS, Checker, KeyLines, check_lengths, short, unquote
from mjwalk.errors import CycleSpecError

TEXT = """name = "x"
scene = "s.xml"

[humanoid]
stature = 1.7

[[task]]
kind = "pick"
site = "a"

[[task]]
kind = "walk"
"""


def test_key_lines_find_keys_tables_and_the_nth_task():
    lines = KeyLines(TEXT)
    assert lines.line("", None, "scene") == 2
    assert lines.line("humanoid", None, "stature") == 5
    assert lines.line("task", 0, "site") == 9
    assert lines.line("task", 1, "site") == 11  # no such key: the table's header
    assert lines.line("nowhere") == 1


def test_unquote_and_short():
    assert unquote(' "a b" ') == "a b" and unquote("'x'") == "x" and unquote("k") == "k"
    assert short("abc") == "abc"
    assert short("y" * 100) == "y" * 40 + "...(100 characters)"


def test_the_checkers_errors_name_the_file_line_and_key():
    check = Checker(Path("c.toml"), KeyLines(TEXT))
    assert check.number({"stature": 1.7}, "stature", 1.4, 2.1, "m", "humanoid") == 1.7
    with pytest.raises(CycleSpecError, match=r"^c.toml:5: key 'stature' in \[humanoid\] must be"):
        check.number({"stature": 3.0}, "stature", 1.4, 2.1, "m", "humanoid")
    with pytest.raises(CycleSpecError, match="must be a number") as err:
        check.number({"stature": True}, "stature", 1.4, 2.1, "m", "humanoid")
    assert (err.value.line, err.value.key) == (5, "stature")
    assert check.string({"site": " a "}, "site", "task", 0) == "a"
    with pytest.raises(CycleSpecError, match=r"c.toml:9: key 'site' in task 1 must be a non-empty"):
        check.string({"site": ""}, "site", "task", 0)
    with pytest.raises(CycleSpecError, match="did you mean 'scene'"):
        check.keys({"scen": 1}, ("name", "scene"))


def test_texts_longer_than_the_limit_are_refused_first():
    check = Checker(Path("c.toml"), KeyLines(TEXT))
    check_lengths(check, {"name": "n" * MAX_LABEL_CHARS})
    with pytest.raises(CycleSpecError, match=f"at most {MAX_LABEL_CHARS}"):
        check_lengths(check, {"name": "n" * (MAX_LABEL_CHARS + 1)})
