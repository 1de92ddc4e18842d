"""Roots of many decreasing functions at once, each kept inside its bracket: no physics.

The batched event searches of the sweep's lanes and of a closed form's instants all reduce to one problem:
per lane, the root of a function that falls through zero on a known bracket, with its derivative at hand.
"""

from __future__ import annotations

import numpy as np

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
