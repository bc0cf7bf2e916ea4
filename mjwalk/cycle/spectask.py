"""The checks of a cycle specification's ``[[task]]`` tables (:mod:`mjwalk.cycle.spec`: the
format and what each check refuses): a task's keys and values, its sites in the scene, and
what the operator can do where they stand with what their hands hold, each refusal a
:class:`~mjwalk.errors.CycleSpecError` naming the task's key (:class:`~mjwalk.cycle.specfile.
Checker`). World frame: metres, z up; masses in kilograms, durations in seconds."""

from __future__ import annotations

import difflib
from dataclasses import dataclass

import numpy as np

from mjwalk.cycle.levelsite import STAND_MAX_Z, level_workplace, site_level
from mjwalk.cycle.specfile import ALL_TASK_KEYS, MAX_CYCLE_SECONDS, Checker
from mjwalk.cycle.types import TASK_KINDS, Task, TaskKindName, grip_sites
from mjwalk.errors import CycleSpecError
from mjwalk.world.workplace import Workplace

#: Farthest horizontal distance from the standing site to a handled site (arm's reach), metres.
MAX_REACH = 0.9
HANDS = ("left", "right")
#: The heaviest part a pick may declare (kg): beyond any manual lift (the revised NIOSH
#: equation's load constant is 23 kg).
MAX_PART_MASS = 100.0
#: Couplings of a part (the revised NIOSH lifting equation's Table 7) and the default (see
#: :mod:`mjwalk.cycle.spec`).
COUPLINGS = ("good", "fair", "poor")
DEFAULT_COUPLING = "poor"
#: Accepted values of a task's ``hand`` ("both": two-handed).
HAND_VALUES = (*HANDS, "both")
#: The table every task's errors name.
TABLE = "task"


def site_error(
    check: Checker, workplace: Workplace, name: str, table: str, index: int | None, key: str
) -> CycleSpecError:
    """The error for a site the scene lacks, with the closest site names as a hint.

    Args:
        check: the spec file's checker.
        workplace: the scene.
        name: the site named in the file.
        table: the table of the key ("" at the top level).
        index: the task's index (from 0) in an array of tables, None otherwise.
        key: the key that names the site.

    Returns:
        The :class:`~mjwalk.errors.CycleSpecError` to raise (``<file>:<line>: ...``).
    """
    close = difflib.get_close_matches(name, list(workplace.stations), n=3, cutoff=0.5)
    hint = f"; did you mean {', '.join(repr(c) for c in close)}?" if close else ""
    return check.fail(
        f"key {key!r} {check.where(table, index)}: the scene {workplace.name!r} has no site "
        f"named {name!r}{hint}",
        table,
        index,
        key,
    )


def check_stand(
    check: Checker,
    workplace: Workplace,
    name: str,
    radius: float,
    table: str,
    index: int | None,
    key: str,
) -> None:
    """Raise unless site ``name`` is a place on a walk surface with room for the body: at most
    :data:`~mjwalk.cycle.levelsite.STAND_MAX_Z` metres above the floor or above a level of a
    scene on several levels (a platform, a mezzanine: :func:`~mjwalk.cycle.levelsite.
    site_level`), and at least ``radius`` metres from an obstacle or the edge of its level.

    Args:
        check: the spec file's checker.
        workplace: the scene.
        name: the standing site.
        radius: the walking (body) radius, metres.
        table: the table of the key ("" at the top level).
        index: the task's index (from 0) in an array of tables, None otherwise.
        key: the key that names the site.

    Raises:
        CycleSpecError: naming ``key`` when the site is too high or too cramped.
    """
    st = workplace.stations[name]
    height = float(st.pos[2] - workplace.floor_z)
    level = site_level(workplace, name)
    if level is None:
        raise check.fail(
            f"key {key!r} {check.where(table, index)}: site {name!r} is {height:.2f} m above the "
            f"floor, not a standing place (standing sites lie within {STAND_MAX_Z} m of the floor "
            "or of a walk surface's top)",
            table,
            index,
            key,
        )
    room = float(level_workplace(workplace, level).walk_clearance(np.asarray(st.xy)))
    if room < radius:
        edge = "the floor's edge" if level == 0 else f"the edge of level L{level}"
        raise check.fail(
            f"key {key!r} {check.where(table, index)}: site {name!r} is {room:.2f} m from an "
            f"obstacle or {edge}, closer than the walking radius {radius:g} m",
            table,
            index,
            key,
        )


