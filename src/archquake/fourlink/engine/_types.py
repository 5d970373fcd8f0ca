"""Numba types of the engine's arrays and the declared signatures of its small helpers.

A helper called with a literal constant (``0``, ``1``) would be compiled once for every
combination of literal values at its call sites (a constant is typed ``Literal[int](0)``, not
``int64``); a declared signature makes it one compilation. Arrays are C-contiguous and writable
(the callers pass writable copies: a read-only array is another type, another compilation).
"""

import numba

F8, I8, B1 = numba.float64, numba.int64, numba.boolean
F8_1D, I8_1D = numba.float64[::1], numba.int64[::1]
F8_2D, I8_2D = numba.float64[:, ::1], numba.int64[:, ::1]
F8_3D, F8_4D = numba.float64[:, :, ::1], numba.float64[:, :, :, ::1]
PACKED_PAIR = numba.types.Tuple((F8_2D, I8_2D, F8_2D, F8_4D))
"""Type of :func:`archquake.fourlink.engine.tables.pack_pair`'s ``(scalars, cells, breaks,
coefficients)``."""
