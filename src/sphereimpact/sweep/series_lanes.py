"""Batched Taylor lanes: eq. 4.2's weightless normal problem, one lane per scene, by series.

Per lane (the dimensionless problem of :mod:`.batch`, without gravity, law ``modified``):

    x' = y,   y' = -P_hat,   P_hat = x + 2 zeta y (1 - exp(-lam x)),   x(0) = 0, y(0) = 1.

Each step is the law's Taylor recurrence to order p on every active lane at once
(:func:`sphereimpact.contact.laws.linear.modified_series_batched`, beside the one-impact
:func:`~sphereimpact.contact.laws.linear.modified_series`), its size from the last two coefficients and its ramp band as in :mod:`sphereimpact.ode.series`.  On the
plane's nodes both these and the Runge-Kutta lanes (:mod:`.batch`) take about 30 steps, but a Taylor step is
p orders of a few array operations where a Runge-Kutta step is 12 evaluations of the ramp, and events need no
extra steps.  Their cost is the steps', nearly whatever
the number of lanes, so they suit batches of a few hundred to a few thousand nodes of an interpolant.

Events are roots on each lane's step polynomials, located after the march in one vectorised pass per kind
by Newton kept inside their bracket: y (maximum compression), x (delta = 0) and Q = P_hat / x (tension
begins; the force criterion's end).  Q is evaluated as 1 + 2 zeta lam y phi(lam x),
phi(u) = (1 - exp(-u)) / u, an entire function: it keeps full precision through x = 0, where it equals
G = 1 + 2 zeta lam y.

Besides the two criteria, a lane may end ``continued``: at the first root of Q after maximum compression
wherever it lies, past delta = 0 (on the law's analytic continuation) where the force does not pull before.
Its outputs equal the force criterion's wherever the force pulls (G < 0 at delta = 0) and continue them
analytically where it does not, so they are smooth across the tension onset: an interpolant of them needs
no cut along it (:class:`.plane.PlaneInterpolant`).

The local tolerance is TOLERANCE_FACTOR x target / max(1, 2 zeta)^2 per lane: near critical damping the
penetration criterion's tau_f is ill-conditioned (x creeps to 0), and without the factor its error reached
0.55 target at zeta = 0.99.
"""

from __future__ import annotations

import numpy as np

from ..contact.laws.linear import modified_series_batched
from ..errors import ImpactError
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
ROOT_ITERATIONS = 60
#: An event's Newton iteration stops when its update is below SETTLED x the event time.
SETTLED = 1e-14


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


def _per_x(x, lam):
    """(1 - exp(-lam x)) / x, lam at x = 0 (entire in x)."""
    u = lam * x
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(u != 0, -np.expm1(-u) / np.where(u != 0, x, 1.0), lam)


def ratio(x, y, two_zeta, lam):
    """Q = P_hat / x = 1 + 2 zeta y (1 - exp(-lam x)) / x, for any x (G = 1 + 2 zeta lam y at x = 0)."""
    return 1.0 + two_zeta * y * _per_x(x, lam)


def _ratio_and_slope(xs, ys, two_zeta, lam):
    """s -> (Q, dQ/ds) along step polynomials: d/ds = 2 zeta (y' phi + y x' dphi/dx), phi = :func:`_per_x`."""
    dxs, dys = _derivative(xs), _derivative(ys)

    def value(s):
        x, y = _horner(xs, s), _horner(ys, s)
        phi = _per_x(x, lam)
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


def _newton(function, a, b, f_a, f_b, tau):
    """Root in s of each lane's decreasing ``function`` (s -> (f, f')) with f(a) = f_a > 0 >= f(b) = f_b.

    Newton from the secant point; a step leaving the bracket bisects instead; a lane stops once its update
    is below SETTLED x its event time tau + s (far below any target; near 1 ulp round-off in f decides, and
    Q's, with terms up to 2 zeta lam |y|, would keep it moving).
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(f_a - f_b > 0, a + (b - a) * f_a / (f_a - f_b), b)
    s = np.clip(s, a, b)
    for _ in range(ROOT_ITERATIONS):
        f, df = function(s)
        a, b = np.where(f > 0, s, a), np.where(f < 0, s, b)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = s - f / df
        new = np.where((step >= a) & (step <= b), step, 0.5 * (a + b))
        settled = (f == 0) | (np.abs(new - s) <= SETTLED * np.maximum(tau + np.abs(s), 1e-300))
        s = np.where(settled, s, new)
        if settled.all():
            break
    return s


def _polynomial_root(coefficients, b, tau):
    """Root in (0, b] of each lane's decreasing polynomial, positive at 0."""
    zero = np.zeros(b.size)
    return _newton(_polynomial(coefficients), zero, b, coefficients[0], _horner(coefficients, b), tau)


SEPARATIONS = ("force", "penetration", "continued")


