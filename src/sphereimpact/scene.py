"""The inputs of one impact: ball, flat, contact law, approach, and how to solve it.

Everything is in SI units except the flat's angle, which is given in degrees
because that is how the chapter (and every user) states it.  Construction
validates every field and raises :class:`ValueError` with one line naming the
parameter and its allowed range, so a bad input can never reach the solver.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, replace

import numpy as np

from .forces import FORCE_MODELS

#: Standard gravity [m/s^2], used when gravity is switched on without a value.
STANDARD_GRAVITY = 9.80665

#: Separation criteria: ``force`` ends contact when P returns to 0 (a
#: unilateral contact cannot pull), ``penetration`` when delta returns to 0.
SEPARATION_CRITERIA = ("force", "penetration")

#: Integration methods: ``closed`` is the exact linear solution (kelvin-voigt
#: only); the others are :func:`scipy.integrate.solve_ivp` methods.
METHODS = ("closed", "RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA")


#: Numeric Scene fields: (allowed range as stated in messages, vectorised test).  One table for the
#: scalar checks of :class:`Scene` and the array checks of sweeps, so both say the same thing.
RULES = {
    "mass": ("a finite number > 0 kg", lambda x: x > 0),
    "diameter": ("a finite number > 0 m", lambda x: x > 0),
    "inertia_factor": ("a finite number in (0, 2/3] (2/3 = 0.6666666666666666)", lambda x: (x > 0) & (x <= 2 / 3)),
    "angle": ("a finite number in [0, 90) degrees", lambda x: (x >= 0) & (x < 90)),
    "speed": ("a finite number > 0 m/s", lambda x: x > 0),
    "mu": ("a finite number >= 0", lambda x: x >= 0),
    "k": ("a finite number > 0 N/m", lambda x: x > 0),
    "b": ("a finite number >= 0 N s/m", lambda x: x >= 0),
    "ramp": ("a finite number > 0", lambda x: x > 0),
    "gravity": ("a finite number >= 0 m/s^2", lambda x: x >= 0),
}


def as_number(name: str, value) -> float:
    """``value`` as a Python float when it is a real number: int, float, a numpy scalar or a 0-d array.

    Booleans are refused (``True`` is not a number a user means), and so is anything else, with a
    ``TypeError`` naming the parameter and the type found.
    """
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number; got {type(value).__name__} {value!r}")
    return float(value)


def _check(name: str, value, allowed: str, ok) -> float:
    """``value`` as a float; ``ValueError`` unless it is finite and satisfies ``ok``."""
    number = as_number(name, value)
    if not math.isfinite(number) or not ok(number):
        raise ValueError(f"{name} must be {allowed}; got {value!r}")
    return number


def _check_choice(name: str, value, choices) -> None:
    if value not in choices:
        raise ValueError(f"{name} must be one of {', '.join(choices)}; got {value!r}")


def check_columns(columns: dict) -> None:
    """Validate arrays of scene parameters (as :class:`Scene` does one value), naming the first bad row.

    Parameters
    ----------
    columns : dict of str -> array_like
        Scene field -> values; numeric fields must be numbers, ``model`` and
        ``separation`` strings.

    Raises
    ------
    ValueError
        ``"<name> must be <range>; got <value> (row <i>)"``.
    """
    for name, values in columns.items():
        if name in RULES:
            allowed, ok = RULES[name]
            raw = np.asarray(values)
            if raw.dtype == bool or (raw.dtype == object and any(isinstance(v, (bool, np.bool_)) for v in raw.flat)):
                raise TypeError(f"{name} must be real numbers; got a boolean")
            try:
                arr = np.asarray(values, dtype=float)
            except (TypeError, ValueError):
                raise ValueError(f"{name} must be {allowed}; got a non-numeric value") from None
            with np.errstate(invalid="ignore"):
                bad = ~(np.isfinite(arr) & ok(arr))
            if bad.any():
                i = int(np.flatnonzero(bad)[0])
                raise ValueError(f"{name} must be {allowed}; got {float(arr[i])!r} (row {i})")
        elif name in ("model", "separation"):
            choices = tuple(FORCE_MODELS) if name == "model" else SEPARATION_CRITERIA
            unknown = sorted({str(v) for v in set(np.asarray(values, dtype=object).ravel().tolist())} - set(choices))
            if unknown:
                raise ValueError(f"{name} must be one of {', '.join(choices)}; got {unknown[0]!r}")
        else:
            raise ValueError(f"unknown scene parameter {name!r}; expected one of "
                             f"{', '.join([*RULES, 'model', 'separation'])}")


@dataclass(frozen=True)
class Scene:
    """One sphere striking a rigid inclined flat.

    Parameters
    ----------
    mass : float
        Ball mass m [kg], > 0.  Chapter: 0.145.
    diameter : float
        Ball diameter D [m], > 0.  Chapter: 0.063.
    inertia_factor : float
        alpha in I = alpha m R^2 [-], in (0, 2/3]: 2/5 solid, 2/3 thin shell
        (2/3 is the largest any mass distribution inside a sphere can give; the command line and the
        config also accept the fraction ``2/3``).
    angle : float
        Inclination beta of the flat to the horizontal [deg], in [0, 90).
    speed : float
        Vertical approach speed v of the centre [m/s], > 0.  The approach is
        v cos(beta) along the normal and v sin(beta) along the flat.
    mu : float
        Kinetic (Coulomb) friction coefficient [-], >= 0.  Chapter: 0.2.
    model : str
        Normal force law, a key of :data:`sphereimpact.forces.FORCE_MODELS`.
    k : float
        Contact stiffness [N/m], > 0.  Chapter: 60000.
    b : float
        Contact damping [N s/m], >= 0.  Chapter: 10.5.
    ramp : float
        Constant c in the modified damping ramp 1 - exp(-c delta / R) [-], > 0.
        Chapter: 100.  Ignored by models without a ramp.
    gravity : float
        Gravitational acceleration g [m/s^2], >= 0; 0 (off) by default.  The weight alone must not
        compress the contact beyond the radius (m g cos(beta) / k <= R).
    separation : str
        ``force`` or ``penetration``, see :data:`SEPARATION_CRITERIA`.
    """

    mass: float = 0.145
    diameter: float = 0.063
    inertia_factor: float = 0.4
    angle: float = 0.0
    speed: float = 3.0
    mu: float = 0.2
    model: str = "modified"
    k: float = 60000.0
    b: float = 10.5
    ramp: float = 100.0
    gravity: float = 0.0
    separation: str = "force"

    def __post_init__(self):
        for name, (allowed, ok) in RULES.items():
            object.__setattr__(self, name, _check(name, getattr(self, name), allowed, ok))
        _check_choice("model", self.model, tuple(FORCE_MODELS))
        _check_choice("separation", self.separation, SEPARATION_CRITERIA)
        static = self.mass * self.g_normal / self.k  # the spring's compression under the ball's weight alone
        if static > self.radius:
            raise ValueError(f"gravity: the ball's weight alone compresses the contact by m g cos(beta) / k = "
                             f"{static:.3g} m, more than its radius R = {self.radius:.3g} m: outside the model "
                             "(lower gravity or mass, or raise k)")

    # Derived quantities (SI) -------------------------------------------------
    @property
    def radius(self) -> float:
        """R = D / 2 [m]."""
        return 0.5 * self.diameter

    @property
    def inertia(self) -> float:
        """I = alpha m R^2 [kg m^2]."""
        return self.inertia_factor * self.mass * self.radius**2

    @property
    def beta(self) -> float:
        """Flat inclination [rad]."""
        return math.radians(self.angle)

    @property
    def v_normal(self) -> float:
        """Approach speed along the normal, v cos(beta) [m/s], > 0."""
        return self.speed * math.cos(self.beta)

    @property
    def v_tangent(self) -> float:
        """Approach speed along the flat, v sin(beta) [m/s], >= 0 (exactly 0 at 0 deg)."""
        return 0.0 if self.angle == 0 else self.speed * math.sin(self.beta)

    @property
    def g_normal(self) -> float:
        """Gravity component pressing the ball into the flat, g cos(beta) [m/s^2]."""
        return self.gravity * math.cos(self.beta)

    @property
    def g_tangent(self) -> float:
        """Gravity component along the flat (down-slope = +t), g sin(beta) [m/s^2]."""
        return 0.0 if self.angle == 0 else self.gravity * math.sin(self.beta)

    @property
    def omega_n(self) -> float:
        """Undamped natural frequency sqrt(k/m) [rad/s]."""
        return math.sqrt(self.k / self.mass)

    @property
    def zeta(self) -> float:
        """Damping ratio b / (2 sqrt(k m)) [-]."""
        return self.b / (2.0 * math.sqrt(self.k * self.mass))

    @property
    def has_tangential_motion(self) -> bool:
        """False for a normal impact (beta = 0): then there is no tangential state at all."""
        return self.angle != 0

    def force(self, delta, delta_dot):
        """Normal contact force P [N] of this scene's law at (delta [m], delta_dot [m/s])."""
        return FORCE_MODELS[self.model].force(delta, delta_dot, self)

    def stage_force(self, delta, delta_dot):
        """The law continued smoothly past delta = 0 [N], for integrator stages only (see ForceModel.continued)."""
        return FORCE_MODELS[self.model].continued(delta, delta_dot, self)

    def with_(self, **changes) -> "Scene":
        """A validated copy with some fields changed."""
        return replace(self, **changes)


