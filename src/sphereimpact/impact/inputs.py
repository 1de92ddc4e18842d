"""What each input of an impact may be: allowed ranges and choices, checked for one scene (by
:class:`~sphereimpact.impact.scene.Scene`) and for a table's columns (by sweeps), from one table of rules so
both say the same thing, with one line naming the parameter and its allowed range."""

from __future__ import annotations

import math
import numbers

import numpy as np

from ..contact.laws import LAWS, PARAMETER_NAMES, Spring, hertz_constant
from ..contact.laws.base import MODULUS
from ..contact.declared import own_parameters
from ..contact.separation import Separation
from ..contact.tangential import TANGENTIAL_PARAMETERS, TANGENTIALS

#: Names of the separation criteria (:class:`~sphereimpact.contact.separation.Separation`).
SEPARATION_CRITERIA = tuple(Separation)

#: Scene fields that hold names, not numbers.
TEXT_FIELDS = ("model", "separation", "tangential")


#: Numeric Scene fields other than the law's parameters: (allowed range as stated in messages, vectorised
#: test).  One table for the scalar checks of :class:`Scene` and the array checks of sweeps, so both say the
#: same thing.  The law's own parameters (k, b, ramp, chi, exponent, modulus) are declared by the law
#: (:mod:`sphereimpact.contact.laws`) and checked by :func:`law_parameters`.
RULES = {
    "mass": ("a finite number > 0 kg", lambda x: x > 0),
    "diameter": ("a finite number > 0 m", lambda x: x > 0),
    "inertia_factor": ("a finite number in (0, 2/3] (2/3 = 0.6666666666666666)", lambda x: (x > 0) & (x <= 2 / 3)),
    "angle": ("a finite number in [0, 90) degrees", lambda x: (x >= 0) & (x < 90)),
    "speed": ("a finite number > 0 m/s", lambda x: x > 0),
    "mu": ("a finite number >= 0", lambda x: x >= 0),
    "gravity": ("a finite number >= 0 m/s^2", lambda x: x >= 0),
    "spin": ("a finite number rad/s (positive: topspin, negative: backspin)", lambda x: x == x),
}
#: The approach described by the ball's path instead of the flat's tilt (optional Scene fields, NaN in a table
#: where not given): (allowed range, vectorised test).
PATH_RULES = {
    "incidence": ("a finite number in [0, 90) degrees from the flat's normal", lambda x: (x >= 0) & (x < 90)),
    "angle_to_surface": ("a finite number in (0, 90] degrees", lambda x: (x > 0) & (x <= 90)),
}


#: A partner sphere the ball strikes instead of the flat (:mod:`.pair`): (allowed range, vectorised test) of its
#: fields, all optional; ``partner_mass`` and ``partner_diameter`` give the partner, the others need it.
PARTNER_RULES = {
    "partner_mass": ("a finite number > 0 kg", lambda x: x > 0),
    "partner_diameter": ("a finite number > 0 m", lambda x: x > 0),
    "partner_inertia_factor": (RULES["inertia_factor"][0], RULES["inertia_factor"][1]),
    "partner_spin": ("a finite number rad/s (in the ball's rotational sense)", lambda x: x == x),
}


def as_number(name: str, value) -> float:
    """``value`` as a Python float when it is a real number: int, float, a numpy scalar or a 0-d array.

    Booleans are refused (``True`` is not a number a user means), and so is anything else, with a
    ``TypeError`` naming the parameter and the type found.
    """
    if type(value) is float:  # the common case, answered before the abstract-class checks below
        return value
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number; got {type(value).__name__} {value!r}")
    try:
        return float(value)
    except OverflowError:  # an integer beyond double precision (10**400)
        digits = len(str(abs(int(value))))
        raise ValueError(f"{name} must be a finite number; got a {digits}-digit integer, beyond double precision "
                         "(about 1.8e308)") from None


def check_flag(name: str, value) -> bool:
    """``value`` as a flag of the API (``chapter_ball``, ...): True or False, else ValueError naming ``name``."""
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be True or False; got {value!r}")
    return bool(value)


def _check(name: str, value, allowed: str, ok) -> float:
    """``value`` as a float; ``ValueError`` unless it is finite and satisfies ``ok``."""
    number = as_number(name, value)
    if not math.isfinite(number) or not ok(number):
        raise ValueError(f"{name} must be {allowed}; got {value!r}")
    return number


