"""Gait-pose dynamics with contact switching (Remillard & Kry, "Modeling Human Motion and Contact
with Gaussian Processes"): a PCA latent space of walking poses and Gaussian-process dynamics
``z(t+1) = mu_s(z(t))`` with one GP per contact state ``s`` (left stance, right stance, double
support). The switching keeps the sharp changes at foot contacts that a single smooth GP averages
away (which shows as foot skating). Used for the arm swing and torso motion while walking.

Pose vector (one row per frame, 30 Hz): the pelvis forward speed (m/s) and height (m), then joint
angles in radians (legs, arms, torso; names in :attr:`GaitPoseModel.names`). Training poses come
from the project's own walks (:func:`training_poses`: footprint walks of varied step length and
cadence through :mod:`mjwalk.body.legs`, arms counter-swinging, torso counter-rotating, with
per-walk random amplitudes).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import mujoco
import numpy as np
from sklearn.decomposition import PCA
from sklearn.gaussian_process import GaussianProcessRegressor
from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel
from sklearn.neighbors import KNeighborsClassifier
from sklearn.pipeline import Pipeline, make_pipeline
from sklearn.preprocessing import StandardScaler

from mjwalk.body.humanoid import humanoid_model
from mjwalk.body.legs import LegMotion, legs_from_walk
from mjwalk.conventions import DEFAULT_STATURE, SAMPLE_RATE_HZ
from mjwalk.errors import MjwalkError
from mjwalk.plan.synthetic import synthetic_walk

#: Contact states (as in :class:`~mjwalk.body.legs.LegMotion`): left stance, right stance, both.
STATES = (0, 1, 2)
#: Weight of the latent velocity in the GP input, relative to the latent pose (same spread = 1).
VEL_WEIGHT = 0.3
#: Channels of the pose vector after the two root channels.
LEG_CHANNELS = tuple(
    f"{j}_{s}" if j in ("knee", "toe") else f"{j.split('_')[0]}_{s}_{j.split('_')[1]}"
    for s in "lr"
    for j in ("hip_flex", "hip_abd", "hip_rot", "knee", "ankle_flex", "ankle_inv")
)
UPPER_CHANNELS = (
    "shoulder_l_flex",
    "shoulder_r_flex",
    "shoulder_l_abd",
    "shoulder_r_abd",
    "elbow_l",
    "elbow_r",
    "thoracic_rot",
    "lumbar_bend",
    "lumbar_flex",
)
NAMES = ("root_speed", "root_z", *LEG_CHANNELS, *UPPER_CHANNELS)


@dataclass
class GaitPoseModel:
    """A fitted gait-pose model.

    Attributes:
        names: the pose channels (see the module docstring), units m/s, m, radians.
        fps: frame rate of the poses and of the dynamics (Hz).
        pca: standardisation + PCA, the latent space (``n_latent`` dimensions).
        gps: contact state -> GP predicting ``z(t+1) - z(t)`` from ``z(t)``; with
            ``switching=False`` a single GP under key -1.
        classifier: latent point -> contact state (the switching variable of a rollout).
        switching: whether the dynamics switch with the contact state.
        start: (K, 2, q) latent starting points and velocities (training frames at the start of
            double support).
        vel_scale: factor on the latent velocity in the GP input (second-order dynamics).
    """

    names: tuple[str, ...]
    fps: float
    pca: Pipeline
    gps: dict[int, GaussianProcessRegressor]
    classifier: KNeighborsClassifier
    switching: bool
    start: np.ndarray
    vel_scale: float = 1.0

    @property
    def n_latent(self) -> int:
        return int(self.pca[-1].n_components_)

    def rollout(
        self,
        n_frames: int,
        rng: np.random.Generator | None = None,
        z0: np.ndarray | None = None,
        reset: bool = True,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Generate ``n_frames`` poses by iterating the mean dynamics from ``z0``.

        Iterated GP means contract: trained on walks of several step lengths and amplitudes,
        the mean step averages neighbouring cycles and a free rollout's swing shrinks to a
        few degrees within 5-10 s. With ``reset`` (default) the state is put back on the
        training data at every switch into double support (heel strike): onto the training
        heel-strike state (latent pose and velocity, :attr:`start`) nearest to it, a phase
        reset at the contact event; between heel strikes the rollout is the GP's mean.
        Without it (the paper's free mean prediction) the swing after several seconds is
        chance: a mean-prediction simulation can settle on a cycle away from the training
        data (Wang, Fleet & Hertzmann, GPDM project page, "Mean-Prediction vs Optimization");
        this model's 20 s arm-swing ratio went 1.0 -> 0.13-1.76 with 0.1 deg of smooth noise
        on its training poses. :func:`upper_body_from_legs` uses the reset.

        Args:
            n_frames: the number of poses, >= 1 (else MjwalkError).
            rng: chooses the training start point when ``z0`` is None (None: the first one).
            z0: (2, q) latent pose and latent velocity per frame to start from.
            reset: put the state back on the training heel-strike states at each heel strike.

        Returns:
            poses (n_frames, D) in the units of :attr:`names` and contact states (n_frames,).
        """
        if n_frames < 1:
            raise MjwalkError(f"gaitpose rollout: n_frames must be >= 1, got {n_frames}")
        if z0 is None:
            k = 0 if rng is None else int(rng.integers(len(self.start)))
            z0 = self.start[k]
        z0 = np.asarray(z0, float).reshape(2, -1)
        z = np.zeros((n_frames + 1, self.n_latent))
        z[0], z[1] = z0[0] - z0[1], z0[0]
        s = np.zeros(n_frames, dtype=int)
        anchors = np.hstack([self.start[:, 0], self.vel_scale * self.start[:, 1]])
        for t in range(n_frames):
            s[t] = int(self.classifier.predict(z[t + 1 : t + 2])[0])
            if reset and t > 0 and s[t] == 2 and s[t - 1] != 2:
                x = np.hstack([z[t + 1], self.vel_scale * (z[t + 1] - z[t])])
                k = int(np.argmin(((anchors - x) ** 2).sum(1)))
                z[t], z[t + 1] = self.start[k, 0] - self.start[k, 1], self.start[k, 0]
            if t + 1 < n_frames:
                gp = self.gps[s[t]] if self.switching else self.gps[-1]
                x = np.hstack([z[t + 1], self.vel_scale * (z[t + 1] - z[t])])[None]
                z[t + 2] = z[t + 1] + gp.predict(x)[0]
        z = z[1:]
        return self.pca.inverse_transform(z), s


