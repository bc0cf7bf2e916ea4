"""Align an unregistered scan of a hall to the scans before it: level both, hypothesise with
Open3D's feature-based global registration, refine with ICP, and verify with free space.

Indoor scans share their floor, so each is first levelled on its own floor
(:func:`~mjwalk.scan.level.find_floor`): what is left is a heading, a horizontal shift
and a small residual.

1. Hypotheses: Open3D's FPFH features (Rusu et al. 2009) matched by RANSAC
   (``registration_ransac_based_on_feature_matching``), run with distinct seeds on clouds
   thinned to :data:`VOXEL` (:data:`RANSAC_RUNS` to :data:`RANSAC_MAX_RUNS` runs, until
   :data:`AGREEING_RUNS` agree on the best verified placement), so that a second, distinct
   alignment (a symmetric hall) has a chance to show up; and the best of them turned by 90°,
   180° and 270° about its middle (a rectangular hall's twin placements).
2. Each hypothesis is refined by Open3D's point-to-plane ICP (Chen & Medioni 1992) with a
   Tukey biweight, coarse to fine (:data:`ICP_SCHEDULE`), run to convergence; its
   ``fitness`` (share of the scan's points with a counterpart within :data:`ICP_DISTANCE`) and
   ``inlier_rmse`` are kept.
3. Verification. A matching score alone cannot tell a wrong merge: on two ray-cast stations of
   the shipped station FPFH + RANSAC + ICP was 2.27 m wrong with 87 % fitness and 1.0 cm RMSE
   (repetitive geometry), while the true pose matched 3.6 %. So every hypothesis is also
   checked against free space (as in occupancy mapping): where one scan saw *floor*, the
   space above it was seen through, so the other scan must not put a low obstacle there
   (:func:`clash`). A hypothesis is accepted when its fitness is at least :data:`MIN_FITNESS`,
   its clash at most :data:`MAX_CLASH` both ways, and no distinct hypothesis, accepted *or
   refuted*, matches nearly as well (:data:`AMBIGUITY`). Otherwise the scan is refused, by
   name, with the figures, and ``--poses`` is suggested: never a silently wrong merge.
4. Why a refuted rival counts. Free space can refute an alignment, never confirm one: it
   sees only what stands on floor the other scan saw (the space a scanner's rays crossed
   higher up is not known without its position). So an accepted hypothesis must also be the
   distinctly best match, as a feature match is kept only when it is distinctly nearer than
   the second nearest (Lowe 2004, "Distinctive image features from scale-invariant
   keypoints", IJCV 60(2), the distance-ratio test, quoted from memory). A pairwise match
   can pass every local check and still be wrong: "some incorrect matches may be locally
   undetectable" (Huber 2001, "Automatic 3D modeling using range images obtained from unknown
   viewpoints", 3DIM, abstract; journal version Huber & Hebert 2003, "Fully automatic
   registration of multiple 3D data sets", Image and Vision Computing 21(7)).
   When a placement far from it matches as well or better and only free space rules that one
   out, the matched surfaces recur elsewhere (repetitive or two-sided geometry): the overlap
   does not fix the pose, and the one left standing is a survivor, not a finding. Measured on
   two ray-cast stations of the shipped station on either side of the car, (0.2, -1.2) and
   (0.0, 2.75), sharing 3.6 % of their surface: the car looks alike from both long sides, so
   the second station's view of its far side, turned 180°, matches the first's view of its
   near side (fitness 0.74, refuted by a 22 % clash); that placement's half-turned twin (the
   quarter turns of 1.), 1.80 m off the truth, lays the far side on the near one from
   behind and passes the free-space check (fitness 0.41, clash 6.3 %): this rule refuses it.
   The genuine pairs (stations 0 and 2, the PCL room scan split in two views) have no
   distinct rival above 0.60 of their best fitness (docs/decisions/009).

Why the placement is the same on every machine (issue 45). RANSAC's hypotheses need not be:
each run is seeded (``o3d.utility.random.seed``), but the samples a seed gives may differ
between Open3D builds (a parallel loop over one generator; ``std::uniform_int_distribution`` is
defined by the C++ library), and FPFH matching turns a last-bit difference in the input
(another MuJoCo or NumPy) into another hypothesis: with the former refinement, a 1 µm jitter of
the moved station gave the issue's exact failure (61 mm off), or a refusal. So nothing here
relies on the hypotheses being equal. It relies on two things measured on two stations of the
shipped station: (a) the refinement converges to one pose from any hypothesis in its basin: the
six of sixteen seeded hypotheses 0.03-0.23 m and 0.8-4° off all end on the same pose, 0.1 mm
and 0.003° from the truth, where the former single 3 cm ICP (50 iterations, no kernel) ended 1,
58, 61 or 143 mm off depending on the start (the issue's 61 mm among them); and (b) runs
continue until two reach the best verified placement, so that basin is found whatever the
hypotheses (a run finds it about one time in three). What stays machine-dependent is only the
chance that no run of :data:`RANSAC_MAX_RUNS` finds it (about 0.6 % at that rate); the scan is
then refused or takes another placement that passes verification, never a shifted copy of the
right one.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from mjwalk.errors import ScanError
from mjwalk.scan.level import find_floor
from mjwalk.scan.obstacles import FLOOR_TOL
from mjwalk.scan.read import open3d_module

#: Voxel of the clouds the features are computed on, metres: half the 0.10 m local-PCA voxel
#: of the levelling (:data:`~mjwalk.scan.level.VOXEL`), ten times the 5 mm range noise of
#: a terrestrial scanner, so a normal's neighbourhood (2 voxels) is well above the noise.
VOXEL = 0.05
#: Voxel of the last ICP, whose fitness and RMSE are reported, metres: 4 range-noise sigmas.
FINE_VOXEL = 0.02
#: Normal radius and FPFH radius in voxels (Open3D's global-registration tutorial: 2 and 5).
NORMAL_RADIUS, FEATURE_RADIUS = 2.0, 5.0
#: RANSAC: inlier distance 1.5 voxels (the tutorial's) and iterations per run.
RANSAC_DISTANCE = 1.5 * VOXEL
RANSAC_ITERATIONS = 100_000
#: RANSAC runs, each with its own seed: at least :data:`RANSAC_RUNS`; then more, up to
#: :data:`RANSAC_MAX_RUNS`, until :data:`AGREEING_RUNS` of them end (after refinement) on the
#: best placement that passes verification. On the shipped station's stations 0 and 2 a run
#: lands in the right placement's basin 9 times in 26 (measured, seeds 0-15 and 100-109): four
#: runs miss it with probability 0.18, twelve with 0.006.
RANSAC_RUNS, RANSAC_MAX_RUNS, AGREEING_RUNS = 4, 12, 2
#: ICP correspondence distance, metres: six standard deviations of a 5 mm range noise (the
#: floor-plane tolerance :data:`~mjwalk.scan.level.PLANE_TOL`).
ICP_DISTANCE = 0.03
#: Refinement: point-to-plane ICP with correspondence distances shrinking 4x, 2x, 1x
#: :data:`ICP_DISTANCE` (coarse to fine, so a hypothesis 0.2 m / 4° off is pulled in), each
#: with Tukey's biweight (Open3D ``TukeyLoss``) of scale :data:`TUKEY_SHARE` times that
#: distance, so pairs from the scans' non-overlapping parts, which fill the window evenly,
#: weigh little and do not drag the pose: without it the same chain ends 61 mm off on the
#: station (an equally good 3 cm fitness, 0.485), with it at 0.1 mm from every start tried.
ICP_SCHEDULE = (4 * ICP_DISTANCE, 2 * ICP_DISTANCE, ICP_DISTANCE)
TUKEY_SHARE = 0.5
#: ICP stop: relative fitness and RMSE change, iterations (per distance). Converged, not cut
#: short: a pose stopped mid-way would depend on where it started.
ICP_STOP = (1e-9, 1e-9, 50)
#: Smallest fitness accepted: scans sharing less than 30 % of their surface are not
#: registered automatically (the 3DMatch benchmark's threshold for a fragment pair to count
#: as overlapping, Zeng et al. 2017, CVPR).
MIN_FITNESS = 0.30
#: Free-space check: low obstacle points, metres above the floor. Below a chair seat (0.40 m,
#: EN 1335-1) a thing standing on the floor hides the floor under it from every scanner, so
#: one scan's low points over the other's seen floor contradict the alignment; table tops and
#: shelves above it may overhang floor that was seen, so they are not used.
LOW_BAND = (0.05, 0.35)
#: Top-view cell of the free-space check, metres, and the margin around the other scan's
#: obstacles that is not counted as free (2 cells: an alignment error of up to 0.1 m, plus
#: mixed cells at obstacle edges).
CLASH_CELL, CLASH_MARGIN = 0.05, 2
#: Largest share of one scan's low points (of those over the other scan's mapped cells) that
#: may stand on the other's seen-free floor. A right alignment puts points there only through
#: edge effects beyond the margin; a wrong one drags walls across the floor.
MAX_CLASH = 0.10
#: Distinct hypotheses: more than this shift (metres) or turn (degrees) apart.
DISTINCT_SHIFT, DISTINCT_TURN = 0.25, 5.0
#: Ambiguous when a distinct hypothesis (accepted or refuted by free space) reaches this share
#: of the best accepted one's fitness (module docstring, 4; the share is the former rule's,
#: which compared accepted hypotheses only; Lowe 2004 keeps a feature match when its distance
#: is below 0.8 of the second nearest's, quoted from memory).
AMBIGUITY = 0.9


@dataclass(frozen=True)
class Alignment:
    """Result of :func:`align`: ``matrix`` (4, 4) taking the scan's points into the
    reference's frame (metres, z up); the ICP's ``fitness`` (share of the scan's points,
    thinned to :data:`VOXEL`, with a counterpart within :data:`ICP_DISTANCE`: the figure
    checked against :data:`MIN_FITNESS`) and ``rmse`` (metres, of the pairs of the last ICP
    on points thinned to :data:`FINE_VOXEL`); ``clash`` (the larger of the two free-space
    contradiction shares, :func:`clash`); the best distinct runner-up's fitness, whether it
    passed verification or not (0 when none); the scan's name."""

    matrix: np.ndarray
    fitness: float
    rmse: float
    clash: float
    runner_up: float
    source: str

    def line(self) -> str:
        """One line for the report.

        Returns:
            The scan's name, fitness, RMSE (mm) and free-space clash (%).
        """
        return (
            f"{self.source}: registered, fitness {self.fitness:.3f} (share of its points, "
            f"thinned to {VOXEL} m, within {ICP_DISTANCE} m of the others), RMSE "
            f"{1000 * self.rmse:.1f} mm (thinned to {FINE_VOXEL} m), free-space clash "
            f"{100 * self.clash:.1f} %"
        )


