"""Batched integration of the dimensionless normal problem: one lane per scene, all lanes at once.

Per lane (tau = omega_n t, x = delta omega_n / v_n, y = x'):

    x' = y,   y' = -P_hat(x, y) + gamma,   x(0) = 0, y(0) = 1,

with P_hat the law's own dimensionless force (``ContactLaw.scaled``): one of :data:`FORMS`, x + 2 zeta y
(eq. 4.1) or x + 2 zeta y r(lam x) with eq. 4.2's ramp r continued past x = 0, lam = c v_n / (omega_n R);
gamma = g cos(beta) / (omega_n v_n).  The step policy and the event function below are built for these
two forms.  Each lane takes fixed steps of the
8th-order Dormand-Prince method (the tableau of :class:`scipy.integrate.DOP853`),
its step chosen from the accuracy target and the lane's fastest scale at its current state.  Events
are roots of y (maximum compression), of the separation function, and of P_hat
(tension begins), located on each lane's one-step map z(s) = Phi_s(z_0),
s in [0, h]: bracketed, then Newton with bisection fallback.  Lanes retire as
they separate; the arrays of the active lanes are compacted as they go.
"""

from __future__ import annotations

from enum import Enum
from functools import cache

import numpy as np

from ..errors import ImpactError
from ..contact.laws import ramp_continued
from ..contact.laws.linear import kelvin_voigt_scaled, modified_per_compression, modified_scaled
from ..contact.separation import Separation
from .outputs import NORMAL_OUTPUTS

#: The dimensionless forces these lanes integrate (a law's ``ContactLaw.scaled``, by identity) -> whether
#: it has eq. 4.2's ramp.
FORMS = {kelvin_voigt_scaled: False, modified_scaled: True}


#: Unit step h_unit = STEP_CONSTANT * target**(1/8) (see :func:`step_size` for the ramp band and the damping
#: limit): calibrated so that the worst relative error over every output stays below the target, with a 5x
#: margin at 1e-8 (checked by tests/test_sweep.py on random samples, targets 1e-3 to 1e-10).
STEP_CONSTANT = 3.6
#: Inside the ramp's band a step changes u = lam x by at most RAMP_FACTOR h_unit exp(u / 9) (see
#: :func:`step_size`): the sweep-path study (results/sweep_paths.csv) found eq. 4.2 at zeta 0.5-1, lam 2-10
#: up to 3.8x its target at the former 4.0; at 2.0 the worst over zeta 0.01-1, lam 0.1-1000 is 0.3x.
RAMP_FACTOR = 2.0
#: At most this change of u = lam x per step inside the ramp's band, whatever the target (one step's
#: polynomial cannot follow exp(-u) over more e-folds at loose targets).
MAX_RAMP_STEP = 2.0
#: Longest dimensionless step (a contact lasts about pi): loose targets still take a dozen steps.
MAX_UNIT_STEP = 0.4
NEWTON_ITERATIONS = 12
#: Dimensionless horizon: far past any contact that ends (see sphereimpact.integrators.normal.horizon).
HORIZON = 100.0 * np.pi


class Forms(Enum):
    """Which of :data:`FORMS` a batch's lanes hold: all eq. 4.2's, all eq. 4.1's, or some of each."""

    MODIFIED = "modified"
    LINEAR = "linear"
    MIXED = "mixed"


class Event(Enum):
    """An event a lane's step is searched for (:func:`_event_value`)."""

    MAX = "max"  # maximum compression: y = 0
    DELTA = "delta"  # delta returns to 0: x = 0
    RATIO = "ratio"  # the force falls to 0: Q = 0 (:meth:`_Lanes.ratio`)


