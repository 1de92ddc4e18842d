"""scipy's DOP853, run in plain Python floats for a small system: method ``DOP853-scalar`` on a law without a
compiled kernel (or before a process loads the compiled one, :mod:`sphereimpact.integrators.dop853_kernel`), and the
compliant tangential springs' stick phases.

:func:`scipy.integrate.solve_ivp` spends most of one impact's time on numpy calls on two-element arrays,
not on arithmetic; :func:`solve` is the same algorithm in plain floats (its cost against solve_ivp's:
``results/bench_stages.csv``).  It has

- the tableau, error estimator, dense output and coefficients of :class:`scipy.integrate.DOP853`
  (Hairer, Norsett & Wanner, *Solving Ordinary Differential Equations I*, 2nd ed., Springer 1993,
  section II.10; the coefficients, scipy's values, in :mod:`.dop853_tableau`);
- scipy's step control: its initial step, safety 0.9, factors 0.2 to 10, exponent -1/8, no growth
  right after a rejection, minimum step 10 ulp of t;
- solve_ivp's events: a sign change between step ends (by direction), the root by Brent's method on the
  step's interpolant to 4 eps (:func:`~sphereimpact.ode.roots.brent`), terminal events ending the integration at
  the root (:func:`located`, which locates the compiled integrator's events too).

So it takes the same steps as solve_ivp's DOP853 up to round-off in the sums (tests/test_dop853.py
compares step sequences, states and events), at a fraction of the cost; the dense output is a
:class:`~sphereimpact.ode.dense.StackedDOP853`.  The right-hand side and the event functions take
``(t, y)`` with y a list of floats and return a sequence (fun) or a float (events).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from operator import mul

import numpy as np
from .dense import StackedDOP853, horner_dop853
from .dop853_tableau import ERROR_ESTIMATOR_ORDER
from .roots import brent

SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0  # scipy's RungeKutta step control
#: The step-size exponent, -1 / (the error estimator's order + 1), as scipy's.
EXPONENT = -1.0 / (ERROR_ESTIMATOR_ORDER + 1)
EPS = np.finfo(float).eps
#: Most iterations of Brent's method locating one event's root on a step's interpolant (it needs far fewer).
ROOT_ITERATIONS = 100
#: solve_ivp's message for each status: a terminal event, the span's end, a step below 10 ulp of t.
MESSAGES = {1: "A termination event occurred.",
            0: "The solver successfully reached the end of the integration interval.",
            -1: "Required step size is less than spacing between numbers."}


def _dense_rows(matrix, lengths) -> list:
    """Row s of ``matrix`` cut to its first lengths[s] weights, as floats (zeros kept: the dot product
    ``sum(map(mul, row, stages))`` with them is one C-level loop, left to right)."""
    return [[float(a) for a in row[:length]] for row, length in zip(np.atleast_2d(matrix), lengths)]


_STAGES = _A = _C = _B = _E3 = _E5 = _EXTRA = _A_EXTRA = _C_EXTRA = _D = None


def _load_tableau() -> None:
    """DOP853's tableau (:mod:`.dop853_tableau`) as float rows, on the first solve."""
    global _STAGES, _A, _C, _B, _E3, _E5, _EXTRA, _A_EXTRA, _C_EXTRA, _D
    from . import dop853_tableau as T

    _STAGES = T.N_STAGES
    _A = _dense_rows(T.A, range(_STAGES))  # stage s: sum over j < s of A[s, j] K_j
    _C = [float(c) for c in T.C]
    _B = _dense_rows(T.B, [_STAGES])[0]
    _E3 = _dense_rows(T.E3, [_STAGES + 1])[0]
    _E5 = _dense_rows(T.E5, [_STAGES + 1])[0]
    _EXTRA = len(T.C_EXTRA)
    _A_EXTRA = _dense_rows(T.A_EXTRA, range(_STAGES + 1, _STAGES + 1 + _EXTRA))
    _C_EXTRA = [float(c) for c in T.C_EXTRA]
    _D = _dense_rows(T.D, [_STAGES + 1 + _EXTRA] * len(T.D))


