"""Step features: landmarks -> cubic B-spline -> PCA -> standardized vector (agethen2018 §4.1).

Each :class:`~mjwalk.gait.step.Step` is reduced to its pelvis path sampled at 6 landmarks that
subdivide the step into 5 parts. The parts are **equidistant in time** (t_i = i·T/5, T the step
duration), not in arc length: decoding then reproduces the speed profile of the step too, and
every step shares the same normalized knot vector, so evaluating the B-spline is one fixed
linear map for all steps (what makes :meth:`StepBatch.resample` a single ``einsum``).

The landmarks are interpolated by a cubic B-spline (``scipy.interpolate.make_interp_spline``,
not-a-knot ends) over normalized time u = t/T in [0, 1].

Raw feature vector (length :data:`N_RAW`), in the step's local frame (start at the origin,
heading +y, x to the walker's right; metres, seconds, radians, yaw CCW with 0 = +y):

====================  ====  ===============================================================
landmarks 1..5 (x,y)   10   pelvis at t = T/5 .. T (landmark 0 is the origin and dropped)
yaw landmarks 1..5      5   pelvis yaw at the same times; the last one is the end pelvis yaw
duration                1   T in seconds
footprint (x,y,yaw)     3   landing (swing) foot at the end of the step
stance (x,y,yaw)        3   the supporting foot during the step (playback needs it)
====================  ====  ===============================================================

:class:`StepFeatures` z-scores the raw features first (so that metres, seconds and radians
weigh alike in the PCA; a plain PCA on mixed units would spend its 95 % on the forward
coordinates alone), then fits ``PCA(svd_solver="full")`` keeping >= ``variance`` of the
variance, then ``StandardScaler`` (as the paper). Everything is affine, so the fitted chain is
stored as two affine maps: ``encode`` and ``decode`` are one matrix product each and
``decode(encode(x))`` is exact (to rounding) when every component is kept.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import BSpline, PPoly, make_interp_spline

from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.errors import MjwalkError
from mjwalk.gait.step import Step

#: Number of landmarks per step (5 equal time parts).
N_LANDMARKS = 6
#: Length of the raw feature vector (see the module docstring).
N_RAW = 2 * (N_LANDMARKS - 1) + (N_LANDMARKS - 1) + 1 + 3 + 3
#: Shortest duration a decoded step may have (s); sampled features are clipped to it.
MIN_DURATION = 0.15
#: Synthesis rate (Hz), as the paper.
FPS = SAMPLE_RATE_HZ

_SL_XY = slice(0, 10)
_SL_YAW = slice(10, 15)
#: Column of the step duration (s) in a raw feature row (:meth:`StepFeatures.decode_raw`).
I_DUR = 15
_SL_FOOT = slice(16, 19)
_SL_STANCE = slice(19, 22)


@functools.lru_cache(maxsize=1)
def _landmark_spline():
    """The interpolating cubic B-spline of the unit landmark vectors (a BSpline with (6, 6)
    coefficients), made once: solving for it costs some 50 µs, evaluating it 8 µs."""
    knots = np.linspace(0.0, 1.0, N_LANDMARKS)
    return make_interp_spline(knots, np.eye(N_LANDMARKS), k=3)


#: Every sample count of the steps decoded at 120 Hz fits the cache (a step of 0.3-2 s takes
#: 37-241; a basis is m x 6 floats): a planned walk's steps are decoded at their own counts.
@functools.lru_cache(maxsize=512)
def spline_basis(m: int) -> np.ndarray:
    """(m, 6) matrix B so that ``B @ landmarks`` evaluates the cubic interpolating B-spline.

    The spline runs over normalized time u in [0, 1] with the 6 landmarks at u = 0, 0.2, ..., 1;
    samples are at ``u = linspace(0, 1, m)``. Row 0 is exactly (1, 0, ..., 0) and row m-1
    exactly (0, ..., 0, 1), so decoded paths start at the origin and end at the last landmark.

    Args:
        m: number of samples, >= 2.

    Returns:
        (m, 6) read-only basis (cached per ``m``).
    """
    if m < 2:
        raise MjwalkError(f"spline_basis: need at least 2 samples, got m={m}")
    basis = _landmark_spline()(np.linspace(0.0, 1.0, m))
    basis[0] = np.eye(N_LANDMARKS)[0]
    basis[-1] = np.eye(N_LANDMARKS)[-1]
    basis.setflags(write=False)
    return basis


@functools.lru_cache(maxsize=1)
def spline_pieces() -> tuple[np.ndarray, np.ndarray]:
    """The landmark spline of :func:`spline_basis` as cubic pieces, for compiled evaluation.

    On piece j the basis is sum_q coef[q, j] (u - start_j)^(3 - q), u in [0, 1] normalized
    time; equal to the B-spline to rounding.

    Returns:
        (start, coef): the pieces' start times (p,) in [0, 1) and their coefficients
        (4, p, 6), highest power first, one column per landmark.
    """
    b = _landmark_spline()
    pieces = [PPoly.from_spline(BSpline(b.t, b.c[:, j], b.k)) for j in range(N_LANDMARKS)]
    x = pieces[0].x
    keep = np.flatnonzero(np.diff(x) > 0.0)  # the knots' non-empty intervals
    coef = np.stack([pp.c[:, keep] for pp in pieces], axis=-1)
    return np.ascontiguousarray(x[keep]), np.ascontiguousarray(coef)


def step_raw_features(step: Step) -> np.ndarray:
    """Raw feature vector of one step (see the module docstring for the layout).

    Landmarks are the pelvis x, y and yaw linearly interpolated at t = T/5, ..., T.

    Args:
        step: a step in its local frame (x right, y forward, metres; yaw radians, 0 = +y).

    Returns:
        (N_RAW,) raw features: metres, seconds, radians.
    """
    k = step.n_samples
    if k < 2 or step.pelvis.shape != (k, 2) or step.yaw.shape != (k,):
        raise MjwalkError(
            f"step {step.take!r}#{step.index}: pelvis {step.pelvis.shape} / yaw "
            f"{step.yaw.shape} are not (K, 2) / (K,) with K >= 2"
        )
    t = np.arange(k) / step.fps
    duration = t[-1]
    tl = np.linspace(0.0, duration, N_LANDMARKS)[1:]
    # Linear interpolation of the captured samples at the landmark times (120 Hz is dense).
    x = np.interp(tl, t, step.pelvis[:, 0])
    y = np.interp(tl, t, step.pelvis[:, 1])
    yaw = np.interp(tl, t, step.yaw)
    out = np.empty(N_RAW)
    out[_SL_XY] = np.column_stack([x, y]).ravel()
    out[_SL_YAW] = yaw
    out[I_DUR] = duration
    out[_SL_FOOT] = np.asarray(step.footprint, dtype=float)[:3]
    out[_SL_STANCE] = np.asarray(step.stance, dtype=float)[:3]
    if not np.all(np.isfinite(out)):
        raise MjwalkError(f"step {step.take!r}#{step.index}: non-finite values in its features")
    return out


def raw_features(steps: Sequence[Step]) -> np.ndarray:
    """Raw feature matrix of ``steps`` (:func:`step_raw_features` per row).

    Args:
        steps: n steps.

    Returns:
        (n, N_RAW) raw features; (0, N_RAW) for no steps.
    """
    if len(steps) == 0:
        return np.zeros((0, N_RAW))
    return np.stack([step_raw_features(s) for s in steps])


def side_array(steps: Sequence[Step]) -> np.ndarray:
    """Side strings of ``steps``.

    Args:
        steps: n steps.

    Returns:
        (n,) "left"/"right" strings (dtype <U5).
    """
    sides = np.array([s.side for s in steps], dtype="<U5")
    bad = ~np.isin(sides, ["left", "right"])
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise MjwalkError(f"step {steps[i].take!r}#{steps[i].index}: side {sides[i]!r} unknown")
    return sides


@dataclass
class StepBatch:
    """A batch of n decoded steps, each in its own local frame (origin, heading +y, x right).

    Attributes:
        side: (n,) "left"/"right": the swing foot of each step.
        features: (n, d) standardized PCA features (the model space).
        landmarks: (n, 6, 2) pelvis landmarks in metres at t = 0, T/5, ..., T; row 0 is the origin.
        yaw_landmarks: (n, 6) pelvis yaw (radians, CCW, 0 = +y) at the same times; column 0 is 0.
        duration: (n,) step duration, seconds.
        footprint: (n, 3) landing foot x, y (metres) and yaw (radians).
        stance: (n, 3) supporting foot x, y, yaw.
    """

    side: np.ndarray
    features: np.ndarray
    landmarks: np.ndarray
    yaw_landmarks: np.ndarray
    duration: np.ndarray
    footprint: np.ndarray
    stance: np.ndarray

    def __len__(self) -> int:
        return int(self.duration.shape[0])

    @property
    def end_xy(self) -> np.ndarray:
        """(n, 2) pelvis position at the end of each step, metres (local frame)."""
        return self.landmarks[:, -1]

    @property
    def end_yaw(self) -> np.ndarray:
        """(n,) pelvis yaw at the end of each step, radians relative to the start heading."""
        return self.yaw_landmarks[:, -1]

    @property
    def length(self) -> np.ndarray:
        """(n,) straight-line pelvis displacement of each step, metres."""
        return np.hypot(self.end_xy[:, 0], self.end_xy[:, 1])

    def n_samples(self, i: int, fps: float = FPS) -> int:
        """Number of samples K = round(duration·fps) + 1 of step ``i`` at ``fps``.

        Args:
            i: row index.
            fps: sampling rate, Hz.

        Returns:
            K.
        """
        return round(float(self.duration[i]) * fps) + 1

    def trajectory(self, i: int, fps: float = FPS) -> tuple[np.ndarray, np.ndarray]:
        """Pelvis path and yaw of step ``i`` at ``fps`` (local frame).

        K = round(duration·fps) + 1 samples evenly spaced over [0, duration]; sample 0 is
        exactly the origin with yaw 0, sample K-1 exactly the end landmark.

        Args:
            i: row index.
            fps: sampling rate, Hz.

        Returns:
            (pelvis (K, 2) metres, yaw (K,) radians).
        """
        basis = spline_basis(max(self.n_samples(i, fps), 2))
        return basis @ self.landmarks[i], basis @ self.yaw_landmarks[i]

    def resample(self, m: int) -> tuple[np.ndarray, np.ndarray]:
        """Every step at ``m`` samples evenly spaced in its own duration (local frames).

        Args:
            m: samples per step, >= 2.

        Returns:
            (pelvis (n, m, 2) metres, yaw (n, m) radians).
        """
        basis = spline_basis(m)
        return (
            np.einsum("mk,nkc->nmc", basis, self.landmarks),
            self.yaw_landmarks @ basis.T,
        )

    def take(self, idx) -> StepBatch:
        """Sub-batch of the rows ``idx``.

        Args:
            idx: index array, slice or boolean mask over the n rows.

        Returns:
            A new batch of the selected rows.
        """
        return StepBatch(
            side=self.side[idx],
            features=self.features[idx],
            landmarks=self.landmarks[idx],
            yaw_landmarks=self.yaw_landmarks[idx],
            duration=self.duration[idx],
            footprint=self.footprint[idx],
            stance=self.stance[idx],
        )

    def to_steps(self, fps: float = FPS) -> list[Step]:
        """The batch as :class:`Step` objects (for playback and analysis).

        Args:
            fps: sampling rate, Hz.

        Returns:
            n steps in their local frames, take "decoded", index = row.
        """
        out = []
        for i in range(len(self)):
            pelvis, yaw = self.trajectory(i, fps)
            out.append(
                Step(
                    side="left" if self.side[i] == "left" else "right",  # checked: side_array
                    fps=fps,
                    pelvis=pelvis,
                    yaw=yaw,
                    footprint=self.footprint[i].copy(),
                    stance=self.stance[i].copy(),
                    take="decoded",
                    index=i,
                )
            )
        return out


def batch_from_raw(raw: np.ndarray, side, features: np.ndarray) -> StepBatch:
    """StepBatch from raw features; durations are clipped to >= :data:`MIN_DURATION`.

    Args:
        raw: (n, N_RAW) raw features (metres, seconds, radians).
        side: (n,) or one value: "left"/"right" strings, or booleans (True = "right").
        features: (n, d) standardized features stored with the batch.

    Returns:
        The n decoded steps.
    """
    n = raw.shape[0]
    landmarks = np.zeros((n, N_LANDMARKS, 2))
    landmarks[:, 1:] = raw[:, _SL_XY].reshape(n, N_LANDMARKS - 1, 2)
    yaw = np.zeros((n, N_LANDMARKS))
    yaw[:, 1:] = raw[:, _SL_YAW]
    side = np.asarray(side)
    if side.dtype == bool:
        side = np.where(side, "right", "left")
    side = np.broadcast_to(side.astype("<U5"), (n,)).copy()
    return StepBatch(
        side=side,
        features=features,
        landmarks=landmarks,
        yaw_landmarks=yaw,
        duration=np.maximum(raw[:, I_DUR], MIN_DURATION),
        footprint=raw[:, _SL_FOOT].copy(),
        stance=raw[:, _SL_STANCE].copy(),
    )


@dataclass
class StepFeatures:
    """Fitted raw-feature z-score -> PCA -> StandardScaler chain, stored as two affine maps.

    ``encode``: z = raw @ enc_matrix - enc_offset;  ``decode``: raw = z @ dec_matrix + dec_offset.

    Attributes:
        raw_mean, raw_scale: (N_RAW,) the first z-score of the raw features.
        components: (d, N_RAW) PCA axes (in z-scored raw space); pca_mean (N_RAW,).
        explained_variance_ratio: (d,) of the kept components.
        z_mean, z_scale: (d,) the final StandardScaler.
    """

    raw_mean: np.ndarray
    raw_scale: np.ndarray
    pca_mean: np.ndarray
    components: np.ndarray
    explained_variance_ratio: np.ndarray
    z_mean: np.ndarray
    z_scale: np.ndarray

    def __post_init__(self) -> None:
        # raw -> z:  (((raw - m0) / s0 - mp) @ C.T - mz) / sz  ==  raw @ enc_matrix - enc_offset
        self.enc_matrix = (self.components / self.raw_scale).T / self.z_scale
        self.enc_offset = (
            ((self.raw_mean / self.raw_scale + self.pca_mean) @ self.components.T) + self.z_mean
        ) / self.z_scale
        # z -> raw:  ((z * sz + mz) @ C + mp) * s0 + m0  ==  z @ dec_matrix + dec_offset
        self.dec_matrix = (self.z_scale[:, None] * self.components) * self.raw_scale
        self.dec_offset = (
            self.z_mean @ self.components + self.pca_mean
        ) * self.raw_scale + self.raw_mean

    @property
    def n_components(self) -> int:
        return int(self.components.shape[0])

    @property
    def variance_kept(self) -> float:
        """Fraction of the (z-scored raw) variance kept by the PCA."""
        return float(self.explained_variance_ratio.sum())

    @classmethod
    def fit(cls, steps_or_raw, *, variance: float = 0.95) -> StepFeatures:
        """Fit the z-score -> PCA -> StandardScaler chain.

        Args:
            steps_or_raw: a list of steps or an (n, N_RAW) raw matrix, n >= 3.
            variance: fraction of the z-scored variance to keep, in (0, 1]; ``1.0`` keeps every
                component (exact inverse). Zero-variance components are dropped.

        Returns:
            The fitted chain.
        """
        # deferred: sklearn is slow to import and only fitting needs it (`mjwalk plan` does not)
        from sklearn.decomposition import PCA  # deferred: as above
        from sklearn.preprocessing import StandardScaler  # deferred: as above

        raw = _as_raw(steps_or_raw)
        if raw.shape[0] < 3:
            raise MjwalkError(f"StepFeatures.fit: need at least 3 steps, got {raw.shape[0]}")
        if not 0.0 < variance <= 1.0:
            raise MjwalkError(f"StepFeatures.fit: variance must be in (0, 1], got {variance}")
        sc0 = StandardScaler().fit(raw)
        x0 = sc0.transform(raw)
        n_comp = None if variance >= 1.0 else variance
        pca = PCA(n_components=n_comp, svd_solver="full").fit(x0)
        # Components without variance (exactly dependent raw features) cannot be standardized;
        # they carry nothing, so they are dropped (decoding stays exact).
        keep = pca.explained_variance_ratio_ > 1e-12
        components = pca.components_[keep]
        zs = (x0 - pca.mean_) @ components.T
        sc1 = StandardScaler().fit(zs)
        return cls(
            raw_mean=sc0.mean_.astype(float),
            raw_scale=sc0.scale_.astype(float),
            pca_mean=pca.mean_.astype(float),
            components=components.astype(float),
            explained_variance_ratio=pca.explained_variance_ratio_[keep].astype(float),
            z_mean=sc1.mean_.astype(float),
            z_scale=sc1.scale_.astype(float),
        )

    def encode_raw(self, raw: np.ndarray) -> np.ndarray:
        """Standardized features z = raw @ enc_matrix - enc_offset.

        Args:
            raw: (n, N_RAW) raw features.

        Returns:
            (n, d) standardized features.
        """
        return raw @ self.enc_matrix - self.enc_offset

    def decode_raw(self, z: np.ndarray) -> np.ndarray:
        """Raw features raw = z @ dec_matrix + dec_offset.

        Args:
            z: (n, d) standardized features.

        Returns:
            (n, N_RAW) raw features.
        """
        return z @ self.dec_matrix + self.dec_offset

    def encode(self, steps: Sequence[Step]) -> np.ndarray:
        """Standardized features of steps.

        Args:
            steps: n steps.

        Returns:
            (n, d) standardized features.
        """
        return self.encode_raw(raw_features(steps))

    def decode(self, z: np.ndarray, side) -> StepBatch:
        """Decode standardized features to steps.

        Args:
            z: (n, d) or (d,) standardized features.
            side: (n,) or one value, as :func:`batch_from_raw`.

        Returns:
            The decoded :class:`StepBatch` (durations clipped to >= MIN_DURATION).
        """
        z = np.atleast_2d(np.asarray(z, dtype=float))
        if z.shape[1] != self.n_components:
            raise MjwalkError(
                f"decode: features have {z.shape[1]} dimensions, the model has {self.n_components}"
            )
        return batch_from_raw(self.decode_raw(z), side, z)

    def scaled(self, factor: np.ndarray) -> StepFeatures:
        """The same chain with every decoded raw feature multiplied by ``factor``.

        ``decode`` of the result is ``factor`` times this chain's decode, and ``encode`` of
        scaled raw features gives back the same z: scaling the first z-score's mean and scale
        by ``factor`` is all it takes (the PCA and the final scaler act on z-scored values).
        The model space (the KDEs, the transition GPs) is untouched; see
        :func:`raw_scale_factors` and :meth:`mjwalk.gait.model.StepModel.for_walker`.

        Args:
            factor: (N_RAW,) positive finite factors.

        Returns:
            A new chain.
        """
        f = np.asarray(factor, dtype=float)
        if f.shape != (N_RAW,) or not np.all(np.isfinite(f)) or np.any(f <= 0):
            raise MjwalkError(f"StepFeatures.scaled: need {N_RAW} positive finite factors")
        return StepFeatures(
            raw_mean=self.raw_mean * f,
            raw_scale=self.raw_scale * f,
            pca_mean=self.pca_mean,
            components=self.components,
            explained_variance_ratio=self.explained_variance_ratio,
            z_mean=self.z_mean,
            z_scale=self.z_scale,
        )

    def arrays(self, prefix: str = "feat_") -> dict[str, np.ndarray]:
        """The fitted parameters as named arrays (for saving).

        Args:
            prefix: prepended to each field name.

        Returns:
            ``{prefix + field: array}`` for the 7 fitted fields.
        """
        return {
            f"{prefix}{k}": getattr(self, k)
            for k in (
                "raw_mean",
                "raw_scale",
                "pca_mean",
                "components",
                "explained_variance_ratio",
                "z_mean",
                "z_scale",
            )
        }

    @classmethod
    def from_arrays(cls, data, prefix: str = "feat_") -> StepFeatures:
        """Inverse of :meth:`arrays`.

        Args:
            data: mapping (dict or npz) holding the ``prefix``-named arrays.
            prefix: the prefix used by :meth:`arrays`.

        Returns:
            The chain.
        """
        return cls(
            **{
                k[len(prefix) :]: np.asarray(data[k], dtype=float)
                for k in data
                if k.startswith(prefix)
            }
        )


def raw_scale_factors(lateral: float, forward: float, time: float) -> np.ndarray:
    """Factors that stretch a step in its local frame (for :meth:`StepFeatures.scaled`).

    ``lateral`` multiplies every x (to the walker's right: pelvis landmarks, footprint, stance
    foot), ``forward`` every y, ``time`` the duration; yaws stay. Both frames' axes are the
    step's own (x right, y forward), so the stretch is well defined for every step, turning
    ones included.

    Args:
        lateral: factor on x coordinates.
        forward: factor on y coordinates.
        time: factor on the duration.

    Returns:
        (N_RAW,) factors.
    """
    f = np.ones(N_RAW)
    f[_SL_XY][0::2] = lateral
    f[_SL_XY][1::2] = forward
    f[I_DUR] = time
    for sl in (_SL_FOOT, _SL_STANCE):
        f[sl.start] = lateral
        f[sl.start + 1] = forward
    return f


def _as_raw(steps_or_raw) -> np.ndarray:
    if isinstance(steps_or_raw, np.ndarray):
        raw = np.asarray(steps_or_raw, dtype=float)
        if raw.ndim != 2 or raw.shape[1] != N_RAW:
            raise MjwalkError(f"raw features must be (n, {N_RAW}), got {raw.shape}")
        return raw
    return raw_features(steps_or_raw)


def concat_batches(batches: Sequence[StepBatch]) -> StepBatch:
    """Concatenate step batches row-wise.

    Args:
        batches: batches with the same feature dimension d.

    Returns:
        One batch of all rows, in order.
    """
    return StepBatch(
        **{
            k: np.concatenate([getattr(b, k) for b in batches])
            for k in (
                "side",
                "features",
                "landmarks",
                "yaw_landmarks",
                "duration",
                "footprint",
                "stance",
            )
        }
    )
