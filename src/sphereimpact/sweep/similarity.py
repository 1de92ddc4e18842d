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

1. the penetration criterion on the whole range, whose tau_m, x_m, tau_f, y_f and largest force are
   smooth in u: they give G, hence its root u*, and every output below u*, where no
   tension arises and both criteria end at delta = 0 with j_p = 1 - y_f (and the force's least value is
   at an end of the contact);
2. the sweep's own criterion on [u*, u_max], where the outputs are smooth again.

Each solve runs 2n - 1 Chebyshev-Lobatto nodes at once: the n-node interpolant
(every other node) is checked against the other n - 1 (its midpoints in angle),
and when it meets the check the (2n - 1)-node interpolant is kept.  A failed
check adds the next level's nodes in one more solve.

The rigid contact grips where the friction-carrying impulse j reaches a scene's level, so t_roll needs the
instant j reaches a level: a function of u and of the level, tabulated on each piece as tensor series in
u and a variable of the level's fraction s of a reference impulse smooth on the piece (1 - y_f on the
penetration solve's range, j_p on the tension piece), in two stretches (:func:`stretches`): up to S_EARLY,
x = s^(1/p), where j grows as the p-th power of the time from first touch (p = 2 for a linear spring, 2.5
for Hertz), so the instant is analytic in x; from there to S_LATE, x = sqrt(1 - s), where j levels off
quadratically at the reference.  At the reference itself j levels off as the cube where tension sets in
(at u*), which no series in u follows, so a level beyond S_LATE is solved for its own scene (the subclass's
``late``: the Taylor lanes stopping at the instant, or the single-impact integrator).  Each stretch's
resolution is chosen first, at three nodes, by the same midpoint check.

The same construction serves any law whose weightless normal motion is a family of
one number q proportional to the approach speed (the Hunt-Crossley laws: chi v_n),
with the nodes solved one by one by the single-impact integrator and the tension
test G read off the law's own force near delta = 0 (:class:`FamilyInterpolant`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InterpolationError
from ..ode.roots import brent
from ..impact.scene import Scene, SolverOptions
from ..impact.solve import reusing_normal_motions, shared_normal_motion
from ..contact.laws.linear import modified_per_compression
from ..contact.separation import Separation
from ..contact.tangential import PositiveImpulse
from . import batch, series_lanes
from .chebyshev import Series, Tensor, lobatto
from .outputs import EXTREMES, NORMAL_OUTPUTS

#: Outputs that are smooth across the tension onset under the penetration criterion.
SMOOTH = ("tau_m", "x_m", "tau_f", "y_f")
#: The first check compares n nodes with their n - 1 midpoints (one solve), n = 2^k + 1 from
#: NODES_PER_DIGIT x (width in u) x (digits asked of the check), and at least FIRST_NODES: the outputs are
#: analytic in u, so the nodes needed grow with both.
NODES_PER_DIGIT = 0.7
FIRST_NODES = 17
MAX_NODES = 513
#: Nodes of a grip table's stretch in its level variable: the first level, and the most (2^k + 1).
FIRST_GRIP_NODES = 17
MAX_GRIP_NODES = 257
#: The grip tables' stretches meet at the fraction S_EARLY of the reference impulse and end at S_LATE.
S_EARLY, S_LATE = 0.75, 0.99
#: A level above (1 + UNREACHED) x j_p is never reached (the scene slides throughout): it gets no instant.
UNREACHED = 1e-9
#: Below this fraction an instant carries the single-impact integrator's absolute error of the impulse near
#: first touch (j ~ 1e-10 read off a dense output accurate to 1e-13): the tables' check ignores it.
S_NOISE = 1e-6
#: Nodes are solved at NODE_FACTOR x the sweep's target: the Runge-Kutta lanes' error stays below a fifth of
#: their target, the Taylor lanes' below a third (0.28 at worst: the penetration criterion's t_f near critical
#: damping, tests/test_series_lanes.py), so node errors stay below target / 30, a third of the check's 0.1
#: target, and interpolation plus nodes below 0.14 target.
NODE_FACTOR = 0.1
NODE_TARGET_MIN = 1e-13


