"""Tests of mjwalk.gait.default: the cached default model's path and training entry."""

from __future__ import annotations

import pytest

from mjwalk.errors import MjwalkError
from mjwalk.gait import corpus
from mjwalk.gait.default import (
    DEFAULT_SEED,
    DEFAULT_SUBJECTS,
    corpus_version,
    default_model_path,
    train_model,
)
from mjwalk.gait.model import MODEL_VERSION
from mjwalk.gait.transition import N_INDUCING


def test_cache_name_carries_every_version(tmp_path, monkeypatch):
    monkeypatch.setenv("MJWALK_CACHE", str(tmp_path))
    assert corpus_version() == corpus.CORPUS_VERSION
    path = default_model_path()
    assert path.parent == tmp_path
    assert path.name == (
        f"stepmodel-v{MODEL_VERSION}-corpus{corpus.CORPUS_VERSION}"
        f"-s{DEFAULT_SUBJECTS}-seed{DEFAULT_SEED}-m{N_INDUCING}.npz"
    )


def test_train_model_needs_steps():
    with pytest.raises(MjwalkError, match="at least"):
        train_model([])
