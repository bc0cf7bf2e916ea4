"""The seeding scheme (mjwalk.cycle.seeding): run k of the batch of seed s draws from
SeedSequence([s, k]) with three spawned side streams, the same whichever caller builds it."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from mjwalk.cycle.seeding import (
    batch_operator,
    rng_entropy,
    run_generator,
    run_streams,
)
from mjwalk.cycle.simulate import simulate_cycle, simulate_cycles
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.cycle.types import Task

ROOT = Path(__file__).parents[2]


def test_run_generator_is_the_batch_scheme():
    want = np.random.default_rng(np.random.SeedSequence([7, 3])).random(5)
    assert np.array_equal(run_generator(7, 3).random(5), want)
    assert not np.array_equal(run_generator(7, 4).random(5), want)
    assert rng_entropy(run_generator(7, 3)) == [7, 3]
    assert rng_entropy(np.random.default_rng(11)) == 11


def test_side_streams_leave_the_runs_own_draws_alone():
    rng = run_generator(0, 1)
    streams = run_streams(rng)
    assert np.array_equal(rng.random(3), run_generator(0, 1).random(3))
    draws = [s.random() for s in streams]
    assert len(set(draws)) == 3  # three distinct streams
    again = run_streams(run_generator(0, 1))
    assert [s.random() for s in again] == draws  # the same streams, in the same order
    assert rng_entropy(streams.operator) is None  # a spawned stream cannot be re-made alone


def _waiting_cycle():
    """The station cycle reduced to one wait (no walk, no reach: fast), its population kept."""
    spec = load_cycle_spec(ROOT / "scenes" / "assembly_station.toml")
    return dataclasses.replace(spec, tasks=[Task("wait", duration=0.5)])


def test_batch_only_run_and_a_lone_run_draw_the_same_operator():
    spec = _waiting_cycle()
    assert spec.population is not None
    batch = simulate_cycles(spec, runs=3, seed=5, collisions=False)
    only = simulate_cycles(spec, runs=3, seed=5, only=[2], collisions=False)[0]
    alone = simulate_cycle(spec, run_generator(5, 2), run=2, collisions=False, ergonomics=False)
    operators = [batch[2].operator, only.operator, alone.operator, batch_operator(spec, 5, 2)]
    assert all(op == operators[0] for op in operators)
    assert batch[0].operator != batch[2].operator  # the runs draw different operators
    assert (only.entropy, alone.entropy, only.seed) == ([5, 2], [5, 2], 5)