#: sqrt of the largest double: the largest speed or diameter whose square is finite.
SQUARE_LIMIT = math.sqrt(np.finfo(float).max)


#: Mean densities [kg/m^3] beyond which no ball lies (an inflatable beach ball is above the lower bound, osmium
#: below the upper): outside them a mass or diameter was most likely typed in grams or millimetres.
DENSITY_RANGE = (10.0, 25_000.0)


def density_problem(mass, diameter, body: str = "ball") -> str | None:
    """One line naming the likely unit slip when the mean density m / (pi D^3 / 6) (arrays, or numbers: the first
    bad row named) lies outside :data:`DENSITY_RANGE`, else None.  A warning, not a refusal: a test body may be
    odd on purpose."""
    if isinstance(mass, float) and isinstance(diameter, float):  # one body (a Scene is built per row): plain floats
        try:
            density = mass / (math.pi / 6.0 * diameter ** 3)
        except (OverflowError, ZeroDivisionError):  # beyond double precision: the magnitude checks speak of that
            return None
        if not math.isfinite(density) or DENSITY_RANGE[0] <= density <= DENSITY_RANGE[1]:
            return None
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        m, d = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float)) for x in (mass, diameter)))
        rho = m / (math.pi / 6.0 * d ** 3)
        low, high = DENSITY_RANGE
        bad = np.isfinite(rho) & ((rho < low) | (rho > high))
    if not bad.any():
        return None
    i = int(np.flatnonzero(bad)[0])
    slip = "is the mass in grams?" if rho[i] > high else "is the diameter in millimetres?"
    rows = f" ({int(bad.sum())} of {m.size} rows, the first row {i})" if m.size > 1 else ""
    return (f"the {body}'s mean density is {rho[i]:.3g} kg/m^3 (mass {m[i]:.4g} kg, diameter {d[i]:.4g} m), outside "
            f"any ball's {low:g} to {high:g} kg/m^3{rows}: {slip}")


#: The smallest normal double.
_TINY = float(np.finfo(float).tiny)


def _floats(*values) -> bool:
    """True when every value is a float (a Python or numpy scalar): one scene's check, which plain float arithmetic
    answers at a fraction of numpy's per-call cost.  Only a pass is taken from it; a failure is worded by the array
    path."""
    return all(isinstance(value, float) for value in values)


def _finite(*values: float) -> bool:
    return all(math.isfinite(value) for value in values)


def magnitude_problem(mass, speed, diameter, spin=0.0) -> str | None:
    """Why squares of these (arrays, or numbers) would overflow double precision, naming the parameters and
    the first bad row, or None.  The outputs hold v^2, R^2, m v^2, I = alpha m R^2 and I omega^2 (energies,
    spin): beyond double precision they are inf or NaN, never a result."""
    if _floats(mass, speed, diameter, spin):  # one scene (a Scene is built per row): its squares in plain floats
        surface = spin * 0.5 * diameter
        if _finite(speed * speed, diameter * diameter, mass * speed * speed,
                   mass * (0.5 * diameter) * (0.5 * diameter), mass * surface * surface):
            return None  # else the arrays below name what overflows
    with np.errstate(over="ignore", invalid="ignore"):
        m, v, d, w = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float))
                                           for x in (mass, speed, diameter, spin)))
        surface = w * 0.5 * d  # the spin's surface speed omega R [m/s]
        checks = ((v * v, f"speed must be below {SQUARE_LIMIT:.4g} m/s (its square overflows double precision)", v),
                  (d * d, f"diameter must be below {SQUARE_LIMIT:.4g} m (its square overflows double precision)", d),
                  (m * v * v, "mass and speed: the kinetic energy m v^2 overflows double precision (lower either)",
                   None),
                  (m * (0.5 * d) * (0.5 * d), "mass and diameter: the moment of inertia alpha m R^2 overflows double "
                                              "precision (lower either)", None),
                  (m * surface * surface, "spin: the rotational energy I omega^2 overflows double precision (lower "
                                          "it)", w))
        for square, message, value in checks:
            bad = ~np.isfinite(square)
            if bad.any():
                i = int(np.flatnonzero(bad)[0])
                row = f" (row {i})" if m.size > 1 else ""
                got = f"; got {float(value[i])!r}" if value is not None else \
                    f"; got mass {float(m[i])!r}, speed {float(v[i])!r}, diameter {float(d[i])!r}"
                return message + got + row
    return None


