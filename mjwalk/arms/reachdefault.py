"""The default reach model: trained on first use from generated reaches, then cached."""

from __future__ import annotations

import sys
import time

import numpy as np

from mjwalk.errors import ModelFileError

#: Bump when the generator or the model changes, so the cache is rebuilt.
REACH_DEFAULT_VERSION = "3"
N_TRAIN = 200
#: The DCS of the default model: network size, RBF width, output ridge, constant or local
#: linear outputs (with the slopes' own ridge) and a global linear term chosen by exact
#: leave-one-out errors on the training reaches (PRESS), as ``benchmarks/bench_reach.py`` runs
#: it on capture (10-fold CV on the Bandai raise-hand clips: 4.21 deg against kNN 4.27 and
#: 4.30 without the global term and slope ridge; leave-one-style-out 14.50 against 16.01).
DEFAULT_DCS = {
    "rng": 0,
    "selection": "loo",
    "local_linear": (False, True),
    "global_linear": (False, True),
    "slope_ridge": (0.1, 1.0, 10.0, 100.0),
}
_MEMO: dict = {}


def default_reach_model(progress: bool = True):
    """The :class:`~mjwalk.arms.reach.ReachModel` of start/end-constrained reaches of the left
    arm (``reachgen.generate("endpoints", 200, seed 0)``), cached beside the step model."""
    from mjwalk.arms import reachgen
    from mjwalk.arms.reach import ReachModel
    from mjwalk.gait.default import cache_dir

    path = cache_dir() / f"reach-endpoints-v{REACH_DEFAULT_VERSION}-n{N_TRAIN}.npz"
    if path in _MEMO:
        return _MEMO[path]
    model = None
    if path.is_file():
        try:
            model = ReachModel.load(path)
        except ModelFileError:
            model = None
    if model is None:
        t0 = time.perf_counter()
        if progress:
            print(f"[mjwalk] building the default reach model -> {path}", file=sys.stderr)
        data = reachgen.generate("endpoints", N_TRAIN, np.random.default_rng(0))
        model = ReachModel(data.lengths, dcs=DEFAULT_DCS).fit(data.constraints, data.directions)
        model.save(path)
        if progress:
            print(
                f"[mjwalk] default reach model ready ({time.perf_counter() - t0:.1f} s)",
                file=sys.stderr,
            )
    _MEMO[path] = model
    return model
