"""A ball described once: its measured COR (and contact time) at a stated speed, calibrated, saved, reused.

A user measures a ball's coefficient of restitution in a normal impact at some speed, perhaps its contact
time too, not a damping coefficient or a stiffness.  :func:`calibrated_ball` sets the law's damping (and k)
from a :class:`Measurement` in a normal impact at the measurement's speed, the same way wherever the ball is
described: ``simulate`` and ``sweep`` on the command line (``--cor``, ``--cor-speed``, ``--contact-time``), the
study config's ``contact`` section and this API.  A :class:`Ball` is the calibrated scene (its approach is the
measurement's) with what was fitted; :func:`save_ball` writes it as JSON and :func:`load_ball` reads it back
for every door (``--ball FILE``, the config's ``ball_file``), so a ball is calibrated once.  The file holds the
ball, its contact and its surface, never an approach: each bounce gives its own (:data:`SECTIONS`).

A law calibrated at one speed extrapolates at others: :meth:`Ball.far_from_measurement` says so, with the
factor, where a scene's normal speed differs from the measurement's by more than :data:`FAR`.
"""

from __future__ import annotations

import json
import math
import sys
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import plugins as plugin_modules
from ..errors import ExtrapolationWarning
from ..files import write_text
from ..contact.declared import own_parameters
from ..contact.laws import LAWS, Relation, Spring
from .calibrate import Calibration, calibrate, check_measurement
from .inputs import as_number, check_flag
from .pair import PARTNER_FIELDS
from .scene import CHAPTER_BALL, SCENE_KEYS, ChapterValue, Scene, SolverOptions, chapter_law_parameters

#: A scene whose normal speed differs from the measurement's by more than this factor (either way) is an
#: extrapolation of the calibrated law, and is said to be.
FAR = 2.0
#: The ball file's format, written into every file and checked on reading.
FORMAT = "sphereimpact-ball/2"
#: Scene fields that describe the approach (not the ball, its contact or the surface); a measured bounce's
#: approach columns, in this order (:mod:`sphereimpact.fit.measured`).
APPROACH = ("speed", "incidence", "angle_to_surface", "angle", "spin")
#: A ball file's sections, each the Scene fields it holds: the ball's body, its contact (the law and its
#: parameters, friction, the separation criterion, the tangential model; a plug-in's parameters too, after these)
#: and what it strikes (the flat's gravity, or a partner sphere).  Together every Scene field and parameter but the
#: :data:`APPROACH`, which each bounce gives.
_BODY, _STRUCK = ("mass", "diameter", "inertia_factor"), ("gravity", *PARTNER_FIELDS)
SECTIONS = {"ball": _BODY,
            "contact": tuple(name for name in SCENE_KEYS if name not in (*APPROACH, *_BODY, *_STRUCK)),
            "surface": _STRUCK}


@dataclass(frozen=True)
class Measurement:
    """What was measured of a ball: its COR in a normal impact at ``speed``, optionally the contact time.

    Attributes
    ----------
    cor : float
        Normal coefficient of restitution, in (0, 1) for a damped law (1 with a contact time for an elastic
        one).
    speed : float
        The normal impact speed of the measurement [m/s], > 0.
    contact_time : float or None
        The contact time measured at that speed [s], > 0: then k is fitted too.
    relation : Relation or str
        ``exact`` (root find) or a published COR relation of the law: a :class:`~sphereimpact.contact.laws.Relation`
        or its word.
    """

    cor: float
    speed: float
    contact_time: float | None = None
    relation: Relation = Relation.EXACT

    def __post_init__(self):
        object.__setattr__(self, "cor", as_number("cor", self.cor))
        speed = as_number("cor_speed", self.speed)
        if not (math.isfinite(speed) and speed > 0):
            raise ValueError(f"cor_speed must be a finite number > 0 m/s (the normal speed of the COR's "
                             f"measurement); got {self.speed!r}")
        object.__setattr__(self, "speed", speed)
        if self.contact_time is not None:
            t = as_number("contact_time", self.contact_time)
            if not (math.isfinite(t) and t > 0):
                raise ValueError(f"contact_time must be a finite number > 0 s; got {self.contact_time!r}")
            object.__setattr__(self, "contact_time", t)
        object.__setattr__(self, "relation", Relation.parse(self.relation, "cor_relation"))

    def extrapolates(self, v_normal):
        """Whether a normal speed [m/s] (a number or an array of them) lies more than :data:`FAR` times from the
        measurement's either way: there the law calibrated to it extrapolates."""
        factor = np.asarray(v_normal) / self.speed
        return (factor > FAR) | (factor < 1.0 / FAR)


