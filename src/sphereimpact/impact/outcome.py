"""The outputs of one impact, and its time histories in the contact and global frames.

Contact frame: t along the flat in the direction of the incoming tangential
motion (down-slope), n the outward normal of the flat.  Global frame: X
horizontal, Y vertical up, origin at the first contact point; the flat's normal
is n = (sin beta, cos beta) and t = (cos beta, -sin beta).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..ode.events import extremum
from .scene import Scene

#: The outputs of one impact, in the order of the JSON object and tables.
OUTPUT_KEYS = ("t_m", "delta_m", "t_f", "vc_t", "vc_n", "ve_t", "ve_n", "omega_f", "cor",
               "regime", "t_roll", "force_min", "force_max", "beyond_radius",
               "switches", "rebound_angle", "rebound_angle_contact", "work_t",
               "method", "rtol", "atol", "nfev", "wall_time")

#: The solver's statistics among OUTPUT_KEYS; the others are the impact's scalar outputs.
SOLVER_KEYS = ("method", "rtol", "atol", "nfev", "wall_time")
#: The scalar outputs of one impact (OUTPUT_KEYS less the solver's statistics): the columns of a sweep's
#: table too (:func:`sphereimpact.sweep.sweep`).
SCALAR_OUTPUTS = tuple(key for key in OUTPUT_KEYS if key not in SOLVER_KEYS)
#: Units of the outputs (SI; angles in degrees).
OUTPUT_UNITS = {"t_m": "s", "delta_m": "m", "t_f": "s", "vc_t": "m/s", "vc_n": "m/s", "ve_t": "m/s", "ve_n": "m/s",
                "omega_f": "rad/s", "cor": "-", "regime": "", "t_roll": "s", "force_min": "N", "force_max": "N",
                "beyond_radius": "", "switches": "-", "rebound_angle": "deg", "rebound_angle_contact": "deg",
                "work_t": "J", "method": "", "rtol": "-", "atol": "-", "nfev": "-", "wall_time": "s"}

#: Columns of :meth:`Outcome.history`, with units.
HISTORY_COLUMNS = {
    "t": "s", "delta": "m", "delta_dot": "m/s", "force": "N", "force_t": "N",
    "u_t": "m", "u_n": "m", "vc_t": "m/s", "vc_n": "m/s", "omega": "rad/s", "ve_t": "m/s", "ve_n": "m/s",
    "X": "m", "Y": "m", "VX": "m/s", "VY": "m/s",
}


@dataclass(frozen=True)
class Outcome:
    """The result of one impact (SI units).

    Attributes
    ----------
    t_m : float
        Time of maximum compression [s] (delta_dot = 0).
    delta_m : float
        Maximum compression [m], positive.
    t_f : float
        Contact duration [s] (separation under the scene's criterion).
    vc_t, vc_n : float
        Centre velocity after impact along the flat and the outward normal [m/s].
    ve_t, ve_n : float
        Contact-point velocity after impact [m/s]; ve_t = vc_t - omega_f R, ve_n = vc_n.
    omega_f : float
        Spin after impact [rad/s], positive in the sense friction spins the ball.
    cor : float
        Coefficient of restitution ve_n / (v cos beta) [-].
    regime : str
        The tangential mode at separation: ``sliding`` or ``rolling`` (rigid tangential contact),
        ``sliding`` or ``sticking`` (compliant), ``none`` for a normal impact.
    t_roll : float or None
        First instant the contact point stops slipping (rolls, or sticks) [s]; None if it never does.
    force_min, force_max : float
        Extremes of the normal force during contact [N] (negative = pulling).
    beyond_radius : bool
        True when delta_m exceeds the radius R: the centre passed the flat's plane, outside what a contact
        law of a ball's surface can describe (:func:`sphereimpact.simulate` warns, or refuses when strict).
    switches : int
        Number of changes of tangential mode during contact.
    rebound_angle, rebound_angle_contact : float
        Direction of the centre's and of the contact point's velocity after impact, from the normal [deg]:
        atan2(vc_t, vc_n) and atan2(ve_t, vc_n); negative when the tangential velocity is reversed.
    work_t : float
        Work of the tangential contact force on the ball [J] (<= 0: friction and a compliant contact's
        hysteresis take energy): the change of translational-tangential and rotational kinetic energy
        less the work of gravity along the flat.
    method, rtol, atol, nfev, wall_time
        Solver statistics; ``wall_time`` [s] covers the whole call.
    """

    t_m: float
    delta_m: float
    t_f: float
    vc_t: float
    vc_n: float
    ve_t: float
    ve_n: float
    omega_f: float
    cor: float
    regime: str
    t_roll: float | None
    force_min: float
    force_max: float
    beyond_radius: bool
    switches: int
    rebound_angle: float
    rebound_angle_contact: float
    work_t: float
    method: str
    rtol: float
    atol: float
    nfev: int
    wall_time: float
    scene: Scene = field(repr=False, compare=False)
    motion: object = field(repr=False, compare=False)

    @classmethod
    def from_motion(cls, motion, wall_time: float) -> "Outcome":
        """Read the outputs off a solved contact motion (reduced or planar).

        ``motion`` has ``scene``, ``t_m``, ``t_f``, ``t_roll``, ``regime``,
        ``grid``, ``stats``, ``force(t)`` and ``kinematics(t)``.
        """
        s = motion.scene
        both = motion.kinematics(np.array([motion.t_m, motion.t_f]))  # one call: [0] at t_m, [1] at t_f
        delta_m = float(both["delta"][0])
        vc_t, vc_n, omega = float(both["vc_t"][1]), float(both["vc_n"][1]), float(both["omega"][1])
        ve_t = vc_t - omega * s.radius
        forces = motion.force(motion.grid)
        work = (0.5 * s.mass * (vc_t * vc_t - s.v_tangent ** 2) + 0.5 * s.inertia * omega * omega
                - s.mass * s.g_tangent * float(both["u_t"][1]) - 0.5 * s.inertia * s.spin * s.spin)
        return cls(
            t_m=motion.t_m, delta_m=delta_m, t_f=motion.t_f,
            vc_t=vc_t, vc_n=vc_n, ve_t=ve_t, ve_n=vc_n, omega_f=omega,
            cor=vc_n / s.v_normal, regime=motion.regime, t_roll=motion.t_roll,
            force_min=extremum(motion.force, motion.grid, "min", forces)[1],
            force_max=extremum(motion.force, motion.grid, "max", forces)[1],
            beyond_radius=bool(delta_m > s.radius), switches=int(motion.switches),
            rebound_angle=math.degrees(math.atan2(vc_t, vc_n)), rebound_angle_contact=math.degrees(math.atan2(ve_t, vc_n)),
            work_t=work, wall_time=wall_time, scene=s, motion=motion, **motion.stats)

    def to_dict(self) -> dict:
        """The outputs as plain Python values, keyed by :data:`OUTPUT_KEYS`."""
        out = {}
        for key in OUTPUT_KEYS:
            value = getattr(self, key)
            out[key] = float(value) if isinstance(value, (float, np.floating)) else value
        return out

    def history(self, n: int = 401):
        """Time histories on ``n`` uniform instants over [0, t_f]: a DataFrame whose columns are
        :data:`HISTORY_COLUMNS` (SI units, recorded in its ``attrs["units"]``).

        Raises
        ------
        ValueError
            ``n`` is not an integer >= 2 (the two ends of the contact at least).
        """
        if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)) or n < 2:
            raise ValueError(f"n must be an integer >= 2 (instants from 0 to t_f); got {n!r}")
        s = self.scene
        t = np.linspace(0.0, self.t_f, n)
        k = self.motion.kinematics(t)
        radius, beta = s.radius, s.tilt  # the flat's tilt orients the global frame
        normal_pos = radius - k["delta"]  # centre height above the flat
        sn, cs = math.sin(beta), math.cos(beta)
        import pandas as pd

        frame = pd.DataFrame({
            "t": t, "delta": k["delta"], "delta_dot": k["delta_dot"], "force": self.motion.force(t),
            "force_t": self.motion.tangential_force(t),
            "u_t": k["u_t"], "u_n": -k["delta"], "vc_t": k["vc_t"], "vc_n": k["vc_n"], "omega": k["omega"],
            "ve_t": k["vc_t"] - k["omega"] * radius, "ve_n": k["vc_n"],
            "X": normal_pos * sn + k["u_t"] * cs, "Y": normal_pos * cs - k["u_t"] * sn,
            "VX": k["vc_n"] * sn + k["vc_t"] * cs, "VY": k["vc_n"] * cs - k["vc_t"] * sn,
        })
        frame.attrs["units"] = dict(HISTORY_COLUMNS)
        return frame