class _Lanes:
    """Per-lane parameters of one batch (arrays of equal length)."""

    def __init__(self, zeta, lam, gamma, modified):
        self.zeta, self.lam, self.gamma, self.modified = zeta, lam, gamma, modified
        self.forms = Forms.MODIFIED if modified.all() else Forms.LINEAR if not modified.any() else Forms.MIXED
        self.ramp_lam = np.where(modified, lam, 0.0)  # lam where a ramp limits the step, 0 where none
        self.two_zeta = 2.0 * zeta
        self.numbers = {"zeta": zeta, "lam": lam}
        self.weightless = not gamma.any()

    def take(self, index):
        return _Lanes(self.zeta[index], self.lam[index], self.gamma[index], self.modified[index])

    def ramp(self, x):
        if self.forms is Forms.LINEAR:
            return 1.0
        ramp = ramp_continued(self.lam * x)
        return ramp if self.forms is Forms.MODIFIED else np.where(self.modified, ramp, 1.0)

    def force(self, x, y):
        """P_hat(x, y): the laws' own dimensionless forces, lane by lane."""
        if self.forms is not Forms.MIXED:
            return (modified_scaled if self.forms is Forms.MODIFIED else kelvin_voigt_scaled)(x, y, self.numbers)
        return np.where(self.modified, modified_scaled(x, y, self.numbers), kelvin_voigt_scaled(x, y, self.numbers))

    def _ratio_terms(self, x):
        """(x > 0, x where positive else 1, ramp there): what Q and its slope share."""
        positive = x > 1e-300
        safe = np.where(positive, x, 1.0)
        return positive, safe, self.ramp(safe)

    def ratio(self, x, y, terms=None):
        """Q = P_hat / x = 1 + 2 zeta y ramp(lam x) / x, and its limit as x -> 0+ where x <= 0.

        Same sign as P_hat while x > 0, but without P_hat's forced zero at x = 0; through restitution
        it only decreases, so its first root (tension, or the force criterion's end) is never skipped
        by a step that P_hat dips below zero and rises again within.  At x -> 0+ it tends to
        G = 1 + 2 zeta lam y (modified: the law's :func:`~sphereimpact.contact.laws.linear.modified_per_compression`)
        or -inf (kelvin-voigt).
        """
        positive, safe, ramp = self._ratio_terms(x) if terms is None else terms
        modified = modified_per_compression(x, y, self.numbers)  # eq. 4.2's own, continued through x = 0
        if self.forms is Forms.MODIFIED:
            return modified
        return np.where(self.modified, modified, np.where(positive, 1.0 + self.two_zeta * y / safe, -np.inf))

    def ratio_and_rate(self, x, y, dy):
        """The function whose root ends the force criterion's contact, and its tau-derivative along the motion
        (dx/dtau = y, dy/dtau = ``dy``), lane by lane: Q (eq. 4.2) or P_hat itself (eq. 4.1).

        Eq. 4.2's P_hat = x Q has a forced zero at x = 0, so its root is Q's: for x > 0, Q = 1 + 2 zeta y r(lam x)
        / x gives 2 zeta (dy r / x + (y / x) y (lam r'(lam x) - r / x)), r' = exp(-u) (u > 0 there); the bracket
        tends to -lam^2 x / 2 as x -> 0, so the form stays finite for tiny x; for x <= 0, the limit's 2 zeta lam
        dy.  Eq. 4.1's P_hat = x + 2 zeta y crosses 0 transversally where x = -2 zeta y > 0 (Q falls there
        towards its pole at x = 0, too steep for Newton at small zeta: the bisections it fell back on left t_f
        2.8e-6 off at zeta 1e-3), so its root is found on P_hat, whose sign is Q's for x > 0: P_hat' = y + 2 zeta
        dy.  Only the search speed depends on the rate: the root is kept bracketed.
        """
        terms = positive, safe, ramp = self._ratio_terms(x)
        slope = np.exp(-self.lam * safe)
        inside = self.two_zeta * (dy * ramp / safe + (y / safe) * y * (self.lam * slope - ramp / safe))
        rate = np.where(positive, inside, self.two_zeta * self.lam * dy)
        if self.forms is Forms.MODIFIED:
            return self.ratio(x, y, terms), rate
        force, force_rate = x + self.two_zeta * y, y + self.two_zeta * dy  # eq. 4.1
        return (np.where(self.modified, self.ratio(x, y, terms), force),
                np.where(self.modified, rate, force_rate))

    def rhs(self, x, y):
        return y, -self.force(x, y) if self.weightless else self.gamma - self.force(x, y)

    def force_slopes(self, x, y):
        """(P_hat, dP_hat/dtau, d2P_hat/dtau2) along the motion, inside contact: with r(u) the ramp at u = lam x
        (1 for eq. 4.1), P_hat' = y + 2 zeta (y' r + lam y^2 r') and P_hat'' = y' + 2 zeta (y'' r + 3 lam y y' r'
        + lam^2 y^3 r''), y' = gamma - P_hat, y'' = -P_hat'.  Turning points of the force are roots of P_hat'."""
        p = self.force(x, y)
        dy = self.gamma - p
        decay = np.where(self.modified, np.exp(-self.ramp_lam * np.maximum(x, 0.0)), 0.0)  # r' = -r'' = exp(-u)
        ramp = self.ramp(x)
        lam = self.ramp_lam
        dp = y + self.two_zeta * (dy * ramp + lam * y * y * decay)
        ddp = dy + self.two_zeta * (-dp * ramp + 3.0 * lam * y * dy * decay - lam * lam * y ** 3 * decay)
        return p, dp, ddp


