"""The leg synthesis's steps in one compiled call (mjwalk.body.legs.synthloop) give the step
by step path's tracks bit for bit (every byte, signed zeros included) on seeded walks of many
shapes, and references off the unit cycle keep the step path."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from mjwalk.body.humanoid import leg_geometry
from mjwalk.body.legs import synthesis, synthloop
from mjwalk.body.legs.reference import DEFAULT_REFERENCE, ReferenceGait, winter_reference
from mjwalk.body.legs.swing import step_chord
from mjwalk.body.legs.synthloop import N_CONSTS, loop_consts
from mjwalk.plan.synthetic import synthetic_walk


def _tracks(legs) -> list[bytes]:
    """Every track of a LegMotion as bytes (dtype and sign of zero count), in a fixed order."""
    arrays = [legs.root, legs.yaw, legs.contact, legs.phase]
    for d in (legs.angles, legs.ankle, legs.pitch):
        arrays += [d[k] for k in sorted(d)]
    return [a.dtype.str.encode() + a.tobytes() for a in arrays]


def _both(monkeypatch, walk, stature, reference=None) -> tuple[list[bytes], list[bytes]]:
    """The tracks of ``walk`` with the steps in one compiled call and step by step."""
    monkeypatch.setattr(synthesis, "COMPILED_STEPS", True)
    one = _tracks(synthesis.legs_from_walk(walk, stature, reference))
    monkeypatch.setattr(synthesis, "COMPILED_STEPS", False)
    steps = _tracks(synthesis.legs_from_walk(walk, stature, reference))
    return one, steps


def _seeded_walks(seed: int, count: int):
    """``count`` synthetic walks with parameters drawn from ``seed``: straight and turning
    either way, short quick and long slow steps, narrow and wide, held or not at the end."""
    rng = np.random.default_rng(seed)
    for _ in range(count):
        radius = None if rng.random() < 0.4 else float(rng.choice([-1, 1]) * rng.uniform(0.8, 4))
        yield (
            synthetic_walk(
                n_steps=int(rng.integers(1, 9)),
                step_len=float(rng.uniform(0.08, 0.95)),
                width=float(rng.uniform(0.08, 0.3)),
                step_time=float(rng.uniform(0.4, 0.8)),
                sway=float(rng.uniform(0.0, 0.05)),
                radius=radius,
                start=(float(rng.uniform(-3, 3)), float(rng.uniform(-3, 3)), rng.uniform(-3, 3)),
                hold=float(rng.choice([0.0, 0.25])),
            ),
            float(rng.uniform(1.5, 2.0)),
        )


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_one_call_gives_the_step_paths_tracks_bit_for_bit(monkeypatch, seed):
    """40 seeded walks a seed (120 in all, statures 1.5-2.0 m): every track's bytes equal."""
    calls = []
    kept = synthloop.synth_steps

    def counted(*args):
        calls.append(1)
        return kept(*args)

    monkeypatch.setattr(synthesis, "synth_steps", counted)
    walks = list(_seeded_walks(seed, 40))
    for walk, stature in walks:
        one, steps = _both(monkeypatch, walk, stature)
        assert one == steps, (seed, len(walk.steps), stature)
    assert len(calls) == len(walks)  # the compiled call ran, once a walk


def test_winter_table_and_early_lift_offs_bit_for_bit(monkeypatch):
    """The plain Winter table (also on the unit cycle) and walks whose trailing foot lifts off
    early (short quick steps, long slow ones): equal bytes."""
    walks = [
        synthetic_walk(n_steps=6),
        synthetic_walk(n_steps=6, radius=1.2),
        synthetic_walk(n_steps=5, step_len=0.12, step_time=0.45),
        synthetic_walk(n_steps=4, step_len=0.95, step_time=0.6),
    ]
    for ref in (DEFAULT_REFERENCE, winter_reference()):
        for walk in walks:
            one, steps = _both(monkeypatch, walk, 1.75, ref)
            assert one == steps


def test_a_reference_off_the_unit_cycle_keeps_the_step_path(monkeypatch):
    """A table whose cycle is not [0, 1] (here [0, 0.999]) takes the scipy splines step by
    step: the compiled call is not made, and the legs come out."""
    base = DEFAULT_REFERENCE
    ref = ReferenceGait(
        cycle=base.cycle * 0.999, hip=base.hip, knee=base.knee, pitch=base.pitch, source="0.999"
    )
    assert not ref._unit

    def refuse(*args):
        raise AssertionError("the compiled loop took a reference off the unit cycle")

    monkeypatch.setattr(synthesis, "synth_steps", refuse)
    legs = synthesis.legs_from_walk(synthetic_walk(n_steps=4), 1.75, ref)
    assert np.isfinite(legs.root).all()


def test_loop_consts_fill_every_slot():
    """The walk's scalars: every slot set, the squares as the step path takes them."""
    geom = leg_geometry(1.75)
    c = loop_consts(DEFAULT_REFERENCE, geom, 0.3, 0.8, 0.81)
    assert c.shape == (N_CONSTS,) and np.isfinite(c).all()
    assert c[synthloop.C_D_LAND_SQ] == 0.8**2 and c[synthloop.C_TWO] == 2.0
    assert c[synthloop.C_KL1SQ] == geom.thigh**2


def test_step_chords_are_step_chords_numbers():
    """synthloop.step_chords gives swing.step_chord's turn, chord, squared length and normal of
    every step bit for bit: seeded footprints with turns past pi either way, short and long
    chords, a zero chord and signed zeros."""
    rng = np.random.default_rng(21)
    m = 4000
    lift = np.column_stack([rng.uniform(-20, 20, (m, 2)), rng.uniform(-7, 7, m)])
    land = lift + np.column_stack(
        [rng.normal(0, 0.4, (m, 2)) * rng.choice([1e-6, 1e-3, 1.0], (m, 1)), rng.normal(0, 2, m)]
    )
    land[:3] = lift[:3]  # no chord, no turn
    lift[3], land[3] = [0.0, -0.0, -0.0], [-0.0, 0.0, 0.0]
    got = synthloop.step_chords(lift, land)
    for k in range(m):
        fr = SimpleNamespace(lift=lift[k], land=land[k])
        want = step_chord(fr)  # type: ignore[arg-type]
        assert np.array([want[0]]).tobytes() == got[0][k : k + 1].tobytes()
        assert want[1].tobytes() == got[1][k].tobytes()
        assert np.array([want[2]]).tobytes() == got[2][k : k + 1].tobytes()
        assert want[3].tobytes() == got[3][k].tobytes()
