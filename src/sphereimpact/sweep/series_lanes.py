"""Batched Taylor lanes: eq. 4.2's weightless normal problem, one lane per scene, by series.

Per lane (the dimensionless problem of :mod:`.batch`, without gravity, law ``modified``):

    x' = y,   y' = -P_hat,   P_hat = x + 2 zeta y (1 - exp(-lam x)),   x(0) = 0, y(0) = 1.

Each step is the law's Taylor recurrence to order p on every active lane at once
(:func:`sphereimpact.contact.laws.linear.modified_series_batched`, beside the one-impact
:func:`~sphereimpact.contact.laws.linear.modified_series`), its size from the last two coefficients and its ramp
band as in :mod:`sphereimpact.ode.series`.  On the plane's nodes both these and the Runge-Kutta lanes
(:mod:`.batch`) take about 30 steps, but a Taylor step is p orders of a few array operations where a Runge-Kutta
step is 12 evaluations of the ramp, and events need no extra steps.  Their cost is the steps', nearly whatever
the number of lanes, so they suit batches of a few hundred to a few thousand nodes of an interpolant.

Events are roots on each lane's step polynomials, located after the march in one vectorised pass per kind
by Newton kept inside their bracket: y (maximum compression), x (delta = 0) and Q = P_hat / x (tension
begins; the force criterion's end).  Q is evaluated as 1 + 2 zeta lam y phi(lam x),
phi(u) = (1 - exp(-u)) / u, an entire function: it keeps full precision through x = 0, where it equals
G = 1 + 2 zeta lam y.

Besides the two criteria, a lane may end ``CONTINUED`` (:class:`End`): at the first root of Q after maximum compression
wherever it lies, past delta = 0 (on the law's analytic continuation) where the force does not pull before.
Its outputs equal the force criterion's wherever the force pulls (G < 0 at delta = 0) and continue them
analytically where it does not, so they are smooth across the tension onset: an interpolant of them needs
no cut along it (:class:`.plane.PlaneInterpolant`).

The local tolerance is TOLERANCE_FACTOR x target / max(1, 2 zeta)^2 per lane: near critical damping the
penetration criterion's tau_f is ill-conditioned (x creeps to 0), and without the factor its error reached
0.55 target at zeta = 0.99.
"""

from __future__ import annotations

from enum import IntEnum

import numpy as np

from ..contact.laws.linear import modified_per_compression, modified_series_batched, ramp_per_x
from ..contact.separation import Separation
from ..errors import ImpactError
from ..ode.roots import falling_root
from ..ode.series import BAND_EDGE, MAX_STEPS, band_limit, order_for
from .batch import HORIZON
from .outputs import NORMAL_OUTPUTS

#: Largest damping ratio and lam the lanes are tested to (tests/test_series_lanes.py; lam up to 1e20 ran
#: without overflow, 1e50 overflows); the engine and the interpolants give them no more (:func:`covers`).
ZETA_MAX, LAM_MAX = 1.0, 1e12
#: Local tolerance per unit of the accuracy target (before the damping's factor, see the module docstring):
#: measured on random (zeta, lam), zeta 0.003-1, lam 0.01-1e4, both criteria, against the Runge-Kutta lanes
#: at target 1e-12 (tests/test_series_lanes.py).
TOLERANCE_FACTOR = 0.01
#: Tightest local tolerance (round-off of the O(1) state).
TOLERANCE_MIN = 1e-15


def covers(zeta, lam):
    """Whether the lanes take (zeta, lam): their tested domain, 0 < zeta <= ZETA_MAX and lam <= LAM_MAX."""
    return (zeta > 0) & (zeta <= ZETA_MAX) & (lam <= LAM_MAX)


def _horner(coefficients, s):
    """sum_k c_k s^k per lane: coefficients (order + 1, ..., lanes), s (lanes,)."""
    value = coefficients[-1] * np.ones_like(s)
    for c in coefficients[-2::-1]:
        value *= s
        value += c
    return value


def _derivative(coefficients):
    return coefficients[1:] * np.arange(1, coefficients.shape[0])[:, None]


def ratio(x, y, two_zeta, lam):
    """Q = P_hat / x, the law's (:func:`~sphereimpact.contact.laws.linear.modified_per_compression`)."""
    return modified_per_compression(x, y, {"zeta": 0.5 * two_zeta, "lam": lam})