def _step(lanes: _Lanes, x, y, h):
    """One DOP853 step of per-lane size h from (x, y); returns the new (x, y).

    x and y travel together as one (2, lanes) array, so each stage costs one weighted sum, not two.
    """
    stage_weights, step_weights = _tableau()
    z0 = np.stack((x, y))
    k = np.empty((len(stage_weights), 2, x.size))
    k[0, 0], k[0, 1] = lanes.rhs(x, y)
    for s in range(1, len(stage_weights)):
        z = z0 + h * _combine(stage_weights[s], k)
        k[s, 0], k[s, 1] = lanes.rhs(z[0], z[1])
    z = z0 + h * _combine(step_weights, k)
    return z[0], z[1]


def _nonzero(weights) -> tuple:
    """(indices, column of weights) of the nonzero entries of one tableau row."""
    index = np.flatnonzero(weights)
    return index, weights[index][:, None]


@cache
def _tableau() -> tuple[list, tuple]:
    """DOP853's tableau rows (:mod:`sphereimpact.ode.dop853_tableau`) without their zeros, made on the first step:
    stage s combines the earlier stages with the first list's entry s, the step the stages with the second (the
    right-hand side is autonomous: the stage times are not needed)."""
    from ..ode import dop853_tableau as T

    a, b = np.array(T.A), np.array(T.B)
    return ([None] + [_nonzero(a[s, :s]) for s in range(1, T.N_STAGES)], _nonzero(b))


#: Up to this many values per stage, one running sum over all terms is cheapest; beyond it, a loop of
#: whole-array additions (add.accumulate along the first axis walks each lane separately, 8x slower at
#: 10^4 lanes).  Both add the same terms in the same order.
_ACCUMULATE_MAX = 512


def _combine(weights: tuple, stages):
    """sum_j w_j stages[j] over a row's nonzero weights (see :func:`_nonzero`), lane by lane.

    The terms are added left to right for every lane, so a lane's result does not depend on the
    batch's width: by ``add.accumulate`` (defined as the running sum r_j = r_{j-1} + term_j) for small
    batches, by a Python loop for large ones.  A BLAS product, or ``add.reduce`` (which sums a
    one-lane batch pairwise), may round differently for different widths; tests/test_sweep.py checks
    both paths against the plain sequential sum.
    """
    index, column = weights
    if stages[0].size <= _ACCUMULATE_MAX:
        return np.add.accumulate(column.reshape((-1,) + (1,) * (stages.ndim - 1)) * stages[index], axis=0)[-1]
    total = column[0, 0] * stages[index[0]]
    for j in range(1, index.size):
        total = total + column[j, 0] * stages[index[j]]
    return total


def _event_value(event, lanes: _Lanes, x, y, s):
    """Event function and its tau-derivative at s into a step: an :class:`Event` (y, x or Q, see
    :meth:`_Lanes.ratio`), or a callable ``event(lanes, x, y, s) -> (g, dg)``."""
    if callable(event):
        return event(lanes, x, y, s)
    dx, dy = lanes.rhs(x, y)
    if event is Event.RATIO:
        return lanes.ratio_and_rate(x, y, dy)
    return (y, dy) if event is Event.MAX else (x, dx)


