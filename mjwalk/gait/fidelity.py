"""Fidelity of a :class:`StepModel` against captured walking (`mjwalk validate` runs it through
:mod:`mjwalk.gait.training`).

Two comparisons (agethen2018 §5.2 reports path-length medians and IQRs the same way):

**Step statistics.** ``n_chains`` chains of ``chain_length`` steps are sampled from the model
(a KDE starter, then one GP successor after another). Like is compared with like: the *steady
state* of the model, every chain step after the KDE starter, against the captured steps that
are neither a gait initiation nor a termination (``Step.meta``; the model's chains never stop,
and a capture of short clips holds many more starts and stops per step than a chain of
``chain_length`` steps, so pooling them would compare clip lengths, not gaits); separately, the
KDE starters against the captured initiation steps (``initiation`` in the report; few in clips
that start in motion). Each pair is compared by the two-sample Kolmogorov-Smirnov statistic
(``scipy.stats.ks_2samp``) on

* step length: straight-line pelvis displacement over the step (m);
* step duration (s); a model step plays back at the capture's frame rate with
  round(T·fps) + 1 samples (:meth:`StepBatch.n_samples`), so its duration is compared at that
  resolution (captured durations are whole frames: at 120 Hz up to 11 % of the steps share one
  value, and comparing them with unrounded model durations adds up to ~0.05 to the KS);
* lateral sway amplitude: half the peak-to-peak signed distance of the pelvis path from the
  step's chord (start -> end), m (:func:`sway_amplitude`);
* heading change: pelvis yaw at the end of the step relative to its start (rad).

**Straight walks** (:mod:`mjwalk.gait.straight`): the capture's straight walks beside the
model's greedy walks over the same distances; medians and IQRs of time and path length are
reported, capture beside model.
"""

from __future__ import annotations

import glob as _glob
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike
from scipy.stats import ks_2samp

from mjwalk.errors import MjwalkError
from mjwalk.gait.features import StepBatch, concat_batches
from mjwalk.gait.model import StepModel
from mjwalk.gait.pace import capture_pace, model_pace
from mjwalk.gait.segment import segment_takes
from mjwalk.gait.step import Step
from mjwalk.gait.straight import (
    PATH_SAMPLES,
    captured_straight_walks,
    model_straight_walks,
    resample_step,
)
from mjwalk.mocap import load_amc, load_bvh

METRICS = ("length", "duration", "sway", "heading")
_UNITS = {"length": "m", "duration": "s", "sway": "m", "heading": "rad"}


# --------------------------------------------------------------------------------------------
# Per-step metrics
# --------------------------------------------------------------------------------------------


def sway_amplitude(pelvis: np.ndarray) -> np.ndarray:
    """Half peak-to-peak lateral pelvis excursion from the chord.

    With the chord c = p_{m-1} - p_0, the lateral coordinate of sample j is
    d_j = (c_x (p_j - p_0)_y - c_y (p_j - p_0)_x) / |c| (positive to the left of the chord), and
    the amplitude is (max_j d_j - min_j d_j) / 2.

    Args:
        pelvis: (n, m, 2) or (m, 2) paths, metres (any planar frame).

    Returns:
        (n,) amplitudes, metres, or a scalar for one (m, 2) path.
    """
    p = np.asarray(pelvis, dtype=float)
    single = p.ndim == 2
    p = np.atleast_3d(p) if not single else p[None]
    chord = p[:, -1] - p[:, 0]
    norm = np.maximum(np.hypot(chord[:, 0], chord[:, 1]), 1e-12)
    rel = p - p[:, :1]
    lat = (chord[:, None, 0] * rel[..., 1] - chord[:, None, 1] * rel[..., 0]) / norm[:, None]
    amp = 0.5 * (lat.max(axis=1) - lat.min(axis=1))
    return amp[0] if single else amp


