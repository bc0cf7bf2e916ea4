"""DCSNetwork (mjwalk.arms.dcs), alone and on real raise-hand capture."""

import os
from pathlib import Path

import numpy as np
import pytest

from mjwalk.arms.armrep import ArmRepresentation, trajectory_error
from mjwalk.arms.dcs import DCSNetwork
from mjwalk.arms.dcsfile import DCS_VERSION
from mjwalk.arms.dcsfit import features, forward, output_form, solve_outputs, split_outputs
from mjwalk.errors import MjwalkError, ModelFileError

#: real capture: ``$MJWALK_SHARED_DATA`` or ../shared/data beside the project
DATA = (
    Path(os.environ.get("MJWALK_SHARED_DATA", Path(__file__).parents[3] / "shared" / "data"))
    / "bandai-raise-hand"
)


def _toy(n, seed):
    rng = np.random.default_rng(seed)
    X = rng.uniform(-1, 1, (n, 2))
    Y = np.c_[np.sin(2 * X[:, 0]) + X[:, 1] ** 2, np.cos(X[:, 1])]
    return X, Y


def test_dcs_learns_smooth_map_and_beats_mean():
    X, Y = _toy(200, 1)
    Xt, Yt = _toy(400, 2)
    net = DCSNetwork(rng=0).fit(X, Y)
    rmse = np.sqrt(((net.predict(Xt) - Yt) ** 2).sum(1).mean())
    base = np.sqrt(((Yt - Y.mean(0)) ** 2).sum(1).mean())
    # seeded: held-out RMSE well below the constant predictor (0.84); measured 0.16
    assert rmse < 0.3 * base
    assert 3 <= net.n_neurons_ <= net.options.max_neurons
    assert net.edges_.shape == (net.n_neurons_,) * 2
    assert (net.edges_ == net.edges_.T).all() and not net.edges_.diagonal().any()


def test_dcs_output_is_normalized_rbf_over_winner_and_neighbours():
    X, Y = _toy(120, 3)
    net = DCSNetwork(rng=1).fit(X, Y)
    x = np.array([0.1, -0.2])
    z = (x - net.x_mean_) / net.x_scale_
    d = np.linalg.norm(net.centers_ - z, axis=1)
    w = int(np.argmin(d))
    act = [*np.flatnonzero(net.edges_[w]).tolist(), w]
    h = np.exp(-0.5 * (d[act] / net.widths_[act]) ** 2)
    expected = (h[:, None] * net.outputs_[act]).sum(0) / h.sum()
    np.testing.assert_allclose(net.predict(x[None])[0], expected, rtol=1e-10)


def test_dcs_deterministic_size_limit_and_growth_stop():
    X, Y = _toy(150, 4)
    a = DCSNetwork(rng=5).fit(X, Y).predict(X)
    b = DCSNetwork(rng=5).fit(X, Y).predict(X)
    np.testing.assert_array_equal(a, b)
    assert DCSNetwork(max_neurons=4, validation_fraction=0).fit(X, Y).n_neurons_ == 4
    net = DCSNetwork(error_threshold=10.0, validation_fraction=0).fit(X, Y)
    assert net.n_neurons_ == 2  # threshold met at once


def test_dcs_global_scaling_ignores_a_near_constant_noise_column():
    # y depends on x0 (spread 1 m); x1 is 1 cm of noise. Per-column standardization blows the
    # noise up to the weight of x0; one global scale keeps distances in metres.
    rng = np.random.default_rng(7)

    def data(n):
        x0 = rng.uniform(-1, 1, n)
        X = np.c_[x0, rng.normal(0, 0.01, n)]
        return X, np.sin(3 * x0)

    X, Y = data(150)
    Xt, Yt = data(300)
    col = DCSNetwork(rng=0).fit(X, Y)
    glob = DCSNetwork(rng=0, scaling="global").fit(X, Y)
    assert glob.x_scale_[0] == glob.x_scale_[1]
    e_col = np.sqrt(((col.predict(Xt) - Yt) ** 2).mean())
    e_glob = np.sqrt(((glob.predict(Xt) - Yt) ** 2).mean())
    # seeded: measured e_glob 0.04 (18 neurons), e_col 0.31 (4 neurons); sd of y 0.73
    assert e_glob < 0.1 < 0.5 * e_col
    with pytest.raises(MjwalkError, match="scaling"):
        DCSNetwork(scaling="minmax").fit(X, Y)


