"""mjwalk.world.cache: content keys and arrays stored once, mapped afterwards."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.world import cache
from mjwalk.world.cache import cached_array, content_key


def test_the_old_cache_variable_still_works_and_says_it_is_deprecated(tmp_path, monkeypatch):
    monkeypatch.setenv("MJWALK_CACHE", str(tmp_path / "root"))
    monkeypatch.setenv("MJWALK_CACHE_DIR", str(tmp_path / "old"))
    cache._deprecated_env.cache_clear()
    with pytest.warns(DeprecationWarning, match="MJWALK_CACHE_DIR is deprecated"):
        assert cache.cache_dir() == tmp_path / "old"
    monkeypatch.delenv("MJWALK_CACHE_DIR")
    assert cache.cache_dir() == tmp_path / "root" / "workplaces"


def test_content_key_follows_the_parts_and_the_array_bytes():
    a = np.arange(6.0).reshape(3, 2)
    key = content_key("clearance", (0.0, 1.0), arrays=[a])
    assert key == content_key("clearance", (0.0, 1.0), arrays=[a.copy()])
    assert len(key) == 64
    assert key != content_key("clearance", (0.0, 1.5), arrays=[a])
    assert key != content_key("clearance", (0.0, 1.0), arrays=[a.astype(np.float32)])
    assert key != content_key("clearance", (0.0, 1.0), arrays=[a.reshape(2, 3)])


def test_cached_array_builds_once_then_maps_the_file(tmp_path, monkeypatch):
    monkeypatch.setenv("MJWALK_CACHE", str(tmp_path))
    monkeypatch.delenv("MJWALK_CACHE_DIR", raising=False)
    calls = []

    def build():
        calls.append(1)
        return np.arange(4.0)

    key = content_key("test", 1)
    first = cached_array(key, "field", build)
    again = cached_array(key, "field", build)
    assert len(calls) == 1
    np.testing.assert_array_equal(again, [0.0, 1.0, 2.0, 3.0])
    np.testing.assert_array_equal(first, again)
    assert isinstance(again.base, np.memmap)


def test_a_stored_array_its_check_refuses_is_rebuilt_over(tmp_path, monkeypatch):
    monkeypatch.setenv("MJWALK_CACHE", str(tmp_path))
    monkeypatch.delenv("MJWALK_CACHE_DIR", raising=False)
    key = content_key("test", 2)
    cached_array(key, "field", lambda: np.arange(3.0))
    calls = []

    def build():
        calls.append(1)
        return np.arange(3.0) + 10

    kept = cached_array(key, "field", build, valid=lambda a: True)
    assert not calls
    np.testing.assert_array_equal(kept, [0.0, 1.0, 2.0])
    again = cached_array(key, "field", build, valid=lambda a: bool(a[0] == 10.0))
    assert len(calls) == 1
    np.testing.assert_array_equal(again, [10.0, 11.0, 12.0])
    np.testing.assert_array_equal(cached_array(key, "field", build), [10.0, 11.0, 12.0])


def test_use_disk_is_the_policy_or_the_default():
    assert cache.use_disk(True, False) and cache.use_disk(None, True)
    assert not cache.use_disk(False, True) and not cache.use_disk(None, False)