def _ratio_and_slope(xs, ys, two_zeta, lam):
    """s -> (Q, dQ/ds) along step polynomials: d/ds = 2 zeta (y' phi + y x' dphi/dx), phi the law's
    :func:`~sphereimpact.contact.laws.linear.ramp_per_x`."""
    dxs, dys = _derivative(xs), _derivative(ys)

    def value(s):
        x, y = _horner(xs, s), _horner(ys, s)
        phi = ramp_per_x(x, lam)
        u = lam * x
        with np.errstate(divide="ignore", invalid="ignore"):  # (lam exp(-u) - phi) / x; -lam^2 / 2 near x = 0
            slope = np.where(np.abs(u) > 1e-4, (lam * np.exp(-u) - phi) / np.where(x != 0, x, 1.0),
                             -0.5 * lam * lam * (1.0 - 2.0 * u / 3.0))
        return 1.0 + two_zeta * y * phi, two_zeta * (_horner(dys, s) * phi + y * _horner(dxs, s) * slope)

    return value


def _polynomial(coefficients):
    """s -> (p(s), p'(s)) of each lane's polynomial (one Horner pass for both)."""
    both = np.zeros((coefficients.shape[0], 2, coefficients.shape[1]))
    both[:, 0], both[:-1, 1] = coefficients, _derivative(coefficients)
    return lambda s: _horner(both, s)


def _polynomial_root(coefficients, b, tau):
    """Root in (0, b] of each lane's decreasing polynomial, positive at 0."""
    zero = np.zeros(b.size)
    return falling_root(_polynomial(coefficients), zero, b, coefficients[0], _horner(coefficients, b), tau)


class End(IntEnum):
    """How a lane ends: under a separation criterion (:meth:`of`), or ``CONTINUED`` (module docstring)."""

    FORCE = 0
    PENETRATION = 1
    CONTINUED = 2

    @classmethod
    def of(cls, separation: Separation) -> End:
        """The end of a lane under the criterion ``separation``."""
        return cls.FORCE if separation.on_force else cls.PENETRATION


def _second_derivative(ys, s):
    """y''(s) of each lane's step polynomial (coefficients ys, shape (order + 1, lanes))."""
    k = np.arange(2, ys.shape[0])[:, None]
    return _horner(ys[2:] * (k * (k - 1)), s)


