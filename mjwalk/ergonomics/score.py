"""The interface of an ergonomic method: what it is given of a cycle and which hooks it fills.

A method is one :class:`Score` subclass, listed in :data:`mjwalk.ergonomics.registry.SCORES`;
:func:`mjwalk.ergonomics.assess.assess_cycle`, the report's figures and Markdown
(:mod:`mjwalk.ergonomics.summary`) and ``ergonomics.csv`` read it only through these hooks:

- scoring one cycle (:func:`~mjwalk.ergonomics.assess.assess_cycle`):
  :meth:`Score.per_frame` (the body angles of every frame and the cycle's :class:`ScoreContext`
  in, the method's frame-by-frame result out), then :meth:`Score.per_task` (that result and one
  :class:`TaskSpan` in, the task's values by name out) and :meth:`Score.per_run` (the cycle's
  values by name); names that are fields of :class:`~mjwalk.ergonomics.results.TaskErgonomics`
  or :class:`~mjwalk.ergonomics.results.RunErgonomics` fill them, the others go to their
  ``extra``;
- the workforce's figures: :meth:`Score.stats` (a group of runs in, plain JSON-ready figures
  out, per operator group and overall in report.json), :attr:`Score.table` (its columns in
  report.md's table, read from those figures) and :meth:`Score.notes` (its lines after it);
- ``ergonomics.csv``: :attr:`Score.columns`, one cell per run and task.

Angles in degrees (the methods' own unit), lengths in metres, masses in kg, times in seconds.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar, Literal

import numpy as np

from mjwalk.ergonomics import reba
from mjwalk.ergonomics.angles import BodyAngles
from mjwalk.ergonomics.results import RunErgonomics

#: Reaches per minute from which a hand's work counts as repeated (RULA muscle use; REBA
#: activity "repeated small range actions, more than 4 times a minute").
REPEATED_PER_MIN = 4.0
#: A task whose hold lasts longer than this (s) is a static posture (RULA, REBA: > 1 min).
STATIC_S = 60.0
#: Confidence level of the shares.
CONFIDENCE = 0.95


@dataclass
class TaskSpan:
    """One task of a cycle on its timeline: frames [start, end), the hand ("left", "right",
    "both"; None for walks), the mass (kg) and coupling of the part it handles, and for a
    reach the site's world position (m).

    What the task's kind does comes with it (the cycle's task kinds table,
    :data:`mjwalk.cycle.types.TASK_KINDS`, says it; ``kind`` is only its name for the report):
    ``reach`` a hand to the site and back; ``part`` "take" (the hand holds the part from this
    task on) or "put" (it puts down the part it took first), else None; ``lifts`` the reach
    lifts the part from the site or lowers it onto it (a NIOSH lift).
    """

    index: int
    kind: str
    start: int
    end: int
    hand: str | None = None
    site: str | None = None
    mass: float = 0.0
    coupling: str = "poor"
    site_pos: np.ndarray | None = None
    reach: bool = False
    part: Literal["take", "put"] | None = None
    lifts: bool = False


@dataclass(frozen=True)
class ScoreContext:
    """What every method reads of a cycle beside its body angles (built by :func:`score_context`).

    Attributes:
        spans: the cycle's tasks in order, covering its frames.
        cycle_time: the cycle's duration, s.
        fps: the timeline's frame rate, frames/s.
        load: (F, 2) the mass in the left and right hand, kg, frame by frame.
        muscle: (F, 2) 1 where a hand's work counts as repeated or static (RULA muscle use,
            REBA activity), else 0.
        coupling: (F, 2) REBA's coupling score of the part in each hand (0 without one).
    """

    spans: tuple[TaskSpan, ...]
    cycle_time: float
    fps: float
    load: np.ndarray
    muscle: np.ndarray
    coupling: np.ndarray


def _sides(hand: str | None) -> list[int]:
    """The hand indices (0 left, 1 right) of a task's ``hand``."""
    return [0, 1] if hand == "both" else [0] if hand == "left" else [1]


