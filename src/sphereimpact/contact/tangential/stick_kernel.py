"""A compliant tangential contact's stick phase, compiled: the DOP853 run of :class:`~.springs.CompliantTangential`.

While the contact sticks, (F_s, J_t, K_t) is integrated on the solved normal motion by DOP853 in plain floats
(:func:`sphereimpact.ode.dop853.solve`) until |F| reaches mu P+: in Python most of a compliant impact's cost, and most
of that calls, for the right-hand side reads the normal motion's dense output and the law's force at every stage.
:func:`stick` is the same run compiled by numba for one signature: the normal motion enters as its dense output's
arrays (:class:`~sphereimpact.contact.motion.KernelState`, read by :func:`~..normal_kernel.normal_state` with the
arithmetic of its Python evaluator), the law's force as its compiled kernel by function pointer,
so one compiled loop serves every law and tangential model and numba caches it on disk once.  The loop is
:func:`~sphereimpact.ode.dop853.solve`'s, step for step and sum for sum (scipy's tableau, step control and event
rule; the roots by the same Brent search on the same interpolant), and the right-hand side and the events are the
stick phase's Python functions' arithmetic in their order, so the run is the Python run to the bit
(tests/test_contact_kernels.py).
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types

from ...ode import dop853
from ...ode.dense import grown
from ...ode.dop853 import EPS, ROOT_ITERATIONS, STEPPED, tableau
from ...ode.roots import NO_BRACKET, bracketed_root
from ..laws.kernels import SIGNATURE
from ..normal_kernel import ARRAY, CUBE, MATRIX, NORMAL, normal_state
from ...kernel_cache import owned, refresh

refresh()  # before any kernel is defined: numba's cache of them true to every source they compile

#: The history rules (``springs.RESCALE``, in its order) as integers.
NEVER, UNLOADING, ALWAYS = 0, 1, 2
#: Statuses: an event ended the run, the span's end reached (``dop853.solve``'s 1 and 0, and its -1,
#: ``STEP_TOO_SMALL``), and an event whose root had no bracket on its step's interpolant (``dop853.solve`` raises there).
TERMINAL, FINISHED, NO_ROOT = 1, 0, -4
#: The stick phase has no budget of right-hand-side evaluations (as its Python run).
_NO_BUDGET = np.iinfo(np.int64).max

_COMPILE = {"cache": True, "nogil": True, "error_model": "numpy"}
_F, _I = types.float64, types.int64
_SIGNATURE = types.Tuple((ARRAY, MATRIX, CUBE, MATRIX, _I, _I, ARRAY, types.int64[:, ::1]))(
    NORMAL, types.FunctionType(SIGNATURE), ARRAY, ARRAY, _I, _F, _F, ARRAY, _F, _F, _F)
_A, _C, _B, _E3, _E5, _A_EXTRA, _C_EXTRA, _D, _STAGES = tableau()
_N = 3  # the state: F_s / fs, J_t / js, K_t w / js

_crossed = numba.njit(**_COMPILE)(owned(dop853._crossed, "stick_kernel"))
_grown = numba.njit(**_COMPILE)(owned(grown, "stick_kernel"))
_advance = numba.njit(inline="always", **_COMPILE)(dop853.advance)  # inlined: the right-hand side is passed
_dense_rows = numba.njit(inline="always", **_COMPILE)(dop853.dense_rows)
_first_step = numba.njit(inline="always", **_COMPILE)(dop853.first_step)
_root = numba.njit(inline="always", **_COMPILE)(bracketed_root)  # inlined: _event_at is called, not passed


@numba.njit(**_COMPILE)
def _stiffness(spring, delta):
    """k_t [N/m] at compression delta: kappa times the normal spring's tangent stiffness (``spring_stiffness``)."""
    kappa, k, nk, n = spring[1], spring[2], spring[3], spring[4]
    return kappa * (k if n == 1.0 else nk * max(delta, 0.0) ** (n - 1.0))


@numba.njit(**_COMPILE)
def _slip(spring, t, impulse):
    """The contact point's slip velocity [m/s] at t [s] with the scaled tangential impulse ``impulse``."""
    slip0, g_t, t0, inverse_mass, js = spring[6], spring[7], spring[8], spring[9], spring[10]
    return slip0 + g_t * (t - t0) + inverse_mass * impulse * js


@numba.njit(**_COMPILE)
def _rhs(args, tau, z, out):
    """The stick phase's right-hand side at (tau, z) into ``out`` (``CompliantTangential._run``'s ``rhs``); True (its
    values stay finite where the normal force does)."""
    normal, force, params, spring, rescale = args
    z0, z1 = z[0], z[1]
    w, n, root_m, fs = spring[0], spring[4], spring[5], spring[11]
    t = tau / w
    delta, delta_dot = normal_state(normal, t)
    k_t = _stiffness(spring, delta)
    slip = _slip(spring, t, z1)
    total = z0 - root_m * math.sqrt(k_t) * slip / fs if root_m else z0
    rho = 0.0  # springs.history_rate
    if not (rescale == NEVER or delta <= 0 or (delta_dot >= 0 and rescale == UNLOADING)):
        rho = (n - 1.0) * delta_dot / delta
    out[0] = (-k_t * slip + rho * z0 * fs) / (w * fs)
    out[1] = total
    out[2] = z1
    return True


