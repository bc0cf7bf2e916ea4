"""The revised NIOSH lifting equation (Waters, Putz-Anderson, Garg & Fine 1993, Ergonomics 36(7),
749-776; Applications Manual, Waters, Putz-Anderson & Garg 1994, DHHS (NIOSH) Publication
No. 94-110): the recommended weight limit and the lifting index of one lift.

RWL = LC x HM x VM x DM x AM x FM x CM, LI = load / RWL. Metric (cm, kg) or U.S. customary
(in, lb) constants, as the manual gives both (they are not exact conversions of each other).
The variable limits are the manual's (section 1.3): H below 25 cm (10 in) is set to it and
above 63 cm (25 in) gives HM = 0; V above 175 cm (70 in) gives VM = 0; D below 25 cm (10 in)
is set to it, above 175 cm (70 in) gives DM = 0; A above 135 deg gives AM = 0; F below 0.2
lifts/min is set to 0.2 and FM is interpolated linearly between Table 5's rows (p. 7).
Table 5 defines FM up to 15 lifts/min, and only the short-duration column with V at or above
75 cm (30 in) goes that far; its other columns reach FM = 0.00 earlier (long duration: from 9
lifts/min with V below 75 cm, from 11 with V at or above it). "Lifting above the maximum
frequency results in a RWL of 0.0" (pp. 14-15). A lift whose RWL is 0 (a multiplier at 0: F
beyond its column, H, V, D or A beyond its limit) has no lifting index: :func:`lift` gives it
``li`` None and says which limit it crossed and what the table or the manual allows.

HM, VM, DM and AM are computed from the formulas (the manual: "each multiplier should be
computed from the appropriate formula", p. 7); the manual's Tables 1-4 round three rows
differently from their formulas (Table 1: H 22 in .46, H 23 in .44; Table 3: D 130 cm .86;
formulas .45, .43, .85), so a worksheet read from those table rows differs in the second
decimal. Provenance (checked 2026-12-01): the manual's text could not be reached directly; the
constants, limits, Table 5 and Table 7 and the worked-example figures used in the tests are
from a public two-pass transcription of the manual (2021 revision, which states its formulas,
multipliers and limits are identical to the 1994 manual's), nbarr1/ErgonomicTool
``docs/methods/rnle.md``, and Table 5 also from a public transcription of the manual's
lifting analysis worksheet (scribd, doc. 53505426). Secondary sources, not the manual itself.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mjwalk.errors import InputError

#: Constants per unit system: load constant, H0 (HM = H0/H), H max, V0 (VM optimum), VM slope,
#: V max, DM numerator, D min, D max, the V bound of Tables 5 and 7 (Waters et al. 1993, Table 1;
#: Applications Manual p. 7).
UNITS = {
    "metric": dict(lc=23.0, h0=25.0, hmax=63.0, v0=75.0, vk=0.003, vmax=175.0, dk=4.5,
                   dmin=25.0, dmax=175.0, vsplit=75.0),
    "us": dict(lc=51.0, h0=10.0, hmax=25.0, v0=30.0, vk=0.0075, vmax=70.0, dk=1.8,
               dmin=10.0, dmax=70.0, vsplit=30.0),
}  # fmt: skip
#: Duration categories (Applications Manual 1.3.5.2, pp. 13-14): short <= 1 h followed by a
#: recovery time of at least 1.0 x the work time (the 1994 edition said 1.2; the 2021 revision
#: changed it), moderate 1-2 h with at least 0.3 x recovery, long 2-8 h.
DURATIONS = ("short", "moderate", "long")
#: Table 5 (Frequency Multiplier): rows F (lifts/min), columns (short V<75cm, short V>=75cm,
#: moderate V<, moderate V>=, long V<, long V>=).
FM_F = np.array([0.2, 0.5, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15])
FM_TABLE = np.array(
    [
        [1.00, 1.00, 0.95, 0.95, 0.85, 0.85],
        [0.97, 0.97, 0.92, 0.92, 0.81, 0.81],
        [0.94, 0.94, 0.88, 0.88, 0.75, 0.75],
        [0.91, 0.91, 0.84, 0.84, 0.65, 0.65],
        [0.88, 0.88, 0.79, 0.79, 0.55, 0.55],
        [0.84, 0.84, 0.72, 0.72, 0.45, 0.45],
        [0.80, 0.80, 0.60, 0.60, 0.35, 0.35],
        [0.75, 0.75, 0.50, 0.50, 0.27, 0.27],
        [0.70, 0.70, 0.42, 0.42, 0.22, 0.22],
        [0.60, 0.60, 0.35, 0.35, 0.18, 0.18],
        [0.52, 0.52, 0.30, 0.30, 0.00, 0.15],
        [0.45, 0.45, 0.26, 0.26, 0.00, 0.13],
        [0.41, 0.41, 0.00, 0.23, 0.00, 0.00],
        [0.37, 0.37, 0.00, 0.21, 0.00, 0.00],
        [0.00, 0.34, 0.00, 0.00, 0.00, 0.00],
        [0.00, 0.31, 0.00, 0.00, 0.00, 0.00],
        [0.00, 0.28, 0.00, 0.00, 0.00, 0.00],
    ]
)  # fmt: skip
#: Table 7 (Coupling Multiplier): (V < 75 cm, V >= 75 cm).
CM_TABLE = {"good": (1.00, 1.00), "fair": (0.95, 1.00), "poor": (0.90, 0.90)}
COUPLINGS = tuple(CM_TABLE)


@dataclass
class Multipliers:
    """The six multipliers of one end of a lift (dimensionless)."""

    hm: float
    vm: float
    dm: float
    am: float
    fm: float
    cm: float

    def product(self) -> float:
        """The product of the six multipliers.

        Returns:
            :math:`HM \\cdot VM \\cdot DM \\cdot AM \\cdot FM \\cdot CM`, dimensionless.
        """
        return self.hm * self.vm * self.dm * self.am * self.fm * self.cm


@dataclass(frozen=True)
class LiftConditions:
    """How a lift is done, the same at both of its ends.

    Attributes:
        f: lifting frequency, lifts/min (below 0.2 taken as 0.2, Table 5).
        duration: the duration category, one of :data:`DURATIONS`.
        coupling: the hand-to-object coupling, one of :data:`COUPLINGS`.
        units: "metric" (cm, kg) or "us" (in, lb), a key of :data:`UNITS`.
    """

    f: float
    duration: str = "long"
    coupling: str = "fair"
    units: str = "metric"


@dataclass(frozen=True)
class LiftEnds:
    """Where the hands are at the (origin, destination) of a lift.

    Attributes:
        h: horizontal distance of the hands from the ankles' mid-point, cm (or in).
        v: height of the hands above the floor the worker stands on, cm (or in).
        a: asymmetry angle, degrees.
    """

    h: tuple[float, float]
    v: tuple[float, float]
    a: tuple[float, float]


def frequency_multiplier(f: float, duration: str, v_origin: float, units: str = "metric") -> float:
    """FM (Table 5), interpolated linearly between its rows (F below 0.2 taken as 0.2; 0
    beyond 15 lifts/min).

    Args:
        f: lifting frequency, lifts/min.
        duration: the duration category, one of :data:`DURATIONS`.
        v_origin: V at the origin, cm (or in), which selects the column.
        units: "metric" or "us".

    Returns:
        FM, dimensionless.

    Raises:
        InputError: an unknown duration, or a frequency not finite and >= 0.
    """
    if duration not in DURATIONS:
        raise InputError(f"NIOSH: duration must be one of {DURATIONS}, got {duration!r}")
    if not np.isfinite(f) or f < 0:
        raise InputError(f"NIOSH: frequency must be >= 0 lifts/min, got {f!r}")
    col = 2 * DURATIONS.index(duration) + int(v_origin >= UNITS[units]["vsplit"])
    if f > FM_F[-1]:
        return 0.0
    return float(np.interp(max(f, FM_F[0]), FM_F, FM_TABLE[:, col]))


def fm_zero_from(duration: str, v_origin: float, units: str = "metric") -> float | None:
    """The lowest Table 5 frequency at which FM is 0.00 for a duration category and V.

    Args:
        duration: the duration category, one of :data:`DURATIONS`.
        v_origin: V at the origin, cm (or in).
        units: "metric" or "us".

    Returns:
        Lifts/min; None where the column is non-zero up to the table's 15 lifts/min.
    """
    col = 2 * DURATIONS.index(duration) + int(v_origin >= UNITS[units]["vsplit"])
    zero = np.flatnonzero(FM_TABLE[:, col] == 0.0)
    return float(FM_F[zero[0]]) if len(zero) else None


def _column(duration: str, v_origin: float, units: str) -> str:
    c = UNITS[units]
    unit = "cm" if units == "metric" else "in"
    hours = {"short": "<= 1 h", "moderate": "1-2 h", "long": "2-8 h"}[duration]
    side = ">=" if v_origin >= c["vsplit"] else "<"
    return f"{duration} duration ({hours}) with V {side} {c['vsplit']:.0f} {unit} at the origin"


def zero_reasons(
    h: float, v: float, d: float, a: float, cond: LiftConditions, v_origin: float,
    end: str = "origin",
) -> list[tuple[str, str, str]]:  # fmt: skip
    """Why :func:`multipliers` gives a multiplier of 0 (RWL 0, no lifting index) at one end of
    a lift.

    Args:
        h: horizontal distance at this end, cm (or in, per ``cond.units``).
        v: height of the hands at this end, cm (or in).
        d: vertical travel of the lift, cm (or in).
        a: asymmetry angle at this end, degrees.
        cond: frequency, duration category and units of the lift (its coupling is not read).
        v_origin: V at the origin, which selects the Table 5 column.
        end: names the end ("origin" or "destination") for H, V and A.

    Returns:
        (variable, value, limit) triples ("lifting frequency", "16.0 lifts/min", what the
        manual allows for it, with its source); empty where every multiplier is above 0.
    """
    f, duration, units = cond.f, cond.duration, cond.units
    c = UNITS[units]
    u = "cm" if units == "metric" else "in"
    out = []
    if h > c["hmax"]:
        lim = f"above {c['hmax']:.0f} {u}, where HM = 0 (Applications Manual 1.3.1.2)"
        out.append((f"H at the {end}", f"{h:.0f} {u}", lim))
    if v > c["vmax"]:
        lim = (
            f"above {c['vmax']:.0f} {u}, the upper limit of vertical reach for lifting, where "
            "VM = 0 (Applications Manual 1.3.2.2)"
        )
        out.append((f"V at the {end}", f"{v:.0f} {u}", lim))
    if d > c["dmax"]:
        lim = f"above {c['dmax']:.0f} {u}, where DM = 0 (Applications Manual 1.3.3.2)"
        out.append(("vertical travel D", f"{d:.0f} {u}", lim))
    if a > 135.0:
        lim = "above 135 deg, where AM = 0 (Applications Manual 1.3.4.2)"
        out.append((f"asymmetry A at the {end}", f"{a:.0f} deg", lim))
    if frequency_multiplier(f, duration, v_origin, units) == 0.0:
        zero = fm_zero_from(duration, v_origin, units)
        top = f"{FM_F[-1]:.0f} lifts/min"
        allows = (
            f"FM > 0 only below {zero:.0f} lifts/min" if zero is not None else f"FM up to {top}"
        )
        lim = (
            f"beyond the NIOSH frequency table for {_column(duration, v_origin, units)}: Table 5 "
            f"gives {allows} there, and defines FM up to {top} at most (short duration, "
            f"V >= {c['vsplit']:.0f} {u}); beyond, FM = 0 and RWL = 0 (Waters et al. 1994, "
            "Applications Manual Table 5)"
        )
        out.append(("lifting frequency", f"{f:.1f} lifts/min", lim))
    return out


def multipliers(
    h: float, v: float, d: float, a: float, cond: LiftConditions, v_origin: float | None = None
) -> Multipliers:
    """The multipliers at one end of a lift (Waters et al. 1993; the Applications Manual, p. 7).

    :math:`HM = H_0 / \\max(H, H_0)`, :math:`VM = 1 - k_V |V - V_0|`,
    :math:`DM = 0.82 + k_D / \\max(D, D_{min})`, :math:`AM = 1 - 0.0032 A`, each 0 beyond its
    limit (:data:`UNITS`); FM from Table 5 and CM from Table 7.

    Args:
        h: horizontal distance of the hands from the ankles' mid-point, cm (or in).
        v: height of the hands above the floor the worker stands on, cm (or in).
        d: vertical travel of the lift, cm (or in).
        a: asymmetry angle, degrees.
        cond: frequency, duration category, coupling and units of the lift.
        v_origin: the origin's V for FM (default ``v``).

    Returns:
        The six multipliers.

    Raises:
        InputError: unknown units, coupling or duration, or H, V, D, A not finite and >= 0.
    """
    f, duration, coupling, units = cond.f, cond.duration, cond.coupling, cond.units
    if units not in UNITS:
        raise InputError(f"NIOSH: units must be 'metric' or 'us', got {units!r}")
    if coupling not in CM_TABLE:
        raise InputError(f"NIOSH: coupling must be one of {COUPLINGS}, got {coupling!r}")
    for name, x in (("H", h), ("V", v), ("D", d), ("A", a)):
        if not np.isfinite(x) or x < 0:
            raise InputError(f"NIOSH: {name} must be finite and >= 0, got {x!r}")
    c = UNITS[units]
    hm = 0.0 if h > c["hmax"] else c["h0"] / max(h, c["h0"])
    vm = 0.0 if v > c["vmax"] else 1.0 - c["vk"] * abs(v - c["v0"])
    dm = 0.0 if d > c["dmax"] else 0.82 + c["dk"] / max(d, c["dmin"])
    am = 0.0 if a > 135.0 else 1.0 - 0.0032 * a
    fm = frequency_multiplier(f, duration, v if v_origin is None else v_origin, units)
    cm = CM_TABLE[coupling][int(v >= c["vsplit"])]
    return Multipliers(hm, vm, dm, am, fm, cm)


def rwl(m: Multipliers, units: str = "metric", round_multipliers: bool = False) -> float:
    """The recommended weight limit, :math:`RWL = LC \\cdot HM \\cdot VM \\cdot DM \\cdot AM
    \\cdot FM \\cdot CM`.

    Args:
        m: the multipliers.
        units: "metric" (LC 23 kg) or "us" (LC 51 lb).
        round_multipliers: round each multiplier to two decimals first, as the manual's
            worksheets do (p. 29), to reproduce their figures.

    Returns:
        The RWL, kg (or lb).
    """
    vals = [m.hm, m.vm, m.dm, m.am, m.fm, m.cm]
    if round_multipliers:
        vals = [round(x + 1e-12, 2) for x in vals]
    return float(UNITS[units]["lc"] * np.prod(vals))


@dataclass
class Lift:
    """One lift (or lowering) of a part: where the hands were at its origin and destination,
    its recommended weight limit and its lifting index (metric: cm, kg, degrees).

    Attributes:
        task: index of the cycle task (one that takes a part from its site or puts it down
            there).
        kind: the task's kind (its name, for the report).
        mass: the part's mass, kg.
        h, v, a: (origin, destination) horizontal distance, height, asymmetry angle.
        d: vertical travel, cm.
        f: lifts per minute.
        rwl: the recommended weight limit, kg: the origin's, and for a lift with significant
            control at the destination (putting the part down onto its site, Applications
            Manual p. 21) the lower of both ends.
        li: mass / rwl; None where the RWL is 0 (a multiplier at 0): the equation gives no
            index for the lift, ``reason`` says why.
        one_handed: the equation is for two-handed lifts (p. 6); a one-handed lift is scored
            as if two-handed and flagged.
        reason: why ``li`` is None: each variable beyond its limit, its value and what the
            manual allows ("" when the index is computed).
        limit: ``reason`` without the measured values (the same for every lift that crossed
            the same limit; for counting them).
    """

    task: int
    kind: str
    hand: str
    mass: float
    h: tuple[float, float]
    v: tuple[float, float]
    a: tuple[float, float]
    d: float
    f: float
    coupling: str
    rwl: float
    li: float | None
    one_handed: bool
    reason: str = ""
    limit: str = ""


def lift(
    task: int, kind: str, hand: str, mass: float, ends: LiftEnds, cond: LiftConditions, *,
    control_at_destination: bool = False,
) -> Lift:  # fmt: skip
    """Score one lift. The RWL is taken at the origin, and with ``control_at_destination`` (a
    part put down onto its site) at both ends (the lower); :math:`LI = mass / RWL`.

    Args:
        task: index of the cycle task.
        kind: the task's kind (a label).
        hand: "left", "right" or "both"; a one-handed lift is flagged.
        mass: the part's mass, kg (or lb with ``cond.units`` "us").
        ends: the hands' H, V (cm) and A (deg) at the origin and the destination.
        cond: frequency, duration category, coupling and units of the lift.
        control_at_destination: the RWL is also taken at the destination.

    Returns:
        The :class:`Lift`, with ``li`` None and the reason where the RWL is 0.
    """
    h, v, a = ends.h, ends.v, ends.a
    d = abs(v[1] - v[0])
    pts = (0, 1) if control_at_destination else (0,)
    limits = [rwl(multipliers(h[e], v[e], d, a[e], cond, v_origin=v[0]), cond.units) for e in pts]
    r = min(limits)
    why: list[tuple[str, str, str]] = []
    if r <= 0:
        for e in pts:
            for w in zero_reasons(h[e], v[e], d, a[e], cond, v[0],
                                  end=("origin", "destination")[e]):  # fmt: skip
                if w not in why:
                    why.append(w)
    reason = "; ".join(f"{var} {val} is {lim}" for var, val, lim in why)
    limit = "; ".join(f"{var} {lim}" for var, _, lim in why)
    li = mass / r if r > 0 else None
    return Lift(task, kind, hand, mass, h, v, a, d, cond.f, cond.coupling, r, li, hand != "both",
                reason, limit)  # fmt: skip