def test_dcs_point_scaling_grid_weighs_points_as_the_data_need(tmp_path):
    # two 3-D points: a (spread 2 cm) and b (spread 30 cm). One global scale sees b alone;
    # one scale per point weighs them alike. The grid ("global", "point") is chosen by PRESS.
    rng = np.random.default_rng(11)

    def data(n, on_a):
        a, b = rng.normal(0, 0.02, (n, 3)), rng.normal(0, 0.3, (n, 3))
        y = np.sin(40 * a[:, 0]) if on_a else np.sin(3 * b[:, 0])
        return np.c_[a, b], y

    def rmse(net, X, Y):
        return float(np.sqrt(((net.predict(X) - Y) ** 2).mean()))

    kw = {"rng": 0, "selection": "loo", "max_neurons": 40}
    for on_a, expect in ((True, "point"), (False, "global")):
        X, Y = data(200, on_a)
        Xt, Yt = data(400, on_a)
        nets = {s: DCSNetwork(**kw, scaling=s).fit(X, Y) for s in ("global", "point")}
        grid = DCSNetwork(**kw, scaling=("global", "point")).fit(X, Y)
        point = nets["point"].x_scale_
        assert point[0] == point[2] != point[3] == point[5]
        errs = {s: rmse(n, Xt, Yt) for s, n in nets.items()}
        other = "global" if expect == "point" else "point"
        # seeded: measured on a: point 0.26, global 0.60 (sd of y 0.60: b's spread swamps
        # a); on b: global 0.20, point 0.41 (a's noise weighs as much as b)
        assert errs[expect] < 0.7 * errs[other]
        assert grid.scaling_ == expect
        assert grid.selection_score_ == min(n.selection_score_ for n in nets.values())
        np.testing.assert_allclose(grid.predict(Xt), nets[expect].predict(Xt))
    # the averaged networks and the trend network take the chosen scaling; it is saved
    both = DCSNetwork(**kw, scaling=("global", "point"), n_networks=2, trend_fallback=True)
    both.fit(*data(200, True))
    assert both.scaling_ == "point"
    for sub in (both.members_[0], both.fallback_):
        assert sub.scaling_ == "point"
        np.testing.assert_allclose(sub.x_scale_, both.x_scale_)
    both.save(tmp_path / "p.npz")
    back = DCSNetwork.load(tmp_path / "p.npz")
    assert back.scaling_ == "point"
    np.testing.assert_allclose(back.predict(Xt), both.predict(Xt))
    with pytest.raises(MjwalkError, match="3-D points"):
        DCSNetwork(scaling="point").fit(np.zeros((10, 4)) + np.arange(10)[:, None], np.ones(10))
    with pytest.raises(MjwalkError, match="scaling"):
        DCSNetwork(scaling=("global", "minmax")).fit(X, Y)


def test_dcs_width_and_ridge_grids_are_chosen_on_held_out_part(tmp_path):
    X, Y = _toy(150, 8)
    Xt, Yt = _toy(300, 9)
    grid = DCSNetwork(rng=0, width_factor=(0.5, 1.0, 2.0), ridge=(1e-6, 0.1, 1.0))
    grid.fit(X, Y)
    assert grid.width_factor_ in (0.5, 1.0, 2.0) and grid.ridge_ in (1e-6, 0.1, 1.0)
    # the chosen pair is no worse on fresh data than the worst fixed pair of the grid
    fixed = [
        DCSNetwork(rng=0, width_factor=w, ridge=r).fit(X, Y)
        for w in (0.5, 2.0)
        for r in (1e-6, 1.0)
    ]

    def rmse(net):
        return np.sqrt(((net.predict(Xt) - Yt) ** 2).sum(1).mean())

    assert rmse(grid) <= max(rmse(n) for n in fixed)
    grid.save(tmp_path / "g.npz")
    back = DCSNetwork.load(tmp_path / "g.npz")
    np.testing.assert_allclose(back.predict(Xt), grid.predict(Xt))
    assert back.width_factor_ == grid.width_factor_
    with pytest.raises(MjwalkError, match="width_factor"):
        DCSNetwork(width_factor=(0.0, 1.0)).fit(X, Y)
    with pytest.raises(MjwalkError, match="ridge"):
        DCSNetwork(ridge=-1.0).fit(X, Y)


