"""Roots of bracketed functions: one scalar function (Brent's method) or many decreasing ones at once: no physics.

Every scalar root search of the package (an event's instant on a dense output, a calibration's damping, a family's
switch of regime) is :func:`brent`: the package's own, so that solving one impact never imports scipy.optimize
(half a second, most of a command's start).  The batched event searches of the sweep's lanes and of a closed
form's instants all reduce to one problem: per lane, the root of a function that falls through zero on a known
bracket, with its derivative at hand (:func:`falling_root`).
"""

from __future__ import annotations

import math

import numpy as np

#: Most iterations of :func:`brent` (each one evaluation); it converges in far fewer (superlinearly, and at worst
#: by bisection: about 2100 halvings reach any double from any double bracket, 100 from a bracket of 1 to 1e-30).
BRENT_ITERATIONS = 200


#: :func:`bracketed_root`'s statuses: a root to the tolerance (or where f is 0), the last iterate after ``maxiter``
#: iterations, no bracket (f(a), f(b) not finite or of one sign).
ROOT, LAST_ITERATE, NO_BRACKET = 0, 1, 2


def brent(f, a: float, b: float, xtol: float, rtol: float, maxiter: int = BRENT_ITERATIONS,
          strict: bool = True) -> float:
    """A root of ``f`` in the bracket [a, b] (f(a) and f(b) of opposite signs, or one of them 0), by Brent's method
    (R. P. Brent, Algorithms for Minimization without Derivatives, 1973, ch. 4): inverse quadratic interpolation or
    the secant, with bisection wherever they would not shrink the bracket fast enough (:func:`bracketed_root`).

    It stops once the bracket's half-width is below (``xtol`` + ``rtol`` |x|) / 2 around the best point x, the
    tolerance scipy.optimize.brentq documents for the same arguments, or where f is exactly 0.

    Raises
    ------
    ValueError
        f(a) and f(b) of the same sign, or an endpoint that is not finite.
    RuntimeError
        Not converged within ``maxiter`` iterations (``strict``); with ``strict`` False, the best point so far.
    """
    root, status, other = bracketed_root(_call, f, float(a), float(b), xtol, rtol, maxiter)
    if status == NO_BRACKET:
        f_a, f_b = float(f(a)), float(f(b))
        raise ValueError(f"brent: f(a) = {f_a!r} and f(b) = {f_b!r} must be finite and of opposite signs")
    if status == LAST_ITERATE and strict:
        raise RuntimeError(f"brent: no convergence in {maxiter} iterations (bracket [{root!r}, {other!r}])")
    return root


def _call(x: float, f) -> float:
    return float(f(x))


def bracketed_root(f, args, a: float, b: float, xtol: float, rtol: float, maxiter: int):
    """Brent's method itself, on ``f(x, args)`` returning a float: (x, status, the bracket's other end), status one
    of :data:`ROOT`, :data:`LAST_ITERATE` (x the best point so far) and :data:`NO_BRACKET` (x NaN).  Plain
    arithmetic on floats, so that numba compiles this very function for the compiled normal motion's events
    (:mod:`sphereimpact.integrators.dop853_kernel`) and :func:`brent` runs it as Python: one implementation."""
    f_a, f_b = f(a, args), f(b, args)
    if f_a == 0.0:
        return a, ROOT, b
    if f_b == 0.0:
        return b, ROOT, a
    if not (math.isfinite(f_a) and math.isfinite(f_b)) or (f_a > 0) == (f_b > 0):
        return math.nan, NO_BRACKET, math.nan
    c, f_c = a, f_a  # the other end of the bracket [b, c]; a: the previous best point
    step = before = b - a  # the last step and the one before it
    for _ in range(maxiter):
        if (f_b > 0) == (f_c > 0):  # keep the root between b and c
            c, f_c = a, f_a
            step = before = b - a
        if abs(f_c) < abs(f_b):  # b the best point so far
            a, b, c = b, c, b
            f_a, f_b, f_c = f_b, f_c, f_b
        tol = 0.5 * (xtol + rtol * abs(b))
        half = 0.5 * (c - b)
        if f_b == 0.0 or abs(half) <= tol:
            return b, ROOT, c
        if abs(before) >= tol and abs(f_a) > abs(f_b):  # interpolate
            s = f_b / f_a
            if a == c:  # two points: the secant
                p, q = 2.0 * half * s, 1.0 - s
            else:  # three: inverse quadratic interpolation
                q, r = f_a / f_c, f_b / f_c
                p = s * (2.0 * half * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0:
                q = -q
            else:
                p = -p
            if 2.0 * p < min(3.0 * half * q - abs(tol * q), abs(before * q)):  # accepted: it shrinks fast enough
                before, step = step, p / q
            else:
                step = before = half
        else:
            step = before = half
        a, f_a = b, f_b
        b += step if abs(step) > tol else math.copysign(tol, half)
        f_b = f(b, args)
    return b, LAST_ITERATE, c


#: Most Newton iterations per search (bisection steps where Newton leaves the bracket included).
ROOT_ITERATIONS = 60
#: A lane's iteration stops when its update is below SETTLED x its time (far below any target).
SETTLED = 1e-14


def falling_root(function, a, b, f_a, f_b, offset=0.0, start=None, f_tol=0.0):
    """Root in s of each lane's ``function`` (s -> (f, f') as arrays) with f(a) = f_a > 0 >= f(b) = f_b.

    Newton from ``start`` (default: the secant point); a step leaving the bracket bisects instead; a lane stops
    once its update is below SETTLED x its time ``offset`` + s (``offset``: where s = 0 lies on the lane's
    clock; round-off of f near 1 ulp would otherwise keep it moving), or once |f| <= ``f_tol`` (f's own
    round-off, where f' is small enough that it moves s by more).
    """
    if start is None:
        with np.errstate(divide="ignore", invalid="ignore"):
            start = np.where(f_a - f_b > 0, a + (b - a) * f_a / (f_a - f_b), b)
    s = np.clip(start, a, b)
    for _ in range(ROOT_ITERATIONS):
        f, df = function(s)
        a, b = np.where(f > 0, s, a), np.where(f < 0, s, b)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = s - f / df
        new = np.where((step >= a) & (step <= b), step, 0.5 * (a + b))
        settled = (np.abs(f) <= f_tol) | (np.abs(new - s) <= SETTLED * np.maximum(offset + np.abs(s), 1e-300))
        s = np.where(settled, s, new)
        if settled.all():
            break
    return s
