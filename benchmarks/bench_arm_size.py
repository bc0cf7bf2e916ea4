"""A walker of another size: the arm model with and without the arm-length scaling of the
constraint (:mod:`mjwalk.arms.armcapture`).

Leave-one-style-out on the Bandai left-arm raises (``bench_reach.load_raise_hand``): the
held-out style is made by a walker whose arms are ``--factor`` times as long -- the same
movements (the same segment directions), positions scaled about the shoulder. ``scaled``: its
constraint is brought back to the reference arm, as :func:`mjwalk.arms.armcapture.arm_movements`
does; ``raw``: given to the network in metres as captured. Both predictions are fitted to the
same start and end hand positions (of the reference arm), so only the network's input differs.
One DCS network (``CAPTURE_DCS``, ``n_networks=1``, seed 0) and the mean trajectory.

Measured 2026-11-27 (``--factor 1.15``), mean error in degrees, DCS scaled / raw (mean
trajectory): feminine 16.87 / 35.37 (51.27), masculine 10.64 / 10.12 (14.07), normal 9.16 /
17.09 (10.35), youthful 10.97 / 20.63 (25.14). The Bandai bones are all one size (every
scale is 1), so the shared clips alone cannot show this.

Run from the repo root:  python benchmarks/bench_arm_size.py --data DIR [--factor F]
"""

from __future__ import annotations

import argparse
import sys
import warnings

import bench_reach as br
import numpy as np
from sklearn.dummy import DummyRegressor

from mjwalk.arms.reach import ReachModel
from mjwalk.arms.reachdefault import CAPTURE_DCS
from mjwalk.errors import MjwalkError


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", help="as benchmarks/bench_reach.py --data")
    ap.add_argument("--factor", type=float, default=1.15, help="held-out walker's arm length")
    args = ap.parse_args(argv)
    if not args.factor > 0:
        print(
            f"bench_arm_size: error: --factor must be positive, got {args.factor}", file=sys.stderr
        )
        return 2
    warnings.filterwarnings("ignore", module="sklearn")
    data_dir = br.data_or_status(args.data)
    if isinstance(data_dir, int):
        return data_dir
    try:
        ds = br.load_raise_hand(data_dir, side="left")
    except MjwalkError as exc:
        print(f"bench_arm_size: error: {exc}", file=sys.stderr)
        return 2
    C, U, L, G = ds.constraints, ds.directions, ds.lengths, ds.groups
    print(f"{len(C)} left raises, held-out walker's arms x {args.factor}; error deg")
    print(f"{'held-out style':<16}{'DCS scaled':>12}{'DCS raw':>10}{'mean only':>11}")
    for style in sorted(set(G)):
        tr, te = np.flatnonzero(G != style), np.flatnonzero(G == style)
        dcs = {**CAPTURE_DCS, "n_networks": 1, "rng": 0}
        model = ReachModel(L, variance=0.98, dcs=dcs).fit(C[tr], U[tr])
        mean = ReachModel(L, variance=0.98, regressor=DummyRegressor())
        mean.fit(C[tr], U[tr], rep=model.rep_)
        err = {
            "scaled": [br.movement_error(model, C[i], U[i], L)[0] for i in te],
            "raw": [br.movement_error(model, C[i] * args.factor, U[i], L)[0] for i in te],
            "mean": [br.movement_error(mean, C[i], U[i], L)[0] for i in te],
        }
        cells = "".join(
            f"{np.mean(err[k]):>{w}.2f}" for k, w in (("scaled", 12), ("raw", 10), ("mean", 11))
        )
        print(f"{style:<16}{cells}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
