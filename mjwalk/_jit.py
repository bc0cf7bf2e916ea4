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

#: ``fastmath`` off by default: the arithmetic stays that of the NumPy code it replaces.
njit = numba.njit(cache=True, nogil=True, fastmath=False)
#: For long dot products: the sums may be reassociated (and multiply-adds fused), so they
#: vectorize, as BLAS's do; nothing else of fastmath (NaN and inf stay IEEE).
njit_sum = numba.njit(cache=True, nogil=True, fastmath={"reassoc", "contract"})
