"""Model selection of a DCS network (mjwalk.arms.dcsfit): input scales, the normalized RBF,
the candidate grids and the scoring of one growth step."""

import numpy as np
import pytest

from mjwalk.arms.dcsfit import (
    SelectionGrids,
    SelectionSamples,
    design,
    grid,
    grid_values,
    input_scale,
    score_step,
)
from mjwalk.errors import MjwalkError


def test_input_scales_per_column_global_and_per_point():
    X = np.random.default_rng(0).normal(size=(200, 6)) * [1, 2, 3, 4, 0, 0]
    sd = X.std(axis=0)
    np.testing.assert_allclose(input_scale(X, "column"), np.where(sd > 0, sd, 1.0))
    np.testing.assert_allclose(input_scale(X, "global"), np.sqrt((sd**2).mean()))
    point = input_scale(X, "point")
    np.testing.assert_allclose(point[:3], np.sqrt((sd[:3] ** 2).mean()))
    np.testing.assert_allclose(point[3:], np.sqrt((sd[3:] ** 2).mean()))


def test_design_rows_are_normalized_over_winner_and_neighbours():
    Z = np.array([[0.0], [0.9], [2.1]])
    centers = np.array([[0.0], [1.0], [2.0]])
    edges = np.array([[0, 1, 0], [1, 0, 1], [0, 1, 0]], dtype=bool)
    Phi = design(Z, centers, np.ones(3), edges)
    np.testing.assert_allclose(Phi.sum(axis=1), 1.0)
    assert Phi[0, 2] == 0.0 and Phi[2, 0] == 0.0  # not a neighbour of the winner
    assert Phi[1].min() > 0.0


def test_grids_are_read_and_checked():
    assert grid_values("ridge", 0.0, True) == (0.0,)
    assert grid_values("width_factor", [0.5, 2], False) == (0.5, 2.0)
    with pytest.raises(MjwalkError, match="width_factor must be > 0"):
        grid_values("width_factor", (0.0, 1.0), False)
    assert grid((False, True)) == (False, True) and grid(1) == (True,)


def test_score_step_picks_the_best_ridge_on_held_out_samples():
    rng = np.random.default_rng(1)
    Z = rng.uniform(-1, 1, size=(40, 1))
    Y = np.sin(3 * Z)
    samples = SelectionSamples(Z[:30], Y[:30], Z[30:], Y[30:], loo=False)
    assert samples.selects and SelectionSamples(Z, Y, Z[:0], Y[:0], loo=False).selects is False
    centers = np.linspace(-1, 1, 5)[:, None]
    ages = np.full((5, 5), -1)
    for i in range(4):
        ages[i, i + 1] = ages[i + 1, i] = 0
    grids = SelectionGrids((1.0,), (1e-6, 1e3), [(False, False, 1.0)])
    score, factor, ridge, form, resid = score_step(samples, grids, centers, ages)
    assert ridge == 1e-6 and factor == 1.0 and form == (False, False, 1.0)
    assert resid.shape == (30,) and score < 0.2
