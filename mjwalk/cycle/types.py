"""Data of an assembly cycle: its specification (from TOML) and the result of simulating it."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from mjwalk.conventions import BODY_RADIUS, DEFAULT_STATURE
from mjwalk.gait.walker import Walker
from mjwalk.plan.walkpath import WalkPath

if TYPE_CHECKING:  # the timeline stage is above this one at run time: no import
    from mjwalk.cycle.population import Population
    from mjwalk.ergonomics.assess import RunErgonomics
    from mjwalk.timeline.collisions import Contact
    from mjwalk.timeline.timeline import Timeline

#: The name of a task kind (the ``kind`` key of a ``[[task]]``; :data:`TASK_KINDS`).
TaskKindName = Literal["walk", "carry", "pick", "place", "fasten", "wait"]


@dataclass(frozen=True)
class TaskKind:
    """What a task of one kind does (an entry of :data:`TASK_KINDS`).

    Attributes:
        name: the ``kind`` of a ``[[task]]``.
        keys: the keys a task of this kind may have in the cycle TOML.
        motion: what the spec checks, the stand zones and the walks take the task for:
            ``"walk"`` (to ``site``: the operator leaves where they stand), ``"reach"`` (a hand
            to ``site``, held there and back) or ``"wait"`` (standing still).
        action: the name of the :class:`~mjwalk.cycle.actions.base.Action` subclass that
            simulates it (``"Walk"``, ``"Reach"``, ``"Wait"``, :mod:`mjwalk.cycle.actions`).
        carries: a walk with a part in the hands.
        part: what a reach does with a part: ``"take"`` it into the hand (the hand holds it
            afterwards), ``"put"`` it down (the hand must hold one), or None.
        lifts: a reach that lifts the part from its site or lowers it onto it, scored by the
            revised NIOSH lifting equation (:mod:`mjwalk.ergonomics.niosh`); a fastening
            holds the part against a surface and is not a lift.
        reach_case: the MTM-1 reach case (:mod:`mjwalk.cycle.handling`) of its reach; the
            return is case E.
        default_hold: seconds at the site (reach) or standing (wait) when the task gives no
            ``duration``: the reference adult's median.
        approach: how the hand comes onto a reach's target (:mod:`mjwalk.cycle.targets`):
            ``"shelf"`` from above and in front, stopping above the site, along the stand
            site's facing; ``"surface"`` level, from the operator, stopping in front of the
            site, the operator facing it squarely.
    """

    name: str
    keys: tuple[str, ...]
    motion: Literal["walk", "reach", "wait"]
    action: str
    carries: bool = False
    part: Literal["take", "put"] | None = None
    lifts: bool = False
    reach_case: str | None = None
    default_hold: float | None = None
    approach: Literal["shelf", "surface"] | None = None


_REACH_KEYS = ("kind", "site", "hand", "part", "duration")
#: Every task kind, in the order reports list them. A new kind is one entry here (and its name
#: in :data:`TaskKindName`); a new action is one module with its
#: :class:`~mjwalk.cycle.actions.base.Action` subclass, which the entry names (README, "Adding
#: a task kind"). Reach cases (MTM-1): a pick takes a small part from a bin of like parts
#: (case C: search and select, the station's screws); a place or fasten brings the hand to a
#: location that varies slightly (case B). Default holds: a pick or place 0.4 s, a fastening
#: 3 s, a wait 1 s.
TASK_KINDS: dict[str, TaskKind] = {
    k.name: k
    for k in (
        TaskKind("walk", ("kind", "site", "route"), "walk", "Walk"),
        TaskKind("carry", ("kind", "site", "route", "hand", "part"), "walk", "Walk",
                 carries=True),
        TaskKind("pick", (*_REACH_KEYS, "mass", "coupling"), "reach", "Reach", part="take",
                 lifts=True, reach_case="C", default_hold=0.4, approach="shelf"),
        TaskKind("place", _REACH_KEYS, "reach", "Reach", part="put", lifts=True,
                 reach_case="B", default_hold=0.4, approach="shelf"),
        TaskKind("fasten", _REACH_KEYS, "reach", "Reach", part="put", reach_case="B",
                 default_hold=3.0, approach="surface"),
        TaskKind("wait", ("kind", "duration"), "wait", "Wait", default_hold=1.0),
    )
}  # fmt: skip


def grip_sites(site: str, hand: str) -> list[tuple[str, str]]:
    """The (side, site name) pairs of the hands reaching for ``site``.

    Args:
        site: the task's site.
        hand: "left", "right" or "both".

    Returns:
        ``[(hand, site)]`` for one hand, ``[("left", site + "_left"), ("right", site +
        "_right")]`` for ``hand = "both"``.
    """
    if hand == "both":
        return [("left", f"{site}_left"), ("right", f"{site}_right")]
    return [(hand, site)]


@dataclass
class Task:
    """One task of a cycle, as written in the spec.

    Attributes:
        kind: "walk" or "carry" (to ``site``), "pick"/"place"/"fasten" (at ``site``), "wait"
            (:data:`TASK_KINDS` says what each does).
        site: the target site (walk/carry: where to stand; pick/place/fasten: the part's site).
        hand: "left", "right" or "both" (pick/place/fasten/carry; "both": a two-handed part
            held at the grip sites ``<site>_left`` and ``<site>_right``).
        duration: seconds the task takes beyond the motion itself (fasten: screwing time;
            wait: the waiting time; pick/place: optional hold time). None = the default.
        route: label of the walk route for the report (e.g. "T1"); walks with the same label are
            pooled.
        part: what is handled (free text, e.g. "screw").
        line: line of the task in the TOML file (for error messages).
        mass: the picked part's mass, kg (pick; 0: not counted), for the ergonomic scores.
        coupling: the grip on the picked part ("good", "fair", "poor").
        options: the task's keys beyond the common ones (a new kind's own, e.g. an
            ``inspect``'s ``look``), as written in the TOML.
    """

    kind: TaskKindName
    site: str | None = None
    hand: str = "left"
    duration: float | None = None
    route: str | None = None
    part: str | None = None
    line: int = 0
    mass: float = 0.0
    coupling: str = "poor"
    options: dict[str, Any] = field(default_factory=dict)


@dataclass
class CycleSpec:
    """A parsed cycle specification.

    Attributes:
        path: the TOML file.
        scene: the MJCF scene (resolved relative to the TOML file).
        start: the site where the operator starts.
        stature: humanoid stature, metres.
        step_model: "default" or a path to a step-model file.
        reach_model: "default" or a path to a reach-model file (an endpoint model of the left
            arm; the right arm mirrors it unless ``reach_model_right`` is given).
        reach_model_right: None (the right arm mirrors ``reach_model``), "default" or a path to
            the right arm's model (trained on right-arm clips, which
            :func:`~mjwalk.arms.armcapture.arm_movements` mirrors into the left arm's frame).
        tasks: the ordered tasks.
        radius: body radius for walking, metres.
        population: who operates each run (:mod:`mjwalk.cycle.population`); None: the step
            model's own pace, handling at the reference adult's pace, the ``stature`` humanoid.
        takt: the takt time, seconds (None: not given); the report gives P(cycle > takt).
        reference, reference_source: published walk lengths per route and their source
            (the spec's [reference] table), set beside the routes in the report.
    """

    path: Path
    scene: Path
    start: str
    tasks: list[Task]
    stature: float = DEFAULT_STATURE
    step_model: str = "default"
    reach_model: str = "default"
    reach_model_right: str | None = None
    radius: float = BODY_RADIUS
    name: str = ""
    population: Population | None = None
    takt: float | None = None
    #: Published walk lengths per route label, metres: (median, IQR) or (median, IQR, the
    #: source's planner's median, its IQR; nan where not given); None: none ([reference]).
    reference: dict[str, tuple[float, ...]] | None = None
    #: Where :attr:`reference` comes from (free text; "" without one).
    reference_source: str = ""


@dataclass
class TaskRecord:
    """When a task happened in a simulated cycle (seconds from the cycle's start)."""

    index: int
    kind: str
    site: str | None
    start: float
    end: float
    route: str | None = None

    @property
    def duration(self) -> float:
        return self.end - self.start


@dataclass
class WalkRecord:
    """One walk of a simulated cycle: the planned path and the grid-A* route for comparison.

    Attributes:
        task: index of the walk's task in the cycle.
        route: the task's route label (several walks may share one, e.g. there and back).
        start_site, goal_site: the sites walked from and to (the walk's direction).
        path: the walk (pelvis path from where the operator stood to where the walk ended).
        baseline_length: metres of the grid-A* route between the walk's own ends
            (``path.xy[0]`` and ``path.xy[-1]``, :func:`~mjwalk.plan.grid.plan_grid`); NaN when
            the grid planner finds none between them.
        baseline: that route (None when not kept or not found).
    """

    task: int
    route: str
    start_site: str
    goal_site: str
    path: WalkPath
    baseline_length: float
    baseline: WalkPath | None = None

    @cached_property
    def length(self) -> float:
        """The walked length (:attr:`WalkPath.length`), kept once read: a report reads every
        walk's about a dozen times.

        Returns:
            Metres along the path's samples.
        """
        return self.path.length

    @property
    def duration(self) -> float:
        return self.path.duration

    @property
    def direction(self) -> str:
        """``"start_site->goal_site"``."""
        return f"{self.start_site}->{self.goal_site}"

    @property
    def vs_baseline(self) -> float:
        """The walk's length over its grid-A* route's, minus 1 (NaN without a route)."""
        base = self.baseline_length
        return self.length / base - 1.0 if base > 0 else float("nan")


@dataclass
class ArmRecord:
    """One arm motion (pick/place/fasten) of a simulated cycle.

    Attributes:
        hand_error: distance of the hand's end from its target at the end of the reach,
            metres, as the humanoid holds it (its joint ranges applied).
        outside: the constraint lay outside the reach model's trained range (see warnings).
        step_back: metres the operator stepped back from where the walk ended so the arm
            clears the scene (:mod:`mjwalk.cycle.standoff`); 0 when it was clear there;
            negative when they stepped in towards a target out of reach from there.
    """

    task: int
    kind: str
    site: str
    hand: str
    duration: float
    hand_error: float
    outside: bool = False
    warnings: list[str] = field(default_factory=list)
    step_back: float = 0.0


@dataclass
class CycleResult:
    """The outcome of simulating one cycle.

    Attributes:
        spec: the specification simulated.
        run: index of the run (Monte Carlo).
        seed: the random seed: the batch's root seed for a run of
            :func:`~mjwalk.cycle.simulate.simulate_cycles` (``--seed``), else the seed the
            cycle's generator was made from (None when it cannot be recovered).
        entropy: the run's ``SeedSequence`` entropy (``[seed, run]`` in a batch): the cycle is
            re-simulated by ``simulate_cycle(spec, default_rng(SeedSequence(entropy)))``.
        tasks: time spans of the tasks.
        walks: the walks, in order.
        arms: the arm motions, in order.
        cycle_time: seconds from the first task's start to the last task's end.
        collisions: humanoid-vs-scene contacts (:class:`~mjwalk.timeline.collisions.Contact`),
            if checked.
        timeline: the per-frame humanoid poses (kept only when asked for: it is large).
        operator: the run's operator, drawn from ``spec.population`` (None without one).
        ergonomics: the run's ergonomic scores (:mod:`mjwalk.ergonomics.assess`; None when not
            scored).
        error: why the run failed (``simulate_cycles(on_error="record")``): then it has no
            tasks, walks or arms and its cycle time is NaN; None for a simulated cycle.
    """

    spec: CycleSpec
    run: int
    seed: int | None
    tasks: list[TaskRecord]
    walks: list[WalkRecord]
    arms: list[ArmRecord]
    cycle_time: float
    collisions: list[Contact] = field(default_factory=list)
    timeline: Timeline | None = None
    entropy: int | list[int] | None = None
    operator: Walker | None = None
    error: str | None = None
    ergonomics: RunErgonomics | None = None

    @property
    def group(self) -> str:
        """The operator's group label ("" without a population)."""
        return "" if self.operator is None else self.operator.group

    def walk_lengths(self) -> dict[str, list[float]]:
        """Walk lengths by route label.

        Returns:
            Route label -> the lengths (m) of the run's walks with that label, in order.
        """
        out: dict[str, list[float]] = {}
        for w in self.walks:
            out.setdefault(w.route, []).append(w.length)
        return out

    def summary(self) -> dict:
        """Plain-data summary (JSON-ready).

        Returns:
            A dict: run, seed, entropy, cycle time (s), operator (:func:`operator_dict`), walks
            (route, sites, length m, duration s, grid-A* length m), tasks (index, kind, site, start
            and end s), the number of collisions, the largest hand error (m) and the number of
            reaches outside the model's range.
        """
        return {
            "run": self.run,
            "seed": self.seed,
            "entropy": self.entropy,
            "cycle_time": self.cycle_time,
            "operator": operator_dict(self.operator),
            "walks": [
                {
                    "route": w.route,
                    "from": w.start_site,
                    "to": w.goal_site,
                    "length": w.length,
                    "duration": w.duration,
                    "baseline_length": w.baseline_length,
                }
                for w in self.walks
            ],
            "tasks": [
                {"index": t.index, "kind": t.kind, "site": t.site, "start": t.start, "end": t.end}
                for t in self.tasks
            ],
            "collisions": len(self.collisions),
            "max_hand_error": max((a.hand_error for a in self.arms), default=0.0),
            "reach_outside_range": int(sum(a.outside for a in self.arms)),
        }


def operator_dict(walker: Walker | None) -> dict | None:
    """A run's operator as plain data.

    Args:
        walker: the operator; None: none (the reference adult).

    Returns:
        group, stature (m), speed (m/s), cadence (steps/min), step_width (m or None), pace
        (speed / reference speed); None without an operator.
    """
    if walker is None:
        return None
    return {
        "group": walker.group,
        "stature": walker.stature,
        "speed": walker.speed,
        "cadence": walker.cadence,
        "step_width": walker.step_width,
        "pace": walker.pace,
    }