def test_dcs_distance_to_training_flags_extrapolation():
    X, Y = _toy(100, 5)
    net = DCSNetwork(rng=0).fit(X, Y)
    d = net.distance_to_training(np.array([[0.0, 0.0], [6.0, 6.0]]))
    assert d[0] < net.range_radius_ < d[1]
    assert net.is_outside(np.array([[6.0, 6.0]]))[0]


def test_dcs_save_load_roundtrip_and_bad_files(tmp_path):
    X, Y = _toy(80, 6)
    net = DCSNetwork(rng=0).fit(X, Y[:, 0])
    path = tmp_path / "net.npz"
    net.save(path)
    back = DCSNetwork.load(path)
    np.testing.assert_allclose(back.predict(X), net.predict(X))
    assert back.predict(X).ndim == 1
    (tmp_path / "bad.npz").write_bytes(b"not a zip")
    with pytest.raises(ModelFileError, match=r"bad\.npz"):
        DCSNetwork.load(tmp_path / "bad.npz")
    with np.load(path) as z:
        data = dict(z)
    header = str(data["header"])
    assert f'"version": {DCS_VERSION}' in header
    data["header"] = np.array(header.replace(f'"version": {DCS_VERSION}', '"version": 99'))
    np.savez(tmp_path / "v99.npz", **data)
    # a version 1 file (before the global linear term) still loads
    data["header"] = np.array(header.replace(f'"version": {DCS_VERSION}', '"version": 1'))
    np.savez(tmp_path / "v1.npz", **data)
    np.testing.assert_allclose(DCSNetwork.load(tmp_path / "v1.npz").predict(X), net.predict(X))
    with pytest.raises(ModelFileError, match="version 99"):
        DCSNetwork.load(tmp_path / "v99.npz")
    with pytest.raises(ModelFileError):
        DCSNetwork.load(tmp_path / "missing.npz")


def test_dcs_rejects_bad_input():
    with pytest.raises(MjwalkError, match="do not match"):
        DCSNetwork().fit(np.zeros((5, 2)), np.zeros(4))
    with pytest.raises(MjwalkError, match="NaN"):
        DCSNetwork().fit(np.full((5, 1), np.nan), np.zeros(5))
    with pytest.raises(MjwalkError, match="not fitted"):
        DCSNetwork().predict(np.zeros((1, 2)))


def _real_raises(step, styles=False):
    """Every ``step``-th left raise-hand clip: constraints (start elbow, start hand, end hand;
    m, shoulder frame), directions (p, 20, 2, 3), segment lengths (2,) -- as the benchmark
    (:func:`mjwalk.arms.armcapture.arm_movements`); with ``styles`` also each clip's style id
    (p,) from the json beside it."""
    import json

    from mjwalk.arms.armcapture import arm_movements
    from mjwalk.mocap import load_bvh

    files = sorted(DATA.glob("*raise-up-left-hand*.bvh"))[::step]
    S = [json.loads(f.with_suffix(".json").read_text())["style"] for f in files]
    takes = [load_bvh(f, skeleton="bandai", fps=30) for f in files]
    mv = arm_movements(takes, "left", "bandai", S)
    assert len(mv) == len(files)  # every clip holds one raise
    if styles:
        return mv.constraints, mv.directions, mv.lengths, mv.groups.astype(int)
    return mv.constraints, mv.directions, mv.lengths


@pytest.mark.skipif(not DATA.is_dir(), reason="../shared/data/bandai-raise-hand absent")
def test_real_raise_hand_pca_is_compact():
    _, U, _ = _real_raises(8)
    rep = ArmRepresentation(variance=0.98).fit(U)
    # paper: first modes 72 %, 11 %, 3 %; measured on 100 clips 77 %, 19 %, 2 %
    assert rep.pca_.explained_variance_ratio_[0] > 0.5
    assert rep.n_modes_ <= 8


def _dcs_and_mean_errors(C, U, L, tr, te, dcs):
    """Per test movement of ``te``: the trajectory error (deg) of the DCS model (settings
    ``dcs``) and of the mean trajectory, both trained on ``tr`` with one PCA/alignment and
    fitted to the movement's true start and end hand positions."""
    from sklearn.dummy import DummyRegressor

    from mjwalk.arms.reach import ReachModel, end_effector

    errs = {}
    rep = None
    for name, reg in (("dcs", None), ("mean", DummyRegressor())):
        m = ReachModel(L, dcs=dcs, regressor=reg).fit(C[tr], U[tr], rep=rep)
        rep = m.rep_
        errs[name] = []
        for i in te:
            hand = end_effector(U[i], L)
            r = m.predict(C[i], start=hand[0], end=hand[-1])
            errs[name].append(np.degrees(trajectory_error(r.directions, U[i])))
    return errs