def scale_problem(mass, v_normal, frequency, law, rows=None) -> str | None:
    """Which of the contact's scales leaves double precision's normal range (arrays or numbers; the first
    bad row named, as ``rows`` numbers them if given), or None.  The motion is solved in
    x = delta / (v_n T), y = delta_dot / v_n, tau = t / T, with forces in units of m v_n / T
    (T = 1 / frequency, the law's contact time)."""
    if _floats(mass, v_normal, frequency) and frequency != 0.0:  # one scene: its scales in plain floats
        scales = (1.0 / frequency, v_normal / frequency, frequency * v_normal, mass * frequency * v_normal)
        if _finite(*scales) and min(scales) >= _TINY:
            return None  # else the arrays below name the scale that leaves the range
    with np.errstate(all="ignore"):
        m, v, w = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, dtype=float)) for x in (mass, v_normal, frequency)))
        scales = {"contact time T": 1.0 / w, "contact's deflection scale v_n T": v / w,
                  "contact's acceleration scale v_n / T": w * v, "contact's force scale m v_n / T": m * w * v}
        for what, value in scales.items():
            bad = ~(np.isfinite(value) & (value >= np.finfo(float).tiny))
            if bad.any():
                i = int(np.flatnonzero(bad)[0])
                uses = ", ".join(["mass", "speed", "angle", *law.parameter_names])
                row = f" (row {i if rows is None else int(rows[i])})" if value.size > 1 or rows is not None else ""
                return (f"the {what} = {float(value[i]):.3g} is outside double precision's normal range "
                        f"(it follows from {uses}){row}: outside what the model computes")
    return None


def _check_choice(name: str, value, choices) -> None:
    if value not in choices:
        raise ValueError(f"{name} must be one of {', '.join(choices)}; got {value!r}")


def law_parameters(model: str, given: dict, radius, rows=None) -> dict:
    """The law parameters of scenes of one law: checked, defaults filled, ``modulus`` turned into ``k``.

    Parameters
    ----------
    model : str
        The law's name.
    given : dict of str -> array or None
        Parameter name (of :data:`sphereimpact.contact.laws.PARAMETER_NAMES`) -> values for each scene, or None
        when not given.  In a table's column (``rows`` given) NaN means "not given" for that row (a table may
        give one row's Hertz law by k and another's by modulus); for one scene, NaN is a bad value.
    radius : float or array
        Ball radius R [m] of each scene (for ``modulus``).
    rows : array of int, optional
        The scenes' rows in a table, for messages.

    Returns
    -------
    dict of str -> float array
        Every name of PARAMETER_NAMES; NaN for the parameters the law does not use.

    Raises
    ------
    ValueError
        A parameter the law does not use, a required one missing, or a value out of its range, in one line
        naming the parameter, the law and (for tables) the row.
    """
    law = LAWS.law(model)
    if rows is None and isinstance(radius, float):
        values = _one_scene(law, given, radius)
        if values is not None:
            return values  # else the arrays below find what is wrong and say it
    shape = np.shape(radius)
    where = (lambda i: "") if rows is None else (lambda i: f" (row {int(rows[i])})")
    values, present = {}, {}  # present: per scene, whether the parameter was given
    for name in PARAMETER_NAMES:
        value = given.get(name)
        values[name] = np.broadcast_to(np.asarray(np.nan if value is None else value, dtype=float), shape).copy()
        present[name] = np.full(shape, value is not None) if rows is None else ~np.isnan(values[name])
    uses = law.parameter_names
    for name in PARAMETER_NAMES:
        if name not in uses and present[name].any():
            extra = np.flatnonzero(present[name].ravel())
            if len(extra):
                raise ValueError(f"{name} is not a parameter of model {model!r} (its parameters: {', '.join(uses)})"
                                 f"{where(extra[0])}")
    if law.spring is Spring.HERTZ and present["modulus"].any():
        by_modulus = present["modulus"]
        _check_array(MODULUS, np.where(by_modulus, values["modulus"], 1.0), where)
        from_modulus = hertz_constant(values["modulus"], radius)
        both = by_modulus & present["k"]
        if np.any(values["k"][both] != np.broadcast_to(from_modulus, shape)[both]):  # equal: a copied scene
            raise ValueError(f"give k or modulus for model {model!r}, not both (k = (4/3) modulus sqrt(R))"
                             f"{where(int(np.flatnonzero(np.ravel(both & (values['k'] != from_modulus)))[0]))}")
        values["k"] = np.where(by_modulus, from_modulus, values["k"])
        present["k"] = present["k"] | by_modulus
    for parameter in law.parameters:
        name = parameter.name
        if name not in PARAMETER_NAMES:  # the law's own: checked with the scene's (Scene, own_parameter_columns)
            continue
        missing = ~present[name]
        if missing.any():
            if parameter.default is None:
                alternative = " (or modulus, the effective modulus E* [Pa])" if law.spring is Spring.HERTZ and name == "k" else ""
                first = int(np.flatnonzero(missing.ravel())[0])
                raise ValueError(f"{name} is required by model {model!r}: {parameter.doc} [{parameter.unit}]"
                                 f"{alternative}{where(first)}")
            values[name][missing] = parameter.default
        _check_array(parameter, values[name], where)
    return values