def _upper_body(legs: LegMotion, amp: np.ndarray) -> dict[str, np.ndarray]:
    """Arm swing and torso motion that go with the legs (amplitudes ``amp`` per walk)."""
    out = {}
    for s in "lr":
        hip = legs.angles[f"hip_{s}_flex"]
        # the shoulder swings against the hip, ``amp[0]`` radians either side of its mean
        # whatever the reference gait's hip range (which differs by ~10 deg between references)
        centred = hip - hip.mean()
        sh = -amp[0] * centred / max(float(np.percentile(np.abs(centred), 95)), 1e-6)
        out[f"shoulder_{s}_flex"] = sh
        out[f"shoulder_{s}_abd"] = np.full_like(hip, amp[1])
        out[f"elbow_{s}"] = amp[2] + np.clip(sh, 0, None) / 3
    diff = legs.angles["hip_l_flex"] - legs.angles["hip_r_flex"]
    out["thoracic_rot"] = amp[3] * diff  # shoulders counter-rotate against the pelvis
    out["lumbar_bend"] = amp[4] * (legs.root[:, 1] - legs.root[:, 1].mean()) / 0.03
    out["lumbar_flex"] = np.full_like(diff, amp[5])
    return out


def training_poses(
    rng: np.random.Generator, n_walks: int = 6, fps: float = 30.0, stature: float = DEFAULT_STATURE
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Walking poses from the project's own gait (no capture needed).

    Each walk draws a step length (0.55-0.75 m), step time (0.50-0.60 s), pelvis sway and arm /
    torso amplitudes from ``rng``; the first two steps (gait start) are dropped.

    Args:
        rng: the random draws (in the order above, per walk).
        n_walks: the number of synthetic walks.
        fps: the pose rate, frames per second.
        stature: the humanoid's stature, metres.

    Returns:
        poses (T, D) in the channels :data:`NAMES`, contact states (T,), walk ids (T,).
    """
    poses, states, ids = [], [], []
    for w in range(n_walks):
        L = rng.uniform(0.55, 0.75)
        T = rng.uniform(0.50, 0.60)
        walk = synthetic_walk(10, L, step_time=T, sway=rng.uniform(0.02, 0.04), hold=0.0)
        legs = legs_from_walk(walk, stature)
        # amplitudes: shoulder swing either side (7-11 deg: 15-22 deg peak to peak, what the
        # earlier hip-proportional swing gave on the Winter reference), shoulder abduction,
        # elbow flexion, thoracic counter-rotation per radian of hip difference, lumbar side
        # bend per 3 cm of pelvis sway, lumbar flexion
        amp = np.array(
            [
                np.deg2rad(rng.uniform(7, 11)),
                np.deg2rad(rng.uniform(4, 8)),
                np.deg2rad(rng.uniform(10, 20)),
                rng.uniform(0.1, 0.2),
                np.deg2rad(rng.uniform(1, 3)),
                np.deg2rad(rng.uniform(2, 6)),
            ]
        )
        up = _upper_body(legs, amp)
        speed = np.gradient(legs.root[:, 0], legs.t)
        cols = [speed, legs.root[:, 2]]
        cols += [legs.angles[c] for c in LEG_CHANNELS] + [up[c] for c in UPPER_CHANNELS]
        q = np.column_stack(cols)
        t_out = np.arange(walk.t[walk.steps[2].start], walk.t[walk.steps[-1].end], 1.0 / fps)
        idx = np.round(t_out * SAMPLE_RATE_HZ).astype(int)
        poses.append(q[idx])
        states.append(legs.contact[idx])
        ids.append(np.full(len(idx), w))
    return np.vstack(poses), np.concatenate(states), np.concatenate(ids)


def fit_gaitpose(
    poses: np.ndarray,
    states: np.ndarray,
    walk_ids: np.ndarray,
    switching: bool = True,
    variance: float = 0.995,
    fps: float = 30.0,
    max_points: int = 300,
    rng: np.random.Generator | None = None,
) -> GaitPoseModel:
    """Fit the latent space and the GP dynamics of a gait-pose model.

    The latent space: standardised poses, PCA keeping ``variance`` (99.5 % because the foot
    position is sensitive to truncation, the paper's Fig. 1). The GP dynamics: zero mean,
    constant * RBF + white noise, hyper-parameters by maximum marginal likelihood, one per
    contact state when ``switching``. The GP input is the latent pose and its velocity
    (weighted :data:`VEL_WEIGHT`), the output the next latent step.

    Args:
        poses: (T, D) poses in the channels :data:`NAMES`.
        states: (T,) contact states (0 left stance, 1 right stance, 2 double support).
        walk_ids: (T,) walk of each pose (transitions do not cross walks).
        switching: one GP per contact state (else one for all).
        variance: the share of the pose variance the PCA keeps.
        fps: the pose rate, frames per second.
        max_points: the most transitions each GP sees (a random subset drawn with ``rng``).
        rng: the subset draws (default seed 0).

    Returns:
        the fitted :class:`GaitPoseModel`.
    """
    rng = rng or np.random.default_rng(0)
    poses = np.asarray(poses, float)
    pca = make_pipeline(StandardScaler(), PCA(n_components=variance, svd_solver="full"))
    z = pca.fit_transform(poses)
    # second-order dynamics: the GP input is the latent pose and its velocity (scaled to the
    # pose's spread), which separates poses that repeat at different walking speeds
    ok = (walk_ids[2:] == walk_ids[1:-1]) & (walk_ids[1:-1] == walk_ids[:-2])
    vel_scale = VEL_WEIGHT * float(z.std() / max(np.diff(z, axis=0).std(), 1e-9))
    x_in = np.hstack([z[1:-1], vel_scale * (z[1:-1] - z[:-2])])[ok]
    dz, s0 = (z[2:] - z[1:-1])[ok], states[1:-1][ok]

    def gp(mask):
        i = np.flatnonzero(mask)
        if len(i) > max_points:
            i = np.sort(rng.choice(i, max_points, replace=False))
        if len(i) < 5:
            raise MjwalkError(f"fit_gaitpose: only {len(i)} training transitions for a GP")
        kern = ConstantKernel(1.0, (1e-2, 1e2)) * RBF(1.0, (0.3, 30.0)) + WhiteKernel(
            1e-5, (1e-8, 1e-3)
        )
        return GaussianProcessRegressor(kern, normalize_y=True, random_state=0).fit(x_in[i], dz[i])

    gps = {s: gp(s0 == s) for s in STATES} if switching else {-1: gp(np.ones(len(s0), bool))}
    clf = KNeighborsClassifier(n_neighbors=3).fit(z, states)
    same = walk_ids[1:] == walk_ids[:-1]
    ds_start = np.flatnonzero((states[1:] == 2) & (states[:-1] != 2) & same) + 1
    start = np.stack([z[ds_start], z[ds_start] - z[ds_start - 1]], axis=1)
    return GaitPoseModel(NAMES, fps, pca, gps, clf, switching, start, vel_scale)


@functools.lru_cache(maxsize=4)
def default_gaitpose(switching: bool = True, seed: int = 0) -> GaitPoseModel:
    """The model fitted on :func:`training_poses` with ``seed`` (cached per process).

    Args:
        switching: one GP per contact state.
        seed: seed of the training walks and the GP subsets.

    Returns:
        the fitted :class:`GaitPoseModel`.
    """
    rng = np.random.default_rng(seed)
    poses, states, ids = training_poses(rng, n_walks=6)
    return fit_gaitpose(poses, states, ids, switching=switching, rng=rng)


def foot_skating(
    poses: np.ndarray,
    fps: float = 30.0,
    stature: float = DEFAULT_STATURE,
    contact_height: float = 0.02,
) -> float:
    """Mean horizontal speed of the lower foot's sole while it touches the floor.

    The root moves forward at the pose's ``root_speed`` (integrated), at height ``root_z``;
    joint angles go through the humanoid's forward kinematics (MuJoCo). A foot counts as touching
    when its sole site is the lower one and below ``contact_height`` metres in two consecutive
    frames. A perfect walk has 0 (planted feet do not slide).

    Args:
        poses: (T, D) poses in the channels :data:`NAMES`.
        fps: the pose rate, frames per second.
        stature: the humanoid's stature, metres.
        contact_height: the sole site's height below which it touches, metres.

    Returns:
        the mean sliding speed, m/s (NaN if no foot touches in two consecutive frames).
    """
    model, jm = humanoid_model(stature)
    data = mujoco.MjData(model)
    col = {n: i for i, n in enumerate(NAMES)}
    x = np.concatenate([[0.0], np.cumsum(poses[:-1, col["root_speed"]]) / fps])
    soles = np.zeros((len(poses), 2, 3))
    sid = [model.site("sole_l").id, model.site("sole_r").id]
    for i, q in enumerate(poses):
        qp = jm.neutral_qpos(model, stature)
        qp[0], qp[2] = x[i], q[col["root_z"]]
        for name in LEG_CHANNELS:
            qp[jm.adr(name)] = q[col[name]]
        data.qpos[:] = qp
        mujoco.mj_kinematics(model, data)
        soles[i] = data.site_xpos[sid]
    low = np.argmin(soles[:, :, 2], axis=1)
    speeds = []
    for i in range(len(poses) - 1):
        k = low[i]
        if (
            low[i + 1] == k
            and soles[i, k, 2] < contact_height
            and soles[i + 1, k, 2] < (contact_height)
        ):
            speeds.append(np.linalg.norm(soles[i + 1, k, :2] - soles[i, k, :2]) * fps)
    return float(np.mean(speeds)) if speeds else float("nan")


def _unwrapped_phase(states: np.ndarray) -> np.ndarray:
    """Gait-cycle position of the left leg (cycles, unwrapped) per frame from contact states.

    A heel strike is the start of a double-support run between single-support runs of
    different sides (flicker between the same side is ignored). A left heel strike (left
    stance follows) starts an integer cycle, a right one the half; linear in time between heel
    strikes, extrapolated at the ends with the neighbouring step's rate. NaN if fewer than two
    heel strikes.
    """
    n = len(states)
    runs: list[tuple[int, int]] = []  # (state, start)
    for i, v in enumerate(states):
        if not runs or runs[-1][0] != v:
            runs.append((int(v), i))
    hs, sides = [], []
    last_single = None
    for j, (v, start) in enumerate(runs):
        if v == 2:
            continue
        if last_single is not None and v != last_single[0]:
            prev = runs[j - 1]
            hs.append(prev[1] if prev[0] == 2 else start)
            sides.append(v)
        last_single = (v, start)
    u = np.full(n, np.nan)
    if len(hs) < 2:
        return u
    base = np.zeros(len(hs))
    cyc = 0
    for j, sd in enumerate(sides):
        if sd == 0 and j > 0:
            cyc += 1
        base[j] = cyc + (0.0 if sd == 0 else 0.5)
    hs_arr = np.array(hs, float)
    frames = np.arange(n, dtype=float)
    u = np.interp(frames, hs_arr, base)
    r0 = (base[1] - base[0]) / (hs_arr[1] - hs_arr[0])
    r1 = (base[-1] - base[-2]) / (hs_arr[-1] - hs_arr[-2])
    u = np.where(frames < hs_arr[0], base[0] + (frames - hs_arr[0]) * r0, u)
    return np.where(frames > hs_arr[-1], base[-1] + (frames - hs_arr[-1]) * r1, u)


def upper_body_from_legs(
    legs: LegMotion,
    t: np.ndarray,
    rng: np.random.Generator | None = None,
    model: GaitPoseModel | None = None,
) -> dict[str, np.ndarray]:
    """Arm swing and torso motion for a leg motion, from a gait-pose rollout.

    The rollout's gait phase (from its contact states) is matched to the legs' phase (from
    their contact states), so arm swing stays in step with the feet over any walk length.

    Args:
        legs: the leg motion (its times and contact states).
        t: (F,) the output times, seconds.
        rng: chooses the rollout's start (see :meth:`GaitPoseModel.rollout`).
        model: the gait-pose model (default :func:`default_gaitpose`).

    Returns:
        joint name -> (F,) angles in radians at the times ``t`` (seconds).
    """
    model = model or default_gaitpose()
    st_t = np.interp(t, legs.t, legs.contact).round().astype(int)
    u_legs = _unwrapped_phase(st_t)
    span = np.nanmax(u_legs) - np.nanmin(u_legs) if np.isfinite(u_legs).any() else 1.0
    n_roll = int((span + 4) * 1.3 * model.fps) + 30
    poses, states = model.rollout(n_roll, rng)
    u_roll = _unwrapped_phase(states)
    ok = np.isfinite(u_roll)
    if ok.sum() < 2:
        raise MjwalkError("gaitpose: the rollout has no foot contact changes (degenerate model)")
    u_r = np.maximum.accumulate(u_roll[ok])
    u_l = np.where(np.isfinite(u_legs), u_legs, 0.0)
    # shift the legs' phase by whole cycles into the rollout's (well-formed) middle
    u_l = u_l - np.floor(np.nanmin(u_l)) + np.ceil(u_r[0]) + 1.0
    out = {}
    col = {n: i for i, n in enumerate(model.names)}
    for name in UPPER_CHANNELS:
        out[name] = np.interp(u_l, u_r, poses[ok, col[name]])
    return out
