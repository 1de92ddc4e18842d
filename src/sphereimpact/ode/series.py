"""The Taylor-series method for the dimensionless normal motion: method ``taylor``.

For a law whose dimensionless force P_hat(x, y) is analytic (eq. 4.1, eq. 4.2, linear Hunt-Crossley), the
Taylor coefficients of the solution through any point follow from a recurrence (the law's ``series``:
for eq. 4.2 one convolution per order, since E = exp(-lam x) obeys E' = -lam y E).  A step is then one
evaluation of that recurrence to order p, in plain floats, and

- its size comes from the last two coefficients: h = min_k (tol / |c_k|)^(1/k), k = p - 1, p (Jorba &
  Zou, "A software package for the numerical integration of ODEs by means of high-order Taylor methods",
  Experimental Mathematics 14, 2005), with p = ceil(-ln(tol) / 2) + 1, their optimal order;
- its dense output is the polynomial itself, of the method's full order (a Runge-Kutta interpolant is one
  order lower, without error control), so events are roots of polynomials and the state at separation
  is read where the root is, with no landing step;
- the ramp's switch-on is in the coefficients (the series of E is computed, not estimated), but the
  last-coefficient rule assumes they decay, and E's terms E_0 (lam |y| h)^k / k! grow up to
  k ~ lam |y| h: where E_0 is small, a loose tolerance let steps cross the ramp band in one go (COR off by
  2e-6 at lam = 70 for every local tolerance from 1e-7 to 1e-9).  Inside the band (lam x < BAND_EDGE) a step
  therefore changes lam x by at most p / e, where those terms decay from the first order on
  (:func:`band_limit`), and a step that would enter the band from outside ends at its edge, also one that
  starts still compressing (y > 0) just outside it: at orders from 16 up such a step crossed the maximum
  and half the band at once (COR off by 1e-9 to 3e-4 at lam 40-60, where x_m lies just outside the band).

On eq. 4.2 at the default tolerance (1e-10: order 13) it takes 14 to 24 steps where DOP853 takes about 25
steps of 12 evaluations and a landing; one impact costs a third as much (``results/work_precision.csv``
and ``results/bench.csv``).
"""

from __future__ import annotations

import bisect
import math

import numpy as np

from .dense import SMALL, is_instant
from .roots import brent
from ..errors import ImpactError, SeriesOverflowError, StepBudgetError

#: lam x at which the ramp band starts: exp(-37) = 8.5e-17, below round-off of 1 - exp(-lam x).
BAND_EDGE = 37.0
#: Most steps one motion may take: a bound on the cost of any input (about 2 s).
MAX_STEPS = 100_000
#: Orders used: at least ORDER_MIN (loose tolerances), at most ORDER_MAX.
ORDER_MIN, ORDER_MAX = 8, 24
EPS = float(np.finfo(float).eps)


def order_for(tol: float) -> int:
    """Jorba and Zou's optimal order for a local tolerance ``tol``: ceil(-ln(tol) / 2) + 1, clipped."""
    return min(max(math.ceil(-0.5 * math.log(tol)) + 1, ORDER_MIN), ORDER_MAX)


def horner(coefficients, s: float) -> float:
    """sum_k c_k s^k by Horner's rule, in floats: a list or an array of coefficients, index by index in plain code that
    the compiled loops compile too (:mod:`sphereimpact.integrators.taylor_kernel`,
    :mod:`sphereimpact.contact.normal_kernel`)."""
    value = 0.0
    for i in range(len(coefficients) - 1, -1, -1):
        value = value * s + coefficients[i]
    return value


def band_limit(order: int, lam, y, dy):
    """Longest step inside the ramp band: lam |x(s) - x(0)| <= order / e, bounded by |y| s + |dy| s^2 / 2.

    A bound on |y| alone (order / (e lam |y|)) fails near maximum compression, where y ~ 0 at the step's
    start but not at its end: with x_m at the band's edge (lam ~ 37) some orders lost 1e-10 in the COR at a
    local tolerance of 1e-12.  Floats or arrays; ``dy`` is y' at the step's start.
    """
    reach = order / (math.e * lam)
    return 2.0 * reach / (abs(y) + (y * y + 2.0 * abs(dy) * reach) ** 0.5)


def step_size(xs, ys, tol: float) -> float:
    """min over the last two orders k of (tol / max(|x_k|, |y_k|))^(1 / k) (inf if both vanish)."""
    h = math.inf
    for k in (len(xs) - 2, len(xs) - 1):
        size = max(abs(xs[k]), abs(ys[k]))
        if size > 0.0:
            h = min(h, (tol / size) ** (1.0 / k))
    return h


