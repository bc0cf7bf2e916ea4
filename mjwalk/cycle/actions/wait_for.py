"""The wait action: a ``wait`` task stands still."""

from __future__ import annotations

import numpy as np

from mjwalk.cycle.actions.base import Action, CycleRun, CycleState, Performed


class Wait(Action):
    """Stand still in the last pose for the task's ``duration`` (else the kind's default),
    to the video frame (at least one frame)."""

    def perform(self, run: CycleRun, state: CycleState, plan: None) -> Performed:
        """The last pose repeated for the task's ``duration`` (else the kind's default), rounded to
        the frame (at least one frame): one piece.

        Args:
            run: what stays the same through the run (its ``fps``).
            state: where the operator is (its ``pose`` is held).
            plan: None (a wait plans nothing).

        Returns:
            One piece of (n, nq) frames lasting n / fps seconds, ``state`` unchanged, no record.
        """
        assert self.kind.default_hold is not None
        hold = self.task.duration if self.task.duration is not None else self.kind.default_hold
        n = max(1, round(hold * run.fps))
        return Performed(((np.repeat(state.pose[None], n, axis=0), n / run.fps),), state)
