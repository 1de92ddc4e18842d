"""The inputs of one impact: ball, flat, contact law, approach, and how to solve it.

Everything is in SI units except the flat's angle, which is given in degrees
because that is how the chapter (and every user) states it.  Construction
validates every field and raises :class:`ValueError` with one line naming the
parameter and its allowed range, so a bad input can never reach the solver.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, fields
from functools import cached_property

import numpy as np

from ..contact.laws import LAWS, PARAMETER_NAMES, Spring
from ..errors import UnitWarning
from ..contact.declared import own_parameters, settings as declared_settings
from ..contact.separation import Separation
from ..integrators import method_names
from ..contact.tangential import (KAPPA_FROM, STIFFNESS, TANGENTIAL_PARAMETERS, TANGENTIALS, kappa_from_poisson,
                                  kappa_from_shear_modulus)
from .inputs import (PARTNER_RULES, PATH_RULES, RULES, _check, _check_choice, as_number, density_problem,
                     law_parameters, magnitude_problem, scale_problem)
from .pair import PARTNER_FIELDS, missing_partner, partner_gravity, reduced_body, stray_partner

#: Scene fields the normal motion does not read (:attr:`Scene.normal_problem`); of ``parameters`` the law's are read,
#: the tangential model's are not.
TANGENTIAL_ONLY = ("mu", "tangential", "spin", "parameters")
#: The built-in models' parameter names: the law parameters the laws' checks resolve together (k, b, ramp, chi,
#: exponent, and modulus for k) and the three ways of giving the tangential stiffness (kappa, poisson,
#: shear_modulus).  A scene holds them in ``parameters`` as it holds a plug-in's own; tables, JSON and
#: :meth:`Scene.as_dict` write each of them always (empty where the scene's models do not use it).
BUILT_IN = (*PARAMETER_NAMES, *TANGENTIAL_PARAMETERS)
#: Standard gravity [m/s^2], used when gravity is switched on without a value.
STANDARD_GRAVITY = 9.80665
#: True while Scenes are built whose bodies were judged already, or are no body (:func:`bodies_judged`).
_JUDGED: ContextVar[bool] = ContextVar("bodies_judged", default=False)


@contextmanager
def bodies_judged():
    """Within it, a Scene built does not judge its bodies' density again: a copy (:meth:`Scene.with_`), whose bodies
    were judged when it was built; a pair's reduced sphere, which is no body; a sweep's rows, judged once per table."""
    token = _JUDGED.set(True)
    try:
        yield
    finally:
        _JUDGED.reset(token)


class ChapterValue(float):
    """A value the scene took from the chapter's because its user did not give it: the ball's mass (0.145 kg) and
    diameter (0.063 m), the stiffness and damping of a law whose defaults are the chapter's (eq. 4.1/4.2's
    k = 60000 N/m, b = 10.5 N s/m), and the approach speed (3 m/s).  A float in every computation, told apart by its
    type, so that a scene knows which parts of its ball and approach are undescribed (:attr:`Scene.chapter_ball`,
    :attr:`Scene.chapter_approach`) and every door can say so: only ``simulate`` runs the chapter's scene unasked
    (:func:`sphereimpact.impact.ball.undescribed`)."""

    __slots__ = ()

    def __repr__(self) -> str:
        return float.__repr__(self)


#: The chapter's ball and its approach speed, as the Scene's defaults.
CHAPTER_MASS, CHAPTER_DIAMETER, CHAPTER_SPEED = ChapterValue(0.145), ChapterValue(0.063), ChapterValue(3.0)
#: The fields of a scene's ball that can be the chapter's (:attr:`Scene.chapter_ball`): its mass and diameter, and
#: a law's stiffness and damping where their defaults are the chapter's.
CHAPTER_BALL = ("mass", "diameter", *PARAMETER_NAMES)


class FrozenMapping(Mapping):
    """Names to values, read-only and hashable as the frozen Scene and SolverOptions that hold them (their own
    model parameters, their models' settings)."""

    __slots__ = ("_values",)

    def __init__(self, values=()):
        self._values = dict(values)

    def __getitem__(self, name: str) -> float:
        return self._values[name]

    def __contains__(self, name) -> bool:  # the dict's own test: Mapping's goes through __getitem__ and KeyError
        return name in self._values

    def get(self, name, default=None):
        return self._values.get(name, default)

    def __iter__(self):
        return iter(self._values)

    def __len__(self) -> int:
        return len(self._values)

    def __hash__(self) -> int:
        return hash(tuple(sorted(self._values.items())))

    def __repr__(self) -> str:
        return repr(self._values)


@dataclass(frozen=True, init=False)
class Scene:
    """One sphere striking a rigid inclined flat, or a partner sphere at rest.

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
        Inclination beta of the flat to the horizontal [deg], in [0, 90), the ball arriving vertically (the
        chapter's description): its incidence from the flat's normal is beta too.
    speed : float
        Approach speed v of the centre along its path [m/s], > 0 (vertical unless ``incidence`` or
        ``angle_to_surface`` is given).  The approach is v cos(theta) along the normal and v sin(theta)
        along the flat, theta the incidence.
    mu : float
        Kinetic (Coulomb) friction coefficient [-], >= 0.  Chapter: 0.2.
    model : str
        Normal force law, a key of :data:`sphereimpact.contact.laws.LAWS` (``kelvin-voigt``, ``modified``,
        ``linear-hunt-crossley``, ``hertz``, ``hunt-crossley`` or a registered one).
    k, b, ramp, chi, exponent, modulus : float or None
        The built-in laws' parameters, given by name like any parameter of a law or tangential model (see
        ``parameters``); each law declares which it uses, their units, ranges and defaults, and a
        parameter the law does not use is refused.  None takes the law's default (an error where it has
        none).  ``k``: stiffness constant of the spring term [N/m for linear laws, N/m^n for Hertz laws;
        chapter 60000 N/m]; ``b``: damping [N s/m], chapter 10.5; ``ramp``: c in 1 - exp(-c delta / R),
        chapter 100; ``chi``: Hunt-Crossley damping factor [s/m]; ``exponent``: n of k delta^n;
        ``modulus``: effective modulus E* [Pa] of a Hertz law, instead of k.
    gravity : float
        Gravitational acceleration g [m/s^2], >= 0; 0 (off) by default.  The weight alone must not
        compress the contact beyond the radius (m g cos(beta) / k <= R).
    separation : Separation or str
        When contact ends: ``force`` (P returns to 0, default) or ``penetration`` (delta returns to 0), see
        :class:`~sphereimpact.contact.separation.Separation`; a name is parsed into the criterion.
    tangential : str
        Tangential contact model, a key of :data:`sphereimpact.contact.tangential.TANGENTIALS`: ``rigid``
        (default, the chapter's), ``linear`` (needs a linear-spring law), ``mindlin`` (needs a Hertz spring,
        exponent 3/2) or a registered one; each declares the law it needs.
    kappa, poisson, shear_modulus : float or None
        The tangential stiffness of a compliant model, in one of the ways it accepts: kappa = k_t / k_n [-]
        > 0; Poisson's ratio nu [-] in (-1, 0.5] of like materials, kappa = 2 (1 - nu) / (2 - nu) (2/3 for
        rubber); or (Hertz-spring models) the effective shear modulus G* [Pa], kappa = 4 G* / E* with
        E* = 3 k / (4 sqrt(R)).  ``kappa`` then holds the value used.  Refused for ``rigid``.
    spin : float
        Incoming spin omega_0 [rad/s] about the axis normal to the plane of motion, positive for topspin
        (the sense in which a ball rolls along +t, the direction of the incoming tangential motion; on a
        level flat approached normally, +t is the direction the topspin drives the ball), negative for
        backspin; 0 by default.  The contact point first slips at v_t - omega_0 R.
    incidence, angle_to_surface : float or None
        The approach described by the ball's path, on a level flat: its incidence from the flat's normal
        [deg] in [0, 90) (Kharaz's and the DEM codes' convention), or its angle to the surface [deg] in
        (0, 90] (the sports convention, 90 - incidence), with ``speed`` along the path.  At most one of
        them, and then ``angle`` stays 0: exactly one description of the approach per scene.
    partner_mass, partner_diameter : float or None
        A partner sphere the ball strikes instead of the flat [kg], [m], both > 0, or None (the rigid flat).  The
        partner starts at rest apart from its spin (any collision can be shifted to that frame); the contact
        frame is the partner's surface's (n its outward normal at the contact, t along the incoming tangential
        motion).  The pair is solved exactly as one sphere on the flat but for the line of centres, held fixed
        (:attr:`reduced`, :mod:`sphereimpact.impact.pair`; ``body='planar'`` frees both centres): the law's ``k``,
        ``modulus`` and ``ramp`` are the contact's, at the Hertz radius R* = R1 R2 / (R1 + R2).  Gravity is
        refused with a partner.
    partner_inertia_factor : float
        The partner's alpha in I = alpha m R^2 [-], in (0, 2/3]; 0.4 by default.
    partner_spin : float
        The partner's spin [rad/s] in the ball's rotational sense (two spheres turning the same way rub at the
        contact: the slip is v_t - omega_0 R - partner_spin R2); 0 by default.
    parameters : mapping of str to float
        The law's and the tangential model's parameters (:mod:`sphereimpact.contact.parameters`), built-in or a
        plug-in's alike: given here or by name (``Scene(k=6e4)`` is ``Scene(parameters={"k": 6e4})``), checked,
        with their defaults filled in (k from ``modulus``, kappa from ``poisson`` or ``shear_modulus``), and each
        read as ``scene.name``: None where the scene's models do not use a parameter some registered model
        declares.  Holds every parameter the scene's models use, and the other ways of giving one that were given.
    """

    mass: float = CHAPTER_MASS
    diameter: float = CHAPTER_DIAMETER
    inertia_factor: float = 0.4
    angle: float = 0.0
    speed: float = CHAPTER_SPEED
    mu: float = 0.2
    model: str = "modified"
    gravity: float = 0.0
    separation: Separation = Separation.FORCE
    tangential: str = "rigid"
    spin: float = 0.0
    incidence: float | None = None
    angle_to_surface: float | None = None
    partner_mass: float | None = None
    partner_diameter: float | None = None
    partner_inertia_factor: float = 0.4
    partner_spin: float = 0.0
    parameters: Mapping[str, float] = FrozenMapping()

    def __init__(self, parameters: Mapping[str, float] = FrozenMapping(), **given):
        """The fields by keyword; any other keyword is a parameter of the scene's models, as a key of ``parameters``
        is (given both ways, refused)."""
        if not isinstance(parameters, Mapping):
            raise TypeError(f"parameters must be a mapping of name to value; got {type(parameters).__name__}")
        named = {name: given.pop(name) for name in list(given) if name not in FIELDS}
        twice = [name for name in named if name in parameters and named[name] is not None]
        if twice:
            raise ValueError(f"{twice[0]} is given twice: by name and in parameters")
        for name, default in FIELD_DEFAULTS.items():
            object.__setattr__(self, name, given.get(name, default))
        raw = {name: value for name, value in {**parameters, **named}.items() if value is not None}
        object.__setattr__(self, "parameters", FrozenMapping(raw))  # as given: resolved by __post_init__
        self.__post_init__()

    def __post_init__(self):
        self._check_numbers(RULES)
        slip = None if _JUDGED.get() else density_problem(self.mass, self.diameter)
        if slip:  # stack: __post_init__, __init__, the caller
            warnings.warn(slip, UnitWarning, stacklevel=3)
        self._check_path()
        if self._check_partner():
            self._take_reduced()
            return
        _check_choice("model", self.model, tuple(LAWS))
        object.__setattr__(self, "separation", Separation.parse(self.separation))
        raw = dict(self.parameters)
        own = self._own_parameters(raw)
        given = {name: None if raw.get(name) is None or type(raw[name]) is ChapterValue
                 else as_number(name, raw[name]) for name in PARAMETER_NAMES}
        values = law_parameters(self.model, given, self.radius)
        chapter = _chapter_parameters(self.law, given)
        resolved = {}
        for name in PARAMETER_NAMES:
            value = float(values[name])
            if not math.isnan(value):
                resolved[name] = ChapterValue(value) if name in chapter else value
        self._hold(resolved)
        self._check_scales()
        self._check_weight()
        self._hold(resolved | self._resolve_kappa(raw) | own)

    def _check_numbers(self, names) -> None:
        """Check the numeric fields among ``names`` (:data:`RULES`, in its order), each held as a float, then their
        magnitudes together."""
        for name, (allowed, ok) in RULES.items():
            if name in names:
                value = getattr(self, name)
                checked = _check(name, value, allowed, ok)  # the chapter's value stays marked as such
                object.__setattr__(self, name, value if type(value) is ChapterValue else checked)
        problem = magnitude_problem(self.mass, self.speed, self.diameter, self.spin)
        if problem:
            raise ValueError(problem)

    def _check_weight(self) -> None:
        """Refuse a ball whose weight alone presses the contact beyond its radius."""
        weight = self.mass * self.g_normal  # pressing the ball into the flat [N]
        if weight > 0 and float(self.force(self.radius, 0.0)) < weight:  # the spring alone cannot hold it at R
            raise ValueError(f"gravity: the ball's weight alone compresses the contact beyond its radius "
                             f"R = {self.radius:.3g} m (m g cos(beta) = {weight:.3g} N, more than the "
                             f"'{self.model}' spring's {float(self.force(self.radius, 0.0)):.3g} N at delta = R): "
                             "outside the model (lower gravity or mass, or raise k)")

    def _hold(self, values: dict) -> None:
        """Hold the resolved ``values`` as the scene's ``parameters``, each also read as ``scene.name`` (an instance
        attribute: the force laws read them in every evaluation)."""
        for name in (*self.__dict__.get("parameters", ()), *_FROM_PARAMETERS):  # the values held before, and what
            self.__dict__.pop(name, None)  # was derived from them: read no longer
        object.__setattr__(self, "parameters", FrozenMapping(values))
        self.__dict__.update(values)

    def _check_partner(self) -> bool:
        """Check the partner's fields; True when the scene has a partner sphere."""
        for name, (allowed, ok) in PARTNER_RULES.items():
            if getattr(self, name) is not None:
                object.__setattr__(self, name, _check(name, getattr(self, name), allowed, ok))
        if self.partner_mass is None and self.partner_diameter is None:
            for name in PARTNER_FIELDS[2:]:
                if getattr(self, name) != Scene.__dataclass_fields__[name].default:
                    raise ValueError(stray_partner(name))
            return False
        if self.partner_mass is None or self.partner_diameter is None:
            raise ValueError(missing_partner("partner_mass" if self.partner_mass is None else "partner_diameter"))
        if self.gravity != 0:
            raise ValueError(partner_gravity(self.gravity))
        slip = None if _JUDGED.get() else density_problem(self.partner_mass, self.partner_diameter, "partner sphere")
        if slip:
            warnings.warn(slip, UnitWarning, stacklevel=4)
        return True

    def _take_reduced(self) -> None:
        """Solve the pair as one sphere on the flat (:attr:`reduced`): build it, which checks the law and the
        tangential model at the contact's mass and radius, and take its resolved parameters."""
        m_star, r_star, alpha_star, spin_star = reduced_body(
            self.mass, self.radius, self.inertia_factor, self.spin, self.partner_mass, 0.5 * self.partner_diameter,
            self.partner_inertia_factor, self.partner_spin)
        own = {f.name: getattr(self, f.name) for f in fields(self) if f.name not in PARTNER_FIELDS}
        with bodies_judged():  # the reduced sphere is no body: each body's density was judged above
            reduced = Scene(**own | dict(mass=m_star, diameter=2.0 * r_star, inertia_factor=alpha_star,
                                         spin=spin_star))
        object.__setattr__(self, "separation", reduced.separation)
        self._hold(dict(reduced.parameters))
        self.__dict__["_reduced"] = reduced

    @property
    def chapter_ball(self) -> tuple:
        """The parts of the ball this scene took from the chapter's because its user did not give them (``mass``,
        ``diameter``, and the law's stiffness ``k`` and damping where they are the chapter's defaults): empty when
        the ball is described (:class:`ChapterValue`)."""
        return tuple(name for name in CHAPTER_BALL if type(getattr(self, name)) is ChapterValue)

    @property
    def chapter_approach(self) -> tuple:
        """``("speed",)`` when this scene took the chapter's approach speed (3 m/s) because its user did not give
        one, else empty (:class:`ChapterValue`)."""
        return ("speed",) if type(self.speed) is ChapterValue else ()

    @property
    def reduced(self) -> "Scene":
        """The one sphere on the rigid flat whose impact is this scene's relative motion: the scene itself without
        a partner; with one, the sphere of mass m*, radius R*, inertia factor alpha* and spin w*
        (:func:`~sphereimpact.impact.pair.reduced_body`)."""
        return self.__dict__.get("_reduced", self)

    @property
    def has_partner(self) -> bool:
        """True when the ball strikes a partner sphere, not the flat."""
        return self.partner_mass is not None

    def _own_parameters(self, raw: dict) -> dict:
        """The law's and the tangential model's parameters beyond the built-in ones (:data:`BUILT_IN`, which
        their own checks take): each given one declared, each checked, the defaults filled in, a required one
        present."""
        law, model = LAWS.law(self.model), TANGENTIALS.model(self.tangential)
        declared = {p.name: (p, f"model {self.model!r}") for p in law.own_parameters}
        declared |= {p.name: (p, f"tangential {self.tangential!r}") for p in model.own_parameters}
        for name, (_, owner) in declared.items():
            if name in FIELDS:
                raise ValueError(f"{owner} declares a parameter {name!r}, the name of a Scene field: rename it")
        for name in raw:
            if name not in declared and name not in BUILT_IN:
                owners = [f"{p.name} ({owner})" for p, owner in declared.values()]
                raise ValueError(f"{name} is not a parameter of model {self.model!r} or tangential "
                                 f"{self.tangential!r}; their own parameters: {', '.join(owners) or 'none'}")
        values = {}
        for name, (parameter, owner) in declared.items():
            value = raw.get(name)
            if value is None:
                if parameter.default is None:
                    raise ValueError(f"{name} is required by {owner}: {parameter.doc} [{parameter.unit}]")
                value = parameter.default
            values[name] = _check(name, value, parameter.range_text, parameter.ok)
        return values

    def __getattr__(self, name: str):
        """A parameter some registered model declares and this scene's models do not use: None (the ones they use
        are read as attributes, :meth:`_hold`)."""
        if not name.startswith("_") and (name in BUILT_IN or name in own_parameters()):
            return None
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def _check_path(self) -> None:
        """At most one path description, and then a level flat: one description of the approach."""
        given = []
        for name, (allowed, ok) in PATH_RULES.items():
            if getattr(self, name) is not None:
                object.__setattr__(self, name, _check(name, getattr(self, name), allowed, ok))
                given.append(name)
        if len(given) > 1:
            raise ValueError("give incidence or angle_to_surface, not both (angle_to_surface = 90 - incidence)")
        if given and self.angle != 0:
            raise ValueError(f"give the flat's tilt (angle, the ball arriving vertically) or the ball's path "
                             f"({given[0]}, on a level flat), not both; got angle {self.angle!r} and "
                             f"{given[0]} {getattr(self, given[0])!r}")

    def _check_scales(self) -> None:
        with np.errstate(all="ignore"):
            try:
                w = float(self.law.frequency(self))
            except ArithmeticError:  # Python floats raise where numpy returns 0 or inf
                w = math.nan
        problem = scale_problem(self.mass, self.v_normal, w, self.law)
        if problem:
            raise ValueError(problem)

    def _resolve_kappa(self, raw: dict) -> dict:
        """Check the tangential model against the law; its stiffness's values: the ways it was given, and ``kappa``
        from whichever way that was."""
        model = TANGENTIALS.model(self.tangential)
        given = {}
        for parameter in STIFFNESS:
            if raw.get(parameter.name) is not None:
                given[parameter.name] = _check(parameter.name, raw[parameter.name], parameter.range_text,
                                               parameter.ok)
        unused = [name for name in given if name not in model.parameter_names]
        if unused and not model.stiffness_parameters:
            raise ValueError(f"{unused[0]} is a parameter of the compliant tangential models "
                             f"({', '.join(TANGENTIALS.taking(unused[0]))}); this scene's tangential model is "
                             f"{self.tangential!r}")
        refusal = model.refusal(self.law, self)
        if refusal:
            raise ValueError(refusal)
        if not model.stiffness_parameters:
            return given
        if unused:
            name = unused[0]
            taking = " or ".join(f"'{other}'" for other in TANGENTIALS.taking(name))
            raise ValueError(f"{name} sets kappa of tangential {taking} ({KAPPA_FROM[name]}); for "
                             f"{self.tangential!r} give {' or '.join(model.parameter_names)}")
        derived = [name for name in ("poisson", "shear_modulus") if name in given]
        if len(derived) > 1:
            raise ValueError("give one of kappa, poisson or shear_modulus, not several")
        if derived:
            name = derived[0]
            value = (kappa_from_poisson(given[name]) if name == "poisson"
                     else kappa_from_shear_modulus(given[name], self.k, self.radius))
            if "kappa" in given and given["kappa"] != value:  # equal: a scene copied with both
                raise ValueError(f"give kappa or {name}, not both (kappa from {name} = {value:.6g})")
            given["kappa"] = float(value)
        elif "kappa" not in given:
            others = [name for name in model.parameter_names if name != "kappa"]
            raise ValueError(f"kappa is required by tangential {self.tangential!r}: k_t / k_n, > 0 "
                             "(2 (1 - nu) / (2 - nu) = 0.667 for rubber, nu = 0.5), or give " + " or ".join(others))
        return {name: given[name] for name in TANGENTIAL_PARAMETERS if name in given}

    # Derived quantities (SI) -------------------------------------------------
    # The geometric ones are cached: the post-processing of one impact reads them thousands of times, and
    # what they depend on (mass, diameter, inertia_factor, angle, speed, gravity) is set once, first thing
    # in __post_init__.
    @cached_property
    def radius(self) -> float:
        """R = D / 2 [m]."""
        return 0.5 * self.diameter

    @cached_property
    def inertia(self) -> float:
        """I = alpha m R^2 [kg m^2]."""
        return self.inertia_factor * self.mass * self.radius**2

    @cached_property
    def incidence_deg(self) -> float:
        """Incidence of the approach from the flat's normal [deg]: ``incidence``, 90 - ``angle_to_surface``, or
        the flat's tilt ``angle`` for a vertical approach."""
        if self.incidence is not None:
            return self.incidence
        if self.angle_to_surface is not None:
            return 90.0 - self.angle_to_surface
        return self.angle

    @cached_property
    def beta(self) -> float:
        """Incidence of the approach [rad] (the flat's inclination when the ball arrives vertically)."""
        return math.radians(self.incidence_deg)

    @cached_property
    def tilt(self) -> float:
        """The flat's inclination to the horizontal [rad]: it sets gravity's components."""
        return math.radians(self.angle)

    @cached_property
    def v_normal(self) -> float:
        """Approach speed along the normal, v cos(theta) [m/s], > 0."""
        return self.speed * math.cos(self.beta)

    @cached_property
    def v_tangent(self) -> float:
        """Approach speed along the flat, v sin(theta) [m/s], >= 0 (exactly 0 at normal incidence)."""
        return 0.0 if self.incidence_deg == 0 else self.speed * math.sin(self.beta)

    @cached_property
    def g_normal(self) -> float:
        """Gravity component pressing the ball into the flat, g cos(tilt) [m/s^2]."""
        return self.gravity * math.cos(self.tilt)

    @cached_property
    def g_tangent(self) -> float:
        """Gravity component along the flat (down-slope = +t), g sin(tilt) [m/s^2]."""
        return 0.0 if self.angle == 0 else self.gravity * math.sin(self.tilt)

    @cached_property
    def law(self):
        """The contact law (:class:`sphereimpact.contact.laws.ContactLaw`), the one ``model`` named when the scene was
        built."""
        return LAWS[self.model]

    @cached_property
    def frequency(self) -> float:
        """1 / T [1/s], T the law's natural contact time (omega_n for a linear spring)."""
        return float(self.law.frequency(self.reduced))

    @property
    def time_scale(self) -> float:
        """The law's natural contact time T [s] (1 / omega_n for a linear spring)."""
        return 1.0 / self.frequency

    @property
    def family(self) -> dict:
        """The law's dimensionless numbers fixing the weightless normal motion (e.g. zeta and lam): a new dict each
        read, of the numbers computed once."""
        return dict(self._family)

    @cached_property
    def _family(self) -> dict:
        return {name: float(value) for name, value in self.law.family(self.reduced).items()}

    @property
    def omega_n(self) -> float:
        """Undamped natural frequency sqrt(k/m) [rad/s] of a linear spring (ValueError for a Hertz law)."""
        self._linear_spring("omega_n")
        return math.sqrt(self.k / self.reduced.mass)

    @property
    def zeta(self) -> float:
        """Damping ratio b / (2 sqrt(k m)) [-] of a linear spring-damper law (ValueError otherwise)."""
        self._linear_spring("zeta")
        if self.b is None:
            raise ValueError(f"zeta: model {self.model!r} has no damping coefficient b")
        return self.b / (2.0 * math.sqrt(self.k * self.reduced.mass))

    def _linear_spring(self, what: str) -> None:
        if self.law.spring is not Spring.LINEAR:
            raise ValueError(f"{what} is defined for a linear spring; model {self.model!r} has a Hertz spring "
                             "(use frequency)")

    @property
    def has_tangential_motion(self) -> bool:
        """False for a normal impact without spin on a level or vertically approached flat: then there is no
        tangential state at all."""
        return self.incidence_deg != 0 or self.reduced.spin != 0 or self.g_tangent != 0

    @property
    def normal_problem(self) -> tuple:
        """What the normal motion depends on, hashable: every field but friction, the tangential contact, the spin
        and the tangential model's own parameters, which the normal motion does not read (the normal force law
        sees delta and its rate alone).  Scenes with equal normal problems have the same normal motion
        (:func:`sphereimpact.impact.solve.reusing_normal_motions` shares it)."""
        law = set(self.law.parameter_names)
        return (tuple((f.name, getattr(self, f.name)) for f in fields(self) if f.name not in TANGENTIAL_ONLY)
                + (tuple(sorted((name, value) for name, value in self.parameters.items() if name in law)),))

    @property
    def slip0(self) -> float:
        """The contact point's tangential velocity at first contact, v_t - omega_0 R [m/s] (relative to the
        partner's surface: v_t - omega_0 R - partner_spin R2)."""
        return self.v_tangent - self.reduced.spin * self.reduced.radius

    def force(self, delta, delta_dot):
        """Normal contact force P [N] of this scene's law at (delta [m], delta_dot [m/s])."""
        return self.law.force(delta, delta_dot, self.reduced)

    def stage_force(self, delta, delta_dot):
        """The law continued smoothly past delta = 0 [N], for integrator stages only (see ContactLaw.continued)."""
        return self.law.continued(delta, delta_dot, self.reduced)

    def as_dict(self) -> dict:
        """The fields and the parameters as plain values, for JSON and tables, in :data:`SCENE_KEYS`' order (every
        built-in parameter, None where unused; the partner's fields left out without a partner), then the
        plug-ins' parameters the scene has: ``Scene(**scene.as_dict())`` is the scene again."""
        out = {name: getattr(self, name) for name in SCENE_KEYS if self.has_partner or name not in PARTNER_FIELDS}
        return out | {name: value for name, value in self.parameters.items() if name not in BUILT_IN}

    def with_(self, **changes) -> "Scene":
        """A validated copy with some fields changed.

        A parameter is changed by its name (``with_(k=...)``, ``with_(name=value)`` for a plug-in's), None dropping
        it.  The parameters that the new law and tangential model do not use are dropped (changing ``model`` or
        ``tangential='rigid'``), the others carry over; ``modulus`` is dropped when ``k`` changes, k follows the
        modulus at a new diameter, and kappa given as poisson or shear_modulus is recomputed.  Giving a path
        (``incidence`` or ``angle_to_surface``) levels the flat and drops the other path; giving a tilt ``angle``
        drops the path.
        """
        named = {name: changes.pop(name) for name in list(changes) if name not in FIELDS}
        kept = "parameters" not in changes and not named  # the parameters carried over as they are
        values = dict(changes.pop("parameters", self.parameters)) | named
        if "k" in named and "modulus" not in named:
            values.pop("modulus", None)
        if any(name in changes for name in PATH_RULES):  # a path given: a level flat, and no other path
            changes = {"angle": 0.0, **{name: None for name in PATH_RULES}} | changes
        elif changes.get("angle"):  # a tilted flat approached vertically: no path
            changes = {name: None for name in PATH_RULES} | changes
        if ("diameter" in changes or "partner_diameter" in changes) and values.get("modulus") is not None \
                and "k" not in named:
            values.pop("k", None)  # k follows the modulus at the new (contact's) radius
        if "kappa" not in named and (values.get("poisson") is not None or values.get("shear_modulus") is not None):
            values.pop("kappa", None)  # kappa follows poisson or shear_modulus (and k, R)
        uses = {*LAWS.law(changes.get("model", self.model)).parameter_names,
                *TANGENTIALS.model(changes.get("tangential", self.tangential)).parameter_names}
        values = {name: value for name, value in values.items() if name in uses or name in named}
        if kept and APPROACH.issuperset(changes) and self.partner_mass is None and values.keys() == {
                *self.parameters} - self._recomputed(values):
            return self._approached(changes)
        fields_now = {name: getattr(self, name) for name in FIELD_DEFAULTS}  # dataclasses.replace's, cheaper
        with bodies_judged():  # judged when this scene was built
            return Scene(values, **(fields_now | changes))

    def _recomputed(self, values: dict) -> set:
        """The parameters :meth:`with_` left out of ``values`` that building the copy computes again from the others,
        to the value held: ``kappa`` from ``poisson`` or ``shear_modulus``, which the copy keeps, with k and R."""
        return {"kappa"} if "kappa" not in values and ("poisson" in values or "shear_modulus" in values) else set()

    def _approached(self, changes: dict) -> "Scene":
        """:meth:`with_`'s copy when ``changes`` are of the approach alone (:data:`APPROACH`) and the scene has no
        partner: every attribute the full build would give it, to the bit (tests/test_scene_copy.py builds both).  The
        law's parameters, the tangential stiffness and the models' checks do not depend on the approach, so they are
        taken as resolved; the changed fields are checked, and then every check the approach enters, in
        ``__post_init__``'s order: the magnitudes, the path, the law's time scale and the weight."""
        copy = object.__new__(Scene)
        held = copy.__dict__
        held.update(self.__dict__)
        for name in _CACHED:  # derived from the fields: read again on the copy's values
            held.pop(name, None)
        held.update(changes)
        copy._check_numbers(changes)
        copy._check_path()
        copy._check_scales()
        copy._check_weight()
        return copy


def chapter_law_parameters(law) -> tuple:
    """The parameters of ``law`` whose defaults are the chapter's ball's: its stiffness ``k`` where it has a default,
    and its damping where the default is not 0 (eq. 4.1's and 4.2's k and b).  One rule for the Scene's marks
    (:class:`ChapterValue`) and the doors that refuse an undescribed ball
    (:func:`sphereimpact.impact.ball.undescribed`)."""
    names = ("k",) if "k" in law.parameter_names and law.parameter("k").default is not None else ()
    damping = law.damping
    return names + ((damping,) if damping is not None and law.parameter(damping).default else ())


def _chapter_parameters(law, given: dict) -> set:
    """The law parameters a scene takes from the chapter's ball: those of :func:`chapter_law_parameters` that were
    not given, nor what sets them instead (``modulus`` for k)."""
    return {name for name in chapter_law_parameters(law)
            if given.get(name) is None and not (name == "k" and given.get("modulus") is not None)}


#: The Scene's fields: any other name given to it or to :meth:`Scene.with_` is a parameter of its models.
FIELDS = frozenset(f.name for f in fields(Scene))
#: The fields of the approach (and friction): what a copy may change without its parameters being resolved again
#: (:meth:`Scene.with_`, :meth:`Scene._approached`).
APPROACH = frozenset({"angle", "speed", "spin", "mu", "gravity", "incidence", "angle_to_surface"})
#: The quantities a Scene derives from its fields and keeps once read (its cached properties).
_CACHED = tuple(name for name, value in vars(Scene).items() if isinstance(value, cached_property))
#: What a Scene derives from its parameters and keeps once read (:meth:`Scene._hold` drops them with the values).
_FROM_PARAMETERS = ("frequency", "_family")
#: Each field's default (``parameters`` aside).
FIELD_DEFAULTS = {f.name: f.default for f in fields(Scene) if f.name != "parameters"}
#: A scene's fields and built-in parameters in the order of its tables' columns and its JSON's keys (each model's
#: parameters after its name): :meth:`Scene.as_dict`'s keys.
SCENE_KEYS = tuple(name for f in fields(Scene) if f.name != "parameters" for name in
                   (f.name, *{"model": PARAMETER_NAMES, "tangential": TANGENTIAL_PARAMETERS}.get(f.name, ())))


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
        ``auto`` or a registered integrator (:data:`sphereimpact.integrators.INTEGRATORS`).  ``auto``: the
        law's closed form if it has one (kelvin-voigt: exact, and the cheapest), else the Taylor method if it
        has a series (eq. 4.2, linear Hunt-Crossley; zeta up to 100), else DOP853-scalar.  ``closed`` is exact,
        for a law that declares a closed form (of the built-in laws, kelvin-voigt).
    rtol, atol : float
        Relative and absolute tolerances of :func:`scipy.integrate.solve_ivp`, rtol in [1e-13, 1e-2] and
        atol in [1e-16, 1e-2].
        ``atol`` applies to the dimensionless state (delta scaled by v_n/omega_n,
        delta_dot by v_n), so one value suits every ball and speed; the state
        is O(1), so atol = rtol.  The default (1e-10) meets 1e-9 on every output in the work-precision
        study with each integrator (``results/work_precision.csv``, notebook ``numerics``); the Taylor
        method bounds each step's truncation error by min(rtol, atol); DOP853-scalar takes DOP853's steps, in
        plain floats (compiled for a law with a kernel), for laws with a scalar formula, and is scipy's DOP853 for
        any other law or body.
    max_step : float
        Largest step [s]; ``inf`` lets the method choose.
    settings : mapping of str to int
        Numerical settings of the tangential models, each declared by a registered model with its range
        (:class:`~sphereimpact.contact.parameters.Setting`), e.g. ``microslip``'s ``elements`` (cells of its
        element row) and ``time_steps`` (steps over the contact).  A model reads its own with
        :meth:`setting`; one not given takes the model's default.
    """

    method: str = "auto"
    rtol: float = 1e-10
    atol: float = 1e-10
    max_step: float = math.inf
    settings: Mapping[str, int] = FrozenMapping()

    def __post_init__(self):
        _check_choice("method", self.method, method_names())
        object.__setattr__(self, "rtol", _check("rtol", self.rtol, RTOL_RANGE, lambda x: 1e-13 <= x <= 1e-2))
        object.__setattr__(self, "atol", _check("atol", self.atol, ATOL_RANGE, lambda x: 1e-16 <= x <= 1e-2))
        step = as_number("max_step", self.max_step)
        if not step > 0:  # also refuses nan
            raise ValueError(f"max_step must be a number > 0 s (inf allowed); got {self.max_step!r}")
        if not isinstance(self.settings, Mapping):
            raise TypeError(f"settings must be a mapping of name to value; got {type(self.settings).__name__}")
        declared = declared_settings()
        for name in self.settings:
            if name not in declared:
                raise ValueError(f"{name} is not a setting of any tangential model; the settings: "
                                 f"{', '.join(f'{s.name} ({s.doc})' for s in declared.values()) or 'none'}")
        object.__setattr__(self, "settings", FrozenMapping(
            {name: declared[name].check(value) for name, value in self.settings.items() if value is not None}))
        object.__setattr__(self, "max_step", step)

    def setting(self, name: str) -> int | None:
        """The setting ``name`` if given, else None (the model's default)."""
        return self.settings.get(name)

