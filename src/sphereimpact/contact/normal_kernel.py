"""A solved normal motion read in compiled code: its state at an instant, and its force's extremes.

A normal motion hands compiled code its dense output (or its closed form's constants) as arrays
(:class:`~.motion.KernelState`); :func:`normal_state` evaluates them with the arithmetic of the Python evaluator
(``TaylorDense.single``, ``StackedDOP853.single``, ``spring_damper_state``) and the kernels of the contact layer
build on it (:mod:`.tangential.stick_kernel`, :mod:`.tangential.rigid_kernel`).
:func:`normal_states` is that state at many instants.  :func:`force_extremes` and :func:`force_roots` are
:meth:`.motion.NormalMotion.force_extremes` and :meth:`~.motion.NormalMotion.force_roots` compiled: the force sampled
on the motion's grid by the law's compiled kernel and refined by the very functions the Python path runs
(``ode.events.refined_minimum`` and ``minimise``; ``roots_at`` and ``refine_root``), so their answers are the Python
ones to the bit (tests/test_contact_kernels.py).
"""

from __future__ import annotations

import numba
import numpy as np
from numba import types

from ..ode.dense import TAYLOR, interpolant_pair
from ..ode.events import NOT_FINITE, minimise, refine_root, refined_minimum, roots_at
from ..ode.roots import bracketed_root
from ..ode.series import horner
from .laws.kernels import SIGNATURE
from .laws.spring_damper import KERNEL_KIND as SPRING_DAMPER, spring_damper_state
from ..kernel_cache import refresh

refresh()  # before any kernel is defined: numba's cache of them true to every source they compile

_COMPILE = {"cache": True, "nogil": True, "error_model": "numpy"}
_F, _I = types.float64, types.int64
ARRAY, MATRIX, CUBE = types.float64[::1], types.float64[:, ::1], types.float64[:, :, ::1]
#: The numba type of a normal motion's arrays (:meth:`~.motion.KernelState.arrays`).
NORMAL = types.Tuple((_I, ARRAY, ARRAY, ARRAY, MATRIX, MATRIX, CUBE, MATRIX, _F, _F, _F))

#: The dense outputs' evaluators, inlined into :func:`normal_state`, itself inlined where it is called: a state read by a
#: call cost about 2.5 times the inlined read (the call passed the motion's eleven arrays each time).
_horner = numba.njit(inline="always", **_COMPILE)(horner)
_interpolant_pair = numba.njit(inline="always", **_COMPILE)(interpolant_pair)
_spring_damper_state = numba.njit(inline="always", **_COMPILE)(spring_damper_state)
_minimise = numba.njit(inline="always", **_COMPILE)(minimise)  # inlined: the function it searches is passed
_refined_minimum = numba.njit(inline="always", **_COMPILE)(refined_minimum)
#: The event search's plain code compiled (``ode.events.roots_at``, ``refine_root``, ``ode.roots.bracketed_root``),
#: inlined: the function searched is passed.
roots_at_compiled = numba.njit(inline="always", **_COMPILE)(roots_at)
refine_root_compiled = numba.njit(inline="always", **_COMPILE)(refine_root)
bracketed_root_compiled = numba.njit(inline="always", **_COMPILE)(bracketed_root)


@numba.njit(inline="always", **_COMPILE)
def normal_state(normal, t):
    """(delta [m], delta_dot [m/s]) at t [s]: the normal motion's ``state`` at one instant (its dense output's
    ``single``, then scaled).  ``normal``: :meth:`~.motion.KernelState.arrays`."""
    kind, knots, starts, sizes, cx, cy, f, y_old, w, d_scale, v = normal
    if kind == SPRING_DAMPER:  # eq. 4.1's exact motion (SpringDamperMotion.state): knots are its constants
        return _spring_damper_state(knots, t)
    tau = t * w
    if kind == TAYLOR:  # TaylorDense.single: knots are the steps' ends
        i = min(np.searchsorted(knots, tau), starts.size - 1)
        s = tau - starts[i]
        x, y = _horner(cx[i], s), _horner(cy[i], s)
    else:  # StackedDOP853.single: knots are the step boundaries, f each step's rows in reverse order
        i = min(max(np.searchsorted(knots, tau) - 1, 0), sizes.size - 1)
        x, y = _interpolant_pair(f[i], (tau - starts[i]) / sizes[i], y_old[i, 0], y_old[i, 1])
    return x * d_scale, y * v


@numba.njit(types.UniTuple(ARRAY, 2)(NORMAL, ARRAY), **_COMPILE)
def normal_states(normal, t):
    """(delta [m], delta_dot [m/s]) at each instant of the array t [s]: :func:`normal_state` at each, which is the
    arithmetic of the dense outputs' vectorised evaluation too (``TaylorDense.__call__``, ``StackedDOP853.__call__``),
    element by element."""
    delta, delta_dot = np.empty(t.size), np.empty(t.size)
    for k in range(t.size):
        delta[k], delta_dot[k] = normal_state(normal, t[k])
    return delta, delta_dot


@numba.njit(**_COMPILE)
def _signed_force(t, args):
    """sgn P(t) [N]: the force at t by the law's kernel, signed so that its least value is the sought extreme."""
    normal, force, params, sgn = args
    delta, delta_dot = normal_state(normal, t)
    return sgn * force(delta, delta_dot, params)


@numba.njit(types.UniTuple(_F, 2)(NORMAL, types.FunctionType(SIGNATURE), ARRAY, ARRAY), **_COMPILE)
def force_extremes(normal, force, params, grid):
    """The normal force's smallest and largest values [N] over the contact (:meth:`.motion.NormalMotion.force_extremes`
    compiled): ``normal`` the motion's arrays, ``force`` and ``params`` the law's compiled kernel and its parameters,
    ``grid`` the motion's sample instants [s]."""
    forces = np.empty(grid.size)
    for k in range(grid.size):
        delta, delta_dot = normal_state(normal, grid[k])
        forces[k] = force(delta, delta_dot, params)
    low = _refined_minimum(_signed_force, (normal, force, params, 1.0), grid, forces, _minimise)[1]
    high = _refined_minimum(_signed_force, (normal, force, params, -1.0), grid, -forces, _minimise)[1]
    return low, -high


@numba.njit(types.Tuple((ARRAY, _I, _F, _F))(NORMAL, types.FunctionType(SIGNATURE), ARRAY, ARRAY), **_COMPILE)
def force_roots(normal, force, params, grid):
    """(the instants [s] on ``grid``'s span where the normal force changes sign, status, the bracket that failed):
    ``ode.events.roots`` of :meth:`.motion.NormalMotion.force` compiled, the force sampled and refined by the law's
    compiled kernel.  Status as ``rigid_kernel.grip``'s (``ode.events.raise_failed`` raises the Python search's
    error for each)."""
    forces = np.empty(grid.size)
    for k in range(grid.size):
        delta, delta_dot = normal_state(normal, grid[k])
        forces[k] = force(delta, delta_dot, params)
    if not np.all(np.isfinite(forces)):
        return np.empty(0), NOT_FINITE, 0.0, 0.0
    found = np.empty(grid.size + 1)
    count, status, low, high = roots_at_compiled(_signed_force, (normal, force, params, 1.0), grid, forces, 0, found,
                                                 refine_root_compiled, bracketed_root_compiled)
    return found[:count].copy(), status, low, high
