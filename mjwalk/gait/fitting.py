"""Fitting the parts of a :class:`~mjwalk.gait.model.StepModel` on aligned steps: which
steps are first steps and captured transitions, the KDE starters per side and the transition
GPs per predecessor side (the scheme and why: :mod:`mjwalk.gait.model`'s module docstring).

Features are the standardized PCA features of :class:`~mjwalk.gait.features.StepFeatures`.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from mjwalk._log import log
from mjwalk.conventions import other_side
from mjwalk.errors import MjwalkError
from mjwalk.gait.step import Step
from mjwalk.gait.transition import TransitionGP

_SIDES: tuple[str, str] = ("left", "right")


def first_step_indices(steps: Sequence[Step]) -> np.ndarray:
    """Indices into ``steps`` of the first step of every take (smallest ``index`` per take).

    Args:
        steps: aligned steps.

    Returns:
        (n_takes,) int64 indices, ascending.
    """
    best: dict[str, int] = {}
    for i, s in enumerate(steps):
        j = best.get(s.take)
        if j is None or s.index < steps[j].index:
            best[s.take] = i
    return np.array(sorted(best.values()), dtype=np.int64)


def transition_pairs(steps: Sequence[Step]) -> tuple[np.ndarray, np.ndarray]:
    """Captured transitions: same take, index i -> i+1, sides alternate.

    Args:
        steps: aligned steps.

    Returns:
        (prev, next): two (n_pairs,) int64 index arrays into ``steps``.
    """
    lookup = {(s.take, s.index): i for i, s in enumerate(steps)}
    prev, nxt = [], []
    for i, s in enumerate(steps):
        j = lookup.get((s.take, s.index + 1))
        if j is not None and steps[j].side != s.side:
            prev.append(i)
            nxt.append(j)
    return np.array(prev, dtype=np.int64), np.array(nxt, dtype=np.int64)


def fit_starters(
    z: np.ndarray, sides: np.ndarray, first: np.ndarray
) -> tuple[dict[str, np.ndarray], dict[str, float], dict[str, dict]]:
    """The KDE starters per side (module doc of :mod:`mjwalk.gait.model`): fitted on the side's
    first steps, or on all its steps when it has fewer than ``max(2(d+1), 10)`` first steps.

    Args:
        z: (N, d) standardized features of the steps.
        sides: (N,) swing side of each step.
        first: indices of the first steps (:func:`first_step_indices`).

    Returns:
        (data, factor, source) per side: the KDE dataset (d, n), its Scott factor and
        ``{"source": ..., "n": n}``.

    Raises:
        MjwalkError: a side has too few steps for a d-dimensional KDE.
    """
    d = z.shape[1]
    min_first = max(2 * (d + 1), 10)
    kde_data, kde_factor, kde_source = {}, {}, {}
    for s in _SIDES:
        idx = first[sides[first] == s]
        src = "first steps"
        if len(idx) < min_first:
            idx = np.flatnonzero(sides == s)
            src = "all steps (too few first steps)"
        if len(idx) <= d + 1:
            raise MjwalkError(
                f"StepModel.fit: only {len(idx)} {s} steps for a {d}-D KDE; need more data"
            )
        # deferred: scipy.stats costs ~1 s to import and only fitting needs it
        from scipy.stats import gaussian_kde

        kde = gaussian_kde(z[idx].T)
        kde_data[s] = z[idx].T.copy()
        kde_factor[s] = float(kde.factor)
        kde_source[s] = {"source": src, "n": len(idx)}
    return kde_data, kde_factor, kde_source


@dataclass(frozen=True)
class GPFitter:
    """Fits the transition GPs of :meth:`StepModel.fit` on its standardized features ``z``
    (N, d) and swing sides (N,), drawing from ``rng`` in the order the GPs are fitted."""

    z: np.ndarray
    sides: np.ndarray
    rng: np.random.Generator
    n_hyper: int
    progress: bool

    def fit(
        self,
        label: str,
        pp: np.ndarray,
        nn: np.ndarray,
        min_pairs: int,
        inducing: Callable[[int], int],
        residual: int | None,
    ) -> tuple[dict[str, TransitionGP], dict[str, int]]:
        """One transition GP per predecessor side on the pairs (pp, nn) of a regime.

        Args:
            label: prefix of the progress line.
            pp: (P,) indices of the predecessors into ``z``.
            nn: (P,) indices of their successors.
            min_pairs: sides with fewer pairs get no GP.
            inducing: pairs of a side -> its inducing inputs.
            residual: residuals pooled per inducing input (None: pairs / inducing inputs).

        Returns:
            (gps, counts): side -> :class:`TransitionGP`, and side -> pairs of that side.
        """
        out, counts = {}, {}
        for s in _SIDES:
            sel = self.sides[pp] == s
            counts[s] = int(sel.sum())
            if counts[s] < min_pairs:
                continue
            t1 = time.perf_counter()
            out[s] = TransitionGP.fit(
                self.z[pp[sel]],
                self.z[nn[sel]],
                rng=self.rng,
                n_hyper=self.n_hyper,
                n_inducing=inducing(counts[s]),
                n_residual=residual,
            )
            if self.progress:
                log.info(
                    f"{label}{s}->{other_side(s)}: {counts[s]} pairs, "
                    f"{time.perf_counter() - t1:.1f} s"
                )
        return out, counts