def integrate(zeta, lam, end, target: float = 1e-8, levels=None, extremes: bool = False,
              partial: bool = False, keep_steps: bool = False) -> dict:
    """Integrate every lane to separation by the Taylor method.

    Parameters
    ----------
    zeta, lam : ndarray
        Damping ratio and ramp parameter c v_n / (omega_n R) (see :mod:`.batch`), finite and positive.
    end : Separation, End or int array of End
        Each lane's end (one for all, or one per lane; see the module docstring for ``CONTINUED``).
    target : float
        Relative accuracy target of every output.
    levels : ndarray, optional
        Per lane, a level of the friction-carrying impulse j = J+ / (m v_n) (NaN: none) whose first instant
        ``tau_g`` is wanted; where j never reaches it, the instant j is largest (P_hat first falls to 0).  Shape
        (lanes,), or (lanes, L) for L levels of each lane: one lane then serves them all (each level's instant the
        one a lane of its own gives, to the bit: the lanes' arithmetic is element by element, and a lane that goes
        on past a level's instant took the steps a lane of that level alone took up to it).
    extremes : bool
        Also the extremes ``p_max`` and ``p_min`` of P_hat over the contact (its ends and its turning points;
        ``CONTINUED`` lanes: its ends and maxima).
    partial : bool
        Only ``tau_g`` (with ``levels``) and ``p_max`` (with ``extremes``): each lane stops once it has both,
        its level's instant and maximum compression (the force's largest value comes before it: there
        dP_hat/dtau = -2 zeta P_hat r < 0, and after it P_hat < x < x_m = P_hat(tau_m)); the rest of its motion
        is not integrated.
    keep_steps : bool
        Also ``steps``, a :class:`Marched` of the lanes' steps, which gives the instants of any levels afterwards
        (:meth:`Marched.instants`) as a ``partial`` call with those levels would, without integrating again.

    Returns
    -------
    dict of ndarray
        :data:`~.outputs.NORMAL_OUTPUTS` as :func:`.batch.integrate` gives them, here without gravity: j_p =
        1 - y_p (``CONTINUED``: tau_f and y_f at the root of Q, j_p = 1 - y_f); with ``levels``, ``tau_g`` (shaped
        as ``levels``); with ``extremes``, ``p_max`` and ``p_min``.  ``partial``: ``tau_g`` and ``p_max`` alone.

    Raises
    ------
    ImpactError
        A lane that does not separate within the horizon, takes more than MAX_STEPS steps or whose series
        leaves double precision.
    """
    zeta, lam = np.asarray(zeta, dtype=float), np.asarray(lam, dtype=float)
    n = zeta.size
    kind = np.broadcast_to(np.asarray(End.of(end) if isinstance(end, Separation) else end), zeta.shape)
    if not np.isin(kind, tuple(End)).all():
        raise ValueError(f"end must be a Separation or one of {', '.join(e.name for e in End)}; got {end!r}")
    wanted = ([*(["tau_g"] if levels is not None else []), *(["p_max"] if extremes else [])] if partial else
              [*NORMAL_OUTPUTS, *(["tau_g"] if levels is not None else []), *(["p_max", "p_min"] if extremes else [])])
    if n == 0:
        return {k: np.empty(0) for k in wanted}
    level = np.full((n, 1), np.nan) if levels is None else np.asarray(levels, dtype=float).reshape(n, -1).copy()
    tol = np.maximum(TOLERANCE_FACTOR * target / np.maximum(1.0, 2.0 * zeta) ** 2, TOLERANCE_MIN)
    order = order_for(TOLERANCE_FACTOR * target)  # the target's, not the batch's: a lane's result is its own
    lane = np.arange(n)
    two_zeta, lam_a, at_root, at_zero = 2.0 * zeta, lam.copy(), kind != End.PENETRATION, kind == End.PENETRATION
    continued = kind == End.CONTINUED
    edge = BAND_EDGE / lam
    x, y, tau = np.zeros(n), np.ones(n), np.zeros(n)
    past = np.zeros(n, bool)
    tension_seen = np.zeros(n, bool)
    crossed = ~(level > 0)  # (lanes, levels): no level to find, or level 0 (reached at first touch)
    turning = np.ones(n)  # sign of dP_hat/dtau = -y'' at the step's start (P_hat rises from first touch)
    records = {"max": [], "tension": [], "end": [], "grip": [], "turn": [], "step": []}
    for _ in range(MAX_STEPS):
        if not lane.size:
            break
        with np.errstate(over="ignore", invalid="ignore"):  # checked just below
            z = modified_series_batched(x, y, two_zeta, lam_a, order)
        xs, ys = z[:, 0], z[:, 1]
        top, below = np.abs(z[-1]).max(axis=0), np.abs(z[-2]).max(axis=0)
        if not np.all(np.isfinite(top) & np.isfinite(below)):
            i = np.flatnonzero(~(np.isfinite(top) & np.isfinite(below)))[0]
            raise ImpactError(f"Taylor coefficients overflow (zeta = {two_zeta[i] / 2:.6g}, lam = {lam_a[i]:.6g})")
        with np.errstate(divide="ignore"):
            h = np.minimum((tol / top) ** (1.0 / order), (tol / below) ** (1.0 / (order - 1)))
        in_band = x <= edge * (1.0 + 1e-9)  # a landing may end a hair above the edge
        h = np.where(in_band, np.minimum(h, band_limit(order, lam_a, y, ys[1])), h)
        x1, y1 = _horner(z, h)
        enter = ~in_band & (edge >= x1)  # also a step still compressing at its start (see taylor.py)
        if enter.any():  # the step ends at the band's edge
            i = np.flatnonzero(enter)
            shifted = xs[:, i].copy()
            shifted[0] -= edge[i]
            h[i] = _polynomial_root(shifted, h[i], tau[i])
            x1[i], y1[i] = _horner(z[:, :, i], h[i])
        hit_max = ~past & (y1 <= 0)
        past |= hit_max
        x_end = past & (x1 <= 0) & ~continued
        pulls = past & ~x_end & (ratio(x1, y1, two_zeta, lam_a) <= 0)
        done = (x_end & at_zero) | (at_root & (pulls | x_end))
        first = pulls & ~tension_seen & ~done
        tension_seen |= first
        cross = _crossings(crossed, y1, level)
        masks = [("max", hit_max), ("tension", first), ("end", done), ("grip", cross.any(axis=1))]
        if extremes:  # records carry the sign at the step's start (turning before the update)
            turned = np.sign(-_second_derivative(ys, h))
            masks.append(("turn", (turned != turning) & (turned != 0)))
        for event, mask in masks:
            if mask.any():
                i = np.flatnonzero(mask)
                records[event].append({"lane": lane[i], "tau": tau[i], "h": h[i], "xs": xs[:, i], "ys": ys[:, i],
                                       "x_end": x_end[i], "seen": tension_seen[i], "cross": cross[i].T,
                                       "rising": turning[i] > 0})
        if keep_steps:  # every step, for Marched.instants to replay a partial call's crossings and stops on
            records["step"].append({"lane": lane, "tau": tau, "h": h, "ys": ys, "y1": y1, "stop": pulls | x_end})
        if extremes:
            turning = np.where(turned != 0, turned, turning)
        tau = tau + h
        x, y = x1, y1
        late = ~done & (tau > HORIZON)
        if late.any():
            raise ImpactError(f"no separation within the horizon for {int(late.sum())} scene(s) "
                              f"(first: zeta = {two_zeta[late][0] / 2:.3g}, lam = {lam_a[late][0]:.3g})")
        if partial:  # done with its instant (or once P_hat first falls to 0: j is largest) and, for the
            done = (crossed.all(axis=1) | pulls | x_end) & (past | (not extremes))  # force's maximum, past its top
        if done.any():  # ended lanes leave the batch
            keep = ~done
            lane, x, y, tau = lane[keep], x[keep], y[keep], tau[keep]
            past, tension_seen, crossed, turning = past[keep], tension_seen[keep], crossed[keep], turning[keep]
            two_zeta, lam_a, edge, tol, level = two_zeta[keep], lam_a[keep], edge[keep], tol[keep], level[keep]
            at_root, at_zero, continued = at_root[keep], at_zero[keep], continued[keep]
    else:
        raise ImpactError(f"the Taylor lanes took more than {MAX_STEPS} steps")
    if partial:
        out = {}
        if levels is not None:
            out["tau_g"] = _level_instants(records, 2.0 * zeta, lam, np.ones(n, bool), levels)
        if extremes:
            out["p_max"] = _turns(records, 2.0 * zeta, lam, np.full(n, np.inf), kind == End.CONTINUED)[0]
        return out
    out = _events(records, 2.0 * zeta, lam, kind != End.PENETRATION, continued_all=kind == End.CONTINUED,
                  extremes=extremes)
    if levels is not None:
        out["tau_g"] = _level_instants(records, 2.0 * zeta, lam, kind != End.PENETRATION, levels)
    if keep_steps:
        out["steps"] = Marched(records, 2.0 * zeta, lam)
    return out


