"""Model selection of a DCS network (:class:`~mjwalk.arms.dcs.DCSNetwork`): the normalized-RBF
features of its neurons, the output vectors by ridge least squares along a path of ridges, and
the score (PRESS, held-out or training RMSE) by which width, ridge, output form and input
scaling are chosen while the network grows.

Model selection (``selection``): ``"holdout"`` scores network size, width and ridge on a
random ``validation_fraction`` of the samples (the centres then never see them); ``"loo"`` grows
the network on every sample and scores each candidate by the exact leave-one-out residuals of
the output least squares, ``r_i / (1 - H_ii)`` with ``H`` the hat matrix (PRESS; the centres are
fixed, the winner-mean ridge prior is refitted approximately). With few samples the single
held-out fifth is a noisy judge (network sizes 4-48 on folds of the same data); PRESS uses all.

Local linear outputs (``local_linear=True``): each neuron's output is ``b_i + S_i (x - c_i)``
inside the same normalized RBF (a local linear map per neuron, Ritter's LLM; eq. 2 is the
constant case ``S_i = 0``), solved by the same ridge least squares after growth. The slopes
let a few neurons follow a smoothly varying map; a grid ``(False, True)`` is chosen on the
held-out/PRESS residuals like the width.

Global linear term (``global_linear=True``): the output gains a term ``T z`` linear in the
whole (standardized) input, a trend shared by all neurons and solved in the same ridge least
squares (penalized towards zero). Inside the data it changes little (the neurons carry the
local shape); outside, where the normalized RBF keeps the nearest neuron's output, the trend
keeps following the data's overall slope -- a new walker whose hand ends higher or lower than
any in training gets the trajectory the trend says, not the outermost neuron's
(docs/decisions/001-dcs-extrapolation.md). The slopes of
the local linear maps get their own penalty ``slope_ridge`` times the ridge (the offsets ``z -
c_i`` are of the width's size, the neuron outputs of the target's: one ridge for both
over-shrinks one or under-shrinks the other). Both are grids chosen on the held-out/PRESS
residuals like the width. Linear maps, the global term and the neurons' slopes, are fitted
only from :data:`SAMPLES_PER_COEFFICIENT` samples per input column on (each has one
coefficient per input and output): with fewer, a plane through ``d`` inputs is set by a
handful of samples and runs off away from them -- a new walker -- and a leave-one-out score
within the samples cannot see that.

Inputs are standardized internally: per column (``scaling="column"``, zero mean, unit variance),
with one scale for all columns (``scaling="global"``: the RMS column sd, so distances keep
the input's units -- right for constraints that are all positions in metres, where per-column
scaling would blow a near-constant column's noise up to the weight of the informative ones),
or with one scale per 3-D point (``scaling="point"``, columns 3k..3k+2: the RMS sd of the
point's coordinates, so each point weighs alike in distances and within a point a metre stays
a metre: "block scaling", Westerhuis, Kourti & MacGregor 1998, "Analysis of multiblock and
hierarchical PCA and PLS models", J. Chemometrics 12:301-321). A sequence is a grid: one
network is grown per scaling from the same seed and the lowest selection score (PRESS) wins,
like the width: which weighting of a reach's start posture against its end position fits
depends on the capture (docs/decisions/002-dcs-input-scaling.md). Widths and
:meth:`~mjwalk.arms.dcs.DCSNetwork.distance_to_training` are in these standardized units.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
from scipy.spatial.distance import cdist

from mjwalk.arms.dcsquery import design_logits
from mjwalk.errors import MjwalkError

#: Fewest training samples per input column for the global linear term (one coefficient per
#: input and output): ten, the usual limit of a regression model's predictors, about m/10 for
#: m samples (Harrell 2015, *Regression Modeling Strategies*, 2nd ed., §4.4). Below it the
#: term is left out (module docstring).
SAMPLES_PER_COEFFICIENT = 10
#: Input scalings (module docstring).
SCALINGS = ("column", "global", "point")


def input_scale(X: np.ndarray, scaling: str) -> np.ndarray:
    """(d,) divisors of the inputs ``X`` (N, d) for ``scaling``, one of :data:`SCALINGS`
    (module docstring; a column without spread is divided by 1). Baselines that must see the
    DCS's distances scale by these (``benchmarks/bench_reach.py``).

    Args:
        X: (N, d) inputs.
        scaling: one of :data:`SCALINGS`.

    Returns:
        (d,) positive divisors, in the units of ``X``.
    """
    scale = np.asarray(X, dtype=float).std(axis=0)
    if scaling == "global":  # one scale for all columns: distances keep their units
        scale = np.full_like(scale, np.sqrt((scale**2).mean()))
    elif scaling == "point":  # one scale per 3-D point: each point weighs alike
        scale = np.repeat(np.sqrt((scale.reshape(-1, 3) ** 2).mean(axis=1)), 3)
    return np.where(scale > 1e-12, scale, 1.0)


@dataclass(frozen=True)
class SelectionSamples:
    """The samples one growth step is fitted and scored on, in standardized input units.

    Attributes:
        train_z: (n, d) training inputs (the centres adapt to these).
        train_y: (n, m) training targets.
        val_z: (v, d) held-out inputs, v = 0 without a held-out part.
        val_y: (v, m) held-out targets.
        loo: score by PRESS (leave-one-out residuals) on the training samples.
    """

    train_z: np.ndarray
    train_y: np.ndarray
    val_z: np.ndarray
    val_y: np.ndarray
    loo: bool

    @property
    def selects(self) -> bool:
        """Whether the steps are scored on data the outputs did not see (held out or PRESS)."""
        return bool(len(self.val_z)) or self.loo


@dataclass(frozen=True)
class SelectionGrids:
    """The candidates each growth step chooses among.

    Attributes:
        factors: width factors (> 0).
        ridges: output ridges (>= 0).
        forms: output forms ``(local linear, global linear, slope ridge)``
            (:func:`output_form`).
    """

    factors: tuple[float, ...]
    ridges: tuple[float, ...]
    forms: list[tuple[bool, bool, float]]


def score_step(samples: SelectionSamples, grids: SelectionGrids, centers, ages):
    """The best candidate of the current centres over the grids.

    Scored by PRESS (``samples.loo``), on the held-out samples when there are any, else by
    the training error (RMSE, output units).

    Args:
        samples: the training and held-out samples (standardized inputs).
        grids: the width factors, ridges and output forms to try.
        centers: (K, d) neuron centres, standardized input units.
        ages: (K, K) int edge ages, -1 where there is no edge.

    Returns:
        ``(score, width factor, ridge, output form, resid)``, ``resid`` (n,) the squared
        training error per sample of the best candidate.
    """
    Ztr, Ytr, Zval, Yval = samples.train_z, samples.train_y, samples.val_z, samples.val_y
    ridges = grids.ridges
    edges = ages >= 0
    base = neuron_widths(centers, edges, 1.0)
    best = None
    for factor, linear in itertools.product(grids.factors, grids.forms):
        widths = factor * base
        F = features(Ztr, centers, widths, edges, linear)
        Fv = features(Zval, centers, widths, edges, linear) if len(Zval) else None
        for ridge, (outputs, hat) in zip(
            ridges, ridge_path(F, Ytr, len(centers), ridges), strict=True
        ):
            resid = ((F @ outputs - Ytr) ** 2).sum(axis=1)
            if samples.loo:  # leave-one-out residuals of the output least squares (PRESS)
                lev = np.minimum(hat, 1.0 - 1e-6)
                score = float(np.sqrt((resid / (1.0 - lev) ** 2).mean()))
            elif Fv is not None:
                score = float(np.sqrt(((Fv @ outputs - Yval) ** 2).sum(axis=1).mean()))
            else:
                score = float(np.sqrt(resid.mean()))
            if best is None or score < best[0] - 1e-12:
                best = (score, factor, ridge, linear, resid)
    assert best is not None  # the grids are non-empty
    return best


def ridge_path(F, Y, k, ridges):
    """``[(outputs, hat diagonal)]`` of the ridge least squares on the features ``F``
    (N, cols) for every ridge in ``ridges``, from one eigendecomposition of ``F.T @ F``.

    Ridge ``lam = ridge * trace(Phi.T Phi) / K`` (``Phi`` the first ``k`` columns, the RBF
    weights) pulls each neuron's output towards the mean target of the samples it wins
    (rather than towards zero) and the local slopes towards zero: outputs
    ``G @ Y`` with ``G = (F.T F + lam I)^-1 (F.T + lam P)``, ``P @ Y`` the prior. The hat
    diagonal ``diag(F G)`` gives the exact leave-one-out residuals ``r_i / (1 - H_ii)``.

    Args:
        F: (N, cols) features (:func:`features`).
        Y: (N, m) targets.
        k: number of neurons (RBF weight columns).
        ridges: ridges to solve for (>= 0).

    Returns:
        one ``(outputs (cols, m), hat diagonal (N,))`` per ridge.
    """
    n, cols = F.shape
    Phi = F[:, :k]
    scale = max(float(np.einsum("ij,ij->", Phi, Phi)) / k, 1e-12)
    bmu = np.argmax(Phi, axis=1)
    cnt = np.bincount(bmu, minlength=k)
    P = np.zeros((cols, n))  # prior = P @ Y
    P[bmu, np.arange(n)] = 1.0 / np.maximum(cnt[bmu], 1)
    P[:k][cnt == 0] = 1.0 / n
    evals, V = np.linalg.eigh(F.T @ F)
    evals = np.maximum(evals, 0.0)
    FV = F @ V  # (N, cols)
    VtP = V.T @ P  # (cols, N)
    FtY = FV.T @ Y  # V.T F.T Y
    PY = VtP @ Y  # V.T P Y
    sq = FV**2
    cross = FV * VtP.T
    tol = max(float(evals.max()), 1e-300) * cols * np.finfo(float).eps
    path = []
    for ridge in ridges:
        lam = ridge * scale
        den = evals + lam
        inv = np.where(den > tol, 1.0 / np.maximum(den, tol), 0.0)  # pinv when lam = 0
        out = V @ (inv[:, None] * (FtY + lam * PY))
        hat = sq @ inv + lam * (cross @ inv)
        path.append((out, hat))
    return path


def solve_outputs(Z, Y, centers, widths, edges, ridge, linear=False, with_hat=False):
    """Stacked output rows (K, m), or (K (1 + d), m) with local linear terms, by ridge
    least squares; with ``with_hat`` also the diagonal (N,) of the hat matrix (prediction
    = H @ Y, the ridge prior being a linear function of Y too), for the leave-one-out
    residuals ``r_i / (1 - H_ii)``.

    Args:
        Z: (N, d) standardized inputs.
        Y: (N, m) targets.
        centers: (K, d) neuron centres.
        widths: (K,) neuron widths.
        edges: (K, K) bool lateral edges.
        ridge: the output ridge.
        linear: output form (:func:`output_form`).
        with_hat: also return the hat diagonal.

    Returns:
        the stacked output rows, or ``(rows, hat diagonal (N,))``.
    """
    F = features(Z, centers, widths, edges, linear)
    ((out, hat),) = ridge_path(F, Y, len(centers), (ridge,))
    return (out, hat) if with_hat else out


def forward(Z, centers, widths, outputs, edges, linear=False):
    """Network outputs ``features @ outputs`` for standardized inputs.

    Args:
        Z: (N, d) standardized inputs.
        centers: (K, d) neuron centres.
        widths: (K,) neuron widths.
        outputs: stacked output rows (:func:`solve_outputs`).
        edges: (K, K) bool lateral edges.
        linear: output form (:func:`output_form`).

    Returns:
        (N, m) outputs.
    """
    return features(Z, centers, widths, edges, linear) @ outputs


def features(Z, centers, widths, edges, linear):
    """(N, K) normalized RBF weights, then with local linear outputs (see
    :func:`output_form`) the weights times the offsets ``z - c_i`` over the square root of the
    slope ridge (so one ridge penalizes the slopes ``slope_ridge`` times more), then with a
    global linear term the inputs ``z``.

    Args:
        Z: (N, d) standardized inputs.
        centers: (K, d) neuron centres.
        widths: (K,) neuron widths.
        edges: (K, K) bool lateral edges.
        linear: output form (:func:`output_form`).

    Returns:
        (N, K), (N, K (1 + d)) or with the global term d more columns.
    """
    Phi = design(Z, centers, widths, edges)
    local, glob, r = output_form(linear)
    cols = [Phi]
    if local:
        offsets = (Z[:, None, :] - centers[None]) / np.sqrt(r)
        cols.append((Phi[:, :, None] * offsets).reshape(len(Z), -1))
    if glob:
        cols.append(Z)
    return np.hstack(cols) if len(cols) > 1 else Phi


def design(Z, centers, widths, edges):
    """(N, K) normalized RBF weights over each sample's winner and its lateral neighbours.

    Args:
        Z: (N, d) standardized inputs.
        centers: (K, d) neuron centres.
        widths: (K,) Gaussian widths.
        edges: (K, K) bool lateral edges.

    Returns:
        (N, K) weights, each row summing to 1.
    """
    # (cdist, the winner, its neighbours and the exponents compiled: the same numbers)
    w = np.exp(design_logits(Z, centers, widths, edges))
    return w / w.sum(axis=1, keepdims=True)


def neuron_widths(centers, edges, factor):
    """Gaussian width of each neuron: ``factor`` times its mean distance to its lateral neighbours
    (to its nearest neuron when it has none), at least 1e-6.

    Args:
        centers: (K, d) neuron centres, standardized units.
        edges: (K, K) bool lateral edges.
        factor: the width factor.

    Returns:
        (K,) widths, standardized units.
    """
    d = cdist(centers, centers)
    widths = np.empty(len(centers))
    for i in range(len(centers)):
        nb = np.flatnonzero(edges[i])
        if len(nb):
            widths[i] = d[i, nb].mean()
        else:
            di = d[i].copy()
            di[i] = np.inf
            widths[i] = di.min()
    return np.maximum(factor * widths, 1e-6)


def output_form(linear) -> tuple[bool, bool, float]:
    """Output form ``(local linear, global linear, slope ridge)``; a bool is the local
    flag alone (constant or local linear outputs, no trend, slope ridge 1).

    Args:
        linear: a bool or a ``(local, global, slope ridge)`` tuple.

    Returns:
        ``(local linear, global linear, slope ridge)``.
    """
    if isinstance(linear, tuple):
        return bool(linear[0]), bool(linear[1]), float(linear[2])
    return bool(linear), False, 1.0


def split_outputs(stacked, k, d, linear):
    """Stacked output rows -> (``outputs`` (K, m), ``slopes`` (K, d, m) or None,
    ``trend`` (d, m) or None).

    Args:
        stacked: stacked output rows (:func:`solve_outputs`).
        k: number of neurons K.
        d: number of inputs.
        linear: output form (:func:`output_form`).

    Returns:
        ``(outputs, slopes, trend)``.
    """
    local, glob, r = output_form(linear)
    m = stacked.shape[1]
    slopes = stacked[k : k + k * d].reshape(k, d, m) / np.sqrt(r) if local else None
    trend = stacked[-d:] if glob else None
    return stacked[:k], slopes, trend


def grid_values(name: str, value, zero_ok: bool) -> tuple[float, ...]:
    """A number or a list of candidates as a tuple of floats, checked: at least one, all
    > 0 (>= 0 with ``zero_ok``).

    Args:
        name: the setting, for the error message.
        value: a number or a sequence of numbers.
        zero_ok: allow 0.

    Returns:
        the candidates as floats.
    """
    out = tuple(float(x) for x in (value if isinstance(value, list | tuple) else (value,)))
    if not out or min(out) < 0 or (min(out) == 0 and not zero_ok):
        bound = ">= 0" if zero_ok else "> 0"
        raise MjwalkError(f"DCSNetwork: {name} must be {bound}, got {value!r}")
    return out


def grid(flag) -> tuple[bool, ...]:
    """A flag or a sequence of flags as a tuple of bools (``(False,)`` when empty).

    Args:
        flag: a bool or a sequence of bools.

    Returns:
        the candidates.
    """
    seq = flag if isinstance(flag, list | tuple) else (flag,)
    return tuple(bool(x) for x in seq) or (False,)
