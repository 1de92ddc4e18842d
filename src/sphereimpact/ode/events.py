"""Locate events on a continuous solution: roots and extrema of functions of time.

The solution is sampled on a grid fine enough that a smooth event function has
at most one sign change between neighbours (the solver's steps, each split in
several parts, or a dense uniform grid for closed forms); each sign change is
then refined with Brent's method on the dense output itself, to a few ulp of t.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import ImpactError  # noqa: F401  (re-exported: its home before errors.py)
from .roots import BRENT_ITERATIONS, ROOT, bracketed_root, brent


def _scalar(f):
    """``f`` as a function of one float returning one float (f may return a 1-element array)."""
    def value(t):
        return _value(t, f)

    return value


def _value(t: float, f) -> float:
    """``f(t)`` as one float (f may return a 1-element array): ``f`` as the plain root functions call it."""
    v = f(t)
    return v if type(v) is float else float(np.reshape(v, -1)[0])


#: Relative tolerance of an event's refinement: a few ulp of t.
REFINE_RTOL = 4 * float(np.finfo(float).eps)


def refine_root(g, args, a: float, b: float, root) -> tuple:
    """(the root of ``g(t, args)`` in [a, b], status): a sign change of its samples there, refined by Brent's method
    (``root``: :func:`~.roots.bracketed_root`, or it compiled), status :data:`~.roots.ROOT` unless that fails.

    Evaluated one instant at a time (the scalar path a function may take) the sign change can vanish into round-off
    at one end: the end that is exactly zero, or else the end nearer zero, is then the root (a random scene's force,
    1e-17 from 0 at a grid point, had Brent's method refuse the bracket).  Plain arithmetic on floats, as
    :func:`roots_at`."""
    g_a, g_b = g(a, args), g(b, args)
    if g_a == 0.0 or g_b == 0.0 or (g_a > 0) == (g_b > 0):
        return (a if g_a == 0.0 or (g_b != 0.0 and abs(g_a) < abs(g_b)) else b), ROOT
    t, status, _ = root(g, args, a, b, 1e-300, REFINE_RTOL, BRENT_ITERATIONS)
    return t, status


def roots_at(g, args, grid, values, direction: int, found, refine, root) -> tuple:
    """The roots of ``g(t, args)`` on ``[grid[0], grid[-1]]`` from its samples ``values`` on the grid, in time order
    into ``found`` (room for one more than the grid's intervals): (how many, status, the bracket that failed).

    Each sign change of the samples (``direction``: -1 from + to - only, +1 from - to + only, 0 both) is refined
    (``refine``: :func:`refine_root`, or it compiled, with ``root``); a sample that is exactly zero is the root.  A
    function that ends at (or near) zero may dip through it and back within the last interval, where no sample shows
    it (the brief pull of a force before delta returns to 0: J+ was 1e-6 off): the value just inside the end decides.
    Status :data:`~.roots.ROOT`, else the refinement's failure on the bracket returned.  Plain arithmetic on floats
    and arrays, so that numba compiles this very function (:mod:`sphereimpact.contact.normal_kernel`, for the
    force's sign changes and the rigid contact's grip) and :func:`roots` runs it as Python."""
    sign = np.sign(values)
    changes = np.flatnonzero((sign[:-1] != 0) & (sign[:-1] != sign[1:]))
    count = 0
    for k in range(changes.size):
        i = changes[k]
        if direction != 0 and direction * sign[i] > 0:  # crossing the wrong way
            continue
        if sign[i + 1] == 0:  # a sample that is exactly zero is the root
            found[count] = grid[i + 1]
        else:
            t, status = refine(g, args, grid[i], grid[i + 1], root)
            if status != ROOT:
                return count, status, grid[i], grid[i + 1]
            found[count] = t
        count += 1
    last = grid.size - 1
    if last >= 1 and sign[last - 1] != 0 and (sign[last] == 0 or sign[last] == sign[last - 1]):
        near = grid[last] - 1e-3 * (grid[last] - grid[last - 1])
        if np.sign(g(near, args)) == -sign[last - 1] and not (direction != 0 and direction * sign[last - 1] > 0):
            t, status = refine(g, args, grid[last - 1], near, root)
            if status != ROOT:
                return count, status, grid[last - 1], near
            k = count  # into time order
            while k > 0 and found[k - 1] > t:
                found[k] = found[k - 1]
                k -= 1
            found[k] = t
            count += 1
    return count, ROOT, 0.0, 0.0


def roots(f, grid, direction: int = 0, after: float | None = None, values=None) -> list[float]:
    """All roots of ``f`` on ``[grid[0], grid[-1]]``, in time order (:func:`roots_at` on its samples).

    Parameters
    ----------
    f : callable
        Vectorised function of time t [s].
    grid : array_like
        Increasing sample times [s].
    direction : {-1, 0, 1}
        Keep only crossings from + to - (-1), from - to + (+1), or both (0).
    after : float, optional
        Ignore roots at or before this time (e.g. a force that starts at 0).
    values : array_like, optional
        ``f`` sampled on ``grid`` (with ``after``, on the instants kept), when the caller has it.

    Returns
    -------
    list of float
        Root times [s].  A sample that is exactly zero counts as a root.

    Raises
    ------
    ImpactError
        ``f`` is not finite on the grid.
    ValueError, RuntimeError
        Brent's method refused a bracket or did not converge (:func:`~.roots.brent`'s errors).
    """
    grid = np.asarray(grid, dtype=float)
    if after is not None:
        grid = grid[grid > after]
    values = np.asarray(f(grid) if values is None else values, dtype=float)
    return sampled_roots(_value, f, grid, values, direction)


def sampled_roots(g, args, grid: np.ndarray, values: np.ndarray, direction: int = 0) -> list[float]:
    """:func:`roots_at` in Python, its failures raised (:func:`raise_failed`)."""
    if not np.all(np.isfinite(values)):
        raise_failed(NOT_FINITE)
    found = np.empty(grid.size + 1)
    count, status, a, b = roots_at(g, args, grid, values, direction, found, refine_root, bracketed_root)
    raise_failed(status, lambda t: g(t, args), a, b)
    return found[:count].tolist()


#: Status of a root search whose samples are not all finite (beside :func:`roots_at`'s).
NOT_FINITE = -1


def raise_failed(status: int, f=None, a: float = 0.0, b: float = 0.0) -> None:
    """The error of a root search (:func:`roots_at`, or compiled code running it) that ended with ``status``:
    ImpactError for samples that are not finite (:data:`NOT_FINITE`), :func:`~.roots.brent`'s own error for a
    refinement of ``f`` on [a, b] that failed (it is run again, in Python, to raise it); nothing for ``ROOT``."""
    if status == NOT_FINITE:
        raise ImpactError("event function is not finite on the solution")
    if status != ROOT:
        brent(f, a, b, xtol=1e-300, rtol=REFINE_RTOL)


def first_root(f, grid, direction: int = 0, after: float | None = None) -> float | None:
    """The earliest root of ``f`` on the grid's span, or ``None`` (see :func:`roots`)."""
    found = roots(f, grid, direction, after)
    return found[0] if found else None


def extremes(f, grid, values=None) -> tuple[float, float]:
    """The smallest and largest values of ``f`` over ``[grid[0], grid[-1]]`` (:func:`extremum` of each, ``f`` sampled on
    the grid once, or ``values``, its samples there, when given)."""
    values = f(grid) if values is None else values
    return extremum(f, grid, "min", values)[1], extremum(f, grid, "max", values)[1]


def extremum(f, grid, kind: str, values=None) -> tuple[float, float]:
    """Global ``'min'`` or ``'max'`` of ``f`` over ``[grid[0], grid[-1]]`` (:func:`refined_minimum` of ``f`` or of
    ``-f``).  ``values``, if given, is f on the grid (computed once for both extremes).

    Returns
    -------
    (t, value) : tuple of float
    """
    grid = np.asarray(grid, dtype=float)
    sgn = 1.0 if kind == "min" else -1.0
    values = sgn * np.asarray(f(grid) if values is None else values, dtype=float)
    g = _scalar(f)
    best_t, best_v = refined_minimum(_signed, (g, sgn), grid, values, minimise)
    return best_t, sgn * best_v


def _signed(t: float, args) -> float:
    g, sgn = args
    return sgn * g(t)


def refined_minimum(g, args, grid, values, search) -> tuple[float, float]:
    """The least value of ``g(t, args)`` over ``[grid[0], grid[-1]]``, and where: ``values`` is g on the grid, ``search``
    :func:`minimise` (or it compiled).

    The best sample is refined by a bounded Brent search between its neighbours (``search``), and so is an end
    interval whose value just inside its end point is below both of its samples, for then it has a minimum inside
    that no sample shows (the brief pull before delta returns to 0 hid behind the end point's value); the end points
    are candidates too.  Plain arithmetic on floats and arrays, so that numba compiles this very function for the
    compiled force extremes (:mod:`sphereimpact.contact.normal_kernel`) and :func:`extremum` runs it as Python.

    Returns
    -------
    (t, value) : tuple of float
    """
    i = int(np.argmin(values))
    best_t, best_v = float(grid[i]), float(values[i])
    last = len(grid) - 1
    if last < 1:
        return best_t, best_v
    # the spans to search, in ascending order: the first interval, the best sample's neighbours, the last interval
    lows, highs, count = [0, 0, 0], [0, 0, 0], 0
    near = float(grid[0]) + 1e-3 * (float(grid[1]) - float(grid[0]))
    if g(near, args) < min(values[0], values[1]):  # below both ends of the interval: one inside
        lows[count], highs[count], count = 0, 1, count + 1
    if 0 < i < last:
        lows[count], highs[count], count = i - 1, i + 1, count + 1
    near = float(grid[last]) + 1e-3 * (float(grid[last - 1]) - float(grid[last]))
    if g(near, args) < min(values[last], values[last - 1]) and not (last == 1 and count):  # (0, 1) once
        lows[count], highs[count], count = last - 1, last, count + 1
    xatol = 1e-14 * max(float(grid[last]), 1e-300)
    for k in range(count):
        t, value = search(g, args, float(grid[lows[k]]), float(grid[highs[k]]), xatol, 500)
        if value < best_v:
            best_t, best_v = t, value
    return best_t, best_v


_GOLDEN = 0.5 * (3.0 - math.sqrt(5.0))
_SQRT_EPS = math.sqrt(2.2e-16)  # scipy's


def minimise(g, args, a: float, b: float, xatol: float, maxfun: int = 500) -> tuple[float, float]:
    """(x, g(x, args)) at a minimum of g on [a, b]: Brent's method (golden section with parabolic steps; Brent,
    *Algorithms for Minimization without Derivatives*, 1973, ch. 5), in plain floats.

    The algorithm of scipy's ``minimize_scalar(method='bounded')``, step for step (the same points, tests
    and stopping rule: tests/test_events.py finds the same evaluations and answer), without its per-call
    overhead, which on one impact's peak force cost more than the eight evaluations it needs.  Plain arithmetic,
    so that numba compiles it too (:func:`refined_minimum`).
    """
    x = w = v = a + _GOLDEN * (b - a)
    fx = fw = fv = g(x, args)
    d = e = 0.0
    for _ in range(maxfun - 1):  # maxfun evaluations at most
        middle = 0.5 * (a + b)
        tol = _SQRT_EPS * abs(x) + xatol / 3.0
        if abs(x - middle) <= 2.0 * tol - 0.5 * (b - a):
            break
        parabolic = False
        if abs(e) > tol:  # a parabola through x, w and v
            r = (x - w) * (fx - fv)
            q = (x - v) * (fx - fw)
            p = (x - v) * q - (x - w) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                p = -p
            q = abs(q)
            r, e = e, d
            if abs(p) < abs(0.5 * q * r) and q * (a - x) < p < q * (b - x):
                d, parabolic = p / q, True
                u = x + d
                if u - a < 2.0 * tol or b - u < 2.0 * tol:  # not too near the ends
                    d = tol if x <= middle else -tol
        if not parabolic:  # golden section into the larger part
            e = (b if x < middle else a) - x
            d = _GOLDEN * e
        u = x + (d if abs(d) >= tol else tol if d == 0 else math.copysign(tol, d))
        fu = g(u, args)
        if fu <= fx:
            if u >= x:
                a = x
            else:
                b = x
            v, fv, w, fw, x, fx = w, fw, x, fx, u, fu
        else:
            if u < x:
                a = u
            else:
                b = u
            if fu <= fw or w == x:
                v, fv, w, fw = w, fw, u, fu
            elif fu <= fv or v == x or v == w:
                v, fv = u, fu
    return x, fx
