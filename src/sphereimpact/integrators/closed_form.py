"""Closed form of the kelvin-voigt normal motion, the exact reference.

Inside contact m delta'' + b delta' + k delta = m g_n is linear.  With the
static offset d_s = m g_n / k, x = delta - d_s, sigma = zeta omega_n, the
solution from x(0) = x0, x'(0) = v0 is

    x(t)  = E(t) [x0 C(t) + (v0 + sigma x0) S(t)]
    x'(t) = E(t) [v0 C(t) - (omega_n^2 x0 + sigma v0) S(t)]

with, for zeta <= 1 (under- and critically damped, omega_d = omega_n sqrt(1 - zeta^2)),
E = exp(-sigma t), C = cos(omega_d t), S = sin(omega_d t) / omega_d (= t at zeta = 1);
and for zeta > 1 (q = omega_n sqrt(zeta^2 - 1), r1 = -omega_n / (zeta + sqrt(zeta^2 - 1))
the slow root), E = exp(r1 t), C = (1 + exp(-2 q t)) / 2, S = -expm1(-2 q t) / (2 q).
These forms never subtract nearly equal numbers (x'(t) over-damped is written with C - sigma S =
(r1 - r2 exp(-2 q t)) / (2 q), see ``_basis``), so they are accurate to a few ulp in every regime,
including zeta -> 1 from either side and zeta in the thousands.

Without gravity the events are formulas (see ``_events``).  With gravity they are the roots of these
exact functions, bracketed on a dense grid
(uniform plus geometric, for the fast and slow time scales) and refined with
Brent's method to a few ulp.
"""

from __future__ import annotations

import math

import numpy as np

from ..ode.dense import is_instant
from ..errors import ImpactError
from ..ode.events import first_root
from ..contact.laws import LAWS
from .normal import NormalMotion, no_separation_message, separation_function
from ..impact.scene import Scene

#: Uniform and geometric samples used to bracket events.
GRID_POINTS = 4097
#: Uniform samples over [0, t_f] (and a quarter as many geometric ones, for an over-damped start) when the
#: events are in closed form: the grid then only brackets the tangential switch and the force's extremes.
EVENT_FREE_GRID = 129


