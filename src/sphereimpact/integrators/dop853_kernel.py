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

:func:`drive` is the whole normal motion in one call: :class:`sphereimpact.integrators.normal.IntegratedNormal`'s
runs of :func:`integrate` (to separation, the ramp band's restart, the landing on t_f and its Newton corrections),
the events located as ``ode.dop853.located`` locates them and the dense outputs joined as ``StackedDOP853.join``
joins them, the driver's arithmetic in its order: its answer is the driver's to the bit (tests/test_kernels.py), at
one Python call instead of a dozen.  Where the Python driver would raise, it hands the motion back to it.
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
from ..kernel_cache import owned, refresh

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


@numba.njit(inline="always", **_COMPILE)
def _rhs(args, t, state, out):
    """(x', y') at the dimensionless state (x, y) into ``out`` (autonomous: t unused); returns False when the force is
    not finite.  ``args``: the force kernel's parameters, scales = (d, v, p, gamma) and the kernel.  Inlined into the
    stepper: called, it passed its arrays at each of a contact's hundreds of evaluations (a fifth of the drive's time)."""
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


_crossed = numba.njit(**_COMPILE)(owned(dop853._crossed, "dop853_kernel"))
_advance = numba.njit(inline="always", **_COMPILE)(dop853.advance)  # inlined: the right-hand side is passed
_dense_rows = numba.njit(inline="always", **_COMPILE)(dop853.dense_rows)
_first_step = numba.njit(inline="always", **_COMPILE)(dop853.first_step)
_root = numba.njit(inline="always", **_COMPILE)(bracketed_root)  # inlined: _event_at is called, not passed


_interpolant_pair = numba.njit(**_COMPILE)(owned(interpolant_pair, "dop853_kernel"))
_grown = numba.njit(**_COMPILE)(owned(grown, "dop853_kernel"))


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


# --- the whole normal motion: IntegratedNormal's drive, compiled -------------------------------------------------
#: :func:`drive`'s statuses: the motion driven to its landing on t_f, or not (a failure, a missed event, the budget):
#: then the Python driver (:class:`sphereimpact.integrators.normal.IntegratedNormal`) runs it and says why.
DRIVEN, UNDRIVEN = 0, 1
_CUBE = types.float64[:, :, ::1]
_DRIVE_RESULT = types.Tuple((_ARRAY, _CUBE, _MATRIX, _ARRAY, _ARRAY, _ARRAY, _F, _F, _F, types.int64, types.int64))
_DRIVE_SIGNATURE = _DRIVE_RESULT(types.FunctionType(SIGNATURE), _ARRAY, _ARRAY, _F, _F, _F, _F, types.int64, _F,
                                 _ARRAY, types.int64, types.int64)


@numba.njit(**_COMPILE)
def _located(ts, ys, coefficients, roots, where, terminal):
    """``ode.dop853.located`` on one run of :func:`integrate`: the step ends and states cut at the first terminal
    root (copies), and each event's first root and the state there (NaN where none), the roots of a step taken in
    ascending order (ties by the event's index) up to its first terminal one."""
    m = terminal.size
    ts, ys = ts.copy(), ys.copy()
    first, x_at, y_at = np.full(m, np.nan), np.full(m, np.nan), np.full(m, np.nan)
    r, count = 0, roots.size
    while r < count:
        step, last = where[r, 0], r
        while last < count and where[last, 0] == step:
            last += 1
        order = np.argsort(roots[r:last], kind="mergesort") + r  # stable: equal roots in their events' order
        t0, t1 = ts[step], ts[step + 1]
        for hit in order:
            i, root = where[hit, 1], roots[hit]
            x, y = _interpolant_pair(coefficients[step][::-1], (root - t0) / (t1 - t0), ys[step, 0], ys[step, 1])
            if np.isnan(first[i]):
                first[i], x_at[i], y_at[i] = root, x, y
            if terminal[i]:
                ts[step + 1], ys[step + 1, 0], ys[step + 1, 1] = root, x, y
                break
        r = last
    return ts, ys, first, x_at, y_at


@numba.njit(**_COMPILE)
def _at(ts, f, y_old, t_old, h, t):
    """``ode.dense.StackedDOP853.single``: the dense output's state at t (a step boundary takes the earlier step)."""
    step = min(max(np.searchsorted(ts, t, side="left") - 1, 0), h.size - 1)
    return _interpolant_pair(f[step][::-1], (t - t_old[step]) / h[step], y_old[step, 0], y_old[step, 1])


@numba.njit(**_COMPILE)
def _joined(ts, f, y_old, t_old, h, ts2, f2, y_old2, t_old2, h2):
    """``ode.dense.StackedDOP853.join``: the first dense output up to the second's start, then the second."""
    keep = np.searchsorted(ts, ts2[0], side="left")
    return (np.concatenate((ts[:keep], ts2)), np.concatenate((f[:keep], f2)),
            np.concatenate((y_old[:keep], y_old2)), np.concatenate((t_old[:keep], t_old2)),
            np.concatenate((h[:keep], h2)))


@numba.njit(**_COMPILE)
def _ending(force, params, scales, on_delta, x, y):
    """The landing's separation function, smooth through its root (``normal._land``'s ``ending``): delta / d, or
    the law's force continued past separation."""
    return x if on_delta else force(x * scales[0], y * scales[1], params)


@numba.njit(**_COMPILE)
def _run(force, params, scales, t0, t_bound, z0, rtol, atol, max_step, first_step, kinds, directions, terminal, lam,
         edge, budget):
    """One run of :func:`integrate` as ``runge_kutta._compiled`` and ``ode.dop853.located`` make it a solution: its
    dense output's arrays (ts cut at a terminal root; the steps' own sizes), the cut step ends and states, each
    event's first root and state there, the evaluations, and whether it may go on (False where the Python run
    raises: the step fell too small, the force left the finite numbers, the budget is spent, or no step was taken)."""
    ts, ys, coefficients, g, nfev, status, roots, where = integrate(
        force, params, scales, t0, t_bound, z0, rtol, atol, max_step, first_step, kinds, directions, lam, edge,
        max(budget, 0))
    sizes = np.diff(ts)
    ts, ys, first, x_at, y_at = _located(ts, ys, coefficients, roots, where, terminal)
    k = coefficients.shape[0]
    ok = (status == TERMINAL or status == FINISHED) and nfev <= budget and k > 0
    dense = (ts, coefficients, ys[:k].copy(), ts[:k].copy(), sizes)
    return dense, ys, first, x_at, y_at, nfev, status, ok


@numba.njit(_DRIVE_SIGNATURE, **_COMPILE)
def drive(force, params, scales, end, rtol, atol, max_step, separation, lam, policy, landings, budget):
    """:class:`~sphereimpact.integrators.normal.IntegratedNormal`'s drive of DOP853 compiled, the Python driver's
    arithmetic in its order: one run from (0, [0, 1]) to separation with the events of maximum compression,
    separation and (lam > 0) eq. 4.2's ramp band; restitution restarted with bounded steps from where it enters
    the band (``normal._RampBand``); the landing on t_f with Newton's corrections (``normal._land``).

    Parameters
    ----------
    force, params, scales, rtol, atol, max_step
        As :func:`integrate` takes them (rtol and atol the conditioned tolerances, max_step the run's bound).
    end : float
        The horizon [tau].
    separation : int
        The separation event's kind (:data:`PENETRATION` or :data:`FORCE`).
    lam : float
        The ramp's rate in x; 0 for a law without a band.
    policy : array (4,)
        The band's edge, step and speed (``normal.BAND_RESTART``, ``BAND_STEP``, ``BAND_SPEED``) and
        ``normal.LANDING_DELTA``.
    landings, budget : int
        ``normal.LANDINGS`` and ``normal.MAX_NFEV``.

    Returns
    -------
    ts, f, y_old, t_old, h, steps, tau_m, tau_f, rate_f, nfev, status
        The joined dense output (``StackedDOP853``'s arrays), the step ends the grid is cut from, maximum
        compression and separation [tau], y at t_f, the evaluations made, and :data:`DRIVEN`, else
        :data:`UNDRIVEN` (the Python driver then runs the motion, and raises what went wrong).
    """
    empty = np.empty(0)
    failed = (empty, np.empty((0, 7, 2)), np.empty((0, 2)), empty, empty, empty, np.nan, np.nan, np.nan, 0, UNDRIVEN)
    band = lam != 0.0
    m = 3 if band else 2
    kinds, directions = np.empty(m, dtype=np.int64), np.full(m, -1, dtype=np.int64)
    kinds[0], kinds[1] = MAX_COMPRESSION, separation
    terminal = np.ones(m, dtype=np.bool_)
    terminal[0] = False
    if band:
        kinds[2] = BAND
    start = np.zeros(2)
    start[1] = 1.0
    dense, ys, first, x_at, y_at, used, status, ok = _run(
        force, params, scales, 0.0, end, start, rtol, atol, max_step, 0.0, kinds, directions, terminal, lam,
        policy[0] if band else 0.0, budget)
    if not ok:
        return failed
    tau_m, tau_f, x_m = first[0], first[1], x_at[0] if not np.isnan(first[0]) else 1.0
    steps, cap = dense[0], max_step
    if band and not np.isnan(first[2]) and np.isnan(first[1]):  # restitution from the band's edge on
        z0 = np.empty(2)
        z0[0], z0[1] = x_at[2], y_at[2]
        cap = min(max_step, policy[1] / (lam * max(abs(z0[1]), policy[2])))
        cut = dense[0]
        first_step = min(cap, cut[-2] - cut[-3]) if cut.size >= 3 else 0.0
        one, sep = np.full(1, separation, dtype=np.int64), np.full(1, -1, dtype=np.int64)
        rest, _, found, _, _, nfev, status, ok = _run(
            force, params, scales, first[2], end, z0, rtol, atol, cap, first_step, one, sep, np.ones(1, np.bool_),
            0.0, 0.0, budget - used)
        used += nfev
        if not ok:
            return failed
        tau_f = found[0]
        if np.isnan(tau_m) and lam * x_at[2] < policy[0]:  # the band's event fired at maximum compression
            tau_m = first[2]
        steps = np.concatenate((cut[:-1], rest[0]))
        dense = _joined(*dense, *rest)
    if status == FINISHED or np.isnan(tau_f) or np.isnan(tau_m):
        return failed
    ts, f, y_old, t_old, h = dense
    x_f, y_f = _at(ts, f, y_old, t_old, h, tau_f)
    on_delta = separation == PENETRATION or (abs(x_f) <= policy[3] * x_m
                                             and not force(0.0 * scales[0], y_f * scales[1], params) < 0)
    # the landing: a step that ends on t_f, Newton's corrections on it while they exceed the tolerance
    tau_k, tau_end = ts[-2], t_old[-1] + h[-1]
    none, no = np.empty(0, dtype=np.int64), np.empty(0, dtype=np.bool_)
    for attempt in range(landings):
        z0 = np.empty(2)
        z0[0], z0[1] = _at(ts, f, y_old, t_old, h, tau_k)
        tail, tail_ys, _, _, _, nfev, status, ok = _run(
            force, params, scales, tau_k, tau_f, z0, rtol, atol, cap, tau_f - tau_k if tau_f > tau_k else 0.0, none,
            none, no, 0.0, 0.0, budget - used)
        used += nfev
        if not ok:
            return failed
        step = 1e-6 * (tau_end - tau_k)
        above, below = min(tau_f + step, tau_end), max(tau_f - step, tau_k)
        xa, ya = _at(ts, f, y_old, t_old, h, above)
        xb, yb = _at(ts, f, y_old, t_old, h, below)
        slope = (_ending(force, params, scales, on_delta, xa, ya)
                 - _ending(force, params, scales, on_delta, xb, yb)) / (above - below)
        last = tail_ys.shape[0] - 1
        correction = (-_ending(force, params, scales, on_delta, tail_ys[last, 0], tail_ys[last, 1]) / slope
                      if slope != 0 else 0.0)
        if not abs(correction) > rtol * tau_f or attempt == landings - 1:
            break
        corrected = min(tau_f + correction, tau_end)
        if not corrected > tau_k:  # the correction leaves the crossing step: keep the landing made
            break
        tau_f = corrected
    steps = np.concatenate((steps[:-1], tail[0][1:]))
    ts, f, y_old, t_old, h = _joined(ts, f, y_old, t_old, h, *tail)
    return ts, f, y_old, t_old, h, steps, tau_m, tau_f, tail_ys[tail_ys.shape[0] - 1, 1], used, DRIVEN
