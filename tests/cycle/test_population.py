"""Issue 14 item 2: the cycle file's [population] (operators drawn per run), takt and the
report's per-group cycle times. Seeded; tolerances stated per test."""

from __future__ import annotations

import csv
import dataclasses
import json

import numpy as np
import pytest

from mjwalk.cycle.copula import STEP_STATURE_MAX
from mjwalk.cycle.population import RANGES, Distribution, parse_population
from mjwalk.cycle.simulate import prepare, simulate_cycle, simulate_cycles
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import CycleSpecError
from mjwalk.gait.walker import PRESETS, REFERENCE_SPEED
from mjwalk.report import over_takt, report_dict, write_report

N_DRAWS = 4000


def _draws(pop, n=N_DRAWS, seed=0):
    rng = np.random.default_rng(seed)
    return [pop.draw(rng) for _ in range(n)]


@pytest.mark.parametrize(
    "table",
    [
        {"dist": "normal", "mean": 1.3, "sd": 0.2},
        {"dist": "truncnorm", "mean": 1.3, "sd": 0.3, "min": 0.9, "max": 1.6},
        {"dist": "lognormal", "median": 1.2, "cv": 0.2},
        {"dist": "lognormal", "mean": 1.2, "sd": 0.25, "max": 1.7},
    ],
)
def test_draws_follow_the_distribution(table):
    """Sample mean and sd of 4000 draws within 0.01 m/s (about 3 standard errors) and 5 % of
    the truncated distribution's; every draw inside its bounds."""
    pop = parse_population({"walker": "adult", "speed": table}, 1.75)
    dist = pop.groups[0].speed
    mean, sd = dist.moments()
    x = np.array([w.speed for w in _draws(pop)])
    assert x.mean() == pytest.approx(mean, abs=0.01)
    assert x.std(ddof=1) == pytest.approx(sd, rel=0.05)
    assert dist.lo <= x.min() and x.max() <= dist.hi
    if table["dist"] == "lognormal" and "median" in table:
        assert np.median(x) == pytest.approx(table["median"], rel=0.02)
    if "min" in table:
        assert x.min() >= table["min"] and x.max() <= table["max"]


def test_moments_of_an_untruncated_normal_are_its_figures():
    d = Distribution("normal", 1.3, 0.2, *RANGES["speed"])
    assert d.moments() == pytest.approx((1.3, 0.2), abs=1e-6)


def test_mixture_shares_and_preset_figures():
    """Shares within 0.025 (about 3.5 standard errors at n = 4000) of the normalised mix;
    each group's speed and cadence means within 0.02 m/s and 1 step/min of its preset's."""
    pop = parse_population({"mix": {"adult": 7, "older_adult": 2, "elderly": 1}}, 1.75)
    ws = _draws(pop)
    groups = np.array([w.group for w in ws])
    for name, share in (("adult", 0.7), ("older_adult", 0.2), ("elderly", 0.1)):
        assert np.mean(groups == name) == pytest.approx(share, abs=0.025)
        sel = [w for w in ws if w.group == name]
        p = PRESETS[name]
        assert np.mean([w.speed for w in sel]) == pytest.approx(p.speed[0], abs=0.02)
        assert np.mean([w.cadence for w in sel]) == pytest.approx(p.cadence[0], abs=1.0)
        assert np.mean([w.stature for w in sel]) == pytest.approx(p.stature[0], abs=0.01)
    # statures come in whole centimetres, within the humanoid's range
    st = np.array([w.stature for w in ws])
    assert np.allclose(st * 100, np.round(st * 100))
    assert RANGES["stature"][0] <= st.min() and st.max() <= RANGES["stature"][1]