def capture_step_metrics(steps: Sequence[Step]) -> dict[str, np.ndarray]:
    """Per-step length, duration, sway and heading change of captured steps.

    Args:
        steps: n captured steps (local frames).

    Returns:
        ``{"length", "duration", "sway", "heading"}`` -> (n,) arrays: metres, seconds,
        metres (:func:`sway_amplitude` on :data:`PATH_SAMPLES` samples), radians.
    """
    paths = np.stack([resample_step(s) for s in steps]) if steps else np.zeros((0, 2, 2))
    return {
        "length": np.array([s.length for s in steps]),
        "duration": np.array([s.duration for s in steps]),
        "sway": sway_amplitude(paths) if len(steps) else np.zeros(0),
        "heading": np.array([s.end_yaw for s in steps]),
    }


def batch_step_metrics(batch: StepBatch, fps: float | None = None) -> dict[str, np.ndarray]:
    """The metrics of :func:`capture_step_metrics` for decoded model steps.

    Args:
        batch: n decoded steps.
        fps: when given, durations are those of the steps played back at ``fps`` Hz (whole
            frames, round(T·fps) / fps, as :meth:`StepBatch.n_samples`); None: the raw T.

    Returns:
        ``{"length", "duration", "sway", "heading"}`` -> (n,) arrays: m, s, m, rad.
    """
    pelvis, _ = batch.resample(PATH_SAMPLES)
    duration = batch.duration.copy() if fps is None else np.round(batch.duration * fps) / fps
    return {
        "length": batch.length,
        "duration": duration,
        "sway": sway_amplitude(pelvis),
        "heading": batch.end_yaw.copy(),
    }


# --------------------------------------------------------------------------------------------
# Report
# --------------------------------------------------------------------------------------------


def _describe(x: ArrayLike) -> dict[str, float]:
    x = np.asarray(x, dtype=float)
    if x.size == 0:
        return {"n": 0}
    q1, med, q3 = np.percentile(x, [25, 50, 75])
    return {
        "n": int(x.size),
        "mean": float(x.mean()),
        "sd": float(x.std(ddof=1)) if x.size > 1 else 0.0,
        "median": float(med),
        "iqr": float(q3 - q1),
    }


def fidelity_from_steps(
    model: StepModel,
    steps: Sequence[Step],
    rng: np.random.Generator,
    *,
    n_chains: int = 400,
    chain_length: int = 8,
    straight_deg: float = 20.0,
    planned: int = 3,
    planned_walks=None,
) -> dict:
    """Fidelity report against already segmented captured ``steps`` (see module docstring).

    Args:
        model: the step model to assess.
        steps: segmented captured steps (their ``meta`` marks initiations/terminations).
        rng: generator for the model's chains and walks.
        n_chains: sampled chains.
        chain_length: steps per chain, >= 2 (the first is the KDE starter).
        straight_deg: largest total heading change of a straight walk, degrees.
        planned: planned walks per captured straight walk (0: none).
        planned_walks: :func:`mjwalk.plan.walktimes.planned_straight_walks` (the planner sits
            above this module; the command line passes it), to time every captured straight
            walk as ``planned`` planned walks too (``straight_walks["planned"]``); None: not.

    Returns:
        JSON-serializable dict: ``model`` (summary), ``pace`` (capture, model),
        ``n_capture_steps``, ``n_model_steps``, ``steps`` and ``initiation`` (per metric KS
        statistic, p-value and summaries), ``straight_walks`` (medians and IQRs, capture and model).

    Raises:
        MjwalkError: on no steps, ``chain_length < 2`` or no steady-state captured step.
    """
    if len(steps) == 0:
        raise MjwalkError("fidelity: no captured steps to compare against")
    if chain_length < 2:
        raise MjwalkError(f"fidelity: chain_length must be >= 2, got {chain_length}")
    fps = float(steps[0].fps)
    starts = [bool(s.meta.get("initiation")) for s in steps]
    steady = [s for s, a in zip(steps, starts, strict=True) if not (a or s.meta.get("termination"))]
    if not steady:
        raise MjwalkError("fidelity: every captured step is a gait initiation or termination")
    chains = concat_batches([model.sample_chain(chain_length, rng) for _ in range(n_chains)])
    is_first = np.arange(len(chains)) % chain_length == 0
    step_report = _ks_table(
        capture_step_metrics(steady), batch_step_metrics(chains.take(~is_first), fps)
    )
    init = [s for s, a in zip(steps, starts, strict=True) if a]
    init_report = {"n_capture": len(init), "n_model": int(is_first.sum())}
    if len(init) >= 2:
        init_report.update(
            _ks_table(capture_step_metrics(init), batch_step_metrics(chains.take(is_first), fps))
        )
    cw = captured_straight_walks(steps, straight_deg)
    walks: dict = {"n": len(cw), "straight_deg": straight_deg}
    if cw:
        mw = model_straight_walks(
            model,
            np.array([w["distance"] for w in cw]),
            rng,
            in_motion=np.array([w["in_motion"] for w in cw], dtype=bool),
        )
        for key in ("distance", "time", "path_length"):
            walks[key] = {
                "capture": _describe([w[key] for w in cw]),
                "model": _describe([w[key] for w in mw]),
            }
        walks["model_end_error"] = _describe([w["end_error"] for w in mw])
        if planned and planned_walks is not None:  # the same walks as the planner walks them
            pt = planned_walks(
                model,
                [w["distance"] for w in cw] * planned,
                [bool(w["in_motion"]) for w in cw] * planned,
                rng,
                failed_as_nan=True,
            )
            ok = [t for t in pt if np.isfinite(t)]
            walks["planned"] = {
                "per_walk": planned,
                "failed": len(pt) - len(ok),
                "time": {"capture": walks["time"]["capture"], "model": _describe(ok)},
            }
        walks["n_steps"] = {
            "capture": _describe([w["n_steps"] for w in cw]),
            "model": _describe([w["n_steps"] for w in mw]),
        }
    try:
        cap_pace: dict | None = capture_pace(steps, straight_deg).as_dict()
    except MjwalkError:  # no straight walking in the capture
        cap_pace = None
    return {
        "model": model.summary(),
        "pace": {"capture": cap_pace, "model": model_pace(model).as_dict()},
        "n_capture_steps": len(steady),
        "n_model_steps": int((~is_first).sum()),
        "steps": step_report,
        "initiation": init_report,
        "straight_walks": walks,
    }


