"""The cycle's bounded memo (:class:`Memo`, made in :mod:`mjwalk.boundedmemo`, named here too).

The cycle's caches are memos with a key of their own, each owned by the module that makes its
values (the planners and grid-A* routes, the prepared contexts and the operators' humanoids by
:mod:`mjwalk.cycle.context`, the stand zones by :mod:`mjwalk.cycle.standing`).
"""

from __future__ import annotations

from mjwalk.boundedmemo import Memo

__all__ = ["Memo"]
