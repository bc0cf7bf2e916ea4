"""StepModel figures: training time, sample_next throughput, fidelity against real capture.

Run from the repository root:  python benchmarks/bench_model.py [--skip-default] [--json out.json]

1. training time on the default virtual corpus (generate + segment + fit, 12 subjects);
2. training time on bandai-walk {masculine, normal} clips (when ../shared/data is present);
3. ``sample_next`` latency for one predecessor (n=10) and throughput for 1000 predecessors;
4. fidelity tables: Bandai {masculine, normal} model vs {feminine, youthful} clips (the two
   actor groups, see ../shared/data/README.md) and vs its own training clips, and the default
   model vs both groups and vs all clips pooled;
5. the floors those tables stand on: the KS statistic between the two groups' captured steps
   (what a perfect {masculine, normal} model scores against {feminine, youthful}; half of it
   bounds the default model's worse group from below, since KS is a distance) and between the
   default model's training corpus and each group (what a perfect default model scores).
   All step figures compare steady-state steps (see mjwalk.gait.fidelity).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from mjwalk.gait.fidelity import fidelity_from_steps, format_fidelity_table
from mjwalk.gait.model import StepModel

DATA = Path(__file__).resolve().parents[2] / "shared" / "data" / "bandai-walk"


def bandai_groups(data: Path = DATA) -> dict[str, list[Path]]:
    styles = (data / "style_label.txt").read_text().split()
    groups: dict[str, list[Path]] = {"masculine+normal": [], "feminine+youthful": []}
    for js in sorted(data.glob("*.json")):
        style = styles[json.loads(js.read_text())["style"]].removeprefix("dataset-2_")
        key = "masculine+normal" if style in ("masculine", "normal") else "feminine+youthful"
        groups[key].append(js.with_suffix(".bvh"))
    return groups


def bench_sampling(model: StepModel) -> dict:
    rng = np.random.default_rng(0)
    one = model.sample_first(1, rng)
    for _ in range(200):
        model.sample_next(one, 10, rng)
    n = 3000
    t = time.perf_counter()
    for _ in range(n):
        model.sample_next(one, 10, rng)
    per_call = (time.perf_counter() - t) / n
    many = model.sample_first(1000, rng)
    t = time.perf_counter()
    reps = 20
    for _ in range(reps):
        model.sample_next(many, 10, rng)
    batch = (time.perf_counter() - t) / reps
    return {
        "sample_next_1x10_ms": per_call * 1e3,
        "successors_per_s_single": 10 / per_call,
        "sample_next_1000x10_ms": batch * 1e3,
        "successors_per_s_batched": 10000 / batch,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--skip-default", action="store_true", help="skip the default corpus model")
    ap.add_argument("--json", help="write all figures to this JSON file")
    ap.add_argument("--chains", type=int, default=400)
    ap.add_argument("--data", type=Path, default=DATA, help="bandai-walk folder")
    args = ap.parse_args()
    out: dict = {}
    models: dict[str, StepModel] = {}

    if not args.skip_default:
        from mjwalk.gait.corpus import generate_corpus
        from mjwalk.gait.default import train_model
        from mjwalk.gait.segment import segment_takes

        t0 = time.perf_counter()
        takes = generate_corpus(n_subjects=12, seed=0)
        t1 = time.perf_counter()
        model, seg = train_model(takes, seed=0, progress=True)
        t2 = time.perf_counter()
        corpus_steps, _ = segment_takes(takes)  # for the floors (not timed)
        out["default"] = {
            "corpus_seconds": t1 - t0,
            "train_seconds": t2 - t1,
            "segmentation": str(seg),
            "summary": model.summary(),
        }
        print(f"default corpus: generate {t1 - t0:.1f} s, segment+fit {t2 - t1:.1f} s; {seg}")
        models["default"] = model

    steps_by_group = {}
    if args.data.is_dir():
        from mjwalk.gait.segment import segment_takes
        from mjwalk.mocap import load_bvh

        for g, files in bandai_groups(args.data).items():
            steps, seg = segment_takes([load_bvh(f) for f in files])
            steps_by_group[g] = steps
            print(f"bandai {g}: {len(files)} clips, {seg}")
        t = time.perf_counter()
        # variance=0.95 (the paper's figure): ~790 transitions per direction support 4 PCA
        # dimensions, not the 8 that 0.99 keeps; with 8, chains drift off the data (in-sample
        # KS over 40-step chains: length 0.17, duration 0.18, sway 0.24; with 4: 0.05, 0.13,
        # 0.19). The default corpus (~9 800 per direction) keeps 0.99 (6 dimensions).
        models["bandai masculine+normal"] = StepModel.fit(
            steps_by_group["masculine+normal"], seed=0, variance=0.95
        )
        out["bandai_train_seconds"] = time.perf_counter() - t
        print(f"bandai masculine+normal fit: {out['bandai_train_seconds']:.1f} s")
    else:
        print(f"({args.data} absent: no real-capture figures)")

    for name, model in models.items():
        out.setdefault("sampling", {})[name] = s = bench_sampling(model)
        print(
            f"[{name}] sample_next(1 prev, n=10): {s['sample_next_1x10_ms']:.3f} ms "
            f"({s['successors_per_s_single']:.0f} successors/s); 1000 prev x 10: "
            f"{s['sample_next_1000x10_ms']:.1f} ms ({s['successors_per_s_batched']:.0f}/s)"
        )

    if steps_by_group:
        steps_by_group["all"] = [s for g in list(steps_by_group) for s in steps_by_group[g]]
    pairs = []
    if "bandai masculine+normal" in models:
        pairs.append(("bandai masculine+normal", "feminine+youthful"))
        pairs.append(("bandai masculine+normal", "masculine+normal"))
    if "default" in models:
        pairs += [("default", g) for g in steps_by_group]
    for name, group in pairs:
        rep = fidelity_from_steps(
            models[name], steps_by_group[group], np.random.default_rng(0), n_chains=args.chains
        )
        out.setdefault("fidelity", {})[f"{name} vs {group}"] = rep
        print(f"\n=== fidelity: model '{name}' vs bandai {group} ===")
        print(format_fidelity_table(rep))

    if steps_by_group:
        floors = {
            "masculine+normal vs feminine+youthful": _steady_ks(
                steps_by_group["masculine+normal"], steps_by_group["feminine+youthful"]
            )
        }
        if "default" in models:
            for g in steps_by_group:
                floors[f"default corpus vs {g}"] = _steady_ks(corpus_steps, steps_by_group[g])
        out["floors"] = floors
        print("\n=== floors: KS between captured steady-state steps ===")
        for name, ks in floors.items():
            print(f"{name:40s} " + "  ".join(f"{k} {v:.3f}" for k, v in ks.items()))

    if args.json:
        Path(args.json).write_text(json.dumps(out, indent=2, default=str))
    sys.stdout.flush()


def _steady_ks(a, b) -> dict[str, float]:
    """KS statistics between two sets of captured steps, initiations/terminations left out."""
    from scipy.stats import ks_2samp

    from mjwalk.gait.fidelity import METRICS, capture_step_metrics

    def steady(steps):
        m = [s for s in steps if not (s.meta.get("initiation") or s.meta.get("termination"))]
        return capture_step_metrics(m)

    ma, mb = steady(a), steady(b)
    return {k: float(ks_2samp(ma[k], mb[k]).statistic) for k in METRICS}


if __name__ == "__main__":
    main()