def _ks_table(cap: dict[str, np.ndarray], mod: dict[str, np.ndarray]) -> dict:
    out = {}
    for k in METRICS:
        ks = ks_2samp(cap[k], mod[k])
        out[k] = {
            "unit": _UNITS[k],
            "ks": float(ks.statistic),
            "p": float(ks.pvalue),
            "capture": _describe(cap[k]),
            "model": _describe(mod[k]),
        }
    return out


def fidelity_report(
    model: StepModel,
    takes,
    rng: np.random.Generator,
    *,
    n_chains: int = 400,
    chain_length: int = 8,
    straight_deg: float = 20.0,
    planned_walks=None,
) -> dict:
    """Compare step chains of ``model`` with the captured ``takes`` (segmented here).

    The caller writes the report (atomically) if wanted; :func:`format_fidelity_table` renders it.

    Args:
        model: the step model to assess.
        takes: captured takes (:class:`mjwalk.mocap.take.Take`).
        rng: generator for the model's chains and walks.
        n_chains: sampled chains.
        chain_length: steps per chain, >= 2.
        straight_deg: largest total heading change of a straight walk, degrees.
        planned_walks: as :func:`fidelity_from_steps` (with its default ``planned``).

    Returns:
        The :func:`fidelity_from_steps` dict plus ``segmentation`` (the segmentation summary).
    """
    steps, summary = segment_takes(takes)
    report = fidelity_from_steps(
        model,
        steps,
        rng,
        n_chains=n_chains,
        chain_length=chain_length,
        straight_deg=straight_deg,
        planned_walks=planned_walks,
    )
    report["segmentation"] = str(summary)
    return report


