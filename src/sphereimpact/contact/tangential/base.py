"""What a tangential contact model is: one object that declares its parameters, what it needs of the normal
law, and the motion it produces.

The shape is the contact laws' (:mod:`sphereimpact.contact.laws`) and LAMMPS's tangential sub-models: one definition
per model, chosen by name (``Scene.tangential``, ``--tangential``), every layer asking the definition.
Adding a model is one :class:`TangentialModel` passed to ``TANGENTIALS.register``.

The tangential stiffness of a compliant model is one number, kappa = k_t / k_n, the ratio of the tangential
to the normal contact stiffness; a model declares which ways to give it it accepts (:data:`STIFFNESS`).  A
model may also declare parameters of its own and numerical settings (:mod:`sphereimpact.contact.parameters`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Callable

from ..laws.base import Spring, spring_exponent
from ..parameters import Parameter, Setting
from ...choice import Choice
from ...registry import Registry as BaseRegistry

class Regime(Choice):
    """The tangential contact's mode at separation, as an impact's ``regime`` output reports it (a plain string
    wherever one is written: a table's cell, a JSON value).  A plug-in model may report a mode of its own."""

    NONE = "none"  # a normal impact: no tangential motion
    SLIDING = "sliding"  # the contact point slips (for microslip: the whole contact slid throughout)
    ROLLING = "rolling"  # the contact point grips (a rigid contact)
    STICKING = "sticking"  # the tangential spring holds (a compliant contact)
    MICROSLIP = "microslip"  # part of the contact stuck at some time (the exact microslip contact)


#: The tangential stiffness, three ways: kappa directly, Poisson's ratio of like materials, or (for a Hertz
#: spring) the effective shear modulus.  One table for the Scene's checks, the sweep's and the help texts.
KAPPA = Parameter("kappa", "-", "tangential stiffness ratio k_t / k_n",
                  "a finite number > 0 (k_t / k_n; 2 (1 - nu) / (2 - nu) for like materials)", lambda x: x > 0)
POISSON = Parameter("poisson", "-", "Poisson's ratio nu of like materials, kappa = 2 (1 - nu) / (2 - nu)",
                    "a finite number in (-1, 0.5]", lambda x: (x > -1) & (x <= 0.5))
SHEAR_MODULUS = Parameter("shear_modulus", "Pa", "effective shear modulus G* of a Hertz contact, kappa = 4 G* / E*",
                          "a finite number > 0", lambda x: x > 0)
STIFFNESS = (KAPPA, POISSON, SHEAR_MODULUS)
#: How each other way of giving kappa sets it, for messages.
KAPPA_FROM = {"poisson": "kappa = 2 (1 - nu) / (2 - nu)", "shear_modulus": "kappa = 4 G* / E*"}
#: The tangential parameters that are Scene fields (a model's own parameters are carried in Scene.parameters).
TANGENTIAL_PARAMETERS = tuple(p.name for p in STIFFNESS)


def slip_per_impulse(mass, alpha):
    """(1 + 1/alpha) / m [1/kg]: the change of the contact point's slip v - omega R per unit tangential impulse
    at the contact (1/m from the centre's velocity, R^2 / I = 1 / (alpha m) from the spin).  Floats or arrays."""
    return (1.0 + 1.0 / alpha) / mass


def kappa_from_poisson(nu):
    """kappa = k_t / k_n = 2 (1 - nu) / (2 - nu) for two bodies of one elastic material (Mindlin 1949)."""
    return 2.0 * (1.0 - nu) / (2.0 - nu)


def kappa_from_shear_modulus(g_star, k, radius):
    """kappa = 4 G* / E* of a Hertz contact whose spring constant k = (4/3) E* sqrt(R) [N/m^1.5]."""
    return 4.0 * g_star / (0.75 * k / math.sqrt(radius))


@dataclass(frozen=True)
class SweptTangential:
    """A tangential model's end state as a function of the normal impulse, for many scenes at once: what a
    sweep asks of a model whose motion follows from the normal motion in closed form.

    Both functions take ``rows``, a namespace of arrays (one entry per scene, every scene with tangential
    motion): the scene table's columns (``mass``, ``mu``, ``inertia_factor``, ``spin``, the model's
    parameters, ...) and ``radius`` [m], ``v_normal`` and ``v_tangent`` [m/s].

    Attributes
    ----------
    levels : callable
        ``levels(rows) -> array`` [N s]: for each scene, the friction-carrying normal impulse J+ (the
        integral of max(P, 0)) at which the model needs to know the instant it is reached (the rigid
        contact: where the contact point stops slipping), NaN where it needs none.
    end : callable
        ``end(rows, impulse, instants) -> dict`` of arrays: ``vc_t`` [m/s], ``omega_f`` [rad/s], ``t_roll``
        [s] (NaN: never), ``switches`` and ``regime``, given each scene's J+ over the contact ``impulse``
        [N s] and ``instants`` [s], when J+ reached each scene's level (NaN where it did not, or where no
        instant was asked for).  Gravity along the flat is 0 on the sweep's fast paths.
    """

    levels: Callable
    end: Callable


@dataclass(frozen=True)
class TangentialModel:
    """A tangential contact model and what it can do.

    Attributes
    ----------
    name : str
        Registry key (``--tangential``, ``Scene.tangential``).
    doc : str
        What the tangential force is, one phrase for help texts (``spring k_t = kappa k, ...``).
    stiffness : str
        How its stiffness is formed, for messages (``k_t = kappa k, constant``); empty for a rigid contact.
    parameters : tuple of Parameter
        The ways of giving kappa it accepts (some of :data:`STIFFNESS`; kappa itself is then required, given
        directly or through one of the others; none: the model has no tangential stiffness), and the model's
        own parameters (:attr:`own_parameters`, read as ``scene.name`` or ``rows.name``).
    spring : Spring or str or None
        The normal law's spring it needs (:class:`~sphereimpact.contact.laws.Spring`, or its word): ``linear``
        (k delta), ``hertz`` (k delta^(3/2)) or None (any law).
    motion : callable
        ``motion(normal, options)``: the tangential motion over the solved normal motion ``normal``
        (:class:`sphereimpact.contact.motion.NormalMotion`) with solver options ``options``, an object with
        ``t_roll`` [s or None], ``regime``, ``switches``, ``at(t)`` -> (v_t [m/s], omega [rad/s], x_t [m])
        and ``force(t)`` -> the tangential force on the ball [N].
    swept : SweptTangential or None
        The end of the tangential motion in closed form from the normal impulse, vectorised over many scenes
        (:class:`SweptTangential`): sweeps then solve only the normal motion of its scenes on their fast
        paths.  None: a sweep solves its scenes with :func:`sphereimpact.impact.solve.simulate_many`.
    settings : tuple of Setting
        Its numerical settings (a resolution), read as ``options.setting(name)`` (None: not given).
    scale_free : bool
        True when its motion, in the contact's own scales (time 1 / w, speed v_n, spin v_n / R), depends only on
        dimensionless numbers (kappa, mu, alpha, the normal law's family and its own dimensionless parameters):
        a sweep then solves scenes alike but for their scales once (the ``similar`` path).  False (the default
        for a model registered from outside): each scene is solved.
    """

    name: str
    doc: str
    stiffness: str
    parameters: tuple
    spring: Spring | None
    motion: Callable
    swept: "SweptTangential | None" = None
    settings: tuple = ()
    scale_free: bool = False

    def __post_init__(self):
        names = [p.name for p in self.parameters]
        if any(not isinstance(p, Parameter) for p in self.parameters) or len(set(names)) != len(names):
            raise ValueError(f"tangential model {self.name!r}: parameters must be distinct Parameter objects; "
                             f"got {names}")
        if any(not isinstance(s, Setting) for s in self.settings):
            raise ValueError(f"tangential model {self.name!r}: settings must be Setting objects")
        if self.stiffness_parameters and "kappa" not in self.parameter_names:
            raise ValueError(f"tangential model {self.name!r}: a model with a stiffness takes kappa")
        if self.spring is not None:
            object.__setattr__(self, "spring", Spring.parse(self.spring, f"tangential model {self.name!r}: spring "
                                                                         "(or None)"))

    @cached_property
    def parameter_names(self) -> tuple:
        return tuple(p.name for p in self.parameters)

    @cached_property
    def stiffness_parameters(self) -> tuple:
        """The ways of giving kappa it accepts (some of :data:`STIFFNESS`); empty: no tangential stiffness."""
        return tuple(p for p in self.parameters if p.name in TANGENTIAL_PARAMETERS)

    @cached_property
    def own_parameters(self) -> tuple:
        """The parameters that are not Scene fields (carried in ``Scene.parameters``)."""
        return tuple(p for p in self.parameters if p.name not in TANGENTIAL_PARAMETERS)

    def refusal(self, law, p) -> str | None:
        """Why this model cannot serve the normal law ``law`` with parameters ``p`` (a Scene), or None."""
        if self.spring is None:
            return None
        from ..laws import LAWS

        if self.spring is Spring.LINEAR and law.spring is not Spring.LINEAR:
            hertzian = _names(TANGENTIALS, Spring.HERTZ)
            return (f"tangential {self.name!r} ({self.stiffness}) needs a linear-spring law "
                    f"({_names(LAWS, Spring.LINEAR)}); model {law.name!r} has a Hertz spring: use tangential {hertzian}")
        if self.spring is Spring.HERTZ and (law.spring is not Spring.HERTZ or spring_exponent(law, p) != 1.5):
            found = (f"a linear spring: use tangential {_names(TANGENTIALS, Spring.LINEAR)}" if law.spring is Spring.LINEAR
                     else f"exponent {spring_exponent(law, p):g}")
            return (f"tangential {self.name!r} ({self.stiffness}) needs a Hertz spring k delta^(3/2) "
                    f"({_names(LAWS, Spring.HERTZ)}, exponent 1.5); model {law.name!r} has {found}")
        return None


def _names(registry, spring: Spring) -> str:
    """The names in ``registry`` whose ``spring`` is ``spring``, listed (tangential models quoted, as a
    command-line value; laws plain)."""
    names = [name for name, item in registry.items() if item.spring == spring]
    return ", ".join(f"'{n}'" for n in names) if registry is TANGENTIALS else ", ".join(names)


class TangentialRegistry(BaseRegistry):
    """Name -> TangentialModel.  :meth:`register` adds a model; nothing else needs to change."""

    def __init__(self):
        super().__init__(TangentialModel, "tangential model", "tangential")

    def model(self, name: str) -> TangentialModel:
        """The model ``name``; ``ValueError`` listing the registered models otherwise."""
        return self.named(name)

    def taking(self, parameter: str) -> list[str]:
        """Names of the models that accept ``parameter``."""
        return [name for name, model in self.items() if parameter in model.parameter_names]


#: The registered tangential models (filled by :mod:`sphereimpact.contact.tangential`).
TANGENTIALS = TangentialRegistry()