def _level_event(level, tau0):
    """The event 'the impulse j = 1 - y + gamma tau reaches ``level``' (per lane, the step starting at tau0):
    g = level - j falls through 0, dg/dtau = -P_hat."""
    def event(lanes, x, y, s):
        return level - (1.0 - y + lanes.gamma * (tau0 + s)), -lanes.force(x, y)

    return event


def _turn_event(rising):
    """The event 'P_hat turns': P_hat' falls through 0 (a maximum, where ``rising``) or rises through it."""
    sign = np.where(rising, 1.0, -1.0)

    def event(lanes, x, y, s):
        _, dp, ddp = lanes.force_slopes(x, y)
        return sign * dp, sign * ddp

    return event


def _start_state(lanes: _Lanes, x0, y0, s):
    """State on each lane's one-step map at s, where s is mostly 0: only lanes with s > 0 pay for a step."""
    x, y = x0.copy(), y0.copy()
    inner = np.flatnonzero(s > 0)
    if inner.size:
        x[inner], y[inner] = _step(lanes.take(inner), x0[inner], y0[inner], s[inner])
    return x, y


def _locate(event, lanes: _Lanes, x0, y0, tau0, lo, hi, at_lo, at_hi):
    """Root in s of the event on the one-step map from (x0, y0) at time tau0, bracketed by g(lo) > 0 >= g(hi).

    ``at_lo`` and ``at_hi`` are the states at lo and hi (see :func:`_start_state`; the march knows the
    step's end).  Newton with bisection fallback; a lane freezes
    at the last point it evaluated once its Newton step is below 2 ulp of the event time tau0 + s
    (below that the update is round-off in g, and would never settle).  Returns (s, state at s).
    """
    g_lo = _event_value(event, lanes, *at_lo, lo)[0]
    g_hi = _event_value(event, lanes, *at_hi, hi)[0]
    s = np.where(g_lo - g_hi > 0, lo + (hi - lo) * g_lo / np.where(g_lo - g_hi > 0, g_lo - g_hi, 1.0), hi)
    frozen = np.zeros(s.size, bool)  # frozen lanes stay put: a lane's root never depends on its batch
    for iteration in range(NEWTON_ITERATIONS):
        xs, ys = _step(lanes, x0, y0, s)
        g, dg = _event_value(event, lanes, xs, ys, s)
        lo = np.where(g > 0, s, lo)
        hi = np.where(g < 0, s, hi)
        newton = s - g / np.where(dg != 0, dg, -1.0)
        s_new = np.where((newton >= lo) & (newton <= hi), newton, 0.5 * (lo + hi))
        frozen |= (g == 0) | (np.abs(s_new - s) <= 4.5e-16 * np.maximum(tau0 + np.abs(s), 1e-300))
        if frozen.all() or iteration == NEWTON_ITERATIONS - 1:
            break
        s = np.where(frozen, s, s_new)
    return s, (xs, ys)


def _first_ratio_root(lanes: _Lanes, x0, y0, tau0, lo, hi, at_hi):
    """Root of Q (see :meth:`_Lanes.ratio`) on (lo, hi] of each lane's step, if Q(hi) <= 0.

    Q decreases through restitution, so one sign change brackets it, and :func:`_locate` finds it by
    Newton on the one-step map, kept inside the bracket.  ``at_hi`` is the state at hi.  Returns
    (s, y at s, found); s = hi where Q(hi) > 0.
    """
    at_lo = _start_state(lanes, x0, y0, lo)
    found = (lanes.ratio(*at_hi) <= 0) & (lanes.ratio(*at_lo) > 0)
    s, y = hi.copy(), at_hi[1].copy()
    if found.any():
        i = np.flatnonzero(found)
        s[i], (_, y[i]) = _locate(Event.RATIO, lanes.take(i), x0[i], y0[i], tau0[i], lo[i], hi[i],
                                  (at_lo[0][i], at_lo[1][i]), (at_hi[0][i], at_hi[1][i]))
    return s, y, found


