"""Score one cycle's timeline task by task: what a run keeps of its ergonomics (no timeline).

:func:`assess_cycle` takes the humanoid's poses (as :class:`~mjwalk.ergonomics.angles.BodyAngles`),
the cycle's tasks as frame spans (:class:`~mjwalk.ergonomics.score.TaskSpan`: hand, the part's
mass and coupling, the site's position, and what the task kind does: a reach, taking or putting
down a part, a lift) and the cycle time, and asks every registered method
(:data:`mjwalk.ergonomics.registry.SCORES`: RULA, REBA, OWAS, NIOSH, ISO 11226) for its frames,
its values per task and per run, through the hooks of :class:`~mjwalk.ergonomics.score.Score`.
It returns a :class:`~mjwalk.ergonomics.results.RunErgonomics`: per task the peak RULA, REBA
and OWAS scores and the body part that drives each peak; per lift of a part with a mass the
revised NIOSH equation's H, V, D, A, F, C, RWL and LI; ISO 11226's static holdings of the trunk
and the upper arms; and the frame-by-frame RULA and REBA scores (small ints) for plots.
"""

from __future__ import annotations

from dataclasses import fields
from typing import Any

from mjwalk.ergonomics.angles import BodyAngles
from mjwalk.ergonomics.registry import SCORES
from mjwalk.ergonomics.results import RunErgonomics, TaskErgonomics
from mjwalk.ergonomics.score import TaskSpan, score_context

#: The names a method's values fill directly (the others go to ``extra``).
TASK_FIELDS = frozenset(f.name for f in fields(TaskErgonomics)) - {"extra"}
RUN_FIELDS = frozenset(f.name for f in fields(RunErgonomics)) - {"extra"}


def _split(values: dict[str, Any], named: frozenset[str]) -> tuple[dict, dict]:
    """``values`` as (those with a field of their own, the others)."""
    own = {k: v for k, v in values.items() if k in named}
    return own, {k: v for k, v in values.items() if k not in named}


def assess_cycle(
    ang: BodyAngles, spans: list[TaskSpan], cycle_time: float, fps: float
) -> RunErgonomics:
    """Score a cycle with every registered method.

    Args:
        ang: the body angles of all its frames.
        spans: its tasks, in order, covering the frames.
        cycle_time: the cycle's duration, s.
        fps: the timeline's frame rate, frames/s.

    Returns:
        The cycle's :class:`~mjwalk.ergonomics.results.RunErgonomics` (a task without frames
        has no entry in its ``tasks``).
    """
    ctx = score_context(ang, spans, cycle_time, fps)
    frames = {name: s.per_frame(ang, ctx) for name, s in SCORES.items()}
    tasks = []
    for sp in spans:
        if sp.end <= sp.start:
            continue
        values: dict[str, Any] = {}
        for name, s in SCORES.items():
            values.update(s.per_task(frames[name], sp, ctx))
        own, extra = _split(values, TASK_FIELDS)
        tasks.append(
            TaskErgonomics(
                index=sp.index, kind=sp.kind, site=sp.site, reach=sp.reach, extra=extra, **own
            )
        )
    values = {}
    for name, s in SCORES.items():
        values.update(s.per_run(frames[name], ang, ctx))
    own, extra = _split(values, RUN_FIELDS)
    return RunErgonomics(tasks=tasks, fps=fps, extra=extra, **own)


__all__ = ["RunErgonomics", "TaskErgonomics", "TaskSpan", "assess_cycle"]