def tableau() -> tuple:
    """DOP853's tableau as the compiled normal motion takes it (:mod:`sphereimpact.integrators.dop853_kernel`):
    (A, C, B, E3, E5, A_EXTRA, C_EXTRA, D) as contiguous float arrays, each row zero beyond the weights it uses, and
    the number of stages."""
    from . import dop853_tableau as T

    arrays = (T.A, T.C, T.B, T.E3, T.E5, T.A_EXTRA, T.C_EXTRA, T.D)
    return (*(np.ascontiguousarray(a, dtype=float) for a in arrays), int(T.N_STAGES))


def _rms(values) -> float:
    return math.sqrt(sum(v * v for v in values) / len(values))


@dataclass
class Solution:
    """What :func:`solve` returns, with the fields of solve_ivp's result it uses (see :func:`solve`)."""

    t: np.ndarray
    y: np.ndarray
    sol: StackedDOP853 | None
    t_events: list
    y_events: list
    nfev: int
    status: int
    message: str
    steps: int = field(default=0)


def _initial_step(fun, t0, y0, f0, t_bound, max_step, rtol, atol) -> tuple[float, int]:
    """scipy's select_initial_step for order 7 (the error estimator's); returns (h, evaluations used)."""
    interval = abs(t_bound - t0)
    if interval == 0.0:
        return 0.0, 0
    scale = [atol + abs(y) * rtol for y in y0]
    d0 = _rms([y / s for y, s in zip(y0, scale)])
    d1 = _rms([f / s for f, s in zip(f0, scale)])
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, interval)
    f1 = fun(t0 + h0, [y + h0 * f for y, f in zip(y0, f0)])
    d2 = _rms([(a - b) / s for a, b, s in zip(f1, f0, scale)]) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** -EXPONENT  # 1 / (error_estimator_order + 1), as scipy
    return min(100 * h0, h1, interval, max_step), 1