class Marched:
    """The steps of lanes integrated to their end (``integrate(..., keep_steps=True)``): the instants of any levels
    of the impulse j, each the one a ``partial`` call with those levels gives, to the bit.  A partial lane takes the
    same steps (a step depends on the lane's own state alone) and stops once it has crossed every level or the
    force first falls to 0 (delta = 0 or tension): :meth:`instants` replays those crossings and stops on the kept
    steps, then locates each instant as that call does (:func:`_level_instants`)."""

    def __init__(self, records: dict, two_zeta, lam):
        self._steps, self._tension, self._end = records["step"], records["tension"], records["end"]
        self._two_zeta, self._lam = two_zeta, lam

    def instants(self, levels) -> np.ndarray:
        """tau_g at ``levels`` (lanes, L) of j = J+ / (m v_n) (NaN: none), shaped as ``levels``."""
        levels = np.asarray(levels, dtype=float)
        n = self._two_zeta.size
        level = levels.reshape(n, -1)
        crossed = ~(level > 0)
        running = np.ones(n, bool)
        grips = []
        for step in self._steps:
            mine = running[step["lane"]]
            if not mine.any():
                continue
            i = np.flatnonzero(mine)
            lane = step["lane"][i]
            reached = crossed[lane]  # a copy: marked by _crossings, then written back
            cross = _crossings(reached, step["y1"][i], level[lane])
            crossed[lane] = reached
            hit = np.flatnonzero(cross.any(axis=1))
            if hit.size:
                grips.append({"lane": lane[hit], "tau": step["tau"][i[hit]], "h": step["h"][i[hit]],
                              "ys": step["ys"][:, i[hit]], "cross": cross[hit].T})
            running[lane[reached.all(axis=1) | step["stop"][i]]] = False
        records = {"grip": grips, "tension": self._tension, "end": self._end}
        return _level_instants(records, self._two_zeta, self._lam, np.ones(n, bool), levels)