def step_size(zeta, lam, x, y, target: float):
    """Per-lane dimensionless step from the accuracy target and the lane's fastest time scale ahead.

    The modified ramp 1 - exp(-u), u = lam x, matters only where exp(-u) is above the target, i.e. for
    u < U = ln(1/target) + 3, near first touch and separation.  There one step's local error in
    following the forcing exp(-u) scales as du^9 exp(-u), so a step may change u by at most
    c exp(u/9), c = RAMP_FACTOR h_unit, with u taken where exp(-u) is largest: at the step's start when
    entering, at its end when approaching x = 0 (du = 9 W((c/9) exp(u/9)), Lambert W as the Wright
    omega function).  Approaching, a step is also no longer than W(c exp(u)) (c is capped at
    MAX_RAMP_STEP): the ramp's rate at the step's end is then resolved too.  Outside the band the ramp
    is constant to the target, and an approaching lane may jump to just inside it.  (A uniform limit
    du <= c took 1.6x the steps for the same accuracy: the band is ~ln(1/target) wide.)
    """
    from scipy.special import wrightomega  # imported on use: a sweep that never takes these lanes does not pay

    unit = min(STEP_CONSTANT * target ** 0.125, MAX_UNIT_STEP)
    c = min(RAMP_FACTOR * unit, MAX_RAMP_STEP)
    band = np.log(1.0 / target) + 3.0
    base = unit / np.maximum(1.0, 2.0 * zeta)
    u = lam * np.maximum(x, 0.0)
    inside = u < band
    ub = np.minimum(u, band)
    graded = c * np.exp(ub / 9.0)  # entering: the step starts where exp(-u) weighs most
    graded_end = 9.0 * wrightomega(ub / 9.0 + np.log(c / 9.0)).real  # approaching: du = c exp((u - du) / 9)
    approach = np.minimum(wrightomega(ub + np.log(c)).real, graded_end)
    du = np.where(y < 0, np.where(inside, approach, u - band + c), np.where(inside, graded, np.inf))
    speed = np.maximum(np.abs(y), 1e-3)  # dtau = du / (lam |y|); |y| > 0 near x = 0 in any contact
    with np.errstate(divide="ignore", invalid="ignore"):
        ramp = np.where(lam > 0, du / (lam * speed), np.inf)
    return np.minimum(base, ramp)


def estimated_contact_time(zeta, lam, separation: Separation) -> np.ndarray:
    """About how long each contact lasts, tau_f (for the engine's choice of path, never for accuracy).

    About pi when under-damped; over-damped (zeta > 1), about pi / sqrt(zeta) under the force criterion,
    and pi + 1.9 sqrt(zeta lam) under the penetration criterion, where the contact creeps back to delta = 0
    (fitted to the modified law at zeta 1-100, lam 4-74: 59 at zeta 64, lam 15 against 61.6 estimated).
    """
    zeta, lam = np.asarray(zeta, dtype=float), np.asarray(lam, dtype=float)
    over = np.maximum(zeta, 1.0)
    creep = np.pi + 1.9 * np.sqrt(over * lam) if separation.pulls else np.pi / np.sqrt(over)
    return np.where(zeta > 1, creep, np.pi)


def estimated_steps(zeta, lam, separation: Separation, target: float) -> np.ndarray:
    """About how many steps each lane takes: :func:`step_size` bounds them by the damping,
    unit / max(1, 2 zeta), over :func:`estimated_contact_time`, plus the ramp band's (within a factor 2.6
    of the steps taken at zeta 0.01-100, lam 4-74, both criteria: 21 040 at zeta 64, lam 15, penetration,
    against 21 942 estimated)."""
    unit = min(STEP_CONSTANT * target ** 0.125, MAX_UNIT_STEP)
    tau_f = estimated_contact_time(zeta, lam, separation)
    return tau_f * np.maximum(1.0, 2.0 * np.asarray(zeta, dtype=float)) / unit + 30.0