def solve(fun, t_span, y0, rtol: float, atol: float, max_step: float = math.inf, events=(),
          first_step: float | None = None) -> Solution:
    """Integrate y' = fun(t, y) forward over t_span with DOP853 in floats, with dense output and events.

    Parameters
    ----------
    fun : callable
        ``fun(t, y)`` -> sequence of len(y) floats.
    t_span : (float, float)
        Start and end, ascending.
    y0 : sequence of float
    rtol, atol : float
        Scalar tolerances, as solve_ivp's.
    max_step : float
        Largest step.
    events : sequence of callables
        ``event(t, y)`` -> float, with optional attributes ``direction`` and ``terminal`` (solve_ivp's).
    first_step : float, optional
        Initial step; scipy's estimate when None.

    Returns
    -------
    Solution
        ``t`` (step ends), ``y`` (the state there, shape (n, len(t))), ``sol`` (dense output),
        ``t_events`` and ``y_events`` (lists of arrays per event), ``nfev``, ``status`` (1 terminal event,
        0 end of span, -1 step too small) and ``message``.
    """
    if _A is None:
        _load_tableau()
    t, t_bound = float(t_span[0]), float(t_span[1])
    y = [float(v) for v in y0]
    n = len(y)
    f = list(fun(t, y))
    nfev = 1
    if first_step is None:
        h_abs, used = _initial_step(fun, t, y, f, t_bound, max_step, rtol, atol)
        nfev += used
    else:
        h_abs = float(first_step)
    directions = [getattr(e, "direction", 0) for e in events]
    terminal = [bool(getattr(e, "terminal", False)) for e in events]
    g = [float(e(t, y)) for e in events]
    gs = [g]
    ts, ys, coefficients = [t], [y], []
    status, message = None, ""
    comps = range(n)
    while status is None:
        if t == t_bound:  # scipy's solver reports 'finished' once t reaches the bound
            status, message = 0, MESSAGES[0]
            break
        min_step = 10 * abs(math.nextafter(t, math.inf) - t)
        h_abs = max_step if h_abs > max_step else min_step if h_abs < min_step else h_abs
        rejected = False
        while True:
            if h_abs < min_step:
                status, message = -1, MESSAGES[-1]
                break
            t_new = t + h_abs
            if t_new - t_bound > 0:
                t_new = t_bound
            h = t_new - t
            h_abs = abs(h)
            k = [[v] for v in f]  # k[c][j]: component c of stage j
            for s in range(1, _STAGES):
                row = _A[s]
                stage = fun(t + _C[s] * h, [y[c] + h * sum(map(mul, row, k[c])) for c in comps])
                for c in comps:
                    k[c].append(stage[c])
            y_new = [y[c] + h * sum(map(mul, _B, k[c])) for c in comps]
            f_new = list(fun(t + h, y_new))
            for c in comps:
                k[c].append(f_new[c])
            nfev += _STAGES
            scale = [atol + max(abs(a), abs(b)) * rtol for a, b in zip(y, y_new)]
            err5 = [sum(map(mul, _E5, k[c])) / scale[c] for c in comps]
            err3 = [sum(map(mul, _E3, k[c])) / scale[c] for c in comps]
            e5, e3 = sum(e * e for e in err5), sum(e * e for e in err3)  # x * x: inf on overflow, as numpy
            error = 0.0 if e5 == 0 and e3 == 0 else h_abs * e5 / math.sqrt((e5 + 0.01 * e3) * n)
            if error < 1:
                factor = MAX_FACTOR if error == 0 else min(MAX_FACTOR, SAFETY * error ** EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                break
            h_abs *= max(MIN_FACTOR, SAFETY * error ** EXPONENT)
            rejected = True
        if status is not None:
            break
        # the step's dense output (three more stages), as DOP853._dense_output_impl
        for row, c_extra in zip(_A_EXTRA, _C_EXTRA):
            stage = fun(t + c_extra * h, [y[c] + h * sum(map(mul, row, k[c])) for c in comps])
            for c in comps:
                k[c].append(stage[c])
        nfev += _EXTRA
        delta = [b - a for a, b in zip(y, y_new)]
        rows = [delta, [h * a - d for a, d in zip(f, delta)],
                [2 * d - h * (a + b) for d, a, b in zip(delta, f_new, f)]]
        rows += [[h * sum(map(mul, weights, k[c])) for c in comps] for weights in _D]
        t, y, f = t_new, y_new, f_new
        coefficients.append(rows)
        ts.append(t)
        ys.append(y)
        if events:
            g_new = [float(e(t, y)) for e in events]
            gs.append(g_new)
            if any(terminal[i] and _crossed(a, b, directions[i]) for i, (a, b) in enumerate(zip(g, g_new))):
                status, message = 1, MESSAGES[1]
            g = g_new
    return located(events, np.array(ts), np.array(ys), np.array(coefficients).reshape(len(coefficients), 7, n),
                   np.array(gs).reshape(len(gs), len(events)), nfev, status, message)


#: :func:`advance`'s statuses beside a step taken (:data:`STEPPED`): the step fell below 10 ulp of t (solve's -1), the
#: right-hand side's budget would be spent, a right-hand side value left the finite numbers.
STEPPED, STEP_TOO_SMALL, BUDGET, OVERFLOW = 2, -1, -2, -3


def first_step(rhs, args, t0, y, f, t_bound, max_step, rtol, atol, probe, out) -> tuple[float, int]:
    """scipy's select_initial_step for the error estimator's order 7 (:func:`_initial_step`, whose sums it takes in
    their order) for the compiled loops (see :func:`advance`): the step to try first from (t0, y), f = y' there, and
    the right-hand side evaluations it made (into ``out``, at ``probe``: scratch arrays of y's size)."""
    n = y.size
    interval = abs(t_bound - t0)
    if interval == 0.0:
        return 0.0, 0
    d0 = d1 = 0.0
    for comp in range(n):
        scale = atol + abs(y[comp]) * rtol
        a, b = y[comp] / scale, f[comp] / scale
        d0 += a * a
        d1 += b * b
    d0, d1 = math.sqrt(d0 / n), math.sqrt(d1 / n)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, interval)
    for comp in range(n):
        probe[comp] = y[comp] + h0 * f[comp]
    rhs(args, t0 + h0, probe, out)
    d2 = 0.0
    for comp in range(n):
        c = (out[comp] - f[comp]) / (atol + abs(y[comp]) * rtol)
        d2 += c * c
    d2 = math.sqrt(d2 / n) / h0
    h1 = max(1e-6, h0 * 1e-3) if d1 <= 1e-15 and d2 <= 1e-15 else (0.01 / max(d1, d2)) ** -EXPONENT
    return min(min(min(100 * h0, h1), interval), max_step), 1