@dataclass(frozen=True)
class Ball:
    """A ball, its contact and its surface, with what was measured and fitted.

    Attributes
    ----------
    scene : Scene
        The ball in a normal impact at the measurement's speed (without a measurement, any scene of the ball; read
        from a file, the Scene's default approach, its speed not given): :func:`ball_scene` puts it in a bounce.
    measurement : Measurement or None
        What its damping (and k) were calibrated to; None when the law's parameters were given.
    fitted : dict
        Parameter -> value set by the calibration (the damping, and ``k`` with a contact time).
    relations : dict
        The law's published COR relations -> the damping each gives for the measured COR (beside ``fitted``).
    options : SolverOptions
        The settings of its tangential model (``SolverOptions.settings``), the integrator's defaults.
    plugins : tuple of str
        The plug-in modules whose models it uses: :func:`load_ball` requires them loaded by the user, never
        importing them itself (a data file runs no code).
    source : str
        Where its numbers come from, for the reader.
    """

    scene: Scene
    measurement: Measurement | None = None
    fitted: dict = field(default_factory=dict)
    relations: dict = field(default_factory=dict)
    options: SolverOptions = SolverOptions()
    plugins: tuple = ()
    source: str = ""

    def far_from_measurement(self, scene: Scene) -> str | None:
        """One line when ``scene``'s normal speed is more than :data:`FAR` times the measurement's (or less
        than 1 / FAR), else None: there the calibrated law extrapolates."""
        if self.measurement is None:
            return None
        if not self.measurement.extrapolates(scene.v_normal):
            return None
        factor = scene.v_normal / self.measurement.speed
        return (f"the normal speed {scene.v_normal:.3g} m/s is {factor:.3g} times the {self.measurement.speed:.3g} "
                f"m/s at which the COR {self.measurement.cor:g} was measured: the {scene.model!r} law, calibrated "
                "there, extrapolates")


#: What describes a ball's stiffness or damping besides the law's own parameter: a measured contact time (k), the
#: bodies' materials (the modulus), a measured COR (the damping).
STIFFNESS_GIVEN = ("k", "modulus", "contact_time", "ball_material")


def undescribed(given, model: str, approach: bool = False) -> list[str]:
    """The parts of a ball's description that ``given`` lacks, where the package's default is the chapter's ball:
    its mass and diameter (145 g, 63 mm), the stiffness and the damping of a law whose defaults are the chapter's
    (k = 60000 N/m, b = 10.5 N s/m), and with ``approach`` its approach speed (3 m/s).  A door that takes the
    user's own ball (``fit``, ``sweep``, a study) refuses it without them, a sweep its speed too (a fit reads the
    approach from its bounces, a plan from its candidates); ``simulate`` alone runs the chapter's scene and says so.

    Parameters
    ----------
    given : collection of str
        The names the user gave: Scene fields, ``cor``, ``contact_time``, ``ball_material``.
    model : str
        The normal force law's name.
    approach : bool
        Whether the approach speed is part of what must be given.

    Returns
    -------
    list of str
        Each missing part as the option that gives it (``mass``, ``diameter``, ``k or modulus or contact_time``,
        ``b or cor``, ``speed``); empty when the ball is described.
    """
    law, given = LAWS.law(model), set(given)
    chapter, damping = chapter_law_parameters(law), law.damping
    missing = [name for name in ("mass", "diameter") if name not in given]
    if "k" in chapter and not given & set(STIFFNESS_GIVEN):
        missing.append(" or ".join(name for name in STIFFNESS_GIVEN if name in law.parameter_names or name == "contact_time"
                                   or (name == "ball_material" and "modulus" in law.parameter_names)))
    if damping in chapter and not given & {damping, "cor"}:
        missing.append(f"{damping} or cor")
    return missing + (["speed"] if approach and "speed" not in given else [])


def check_described(ball, door: str, chapter_ball: bool) -> None:
    """Refuse (ValueError naming the parts) a ``ball`` whose scene took parts of the chapter's ball where its maker was
    silent (:attr:`Scene.chapter_ball <sphereimpact.Scene.chapter_ball>`), unless ``chapter_ball``: the API's
    ``fit`` and ``plan`` take the user's ball, as their command lines do; only ``simulate`` takes the chapter's
    unasked."""
    taken = () if check_flag("chapter_ball", chapter_ball) else ball.scene.chapter_ball
    if taken:
        raise ValueError(f"{door}: describe the ball: its {', '.join(taken)} are the chapter's defaults, not given "
                         f"(give them, or ask for the chapter's: chapter_ball=True, --chapter-ball); only simulate "
                         "takes the chapter's ball unasked")


def chapter_parts(scene) -> list[str]:
    """The parts of ``scene``'s ball taken from the chapter's (:attr:`Scene.chapter_ball
    <sphereimpact.Scene.chapter_ball>`), named as :func:`undescribed` names them: what a note asks the user to give."""
    taken, damping = set(scene.chapter_ball), scene.law.damping
    given = {"mass", "diameter"} - taken
    if "k" not in taken:
        given |= set(STIFFNESS_GIVEN)
    if damping is None or damping not in taken:
        given |= {"cor", *([damping] if damping else [])}
    return undescribed(given, scene.model)


