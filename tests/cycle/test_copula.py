"""The Gaussian copula of stature, speed and cadence (issue 47's walker profiles): correlations
from the coefficients of variation, and the quantiles that carry them. Seeded; tolerances
stated per test."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import ndtri

from mjwalk.cycle.copula import STEP_STATURE_MAX, GaitCopula
from mjwalk.gait.walker import PRESETS


def _copula(name: str) -> GaitCopula:
    p = PRESETS[name]
    return GaitCopula(*(sd / mean for mean, sd in (p.stature, p.speed, p.cadence)))


def test_adult_correlations_are_the_derived_ones():
    """Adult preset: rho_vf = cv_f / cv_v (0.58), step CV sqrt(cv_v^2 - cv_f^2) (0.10),
    stature-step r = cv_H / cv_L (0.52, between Samson et al. 2001's partial 0.49 and 0.59),
    stature-speed cv_H / cv_v (0.42)."""
    c = _copula("adult")
    assert c.speed_cadence_rho() == pytest.approx(c.cv_cadence / c.cv_speed)
    assert c.step_cv() == pytest.approx(math.sqrt(c.cv_speed**2 - c.cv_cadence**2))
    assert c.stature_step_rho() == pytest.approx(0.52, abs=0.005)
    assert 0.49 <= c.stature_step_rho() <= 0.59
    assert c.stature_speed_rho() == pytest.approx(c.cv_stature / c.cv_speed)


def test_quantiles_carry_the_correlations():
    """20 000 seeded draws: the normal scores' correlations within 0.03 (about 4 standard
    errors) of stature-speed, speed-cadence and 0 for stature-cadence; the uniforms stay in
    (0, 1) and uniform (mean 0.5 within 0.01)."""
    c = _copula("older_adult")
    rng = np.random.default_rng(7)
    z_h = rng.standard_normal(20000)
    u = np.array([c.quantiles(float(z), *map(float, rng.random(2))) for z in z_h])
    z = ndtri(u)
    r = np.corrcoef(np.vstack([z_h, z.T]))
    assert r[0, 1] == pytest.approx(c.stature_speed_rho(), abs=0.03)
    assert r[1, 2] == pytest.approx(c.speed_cadence_rho(), abs=0.03)
    assert abs(r[0, 2]) < 0.03
    assert 0.0 < u.min() and u.max() < 1.0
    assert u.mean(axis=0) == pytest.approx([0.5, 0.5], abs=0.01)


def test_fixed_stature_keeps_the_speed_quantile():
    """No stature spread: no stature correlation, and the speed's quantile is the uniform
    itself (the draws of a fixed-stature population are the same as before)."""
    c = GaitCopula(0.0, 0.12, 0.07)
    assert c.stature_speed_rho() == 0.0 and c.stature_step_rho() == 0.0
    assert c.quantiles(1.3, 0.123, 0.8)[0] == 0.123


@pytest.mark.parametrize(
    ("cvs", "r_hl", "r_hv"),
    [
        ((0.05, 0.06, 0.08), 0.0, 0.0),  # cadence varies more than speed: no step spread
        ((0.10, 0.08, 0.0), 1.0, 1.0),  # fixed cadence, stature wider than speed: r capped
        ((0.10, 0.10, 0.06), 1.0, 0.8),  # stature wider than the step: r = 1, rho_Hv = cv_L/cv_v
    ],
)
def test_edges_stay_a_valid_copula(cvs, r_hl, r_hv):
    """Where the marginals leave the step no spread of its own the correlations cap at 1 and the
    quantiles stay finite and inside (0, 1)."""
    c = GaitCopula(*cvs)
    assert c.stature_step_rho() == pytest.approx(r_hl)
    assert c.stature_speed_rho() == pytest.approx(r_hv)
    for z in (-3.0, 0.0, 2.5):
        us, uc = c.quantiles(z, 0.3, 0.9)
        assert 0.0 < us < 1.0 and 0.0 < uc < 1.0


def test_cap_is_above_every_preset_mean():
    """The cap (0.55) is above every preset's typical step over stature (brisk: 0.46)."""
    for p in PRESETS.values():
        assert p.speed[0] * 60.0 / p.cadence[0] / p.stature[0] < STEP_STATURE_MAX
