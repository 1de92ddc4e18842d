"""The Taylor method on the normal motion, compiled: the step loop of :func:`sphereimpact.ode.series.solve`.

:func:`solve` is that loop compiled by numba for one signature: the law's series (its ``series_kernel``, the
recurrence of its ``series`` writing into arrays) and its force (its ``kernel``, for the force criterion's
separation) enter by function pointer (:mod:`sphereimpact.contact.laws.kernels`), so one compiled loop serves every
law with a series and numba caches it on disk once.  Each step is the Python loop's, in its order: the coefficients,
the step from the last two of them (``series.step_size``), the ramp band's bound and edge (``series.band_limit``),
the events' roots by Brent's method (``ode.roots.bracketed_root``, that very function compiled) on the step's
polynomials, so the answer is the Python-float method's to the bit (tests/test_kernels.py).  :func:`solved` runs it
and returns what ``series.solve`` returns, raising what it raises.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types

from ..contact.laws.kernels import SERIES_SIGNATURE, SIGNATURE
from ..errors import ImpactError, SeriesOverflowError, StepBudgetError
from ..ode import series
from ..ode.dense import grown
from ..ode.roots import BRENT_ITERATIONS, NO_BRACKET, bracketed_root
from ..kernel_cache import owned, refresh

refresh()  # before any kernel is defined: numba's cache of them true to every source they compile

#: Statuses: separation found, the horizon reached without it, the step budget spent, coefficients not finite,
#: separation before maximum compression, a division by zero (the ramp band's bound at rest), a root search that
#: found no bracket or did not converge.
SEPARATED, HORIZON, BUDGET, OVERFLOW, EARLY, ZERO_DIVISION, NO_ROOT, ROOT_UNCONVERGED = range(8)
#: The root searches' functions of the step's fraction s: x(s) - edge, y(s), the separation at (x(s), y(s)).
_EDGE, _RATE, _SEPARATION = 0, 1, 2

_COMPILE = {"cache": True, "nogil": True, "error_model": "numpy"}
_F, _I = types.float64, types.int64
_ARRAY, _MATRIX = types.float64[::1], types.float64[:, ::1]
_RESULT = types.Tuple((_ARRAY, _ARRAY, _MATRIX, _MATRIX, _F, _F, _F, _F, _F, _I))
_SIGNATURE = _RESULT(types.FunctionType(SERIES_SIGNATURE), types.FunctionType(SIGNATURE), _ARRAY, _ARRAY, _F, _F,
                     _F, _F, _F, _F, _F, _I, types.boolean, _F)
_ROOT_TOL = 4 * series.EPS  # series._root's relative tolerance


_horner = numba.njit(**_COMPILE)(owned(series.horner, "taylor_kernel"))


@numba.njit(**_COMPILE)
def _separation(force, params, d_scale, v, pulls, x, y):
    """``normal.scalar_separation_function`` at the dimensionless state (x, y): delta, or the force inside."""
    delta = x * d_scale
    if pulls:
        return delta
    return force(delta, y * v, params) if delta > 0 else -1.0


@numba.njit(**_COMPILE)
def _event(s, args):
    """The root searches' function of kind ``args[0]`` at s into the step (see :data:`_EDGE`)."""
    kind, xs, ys, edge, force, params, d_scale, v, pulls = args
    if kind == _EDGE:
        return _horner(xs, s) - edge
    if kind == _RATE:
        return _horner(ys, s)
    return _separation(force, params, d_scale, v, pulls, _horner(xs, s), _horner(ys, s))


_root = numba.njit(inline="always", **_COMPILE)(bracketed_root)  # inlined: _event is called, not passed


@numba.njit(**_COMPILE)
def _event_root(kind, xs, ys, edge, force, params, d_scale, v, pulls, h):
    """``series._root`` of the event of ``kind`` on [0, h]: (s, status) (one call site, so compiled once)."""
    s, status, _ = _root(_event, (kind, xs, ys, edge, force, params, d_scale, v, pulls), 0.0, h, 1e-300, _ROOT_TOL,
                         BRENT_ITERATIONS)
    return s, status


_step_size = numba.njit(**_COMPILE)(series.step_size)  # that very function compiled


_grown = numba.njit(**_COMPILE)(owned(grown, "taylor_kernel"))