def starting_stiffness(model: str, mass: float, contact_time: float, speed: float) -> float:
    """A stiffness k whose contact lasts about ``contact_time`` [s] at ``speed`` [m/s], to start a fit from:
    t = pi sqrt(m / k) for a linear spring, t = 2.94 (5 m / (4 k))^(2/5) v^(-1/5) for a Hertz one."""
    if LAWS.law(model).spring is Spring.LINEAR:
        return mass * (math.pi / contact_time) ** 2
    return 1.25 * mass / (contact_time * speed ** 0.2 / 2.94) ** 2.5


def uncalibrated(measurement: Measurement, **fields) -> Scene:
    """The scene :func:`calibrated_ball` calibrates: the ball of Scene ``fields`` in a normal impact at the
    measurement's speed, with stand-ins for what the calibration sets (the damping, and k with a contact time).
    Building it checks every input but whether the measurement can be reached, without solving anything.

    Raises
    ------
    ValueError
        A measurement the law cannot take (:func:`~.calibrate.check_measurement`), the damping or k given besides
        the measurement that sets them, or a field Scene refuses.
    """
    law = LAWS.law(fields.get("model", Scene.__dataclass_fields__["model"].default))
    check_measurement(law, measurement.cor, measurement.relation, measurement.contact_time)
    if law.damping is not None and fields.get(law.damping) is not None:
        raise ValueError(f"give {law.damping} or cor, not both (cor sets {law.damping})")
    for name in ("k", "modulus"):
        if measurement.contact_time is not None and fields.get(name) is not None:
            raise ValueError(f"give {name} or contact_time, not both (contact_time fits k)")
    base = {name: value for name, value in fields.items() if name not in APPROACH} | {"speed": measurement.speed}
    if measurement.contact_time is not None:
        base["k"] = starting_stiffness(law.name, base.get("mass", Scene.__dataclass_fields__["mass"].default),
                                       measurement.contact_time, measurement.speed)
    if law.damping is not None:
        base[law.damping] = 0.0  # a stand-in: the calibration sets it
    return Scene(**base)


def calibrated_ball(measurement: Measurement, options: SolverOptions | None = None, plugin_names=(),
                    source: str = "", **fields) -> Ball:
    """The ball described by Scene ``fields`` (mass, diameter, model, its other parameters, tangential model,
    surface) with the law's damping (and, with a contact time, k) set from ``measurement``, in a normal impact
    at the measurement's speed whatever approach ``fields`` give (:func:`uncalibrated`)."""
    calibration: Calibration = calibrate(uncalibrated(measurement, **fields), measurement.cor, measurement.relation,
                                         measurement.contact_time)
    damping = calibration.scene.law.damping
    fitted = {} if damping is None else {damping: getattr(calibration.scene, damping)}
    if measurement.contact_time is not None:
        fitted["k"] = calibration.scene.k
    return Ball(calibration.scene, measurement, fitted, dict(calibration.relations), options or SolverOptions(),
                tuple(plugin_names), source)


def ball_scene(ball: Ball, **approach) -> Scene:
    """The ball in the bounce ``approach`` (some of angle, speed, spin, incidence, angle_to_surface; the rest of
    the approach as the Scene's defaults: a vertical drop on a level flat, no spin); an
    :class:`~sphereimpact.errors.ExtrapolationWarning` where its normal speed is far from the measurement's."""
    unknown = [name for name in approach if name not in APPROACH]
    if unknown:
        raise ValueError(f"{unknown[0]} is not part of the approach ({', '.join(APPROACH)}); the ball file sets "
                         "the rest")
    defaults = {name: Scene.__dataclass_fields__[name].default for name in APPROACH}
    scene = ball.scene.with_(**(defaults | approach))
    far = ball.far_from_measurement(scene)
    if far:
        warnings.warn(far, ExtrapolationWarning, stacklevel=2)
    return scene


def ball_columns(ball: Ball, exclude=()) -> dict:
    """The ball's fields as a sweep table's constant columns (its models' own parameters too), leaving out the
    approach, the names in ``exclude`` and the parameters it does not give."""
    return {name: value for name, value in ball.scene.as_dict().items()
            if name not in (*APPROACH, *exclude) and value is not None and name != "modulus"}  # k holds it


