"""Successor draws of a :class:`~mjwalk.gait.transition.TransitionGP`, compiled
(:mod:`mjwalk._jit`).

The planner draws ten successors of one to a few predecessors at a time, thousands of times per
second; as NumPy calls the draw is a dozen small operations whose overhead outweighs their
arithmetic. These loops do the same arithmetic in the same order and take their random numbers
from the caller's ``numpy.random.Generator`` in the order NumPy code would (all pool choices,
then all pool members, then all normal deviates), so :meth:`TransitionGP.sample` gives the
draws it gave as NumPy code (to rounding; ``tests/gait/test_model.py`` compares with a NumPy
reference).

x (p, d) are predecessor features; ``gp`` is the tuple :attr:`TransitionGP.kernel` folds in
``__post_init__``: ``neg_zs_t`` (d, m) = -(Z/ℓ²)ᵀ; ``half_zs2`` (m,) = |Z/ℓ|²/2;
``half_inv_l2`` (d,) = 1/(2ℓ²); ``c_alpha`` (m, d) = C·α; ``c2_w`` (m, m) = C²·W and its
:func:`pack_upper`; C; ``pool`` (m·k, d) the residual pools flattened, k residuals per inducing
input; k; ``var_cap`` an upper bound of every variance
(:func:`mjwalk.gait.transition.variance_cap`). :func:`sample` is :func:`draw_parts` (all but the
variance, all the random numbers), :func:`variance` and :func:`compose`, so a caller that can
do without the variance skips it (:func:`mjwalk.plan.search.search`'s closing draws).
The search draws thousands of times per walk, one predecessor at a time: it keeps one set of
work arrays (:func:`new_work`) and draws into its own node arrays (:func:`sample_into`,
:func:`draw_parts_into`, :func:`compose_into`), the same loops without a dozen small
allocations per draw.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk._jit import njit, njit_sum


def pack_upper(w: np.ndarray) -> np.ndarray:
    """The upper triangle of the symmetric ``w``, row by row, off-diagonal entries doubled:
    Σ_i e_i Σ_{j>=i} P_ij e_j = e W eᵀ, reading half of W (which does not fit a core's
    cache at m = 400; the default model has m = 200).

    Args:
        w: (m, m) symmetric matrix.

    Returns:
        (m(m+1)/2,) packed entries P.
    """
    i, j = np.triu_indices(w.shape[0])  # row by row
    return np.where(i == j, 1.0, 2.0) * w[i, j]


@njit_sum
def _quadratic_packed(e, packed):
    """e W eᵀ per row of e (p, m) through :func:`pack_upper` (half of W's memory traffic).
    Sums may be reassociated (:data:`mjwalk._jit.njit_sum`), as BLAS reassociates them."""
    p, m = e.shape
    out = np.zeros(p)
    s = 0
    for i in range(m):
        n = m - i
        for r in range(p):
            acc = 0.0
            for j in range(n):
                acc += packed[s + j] * e[r, i + j]
            out[r] += e[r, i] * acc
        s += n
    return out


@njit
def _quadratic(e, c2_w, packed):
    """e W eᵀ per row of e (p, m): packed for one or two rows, as one matrix product (BLAS,
    which reads W once for all rows) for more."""
    if e.shape[0] <= 2:
        return _quadratic_packed(e, packed)
    ew = np.dot(e, c2_w)
    out = np.empty(e.shape[0])
    for r in range(e.shape[0]):
        s = 0.0
        for j in range(e.shape[1]):
            s += ew[r, j] * e[r, j]
        out[r] = s
    return out


@njit
def moments(x, gp):
    """Posterior mean, latent variance and half squared scaled distances to the inducing inputs.

    h_ij = |x_i/ℓ - z_j/ℓ|²/2 (clipped at 0), kernel rows C·exp(-h);
    mean_i = Σ_j exp(-h_ij) (C·α)_j, var_i = C - e_i (C²·W) e_iᵀ with e_i = exp(-h_i).

    Args:
        x: (p, d) predecessor features.
        gp: :attr:`TransitionGP.kernel`.

    Returns:
        (mean (p, d), var (p,) not clipped at 0, h (p, m)).
    """
    mean, var, h, _ = _moments(x, gp)
    return mean, var, h


@njit
def _moments(x, gp):
    """:func:`moments` and exp(-h) (p, m)."""
    mean, h, e = _kernel_rows(x, gp)
    return mean, variance(e, gp), h, e


@njit
def _kernel_rows(x, gp):
    """The posterior mean (p, d), h (p, m) and exp(-h) (p, m) of :func:`moments`: all of it
    but the variance."""
    p = x.shape[0]
    m = gp[1].shape[0]
    h = np.empty((p, m))
    e = np.empty((p, m))
    mean = np.empty((p, gp[3].shape[1]))
    _kernel_rows_into(x, gp, mean, h, e)
    return mean, h, e


@njit
def _kernel_rows_into(x, gp, mean, h, e):
    """:func:`_kernel_rows` into ``mean`` (p, d), ``h`` and ``e`` (p, m each)."""
    half_sq_into(x, gp, h)
    exp_rows_into(gp, h, mean, e)


@njit
def half_sq_into(x, gp, h):
    """h_ij = |x_i/ℓ - z_j/ℓ|²/2 (clipped at 0) of :func:`moments` into ``h`` (p, m).

    Args:
        x: (p, d) predecessor features.
        gp: :attr:`TransitionGP.kernel`.
        h: (p, m) takes h.
    """
    neg_zs_t, half_zs2, half_inv_l2 = gp[:3]
    p, d = x.shape
    m = half_zs2.shape[0]
    for i in range(p):
        xx = 0.0
        for a in range(d):
            xx += x[i, a] * half_inv_l2[a] * x[i, a]
        # the cross terms x·(-z_j/ℓ²) summed over a in order for all j at once (vectorized)
        hi = h[i]
        hi[:] = 0.0
        for a in range(d):
            xa = x[i, a]
            row = neg_zs_t[a]
            for j in range(m):
                hi[j] += xa * row[j]
        for j in range(m):
            v = hi[j] + half_zs2[j] + xx
            if v < 0.0:
                v = 0.0
            hi[j] = v


@njit
def exp_rows_into(gp, h, mean, e):
    """The kernel rows exp(-h) into ``e`` and the posterior mean into ``mean`` (p, d) of
    :func:`half_sq_into`'s ``h`` (p, m).

    Args:
        gp: :attr:`TransitionGP.kernel`.
        h: (p, m) half squared scaled distances.
        mean: (p, d) takes the posterior mean.
        e: (p, m) takes exp(-h).
    """
    c_alpha = gp[3]
    p, m = h.shape
    for i in range(p):
        for a in range(c_alpha.shape[1]):
            mean[i, a] = 0.0
        for j in range(m):
            ej = math.exp(-h[i, j])
            e[i, j] = ej
            for a in range(c_alpha.shape[1]):
                mean[i, a] += ej * c_alpha[j, a]


@njit
def variance(e, gp):
    """The latent variance C - e (C²·W) eᵀ (p,) (not clipped at 0) of the kernel rows
    exp(-h) ``e`` (p, m): the dense quadratic form, most of a draw's arithmetic.

    Args:
        e: (p, m) exp(-h) of :func:`draw_parts`.
        gp: :attr:`TransitionGP.kernel`.
    """
    return gp[6] - _quadratic(e, gp[4], gp[5])


@njit
def sample(x, n, rng, gp, sharp):
    """Successors y = μ(x) + √v(x)·ε + r of each predecessor x[i].

    r is from the pool of inducing input j, drawn with probability
    ∝ exp(-sharp·(h_j - min h)) = (k_j/max k)^sharp (the power for a whole sharpness: equal to
    rounding, so a choice could only differ where the uniform number falls within a few
    roundings of a boundary between two inducing inputs), and a uniform member of it;
    ε standard normal. :func:`draw_parts`, :func:`variance` and :func:`compose`.

    Args:
        x: (p, d) predecessor features.
        n: successors per predecessor.
        rng: ``numpy.random.Generator``: p·n uniforms, p·n integers, then p·n·d normals.
        gp: :attr:`TransitionGP.kernel`.
        sharp: sharpness of the pool choice (>= 0; 0: uniform over the inducing inputs).

    Returns:
        (p, n, d) successor features.
    """
    mean, e, rows, eps = draw_parts(x, n, rng, gp, sharp)
    return compose(mean, variance(e, gp), rows, eps, n, gp[7])


@njit
def draw_parts(x, n, rng, gp, sharp):
    """Everything of :func:`sample` but the variance, which the random numbers do not depend
    on: the posterior mean (p, d), exp(-h) (p, m), each successor's residual row of the
    flattened pools (p·n,) and its normal deviates (p·n·d,), drawn from ``rng`` as
    :func:`sample` draws them.

    Args:
        x: (p, d) predecessor features.
        n: successors per predecessor.
        rng: ``numpy.random.Generator``: p·n uniforms, p·n integers, then p·n·d normals.
        gp: :attr:`TransitionGP.kernel`.
        sharp: sharpness of the pool choice (as for :func:`sample`).
    """
    work = new_work(x.shape[0], gp)
    rows = np.empty(x.shape[0] * n, dtype=np.intp)
    eps = draw_parts_into(x, n, rng, gp, sharp, work, rows)
    return work[0], work[2], rows, eps


@njit
def new_work(p, gp):
    """Work arrays for :func:`draw_parts_into` and :func:`sample_into`: draws of ``p``
    predecessors by the GP ``gp`` (:attr:`TransitionGP.kernel`; m inducing inputs, d
    features).

    Args:
        p: predecessors per draw.
        gp: :attr:`TransitionGP.kernel`.

    Returns:
        (mean (p, d), h (p, m), exp(-h) (p, m), two (m,) rows for the pool weights).
    """
    m = gp[1].shape[0]
    return (
        np.empty((p, gp[3].shape[1])),
        np.empty((p, m)),
        np.empty((p, m)),
        np.empty(m),
        np.empty(m),
    )


@njit
def draw_parts_into(x, n, rng, gp, sharp, work, rows):
    """:func:`draw_parts` into the work arrays ``work`` (:func:`new_work` of x's p rows and
    ``gp``) and ``rows`` (at least p·n): afterwards ``work[0]`` is the posterior mean and
    ``work[2]`` exp(-h); returns the normal deviates (p·n·d,), drawn from ``rng`` as
    :func:`draw_parts` draws them.

    Args:
        x: (p, d) predecessor features.
        n: successors per predecessor.
        rng: ``numpy.random.Generator``.
        gp: :attr:`TransitionGP.kernel`.
        sharp: sharpness of the pool choice (as for :func:`sample`).
        work: :func:`new_work`'s arrays.
        rows: (>= p·n,) int, takes each successor's residual row of the flattened pools.
    """
    mean, h, e = work[:3]
    _kernel_rows_into(x, gp, mean, h, e)
    u, member, eps = draw_numbers(rng, x.shape[0], n, gp)
    choose_rows(h, e, u, member, n, gp, sharp, work, rows)
    return eps


@njit
def draw_numbers(rng, p, n, gp):
    """The random numbers of a draw of ``n`` successors of ``p`` predecessors by ``gp``, drawn
    from ``rng`` in :func:`sample`'s order: p·n uniforms (the pool choices), p·n pool members,
    p·n·d standard normal deviates.

    Args:
        rng: ``numpy.random.Generator``.
        p: predecessors.
        n: successors per predecessor.
        gp: :attr:`TransitionGP.kernel` (its pools' size k and features d).

    Returns:
        (u (p·n,), member (p·n,) int in [0, k), eps (p·n·d,)).
    """
    u = rng.random(p * n)
    member = rng.integers(0, gp[8], p * n)
    return u, member, rng.standard_normal(p * n * gp[7].shape[1])


@njit
def choose_rows(h, e, u, member, n, gp, sharp, work, rows):
    """Each successor's residual row of the flattened pools into ``rows`` (p·n,): the pool of
    inducing input j with probability ∝ exp(-sharp·(h_j - min h)) (:func:`sample`) at the
    uniform number ``u``, its member ``member``.

    Args:
        h: (p, m) half squared scaled distances.
        e: (p, m) exp(-h).
        u: (p·n,) uniforms.
        member: (p·n,) pool members.
        n: successors per predecessor.
        gp: :attr:`TransitionGP.kernel`.
        sharp: sharpness of the pool choice (as for :func:`sample`).
        work: :func:`new_work`'s arrays (its two (m,) rows).
        rows: (>= p·n,) takes the rows.
    """
    k = gp[8]
    p, m = h.shape
    c, sq = work[3], work[4]
    # a whole sharpness (up to 64): the weights are that power of exp(-h) over its largest
    # value, by multiplications, instead of a second exp per inducing input
    power = int(sharp) if sharp == math.floor(sharp) and 1.0 <= sharp <= 64.0 else 0
    for i in range(p):
        lo = h[i, 0]
        near = 0
        for j in range(1, m):
            if h[i, j] < lo:
                lo = h[i, j]
                near = j
        if power > 0 and lo < 600.0:
            # exp(-sharp·(h_j - lo)) = (e_j / e_near)^sharp to a few roundings (e_near is a
            # normal number here; an e_j that underflows gives a weight of 0 either way)
            # (repeated squaring, x^power = product of x^(2^k) over power's set bits, on the
            # whole row at once so it vectorizes)
            top = 1.0 / e[i, near]
            for j in range(m):
                sq[j] = e[i, j] * top
                c[j] = 1.0
            b = power
            while True:
                if b & 1:
                    for j in range(m):
                        c[j] *= sq[j]
                b >>= 1
                if b == 0:
                    break
                for j in range(m):
                    sq[j] *= sq[j]
        else:
            for j in range(m):
                c[j] = math.exp(-sharp * (h[i, j] - lo))
        acc = 0.0
        for j in range(m):
            acc += c[j]
            c[j] = acc
        for r in range(n):
            # the first j with c_j >= u (u <= c_{m-1}: never past the last)
            rows[i * n + r] = k * np.searchsorted(c, u[i * n + r] * acc) + member[i * n + r]


@njit
def compose(mean, var, rows, eps, n, pool):
    """The successors eps·√max(v, 0) + μ + r (p, n, d) of :func:`draw_parts`' mean, rows and
    deviates, with the variances ``var`` (p,).

    Args:
        mean: (p, d) posterior means.
        var: (p,) latent variances.
        rows: (p·n,) residual rows of ``pool``.
        eps: (p·n·d,) normal deviates.
        n: successors per predecessor.
        pool: (m·k, d) the flattened residual pools.
    """
    p, d = mean.shape
    out = np.empty((p, n, d))
    for i in range(p):
        sd = math.sqrt(max(var[i], 0.0))
        for r in range(n):
            q = i * n + r
            row = rows[q]
            for a in range(d):
                out[i, r, a] = eps[q * d + a] * sd + mean[i, a] + pool[row, a]
    return out


@njit
def compose_into(mean, var, rows, eps, n, pool, out, o0):
    """:func:`compose` for one predecessor (``mean`` (1, d)) with the variance ``var`` (a
    float) into the rows ``o0`` .. ``o0`` + n - 1 of ``out`` (.., d).

    Args:
        mean: (1, d) the posterior mean.
        var: the latent variance.
        rows: (>= n,) residual rows of ``pool``.
        eps: (n·d,) normal deviates.
        n: successors.
        pool: (m·k, d) the flattened residual pools.
        out: (>= o0 + n, d) takes the successors.
        o0: the first row of ``out`` taken.
    """
    d = mean.shape[1]
    sd = math.sqrt(max(var, 0.0))
    for r in range(n):
        row = rows[r]
        for a in range(d):
            out[o0 + r, a] = eps[r * d + a] * sd + mean[0, a] + pool[row, a]


@njit
def sample_into(x, n, rng, gp, sharp, work, rows, out, o0):
    """:func:`sample` of one predecessor ``x`` (1, d) into the rows ``o0`` .. ``o0`` + n - 1
    of ``out``, with the work arrays ``work`` (:func:`new_work`) and ``rows`` (>= n): the same
    numbers, drawn from ``rng`` as :func:`sample` draws them.

    Args:
        x: (1, d) the predecessor's features.
        n: successors.
        rng: ``numpy.random.Generator``.
        gp: :attr:`TransitionGP.kernel`.
        sharp: sharpness of the pool choice (as for :func:`sample`).
        work: :func:`new_work` of 1 predecessor and ``gp``.
        rows: (>= n,) int work array.
        out: (>= o0 + n, d) takes the successors.
        o0: the first row of ``out`` taken.
    """
    eps = draw_parts_into(x, n, rng, gp, sharp, work, rows)
    compose_into(work[0], variance(work[2], gp)[0], rows, eps, n, gp[7], out, o0)