#: Allowed tolerances.  Looser than 1e-2 the outputs are meaningless (rtol 0.5 moves the COR by 2e-3 and
#: can report a rebound faster than the approach); below 1e-16 atol is beneath double precision on the
#: O(1) dimensionless state, and rtol below 1e-13 beneath what the integrators honour.
RTOL_RANGE = "a finite number in [1e-13, 1e-2] (looser tolerances make the outputs meaningless)"
ATOL_RANGE = ("a finite number in [1e-16, 1e-2] (on the O(1) dimensionless state: looser is meaningless, "
              "tighter is below double precision)")


@dataclass(frozen=True)
class SolverOptions:
    """How to integrate the normal motion.

    Parameters
    ----------
    method : str
        One of :data:`METHODS`.  ``closed`` is exact and only for kelvin-voigt.
    rtol, atol : float
        Relative and absolute tolerances of :func:`scipy.integrate.solve_ivp`, rtol in [1e-13, 1e-2] and
        atol in [1e-16, 1e-2].
        ``atol`` applies to the dimensionless state (delta scaled by v_n/omega_n,
        delta_dot by v_n), so one value suits every ball and speed; the state
        is O(1), so atol = rtol.  The default (DOP853, 1e-10) is the cheapest
        setting meeting 1e-9 on every output in the work-precision study
        (``results/work_precision.csv``, notebook ``numerics``).
    max_step : float
        Largest step [s]; ``inf`` lets the method choose.
    """

    method: str = "DOP853"
    rtol: float = 1e-10
    atol: float = 1e-10
    max_step: float = math.inf

    def __post_init__(self):
        _check_choice("method", self.method, METHODS)
        object.__setattr__(self, "rtol", _check("rtol", self.rtol, RTOL_RANGE, lambda x: 1e-13 <= x <= 1e-2))
        object.__setattr__(self, "atol", _check("atol", self.atol, ATOL_RANGE, lambda x: 1e-16 <= x <= 1e-2))
        step = as_number("max_step", self.max_step)
        if not step > 0:  # also refuses nan
            raise ValueError(f"max_step must be a number > 0 s (inf allowed); got {self.max_step!r}")
        object.__setattr__(self, "max_step", step)