def _seen_free(levelled: np.ndarray, origin: np.ndarray, shape: tuple[int, int]):
    """Top-view masks of a levelled cloud on the grid (origin, shape): cells it mapped
    (floor or low obstacle) and cells of floor it saw with no low obstacle near."""
    z = levelled[:, 2]

    def mask(sel):
        m = np.zeros(shape, dtype=bool)
        ij = np.floor((levelled[sel, :2] - origin) / CLASH_CELL).astype(np.int64)
        ok = (ij >= 0).all(axis=1) & (ij[:, 0] < shape[1]) & (ij[:, 1] < shape[0])
        m[ij[ok, 1], ij[ok, 0]] = True
        return m

    floor = mask(np.abs(z) <= FLOOR_TOL)
    low = mask((z >= LOW_BAND[0]) & (z <= LOW_BAND[1]))
    free = floor & ~ndimage.binary_dilation(low, iterations=CLASH_MARGIN)
    return floor | low, free


def clash(moved: np.ndarray, other: np.ndarray) -> float:
    """Share of one scan's low points standing on floor the other saw free.

    Args:
        moved: (N, 3) levelled points of the scan placed, metres.
        other: (M, 3) levelled points of the other scan, metres.

    Returns:
        The share of ``moved``'s low points (:data:`LOW_BAND`) over cells ``other`` mapped that
        stand on its seen-free floor, in [0, 1] (0 when none overlap).
    """
    z = moved[:, 2]
    low = moved[(z >= LOW_BAND[0]) & (z <= LOW_BAND[1]), :2]
    if not len(low):
        return 0.0
    origin = other[:, :2].min(axis=0) - CLASH_CELL
    shape = tuple((np.floor((other[:, :2].max(axis=0) - origin) / CLASH_CELL) + 2).astype(int))
    mapped, free = _seen_free(other, origin, shape[::-1])
    ij = np.floor((low - origin) / CLASH_CELL).astype(np.int64)
    ok = (ij >= 0).all(axis=1) & (ij[:, 0] < mapped.shape[1]) & (ij[:, 1] < mapped.shape[0])
    ij = ij[ok]
    over = mapped[ij[:, 1], ij[:, 0]]
    if not over.any():
        return 0.0
    return float(free[ij[over, 1], ij[over, 0]].sum()) / int(over.sum())