def _one_scene(law, given: dict, radius: float) -> dict | None:
    """:func:`law_parameters` of one scene in plain floats, where every given value is a float or None and all is
    well: the same rules (each parameter the law's, k from ``modulus``, defaults, ranges) and the same values, or
    None at the first thing amiss, which the array path then names (a numpy call costs more than this scene)."""
    if not all(value is None or isinstance(value, float) for value in given.values()):
        return None
    uses = law.parameter_names
    if any(value is not None and name not in uses for name, value in given.items()):
        return None
    k, modulus = given.get("k"), given.get("modulus")
    if law.spring is Spring.HERTZ and modulus is not None:
        if not (math.isfinite(modulus) and MODULUS.ok(modulus)):
            return None
        from_modulus = float(hertz_constant(modulus, radius))
        if k is not None and k != from_modulus:
            return None
        k = from_modulus
    values = dict.fromkeys(PARAMETER_NAMES, math.nan)
    if modulus is not None:
        values["modulus"] = modulus
    for parameter in law.parameters:
        name = parameter.name
        if name not in PARAMETER_NAMES:  # the law's own: checked with the scene's
            continue
        value = k if name == "k" else given.get(name)
        if value is None:
            value = parameter.default
        if value is None or not (math.isfinite(value) and parameter.ok(value)):
            return None
        values[name] = float(value)
    return values


def _check_array(parameter, values: np.ndarray, where) -> None:
    with np.errstate(invalid="ignore"):
        bad = ~(np.isfinite(values) & parameter.ok(values))
    if np.any(bad):
        i = int(np.flatnonzero(np.ravel(bad))[0])
        raise ValueError(f"{parameter.name} must be {parameter.range_text}; got {float(np.ravel(values)[i])!r}"
                         f"{where(i)}")