def test_speed_and_cadence_correlate_as_step_length_and_cadence_vary_independently():
    """Adult preset, 4000 draws: the logs of speed and cadence correlate with rho = cv_cadence /
    cv_speed (0.58) within 0.05 (about 3.5 standard errors); step length (speed * 60 / cadence)
    is then uncorrelated with cadence (|r| < 0.05) and its CV is sqrt(cv_s^2 - cv_c^2) (0.10)
    within 0.01; the marginals keep their preset's means and SDs."""
    pop = parse_population({"mix": {"adult": 1}}, 1.75)
    ws = _draws(pop)
    speed = np.array([w.speed for w in ws])
    cadence = np.array([w.cadence for w in ws])
    step = np.array([w.step_length for w in ws])
    p = PRESETS["adult"]
    cv_s, cv_c = p.speed[1] / p.speed[0], p.cadence[1] / p.cadence[0]
    rho = pop.groups[0].speed_cadence_rho()
    assert rho == pytest.approx(cv_c / cv_s)
    assert np.corrcoef(np.log(speed), np.log(cadence))[0, 1] == pytest.approx(rho, abs=0.05)
    assert abs(np.corrcoef(np.log(step), np.log(cadence))[0, 1]) < 0.05
    assert step.std() / step.mean() == pytest.approx(np.sqrt(cv_s**2 - cv_c**2), abs=0.01)
    assert speed.std() == pytest.approx(p.speed[1], rel=0.05)
    assert cadence.std() == pytest.approx(p.cadence[1], rel=0.05)
    # a fixed cadence: no correlation to model
    assert (
        parse_population(
            {"walker": "adult", "speed": {"dist": "normal", "mean": 1.3, "sd": 0.1}}, 1.75
        )
        .groups[0]
        .speed_cadence_rho()
        == 0.0
    )


@pytest.mark.parametrize("name", list(PRESETS))
def test_stature_and_step_length_correlate_keeping_the_marginals(name):
    """Each preset, 10 000 seeded draws: stature and step length correlate (logs) within 0.03
    (about 3 standard errors, the centimetre statures and the cap included) of
    ``stature_step_rho`` (adult 0.52, elderly 0.29, brisk 0.81); stature and cadence do not
    (|r| < 0.03, Samson et al. 2001); each figure's mean within 3 standard errors and SD within
    3 % of its preset's (the marginals unchanged); step over stature never above the cap."""
    pop = parse_population({"mix": {name: 1}}, 1.75)
    ws = _draws(pop, 10000, seed=47)
    st, sp, ca = (np.array([getattr(w, f) for w in ws]) for f in ("stature", "speed", "cadence"))
    step = sp * 60.0 / ca
    g = pop.groups[0]
    assert np.corrcoef(np.log(st), np.log(step))[0, 1] == pytest.approx(
        g.stature_step_rho(), abs=0.03
    )
    assert abs(np.corrcoef(st, ca)[0, 1]) < 0.03
    p = PRESETS[name]
    for x, (mean, sd) in ((st, p.stature), (sp, p.speed), (ca, p.cadence)):
        assert x.mean() == pytest.approx(mean, abs=3 * sd / 100)
        assert x.std() == pytest.approx(sd, rel=0.03)
    assert (step / st).max() <= STEP_STATURE_MAX
    assert pop.describe()[0]["stature_step_rho"] == round(g.stature_step_rho(), 3)


def test_step_over_stature_cap_and_what_the_marginals_force():
    """A wide speed at a short stature (4000 seeded draws): no step above STEP_STATURE_MAX x
    stature, the stature's mean and SD still its own (within 0.005 m and 5 % of the truncated
    normal's); the same figures
    at a fixed stature have no cap (more than 10 % of the steps above it, as before). A fixed
    fast walker of varying stature whose step is above the cap at every stature (2.4 m/s at 100
    steps/min: 1.44 m) is what the marginals force: the draws stand (speed and cadence as given,
    the stature drawn)."""
    figs = {
        "speed": {"dist": "normal", "mean": 1.5, "sd": 0.3},
        "cadence": {"dist": "normal", "mean": 105, "sd": 8},
    }
    wide = parse_population({"stature": {"dist": "normal", "mean": 1.55, "sd": 0.08}, **figs}, 1.75)
    ws = _draws(wide, 4000, seed=3)
    st = np.array([w.stature for w in ws])
    assert max(w.step_length / w.stature for w in ws) <= STEP_STATURE_MAX
    mean, sd = wide.groups[0].stature.moments()  # truncated at the humanoid's 1.4 m
    assert st.mean() == pytest.approx(mean, abs=0.005) and st.std() == pytest.approx(sd, rel=0.05)
    fixed_stature = parse_population({"stature": 1.55, **figs}, 1.75)
    over = [w.step_length / w.stature > STEP_STATURE_MAX for w in _draws(fixed_stature, 4000)]
    assert np.mean(over) > 0.1
    forced = parse_population(
        {"stature": {"dist": "normal", "mean": 1.7, "sd": 0.08}, "speed": 2.4, "cadence": 100},
        1.75,
    )
    fw = _draws(forced, 500)
    assert {(w.speed, w.cadence) for w in fw} == {(2.4, 100.0)}
    assert np.std([w.stature for w in fw]) == pytest.approx(0.08, rel=0.15)