@pytest.mark.slow
@pytest.mark.skipif(not DATA.is_dir(), reason="../shared/data/bandai-raise-hand absent")
def test_real_raise_hand_dcs_beats_mean_trajectory():
    from sklearn.model_selection import KFold

    C, U, L = _real_raises(4)  # 65 clips, all four styles
    errs = {"dcs": [], "mean": []}
    for fold, (tr, te) in enumerate(KFold(4, shuffle=True, random_state=0).split(C)):
        fold_errs = _dcs_and_mean_errors(C, U, L, tr, te, {"scaling": "global", "rng": fold})
        for name in errs:
            errs[name] += fold_errs[name]
    dcs, mean = np.mean(errs["dcs"]), np.mean(errs["mean"])
    # seeded, 4-fold on 65 clips: measured DCS 5.7 deg, mean trajectory 19.3 deg
    assert dcs < 0.5 * mean
    assert dcs < 8.0


@pytest.mark.slow
@pytest.mark.skipif(not DATA.is_dir(), reason="../shared/data/bandai-raise-hand absent")
def test_real_raise_hand_dcs_beats_mean_trajectory_on_a_style_it_has_not_seen():
    # leave-one-style-out (train on three Bandai styles, test on the fourth): every held-out
    # style raises to heights the others never reach, so the network extrapolates; the trend
    # fallback carries it (benchmarks/bench_reach.py --side left, rng = fold index: DCS
    # 16.7 / 10.3 / 9.5 / 11.7 deg against the mean trajectory 51.3 / 14.1 / 10.4 / 25.1;
    # without the fallback and dead-unit pruning the masculine style gave 14.6, at other
    # seeds 15-25). The shipped settings with two averaged networks instead of five, to keep
    # the suite within its CI budget (68 s -> 36 s here; the benchmark runs the five): DCS
    # 19.7 / 10.6 / 9.5 / 11.8 deg, the same side of the mean trajectory in every fold.
    from mjwalk.arms.reachdefault import CAPTURE_DCS

    C, U, L, S = _real_raises(1, styles=True)
    for fold, style in enumerate(np.unique(S)):
        tr, te = np.flatnonzero(S != style), np.flatnonzero(S == style)
        dcs = {**CAPTURE_DCS, "rng": fold, "n_networks": 2}
        errs = _dcs_and_mean_errors(C, U, L, tr, te, dcs)
        errs = {name: float(np.mean(e)) for name, e in errs.items()}
        assert errs["dcs"] < errs["mean"], (style, errs)


def test_dcs_leave_one_out_residuals_match_refits():
    # selection="loo" scores each candidate by the PRESS residuals r_i / (1 - H_ii) of the
    # output least squares; with a small ridge they equal refitting without sample i
    X, Y = _toy(60, 3)
    # output forms: constant, local linear, local linear with its own slope ridge and a
    # global linear term, constant with a global linear term
    for linear in (False, True, (True, True, 10.0), (False, True, 1.0)):
        local, glob, r = output_form(linear)
        net = DCSNetwork(
            rng=0,
            max_neurons=6,
            validation_fraction=0,
            local_linear=local,
            global_linear=glob,
            slope_ridge=r,
            ridge=1e-6,
        ).fit(X, Y)
        Z = (X - net.x_mean_) / net.x_scale_
        c, w, e = net.centers_, net.widths_, net.edges_
        out, hat = solve_outputs(Z, Y, c, w, e, 1e-6, linear, with_hat=True)
        fast = (Y - forward(Z, c, w, out, e, linear)) / (1 - hat[:, None])
        for i in range(0, len(Z), 7):
            keep = np.arange(len(Z)) != i
            o = solve_outputs(Z[keep], Y[keep], c, w, e, 1e-6, linear)
            refit = Y[i] - forward(Z[i : i + 1], c, w, o, e, linear)[0]
            np.testing.assert_allclose(fast[i], refit, atol=1e-4)
    net = DCSNetwork(rng=0, selection="loo").fit(X, Y)
    assert np.isfinite([h[2] for h in net.history_]).all()
    with pytest.raises(MjwalkError, match="selection"):
        DCSNetwork(selection="kfold").fit(X, Y)


