"""The growth steps of a DCS network (mjwalk.arms.dcsgrow)."""

import numpy as np

from mjwalk.arms.dcsgrow import adapt, insert_neuron, insertion_pair, prune, start_neurons
from mjwalk.arms.dcsoptions import DCSOptions


def _chain(k):
    """``k`` neurons on a line at 0, 1, ..., joined in a chain."""
    centers = np.arange(float(k))[:, None]
    ages = np.full((k, k), -1, dtype=np.int64)
    for i in range(k - 1):
        ages[i, i + 1] = ages[i + 1, i] = 0
    return centers, ages


def test_start_neurons_are_two_joined_samples():
    Z = np.arange(10.0).reshape(5, 2)
    centers, ages = start_neurons(Z, np.random.default_rng(0))
    assert centers.shape == (2, 2) and not np.allclose(centers[0], centers[1])
    assert all(any((c == z).all() for z in Z) for c in centers)
    assert ages.tolist() == [[-1, 0], [0, -1]]


def test_insertion_goes_between_the_worst_neuron_and_its_worst_neighbour():
    centers, ages = _chain(3)
    Z = np.array([[0.0], [1.0], [2.0], [2.1]])
    q, f = insertion_pair(Z, centers, ages, np.array([0.0, 1.0, 5.0, 5.0]))
    assert (q, f) == (2, 1)
    grown_c, grown_a = insert_neuron(centers, ages, q, f)
    assert grown_c[-1, 0] == 1.5
    assert grown_a[1, 2] == -1 and grown_a[1, 3] == 0 and grown_a[2, 3] == 0


def test_prune_removes_a_neuron_that_wins_nothing_and_cuts_its_parents_edge():
    centers = np.array(
        [[0.0], [2.0], [10.0]]
    )  # the last one, inserted between 0 and 1, wins nothing
    ages = np.array([[-1, -1, 0], [-1, -1, 0], [0, 0, -1]])
    ages[0, 1] = ages[1, 0] = 3
    Z = np.array([[0.1], [1.9], [0.0]])
    kept, kept_ages, died, removed = prune(Z, centers, ages, (0, 1), 1)
    assert died and removed == 1 and len(kept) == 2
    assert kept_ages[0, 1] == -1  # no data joins the parents
    assert prune(Z, centers, ages, None, 0)[3] == 0  # min_wins 0 keeps every neuron


def test_adapt_moves_the_winner_towards_the_samples_and_joins_the_two_best():
    centers, ages = _chain(3)
    ages[0, 1] = ages[1, 0] = -1
    Z = np.array([[0.4]])
    opts = DCSOptions(n_epochs=1, eps_winner=0.5, eps_neighbour=0.0)
    new_c, new_a = adapt(Z, centers, ages, np.random.default_rng(0), opts)
    assert new_c[0, 0] == 0.2 and new_c[1, 0] == 1.0
    assert new_a[0, 1] == 0 and centers[0, 0] == 0.0  # the inputs are not modified