def advance(rhs, args, t, y, f, h_abs, t_bound, max_step, rtol, atol, tab, k, stage, y_new, f_new, nfev, max_nfev):
    """One accepted step of :func:`solve`'s loop from (t, y), f = y' there, for the compiled loops: scipy's step
    control (the step clamped to [10 ulp of t, ``max_step``] and to ``t_bound``, tried and shrunk until its error
    estimate is below 1, no growth right after a rejection) and DOP853's stages, every sum in :func:`solve`'s order.
    Plain code on float arrays, which numba compiles into each loop
    (:mod:`sphereimpact.integrators.dop853_kernel`, :mod:`sphereimpact.contact.tangential.stick_kernel`).

    ``rhs(args, t, state, out)`` writes y' into ``out`` and returns whether it is finite; ``tab`` is
    :func:`tableau`'s tuple; ``k`` (stages + 4, n) receives the stages, ``y_new`` and ``f_new`` the step's end.

    Returns
    -------
    status, t_new, h, h_abs, nfev
        :data:`STEPPED` (or why not), the step's end and size, the size to try next, the evaluations made so far.
    """
    a, c, b, e3, e5, c_extra, stages = tab[0], tab[1], tab[2], tab[3], tab[4], tab[6], tab[8]
    n, extra = y.size, c_extra.size
    min_step = 10 * abs(np.nextafter(t, np.inf) - t)
    h_abs = max_step if h_abs > max_step else min_step if h_abs < min_step else h_abs
    rejected = False
    while True:
        if h_abs < min_step:
            return STEP_TOO_SMALL, t, 0.0, h_abs, nfev
        if nfev + stages + extra > max_nfev:
            return BUDGET, t, 0.0, h_abs, nfev
        t_new = t + h_abs
        if t_new - t_bound > 0:
            t_new = t_bound
        h = t_new - t
        h_abs = abs(h)
        for comp in range(n):
            k[0, comp] = f[comp]
        finite = True
        for s in range(1, stages):
            for comp in range(n):
                total = 0.0
                for j in range(s):
                    total += a[s, j] * k[j, comp]
                stage[comp] = y[comp] + h * total
            finite &= rhs(args, t + c[s] * h, stage, k[s])
        for comp in range(n):
            total = 0.0
            for j in range(stages):
                total += b[j] * k[j, comp]
            y_new[comp] = y[comp] + h * total
        finite &= rhs(args, t + h, y_new, f_new)
        for comp in range(n):
            k[stages, comp] = f_new[comp]
        nfev += stages
        if not finite:
            return OVERFLOW, t, h, h_abs, nfev
        sum5, sum3 = 0.0, 0.0
        for comp in range(n):
            scale = atol + max(abs(y[comp]), abs(y_new[comp])) * rtol
            total5, total3 = 0.0, 0.0
            for j in range(stages + 1):
                total5 += e5[j] * k[j, comp]
            for j in range(stages + 1):
                total3 += e3[j] * k[j, comp]
            error5, error3 = total5 / scale, total3 / scale
            sum5 += error5 * error5
            sum3 += error3 * error3
        error = 0.0 if sum5 == 0 and sum3 == 0 else h_abs * sum5 / math.sqrt((sum5 + 0.01 * sum3) * n)
        if error < 1:
            factor = MAX_FACTOR if error == 0 else min(MAX_FACTOR, SAFETY * error ** EXPONENT)
            if rejected:
                factor = min(1.0, factor)
            return STEPPED, t_new, h, h_abs * factor, nfev
        h_abs *= max(MIN_FACTOR, SAFETY * error ** EXPONENT)
        rejected = True


