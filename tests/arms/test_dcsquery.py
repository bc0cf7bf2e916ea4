"""Brute-force nearest training inputs (mjwalk.arms.dcsquery): the same distances to the bit
as SciPy's cKDTree over seeded tables of 1-9 dimensions (the tree's summation order: four
running sums, then the rest), and the DCS network's distance_to_training unchanged by it."""

import numpy as np
import pytest
from scipy.spatial import cKDTree

from mjwalk.arms.dcs import DCSNetwork
from mjwalk.arms.dcsfit import design
from mjwalk.arms.dcsquery import BRUTE_MAX, nearest_distances, use_brute


@pytest.mark.parametrize("d", range(1, 10))
def test_same_bits_as_the_tree(d):
    rng = np.random.default_rng(d)
    for _ in range(20):
        n = int(rng.integers(1, 400))
        train = rng.normal(size=(n, d)) * rng.uniform(0.1, 10.0)
        queries = rng.normal(size=(40, d)) * rng.uniform(0.1, 10.0, size=(40, 1))
        # queries on and a hair off training rows too (the smallest distances)
        k = min(n, 5)
        queries = np.vstack([queries, train[:k], train[:k] + 1e-9 * rng.normal(size=(k, d))])
        want, _ = cKDTree(train).query(queries, k=1)
        got = nearest_distances(train, queries)
        assert got.tobytes() == np.asarray(want, dtype=float).tobytes()


def test_one_row_and_far_queries():
    train = np.array([[0.5, -1.0, 2.0, 0.0, 1.0, 3.0]])
    q = np.array([[1e150, 0, 0, 0, 0, 0], [0.5, -1.0, 2.0, 0.0, 1.0, 3.0]])
    want, _ = cKDTree(train).query(q, k=1)
    assert nearest_distances(train, q).tobytes() == np.asarray(want, dtype=float).tobytes()


def test_use_brute_bound():
    assert use_brute(320, 1)
    assert use_brute(BRUTE_MAX, 1)
    assert not use_brute(BRUTE_MAX, 2)


def test_network_distance_matches_its_tree():
    rng = np.random.default_rng(3)
    X = rng.uniform(-1.0, 1.0, size=(120, 6))
    y = np.sin(X @ rng.normal(size=(6, 2)))
    net = DCSNetwork(max_neurons=6, rng=0).fit(X, y)
    Q = rng.uniform(-1.5, 1.5, size=(30, 6))
    tree_d, _ = net._tree.query(net._standardize(Q), k=1)
    for q, want in zip(
        Q, tree_d, strict=True
    ):  # one query at a time, as a reach asks (brute force)
        assert net.distance_to_training(q[None]).tobytes() == np.float64(want).tobytes()
    big = rng.uniform(-1.5, 1.5, size=(BRUTE_MAX // 120 + 1, 6))  # the tree's own answer
    assert np.array_equal(net.distance_to_training(big), net._tree.query(net._standardize(big))[0])


def _design_numpy(Z, centers, widths, edges):
    """The NumPy design this module's logits replaced (mjwalk.arms.dcsfit before issue 50)."""
    from scipy.spatial.distance import cdist

    d = cdist(Z, centers)
    bmu = np.argmin(d, axis=1)
    active = edges[bmu].copy()
    active[np.arange(len(Z)), bmu] = True
    logit = np.where(active, -0.5 * (d / widths) ** 2, -np.inf)
    logit -= logit.max(axis=1, keepdims=True)
    w = np.exp(logit)
    return w / w.sum(axis=1, keepdims=True)


@pytest.mark.parametrize("d", [1, 2, 3, 6, 9, 11])
def test_design_same_bits(d):
    rng = np.random.default_rng(10 + d)
    for _ in range(30):
        k = int(rng.integers(1, 25))
        centers = rng.normal(size=(k, d))
        widths = rng.uniform(0.05, 2.0, size=k)
        edges = rng.random((k, k)) < 0.3
        edges = edges | edges.T
        np.fill_diagonal(edges, False)
        Z = np.vstack([rng.normal(size=(20, d)) * 2.0, centers[:2]])  # on a centre too
        assert design(Z, centers, widths, edges).tobytes() == (
            _design_numpy(Z, centers, widths, edges).tobytes()
        )


def test_design_nan_as_numpy():
    centers = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])
    widths = np.array([0.5, 1.0, 2.0])
    edges = np.array([[0, 1, 0], [1, 0, 1], [0, 1, 0]], dtype=bool)
    Z = np.array([[np.nan, 0.0], [0.9, 1.1]])
    with np.errstate(invalid="ignore"):
        want = _design_numpy(Z, centers, widths, edges)
        got = design(Z, centers, widths, edges)
    assert np.array_equal(got, want, equal_nan=True)