def test_extreme_distributions_are_truncated_not_raised():
    """A wide distribution never gives an operator outside the human ranges (no mid-run error)."""
    pop = parse_population(
        {
            "speed": {"dist": "normal", "mean": 0.5, "sd": 1.0},
            "cadence": {"dist": "lognormal", "median": 170, "cv": 0.5},
            "stature": {"dist": "normal", "mean": 1.5, "sd": 0.5},
        },
        1.75,
    )
    ws = _draws(pop, 2000)
    for f in ("speed", "cadence", "stature"):
        x = [getattr(w, f) for w in ws]
        assert RANGES[f][0] <= min(x) and max(x) <= RANGES[f][1]
    assert {w.group for w in ws} == {"population"}


def test_fixed_walker_and_plain_numbers():
    pop = parse_population({"walker": "older_adult"}, 1.75)
    (w,) = {pop.draw(np.random.default_rng(k)) for k in range(3)}  # always the same
    p = PRESETS["older_adult"]
    assert (w.stature, w.speed, w.cadence, w.group) == (
        p.stature[0],
        p.speed[0],
        p.cadence[0],
        "older_adult",
    )
    pop = parse_population({"speed": 1.1, "cadence": 100, "group": "trainee"}, 1.68)
    w = pop.draw(np.random.default_rng(0))
    assert (w.stature, w.speed, w.cadence, w.group) == (1.68, 1.1, 100.0, "trainee")


# ------------------------------------------------------------------------------ bad tables

BAD = [
    ("mix = { adult = 0.5, youngster = 0.5 }", "youngster"),
    ("mix = { adult = 0.5, older_adult = 0 }", "share must be > 0"),
    ("mix = { adult = -1 }", "share must be > 0"),
    ("mix = {}", "population.mix"),
    ("mix = { adult = 1 }\nspeed = 1.2", "'mix' stands alone"),
    ('walker = "sprinter"', "unknown walker preset 'sprinter'"),
    ('speed = { dist = "normal", mean = 1.3, sd = -0.1 }', "population.speed.sd must be > 0"),
    ('speed = { dist = "gamma", mean = 1.3, sd = 0.1 }', "unknown distribution 'gamma'"),
    ("speed = { mean = 1.3, sd = 0.1 }", "missing key 'dist'"),
    ('speed = { dist = "normal", mean = 1.3 }', "needs key 'sd'"),
    ('speed = { dist = "normal", mean = 1.3, sd = 0.1, min = 1.0 }', "unknown key 'min'"),
    ('speed = { dist = "truncnorm", mean = 1.3, sd = 0.1 }', "needs 'min' and/or 'max'"),
    ('speed = { dist = "truncnorm", mean = 1.3, sd = 0.1, min = 1.5, max = 1.2 }', "min 1.5"),
    ('speed = { dist = "truncnorm", mean = 1.3, sd = 0.1, min = 0.1 }', "population.speed.min"),
    ('speed = { dist = "lognormal", median = 1.2, cv = 0.1, sd = 0.1 }', "either median and cv"),
    ('speed = { dist = "normal", mean = 130, sd = 10 }', "check its figures and unit"),
    ("speed = 5.0", "outside the human range"),
    ('speed = "fast"', "population.speed must be a finite number"),
    ("cadence = 110", "needs 'speed'"),
    ('walker = "adult"\nsped = 1.2', "unknown key 'sped'"),
    ('walker = "adult"\nstep_width = 0.9', "population.step_width"),
    ('walker = "adult"\ngroup = ""', "population.group"),
]