def dense_rows(rhs, args, t, y, f, y_new, f_new, h, tab, k, stage, row):
    """The three more stages of an accepted step and its interpolant's rows (scipy's F) into ``row`` (7, n), as
    :func:`solve` computes them (``DOP853._dense_output_impl``), for the compiled loops (see :func:`advance`); returns
    whether every right-hand side value was finite."""
    a_extra, c_extra, d, stages = tab[5], tab[6], tab[7], tab[8]
    n = y.size
    finite = True
    for i in range(c_extra.size):
        for comp in range(n):
            total = 0.0
            for j in range(stages + 1 + i):
                total += a_extra[i, j] * k[j, comp]
            stage[comp] = y[comp] + h * total
        finite &= rhs(args, t + c_extra[i] * h, stage, k[stages + 1 + i])
    for comp in range(n):
        change = y_new[comp] - y[comp]
        row[0, comp] = change
        row[1, comp] = h * f[comp] - change
        row[2, comp] = 2 * change - h * (f_new[comp] + f[comp])
        for i in range(d.shape[0]):
            total = 0.0
            for j in range(d.shape[1]):
                total += d[i, j] * k[j, comp]
            row[3 + i, comp] = h * total
    return finite


def _crossed(before, after, direction):
    """An event function's sign change from ``before`` to ``after`` in its ``direction`` (solve_ivp's rule): floats,
    or arrays that broadcast (one bool each)."""
    up, down = (before <= 0) & (after >= 0), (before >= 0) & (after <= 0)
    return (up & (direction > 0)) | (down & (direction < 0)) | ((up | down) & (direction == 0))


def located(events, ts, ys, coefficients, g, nfev: int, status: int, message: str, found=None) -> Solution:
    """A DOP853 run as a :class:`Solution`, its events located: what :func:`solve` and the compiled normal
    motion (:mod:`sphereimpact.integrators.dop853_kernel`) return.

    Parameters
    ----------
    events : sequence of callables
        The event functions, as :func:`solve` takes them.
    ts, ys : arrays (k + 1,), (k + 1, n)
        Step ends and the states there.
    coefficients : array (k, 7, n)
        Each step's interpolation coefficients (scipy's F).
    g : array (k + 1, len(events))
        The events' values at the step ends; the run stopped after the first step across which a terminal
        event fell through zero in its direction.
    nfev, status, message
        As :func:`solve` reports them.
    found : mapping or None
        (step, event index) -> root of every crossing, where the compiled loop found them by the same rule and
        search; None: found here.

    Every step across which an event changes sign in its direction has its root found by Brent's method on
    the step's interpolant to 4 eps (:func:`~sphereimpact.ode.roots.brent`), the roots of one step in order;
    at a terminal event's root the solution ends (its last step end and state are the root's).
    """
    n = ys.shape[1]
    sizes = np.diff(ts)  # each step's own size, before a terminal root cuts the last
    ts, ys = np.array(ts, dtype=float), np.array(ys, dtype=float)  # copies, which a terminal root cuts
    t_events: list[list] = [[] for _ in events]
    y_events: list[list] = [[] for _ in events]
    directions = [getattr(e, "direction", 0) for e in events]
    terminal = [bool(getattr(e, "terminal", False)) for e in events]
    if events and len(ts) > 1:
        crossed = _crossed(g[:-1], g[1:], np.array(directions))
        for step in np.flatnonzero(crossed.any(axis=1)).tolist():
            t0, t1 = float(ts[step]), float(ts[step + 1])
            rows, h, y0 = coefficients[step][::-1].tolist(), t1 - t0, ys[step].tolist()

            def state(time, rows=rows, t0=t0, h=h, y0=y0):
                return horner_dop853(rows, (time - t0) / h, y0)

            hits = []
            for i in np.flatnonzero(crossed[step]).tolist():
                # to a few ulp; an event function whose round-off keeps Brent from settling there still
                # leaves it a bracket that narrow: its last iterate, not an error
                root = found[step, i] if found is not None else brent(
                    lambda time, e=events[i]: float(e(time, state(time))), t0, t1, xtol=4 * EPS,
                    rtol=4 * EPS, maxiter=ROOT_ITERATIONS, strict=False)
                hits.append((root, i))
            hits.sort()
            for root, i in hits:
                t_events[i].append(root)
                y_events[i].append(np.array(state(root)))
                if terminal[i]:
                    ts[step + 1], ys[step + 1] = root, state(root)
                    break
    steps = len(coefficients)
    sol = StackedDOP853(ts, coefficients, ys[:steps], ts[:steps], sizes) if steps else None
    return Solution(t=ts, y=ys.T, sol=sol, nfev=nfev, status=status, message=message,
                    t_events=[np.array(v) for v in t_events],
                    y_events=[np.array(v).reshape(len(v), n) for v in y_events], steps=steps)