class TaylorDense:
    """The polynomial pieces of a Taylor solution: state (x, y) at any tau on [ts[0], ts[-1]].

    Parameters
    ----------
    starts : list or array of float
        Each step's start tau_i (ascending).
    ends : list or array of float
        Each step's end (the last one may be cut at a terminal event).
    xs, ys : list of lists, or arrays (steps, order + 1)
        Each step's Taylor coefficients in powers of (tau - tau_i), as many for every step (one order).  Arrays (a
        compiled loop's) are kept, not copied: they must not change after.
    """

    def __init__(self, starts, ends, xs, ys):
        # float arrays for the vectorised evaluation and pieces(); the steps' bounds as lists for single(), and a
        # step's coefficients as lists when single() first reads it (an impact reads two or three steps of many)
        self._starts_array, self._ends_array = np.asarray(starts, dtype=float), np.asarray(ends, dtype=float)
        self._cx, self._cy = np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)  # (steps, order + 1)
        self._starts, self._ends = self._starts_array.tolist(), self._ends_array.tolist()
        self.ts = np.concatenate([self._starts_array[:1], self._ends_array])
        self._last = len(self._starts) - 1
        self._rows: dict = {}

    @property
    def steps(self) -> int:
        return self._last + 1

    def pieces(self) -> tuple:
        """(starts, ends, cx, cy): each step's start and end, and its coefficients of x and y (steps, order + 1), as
        float arrays: what :meth:`single` reads, for compiled code that evaluates the same polynomials."""
        return self._starts_array, self._ends_array, self._cx, self._cy

    def single(self, tau: float) -> list:
        """[x, y] at one instant, in floats (an instant on a step boundary takes the earlier step)."""
        i = min(bisect.bisect_left(self._ends, tau), self._last)
        s = tau - self._starts[i]
        rows = self._rows.get(i)
        if rows is None:
            rows = self._rows[i] = (self._cx[i].tolist(), self._cy[i].tolist())
        return [horner(rows[0], s), horner(rows[1], s)]

    def __call__(self, tau):
        """The state at tau: shape (2,) for a scalar, (2, len(tau)) for an array."""
        if is_instant(tau):
            return np.array(self.single(float(tau)))
        tau = np.asarray(tau, dtype=float)
        if tau.size <= SMALL:  # a few instants: the float path per instant beats numpy's per-call cost
            return np.array([self.single(instant) for instant in tau.ravel().tolist()], dtype=float).T.reshape(
                (2, *tau.shape))
        i = np.clip(np.searchsorted(self.ts, tau, side="left") - 1, 0, self._last)
        s = tau - self.ts[i]
        cx, cy = self._cx[i], self._cy[i]  # each instant's step's coefficients, gathered once
        x, y = np.zeros(tau.shape), np.zeros(tau.shape)
        for k in range(self._cx.shape[1] - 1, -1, -1):
            x = x * s + cx[..., k]
            y = y * s + cy[..., k]
        return np.array([x, y])


def _root(f, a: float, b: float) -> float:
    return brent(f, a, b, xtol=1e-300, rtol=4 * EPS)


def solve(series, numbers: dict, gamma: float, tol: float, end: float, separation, lam: float | None = None,
          max_step: float = math.inf) -> dict:
    """Integrate x' = y, y' = -P_hat + gamma from (0, 1) until separation, by the Taylor method.

    Parameters
    ----------
    series : callable
        The law's ``series`` (see :class:`sphereimpact.contact.laws.ContactLaw`).
    numbers : dict
        The law's family numbers, as floats.
    gamma : float
        Dimensionless gravity along the normal.
    tol : float
        Local error bound per step on the O(1) state.
    end : float
        Dimensionless horizon: no separation before it ends the search.
    separation : callable
        ``separation(x, y)`` whose fall through zero (from > 0 to <= 0) ends contact.
    lam : float or None
        The ramp's rate in x (u = lam x), for a law with a ramp: steps entering its band end at its edge.
    max_step : float
        Largest step.

    Returns
    -------
    dict
        ``dense`` (:class:`TaylorDense`), ``tau_m`` and ``tau_f`` (None where not found), ``state_f``
        ([x, y] at tau_f), ``order``.

    Raises
    ------
    StepBudgetError
        More than MAX_STEPS steps.
    SeriesOverflowError
        The coefficients are not finite.
    ImpactError
        Separation before maximum compression.
    """
    order = order_for(tol)
    tau, x, y = 0.0, 0.0, 1.0
    starts, ends, xs_all, ys_all = [], [], [], []
    tau_m = tau_f = state_f = None
    g = separation(x, y)
    edge = None if lam is None else BAND_EDGE / lam
    band_top = None if lam is None else edge * (1.0 + 1e-9)
    while tau < end:
        if len(starts) >= MAX_STEPS:
            raise StepBudgetError(f"more than {MAX_STEPS} steps")
        xs, ys = series(x, y, numbers, gamma, order)
        if not math.isfinite(xs[-2] + ys[-2] + xs[-1] + ys[-1]):  # an inf or nan reaches the top orders
            raise SeriesOverflowError(f"Taylor coefficients overflow at tau = {tau:.6g}")
        h = min(step_size(xs, ys, tol), max_step, end - tau)
        if edge is not None and x <= band_top:  # in the band (a landing may end a hair above)
            h = min(h, band_limit(order, lam, y, ys[1]))
        x_end = horner(xs, h)
        if edge is not None and x > band_top and edge >= x_end:  # entering the ramp band: stop at its edge
            h = _root(lambda s: horner(xs, s) - edge, 0.0, h)
            x_end = horner(xs, h)
        y_end = horner(ys, h)
        starts.append(tau)
        xs_all.append(xs)
        ys_all.append(ys)
        if tau_m is None and y > 0.0 >= y_end:
            s = _root(lambda s: horner(ys, s), 0.0, h)
            tau_m = tau + s
        g_end = separation(x_end, y_end)
        if tau_m is not None and g > 0.0 >= g_end:
            s = _root(lambda s: separation(horner(xs, s), horner(ys, s)), 0.0, h)
            if tau_m > tau + s:
                raise ImpactError("separation found before maximum compression (method taylor): the damping "
                                  "stops the ball within round-off of first touch (beyond what the solver resolves)")
            tau_f, state_f = tau + s, [horner(xs, s), horner(ys, s)]
            ends.append(tau_f)
            break
        ends.append(tau + h)
        tau, x, y, g = tau + h, x_end, y_end, g_end
    dense = TaylorDense(starts, ends, xs_all, ys_all)
    return {"dense": dense, "tau_m": tau_m, "tau_f": tau_f, "state_f": state_f, "order": order}
