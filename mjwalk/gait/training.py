"""Train a step model from files and check a saved one against capture: the library behind
``mjwalk train`` and ``mjwalk validate``.

:class:`CaptureFiles` names the capture (a BVH glob, an AMC glob with its ASF skeleton, the
skeleton preset); :func:`train_model_file` trains on it (and/or on virtual subjects) and saves
the model; :func:`validate_model_file` compares a saved (or the default) model with it
(:func:`mjwalk.gait.fidelity.fidelity_report`).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from mjwalk._io import atomic_path
from mjwalk._log import log
from mjwalk.errors import InputError, MjwalkError
from mjwalk.gait.corpus import generate_corpus
from mjwalk.gait.default import default_model, train_model
from mjwalk.gait.fidelity import fidelity_report, load_capture
from mjwalk.gait.model import StepModel
from mjwalk.gait.walker import Walker


@dataclass(frozen=True)
class CaptureFiles:
    """Captured walking on disk.

    Args:
        bvh: glob of BVH files, or None.
        amc: glob of AMC files (needs ``asf``), or None.
        asf: the ASF skeleton of the AMC files, or None.
        skeleton: skeleton preset of the files (``bandai``, ``cmu``, ``cmu_bvh``), or None to
            detect it.
    """

    bvh: str | None = None
    amc: str | None = None
    asf: str | None = None
    skeleton: str | None = None

    @classmethod
    def of_glob(
        cls, pattern: str, asf: str | None = None, skeleton: str | None = None
    ) -> CaptureFiles:
        """The files of one glob: AMC (with ``asf``) when it ends in ``.amc``, else BVH.

        Args:
            pattern: glob of ``.bvh`` or ``.amc`` files.
            asf: the ASF skeleton, used for AMC files only.
            skeleton: skeleton preset, or None.

        Returns:
            The capture files.
        """
        if str(pattern).lower().endswith(".amc"):
            return cls(amc=pattern, asf=asf, skeleton=skeleton)
        return cls(bvh=pattern, skeleton=skeleton)

    def load(self) -> list:
        """The takes of these files, sorted by file name (:func:`.fidelity.load_capture`).

        Returns:
            The takes (:class:`~mjwalk.mocap.Take`), empty when no glob is given.
        """
        return load_capture(self.bvh, self.amc, self.asf, skeleton=self.skeleton)


def load_model(path: str | Path | None) -> StepModel:
    """A step model from its file, or the built-in default model.

    Args:
        path: model file (``.npz``), or None for :func:`~mjwalk.gait.default.default_model`.

    Returns:
        The step model.
    """
    return default_model() if path is None else StepModel.load(path)


def train_model_file(
    out: str | Path,
    capture: CaptureFiles = CaptureFiles(),
    *,
    virtual: int | None = None,
    seed: int = 0,
    progress: bool = True,
    variance: float | None = None,
) -> dict:
    """Train a step model and save it to ``out``.

    Data: the capture files and/or ``virtual`` N virtual subjects (``generate_corpus(N, seed)``);
    at least one is required.

    Args:
        out: model file to write (``.npz``).
        capture: the captured walking to train on (none by default).
        virtual: number of virtual subjects to add, or None.
        seed: random seed of the virtual subjects and of the fit.
        progress: log progress messages.
        variance: the share of the step features' variance the PCA keeps, in (0, 1] (None:
            :meth:`StepModel.fit`'s default, 0.99; the paper keeps >= 0.95, which suits small
            captures, see there).

    Returns:
        The model's summary (:meth:`StepModel.summary`) with its ``"segmentation"``.

    Raises:
        InputError: ``variance`` is outside (0, 1].
        MjwalkError: no data was given, or a glob matches no file.
    """
    if variance is not None and not 0.0 < variance <= 1.0:
        raise InputError(f"train: the PCA variance to keep must be in (0, 1], got {variance!r}")
    fit: dict[str, Any] = {} if variance is None else {"variance": float(variance)}
    takes = capture.load()
    if virtual:
        takes += generate_corpus(n_subjects=int(virtual), seed=seed)
    if not takes:
        raise MjwalkError("train: give a BVH glob, an AMC glob with its ASF, or virtual N")
    if progress:
        log.info(f"training on {len(takes)} takes")
    model, seg = train_model(takes, seed=seed, progress=progress, **fit)
    model.pace()  # measured once, saved with the model (mjwalk.gait.pace)
    model.save(out)
    summary = model.summary()
    summary["segmentation"] = str(seg)
    if progress:
        log.info(f"{seg}; model written to {out}")
    return summary


def validate_model_file(
    model_path: str | Path | None,
    capture: CaptureFiles,
    json_path: str | Path | None = None,
    *,
    seed: int = 0,
    n_chains: int = 400,
    walker: Walker | None = None,
    planned_walks: Callable | None = None,
) -> dict:
    """Fidelity of a saved (or the default) step model against captured walking.

    Args:
        model_path: model file, or None for the default model.
        capture: the captured walking to compare with.
        json_path: write the report here as JSON (atomically), or None.
        seed: random seed of the model's sampled chains.
        n_chains: number of sampled step chains.
        walker: condition the model on this operator (:meth:`StepModel.for_walker`), or None.
        planned_walks: see :func:`~mjwalk.gait.fidelity.fidelity_from_steps`.

    Returns:
        The fidelity report (:func:`~mjwalk.gait.fidelity.fidelity_report`;
        :func:`~mjwalk.gait.fidelity.format_fidelity_table` formats it).
    """
    takes = capture.load()
    model = load_model(model_path).for_walker(walker)
    report = fidelity_report(
        model, takes, np.random.default_rng(seed), n_chains=n_chains, planned_walks=planned_walks
    )
    if json_path is not None:
        with atomic_path(json_path, suffix=".json") as tmp:
            tmp.write_text(json.dumps(report, indent=2))
    return report
