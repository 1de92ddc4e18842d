"""Similarity: for one ball without gravity, the modified law's normal problem is a one-parameter family.

In dimensionless form the normal outputs depend only on zeta (fixed by the
ball and contact) and lam = c v_n / (omega_n R).  An angle x speed sweep of
one ball therefore needs the outputs as functions of lam alone: solve a few
accurate nodes with the batched integrator, interpolate by Chebyshev series in
u = log(lam), and check the interpolant at the midpoints between nodes before
trusting it (doubling the nodes until the check meets the target).

The outputs have a kink where tension appears (the force turns negative before
delta = 0): it happens iff G(lam) = 1 + 2 zeta lam y(delta = 0) < 0, because
P_hat / x >= 1 + 2 zeta lam y during restitution.  G is smooth, so its root
lam* is found first and each side gets its own interpolant.
"""

from __future__ import annotations

import numpy as np
from numpy.polynomial import Chebyshev
from scipy.optimize import brentq

from . import batch

OUTPUTS = ("tau_m", "x_m", "tau_f", "y_f", "y_p")
#: Node accuracy: far below any sweep target.
NODE_TARGET = 1e-13
MAX_NODES = 257


def _solve(zeta: float, lam, separation: str) -> dict:
    lam = np.atleast_1d(np.asarray(lam, dtype=float))
    return batch.integrate(np.full(lam.size, zeta), lam, np.zeros(lam.size), np.ones(lam.size, bool),
                           separation, NODE_TARGET)


def _tension_onset(zeta: float, u_lo: float, u_hi: float) -> float | None:
    """u* = log(lam*) where G changes sign on [u_lo, u_hi], or None."""
    def g(u):
        return 1.0 + 2.0 * zeta * np.exp(u) * _solve(zeta, np.exp(u), "penetration")["y_f"]

    ends = g(np.array([u_lo, u_hi]))
    if np.sign(ends[0]) == np.sign(ends[1]):
        return None
    return brentq(lambda u: float(g(np.array([u]))[0]), u_lo, u_hi, xtol=1e-14, rtol=1e-15)


def _nodes(a: float, b: float, n: int) -> np.ndarray:
    return 0.5 * (a + b) + 0.5 * (b - a) * np.cos(np.pi * np.arange(n) / (n - 1))


def _errors(got: dict, ref: dict) -> float:
    """Worst error in the sweep's measure: times relative to tau_f, x_m relative, y absolute (COR)."""
    scale = np.abs(ref["tau_f"])
    return float(max(np.max(np.abs(got["tau_m"] - ref["tau_m"]) / scale),
                     np.max(np.abs(got["tau_f"] - ref["tau_f"]) / scale),
                     np.max(np.abs(got["x_m"] / ref["x_m"] - 1)),
                     np.max(np.abs(got["y_f"] - ref["y_f"])), np.max(np.abs(got["y_p"] - ref["y_p"]))))


class LambdaInterpolant:
    """Normal outputs of the modified law for one zeta, as functions of lam on [lam_min, lam_max].

    Parameters
    ----------
    zeta : float
    lam_min, lam_max : float
        The range to cover (> 0).
    separation : {'force', 'penetration'}
    target : float
        Accuracy the midpoint check must meet (a tenth of it, for margin).

    Raises
    ------
    ValueError
        If MAX_NODES do not meet the target on a piece (the caller then integrates directly).
    """

    def __init__(self, zeta: float, lam_min: float, lam_max: float, separation: str, target: float):
        u_lo, u_hi = np.log(lam_min), np.log(lam_max)
        if u_hi - u_lo < 1e-12:
            u_hi = u_lo + 1e-6
        cut = _tension_onset(zeta, u_lo, u_hi)
        edges = [u_lo, u_hi] if cut is None else [u_lo, cut, u_hi]
        self.cuts = np.array(edges[1:-1])
        self.pieces, self.nodes = [], 0
        for a, b in zip(edges[:-1], edges[1:]):
            self.pieces.append(self._fit(zeta, a, b, separation, target))

    def _fit(self, zeta, a, b, separation, target):
        n = 17
        while n <= MAX_NODES:
            u = _nodes(a, b, n)
            values = _solve(zeta, np.exp(u), separation)
            series = {k: Chebyshev.fit(u, values[k], n - 1, domain=[a, b]) for k in OUTPUTS}
            mid = 0.5 * (u[:-1] + u[1:])
            check = _solve(zeta, np.exp(mid), separation)
            self.nodes += 2 * n - 1
            if _errors({k: series[k](mid) for k in OUTPUTS}, check) <= 0.1 * target:
                return series
            n = 2 * n - 1
        raise ValueError(f"Chebyshev interpolation in lam did not reach {target:g} with {MAX_NODES} nodes")

    def __call__(self, lam) -> dict:
        u = np.log(np.asarray(lam, dtype=float))
        piece = np.searchsorted(self.cuts, u)
        out = {k: np.empty(u.size) for k in OUTPUTS}
        for i, series in enumerate(self.pieces):
            mask = piece == i
            for k in OUTPUTS:
                out[k][mask] = series[k](u[mask])
        return out