@dataclass(frozen=True)
class Stretch:
    """One stretch of a grip table: the fraction s of its reference impulse as a function of the table's
    variable x on [lo, hi] (``fraction``), and back (``variable``)."""

    name: str
    lo: float
    hi: float
    fraction: object
    variable: object

    def keys(self, n: int) -> tuple:
        """Names of a profile's n instants on this stretch."""
        return tuple(f"tau_{self.name}{k}" for k in range(n))

    def nodes(self, n: int) -> np.ndarray:
        """The fractions at n Lobatto points of x, from hi down to lo (the order a :class:`~.chebyshev.Tensor`
        reads)."""
        return self.fraction(lobatto(self.lo, self.hi, n))


def stretches(power: float) -> tuple:
    """The two stretches of a grip table for an impulse growing as the ``power``-th power of the time from
    first touch (see the module docstring)."""
    return (Stretch("early", 0.0, S_EARLY ** (1.0 / power), lambda x: x ** power, lambda f: f ** (1.0 / power)),
            Stretch("late", math.sqrt(1.0 - S_LATE), math.sqrt(1.0 - S_EARLY), lambda x: 1.0 - x * x,
                    lambda f: np.sqrt(np.maximum(1.0 - f, 0.0))))


@dataclass(frozen=True)
class Asked:
    """What a node solve computes besides the normal outputs: the force's extremes (``p_max``, ``p_min``), and
    grip profiles, the instants j reaches each (stretch, n) of ``grip``'s n fractions (:meth:`Stretch.nodes`)
    of the reference impulse ``reference`` (``j_p``, or ``1 - y_f``), named by :meth:`Stretch.keys`."""

    extremes: bool = False
    grip: tuple = ()
    reference: str = "j_p"
    #: The indices of the nodes whose grip profiles are asked (None: every node's; the others' are NaN).
    profiled: tuple | None = None

    def fractions(self) -> np.ndarray:
        """Every asked fraction, the stretches' in turn."""
        return np.concatenate([stretch.nodes(n) for stretch, n in self.grip]) if self.grip else np.zeros(0)

    def keys(self) -> tuple:
        return tuple(key for stretch, n in self.grip for key in stretch.keys(n))

    def noisy(self) -> set:
        """The grip instants at fractions below S_NOISE (not checked: see S_NOISE)."""
        return {key for stretch, n in self.grip for key, f in zip(stretch.keys(n), stretch.nodes(n)) if f < S_NOISE}


def reference_impulse(values: dict, reference: str):
    """The reference impulse of a grip profile: ``j_p``, or ``1 - y_f`` (j at delta = 0 on the penetration
    solve's range, smooth across the tension onset)."""
    return values["j_p"] if reference == "j_p" else 1.0 - values["y_f"]


def _errors(got: dict, ref: dict, keys) -> float:
    """Worst error in the sweep's measure: times relative to tau_f, x_m relative, y, j and forces absolute."""
    def error(k):
        if k == "x_m":
            return np.abs(got[k] / ref[k] - 1)
        return np.abs(got[k] - ref[k]) / (np.abs(ref["tau_f"]) if k.startswith("tau") else 1.0)

    return float(max(np.max(error(k)) for k in keys))


def _node_target(target: float) -> float:
    return max(NODE_FACTOR * target, NODE_TARGET_MIN)


