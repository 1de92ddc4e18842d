"""The rigid tangential contact's grip searches, compiled: where a sliding phase's slip falls to zero, and where the
positive normal impulse J+ reaches given levels (a sweep's grip instants).

A sliding phase of :class:`~.rigid.TangentialMotion` ends where sigma (v_t - omega R) falls through zero, the slip read
off the positive normal impulse J+ (:func:`~.rigid.from_impulse`): in Python a search sampled on the normal motion's
grid and refined by Brent's method, each evaluation reading the dense output, most of a gripping impact's tangential
cost.  :func:`grip` is that search compiled: the normal motion enters as its dense output's arrays
(:func:`~..normal_kernel.normal_state`, the arithmetic of its Python evaluator), the slip is the Python functions'
arithmetic in their order, and the sampling and refinement are the very functions the Python search runs
(``ode.events.roots_at``, ``refine_root``, ``ode.roots.bracketed_root``), so its instant is the Python one to the bit
(tests/test_contact_kernels.py).  It serves a contact whose force pushes over one interval (J+ = J - J(a) there),
the force criterion's case; the Python search serves the others.  :func:`positive_impulses` and
:func:`impulse_gaps` are the functions ``PositiveImpulse.instants`` evaluates on the same terms (J+ on the grid, and
the function its Newton iteration, ``ode.roots.falling_root``, runs on).
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types

from ...ode.events import NOT_FINITE
from ...ode.roots import ROOT
from ..laws.kernels import SIGNATURE
from ..normal_kernel import (ARRAY, NORMAL, bracketed_root_compiled, normal_state, refine_root_compiled,
                             roots_at_compiled)
from ...kernel_cache import refresh

refresh()  # before any kernel is defined: numba's cache of them true to every source they compile

_COMPILE = {"cache": True, "nogil": True, "error_model": "numpy"}
_F, _I = types.float64, types.int64
#: The phase's numbers in :func:`grip`'s ``phase`` array, in order.
PHASE = ("sigma", "mu", "mass", "radius", "inertia_factor", "v0", "omega0", "t0", "g_tangent", "j0")
#: The one pushing interval's numbers in the ``pushing`` array every kernel here takes, in order: its start and end
#: [s] and J there [N s], then the ball's mass [kg] and the normal approach [m/s] and gravity [m/s^2]
#: (``PositiveImpulse.kernel_terms``).
PUSHING = ("a", "b", "ja", "mass", "v_normal", "g_normal")


@numba.njit(inline="always", **_COMPILE)
def positive_impulse_inside(pushing, c, rate):
    """J+(c) [N s] at an instant c inside the one pushing interval, the normal rate there ``rate`` [m/s]: J(c) - J(a),
    J from the momentum balance (``NormalMotion.impulse``), in ``PositiveImpulse``'s order."""
    return 0.0 + pushing[3] * (pushing[4] - rate + pushing[5] * c) - pushing[2]


@numba.njit(**_COMPILE)
def positive_impulse(normal, pushing, t):
    """J+(t) [N s] (``PositiveImpulse.__call__``) for one pushing interval: 0 before it, J(c) - J(a) with c = t clipped
    to it (:func:`positive_impulse_inside`)."""
    a, b = pushing[0], pushing[1]
    if t < a:
        return 0.0
    c = min(max(t, a), b)
    return positive_impulse_inside(pushing, c, normal_state(normal, c)[1])


@numba.njit(**_COMPILE)
def _signed_slip(t, args):
    """sigma (v_t - omega R) [m/s] at t [s] in the sliding phase: ``TangentialMotion._slip`` times sigma."""
    normal, pushing, phase = args
    sigma, mu, mass, radius, alpha, v0, omega0, t0, g_t, j0 = (
        phase[0], phase[1], phase[2], phase[3], phase[4], phase[5], phase[6], phase[7], phase[8], phase[9])
    dt = t - t0
    impulse = -sigma * mu * (positive_impulse(normal, pushing, t) - j0)
    v = v0 + g_t * dt + impulse / mass
    omega = omega0 - impulse / (alpha * mass * radius)
    return sigma * (v - omega * radius)


@numba.njit(types.Tuple((_F, _I, _F, _F))(NORMAL, ARRAY, ARRAY, ARRAY), **_COMPILE)
def grip(normal, pushing, phase, grid):
    """(the first instant [s] the sliding phase's slip falls through zero on ``grid``, NaN if none; status; the
    bracket that failed): ``first_root`` of the signed slip with direction -1, compiled.  ``normal``: the motion's
    :meth:`~..motion.KernelState.arrays`; ``pushing``: the numbers of :data:`PUSHING`; ``phase``: those of
    :data:`PHASE`.  Status ``ode.roots.ROOT``, or ``ode.events.NOT_FINITE``, or the refinement's failure
    (``ode.roots.NO_BRACKET``, ``LAST_ITERATE``) on the bracket returned (``ode.events.raise_failed`` raises the
    Python search's error for each)."""
    args = (normal, pushing, phase)
    values = np.empty(grid.size)
    for k in range(grid.size):
        values[k] = _signed_slip(grid[k], args)
    if not np.all(np.isfinite(values)):
        return math.nan, NOT_FINITE, 0.0, 0.0
    found = np.empty(grid.size + 1)
    count, status, low, high = roots_at_compiled(_signed_slip, args, grid, values, -1, found,
                                                 refine_root_compiled, bracketed_root_compiled)
    if status != ROOT:
        return math.nan, status, low, high
    return (found[0] if count else math.nan), ROOT, 0.0, 0.0


@numba.njit(ARRAY(NORMAL, ARRAY, ARRAY), **_COMPILE)
def positive_impulses(normal, pushing, times):
    """J+ [N s] at each of ``times`` [s] (``PositiveImpulse.__call__`` on the array, compiled; ``pushing``: the numbers
    of :data:`PUSHING`)."""
    out = np.empty(times.size)
    for k in range(times.size):
        out[k] = positive_impulse(normal, pushing, times[k])
    return out


@numba.njit(types.UniTuple(ARRAY, 2)(NORMAL, types.FunctionType(SIGNATURE), ARRAY, ARRAY, ARRAY, ARRAY), **_COMPILE)
def impulse_gaps(normal, force, params, pushing, levels, s):
    """(level - J+(s), -max(P(s), 0)) of each lane at its instant ``s`` [s]: the function ``PositiveImpulse.instants``'
    Newton iteration runs on, compiled.  ``normal``: the motion's :meth:`~..motion.KernelState.arrays`; ``force`` and
    ``params``: the law's compiled kernel and its parameters; ``pushing``: the numbers of :data:`PUSHING`; ``levels``
    [N s]: each lane's."""
    f, df = np.empty(s.size), np.empty(s.size)
    for k in range(s.size):
        f[k] = levels[k] - positive_impulse(normal, pushing, s[k])
        delta, delta_dot = normal_state(normal, s[k])
        p = force(delta, delta_dot, params)
        df[k] = -(p if p >= 0.0 or p != p else 0.0)  # -np.maximum(P, 0): NaN stays NaN
    return f, df
