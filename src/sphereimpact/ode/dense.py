"""Fast evaluation of a DOP853 dense output, bit for bit the values of scipy's.

:class:`scipy.integrate.OdeSolution` evaluates each solver step's interpolant through a Python call per
step touched (a vector of instants over a whole contact visits every step) and a scalar instant through
several layers of checks.  The post-processing of one impact evaluates its solution a few hundred times
(event roots and extrema refined by Brent's method, grids), and through OdeSolution that cost as much as
the integration itself.

:class:`StackedDOP853` holds the interpolants of a DOP853 solution as stacked arrays and evaluates them
with the same arithmetic, in the same order, as :class:`scipy.integrate._ivp.rk.Dop853DenseOutput`
(``y = (((F_6 x + F_5)(1 - x) + F_4) x + ...) + y_old``, x the fraction of the step), so the values are
identical to the last bit (tests/test_dense.py): vectorised over all steps at once for arrays, in plain
float arithmetic for a scalar.  Instants on a step boundary take the earlier step, as OdeSolution does.
:func:`fast_solution` returns it for a DOP853 solution and the OdeSolution unchanged for any other method;
:mod:`sphereimpact.ode.dop853` builds it directly.
"""

from __future__ import annotations

import bisect

import numpy as np


#: Up to this many instants an array is evaluated instant by instant (same values, bit for bit).
SMALL = 4
#: The dense outputs compiled code reads as arrays (``contact.motion.KernelState.kind``): a Taylor method's series
#: (``series.TaylorDense``), a DOP853 interpolant (:class:`StackedDOP853`).
TAYLOR, DOP853 = 0, 1


def is_instant(t) -> bool:
    """True for one instant (a Python or numpy scalar, or a 0-d array): the cheap test first, since the
    scalar paths of the post-processing and of right-hand sides call it thousands of times an impact."""
    return type(t) is float or np.ndim(t) == 0


def horner_dop853(coefficients, x: float, y_old) -> list:
    """One step's DOP853 interpolant at fraction x in plain floats.

    ``coefficients`` are the rows of scipy's F (7 rows of n values) in reverse order; the arithmetic is
    scipy's, in its order.
    """
    if len(y_old) == 2:  # the normal motion's state, unrolled (the same operations, a third of the time)
        return list(interpolant_pair(coefficients, x, y_old[0], y_old[1]))
    y = [0.0] * len(y_old)
    for i, row in enumerate(coefficients):
        factor = x if i % 2 == 0 else 1 - x
        y = [(a + b) * factor for a, b in zip(y, row)]
    return [a + b for a, b in zip(y, y_old)]


def interpolant_pair(rows, x: float, first: float, second: float) -> tuple[float, float]:
    """:func:`horner_dop853` for a state of two components (``first``, ``second`` at the step's start): ``rows``
    the 7 rows of F in reverse order, each a pair.  Plain float arithmetic, so that numba compiles this very
    function for the compiled normal motion's event search (:mod:`sphereimpact.integrators.dop853_kernel`)."""
    a = b = 0.0
    rest = 1 - x
    for i in range(len(rows)):
        factor = x if i % 2 == 0 else rest
        a, b = (a + rows[i][0]) * factor, (b + rows[i][1]) * factor
    return a + first, b + second


