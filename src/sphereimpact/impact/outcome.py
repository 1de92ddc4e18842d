"""The outputs of one impact, and its time histories in the contact and global frames.

Contact frame: t along the flat in the direction of the incoming tangential
motion (down-slope), n the outward normal of the flat.  Global frame: X
horizontal, Y vertical up, origin at the first contact point; the flat's normal
is n = (sin beta, cos beta) and t = (cos beta, -sin beta).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from .declarations import (NUMERIC_OUTPUTS, OUTPUT_KEYS, OUTPUT_UNITS, PARTNER_OUTPUTS,  # noqa: F401 (re-exported:
                           SCALAR_OUTPUTS, SOLVER_KEYS)                                # declared once there)
from .scene import Scene


#: A tangential contact whose work exceeds this fraction of the incoming kinetic energy made energy (above the
#: solvers' round-off and tolerances: the rigid contact's work is exact to about 1e-15 of it).
ENERGY_GAIN = 1e-8

#: Columns of :meth:`Outcome.history`, with units.
HISTORY_COLUMNS = {
    "t": "s", "delta": "m", "delta_dot": "m/s", "force": "N", "force_t": "N",
    "u_t": "m", "u_n": "m", "vc_t": "m/s", "vc_n": "m/s", "omega": "rad/s", "ve_t": "m/s", "ve_n": "m/s",
    "X": "m", "Y": "m", "VX": "m/s", "VY": "m/s",
}


class EndState(NamedTuple):
    """What a solver computed of one impact, or of many (each field a float, or arrays of one length), in SI
    units: the scene's incoming state, the normal motion's events and the tangential motion's end (a named tuple:
    a record made once per impact, at a fifth of a frozen dataclass's cost).
    :func:`outputs` derives every output from it, for ``simulate`` and for every sweep path alike.

    Attributes
    ----------
    mass, radius, inertia_factor : float or array
        m [kg], R [m] and alpha = I / (m R^2) [-].
    v_normal, v_tangent, spin, g_tangent : float or array
        Approach speed along the normal and along the flat [m/s], incoming spin [rad/s], gravity along the
        flat [m/s^2].
    t_m, delta_m, t_f : float or array
        Time of maximum compression [s], maximum compression [m], contact duration [s].
    vc_n, vc_t, omega_f : float or array
        The centre's velocity after impact along the normal and the flat [m/s], spin after impact [rad/s].
    u_t : float or array
        The centre's displacement along the flat over the contact [m] (its work against gravity along the
        flat; any value where ``g_tangent`` is 0).
    force_min, force_max : float or array
        Extremes of the normal force over the contact [N] (NaN where not computed).
    t_roll : float or array
        First instant the contact point stops slipping [s], NaN where it never does.
    switches : int or array
        Changes of tangential mode.
    regime : str or array of str
        The tangential mode at separation (see :class:`Outcome`).
    """

    mass: object
    radius: object
    inertia_factor: object
    v_normal: object
    v_tangent: object
    spin: object
    g_tangent: object
    t_m: object
    delta_m: object
    t_f: object
    vc_n: object
    vc_t: object
    omega_f: object
    u_t: object
    force_min: object
    force_max: object
    t_roll: object
    switches: object
    regime: object

    @classmethod
    def of_scene(cls, scene, **motion) -> "EndState":
        """The end state of one impact of ``scene`` (a :class:`Scene`), given what its motion computed."""
        return cls(mass=scene.mass, radius=scene.radius, inertia_factor=scene.inertia_factor,
                   v_normal=scene.v_normal, v_tangent=scene.v_tangent, spin=scene.spin, g_tangent=scene.g_tangent,
                   **motion)


def outputs(end: EndState) -> dict:
    """Every scalar output (:data:`SCALAR_OUTPUTS`) of an end state: the one place they are derived from what a
    solver computed, for one impact (floats) or many (arrays).

    ve_t = vc_t - omega_f R and ve_n = vc_n (the contact point), cor = vc_n / v_n, the rebound angles from the
    normal atan2(vc_t, vc_n) and atan2(ve_t, vc_n) [deg] and the centre's to the surface, 90 - atan2(vc_t, vc_n),
    ``beyond_radius`` = delta_m > R, ``energy_gained`` = work_t > ENERGY_GAIN x the incoming kinetic energy,
    and work_t, the work
    of the tangential contact force [J]: the change of tangential and rotational kinetic energy less the work
    of gravity along the flat, m g_t u_t.
    """
    inertia = end.inertia_factor * end.mass * end.radius ** 2
    ve_t = end.vc_t - end.omega_f * end.radius
    work = (0.5 * end.mass * (end.vc_t * end.vc_t - end.v_tangent ** 2) + 0.5 * inertia * end.omega_f * end.omega_f
            - end.mass * end.g_tangent * end.u_t - 0.5 * inertia * end.spin * end.spin)
    rebound = _degrees_atan2(end.vc_t, end.vc_n)
    return {"t_m": end.t_m, "delta_m": end.delta_m, "t_f": end.t_f, "vc_t": end.vc_t, "vc_n": end.vc_n,
            "ve_t": ve_t, "ve_n": end.vc_n, "omega_f": end.omega_f, "cor": end.vc_n / end.v_normal,
            "regime": end.regime, "t_roll": end.t_roll, "force_min": end.force_min, "force_max": end.force_max,
            "beyond_radius": end.delta_m > end.radius, "switches": end.switches,
            "rebound_angle": rebound, "rebound_angle_contact": _degrees_atan2(ve_t, end.vc_n),
            "rebound_angle_to_surface": 90.0 - rebound, "work_t": work,
            "energy_gained": gains_energy(work, end.mass, (end.v_normal ** 2 + end.v_tangent ** 2) ** 0.5, inertia,
                                          end.spin)}


def gains_energy(work_t, mass, speed, inertia, spin):
    """True where the tangential contact's work ``work_t`` [J] exceeds :data:`ENERGY_GAIN` of the incoming kinetic
    energy (m v^2 + I omega_0^2) / 2: the model made energy (floats or arrays)."""
    return work_t > ENERGY_GAIN * (0.5 * mass * speed * speed + 0.5 * inertia * spin * spin)


def _degrees_atan2(y, x):
    """atan2(y, x) in degrees, for floats (math) or arrays (numpy)."""
    if (isinstance(y, float) and isinstance(x, float)) or (np.ndim(y) == 0 and np.ndim(x) == 0):  # floats first: cheap
        return math.degrees(math.atan2(y, x))
    return np.degrees(np.arctan2(y, x))


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
        atan2(vc_t, vc_n) and atan2(ve_t, vc_n), in (-90, 90); negative when the tangential velocity is
        reversed (the ball kicks back against its incoming tangential motion).
    rebound_angle_to_surface : float
        The centre's rebound direction as its angle to the surface [deg], 90 - rebound_angle, in (0, 180): the
        convention of ``angle_to_surface`` (sports); above 90 the ball leaves backwards.
    work_t : float
        Work of the tangential contact force on the ball [J] (<= 0: friction and a compliant contact's
        hysteresis take energy): the change of translational-tangential and rotational kinetic energy
        less the work of gravity along the flat.
    energy_gained : bool
        True when work_t is positive beyond :data:`ENERGY_GAIN` of the incoming kinetic energy: the tangential
        model made energy, which no passive contact does (a known artefact of some spring models;
        :func:`sphereimpact.simulate` warns with an :class:`~sphereimpact.errors.EnergyGainWarning`).
    method, rtol, atol, nfev, wall_time
        Solver statistics; ``wall_time`` [s] covers the whole call.
    partner_vc_t, partner_vc_n, partner_omega_f : float or None
        With a partner sphere (:attr:`Scene.partner_mass`): its centre's velocity along t and n [m/s] and its
        spin [rad/s] after the impact; None on the flat.  Then ``vc_t``, ``vc_n`` and ``omega_f`` are the
        ball's (the partner at rest before), and ``ve_t``, ``ve_n``, ``cor``, the rebound angles, ``work_t`` and
        the normal outputs are of the relative motion (:attr:`Scene.reduced`): ``ve_t`` is the slip of the
        ball's surface on the partner's, and the COR is of the relative normal velocities.
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
    rebound_angle_to_surface: float
    work_t: float
    energy_gained: bool
    method: str
    rtol: float
    atol: float
    nfev: int
    wall_time: float
    scene: Scene = field(repr=False, compare=False)
    motion: object = field(repr=False, compare=False)
    partner_vc_t: float | None = None
    partner_vc_n: float | None = None
    partner_omega_f: float | None = None

    @property
    def chapter_ball(self) -> tuple:
        """The parts of the ball the scene took from the chapter's, its user not giving them
        (:attr:`Scene.chapter_ball`): the outcome is the chapter's ball's where this is not empty."""
        return self.scene.chapter_ball

    @classmethod
    def from_motion(cls, motion, wall_time: float) -> "Outcome":
        """Read the outputs off a solved contact motion (reduced or planar), through :func:`outputs`.

        ``motion`` has ``scene``, ``t_m``, ``t_f``, ``t_roll``, ``regime``, ``switches``,
        ``grid``, ``stats``, ``force(t)``, ``force_extremes()`` (the normal force's least and greatest values [N])
        and ``ends()`` (floats: delta at t_m, ``delta_m``, and ``vc_n``, ``vc_t``, ``omega`` and ``u_t`` at t_f).
        """
        s = motion.scene
        ends = motion.ends()
        force_min, force_max = motion.force_extremes()
        vc_n = ends["vc_n"]
        if s.law.passive and s.g_normal == 0:  # a passive law rebounds no faster than it came: COR <= 1, where
            vc_n = min(vc_n, s.reduced.v_normal)  # the integrator's error alone crossed it (ContactLaw.passive)
        end = EndState.of_scene(
            s, t_m=motion.t_m, delta_m=ends["delta_m"], t_f=motion.t_f, vc_n=vc_n,
            force_min=force_min, force_max=force_max, vc_t=ends["vc_t"], omega_f=ends["omega"], u_t=ends["u_t"],
            t_roll=math.nan if motion.t_roll is None else motion.t_roll, switches=int(motion.switches),
            regime=motion.regime)
        values = outputs(end)
        values["t_roll"] = motion.t_roll  # None where it never happens, as the dataclass says
        values["beyond_radius"] = bool(values["beyond_radius"])
        return cls(**values, wall_time=wall_time, scene=s, motion=motion, **motion.stats)

    @property
    def e_t(self) -> float:
        """The centre's tangential coefficient of restitution vc_t / v_t [-] (what Kharaz et al. and Chung & Ooi
        report); NaN at normal incidence, where v_t = 0."""
        v_t = self.scene.v_tangent
        return self.vc_t / v_t if v_t > 0 else math.nan

    def output_keys(self) -> tuple:
        """The names of its outputs: :data:`OUTPUT_KEYS` and, with a partner sphere,
        :data:`~sphereimpact.impact.pair.PARTNER_OUTPUTS` (:meth:`to_dict`'s keys)."""
        return (*OUTPUT_KEYS, *(PARTNER_OUTPUTS if self.partner_vc_n is not None else ()))

    def to_dict(self) -> dict:
        """The outputs as plain Python values, keyed by :meth:`output_keys`."""
        out = {}
        for key in self.output_keys():
            value = getattr(self, key)
            out[key] = float(value) if isinstance(value, (float, np.floating)) else value
        return out

    def history(self, n: int = 401):
        """Time histories on ``n`` uniform instants over [0, t_f]: a DataFrame whose columns are
        :data:`HISTORY_COLUMNS` (SI units, recorded in its ``attrs["units"]``).  With a partner sphere, the
        relative motion: the reduced sphere's (:attr:`Scene.reduced`) on the partner's surface.

        Raises
        ------
        ValueError
            ``n`` is not an integer >= 2 (the two ends of the contact at least).
        """
        if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)) or n < 2:
            raise ValueError(f"n must be an integer >= 2 (instants from 0 to t_f); got {n!r}")
        s = self.motion.scene
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
