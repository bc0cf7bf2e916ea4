"""Read and check a cycle specification: a TOML file describing one assembly cycle.

Format (every path is relative to the TOML file; lengths in metres, times in seconds)::

    name = "assembly station of agethen2018"   # optional, free text
    scene = "assembly_station.xml"              # required: the MJCF workplace
    start = "stand_rack2"                       # required: standing site where the operator starts
    takt = 60.0                                 # optional: seconds; the report gives the share
                                                # of cycles over takt (at least 1 s and the
                                                # cycle's waits: MIN_TAKT_SECONDS)

    [humanoid]                                  # optional table
    stature = 1.75                              # metres, 1.4 to 2.1 (default 1.75); with a
                                                # [population] each run's operator's stature

    [models]                                    # optional table
    step = "default"                            # "default" or a step-model file
    reach = "default"                           # "default" or a reach-model file
    reach_right = "right.npz"                   # optional: the right arm's model (default: the
                                                # reach model mirrored); see below

    [walking]                                   # optional table
    radius = 0.25                               # body radius for walking, metres (0.1 to 0.6)

    [population]                                # optional: who operates each run
    mix = { adult = 0.7, older_adult = 0.2, fatigued = 0.1 }   # or walker/figures, see
                                                # mjwalk.cycle.population

    [reference]                                 # optional: published walk lengths per route
    source = "agethen2018 Table 1"              # free text, shown in the report
    median = { T1 = 2.38 }                      # route label -> metres: captured median, IQR,
    iqr = { T1 = 0.21 }                         # and (optional) the source's own planner's
    planner_median = { T1 = 2.41 }              # median and IQR; the report sets them beside
    planner_iqr = { T1 = 0.16 }                 # each route's figures

    [[task]]                                    # one table per task, in order (at least one)
    kind = "pick"                               # walk | carry | pick | place | fasten | wait
    site = "rack2_screw1"
    hand = "left"
    part = "screw"

Keys of a task, by kind (``kind`` is always required):

========  ==========================================  ==========================================
kind      required                                    optional
========  ==========================================  ==========================================
walk      site (a standing site on a walk surface)    route
carry     site (a standing site on a walk surface)    route, hand, part
pick      site (where the part lies)                  hand, part, duration (hold time),
                                                      mass (kg), coupling
place     site (where the part goes)                  hand, part, duration (hold time)
fasten    site (where the part is fastened)           hand, part, duration (screwing time)
wait      duration                                    --
========  ==========================================  ==========================================

``hand`` is "left" (default), "right" or "both"; a carry's hand defaults to the hand holding a part.
``hand = "both"`` is a two-handed pick / carry / place of a large part: the pick and place site
``S`` is the part's centre and the scene must also have the grip sites ``S_left`` and ``S_right``
(where the operator's left and right hand hold it); both hands reach their grips together, hold
the part while carrying, and the place releases both.
``mass`` (kg, default 0: a part too light to count) and ``coupling`` (the grip on it: "good",
"fair" or "poor"; default "poor", the Applications Manual's rule for the revised NIOSH lifting
equation, Waters et al. 1994 p. 16: "if there is any doubt ... the more stressful classification
should be selected") describe the picked part for the ergonomic scores (:mod:`mjwalk.ergonomics`):
the load in the hand until its place or fasten, and a NIOSH lift for its pick and its place.
``route`` labels a walk for the report (walks with one label are pooled, like the paper's T1-T5);
it defaults to ``"<from site>-><to site>"``. ``duration`` is seconds, >= 0; None (absent) means the
simulator's default.

The checks, each raising :class:`~mjwalk.errors.CycleSpecError` whose message starts with
``<file>:<line>:`` and names the key: TOML syntax; unknown keys (with the closest valid key);
missing required keys; wrong types and values; sites the scene lacks (with close names); missing
scene or model files; and impossible tasks, found by following the operator through the cycle from
``start``: a walk/carry to a site that is not a standing place (site higher than
:data:`~mjwalk.cycle.levelsite.STAND_MAX_Z` above the floor and above every level of a scene
on several levels, or closer to an obstacle or its level's edge than the walking radius), a
walk/carry to where the operator already stands, a pick/place/fasten farther
than :data:`~mjwalk.cycle.spectask.MAX_REACH` (horizontally) from where the operator stands, and
a place/fasten/carry with nothing in that hand (picks add a part to the hand; places and fastens
take one away), and a one-handed pick/place/fasten while both hands hold a two-handed part.
"""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path