def save_ball(ball: Ball, path) -> None:
    """Write ``ball`` as JSON (format :data:`FORMAT`): its scene without the approach, in :data:`SECTIONS` (each
    bounce gives its own approach; the measurement states the speed it was calibrated at), its measurement, what
    was fitted, its settings, plug-ins and source.  The parts of its ball taken from the chapter's
    (:class:`ChapterValue`) are listed under ``chapter``, so that the ball read back is as undescribed as it was: a
    number alone cannot say it."""
    scene = {k: v for k, v in ball.scene.as_dict().items() if k != "modulus" or ball.scene.modulus is not None}
    record = {"format": FORMAT, "source": ball.source,
              **({"chapter": list(ball.scene.chapter_ball)} if ball.scene.chapter_ball else {}),
              **({"plugins": list(ball.plugins)} if ball.plugins else {}),
              **({"settings": dict(ball.options.settings)} if ball.options.settings else {}),
              **{section: {name: scene[name] for name in _section(section) if name in scene} for section in SECTIONS},
              "measurement": None if ball.measurement is None else {
                  "cor": ball.measurement.cor, "cor_speed": ball.measurement.speed,
                  "contact_time": ball.measurement.contact_time, "relation": ball.measurement.relation},
              "fitted": ball.fitted, **({"relations": ball.relations} if ball.relations else {})}
    write_text(path, json.dumps(record, indent=2) + "\n")  # whole or not at all: --force never truncates a ball


def _section(section: str) -> tuple:
    """The names ``section`` may hold: those of :data:`SECTIONS`, and in ``contact`` every parameter a registered
    model declares besides (a plug-in's, which the file names the plug-in of)."""
    return (*SECTIONS[section], *(own_parameters() if section == "contact" else ()))


def load_ball(path, plugins=()) -> Ball:
    """The ball :func:`save_ball` wrote.

    A ball file names the plug-ins whose models it uses but never imports them: a data file from someone else
    must not run code.  Each must be among ``plugins`` (the modules the user names: ``--plugin``, a study
    config's ``plugins``), which are imported here, or already imported.

    Raises
    ------
    ValueError
        A file that is not a ball file of this format, a plug-in it names that the user did not load, or a scene
        the package refuses (naming the file).
    """
    try:
        record = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as err:
        raise ValueError(f"ball: cannot read {str(path)!r} ({err.strerror or err})") from None
    except json.JSONDecodeError as err:
        raise ValueError(f"ball: {str(path)!r} is not JSON ({err.msg}, line {err.lineno})") from None
    if not isinstance(record, dict) or record.get("format") != FORMAT:
        found = f"; its format is {record['format']!r}" if isinstance(record, dict) and "format" in record else ""
        raise ValueError(f"ball: {str(path)!r} is not a ball file of format {FORMAT!r} (written by --save-ball, "
                         f"save_ball or a study's ball.json){found}")
    named = record.get("plugins", [])
    if not isinstance(named, list) or not all(isinstance(name, str) for name in named):
        raise ValueError(f"ball: {str(path)!r}: plugins must be a list of module names; got {named!r}")
    loaded = set(plugin_modules.load(plugins))
    missing = [name for name in named if name not in loaded and name not in sys.modules]
    if missing:
        raise ValueError(f"ball: {str(path)!r} uses the plug-in {missing[0]!r}, which is not loaded; a ball file "
                         f"never imports code: load it yourself (--plugin {missing[0]}, the study config's plugins, "
                         f"or import {missing[0]}) if you trust it")
    chapter = record.get("chapter", [])
    if not isinstance(chapter, list) or not set(chapter) <= set(CHAPTER_BALL):
        raise ValueError(f"ball: {str(path)!r}: chapter must be a list of the parts taken from the chapter's ball "
                         f"({', '.join(CHAPTER_BALL)}); got {chapter!r}")
    given = {}
    for section in SECTIONS:
        values = record.get(section, {})
        names = _section(section)
        stray = [name for name in values if name not in names] if isinstance(values, dict) else None
        if stray is None or stray:
            where = (f"{stray[0]!r} is part of the approach, which each bounce gives, not the ball file" if stray
                     and stray[0] in APPROACH else f"it holds {', '.join(names)}; got {values if stray is None else stray!r}")
            raise ValueError(f"ball: {str(path)!r}: section {section!r}: {where}")
        given |= values
    try:
        measured = record.get("measurement")
        measurement = None if measured is None else Measurement(measured["cor"], measured["cor_speed"],
                                                                measured.get("contact_time"),
                                                                measured.get("relation", Relation.EXACT))
        scene = Scene(**given | {name: ChapterValue(given[name]) for name in chapter if given.get(name) is not None},
                      **({} if measurement is None else {"speed": measurement.speed}))
        options = SolverOptions(settings=record.get("settings", {}))
    except (KeyError, TypeError, ValueError) as err:
        raise ValueError(f"ball: {str(path)!r}: {err}") from None
    return Ball(scene, measurement, dict(record.get("fitted", {})), dict(record.get("relations", {})), options,
                tuple(named), record.get("source", ""))