def integrate(zeta, lam, separation, target: float = 1e-8) -> dict:
    """Integrate every lane to separation by the Taylor method.

    Parameters
    ----------
    zeta, lam : ndarray
        Damping ratio and ramp parameter c v_n / (omega_n R) (see :mod:`.batch`), finite and positive.
    separation : {'force', 'penetration', 'continued'} or array of them
        Each lane's end (one for all, or one per lane; see the module docstring for ``continued``).
    target : float
        Relative accuracy target of every output.

    Returns
    -------
    dict of ndarray
        ``tau_m``, ``x_m``, ``tau_f``, ``y_f`` and ``y_p`` as :func:`.batch.integrate` gives them
        (``continued``: tau_f and y_f = y_p at the root of Q).

    Raises
    ------
    ImpactError
        A lane that does not separate within the horizon, takes more than MAX_STEPS steps or whose series
        leaves double precision.
    """
    zeta, lam = np.asarray(zeta, dtype=float), np.asarray(lam, dtype=float)
    n = zeta.size
    kind = np.broadcast_to(np.asarray(separation), zeta.shape)
    if not np.isin(kind, SEPARATIONS).all():
        raise ValueError(f"separation must be one of {', '.join(SEPARATIONS)}")
    if n == 0:
        return {k: np.empty(0) for k in NORMAL_OUTPUTS}
    tol = np.maximum(TOLERANCE_FACTOR * target / np.maximum(1.0, 2.0 * zeta) ** 2, TOLERANCE_MIN)
    order = order_for(TOLERANCE_FACTOR * target)  # the target's, not the batch's: a lane's result is its own
    lane = np.arange(n)
    two_zeta, lam_a, at_root, at_zero = 2.0 * zeta, lam.copy(), kind != "penetration", kind == "penetration"
    continued = kind == "continued"
    edge = BAND_EDGE / lam
    x, y, tau = np.zeros(n), np.ones(n), np.zeros(n)
    past = np.zeros(n, bool)
    tension_seen = np.zeros(n, bool)
    records = {"max": [], "tension": [], "end": []}
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
        for event, mask in (("max", hit_max), ("tension", first), ("end", done)):
            if mask.any():
                i = np.flatnonzero(mask)
                records[event].append({"lane": lane[i], "tau": tau[i], "h": h[i], "xs": xs[:, i], "ys": ys[:, i],
                                       "x_end": x_end[i], "seen": tension_seen[i]})
        tau = tau + h
        x, y = x1, y1
        late = ~done & (tau > HORIZON)
        if late.any():
            raise ImpactError(f"no separation within the horizon for {int(late.sum())} scene(s) "
                              f"(first: zeta = {two_zeta[late][0] / 2:.3g}, lam = {lam_a[late][0]:.3g})")
        if done.any():  # ended lanes leave the batch
            keep = ~done
            lane, x, y, tau = lane[keep], x[keep], y[keep], tau[keep]
            past, tension_seen = past[keep], tension_seen[keep]
            two_zeta, lam_a, edge, tol = two_zeta[keep], lam_a[keep], edge[keep], tol[keep]
            at_root, at_zero, continued = at_root[keep], at_zero[keep], continued[keep]
    else:
        raise ImpactError(f"the Taylor lanes took more than {MAX_STEPS} steps")
    return _events(records, 2.0 * zeta, lam, kind != "penetration")


def _join(store: list) -> dict | None:
    if not store:
        return None
    return {k: np.concatenate([r[k] for r in store], axis=-1) for k in store[0]}


def _ratio_root(xs, ys, two_zeta, lam, b, q_b, tau):
    """Root in (0, b] of Q along each lane's step polynomials, Q(0) > 0 >= Q(b) = ``q_b``."""
    q_0 = ratio(xs[0], ys[0], two_zeta, lam)
    return _newton(_ratio_and_slope(xs, ys, two_zeta, lam), np.zeros(b.size), b, q_0, q_b, tau)


def _events(records: dict, two_zeta, lam, at_root) -> dict:
    """Locate the bracketed events (see :func:`integrate` for the outputs); ``at_root``: lanes that end at
    Q's root (force criterion, continued)."""
    out = {k: np.full(two_zeta.size, np.nan) for k in NORMAL_OUTPUTS}
    m = _join(records["max"])
    s_m = _polynomial_root(m["ys"], m["h"], m["tau"])
    out["tau_m"][m["lane"]], out["x_m"][m["lane"]] = m["tau"] + s_m, _horner(m["xs"], s_m)
    t = _join(records["tension"])
    if t is not None:  # penetration criterion: tension begins while delta > 0 (y_p there)
        j = t["lane"]
        q_h = ratio(_horner(t["xs"], t["h"]), _horner(t["ys"], t["h"]), two_zeta[j], lam[j])
        s = _ratio_root(t["xs"], t["ys"], two_zeta[j], lam[j], t["h"], q_h, t["tau"])
        out["y_p"][j] = _horner(t["ys"], s)
    e = _join(records["end"])
    j = e["lane"]
    s_end = e["h"].copy()
    if e["x_end"].any():
        i = np.flatnonzero(e["x_end"])
        s_end[i] = _polynomial_root(e["xs"][:, i], e["h"][i], e["tau"][i])
    y_end = _horner(e["ys"], s_end)
    q_end = ratio(np.where(e["x_end"], 0.0, _horner(e["xs"], s_end)), y_end, two_zeta[j], lam[j])
    search = (q_end <= 0) & (~e["seen"] | at_root[j])  # Q falls through 0 within this step
    s_p, y_p = s_end.copy(), y_end.copy()
    if search.any():
        i = np.flatnonzero(search)
        s_p[i] = _ratio_root(e["xs"][:, i], e["ys"][:, i], two_zeta[j[i]], lam[j[i]], s_end[i], q_end[i], e["tau"][i])
        y_p[i] = _horner(e["ys"][:, i], s_p[i])
    root = at_root[j]
    out["tau_f"][j] = e["tau"] + np.where(root, s_p, s_end)
    out["y_f"][j] = np.where(root, y_p, y_end)
    fresh = np.isnan(out["y_p"][j])
    out["y_p"][j[fresh]] = np.where(root | search, y_p, y_end)[fresh]
    return out
