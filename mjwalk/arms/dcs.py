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

Dead units (``min_wins``): after every adaptation pass, a neuron that wins fewer than
``min_wins`` training samples (default 1: none) is removed with its edges, as growing networks
remove units the data no longer supports (Fritzke 1995, "A growing neural gas network learns
topologies"). A neuron inserted half way between two others can fall into a gap between
clusters of the data; winning no sample, its output and slopes are set by nothing but the
ridge, and a new input in that gap (a walker between the trained styles) would get them
(docs/decisions/001-dcs-extrapolation.md). When the neuron just inserted dies, the edge
between its two parents is cut too, so the next insertion goes elsewhere.

Trend fallback (``trend_fallback=True``): outside the data, no local structure is known, so
the output blends into the *trend network* -- the network growth starts from (two neurons,
constant outputs) with the global linear term, fitted on the same samples with the same grids
-- with the weight ``g = exp(-d^2 / (2 r^2))`` of the full network, ``d`` the distance to the
nearest training input and ``r`` the trained-range radius (``range_radius_``, where
:meth:`DCSNetwork.is_outside` starts to flag a query). A Gaussian process with a linear mean
function reverts to its mean function away from its data in the same way (Rasmussen &
Williams 2006, §2.7). Inside the data ``g`` is close to 1; a walker unlike every trained one
gets the trend, not the outermost neuron's local map (docs/decisions/001-dcs-extrapolation.md).

Seed averaging (``n_networks``): the growth is stochastic (random start neurons, random
presentation order), and two networks grown from different seeds on the same samples differ
most where the data say least. ``n_networks > 1`` grows that many networks from independent
seeds (``numpy.random.SeedSequence.spawn``) and averages their outputs (an ensemble of
networks differing only in their initial conditions: Hansen & Salamon 1990, "Neural network
ensembles").

Inputs are standardized and the grids chosen as :mod:`mjwalk.arms.dcsfit` describes; widths and
:meth:`DCSNetwork.distance_to_training` are in standardized units. The saved file keeps the
standardized training inputs (not the outputs) for that distance.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from mjwalk._io import load_npz, save_npz
from mjwalk.arms.dcsfile import (
    network_arrays,
    network_from_arrays,
    network_header,
)
from mjwalk.arms.dcsfit import (
    SAMPLES_PER_COEFFICIENT,
    SCALINGS,
    SelectionGrids,
    SelectionSamples,
    design,
    forward,
    grid,
    grid_values,
    input_scale,
    neuron_widths,
    score_step,
    solve_outputs,
    split_outputs,
)
from mjwalk.arms.dcsgrow import adapt, insert_neuron, insertion_pair, prune, start_neurons
from mjwalk.arms.dcsoptions import DCSOptions
from mjwalk.arms.dcsquery import nearest_distances, use_brute
from mjwalk.errors import MjwalkError


class DCSNetwork:
    """Growing normalized-RBF network with competitive-Hebbian lateral edges.

    Args:
        options: the growth and selection settings (:class:`~mjwalk.arms.dcsoptions.DCSOptions`,
            whose docstring gives each default and its source); None: the defaults.
        rng: seed or ``numpy.random.Generator``; same seed, same network.
        **settings: fields of :class:`~mjwalk.arms.dcsoptions.DCSOptions` overriding
            ``options`` (``DCSNetwork(max_neurons=8, rng=0)``; an unknown name raises
            TypeError). ``n_networks > 1``: the fitted attributes describe the first network,
            ``members_`` the others.

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
        options: DCSOptions | None = None,
        *,
        rng: int | np.random.Generator | None = 0,
        **settings,
    ):
        self.options = replace(options if options is not None else DCSOptions(), **settings)
        self.rng = rng

    # ------------------------------------------------------------------ fitting
    def fit(self, X: np.ndarray, Y: np.ndarray) -> DCSNetwork:
        """Grow the network on inputs ``X`` (N, d) and targets ``Y`` (N, m) or (N,).

        Args:
            X: (N, d) inputs, N >= 2, or (N,) for d = 1.
            Y: (N, m) or (N,) targets.

        Returns:
            this network, fitted.
        """
        X = np.asarray(X, dtype=float)
        Y = np.asarray(Y, dtype=float)
        if X.ndim == 1:
            X = X[:, None]
        self.y_1d_ = Y.ndim == 1
        if Y.ndim == 1:
            Y = Y[:, None]
        if X.ndim != 2 or Y.ndim != 2 or len(X) != len(Y):
            raise MjwalkError(f"DCSNetwork.fit: X {X.shape} and Y {Y.shape} do not match")
        if len(X) < 2:
            raise MjwalkError(f"DCSNetwork.fit: need at least 2 samples, got {len(X)}")
        if not (np.isfinite(X).all() and np.isfinite(Y).all()):
            raise MjwalkError("DCSNetwork.fit: X or Y holds NaN or infinite values")
        self.options.check()
        scalings = self._scalings(X.shape[1])
        member_seeds = self._member_seeds()
        if len(scalings) == 1:
            self._grow_first(X, Y, scalings[0], np.random.default_rng(self.rng))
        else:
            # one network per input scaling, grown from the same seed; the lowest selection
            # score (PRESS) wins, like the width (:mod:`mjwalk.arms.dcsfit`)
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
        if self.options.trend_fallback:
            self.fallback_ = DCSNetwork(**self._trend_params()).fit(X, Y[:, 0] if self.y_1d_ else Y)
        self.members_ = [
            DCSNetwork(
                **{**self.params(), "scaling": self.scaling_, "n_networks": 1, "rng": seed}
            ).fit(X, Y[:, 0] if self.y_1d_ else Y)
            for seed in member_seeds
        ]
        return self

    def _scalings(self, d: int) -> tuple[str, ...]:
        """The input scalings to try (``scaling``: one or a sequence), checked for ``d``
        input columns."""
        seq = (
            tuple(self.options.scaling)
            if isinstance(self.options.scaling, list | tuple)
            else (self.options.scaling,)
        )
        if not seq or any(s not in SCALINGS for s in seq):
            raise MjwalkError(
                f"DCSNetwork: scaling must be one of {', '.join(map(repr, SCALINGS))} or a "
                f"sequence of them, got {self.options.scaling!r}"
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
        samples = self._split(Z, Y, rng)
        centers, ages = start_neurons(samples.train_z, rng)
        self.history_: list[tuple[int, float, float]] = []
        self.n_pruned_ = 0
        grids = self._grids(len(samples.train_z), Z.shape[1])
        centers, ages, factor, ridge, linear, best_val = self._grow_loop(
            samples, grids, centers, ages, rng
        )
        self._set_outputs(Z, Y, centers, ages, (factor, ridge, linear))
        # without selection: the final network's training error (as the width grid's score)
        self.selection_score_ = float(best_val) if samples.selects else self.train_rmse_
        self.set_training_points(Z)

    def _split(self, Z, Y, rng: np.random.Generator) -> SelectionSamples:
        """Hold out ``validation_fraction`` of the samples (none with ``selection="loo"`` or
        when fewer than two would be left to train on), drawn by one permutation."""
        n = len(Z)
        loo = self.options.selection == "loo"
        fraction = self.options.validation_fraction
        n_val = round(fraction * n) if fraction > 0 else 0
        if n - n_val < 2 or loo:
            n_val = 0
        perm = rng.permutation(n)
        val_idx, tr_idx = perm[:n_val], perm[n_val:]
        return SelectionSamples(Z[tr_idx], Y[tr_idx], Z[val_idx], Y[val_idx], loo)

    def _grids(self, n_train: int, d: int) -> SelectionGrids:
        """The width factors, ridges and output forms (local linear, global linear, slope
        ridge) each growth step chooses among, for ``n_train`` samples of ``d`` inputs."""
        factors = self._factors()
        ridges = self._ridges()
        # a linear map (global or per neuron) has one coefficient per input and output
        linear_ok = n_train >= SAMPLES_PER_COEFFICIENT * d
        # output forms (local linear, global linear, slope ridge), chosen like the width
        forms = [
            (local, glob, r)
            for local in (grid(self.options.local_linear) if linear_ok else (False,))
            for glob in (grid(self.options.global_linear) if linear_ok else (False,))
            for r in (self._slope_ridges() if local else (1.0,))
        ]
        return SelectionGrids(factors, ridges, forms)

    def _grow_loop(self, samples: SelectionSamples, grids: SelectionGrids, centers, ages, rng):
        """Adapt, prune, score and insert until a stopping rule holds (module docstring).
        Returns the centres, edge ages, width factor, ridge and output form of the network
        kept (the best scored one when the steps are selected on, else the last) and the best
        selection score."""
        opts = self.options
        Ztr, select = samples.train_z, samples.selects
        best = None
        best_val = np.inf
        no_change = 0
        stalled = 0  # insertions in a row whose neuron died at once
        parents: tuple[int, int] | None = None
        resid = np.zeros(len(Ztr))  # squared training error per sample, set by every step
        while True:
            centers, ages = adapt(Ztr, centers, ages, rng, opts)
            centers, ages, newest_died, removed = prune(Ztr, centers, ages, parents, opts.min_wins)
            self.n_pruned_ += removed
            stalled = stalled + 1 if newest_died else 0
            if newest_died:  # nothing new to score; insert elsewhere (the parents' edge is cut)
                if stalled >= max(opts.n_iter_no_change, 1):
                    break
            else:
                val_rmse, factor, ridge, linear, resid = score_step(samples, grids, centers, ages)
                train_rmse = float(np.sqrt(resid.mean()))
                self.history_.append((len(centers), train_rmse, val_rmse if select else np.nan))
                if val_rmse < best_val - 1e-12:
                    best_val = val_rmse
                    best = (centers.copy(), ages.copy(), factor, ridge, linear)
                    no_change = 0
                else:
                    no_change += 1
                if (
                    train_rmse <= opts.error_threshold
                    or len(centers) >= opts.max_neurons
                    or len(centers) >= len(Ztr)
                    or (select and no_change >= opts.n_iter_no_change)
                ):
                    break
            parents = insertion_pair(Ztr, centers, ages, resid)
            centers, ages = insert_neuron(centers, ages, *parents)
        if select and best is not None:
            centers, ages, factor, ridge, linear = best
        return centers, ages, factor, ridge, linear, best_val

    def _set_outputs(self, Z, Y, centers, ages, chosen) -> None:
        """Set the fitted network: the grids' ``chosen`` (width factor, ridge, output form),
        the widths, and the output vectors solved on every sample (train + held-out)."""
        factor, ridge, linear = chosen
        edges = ages >= 0
        self.width_factor_ = float(factor)
        self.ridge_ = float(ridge)
        self.local_linear_ = bool(linear[0])
        self.global_linear_ = bool(linear[1])
        self.slope_ridge_ = float(linear[2])
        widths = neuron_widths(centers, edges, factor)
        self.centers_ = centers
        self.edges_ = edges
        self.widths_ = widths
        stacked = solve_outputs(Z, Y, centers, widths, edges, ridge, linear)
        self.outputs_, self.slopes_, self.trend_ = split_outputs(
            stacked, len(centers), Z.shape[1], linear
        )
        self.n_neurons_ = len(centers)
        self.train_rmse_ = float(
            np.sqrt(
                ((forward(Z, centers, widths, stacked, edges, linear) - Y) ** 2).sum(axis=1).mean()
            )
        )

    def _member_seeds(self) -> list[int]:
        """Seeds of the networks after the first (``n_networks - 1``): spawned from an integer
        seed without drawing from it (the first network is the one ``n_networks=1`` grows),
        else drawn from the generator first."""
        if self.options.n_networks <= 1:
            return []
        if isinstance(self.rng, np.random.Generator):
            entropy = int(self.rng.integers(2**63))
            return [
                int(x)
                for x in np.random.default_rng(entropy).integers(
                    2**31, size=self.options.n_networks - 1
                )
            ]
        seq = np.random.SeedSequence(self.rng)
        return [int(c.generate_state(1)[0]) for c in seq.spawn(self.options.n_networks - 1)]

    def _trend_params(self) -> dict:
        """The trend network's settings: this network's, grown no further than the two
        neurons growth starts from, constant outputs, with the global linear term."""
        params = self.params()
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

    def _factors(self) -> tuple[float, ...]:
        return grid_values("width_factor", self.options.width_factor, False)

    def _ridges(self) -> tuple[float, ...]:
        return grid_values("ridge", self.options.ridge, True)

    def _slope_ridges(self) -> tuple[float, ...]:
        return grid_values("slope_ridge", self.options.slope_ridge, False)

    def set_training_points(self, Z):
        """Keep the standardized training inputs and the trained-range radius ``range_radius_``.

        Args:
            Z: (N, d) standardized training inputs.
        """
        self.train_z_ = Z
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

    def predict(self, X: np.ndarray, distance: np.ndarray | None = None) -> np.ndarray:
        """Outputs (N, m) for inputs ``X`` (N, d) by the normalized RBF of eq. 2 (blended into
        the trend network outside the trained range when it has one, see the module doc).

        Args:
            X: (N, d) inputs; a 1-D array is one input (d > 1) or N inputs (d = 1).
            distance: (N,) :meth:`distance_to_training` of ``X`` when the caller has it
                already (the weight then skips its nearest-neighbour query: the same
                numbers); None: computed here.

        Returns:
            (N, m) outputs, or (N,) when fitted on 1-D targets.
        """
        self._check_fitted()
        # one weight for all networks: they share the training inputs, hence d and r
        g = self.network_weight(X, distance) if self._fallback() is not None else None
        out = self._predict_one(X, g)
        members = getattr(self, "members_", [])
        if members:
            out = (out + sum(m._predict_one(X, g) for m in members)) / (1 + len(members))
        return out[:, 0] if self.y_1d_ else out

    def _predict_one(self, X: np.ndarray, g: np.ndarray | None) -> np.ndarray:
        """(N, m) output of this network alone, blended into its trend network with the full
        network's weight ``g`` (:meth:`network_weight`) when it has one."""
        out = self._predict_network(X)
        fallback = self._fallback()
        if fallback is not None and g is not None:
            trend = fallback._predict_network(X)
            out = trend + g[:, None] * (out - trend)
        return out

    def network_weight(self, X: np.ndarray, distance: np.ndarray | None = None) -> np.ndarray:
        """(N,) weight of the full network in :meth:`predict`: ``exp(-d^2 / (2 r^2))``,
        ``d`` the distance to the nearest training input, ``r = range_radius_``; 1 without a
        trend fallback.

        Args:
            X: (N, d) inputs.
            distance: (N,) :meth:`distance_to_training` of ``X`` if known; None: computed.

        Returns:
            (N,) weights in (0, 1].
        """
        self._check_fitted()
        if self._fallback() is None:
            return np.ones(len(self._standardize(X)))
        d = self.distance_to_training(X) if distance is None else distance
        q = d / max(self.range_radius_, 1e-12)
        return np.exp(-0.5 * q**2)

    def _predict_network(self, X: np.ndarray) -> np.ndarray:
        """(N, m) outputs of this network alone."""
        Z = self._standardize(X)
        Phi = design(Z, self.centers_, self.widths_, self.edges_)
        out = Phi @ self.outputs_
        if self.slopes_ is not None:  # local linear terms: sum_i h_i (z - c_i) @ S_i
            offsets = Z[:, None, :] - self.centers_[None]
            out = out + np.einsum("nk,nkd,kdm->nm", Phi, offsets, self.slopes_)
        if self.trend_ is not None:  # global linear term
            out = out + Z @ self.trend_
        return out

    def distance_to_training(self, X: np.ndarray) -> np.ndarray:
        """(N,) distance of each input to its nearest training input, in standardized units
        (training standard deviations). Compare with ``range_radius_`` to flag extrapolation.

        Args:
            X: (N, d) inputs.

        Returns:
            (N,) distances, standardized units.
        """
        self._check_fitted()
        Z = self._standardize(X)
        train = self.train_z_
        if len(train) and use_brute(len(train), len(Z)):  # the tree's numbers, without it
            return nearest_distances(train, Z)
        d, _ = self._tree.query(Z, k=1)
        return np.atleast_1d(d).astype(float)

    def is_outside(self, X: np.ndarray) -> np.ndarray:
        """(N,) True where the input lies outside the trained range (see ``range_radius_``).

        Args:
            X: (N, d) inputs.

        Returns:
            (N,) bool.
        """
        return self.distance_to_training(X) > self.range_radius_

    # ------------------------------------------------------------------ persistence
    def _fallback(self) -> DCSNetwork | None:
        """The trend network, or None (none fitted, or a version 1-2 file)."""
        return getattr(self, "fallback_", None)

    def to_arrays(self, with_training: bool = True) -> dict:
        """The arrays :meth:`save` writes (:func:`~mjwalk.arms.dcsfile.network_arrays`).

        Args:
            with_training: include the standardized training inputs.

        Returns:
            ``{name: array}``.
        """
        return network_arrays(self, with_training)

    def params(self) -> dict:
        """The constructor arguments (a seed as is; a Generator as None).

        Returns:
            the :class:`~mjwalk.arms.dcsoptions.DCSOptions` fields in order, then ``rng``.
        """
        params = self.options.as_dict()
        rs = self.rng
        params["rng"] = rs if isinstance(rs, int | None) else None
        return params

    def header(self) -> dict:
        """The header :meth:`save` writes (:func:`~mjwalk.arms.dcsfile.network_header`).

        Returns:
            the header dict (JSON-serializable).
        """
        return network_header(self)

    def save(self, path: str | Path) -> None:
        """Write the fitted network to one versioned ``.npz`` file (atomically).

        Args:
            path: the ``.npz`` file to write.
        """
        self._check_fitted()
        save_npz(path, network_header(self), network_arrays(self))

    @classmethod
    def from_arrays(
        cls, header: dict, data: dict, source: str = "<arrays>", train_z: np.ndarray | None = None
    ) -> DCSNetwork:
        """Rebuild a network from :meth:`save`'s header and arrays (used by composite models);
        ``train_z``: the training inputs of the network this one belongs to (its trend network
        or an averaged network), used when ``data`` has none.

        Args:
            header: the header :meth:`header` returns.
            data: the arrays :meth:`to_arrays` returns.
            source: name of the source in errors.
            train_z: (N, d) standardized training inputs, or None.

        Returns:
            the fitted network.
        """
        return network_from_arrays(cls, header, data, source, train_z)

    @classmethod
    def load(cls, path: str | Path) -> DCSNetwork:
        """Read a network written by :meth:`save`; corrupt/foreign files raise ModelFileError.

        Args:
            path: the ``.npz`` file.

        Returns:
            the fitted network.
        """
        header, data = load_npz(path, "DCS network")
        return cls.from_arrays(header, data, source=str(path))
