"""DOP853 on the normal motion, compiled: the integration loop of method ``DOP853-scalar``.

The dimensionless normal motion x' = y, y' = -P(x d, y v) / p + gamma (see :mod:`.normal`) is integrated by
:func:`integrate`, compiled by numba for one signature: the law's force enters as a compiled kernel passed by
function pointer (:mod:`sphereimpact.contact.laws.kernels`), so one compiled integrator serves every law and is
cached on disk once (beside this file, or in ``NUMBA_CACHE_DIR``).  It is the algorithm of
:class:`scipy.integrate.DOP853` (Hairer, Norsett & Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
1993, section II.10), with scipy's coefficients (:mod:`sphereimpact.ode.dop853_tableau`) and scipy's
step control (initial step, safety 0.9, factors 0.2 to 10, exponent -1/8, no growth right after a rejection,
minimum step 10 ulp of t), every sum taken in scipy's order: the same steps as solve_ivp's DOP853 up to round-off
(tests/test_dop853.py), and the Python-float DOP853's answer (:mod:`sphereimpact.ode.dop853`) to the bit
(tests/test_kernels.py).

The events are evaluated at each step's end, by kind (:data:`MAX_COMPRESSION`, :data:`PENETRATION`,
:data:`FORCE`, :data:`BAND`), and the integration stops after the first step across which a terminal one falls
through zero.  Their roots are then found on each crossed step's interpolant as the Python-float run finds them
(:func:`sphereimpact.ode.dop853.located`): by the same crossing rule (``ode.dop853._crossed``) and Brent's method
(``ode.roots.bracketed_root``) on the same interpolant (``ode.dense.interpolant_pair``), those very
functions compiled here.
"""

from __future__ import annotations

import numba
import numpy as np
from numba import types

from ..contact.laws.kernels import SIGNATURE
from ..ode import dop853
from ..ode.dop853 import (BUDGET, EPS, OVERFLOW, ROOT_ITERATIONS, STEP_TOO_SMALL,  # noqa: F401 (the
                          STEPPED, tableau)                                                  # statuses re-exported)
from ..ode.dense import grown, interpolant_pair
from ..ode.roots import bracketed_root
from .event_kinds import EventKind
from ..kernel_cache import refresh

refresh()  # before any kernel is defined: numba's cache of them true to every source they compile

#: The events' codes (:class:`.event_kinds.EventKind`), as plain integers for the compiled code.
MAX_COMPRESSION, PENETRATION, FORCE, BAND = (int(kind) for kind in EventKind)
#: Statuses: a terminal event fell through zero in the last step, the span's end reached; or (``ode.dop853.advance``'s)
#: the step fell below 10 ulp of t, the right-hand side's budget spent, the force left the finite numbers.
TERMINAL, FINISHED = 1, 0

_COMPILE = {"cache": True, "nogil": True, "error_model": "numpy"}
_F = types.float64
_ARRAY, _MATRIX = types.float64[::1], types.float64[:, ::1]
_RESULT = types.Tuple((_ARRAY, _MATRIX, types.float64[:, :, ::1], _MATRIX, types.int64, types.int64, _ARRAY,
                       types.int64[:, ::1]))
_SIGNATURE = _RESULT(types.FunctionType(SIGNATURE), _ARRAY, _ARRAY, _F, _F, _ARRAY, _F, _F, _F, _F,
                     types.int64[::1], types.int64[::1], _F, _F, types.int64)
#: DOP853's tableau, frozen into the compiled code as constants (:func:`sphereimpact.ode.dop853.tableau`).
_A, _C, _B, _E3, _E5, _A_EXTRA, _C_EXTRA, _D, _STAGES = tableau()


@numba.njit(**_COMPILE)
def _rhs(args, t, state, out):
    """(x', y') at the dimensionless state (x, y) into ``out`` (autonomous: t unused); returns False when the force is
    not finite.  ``args``: the force kernel's parameters, scales = (d, v, p, gamma) and the kernel."""
    params, scales, force = args
    p = force(state[0] * scales[0], state[1] * scales[1], params)
    out[0] = state[1]
    out[1] = -p / scales[2] + scales[3]
    return np.isfinite(p)


@numba.njit(**_COMPILE)
def _event(kind, force, params, scales, lam, band, x, y):
    """The event function of ``kind`` at the dimensionless state (x, y)."""
    if kind == MAX_COMPRESSION:
        return y
    if kind == PENETRATION:
        return x * scales[0]
    if kind == FORCE:
        delta = x * scales[0]
        return force(delta, y * scales[1], params) if delta > 0 else -1.0
    return max(lam * x - band, y)


_crossed = numba.njit(**_COMPILE)(dop853._crossed)
_advance = numba.njit(inline="always", **_COMPILE)(dop853.advance)  # inlined: the right-hand side is passed
_dense_rows = numba.njit(inline="always", **_COMPILE)(dop853.dense_rows)
_first_step = numba.njit(inline="always", **_COMPILE)(dop853.first_step)
_root = numba.njit(inline="always", **_COMPILE)(bracketed_root)  # inlined: _event_at is called, not passed


_interpolant_pair = numba.njit(**_COMPILE)(interpolant_pair)
_grown = numba.njit(**_COMPILE)(grown)


