"""Dynamic Cell Structure (DCS) network: a growing, topology-preserving RBF regressor.

Bruske & Sommer (1995), "Dynamic cell structure learns perfectly topology preserving map", as used
by Al-Zubi & Sommer to map a constraint vector (start/end hand positions, obstacle ratio, object
size...) to PCA coefficients of an arm trajectory.

The network holds ``K`` neurons, each with a centre ``c_i`` in the (standardized) input space, an
output vector ``b_i`` and a Gaussian width ``sigma_i``, plus a graph of lateral edges learned by
competitive Hebbian learning (the best and second-best matching neuron of every sample are joined;
the other edges of the winner age and are removed past ``max_age``). Its output is the normalized
Gaussian RBF over the best-matching neuron and its lateral neighbours (Al-Zubi & Sommer eq. 2)::

    b(x) = sum_{i in A(x)} b_i h(|x - c_i| / sigma_i) / sum_{j in A(x)} h(|x - c_j| / sigma_j)

Growth inserts a neuron half way between the neuron with the largest accumulated error and its
lateral neighbour with the largest accumulated error, until the training RMSE falls below
``error_threshold``, ``max_neurons`` is reached, or (when ``validation_fraction > 0``) the
held-out error stops improving for ``n_iter_no_change`` insertions; the best network seen on the
held-out part is kept. Output vectors are the least-squares solution on the normalized-RBF design
matrix (a ridge towards each neuron's mean target keeps it well posed), refit on all samples at
the end. ``width_factor`` and ``ridge`` may be grids: at every growth step each pair is tried and
the best on the held-out part is kept with the network (inner validation; the test data of a
benchmark never choose them).

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
any in training gets the trajectory the trend says, not the outermost neuron's (Bandai
raise-hand clips, leave-one-style-out in ``benchmarks/bench_reach.py``: 16.0 -> 14.5 deg, the
held-out feminine style 28.1 -> 21.5). The slopes of
the local linear maps get their own penalty ``slope_ridge`` times the ridge (the offsets ``z -
c_i`` are of the width's size, the neuron outputs of the target's: one ridge for both
over-shrinks one or under-shrinks the other). Both are grids chosen on the held-out/PRESS
residuals like the width. Linear maps, the global term and the neurons' slopes, are fitted
only from :data:`SAMPLES_PER_COEFFICIENT` samples per input column on (each has one
coefficient per input and output): with fewer, a plane through ``d`` inputs is set by a
handful of samples and runs off away from them -- a new walker -- and a leave-one-out score
within the samples cannot see that.

Dead units (``min_wins``): after every adaptation pass, a neuron that wins fewer than
``min_wins`` training samples (default 1: none) is removed with its edges, as growing networks
remove units the data no longer supports (Fritzke 1995, "A growing neural gas network learns
topologies"). A neuron inserted half way between two others can fall into a gap between
clusters of the data; winning no sample, its output and slopes are set by nothing but the
ridge, and a new input in that gap (a walker between the trained styles) got them: Bandai
raise-hand clips, leave-one-style-out, the held-out normal style fell to such a neuron and
gave 49 deg at one network seed against 9.8 at another. When the neuron just inserted dies,
the edge between its two parents is cut too, so the next insertion goes elsewhere.

Trend fallback (``trend_fallback=True``): outside the data, no local structure is known, so
the output blends into the *trend network* -- the network growth starts from (two neurons,
constant outputs) with the global linear term, fitted on the same samples with the same grids
-- with the weight ``g = exp(-d^2 / (2 r^2))`` of the full network, ``d`` the distance to the
nearest training input and ``r`` the trained-range radius (``range_radius_``, where
:meth:`DCSNetwork.is_outside` starts to flag a query). A Gaussian process with a linear mean
function reverts to its mean function away from its data in the same way (Rasmussen &
Williams 2006, §2.7). Inside the data ``g`` is close to 1 (10-fold cross-validation moves by
less than 0.05 deg); a walker unlike every trained one gets the trend, not the outermost neuron's
local map (leave-one-style-out in ``benchmarks/bench_reach.py``: the held-out masculine
style 14.6 -> 10.6 deg, feminine 21.5 -> 16.9; without it the local maps extrapolate to
15-74 deg depending on the network seed).

Seed averaging (``n_networks``): the growth is stochastic (random start neurons, random
presentation order), and two networks grown from different seeds on the same samples differ
most where the data say least. ``n_networks > 1`` grows that many networks from independent
seeds (``numpy.random.SeedSequence.spawn``) and averages their outputs (an ensemble of
networks differing only in their initial conditions: Hansen & Salamon 1990, "Neural network
ensembles"). Bandai raise-hand clips, 10-fold CV with other folds and seeds (``--seed 20``):
one network 4.42 deg, five 4.27 (kNN 4.33); seed 0: 4.21 and 4.21.

Inputs are standardized internally: per column (``scaling="column"``, zero mean, unit variance),
with one scale for all columns (``scaling="global"``: the RMS column sd, so distances keep
the input's units -- right for constraints that are all positions in metres, where per-column
scaling would blow a near-constant column's noise up to the weight of the informative ones),
or with one scale per 3-D point (``scaling="point"``, columns 3k..3k+2: the RMS sd of the
point's coordinates, so each point weighs alike in distances and within a point a metre stays
a metre: "block scaling", Westerhuis, Kourti & MacGregor 1998, "Analysis of multiblock and
hierarchical PCA and PLS models", J. Chemometrics 12:301-321). A sequence is a grid: one
network is grown per scaling from the same seed and the lowest selection score (PRESS) wins,
like the width. Which weighting of a reach's start posture against its end position fits
depends on the capture: on the Bandai right-arm raises a centimetre of the start hand changes
the movement about five times as much as a centimetre of the end hand (pairs of clips, ad hoc
2026-11-28), and the end position's spread is six times the start's, so one global scale all
but ignores the start posture; on the left-arm raises it does not (PRESS picks "global" there,
"point" on the right arm, in each of the three folds per arm looked at).
Widths and :meth:`DCSNetwork.distance_to_training` are in these standardized units. The saved
file keeps the standardized training inputs (not the outputs) for that distance.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree
from scipy.spatial.distance import cdist

from mjwalk._io import check_header, load_npz, save_npz
from mjwalk.errors import MjwalkError, ModelFileError

DCS_FORMAT = "mjwalk.dcs"
#: 2: optional global linear term (``trend``) and slope ridge; 3: dead-unit pruning and the
#: trend fallback network. Version 1 and 2 files still load (no fallback).
DCS_VERSION = 3
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
    DCS's distances scale by these (``benchmarks/bench_reach.py``)."""
    scale = np.asarray(X, dtype=float).std(axis=0)
    if scaling == "global":  # one scale for all columns: distances keep their units
        scale = np.full_like(scale, np.sqrt((scale**2).mean()))
    elif scaling == "point":  # one scale per 3-D point: each point weighs alike
        scale = np.repeat(np.sqrt((scale.reshape(-1, 3) ** 2).mean(axis=1)), 3)
    return np.where(scale > 1e-12, scale, 1.0)