def format_fidelity_table(report: dict) -> str:
    """Plain-text table of a :func:`fidelity_report`.

    Args:
        report: the report dict.

    Returns:
        The table, lines joined by newlines.
    """
    lines = [
        f"steady-state steps: capture n={report['n_capture_steps']} (no initiations or "
        f"terminations), model n={report['n_model_steps']} (chain steps after the starter)",
        f"{'metric':<16}{'KS':>7}   {'capture mean±sd':>20}   {'model mean±sd':>20}",
    ]
    for k, r in report["steps"].items():
        c, m = r["capture"], r["model"]
        lines.append(
            f"{k + ' [' + r['unit'] + ']':<16}{r['ks']:>7.3f}   "
            f"{c['mean']:>10.3f} ± {c['sd']:<7.3f}   {m['mean']:>10.3f} ± {m['sd']:<7.3f}"
        )
    pace = report.get("pace", {})
    for who in ("capture", "model"):
        q = pace.get(who)
        if q:
            lines.append(
                f"pace of the {who + ' (steady straight steps)':<31} {q['speed']:.3f} m/s, "
                f"{q['cadence']:.1f} steps/min, step {q['step_length']:.3f} m, "
                f"width {q['step_width']:.3f} m (n={q['n_steps']})"
            )
    walker = report.get("model", {}).get("walker")
    if walker:
        lines.append(
            f"model conditioned on the walker {walker['speed']:.3f} m/s, "
            f"{walker['cadence']:.1f} steps/min, stature {walker['stature']:.2f} m"
        )
    ini = report.get("initiation", {})
    if "length" in ini:
        lines.append(
            f"gait initiation (capture n={ini['n_capture']}, KDE starters n={ini['n_model']}): KS "
            + ", ".join(f"{k} {ini[k]['ks']:.3f}" for k in METRICS)
            + f"; length {ini['length']['capture']['mean']:.3f} vs "
            f"{ini['length']['model']['mean']:.3f} m"
        )
    w = report["straight_walks"]
    lines.append(f"straight walks: n={w['n']} (heading change < {w['straight_deg']}°)")
    if w["n"]:
        lines.append(f"{'':<16}{'capture median (IQR)':>24}   {'model median (IQR)':>22}")
        for key, unit in (("distance", "m"), ("time", "s"), ("path_length", "m")):
            c, m = w[key]["capture"], w[key]["model"]
            lines.append(
                f"{key + ' [' + unit + ']':<16}{c['median']:>14.3f} ({c['iqr']:.3f})   "
                f"{m['median']:>12.3f} ({m['iqr']:.3f})"
            )
        e = w["model_end_error"]
        lines.append(f"model end error to goal [m]: median {e['median']:.3f}, IQR {e['iqr']:.3f}")
        p = w.get("planned")
        if p:
            c, m = p["time"]["capture"], p["time"]["model"]
            planned = f"{m['median']:>12.3f} ({m['iqr']:.3f})" if m["n"] else f"{'-':>12}        "
            lines.append(
                f"{'planned time [s]':<16}{c['median']:>14.3f} ({c['iqr']:.3f})   {planned}   "
                f"(hybrid A*, {p['per_walk']} per walk, {p['failed']} not plannable)"
            )
    return "\n".join(lines)


# --------------------------------------------------------------------------------------------
# Entry points for the CLI
# --------------------------------------------------------------------------------------------


def load_capture(
    bvh: str | None = None,
    amc: str | None = None,
    asf: str | None = None,
    *,
    skeleton: str | None = None,
) -> list:
    """Takes from a BVH glob and/or an AMC glob with its ASF skeleton; sorted by file name.

    Args:
        bvh: glob of ``.bvh`` files, or None.
        amc: glob of ``.amc`` files, or None.
        asf: the ``.asf`` skeleton of the AMC files (required with ``amc``).
        skeleton: skeleton preset, convention or map file (``*.toml``); default: detected from
            the joint names for BVH (:func:`mjwalk.mocap.naming.resolve_skeleton`),
            ``"cmu"`` for AMC.

    Returns:
        The BVH takes, then the AMC takes (metres, z up).

    Raises:
        MjwalkError: when a glob matches nothing or ``amc`` comes without ``asf``.
    """
    takes = []
    if bvh:
        files = sorted(_glob.glob(str(bvh)))
        if not files:
            raise MjwalkError(f"no BVH files match {bvh!r}")
        takes += [load_bvh(f, skeleton=skeleton) for f in files]
    if amc:
        if not asf:
            raise MjwalkError(f"AMC glob {amc!r} given without its ASF skeleton file")
        files = sorted(_glob.glob(str(amc)))
        if not files:
            raise MjwalkError(f"no AMC files match {amc!r}")
        takes += [load_amc(f, asf, skeleton=skeleton or "cmu") for f in files]
    return takes
