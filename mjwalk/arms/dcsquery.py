"""A DCS network's per-query arithmetic compiled (issue 50), the same numbers to the bit as
the SciPy and NumPy code it replaces: the nearest training input (:func:`nearest_distances`,
SciPy's ``cKDTree.query(x, k=1)``) and the logits of the normalized RBF
(:func:`design_logits`, :func:`~mjwalk.arms.dcsfit.design`'s ``cdist``, winner, lateral
neighbours and Gaussian exponents).

A reach asks :meth:`~mjwalk.arms.dcs.DCSNetwork.distance_to_training` one query at a time,
against a few hundred training inputs (the default model: 320 of 6 values): a k-d tree's
traversal and its call cost more than the 2000 squared differences. :func:`nearest_distances`
computes every squared distance in the order SciPy's tree does (``sqeuclidean_distance_double``
in ``scipy/spatial/ckdtree/src/distance.h``: four running sums over the dimensions in steps of
four, added as ``((s0 + s1) + s2) + s3``, then the remaining dimensions one by one, no fused
multiply-adds), keeps the smallest and takes its square root, as the tree takes the root of
the smallest squared distance it found; the square root is correctly rounded and monotonic, so
the result is the tree's to the bit. :data:`BRUTE_MAX` bounds the work done this way; past it
the tree answers (many queries at once: a benchmark's test set). ``cdist``'s Euclidean
distance sums the squared differences one dimension after the other (measured: the same bits
for 1-11 dimensions), and the exponent's arithmetic is elementwise, so
:func:`design_logits` is NumPy's to the bit too; ``np.exp`` and the normalization stay
NumPy's (its vectorised ``exp`` differs from the C library's in the last bit).
``tests/arms/test_dcsquery.py`` compares both with the code they replace over seeded inputs.

Units: the network's standardized input units.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit

#: Queries times training inputs up to which :func:`use_brute` chooses brute force (a choice:
#: 64 k squared distances take about as long as one tree query's call; the default model's one
#: query against 320 inputs is 320).
BRUTE_MAX = 65536


@njit
def _nearest(train, queries, out):
    """``out[i]``: the Euclidean distance of ``queries[i]`` to its nearest row of ``train``
    (N, d), each squared distance summed as cKDTree sums it (see the module doc)."""
    n, d = train.shape
    for i in range(queries.shape[0]):
        best = math.inf
        for r in range(n):
            k = 0
            s = 0.0
            if d >= 4:
                a0 = 0.0
                a1 = 0.0
                a2 = 0.0
                a3 = 0.0
                while k + 4 <= d:
                    e0 = train[r, k] - queries[i, k]
                    e1 = train[r, k + 1] - queries[i, k + 1]
                    e2 = train[r, k + 2] - queries[i, k + 2]
                    e3 = train[r, k + 3] - queries[i, k + 3]
                    a0 += e0 * e0
                    a1 += e1 * e1
                    a2 += e2 * e2
                    a3 += e3 * e3
                    k += 4
                s = ((a0 + a1) + a2) + a3
            while k < d:
                e = train[r, k] - queries[i, k]
                s += e * e
                k += 1
            if s < best:
                best = s
        out[i] = math.sqrt(best)


def use_brute(n_train: int, n_queries: int) -> bool:
    """Whether :func:`nearest_distances` (rather than the k-d tree) answers ``n_queries``
    against ``n_train`` training inputs (:data:`BRUTE_MAX`).

    Args:
        n_train: rows of the training table.
        n_queries: rows of the queries.

    Returns:
        True for brute force.
    """
    return n_train * n_queries <= BRUTE_MAX


def nearest_distances(train: np.ndarray, queries: np.ndarray) -> np.ndarray:
    """(Q,) distance of each query to its nearest training input: ``cKDTree(train).query(
    queries, k=1)[0]`` to the bit.

    Args:
        train: (N, d) training inputs, N >= 1.
        queries: (Q, d) queries.

    Returns:
        (Q,) distances, the inputs' units.
    """
    out = np.empty(len(queries))
    _nearest(
        np.ascontiguousarray(train, dtype=float), np.ascontiguousarray(queries, dtype=float), out
    )
    return out


@njit
def _logits(Z, centers, widths, edges, out):
    """:func:`design_logits` into ``out`` (N, K)."""
    n, k_n = out.shape
    d_n = Z.shape[1]
    dist = np.empty(k_n)
    for i in range(n):
        bmu = 0
        for k in range(k_n):
            s = 0.0
            for j in range(d_n):
                e = Z[i, j] - centers[k, j]
                s += e * e
            dist[k] = math.sqrt(s)
            # np.argmin: the first smallest, the first NaN if there is one
            if dist[bmu] == dist[bmu] and (dist[k] < dist[bmu] or dist[k] != dist[k]):
                bmu = k
        top = -math.inf
        for k in range(k_n):
            if edges[bmu, k] or k == bmu:
                r = dist[k] / widths[k]
                v = -0.5 * (r * r)
            else:
                v = -math.inf
            out[i, k] = v
            # np.max: NaN propagates
            if v != v or top != top:
                top = math.nan
            elif v > top:
                top = v
        for k in range(k_n):
            out[i, k] -= top


def design_logits(
    Z: np.ndarray, centers: np.ndarray, widths: np.ndarray, edges: np.ndarray
) -> np.ndarray:
    """(N, K) logits of the normalized RBF over each input's winner and its lateral
    neighbours, less the row's largest: ``-0.5 (d / width)^2`` (``d`` SciPy's ``cdist`` to
    each centre) for the winner and its neighbours, ``-inf`` for the other neurons.

    Args:
        Z: (N, d) standardized inputs.
        centers: (K, d) neuron centres.
        widths: (K,) Gaussian widths.
        edges: (K, K) bool lateral edges.

    Returns:
        (N, K) logits (their ``exp``, normalized, are the design's weights).
    """
    Z = np.ascontiguousarray(Z, dtype=float)
    out = np.empty((len(Z), len(centers)))
    _logits(
        Z,
        np.ascontiguousarray(centers, dtype=float),
        np.ascontiguousarray(widths, dtype=float),
        np.ascontiguousarray(edges, dtype=np.bool_),
        out,
    )
    return out