def _loads(spans: Sequence[TaskSpan], n: int) -> np.ndarray:
    """(F, 2) the mass (kg) in each hand, frame by frame: a part is held from its pick to its
    place or fasten, both included."""
    load = np.zeros((n, 2))
    held = [0.0, 0.0]
    for sp in spans:
        sides = _sides(sp.hand)
        if sp.part == "take" and sp.hand:
            for s in sides:
                held[s] += sp.mass / len(sides)
        for s in (0, 1):
            load[sp.start : sp.end, s] = held[s]
        if sp.part == "put" and sp.hand:
            for s in sides:
                held[s] = max(held[s] - sp.mass / len(sides), 0.0)
    return load


def score_context(
    ang: BodyAngles, spans: Sequence[TaskSpan], cycle_time: float, fps: float
) -> ScoreContext:
    """The force and activity terms of a cycle's tasks, frame by frame.

    Muscle use (RULA) and activity (REBA) count a hand repeating reaches
    :data:`REPEATED_PER_MIN` times a minute or more over the cycle, and a reach held longer
    than :data:`STATIC_S` in one task (a long fasten) as static.

    Args:
        ang: the body angles of the cycle's F frames.
        spans: its tasks, in order, covering the frames.
        cycle_time: the cycle's duration, s.
        fps: the timeline's frame rate, frames/s.

    Returns:
        The :class:`ScoreContext` of the cycle.
    """
    n = ang.n_frames
    minutes = max(cycle_time, 1e-9) / 60.0
    reps = [
        sum(1 for s in spans if s.reach and s.hand in (side, "both")) for side in ("left", "right")
    ]
    repeated = np.array([r / minutes >= REPEATED_PER_MIN for r in reps])
    muscle = np.zeros((n, 2), dtype=int)
    muscle[:] = repeated
    coupling = np.zeros((n, 2), dtype=int)
    for sp in spans:
        if (sp.end - sp.start) / fps > STATIC_S and sp.reach:
            muscle[sp.start : sp.end] = 1
        if sp.mass > 0 and sp.hand:
            for s in _sides(sp.hand):
                coupling[sp.start : sp.end, s] = reba.COUPLING.get(sp.coupling, 2)
    return ScoreContext(tuple(spans), cycle_time, fps, _loads(spans, n), muscle, coupling)


@dataclass(frozen=True)
class Column:
    """One column a method writes: its header and how a row's cell is made.

    Attributes:
        name: the header (ergonomics.csv) or the table's head (report.md).
        cell: ergonomics.csv: ``cell(run, task)`` of a :class:`RunErgonomics` and one of its
            :class:`TaskErgonomics`; report.md: ``cell(stats)`` of the method's
            :meth:`Score.stats` of a group. Returns the cell (str, int or float as written).
    """

    name: str
    cell: Callable[..., Any]