from mjwalk._io import read_toml
from mjwalk.arms.reach import load_endpoint_model
from mjwalk.conventions import BODY_RADIUS, DEFAULT_STATURE
from mjwalk.cycle.levelsite import site_level
from mjwalk.cycle.population import HUMANOID_STATURE_RANGE, Population, parse_population
from mjwalk.cycle.specfile import (
    MAX_CYCLE_SECONDS,
    MIN_TAKT_SECONDS,
    REFERENCE_KEYS,
    TABLE_KEYS,
    TOP_KEYS,
    Checker,
    KeyLines,
    check_lengths,
)
from mjwalk.cycle.spectask import HANDS, check_stand, check_task, site_error
from mjwalk.cycle.types import TASK_KINDS, CycleSpec, Task
from mjwalk.errors import CycleSpecError, MjwalkError, PlanningError, SceneError

# the grid planner looked up per call (tests replace plan_grid to show no work starts)
from mjwalk.plan import grid as _grid
from mjwalk.plan import occupancy as _occupancy
from mjwalk.world.workplace import Workplace, shared_workplace

#: Allowed humanoid stature, metres.
STATURE_RANGE = HUMANOID_STATURE_RANGE
#: Allowed walking (body) radius, metres.
RADIUS_RANGE = (0.1, 0.6)
#: Largest walk length a [reference] table may give (m): a plausibility bound (a hall's walk).
MAX_REFERENCE_M = 1000.0


def load_cycle_spec(path: str | Path, *, workplace: Workplace | None = None) -> CycleSpec:
    """Read, check and resolve a cycle specification (TOML; format in the module docstring).

    Args:
        path: the TOML file.
        workplace: the scene already loaded (saves loading it again; it must be the spec's
            ``scene``). Default: :func:`mjwalk.world.shared_workplace`.

    Returns:
        The :class:`CycleSpec` with absolute ``scene`` and model paths (models stay
        ``"default"`` when so written), every walk/carry with a ``route`` label and every carry
        with the hand that holds the part; ``Task.line`` is the task's ``[[task]]`` line.

    Raises:
        CycleSpecError: ``<file>:<line>: ...`` naming the offending key (see module docstring).
    """
    path = Path(path)
    data, text = _read(path)
    check = Checker(path, KeyLines(text))
    check_lengths(check, data)
    check.keys(data, TOP_KEYS)
    for key in ("scene", "start", "task"):
        if key not in data:
            what = "at least one [[task]] table" if key == "task" else f"{key} = ..."
            raise check.fail(f"missing required key {key!r} at the top level ({what})", key=key)
    name = check.string(data, "name") if "name" in data else ""
    tables = _tables(check, data)
    stature = DEFAULT_STATURE
    if "stature" in tables["humanoid"]:
        stature = check.number(tables["humanoid"], "stature", *STATURE_RANGE, "m", "humanoid")
    radius = BODY_RADIUS
    if "radius" in tables["walking"]:
        radius = check.number(tables["walking"], "radius", *RADIUS_RANGE, "m", "walking")
    takt = _takt(check, data)
    population: Population | None = None
    if "population" in data:

        def pop_fail(msg: str, key: str) -> CycleSpecError:
            return check.fail(msg, "population", None, key)

        population = parse_population(data["population"], stature, pop_fail)
    base = path.resolve().parent
    models = _models(check, tables["models"], base)
    scene = check.file(data, "scene", base)
    if workplace is None:
        try:
            workplace = shared_workplace(scene)
        except SceneError as exc:
            raise check.fail(f"key 'scene': {exc}", key="scene") from exc

    start = check.string(data, "start")
    if start not in workplace.stations:
        raise site_error(check, workplace, start, "", None, "start")
    check_stand(check, workplace, start, radius, "", None, "start")
    tasks = _tasks(check, workplace, data["task"], start, radius)
    waits = sum(t.duration or 0.0 for t in tasks if TASK_KINDS[t.kind].motion == "wait")
    if takt is not None and takt < waits:
        raise check.fail(
            f"key 'takt' at the top level: {takt:g} s is shorter than the cycle's waits alone "
            f"({waits:g} s), so every cycle would be over takt",
            key="takt",
        )
    _check_routes(check, workplace, start, tasks, radius)
    reference, source = _reference(check, data.get("reference"), tasks)
    return CycleSpec(
        path=path,
        scene=scene,
        start=start,
        tasks=tasks,
        stature=stature,
        step_model=str(models["step"]),
        reach_model=str(models["reach"]),
        reach_model_right=models["reach_right"],
        radius=radius,
        name=name,
        population=population,
        takt=takt,
        reference=reference,
        reference_source=source,
    )