def grown(array, size: int, capacity: int):
    """``array`` (C-contiguous) with its first axis ``capacity`` long and its first ``size`` entries kept: the per-step
    arrays of a compiled integration loop outgrowing their room.  Element by element, in plain code that numba compiles
    for each loop in a fraction of the time a slice assignment takes (seconds on every fresh machine)."""
    bigger = np.empty((capacity,) + array.shape[1:])
    flat, old = bigger.reshape(bigger.size), array.reshape(array.size)
    for i in range(size * (array.size // max(array.shape[0], 1))):
        flat[i] = old[i]
    return bigger


class StackedDOP853:
    """A DOP853 dense output over ascending steps, evaluated like OdeSolution (see module docstring).

    Parameters
    ----------
    ts : array_like, shape (n_steps + 1,)
        Step boundaries, ascending (the last may end inside its step, at a terminal event).
    f : array_like, shape (n_steps, 7, n)
        Each step's interpolation coefficients, scipy's ``F``.
    y_old, t_old, h : array_like
        Each step's start state (n_steps, n), start time and signed size (n_steps,).
    """

    def __init__(self, ts, f, y_old, t_old, h):
        self.ts = np.asarray(ts, dtype=float)
        self.f = np.asarray(f, dtype=float)
        self.y_old = np.asarray(y_old, dtype=float)
        self.t_old = np.asarray(t_old, dtype=float)
        self.h = np.asarray(h, dtype=float)
        self._last = len(self.h) - 1
        self._reversed = self.f[:, ::-1]  # the evaluation runs from the highest coefficient down
        self._ts_list = None  # the float path's step ends, made on its first call (a solution joined into another
        self._rows: dict = {}  # never is), and the steps it visited as lists of floats

    @classmethod
    def from_solution(cls, solution) -> "StackedDOP853":
        """The stacked form of an ascending OdeSolution of DOP853 interpolants."""
        steps = solution.interpolants
        return cls(solution.ts, [p.F for p in steps], [p.y_old for p in steps], [p.t_old for p in steps],
                   [p.h for p in steps])

    def join(self, later: "StackedDOP853") -> "StackedDOP853":
        """This solution up to ``later.ts[0]``, then ``later`` (whose first step starts there)."""
        keep = int(np.searchsorted(self.ts, later.ts[0], side="left"))  # steps ending at or before the join
        return StackedDOP853(np.concatenate([self.ts[:keep], later.ts]),
                             np.concatenate([self.f[:keep], later.f]),
                             np.concatenate([self.y_old[:keep], later.y_old]),
                             np.concatenate([self.t_old[:keep], later.t_old]),
                             np.concatenate([self.h[:keep], later.h]))

    def __call__(self, t):
        """The state at t: shape (n,) for a scalar t, (n, len(t)) for an array (as OdeSolution)."""
        if is_instant(t):
            return np.array(self.single(float(t)))
        t = np.asarray(t, dtype=float)
        if t.size <= SMALL:  # a few instants: the float path per instant beats numpy's per-call cost
            return np.array([self.single(instant) for instant in t.tolist()], dtype=float).reshape(
                t.size, self.y_old.shape[1]).T
        step = np.clip(np.searchsorted(self.ts, t, side="left") - 1, 0, self._last)
        x = ((t - self.t_old[step]) / self.h[step])[:, None]
        f = self._reversed[step]
        y = np.zeros((t.size, self.y_old.shape[1]))
        for i in range(f.shape[1]):
            y += f[:, i]
            if i % 2 == 0:
                y *= x
            else:
                y *= 1 - x
        y += self.y_old[step]
        return y.T

    def single(self, t: float) -> list:
        """The state at one instant t, as a list of floats (the cheapest call)."""
        if self._ts_list is None:
            self._ts_list = self.ts.tolist()
        step = min(max(bisect.bisect_left(self._ts_list, t) - 1, 0), self._last)
        row = self._rows.get(step)
        if row is None:  # a contact's few queries visit a few of its steps: convert those alone
            row = self._rows[step] = (self._reversed[step].tolist(), float(self.t_old[step]), float(self.h[step]),
                                      self.y_old[step].tolist())
        f, t_old, h, y_old = row
        return horner_dop853(f, (t - t_old) / h, y_old)


def fast_solution(solution):
    """A faster evaluator with identical values for a DOP853 OdeSolution; anything else is returned as is."""
    if isinstance(solution, StackedDOP853):
        return solution
    steps = solution.interpolants
    ascending = solution.ts[-1] > solution.ts[0]
    if ascending and steps and all(type(p).__name__ == "Dop853DenseOutput" and hasattr(p, "F") for p in steps):
        return StackedDOP853.from_solution(solution)
    return solution
