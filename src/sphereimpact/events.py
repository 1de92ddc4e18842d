"""Locate events on a continuous solution: roots and extrema of functions of time.

The solution is sampled on a grid fine enough that a smooth event function has
at most one sign change between neighbours (the solver's steps, each split in
several parts, or a dense uniform grid for closed forms); each sign change is
then refined with Brent's method on the dense output itself, to a few ulp of t.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq, minimize_scalar


class ImpactError(RuntimeError):
    """The impact has no valid outcome (e.g. the ball never separates) or an event was missed."""


def _scalar(f):
    """``f`` as a function of one float returning one float (f may return a 1-element array)."""
    def value(t):
        v = f(t)
        return v if type(v) is float else float(np.reshape(v, -1)[0])

    return value


def _refine(f, a: float, b: float) -> float:
    return brentq(_scalar(f), a, b, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=200)


def roots(f, grid, direction: int = 0, after: float | None = None) -> list[float]:
    """All roots of ``f`` on ``[grid[0], grid[-1]]``, in time order.

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

    Returns
    -------
    list of float
        Root times [s].  A sample that is exactly zero counts as a root.
    """
    grid = np.asarray(grid, dtype=float)
    if after is not None:
        grid = grid[grid > after]
    values = np.asarray(f(grid), dtype=float)
    if not np.all(np.isfinite(values)):
        raise ImpactError("event function is not finite on the solution")
    sign = np.sign(values)
    found = []
    for i in np.flatnonzero((sign[:-1] != 0) & (sign[:-1] != sign[1:])):
        s0 = sign[i]
        if direction and direction * s0 > 0:  # crossing the wrong way
            continue
        if sign[i + 1] == 0:  # a sample that is exactly zero is the root
            found.append(float(grid[i + 1]))
        else:
            found.append(_refine(f, grid[i], grid[i + 1]))
    return found


def first_root(f, grid, direction: int = 0, after: float | None = None) -> float | None:
    """The earliest root of ``f`` on the grid's span, or ``None`` (see :func:`roots`)."""
    found = roots(f, grid, direction, after)
    return found[0] if found else None


def extremum(f, grid, kind: str, values=None) -> tuple[float, float]:
    """Global ``'min'`` or ``'max'`` of ``f`` over ``[grid[0], grid[-1]]``.

    The best sample is refined by a bounded Brent search between its
    neighbours; the end points are candidates too.  ``values``, if given, is f on the grid (computed
    once for both extremes).

    Returns
    -------
    (t, value) : tuple of float
    """
    grid = np.asarray(grid, dtype=float)
    sgn = 1.0 if kind == "min" else -1.0
    values = sgn * np.asarray(f(grid) if values is None else values, dtype=float)
    i = int(np.argmin(values))
    best_t, best_v = float(grid[i]), float(values[i])
    if 0 < i < len(grid) - 1:
        g = _scalar(f)
        res = minimize_scalar(lambda t: sgn * g(t), bounds=(grid[i - 1], grid[i + 1]),
                              method="bounded", options={"xatol": 1e-14 * max(grid[-1], 1e-300)})
        if res.fun < best_v:
            best_t, best_v = float(res.x), float(res.fun)
    return best_t, sgn * best_v