class DCSNetwork:
    """Growing normalized-RBF network with competitive-Hebbian lateral edges.

    Args:
        max_neurons: upper bound on the number of neurons.
        error_threshold: stop growing once the training RMSE (output units) is below this.
        max_age: lateral edges not refreshed for more than this many winning presentations of
            their endpoint are removed.
        width_factor: sigma_i = width_factor * mean distance of neuron i to its lateral
            neighbours; a sequence is a grid chosen on the held-out part (see module docstring).
        eps_winner, eps_neighbour: Kohonen learning rates of the winner and its neighbours.
        n_epochs: presentations of the whole training set per growth step.
        validation_fraction: share of samples held out to select the network size (0 disables).
        n_iter_no_change: insertions without held-out improvement before growth stops.
        ridge: Tikhonov regularization of the output least squares (relative to the design
            scale), towards each neuron's mean target; a sequence is a grid like width_factor.
        rng: seed or ``numpy.random.Generator``; same seed, same network.
        scaling: input standardization, ``"column"``, ``"global"`` or ``"point"``; a sequence
            is a grid like width_factor (see module docstring).
        selection: ``"holdout"`` or ``"loo"`` (PRESS on all samples; see module docstring).
        local_linear: per-neuron local linear outputs; a sequence is a grid like width_factor.
        global_linear: add a global linear term ``T z``; a sequence is a grid like width_factor.
            Left out, like ``local_linear``, with fewer than :data:`SAMPLES_PER_COEFFICIENT`
            samples per input column.
        slope_ridge: penalty of the local slopes relative to ``ridge`` (> 0); a sequence is a
            grid like width_factor (used only with local linear outputs).
        min_wins: neurons winning fewer training samples after an adaptation pass are removed
            (dead units; 0 keeps every neuron).
        trend_fallback: blend into the trend network outside the trained range (see the
            module docstring).
        n_networks: networks grown from independent seeds and averaged (see the module
            docstring); the fitted attributes describe the first, ``members_`` the others.

    Fitted attributes: ``centers_`` (K, d) standardized, ``outputs_`` (K, m), ``widths_`` (K,),
    ``edges_`` (K, K) bool adjacency, ``x_mean_``/``x_scale_`` (d,), ``n_neurons_``,
    ``train_rmse_``, ``history_`` (list of (neurons, train RMSE, held-out RMSE)), ``n_pruned_``
    (dead units removed while growing), ``fallback_`` the trend network or None,
    ``width_factor_``, ``ridge_``, ``local_linear_``, ``global_linear_``, ``slope_ridge_`` and
    ``scaling_`` (the values used), ``selection_score_`` (the score they were chosen by),
    ``slopes_`` (K, d, m) local linear terms in standardized input units, or None, ``trend_``
    (d, m) the global linear term in standardized input units, or None.
    """

    def __init__(
        self,
        max_neurons: int = 30,
        error_threshold: float = 0.0,
        max_age: int = 30,
        width_factor: float = 1.0,
        eps_winner: float = 0.05,
        eps_neighbour: float = 0.005,
        n_epochs: int = 3,
        validation_fraction: float = 0.2,
        n_iter_no_change: int = 6,
        ridge: float = 1e-6,
        rng: int | np.random.Generator | None = 0,
        scaling: str | tuple[str, ...] = "column",
        selection: str = "holdout",
        local_linear: bool | tuple[bool, ...] = False,
        global_linear: bool | tuple[bool, ...] = False,
        slope_ridge: float | tuple[float, ...] = 1.0,
        min_wins: int = 1,
        trend_fallback: bool = False,
        n_networks: int = 1,
    ):
        self.max_neurons = max_neurons
        self.error_threshold = error_threshold
        self.max_age = max_age
        self.width_factor = width_factor
        self.eps_winner = eps_winner
        self.eps_neighbour = eps_neighbour
        self.n_epochs = n_epochs
        self.validation_fraction = validation_fraction
        self.n_iter_no_change = n_iter_no_change
        self.ridge = ridge
        self.rng = rng
        self.scaling = scaling
        self.selection = selection
        self.local_linear = local_linear
        self.global_linear = global_linear
        self.slope_ridge = slope_ridge
        self.min_wins = min_wins
        self.trend_fallback = trend_fallback
        self.n_networks = n_networks

    # ------------------------------------------------------------------ fitting
    def fit(self, X: np.ndarray, Y: np.ndarray) -> DCSNetwork:
        """Grow the network on inputs ``X`` (N, d) and targets ``Y`` (N, m) or (N,)."""
        X = np.asarray(X, dtype=float)
        Y = np.asarray(Y, dtype=float)
        if X.ndim == 1:
            X = X[:, None]
        self._y_1d = Y.ndim == 1
        if Y.ndim == 1:
            Y = Y[:, None]
        if X.ndim != 2 or Y.ndim != 2 or len(X) != len(Y):
            raise MjwalkError(f"DCSNetwork.fit: X {X.shape} and Y {Y.shape} do not match")
        if len(X) < 2:
            raise MjwalkError(f"DCSNetwork.fit: need at least 2 samples, got {len(X)}")
        if not (np.isfinite(X).all() and np.isfinite(Y).all()):
            raise MjwalkError("DCSNetwork.fit: X or Y holds NaN or infinite values")
        if self.max_neurons < 2:
            raise MjwalkError(f"DCSNetwork: max_neurons must be >= 2, got {self.max_neurons}")
        if int(self.min_wins) != self.min_wins or self.min_wins < 0:
            raise MjwalkError(f"DCSNetwork: min_wins must be an integer >= 0, got {self.min_wins}")
        if int(self.n_networks) != self.n_networks or self.n_networks < 1:
            raise MjwalkError(
                f"DCSNetwork: n_networks must be an integer >= 1, got {self.n_networks}"
            )
        if self.selection not in ("holdout", "loo"):
            raise MjwalkError(
                f"DCSNetwork: selection must be 'holdout' or 'loo', got {self.selection!r}"
            )
        scalings = self._scalings(X.shape[1])
        member_seeds = self._member_seeds()
        if len(scalings) == 1:
            self._grow_first(X, Y, scalings[0], np.random.default_rng(self.rng))
        else:
            # one network per input scaling, grown from the same seed; the lowest selection
            # score (PRESS) wins, like the width (module docstring)
            grid_seed = self.rng
            if isinstance(grid_seed, np.random.Generator):
                grid_seed = int(grid_seed.integers(2**63))
            best: dict | None = None
            for scaling in scalings:
                self._grow_first(X, Y, scaling, np.random.default_rng(grid_seed))
                if best is None or self.selection_score_ < best["selection_score_"] - 1e-12:
                    best = dict(vars(self))  # each growth rebinds, never mutates, its arrays
            assert best is not None
            vars(self).update(best)
        self.fallback_ = None
        if self.trend_fallback:
            self.fallback_ = DCSNetwork(**self._trend_params()).fit(X, Y[:, 0] if self._y_1d else Y)
        self.members_ = [
            DCSNetwork(
                **{**self._params(), "scaling": self.scaling_, "n_networks": 1, "rng": seed}
            ).fit(X, Y[:, 0] if self._y_1d else Y)
            for seed in member_seeds
        ]
        return self

    def _scalings(self, d: int) -> tuple[str, ...]:
        """The input scalings to try (``scaling``: one or a sequence), checked for ``d``
        input columns."""
        seq = tuple(self.scaling) if isinstance(self.scaling, list | tuple) else (self.scaling,)
        if not seq or any(s not in SCALINGS for s in seq):
            raise MjwalkError(
                f"DCSNetwork: scaling must be one of {', '.join(map(repr, SCALINGS))} or a "
                f"sequence of them, got {self.scaling!r}"
            )
        if "point" in seq and d % 3:
            raise MjwalkError(
                f"DCSNetwork: scaling 'point' needs inputs made of 3-D points (a multiple of 3 "
                f"columns), got {d} columns"
            )
        return seq

    def _grow_first(self, X, Y, scaling: str, rng: np.random.Generator) -> None:
        """Grow one network on ``X``, ``Y`` with the input ``scaling`` and set the fitted
        attributes (not the trend network or the averaged networks)."""
        self.scaling_ = scaling
        self.x_mean_ = X.mean(axis=0)
        self.x_scale_ = input_scale(X, scaling)
        Z = (X - self.x_mean_) / self.x_scale_

        n = len(Z)
        loo = self.selection == "loo"
        n_val = round(self.validation_fraction * n) if self.validation_fraction > 0 else 0
        if n - n_val < 2 or loo:
            n_val = 0
        select = bool(n_val) or loo
        perm = rng.permutation(n)
        val_idx, tr_idx = perm[:n_val], perm[n_val:]
        Ztr, Ytr = Z[tr_idx], Y[tr_idx]

        # Two neurons at distinct random training samples, joined by an edge.
        first = rng.choice(len(Ztr), size=2, replace=False)
        centers = Ztr[first].copy()
        if np.allclose(centers[0], centers[1]):
            centers[1] = centers[1] + 1e-3
        ages = np.full((2, 2), -1, dtype=np.int64)  # -1: no edge
        ages[0, 1] = ages[1, 0] = 0

        best = None
        best_val = np.inf
        no_change = 0
        stalled = 0  # insertions in a row whose neuron died at once
        parents: tuple[int, int] | None = None
        resid = np.zeros(len(Ztr))  # squared training error per sample, set by every step
        self.history_ = []
        self.n_pruned_ = 0
        factors = self._factors()
        ridges = self._ridges()
        # a linear map (global or per neuron) has one coefficient per input and output
        linear_ok = len(Ztr) >= SAMPLES_PER_COEFFICIENT * Z.shape[1]
        # output forms (local linear, global linear, slope ridge), chosen like the width
        forms = [
            (local, glob, r)
            for local in (self._grid(self.local_linear) if linear_ok else (False,))
            for glob in (self._grid(self.global_linear) if linear_ok else (False,))
            for r in (self._slope_ridges() if local else (1.0,))
        ]
        while True:
            centers, ages = self._adapt(Ztr, centers, ages, rng)
            centers, ages, newest_died = self._prune(Ztr, centers, ages, parents)
            stalled = stalled + 1 if newest_died else 0
            if newest_died:  # nothing new to score; insert elsewhere (the parents' edge is cut)
                if stalled >= max(self.n_iter_no_change, 1):
                    break
            else:
                val_rmse, factor, ridge, linear, resid = self._score_step(
                    Ztr, Ytr, Z[val_idx], Y[val_idx], centers, ages, ridges, factors, forms, loo
                )
                train_rmse = float(np.sqrt(resid.mean()))
                self.history_.append((len(centers), train_rmse, val_rmse if select else np.nan))
                if val_rmse < best_val - 1e-12:
                    best_val = val_rmse
                    best = (centers.copy(), ages.copy(), factor, ridge, linear)
                    no_change = 0
                else:
                    no_change += 1
                if (
                    train_rmse <= self.error_threshold
                    or len(centers) >= self.max_neurons
                    or len(centers) >= len(Ztr)
                    or (select and no_change >= self.n_iter_no_change)
                ):
                    break
            parents = self._insert_at_largest_error(Ztr, centers, ages, resid)
            centers, ages = self._grow(centers, ages, *parents)

        if select and best is not None:
            centers, ages, factor, ridge, linear = best
        edges = ages >= 0
        self.width_factor_ = float(factor)
        self.ridge_ = float(ridge)
        self.local_linear_ = bool(linear[0])
        self.global_linear_ = bool(linear[1])
        self.slope_ridge_ = float(linear[2])
        widths = self._widths(centers, edges, factor)
        # Final output vectors on every sample (train + held-out).
        self.centers_ = centers
        self.edges_ = edges
        self.widths_ = widths
        stacked = self._solve_outputs(Z, Y, centers, widths, edges, ridge, linear)
        self.outputs_, self.slopes_, self.trend_ = self._split(
            stacked, len(centers), Z.shape[1], linear
        )
        self.n_neurons_ = len(centers)
        self.train_rmse_ = float(
            np.sqrt(
                ((self._forward(Z, centers, widths, stacked, edges, linear) - Y) ** 2)
                .sum(axis=1)
                .mean()
            )
        )
        # without selection: the final network's training error (as the width grid's score)
        self.selection_score_ = float(best_val) if select else self.train_rmse_
        self._set_training_points(Z)

    def _score_step(self, Ztr, Ytr, Zval, Yval, centers, ages, ridges, factors, forms, loo):
        """The best (score, width factor, ridge, output form, squared training error per
        sample) of the current centres over the grids: scored by PRESS (``loo``), on the
        held-out samples ``Zval`` when there are any, else by the training error (RMSE)."""
        edges = ages >= 0
        base = self._widths(centers, edges, 1.0)
        best = None
        for factor, linear in itertools.product(factors, forms):
            widths = factor * base
            F = self._features(Ztr, centers, widths, edges, linear)
            Fv = self._features(Zval, centers, widths, edges, linear) if len(Zval) else None
            for ridge, (outputs, hat) in zip(
                ridges, self._ridge_path(F, Ytr, len(centers), ridges), strict=True
            ):
                resid = ((F @ outputs - Ytr) ** 2).sum(axis=1)
                if loo:  # leave-one-out residuals of the output least squares (PRESS)
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

    def _member_seeds(self) -> list[int]:
        """Seeds of the networks after the first (``n_networks - 1``): spawned from an integer
        seed without drawing from it (the first network is the one ``n_networks=1`` grows),
        else drawn from the generator first."""
        if self.n_networks <= 1:
            return []
        if isinstance(self.rng, np.random.Generator):
            entropy = int(self.rng.integers(2**63))
            return [
                int(x)
                for x in np.random.default_rng(entropy).integers(2**31, size=self.n_networks - 1)
            ]
        seq = np.random.SeedSequence(self.rng)
        return [int(c.generate_state(1)[0]) for c in seq.spawn(self.n_networks - 1)]

    def _trend_params(self) -> dict:
        """The trend network's settings: this network's, grown no further than the two
        neurons growth starts from, constant outputs, with the global linear term."""
        params = self._params()
        params.update(
            scaling=self.scaling_,
            max_neurons=2,
            n_iter_no_change=1,
            local_linear=False,
            global_linear=True,
            trend_fallback=False,
            n_networks=1,
        )
        return params

    @staticmethod
    def _insert_at_largest_error(Z, centers, ages, resid) -> tuple[int, int]:
        """Growth: the neuron ``q`` with the largest accumulated squared error over the samples
        it wins and its lateral neighbour ``f`` with the largest (the nearest neuron when ``q``
        has no edge); the new neuron goes half way between them."""
        bmu = np.argmin(cdist(Z, centers), axis=1)
        err = np.bincount(bmu, weights=resid, minlength=len(centers))
        q = int(np.argmax(err))
        nbrs = np.flatnonzero(ages[q] >= 0)
        if len(nbrs) == 0:
            d = np.linalg.norm(centers - centers[q], axis=1)
            d[q] = np.inf
            nbrs = np.array([int(np.argmin(d))])
        return q, int(nbrs[np.argmax(err[nbrs])])

    @staticmethod
    def _grow(centers, ages, q: int, f: int):
        """Insert a neuron half way between ``q`` and ``f``, replacing their edge by two."""
        k = len(centers)
        centers = np.vstack([centers, 0.5 * (centers[q] + centers[f])])
        grown = np.full((k + 1, k + 1), -1, dtype=np.int64)
        grown[:k, :k] = ages
        grown[q, f] = grown[f, q] = -1
        grown[q, k] = grown[k, q] = 0
        grown[f, k] = grown[k, f] = 0
        return centers, grown

    def _prune(self, Z, centers, ages, parents):
        """Remove dead units (fewer than ``min_wins`` wins), keeping at least two neurons.
        Returns the centres, the edge ages and whether the neuron inserted last (between
        ``parents``) died; then the parents' edge is cut, as no data joins them."""
        if self.min_wins <= 0 or len(centers) <= 2:
            return centers, ages, False
        wins = np.bincount(np.argmin(cdist(Z, centers), axis=1), minlength=len(centers))
        keep = wins >= self.min_wins
        if keep.all() or keep.sum() < 2:
            return centers, ages, False
        self.n_pruned_ += int((~keep).sum())
        newest_died = parents is not None and not keep[-1]
        centers, ages = centers[keep], ages[np.ix_(keep, keep)].copy()
        if newest_died:
            index = np.cumsum(keep) - 1
            q, f = parents
            if keep[q] and keep[f]:
                ages[index[q], index[f]] = ages[index[f], index[q]] = -1
        return centers, ages, bool(newest_died)

    def _adapt(self, Z, centers, ages, rng):
        """Competitive Hebbian edges + Kohonen adaptation of centres, ``n_epochs`` passes."""
        centers = centers.copy()
        ages = ages.copy()
        k = len(centers)
        for _ in range(self.n_epochs):
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
                old = ages[w] > self.max_age
                ages[w, old] = -1
                ages[old, w] = -1
                nb = ages[w] >= 0
                centers[w] += self.eps_winner * (x - centers[w])
                centers[nb] += self.eps_neighbour * (x - centers[nb])
        return centers, ages

    @staticmethod
    def _grid_values(name: str, value, zero_ok: bool) -> tuple[float, ...]:
        """A number or a list of candidates as a tuple of floats, checked: at least one, all
        > 0 (>= 0 with ``zero_ok``)."""
        out = tuple(float(x) for x in (value if isinstance(value, list | tuple) else (value,)))
        if not out or min(out) < 0 or (min(out) == 0 and not zero_ok):
            bound = ">= 0" if zero_ok else "> 0"
            raise MjwalkError(f"DCSNetwork: {name} must be {bound}, got {value!r}")
        return out

    def _factors(self) -> tuple[float, ...]:
        return self._grid_values("width_factor", self.width_factor, False)

    def _ridges(self) -> tuple[float, ...]:
        return self._grid_values("ridge", self.ridge, True)

    def _slope_ridges(self) -> tuple[float, ...]:
        return self._grid_values("slope_ridge", self.slope_ridge, False)

    @staticmethod
    def _grid(flag) -> tuple[bool, ...]:
        seq = flag if isinstance(flag, list | tuple) else (flag,)
        return tuple(bool(x) for x in seq) or (False,)

    @staticmethod
    def _form(linear) -> tuple[bool, bool, float]:
        """Output form ``(local linear, global linear, slope ridge)``; a bool is the local
        flag alone (constant or local linear outputs, no trend, slope ridge 1)."""
        if isinstance(linear, tuple):
            return bool(linear[0]), bool(linear[1]), float(linear[2])
        return bool(linear), False, 1.0

    @classmethod
    def _split(cls, stacked, k, d, linear):
        """Stacked output rows -> (``outputs`` (K, m), ``slopes`` (K, d, m) or None,
        ``trend`` (d, m) or None)."""
        local, glob, r = cls._form(linear)
        m = stacked.shape[1]
        slopes = stacked[k : k + k * d].reshape(k, d, m) / np.sqrt(r) if local else None
        trend = stacked[-d:] if glob else None
        return stacked[:k], slopes, trend

    def _widths(self, centers, edges, factor):
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

    @staticmethod
    def _design(Z, centers, widths, edges):
        """(N, K) normalized RBF weights over each sample's winner and its lateral neighbours."""
        d = cdist(Z, centers)
        bmu = np.argmin(d, axis=1)
        active = edges[bmu].copy()
        active[np.arange(len(Z)), bmu] = True
        logit = np.where(active, -0.5 * (d / widths) ** 2, -np.inf)
        logit -= logit.max(axis=1, keepdims=True)
        w = np.exp(logit)
        return w / w.sum(axis=1, keepdims=True)

    @classmethod
    def _features(cls, Z, centers, widths, edges, linear):
        """(N, K) normalized RBF weights, then with local linear outputs (see
        :meth:`_form`) the weights times the offsets ``z - c_i`` over the square root of the
        slope ridge (so one ridge penalizes the slopes ``slope_ridge`` times more), then with a
        global linear term the inputs ``z``."""
        Phi = cls._design(Z, centers, widths, edges)
        local, glob, r = cls._form(linear)
        cols = [Phi]
        if local:
            offsets = (Z[:, None, :] - centers[None]) / np.sqrt(r)
            cols.append((Phi[:, :, None] * offsets).reshape(len(Z), -1))
        if glob:
            cols.append(Z)
        return np.hstack(cols) if len(cols) > 1 else Phi

    def _solve_outputs(self, Z, Y, centers, widths, edges, ridge, linear=False, with_hat=False):
        """Stacked output rows (K, m), or (K (1 + d), m) with local linear terms, by ridge
        least squares; with ``with_hat`` also the diagonal (N,) of the hat matrix (prediction
        = H @ Y, the ridge prior being a linear function of Y too), for the leave-one-out
        residuals ``r_i / (1 - H_ii)``."""
        F = self._features(Z, centers, widths, edges, linear)
        ((out, hat),) = self._ridge_path(F, Y, len(centers), (ridge,))
        return (out, hat) if with_hat else out

    @staticmethod
    def _ridge_path(F, Y, k, ridges):
        """``[(outputs, hat diagonal)]`` of the ridge least squares on the features ``F``
        (N, cols) for every ridge in ``ridges``, from one eigendecomposition of ``F.T @ F``.

        Ridge ``lam = ridge * trace(Phi.T Phi) / K`` (``Phi`` the first ``k`` columns, the RBF
        weights) pulls each neuron's output towards the mean target of the samples it wins
        (rather than towards zero) and the local slopes towards zero: outputs
        ``G @ Y`` with ``G = (F.T F + lam I)^-1 (F.T + lam P)``, ``P @ Y`` the prior. The hat
        diagonal ``diag(F G)`` gives the exact leave-one-out residuals ``r_i / (1 - H_ii)``.
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

    def _forward(self, Z, centers, widths, outputs, edges, linear=False):
        return self._features(Z, centers, widths, edges, linear) @ outputs

    def _set_training_points(self, Z):
        self._train_z = Z
        self._tree = cKDTree(Z)
        if len(Z) > 1:
            d, _ = self._tree.query(Z, k=2)
            nn = d[:, 1]
        else:
            nn = np.zeros(1)
        #: Input distance (standardized units) above which a query counts as outside the
        #: trained range: twice the 95th percentile of the training nearest-neighbour distances.
        self.range_radius_ = float(2.0 * np.percentile(nn, 95)) if len(nn) else 0.0

    # ------------------------------------------------------------------ prediction
    def _check_fitted(self):
        if not hasattr(self, "centers_"):
            raise MjwalkError("DCSNetwork is not fitted; call fit() or load() first")

    def _standardize(self, X):
        X = np.asarray(X, dtype=float)
        if X.ndim == 1:
            X = X[None, :] if len(self.x_mean_) > 1 else X[:, None]
        if X.shape[1] != len(self.x_mean_):
            raise MjwalkError(
                f"DCSNetwork: input has {X.shape[1]} columns, the network was trained on "
                f"{len(self.x_mean_)}"
            )
        return (X - self.x_mean_) / self.x_scale_

    def predict(self, X: np.ndarray) -> np.ndarray:
        """Outputs (N, m) for inputs ``X`` (N, d) by the normalized RBF of eq. 2 (blended into
        the trend network outside the trained range when it has one, see the module doc)."""
        self._check_fitted()
        # one weight for all networks: they share the training inputs, hence d and r
        g = self.network_weight(X) if self._fallback() is not None else None
        out = self._predict_one(X, g)
        members = getattr(self, "members_", [])
        if members:
            out = (out + sum(m._predict_one(X, g) for m in members)) / (1 + len(members))
        return out[:, 0] if self._y_1d else out

    def _predict_one(self, X: np.ndarray, g: np.ndarray | None) -> np.ndarray:
        """(N, m) output of this network alone, blended into its trend network with the full
        network's weight ``g`` (:meth:`network_weight`) when it has one."""
        out = self._predict_network(X)
        fallback = self._fallback()
        if fallback is not None and g is not None:
            trend = fallback._predict_network(X)
            out = trend + g[:, None] * (out - trend)
        return out

    def network_weight(self, X: np.ndarray) -> np.ndarray:
        """(N,) weight of the full network in :meth:`predict`: ``exp(-d^2 / (2 r^2))``,
        ``d`` the distance to the nearest training input, ``r = range_radius_``; 1 without a
        trend fallback."""
        self._check_fitted()
        if self._fallback() is None:
            return np.ones(len(self._standardize(X)))
        q = self.distance_to_training(X) / max(self.range_radius_, 1e-12)
        return np.exp(-0.5 * q**2)

    def _predict_network(self, X: np.ndarray) -> np.ndarray:
        """(N, m) outputs of this network alone."""
        Z = self._standardize(X)
        Phi = self._design(Z, self.centers_, self.widths_, self.edges_)
        out = Phi @ self.outputs_
        if self.slopes_ is not None:  # local linear terms: sum_i h_i (z - c_i) @ S_i
            offsets = Z[:, None, :] - self.centers_[None]
            out = out + np.einsum("nk,nkd,kdm->nm", Phi, offsets, self.slopes_)
        if self.trend_ is not None:  # global linear term
            out = out + Z @ self.trend_
        return out

    def distance_to_training(self, X: np.ndarray) -> np.ndarray:
        """(N,) distance of each input to its nearest training input, in standardized units
        (training standard deviations). Compare with ``range_radius_`` to flag extrapolation."""
        self._check_fitted()
        d, _ = self._tree.query(self._standardize(X), k=1)
        return np.atleast_1d(d).astype(float)

    def is_outside(self, X: np.ndarray) -> np.ndarray:
        """(N,) True where the input lies outside the trained range (see ``range_radius_``)."""
        return self.distance_to_training(X) > self.range_radius_

    # ------------------------------------------------------------------ persistence
    def _fallback(self) -> DCSNetwork | None:
        """The trend network, or None (none fitted, or a version 1-2 file)."""
        return getattr(self, "fallback_", None)

    def _arrays(self, with_training: bool = True) -> dict:
        """The arrays :meth:`save` writes. The trend network and the averaged networks were
        fitted on the same inputs, so only the first network keeps the training inputs
        (``with_training``); they borrow them on load."""
        fallback = self._fallback()
        return {
            "centers": self.centers_,
            "outputs": self.outputs_,
            "widths": self.widths_,
            "edges": self.edges_,
            "x_mean": self.x_mean_,
            "x_scale": self.x_scale_,
            **({"train_z": self._train_z} if with_training else {}),
            **({} if self.slopes_ is None else {"slopes": self.slopes_}),
            **({} if self.trend_ is None else {"trend": self.trend_}),
            **(
                {}
                if fallback is None
                else {f"fallback.{k}": v for k, v in fallback._arrays(False).items()}
            ),
            **{
                f"member{j}.{k}": v
                for j, m in enumerate(getattr(self, "members_", []))
                for k, v in m._arrays(False).items()
            },
        }

    _PARAMS = (
        "max_neurons",
        "error_threshold",
        "max_age",
        "width_factor",
        "eps_winner",
        "eps_neighbour",
        "n_epochs",
        "validation_fraction",
        "n_iter_no_change",
        "ridge",
        "scaling",
        "selection",
        "local_linear",
        "global_linear",
        "slope_ridge",
        "min_wins",
        "trend_fallback",
        "n_networks",
    )

    def _params(self) -> dict:
        """The constructor arguments (a seed as is; a Generator as None)."""
        params = {k: getattr(self, k) for k in self._PARAMS}
        rs = self.rng
        params["rng"] = rs if isinstance(rs, int | None) else None
        return params

    def _header(self) -> dict:
        params = self._params()
        fallback = self._fallback()
        return {
            "format": DCS_FORMAT,
            "version": DCS_VERSION,
            "params": params,
            "y_1d": bool(self._y_1d),
            "train_rmse": self.train_rmse_,
            "width_factor_": getattr(self, "width_factor_", None),
            "ridge_": getattr(self, "ridge_", None),
            "local_linear_": self.slopes_ is not None,
            "global_linear_": self.trend_ is not None,
            "slope_ridge_": getattr(self, "slope_ridge_", None),
            "scaling_": getattr(self, "scaling_", None),
            "history": [[int(a), float(b), float(c)] for a, b, c in self.history_],
            "n_pruned_": int(getattr(self, "n_pruned_", 0)),
            **({} if fallback is None else {"fallback": fallback._header()}),
            "members": [m._header() for m in getattr(self, "members_", [])],
        }

    def save(self, path: str | Path) -> None:
        """Write the fitted network to one versioned ``.npz`` file (atomically)."""
        self._check_fitted()
        save_npz(path, self._header(), self._arrays())

    @classmethod
    def from_arrays(
        cls, header: dict, data: dict, source: str = "<arrays>", train_z: np.ndarray | None = None
    ) -> DCSNetwork:
        """Rebuild a network from :meth:`save`'s header and arrays (used by composite models);
        ``train_z``: the training inputs of the network this one belongs to (its trend network
        or an averaged network), used when ``data`` has none."""
        version = header.get("version")  # version 1-2 files (no trend/fallback) read the same
        check_header(
            header, source, "DCS network", DCS_FORMAT, version if version in (1, 2) else DCS_VERSION
        )
        try:
            params = dict(header["params"])
            if "random_state" in params:  # files written before the rng/seed convention
                params["rng"] = params.pop("random_state")
            net = cls(**params)
            net.centers_ = np.asarray(data["centers"], dtype=float)
            net.outputs_ = np.asarray(data["outputs"], dtype=float)
            net.widths_ = np.asarray(data["widths"], dtype=float)
            net.edges_ = np.asarray(data["edges"], dtype=bool)
            net.x_mean_ = np.asarray(data["x_mean"], dtype=float)
            net.x_scale_ = np.asarray(data["x_scale"], dtype=float)
            net._y_1d = bool(header["y_1d"])
            net.train_rmse_ = float(header["train_rmse"])
            net.width_factor_ = header.get("width_factor_")  # type: ignore[assignment]
            net.ridge_ = header.get("ridge_")  # type: ignore[assignment]
            net.local_linear_ = bool(header.get("local_linear_", False))
            net.slopes_ = np.asarray(data["slopes"], dtype=float) if net.local_linear_ else None
            net.global_linear_ = bool(header.get("global_linear_", False))
            net.slope_ridge_ = header.get("slope_ridge_")  # type: ignore[assignment]
            net.trend_ = np.asarray(data["trend"], dtype=float) if net.global_linear_ else None
            net.scaling_ = header.get("scaling_") or params.get("scaling", "column")
            net.history_ = [tuple(h) for h in header.get("history", [])]
            net.n_pruned_ = int(header.get("n_pruned_", 0))
            own = np.asarray(data["train_z"] if "train_z" in data else train_z, dtype=float)
            if own.ndim != 2:
                raise ValueError("no training inputs")
            net.fallback_ = None
            if "fallback" in header:
                sub = {k[9:]: v for k, v in data.items() if k.startswith("fallback.")}
                net.fallback_ = cls.from_arrays(header["fallback"], sub, source, own)
            net.members_ = []
            for j, sub_header in enumerate(header.get("members", [])):
                pre = f"member{j}."
                sub = {k[len(pre) :]: v for k, v in data.items() if k.startswith(pre)}
                net.members_.append(cls.from_arrays(sub_header, sub, source, own))
            k = len(net.centers_)
            if (
                net.outputs_.shape[0] != k
                or net.widths_.shape != (k,)
                or net.edges_.shape != (k, k)
                or net.centers_.shape[1] != len(net.x_mean_)
                or (
                    net.slopes_ is not None
                    and net.slopes_.shape != (k, len(net.x_mean_), net.outputs_.shape[1])
                )
                or (
                    net.trend_ is not None
                    and net.trend_.shape != (len(net.x_mean_), net.outputs_.shape[1])
                )
            ):
                raise ValueError("array shapes are inconsistent")
            net.n_neurons_ = k
            net._set_training_points(own)
        except (KeyError, TypeError, ValueError, IndexError) as exc:
            raise ModelFileError(f"{source}: corrupt DCS network ({exc})") from exc
        return net

    @classmethod
    def load(cls, path: str | Path) -> DCSNetwork:
        """Read a network written by :meth:`save`; corrupt/foreign files raise ModelFileError."""
        header, data = load_npz(path, "DCS network")
        return cls.from_arrays(header, data, source=str(path))