@numba.njit(_SIGNATURE, **_COMPILE)
def solve(series_kernel, force, numbers, params, gamma, tol, end, lam, max_step, d_scale, v, order, pulls, half):
    """``series.solve`` compiled (its arguments but the law's two kernels, ``params`` the force kernel's and
    (d_scale [m], v [m/s]) the scales of its separation function; lam 0 for a law without a ramp).  ``half`` is 0.5,
    the band bound's exponent, passed in: as a constant LLVM turns x ** 0.5 into sqrt(x), which differs from the C
    library's pow (Python's x ** 0.5) in the last bit now and then.  Returns the steps' starts and ends, their
    coefficients (steps, order + 1) of x and y, tau_m and tau_f (NaN where not found), the state at tau_f, the tau
    a failure happened at, and the status (:data:`SEPARATED`, ...)."""
    n = order + 1
    capacity = 64
    starts, ends = np.empty(capacity), np.empty(capacity)
    cx, cy = np.empty((capacity, n)), np.empty((capacity, n))
    xs, ys = np.empty(n), np.empty(n)
    tau, x, y = 0.0, 0.0, 1.0
    steps = 0
    tau_m = tau_f = x_f = y_f = math.nan
    status = HORIZON
    g = _separation(force, params, d_scale, v, pulls, x, y)
    band = lam != 0.0
    edge = series.BAND_EDGE / lam if band else 0.0
    band_top = edge * (1.0 + 1e-9)
    while tau < end:
        if steps >= series.MAX_STEPS:
            status = BUDGET
            break
        series_kernel(x, y, numbers, gamma, order, xs, ys)
        if not math.isfinite(xs[n - 2] + ys[n - 2] + xs[n - 1] + ys[n - 1]):
            status = OVERFLOW
            break
        h = min(_step_size(xs, ys, tol), max_step, end - tau)
        if band and x <= band_top:
            reach = order / (math.e * lam)  # series.band_limit, its division checked as Python's raises
            dy = ys[1]
            below = abs(y) + (y * y + 2.0 * abs(dy) * reach) ** half
            if below == 0.0:
                status = ZERO_DIVISION
                break
            h = min(h, 2.0 * reach / below)
        x_end = _horner(xs, h)
        if band and x > band_top and edge >= x_end:
            h, found = _event_root(_EDGE, xs, ys, edge, force, params, d_scale, v, pulls, h)
            if found != 0:
                status = NO_ROOT if found == NO_BRACKET else ROOT_UNCONVERGED
                break
            x_end = _horner(xs, h)
        y_end = _horner(ys, h)
        if steps == capacity:
            capacity *= 2
            starts, ends = _grown(starts, steps, capacity), _grown(ends, steps, capacity)
            cx, cy = _grown(cx, steps, capacity), _grown(cy, steps, capacity)
        starts[steps] = tau
        cx[steps], cy[steps] = xs, ys
        if math.isnan(tau_m) and y > 0.0 >= y_end:
            s, found = _event_root(_RATE, xs, ys, edge, force, params, d_scale, v, pulls, h)
            if found != 0:
                status = NO_ROOT if found == NO_BRACKET else ROOT_UNCONVERGED
                break
            tau_m = tau + s
        g_end = _separation(force, params, d_scale, v, pulls, x_end, y_end)
        if not math.isnan(tau_m) and g > 0.0 >= g_end:
            s, found = _event_root(_SEPARATION, xs, ys, edge, force, params, d_scale, v, pulls, h)
            if found != 0:
                status = NO_ROOT if found == NO_BRACKET else ROOT_UNCONVERGED
                break
            if tau_m > tau + s:
                status = EARLY
                break
            tau_f, x_f, y_f = tau + s, _horner(xs, s), _horner(ys, s)
            ends[steps] = tau_f
            steps += 1
            status = SEPARATED
            break
        ends[steps] = tau + h
        steps += 1
        tau, x, y, g = tau + h, x_end, y_end, g_end
    return starts[:steps], ends[:steps], cx[:steps], cy[:steps], tau_m, tau_f, x_f, y_f, tau, status


def solved(series_kernel, force, numbers, params, gamma: float, tol: float, end: float, lam, max_step: float,
           d_scale: float, v: float, pulls: bool) -> dict:
    """:func:`solve` with ``series.solve``'s result and exceptions (``lam`` None for a law without a ramp;
    ``series_kernel`` and ``force`` the law's compiled kernels, by address)."""
    order = series.order_for(tol)
    starts, ends, cx, cy, tau_m, tau_f, x_f, y_f, tau, status = solve(
        series_kernel, force, np.array(numbers, dtype=float), np.array(params, dtype=float), float(gamma),
        float(tol), float(end), float(lam or 0.0), float(max_step), float(d_scale), float(v), order, bool(pulls), 0.5)
    if status == BUDGET:
        raise StepBudgetError(f"more than {series.MAX_STEPS} steps")
    if status == OVERFLOW:
        raise SeriesOverflowError(f"Taylor coefficients overflow at tau = {tau:.6g}")
    if status == ZERO_DIVISION:
        raise ZeroDivisionError("float division by zero")
    if status == EARLY:
        raise ImpactError("separation found before maximum compression (method taylor): the damping stops the ball "
                          "within round-off of first touch (beyond what the solver resolves)")
    if status == NO_ROOT:
        raise ValueError("brent: f(a) and f(b) must be finite and of opposite signs")
    if status == ROOT_UNCONVERGED:
        raise RuntimeError(f"brent: no convergence in {BRENT_ITERATIONS} iterations")
    dense = series.TaylorDense(starts, ends, cx, cy)
    return {"dense": dense, "tau_m": None if math.isnan(tau_m) else tau_m,
            "tau_f": None if math.isnan(tau_f) else tau_f, "state_f": None if math.isnan(tau_f) else [x_f, y_f],
            "order": order}