def _fit(solve, a: float, b: float, separation: Separation, target: float, keys, asked: Asked, what: str,
         per_digit: float = NODES_PER_DIGIT) -> tuple[Series, int]:
    """Chebyshev series in u on [a, b] of ``keys``, checked to 0.1 target (see the module docstring; grip
    instants below S_NOISE are not checked), and the number of nodes solved.  ``solve(u, separation,
    node_target, asked)`` gives the outputs at the nodes u; ``what`` names the family in messages;
    ``per_digit`` sets the first level (NODES_PER_DIGIT).

    Raises
    ------
    InterpolationError
        If MAX_NODES nodes do not meet the check.
    """
    node_target = _node_target(target)
    n, values = _first_level(a, b, target, per_digit), None
    while 2 * n - 1 <= MAX_NODES:
        u = lobatto(a, b, 2 * n - 1)
        new = np.arange(u.size) if values is None else np.arange(1, u.size, 2)  # the coarse level is known
        solved = solve(u[new], separation, node_target, asked)
        merged = {k: np.empty(u.size) for k in keys}
        for k in keys:
            merged[k][new] = solved[k]
            if values is not None:
                merged[k][0::2] = values[k]
        values = merged
        coarse = Series(a, b, {k: values[k][0::2] for k in keys})
        checked = [k for k in keys if k not in asked.noisy()]
        if _errors(coarse(u[1::2]), {k: values[k][1::2] for k in keys}, checked) <= 0.1 * target:
            return Series(a, b, values), u.size
        n = 2 * n - 1
    raise InterpolationError(f"Chebyshev interpolation did not reach {target:g} with {MAX_NODES} nodes ({what}, "
                             f"u = log of the family number in [{a:g}, {b:g}])")


def _first_level(a: float, b: float, target: float, per_digit: float) -> int:
    """n of :func:`_fit`'s first check on [a, b]: its first solve is the 2n - 1 Lobatto nodes."""
    wanted = per_digit * (b - a) * np.log10(10.0 / target)
    n = FIRST_NODES
    while n < wanted and 2 * n - 1 <= MAX_NODES:
        n = 2 * n - 1
    return n


def _grip_resolution(solve, a: float, b: float, separation: Separation, target: float, reference: str, power: float,
                     what: str, first_level: tuple | None = None) -> tuple:
    """The grip table's stretches (:func:`stretches`) with their nodes on [a, b] in u: for each, the fewest
    Lobatto levels (from FIRST_GRIP_NODES, 2n - 1 at a time) whose interpolant meets 0.1 target at the
    midpoints (above S_NOISE), at u = a, (a + b) / 2 and b; the stretches still refining share each solve.

    ``first_level``: (per_digit, extremes) of the :func:`_fit` that follows, for a ``solve`` that batches its nodes
    and keeps them: every solve is then of that fit's first nodes, profiled at its end and middle nodes alone
    (``Asked.profiled``), which the checks read, and the fit finds those nodes solved (one batched call fewer, whose
    per-step cost was a 3-node call's whole cost); None: the three nodes alone (a solve that costs one impact a
    node).

    Raises
    ------
    InterpolationError
        If MAX_GRIP_NODES nodes do not meet the check.
    """
    if first_level is None:
        u, extremes = np.array([b, 0.5 * (a + b), a]), False
        picked = np.arange(3)
    else:
        per_digit, extremes = first_level
        u = lobatto(a, b, 2 * _first_level(a, b, target, per_digit) - 1)
        picked = np.array([0, u.size // 2, u.size - 1])
    nodes = {stretch: FIRST_GRIP_NODES for stretch in stretches(power)}
    done: dict = {}
    while len(done) < len(nodes):
        refining = [stretch for stretch in nodes if stretch not in done]
        if any(2 * nodes[stretch] - 1 > MAX_GRIP_NODES for stretch in refining):
            raise InterpolationError(f"the grip instants did not reach {target:g} with {MAX_GRIP_NODES} nodes "
                                     f"({what}, {refining[0].name} stretch)")
        asked = Asked(extremes, tuple((stretch, 2 * nodes[stretch] - 1) for stretch in refining), reference,
                      None if first_level is None else tuple(picked.tolist()))
        solved = {k: value[picked] for k, value in solve(u, separation, _node_target(target), asked).items()}
        for stretch, fine in asked.grip:
            profile = np.stack([solved[k] for k in stretch.keys(fine)])  # (fine, 3), x from hi down to lo
            x = lobatto(stretch.lo, stretch.hi, fine)
            coarse = Series(stretch.lo, stretch.hi, {str(i): profile[0::2, i] for i in range(picked.size)})(x[1::2])
            checked = stretch.fraction(x[1::2]) >= S_NOISE
            error = max(np.max(np.abs(coarse[str(i)] - profile[1::2, i])[checked]) / solved["tau_f"][i]
                        for i in range(picked.size))
            if error <= 0.1 * target:
                done[stretch] = nodes[stretch]
            else:
                nodes[stretch] = fine
    return tuple((stretch, done[stretch]) for stretch in nodes)


def _onset(exit_ratio, series: Series, what: str) -> tuple[float | None, bool]:
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
    g = np.array([exit_ratio(float(v), float(y)) for v, y in zip(u, series.column("y_f"))])
    change = np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:]))
    if change.size > 1:
        raise InterpolationError(f"the tension onset is not unique ({what})")
    if change.size == 0:
        return None, bool(g[0] < 0)

    def g_series(v):
        return exit_ratio(v, float(series.value("y_f", v)))

    j = change[0]  # nodes run from u = b down to a
    return brent(g_series, u[j + 1], u[j], xtol=1e-14, rtol=1e-15), bool(g[0] < 0)


