"""The leg IK cache (mjwalk.body.legs.ikcache): re-solved rows and kept yaw sines, bit for
bit those of leg_ik_world."""

from __future__ import annotations

import math

import numpy as np

from mjwalk.body.humanoid import ROM_DEG, leg_geometry
from mjwalk.body.legs.ik import (
    LEG_JOINTS,
    foot_lowest,
    generic_joint,
    hip_world,
    ik_lengths,
    leg_ik_world,
)
from mjwalk.body.legs.ikcache import LegIKCache, clip1, leg_ik_world_cached_where, yaw_trig_row
from mjwalk.conventions import side_of_prefix


def test_cached_where_solves_only_the_chosen_changed_rows():
    """leg_ik_world_cached_where solves the chosen rows whose inputs changed (leg_ik_world's
    angles, bit for bit) and leaves every other row's cached inputs and angles as they were;
    a cache's flexion-only buffers are new (all rows unsolved) for another sample count."""
    g = leg_geometry(1.75)
    rng = np.random.default_rng(3)
    n = 50
    ankle = np.column_stack([rng.uniform(-0.3, 0.3, n), rng.uniform(0, 0.2, n), np.full(n, 0.1)])
    root = np.column_stack([np.zeros(n), np.zeros(n), np.full(n, 0.9)])
    fyaw, pitch, yaw = rng.uniform(-0.2, 0.2, (3, n))
    cache = LegIKCache("l", g)
    inputs, out = cache.buffers(n)
    out[:] = 7.0
    rows = rng.uniform(size=n) < 0.5
    args = (ankle, fyaw, pitch, root, yaw, 1.0, g.hip_y, *ik_lengths(g), inputs, out)
    leg_ik_world_cached_where(rows, *args, *cache.trig_buffers(n))
    want = leg_ik_world(ankle, fyaw, pitch, root, yaw, "l", g)
    for k, name in enumerate(("hip_l_rot", "hip_l_flex", "hip_l_abd", "knee_l", "ankle_l_flex")):
        assert np.array_equal(out[rows, k], want[name][rows])
    assert np.all(out[~rows] == 7.0) and np.all(np.isnan(inputs[~rows]))
    assert np.array_equal(inputs[rows, :3], ankle[rows])
    out[rows] = 8.0  # unchanged inputs: not solved again
    leg_ik_world_cached_where(rows, *args, *cache.trig_buffers(n))
    assert np.all(out[rows] == 8.0)
    f_in, flex = cache.flex_buffers(n)
    assert flex.shape == (n,) and np.all(np.isnan(f_in)) and cache.flex_buffers(n)[1] is flex
    assert cache.flex_buffers(n + 1)[1].shape == (n + 1,)
    key = cache.trig_buffers(n)[0]
    assert np.all(np.isnan(key[~rows])) and cache.trig_buffers(n + 1)[0].shape == (n + 1, 2)


def test_cache_keeps_the_yaws_sines_only_for_the_same_yaws():
    """The IK cache's per-sample sines and cosines of the yaws are reused only for bit-equal
    pelvis and foot yaws (+0.0 and -0.0 told apart): over calls that change the ankles, the
    pitches, the yaws and their zeros' signs, its angles stay leg_ik_world's, bit for bit."""
    g = leg_geometry(1.75)
    rng = np.random.default_rng(5)
    n = 60
    root = np.column_stack([rng.normal(size=(n, 2)), np.full(n, 0.9)])
    root[:5, :2] = -0.0  # signed zeros where the hip's offset adds +-0.0
    yaw = rng.uniform(-4, 4, n)
    yaw[:10] = 0.0
    ankle = root + rng.normal(scale=0.2, size=(n, 3))
    ankle[:5, :2] = 0.0
    ankle[:, 2] = rng.uniform(0.05, 0.3, n)
    fyaw, pitch = yaw + rng.normal(scale=0.3, size=n), rng.normal(scale=0.2, size=n)
    fyaw[:3] = 0.0
    cache = LegIKCache("l", g)
    for step in range(5):
        got = cache(ankle, fyaw, pitch, root, yaw)
        ref = leg_ik_world(ankle, fyaw, pitch, root, yaw, "l", g)
        for k in ref:
            assert np.array_equal(got[k], ref[k]), (k, step)
            assert np.array_equal(np.signbit(got[k]), np.signbit(ref[k])), (k, step)
        ankle = ankle.copy()
        ankle[rng.uniform(size=n) < 0.3, 2] += 0.01  # new ankles under the same yaws
        yaw, fyaw = yaw.copy(), fyaw.copy()
        if step == 1:
            yaw[:10], fyaw[:3] = -0.0, -0.0
        if step == 2:
            yaw[rng.uniform(size=n) < 0.3] += 0.1


def test_yaw_trig_row_tells_signed_zeros_apart():
    """yaw_trig_row's kept numbers are those of the row's own yaws: a yaw of -0.0 after +0.0
    (equal as numbers) is taken again (sin(-yaw) changes its zero's sign), a repeated yaw is
    read back."""
    key, vals = np.full((1, 2), np.nan), np.empty((1, 7))
    for y, fy in ((0.0, 0.3), (-0.0, 0.3), (-0.0, 0.3), (1.2, -0.0), (1.2, 0.0)):
        got = yaw_trig_row(np.array([fy]), np.array([y]), 0, key, vals)
        d = fy - y
        yrel = math.atan2(math.sin(d), math.cos(d))
        want = (math.cos(y), math.sin(y), math.cos(-y), math.sin(-y), yrel, math.cos(yrel),
                math.sin(yrel))  # fmt: skip
        assert got == want and [math.copysign(1, v) for v in got] == [
            math.copysign(1, v) for v in want
        ]


