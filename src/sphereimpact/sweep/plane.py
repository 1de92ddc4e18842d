"""Two-number similarity: eq. 4.2's weightless normal outputs as functions of (zeta, lam), for sweeps of many balls.

A sweep over k, b, m, D, speed and angle gives every scene its own (zeta, lam), so the one-ball interpolant
in lam (:class:`.similarity.LambdaInterpolant`) does not apply; but the outputs are still smooth functions of
the two numbers, and one interpolant on the sweep's rectangle serves every scene.  It has two pieces, each a
tensor Chebyshev series on Lobatto nodes in zeta and a second number, all nodes solved in one call of the
Taylor lanes (:mod:`.series_lanes`):

1. ``calm``: the penetration criterion's tau_m, x_m, tau_f and y_f in (zeta, u = log lam), smooth on the whole
   rectangle.  They give G = 1 + 2 zeta lam y_f, the force's sign as delta -> 0+: the force pulls before
   delta = 0 iff G < 0, and otherwise both criteria end at delta = 0 with j_p = 1 - y_f;
2. ``tension``: the ``continued`` end's tau_f and y_f (the first root of P_hat / x, continued past delta = 0
   where the force does not pull before it), in (zeta, v = log(2 zeta lam)).  They equal the force
   criterion's end wherever the force pulls and are smooth across the onset, so the piece needs no cut
   along the onset curve, only a lower edge below it: the onset lies at v* = -ln|y_f| (measured
   v* ~ pi zeta / (1 + 2.8 zeta) within 5 % for zeta 0.003-1), and the piece starts at ONSET_MARGIN v*.
   A scene that pulls below that edge (none measured) is integrated by the lanes instead.

Each piece is accepted when its tails, the last two Chebyshev coefficients in each direction (summed over the
other), are below the target (TAIL_FACTOR): measured, the errors between nodes are 3 to 5 times below the
tails.  Otherwise that direction's nodes grow by GROWTH and every node is solved again, up to MAX_NODES per
piece (InterpolationError: the caller integrates the scenes).  Nodes are solved at NODE_FACTOR x the target,
as for the one-ball interpolant.  The series are evaluated by BLAS products on blocks of a fixed width
(EVAL_BLOCK), so a scene's value does not depend on the shard or chunk it is evaluated in.
"""

from __future__ import annotations

import math

import numpy as np

from . import series_lanes
from ..contact.laws.linear import modified_per_compression
from ..contact.separation import Separation
from ..errors import InterpolationError
from .chebyshev import Tensor, lobatto
from .series_lanes import End
from .similarity import NODE_FACTOR, NODE_TARGET_MIN

#: Largest zeta the plane takes: towards critical damping the penetration criterion's t_f steepens (x creeps
#: back to 0) and the calm piece needs ever more nodes in zeta (zeta 0.01 to 0.5, 0.6, 0.8 with lam 1e-3 to
#: 1e4: 2534, 6682 and 12 102 nodes).  Scenes beyond it take the Taylor lanes.
ZETA_MAX = 0.5
#: lam range the plane takes: the range its accuracy is tested on (tests/test_plane.py); beyond it the scenes
#: take the Taylor lanes.
LAM_MIN, LAM_MAX = 1e-3, 1e6
#: The tension piece starts at this fraction of the estimated onset v* = pi zeta / (1 + 2.8 zeta).
ONSET_MARGIN = 0.8
#: First nodes of each piece in zeta, and in its second number (u or v) per unit of its width and digit of
#: the target (odd; at least MIN_NODES): the fewest that met 1e-8 on random balls (tests/test_plane.py).
FIRST_ZETA_NODES = {"calm": 13, "tension": 25}
NODES_PER_DIGIT = 0.64
MIN_NODES = 9
#: A piece whose tails miss the target grows by this factor in that direction, up to MAX_NODES nodes.
GROWTH = 1.5
MAX_NODES = 8192
#: Outputs of each piece.
CALM = ("tau_m", "x_m", "tau_f", "y_f")
TENSION = ("tau_f", "y_f")
#: A piece is accepted when its tails are below TAIL_FACTOR x target (see the module docstring).
TAIL_FACTOR = 1.0
def _odd(n: float) -> int:
    """The odd integer at or above n, at least MIN_NODES."""
    n = max(math.ceil(n), MIN_NODES)
    return n + 1 - n % 2


