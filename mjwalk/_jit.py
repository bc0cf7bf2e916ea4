"""Compiled inner loops: numba's ``njit`` with mjwalk's settings.

The hybrid A* spends its time in a few dozen small array operations per sampled step (GP
successor draws, decoding, collision and reach checks): in NumPy each costs more in call
overhead than in arithmetic. numba compiles those loops once per machine (``cache=True``: the
machine code is kept beside the module, or in numba's user-wide cache where that is read-only;
a fresh checkout compiles in a few seconds on first use). Compiled functions take
``numpy.random.Generator`` arguments and draw from the same bit generator with NumPy's own
algorithms, so a seed gives the same numbers inside and outside them.
"""

from __future__ import annotations

import numba

#: ``fastmath`` stays off: the GP variance is a cancellation (C - k W kᵀ ~ 1e-3 C) that
#: reassociated sums would spoil; ``boundscheck`` off as usual.
njit = numba.njit(cache=True, nogil=True, fastmath=False)