def test_dcs_local_linear_outputs_reproduce_a_linear_map(tmp_path):
    # b_i + S_i (x - c_i) per neuron: three neurons carry an affine map exactly, where
    # constant outputs (eq. 2 as printed) leave a piecewise-constant error
    rng = np.random.default_rng(0)
    W = np.array([[1.0, 2.0], [0.5, -1.0], [0.0, 3.0]])
    X = rng.uniform(-1, 1, (80, 3))
    Xt = rng.uniform(-0.8, 0.8, (50, 3))
    kw = {"rng": 0, "max_neurons": 3, "validation_fraction": 0}
    lin = DCSNetwork(local_linear=True, **kw).fit(X, X @ W + 0.2)
    const = DCSNetwork(**kw).fit(X, X @ W + 0.2)
    assert np.abs(lin.predict(Xt) - (Xt @ W + 0.2)).max() < 1e-3  # measured 1e-4
    assert np.abs(const.predict(Xt) - (Xt @ W + 0.2)).max() > 0.5  # measured 1.6
    assert lin.slopes_.shape == (3, 3, 2) and const.slopes_ is None
    lin.save(tmp_path / "lin.npz")
    back = DCSNetwork.load(tmp_path / "lin.npz")
    np.testing.assert_allclose(back.predict(Xt), lin.predict(Xt))
    # a grid (False, True) is chosen with the network size on the held-out residuals
    grid = DCSNetwork(rng=0, selection="loo", local_linear=(False, True)).fit(X, X @ W)
    assert grid.local_linear_ is True


def test_dcs_slope_ridge_penalizes_slopes_relative_to_ridge():
    # slope_ridge r: the local slopes carry r times the output ridge; the stacked solution
    # equals the explicit ridge normal equations with that per-column penalty
    X, Y = _toy(70, 5)
    net = DCSNetwork(rng=0, max_neurons=5, validation_fraction=0, local_linear=True).fit(X, Y)
    Z = (X - net.x_mean_) / net.x_scale_
    c, w, e = net.centers_, net.widths_, net.edges_
    k, d = len(c), X.shape[1]
    r, ridge = 30.0, 1e-2
    out = solve_outputs(Z, Y, c, w, e, ridge, (True, False, r))
    _, slopes, trend = split_outputs(out, k, d, (True, False, r))
    assert trend is None
    F = features(Z, c, w, e, True)  # unscaled slope columns
    Phi = F[:, :k]
    lam = ridge * np.sum(Phi**2) / k
    bmu = np.argmax(Phi, axis=1)
    P = np.zeros((F.shape[1], len(Z)))
    P[bmu, np.arange(len(Z))] = 1.0 / np.bincount(bmu, minlength=k)[bmu]
    pen = np.r_[np.full(k, lam), np.full(k * d, r * lam)]
    beta = np.linalg.solve(F.T @ F + np.diag(pen), F.T @ Y + pen[:, None] * (P @ Y))
    np.testing.assert_allclose(slopes, beta[k:].reshape(k, d, -1), rtol=1e-6, atol=1e-9)
    with pytest.raises(MjwalkError, match="slope_ridge"):
        DCSNetwork(local_linear=True, slope_ridge=0.0).fit(X, Y)


def _affine_and_bump(X):
    """y = 1.5 x0 - 0.5 x1 + a Gaussian bump at the origin, (N, 1)."""
    return X @ np.array([[1.5], [-0.5]]) + 0.3 * np.exp(-4 * (X**2).sum(1, keepdims=True))


def test_dcs_global_linear_term_extrapolates_the_trend(tmp_path):
    # y = affine + a bump: inside the data both forms fit; beyond it the normalized RBF keeps
    # the outermost neuron's output while the global linear term carries on along the trend
    rng = np.random.default_rng(2)
    f = _affine_and_bump
    X = rng.uniform(-1, 1, (150, 2))
    Xfar = rng.uniform(1.5, 2.0, (40, 2))
    kw = {"rng": 0, "max_neurons": 8, "validation_fraction": 0}
    glob = DCSNetwork(global_linear=True, **kw).fit(X, f(X))
    const = DCSNetwork(**kw).fit(X, f(X))
    assert glob.trend_.shape == (2, 1) and const.trend_ is None
    err_glob = np.abs(glob.predict(Xfar) - f(Xfar)).mean()
    err_const = np.abs(const.predict(Xfar) - f(Xfar)).mean()
    assert err_glob < 0.3 * err_const  # measured 0.06 vs 1.03
    glob.save(tmp_path / "glob.npz")
    back = DCSNetwork.load(tmp_path / "glob.npz")
    np.testing.assert_allclose(back.predict(Xfar), glob.predict(Xfar))
    assert back.global_linear_ and back.trend_.shape == (2, 1)
    # the grid (False, True) is chosen with the network size on the PRESS residuals
    grid = DCSNetwork(rng=0, selection="loo", global_linear=(False, True)).fit(
        X, X @ np.array([[1.5], [-0.5]])
    )
    assert grid.global_linear_ is True