@numba.njit(**_COMPILE)
def _event(which, args, tau, z0, z1):
    """The stick phase's event ``which`` at (tau, z): 0 is F reaching +mu P+, 1 is F reaching -mu P+ (``upper``
    and ``lower``)."""
    normal, force, params, spring, rescale = args
    w, root_m, fs, mu = spring[0], spring[5], spring[11], spring[12]
    t = tau / w
    delta, delta_dot = normal_state(normal, t)
    p = force(delta, delta_dot, params)
    cap = mu * (p if p >= 0.0 or p != p else 0.0)  # np.maximum(P, 0): NaN stays NaN
    total = z0
    if root_m:  # the dashpot's share, as ``dashpot(t)`` and ``total`` compute it
        slip = _slip(spring, t, z1)
        total = z0 - root_m * np.sqrt(_stiffness(spring, normal_state(normal, t)[0])) * slip / fs
    return cap / fs - total if which == 0 else cap / fs + total


@numba.njit(**_COMPILE)
def _event_at(tau, args):
    """An event's value at tau inside one step: the step's interpolant there (``ode.dense.horner_dop853`` for three
    components), then the event.  ``args``: (which, the run's args, the step's rows of F in reverse order, its start,
    its size, its start state)."""
    which, run, rows, t0, h, y0 = args
    x = (tau - t0) / h
    rest = 1 - x
    a = b = c = 0.0
    for i in range(rows.shape[0]):
        factor = x if i % 2 == 0 else rest
        a, b, c = (a + rows[i, 0]) * factor, (b + rows[i, 1]) * factor, (c + rows[i, 2]) * factor
    return _event(which, run, tau, a + y0[0], b + y0[1])


@numba.njit(_SIGNATURE, **_COMPILE)
def stick(normal, force, params, spring, rescale, t0, t_bound, z0, rtol, atol, max_step):
    """Integrate one stick phase from (t0, z0) towards t_bound [tau] with DOP853 until an event ends it.

    Parameters
    ----------
    normal : tuple
        The normal motion's dense output (:meth:`~sphereimpact.contact.motion.KernelState.arrays`).
    force, params : kernel, array
        The law's compiled force P(delta, delta_dot, params) [N] and its parameters.
    spring : array (13,)
        w [1/s], kappa [-], k [N/m^n], n k, n [-], root_m [sqrt(kg)] (0: no dashpot), the slip s0 [m/s] at the
        phase's start t0 [s], g_t [m/s^2], t0, 1/m* [1/kg] (slip per impulse), js [N s], fs [N], mu [-].
    rescale : int
        The history rule (:data:`NEVER`, :data:`UNLOADING`, :data:`ALWAYS`).
    t0, t_bound, z0, rtol, atol, max_step
        As :func:`sphereimpact.ode.dop853.solve` takes them (first step: scipy's estimate).

    Returns
    -------
    ts, ys, coefficients, g, nfev, status, roots, where
        As :func:`sphereimpact.integrators.dop853_kernel.integrate` returns them, for the two events.
    """
    tab, extra, m = (_A, _C, _B, _E3, _E5, _A_EXTRA, _C_EXTRA, _D, _STAGES), _C_EXTRA.size, 2
    args = (normal, force, params, spring, rescale)
    capacity = 64
    ts, ys = np.empty(capacity), np.empty((capacity, _N))
    coefficients, g = np.empty((capacity, 7, _N)), np.empty((capacity, m))
    k = np.empty((_STAGES + 1 + extra, _N))
    f, f_new, stage, y_new = np.empty(_N), np.empty(_N), np.empty(_N), np.empty(_N)
    t, y = t0, z0.copy()
    _rhs(args, t, y, f)
    nfev = 1
    h_abs, used = _first_step(_rhs, args, t0, y, f, t_bound, max_step, rtol, atol, y_new, stage)
    nfev += used
    ts[0] = t
    for comp in range(_N):
        ys[0, comp] = y[comp]
    for j in range(m):
        g[0, j] = _event(j, args, t, y[0], y[1])
    steps, status = 0, STEPPED
    while status == STEPPED:
        if t == t_bound:
            status = FINISHED
            break
        status, t_new, h, h_abs, nfev = _advance(_rhs, args, t, y, f, h_abs, t_bound, max_step, rtol, atol, tab, k,
                                                 stage, y_new, f_new, nfev, _NO_BUDGET)
        if status != STEPPED:
            break
        if steps + 2 > ts.size:
            room = 2 * ts.size
            ts, ys, coefficients, g = (_grown(ts, steps + 1, room), _grown(ys, steps + 1, room),
                                       _grown(coefficients, steps, room), _grown(g, steps + 1, room))
        _dense_rows(_rhs, args, t, y, f, y_new, f_new, h, tab, k, stage, coefficients[steps])
        nfev += extra
        t = t_new
        for comp in range(_N):
            y[comp], f[comp] = y_new[comp], f_new[comp]
        steps += 1
        ts[steps] = t
        for comp in range(_N):
            ys[steps, comp] = y[comp]
        for j in range(m):
            g[steps, j] = _event(j, args, t, y[0], y[1])
            if _crossed(g[steps - 1, j], g[steps, j], -1):
                status = TERMINAL
    roots, where, count = np.empty(steps * m), np.empty((steps * m, 2), dtype=np.int64), 0
    for s in range(steps):
        for j in range(m):
            if _crossed(g[s, j], g[s + 1, j], -1):
                root, found, _ = _root(_event_at, (j, args, coefficients[s][::-1], ts[s], ts[s + 1] - ts[s], ys[s]),
                                       ts[s], ts[s + 1], 4 * EPS, 4 * EPS, ROOT_ITERATIONS)
                if found == NO_BRACKET:
                    status = NO_ROOT
                roots[count] = root
                where[count, 0], where[count, 1] = s, j
                count += 1
    return (ts[:steps + 1], ys[:steps + 1], coefficients[:steps], g[:steps + 1], nfev, status, roots[:count],
            where[:count])
