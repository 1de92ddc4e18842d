"""What a normal contact law is: one object that declares its parameters, force and capabilities.

Every layer (scene validation, the single-impact integrator, the closed form, the sweep engine, the
calibration, the command line and the config) asks the law, never its name.  A layer that cannot serve
a law says so, or takes a path that is exact for any law (the single-impact integrator), never a
different law's.  The shape follows LAMMPS's granular sub-models: one definition per law, chosen by name.

Conventions: delta >= 0 is compression [m], delta_dot its rate [m/s] (> 0 while compressing), and P [N]
is the force the flat pushes on the ball along the outward normal.  A force function takes
``(delta, delta_dot, p)`` where ``p`` is anything with the attributes ``mass`` [kg], ``radius`` [m],
``v_normal`` [m/s] and the law's parameters (a :class:`sphereimpact.Scene`, or a namespace of arrays in
sweeps), and is numpy-vectorised.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Callable, Mapping

import numpy as np

from ...choice import Choice
from ...ode.dense import is_instant
from ...registry import Registry as BaseRegistry
from ..parameters import Parameter
from .closed_form import ClosedForm

#: The law parameters that are Scene fields, in the order Scene declares them.  A law uses a subset, and may
#: declare parameters of its own besides (carried in ``Scene.parameters``).
PARAMETER_NAMES = ("k", "b", "ramp", "chi", "exponent", "modulus")


class Spring(Choice):
    """The elastic term of a law's force, which fixes what its stiffness means and which tangential models it serves
    (written as its word wherever a law's description is)."""

    LINEAR = "linear"  # P ~ k delta: k in N/m; omega_n and zeta defined
    HERTZ = "hertz"  # P ~ k delta^n (3/2 unless the law declares an exponent); k may be given as E*, k = (4/3) E* sqrt(R)


class Relation(Choice):
    """How a measured COR sets a law's damping: the root find on the law itself, or a published relation the law
    declares (``ContactLaw.cor_relations``, keyed by these).  The calibration (:mod:`sphereimpact.impact.calibrate`)
    takes any of them by its word (``--cor-relation``)."""

    EXACT = "exact"  # the root find, to 1e-9: no formula
    HUNT_CROSSLEY = "hunt-crossley"  # Hunt & Crossley (1975)
    LANKARANI_NIKRAVESH = "lankarani-nikravesh"  # Lankarani & Nikravesh (1990)
    FLORES = "flores"  # Flores, Machado, Silva & Martins (2011)
    GONTHIER = "gonthier"  # Gonthier, McPhee, Lange & Piedboeuf (2004)


@dataclass(frozen=True)
class Kernel:
    """A law's force compiled by numba, for the compiled integrator of the normal motion (``DOP853-scalar``).

    Attributes
    ----------
    function : str or callable
        The force P(delta, delta_dot, params) [N], a function numba compiles for
        :data:`sphereimpact.contact.laws.kernels.SIGNATURE` on first use: one of that module by name (imported,
        with numba, then), ``"module:name"`` for a plug-in's own, or the function itself (plain, or already
        compiled for that signature).  It must be the law's ``scalar`` formula, in its arithmetic (the
        integrator's events and landing evaluate that one): on its first use in a process it is compiled and held
        to that formula at a few states of the scene (``integrators.compiled.checked_kernel``), and refused by
        name where it does not compile or differs.
    parameters : callable
        ``parameters(p) -> tuple of float``: the ``params`` the kernel reads, from a Scene.
    """

    function: object
    parameters: Callable

    def load(self, series: bool = False):
        """The compiled function (compiled or loaded from numba's disk cache on the process's first call): a force
        kernel, or with ``series`` a series kernel (:data:`~sphereimpact.contact.laws.kernels.SERIES_SIGNATURE`)."""
        from . import kernels

        function = self.function
        if isinstance(function, str):
            import importlib

            module, _, name = function.rpartition(":")
            function = getattr(importlib.import_module(module) if module else kernels, name)
        if hasattr(function, "signatures"):
            return function
        return kernels.compiled(function, kernels.SERIES_SIGNATURE if series else kernels.SIGNATURE)


@dataclass(frozen=True)
class ContactLaw:
    """A normal contact force law and what it can do.

    Attributes
    ----------
    name : str
        Registry key (``--model``, ``Scene.model``).
    doc : str
        One line for help texts and reports.
    parameters : tuple of Parameter
        The law's parameters; a Scene refuses any other law parameter.  Those named in
        :data:`PARAMETER_NAMES` are Scene fields; any other is the law's own (:attr:`own_parameters`), given
        in ``Scene.parameters``, a table column or ``--name``, and read as ``p.name`` like the others.
    continued : callable
        ``continued(delta, delta_dot, p)``: the in-contact formula continued smoothly a little past
        delta = 0.  Integrators use it for their stages and the force during contact is evaluated with
        it, so the ends of [0, t_f] are one-sided limits whatever side of zero round-off puts delta (a
        kink or jump at separation spoils the crossing step's interpolant: COR error 8.9e-11 with it,
        8.4e-13 without, at rtol 1e-12 for eq. 4.1).  The law itself, :meth:`force`, derives from it.
    frequency : callable
        ``frequency(p) -> 1 / T`` [1/s], numpy-vectorised: the inverse of the contact's natural time T.
        The normal motion is solved in tau = t / T, x = delta / (v_n T), y = delta_dot / v_n, so one
        tolerance and one horizon suit every ball and speed (omega_n = sqrt(k / m) for a linear spring; a
        Hertz contact has no omega_n and uses its elastic compression time).
    family : callable
        ``family(p) -> dict`` of the dimensionless numbers that fix the weightless normal motion in
        (tau, x, y) (its similarity family): scenes with equal numbers share tau_m, x_m, tau_f and the
        COR.  Vectorised.
    horizon : callable
        ``horizon(p)``: the longest dimensionless contact (in tau) searched for a separation before
        giving up; far beyond any contact that ends.
    spring : Spring or str
        :class:`Spring` (or its word): ``linear`` (P ~ k delta; k in N/m, omega_n and zeta defined) or ``hertz``
        (P ~ k delta^n; k may be given as an effective modulus E*, k = (4/3) E* sqrt(R)).
    damping : str or None
        The parameter that ``cor`` calibration sets (None: the law is elastic and cannot be calibrated).
    cor_relations : mapping of Relation -> callable
        Published approximate COR-to-damping relations: :class:`Relation` (or its word; not ``exact``) ->
        ``relation(e, p) -> damping value``.
    scaled : callable or None
        ``scaled(x, y, numbers) -> P_hat``: the law's force in the dimensionless variables of ``frequency``,
        P_hat = P / (m v_n / T) at delta = x v_n T, delta_dot = y v_n, with ``numbers`` the law's ``family``
        (floats or arrays of lanes).  The same law as ``continued`` (tested for every registered law), the
        form that the sweep's batched lanes integrate: they take a law whose ``scaled`` is one of the forms
        they were built for (:data:`sphereimpact.sweep.batch.FORMS`, eq. 4.1's and eq. 4.2's), by identity,
        never by a name; other laws are solved per similarity family by the single-impact integrator,
        which is exact for every law, or interpolated in the family's last number where many scenes differ
        only in it (:mod:`sphereimpact.sweep.paths`).
    closed_form : ClosedForm or None
        The law's exact solution (:class:`sphereimpact.contact.laws.closed_form.ClosedForm`: one scene's motion in SI
        units for the ``closed`` integrator, the weightless events vectorised for sweeps), or None.
    ramp_rate : callable or None
        ``ramp_rate(p) -> c / R`` [1/m] for a law whose damping is switched on by a ramp in
        u = (c / R) delta; integrators bound their steps where it switches off.
    scalar : callable or None
        ``scalar(delta, delta_dot, p) -> float``: ``continued`` for Python floats, without numpy (the
        single-impact integrator calls its right-hand side thousands of times with scalars, where numpy's
        per-call overhead dominates).  Must agree with ``continued`` to rounding (tested); None: the
        integrator calls ``continued``.
    rate : callable or None
        ``rate(delta, delta_dot, delta_ddot, p) -> dP/dt`` [N/s] inside contact, the chain rule of the
        force.  Tangential compliance needs it to tell when a slipping contact sticks again (the Coulomb
        cap mu P moves with P).  None: :func:`force_rate` differentiates ``continued`` numerically.
    series : callable or None
        ``series(x, y, numbers, gamma, order) -> (xs, ys)``: the Taylor coefficients, orders 0 to
        ``order`` (lists of floats), of the dimensionless normal motion x' = y, y' = -P_hat(x, y) + gamma
        through the point (x, y), ``numbers`` being the law's ``family`` (floats).  Only for a law whose
        P_hat is analytic in x >= 0 and y (a recurrence on its series exists): then the Taylor method
        (:mod:`sphereimpact.ode.series`) integrates it.  None: the law has no series, and ``auto`` takes the
        Runge-Kutta integrator.
    passive : bool
        True when the law never does net positive work on the ball over a contact (its damping dissipates for
        every allowed parameter, its spring is conservative): a weightless impact then rebounds no faster than it
        came, COR <= 1, and :class:`~sphereimpact.impact.outcome.Outcome` bounds the rebound by the approach
        (the integrators' error alone crossed it: COR 1 + 1e-10 for an undamped contact).  False (the
        default, a plug-in's unless it declares it): no bound is applied.
    kernel : Kernel or None
        The law's force compiled (:class:`Kernel`): method ``DOP853-scalar`` then integrates the normal motion in
        compiled code (:mod:`sphereimpact.integrators.dop853_kernel`); without one it runs the same algorithm on
        ``scalar`` in Python floats, or scipy's DOP853 without that either.
    series_kernel : Kernel or None
        The law's ``series`` compiled (a function of :mod:`~sphereimpact.contact.laws.kernels` by name, its
        ``parameters`` the family numbers it reads, in order): method ``taylor`` then integrates in compiled
        code (:mod:`sphereimpact.integrators.taylor_kernel`) once the process integrates compiled, with the
        Python series' answer to the bit; without one it runs ``series`` in Python floats.
    per_compression : callable or None
        ``per_compression(x, y, numbers) -> Q``: P_hat / x, continued through x = 0, for a law whose force
        has a forced zero at first touch and separation (eq. 4.2): its sign is the force's inside the contact,
        without the zero, and Q(0, y_f) < 0 says the force pulls before delta returns to 0.  The sweep's
        lanes end a contact on its root, and its interpolants cut at its sign change.
    """

    name: str
    doc: str
    parameters: tuple
    continued: Callable
    frequency: Callable
    family: Callable
    horizon: Callable
    spring: Spring = Spring.LINEAR
    damping: str | None = None
    cor_relations: Mapping[Relation, Callable] = field(default_factory=dict)
    scaled: Callable | None = None
    closed_form: ClosedForm | None = None
    ramp_rate: Callable | None = None
    scalar: Callable | None = None
    rate: Callable | None = None
    series: Callable | None = None
    per_compression: Callable | None = None
    passive: bool = False
    kernel: Kernel | None = None
    series_kernel: Kernel | None = None

    def __post_init__(self):
        names = [p.name for p in self.parameters]
        if any(not isinstance(p, Parameter) for p in self.parameters) or len(set(names)) != len(names):
            raise ValueError(f"law {self.name!r}: parameters must be distinct Parameter objects; got {names}")
        object.__setattr__(self, "spring", Spring.parse(self.spring, f"law {self.name!r}: spring"))
        relations = {Relation.parse(name, f"law {self.name!r}: a cor_relations key"): relation
                     for name, relation in self.cor_relations.items()}
        if Relation.EXACT in relations:
            raise ValueError(f"law {self.name!r}: 'exact' is the calibration's root find, not a published relation")
        object.__setattr__(self, "cor_relations", relations)
        if self.damping is not None and self.damping not in names:
            raise ValueError(f"law {self.name!r}: damping {self.damping!r} is not one of its parameters")
        if self.kernel is not None and (not isinstance(self.kernel, Kernel) or self.scalar is None):
            raise ValueError(f"law {self.name!r}: kernel must be a Kernel, and the law must declare the scalar formula "
                             f"it compiles; got kernel {self.kernel!r}, scalar {self.scalar!r}")
        if self.closed_form is not None and not isinstance(self.closed_form, ClosedForm):
            raise ValueError(f"law {self.name!r}: closed_form must be a ClosedForm (the linear spring-damper's is "
                             f"sphereimpact.contact.laws.spring_damper.SPRING_DAMPER) or None; got {self.closed_form!r}")

    def in_floats(self, p):
        """``continued`` for one state: a function (delta [m], delta_dot [m/s]) -> P [N] of two floats, the law's
        ``scalar`` formula where it declares one (the same arithmetic without numpy's cost per call, most of an
        integrator's right-hand side on one state), else ``continued`` itself, its value as a float.  ``p``: the
        scene, as ``continued`` takes it (``Scene.stage_force`` passes its reduced sphere)."""
        scalar, continued = self.scalar, self.continued
        if scalar is None:
            return lambda delta, delta_dot: float(continued(delta, delta_dot, p))
        return lambda delta, delta_dot: scalar(delta, delta_dot, p)

    def force(self, delta, delta_dot, p):
        """P [N] of the law: ``continued`` inside contact (delta > 0) and 0 outside, where nothing is evaluated
        beyond delta = 0 (continued at max(delta, 0)).  Separation events use it."""
        delta = np.asarray(delta, dtype=float)
        return np.where(delta > 0, self.continued(np.maximum(delta, 0.0), delta_dot, p), 0.0)

    @cached_property
    def parameter_names(self) -> tuple:
        """Names of the parameters the law uses (plus ``modulus`` for a Hertz spring)."""
        names = tuple(p.name for p in self.parameters)
        return (*names, "modulus") if self.spring is Spring.HERTZ else names

    @cached_property
    def own_parameters(self) -> tuple:
        """The parameters that are not Scene fields (carried in ``Scene.parameters``)."""
        return tuple(p for p in self.parameters if p.name not in PARAMETER_NAMES)

    def parameter(self, name: str) -> Parameter:
        """The declared parameter ``name`` (``KeyError`` if the law has none)."""
        for p in self.parameters:
            if p.name == name:
                return p
        raise KeyError(name)


def spring_exponent(law: ContactLaw, p):
    """n of the law's spring term k delta^n: 1 for a linear spring, the law's ``exponent`` or 3/2 for Hertz."""
    if law.spring is Spring.LINEAR:
        return 1.0
    return p.exponent if "exponent" in law.parameter_names else 1.5


def spring_stiffness(law: ContactLaw, delta, p):
    """Tangent stiffness d(k delta^n)/d delta = n k delta^(n-1) of the law's spring term [N/m], delta >= 0.

    The normal contact stiffness that a tangential spring is scaled from (k itself for a linear spring;
    2 E* a, a = sqrt(R delta), for Hertz).
    """
    n = spring_exponent(law, p)
    if is_instant(delta):  # one instant (a stick phase's right-hand side): plain floats
        return float(p.k) if n == 1.0 else n * p.k * max(float(delta), 0.0) ** (n - 1.0)
    delta = np.maximum(np.asarray(delta, dtype=float), 0.0)
    return np.broadcast_to(p.k * np.ones_like(delta), delta.shape) if n == 1.0 else n * p.k * delta ** (n - 1.0)


def force_rate(law: ContactLaw, delta, delta_dot, delta_ddot, p):
    """dP/dt [N/s] inside contact: the law's ``rate``, or a fourth-order central difference of
    ``continued`` in delta and delta_dot (relative error about 1e-11) for a law that declares none."""
    if law.rate is not None:
        return law.rate(delta, delta_dot, delta_ddot, p)
    delta, delta_dot = np.asarray(delta, dtype=float), np.asarray(delta_dot, dtype=float)

    def partial(f, x, scale):
        h = 1e-3 * np.maximum(np.abs(x), scale)
        return (8.0 * (f(x + h) - f(x - h)) - (f(x + 2 * h) - f(x - 2 * h))) / (12.0 * h)

    d_scale = np.maximum(np.abs(delta), 1e-3 * np.asarray(p.radius))
    v_scale = np.maximum(np.abs(delta_dot), 1e-3 * np.asarray(p.v_normal))
    by_delta = partial(lambda x: law.continued(x, delta_dot, p), delta, d_scale)
    by_rate = partial(lambda y: law.continued(delta, y, p), delta_dot, v_scale)
    return by_delta * delta_dot + by_rate * delta_ddot


def hertz_constant(modulus, radius):
    """k = (4/3) E* sqrt(R) [N/m^1.5] for an effective modulus E* [Pa] and radius R [m]."""
    return 4.0 / 3.0 * modulus * np.sqrt(radius)


def hertz_modulus(p) -> float:
    """E* = 3 k / (4 sqrt(R)) [Pa]: the effective modulus of a Hertz spring k delta^(3/2) (``p``: k, radius)."""
    return 0.75 * p.k / math.sqrt(p.radius)


MODULUS = Parameter("modulus", "Pa", "effective modulus E* of ball and flat (instead of k: k = (4/3) E* sqrt(R))",
                    "a finite number > 0", lambda x: x > 0)


class LawRegistry(BaseRegistry):
    """Name -> ContactLaw.  :meth:`register` adds a law; nothing else needs to change."""

    def __init__(self):
        super().__init__(ContactLaw, "law", "model")

    def law(self, name: str) -> ContactLaw:
        """The law ``name``; ``ValueError`` listing the registered laws otherwise."""
        return self.named(name)


#: The registered laws (filled by :mod:`sphereimpact.contact.laws`).
LAWS = LawRegistry()
