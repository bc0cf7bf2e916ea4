"""Walkers: the step model conditioned on an operator's pace (mjwalk.gait.walker, .pace)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import ks_2samp

from mjwalk.gait.features import N_RAW, raw_scale_factors
from mjwalk.gait.pace import SKIP_END, SKIP_START, capture_pace, model_pace, stretch_step
from mjwalk.gait.walker import PRESETS, Walker, WalkerError, get_preset


@pytest.fixture(scope="module")
def model():
    from mjwalk.gait.default import default_model

    return default_model(progress=False)


# -- the Walker ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("figures", "word"),
    [
        ({"speed": float("nan")}, "speed"),
        ({"speed": 5.0}, "speed"),
        ({"cadence": 20.0}, "cadence"),
        ({"stature": 3.0}, "stature"),
        ({"step_width": -0.1}, "step_width"),
    ],
)
def test_walker_rejects_figures_outside_human_ranges(figures, word):
    with pytest.raises(WalkerError, match=word):
        Walker(**figures)


def test_walker_step_length_and_duration():
    w = Walker(speed=1.2, cadence=120.0)
    assert w.step_length == pytest.approx(0.6)
    assert w.step_duration == pytest.approx(0.5)
    assert w.pace == pytest.approx(1.2 / 1.37)


def test_presets_cite_a_source_and_are_ordered_by_age():
    for name, p in PRESETS.items():
        assert p.source, name
        Walker.preset(name)  # within the human ranges
    assert PRESETS["adult"].speed[0] > PRESETS["older_adult"].speed[0] > PRESETS["elderly"].speed[0]
    assert Walker.preset("adult", speed=1.0).speed == 1.0
    with pytest.raises(WalkerError, match="known: adult"):
        get_preset("athlete")


# -- conditioning -------------------------------------------------------------------------------


def test_scaled_features_decode_stretched_steps_and_encode_back(model):
    rng = np.random.default_rng(0)
    z = rng.standard_normal((20, model.n_dims))
    f = raw_scale_factors(1.1, 0.8, 1.3)
    feats = model.features
    scaled = feats.scaled(f)
    raw = feats.decode_raw(z)
    np.testing.assert_allclose(scaled.decode_raw(z), raw * f, atol=1e-12)
    np.testing.assert_allclose(scaled.encode_raw(raw * f), z, atol=1e-9)
    assert f.shape == (N_RAW,)


def test_for_walker_does_not_compound_and_none_is_the_model(model, tmp_path):
    w = Walker(speed=0.9, cadence=100.0)
    once = model.for_walker(w)
    twice = once.for_walker(w)
    np.testing.assert_allclose(once.features.dec_matrix, twice.features.dec_matrix)
    assert once.for_walker(None) is model
    assert once.walker == w and model.walker is None
    # a conditioned model saves the learned model: the walker is a planning-time choice
    from mjwalk.gait.model import StepModel

    once.save(tmp_path / "m.npz")
    back = StepModel.load(tmp_path / "m.npz")
    np.testing.assert_allclose(back.features.dec_matrix, model.features.dec_matrix)


@pytest.mark.parametrize(
    ("speed", "cadence", "stature"),
    [(0.6, 90.0, 1.60), (0.95, 104.0, 1.66), (1.37, 113.0, 1.75), (1.7, 140.0, 1.90)],
)
def test_walker_straight_walks_have_the_requested_speed_and_cadence(model, speed, cadence, stature):
    """Seeded: the steady steps of straight walks of a conditioned model reproduce the walker's
    speed and cadence within 5 % (another seed than the model's own pace measurement)."""
    w = Walker(speed=speed, cadence=cadence, stature=stature)
    pace = model_pace(model.for_walker(w), seed=11)
    assert pace.speed == pytest.approx(speed, rel=0.05)
    assert pace.cadence == pytest.approx(cadence, rel=0.05)
    # the lateral step width follows stature (the model's width at 1.75 m); the greedy straight
    # walks measure a slow walker's width low (mjwalk.gait.pace's KNOWN BIAS: 0.87-0.92 of its
    # stature's at 0.6 m/s over seeds 11-13, for the default model with 200 or 400 inducing
    # inputs alike; the model's own chains keep it), so 15 % there, 10 % for the others
    tol = 0.15 if speed < 0.8 else 0.1
    assert pace.step_width == pytest.approx(model.pace().step_width * stature / 1.75, rel=tol)


def test_walker_keeps_the_models_relative_step_variability(model):
    """Within-person variability scales with the pace (coefficient of variation constant):
    the CV of steady step length and duration of a slow and a fast walker agree within 20 %."""
    from mjwalk.gait.straight import model_straight_walks

    cvs = []
    for w in (Walker(speed=0.7, cadence=95.0), Walker(speed=1.6, cadence=130.0)):
        walks = model_straight_walks(
            model.for_walker(w),
            np.full(80, 8.0),
            np.random.default_rng(2),
            record_steps=True,
        )
        sl = slice(SKIP_START, -SKIP_END)
        length = np.concatenate([x["lengths"][sl] for x in walks])
        dur = np.concatenate([x["durations"][sl] for x in walks])
        cvs.append((length.std() / length.mean(), dur.std() / dur.mean()))
    (l0, d0), (l1, d1) = cvs
    assert l1 == pytest.approx(l0, rel=0.2)
    assert d1 == pytest.approx(d0, rel=0.2)


def test_stretch_step_is_measured_as_the_stretched_pace(model):
    """capture_pace of stretched steps is the stretched pace (normalize_paces relies on it)."""
    batch = model.sample_chain(60, np.random.default_rng(4), side="left")
    steps = batch.to_steps()
    for i, s in enumerate(steps):
        s.take, s.index = "t", i
    p0 = capture_pace(steps, straight_deg=1e6)
    p1 = capture_pace([stretch_step(s, 1.2, 0.9, 1.1) for s in steps], straight_deg=1e6)
    assert p1.step_duration == pytest.approx(1.1 * p0.step_duration, rel=0.02)
    assert p1.step_length == pytest.approx(p0.step_length, rel=0.15)  # mixes x and y


# -- against capture (skips without ../shared/data) ----------------------------------------------

STYLES = ("normal", "masculine", "feminine", "youthful")


@pytest.fixture(scope="module")
def bandai_styles(shared_data):
    from mjwalk.gait.fidelity import load_capture
    from mjwalk.gait.segment import segment_takes

    out = {}
    for style in STYLES:
        takes = load_capture(bvh=str(shared_data / "bandai-walk" / f"*_{style}_*.bvh"))
        out[style] = segment_takes(takes)[0]
    return out


@pytest.mark.slow  # among the fast tier's longest in a quiet warm run (9-10 s): its 5 min budget
@pytest.mark.parametrize("style", STYLES)
def test_held_out_style_conditioned_on_its_pace_only(model, bandai_styles, style):
    """Leave-one-group-out, stricter: the default model never saw any Bandai capture. Told
    only a style's speed and cadence (its steady straight pace), its steady straight steps
    match the style's: two-sample KS of step length and duration <= 0.15 (seeded)."""
    from mjwalk.gait.straight import model_straight_walks, straight_runs

    steps = bandai_styles[style]
    pace = capture_pace(steps)
    w = Walker(speed=pace.speed, cadence=pace.cadence)
    steady = [
        s
        for run in straight_runs(steps)
        for s in run
        if not (s.meta.get("initiation") or s.meta.get("termination"))
    ]
    walks = model_straight_walks(
        model.for_walker(w), np.full(200, 8.0), np.random.default_rng(3), record_steps=True
    )
    sl = slice(SKIP_START, -SKIP_END)
    length = np.concatenate([x["lengths"][sl] for x in walks])
    dur = np.round(np.concatenate([x["durations"][sl] for x in walks]) * 120) / 120
    assert ks_2samp([s.length for s in steady], length).statistic <= 0.15
    assert ks_2samp([s.duration for s in steady], dur).statistic <= 0.15


def test_validate_cli_for_a_walker(shared_data, tmp_path, capsys):
    """`mjwalk validate --against GLOB --speed V --cadence C --json FILE`: the report keeps its
    layout, says which walker the model was conditioned on and both paces."""
    import json

    from mjwalk.cli import main

    out = tmp_path / "fidelity.json"
    glob = str(shared_data / "bandai-walk" / "dataset-2_walk_normal_00[1-4].bvh")
    code = main(
        ["validate", "--against", glob, "--speed", "1.15", "--cadence", "109", "--json", str(out)]
    )
    assert code == 0
    report = json.loads(out.read_text())
    assert {"steps", "straight_walks", "initiation", "pace"} <= set(report)
    assert report["model"]["walker"]["speed"] == pytest.approx(1.15)
    assert report["pace"]["model"]["speed"] == pytest.approx(1.15, rel=0.05)
    assert "pace of the capture" in capsys.readouterr().out


def test_plan_cli_rejects_a_walker_outside_human_ranges(capsys):
    from mjwalk.cli import main

    code = main(["plan", "station", "--from", "stand_rack2", "--to", "stand_car1", "--speed", "7"])
    assert code == 2
    assert "speed 7 is outside the human range" in capsys.readouterr().err


@pytest.mark.slow  # among the fast tier's longest in a quiet warm run (9-10 s): its 5 min budget
def test_planned_straight_walks_take_as_long_as_the_captured_ones(bandai_styles):
    """Issue 14 item 5: every captured straight walk of the four Bandai styles (91) walked 10
    times by the planner with the default model conditioned on its style's pace only (the
    population that matches the captured walkers): pooled time median within 3 % of the
    capture's and IQR within 70-130 % (seeded; here +0.2 % and 112 %). Measured with 10 per
    walk, seeds 0-2 (benchmarks/bench_variability.py): median +0.3/+0.6/+0.6 %, IQR
    117/121/113 % (the capture's own bootstrap 90 % interval is 76-135 % of its IQR)."""
    from mjwalk.gait.default import default_model
    from mjwalk.gait.straight import captured_straight_walks
    from mjwalk.plan.walktimes import planned_straight_walks

    model = default_model(progress=False)
    rng = np.random.default_rng(0)
    cap, mod = [], []
    for style in STYLES:
        steps = bandai_styles[style]
        pace = capture_pace(steps)
        walker = Walker(speed=pace.speed, cadence=pace.cadence)
        cw = captured_straight_walks(steps)
        cap += [w["time"] for w in cw]
        mod += planned_straight_walks(
            model.for_walker(walker),
            [w["distance"] for w in cw] * 10,
            [bool(w["in_motion"]) for w in cw] * 10,
            rng,
        )
    (c25, c50, c75), (m25, m50, m75) = (
        np.percentile(cap, [25, 50, 75]),
        np.percentile(mod, [25, 50, 75]),
    )
    assert len(cap) == 91
    assert m50 == pytest.approx(c50, rel=0.03)
    ratio = (m75 - m25) / (c75 - c25)
    assert 0.7 <= ratio <= 1.3, ratio