def _apart(a: np.ndarray, b: np.ndarray) -> tuple[float, float]:
    """Shift (metres) and turn (degrees) between two (4, 4) poses."""
    d = np.linalg.inv(a) @ b
    turn = np.degrees(np.arccos(np.clip((np.trace(d[:3, :3]) - 1) / 2, -1, 1)))
    return float(np.linalg.norm(d[:3, 3])), float(turn)


def _distinct(a: np.ndarray, b: np.ndarray) -> bool:
    shift, turn = _apart(a, b)
    return shift > DISTINCT_SHIFT or turn > DISTINCT_TURN


def _passes(h: tuple[float, float, float, np.ndarray]) -> bool:
    return h[0] >= MIN_FITNESS and h[2] <= MAX_CLASH


def _settled(hypotheses: list[tuple[float, float, float, np.ndarray]]) -> bool:
    """Whether :data:`AGREEING_RUNS` refined RANSAC runs end on the best passing placement."""
    passed = [h for h in hypotheses if _passes(h)]
    if not passed:
        return False
    best = max(passed, key=lambda h: h[0])[3]
    return sum(not _distinct(best, h[3]) for h in hypotheses) >= AGREEING_RUNS


def _move(points: np.ndarray, m: np.ndarray) -> np.ndarray:
    return points @ m[:3, :3].T + m[:3, 3]


