"""What a walker needs of a step model: starters and successors, as a protocol.

The straight-walk measurements (:func:`mjwalk.gait.straight.model_straight_walks`) and the pace
measured on them (:func:`mjwalk.gait.pace.model_pace`) draw steps and nothing else, so they take
any :class:`StepSampler`; :class:`~mjwalk.gait.model.StepModel` is one (and conditions itself
on a walker with that pace, which is why the pace must not need the model's class).

Steps come as a :class:`~mjwalk.gait.features.StepBatch`, each step in its own local frame
(origin at its start, heading +y, x right; metres, seconds, radians).
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np

from mjwalk.conventions import Side
from mjwalk.gait.features import StepBatch


@runtime_checkable
class StepSampler(Protocol):
    """Draws gait-initiation steps and successors of steps (a :class:`~mjwalk.gait.model.
    StepModel` does, from its KDE starters and transition GPs)."""

    def sample_first(self, n: int, rng: np.random.Generator, side: Side | None = None) -> StepBatch:
        """``n`` steps from standing.

        Args:
            n: steps to draw.
            rng: the random stream the draws come from.
            side: swing side of all of them; None: ``n - n // 2`` left, then ``n // 2`` right.

        Returns:
            The ``n`` steps.
        """
        ...

    def sample_next(self, prev: StepBatch, n: int, rng: np.random.Generator) -> StepBatch:
        """``n`` successors of every step in ``prev``, swinging the other foot.

        Args:
            prev: the p predecessor steps.
            n: successors per predecessor.
            rng: the random stream the draws come from.

        Returns:
            p·n steps; rows i·n .. i·n + n - 1 follow ``prev``'s row i.
        """
        ...