def _spec_text(scenes_dir, population: str | None, takt: str = "") -> str:
    pop = f"\n[population]\n{population}\n" if population is not None else ""
    return f"""
name = "short"
scene = "{(scenes_dir / "assembly_station.xml").as_posix()}"
start = "stand_rack2"
{takt}
{pop}
[[task]]
kind = "pick"
site = "rack2_screw1"
[[task]]
kind = "carry"
site = "stand_car1"
route = "T1"
[[task]]
kind = "fasten"
site = "car_screw1"
duration = 1.0
"""


@pytest.mark.parametrize(("table", "message"), BAD)
def test_bad_population_tables_fail_when_read(scenes_dir, tmp_path, table, message):
    path = tmp_path / "bad.toml"
    path.write_text(_spec_text(scenes_dir, table))
    with pytest.raises(CycleSpecError, match=r"bad\.toml:[0-9]+: ") as exc:
        load_cycle_spec(path)
    assert message in str(exc.value)
    # the line named is a [population] line
    lines = path.read_text().splitlines()
    start = lines.index("[population]") + 1
    assert start <= exc.value.line <= start + table.count("\n") + 1


@pytest.mark.parametrize(
    ("takt", "message"),
    [("takt = 0", "'takt'"), ("takt = -5.0", "'takt'"), ('takt = "60"', "'takt'")],
)
def test_bad_takt(scenes_dir, tmp_path, takt, message):
    path = tmp_path / "bad.toml"
    path.write_text(_spec_text(scenes_dir, None, takt))
    with pytest.raises(CycleSpecError, match=message):
        load_cycle_spec(path)


def test_population_must_be_a_table(scenes_dir, tmp_path):
    path = tmp_path / "bad.toml"
    text = _spec_text(scenes_dir, None, 'population = "adult"')
    path.write_text(text)
    with pytest.raises(CycleSpecError, match="'population' must be a table"):
        load_cycle_spec(path)


def test_station_ships_a_mixed_workforce_and_a_takt(scenes_dir):
    spec = load_cycle_spec(scenes_dir / "assembly_station.toml")
    assert spec.takt is not None and spec.takt > 0
    assert spec.population is not None
    shares = {g.name: g.share for g in spec.population.groups}
    assert set(shares) == {"adult", "older_adult", "fatigued"}
    assert sum(shares.values()) == pytest.approx(1.0)


# ------------------------------------------------------------------------------ simulation


@pytest.fixture(scope="module")
def short(tmp_path_factory, scenes_dir):
    """The short cycle (pick, carry 2.4 m, fasten) without a population, prepared once."""
    path = tmp_path_factory.mktemp("pop") / "short.toml"
    path.write_text(_spec_text(scenes_dir, None, "takt = 12.0"))
    return path, prepare(load_cycle_spec(path))


def _with(ctx, table):
    pop = None if table is None else parse_population(table, ctx.spec.stature)
    return dataclasses.replace(ctx, spec=dataclasses.replace(ctx.spec, population=pop))


def test_without_population_nothing_changes(short):
    """No [population]: no operator, the humanoid of the spec's stature."""
    _, ctx = short
    r = simulate_cycle(ctx, 3, collisions=False)
    assert r.operator is None and r.group == ""
    assert r.spec is ctx.spec