def test_clip1_is_numpys_clip_bit_for_bit():
    """clip1 gives np.clip's numbers for scalar bounds, signed zeros, NaN, infinities and values
    on the bounds included."""
    rng = np.random.default_rng(11)
    special = [0.0, -0.0, np.nan, np.inf, -np.inf, 1.0, -1.0, 0.5, -0.5, 5e-324, -5e-324]
    x = np.concatenate([rng.uniform(-3, 3, 20_000), np.repeat(special, 50)])
    rng.shuffle(x)
    bounds = ((-1.0, 1.0), (0.0, 0.5), (-0.5, -0.0), (-0.0, 0.0), (0.0, 0.0), (-0.0, -0.0))
    for lo, hi in bounds:
        for v in (x, x[::3], np.array(special)):  # long, strided and short arrays
            want = np.clip(v, lo, hi)
            got = np.array([clip1(e, lo, hi) for e in v])
            assert want.tobytes() == got.tobytes()


def test_floor_round_is_the_clipped_ik_and_foot_lowest_bit_for_bit():
    """LegIKCache.floor_round gives the angles of LegIKCache.__call__ clipped by np.clip to the
    humanoid's ranges, the foot's lowest point of hip_world + foot_lowest, and leaves the cache
    as __call__ would, bit for bit (both legs, targets out of reach, joints past their ranges)."""
    rng = np.random.default_rng(5)
    n = 400
    for stature, side in ((1.55, "l"), (1.75, "r"), (1.95, "l")):
        g = leg_geometry(stature)
        ankle = np.column_stack(
            [rng.uniform(-0.9, 0.9, n), rng.uniform(-0.5, 0.5, n), rng.uniform(-0.1, 0.6, n)]
        )
        root = np.column_stack([rng.uniform(-0.2, 0.2, (n, 2)), rng.uniform(0.6, 1.2, n)])
        fyaw, yaw = rng.uniform(-3.5, 3.5, (2, n))
        pitch, toe = rng.uniform(-1.2, 1.2, (2, n))
        toe[:3] = [0.0, -0.0, 2.0]
        a, b = LegIKCache(side, g), LegIKCache(side, g)
        raw = a(ankle, fyaw, pitch, root, yaw)
        names = [k.format(side) for k in LEG_JOINTS]
        lo, hi = np.deg2rad(np.array([ROM_DEG[generic_joint(k)] for k in names])).T
        want = [np.clip(raw[k], lo[i], hi[i]) for i, k in enumerate(names[:6])]
        want.append(np.clip(toe, lo[6], hi[6]))
        hip = hip_world(root, yaw, side, g)
        low_want = hip[:, 2] + foot_lowest(
            dict(zip(names, want, strict=True)), side_of_prefix(side), g
        )
        q, low = b.floor_round(ankle, fyaw, pitch, toe, root, yaw)
        assert [w.tobytes() for w in want] == [r.tobytes() for r in q]
        assert low.tobytes() == low_want.tobytes()
        assert a.out.tobytes() == b.out.tobytes() and a.inputs.tobytes() == b.inputs.tobytes()


def test_shared_trig_is_each_legs_own():
    """share_trig fills both legs' kept sines and cosines with the numbers yaw_trig_row keeps
    for their own yaws (bit for bit, signed zeros, wrap-around and NaN yaws included), and
    the legs then solve as leg_ik_world does."""
    g = leg_geometry(1.75)
    rng = np.random.default_rng(11)
    n = 80
    yaw = rng.uniform(-4.0, 4.0, n)
    fl, fr = yaw + rng.uniform(-0.5, 0.5, n), yaw + rng.uniform(-0.5, 0.5, n)
    yaw[:3], fl[:3], fr[3:5] = (-0.0, 0.0, np.nan), (0.0, -0.0, 1.0), (np.pi, -np.pi)
    left, right = LegIKCache("l", g), LegIKCache("r", g)
    left.share_trig(right, fl, fr, yaw)
    for fy, cache in ((fl, left), (fr, right)):
        key, vals = np.full((n, 2), np.nan), np.empty((n, 7))
        want = np.array([yaw_trig_row(fy, yaw, i, key, vals) for i in range(n)])
        got_key, got = cache.trig_buffers(n)
        ok = ~np.isnan(yaw)
        assert got[ok].tobytes() == want[ok].tobytes()
        assert got_key.tobytes() == key.tobytes()
    ankle = np.column_stack([rng.uniform(-0.3, 0.3, n), rng.uniform(0, 0.2, n), np.full(n, 0.1)])
    root = np.column_stack([rng.uniform(-0.1, 0.1, (n, 2)), np.full(n, 0.9)])
    pitch = rng.uniform(-0.3, 0.3, n)
    for side, fy, cache in (("l", fl, left), ("r", fr, right)):
        got = cache(ankle, fy, pitch, root, yaw)
        want = leg_ik_world(ankle, fy, pitch, root, yaw, side, g)
        for name in want:
            assert got[name].tobytes() == want[name].tobytes(), name