def onset_edge(zeta):
    """The tension piece's lower edge in v = log(2 zeta lam): ONSET_MARGIN x the estimated onset."""
    zeta = np.asarray(zeta, dtype=float)
    return ONSET_MARGIN * np.pi * zeta / (1.0 + 2.8 * zeta)


class PlaneInterpolant:
    """Normal outputs of eq. 4.2 without gravity as functions of (zeta, lam) on a rectangle.

    Parameters
    ----------
    zeta_min, zeta_max : float
        Damping ratios to cover, in (0, ZETA_MAX].
    lam_min, lam_max : float
        lam to cover, in [LAM_MIN, LAM_MAX].
    separation : Separation
        When the contact ends.
    target : float
        Accuracy the interpolant must meet (its Chebyshev tails below it, see the module docstring).
    extremes : bool
        Also the force's extremes: the largest by the Taylor lanes up to maximum compression (see
        :meth:`__call__`), the least 0 wherever the force does not pull before the contact ends, and by the
        Taylor lanes where it does (the penetration criterion's tension).

    Attributes
    ----------
    zeta_min, zeta_max, lam_min, lam_max : float
        The rectangle covered (a call outside it would extrapolate).
    nodes : int
        Nodes solved for the build (every attempt).

    Raises
    ------
    InterpolationError
        Outside the ranges above, with tension nodes beyond the Taylor lanes' lam, or when a piece needs more
        than MAX_NODES nodes.
    """

    def __init__(self, zeta_min: float, zeta_max: float, lam_min: float, lam_max: float, separation: Separation,
                 target: float, extremes: bool = False):
        if not (0 < zeta_min <= zeta_max <= ZETA_MAX and LAM_MIN <= lam_min <= lam_max <= LAM_MAX):
            raise InterpolationError(f"the (zeta, lam) plane covers zeta in (0, {ZETA_MAX:g}] and lam in "
                                     f"[{LAM_MIN:g}, {LAM_MAX:g}]; got zeta [{zeta_min:g}, {zeta_max:g}], "
                                     f"lam [{lam_min:g}, {lam_max:g}]")
        self.separation, self.extremes, self.target = separation, extremes, target

        self.zeta_min, self.zeta_max, self.lam_min, self.lam_max = zeta_min, zeta_max, lam_min, lam_max
        self.zeta = (zeta_min, max(zeta_max, zeta_min * (1.0 + 1e-6)))
        u_lo, u_hi = math.log(lam_min), math.log(lam_max)
        self.u = (u_lo, max(u_hi, u_lo + 1e-6))
        self.v_top = max(math.log(2.0 * zeta_max * lam_max), float(onset_edge(zeta_max)) + 1e-6)
        if math.exp(self.v_top) / (2.0 * zeta_min) > series_lanes.LAM_MAX:  # the tension piece's largest lam
            raise InterpolationError(f"the (zeta, lam) plane's tension nodes would reach lam "
                                     f"{math.exp(self.v_top) / (2.0 * zeta_min):.3g}, beyond the Taylor lanes' "
                                     f"{series_lanes.LAM_MAX:g} (zeta from {zeta_min:g})")
        self.node_target = node_target = max(NODE_FACTOR * target, NODE_TARGET_MIN)
        widths = {"calm": self.u[1] - self.u[0], "tension": self.v_top - float(onset_edge(zeta_min))}
        sizes = {piece: (FIRST_ZETA_NODES[piece], _odd(NODES_PER_DIGIT * math.log10(10.0 / target) * width))
                 for piece, width in widths.items()}
        self.nodes = 0
        while True:
            if any(math.prod(size) > MAX_NODES for size in sizes.values()):
                raise InterpolationError(f"the (zeta, lam) plane did not reach {target:g} with {MAX_NODES} nodes "
                                         f"per piece (zeta in [{zeta_min:g}, {zeta_max:g}], lam in "
                                         f"[{lam_min:g}, {lam_max:g}])")
            grids = {piece: self._grid(piece, *size) for piece, size in sizes.items()}
            zeta = np.concatenate([g[0].ravel() for g in grids.values()])
            lam = np.concatenate([g[1].ravel() for g in grids.values()])
            split = grids["calm"][0].size
            ends = np.where(np.arange(zeta.size) < split, End.PENETRATION, End.CONTINUED)
            solved = series_lanes.integrate(zeta, lam, ends, node_target)
            self.nodes += zeta.size
            self.calm = Tensor(*self.zeta, np.stack([solved[k][:split].reshape(sizes["calm"]) for k in CALM], -1),
                               target)
            self.tension = Tensor(*self.zeta, np.stack([solved[k][split:].reshape(sizes["tension"])
                                                         for k in TENSION], -1), target)
            grown = {piece: tuple(_odd(GROWTH * n) if tail > TAIL_FACTOR * target else n
                                  for n, tail in zip(sizes[piece], getattr(self, piece).tails))
                     for piece in sizes}
            if grown == sizes:
                return
            sizes = grown

    def _grid(self, piece: str, n_zeta: int, n_other: int) -> tuple[np.ndarray, np.ndarray]:
        """(zeta, lam) of a piece's Lobatto grid, shape (n_zeta, n_other): the calm piece in (zeta, u), the
        tension piece in (zeta, v) from its edge to v_top (s in [0, 1] between them)."""
        zeta = lobatto(*self.zeta, n_zeta)[:, None]
        s = lobatto(0.0, 1.0, n_other)[None, :]
        if piece == "calm":
            lam = np.exp(self.u[0] + s * (self.u[1] - self.u[0]))
        else:
            edge = onset_edge(zeta)
            lam = np.exp(edge + s * (self.v_top - edge)) / (2.0 * zeta)
        return np.broadcast_arrays(zeta, lam)

    def __call__(self, zeta, lam, levels=None) -> dict:
        """tau_m, x_m, tau_f, y_f and j_p at each (zeta, lam) of the rectangle; with ``levels`` (of the impulse j,
        NaN: none), tau_g, the instant j reaches each; built with extremes, p_max and p_min.  The instants and
        the largest force come from the Taylor lanes, each stopping once it has them (:func:`.series_lanes.
        integrate`, ``partial``): the largest force is not smooth on the plane (where the ramp's early peak
        overtakes the peak near maximum compression a tensor series needs ten times the nodes in zeta)."""
        zeta, lam = np.asarray(zeta, dtype=float), np.asarray(lam, dtype=float)
        calm = self.calm(zeta, (np.log(lam) - self.u[0]) / (self.u[1] - self.u[0]))
        out = dict(zip(CALM, calm))
        out["j_p"] = 1.0 - out["y_f"]
        if self.extremes or levels is not None:
            rows = np.arange(zeta.size) if self.extremes else np.flatnonzero(np.isfinite(levels))
            if rows.size:
                solved = series_lanes.integrate(zeta[rows], lam[rows], self.separation, self.target,
                                                levels=None if levels is None else levels[rows],
                                                extremes=self.extremes, partial=True)
                for key, values in solved.items():
                    out.setdefault(key, np.full(zeta.size, np.nan))[rows] = values
        if self.extremes:
            out["p_min"] = np.zeros(zeta.size)
        pulls = np.flatnonzero(modified_per_compression(0.0, out["y_f"], {"zeta": zeta, "lam": lam}) < 0)
        if pulls.size:
            z = zeta[pulls]
            edge = onset_edge(z)
            s = (np.log(2.0 * z * lam[pulls]) - edge) / (self.v_top - edge)
            rest = {k: np.empty(pulls.size) for k in TENSION}
            inside = s >= 0
            if inside.any():
                for k, values in zip(TENSION, self.tension(z[inside], s[inside])):
                    rest[k][inside] = values
            if not inside.all():  # pulls below the piece's edge: integrated
                alone = series_lanes.integrate(z[~inside], lam[pulls][~inside], Separation.FORCE, self.node_target)
                for k in TENSION:
                    rest[k][~inside] = alone[k]
            out["j_p"][pulls] = 1.0 - rest["y_f"]
            if self.extremes and self.separation.pulls:  # the tension's least force: integrated
                out["p_min"][pulls] = series_lanes.integrate(z, lam[pulls], Separation.PENETRATION,
                                                             self.node_target, extremes=True)["p_min"]
            if self.separation.on_force:
                out["tau_f"][pulls], out["y_f"][pulls] = rest["tau_f"], rest["y_f"]
        return out