def hands_of(hand: str) -> tuple[str, ...]:
    """The hands of a task's ``hand`` value.

    Args:
        hand: "left", "right" or "both".

    Returns:
        ``("left", "right")`` for "both", else ``(hand,)``.
    """
    return HANDS if hand == "both" else (hand,)


@dataclass
class _Fields:
    """The values of a task's keys, checked (None or the default where a key is absent)."""

    site: str | None
    hand: str | None
    duration: float | None
    route: str | None
    part: str | None
    mass: float
    coupling: str


class _TaskTable:
    """The ``i``-th ``[[task]]`` table ``raw`` of a spec file being checked against the scene
    ``workplace``; its errors name the table's keys (``check.fail(..., "task", i, key)``)."""

    def __init__(self, check: Checker, workplace: Workplace, raw: dict, i: int):
        self.check, self.workplace, self.raw, self.i = check, workplace, raw, i
        self.where = check.where(TABLE, i)

    def fail(self, msg: str, key: str) -> CycleSpecError:
        return self.check.fail(msg, TABLE, self.i, key)

    def kind(self) -> TaskKindName:
        """The task's kind, after checking its keys: known, ``kind`` present and valid, each
        key one of the kind's, the kind's required keys present."""
        check, raw, where = self.check, self.raw, self.where
        own = (k for kind in TASK_KINDS.values() for k in kind.keys if k not in ALL_TASK_KEYS)
        check.keys(raw, (*ALL_TASK_KEYS, *dict.fromkeys(own)), TABLE, self.i)
        if "kind" not in raw:
            raise self.fail(f"missing required key 'kind' {where}", "kind")
        kind: TaskKindName = raw["kind"]
        if kind not in TASK_KINDS:
            close = difflib.get_close_matches(str(kind), TASK_KINDS, n=1, cutoff=0.5)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise self.fail(
                f"key 'kind' {where}: {kind!r} is not a task kind ({' | '.join(TASK_KINDS)}){hint}",
                "kind",
            )
        allowed = TASK_KINDS[kind].keys
        for key in raw:
            if key not in allowed:
                raise self.fail(
                    f"key {key!r} {where} does not apply to a {kind!r} task "
                    f"(keys of a {kind} task: {', '.join(allowed)})",
                    key,
                )
        required = ("duration",) if TASK_KINDS[kind].motion == "wait" else ("site",)
        for key in required:
            if key not in raw:
                raise self.fail(f"missing required key {key!r} {where} ({kind} task)", key)
        return kind

    def fields(self) -> _Fields:
        """The values of the task's keys, each checked (type, range, a site of the scene)."""
        check, raw, where, t, i = self.check, self.raw, self.where, TABLE, self.i
        site = check.string(raw, "site", t, i) if "site" in raw else None
        if site is not None and site not in self.workplace.stations:
            raise site_error(check, self.workplace, site, t, i, "site")
        hand = None
        if "hand" in raw:
            hand = raw["hand"]
            if hand not in HAND_VALUES:
                raise self.fail(
                    f"key 'hand' {where} must be 'left', 'right' or 'both', got {hand!r}", "hand"
                )
        duration = None
        if "duration" in raw:
            duration = check.number(raw, "duration", 0.0, MAX_CYCLE_SECONDS, "s", t, i)
        route = check.string(raw, "route", t, i) if "route" in raw else None
        part = check.string(raw, "part", t, i) if "part" in raw else None
        mass = check.number(raw, "mass", 0.0, MAX_PART_MASS, "kg", t, i) if "mass" in raw else 0.0
        coupling = check.string(raw, "coupling", t, i) if "coupling" in raw else DEFAULT_COUPLING
        if coupling not in COUPLINGS:
            raise self.fail(
                f"key 'coupling' {where} must be one of {', '.join(COUPLINGS)}, got {coupling!r}",
                "coupling",
            )
        return _Fields(site, hand, duration, route, part, mass, coupling)

    def walk(self, kind: str, f: _Fields, radius: float, stand: str, held: dict[str, int]):
        """Check a walk or carry from ``stand`` to ``f.site``: a standing place elsewhere, and
        a carry's hand holding a part; set the carry's hand and the route's label."""
        site, where = f.site, self.where
        assert site is not None  # required (kind)
        if site == stand:
            raise self.fail(f"key 'site' {where}: the operator already stands at {site!r}", "site")
        check_stand(self.check, self.workplace, site, radius, TABLE, self.i, "site")
        if TASK_KINDS[kind].carries:
            if f.hand is None:
                f.hand = next((h for h in HANDS if held[h] > 0), "left")
            if any(held[h] == 0 for h in hands_of(f.hand)):
                key = "hand" if "hand" in self.raw else "kind"
                raise self.fail(
                    f"key {key!r} {where}: a carry with nothing in the {f.hand} hand (pick a part "
                    "first, or use kind = 'walk')",
                    key,
                )
        f.route = f.route or f"{stand}->{site}"

    def reach(self, kind: str, f: _Fields, stand: str, held: dict[str, int]) -> None:
        """Check a pick, place or fasten at ``f.site`` from ``stand``: a hand free for it, a
        two-handed part's grip sites, the site within :data:`MAX_REACH`; then update ``held``
        (a take adds a part to its hands, a put takes one away: there must be one)."""
        site, where, stations = f.site, self.where, self.workplace.stations
        assert site is not None  # required (kind)
        hand = f.hand = f.hand or "left"
        if held["both"] >= 0 and hand != "both":
            # both hands are on the grips of a large part (agethen2018's two-handed parts): a
            # one-handed reach would need a hand the part cannot spare
            raise self.fail(
                f"key 'hand' {where}: a one-handed {kind} ({hand} hand) while both hands hold "
                f"the two-handed part picked at task {held['both']}; place it (hand = 'both') "
                "first",
                "hand" if "hand" in self.raw else "kind",
            )
        if hand == "both":
            for _, grip in grip_sites(site, hand):
                if grip not in stations:
                    raise self.fail(
                        f"key 'site' {where}: a two-handed {kind} (hand = 'both') needs the grip "
                        f"sites {site + '_left'!r} and {site + '_right'!r} in the scene; "
                        f"{grip!r} is missing",
                        "site",
                    )
        dist = float(np.linalg.norm(stations[site].xy - stations[stand].xy))
        if dist > MAX_REACH:
            raise self.fail(
                f"key 'site' {where}: {site!r} is {dist:.2f} m (horizontally) from where the "
                f"operator stands ({stand!r}), beyond arm's reach ({MAX_REACH} m)",
                "site",
            )
        self.handle(kind, hand, held)

    def handle(self, kind: str, hand: str, held: dict[str, int]) -> None:
        """Update ``held`` for a pick (a part into ``hand``) or a place/fasten (one out of it,
        raising when there is none)."""
        if TASK_KINDS[kind].part == "take":
            for h in hands_of(hand):
                held[h] += 1
            if hand == "both":
                held["both"] = self.i
        elif TASK_KINDS[kind].part == "put" and any(held[h] == 0 for h in hands_of(hand)):
            raise self.fail(
                f"key 'kind' {self.where}: a {kind} with nothing in the {hand} hand (no part "
                "picked and not yet placed or fastened)",
                "kind",
            )
        elif TASK_KINDS[kind].part == "put":
            for h in hands_of(hand):
                held[h] -= 1
            if hand == "both":
                held["both"] = -1