def integrate(zeta, lam, gamma, modified, separation: Separation, target: float = 1e-8, levels=None,
              extremes: bool = False) -> dict:
    """Integrate every lane to separation.

    Parameters
    ----------
    zeta, lam, gamma : ndarray
        Damping ratio, ramp parameter c v_n / (omega_n R), gravity gamma (see module docstring).
    modified : ndarray of bool
        True for the modified law, False for kelvin-voigt.
    separation : Separation
        When the lanes end.
    target : float
        Relative accuracy target of every output.
    levels : ndarray, optional
        Per lane, a level of the friction-carrying impulse j = 1 - y + gamma tau (NaN: none) whose first
        instant ``tau_g`` is wanted; where j never reaches it, tau_p (j is largest there).
    extremes : bool
        Also the extremes ``p_max`` and ``p_min`` of P_hat over the contact (at first touch, at separation
        and at its turning points in between).

    Returns
    -------
    dict of ndarray
        :data:`~.outputs.NORMAL_OUTPUTS`, dimensionless: ``tau_m``, ``x_m``, ``tau_f``, ``y_f`` and ``j_p``, the
        impulse of P_hat while positive, 1 - y_p + gamma tau_p where (tau_p, y_p) is where P_hat first falls to
        0 after maximum compression (separation if it does not before); ``tau_g`` with ``levels``, ``p_max``
        and ``p_min`` with ``extremes``.

    Raises
    ------
    ImpactError
        When a lane does not separate within the horizon.
    """
    n = zeta.size
    params = _Lanes(np.asarray(zeta, float), np.asarray(lam, float), np.asarray(gamma, float),
                    np.asarray(modified, bool))
    force_criterion = separation.on_force
    lane = np.arange(n)
    x, y, tau = np.zeros(n), np.ones(n), np.zeros(n)
    past_max = np.zeros(n, bool)  # maximum compression passed
    tension_seen = np.zeros(n, bool)  # P_hat <= 0 seen at a step end (penetration criterion)
    level = np.full(n, np.nan) if levels is None else np.asarray(levels, dtype=float)
    crossed = ~(level > 0)  # no level to find, or 0: reached at first touch
    rising = params.force_slopes(x, y)[1] > 0  # P_hat' > 0 at the step's start
    # Events are only bracketed during the march (step start, size, flags); they are located afterwards
    # in one vectorised pass per kind, so the per-call cost of the step map is paid a few times, not per step.
    records = {"max": [], "tension": [], "end": [], "grip": [], "turn": []}
    while lane.size:
        lanes = params.take(lane)
        h = step_size(lanes.zeta, lanes.ramp_lam, x, y, target)
        x1, y1 = _step(lanes, x, y, h)
        hit_max = ~past_max & (y1 <= 0)
        past_max |= hit_max
        q1 = lanes.ratio(x1, y1)
        x_end = past_max & (x1 <= 0)
        done = x_end | (past_max & (q1 <= 0)) if force_criterion else x_end
        if not force_criterion:
            first = past_max & ~tension_seen & (q1 <= 0) & ~done
            tension_seen |= first
            _record(records["tension"], first, lane, x, y, h, tau, x1=x1, y1=y1)
        _record(records["max"], hit_max, lane, x, y, h, tau, x1=x1, y1=y1)
        _record(records["end"], done, lane, x, y, h, tau, x1=x1, y1=y1, x_end=x_end, tension_seen=tension_seen)
        cross = ~crossed & (1.0 - y1 + lanes.gamma * (tau + h) >= level[lane])  # j reaches the level
        crossed |= cross
        _record(records["grip"], cross, lane, x, y, h, tau, x1=x1, y1=y1)
        if extremes:
            now = lanes.force_slopes(x1, y1)[1] > 0
            _record(records["turn"], now != rising, lane, x, y, h, tau, x1=x1, y1=y1, rising=rising)
            rising = now
        tau = tau + h
        late = ~done & (tau > HORIZON)
        if late.any():
            raise ImpactError(f"no separation within the horizon for {int(late.sum())} scene(s) "
                              f"(first: zeta = {lanes.zeta[late][0]:.3g}, separation '{separation}')")
        keep = ~done
        lane, x, y, tau = lane[keep], x1[keep], y1[keep], tau[keep]
        past_max, tension_seen, crossed, rising = past_max[keep], tension_seen[keep], crossed[keep], rising[keep]
    out = _locate_events(params, records, n, force_criterion, level if levels is not None else None, extremes)
    return out


def _record(store: list, mask, lane, x, y, h, tau, **flags) -> None:
    if mask.any():
        i = np.flatnonzero(mask)
        store.append({"lane": lane[i], "x": x[i], "y": y[i], "h": h[i], "tau": tau[i],
                      **{k: v[i] for k, v in flags.items()}})


