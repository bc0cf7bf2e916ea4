"""The ergonomic methods mjwalk scores a cycle with, in one table: :data:`SCORES`.

:func:`~mjwalk.ergonomics.assess.assess_cycle`, the report's figures and Markdown
(:mod:`mjwalk.ergonomics.summary`) and ``ergonomics.csv`` read the methods from here, in this
order; adding a method is one module with a :class:`~mjwalk.ergonomics.score.Score` subclass and
one entry here (or, at run time, :func:`register`).

report.json and ergonomics.csv keep the order of keys and columns their readers know
(:data:`STATS_ORDER`, :data:`CSV_ORDER`, interleaving the built-in methods); a registered
method's keys and columns follow them, in the registry's order.
"""

from __future__ import annotations

from collections.abc import Iterable

from mjwalk.ergonomics.exposure import ExposureScore
from mjwalk.ergonomics.lifting import NioshScore
from mjwalk.ergonomics.postures import Iso11226Score, OwasScore, RebaScore, RulaScore
from mjwalk.ergonomics.score import Column, Score
from mjwalk.errors import MjwalkError

#: The methods by name, in the report's order (its table's columns, its notes).
SCORES: dict[str, Score] = {
    s.name: s
    for s in (
        RulaScore(), RebaScore(), OwasScore(), NioshScore(), Iso11226Score(), ExposureScore()
    )
}  # fmt: skip
#: The columns of ergonomics.csv before any method's: the run, its operator and the task.
TASK_COLUMNS = ("run", "seed", "group", "stature_m", "task", "kind", "site")
#: ergonomics.csv's established column order (the built-in methods' columns, interleaved).
CSV_ORDER = (
    *TASK_COLUMNS, "rula_peak", "rula_action_level", "reba_peak", "reba_risk_level", "owas_peak",
    "rula_time_s", "rula_driver", "reba_driver", "arm", "upper_arm_score", "lifting_index",
    "rwl_kg", "mass_kg", "lifts_per_min", "lifting_index_note",
)  # fmt: skip
#: The established order of the figures of a group of runs in report.json.
STATS_ORDER = (
    "runs", "rula_peak", "reba_peak", "rula_action_level", "reba_risk_level", "owas_peak",
    "lifting_index", "lifts_per_cycle", "cycles_li_over_1", "lifting_index_not_computed",
    "iso11226_not_acceptable",
)  # fmt: skip


class ScoreRegistryError(MjwalkError):
    """A method cannot be registered: its name or one of its columns is taken."""


def register(score: Score) -> Score:
    """Add ``score`` to :data:`SCORES` (after the others); remove it with
    ``SCORES.pop(score.name)``.

    Only this process sees it: runs that joblib farms out to worker processes
    (``simulate_cycles(n_jobs > 1)``, a Dask scheduler) import the registry afresh and score
    without it; a method for every run is an entry in :data:`SCORES` itself.

    Args:
        score: an instance of a :class:`~mjwalk.ergonomics.score.Score` subclass.

    Returns:
        ``score``.

    Raises:
        ScoreRegistryError: its name is empty or taken, or a column's name is taken.
    """
    if not score.name or score.name in SCORES:
        raise ScoreRegistryError(f"ergonomic method name {score.name!r} is empty or taken")
    taken = {c.name for c in csv_columns()} | {c.name for s in SCORES.values() for c in s.table}
    clash = [c.name for c in (*score.columns, *score.table) if c.name in taken]
    if clash:
        raise ScoreRegistryError(f"ergonomic method {score.name!r}: columns taken: {clash}")
    SCORES[score.name] = score
    return score


def in_order(names: Iterable[str], established: tuple[str, ...]) -> list[str]:
    """Names with those of an established order first, in its order, then the others in theirs.

    Args:
        names: the names.
        established: the established order.

    Returns:
        The names, reordered.
    """
    names = list(names)
    rank = {n: i for i, n in enumerate(established)}
    first = sorted((n for n in names if n in rank), key=rank.__getitem__)
    return first + [n for n in names if n not in rank]


def csv_columns() -> list[Column]:
    """The registered methods' ergonomics.csv columns, in the file's order (after
    :data:`TASK_COLUMNS`).

    Returns:
        The :class:`~mjwalk.ergonomics.score.Column` s, :data:`CSV_ORDER` first.
    """
    cols = {c.name: c for s in SCORES.values() for c in s.columns}
    return [cols[n] for n in in_order(cols, CSV_ORDER)]
