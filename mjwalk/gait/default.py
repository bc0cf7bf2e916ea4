"""The default step model: trained on first use from the virtual-subject corpus, then cached.

The cache file lives in the cache root (:func:`mjwalk._io.cache_root`: ``$MJWALK_CACHE`` or
``~/.cache/mjwalk``); its name carries the
step-model file version and the corpus generator version, so a new mjwalk that changes either
builds a fresh model instead of reading a stale one. A missing or unreadable cache file is
rebuilt (and rewritten atomically).
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from pathlib import Path

from mjwalk._buildonce import built_once
from mjwalk._io import cache_root, check_cache_writable
from mjwalk._log import log
from mjwalk.errors import MjwalkError, ModelFileError
from mjwalk.gait import corpus
from mjwalk.gait.corpus import generate_corpus
from mjwalk.gait.model import MIN_STEPS, MODEL_VERSION, StepModel
from mjwalk.gait.pace import normalize_paces
from mjwalk.gait.segment import segment_takes
from mjwalk.gait.transition import N_INDUCING

#: Corpus generation used for the default model (agethen2018: 12 subjects).
DEFAULT_SUBJECTS = 12
DEFAULT_SEED = 0
#: The default model learns steps within a person: each virtual subject's steps are brought to
#: the subjects' common pace before fitting (:func:`mjwalk.gait.pace.normalize_paces`).
DEFAULT_NORMALIZE_BY = "subject"

_MEMO: dict[Path, StepModel] = {}


def corpus_version() -> str:
    """Version string of the corpus generator (``mjwalk.gait.corpus.CORPUS_VERSION``).

    Returns:
        The version, e.g. ``"2"``.
    """
    return str(getattr(corpus, "CORPUS_VERSION", "0"))


def default_model_path() -> Path:
    """Path of the cached default model (name includes the model and corpus versions and the
    transition GPs' inducing inputs).

    Returns:
        The ``.npz`` path in the cache root.
    """
    return cache_root() / (
        f"stepmodel-v{MODEL_VERSION}-corpus{corpus_version()}"
        f"-s{DEFAULT_SUBJECTS}-seed{DEFAULT_SEED}-m{N_INDUCING}.npz"
    )


def train_model(
    takes: Sequence,
    *,
    seed: int = 0,
    progress: bool = False,
    normalize_by: str | None = None,
    **fit_kwargs,
):
    """Segment ``takes`` into steps and fit a :class:`StepModel`.

    Args:
        takes: captured or virtual takes (metres, z up).
        seed: seed of :meth:`StepModel.fit`.
        progress: log timings.
        normalize_by: a take ``meta`` key naming the walker (``"subject"`` for the virtual
            corpus): the steps of every walker are first brought to one common pace
            (:func:`mjwalk.gait.pace.normalize_paces`), so the model learns the variance within
            a person and a population's walkers (:meth:`StepModel.for_walker`) supply the rest.
        **fit_kwargs: passed to :meth:`StepModel.fit`.

    Returns:
        (model, SegmentationSummary).
    """
    t0 = time.perf_counter()
    steps, summary = segment_takes(takes)
    norm: dict = {}
    if normalize_by:
        steps, norm = normalize_paces(steps, key=normalize_by)
    if progress:
        log.info(
            f"segmented {len(takes)} takes into {len(steps)} steps "
            f"({time.perf_counter() - t0:.1f} s)"
        )
    if len(steps) < MIN_STEPS:
        raise MjwalkError(
            f"train_model: only {len(steps)} steps found in {len(takes)} takes; a step model "
            f"needs at least {MIN_STEPS} steps: give more walking capture"
        )
    model = StepModel.fit(steps, seed=seed, progress=progress, **fit_kwargs)
    if normalize_by:
        model.info["normalized_by"] = normalize_by
        model.info["normalized_walkers"] = len(norm)
    return model, summary


def default_model(progress: bool = True) -> StepModel:
    """The default :class:`StepModel`, loaded from the cache or built and cached on first use.

    Building generates the virtual corpus (``generate_corpus(12, seed=0)``), segments it and
    fits the model (about a minute).

    Args:
        progress: log progress to stderr while building.

    Returns:
        The model (memoized per cache path).
    """
    path = default_model_path()
    if path in _MEMO:
        return _MEMO[path]

    def build() -> StepModel:
        check_cache_writable("the default step model")  # before a minute of training

        t0 = time.perf_counter()
        if progress:
            log.info(
                f"building the default step model ({DEFAULT_SUBJECTS} virtual subjects) -> {path}"
            )
        takes = generate_corpus(n_subjects=DEFAULT_SUBJECTS, seed=DEFAULT_SEED)
        if progress:
            log.info(f"corpus: {len(takes)} takes ({time.perf_counter() - t0:.1f} s)")
        built, _ = train_model(
            takes, seed=DEFAULT_SEED, progress=progress, normalize_by=DEFAULT_NORMALIZE_BY
        )
        built.info["corpus_version"] = corpus_version()
        built.pace()  # measured once, saved with the model (mjwalk.gait.pace)
        built.save(path)
        if progress:
            log.info(f"default model ready ({time.perf_counter() - t0:.1f} s)")
        return built

    def stale(exc: ModelFileError) -> None:
        if progress:
            log.info(f"rebuilding default model: {exc}")

    model = built_once(path, StepModel.load, build, on_stale=stale)
    _MEMO[path] = model
    return model
