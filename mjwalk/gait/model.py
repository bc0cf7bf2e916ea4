"""The ``StepModel``: KDE for first steps, Gaussian-process transitions (agethen2018 §3.4-4.1).

Steps live in the standardized PCA feature space of :class:`~mjwalk.gait.features.StepFeatures`.

**First steps** (gait initiation): one ``scipy.stats.gaussian_kde`` (Scott's bandwidth) per side,
fitted on the first step of every take (the step with the smallest index). The planner starts
walkers from standing, so the starters should be initiation steps, as in the paper. When a side
has fewer than ``max(2·(d+1), 10)`` first steps (a corpus of few long takes), that side's KDE is
fitted on all its steps instead (recorded in :meth:`StepModel.summary` as ``kde_source``).

**Transitions** left->right and right->left, each a Gaussian process from the predecessor's
features to the successor's (zero mean, ``normalize_y=False`` on the standardized features,
kernel ``C·RBF(per-dimension length scales) + White``), trained on every captured transition
*except those into a gait termination* (``Step.meta["termination"]``: the closing step of a
take that ends standing). No step follows a termination, so a forward-sampled chain that drew
one would stop walking mid-way and wander among short steps; the planner's walks end in the
goal area. (On the default corpus, 9 % of the transitions end in a termination; trained on
them, 41 % of the steps of 40-step chains were shorter than 0.45 m against 1 % of the corpus's
steady-state steps.) Terminations are a regime of their own: two more GPs of the same kind, the
*stop GPs*, learn the closing step from its predecessor, and :meth:`StepModel.sample_stop` draws
it; the planner offers such closing steps near the goal (a short walk must be able to stop
short of a full stride). An exact GP on ~10 000 pairs per direction
needs 10 000² matrices, so the scheme is (Rasmussen & Williams 2006, §8.3):

1. hyper-parameters (C, length scales, noise σ²) by maximizing the log-marginal likelihood
   with sklearn ``GaussianProcessRegressor`` on a random subset of ``n_hyper`` pairs;
2. ``n_inducing`` inducing inputs Z = k-means centres of all predecessor features;
3. the DTC / projected-process predictor with those hyper-parameters and Z, conditioned on
   ALL pairs: Σ = (K_mm + σ⁻² K_mn K_nm)⁻¹, mean μ(x) = σ⁻² k_xm Σ K_mn Y = k_xm α,
   latent variance v(x) = C - k_xm (K_mm⁻¹ - Σ) k_mx = C - k_xm W k_mx.
   α (m, d) and W (m, m) are precomputed (through Cholesky factors), so one prediction is a
   kernel row against m points and two small products;
4. the observation noise of successors is *local and empirical*: for every inducing input
   z_j, the residuals Y - μ(X) of the ``n_residual`` training pairs whose predecessors lie
   nearest to z_j (in the length-scale-scaled metric of the kernel) form its residual pool
   R_j (``n_residual`` ≈ N / m, so the pools together hold about every residual once). The
   multi-output sklearn GP must share one White σ² across outputs and across the whole input
   space, but the captured noise differs by regime (straight walking, turning on the spot,
   side steps) and is neither Gaussian nor uncorrelated across features: one global residual
   covariance drew successors that combine, e.g., a turning step's yaw with a straight step's
   length, off the data, and chains drifted. Pooling residuals by inducing input keeps the
   noise of the regime the predecessor is in, with its correlations.

A successor of x is drawn as  y = μ(x) + √v(x)·ε + r,  ε ~ N(0, I) and r drawn uniformly from
the pool R_j of an inducing input z_j drawn with probability ∝ k(x, z_j)^10 (kernel values
already computed for μ; mostly the nearest, now and then a neighbouring regime: see
:data:`POOL_SHARPNESS`). Far from the data v(x) grows towards C, so the GP's uncertainty is
still sampled there.

The model is saved to ONE ``.npz`` file (format name + version in a JSON header, plain arrays,
no pickle), written atomically.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from mjwalk._args import as_generator
from mjwalk._io import check_header, load_npz, save_npz
from mjwalk._log import log
from mjwalk.conventions import DEFAULT_STATURE, Side, other_side
from mjwalk.errors import MjwalkError, ModelFileError
from mjwalk.gait.features import (
    StepBatch,
    StepFeatures,
    concat_batches,
    raw_features,
    raw_scale_factors,
    side_array,
)
from mjwalk.gait.fitting import GPFitter, first_step_indices, fit_starters, transition_pairs
from mjwalk.gait.pace import PACE_VERSION, Pace, model_pace
from mjwalk.gait.step import Step
from mjwalk.gait.transition import N_INDUCING, TransitionGP
from mjwalk.gait.walker import Walker

MODEL_FORMAT = "mjwalk.stepmodel"
#: Bump whenever the saved arrays or their meaning change (4: the default model is trained on
#: pace-normalized steps and saves its pace, mjwalk.gait.pace).
MODEL_VERSION = 4
#: Fewest aligned steps a model is fitted on: with alternating sides, 10 steps give each
#: transition GP its minimum of 5 pairs per direction (:meth:`TransitionGP.fit`).
MIN_STEPS = 10

#: Fewest transitions into a gait termination, per side, for which a stop GP is fitted.
MIN_STOP_PAIRS = 20

_SIDES = ("left", "right")


# --------------------------------------------------------------------------------------------
# Step model
# --------------------------------------------------------------------------------------------


@dataclass
class StepModel:
    """Generative step model: KDE starters per side + GP transitions per side pair.

    Build with :meth:`fit`; draw with :meth:`sample_first` and :meth:`sample_next`; every
    returned :class:`StepBatch` is in its steps' local frames (origin, heading +y, x right).
    """

    features: StepFeatures
    kde_data: dict[str, np.ndarray]  # side -> (d, n) KDE dataset
    kde_factor: dict[str, float]  # side -> Scott factor used
    gp: dict[str, TransitionGP]  # predecessor side -> GP to the other side
    info: dict = field(default_factory=dict)
    stop_gp: dict[str, TransitionGP] = field(default_factory=dict)  # ... to a closing step
    #: set by :meth:`for_walker`: the learned model and the walker it is conditioned on
    _base: StepModel | None = field(default=None, repr=False, compare=False)
    _walker: Walker | None = field(default=None, repr=False, compare=False)
    #: the last (walker, conditioned model) of :meth:`for_walker`: a cycle conditions the model
    #: on its run's operator for every walk, and the planner keys its decoder on the model
    _last: tuple | None = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        # scipy.stats.gaussian_kde(data, bw_method=factor) with its uniform weights: kernel
        # covariance = the data's (unbiased) covariance times factor squared. Its resample
        # factors that covariance (SVD) and normalizes the weights on every call; both are
        # fixed, so they are computed here, once (see _kde_resample). Building the kde objects
        # themselves would import scipy.stats (about 1 s) for every ``mjwalk plan``.
        b = self._base  # for_walker's model: its base's KDE, so its factors
        if b is not None and b.kde_data is self.kde_data and b.kde_factor is self.kde_factor:
            self._kde_draw: dict[str, tuple[np.ndarray, np.ndarray]] = b._kde_draw
            return
        self._kde_draw = {}
        for s in _SIDES:
            data = self.kde_data[s]
            n = data.shape[1]
            cov = np.atleast_2d(np.cov(data, rowvar=True, bias=False, aweights=np.full(n, 1 / n)))
            u, sv, _ = np.linalg.svd(cov * self.kde_factor[s] ** 2)
            cdf = np.cumsum(np.full(n, 1 / n))
            self._kde_draw[s] = (u * np.sqrt(sv), cdf / cdf[-1])

    # -- fitting -----------------------------------------------------------------------------

    @classmethod
    def fit(
        cls,
        steps: Sequence[Step],
        *,
        seed: int = 0,
        variance: float = 0.99,
        n_hyper: int = 600,
        n_inducing: int = N_INDUCING,
        n_residual: int | None = None,
        progress: bool = False,
    ) -> StepModel:
        """Fit features, KDEs and both transition GPs on aligned ``steps``.

        Args:
            steps: aligned steps; captured transitions are consecutive ``index`` values of one
                ``take`` with alternating sides.
            seed: seeds the LML subset, k-means and optimizer.
            variance: PCA variance to keep (the paper: >= 0.95; 1.0 keeps all). Default 0.99:
                the lateral sway (~1.5 cm) lives mostly in the last few percent; on Bandai
                {masculine, normal} 0.99 halves its reconstruction error (2.9 -> 1.5 mm). Every
                kept dimension needs transitions to learn: 0.99 suits the default corpus
                (~9 800 pairs per direction, 6 dimensions); on the ~790 pairs per direction of
                Bandai {masculine, normal} it keeps 8 and chains drift (in-sample KS of 40-step
                chains: length 0.17, sway 0.24), where 0.95 (4 dimensions) gives 0.05, 0.19.
            n_hyper: pairs per direction for the hyper-parameter (LML) fit.
            n_inducing: inducing points per direction for the DTC posterior
                (:data:`~mjwalk.gait.transition.N_INDUCING`, which says why 200).
            n_residual: residuals pooled per inducing point (None: pairs / inducing points).
            progress: print timings to stderr.
        Returns:
            The fitted model (``info`` holds data sizes, seed and fit time).
        """
        t0 = time.perf_counter()
        rng = as_generator(seed, "StepModel.fit: seed")
        steps = list(steps)
        if len(steps) < MIN_STEPS:
            raise MjwalkError(f"StepModel.fit: need at least {MIN_STEPS} steps, got {len(steps)}")
        raw = raw_features(steps)
        sides = side_array(steps)
        feats = StepFeatures.fit(raw, variance=variance)
        z = feats.encode_raw(raw)
        _log(
            progress,
            f"features: {len(steps)} steps -> {feats.n_components} PCA dims "
            f"({100 * feats.variance_kept:.1f} % variance)",
        )
        first = first_step_indices(steps)
        kde_data, kde_factor, kde_source = fit_starters(z, sides, first)

        prev, nxt = transition_pairs(steps)
        # No step follows a gait termination: transitions into one are not modelled (module doc).
        term = np.array([bool(steps[j].meta.get("termination")) for j in nxt], dtype=bool)
        stop_prev, stop_nxt = prev[term], nxt[term]
        prev, nxt = prev[~term], nxt[~term]
        fitter = GPFitter(z, sides, rng, n_hyper, progress)
        gps, n_trans = fitter.fit("GP ", prev, nxt, 0, lambda n: n_inducing, n_residual)
        # ... they are their own regime: a stop GP per side, drawn by sample_stop (module doc)
        stop_gps, n_stop = fitter.fit(
            "stop GP ",
            stop_prev,
            stop_nxt,
            MIN_STOP_PAIRS,
            lambda n: min(n_inducing, max(5, n // 4)),
            None,
        )
        info = {
            "n_steps": len(steps),
            "n_takes": len(first),
            "n_transitions": n_trans,
            "n_terminations_excluded": int(term.sum()),
            "n_stop_transitions": n_stop,
            "kde": kde_source,
            "seed": seed,
            "fit_seconds": round(time.perf_counter() - t0, 3),
            "train_length_mean": float(np.mean(np.hypot(raw[:, 8], raw[:, 9]))),
            "train_duration_mean": float(np.mean(raw[:, 15])),
        }
        return cls(
            features=feats,
            kde_data=kde_data,
            kde_factor=kde_factor,
            gp=gps,
            info=info,
            stop_gp=stop_gps,
        )

    # -- sampling ----------------------------------------------------------------------------

    @property
    def n_dims(self) -> int:
        return self.features.n_components

    def encode(self, steps: Sequence[Step]) -> np.ndarray:
        """Standardized features of ``steps``.

        Args:
            steps: n steps.
        Returns:
            (n, d) features.
        """
        return self.features.encode(steps)

    def decode(self, z: np.ndarray, side) -> StepBatch:
        """Decode standardized features (:meth:`StepFeatures.decode`).

        Args:
            z: (n, d) features.
            side: swing sides, (n,) or one value.
        Returns:
            The steps in their local frames.
        """
        return self.features.decode(z, side)

    def sample_first(self, n: int, rng: np.random.Generator, side: Side | None = None) -> StepBatch:
        """``n`` gait-initiation steps from the KDE.

        Args:
            n: steps.
            rng: the random generator.
            side: None: ``n - n//2`` left then ``n//2`` right steps; else all of ``side``.
        Returns:
            The n steps in their local frames.
        """
        z, sides = self.sample_first_features(n, rng, side)
        return self.features.decode(z, sides)

    def sample_first_features(
        self, n: int, rng: np.random.Generator, side: Side | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`sample_first`'s draws, not decoded (the planner decodes only the steps of the
        walk it returns); arguments as :meth:`sample_first`.

        Args:
            n: steps.
            rng: the random generator.
            side: swing side, or None for both.
        Returns:
            (features (n, d), swing sides (n,)).
        """
        if side is None:
            counts = {"left": n - n // 2, "right": n // 2}
        elif side in _SIDES:
            counts = {side: n}
        else:
            raise MjwalkError(f"sample_first: side must be 'left', 'right' or None, got {side!r}")
        zs, ss = [], []
        for s, c in counts.items():
            if c > 0:
                zs.append(self._kde_resample(s, c, rng))
                ss.extend([s] * c)
        z = np.concatenate(zs) if zs else np.zeros((0, self.n_dims))
        return z, np.array(ss, dtype="<U5")

    def _kde_resample(self, side: str, n: int, rng: np.random.Generator) -> np.ndarray:
        """(n, d) draws from ``side``'s KDE: ``gaussian_kde.resample(n, seed=rng).T``, the same
        draws from the same random stream (a kernel offset N(0, covariance) through numpy's
        SVD factor, then a data point chosen by weight), with the factor computed once."""
        factor, cdf = self._kde_draw[side]
        offset = rng.standard_normal((n, factor.shape[0])) @ factor.T
        idx = cdf.searchsorted(rng.random(n), side="right")
        return self.kde_data[side][:, idx].T + offset

    def sample_next(self, prev: StepBatch, n: int, rng: np.random.Generator) -> StepBatch:
        """``n`` successors of every step in ``prev``: they swing the other foot and keep walking.

        Args:
            prev: p predecessor steps (their features are used).
            n: successors per predecessor.
            rng: the random generator.
        Returns:
            p·n steps; rows i·n .. i·n+n-1 follow ``prev[i]``.
        """
        return self._sample(self.gp, prev, n, rng, "sample_next")

    @property
    def can_stop(self) -> bool:
        """Whether the model has a stop GP for both sides (see :meth:`sample_stop`)."""
        return all(s in self.stop_gp for s in _SIDES)

    def sample_stop(self, prev: StepBatch, n: int, rng: np.random.Generator) -> StepBatch:
        """``n`` closing steps after every step in ``prev``: the step that brings the walk to a
        stand (gait termination, usually shorter and slower), from the stop GPs. Raises
        MjwalkError when the model has none (:attr:`can_stop`: the training data had fewer than
        :data:`MIN_STOP_PAIRS` terminations per side).

        Args:
            prev: p predecessor steps.
            n: successors per predecessor.
            rng: the random generator.
        Returns:
            p·n steps, laid out as :meth:`sample_next`'s.
        """
        if not self.can_stop:
            raise MjwalkError(
                "sample_stop: this step model has no stop GPs (its training data held fewer "
                f"than {MIN_STOP_PAIRS} gait terminations per side)"
            )
        return self._sample(self.stop_gp, prev, n, rng, "sample_stop")

    def _sample(self, gps, prev: StepBatch, n: int, rng, who: str) -> StepBatch:
        p = len(prev)
        d = self.n_dims
        x = prev.features
        if x.shape != (p, d):
            raise MjwalkError(f"{who}: predecessor features {x.shape}, expected ({p}, {d})")
        is_left = prev.side == "left"
        if is_left.all() or not is_left.any():
            s = "left" if p and is_left[0] else "right"
            z = gps[s].sample(x, n, rng).reshape(p * n, d)
            side = np.full(p * n, other_side(s), dtype="<U5")
        else:
            z = np.empty((p, n, d))
            for s, mask in (("left", is_left), ("right", ~is_left)):
                z[mask] = gps[s].sample(x[mask], n, rng)
            z = z.reshape(p * n, d)
            side = np.repeat(np.where(is_left, "right", "left"), n)
        return self.features.decode(z, side)

    def sample_next_features(
        self, x: np.ndarray, side: str, n: int, rng: np.random.Generator, stop: bool = False
    ) -> np.ndarray:
        """The inner routine of :meth:`sample_next` (of :meth:`sample_stop` with ``stop``), without
        decoding, for callers that decode only some successors (the planner); same draws.

        Args:
            x: (p, d) predecessor features.
            side: swing foot of every predecessor.
            n: successors per predecessor.
            rng: the random generator.
            stop: draw closing steps (the stop GPs).
        Returns:
            (p·n, d) successor features; rows i·n .. i·n+n-1 follow ``x[i]``.
        """
        gps = self.stop_gp if stop else self.gp
        if side not in gps:
            raise MjwalkError(f"sample_next_features: no {'stop ' if stop else ''}GP for {side!r}")
        return gps[side].sample(x, n, rng).reshape(len(x) * n, self.n_dims)

    def sample_chain(
        self, n_steps: int, rng: np.random.Generator, side: Side | None = None
    ) -> StepBatch:
        """One walk: a KDE starter, then one GP successor after another.

        Args:
            n_steps: steps in the walk.
            rng: the random generator.
            side: swing side of the starter; None: drawn from ``rng``, even odds.
        Returns:
            The ``n_steps`` steps, each in its own local frame.
        """
        first = self.sample_first(1, rng, side=side or ("left" if rng.random() < 0.5 else "right"))
        parts = [first]
        for _ in range(n_steps - 1):
            parts.append(self.sample_next(parts[-1], 1, rng))
        return concat_batches(parts)

    # -- walkers -----------------------------------------------------------------------------

    def pace(self) -> Pace:
        """The model's own steady straight-walking pace (:func:`mjwalk.gait.pace.model_pace`,
        seeded): measured once on first use and kept in ``info["pace"]`` (saved with the
        model). For a model conditioned with :meth:`for_walker`, the pace of the model it
        was conditioned from.

        Returns:
            The pace.
        """
        base = self._base or self
        if base.info.get("pace", {}).get("version") != PACE_VERSION:
            base.info["pace"] = model_pace(base).as_dict()
        return Pace.from_dict(base.info["pace"])

    @property
    def walker(self) -> Walker | None:
        """The walker this model was conditioned on (:meth:`for_walker`), else None."""
        return self._walker

    def for_walker(self, walker: Walker | None) -> StepModel:
        """This model conditioned on ``walker``: its steps, stretched in their local frames so
        that the steady straight walking of the result has the walker's preferred step length
        (``walker.speed * 60 / walker.cadence``) and step duration (``60 / walker.cadence``)
        as centres (:class:`~mjwalk.gait.pace.Pace`), and the walker's step width
        (``walker.step_width``; when None, the model's width scaled by ``walker.stature / model
        stature``, Perry & Burnfield 2010). Shapes, turning and the variance relative to the pace
        are the model's (:mod:`mjwalk.gait.pace` says why).

        The KDE starters and the transition GPs are shared (they live in feature space); only
        the decoding changes (:meth:`StepFeatures.scaled`), so a conditioned model costs
        nothing to build beyond the model's pace, which is measured once.

        Args:
            walker: the walker; None gives the unconditioned model back.
        Returns:
            The conditioned model (the last one is cached on the base model).
        """
        base = self._base or self
        if walker is None:
            return base
        if base._last is not None and base._last[0] == walker:
            return base._last[1]
        ref = base.pace()
        if walker.step_width is not None:
            lateral = walker.step_width / max(ref.step_width, 1e-3)
        else:
            lateral = walker.stature / float(base.info.get("stature", DEFAULT_STATURE))
        forward = walker.step_length / ref.step_length
        time_ = walker.step_duration / ref.step_duration
        out = replace(
            base,
            features=base.features.scaled(raw_scale_factors(lateral, forward, time_)),
            info={
                **base.info,
                "walker": {
                    "stature": walker.stature,
                    "speed": walker.speed,
                    "cadence": walker.cadence,
                    "step_width": walker.step_width,
                    "group": walker.group,
                    "scale": {"lateral": lateral, "forward": forward, "time": time_},
                },
            },
            _base=base,
            _walker=walker,
            _last=None,
        )
        base._last = (walker, out)
        return out

    # -- persistence -------------------------------------------------------------------------

    def summary(self) -> dict:
        """Figures of the fitted model.

        Returns:
            ``info`` plus ``pca_dims``, ``variance_kept`` and per-direction ``kernels`` and
            ``stop_kernels`` (kernel parameters, data sizes).
        """
        out = dict(self.info)
        out.update(
            pca_dims=self.n_dims,
            variance_kept=round(self.features.variance_kept, 5),
            kernels={
                f"{s}->{other_side(s)}": {
                    "signal_var": round(g.signal_var, 5),
                    "noise_var": round(g.noise_var, 5),
                    "length_scale": [round(float(v), 4) for v in g.length_scale],
                    "lml_subset": round(g.lml, 3),
                    "n_hyper": g.n_hyper,
                    "n_inducing": int(g.inducing.shape[0]),
                    "n_residual": int(g.res_pool.shape[1]),
                    "n_pairs": g.n_pairs,
                    "nystrom_share": round(g.nystrom, 5),
                }
                for s, g in self.gp.items()
            },
            stop_kernels={
                f"{s}->{other_side(s)}": {
                    "n_pairs": g.n_pairs,
                    "n_inducing": int(g.inducing.shape[0]),
                }
                for s, g in self.stop_gp.items()
            },
        )
        return out

    def save(self, path: str | Path) -> None:
        """Write the model to one versioned ``.npz`` file, atomically. A model conditioned on
        a walker (:meth:`for_walker`) writes the model it was conditioned from: the walker is a
        choice made when planning, not part of the learned model.

        Args:
            path: the file.
        """
        base = self._base
        if base is not None:
            base.save(path)
            return
        arrays = self.features.arrays("feat_")
        for s in _SIDES:
            arrays[f"kde_{s}"] = self.kde_data[s]
            arrays.update(self.gp[s].arrays(f"gp_{s}_"))
        for s, g in self.stop_gp.items():
            arrays.update(g.arrays(f"stop_{s}_"))
        header = {
            "format": MODEL_FORMAT,
            "version": MODEL_VERSION,
            "kde_factor": self.kde_factor,
            "stop_sides": sorted(self.stop_gp),
            "info": self.info,
        }
        save_npz(path, header, arrays)

    @classmethod
    def load(cls, path: str | Path) -> StepModel:
        """Read a model written by :meth:`save`; any problem raises ``ModelFileError``.

        Args:
            path: the file.
        Returns:
            The (unconditioned) model.
        """
        header, data = load_npz(path, "step-model")
        check_header(header, path, "step-model", MODEL_FORMAT, MODEL_VERSION)
        try:
            feats = StepFeatures.from_arrays(data, "feat_")
            model = cls(
                features=feats,
                kde_data={s: np.asarray(data[f"kde_{s}"], dtype=float) for s in _SIDES},
                kde_factor={s: float(header["kde_factor"][s]) for s in _SIDES},
                gp={s: TransitionGP.from_arrays(data, f"gp_{s}_") for s in _SIDES},
                info=dict(header.get("info", {})),
                stop_gp={
                    s: TransitionGP.from_arrays(data, f"stop_{s}_")
                    for s in header.get("stop_sides", [])
                    if s in _SIDES
                },
            )
            _check_shapes(model)
        except ModelFileError:
            raise
        except (KeyError, TypeError, ValueError, np.linalg.LinAlgError) as exc:
            raise ModelFileError(
                f"{path}: step-model file is incomplete or corrupt ({exc!r})"
            ) from exc
        return model


def _check_shapes(model: StepModel) -> None:
    d = model.n_dims
    f = model.features
    if (
        f.components.ndim != 2
        or f.z_scale.shape != (d,)
        or f.raw_mean.shape != (f.components.shape[1],)
    ):
        raise ValueError("feature arrays have inconsistent shapes")
    for s, g in [*model.gp.items(), *model.stop_gp.items()]:
        m = g.inducing.shape[0]
        if (
            g.inducing.shape != (m, d)
            or g.alpha.shape != (m, d)
            or g.w.shape != (m, m)
            or g.res_pool.ndim != 3
            or g.res_pool.shape[0] != m
            or g.res_pool.shape[2] != d
            or g.res_pool.shape[1] < 1
            or model.kde_data[s].shape[0] != d
        ):
            raise ValueError(f"{s} GP/KDE arrays have inconsistent shapes")
        arrs = (g.inducing, g.alpha, g.w, g.res_pool, model.kde_data[s])
        if not all(np.all(np.isfinite(a)) for a in arrs):
            raise ValueError(f"{s} GP/KDE arrays hold non-finite values")


def _log(progress: bool, msg: str) -> None:
    if progress:
        log.info(f"{msg}")