def _wins(net, X):
    z = (np.atleast_2d(X.T).T - net.x_mean_) / net.x_scale_
    d = np.linalg.norm(z[:, None, :] - net.centers_[None], axis=2)
    return np.bincount(d.argmin(1), minlength=net.n_neurons_)


def test_dcs_removes_dead_units_in_a_gap_of_the_data():
    # two clusters with a wide gap: a neuron inserted half way between them wins no sample,
    # so nothing but the ridge sets its output; min_wins=1 removes such units while growing
    rng = np.random.default_rng(0)
    X = np.r_[rng.uniform(-3.0, -2.5, 60), rng.uniform(2.5, 3.0, 60)][:, None]
    Y = np.sin(3 * X[:, 0])
    kw = {"rng": 0, "max_neurons": 10, "validation_fraction": 0}
    kept = DCSNetwork(min_wins=0, **kw).fit(X, Y)
    pruned = DCSNetwork(**kw).fit(X, Y)
    assert (_wins(kept, X) == 0).any()  # the failure: a unit in the gap
    assert (_wins(pruned, X) >= 1).all()
    assert pruned.n_pruned_ >= 1 and kept.n_pruned_ == 0
    assert 2 <= pruned.n_neurons_ <= 10
    with pytest.raises(MjwalkError, match="min_wins"):
        DCSNetwork(min_wins=-1).fit(X, Y)


def test_dcs_trend_fallback_blends_into_the_trend_outside_the_data(tmp_path):
    # y = affine + a bump, local linear outputs: inside the data the network is used as is;
    # far outside, the output is the trend network's (two neurons + the global linear term)
    rng = np.random.default_rng(2)
    f = _affine_and_bump
    X = rng.uniform(-1, 1, (150, 2))
    kw = {"rng": 0, "max_neurons": 8, "validation_fraction": 0, "local_linear": True}
    net = DCSNetwork(trend_fallback=True, **kw).fit(X, f(X))
    plain = DCSNetwork(**kw).fit(X, f(X))
    trend = net.fallback_
    assert trend is not None and trend.n_neurons_ == 2 and trend.trend_ is not None
    assert plain.fallback_ is None
    # at the training inputs (distance 0) the weight is 1: the network alone
    np.testing.assert_allclose(net.network_weight(X), 1.0)
    np.testing.assert_allclose(net.predict(X), plain.predict(X), rtol=1e-12, atol=1e-12)
    # the weight falls with the distance in trained-range radii, exp(-q^2 / 2), and the
    # output moves from the network's to the trend's in proportion
    x_edge = np.array([[1.2, 1.3], [1.6, 1.0]])
    q = net.distance_to_training(x_edge) / net.range_radius_
    g = net.network_weight(x_edge)
    np.testing.assert_allclose(g, np.exp(-0.5 * q**2))
    assert (0.0 < g).all() and (g < 1.0).all()
    blend = trend.predict(x_edge) + g[:, None] * (plain.predict(x_edge) - trend.predict(x_edge))
    np.testing.assert_allclose(net.predict(x_edge), blend, rtol=1e-12, atol=1e-12)
    # a caller's own distances (ReachModel.predict has them) give the same numbers
    d_edge = net.distance_to_training(x_edge)
    assert np.array_equal(net.network_weight(x_edge, d_edge), g)
    assert np.array_equal(net.predict(x_edge, d_edge), net.predict(x_edge))
    Xfar = rng.uniform(4.0, 5.0, (40, 2))
    assert (net.network_weight(Xfar) < 1e-6).all()
    np.testing.assert_allclose(net.predict(Xfar), trend.predict(Xfar), rtol=1e-5, atol=1e-5)
    # saved and loaded with its trend network; a version 2 file (no fallback) still loads
    net.save(tmp_path / "fb.npz")
    back = DCSNetwork.load(tmp_path / "fb.npz")
    np.testing.assert_allclose(back.predict(Xfar), net.predict(Xfar))
    assert back.fallback_ is not None
    plain.save(tmp_path / "plain.npz")
    with np.load(tmp_path / "plain.npz") as z:
        data = dict(z)
    data["header"] = np.array(
        str(data["header"]).replace(f'"version": {DCS_VERSION}', '"version": 2')
    )
    np.savez(tmp_path / "v2.npz", **data)
    np.testing.assert_allclose(
        DCSNetwork.load(tmp_path / "v2.npz").predict(Xfar), plain.predict(Xfar)
    )


