"""The cycle's bounded memo (:class:`Memo`, made in :mod:`mjwalk.boundedmemo`, named here too)
and its scratch MjData, one per model layout and thread (:class:`ScratchData`).

The cycle's caches are memos with a key of their own, each owned by the module that makes its
values (the planners and grid-A* routes, the prepared contexts and the operators' humanoids by
:mod:`mjwalk.cycle.context`, the stand zones by :mod:`mjwalk.cycle.standing`).
"""

from __future__ import annotations

import threading

import mujoco

from mjwalk.boundedmemo import Memo

__all__ = ["Memo", "ScratchData", "data_layout"]


def data_layout(model: mujoco.MjModel) -> tuple:
    """What an MjData of ``model`` is made for: MuJoCo's size signature of the model with its
    buffer and arena sizes (the humanoids of every stature in one scene share it); a model with
    mocap bodies keys by itself (an MjData starts its mocap poses at its own model's, which the
    kinematics read).

    Args:
        model: the model.

    Returns:
        A hashable key: models with equal keys can share one MjData.
    """
    if model.nmocap:
        return (model,)
    return (model.signature, model.nbuffer, model.narena, model.nq, model.ngeom)


class ScratchData:
    """Scratch MjData kept per thread and model layout (:func:`data_layout`), at most ``limit``
    layouts a thread, the one kept longest dropped first. Its users set the whole qpos before
    each use and pass their own model to MuJoCo (as :func:`mujoco.rollout.rollout` runs one
    MjData with several models of one size signature), and a thread's runs go one after the
    other. An MjData holds the model it was made for, so the memo is bounded, not weak.

    Args:
        limit: layouts kept per thread.
    """

    def __init__(self, limit: int):
        self.limit = int(limit)
        self._local = threading.local()

    def of(self, model: mujoco.MjModel) -> mujoco.MjData:
        """This thread's scratch MjData for ``model``'s layout, made on first use.

        Args:
            model: the model the caller computes with.

        Returns:
            An MjData made for a model of ``model``'s layout.
        """
        memo = getattr(self._local, "memo", None)
        if memo is None:
            memo = self._local.memo = Memo(limit=self.limit)
        return memo.get(data_layout(model), lambda: mujoco.MjData(model))

    def __len__(self) -> int:
        """The layouts this thread keeps an MjData for."""
        memo = getattr(self._local, "memo", None)
        return 0 if memo is None else len(memo)
