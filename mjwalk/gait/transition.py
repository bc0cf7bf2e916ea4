"""The transition Gaussian process of the step model (agethen2018 §4.1): from a step's
standardized features to its successor's, a DTC (projected-process) predictor with local
empirical residual pools. The scheme (hyper-parameters on a subset, k-means inducing inputs,
the DTC posterior on all pairs, residual pools per inducing input) and why is in
:mod:`mjwalk.gait.model`'s module docstring, steps 1-4; draws are compiled in
:mod:`mjwalk.gait.gpdraw`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
from scipy.linalg import cho_solve, cholesky, solve_triangular

from mjwalk.errors import MjwalkError
from mjwalk.gait import gpdraw

#: Sharpness of the choice of residual pool (module doc, step 4): inducing input j is drawn
#: with probability ∝ k(x, z_j)^POOL_SHARPNESS: sharp enough not to mix the gait regimes
#: (proportional to k does), soft enough that sharp turns find residuals (the nearest pool alone
#: does not) (docs/decisions/008-transition-gp-size.md).
POOL_SHARPNESS = 10.0
#: Inducing inputs per transition GP (module doc of :mod:`mjwalk.gait.model`, step 2). A draw's
#: latent variance is an m x m quadratic form (:func:`mjwalk.gait.gpdraw._quadratic`), about
#: half of a planner expansion's time at m = 400; 200 keep the DTC's own error around 1-2 % of
#: the noise variance and the walks' statistics those of 400, at about 1.6x the planner's speed
#: (docs/decisions/008-transition-gp-size.md).
N_INDUCING = 200


def variance_cap(c2_w: np.ndarray, signal_var: float) -> float:
    """An upper bound of every latent variance C - e (C²·W) eᵀ that
    :func:`mjwalk.gait.gpdraw.variance` computes, for any kernel row e in [0, 1]^m.

    C²·W's least eigenvalue bounds e W eᵀ >= λ_min·|e|² >= min(λ_min, 0)·m; for λ_min a lower
    bound from a successful Cholesky factorisation (its backward error: RᵀR = A + ΔA with
    |ΔA| <= γ_(m+1)·|Rᵀ||R|, Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed.
    2002, Thm 10.3, so λ_min(A) >= -γ_(m+1)·‖R‖_F²), else from the symmetric eigenvalues less
    m·u·‖A‖_F. The computed quadratic form is within γ_(2m)·Σ|A_ij| of its exact value
    (ibid. §3.1; the packed and BLAS sums alike, reassociated or not), which the bound adds,
    doubled. The default model's forms are positive definite: the cap is C plus about 1e-6.

    Args:
        c2_w: (m, m) the symmetric C²·W.
        signal_var: the signal variance C.

    Returns:
        The cap on the variance (same units as C).
    """
    m = c2_w.shape[0]
    unit = 2.0**-53
    try:
        r = np.linalg.cholesky(c2_w)
        lowest = -1.01 * ((m + 1) * unit / (1 - (m + 1) * unit)) * float(np.sum(r * r))
    except np.linalg.LinAlgError:
        lowest = float(np.linalg.eigvalsh(c2_w)[0]) - 4 * m * unit * float(np.linalg.norm(c2_w))
    rounding = 2.0 * (2 * m * unit / (1 - 2 * m * unit)) * float(np.abs(c2_w).sum())
    return (signal_var + m * max(-lowest, 0.0) + rounding) * (1.0 + 1e-9)


@dataclass
class TransitionGP:
    """DTC (projected-process) GP predictor from predecessor to successor features.

    Attributes:
        inducing: (m, d) inducing inputs (k-means centres), standardized features.
        alpha: (m, d) so that the posterior mean is ``k(x, Z) @ alpha``.
        w: (m, m) ``K_mm⁻¹ - Σ``; latent variance = C - k W kᵀ.
        length_scale: (d,) RBF length scales; signal_var C; noise_var σ² (White kernel).
        res_pool: (m, k, d) residual pool of every inducing input: the residuals y - μ(x) of
            the k training pairs whose predecessors are nearest to it (module doc, step 4).
        n_pairs: pairs the posterior is conditioned on; n_hyper: pairs used for the LML fit;
        lml: log-marginal likelihood of the hyper-parameters on the subset.
        nystrom: mean Nyström residual C - k(x, Z) K_mm⁻¹ k(Z, x) over the training
            predecessors as a share of the noise variance σ²: how much of the signal the
            inducing inputs cannot represent (the DTC's approximation error; Rasmussen &
            Williams 2006, §8.3); NaN for a model saved before it was recorded.
    """

    inducing: np.ndarray
    alpha: np.ndarray
    w: np.ndarray
    length_scale: np.ndarray
    signal_var: float
    noise_var: float
    res_pool: np.ndarray
    n_pairs: int
    n_hyper: int
    lml: float
    nystrom: float = float("nan")

    def __post_init__(self) -> None:
        self._zs = self.inducing / self.length_scale
        self._zs2 = np.einsum("md,md->m", self._zs, self._zs)
        # For sample(), with the constants folded in: half squared distances
        # x·(x/2ℓ²) + (-z/ℓ²)·x + z·(z/2ℓ²), kernel rows C·e with e = exp(-half), so the mean is
        # e @ (C·alpha) and k W kᵀ = e (C²·W) eᵀ; the residual pools flattened for one gather.
        self._half_inv_l2 = 0.5 / self.length_scale**2
        self._neg_zs_t = np.ascontiguousarray((-self._zs / self.length_scale).T)
        self._half_zs2 = 0.5 * self._zs2
        self._c_alpha = self.signal_var * self.alpha
        self._c2_w = np.ascontiguousarray(self.signal_var**2 * self.w)
        self._pool_flat = np.ascontiguousarray(self.res_pool.reshape(-1, self.res_pool.shape[2]))
        #: the folded arrays as one tuple for the compiled draws (:mod:`mjwalk.gait.gpdraw`)
        self.kernel = (
            np.ascontiguousarray(self._neg_zs_t),
            np.ascontiguousarray(self._half_zs2),
            np.ascontiguousarray(self._half_inv_l2),
            np.ascontiguousarray(self._c_alpha),
            self._c2_w,
            gpdraw.pack_upper(self._c2_w),
            float(self.signal_var),
            self._pool_flat,
            int(self.res_pool.shape[1]),
            variance_cap(self._c2_w, float(self.signal_var)),
        )

    def kernel_rows(self, x: np.ndarray) -> np.ndarray:
        """Signal kernel k(x, z_j) = C·exp(-|x/ℓ - z_j/ℓ|²/2) to the inducing inputs.

        Args:
            x: (P, d) standardized features.

        Returns:
            (P, m) kernel rows.
        """
        xs = x / self.length_scale
        sq = np.einsum("pd,pd->p", xs, xs)[:, None] + self._zs2[None, :] - 2.0 * (xs @ self._zs.T)
        np.maximum(sq, 0.0, out=sq)
        return self.signal_var * np.exp(-0.5 * sq)

    @cached_property
    def _mean_gram(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """αᵀKα (d, d) and Kα (m, d) with K = k(Z, Z), and the same of |α| (the rounding
        bounds of :meth:`mean_reach`)."""
        k = self.kernel_rows(self.inducing)
        ka, kb = k @ self.alpha, k @ np.abs(self.alpha)
        return self.alpha.T @ ka, ka, np.abs(self.alpha).T @ kb, kb

    def mean_reach(self, v: np.ndarray) -> tuple[float, np.ndarray, float]:
        """How far the posterior mean's projection f(x) = μ(x)·v (v (d,) complex, as a
        decoder column) can lie from its value at an inducing input, for any x.

        f(x) = Σ_j k(x, z_j) α_j·v lies in the kernel's reproducing kernel Hilbert space with
        norm² βᵀKβ (β = αv, real and imaginary parts apart), and f(x) - f(z) = <f, k(x, ·) -
        k(z, ·)>, so |f(x) - f(z_j)| <= ‖f‖ ‖k(x, ·) - k(z_j, ·)‖ = ‖f‖ √(2C(1 - e_j)), e_j =
        k(x, z_j)/C (Cauchy-Schwarz; Rasmussen & Williams, *Gaussian Processes for Machine
        Learning*, 2006, §6.1, the reproducing property). The norms are raised by 1e-10 of
        the same sums in absolute values, far more than their roundings.

        Args:
            v: (d,) complex, the projection (a decoder column: metres per unit feature).

        Returns:
            (r, f_z, slack): |f(x) - f(z_j)| <= r·√(2(1 - e_j)) for every x and j; f_z (m,)
            complex, f at the inducing inputs; slack (m) bounds f_z's roundings.
        """
        g, ka, g_abs, kb = self._mean_gram
        tol = 1e-10
        q = 0.0
        for part in (v.real, v.imag):
            q += max(float(part @ g @ part), 0.0) + tol * float(np.abs(part) @ g_abs @ np.abs(part))
        r = math.sqrt(self.signal_var * q) * (1.0 + 1e-9)
        slack = tol * float((kb @ np.abs(v)).max(initial=0.0)) + 1e-12
        return r, ka @ v, slack

    def _predict(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        k = self.kernel_rows(x)
        mean = k @ self.alpha
        var = self.signal_var - np.einsum("pm,pm->p", k @ self.w, k)
        return mean, np.maximum(var, 0.0), k

    def predict(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Posterior mean μ(x) = k(x, Z)·α and latent variance v(x) = C - k W kᵀ (clipped at 0).

        Args:
            x: (P, d) predecessor features (standardized).

        Returns:
            (mean (P, d), variance (P,)).
        """
        mean, var, _ = self._predict(x)
        return mean, var

    def _moments(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`predict`'s mean (P, d) and latent variance (P,) (not clipped at 0) with the
        constants folded in, and the half squared scaled distances h (P, m) to the inducing
        inputs (k = C·exp(-h)); the dense formulas, equal to :meth:`predict`'s to rounding
        (compiled: :func:`mjwalk.gait.gpdraw.moments`)."""
        return gpdraw.moments(np.ascontiguousarray(x, dtype=float), self.kernel)

    def sample(self, x: np.ndarray, n: int, rng: np.random.Generator) -> np.ndarray:
        """n successor draws for each of the P predecessors.

        y = μ(x) + √v(x)·ε + r, r from the residual pool of an inducing input drawn with
        probability ∝ k(x, z_j)^POOL_SHARPNESS (module doc). μ and v are :meth:`predict`'s
        (:meth:`_moments`: the same formulas with the constants folded in, equal to rounding;
        tests/gait/test_model.py checks them); the pool weights are exp(-POOL_SHARPNESS·(h - min h))
        for the half squared scaled distances h, that is (k / max k)^POOL_SHARPNESS without an
        underflow to all-zero weights far from the data. Compiled
        (:func:`mjwalk.gait.gpdraw.sample`); the random numbers are drawn from ``rng`` as
        NumPy would: all pool choices (uniform), all pool members, then all normal deviates.

        Args:
            x: (P, d) predecessor features (standardized).
            n: draws per predecessor.
            rng: the random generator.

        Returns:
            (P, n, d) successor features.
        """
        return gpdraw.sample(
            np.ascontiguousarray(x, dtype=float), int(n), rng, self.kernel, POOL_SHARPNESS
        )

    @classmethod
    def fit(
        cls,
        x: np.ndarray,
        y: np.ndarray,
        *,
        rng: np.random.Generator,
        n_hyper: int = 600,
        n_inducing: int = N_INDUCING,
        n_residual: int | None = None,
    ) -> TransitionGP:
        """Fit on step pairs (standardized features); see module doc.

        Args:
            x: (N, d) predecessor features, N >= 5.
            y: (N, d) successor features.
            rng: draws the hyper-parameter subset and the k-means/GP seed.
            n_hyper: pairs in the subset for the LML fit of the hyper-parameters.
            n_inducing: inducing inputs m (k-means centres; all x when m >= N).
            n_residual: residuals pooled per inducing input; None: ``ceil(N / m)``, at least 5
                (at most N).

        Returns:
            The fitted predictor.

        Raises:
            MjwalkError: with fewer than 5 pairs.
        """
        # deferred: scipy.spatial and sklearn are slow to import and only fitting needs them
        from scipy.spatial import cKDTree
        from sklearn.cluster import KMeans  # deferred: as above

        n, d = x.shape
        if n < 5:
            raise MjwalkError(f"transition GP: need at least 5 step pairs, got {n}")
        seed = int(rng.integers(2**31 - 1))
        sub = rng.choice(n, size=min(n_hyper, n), replace=False)
        c, ls, s2, lml = _hyperparameters(x[sub], y[sub], seed)
        m = min(n_inducing, n)
        if m < n:
            km = KMeans(n_clusters=m, n_init=1, max_iter=50, random_state=seed).fit(x)
            z = km.cluster_centers_
        else:
            z = x.copy()
        proto = cls(
            inducing=z,
            alpha=np.zeros((m, d)),
            w=np.zeros((m, m)),
            length_scale=ls,
            signal_var=c,
            noise_var=s2,
            res_pool=np.zeros((m, 1, d)),
            n_pairs=n,
            n_hyper=len(sub),
            lml=lml,
        )
        proto.alpha, proto.w, nystrom = _dtc_posterior(proto, x, y)
        resid = y - proto.predict(x)[0]
        k_res = min(n, n_residual or max(5, -(-n // m)))
        _, near = cKDTree(x / ls).query(z / ls, k=k_res)
        # a new instance: its constructor derives sample()'s folded arrays from the final ones
        return replace(proto, res_pool=resid[np.asarray(near).reshape(m, k_res)], nystrom=nystrom)

    def arrays(self, prefix: str) -> dict[str, np.ndarray]:
        """The fitted parameters as named arrays (for saving).

        Args:
            prefix: prepended to each name.

        Returns:
            ``inducing``, ``alpha``, ``w``, ``length_scale``, ``res_pool`` and ``scalars``
            (signal_var, noise_var, n_pairs, n_hyper, lml, nystrom), each under ``prefix``.
        """
        return {
            f"{prefix}inducing": self.inducing,
            f"{prefix}alpha": self.alpha,
            f"{prefix}w": self.w,
            f"{prefix}length_scale": self.length_scale,
            f"{prefix}res_pool": self.res_pool,
            f"{prefix}scalars": np.array(
                [
                    self.signal_var,
                    self.noise_var,
                    self.n_pairs,
                    self.n_hyper,
                    self.lml,
                    self.nystrom,
                ]
            ),
        }

    @classmethod
    def from_arrays(cls, data, prefix: str) -> TransitionGP:
        """Inverse of :meth:`arrays` (a missing ``nystrom``, older files, reads as NaN).

        Args:
            data: mapping (dict or npz) holding the ``prefix``-named arrays.
            prefix: the prefix used by :meth:`arrays`.

        Returns:
            The predictor.
        """
        sc = np.asarray(data[f"{prefix}scalars"], dtype=float)
        return cls(
            inducing=np.asarray(data[f"{prefix}inducing"], dtype=float),
            alpha=np.asarray(data[f"{prefix}alpha"], dtype=float),
            w=np.asarray(data[f"{prefix}w"], dtype=float),
            length_scale=np.asarray(data[f"{prefix}length_scale"], dtype=float),
            res_pool=np.asarray(data[f"{prefix}res_pool"], dtype=float),
            signal_var=float(sc[0]),
            noise_var=float(sc[1]),
            n_pairs=int(sc[2]),
            n_hyper=int(sc[3]),
            lml=float(sc[4]),
            nystrom=float(sc[5]) if sc.size > 5 else float("nan"),
        )


def _hyperparameters(
    x: np.ndarray, y: np.ndarray, seed: int
) -> tuple[float, np.ndarray, float, float]:
    """Signal variance C, RBF length scales (d,), noise variance σ² and log-marginal
    likelihood of ``C·RBF + White`` fitted to the pairs ``x`` -> ``y`` (n, d) by maximizing
    the LML (module doc of :mod:`mjwalk.gait.model`, step 1)."""
    # deferred: sklearn is slow to import and only fitting needs it
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.gaussian_process import GaussianProcessRegressor  # deferred: as above
    from sklearn.gaussian_process.kernels import (  # deferred: as above
        RBF,
        ConstantKernel,
        WhiteKernel,
    )

    d = x.shape[1]
    kernel = ConstantKernel(1.0, (1e-2, 1e2)) * RBF(np.full(d, 2.0), (1e-2, 1e3)) + WhiteKernel(
        0.3, (1e-4, 1e1)
    )
    gpr = GaussianProcessRegressor(
        kernel,
        optimizer=_lbfgs,
        normalize_y=False,
        n_restarts_optimizer=0,
        random_state=seed,
    )
    with warnings.catch_warnings():
        # A length scale at its upper bound just means "this input is irrelevant".
        warnings.simplefilter("ignore", ConvergenceWarning)
        gpr.fit(x, y)
    k = gpr.kernel_
    c = float(k.k1.k1.constant_value)
    ls = np.broadcast_to(np.asarray(k.k1.k2.length_scale, dtype=float), (d,)).copy()
    return c, ls, float(k.k2.noise_level), float(gpr.log_marginal_likelihood_value_)


def _dtc_posterior(
    proto: TransitionGP, x: np.ndarray, y: np.ndarray
) -> tuple[np.ndarray, np.ndarray, float]:
    """The DTC posterior's alpha (m, d) and W (m, m) conditioned on all pairs ``x`` -> ``y``
    (N, d), with the hyper-parameters and inducing inputs of ``proto``, and the mean Nyström
    residual as a share of σ² (module doc of :mod:`mjwalk.gait.model`, step 3)."""
    z, c, s2 = proto.inducing, proto.signal_var, proto.noise_var
    m = z.shape[0]
    kmm = proto.kernel_rows(z)
    kmm[np.diag_indices(m)] += 1e-6 * c
    lmm = cholesky(kmm, lower=True)
    # V = L⁻¹ K_mn in chunks of rows of x (memory: m × N).
    v = solve_triangular(lmm, proto.kernel_rows(x).T, lower=True)
    nystrom = float(np.mean(c - np.einsum("mn,mn->n", v, v)) / s2)
    b = np.eye(m) + (v @ v.T) / s2
    lb = cholesky(b, lower=True)
    # alpha = L⁻ᵀ B⁻¹ V Y / σ²
    alpha = solve_triangular(lmm.T, cho_solve((lb, True), v @ y), lower=False) / s2
    # W = K_mm⁻¹ - Σ = L⁻ᵀ (I - B⁻¹) L⁻¹
    linv = solve_triangular(lmm, np.eye(m), lower=True)
    w = linv.T @ (np.eye(m) - cho_solve((lb, True), np.eye(m))) @ linv
    return alpha, 0.5 * (w + w.T), nystrom


def _lbfgs(obj_func, initial_theta, bounds):
    """L-BFGS-B on the negative LML (as sklearn's default) with a bounded iteration budget."""
    from scipy.optimize import minimize  # deferred: slow to import, only fitting needs it

    res = minimize(
        obj_func,
        initial_theta,
        method="L-BFGS-B",
        jac=True,
        bounds=bounds,
        options={"maxiter": 80},
    )
    return res.x, res.fun
