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
These forms never subtract nearly equal numbers, so they are accurate to a
few ulp in every regime, including zeta -> 1 from either side.

Events are the roots of these exact functions, bracketed on a dense grid
(uniform plus geometric, for the fast and slow time scales) and refined with
Brent's method to a few ulp.
"""

from __future__ import annotations

import math

import numpy as np

from .events import ImpactError, first_root
from .laws import LAWS
from .normal import NormalMotion, no_separation_message, separation_function
from .scene import Scene

#: Uniform and geometric samples used to bracket events.
GRID_POINTS = 4097


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
            t_scan = 60.0 / -self._slow
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

    def _basis(self, t):
        if self._under:
            return (np.exp(-self._sigma * t), np.cos(self._freq * t),
                    t * np.sinc(self._freq * t / math.pi))
        q2t = 2.0 * self._freq * t  # q > 0 for zeta > 1; expm1 keeps S exact as q t -> 0
        return np.exp(self._slow * t), 0.5 * (1.0 + np.exp(-q2t)), -np.expm1(-q2t) / (2.0 * self._freq)

    def state(self, t):
        t = np.asarray(t, dtype=float)
        e, c, s = self._basis(t)
        x0, v0 = self._x0, self._v0
        x = e * (x0 * c + (v0 + self._sigma * x0) * s)
        xd = e * (v0 * c - (self._w2 * x0 + self._sigma * v0) * s)
        return x + self._offset, xd


#: Exact normal motions by the ODE they solve; a law names its own in ``ContactLaw.closed_form``.
CLOSED_FORMS = {"kelvin-voigt": ClosedFormNormal}