def _read(path: Path) -> tuple[dict, str]:
    """The TOML file's data and text; a syntax error as a CycleSpecError citing its line (and
    a ``[task]`` written for ``[[task]]``)."""
    try:
        return read_toml(path, "cycle spec", CycleSpecError)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        line = int(m.group(1)) if m else 1
        msg = f"{path}:{line}: TOML syntax error: {exc}"
        single = re.search(r"^[ \t]*\[[ \t]*task[ \t]*\]", path.read_text("utf-8"), re.M)
        if single:  # [task] then [[task]]: tomllib cites the second
            at = path.read_text("utf-8").count("\n", 0, single.start()) + 1
            msg += f"; [task] at line {at} is one table: write [[task]] for every task"
        err = CycleSpecError(msg)
        err.path, err.line, err.key = path, line, None
        raise err from exc


def _tables(check: Checker, data: dict) -> dict[str, dict]:
    """The optional tables ([humanoid], [models], [walking], ...), each checked to be a table
    of known keys (empty when absent)."""
    tables: dict[str, dict] = {}
    for table, allowed in TABLE_KEYS.items():
        value = data.get(table, {})
        if not isinstance(value, dict):
            raise check.fail(f"{table!r} must be a table ([{table}])", key=table)
        check.keys(value, allowed, table)
        tables[table] = value
    return tables


def _takt(check: Checker, data: dict) -> float | None:
    """The top-level ``takt`` (seconds), None without one; at least :data:`MIN_TAKT_SECONDS`."""
    takt = None
    if "takt" in data:
        takt = check.number(data, "takt", 0.0, MAX_CYCLE_SECONDS, "s")
        if takt < MIN_TAKT_SECONDS:
            raise check.fail(
                f"key 'takt' at the top level: {takt:g} s is shorter than any cycle can be (at "
                f"least {MIN_TAKT_SECONDS:g} s: one pick takes about a second); takt is the "
                "seconds allowed per cycle, e.g. 60",
                key="takt",
            )
    return takt


def _models(check: Checker, table: dict, base: Path) -> dict[str, str | None]:
    """The [models] table as model name -> "default", an absolute file path (relative to
    ``base``), or for reach_right None: the reach model mirrored. Each reach model file is
    loaded once to check its kind, before any work (a few ms)."""
    models: dict[str, str | None] = {"step": "default", "reach": "default", "reach_right": None}
    for key in TABLE_KEYS["models"]:
        if key in table and table[key] != "default":
            models[key] = str(check.file(table, key, base, "models"))
        elif key in table:
            models[key] = "default"
    for key in ("reach", "reach_right"):
        file = models[key]
        if file is None or file == "default":
            continue
        try:
            load_endpoint_model(file)
        except MjwalkError as exc:
            raise check.fail(f"key {key!r} in [models]: {exc}", "models", None, key) from None
    return models


def _tasks(
    check: Checker, workplace: Workplace, raw_tasks, start: str, radius: float
) -> list[Task]:
    """The [[task]] tables checked in order (:func:`~mjwalk.cycle.spectask.check_task`),
    following the operator from ``start`` and what the hands hold; then their durations."""
    if isinstance(raw_tasks, dict):  # [task] written for [[task]]: cite the table's line
        raise check.fail(
            "[task] is one table; write [[task]] (double brackets: an array of tables, one "
            "per task)",
            "task",
        )
    if not isinstance(raw_tasks, list) or not raw_tasks:
        raise check.fail("key 'task' must be one or more [[task]] tables", key="task")
    tasks: list[Task] = []
    stand = start
    held = dict.fromkeys(HANDS, 0)
    held["both"] = -1  # the task index of the two-handed part in the hands, -1: none
    for i, raw in enumerate(raw_tasks):
        if not isinstance(raw, dict):
            raise check.fail(f"task {i + 1} must be a table ([[task]])", "task", i)
        tasks.append(check_task(check, workplace, raw, i, radius, stand, held))
        if TASK_KINDS[tasks[-1].kind].motion == "walk":
            assert tasks[-1].site is not None  # checked by check_task: walks need a site
            stand = tasks[-1].site
    try:
        check_durations(tasks)
    except CycleSpecError as exc:
        raise check.fail(str(exc), "task", len(tasks) - 1, "duration") from None
    return tasks