def _crossings(crossed, y1, level):
    """The levels (lanes, L) that the impulse j = 1 - y reaches within a step ending at y1, not reached before:
    marked in ``crossed`` too (the march's rule, and :meth:`Marched.instants`' replay of it)."""
    cross = ~crossed & ((1.0 - y1)[:, None] >= level)
    crossed |= cross
    return cross


def _join(store: list) -> dict | None:
    if not store:
        return None
    return {k: np.concatenate([r[k] for r in store], axis=-1) for k in store[0]}


def _ratio_root(xs, ys, two_zeta, lam, b, q_b, tau):
    """Root in (0, b] of Q along each lane's step polynomials, Q(0) > 0 >= Q(b) = ``q_b``."""
    q_0 = ratio(xs[0], ys[0], two_zeta, lam)
    return falling_root(_ratio_and_slope(xs, ys, two_zeta, lam), np.zeros(b.size), b, q_0, q_b, tau)


def _first_zero(rec, two_zeta, lam):
    """Where P_hat first falls to 0 within each recorded step (a tension or an end step): (s, x_end)."""
    j = rec["lane"]
    s_end = rec["h"].copy()
    if rec["x_end"].any():
        i = np.flatnonzero(rec["x_end"])
        s_end[i] = _polynomial_root(rec["xs"][:, i], rec["h"][i], rec["tau"][i])
    y_end = _horner(rec["ys"], s_end)
    q_end = ratio(np.where(rec["x_end"], 0.0, _horner(rec["xs"], s_end)), y_end, two_zeta[j], lam[j])
    return s_end, q_end


def _level_instants(records: dict, two_zeta, lam, at_root, levels) -> np.ndarray:
    """tau_g of every lane's levels, shaped as ``levels`` ((lanes,) or (lanes, L)): the root of 1 - y(s) = level in
    the step where j first reached it or, where no step end showed it, on [0, s_p] of the step where P_hat first
    falls to 0 (j's maximum there, the level clamped to it).  Each (lane, level) pair is its own root search, the
    one a lane of that level alone makes; what belongs to the lane (its step's s_p and y there) is found once."""
    levels = np.asarray(levels, dtype=float)
    level = levels.reshape(two_zeta.size, -1)
    tau_g = np.where(level == 0, 0.0, np.nan)
    g = _join(records["grip"])
    if g is not None:
        step, column = np.nonzero(g["cross"].T)  # each crossing: its record and its level
        lane = g["lane"][step]
        shifted = g["ys"][:, step]
        shifted[0] -= 1.0 - level[lane, column]  # y(s) - (1 - level): positive at the step's start, <= 0 at its end
        tau_g[lane, column] = g["tau"][step] + _polynomial_root(shifted, g["h"][step], g["tau"][step])
    todo = np.isnan(tau_g) & (level > 0)
    for kind in ("tension", "end"):  # the step where P_hat first falls to 0 (a tension step comes first)
        if not todo.any():
            break
        rec = _join(records[kind])
        if rec is None:
            continue
        pick = np.flatnonzero(todo[rec["lane"]].any(axis=1))
        if not pick.size:
            continue
        rec = {k: v[..., pick] for k, v in rec.items()}
        j = rec["lane"]
        s_end, q_end = _first_zero(rec, two_zeta, lam)
        s_p = s_end.copy()
        search = q_end <= 0
        if search.any():
            i = np.flatnonzero(search)
            s_p[i] = _ratio_root(rec["xs"][:, i], rec["ys"][:, i], two_zeta[j[i]], lam[j[i]], s_end[i], q_end[i],
                                 rec["tau"][i])
        # an end step holds the first zero only where no tension step came before
        use = ~rec["seen"] | at_root[j] if kind == "end" else np.ones(j.size, bool)
        y_p = _horner(rec["ys"], s_p)
        step, column = np.nonzero(todo[j] & use[:, None])  # the pairs this kind's steps serve
        lane, wanted = j[step], level[j[step], column]
        shifted = rec["ys"][:, step]
        shifted[0] -= np.maximum(1.0 - wanted, y_p[step])  # the level, at most j's largest value
        s = _polynomial_root(shifted, s_p[step], rec["tau"][step])
        tau_g[lane, column] = rec["tau"][step] + np.where(y_p[step] >= 1.0 - wanted, s_p[step], s)
        todo[lane, column] = False
    return tau_g.reshape(levels.shape)


