"""The workforce's exposure: verdict shares with their intervals, the stature trend, the shift."""

from __future__ import annotations

import json

import numpy as np
import pytest

from mjwalk.ergonomics.results import RunErgonomics
from mjwalk.ergonomics.summary import RunRecord
from mjwalk.ergonomics.workforce import SHIFT_S, exposure_markdown, exposure_summary, stature_trend

PART = {"en1005": "acceptable", "iso11226": "acceptable"}


def record(run: int, verdict: str, arm_s: float, stature: float | None = None, group: str = ""):
    """A scored run with the exposure method's values (no frames)."""
    extra = {
        "exposure_verdict": verdict,
        "arm_over60_s": arm_s,
        "trunk_over20_s": 1.0,
        "cycle_time_s": 30.0,
        "exposure": {p: dict(PART) for p in ("upper_arm_left", "upper_arm_right", "trunk")},
    }
    e = RunErgonomics([], [], [], 30.0, np.ones(3, np.int8), np.ones(3, np.int8), extra=extra)
    return RunRecord(run, run, group, stature, e)


def test_the_verdict_shares_intervals_cover_the_true_share_at_the_stated_rate():
    # seeded: 300 workforces of 40 operators, each not acceptable with probability 0.3
    rng = np.random.default_rng(49)
    p, n, trials, covered = 0.3, 40, 300, 0
    for _ in range(trials):
        bad = rng.random(n) < p
        recs = [record(k, "not acceptable" if b else "acceptable", 1.0) for k, b in enumerate(bad)]
        s = exposure_summary(recs)["overall"]["verdicts"]["not acceptable"]
        covered += s["low"] <= p <= s["high"]
    # a 95 % interval: coverage 0.95; 300 trials give a binomial SD of 1.3 points
    assert 0.91 <= covered / trials <= 0.99


def test_the_stature_trend_follows_the_runs_not_a_formula():
    rng = np.random.default_rng(0)
    st = rng.uniform(1.55, 1.90, 60)
    y = np.clip(40.0 * (1.85 - st), 0, None) + rng.normal(0, 0.3, 60)  # shorter: longer raised
    t = stature_trend(st, y)
    assert t["range_m"] == [pytest.approx(st.min()), pytest.approx(st.max())]
    assert t["short_third"]["median"] > t["tall_third"]["median"]
    assert t["low"] <= t["slope_per_10cm"] <= t["high"] < 0  # the interval excludes none
    assert len(t["bins"]) == 5 and sum(b["n"] for b in t["bins"]) == 60
    assert stature_trend(np.full(8, 1.7), np.ones(8)) is None


def test_the_summary_has_groups_a_shift_and_a_markdown_table():
    recs = [record(k, ["acceptable", "not acceptable"][k % 2], float(k), 1.6 + 0.02 * k,
                   "adult" if k < 6 else "older") for k in range(10)]  # fmt: skip
    e = exposure_summary(recs, takt=60.0)
    json.dumps(e, allow_nan=False)
    assert e["shift"]["cycles"] == pytest.approx(SHIFT_S / 60.0) and e["shift"]["basis"] == "takt"
    assert set(e["groups"]) == {"adult", "older"}
    assert e["overall"]["arm_over60_shift_min"]["p50"] == pytest.approx(4.5 * SHIFT_S / 60 / 60)
    assert e["groups"]["adult"]["verdicts"]["not acceptable"]["k"] == 3
    md = "\n".join(exposure_markdown(e))
    assert "| adult | 6 |" in md and "Along stature (1.60-1.78 m)" in md
    assert exposure_summary([]) is None and exposure_markdown(None) == []


