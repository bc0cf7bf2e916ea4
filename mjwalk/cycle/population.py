"""The operator population of a cycle: who walks each Monte-Carlo run.

A cycle file's optional ``[population]`` table says how the operator of each run is drawn: a
mixture of named walker presets with shares, per-figure distributions of stature, speed and
cadence, or one fixed walker. Each run draws one :class:`~mjwalk.gait.walker.Walker` from its own
random stream (:meth:`Population.draw`), so the draws do not depend on the number of workers.

Format (lengths in metres, speeds in metres per second, cadences in steps per minute)::

    takt = 60.0                 # optional, top level: seconds; the report gives P(cycle > takt)

    [population]                # either a mixture of presets ...
    mix = { adult = 0.7, older_adult = 0.2, fatigued = 0.1 }

    [population]                # ... or one walker (a preset's typical figures) ...
    walker = "adult"

    [population]                # ... or figures, each a plain number or a distribution
    group = "night shift"       # label in the reports (default: the walker preset, else
                                # "population")
    walker = "older_adult"      # optional base: figures not given are this preset's means
    stature = { dist = "normal", mean = 1.72, sd = 0.09 }
    speed = { dist = "truncnorm", mean = 1.3, sd = 0.2, min = 0.8, max = 1.8 }
    cadence = { dist = "lognormal", median = 110.0, cv = 0.08 }   # or mean = .., sd = ..
    step_width = 0.10           # optional, fixed (default: the step model's, scaled by stature)
    step_up = 0.0               # optional, any form: metres, or { group = metres } (stepup.py)

``mix``: preset names of :data:`mjwalk.gait.walker.PRESETS` (adult, older_adult, elderly,
fatigued, brisk) with positive relative shares (normalised to sum to 1); each group draws every
figure from its preset's normal distribution (mean, between-person SD). ``mix`` stands alone in the
table. Distributions (``dist``): ``"fixed"`` (``value``), ``"normal"`` (``mean``, ``sd``),
``"truncnorm"`` (``mean``, ``sd`` of the untruncated normal and ``min`` and/or ``max``) and
``"lognormal"`` (``median`` and ``cv``, or ``mean`` and ``sd`` of the variable itself; optional
``min``/``max``). Without a stature figure (no ``mix``, no ``walker``, no ``stature``) the
operator has the ``[humanoid]`` stature.

Every draw is truncated to the human ranges (:data:`RANGES`: the
:class:`~mjwalk.gait.walker.Walker` checks, and the humanoid's statures) by inverse-CDF sampling,
so no run fails on an implausible operator; a distribution that puts less than
:data:`MIN_MASS` of its draws inside those ranges is refused when the cycle file is read.
Statures are drawn to the centimetre (the humanoid is built per centimetre).

Stature, speed and cadence are drawn through a Gaussian copula whose correlations follow from
step length growing with stature while the cadence does not (:mod:`mjwalk.cycle.copula`, which
derives them and caps step length over stature), so each figure keeps its own distribution.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
from scipy.special import ndtr, ndtri

from mjwalk.cycle.copula import STEP_STATURE_MAX, STEP_STATURE_TRIES, GaitCopula
from mjwalk.cycle.stepup import parse_step_up
from mjwalk.errors import CycleSpecError
from mjwalk.gait.walker import CADENCE_RANGE, PRESETS, SPEED_RANGE, Walker
from mjwalk.gait.walker import STATURE_RANGE as WALKER_STATURE_RANGE

#: Statures the humanoid is built for, metres (the ``[humanoid]`` stature's range too).
HUMANOID_STATURE_RANGE = (1.4, 2.1)
#: Where drawn figures are truncated: the Walker's human ranges, statures also to the humanoid's.
RANGES: dict[str, tuple[float, float]] = {
    "stature": (
        max(WALKER_STATURE_RANGE[0], HUMANOID_STATURE_RANGE[0]),
        min(WALKER_STATURE_RANGE[1], HUMANOID_STATURE_RANGE[1]),
    ),
    "speed": SPEED_RANGE,
    "cadence": CADENCE_RANGE,
}
UNITS = {"stature": "m", "speed": "m/s", "cadence": "steps/min"}
FIGURES = ("stature", "speed", "cadence")
#: A distribution must put at least this share of its draws inside the human range (else its
#: mean or sd is most likely in the wrong unit); checked when the cycle file is read.
MIN_MASS = 0.01
#: Statures are drawn to this resolution (m): the humanoid is rebuilt per value.
STATURE_STEP = 0.01
#: The group label of per-figure draws without a preset or a ``group``.
POPULATION_GROUP = "population"
DISTS = ("fixed", "normal", "truncnorm", "lognormal")
_POP_KEYS = ("mix", "walker", "group", "stature", "speed", "cadence", "step_width", "step_up")
_DIST_KEYS = {
    "fixed": ("dist", "value"),
    "normal": ("dist", "mean", "sd"),
    "truncnorm": ("dist", "mean", "sd", "min", "max"),
    "lognormal": ("dist", "median", "cv", "mean", "sd", "min", "max"),
}


@dataclass(frozen=True)
class Distribution:
    """One figure's distribution, truncated to ``[lo, hi]``.

    Attributes:
        kind: "fixed", "normal", "truncnorm" or "lognormal".
        mu, sigma: the normal's mean and sd (lognormal: of the logarithm; fixed: the value, 0).
        lo, hi: truncation bounds in the figure's unit (always within :data:`RANGES`).
    """

    kind: str
    mu: float
    sigma: float
    lo: float
    hi: float

    @property
    def _log(self) -> bool:
        return self.kind == "lognormal"

    def _ab(self) -> tuple[float, float]:
        f = math.log if self._log else float
        return (f(self.lo) - self.mu) / self.sigma, (f(self.hi) - self.mu) / self.sigma

    def ppf(self, u: float) -> float:
        """The value at quantile ``u`` of the truncated distribution.

        Args:
            u: the quantile, 0 to 1.

        Returns:
            The value in the figure's unit, within ``[lo, hi]`` (``mu`` for a fixed figure).
        """
        if self.kind == "fixed" or self.sigma == 0.0:
            return float(self.mu)
        a, b = self._ab()
        z = _truncnorm_ppf(u, a, b)
        x = self.mu + self.sigma * z
        return float(np.clip(math.exp(x) if self._log else x, self.lo, self.hi))

    def mass(self) -> float:
        """Share of the untruncated distribution inside ``[lo, hi]``.

        Returns:
            The probability, 0 to 1 (a fixed figure: 1 inside the bounds, else 0).
        """
        if self.kind == "fixed" or self.sigma == 0.0:
            return 1.0 if self.lo <= self.mu <= self.hi else 0.0
        a, b = self._ab()
        return float(ndtr(b) - ndtr(a))

    def moments(self) -> tuple[float, float]:
        """Mean and standard deviation of the truncated distribution.

        Returns:
            (mean, sd) in the figure's unit.
        """
        if self.kind == "fixed" or self.sigma == 0.0:
            return float(self.mu), 0.0
        a, b = self._ab()
        if not self._log:
            # deferred: scipy.stats takes ~1 s to import and only this summary needs it
            from scipy.stats import truncnorm

            m, v = truncnorm.stats(a, b, loc=self.mu, scale=self.sigma, moments="mv")
            return float(m), float(math.sqrt(v))

        # E[exp(k X)] of the truncated normal X: closed form (raw moments of a lognormal
        # restricted to [lo, hi])
        def raw(k: int) -> float:
            s = self.sigma
            num = ndtr(b - k * s) - ndtr(a - k * s)
            return math.exp(k * self.mu + 0.5 * k * k * s * s) * num / (ndtr(b) - ndtr(a))

        m1, m2 = raw(1), raw(2)
        return m1, math.sqrt(max(m2 - m1 * m1, 0.0))

    def cv(self) -> float:
        r"""Coefficient of variation of the untruncated distribution: :math:`\sigma / |\mu|` for a
        normal, :math:`\sqrt{e^{\sigma^2} - 1}` for a lognormal.

        Returns:
            The coefficient (0 for a fixed figure, ``inf`` for a normal of mean 0).
        """
        if self.kind == "fixed" or self.sigma == 0.0:
            return 0.0
        if self._log:
            return math.sqrt(math.expm1(self.sigma**2))
        return self.sigma / abs(self.mu) if self.mu != 0.0 else math.inf

    def describe(self, unit: str = "") -> str:
        """Short text, e.g. ``normal(1.38, 0.17) m/s in 0.3-2.5``.

        Args:
            unit: the figure's unit.

        Returns:
            The text.
        """
        if self.kind == "fixed":
            return f"{self.mu:g} {unit}".strip()
        if self._log:
            cv = math.sqrt(math.expm1(self.sigma**2))
            head = f"lognormal(median {math.exp(self.mu):.3g}, cv {cv:.2f})"
        else:
            head = f"{self.kind}({self.mu:.3g}, {self.sigma:.3g})"
        return f"{head} {unit} in {self.lo:g}-{self.hi:g}".replace("  ", " ")


def _truncnorm_ppf(u: float, a: float, b: float) -> float:
    """Quantile ``u`` of the standard normal truncated to ``[a, b]`` (inverse CDF; the upper
    tail through the mirror image, where the lower tail's probabilities keep their precision)."""
    if a > 0.0:
        return -_truncnorm_ppf(1.0 - u, -b, -a)
    pa, pb = float(ndtr(a)), float(ndtr(b))
    return float(np.clip(ndtri(pa + u * (pb - pa)), a, b))


def fixed(value: float) -> Distribution:
    """A figure that does not vary.

    Args:
        value: the figure's value (its unit).

    Returns:
        The "fixed" :class:`Distribution` at ``value``.
    """
    return Distribution("fixed", float(value), 0.0, float(value), float(value))


@dataclass(frozen=True)
class OperatorGroup:
    """One group of the workforce: its share and the distribution of each figure.

    Attributes:
        name: the label in reports (preset name, ``group`` or "population").
        share: the group's share of the runs (the groups' shares sum to 1).
        stature, speed, cadence: the figures' distributions (m, m/s, steps/min).
        step_width: fixed step width (m) or None (the step model's, scaled by stature).
    """

    name: str
    share: float
    stature: Distribution
    speed: Distribution
    cadence: Distribution
    step_width: float | None = None

    @property
    def copula(self) -> GaitCopula:
        """The correlations of the group's stature, speed and cadence draws
        (:class:`~mjwalk.cycle.copula.GaitCopula` of the figures' coefficients of variation)."""
        return GaitCopula(self.stature.cv(), self.speed.cv(), self.cadence.cv())

    def speed_cadence_rho(self) -> float:
        """Correlation of the speed and cadence draws (:meth:`GaitCopula.speed_cadence_rho`).

        Returns:
            The correlation, 0 to 1 (0 when either figure is fixed).
        """
        return self.copula.speed_cadence_rho()

    def stature_step_rho(self) -> float:
        """Correlation of stature and step length (:meth:`GaitCopula.stature_step_rho`).

        Returns:
            The correlation, 0 to 1 (0 when the stature or the step length does not vary).
        """
        return self.copula.stature_step_rho()

    def describe(self) -> dict[str, str | float | None]:
        """The group as plain data (for the report).

        Returns:
            group, share, each figure's :meth:`Distribution.describe`, the speed-cadence and
            stature-step length correlations and the step width (m or None).
        """
        return {
            "group": self.name,
            "share": self.share,
            **{f: getattr(self, f).describe(UNITS[f]) for f in FIGURES},
            "speed_cadence_rho": round(self.speed_cadence_rho(), 3),
            "stature_step_rho": round(self.stature_step_rho(), 3),
            "step_width": self.step_width,
        }


@dataclass(frozen=True)
class Population:
    """The operators of a cycle's runs: groups with shares (one group for a fixed walker or
    per-figure distributions)."""

    groups: tuple[OperatorGroup, ...]
    #: (group, step-up limit in metres) of the groups that have one (:mod:`mjwalk.cycle.stepup`).
    step_up: tuple[tuple[str, float], ...] = ()

    def draw(self, rng: np.random.Generator) -> Walker:
        """One operator: the group by its share, its stature at a uniform quantile, then speed
        and cadence at quantiles correlated with it and each other
        (:meth:`~mjwalk.cycle.copula.GaitCopula.quantiles`); four uniforms from ``rng``, two
        more per speed and cadence drawn again over
        :data:`~mjwalk.cycle.copula.STEP_STATURE_MAX`. Stature is
        rounded to :data:`STATURE_STEP`.

        Args:
            rng: the run's operator stream.

        Returns:
            The :class:`~mjwalk.gait.walker.Walker` (stature m, speed m/s, cadence steps/min).
        """
        u = rng.random(4)
        cum = np.cumsum([g.share for g in self.groups])
        k = min(int(np.searchsorted(cum, u[0] * cum[-1], side="right")), len(self.groups) - 1)
        g = self.groups[k]
        lo, hi = RANGES["stature"]
        stature = round(g.stature.ppf(float(u[1])) / STATURE_STEP) * STATURE_STEP
        stature = float(np.clip(round(stature, 2), lo, hi))
        cop, z_stature = g.copula, float(ndtri(u[1]))

        def pace(u_speed: float, u_other: float) -> tuple[float, float]:
            us, uc = cop.quantiles(z_stature, u_speed, u_other)
            return g.speed.ppf(us), g.cadence.ppf(uc)

        speed, cadence = pace(float(u[2]), float(u[3]))
        # the cap (mjwalk.cycle.copula): only with a stature that varies, and only when some
        # speed and cadence within their bounds give a step under it at this stature
        cap = STEP_STATURE_MAX * stature / 60.0
        if cop.cv_stature > 0.0 and g.speed.lo / g.cadence.hi <= cap and speed / cadence > cap:
            for _ in range(STEP_STATURE_TRIES):  # none under the cap: the first draw stands
                s2, c2 = pace(*map(float, rng.random(2)))
                if s2 / c2 <= cap:
                    speed, cadence = s2, c2
                    break
        return Walker(stature, speed, cadence, step_width=g.step_width, group=g.name)

    @property
    def group_names(self) -> list[str]:
        return [g.name for g in self.groups]

    def describe(self) -> list[dict[str, str | float | None]]:
        """The groups as plain data (for the report).

        Returns:
            One :meth:`OperatorGroup.describe` dict per group.
        """
        return [g.describe() for g in self.groups]


# ------------------------------------------------------------------------------ parsing

#: ``fail(message, key)`` returns the CycleSpecError to raise (the spec loader's, which adds the
#: file and the key's line).
Fail = Callable[[str, str], CycleSpecError]


def _default_fail(msg: str, key: str) -> CycleSpecError:
    exc = CycleSpecError(msg)
    exc.key = key
    return exc


def _num(value, where: str, key: str, fail: Fail) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise fail(f"{where} must be a finite number, got {value!r}", key)
    return float(value)


def _preset(name, where: str, key: str, fail: Fail):
    if not isinstance(name, str) or name not in PRESETS:
        raise fail(f"{where}: unknown walker preset {name!r} (known: {', '.join(PRESETS)})", key)
    return PRESETS[name]


def _check_range(value: float, figure: str, where: str, key: str, fail: Fail) -> float:
    lo, hi = RANGES[figure]
    if not lo <= value <= hi:
        raise fail(
            f"{where} = {value:g} {UNITS[figure]} is outside the human range {lo:g}-{hi:g}", key
        )
    return value


def parse_distribution(value, figure: str, fail: Fail = _default_fail) -> Distribution:
    """A figure of ``[population]``: a plain number (fixed) or a ``{dist = ...}`` table.

    Args:
        value: the figure's value as read from the TOML.
        figure: "stature", "speed" or "cadence".
        fail: builds the error to raise from a message and the offending key.

    Returns:
        The figure's :class:`Distribution`.

    Raises:
        CycleSpecError: an unknown distribution or key, a value outside the human range, or a
            distribution with too little of its mass in the range.
    """
    where = f"population.{figure}"
    if not isinstance(value, dict):
        v = _num(value, where, figure, fail)
        return fixed(_check_range(v, figure, where, figure, fail))
    if "dist" not in value:
        raise fail(f"{where}: missing key 'dist' ({' | '.join(DISTS)})", figure)
    kind = value["dist"]
    if kind not in DISTS:
        raise fail(
            f"{where}.dist: unknown distribution {kind!r} (known: {', '.join(DISTS)})", figure
        )
    allowed = _DIST_KEYS[kind]
    for key in value:
        if key not in allowed:
            raise fail(
                f"{where}: unknown key {key!r} for dist = {kind!r} (valid keys: "
                f"{', '.join(allowed)})",
                figure,
            )
    nums = {k: _num(v, f"{where}.{k}", figure, fail) for k, v in value.items() if k != "dist"}
    lo, hi = RANGES[figure]

    def need(*keys: str) -> None:
        for k in keys:
            if k not in nums:
                raise fail(f"{where}: dist = {kind!r} needs key {k!r}", figure)

    if kind == "fixed":
        need("value")
        return fixed(_check_range(nums["value"], figure, f"{where}.value", figure, fail))
    for k in ("min", "max"):
        if k in nums:
            _check_range(nums[k], figure, f"{where}.{k}", figure, fail)
    t_lo, t_hi = nums.get("min", lo), nums.get("max", hi)
    if t_lo >= t_hi:
        raise fail(f"{where}: min {t_lo:g} must be below max {t_hi:g}", figure)
    if kind == "truncnorm" and "min" not in nums and "max" not in nums:
        raise fail(f"{where}: dist = 'truncnorm' needs 'min' and/or 'max'", figure)
    for k in ("sd", "cv"):
        if k in nums and nums[k] <= 0.0:
            raise fail(
                f"{where}.{k} must be > 0, got {nums[k]:g} (a plain number gives a fixed figure)",
                figure,
            )
    if kind in ("normal", "truncnorm"):
        need("mean", "sd")
        dist = Distribution(kind, nums["mean"], nums["sd"], t_lo, t_hi)
    else:  # lognormal: median and cv, or mean and sd of the variable
        if "median" in nums or "cv" in nums:
            if "mean" in nums or "sd" in nums:
                raise fail(f"{where}: give either median and cv, or mean and sd", figure)
            need("median", "cv")
            median, cv = nums["median"], nums["cv"]
        else:
            need("mean", "sd")
            cv = nums["sd"] / nums["mean"] if nums["mean"] > 0 else -1.0
            median = nums["mean"] / math.sqrt(1.0 + cv * cv) if cv > 0 else -1.0
        if median <= 0.0:
            raise fail(f"{where}: a lognormal's median (or mean) must be > 0", figure)
        dist = Distribution(kind, math.log(median), math.sqrt(math.log1p(cv * cv)), t_lo, t_hi)
    mass = dist.mass()
    if mass < MIN_MASS:
        raise fail(
            f"{where}: only {100 * mass:.2g} % of the distribution lies within "
            f"{t_lo:g}-{t_hi:g} {UNITS[figure]} (the human range or min/max); check its "
            "figures and unit",
            figure,
        )
    return dist


def preset_group(name: str, share: float = 1.0) -> OperatorGroup:
    """The group of a :data:`PRESETS` entry: each figure normal(mean, sd), truncated to its
    human range (fixed when its sd is 0).

    Args:
        name: the preset's name.
        share: the group's share of the runs.

    Returns:
        The :class:`OperatorGroup`.
    """
    p = PRESETS[name]
    figs = {}
    for f in FIGURES:
        mean, sd = getattr(p, f)
        lo, hi = RANGES[f]
        figs[f] = Distribution("normal", mean, sd, lo, hi) if sd > 0 else fixed(mean)
    return OperatorGroup(name, share, step_width=p.step_width, **figs)


def parse_population(table, humanoid_stature: float, fail: Fail = _default_fail) -> Population:
    """The :class:`Population` of a ``[population]`` table (format in the module docstring).

    Args:
        table: the parsed TOML table.
        humanoid_stature: the ``[humanoid]`` stature (m), used when no figure gives one.
        fail: builds the error to raise from a message and the offending key.

    Returns:
        The population (one group per preset of ``mix``, else one group).

    Raises:
        CycleSpecError: unknown keys, presets or distributions; shares that are not positive;
            sd or cv not positive; figures outside the human ranges; ``mix`` with other keys.
    """
    if not isinstance(table, dict):
        raise fail("'population' must be a table ([population])", "population")
    if "step_up" in table:  # besides any form: the groups' limits (mjwalk.cycle.stepup)
        rest = {k: v for k, v in table.items() if k != "step_up"}
        pop = parse_population(rest, humanoid_stature, fail)
        return replace(pop, step_up=parse_step_up(table["step_up"], pop.group_names, fail))
    for key in table:
        if key not in _POP_KEYS:
            raise fail(
                f"unknown key {key!r} in [population] (valid keys: {', '.join(_POP_KEYS)})", key
            )
    if not table:
        raise fail(
            '[population] is empty: give mix = {...}, walker = "<preset>" or figures '
            "(stature, speed, cadence)",
            "population",
        )
    if "mix" in table:
        others = [k for k in table if k != "mix"]
        if others:
            raise fail(
                f"[population]: 'mix' stands alone (each preset brings its own figures); "
                f"remove {', '.join(repr(k) for k in others)}",
                others[0],
            )
        mix = table["mix"]
        if not isinstance(mix, dict) or not mix:
            raise fail(
                "population.mix must be a table of preset = share, e.g. "
                "{ adult = 0.8, older_adult = 0.2 }",
                "mix",
            )
        shares = {}
        for name, share in mix.items():
            _preset(name, f"population.mix.{name}", "mix", fail)
            s = _num(share, f"population.mix.{name}", "mix", fail)
            if s <= 0.0:
                raise fail(f"population.mix.{name}: share must be > 0, got {s:g}", "mix")
            shares[name] = s
        total = sum(shares.values())
        return Population(tuple(preset_group(n, s / total) for n, s in shares.items()))

    base = None
    if "walker" in table:
        base = _preset(table["walker"], "population.walker", "walker", fail)
    group = table.get("group", table.get("walker", POPULATION_GROUP))
    if not isinstance(group, str) or not group.strip():
        raise fail(f"population.group must be a non-empty string, got {group!r}", "group")
    figs: dict[str, Distribution] = {}
    for f in FIGURES:
        if f in table:
            figs[f] = parse_distribution(table[f], f, fail)
        elif base is not None:
            figs[f] = fixed(getattr(base, f)[0])
        elif f == "stature":
            figs[f] = fixed(humanoid_stature)
        else:
            raise fail(
                f"[population] needs {f!r} (a number or a distribution), a walker preset "
                '(walker = "adult") or a mix',
                f,
            )
    width = base.step_width if base is not None else None
    if "step_width" in table:
        width = _num(table["step_width"], "population.step_width", "step_width", fail)
        if not 0.0 <= width <= 0.4:
            raise fail(f"population.step_width must be within 0-0.4 m, got {width:g}", "step_width")
    return Population((OperatorGroup(group.strip(), 1.0, step_width=width, **figs),))
