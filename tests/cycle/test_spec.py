"""Cycle specifications: the shipped assembly cycle parses as the paper describes it, and every kind
of mistake raises a CycleSpecError naming the key and its line."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.cycle.types import TASK_KINDS
from mjwalk.errors import CycleSpecError
from mjwalk.world import load_workplace

SCENES = Path(__file__).resolve().parents[2] / "scenes"
SHIPPED = SCENES / "assembly_station.toml"
SCENE = SCENES / "assembly_station.xml"


@pytest.fixture(scope="module")
def workplace():
    return load_workplace(SCENE)


def _line_of(text: str, needle: str, nth: int = 0) -> int:
    hits = [k for k, line in enumerate(text.splitlines(), start=1) if needle in line]
    return hits[nth]


def _shipped_text() -> str:
    # the scene by absolute path, so the text can be written anywhere (same line count)
    return SHIPPED.read_text().replace('"assembly_station.xml"', f'"{SCENE}"')


def _mutate(text: str, old: str, new: str, nth: int = 0) -> str:
    parts = text.split(old)
    assert len(parts) > nth + 1, f"{old!r} occurs fewer than {nth + 1} times"
    return old.join(parts[: nth + 1]) + new + old.join(parts[nth + 1 :])


def _small(tasks: str, start: str = "stand_rack2", extra: str = "") -> str:
    return f'scene = "{SCENE}"\nstart = "{start}"\n{extra}\n{tasks}'


def _expect_error(tmp_path, workplace, text: str, key: str | None, line: int) -> CycleSpecError:
    path = tmp_path / "cycle.toml"
    path.write_text(text)
    with pytest.raises(CycleSpecError) as info:
        load_cycle_spec(path, workplace=workplace)
    msg = str(info.value)
    assert msg.startswith(f"{path}:{line}: "), msg
    assert info.value.line == line
    if key is not None:
        assert f"{key!r}" in msg, msg
        assert info.value.key == key
    return info.value


def test_shipped_cycle_is_the_papers(workplace):
    spec = load_cycle_spec(SHIPPED, workplace=workplace)
    assert spec.name == "assembly station of agethen2018"
    assert spec.scene == SCENE.resolve() and spec.start == "stand_rack2"
    assert spec.stature == 1.75 and 0.2 <= spec.radius <= 0.35
    assert spec.step_model == spec.reach_model == "default"
    kinds = [t.kind for t in spec.tasks]
    assert kinds == (
        ["pick", "pick", "carry", "fasten", "fasten"]
        + ["walk", "pick", "pick", "carry", "fasten", "fasten"] * 2
        + ["walk", "pick", "carry", "place"]
    )
    walks = [t for t in spec.tasks if t.kind in ("walk", "carry")]
    assert len(walks) == 7
    assert [t.route for t in walks] == ["T1", "T2", "T2", "T3", "T3", "T4", "T5"]
    assert len({t.route for t in walks}) == 5
    assert [t.site for t in walks] == [
        "stand_car1",
        "stand_rack3",
        "stand_car2",
        "stand_rack1",
        "stand_car3",
        "stand_rack2",
        "stand_rack3",
    ]
    fastens = [t for t in spec.tasks if t.kind == "fasten"]
    assert [t.site for t in fastens] == [f"car_screw{k}" for k in range(1, 7)]
    assert all(t.duration == 4.0 for t in fastens)
    # a right-handed operator: screws with the left hand, the tool with the right
    assert all(t.hand == ("right" if t.part == "tool" else "left") for t in spec.tasks)
    assert spec.tasks[-1].site == "rack3_tool" and spec.tasks[-1].part == "tool"
    text = SHIPPED.read_text()
    assert [t.line for t in spec.tasks] == [
        _line_of(text, "[[task]]", k) for k in range(len(spec.tasks))
    ]


def test_loads_the_scene_itself_and_defaults():
    spec = load_cycle_spec(SHIPPED)  # loads the workplace (about a second)
    assert len(spec.tasks) == 21


def test_defaults_routes_and_carry_hand(tmp_path, workplace):
    text = _small(
        '[[task]]\nkind = "pick"\nsite = "rack2_screw1"\nhand = "right"\n'
        '[[task]]\nkind = "carry"\nsite = "stand_car1"\n'
        '[[task]]\nkind = "wait"\nduration = 2.5\n'
    )
    path = tmp_path / "c.toml"
    path.write_text(text)
    spec = load_cycle_spec(path, workplace=workplace)
    assert spec.tasks[1].route == "stand_rack2->stand_car1"
    assert spec.tasks[1].hand == "right"  # the hand that holds the part
    assert spec.tasks[2].site is None and spec.tasks[2].duration == 2.5
    assert spec.stature == 1.75 and spec.radius == 0.25


def test_toml_syntax_error(tmp_path, workplace):
    text = _mutate(_shipped_text(), "stature = 1.75", "stature = = 1.75")
    err = _expect_error(tmp_path, workplace, text, None, _line_of(text, "stature = ="))
    assert "TOML syntax error" in str(err)


@pytest.mark.parametrize(
    ("old", "new", "key", "suggest"),
    [
        ('name = "assembly', 'nmae = "assembly', "nmae", "name"),
        ("stature = 1.75", "statur = 1.75", "statur", "stature"),
        ('reach = "default"', 'raech = "default"', "raech", "reach"),
        ("radius = ", "radus = ", "radus", "radius"),
    ],
)
def test_unknown_top_and_table_keys(tmp_path, workplace, old, new, key, suggest):
    text = _mutate(_shipped_text(), old, new)
    err = _expect_error(tmp_path, workplace, text, key, _line_of(text, new))
    assert f"did you mean {suggest!r}" in str(err)


def test_unknown_task_key_names_its_line(tmp_path, workplace):
    # the 7th task (a pick at rack 3) gets a misspelt hand
    text = _mutate(_shipped_text(), 'hand = "left"', 'hnd = "left"', nth=5)
    line = _line_of(text, 'hnd = "left"')
    assert _line_of(text, 'site = "rack3_screw1"') < line
    err = _expect_error(tmp_path, workplace, text, "hnd", line)
    assert "did you mean 'hand'" in str(err) and "task 7" in str(err)


def test_key_not_for_this_kind(tmp_path, workplace):
    text = _mutate(_shipped_text(), 'route = "T4"', 'route = "T4"\nduration = 1.0')
    line = _line_of(text, "duration = 1.0")
    err = _expect_error(tmp_path, workplace, text, "duration", line)
    assert "does not apply to a 'walk' task" in str(err)


def test_missing_required_keys(tmp_path, workplace):
    text = _mutate(_shipped_text(), 'start = "stand_rack2"\n', "\n")
    _expect_error(tmp_path, workplace, text, "start", 1)
    # a task without site: the error points at its [[task]] header
    text = _mutate(_shipped_text(), 'site = "stand_rack1"\n', "")
    header = _line_of(text, 'route = "T3"') - 2
    assert text.splitlines()[header - 1] == "[[task]]"
    _expect_error(tmp_path, workplace, text, "site", header)
    _expect_error(tmp_path, workplace, _small('[[task]]\nkind = "wait"\n'), "duration", 4)
    _expect_error(tmp_path, workplace, _small(""), "task", 1)


@pytest.mark.parametrize(
    ("old", "new", "key", "nth", "words"),
    [
        ('kind = "fasten"', 'kind = "screw"', "kind", 0, "not a task kind"),
        ('kind = "walk"', 'kind = "wakl"', "kind", 1, "did you mean 'walk'"),
        ('hand = "left"', 'hand = "middle"', "hand", 3, "'left', 'right' or 'both'"),
        ("duration = 4.0", "duration = -1.0", "duration", 2, "between 0 and 3600 s"),
        ("duration = 4.0", 'duration = "4 s"', "duration", 0, "must be a number"),
        ("stature = 1.75", "stature = 2.5", "stature", 0, "between 1.4 and 2.1"),
        ('site = "car_screw4"', 'site = "car_screw7"', "site", 0, "no site named 'car_screw7'"),
        ('site = "car_screw4"', "site = 4", "site", 0, "non-empty string"),
        ('start = "stand_rack2"', 'start = "stand_rak2"', "start", 0, "did you mean 'stand_rack2'"),
        ('scene = "', 'scene = "nope/', "scene", 0, "not found"),
        ('step = "default"', 'step = "missing_model.npz"', "step", 0, "not found"),
    ],
)
def test_wrong_values(tmp_path, workplace, old, new, key, nth, words):
    text = _mutate(_shipped_text(), old, new, nth=nth)
    err = _expect_error(tmp_path, workplace, text, key, _line_of(text, new))
    assert words in str(err)


def test_walk_to_a_site_that_is_not_a_standing_place(tmp_path, workplace):
    text = _mutate(_shipped_text(), 'site = "stand_rack3"', 'site = "rack3_screw1"')
    err = _expect_error(tmp_path, workplace, text, "site", _line_of(text, 'site = "rack3_screw1"'))
    assert "not a standing place" in str(err)


def test_stand_site_too_close_to_obstacles(tmp_path, workplace):
    text = re.sub(r"radius = [\d.]+", "radius = 0.5", _shipped_text())
    err = _expect_error(tmp_path, workplace, text, "start", _line_of(text, "start = "))
    assert "closer than the walking radius 0.5 m" in str(err)


def test_pick_beyond_reach(tmp_path, workplace):
    # from stand_rack2 the screws of rack 3 are 1.12 m away
    text = _mutate(_shipped_text(), 'site = "rack2_screw2"', 'site = "rack3_screw2"')
    err = _expect_error(tmp_path, workplace, text, "site", _line_of(text, 'site = "rack3_screw2"'))
    assert "beyond arm's reach" in str(err) and "'stand_rack2'" in str(err)
    # ... and the tracked stand site follows the walks: car_screw1 is out of reach from stand_car2
    text = _mutate(_shipped_text(), 'site = "car_screw3"', 'site = "car_screw1"')
    err = _expect_error(tmp_path, workplace, text, "site", _line_of(text, 'site = "car_screw1"', 1))
    assert "'stand_car2'" in str(err)


def test_fasten_and_carry_with_empty_hand(tmp_path, workplace):
    tasks = (
        '[[task]]\nkind = "pick"\nsite = "rack2_screw1"\n'
        '[[task]]\nkind = "carry"\nsite = "stand_car1"\n'
        '[[task]]\nkind = "fasten"\nsite = "car_screw1"\n'
        '[[task]]\nkind = "fasten"  # nothing left\nsite = "car_screw2"\n'
    )
    text = _small(tasks)
    err = _expect_error(tmp_path, workplace, text, "kind", _line_of(text, "nothing left"))
    assert "fasten with nothing in the left hand" in str(err)
    # a pick with the right hand does not fill the left one
    text = _small(tasks.replace('site = "rack2_screw1"', 'site = "rack2_screw1"\nhand = "right"'))
    text = text.replace('site = "stand_car1"', 'site = "stand_car1"\nhand = "right"')
    _expect_error(tmp_path, workplace, text, "kind", _line_of(text, 'kind = "fasten"'))
    text = _small('[[task]]\nkind = "carry"\nsite = "stand_car1"\n')
    err = _expect_error(tmp_path, workplace, text, "kind", _line_of(text, 'kind = "carry"'))
    assert "carry with nothing" in str(err)


def test_walk_to_where_the_operator_stands(tmp_path, workplace):
    text = _mutate(_shipped_text(), 'site = "stand_car2"', 'site = "stand_rack3"')
    line = _line_of(text, 'site = "stand_rack3"', 1)
    err = _expect_error(tmp_path, workplace, text, "site", line)
    assert re.search(r"already stands at 'stand_rack3'", str(err))


def test_missing_spec_file(tmp_path):
    with pytest.raises(CycleSpecError, match="not found"):
        load_cycle_spec(tmp_path / "nope.toml")


def test_task_kinds_table_says_what_the_lower_stages_read():
    """The flags the cycle hands to the ergonomics and the timeline (reach, part, lifts) come
    from the one table: the reaches are pick, place and fasten; a pick takes its part, a place
    or fasten puts it down; pick and place are NIOSH lifts, a fastening is not."""
    reach = {k for k, v in TASK_KINDS.items() if v.motion == "reach"}
    assert reach == {"pick", "place", "fasten"}
    assert {k: v.part for k, v in TASK_KINDS.items() if v.part} == {
        "pick": "take",
        "place": "put",
        "fasten": "put",
    }
    assert {k for k, v in TASK_KINDS.items() if v.lifts} == {"pick", "place"}


def test_reference_table_is_read_and_checked(tmp_path, workplace):
    """The shipped cycle's [reference] is agethen2018 Table 1 (captured and the paper's
    planner); a route no walk has, a missing IQR or a negative length is named."""
    path = tmp_path / "cycle.toml"
    text = _shipped_text()
    path.write_text(text)
    spec = load_cycle_spec(path, workplace=workplace)
    assert spec.reference is not None and set(spec.reference) == {"T1", "T2", "T3", "T4", "T5"}
    assert spec.reference["T3"] == (3.15, 0.38, 3.11, 0.21)
    assert "agethen2018" in spec.reference_source
    bad = _mutate(text, "iqr = { T1 = 0.21,", "iqr = { T9 = 0.21,")
    path.write_text(bad)
    with pytest.raises(CycleSpecError, match="route 'T9'"):
        load_cycle_spec(path, workplace=workplace)
    path.write_text(_mutate(text, "iqr = { T1 = 0.21, ", "iqr = { "))
    with pytest.raises(CycleSpecError, match="'T1' in \\[reference\\] needs both"):
        load_cycle_spec(path, workplace=workplace)
    path.write_text(_mutate(text, "median = { T1 = 2.38", "median = { T1 = -2.38"))
    with pytest.raises(CycleSpecError, match="'T1'"):
        load_cycle_spec(path, workplace=workplace)
