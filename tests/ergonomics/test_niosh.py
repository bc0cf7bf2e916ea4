"""mjwalk.ergonomics.niosh: the revised NIOSH lifting equation against the Applications
Manual's worked examples and tables, its limits, and lifts it gives no index (issue 45)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.ergonomics import niosh
from mjwalk.ergonomics.niosh import LiftConditions, LiftEnds
from mjwalk.errors import InputError


def test_niosh_example_4_package_inspection():
    """Applications Manual (Waters et al. 1994), Example 4 'Package Inspection', Figure 14
    (p. 46), U.S. units: origin H 10 in, V 22 in, D 37 in, A 0, FM .88, coupling fair;
    destination H 20 in, V 59 in. The worksheet multiplies multipliers rounded to two
    decimals (p. 29): RWL 34.9 lb at the origin, 15.2 lb at the destination; at full
    precision 34.8 and 15.3 lb. Source: the two-pass transcription of the manual (2021
    revision) in nbarr1/ErgonomicTool docs/methods/rnle.md ("Rounding" and "Coupling
    Multiplier"), which quotes the origin product and both RWLs and reads CM from the worksheet
    (.95 at V 22 in, 1.0 at V 59 in, fair). L, F and the duration are not quoted there: F 3
    lifts/min over <= 1 h is the Table 5 row that gives the quoted FM .88. Secondary source:
    NOT checked against the manual's page itself."""
    cond = LiftConditions(f=3.0, duration="short", coupling="fair", units="us")
    o = niosh.multipliers(10.0, 22.0, 37.0, 0.0, cond, v_origin=22.0)
    d = niosh.multipliers(20.0, 59.0, 37.0, 0.0, cond, v_origin=22.0)
    assert (o.hm, round(o.vm, 2), round(o.dm, 2), o.am, o.fm, o.cm) == (
        1.0,
        0.94,
        0.87,
        1.0,
        0.88,
        0.95,
    )
    assert (d.hm, round(d.vm, 2), d.fm, d.cm) == (0.5, 0.78, 0.88, 1.0)
    assert round(niosh.rwl(o, "us", round_multipliers=True), 1) == 34.9
    assert round(niosh.rwl(d, "us", round_multipliers=True), 1) == 15.2
    assert round(niosh.rwl(o, "us"), 1) == 34.8
    assert round(niosh.rwl(d, "us"), 1) == 15.3


def test_niosh_example_2_loading_supply_rolls():
    """Applications Manual (Waters et al. 1994), Example 2 "Loading Supply Rolls", worksheet
    Figure 9, U.S. units, as transcribed in a third-party public test file (vitest
    "nioshLifting" tests citing DHHS (NIOSH) 94-110; public-code index id 70275093896; the
    manual's page itself was NOT reachable, one secondary source only): L 35 lb; origin H 15 in,
    V 27 in; destination H 20 in, V 10 in; D 17 in; A 0; F < 0.2 lifts/min (set to 0.2);
    <= 1 h; coupling poor. Worksheet multipliers: origin HM .67 VM .98 DM .93 AM 1.0 FM 1.0 CM
    .90 -> RWL 28.0 lb; destination HM .50 VM .85 -> RWL 18.1 lb; LI 35/18.1 = 1.9 at the
    destination. (The origin LI 35/28.0 = 1.25; its printed one-decimal value is not in the
    transcription.)"""
    cond = LiftConditions(f=0.1, duration="short", coupling="poor", units="us")
    o = niosh.multipliers(15.0, 27.0, 17.0, 0.0, cond, v_origin=27.0)
    d = niosh.multipliers(20.0, 10.0, 17.0, 0.0, cond, v_origin=27.0)
    rounded = [round(x + 1e-12, 2) for x in (o.hm, o.vm, o.dm, o.am, o.fm, o.cm)]
    assert rounded == [0.67, 0.98, 0.93, 1.0, 1.0, 0.90]
    rounded = [round(x + 1e-12, 2) for x in (d.hm, d.vm, d.dm, d.am, d.fm, d.cm)]
    assert rounded == [0.50, 0.85, 0.93, 1.0, 1.0, 0.90]
    rwl_o = round(niosh.rwl(o, "us", round_multipliers=True), 1)
    rwl_d = round(niosh.rwl(d, "us", round_multipliers=True), 1)
    assert (rwl_o, rwl_d) == (28.0, 18.1)
    assert round(35.0 / rwl_d, 1) == 1.9 and round(35.0 / rwl_o, 2) == 1.25
    # at full precision (no rounded multipliers): 27.7 and 18.1 lb
    assert round(niosh.rwl(o, "us"), 1) == 27.7 and round(niosh.rwl(d, "us"), 1) == 18.1


def test_niosh_frequency_table_matches_the_worksheet_transcription():
    """Table 5 rows as printed on the manual's lifting analysis worksheet (public transcription,
    scribd doc. 53505426): columns <= 1 h V < 30 in, V >= 30; 1-2 h; 2-8 h."""
    rows = {
        0.2: [1.00, 1.00, 0.95, 0.95, 0.85, 0.85],
        0.5: [0.97, 0.97, 0.92, 0.92, 0.81, 0.81],
        1: [0.94, 0.94, 0.88, 0.88, 0.75, 0.75],
        2: [0.91, 0.91, 0.84, 0.84, 0.65, 0.65],
        3: [0.88, 0.88, 0.79, 0.79, 0.55, 0.55],
        4: [0.84, 0.84, 0.72, 0.72, 0.45, 0.45],
        5: [0.80, 0.80, 0.60, 0.60, 0.35, 0.35],
        6: [0.75, 0.75, 0.50, 0.50, 0.27, 0.27],
        7: [0.70, 0.70, 0.42, 0.42, 0.22, 0.22],
        8: [0.60, 0.60, 0.35, 0.35, 0.18, 0.18],
        9: [0.52, 0.52, 0.30, 0.30, 0.00, 0.15],
        10: [0.45, 0.45, 0.26, 0.26, 0.00, 0.13],
    }
    for f, want in rows.items():
        got = [
            niosh.frequency_multiplier(f, dur, v, "us")
            for dur in niosh.DURATIONS
            for v in (20.0, 40.0)
        ]
        assert got == pytest.approx(want, abs=1e-9), f


def test_niosh_multipliers_by_formula_not_by_table_row():
    """The manual's Tables 1 and 3 round three rows unlike their formulas (transcription in
    nbarr1/ErgonomicTool docs/methods/rnle.md): H 22 in .46 and H 23 in .44 in Table 1, D 130 cm
    .86 in Table 3; mjwalk computes the formulas (the manual's rule, p. 7): .45, .43, .85."""
    us = LiftConditions(f=1.0, duration="short", coupling="good", units="us")
    cm = LiftConditions(f=1.0, duration="short", coupling="good")
    assert round(niosh.multipliers(22.0, 30.0, 10.0, 0.0, us).hm, 2) == 0.45
    assert round(niosh.multipliers(23.0, 30.0, 10.0, 0.0, us).hm, 2) == 0.43
    assert round(niosh.multipliers(25.0, 75.0, 130.0, 0.0, cm).dm, 2) == 0.85
    # the other rows agree, e.g. Table 1 H 11 in .91, Table 2 V 0 .78, Table 4 A 90 deg .71
    assert round(niosh.multipliers(11.0, 0.0, 10.0, 0.0, us).hm, 2) == 0.91
    assert round(niosh.multipliers(10.0, 0.0, 10.0, 0.0, us).vm, 2) == 0.78
    assert (
        round(niosh.multipliers(25.0, 75.0, 25.0, 90.0, LiftConditions(1.0, "short")).am, 2) == 0.71
    )


def test_niosh_ideal_lift_is_the_load_constant_and_limits():
    m = niosh.multipliers(25.0, 75.0, 25.0, 0.0, LiftConditions(0.2, "short", "good"))
    assert niosh.rwl(m) == pytest.approx(23.0)
    long = LiftConditions(1, "long")
    assert niosh.multipliers(70.0, 75.0, 25.0, 0.0, long).hm == 0.0  # H > 63 cm
    assert niosh.multipliers(30.0, 180.0, 25.0, 0.0, long).vm == 0.0  # V > 175 cm
    assert niosh.multipliers(30.0, 75.0, 25.0, 140.0, long).am == 0.0  # A > 135 deg
    assert niosh.frequency_multiplier(16.0, "short", 80.0) == 0.0
    assert niosh.frequency_multiplier(2.5, "long", 50.0) == pytest.approx(0.60)  # interpolated
    with pytest.raises(InputError):
        niosh.multipliers(30.0, 75.0, 25.0, 0.0, LiftConditions(1, "forever"))
    with pytest.raises(InputError):
        niosh.multipliers(30.0, 75.0, 25.0, 0.0, LiftConditions(1, "long", coupling="sticky"))
    with pytest.raises(InputError):
        niosh.multipliers(30.0, 75.0, 25.0, 0.0, LiftConditions(1, units="imperial"))
    with pytest.raises(InputError):
        niosh.multipliers(-1.0, 75.0, 25.0, 0.0, long)


def test_niosh_heavier_low_pick_raises_the_lifting_index():
    """Adding 10 kg to a low pick raises its lifting index (the RWL does not depend on mass)."""
    ends = LiftEnds((40.0, 30.0), (20.0, 90.0), (0.0, 0.0))
    a = niosh.lift(0, "pick", "both", 5.0, ends, LiftConditions(1.0, coupling="fair"))
    b = niosh.lift(0, "pick", "both", 15.0, ends, LiftConditions(1.0, coupling="fair"))
    assert b.rwl == pytest.approx(a.rwl) and b.li == pytest.approx(3 * a.li) and b.li > 1.0


def test_niosh_control_at_destination_takes_the_lower_end():
    """A part put down onto its site (control at the destination, Applications Manual p. 21):
    the RWL is the lower of the origin's and the destination's; without it, the origin's."""
    args = ("both", 5.0, LiftEnds((25.0, 50.0), (75.0, 20.0), (0.0, 0.0)), LiftConditions(1.0))
    free = niosh.lift(0, "place", *args)
    put = niosh.lift(0, "place", *args, control_at_destination=True)
    d = 55.0
    cond = LiftConditions(1.0, "long", "fair")
    origin = niosh.rwl(niosh.multipliers(25.0, 75.0, d, 0.0, cond, v_origin=75.0))
    dest = niosh.rwl(niosh.multipliers(50.0, 20.0, d, 0.0, cond, v_origin=75.0))
    assert dest < origin
    assert free.rwl == pytest.approx(origin) and put.rwl == pytest.approx(dest)


@pytest.mark.parametrize(
    ("duration", "v", "zero"),
    [("short", 50, 13), ("short", 80, None), ("moderate", 50, 11), ("moderate", 80, 13),
     ("long", 50, 9), ("long", 80, 11)],
)  # fmt: skip
def test_each_table_5_column_ends_where_its_fm_reaches_zero(duration, v, zero):
    """fm_zero_from agrees with frequency_multiplier: FM > 0 just below the first 0.00 row, 0
    from it; only the short-duration column with V >= 75 cm runs to 15 lifts/min."""
    assert niosh.fm_zero_from(duration, v) == zero
    top = 15.0 if zero is None else zero
    assert niosh.frequency_multiplier(top - 0.01, duration, v) > 0
    if zero is not None:
        assert niosh.frequency_multiplier(zero, duration, v) == 0.0
    assert niosh.frequency_multiplier(15.01, duration, v) == 0.0


def lift_at(f: float, duration: str = "long", v0: float = 80.0, **kw) -> niosh.Lift:
    ends = LiftEnds((30.0, 30.0), (v0, v0 + 10.0), (0.0, 0.0))
    return niosh.lift(0, "pick", "right", 1.5, ends, LiftConditions(f, duration, "good"), **kw)


def test_a_lift_beyond_the_frequency_table_has_no_index_and_says_why():
    lf = lift_at(16.0)  # the tool: 2 lifts in 7.5 s
    assert lf.li is None and lf.rwl == 0.0
    assert lf.reason.startswith("lifting frequency 16.0 lifts/min is beyond the NIOSH frequency")
    for part in ("long duration (2-8 h) with V >= 75 cm at the origin",
                 "FM > 0 only below 11 lifts/min there", "defines FM up to 15 lifts/min at most",
                 "Table 5"):  # fmt: skip
        assert part in lf.reason
    assert "16.0" not in lf.limit and lf.limit.startswith("lifting frequency beyond")
    # the short-duration column with V >= 75 cm is the one that reaches 15 lifts/min
    short = lift_at(14.0, "short")
    assert short.li == pytest.approx(1.5 / short.rwl) and short.reason == ""
    over = lift_at(16.0, "short")
    assert over.li is None and "FM up to 15 lifts/min there" in over.reason
    fine = lift_at(10.0)
    assert fine.li is not None and np.isfinite(fine.li) and fine.reason == "" == fine.limit


def test_zero_reasons_name_each_limit_crossed():
    cond = LiftConditions(16.0, "long")
    why = niosh.zero_reasons(70.0, 190.0, 180.0, 140.0, cond, 80.0, end="destination")
    assert [w[0] for w in why] == [
        "H at the destination",
        "V at the destination",
        "vertical travel D",
        "asymmetry A at the destination",
        "lifting frequency",
    ]
    assert niosh.zero_reasons(30.0, 80.0, 10.0, 0.0, LiftConditions(1.0), 80.0) == []
    m = niosh.multipliers(25.0, 75.0, 25.0, 0.0, LiftConditions(0.2, "short", "good"))
    assert m.product() == pytest.approx(1.0)


def test_each_multiplier_at_zero_is_named_at_its_end():
    ends = LiftEnds((70.0, 30.0), (80.0, 190.0), (0.0, 140.0))
    lf = niosh.lift(0, "place", "both", 5.0, ends, LiftConditions(1.0), control_at_destination=True)
    assert lf.li is None and lf.rwl == 0.0
    assert "H at the origin 70 cm is above 63 cm, where HM = 0" in lf.reason
    assert "V at the destination 190 cm is above 175 cm" in lf.reason
    assert "asymmetry A at the destination 140 deg is above 135 deg" in lf.reason
    assert "lifting frequency" not in lf.reason  # 1 lift/min is in the table
    assert "70 cm" not in lf.limit and "H at the origin above 63 cm" in lf.limit