def align(
    points: np.ndarray, reference: np.ndarray, *, source: str = "scan", seed: int = 0
) -> Alignment:
    """The rigid transform taking ``points`` onto ``reference``.

    Both clouds are levelled on their own floors first; RANSAC on FPFH features proposes
    alignments, ICP refines them, free space verifies them (see the module docstring).

    Args:
        points: (N, 3) points, metres, z up roughly.
        reference: (M, 3) points of the scans before it, metres, z up roughly.
        source: the scan's name in errors and in the alignment's line.
        seed: seeds RANSAC (run ``k`` uses ``seed + k``).

    Returns:
        The alignment: its (4, 4) matrix takes ``points`` into the frame of ``reference``.

    Raises:
        ScanError: naming ``source`` when no hypothesis passes verification (too little
            overlap, or every alignment found contradicts free space) or when two distinct
            ones do (ambiguous).
    """
    lev_p = find_floor(points, source=source)
    lev_r = find_floor(reference, source="the scans before it")
    p = lev_p.apply(points)
    r = lev_r.apply(reference)
    o3d = open3d_module()
    (pc_p, f_p), (pc_r, f_r) = _features(o3d, p), _features(o3d, r)

    def refine(start: np.ndarray) -> tuple[float, float, float, np.ndarray]:
        return _refine(o3d, (pc_p, pc_r), p, r, start)

    hypotheses = _ransac(o3d, (pc_p, f_p), (pc_r, f_r), refine, seed)
    hypotheses += _quarter_turns(p, max(hypotheses, key=lambda h: h[0])[3], refine)
    hypotheses.sort(key=lambda h: -h[0])
    best, runner_up = choose(hypotheses, source)
    rmse, m = _fine_icp(o3d, p, r, best[3])
    total = np.linalg.inv(lev_r.matrix) @ m @ lev_p.matrix
    return Alignment(total, best[0], rmse, best[2], runner_up, source)