class _Piece:
    """One piece of a :class:`_Pieces`: its series in u, whether it is the tension-free range (``calm``: the
    penetration solve, j_p = 1 - y_f, the least force at an end of the contact), and its grip tables, one per
    stretch ((stretch, nodes) pairs in ``grip``)."""

    def __init__(self, series: Series, calm: bool, grip: tuple, target: float):
        self.series, self.calm = series, calm
        self.reference = "y_f" if calm else "j_p"
        self.tables = []
        for stretch, n in grip:  # (u, x) from the top down, as the series' nodes and the stretch's nodes run
            values = np.stack([series.column(k) for k in stretch.keys(n)], axis=1)[:, :, None]
            self.tables.append((stretch, Tensor(series.a, series.b, values, target)))
        self.outputs = [k for k in series.keys if not k.startswith(("tau_early", "tau_late"))]

    def __call__(self, u, levels, late) -> dict:
        out = self.series(u, self.outputs)
        if self.calm:
            out["j_p"] = 1.0 - out["y_f"]
            if "p_ends" in out:  # no tension: the least force is at an end of the contact
                out["p_min"] = out.pop("p_ends")
        if levels is not None:
            reference = reference_impulse(out, self.reference)
            with np.errstate(invalid="ignore", divide="ignore"):
                fraction = np.maximum(levels / reference, 0.0)
            tau_g = np.full(u.size, np.nan)
            below = 0.0  # without tables (see _Pieces) every level is solved alone
            for stretch, table in self.tables:  # each stretch holds fractions in (below, top]
                top = max(stretch.fraction(stretch.lo), stretch.fraction(stretch.hi))
                rows = np.flatnonzero((fraction > below) & (fraction <= top))
                if rows.size:
                    x = stretch.variable(fraction[rows])
                    tau_g[rows] = table(u[rows], (x - stretch.lo) / (stretch.hi - stretch.lo))[0]
                below = top
            # near the impulse's largest value: solved alone; beyond it j never reaches the level (NaN)
            beyond = np.flatnonzero((fraction > below) & (fraction <= 1.0 + UNREACHED))
            if beyond.size:
                tau_g[beyond] = late(u[beyond], levels[beyond])
            out["tau_g"] = np.where(levels == 0, 0.0, tau_g)
        return out


