"""Capture import speed and summary figures on the real data (run from the repo root).

    python benchmarks/bench_mocap.py [n_clips]

Prints per-clip load time (parse, forward kinematics, whole ``load_bvh``) over the Bandai walk
clips in ``../shared/data/bandai-walk`` and the CMU 35_01 ASF/AMC load time, plus the median
pelvis height and walking speed of the clips read.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from mjwalk.mocap import bvh_forward_kinematics, load_amc, load_bvh, parse_bvh

DATA = Path(__file__).resolve().parents[2] / "shared" / "data"


def main(n_clips: int | None = None) -> None:
    files = sorted((DATA / "bandai-walk").glob("*.bvh"))[:n_clips]
    if not files:
        print(f"no capture in {DATA / 'bandai-walk'}")
        return
    t_parse, t_fk, t_load, heights, speeds = [], [], [], [], []
    for f in files:
        t0 = time.perf_counter()
        bvh = parse_bvh(f)
        t1 = time.perf_counter()
        bvh_forward_kinematics(bvh)
        t2 = time.perf_counter()
        take = load_bvh(f, skeleton="bandai")
        t3 = time.perf_counter()
        t_parse.append(t1 - t0)
        t_fk.append(t2 - t1)
        t_load.append(t3 - t2)
        heights.append(np.median(take.pelvis[:, 2]))
        hops = np.linalg.norm(np.diff(take.pelvis[::12, :2], axis=0), axis=1)
        speeds.append(hops.sum() / take.time[::12][-1])
    ms = 1000.0 * np.array(t_load)
    print(f"Bandai BVH clips: {len(files)}")
    print(f"  parse_bvh            median {1000 * np.median(t_parse):6.1f} ms")
    print(f"  forward kinematics   median {1000 * np.median(t_fk):6.1f} ms")
    print(
        f"  load_bvh (to 120 Hz) median {np.median(ms):6.1f} ms, max {ms.max():6.1f} ms, "
        f"all clips {ms.sum() / 1000:5.2f} s"
    )
    print(f"  pelvis height median {np.median(heights):.3f} m")
    print(
        f"  walking speed median {np.median(speeds):.2f} m/s "
        f"(range {np.min(speeds):.2f}-{np.max(speeds):.2f})"
    )
    amc, asf = DATA / "cmu-35" / "35_01.amc", DATA / "cmu-35" / "35.asf"
    if amc.is_file():
        t0 = time.perf_counter()
        take = load_amc(amc, asf, skeleton="cmu")
        print(
            f"CMU 35_01 ASF/AMC: load_amc {1000 * (time.perf_counter() - t0):.1f} ms, "
            f"{take.n_frames} frames, pelvis height {np.median(take.pelvis[:, 2]):.3f} m"
        )


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else None)
