"""The growth steps of a DCS network (:class:`~mjwalk.arms.dcs.DCSNetwork`): the two start
neurons, competitive Hebbian edges with Kohonen adaptation (Bruske & Sommer 1995), dead-unit
removal (Fritzke 1995) and the insertion of a neuron half way between the neuron with the
largest accumulated error and its worst neighbour.

Centres are in standardized input units (:mod:`mjwalk.arms.dcsfit`); ``ages`` is the (K, K)
int64 matrix of lateral edge ages, -1 where two neurons are not joined.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.distance import cdist

from mjwalk.arms.dcsoptions import DCSOptions


def start_neurons(Z: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Two neurons at distinct random samples, joined by an edge.

    Args:
        Z: (n, d) standardized training inputs, n >= 2.
        rng: random generator (one ``choice`` draw).

    Returns:
        ``(centers (2, d), ages (2, 2))``; the centres are nudged apart by 1e-3 when the two
        samples coincide.
    """
    first = rng.choice(len(Z), size=2, replace=False)
    centers = Z[first].copy()
    if np.allclose(centers[0], centers[1]):
        centers[1] = centers[1] + 1e-3
    ages = np.full((2, 2), -1, dtype=np.int64)  # -1: no edge
    ages[0, 1] = ages[1, 0] = 0
    return centers, ages


def adapt(
    Z: np.ndarray,
    centers: np.ndarray,
    ages: np.ndarray,
    rng: np.random.Generator,
    options: DCSOptions,
) -> tuple[np.ndarray, np.ndarray]:
    """Competitive Hebbian edges and Kohonen adaptation of the centres, ``n_epochs`` passes.

    Each sample, in a random order per pass, joins its best and second-best matching neurons
    (edge age 0), ages the winner's other edges (removing those past ``max_age``) and moves the
    winner by ``eps_winner`` and its neighbours by ``eps_neighbour`` of their offset to it.

    Args:
        Z: (n, d) standardized training inputs.
        centers: (K, d) neuron centres (not modified).
        ages: (K, K) edge ages (not modified).
        rng: random generator (one permutation per pass).
        options: the network's settings (``n_epochs``, ``max_age``, the learning rates).

    Returns:
        ``(centers, ages)`` after adaptation, new arrays.
    """
    centers = centers.copy()
    ages = ages.copy()
    k = len(centers)
    max_age, eps_w, eps_n = options.max_age, options.eps_winner, options.eps_neighbour
    for _ in range(options.n_epochs):
        for x in Z[rng.permutation(len(Z))]:
            d = np.einsum("ij,ij->i", centers - x, centers - x)
            if k > 2:
                two = np.argpartition(d, 1)[:2]
                w, s = two if d[two[0]] <= d[two[1]] else two[::-1]
            else:
                w, s = (0, 1) if d[0] <= d[1] else (1, 0)
            row = ages[w] >= 0
            ages[w, row] += 1
            ages[row, w] += 1
            ages[w, s] = ages[s, w] = 0
            old = ages[w] > max_age
            ages[w, old] = -1
            ages[old, w] = -1
            nb = ages[w] >= 0
            centers[w] += eps_w * (x - centers[w])
            centers[nb] += eps_n * (x - centers[nb])
    return centers, ages


def prune(
    Z: np.ndarray,
    centers: np.ndarray,
    ages: np.ndarray,
    parents: tuple[int, int] | None,
    min_wins: int,
) -> tuple[np.ndarray, np.ndarray, bool, int]:
    """Remove dead units (fewer than ``min_wins`` winning samples), keeping at least two.

    When the neuron inserted last (between ``parents``) dies, the parents' edge is cut, as no
    data joins them.

    Args:
        Z: (n, d) standardized training inputs.
        centers: (K, d) neuron centres.
        ages: (K, K) edge ages.
        parents: indices of the neurons the last neuron was inserted between, or None.
        min_wins: fewest wins a neuron keeps its place with (0: none removed).

    Returns:
        ``(centers, ages, newest_died, removed)``: the kept neurons and their edges, whether
        the last neuron died, and how many neurons were removed.
    """
    if min_wins <= 0 or len(centers) <= 2:
        return centers, ages, False, 0
    wins = np.bincount(np.argmin(cdist(Z, centers), axis=1), minlength=len(centers))
    keep = wins >= min_wins
    if keep.all() or keep.sum() < 2:
        return centers, ages, False, 0
    removed = int((~keep).sum())
    newest_died = parents is not None and not keep[-1]
    centers, ages = centers[keep], ages[np.ix_(keep, keep)].copy()
    if newest_died:
        index = np.cumsum(keep) - 1
        q, f = parents  # type: ignore[misc]
        if keep[q] and keep[f]:
            ages[index[q], index[f]] = ages[index[f], index[q]] = -1
    return centers, ages, bool(newest_died), removed


def insertion_pair(
    Z: np.ndarray, centers: np.ndarray, ages: np.ndarray, resid: np.ndarray
) -> tuple[int, int]:
    """Where the next neuron goes: between the neuron ``q`` with the largest accumulated
    squared error over the samples it wins and its lateral neighbour ``f`` with the largest
    (the nearest neuron when ``q`` has no edge).

    Args:
        Z: (n, d) standardized training inputs.
        centers: (K, d) neuron centres.
        ages: (K, K) edge ages.
        resid: (n,) squared training error per sample.

    Returns:
        ``(q, f)`` neuron indices.
    """
    bmu = np.argmin(cdist(Z, centers), axis=1)
    err = np.bincount(bmu, weights=resid, minlength=len(centers))
    q = int(np.argmax(err))
    nbrs = np.flatnonzero(ages[q] >= 0)
    if len(nbrs) == 0:
        d = np.linalg.norm(centers - centers[q], axis=1)
        d[q] = np.inf
        nbrs = np.array([int(np.argmin(d))])
    return q, int(nbrs[np.argmax(err[nbrs])])


def insert_neuron(
    centers: np.ndarray, ages: np.ndarray, q: int, f: int
) -> tuple[np.ndarray, np.ndarray]:
    """Insert a neuron half way between ``q`` and ``f``, replacing their edge by two.

    Args:
        centers: (K, d) neuron centres.
        ages: (K, K) edge ages.
        q: one neuron.
        f: the other.

    Returns:
        ``(centers (K + 1, d), ages (K + 1, K + 1))``, the new neuron last.
    """
    k = len(centers)
    centers = np.vstack([centers, 0.5 * (centers[q] + centers[f])])
    grown = np.full((k + 1, k + 1), -1, dtype=np.int64)
    grown[:k, :k] = ages
    grown[q, f] = grown[f, q] = -1
    grown[q, k] = grown[k, q] = 0
    grown[f, k] = grown[k, f] = 0
    return centers, grown