def _features(o3d, x: np.ndarray):
    """The cloud ``x`` thinned to :data:`VOXEL`, with normals, and its FPFH features."""
    reg = o3d.pipelines.registration
    kd = o3d.geometry.KDTreeSearchParamHybrid
    pc = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(x)).voxel_down_sample(VOXEL)
    pc.estimate_normals(kd(radius=NORMAL_RADIUS * VOXEL, max_nn=30))
    return pc, reg.compute_fpfh_feature(pc, kd(radius=FEATURE_RADIUS * VOXEL, max_nn=100))


def _tukey(o3d, distance: float):
    """Point-to-plane estimation with a Tukey loss scaled to the correspondence ``distance``."""
    reg = o3d.pipelines.registration
    return reg.TransformationEstimationPointToPlane(reg.TukeyLoss(k=TUKEY_SHARE * distance))


def _refine(
    o3d, clouds: tuple, p: np.ndarray, r: np.ndarray, start: np.ndarray
) -> tuple[float, float, float, np.ndarray]:
    """ICP over :data:`ICP_SCHEDULE` from ``start`` between the thinned ``clouds``; the
    hypothesis (fitness, RMSE, free-space clash both ways, matrix)."""
    reg = o3d.pipelines.registration
    pc_p, pc_r = clouds
    m = start
    for distance in ICP_SCHEDULE:
        icp = reg.registration_icp(
            pc_p, pc_r, distance, m, _tukey(o3d, distance), reg.ICPConvergenceCriteria(*ICP_STOP)
        )
        m = np.asarray(icp.transformation).copy()
    c = max(clash(_move(p, m), r), clash(_move(r, np.linalg.inv(m)), p))
    return float(icp.fitness), float(icp.inlier_rmse), c, m


def _ransac(
    o3d, moving: tuple, fixed: tuple, refine: Callable, seed: int
) -> list[tuple[float, float, float, np.ndarray]]:
    """RANSAC runs on the (cloud, features) pairs, each refined, until they settle."""
    reg = o3d.pipelines.registration
    (pc_p, f_p), (pc_r, f_r) = moving, fixed
    hypotheses: list[tuple[float, float, float, np.ndarray]] = []
    for run in range(RANSAC_MAX_RUNS):
        if run >= RANSAC_RUNS and _settled(hypotheses):
            break
        o3d.utility.random.seed(seed + run)
        res = reg.registration_ransac_based_on_feature_matching(
            pc_p,
            pc_r,
            f_p,
            f_r,
            True,
            RANSAC_DISTANCE,
            reg.TransformationEstimationPointToPoint(False),
            3,
            [
                reg.CorrespondenceCheckerBasedOnEdgeLength(0.9),
                reg.CorrespondenceCheckerBasedOnDistance(RANSAC_DISTANCE),
            ],
            reg.RANSACConvergenceCriteria(RANSAC_ITERATIONS, 0.999),
        )
        hypotheses.append(refine(np.asarray(res.transformation)))
    return hypotheses


