"""Similarity: for one ball without gravity, the modified law's normal problem is a one-parameter family.

In dimensionless form the normal outputs depend only on zeta (fixed by the
ball and contact) and lam = c v_n / (omega_n R).  An angle x speed sweep of
one ball therefore needs the outputs as functions of lam alone: solve a few
accurate nodes with the batched integrator, interpolate by Chebyshev series in
u = log(lam), and check before trusting.

The outputs have a kink where tension appears (the force turns negative before
delta = 0): it happens iff G(lam) = 1 + 2 zeta lam y(delta = 0) < 0, because
P_hat / x >= 1 + 2 zeta lam y during restitution.  The build therefore takes two
batched solves:

1. the penetration criterion on the whole range, whose tau_m, x_m, tau_f and y_f are
   smooth in u: they give G, hence its root u*, and every output below u*, where no
   tension arises and both criteria end at delta = 0 with y_p = y_f;
2. the sweep's own criterion on [u*, u_max], where the outputs are smooth again.

Each solve runs 2n - 1 Chebyshev-Lobatto nodes at once: the n-node interpolant
(every other node) is checked against the other n - 1 (its midpoints in angle),
and when it meets the check the (2n - 1)-node interpolant is kept.  A failed
check adds the next level's nodes in one more solve.

The same construction serves any law whose weightless normal motion is a family of
one number q proportional to the approach speed (the Hunt-Crossley laws: chi v_n),
with the nodes solved one by one by the single-impact integrator and the tension
test G read off the law's own force near delta = 0 (:class:`FamilyInterpolant`).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.polynomial.chebyshev import chebval
from scipy.fft import dct
from scipy.optimize import brentq

from ..errors import InterpolationError
from ..impact.scene import Scene, SolverOptions
from ..impact.solve import normal_motion
from ..contact.tangential import PositiveImpulse
from . import batch, series_lanes
from .outputs import NORMAL_OUTPUTS

#: Outputs that are smooth across the tension onset under the penetration criterion.
SMOOTH = ("tau_m", "x_m", "tau_f", "y_f")
#: The first check compares n nodes with their n - 1 midpoints (one solve), n = 2^k + 1 from
#: NODES_PER_DIGIT x (width in u) x (digits asked of the check), and at least FIRST_NODES: the outputs are
#: analytic in u, so the nodes needed grow with both.
NODES_PER_DIGIT = 0.7
FIRST_NODES = 17
MAX_NODES = 513
#: Nodes are solved at NODE_FACTOR x the sweep's target: the Runge-Kutta lanes' error stays below a fifth of
#: their target, the Taylor lanes' below a third (0.28 at worst: the penetration criterion's t_f near critical
#: damping, tests/test_series_lanes.py), so node errors stay below target / 30, a third of the check's 0.1
#: target, and interpolation plus nodes below 0.14 target.
NODE_FACTOR = 0.1
NODE_TARGET_MIN = 1e-13


def _lobatto(a: float, b: float, n: int) -> np.ndarray:
    """n Chebyshev-Lobatto points on [a, b], from b down to a."""
    return 0.5 * (a + b) + 0.5 * (b - a) * np.cos(np.pi * np.arange(n) / (n - 1))


def _errors(got: dict, ref: dict, keys) -> float:
    """Worst error in the sweep's measure: times relative to tau_f, x_m relative, y absolute (COR)."""
    def error(k):
        if k == "x_m":
            return np.abs(got[k] / ref[k] - 1)
        return np.abs(got[k] - ref[k]) / (np.abs(ref["tau_f"]) if k.startswith("tau") else 1.0)

    return float(max(np.max(error(k)) for k in keys))


class _Series:
    """Chebyshev series in u on [a, b] of several outputs, interpolating values at Lobatto points.

    The coefficients come from a type-I DCT of the values (exact interpolation at the points
    cos(pi j / (N - 1)), in O(N log N)); all outputs are evaluated by one Clenshaw recurrence.
    """

    def __init__(self, a: float, b: float, values: dict):
        self.a, self.b, self.keys = a, b, tuple(values)
        self.values = np.stack([values[k] for k in self.keys], axis=1)  # (N, outputs), from u = b down to a
        self.nodes = _lobatto(a, b, self.values.shape[0])
        coef = dct(self.values, type=1, axis=0) / (self.values.shape[0] - 1)
        coef[0] /= 2.0
        coef[-1] /= 2.0
        self.coef = coef

    def _local(self, u):
        """u mapped onto the series' variable t in [-1, 1]."""
        return (2.0 * np.asarray(u, dtype=float) - (self.a + self.b)) / (self.b - self.a)

    def __call__(self, u) -> dict:
        return dict(zip(self.keys, chebval(self._local(u), self.coef)))  # chebval: (outputs, len(u))

    def value(self, key: str, u):
        """One output at u (a root search needs no others)."""
        return chebval(self._local(u), self.coef[:, self.keys.index(key)])

    def with_alias(self, new: str, old: str) -> _Series:
        """The same series with output ``new`` added as a copy of ``old``."""
        column = self.keys.index(old)
        return _Series(self.a, self.b, {k: self.values[:, i] for i, k in enumerate(self.keys)}
                       | {new: self.values[:, column]})