@numba.njit(**_COMPILE)
def _event_at(t, args):
    """An event's value at time t inside one step: its interpolant at t (``ode.dense.interpolant_pair``, the
    Python run's arithmetic), then the event of its kind.  ``args``: (kind, force, params, scales, lam, band, the
    step's coefficients (7, 2) in reverse order, its start, its size, its start state x, y)."""
    kind, force, params, scales, lam, band, rows, t0, h, x0, y0 = args
    x, y = _interpolant_pair(rows, (t - t0) / h, x0, y0)
    return _event(kind, force, params, scales, lam, band, x, y)


@numba.njit(_SIGNATURE, **_COMPILE)
def integrate(force, params, scales, t0, t_bound, z0, rtol, atol, max_step, first_step, kinds, directions, lam,
              band, max_nfev):
    """Integrate the dimensionless normal motion from (t0, z0) towards t_bound with DOP853.

    Parameters
    ----------
    force, params : kernel, array
        The law's compiled force P(delta, delta_dot, params) [N] and its parameters.
    scales : array (4,)
        d = v_n T [m], v = v_n [m/s], p = m v_n / T [N] and the dimensionless gravity gamma.
    t0, t_bound : float
        Span in dimensionless time, ascending.
    z0 : array (2,)
        Start state (x, y).
    rtol, atol, max_step, first_step : float
        Tolerances, the largest step, and the first step (scipy's estimate when not > 0).
    kinds, directions : int arrays (m,)
        The events (kinds above; all but MAX_COMPRESSION are terminal) and their directions (-1, 0, 1).
    lam, band : float
        The ramp's rate in x and the band's edge, for a BAND event.
    max_nfev : int
        Right-hand-side evaluations allowed.

    Returns
    -------
    ts, ys, coefficients, g, nfev, status, roots, where
        Step ends (k + 1,), the states there (k + 1, 2), each step's interpolation coefficients, scipy's F
        (k, 7, 2), the events' values at the step ends (k + 1, m), the evaluations used, the status, and the root of
        every event on every step across which it changed sign in its direction (r,), with that step and event's
        index (r, 2), in the steps' order.
    """
    tab, extra, m = (_A, _C, _B, _E3, _E5, _A_EXTRA, _C_EXTRA, _D, _STAGES), _C_EXTRA.size, kinds.size
    args = (params, scales, force)  # not the kernel first: numba would try a tuple of functions, and warn
    capacity = 64
    ts, ys = np.empty(capacity), np.empty((capacity, 2))
    coefficients, g = np.empty((capacity, 7, 2)), np.empty((capacity, m))
    k = np.empty((_STAGES + 1 + extra, 2))
    f, f_new, stage, y_new = np.empty(2), np.empty(2), np.empty(2), np.empty(2)
    t, y = t0, z0.copy()
    finite = _rhs(args, t, y, f)
    nfev = 1
    ts[0], ys[0, 0], ys[0, 1] = t, y[0], y[1]
    for j in range(m):
        g[0, j] = _event(kinds[j], force, params, scales, lam, band, y[0], y[1])
    if not finite:
        return ts[:1], ys[:1], coefficients[:0], g[:1], nfev, OVERFLOW, np.empty(0), np.empty((0, 2), dtype=np.int64)
    if first_step > 0.0:
        h_abs = first_step
    else:  # scipy's estimate
        h_abs, used = _first_step(_rhs, args, t0, y, f, t_bound, max_step, rtol, atol, y_new, stage)
        nfev += used
    steps, status = 0, STEPPED
    while status == STEPPED:
        if t == t_bound:
            status = FINISHED
            break
        status, t_new, h, h_abs, nfev = _advance(_rhs, args, t, y, f, h_abs, t_bound, max_step, rtol, atol, tab, k,
                                                 stage, y_new, f_new, nfev, max_nfev)
        if status != STEPPED:
            break
        if steps + 2 > ts.size:
            room = 2 * ts.size
            ts, ys, coefficients, g = (_grown(ts, steps + 1, room), _grown(ys, steps + 1, room),
                                       _grown(coefficients, steps, room), _grown(g, steps + 1, room))
        finite = _dense_rows(_rhs, args, t, y, f, y_new, f_new, h, tab, k, stage, coefficients[steps])
        nfev += extra
        if not finite:
            status = OVERFLOW
            break
        t = t_new
        y[0], y[1], f[0], f[1] = y_new[0], y_new[1], f_new[0], f_new[1]
        steps += 1
        ts[steps], ys[steps, 0], ys[steps, 1] = t, y[0], y[1]
        for j in range(m):
            g[steps, j] = _event(kinds[j], force, params, scales, lam, band, y[0], y[1])
            if _crossed(g[steps - 1, j], g[steps, j], directions[j]) and kinds[j] != MAX_COMPRESSION:
                status = TERMINAL
    roots, where, count = np.empty(steps * m), np.empty((steps * m, 2), dtype=np.int64), 0
    for s in range(steps):
        for j in range(m):
            if _crossed(g[s, j], g[s + 1, j], directions[j]):
                args = (kinds[j], force, params, scales, lam, band, coefficients[s][::-1], ts[s], ts[s + 1] - ts[s],
                        ys[s, 0], ys[s, 1])
                roots[count] = _root(_event_at, args, ts[s], ts[s + 1], 4 * EPS, 4 * EPS, ROOT_ITERATIONS)[0]
                where[count, 0], where[count, 1] = s, j
                count += 1
    return (ts[:steps + 1], ys[:steps + 1], coefficients[:steps], g[:steps + 1], nfev, status, roots[:count],
            where[:count])