def _reference(check: Checker, table, tasks: list[Task]) -> tuple[dict | None, str]:
    """The [reference] table (format in the module doc) as route label -> (median, IQR[,
    planner median, planner IQR]) in metres, and its source; (None, "") without one. Every
    label must be a walk's route; median and IQR are required for each label given."""
    if table is None:
        return None, ""
    if not isinstance(table, dict):
        raise check.fail("'reference' must be a table ([reference])", key="reference")
    check.keys(table, REFERENCE_KEYS, "reference")
    source = check.string(table, "source", "reference") if "source" in table else ""
    routes = {t.route or "" for t in tasks if TASK_KINDS[t.kind].motion == "walk"}
    figures: dict[str, dict[str, float]] = {}
    for key in REFERENCE_KEYS[1:]:
        per_route = table.get(key, {})
        if not isinstance(per_route, dict):
            raise check.fail(
                f"key {key!r} in [reference] must be a table of route label -> metres "
                "(e.g. { T1 = 2.38 })",
                "reference",
                None,
                key,
            )
        for label in per_route:
            if label not in routes:  # the labels of walks' own `route` keys
                raise check.fail(
                    f"key {key!r} in [reference] names route {label!r}, which no walk has "
                    f"(routes: {', '.join(sorted(r for r in routes if r)) or 'none'})",
                    "reference",
                    None,
                    key,
                )
            value = check.number(per_route, label, 0.0, MAX_REFERENCE_M, "m", "reference")
            figures.setdefault(label, {})[key] = value
    out = {}
    for label, f in figures.items():
        if "median" not in f or "iqr" not in f:
            raise check.fail(
                f"route {label!r} in [reference] needs both 'median' and 'iqr'", "reference"
            )
        row: tuple[float, ...] = (f["median"], f["iqr"])
        if "planner_median" in f or "planner_iqr" in f:
            row += (f.get("planner_median", math.nan), f.get("planner_iqr", math.nan))
        out[label] = row
    return out or None, source


def _check_routes(
    check: Checker, workplace: Workplace, start: str, tasks: list[Task], radius: float
) -> None:
    """Raise naming the task of the first walk or carry whose site cannot be reached from
    where the operator stands (grid A* with the walking radius, :func:`mjwalk.plan.grid.
    plan_grid`, on the scene's shared occupancy grid: milliseconds per route): a wall or a
    gap narrower than the body between two sites would make every run fail. A walk to or from a
    site on a raised level needs its levels joined by steps, ramps or stairs
    (:meth:`~mjwalk.world.levels.LevelGraph.reachable`)."""
    occupancy = None
    stand = start
    seen: set[tuple[str, str]] = set()
    for i, task in enumerate(tasks):
        if TASK_KINDS[task.kind].motion != "walk" or task.site is None:
            continue
        pair = (stand, task.site)
        stand = task.site
        if pair in seen:
            continue
        seen.add(pair)
        levels = (site_level(workplace, pair[0]), site_level(workplace, pair[1]))
        if levels != (0, 0):  # a site on a raised level: the levels must connect them
            if levels[1] not in workplace.levels.reachable(levels[0] or 0):
                raise check.fail(
                    f"key 'site' in task {i + 1}: no steps, ramp or stair lead from {pair[0]!r} "
                    f"(level L{levels[0]}) to {pair[1]!r} (level L{levels[1]})",
                    "task",
                    i,
                    "site",
                )
            continue
        if occupancy is None:
            occupancy = _occupancy.shared_grid(workplace, radius=radius)
        try:
            _grid.plan_grid(workplace, pair[0], pair[1], radius=radius, grid=occupancy)
        except PlanningError as exc:
            raise check.fail(
                f"key 'site' in task {i + 1}: no walkable route from {pair[0]!r} to "
                f"{pair[1]!r} for the walking radius {radius:g} m ({exc})",
                "task",
                i,
                "site",
            ) from None


def check_durations(tasks) -> None:
    """Raise CycleSpecError when the tasks' ``duration``s (seconds) add up to more than
    :data:`MAX_CYCLE_SECONDS` (or one is negative or not finite): checked before a cycle's
    timeline is laid out, also for specs built in Python.

    Args:
        tasks: the cycle's tasks (their ``duration``, seconds or None).

    Raises:
        CycleSpecError: naming the task with a bad duration, or the total.
    """
    total = 0.0
    for i, task in enumerate(tasks):
        if task.duration is None:
            continue
        d = float(task.duration)
        if not (math.isfinite(d) and d >= 0.0):
            raise CycleSpecError(f"task {i + 1}: duration must be >= 0 s and finite, got {d:g}")
        total += d
    if total > MAX_CYCLE_SECONDS:
        raise CycleSpecError(
            f"the tasks' durations add up to {total:g} s, more than the longest cycle mjwalk "
            f"simulates ({MAX_CYCLE_SECONDS:g} s)"
        )