class _Pieces:
    """Normal outputs of a one-parameter family as functions of its number q, u = log q (see the module
    docstring): the penetration criterion's smooth outputs over the whole range, and the sweep's criterion
    on the piece where the force pulls before delta = 0; with ``extremes``, the force's extremes, and with
    ``grips``, the grip tables (without them, every level asked of a call is solved alone, by ``late``).

    ``solve(u, separation, node_target, asked)`` -> outputs at u (:class:`Asked`); ``exit_ratio(u, y_f)`` -> G
    (see :func:`_onset`); ``per_digit``: see :func:`_fit`.
    """

    #: Whether ``solve`` solves its nodes in one batched call and keeps them, and honours ``Asked.profiled``: the grip
    #: tables' resolution then solves the first nodes of the fit that follows instead of three of its own
    #: (:func:`_grip_resolution`).
    batched = False

    def __init__(self, solve, exit_ratio, q_min: float, q_max: float, separation: Separation, target: float, what: str,
                 per_digit: float = NODES_PER_DIGIT, extremes: bool = False, grips: bool = False, power: float = 2.0):
        self.lo, self.hi = float(q_min), float(q_max)
        self.extremes, self.grips, self.separation, self.target = extremes, grips, separation, target
        u_lo, u_hi = np.log(q_min), np.log(q_max)
        if u_hi - u_lo < 1e-12:
            u_hi = u_lo + 1e-6
        self.nodes = 0

        def fit(a, b, criterion, calm):
            reference = "y_f" if calm else "j_p"
            first = (per_digit, extremes) if self.batched else None
            grip = _grip_resolution(solve, a, b, criterion, target, reference, power, what, first) if grips else ()
            asked = Asked(extremes, grip, reference)
            keys = (*(SMOOTH if calm else NORMAL_OUTPUTS), *((("p_max", "p_ends") if calm else EXTREMES) * extremes),
                    *asked.keys())
            series, nodes = _fit(solve, a, b, criterion, target, keys, asked, what, per_digit)
            self.nodes += nodes
            return _Piece(series, calm, grip, target)

        whole = fit(u_lo, u_hi, Separation.PENETRATION, calm=True)
        cut, tension_at_top = _onset(exit_ratio, whole.series, what)
        self.cuts = np.array([] if cut is None else [cut])
        if cut is None and not tension_at_top:
            self.pieces = [whole]
            return
        # tension on [cut, u_hi] (G falls as q grows), everywhere, or in principle on [u_lo, cut]
        a, b = (u_lo if cut is None else cut, u_hi) if tension_at_top else (u_lo, cut)
        tense = fit(a, b, separation, calm=False)
        self.pieces = [tense] if cut is None else [whole, tense] if tension_at_top else [tense, whole]

    def __call__(self, q, levels=None) -> dict:
        """The outputs at q: :data:`NORMAL_OUTPUTS`, ``p_max`` and ``p_min`` if built with extremes, and
        ``tau_g`` at the dimensionless ``levels`` of j (NaN: none) if built with grips."""
        u = np.log(np.asarray(q, dtype=float))
        piece = np.searchsorted(self.cuts, u)
        keys = [*NORMAL_OUTPUTS, *(EXTREMES if self.extremes else ()), *(["tau_g"] if levels is not None else [])]
        out = {k: np.empty(u.size) for k in keys}
        for i, part in enumerate(self.pieces):
            mask = piece == i
            if not mask.any():
                continue
            values = part(u[mask], None if levels is None else levels[mask], self.late)
            for k in keys:
                out[k][mask] = values[k]
        return out

    def late(self, u, levels) -> np.ndarray:
        """tau_g of scenes at u whose level lies beyond the grip table, each solved for its own scene."""
        raise NotImplementedError


def _profile(out: dict, asked: Asked) -> np.ndarray:
    """The levels of each node's grip profiles: (nodes, every asked fraction)."""
    return reference_impulse(out, asked.reference)[:, None] * asked.fractions()[None, :]