def test_the_drivers_sentence_says_none_when_no_cycle_is_not_acceptable():
    """Tasks beyond the limits but every cycle acceptable: the sentence closes on "none", not on
    an empty list."""
    from mjwalk.ergonomics.results import TaskErgonomics

    recs = []
    for k in range(4):
        r = record(k, "conditionally acceptable", 2.0, 1.7)
        t = TaskErgonomics(0, "pick", "rack", 3, 3, 2, 0.0, "", "", "left", 2)
        t.extra.update(arm_over60_s=2.0, trunk_over20_s=0.5, arm_peak_deg=80.0)
        r.ergo.tasks.append(t)
        recs.append(r)
    md = "\n".join(exposure_markdown(exposure_summary(recs)))
    assert "task 0 pick rack: 2.0 / 0.5" in md
    assert "Cycles not acceptable by body part and standard: none." in md


def test_the_smooth_trend_follows_a_bend_that_the_straight_line_misses():
    """Seeded: a figure flat to 1.70 m, then falling 1 s per cm, with noise of 0.2 s; the
    LOWESS trend is within 0.5 s of the true curve at 1.62 and 1.85 m (a straight line misses
    by more), and a straight line is given back exactly."""
    from mjwalk.ergonomics.workforce import lowess

    rng = np.random.default_rng(0)
    x = np.sort(rng.uniform(1.55, 1.95, 200))
    truth = np.where(x < 1.70, 20.0, 20.0 - 100.0 * (x - 1.70))
    y = truth + rng.normal(0.0, 0.2, len(x))
    at = np.array([1.62, 1.85])
    fit = lowess(x, y, at, span=0.3)
    np.testing.assert_allclose(fit, [20.0, 5.0], atol=0.5)
    line = np.polyval(np.polyfit(x, y, 1), at)
    assert np.abs(line - [20.0, 5.0]).max() > 1.0
    np.testing.assert_allclose(lowess(x, 3.0 * x + 1.0, at), 3.0 * at + 1.0)
    t = stature_trend(x, y)
    assert len(t["smooth"]) == 9 and t["smooth"][0]["stature_m"] == pytest.approx(x.min())


def test_the_trend_band_covers_the_true_line_and_narrows_with_more_runs():
    """Seeded: 20 workforces of 40 runs on a straight line (-2 s per 10 cm, noise 0.5 s); the
    bootstrap 95 % band at the middle stature holds the true value in at least 17 of 20 (a 95 %
    band: 19 expected, binomial SD 1), and 160 runs give a narrower band than 40."""
    from mjwalk.ergonomics.workforce import lowess_band

    rng = np.random.default_rng(7)
    at = np.array([1.72])
    hits, widths = 0, []
    for n in [40] * 20 + [160]:
        x = rng.uniform(1.55, 1.90, n)
        y = 10.0 - 20.0 * (x - 1.72) + rng.normal(0.0, 0.5, n)
        lo, hi = lowess_band(x, y, at)
        hits += bool(lo[0] <= 10.0 <= hi[0]) if n == 40 else 0
        widths.append(float(hi[0] - lo[0]))
    assert hits >= 17
    assert widths[-1] < np.median(widths[:-1])


def test_one_verdict_for_all_says_so_and_the_trend_table_shows_the_arm_at_the_top():
    recs = [record(k, "not acceptable", 5.0 - 0.1 * k, 1.60 + 0.03 * k) for k in range(10)]
    for k, r in enumerate(recs):
        r.ergo.extra["arm_top_deg"] = 120.0 - 2.0 * k  # -2 deg per 3 cm: -6.7 deg per 10 cm
        r.ergo.extra["arm_over60_per_min"] = 12.0
    e = exposure_summary(recs, takt=20.0)
    assert e["stature_arm_top"]["slope_per_10cm"] == pytest.approx(-20.0 / 3.0)
    assert e["overall"]["arm_over60_per_min"]["p50"] == pytest.approx(12.0)
    md = "\n".join(exposure_markdown(e))
    assert "Every run is not acceptable: the verdicts do not tell operators apart" in md
    assert "| stature m | arm >60 deg s per cycle (95 %) | arm at the highest grasp deg" in md
    assert "| 1.60 | 5.0 (" in md and "-6.7 deg per 10 cm" in md
    # mixed verdicts: no such sentence
    recs[0].ergo.extra["exposure_verdict"] = "acceptable"
    assert "Every run is" not in "\n".join(exposure_markdown(exposure_summary(recs)))