def _quarter_turns(
    p: np.ndarray, best_m: np.ndarray, refine: Callable
) -> list[tuple[float, float, float, np.ndarray]]:
    """The best one turned by quarter turns about the middle of its placed points, refined:
    halls are often rectangular with mirror-image fittings, and RANSAC need not find the twin."""
    middle = np.median(_move(p, best_m)[:, :2], axis=0)
    out = []
    for quarter in (1, 2, 3):
        turn = np.eye(4)
        a = quarter * np.pi / 2
        turn[:2, :2] = [[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]
        turn[:2, 3] = middle - turn[:2, :2] @ middle
        out.append(refine(turn @ best_m))
    return out


def choose(
    hypotheses: list[tuple[float, float, float, np.ndarray]], source: str
) -> tuple[tuple[float, float, float, np.ndarray], float]:
    """The refined hypothesis to accept, if any (module docstring, 3 and 4).

    Args:
        hypotheses: refined hypotheses (fitness, RMSE metres, free-space clash, (4, 4)
            matrix), sorted by fitness, best first.
        source: the scan's name in errors.

    Returns:
        The best hypothesis passing :data:`MIN_FITNESS` and :data:`MAX_CLASH`, and the best
        distinct rival's fitness, passing or not (0 when none).

    Raises:
        ScanError: naming ``source`` when none passes, or when a distinct one, passing or
            refuted by free space, reaches :data:`AMBIGUITY` of its fitness.
    """
    passed = [h for h in hypotheses if _passes(h)]
    figures = "; ".join(
        f"fitness {f:.2f}, RMSE {1000 * e:.1f} mm, clash {100 * c:.0f} %"
        for f, e, c, _ in hypotheses
    )
    if not passed:
        raise ScanError(
            f"{source}: could not be aligned to the scans before it: no alignment found has "
            f"at least {100 * MIN_FITNESS:.0f} % of its points matched within {ICP_DISTANCE} m "
            f"and at most {100 * MAX_CLASH:.0f} % of its low points on floor the other scan "
            f"saw empty ({figures}); too little overlap? Give its pose with --poses"
        )
    best = passed[0]
    rivals = [h for h in hypotheses if h is not best and _distinct(best[3], h[3])]
    runner_up = rivals[0][0] if rivals else 0.0
    if runner_up < AMBIGUITY * best[0]:
        return best, runner_up
    if _passes(rivals[0]):
        raise ScanError(
            f"{source}: cannot be aligned to the scans before it unambiguously: two "
            f"alignments over {DISTINCT_SHIFT} m or {DISTINCT_TURN:g}° apart both pass "
            f"(fitness {best[0]:.2f} and {runner_up:.2f}; a symmetric hall?); give its pose "
            "with --poses"
        )
    shift, turn = _apart(best[3], rivals[0][3])
    raise ScanError(
        f"{source}: could not be aligned to the scans before it: the alignment that passes "
        f"the free-space check (fitness {best[0]:.2f}, clash {100 * best[2]:.1f} %) is not the "
        f"best match: one {shift:.2f} m and {turn:.0f}° from it matches "
        f"{'more' if runner_up > best[0] else 'nearly as well'} (fitness {runner_up:.2f}) but "
        f"puts {100 * rivals[0][2]:.0f} % of its low points on floor the other scan saw empty, "
        "so the shared surfaces recur and do not fix the pose (repetitive or two-sided "
        "geometry?); give its pose with --poses"
    )


def _fine_icp(o3d, p: np.ndarray, r: np.ndarray, m: np.ndarray) -> tuple[float, np.ndarray]:
    """The figures reported: a last point-to-plane ICP from ``m`` on clouds thinned to
    :data:`FINE_VOXEL`, so the RMSE measures the surfaces' agreement rather than the
    :data:`VOXEL` spacing of the thinned points; (RMSE metres, (4, 4) matrix)."""
    reg = o3d.pipelines.registration
    kd = o3d.geometry.KDTreeSearchParamHybrid
    fine_p, fine_r = (
        o3d.geometry.PointCloud(o3d.utility.Vector3dVector(x)).voxel_down_sample(FINE_VOXEL)
        for x in (p, r)
    )
    fine_r.estimate_normals(kd(radius=NORMAL_RADIUS * VOXEL, max_nn=30))
    icp = reg.registration_icp(
        fine_p,
        fine_r,
        ICP_DISTANCE,
        m,
        _tukey(o3d, ICP_DISTANCE),
        reg.ICPConvergenceCriteria(*ICP_STOP),
    )
    return float(icp.inlier_rmse), np.asarray(icp.transformation)
