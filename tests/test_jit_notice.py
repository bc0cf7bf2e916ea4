"""The one-line notice while numba compiles mjwalk's planner (issue 17, item 3)."""

from __future__ import annotations

import numba

from mjwalk import _jit


def _fresh(module: str):
    def add_one(x):
        return x + 1

    add_one.__module__ = module
    return numba.njit(cache=False)(add_one)


def test_notice_once_when_mjwalk_code_compiles(capsys, monkeypatch):
    monkeypatch.setattr(_jit.NOTICE, "shown", False)
    assert _fresh("someone_else")(1) == 2  # other packages' compilations: no notice
    assert capsys.readouterr().err == ""
    assert _fresh("mjwalk.plan.probe")(1) == 2
    assert _fresh("mjwalk.plan.probe2")(2) == 3
    assert capsys.readouterr().err.splitlines() == [_jit.COMPILE_NOTICE]  # one line, once
