"""The compiled check's parameter vectors (mjwalk.plan.slots): keyword slots to flat arrays."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.plan import slots


def test_params_fill_named_slots_and_leave_the_rest_nan():
    vec = slots.params(goal_x=1.5, goal_y=-2.0)
    assert vec.shape == (slots.N_PARAMS,)
    assert vec[slots.P_GOAL_X] == 1.5 and vec[slots.P_GOAL_Y] == -2.0
    assert np.isnan(np.delete(vec, [slots.P_GOAL_X, slots.P_GOAL_Y])).all()


def test_iparams_fill_named_slots_and_leave_the_rest_zero():
    vec = slots.iparams(m=16, max_expansions=500)
    assert vec.dtype == np.int64 and vec.shape == (slots.N_IPARAMS,)
    assert vec[slots.I_M] == 16 and vec[slots.I_MAX_EXPANSIONS] == 500
    assert np.count_nonzero(vec) == 2


def test_unknown_slot_names_are_refused():
    with pytest.raises(KeyError):
        slots.params(no_such_slot=1.0)
    with pytest.raises(KeyError):
        slots.iparams(no_such_slot=1)