class LambdaInterpolant(_Pieces):
    """Normal outputs of the modified law for one zeta, as functions of lam on [lam_min, lam_max] (its nodes: batched
    lanes, kept).

    Parameters
    ----------
    zeta : float
    lam_min, lam_max : float
        The range to cover (> 0).
    separation : Separation
        When the contact ends.
    target : float
        Accuracy the interpolant must meet (checked at a tenth of it).
    extremes, grips : bool
        Also tabulate the force's extremes, and the grip tables (see the module docstring).

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

    batched = True  # its nodes: batched lanes, kept

    def __init__(self, zeta: float, lam_min: float, lam_max: float, separation: Separation, target: float,
                 extremes: bool = False, grips: bool = False):
        taylor = series_lanes.covers(zeta, lam_max)

        def lanes(lam, criterion, node_target, **asked):  # the batched lanes: Taylor's where they apply
            n = lam.size
            if taylor:
                return series_lanes.integrate(np.full(n, zeta), lam, criterion, node_target, **asked)
            asked.pop("partial", None)
            return batch.integrate(np.full(n, zeta), lam, np.zeros(n), np.ones(n, bool), criterion, node_target,
                                   **asked)

        solved: dict = {}  # the normal lanes of nodes solved before: the grip tables' refinement asks them again

        def solve(u, criterion, node_target, asked: Asked):
            lam = np.exp(u)
            key = (u.tobytes(), criterion, node_target, asked.extremes)
            if key not in solved:  # with grip tables, the Taylor lanes keep their steps for the levels asked later
                solved[key] = lanes(lam, criterion, node_target, extremes=asked.extremes,
                                    **({"keep_steps": True} if taylor and grips else {}))
            out = dict(solved[key])
            steps = out.pop("steps", None)
            if asked.extremes:  # eq. 4.2's force is 0 at both ends of the contact (delta = 0, the ramp off)
                out["p_ends"] = np.zeros(lam.size)
            if asked.grip:  # each node's levels: off its lane's kept steps, else a Runge-Kutta lane per level
                levels = _profile(out, asked)
                rows = np.arange(lam.size) if asked.profiled is None else np.array(asked.profiled)
                if steps is not None:  # what Taylor lanes stopping at these levels give, to the bit (Marched)
                    profiled = np.full(levels.shape, np.nan)  # NaN: reached at once, so those lanes stop at once
                    profiled[rows] = levels[rows]
                    tau = steps.instants(profiled)
                else:  # the profiled nodes' lanes alone
                    tau = np.full(levels.shape, np.nan)
                    tau[rows] = lanes(np.repeat(lam[rows], levels.shape[1]), criterion, node_target,
                                      levels=levels[rows].ravel(), partial=True)["tau_g"].reshape(rows.size, -1)
                out |= dict(zip(asked.keys(), tau.T))
            return out

        def exit_ratio(u, y_f):  # P / (k delta) as delta -> 0+, the law's: 1 + 2 zeta lam y
            return modified_per_compression(0.0, y_f, {"zeta": zeta, "lam": np.exp(u)})

        self.zeta = zeta
        self._lanes = lanes
        super().__init__(solve, exit_ratio, lam_min, lam_max, separation, target, f"zeta = {zeta:g}",
                         extremes=extremes, grips=grips)

    def late(self, u, levels) -> np.ndarray:
        """The lanes for each scene, stopping at its instant."""
        return self._lanes(np.exp(u), self.separation, self.target, levels=levels, partial=True)["tau_g"]


def dimensionless_motion(scene: Scene, options: SolverOptions, extremes: bool = False, levels=None,
                         asked: Asked | None = None) -> dict:
    """tau_m, x_m, tau_f, y_f and j_p (J+ / (m v_n), J+ the impulse of max(P, 0)) of one scene, by the
    single-impact path's normal motion (``options.method`` as ``simulate`` resolves it); with ``extremes``,
    p_max and p_min (the force's extremes over m v_n w); with ``levels`` (of j = J+ / (m v_n)), tau_g, the
    instants J+ reaches them; with ``asked``, its extremes and grip profile (:class:`Asked`)."""
    normal = shared_normal_motion(scene, options)  # inside a fit, solved once for every evaluation
    w, v, m = scene.frequency, scene.v_normal, scene.mass
    impulse = PositiveImpulse(normal)
    out = {"tau_m": normal.t_m * w, "x_m": normal.delta_m * w / v, "tau_f": normal.t_f * w,
           "y_f": float(normal.state(normal.t_f)[1]) / v, "j_p": float(impulse(normal.t_f)) / (m * v)}
    if extremes or (asked is not None and asked.extremes):
        ends = normal.force(normal.grid[[0, -1]])
        scale = m * v * w
        low, high = normal.force_extremes()
        out["p_max"], out["p_min"] = high / scale, low / scale
        out["p_ends"] = min(ends[0], ends[-1]) / scale  # the least force at an end of the contact
    if levels is not None:
        out["tau_g"] = impulse.instants(np.asarray(levels, dtype=float) * (m * v)) * w
    if asked is not None and asked.grip:
        tau = impulse.instants(_profile({k: np.atleast_1d(x) for k, x in out.items()}, asked)[0] * (m * v)) * w
        out |= dict(zip(asked.keys(), tau))
    return out


#: Where the force's sign at delta -> 0+ is read for a law without a formula for it (G, see :func:`_onset`):
#: delta = EXIT_DELTA x R, small enough that a ramp in delta / R has no say.
EXIT_DELTA = 1e-12


def onset_exponent(scene: Scene) -> float:
    """n of the law's force at first touch, P ~ delta^n as delta -> 0+ at the approach rate (1 for a linear
    spring, 3/2 for Hertz, 0 where the damping makes it jump), read off the law at EXIT_DELTA x R and twice it:
    the impulse then grows as the (n + 1)-th power of the time (the grip tables' variable, :func:`stretches`)."""
    delta = EXIT_DELTA * scene.radius
    low, high = float(scene.stage_force(delta, scene.v_normal)), float(scene.stage_force(2.0 * delta, scene.v_normal))
    return round(math.log2(high / low), 6) if low > 0 and high > 0 else 1.0


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
    separation : Separation
        When the contact ends.
    target : float
        Accuracy the interpolant must meet (checked at a tenth of it).
    extremes, grips : bool
        Also tabulate the force's extremes, and the grip tables (see the module docstring).
    """

    def __init__(self, scene: Scene, q_min: float, q_max: float, separation: Separation, target: float,
                 extremes: bool = False, grips: bool = False):
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

        def solve(u, criterion, node_target, asked: Asked):
            # the integrator's error stays below a tenth of the node's; grip profiles read small impulses off
            # the dense output, whose error is absolute: at the tightest tolerance
            tol = 1e-13 if asked.grip else max(node_target / 100.0, 1e-13)
            rows = [dimensionless_motion(node(float(v)).with_(separation=criterion), SolverOptions(rtol=tol, atol=tol),
                                         asked=asked) for v in u]
            return {k: np.array([row[k] for row in rows]) for k in rows[0]}

        def exit_ratio(u, y_f):  # P / (P at rest) as delta -> 0+, at the rebound rate
            at = node(u)
            delta = EXIT_DELTA * at.radius
            return float(at.stage_force(delta, y_f * at.v_normal)) / float(at.stage_force(delta, 0.0))

        self._node = node
        # nodes cost one impact each here (not one batched call): start from FIRST_NODES and refine; a node asked
        # again (the grip tables' refinement asks the same three at every level) reuses its normal motion
        with reusing_normal_motions():
            super().__init__(solve, exit_ratio, q_min, q_max, separation, target,
                             f"model {scene.model!r}, {name} in [{q_min:g}, {q_max:g}]", per_digit=0.0,
                             extremes=extremes, grips=grips, power=1.0 + onset_exponent(scene))

    def late(self, u, levels) -> np.ndarray:
        """The single-impact integrator on each scene's own copy of the group's scene."""
        tol = max(_node_target(self.target) / 100.0, 1e-13)
        return np.array([dimensionless_motion(self._node(float(v)).with_(separation=self.separation),
                                              SolverOptions(rtol=tol, atol=tol), levels=[level])["tau_g"][0]
                         for v, level in zip(u, levels)])