def test_the_band_is_the_same_bit_for_bit_whatever_block_the_resamples_are_done_in(monkeypatch):
    """The resamples go in cache-sized blocks; each resample's fit only reads its own row, so
    one block of all 2000 and blocks of 7 give the same band to the last bit."""
    from mjwalk.ergonomics import workforce

    rng = np.random.default_rng(5)
    x = rng.uniform(1.5, 1.95, 300)
    y = 40 - 20 * x + rng.normal(0, 1.0, 300)
    at = np.linspace(x.min(), x.max(), 9)
    monkeypatch.setattr(workforce, "_BAND_BLOCK", 300 * workforce.BOOTSTRAP)  # one block
    whole = workforce.lowess_band(x, y, at)
    monkeypatch.setattr(workforce, "_BAND_BLOCK", 300 * 7)  # blocks of 7 resamples
    blocks = workforce.lowess_band(x, y, at)
    for a, b in zip(whole, blocks, strict=True):
        assert a.tobytes() == b.tobytes()


def test_the_band_finds_each_resamples_kth_nearest_run_as_partitioning_does(monkeypatch):
    """Each resample's span ends at its k-th nearest run, found by counting its draws along
    the distances' order (issue 50: faster than partitioning every resample): the same band,
    bit for bit, as with ``np.partition`` of each resample's distances, with tied statures
    and runs drawn many times (a resample of 12 runs over 3 statures)."""
    from mjwalk.ergonomics import workforce

    real = workforce._lowess_rows

    def partitioned(xs, ys, at, kth):
        k = min(xs.shape[1], max(3, int(np.ceil(workforce.LOWESS_SPAN * xs.shape[1]))))
        for i, a in enumerate(at):
            d = np.abs(xs - a)
            assert kth[i].tobytes() == np.partition(d, k - 1, axis=1)[:, k - 1].tobytes()
        return real(xs, ys, at, kth)

    monkeypatch.setattr(workforce, "_lowess_rows", partitioned)
    rng = np.random.default_rng(11)
    for x in (rng.uniform(1.5, 1.95, 300), rng.choice([1.60, 1.70, 1.80], 12)):
        y = 40 - 20 * x + rng.normal(0, 1.0, len(x))
        workforce.lowess_band(x, y, np.linspace(x.min(), x.max(), 9))


def test_the_two_trends_at_once_are_the_trends_one_by_one():
    """exposure_summary draws its two stature trends in two threads: the same figures as
    stature_trend of each alone."""
    from mjwalk.ergonomics import workforce

    recs = [record(k, "acceptable", 5.0 - 0.2 * k + 0.1 * (k % 3), 1.55 + 0.02 * k)
            for k in range(20)]  # fmt: skip
    for k, r in enumerate(recs):
        r.ergo.extra["arm_top_deg"] = 120.0 - 2.0 * k + (k % 4)
    e = exposure_summary(recs)
    workforce._TRENDS.clear()
    x = np.array([r.stature for r in recs])
    alone = workforce.stature_trend(x, np.array([r.ergo.extra["arm_over60_s"] for r in recs]))
    top = workforce.stature_trend(x, np.array([r.ergo.extra["arm_top_deg"] for r in recs]))
    assert e["stature"] == alone and e["stature_arm_top"] == top


def test_a_trend_asked_twice_is_the_same_and_a_changed_copy_does_not_leak():
    """The report asks for each trend several times; the second answer is the first one's
    figures, and changing one answer does not change the next."""
    rng = np.random.default_rng(2)
    x = rng.uniform(1.5, 1.95, 40)
    y = 30 - 10 * x + rng.normal(0, 0.5, 40)
    first = stature_trend(x, y)
    assert first is not None
    first["smooth"][0]["value"] = -1.0
    again = stature_trend(x.copy(), y.copy())
    assert again is not None and again["smooth"][0]["value"] != -1.0
    y2 = y.copy()
    y2[0] += 1.0  # other figures: computed again
    assert stature_trend(x, y2)["slope_per_10cm"] != again["slope_per_10cm"]