def check_task(
    check: Checker,
    workplace: Workplace,
    raw: dict,
    i: int,
    radius: float,
    stand: str,
    held: dict[str, int],
) -> Task:
    """Check the ``i``-th task given where the operator stands and what each hand holds.

    Args:
        check: the spec file's checker.
        workplace: the scene.
        raw: the task's table as read from the TOML file.
        i: the task's index (from 0).
        radius: the walking (body) radius, metres.
        stand: the standing site the operator is at before the task.
        held: parts in each hand ("left", "right") and the index of the task that picked the
            two-handed part in the hands ("both", -1: none); updated for this task.

    Returns:
        The :class:`~mjwalk.cycle.types.Task` (a carry's hand and a walk's route label filled
        in; ``line`` the table's line in the file).

    Raises:
        CycleSpecError: naming the task's offending key.
    """
    table = _TaskTable(check, workplace, raw, i)
    kind = table.kind()
    f = table.fields()
    motion = TASK_KINDS[kind].motion
    if motion == "walk":
        table.walk(kind, f, radius, stand, held)
    elif motion == "reach":
        table.reach(kind, f, stand, held)
    return Task(
        kind=kind,
        site=f.site,
        hand=f.hand or "left",
        duration=f.duration,
        route=f.route,
        part=f.part,
        line=check.lines.line(TABLE, i),
        mass=f.mass,
        coupling=f.coupling,
        options={k: v for k, v in raw.items() if k not in ALL_TASK_KEYS},
    )