def _join(store: list) -> dict:
    return {k: np.concatenate([r[k] for r in store]) for k in store[0]} if store else None


def _locate_events(params: _Lanes, records: dict, n: int, force_criterion: bool, level, extremes: bool) -> dict:
    """Locate every bracketed event at once; see :func:`integrate` for the outputs."""
    out = {k: np.full(n, np.nan) for k in NORMAL_OUTPUTS}
    y_p, tau_p = np.full(n, np.nan), np.full(n, np.nan)  # where P_hat first falls to 0
    where_p = {}  # lane -> (record, index, s) of the step where P_hat first falls to 0
    step_of_max = np.full(n, np.nan)
    s_of_max = np.zeros(n)
    m = _join(records["max"])
    s, (xm, _) = _locate(Event.MAX, params.take(m["lane"]), m["x"], m["y"], m["tau"], np.zeros(m["lane"].size),
                           m["h"], (m["x"], m["y"]), (m["x1"], m["y1"]))
    out["tau_m"][m["lane"]], out["x_m"][m["lane"]] = m["tau"] + s, xm
    step_of_max[m["lane"]], s_of_max[m["lane"]] = m["tau"], s

    def start_of(rec):  # events after maximum compression only, within the step where it happened
        return np.where(rec["tau"] == step_of_max[rec["lane"]], s_of_max[rec["lane"]], 0.0)

    t = _join(records["tension"])
    if t is not None:
        s_t, y_t, found = _first_ratio_root(params.take(t["lane"]), t["x"], t["y"], t["tau"], start_of(t), t["h"],
                                            (t["x1"], t["y1"]))
        y_p[t["lane"][found]], tau_p[t["lane"][found]] = y_t[found], t["tau"][found] + s_t[found]
        where_p["tension"] = (t, np.flatnonzero(found), s_t[found])
    e = _join(records["end"])
    lanes, start = params.take(e["lane"]), start_of(e)
    s_x, x_x, y_x = e["h"].copy(), e["x1"].copy(), e["y1"].copy()  # where delta = 0, and the state there
    if e["x_end"].any():
        i = np.flatnonzero(e["x_end"])
        at_start = _start_state(lanes.take(i), e["x"][i], e["y"][i], start[i])
        s_x[i], (x_x[i], y_x[i]) = _locate(Event.DELTA, lanes.take(i), e["x"][i], e["y"][i], e["tau"][i], start[i],
                                           e["h"][i], at_start, (e["x1"][i], e["y1"][i]))
    search = ~e["tension_seen"] | force_criterion  # P_hat = 0 with delta > 0, not found before this step
    s_p, y_e, found = np.full(e["lane"].size, np.inf), np.full(e["lane"].size, np.nan), np.zeros(e["lane"].size, bool)
    if search.any():
        i = np.flatnonzero(search)
        s_i, y_i, f_i = _first_ratio_root(lanes.take(i), e["x"][i], e["y"][i], e["tau"][i], start[i], s_x[i],
                                          (x_x[i], y_x[i]))
        s_p[i[f_i]], y_e[i[f_i]], found[i[f_i]] = s_i[f_i], y_i[f_i], True
    ends_at_p = force_criterion & found & (s_p <= s_x)
    j = e["lane"]
    out["tau_f"][j] = e["tau"] + np.where(ends_at_p, s_p, s_x)
    out["y_f"][j] = np.where(ends_at_p, y_e, y_x)
    fresh = found & np.isnan(y_p[j])
    y_p[j[fresh]], tau_p[j[fresh]] = y_e[fresh], e["tau"][fresh] + s_p[fresh]
    never = np.isnan(y_p)  # P_hat does not fall to 0 before separation: at separation
    y_p[never], tau_p[never] = out["y_f"][never], out["tau_f"][never]
    where_p["end"] = (e, np.flatnonzero(fresh | never[j]), np.where(ends_at_p | fresh, s_p, s_x)[fresh | never[j]])
    # J+ / (m v_n): the impulse of P_hat while positive, v_n (1 - y) of the motion plus gravity's share gamma tau
    out["j_p"] = 1.0 - y_p + params.gamma * tau_p
    if level is not None:
        out["tau_g"] = _grip_instants(params, records, level, out["j_p"], where_p)
    if extremes:
        out |= _extremes(params, records, out, ends_at_p, j, (x_x, y_x), y_e)
    return out