def _scan_grid(t_end: float) -> np.ndarray:
    uniform = np.linspace(0.0, t_end, GRID_POINTS)
    geometric = np.geomspace(t_end * 1e-9, t_end, GRID_POINTS // 2)
    return np.unique(np.concatenate([uniform, geometric]))


class ClosedFormNormal(NormalMotion):
    """Exact kelvin-voigt normal motion.

    Parameters
    ----------
    scene : Scene
        Its model must be linear (``kelvin-voigt``).

    Raises
    ------
    ValueError
        For a nonlinear force model.
    ImpactError
        When the contact never separates under the scene's criterion.
    """

    def __init__(self, scene: Scene):
        if scene.law.closed_form != "kelvin-voigt":
            closed = ", ".join(name for name, law in LAWS.items() if law.closed_form == "kelvin-voigt")
            raise ValueError(f"method 'closed' needs a law with a closed form ({closed}); got model {scene.model!r}")
        self.scene = scene
        w, zeta = scene.omega_n, scene.zeta
        self._w2, self._sigma = w * w, zeta * w
        self._offset = scene.mass * scene.g_normal / scene.k
        self._x0, self._v0 = -self._offset, scene.v_normal
        if zeta <= 1.0:
            self._under, self._freq = True, w * math.sqrt(max(0.0, 1.0 - zeta * zeta))
            t_scan = min(2 * math.pi / self._freq if self._freq > 0 else math.inf,
                         60.0 / self._sigma if self._sigma > 0 else math.inf)
        else:
            root = math.sqrt(zeta * zeta - 1.0)
            self._under, self._freq = False, w * root
            self._slow = -w / (zeta + root)
            if not self._slow < 0.0:  # w / (2 zeta) underflowed
                raise ImpactError(f"the over-damped contact's slow rate omega_n / (2 zeta) underflows double "
                                  f"precision (zeta = {zeta:.3g}): outside what the model computes")
            t_scan = 60.0 / -self._slow
        if self._offset == 0.0:  # without gravity the events are in closed form too
            self.t_m, self.t_f = self._events()
            self.grid = np.unique(np.concatenate([np.linspace(0.0, self.t_f, EVENT_FREE_GRID),
                                                  np.geomspace(self.t_f * 1e-9, self.t_f, EVENT_FREE_GRID // 4)]))
            self.stats = {"method": "closed", "rtol": 0.0, "atol": 0.0, "nfev": 0}
            return
        scan = _scan_grid(t_scan)
        t_m = first_root(lambda t: self.state(t)[1], scan, direction=-1)
        sep = separation_function(scene)
        t_f = first_root(lambda t: sep(*self.state(t)), scan, direction=-1)
        if t_f is None:
            raise ImpactError(no_separation_message(scene, t_scan))
        if t_m is None or t_m > t_f:
            raise ImpactError("no maximum compression before separation")
        self.t_m, self.t_f = t_m, t_f
        self.grid = np.append(scan[scan < t_f], t_f)
        self.stats = {"method": "closed", "rtol": 0.0, "atol": 0.0, "nfev": 0}

    def _events(self) -> tuple[float, float]:
        """t_m and t_f in closed form, for a contact without gravity (x0 = 0).

        Under-damped, with theta = omega_d t: delta = E v0 sin(theta) / omega_d and delta_dot = E v0
        (cos(theta) - sigma sin(theta) / omega_d), so maximum compression is at theta = atan2(omega_d,
        sigma); delta returns to 0 at theta = pi; P = k delta + b delta_dot = E v0 (A sin(theta) + b
        cos(theta)), A = (k - b sigma) / omega_d, falls to 0 at theta = pi - atan2(b, A), before pi (P
        starts at b v0 > 0).  Critically and over-damped, with the roots r1 (slow) and r2 of m r^2 + b r
        + k = 0: delta = v0 (e^(r1 t) - e^(r2 t)) / (r1 - r2) > 0 for every t > 0 (delta never returns
        to 0), maximum compression at t_m = ln(r2 / r1) / (r1 - r2) = acosh(zeta) / q, and since k + b r
        = -m r^2, P = 0 at e^((r1 - r2) t) = (r2 / r1)^2: t_f = 2 t_m (1 / omega_n and 2 / omega_n at zeta
        = 1).  No root search, so no cancellation: at zeta = 5361 a search on P = k delta + b delta_dot
        (two terms of 1e6 times their difference) missed t_f by 1 %.

        Raises
        ------
        ImpactError
            Penetration criterion, critically or over-damped: delta never returns to 0.
        """
        s, w, zeta = self.scene, self.scene.omega_n, self.scene.zeta
        if self._under and self._freq > 0.0:
            wd = self._freq
            t_m = math.atan2(wd, self._sigma) / wd
            if s.separation == "penetration":
                return t_m, math.pi / wd
            return t_m, (math.pi - math.atan2(s.b, (s.k - s.b * self._sigma) / wd)) / wd
        if s.separation == "penetration":
            raise ImpactError(no_separation_message(s, math.inf))
        root = math.sqrt((zeta - 1.0) * (zeta + 1.0))  # no cancellation as zeta -> 1
        t_m = 1.0 / w if root == 0.0 else math.acosh(zeta) / (w * root)
        return t_m, 2.0 * t_m

    def _basis(self, t):
        """(E, C, S, C - sigma S) at t: under-damped directly; over-damped with D = exp(-2 q t), C - sigma S =
        (r1 - r2 D) / (2 q), r2 = -(sigma + q): 1 - sigma / q = r1 / q is computed as r1 itself, where the
        direct form subtracts nearly equal numbers (at zeta = 5361 it lost 9 digits of delta_dot)."""
        if self._under:
            e, c, s = np.exp(-self._sigma * t), np.cos(self._freq * t), t * np.sinc(self._freq * t / math.pi)
            return e, c, s, c - self._sigma * s
        q, q2t = self._freq, 2.0 * self._freq * t  # q > 0 for zeta > 1; expm1 keeps S exact as q t -> 0
        d = np.exp(-q2t)
        return (np.exp(self._slow * t), 0.5 * (1.0 + d), -np.expm1(-q2t) / (2.0 * q),
                (self._slow + (self._sigma + q) * d) / (2.0 * q))

    def state(self, t):
        if self._under and is_instant(t):  # one instant (root and extremum searches): plain floats
            t = float(t)
            e, c = math.exp(-self._sigma * t), math.cos(self._freq * t)
            s = math.sin(self._freq * t) / self._freq if self._freq * t != 0.0 else t
            damped = c - self._sigma * s
        else:
            t = np.asarray(t, dtype=float)
            e, c, s, damped = self._basis(t)
        x0, v0 = self._x0, self._v0
        x = e * (x0 * c + (v0 + self._sigma * x0) * s)
        xd = e * (v0 * damped - self._w2 * x0 * s)
        return x + self._offset, xd


#: Exact normal motions by the ODE they solve; a law names its own in ``ContactLaw.closed_form``.
CLOSED_FORMS = {"kelvin-voigt": ClosedFormNormal}
