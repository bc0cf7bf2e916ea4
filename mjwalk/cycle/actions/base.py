"""What a cycle's task does, as a class: the :class:`Action` base, the cycle's state passed from
one action to the next (:class:`CycleState`) and what an action hands back (:class:`Performed`).

A task kind (:data:`mjwalk.cycle.types.TASK_KINDS`) names the action that simulates it by the
class's name (``TaskKind.action``, e.g. ``"Walk"``); every subclass of :class:`Action` is
known by its name as soon as it is defined (:func:`action_class`). The cycle
(:func:`mjwalk.cycle.simulate.simulate_cycle`) is a loop: for each task it builds the kind's
action, calls :meth:`Action.check` (before any work), :meth:`Action.plan` (the draws and decisions
made before moving) and then
:meth:`Action.perform` (the humanoid's frames, how long each piece lasts, where the operator
ends up and what the hands hold), and lays the frames end to end.

World frame: metres, z up, yaw in radians from +x; times in seconds.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from mjwalk.errors import CycleSpecError, InputError

if TYPE_CHECKING:
    from mjwalk.cycle.context import CycleContext
    from mjwalk.cycle.types import ArmRecord, Task, TaskKind, WalkRecord
    from mjwalk.gait.walker import Walker

#: Every :class:`Action` subclass by its class name (filled as each is defined).
_ACTIONS: dict[str, type[Action]] = {}


@dataclass(frozen=True, eq=False)
class CycleState:
    """Where the operator is between two tasks: what one action hands to the next.

    Attributes:
        x, y: the pelvis's position on the floor (world, m).
        yaw: the heading the operator faces (radians from +x).
        here: the site the operator works at (the start site, then the last walk's goal).
        home: where the last walk ended (x, y; m): a reach there steps back or in from it.
        grip: the grip distance (m) of the two-handed part in the hands; None: none held.
        t: seconds from the cycle's start.
        pose: the humanoid's last frame (qpos, (nq,)).
    """

    x: float
    y: float
    yaw: float
    here: str
    home: tuple[float, float]
    pose: np.ndarray
    grip: float | None = None
    t: float = 0.0

    def moved(self, **changes: Any) -> CycleState:
        """This state with ``changes`` (a new one: a state never changes).

        Args:
            **changes: new values of fields, by name (e.g. ``x=1.2, here="stand_rack1"``).

        Returns:
            A new :class:`CycleState`.
        """
        return replace(self, **changes)


@dataclass(frozen=True, eq=False)
class CycleRun:
    """What stays the same through one run's actions.

    Attributes:
        ctx: the prepared cycle (models, scene, caches) at the operator's stature.
        walker: the run's operator (None without a ``[population]``: the reference adult).
        fps: frames per second of the humanoid timeline.
        rng: the run's generator (the walks draw from it).
        handling: the stream of the task-time factors (:func:`mjwalk.cycle.handling.task_factor`).
        standing: the stream of where the operator stands (the spot each walk aims at).
        first_pose: the humanoid's first frame (qpos, (nq,)): the standing pose the carrying
            posture starts from.
    """

    ctx: CycleContext
    walker: Walker | None
    fps: float
    rng: np.random.Generator
    handling: np.random.Generator
    standing: np.random.Generator
    first_pose: np.ndarray

    @property
    def pace(self) -> float:
        """The operator's handling pace (1: the reference adult's)."""
        return 1.0 if self.walker is None else self.walker.pace


@dataclass(frozen=True, eq=False)
class Performed:
    """What an action did.

    Attributes:
        pieces: the action's motion as (frames (n, nq), seconds) pieces, in order; the cycle's
            clock advances by each piece's seconds in turn.
        state: where the operator is afterwards (its ``t`` and ``pose`` are set by the cycle
            from the pieces).
        record: the walk or arm motion for the result (None: neither).
        ground: (n,) world z (m) of the surface the operator stands on in each of the pieces'
            frames, in order (the ergonomics measure heights above it); None: the surface under
            where the operator stood before the action (:meth:`CycleContext.ground
            <mjwalk.cycle.context.CycleContext.ground>`), throughout.
    """

    pieces: tuple[tuple[np.ndarray, float], ...]
    state: CycleState
    record: WalkRecord | ArmRecord | None = None
    ground: np.ndarray | None = None


class Action:
    """One task of a cycle in motion. Subclasses fill :meth:`perform` (and :meth:`plan` when
    they draw or decide something first); they are known by their class name
    (:func:`action_class`), which a :class:`~mjwalk.cycle.types.TaskKind` gives as its
    ``action``.

    Args:
        task: the task as the spec gives it.
        kind: its kind (:data:`~mjwalk.cycle.types.TASK_KINDS`).
        index: the task's index in the cycle.
    """

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        known = _ACTIONS.get(cls.__name__)
        if known is not None and (known.__module__, known.__qualname__) != (
            cls.__module__,
            cls.__qualname__,
        ):
            raise InputError(
                f"action {cls.__name__!r} is defined twice ({known.__module__} and "
                f"{cls.__module__}): give the new action another class name"
            )
        _ACTIONS[cls.__name__] = cls  # a module run again replaces its own class

    def __init__(self, task: Task, kind: TaskKind, index: int) -> None:
        self.task = task
        self.kind = kind
        self.index = index

    def check(self, ctx: CycleContext) -> None:
        """Raise :class:`~mjwalk.errors.CycleSpecError` when the task cannot be performed in
        ``ctx``'s scene (called for every task before the cycle starts). Nothing by default.

        Args:
            ctx: the prepared cycle.
        """

    def plan(self, run: CycleRun, state: CycleState) -> Any:
        """What the action draws or decides before moving (a walk's path, a reach's hold time);
        passed to :meth:`perform`. None by default.

        Args:
            run: what stays the same through the run.
            state: where the operator is before the task.

        Returns:
            The action's plan (None by default).
        """
        return None

    def perform(self, run: CycleRun, state: CycleState, plan: Any) -> Performed:
        """The action's frames, how long each piece lasts, the state it leaves and its record.

        Args:
            run: what stays the same through the run.
            state: where the operator is before the task.
            plan: what :meth:`plan` returned.

        Returns:
            What the action did (:class:`Performed`).
        """
        raise NotImplementedError(f"{type(self).__name__}.perform")


def action_class(kind: TaskKind) -> type[Action]:
    """The :class:`Action` subclass that ``kind.action`` names.

    Args:
        kind: the task kind.

    Returns:
        The action class.

    Raises:
        CycleSpecError: no action of that name is defined.
    """
    cls = _ACTIONS.get(kind.action)
    if cls is None:
        raise CycleSpecError(
            f"task kind {kind.name!r}: no action class named {kind.action!r} "
            f"(defined: {', '.join(sorted(_ACTIONS))})"
        )
    return cls
