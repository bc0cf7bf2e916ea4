"""The error hierarchy: every deliberate failure is an MjwalkError; the input and write errors are
also the standard exceptions code may already catch."""

from __future__ import annotations

import inspect

import pytest

from mjwalk import errors
from mjwalk.errors import (
    CycleSpecError,
    InputError,
    MjwalkError,
    ScanError,
    SceneError,
    WriteError,
)


def test_every_error_is_an_mjwalk_error():
    classes = [
        c for _, c in inspect.getmembers(errors, inspect.isclass) if c.__module__ == errors.__name__
    ]
    assert len(classes) >= 8
    for c in classes:
        assert issubclass(c, MjwalkError), c


def test_standard_exceptions_still_catch_them():
    with pytest.raises(ValueError):
        raise InputError("speed: -1 is not positive")
    with pytest.raises(OSError):
        raise WriteError("out.mp4: disk full")
    with pytest.raises(SceneError):
        raise ScanError("scan.ply: no floor")


def test_cycle_spec_error_locates_the_problem():
    e = CycleSpecError("unknown key 'sitee'")
    assert (e.path, e.line, e.key) == (None, None, None)
    e.path, e.line, e.key = "cycle.toml", 12, "sitee"
    assert str(e) == "unknown key 'sitee'"
