"""Batched integration of the dimensionless normal problem: one lane per scene, all lanes at once.

Per lane (tau = omega_n t, x = delta omega_n / v_n, y = x'):

    x' = y,   y' = -P_hat(x, y) + gamma,   P_hat = x + 2 zeta y r(lam x),   x(0) = 0, y(0) = 1,

with r = 1 (kelvin-voigt) or the modified ramp continued past x = 0
(:func:`sphereimpact.forces.ramp_continued`), lam = c v_n / (omega_n R) and
gamma = g cos(beta) / (omega_n v_n).  Each lane takes fixed steps of the
8th-order Dormand-Prince method (the tableau of :class:`scipy.integrate.DOP853`),
its step chosen from the accuracy target and the lane's fastest scale at its current state.  Events
are roots of y (maximum compression), of the separation function, and of P_hat
(tension begins), located on each lane's one-step map z(s) = Phi_s(z_0),
s in [0, h]: bracketed, then Newton with bisection fallback.  Lanes retire as
they separate; the arrays of the active lanes are compacted as they go.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import DOP853

from ..events import ImpactError
from ..forces import ramp_continued

_A = DOP853.A
_B = DOP853.B
_C = DOP853.C
_STAGES = DOP853.n_stages

#: Step h = STEP_CONSTANT * target**(1/8) / max(1, 2 zeta, lam exp(-lam x) / 4): calibrated so that the worst relative
#: error over every output stays below the target (checked by tests/test_sweep.py on random samples).
STEP_CONSTANT = 1.2
NEWTON_ITERATIONS = 12
#: Dimensionless horizon: far past any contact that ends (see sphereimpact.normal.horizon).
HORIZON = 100.0 * np.pi


class _Lanes:
    """Per-lane parameters of one batch (arrays of equal length)."""

    def __init__(self, zeta, lam, gamma, modified):
        self.zeta, self.lam, self.gamma, self.modified = zeta, lam, gamma, modified

    def take(self, index):
        return _Lanes(self.zeta[index], self.lam[index], self.gamma[index], self.modified[index])

    def force(self, x, y):
        ramp = np.where(self.modified, ramp_continued(self.lam * x), 1.0)
        return x + 2.0 * self.zeta * y * ramp

    def force_rate(self, x, y, dy):
        """d P_hat / d tau (its ramp derivative only approximate past x = 0: Newton needs no more)."""
        u = self.lam * x
        ramp = np.where(self.modified, ramp_continued(u), 1.0)
        slope = np.where(self.modified, np.exp(-np.maximum(u, 0.0)) * self.lam, 0.0)
        return y + 2.0 * self.zeta * (dy * ramp + y * slope * y)

    def rhs(self, x, y):
        return y, self.gamma - self.force(x, y)


def _step(lanes: _Lanes, x, y, h):
    """One DOP853 step of per-lane size h from (x, y); returns the new (x, y)."""
    kx = np.empty((_STAGES, x.size))
    ky = np.empty((_STAGES, x.size))
    kx[0], ky[0] = lanes.rhs(x, y)
    for s in range(1, _STAGES):
        a = _A[s, :s]
        xs = x + h * (a @ kx[:s])
        ys = y + h * (a @ ky[:s])
        kx[s], ky[s] = lanes.rhs(xs, ys)
    return x + h * (_B @ kx), y + h * (_B @ ky)


def _event_value(kind: str, lanes: _Lanes, x, y):
    """Event function and its tau-derivative: kind 'max' (y), 'delta' (x) or 'force' (P_hat)."""
    dx, dy = lanes.rhs(x, y)
    if kind == "max":
        return y, dy
    if kind == "delta":
        return x, dx
    return lanes.force(x, y), lanes.force_rate(x, y, dy)


def _locate(kind: str, lanes: _Lanes, x0, y0, lo, hi):
    """Root in s of the event on the one-step map from (x0, y0), bracketed by g(lo) > 0 >= g(hi)."""
    g_lo = _event_value(kind, lanes, *_step(lanes, x0, y0, lo))[0]
    g_hi = _event_value(kind, lanes, *_step(lanes, x0, y0, hi))[0]
    s = np.where(g_lo - g_hi > 0, lo + (hi - lo) * g_lo / np.where(g_lo - g_hi > 0, g_lo - g_hi, 1.0), hi)
    frozen = np.zeros(s.size, bool)  # converged lanes stay put: a lane's root never depends on its batch
    for _ in range(NEWTON_ITERATIONS):
        xs, ys = _step(lanes, x0, y0, s)
        g, dg = _event_value(kind, lanes, xs, ys)
        lo = np.where(g > 0, s, lo)
        hi = np.where(g < 0, s, hi)
        newton = s - g / np.where(dg != 0, dg, -1.0)
        inside = (newton >= lo) & (newton <= hi)
        s_new = np.where(frozen | (g == 0), s, np.where(inside, newton, 0.5 * (lo + hi)))
        frozen |= np.abs(s_new - s) <= 4e-16 * np.maximum(np.abs(s), 1e-300)
        s = s_new
        if frozen.all():
            break
    return s, _step(lanes, x0, y0, s)


def _first_force_root(lanes: _Lanes, x0, y0, lo, hi, samples: int = 8):
    """Earliest root of P_hat on (lo, hi] of each lane's step, by sampling then refining.

    P_hat can fall through zero and rise again within one step near x = 0 (its
    ramp term is nonlinear there), so a sign check at the step end alone can
    miss the root.  Returns (s, y at s, found) with s = hi where none is found.
    """
    s_found, y_found, found = hi.copy(), np.full(lo.size, np.nan), np.zeros(lo.size, bool)
    prev = lo
    for k in range(1, samples + 1):
        s_k = lo + (hi - lo) * (k / samples)
        g = lanes.force(*_step(lanes, x0, y0, s_k))
        new = ~found & (g <= 0)
        if new.any():
            i = np.flatnonzero(new)
            s, (_, ys) = _locate("force", lanes.take(i), x0[i], y0[i], prev[i], s_k[i])
            s_found[i], y_found[i], found[i] = s, ys, True
        prev = s_k
        if found.all():
            break
    return s_found, y_found, found


def step_size(zeta, lam, x, y, target: float):
    """Per-lane dimensionless step from the accuracy target and the lane's fastest time scale ahead.

    The modified ramp varies at rate lam exp(-lam x) in x: fast only near x = 0 (first touch and
    separation).  The rate is taken at the smallest x the lane can reach within one base step
    (x - |y| h_base), so a step never leaps into the fast region unresolved.
    """
    base = STEP_CONSTANT * target ** 0.125 / np.maximum(1.0, 2.0 * zeta)
    reach = np.maximum(x - 1.5 * np.abs(y) * base, 0.0)
    ramp_rate = lam * np.exp(-lam * reach)
    return STEP_CONSTANT * target ** 0.125 / np.maximum.reduce([np.ones_like(zeta), 2.0 * zeta, ramp_rate / 4.0])


def integrate(zeta, lam, gamma, modified, separation: str, target: float = 1e-8) -> dict:
    """Integrate every lane to separation.

    Parameters
    ----------
    zeta, lam, gamma : ndarray
        Damping ratio, ramp parameter c v_n / (omega_n R), gravity gamma (see module docstring).
    modified : ndarray of bool
        True for the modified law, False for kelvin-voigt.
    separation : {'force', 'penetration'}
    target : float
        Relative accuracy target of every output.

    Returns
    -------
    dict of ndarray
        ``tau_m``, ``x_m``, ``tau_f``, ``y_f`` and ``y_p`` (y where P_hat first falls to 0 after
        maximum compression, or y_f if it does not before separation), dimensionless.

    Raises
    ------
    ImpactError
        When a lane does not separate within the horizon.
    """
    n = zeta.size
    params = _Lanes(np.asarray(zeta, float), np.asarray(lam, float), np.asarray(gamma, float),
                    np.asarray(modified, bool))
    out = {k: np.full(n, np.nan) for k in ("tau_m", "x_m", "tau_f", "y_f", "y_p")}
    sep_kind = "delta" if separation == "penetration" else "force"  # force: first of P_hat = 0 and x = 0
    lane = np.arange(n)
    x, y, tau = np.zeros(n), np.ones(n), np.zeros(n)
    past_max = np.zeros(n, bool)  # maximum compression found
    tension = np.zeros(n, bool)  # P_hat fell to 0 while delta > 0
    while lane.size:
        lanes = params.take(lane)
        h = step_size(lanes.zeta, np.where(lanes.modified, lanes.lam, 0.0), x, y, target)
        x1, y1 = _step(lanes, x, y, h)
        start = np.zeros(lane.size)  # where in the step events may still happen
        # maximum compression
        hit = ~past_max & (y1 <= 0)
        if hit.any():
            i = np.flatnonzero(hit)
            s, (xm, _) = _locate("max", lanes.take(i), x[i], y[i], np.zeros(i.size), h[i])
            out["tau_m"][lane[i]], out["x_m"][lane[i]] = tau[i] + s, xm
            past_max[i], start[i] = True, s
        # contact ends: delta = 0 (both criteria), or P_hat = 0 before it (force criterion)
        x_end = past_max & (x1 <= 0)
        s_x = h.copy()
        if x_end.any():
            i = np.flatnonzero(x_end)
            s_x[i] = _locate("delta", lanes.take(i), x[i], y[i], start[i], h[i])[0]
        # P_hat = 0 with delta > 0: separation (force) or the start of tension (penetration)
        look = past_max & ~tension & (x_end | (lanes.force(x1, y1) <= 0))
        s_p = np.full(lane.size, np.inf)
        if look.any():
            i = np.flatnonzero(look)
            s, yp, found = _first_force_root(lanes.take(i), x[i], y[i], start[i], s_x[i])
            s_p[i[found]] = s[found]
            out["y_p"][lane[i[found]]] = yp[found]
            tension[i[found]] = True
        done = x_end | (np.isfinite(s_p) if sep_kind == "force" else False)
        if done.any():
            i = np.flatnonzero(done)
            s_end = np.minimum(s_x[i], s_p[i]) if sep_kind == "force" else s_x[i]
            out["tau_f"][lane[i]] = tau[i] + s_end
            out["y_f"][lane[i]] = _step(lanes.take(i), x[i], y[i], s_end)[1]
        tau = tau + h
        late = ~done & (tau > HORIZON)
        if late.any():
            raise ImpactError(f"no separation within the horizon for {int(late.sum())} scene(s) "
                              f"(first: zeta = {lanes.zeta[late][0]:.3g}, separation '{separation}')")
        keep = ~done
        lane, x, y, tau = lane[keep], x1[keep], y1[keep], tau[keep]
        past_max, tension = past_max[keep], tension[keep]
    out["y_p"] = np.where(np.isnan(out["y_p"]), out["y_f"], out["y_p"])
    return out