def _grip_instants(params: _Lanes, records: dict, level, j_p, where_p: dict) -> np.ndarray:
    """tau_g: where j = 1 - y + gamma tau first reaches each lane's level, in the step whose end showed it;
    where no step end did, on the step where P_hat first falls to 0, up to that instant, the level clamped to
    j's largest value j_p (tau_p where the level is beyond it)."""
    tau_g = np.where(level == 0, 0.0, np.nan)
    g = _join(records["grip"])
    if g is not None:
        i = g["lane"]
        s, _ = _locate(_level_event(level[i], g["tau"]), params.take(i), g["x"], g["y"], g["tau"],
                       np.zeros(i.size), g["h"], (g["x"], g["y"]), (g["x1"], g["y1"]))
        tau_g[i] = g["tau"] + s
    for rec, pick, s_p in where_p.values():
        i = rec["lane"][pick]
        todo = np.isnan(tau_g[i]) & (level[i] > 0)
        if not todo.any():
            continue
        i, pick, s_p = i[todo], pick[todo], s_p[todo]
        clamped = np.minimum(level[i], j_p[i])
        x0, y0, tau0 = rec["x"][pick], rec["y"][pick], rec["tau"][pick]
        s = s_p.copy()  # a level at or beyond j_p: reached (clamped) where P_hat falls to 0
        k = np.flatnonzero(clamped < j_p[i])
        if k.size:  # j rises from the step's start to j_p at s_p
            lanes = params.take(i[k])
            at_hi = _start_state(lanes, x0[k], y0[k], s_p[k])
            s[k], _ = _locate(_level_event(clamped[k], tau0[k]), lanes, x0[k], y0[k], tau0[k], np.zeros(k.size),
                              s_p[k], (x0[k], y0[k]), at_hi)
        tau_g[i] = tau0 + s
    return tau_g


def _extremes(params: _Lanes, records: dict, out: dict, ends_at_p, j, at_x, y_e) -> dict:
    """p_max and p_min: P_hat at first touch (x = 0, y = 1), at separation (0 where the force criterion ends
    the contact), and at each turning point before separation (roots of P_hat')."""
    n = out["tau_f"].size
    start = params.force(np.zeros(n), np.ones(n))
    end = np.zeros(n)
    end[j] = np.where(ends_at_p, 0.0, params.take(j).force(*at_x))
    p_max, p_min = np.maximum(start, end), np.minimum(start, end)
    turn = _join(records["turn"])
    if turn is not None:
        i = turn["lane"]
        lanes = params.take(i)
        # in the step where the contact ends, only up to its end: past it the continued force turns too, and
        # a turn just inside (the brief pull before delta returns to 0) must not be lost to one just outside
        hi = np.minimum(turn["h"], out["tau_f"][i] - turn["tau"])
        at_hi = _start_state(lanes, turn["x"], turn["y"], np.where(hi < turn["h"], hi, 0.0))
        at_hi = tuple(np.where(hi < turn["h"], a, b) for a, b in zip(at_hi, (turn["x1"], turn["y1"])))
        event = _turn_event(turn["rising"])
        bracketed = (event(lanes, turn["x"], turn["y"], 0.0)[0] > 0) & (event(lanes, *at_hi, hi)[0] <= 0)
        k = np.flatnonzero(bracketed)
        if k.size:
            rising = turn["rising"][k]
            _, (x, y) = _locate(_turn_event(rising), lanes.take(k), turn["x"][k], turn["y"][k], turn["tau"][k],
                                np.zeros(k.size), hi[k], (turn["x"][k], turn["y"][k]), (at_hi[0][k], at_hi[1][k]))
            value = lanes.take(k).force(x, y)
            np.maximum.at(p_max, i[k][rising], value[rising])
            np.minimum.at(p_min, i[k][~rising], value[~rising])
    return {"p_max": p_max, "p_min": p_min}