def test_slower_operators_take_longer_and_handling_scales_with_pace(short):
    """Fixed adults at 0.8 and 1.6 m/s (cadence at the adult's step length), 6 seeded runs
    each: the slow one's median walk and cycle take longer; with the same seed the task-time
    factors are the same, so an arm motion from the same place lasts 1/pace times as long
    (within 2 frames). The walk itself depends on the pace (a turn on the spot costs its time
    at the walker's pace, the search along the walk's guide weighs steps by it), so a run whose
    walks end elsewhere reaches over another distance: the arm motions before the first walk
    (from the same spot of the start zone) are compared in every run, the later ones in the
    runs whose walks end at the same place (within 1 mm)."""
    _, ctx = short
    out = {}
    for speed in (0.8, 1.6):
        c = _with(ctx, {"walker": "adult", "speed": speed, "cadence": 113.0 * speed / 1.38})
        out[speed] = [simulate_cycle(c, k, collisions=False) for k in range(6)]
        assert {r.operator.speed for r in out[speed]} == {speed}
    slow, fast = out[0.8], out[1.6]
    walk = {s: np.median([w.duration for r in out[s] for w in r.walks]) for s in out}
    assert walk[0.8] > 1.4 * walk[1.6]
    cycle = {s: np.median([r.cycle_time for r in out[s]]) for s in out}
    assert cycle[0.8] > 1.4 * cycle[1.6]
    same_place = [
        (a, b)
        for a, b in zip(slow, fast, strict=True)
        if all(
            np.allclose(wa.path.xy[-1], wb.path.xy[-1], atol=1e-3)
            for wa, wb in zip(a.walks, b.walks, strict=True)
        )
    ]
    first_walk = min(w.task for w in slow[0].walks)
    alike = {id(a) for a, _ in same_place}
    compared = 0
    for a, b in zip(slow, fast, strict=True):
        before = [(x, y) for x, y in zip(a.arms, b.arms, strict=True) if x.task < first_walk]
        pairs = list(zip(a.arms, b.arms, strict=True)) if id(a) in alike else before
        for arm_slow, arm_fast in pairs:
            assert arm_slow.duration == pytest.approx(2.0 * arm_fast.duration, abs=2 / 30 * 3)
            compared += 1
    assert compared >= len(slow)  # at least the arm motion before the walk of every run


@pytest.mark.parametrize("stature", [1.55, 1.95])
def test_operator_stature_builds_the_humanoid(short, stature):
    """The run's humanoid has the operator's stature, and its hand still reaches every target
    within 1 cm (the reach is solved at the reach model's size and scaled)."""
    _, ctx = short
    c = _with(ctx, {"walker": "adult", "stature": stature})
    r = simulate_cycle(c, 0, keep_timeline=True, collisions=False)
    assert r.operator.stature == stature
    assert r.timeline.stature == stature
    assert r.timeline.model is not ctx.model
    assert r.spec.stature == ctx.spec.stature  # the result keeps the spec as written
    assert max(a.hand_error for a in r.arms) < 0.01


@pytest.mark.parametrize("speed", [1.0, 1.5])
def test_a_walkers_steady_speed_reaches_the_walk(scenes_dir, tmp_path, speed):
    """An 8 m straight walk on the open floor: the pelvis speed over the middle half of the
    walk (after starting, before stopping) is within 10 % of the walker's preferred speed.
    Over 12 walks: a walk's own speed varies (as a person's does from walk to walk; at 1.5
    m/s, 1.0-1.7 m/s over 12 seeds), so the median of three was a draw."""
    path = tmp_path / "straight.toml"
    path.write_text(
        f"""
scene = "{(scenes_dir / "open_floor.xml").as_posix()}"
start = "west"
[population]
walker = "adult"
speed = {speed}
cadence = {113.0 * (speed / 1.38) ** 0.5:.2f}
[[task]]
kind = "walk"
site = "east"
"""
    )
    ctx = prepare(load_cycle_spec(path))
    speeds = []
    for k in range(12):
        p = simulate_cycle(ctx, k, collisions=False).walks[0].path
        mid = (p.t >= 0.25 * p.t[-1]) & (p.t <= 0.75 * p.t[-1])
        xy, t = p.xy[mid], p.t[mid]
        speeds.append(np.sum(np.linalg.norm(np.diff(xy, axis=0), axis=1)) / (t[-1] - t[0]))
    assert np.median(speeds) == pytest.approx(speed, rel=0.10)


