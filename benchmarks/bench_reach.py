"""10-fold cross-validation of the PCA + DCS arm model (Al-Zubi & Sommer §5) beside baselines.

Real data: ../shared/data/bandai-raise-hand (left-hand clips, the raising phase from the first
frame to the highest hand position). Constraint = start and end hand (wrist) positions relative
to the shoulder (UpperArm_L) in the body frame of the first frame; chain = upper arm, forearm.
Synthetic spaces (mjwalk.body.reachgen): (a) start/end, (b) obstacle ratio B/A, (c) grasp size
and orientation.

Error = mean angle between predicted and actual segment directions over the n samples and the
segments (degrees), per test movement; the table shows mean +/- sd over all test movements of
the 10 folds and the DCS neuron count range; for grasps also the RMS over time of the grip
aperture (mm; paper: thumb-index distance) and forearm roll (deg), mean over test movements.
Paper: 3.9 +/- 2.1 deg with 6-11 neurons; grasping RMS 8.5 deg (finger direction).
Baselines on the same PCA coefficients and poses: kNN, an ARD Gaussian process, and "mean only"
(the mean aligned trajectory, fitted to start/end like the others: the floor of the method).

Run from the repo root:  python benchmarks/bench_reach.py [--max-clips N]
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np
from sklearn.dummy import DummyRegressor
from sklearn.gaussian_process import GaussianProcessRegressor
from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel
from sklearn.model_selection import KFold
from sklearn.neighbors import KNeighborsRegressor
from sklearn.pipeline import make_pipeline
from sklearn.preprocessing import StandardScaler

import mjwalk.render  # noqa: F401  (picks a headless GL backend before mujoco is loaded)
from mjwalk.arms.armrep import resample_trajectory, segment_directions, trajectory_error
from mjwalk.arms.reach import ReachModel, end_effector

DATA = Path(__file__).resolve().parents[2] / "shared" / "data" / "bandai-raise-hand"
N_SAMPLES = 20


def load_raise_hand(max_clips: int | None = None):
    """Constraints (p, 6), directions (p, n, 2, 3), segment lengths (2,) from the capture."""
    from mjwalk.mocap import load_bvh

    files = sorted(DATA.glob("*raise-up-left-hand*.bvh"))[:max_clips]
    C, U, L = [], [], []
    for f in files:
        tk = load_bvh(f, skeleton="bandai", fps=30)
        P = np.stack([tk.joints[j] for j in ("UpperArm_L", "LowerArm_L", "Hand_L")], axis=1)
        yaw = tk.pelvis_yaw[0]
        c, s = np.cos(-yaw), np.sin(-yaw)
        rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        P = (P - P[:, :1]) @ rz.T  # shoulder at origin, body frame (x forward)
        k = int(np.argmax(P[:, 2, 2]))
        if k < 4:
            continue
        Pn = resample_trajectory(P[: k + 1], N_SAMPLES)
        U.append(segment_directions(Pn))
        L.append(np.linalg.norm(np.diff(P[0], axis=0), axis=1))
        C.append(np.r_[Pn[0, 2], Pn[-1, 2]])
    return np.array(C), np.array(U), np.mean(L, axis=0)


def regressors(seed: int, n_inputs: int):
    """The DCS (None: ReachModel's own) and the baselines, all on the same PCA targets."""
    gpr = make_pipeline(
        StandardScaler(),
        GaussianProcessRegressor(
            ConstantKernel(1.0) * RBF(np.ones(n_inputs)) + WhiteKernel(1e-1, (1e-3, 10.0)),
            normalize_y=True,
            random_state=seed,
        ),
    )
    return {
        "DCS": None,
        "kNN (k=5)": make_pipeline(StandardScaler(), KNeighborsRegressor(5, weights="distance")),
        "GPR (ARD)": gpr,
        "mean only": DummyRegressor(),
    }


def cross_validate(C, U, lengths, extras=None, endpoints=True, seed=0, folds=10):
    """Per regressor: (errors in degrees over all test movements, neuron counts, seconds)."""
    out = {}
    kf = KFold(folds, shuffle=True, random_state=seed)
    reps = {}
    for name in regressors(seed, C.shape[1]):
        errs, ex_errs, neurons, t0 = [], [], [], time.perf_counter()
        for fold, (tr, te) in enumerate(kf.split(C)):
            reg = regressors(seed + fold, C.shape[1])[name]
            model = ReachModel(lengths, variance=0.98, dcs={"rng": seed + fold}, regressor=reg)
            model.fit(C[tr], U[tr], None if extras is None else extras[tr], rep=reps.get(fold))
            reps[fold] = model.rep_  # the PCA/alignment is shared by all regressors of a fold
            if model.n_neurons is not None:
                neurons.append(model.n_neurons)
            for i in te:
                hand = end_effector(U[i], lengths)
                r = model.predict(
                    C[i],
                    start=hand[0] if endpoints else None,
                    end=hand[-1] if endpoints else None,
                )
                errs.append(np.degrees(trajectory_error(r.directions, U[i])))
                if extras is not None:  # RMS over time of each extra channel
                    ex_errs.append(np.sqrt(((r.extras - extras[i]) ** 2).mean(axis=0)))
        out[name] = (np.array(errs), neurons, time.perf_counter() - t0, np.array(ex_errs))
    return out


def print_table(title, res, extra=""):
    print(f"\n## {title}{extra}")
    grasp = any(len(v[3]) for v in res.values())
    head = f"{'model':<12} {'error deg (mean +/- sd)':>24} {'median':>8} {'neurons':>10} {'s':>7}"
    if grasp:
        head += f" {'aperture RMS mm':>16} {'roll RMS deg':>13}"
    print(head)
    for name, (e, neurons, secs, ex) in res.items():
        nn = f"{min(neurons)}-{max(neurons)}" if neurons else "-"
        line = (
            f"{name:<12} {e.mean():>13.2f} +/- {e.std():<6.2f} {np.median(e):>8.2f} "
            f"{nn:>10} {secs:>7.1f}"
        )
        if grasp:
            line += f" {1000 * ex[:, 0].mean():>16.1f} {np.degrees(ex[:, 1].mean()):>13.1f}"
        print(line)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-clips", type=int, default=None)
    ap.add_argument("--no-real", action="store_true")
    ap.add_argument("--no-synthetic", action="store_true")
    ap.add_argument("--video", help="also render the rack-2 shelf reach to this mp4")
    ap.add_argument("--spaces", default="endpoints,obstacle,grasp", help="synthetic spaces")
    args = ap.parse_args(argv)
    warnings.filterwarnings("ignore", module="sklearn")
    if not args.no_real:
        if not DATA.is_dir():
            print(f"skip real data: {DATA} absent")
        else:
            t = time.perf_counter()
            C, U, L = load_raise_hand(args.max_clips)
            print(
                f"loaded {len(C)} raising movements in {time.perf_counter() - t:.1f} s; "
                f"segments {np.round(L, 3)} m"
            )
            res = cross_validate(C, U, L)
            print_table(
                "bandai-raise-hand, constraint = start/end hand",
                res,
                f" (p={len(C)}, n={N_SAMPLES})",
            )
    if not args.no_synthetic:
        try:
            from mjwalk.arms import reachgen
        except ImportError:
            print("reachgen not available")
            return 0
        rng = np.random.default_rng(0)
        for space in args.spaces.split(","):
            data = reachgen.generate(space, 150, rng)
            res = cross_validate(
                data.constraints, data.directions, data.lengths, extras=data.extras, endpoints=True
            )
            print_table(
                f"synthetic space {space!r}", res, f" (p=150, n={data.directions.shape[1]})"
            )
    if args.video:
        scene_clip(args.video)
    return 0


def scene_clip(path: str) -> None:
    """Humanoid at stand_rack2 reaching 6 cm above rack2_screw2: contacts and an mp4 clip."""
    from mjwalk.arms import reachgen
    from mjwalk.render import render_video
    from mjwalk.timeline import collision_report, reach_in_scene

    scene = Path(__file__).resolve().parents[1] / "scenes" / "assembly_station.xml"
    data = reachgen.generate("endpoints", 150, np.random.default_rng(0))
    model = ReachModel(data.lengths, dcs={"rng": 0}).fit(data.constraints, data.directions)
    tl, res = reach_in_scene(
        scene, model, "stand_rack2", "rack2_screw2", target_offset=(0, 0, 0.06)
    )
    contacts = collision_report(tl)
    print(
        f"\n## scene reach: {tl.n_frames} frames, {len(contacts)} arm/body-scene contacts, "
        f"constraint {res.distance:.2f} sd from training, warnings {res.warnings}"
    )
    t = time.perf_counter()
    render_video(tl, path, camera="track", draw_path=False, progress=False)
    print(f"rendered {path} in {time.perf_counter() - t:.1f} s")


if __name__ == "__main__":
    sys.exit(main())