def _fit(solve, a: float, b: float, separation: str, target: float, keys, what: str,
         per_digit: float = NODES_PER_DIGIT) -> tuple[_Series, int]:
    """Chebyshev series in u on [a, b] of ``keys``, checked to 0.1 target (see the module docstring),
    and the number of nodes solved.  ``solve(u, separation, node_target)`` gives the outputs at the
    nodes u; ``what`` names the family in messages; ``per_digit`` sets the first level (NODES_PER_DIGIT).

    Raises
    ------
    InterpolationError
        If MAX_NODES nodes do not meet the check.
    """
    node_target = max(NODE_FACTOR * target, NODE_TARGET_MIN)
    wanted = per_digit * (b - a) * np.log10(10.0 / target)
    n, values = FIRST_NODES, None
    while n < wanted and 2 * n - 1 <= MAX_NODES:
        n = 2 * n - 1
    while 2 * n - 1 <= MAX_NODES:
        u = _lobatto(a, b, 2 * n - 1)
        new = np.arange(u.size) if values is None else np.arange(1, u.size, 2)  # the coarse level is known
        solved = solve(u[new], separation, node_target)
        merged = {k: np.empty(u.size) for k in keys}
        for k in keys:
            merged[k][new] = solved[k]
            if values is not None:
                merged[k][0::2] = values[k]
        values = merged
        coarse = _Series(a, b, {k: values[k][0::2] for k in keys})
        if _errors(coarse(u[1::2]), {k: values[k][1::2] for k in keys}, keys) <= 0.1 * target:
            return _Series(a, b, values), u.size
        n = 2 * n - 1
    raise InterpolationError(f"Chebyshev interpolation did not reach {target:g} with {MAX_NODES} nodes ({what}, "
                             f"u = log of the family number in [{a:g}, {b:g}])")


def _onset(exit_ratio, series: _Series, what: str) -> tuple[float | None, bool]:
    """(u* where G = ``exit_ratio(u, y_f)`` changes sign on the series' range or None, tension at the top end).

    G is the force's sign as delta -> 0+ at the rebound rate y_f (P / its spring term there): negative
    means the force pulls before delta returns to 0.  Its sign change is bracketed between two of the
    series' nodes, then refined on the y_f series.

    Raises
    ------
    InterpolationError
        If G changes sign more than once (the two-piece split would not hold).
    """
    u = series.nodes
    g = np.array([exit_ratio(float(v), float(y)) for v, y in zip(u, series.values[:, series.keys.index("y_f")])])
    change = np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:]))
    if change.size > 1:
        raise InterpolationError(f"the tension onset is not unique ({what})")
    if change.size == 0:
        return None, bool(g[0] < 0)

    def g_series(v):
        return exit_ratio(v, float(series.value("y_f", v)))

    j = change[0]  # nodes run from u = b down to a
    return brentq(g_series, u[j + 1], u[j], xtol=1e-14, rtol=1e-15), bool(g[0] < 0)


class _Pieces:
    """Normal outputs of a one-parameter family as functions of its number q, u = log q (see the module
    docstring): the penetration criterion's smooth outputs over the whole range, and the sweep's criterion
    on the piece where the force pulls before delta = 0.

    ``solve(u, separation, node_target)`` -> outputs at u; ``exit_ratio(u, y_f)`` -> G (see :func:`_onset`);
    ``per_digit``: see :func:`_fit`.
    """

    def __init__(self, solve, exit_ratio, q_min: float, q_max: float, separation: str, target: float, what: str,
                 per_digit: float = NODES_PER_DIGIT):
        self.lo, self.hi = float(q_min), float(q_max)
        u_lo, u_hi = np.log(q_min), np.log(q_max)
        if u_hi - u_lo < 1e-12:
            u_hi = u_lo + 1e-6
        whole, self.nodes = _fit(solve, u_lo, u_hi, "penetration", target, SMOOTH, what, per_digit)
        cut, tension_at_top = _onset(exit_ratio, whole, what)
        calm = whole.with_alias("y_p", "y_f")  # no tension: both criteria end at delta = 0, y_p = y_f
        self.cuts = np.array([] if cut is None else [cut])
        if cut is None and not tension_at_top:
            self.pieces = [calm]
            return
        # tension on [cut, u_hi] (G falls as q grows), everywhere, or in principle on [u_lo, cut]
        a, b = (u_lo if cut is None else cut, u_hi) if tension_at_top else (u_lo, cut)
        tense, nodes = _fit(solve, a, b, separation, target, NORMAL_OUTPUTS, what, per_digit)
        self.nodes += nodes
        self.pieces = [tense] if cut is None else [calm, tense] if tension_at_top else [tense, calm]

    def __call__(self, q) -> dict:
        u = np.log(np.asarray(q, dtype=float))
        piece = np.searchsorted(self.cuts, u)
        out = {k: np.empty(u.size) for k in NORMAL_OUTPUTS}
        for i, series in enumerate(self.pieces):
            mask = piece == i
            for k, value in series(u[mask]).items():
                out[k][mask] = value
        return out