def test_dcs_averages_networks_grown_from_independent_seeds(tmp_path):
    X, Y = _toy(120, 7)
    Xt, _ = _toy(50, 8)
    kw = {"rng": 3, "max_neurons": 8, "validation_fraction": 0, "trend_fallback": True}
    one = DCSNetwork(**kw).fit(X, Y)
    avg = DCSNetwork(n_networks=3, **kw).fit(X, Y)
    assert len(avg.members_) == 2 and one.members_ == []
    # each network has its own two-neuron trend network, itself a single network
    assert all(m.fallback_.n_neurons_ == 2 for m in (avg, *avg.members_))
    assert avg.fallback_.members_ == []
    # the first network is the one a single-network fit grows; the others differ
    np.testing.assert_array_equal(avg.centers_, one.centers_)
    assert not np.allclose(avg.members_[0].predict(Xt), one.predict(Xt))
    mean = (one.predict(Xt) + sum(m.predict(Xt) for m in avg.members_)) / 3
    np.testing.assert_allclose(avg.predict(Xt), mean, rtol=1e-12, atol=1e-12)
    # the same seed gives the same ensemble; saved and loaded with its members
    np.testing.assert_array_equal(
        DCSNetwork(n_networks=3, **kw).fit(X, Y).predict(Xt), avg.predict(Xt)
    )
    avg.save(tmp_path / "avg.npz")
    back = DCSNetwork.load(tmp_path / "avg.npz")
    assert len(back.members_) == 2
    np.testing.assert_allclose(back.predict(Xt), avg.predict(Xt))
    # the training inputs are stored once: the trend and averaged networks borrow them
    with np.load(tmp_path / "avg.npz") as z:
        assert [k for k in z.files if k.endswith("train_z")] == ["train_z"]
    for sub in (back.fallback_, *back.members_):
        np.testing.assert_array_equal(sub.distance_to_training(Xt), back.distance_to_training(Xt))
    with pytest.raises(MjwalkError, match="n_networks"):
        DCSNetwork(n_networks=0).fit(X, Y)


def test_dcs_fits_linear_maps_only_from_ten_samples_per_input():
    # a linear map through d = 3 inputs: with 40 samples (>= 10 per input) the PRESS
    # selection takes a linear term; with 12 a plane would be set by a handful of samples and
    # run off away from them, so the network and its trend keep constant outputs: far
    # outside the prediction is a convex combination of neuron outputs, not a plane
    from mjwalk.arms.dcsfit import SAMPLES_PER_COEFFICIENT

    assert SAMPLES_PER_COEFFICIENT == 10
    rng = np.random.default_rng(4)
    W = np.array([[1.0, -2.0], [0.5, 1.0], [-1.0, 0.3]])
    kw = {
        "rng": 0,
        "selection": "loo",
        "local_linear": (False, True),
        "global_linear": (False, True),
        "trend_fallback": True,
    }
    X = rng.normal(size=(40, 3))
    net = DCSNetwork(**kw).fit(X, X @ W + 0.01 * rng.normal(size=(40, 2)))
    assert net.global_linear_ or net.local_linear_
    assert net.fallback_.global_linear_
    X, far = X[:12], 10.0 * rng.normal(size=(50, 3))
    Y = X @ W
    net = DCSNetwork(**kw).fit(X, Y)
    assert not (net.global_linear_ or net.local_linear_ or net.fallback_.global_linear_)
    out = net.predict(far)
    neurons = np.vstack([net.outputs_, net.fallback_.outputs_])
    assert (out >= neurons.min(axis=0) - 1e-9).all() and (out <= neurons.max(axis=0) + 1e-9).all()
    assert np.abs(out).max() < 0.25 * np.abs(far @ W).max()  # the plane goes 4x further