def check_columns(columns: dict) -> dict:
    """Validate arrays of scene parameters (as :class:`Scene` does one value), naming the first bad row.

    Parameters
    ----------
    columns : dict of str -> array_like
        Scene field -> values; numeric fields must be numbers, ``model``, ``separation`` and ``tangential``
        strings.  (The tangential parameters are checked per scene, by :class:`Scene`.)  Law
        parameters (k, b, ...) are checked against each row's law (missing ones take the law's default).

    Returns
    -------
    dict of str -> float array
        The law parameters of every row (:func:`law_parameters`), when ``model`` and ``diameter`` are given.

    Raises
    ------
    ValueError
        ``"<name> must be <range>; got <value> (row <i>)"``.
    """
    for name, values in columns.items():
        if name in RULES or name in PATH_RULES or name in PARTNER_RULES:
            optional = name not in RULES  # a path or partner field is NaN in the rows that do not give it
            allowed, ok = (RULES | PATH_RULES | PARTNER_RULES)[name]
            raw = np.asarray(values)
            if raw.dtype == bool or (raw.dtype == object and any(isinstance(v, (bool, np.bool_)) for v in raw.flat)):
                raise TypeError(f"{name} must be real numbers; got a boolean")
            try:
                arr = np.asarray(values, dtype=float)
            except (TypeError, ValueError):
                raise ValueError(f"{name} must be {allowed}; got a non-numeric value") from None
            with np.errstate(invalid="ignore"):
                bad = ~(np.isfinite(arr) & ok(arr))
            if optional:
                bad &= ~np.isnan(arr)
            if bad.any():
                i = int(np.flatnonzero(bad)[0])
                raise ValueError(f"{name} must be {allowed}; got {float(arr[i])!r} (row {i})")
        elif name in TEXT_FIELDS:
            choices = {"model": tuple(LAWS), "separation": SEPARATION_CRITERIA, "tangential": tuple(TANGENTIALS)}[name]
            unknown = sorted({str(v) for v in set(np.asarray(values, dtype=object).ravel().tolist())} - set(choices))
            if unknown:
                raise ValueError(f"{name} must be one of {', '.join(choices)}; got {unknown[0]!r}")
        elif name in PARAMETER_NAMES or name in TANGENTIAL_PARAMETERS or name in own_parameters():
            raw = np.asarray(values)
            if raw.dtype == bool:
                raise TypeError(f"{name} must be real numbers; got a boolean")
            try:
                np.asarray(values, dtype=float)
            except (TypeError, ValueError):
                raise ValueError(f"{name} must be a number; got a non-numeric value") from None
        else:
            known = [*RULES, *PATH_RULES, *PARTNER_RULES, *TEXT_FIELDS, *PARAMETER_NAMES, *TANGENTIAL_PARAMETERS,
                     *own_parameters()]
            raise ValueError(f"unknown scene parameter {name!r}; expected one of {', '.join(known)}")
    if all(name in columns for name in ("mass", "speed", "diameter")):
        problem = magnitude_problem(columns["mass"], columns["speed"], columns["diameter"], columns.get("spin", 0.0))
        if problem:
            raise ValueError(problem)
    if "model" not in columns or "diameter" not in columns:
        return {}
    models = np.asarray(columns["model"], dtype=object).ravel()
    radius = 0.5 * np.broadcast_to(np.asarray(columns["diameter"], dtype=float), models.shape)
    out = {name: np.full(models.shape, np.nan) for name in PARAMETER_NAMES}
    for model in dict.fromkeys(models.tolist()):
        rows = np.flatnonzero(models == model)
        given = {name: np.broadcast_to(np.asarray(columns[name], dtype=float), models.shape)[rows]
                 for name in PARAMETER_NAMES if name in columns}
        resolved = law_parameters(model, given, radius[rows], rows=rows)
        for name in PARAMETER_NAMES:
            out[name][rows] = resolved[name]
    return out


def own_parameter_columns(columns: dict, n: int) -> dict:
    """The own parameters of each row's law and tangential model (:mod:`sphereimpact.contact.parameters`), as
    :class:`~sphereimpact.impact.scene.Scene` checks one scene's: given in the rows whose models declare them,
    defaults filled in, each value in its range.

    Parameters
    ----------
    columns : dict of str -> array
        The table's columns: ``model`` and ``tangential`` (names per row) and any own parameter's values
        (NaN or a missing column: not given).
    n : int
        Rows.

    Returns
    -------
    dict of str -> float array
        Every own parameter the table's models declare: its values, NaN in the rows whose models do not.

    Raises
    ------
    ValueError
        A value given in a row whose models do not declare it, a required one missing, or one out of its
        range, naming the parameter and the row.
    """
    models, tangentials = (np.asarray(columns[key], dtype=object).ravel() for key in ("model", "tangential"))
    out = {}
    for name, parameter in own_parameters().items():
        owners = [("model", law.name, models) for law in LAWS.values() if parameter in law.own_parameters]
        owners += [("tangential", model.name, tangentials) for model in TANGENTIALS.values()
                   if parameter in model.own_parameters]
        users = np.zeros(n, bool)
        for _, owner, names in owners:
            users |= names == owner
        values = (np.broadcast_to(np.asarray(columns[name], dtype=float), (n,)).copy() if name in columns
                  else np.full(n, np.nan))
        present = ~np.isnan(values)
        stray = np.flatnonzero(present & ~users)
        if stray.size:
            i = int(stray[0])
            raise ValueError(f"{name} is not a parameter of model {models[i]!r} or tangential {tangentials[i]!r} "
                             f"(row {i})")
        missing = np.flatnonzero(users & ~present)
        if missing.size:
            if parameter.default is None:
                i = int(missing[0])
                owner = next(f"{kind} {who!r}" for kind, who, names in owners if names[i] == who)
                raise ValueError(f"{name} is required by {owner}: {parameter.doc} [{parameter.unit}] (row {i})")
            values[missing] = parameter.default
        rows = np.flatnonzero(users)
        if rows.size:
            _check_array(parameter, values[rows], lambda i: f" (row {int(rows[i])})")
            out[name] = values
    return out
