"""How an operator's stature, speed and cadence go together: the Gaussian copula of a population
group's draws (:meth:`mjwalk.cycle.population.Population.draw`) and the longest step it allows.

Speed is step length times cadence, and between people the step length scales with body size
while the cadence does not. mjwalk takes the step length ``L`` as proportional to stature ``H``
times a size-free factor (Hof, "Scaling gait data to body size", Gait Posture 4:222-223, 1996:
step length over leg length is the dimensionless step length, and leg length is a fixed share of
stature), and that factor and the cadence ``f`` to vary independently between people and of
stature (Samson et al., "Differences in gait parameters at a preferred walking speed in healthy
subjects due to age, height and body weight", Aging Clin Exp Res 13:16-21, 2001: cadence "was not
associated with age, height and body weight"). With the figures' coefficients of variation
``c_H, c_v, c_f`` (their logarithms' SDs), ``log v = log L + log f`` gives the step length's
``c_L = sqrt(c_v**2 - c_f**2)`` and the figures' normal scores correlate as

- speed-cadence: ``rho_vf = c_f / c_v``, capped at 1 (:meth:`GaitCopula.speed_cadence_rho`);
- stature-speed: ``rho_Hv = min(c_H, c_L) / c_v`` (:meth:`GaitCopula.stature_speed_rho`);
- stature-cadence: 0;

so stature and step length correlate with ``r = min(c_H / c_L, 1)``
(:meth:`GaitCopula.stature_step_rho`; 1 where the marginals leave the step no spread of its own
beyond the stature's, and then the step over stature does not vary). The adult preset (stature
1.72 +- 0.09 m, speed 1.38 +- 0.17 m/s, cadence 113 +- 8 steps/min) has rho_vf = 0.58, a step
length CV of 10 % and r = 0.52; Samson et al. 2001 report that height, beside age, takes 13 %
(men) and 19 % (women) off the stride length's standard error: partial correlations of about
0.49 and 0.59 (``sqrt(1 - 0.87**2)``, ``sqrt(1 - 0.81**2)``). The older presets' wider speed
spread gives weaker correlations (older adult 0.44, elderly 0.29), brisk walking 0.81.

The draw takes the stature at its own quantile (as without the copula), then speed and cadence
at quantiles correlated with its normal score (:meth:`GaitCopula.quantiles`), so each figure
keeps its own distribution. Besides, no operator takes steps longer than
:data:`STEP_STATURE_MAX` times its stature: the speed and cadence of such a draw are drawn again
at the same stature until its step is under the cap. This redraws at most 0.04 % of a preset's
draws (10 000 each, seeded), too few to move its marginals. Where the marginals force longer
steps -- no speed and cadence within their bounds give one under the cap at the operator's
stature, or none of :data:`STEP_STATURE_TRIES` draws does (about 1 % of the pairs or fewer lie
under it) -- the first draw stands: a population file's own figures are never bent by the cap.
A fixed stature has no correlation to model and no cap: its speed-cadence draw is the same as
before stature entered the copula.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.special import ndtr, ndtri

#: Longest step length (m) over stature an operator takes at its preferred pace: young adults'
#: 0.433 +- 0.035 (mean, between-person SD; Espy, Yang, Bhatt & Pai, "Independent influence of
#: gait speed and step length on stability and fall risk", Gait Posture 32:378-382, 2010,
#: Table 2, the longest-step group) plus three SDs, rounded (ASSUMPTION: the three SDs).
STEP_STATURE_MAX = 0.55
#: Speed-cadence draws tried again per operator above :data:`STEP_STATURE_MAX` before the first
#: one stands.
STEP_STATURE_TRIES = 64


@dataclass(frozen=True)
class GaitCopula:
    """The correlations of a group's stature, speed and cadence draws, from the figures'
    coefficients of variation (module docstring).

    Attributes:
        cv_stature, cv_speed, cv_cadence: the coefficients (0 for a fixed figure).
    """

    cv_stature: float
    cv_speed: float
    cv_cadence: float

    def speed_cadence_rho(self) -> float:
        """Correlation of the speed and cadence draws: ``cv_cadence / cv_speed`` capped at 1.

        Returns:
            The correlation, 0 to 1 (0 when either figure is fixed).
        """
        cs, cc = self.cv_speed, self.cv_cadence
        if cs == 0.0 or cc == 0.0:
            return 0.0
        return min(cc / cs, 1.0)

    def step_cv(self) -> float:
        """Between-person coefficient of variation of the step length:
        ``sqrt(cv_speed**2 - cv_cadence**2)``.

        Returns:
            The coefficient (0 when the cadence varies as much as the speed or more, or the
            speed's is not finite).
        """
        cs, cc = self.cv_speed, self.cv_cadence
        return math.sqrt(max(cs * cs - cc * cc, 0.0)) if math.isfinite(cs) else 0.0

    def stature_step_rho(self) -> float:
        """Correlation of stature and step length: ``min(cv_stature / cv_step, 1)``.

        Returns:
            The correlation, 0 to 1 (0 when the stature or the step length does not vary).
        """
        ch, cl = self.cv_stature, self.step_cv()
        if ch == 0.0 or cl == 0.0:
            return 0.0
        return min(ch / cl, 1.0)

    def stature_speed_rho(self) -> float:
        """Correlation of the stature and speed draws: ``min(cv_stature, cv_step) / cv_speed``.

        Returns:
            The correlation, 0 to 1 (0 when the stature or the step length does not vary).
        """
        if self.stature_step_rho() == 0.0:
            return 0.0
        return min(min(self.cv_stature, self.step_cv()) / self.cv_speed, 1.0)

    def quantiles(self, z_stature: float, u_speed: float, u_other: float) -> tuple[float, float]:
        """The speed's and the cadence's quantiles for a stature's normal score and two
        independent uniforms (the lower Cholesky factor of the correlations, stature first).

        Args:
            z_stature: the stature's standard normal score.
            u_speed: a uniform quantile, 0 to 1 (open).
            u_other: another, independent of ``u_speed``.

        Returns:
            (speed quantile, cadence quantile), 0 to 1; without a stature-speed correlation the
            speed's is ``u_speed`` itself and the pair is the speed-cadence copula's alone.
        """
        r_hv, r_vf = self.stature_speed_rho(), self.speed_cadence_rho()
        z_speed = float(ndtri(u_speed))
        if r_hv > 0.0:
            rest = math.sqrt(max(1.0 - r_hv * r_hv, 0.0))
            u_speed = float(ndtr(r_hv * z_stature + rest * z_speed))
            r_vf = min(r_vf / rest, 1.0) if rest > 0.0 else 0.0
        z_other = float(ndtri(u_other))
        u_cadence = float(ndtr(r_vf * z_speed + math.sqrt(max(1.0 - r_vf * r_vf, 0.0)) * z_other))
        return u_speed, u_cadence