def _events(records: dict, two_zeta, lam, at_root, continued_all, extremes: bool) -> dict:
    """Locate the bracketed events (see :func:`integrate` for the outputs); ``at_root``: lanes that end at
    Q's root (force criterion, continued)."""
    n = two_zeta.size
    out = {k: np.full(n, np.nan) for k in NORMAL_OUTPUTS}
    first_zero = np.full(n, np.nan)  # y where P_hat first falls to 0
    m = _join(records["max"])
    s_m = _polynomial_root(m["ys"], m["h"], m["tau"])
    out["tau_m"][m["lane"]], out["x_m"][m["lane"]] = m["tau"] + s_m, _horner(m["xs"], s_m)
    t = _join(records["tension"])
    if t is not None:  # penetration criterion: tension begins while delta > 0 (y_p there)
        j = t["lane"]
        q_h = ratio(_horner(t["xs"], t["h"]), _horner(t["ys"], t["h"]), two_zeta[j], lam[j])
        s = _ratio_root(t["xs"], t["ys"], two_zeta[j], lam[j], t["h"], q_h, t["tau"])
        first_zero[j] = _horner(t["ys"], s)
    e = _join(records["end"])
    j = e["lane"]
    s_end, q_end = _first_zero(e, two_zeta, lam)
    y_end = _horner(e["ys"], s_end)
    search = (q_end <= 0) & (~e["seen"] | at_root[j])  # Q falls through 0 within this step
    s_p, y_p = s_end.copy(), y_end.copy()
    if search.any():
        i = np.flatnonzero(search)
        s_p[i] = _ratio_root(e["xs"][:, i], e["ys"][:, i], two_zeta[j[i]], lam[j[i]], s_end[i], q_end[i], e["tau"][i])
        y_p[i] = _horner(e["ys"][:, i], s_p[i])
    root = at_root[j]
    out["tau_f"][j] = e["tau"] + np.where(root, s_p, s_end)
    out["y_f"][j] = np.where(root, y_p, y_end)
    fresh = np.isnan(first_zero[j])
    first_zero[j[fresh]] = np.where(root | search, y_p, y_end)[fresh]
    out["j_p"] = 1.0 - first_zero  # the impulse of P_hat while positive, no gravity: v_n (1 - y_p)
    if extremes:
        out["p_max"], out["p_min"] = _turns(records, two_zeta, lam, out["tau_f"], continued_all)
    return out


def _turns(records: dict, two_zeta, lam, tau_f, continued) -> tuple:
    """(p_max, p_min): 0 (P_hat at both ends of the contact: x = 0 with the ramp off, or the force criterion's
    P_hat = 0), and P_hat at every recorded turning point before tau_f (roots of y'', where P_hat is evaluated
    from the state); a continued lane's minima past delta = 0 are not the contact's (the force criterion's
    end is P_hat = 0, and P_hat >= 0 before it)."""
    n = two_zeta.size
    p_max, p_min = np.zeros(n), np.zeros(n)
    turn = _join(records["turn"])
    if turn is not None:
        d2 = _derivative(_derivative(turn["ys"]))
        rising = turn["rising"]  # P_hat rose at the step's start: it turns to a maximum in this step
        f = np.where(rising, -d2, d2)  # P_hat' (maximum) or -P_hat' (minimum): falls through 0
        s = np.where(f[0] > 0, _polynomial_root(f, turn["h"], turn["tau"]), 0.0)  # at the start: s = 0
        # P_hat from the state there, x Q(x, y): the step polynomial's own derivative -y' carries its
        # truncation error over the step's length (1.8e-8 of the largest force at lam ~ 1e3)
        x, y = _horner(turn["xs"], s), _horner(turn["ys"], s)
        j = turn["lane"]
        value = x * ratio(x, y, two_zeta[j], lam[j])
        inside = turn["tau"] + s < tau_f[j]
        top = inside & rising
        low = inside & ~rising & ~continued[j]
        np.maximum.at(p_max, j[top], value[top])
        np.minimum.at(p_min, j[low], value[low])
    return p_max, p_min