class Score:
    """An ergonomic method: subclass it, fill the hooks it needs, and list an instance in
    :data:`mjwalk.ergonomics.registry.SCORES`. Every hook has a default that contributes
    nothing, so a method fills only what it gives.

    Attributes:
        name: the method's key (report.json's ``methods``; the registry's key).
        source: the method's reference, as report.json names it.
        columns: its ergonomics.csv columns (``cell(run, task)``).
        table: its columns in report.md's table of the operator groups (``cell(stats)``).
    """

    name: ClassVar[str] = ""
    source: ClassVar[str] = ""
    columns: ClassVar[tuple[Column, ...]] = ()
    table: ClassVar[tuple[Column, ...]] = ()

    def per_frame(self, ang: BodyAngles, ctx: ScoreContext) -> Any:
        """The method's frame-by-frame result, passed back to :meth:`per_task` and
        :meth:`per_run` (its form is the method's own).

        Args:
            ang: the body angles of the cycle's F frames.
            ctx: the cycle's tasks, loads and activity.

        Returns:
            Anything; None by default.
        """
        return None

    def per_task(self, frames: Any, span: TaskSpan, ctx: ScoreContext) -> dict[str, Any]:
        """One task's values (called for the tasks with at least one frame).

        Args:
            frames: what :meth:`per_frame` returned.
            span: the task and its frames ``[span.start, span.end)``.
            ctx: the cycle's tasks, loads and activity.

        Returns:
            Values by name (fields of :class:`TaskErgonomics`, or new names for its ``extra``).
        """
        return {}

    def per_run(self, frames: Any, ang: BodyAngles, ctx: ScoreContext) -> dict[str, Any]:
        """The cycle's values.

        Args:
            frames: what :meth:`per_frame` returned.
            ang: the body angles of the cycle's F frames.
            ctx: the cycle's tasks, loads and activity.

        Returns:
            Values by name (fields of :class:`RunErgonomics`, or new names for its ``extra``).
        """
        return {}

    def stats(self, runs: Sequence[RunErgonomics]) -> dict[str, Any]:
        """The method's figures of a group of runs (report.json, per group and overall).

        Args:
            runs: the group's scored cycles (at least one).

        Returns:
            Plain, JSON-ready figures by name.
        """
        return {}

    def notes(self, stats: dict[str, Any]) -> list[str]:
        """report.md's lines of the method after the table of the operator groups.

        Args:
            stats: all operators' figures (every method's :meth:`stats`, merged).

        Returns:
            Markdown lines (a paragraph ends with an empty line); none by default.
        """
        return []


def percentiles(x: Sequence[float] | np.ndarray) -> dict:
    """P50 and P95 of some values and their number.

    Args:
        x: the values.

    Returns:
        ``p50``, ``p95`` (None when empty) and ``n``.
    """
    x = np.asarray(x, dtype=float)
    if not len(x):
        return {"p50": None, "p95": None, "n": 0}
    return {"p50": float(np.percentile(x, 50)), "p95": float(np.percentile(x, 95)), "n": len(x)}


def share(k: int, n: int, confidence: float = CONFIDENCE) -> dict:
    """``k`` of ``n`` as a share with its Wilson score interval (Wilson 1927).

    Args:
        k: the count.
        n: of how many (0: no share).
        confidence: the interval's confidence level.

    Returns:
        ``share``, ``low``, ``high`` (None when ``n`` is 0), ``k`` and ``n``.
    """
    from scipy.stats import binomtest  # deferred: scipy.stats takes ~0.3 s to import

    if n == 0:
        return {"share": None, "low": None, "high": None, "k": 0, "n": 0}
    ci = binomtest(k, n).proportion_ci(confidence_level=confidence, method="wilson")
    return {"share": k / n, "low": float(ci.low), "high": float(ci.high), "k": k, "n": n}


def fmt(x: float | None, d: int = 1) -> str:
    """A table cell of a number.

    Args:
        x: the number, or None.
        d: decimal places.

    Returns:
        ``x`` to ``d`` places, "-" for None.
    """
    return "-" if x is None else f"{x:.{d}f}"


def fmt_share(e: dict) -> str:
    """A table cell of a :func:`share`, in percent with its interval.

    Args:
        e: the share (``share``, ``low``, ``high``).

    Returns:
        e.g. "40 % (20-63)"; "-" without a share.
    """
    if e["share"] is None:
        return "-"
    return f"{100 * e['share']:.0f} % ({100 * e['low']:.0f}-{100 * e['high']:.0f})"


__all__ = [
    "CONFIDENCE",
    "REPEATED_PER_MIN",
    "STATIC_S",
    "Column",
    "Score",
    "ScoreContext",
    "TaskSpan",
    "fmt",
    "fmt_share",
    "percentiles",
    "score_context",
    "share",
]