class LambdaInterpolant(_Pieces):
    """Normal outputs of the modified law for one zeta, as functions of lam on [lam_min, lam_max].

    Parameters
    ----------
    zeta : float
    lam_min, lam_max : float
        The range to cover (> 0).
    separation : {'force', 'penetration'}
    target : float
        Accuracy the interpolant must meet (checked at a tenth of it).

    Attributes
    ----------
    lo, hi : float
        The lam range covered (a call outside it would extrapolate).
    cuts : ndarray
        u* where tension sets in, when it lies inside the range.
    nodes : int
        Nodes solved for the build.

    Raises
    ------
    InterpolationError
        If MAX_NODES nodes do not meet the target on a piece.
    """

    def __init__(self, zeta: float, lam_min: float, lam_max: float, separation: str, target: float):
        def solve(u, criterion, node_target):  # the batched lanes, one per node: Taylor's where they apply
            n = u.size
            if series_lanes.covers(zeta, lam_max):
                return series_lanes.integrate(np.full(n, zeta), np.exp(u), criterion, node_target)
            return batch.integrate(np.full(n, zeta), np.exp(u), np.zeros(n), np.ones(n, bool), criterion,
                                   node_target)

        def exit_ratio(u, y_f):  # P / (k delta) as delta -> 0+: 1 + 2 zeta lam y
            return 1.0 + 2.0 * zeta * np.exp(u) * y_f

        super().__init__(solve, exit_ratio, lam_min, lam_max, separation, target, f"zeta = {zeta:g}")


def dimensionless_motion(scene: Scene, options: SolverOptions) -> dict:
    """tau_m, x_m, tau_f, y_f and y_p (1 - J+ / (m v_n), J+ the impulse of max(P, 0)) of one scene, by the
    single-impact path's normal motion (``options.method`` as ``simulate`` resolves it)."""
    normal = normal_motion(scene, options)
    w, v = scene.frequency, scene.v_normal
    positive = float(PositiveImpulse(normal)(normal.t_f))
    return {"tau_m": normal.t_m * w, "x_m": normal.delta_m * w / v, "tau_f": normal.t_f * w,
            "y_f": float(normal.state(normal.t_f)[1]) / v, "y_p": 1.0 - positive / (scene.mass * v)}


#: Where the force's sign at delta -> 0+ is read for a law without a formula for it (G, see :func:`_onset`):
#: delta = EXIT_DELTA x R, small enough that a ramp in delta / R has no say.
EXIT_DELTA = 1e-12


class FamilyInterpolant(_Pieces):
    """Normal outputs of a law without a batched kernel, for the scenes that share all but the last of its
    family's numbers, as functions of that last number q (chi v_n for the Hunt-Crossley laws) on
    [q_min, q_max].

    The nodes are solved one by one by the single-impact integrator (exact for every law) on copies of
    ``scene`` at the approach speed that gives each q: so q must be proportional to the approach speed,
    with the family's other numbers independent of it (checked: InterpolationError otherwise, and the
    sweep solves the scenes family by family).  Tension is read off the law's own force near delta = 0.

    Parameters
    ----------
    scene : Scene
        Any scene of the group, without gravity (its outputs depend on its family only).
    q_min, q_max : float
        The range to cover (> 0).
    separation : {'force', 'penetration'}
    target : float
        Accuracy the interpolant must meet (checked at a tenth of it).
    """

    def __init__(self, scene: Scene, q_min: float, q_max: float, separation: str, target: float):
        names = list(scene.family)
        if not names or not 0 < q_min <= q_max or scene.gravity != 0:
            raise InterpolationError(f"model {scene.model!r}: no positive family number to interpolate in")
        name, q0 = names[-1], scene.family[names[-1]]
        doubled = scene.with_(speed=2.0 * scene.speed).family
        others_fixed = all(doubled[k] == scene.family[k] for k in names[:-1])
        if not (q0 > 0 and others_fixed and abs(doubled[name] / (2.0 * q0) - 1.0) <= 1e-12):
            raise InterpolationError(f"model {scene.model!r}: {name} is not proportional to the approach speed")

        def node(u: float) -> Scene:
            return scene.with_(speed=scene.speed * math.exp(u) / q0)

        def solve(u, criterion, node_target):
            tol = max(node_target / 100.0, 1e-13)  # the integrator's error stays below a tenth of the node's
            rows = [dimensionless_motion(node(float(v)).with_(separation=criterion), SolverOptions(rtol=tol, atol=tol))
                    for v in u]
            return {k: np.array([row[k] for row in rows]) for k in rows[0]}

        def exit_ratio(u, y_f):  # P / (P at rest) as delta -> 0+, at the rebound rate
            at = node(u)
            delta = EXIT_DELTA * at.radius
            return float(at.stage_force(delta, y_f * at.v_normal)) / float(at.stage_force(delta, 0.0))

        # nodes cost one impact each here (not one batched call): start from FIRST_NODES and refine
        super().__init__(solve, exit_ratio, q_min, q_max, separation, target,
                         f"model {scene.model!r}, {name} in [{q_min:g}, {q_max:g}]", per_digit=0.0)