def test_runs_independent_of_jobs_and_csv_carries_the_operator(tmp_path, scenes_dir):
    """Two runs with a mixed population: the same operators and cycles for 1 and 2 workers;
    --only-run K gives run K's operator; cycles.csv and walks.csv carry each run's operator."""
    path = tmp_path / "mix.toml"
    path.write_text(_spec_text(scenes_dir, "mix = { adult = 0.5, elderly = 0.5 }", "takt = 12.0"))
    one = simulate_cycles(path, runs=2, seed=4, n_jobs=1, collisions=False)
    two = simulate_cycles(path, runs=2, seed=4, n_jobs=2, collisions=False)
    assert [r.operator for r in one] == [r.operator for r in two]
    assert [r.cycle_time for r in one] == [r.cycle_time for r in two]
    assert one[0].operator != one[1].operator
    (again,) = simulate_cycles(path, runs=2, seed=4, only=[1], collisions=False)
    assert again.operator == one[1].operator and again.cycle_time == one[1].cycle_time
    files = write_report(one, tmp_path / "out", baseline={})
    for key in ("cycles", "walks"):
        with open(files[key]) as fh:
            rows = list(csv.DictReader(fh))
        for row in rows:
            r = one[int(row["run"])]
            assert row["group"] == r.operator.group
            assert float(row["stature_m"]) == pytest.approx(r.operator.stature)
            assert float(row["speed_m_s"]) == pytest.approx(r.operator.speed, abs=1e-4)
            assert float(row["cadence_steps_min"]) == pytest.approx(r.operator.cadence, abs=0.01)
    rep = json.loads(files["json"].read_text())
    assert rep["takt"] == 12.0 and rep["over_takt"]["runs"] == 2
    assert set(rep["groups"]) == {"adult", "elderly"}
    assert rep["per_run"][0]["operator"]["group"] == one[0].operator.group
    md = files["markdown"].read_text()
    assert "## Operators" in md and "over takt" in md and "P95 [s]" in md
    # the groups' copula correlations in the JSON and the markdown (adult r = 0.52)
    assert {g["group"]: g["stature_step_rho"] for g in rep["population"]}["adult"] == 0.519
    assert "stature-step length 0.52" in md and "stature-step length 0.29" in md  # elderly


# ------------------------------------------------------------------------------ report


def test_over_takt_share_and_wilson_interval():
    """3 of 10 cycles over takt: share 0.3, Wilson 95 % interval 0.1078-0.6032 (Wilson's
    formula with z = 1.96: (p + z²/2n ± z·sqrt(p(1-p)/n + z²/4n²)) / (1 + z²/n)); a cycle at
    exactly takt is not over it."""
    times = [50, 55, 58, 59, 60, 60.0, 61, 62, 70, 45]
    e = over_takt(times, 60.0)
    assert (e["over"], e["runs"], e["share"]) == (3, 10, 0.3)
    z, n, p = 1.959964, 10, 0.3
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    assert e["ci_low"] == pytest.approx(centre - half, abs=1e-6)
    assert e["ci_high"] == pytest.approx(centre + half, abs=1e-6)
    assert e["ci_low"] == pytest.approx(0.1078, abs=1e-4)
    assert e["ci_high"] == pytest.approx(0.6032, abs=1e-4)
    none = over_takt([1.0, 2.0], 60.0)
    assert none["share"] == 0.0 and none["ci_low"] == 0.0 and 0.5 < none["ci_high"] < 0.9


def test_report_percentiles_per_group(short):
    """Cycle-time P5/P50/P95 overall and per group are numpy's percentiles of those runs."""
    _, ctx = short
    c = _with(ctx, {"mix": {"adult": 0.5, "elderly": 0.5}})
    results = [simulate_cycle(c, k, run=k, collisions=False) for k in range(6)]
    rep = report_dict(results)
    times = [r.cycle_time for r in results]
    p = np.percentile(times, [5, 50, 95])
    ct = rep["cycle_time"]
    assert (ct["p5"], ct["p50"], ct["p95"]) == pytest.approx(tuple(p))
    for name, e in rep["groups"].items():
        sel = [r.cycle_time for r in results if r.group == name]
        assert e["runs"] == len(sel)
        if sel:
            assert e["cycle_time"]["p50"] == pytest.approx(np.median(sel))
        assert e["over_takt"]["over"] == sum(t > 12.0 for t in sel)
    assert sum(e["runs"] for e in rep["groups"].values()) == 6
    assert rep["over_takt"]["share"] == pytest.approx(np.mean(np.array(times) > 12.0))
    assert REFERENCE_SPEED == 1.37  # the pace unit the handling times are divided by
