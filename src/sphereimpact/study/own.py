"""A study of one's own ball: its scenes from its config sections, and their checks (the tables, figures and
page it writes are :mod:`.own_outputs`'), all under ``results/studies/<name>/``.

A study other than the chapter's (config key ``study``) reads only its own sections: ``ball`` (mass,
diameter, inertia factor, the numbers' source), ``surface`` (friction, gravity along the level surface's
normal), ``contact`` (a law and its parameters, or its damping, and stiffness, set from a COR, and contact
time, measured at ``cor_speed``; a tangential model), ``bounces`` (name -> speed along the path, one
description of the approach, spin) and ``ranges`` (the speed curve's and the maps' grids).  It never reads or
writes the chapter's files.
"""

from __future__ import annotations

import math

from .. import plugins
from ..impact.calibrate import calibrate
from ..contact.laws import LAWS, PARAMETER_NAMES
from ..parsing import parse_range
from ..impact.inputs import PATH_RULES
from ..impact.scene import Scene, SolverOptions
from ..contact.tangential import TANGENTIAL_PARAMETERS

#: The chapter's study: the replication.  Any other name is a study of one's own ball.
CHAPTER = "chapter4"
#: Where a study's files go.
ROOT = "results/studies"


def is_own(config: dict) -> bool:
    """True for a study of one's own ball (any ``study`` name but the chapter's)."""
    return config.get("study", CHAPTER) != CHAPTER


def folder(config: dict) -> str:
    """The study's folder, ``results/studies/<name>``."""
    return f"{ROOT}/{config['study']}"


def _starting_k(law, mass: float, contact_time: float, speed: float) -> float:
    """A stiffness whose contact lasts about ``contact_time`` [s] at ``speed`` [m/s], to start the fit from:
    t = pi sqrt(m / k) for a linear spring, t = 2.94 (5 m / (4 k))^(2/5) v^(-1/5) for a Hertz one."""
    if law.spring == "linear":
        return mass * (math.pi / contact_time) ** 2
    return 1.25 * mass / (contact_time * speed ** 0.2 / 2.94) ** 2.5


def ball_scene(config: dict) -> Scene:
    """The study's ball on its surface, with its contact law, approached normally at the COR's speed (or 1
    m/s): its damping (and k) calibrated to the configured COR (and contact time) when one is given.  The
    config's ``plugins`` are imported first, and ``contact.parameters`` are its models' own parameters."""
    plugins.load(config.get("plugins", []))
    ball, surface, contact = config["ball"], config["surface"], config["contact"]
    law = LAWS.law(contact["model"])
    given = {name: contact[name] for name in (*PARAMETER_NAMES, *TANGENTIAL_PARAMETERS) if name in contact}
    speed = contact.get("cor_speed", 1.0)
    if "contact_time" in contact and "cor" in contact and "k" not in given and "modulus" not in given:
        given["k"] = _starting_k(law, ball["mass"], contact["contact_time"], speed)
    scene = Scene(mass=ball["mass"], diameter=ball["diameter"], inertia_factor=ball["inertia_factor"],
                  mu=surface["mu"], gravity=surface["gravity"], model=contact["model"], speed=speed,
                  separation=contact["separation"], tangential=contact["tangential"], **given,
                  parameters=contact.get("parameters", {}))
    if "cor" not in contact:
        return scene
    return calibrate(scene, contact["cor"], contact["cor_relation"], contact.get("contact_time")).scene


def ball_options(config: dict) -> SolverOptions:
    """The solver options of the study's impacts: its tangential model's settings (``contact.settings``)."""
    plugins.load(config.get("plugins", []))
    return SolverOptions(settings=config["contact"].get("settings", {}))


def bounce_scene(ball: Scene, spec: dict) -> Scene:
    """The ball in one configured bounce: speed along the path, the approach, spin."""
    path = {name: spec[name] for name in ("angle", *PATH_RULES) if name in spec}
    return ball.with_(speed=spec["speed"], spin=spec.get("spin", 0.0), **({"angle": 0.0} | path))


def own_errors(config: dict) -> list[str]:
    """Every problem of an own study's sections, one line each naming the key (before any job runs)."""
    if not is_own(config):
        return []
    errors = []
    if not config.get("bounces"):
        errors.append("config key bounces: a study of one's own ball needs at least one bounce")
    for key in ("speeds", "map_speeds", "map_angles"):
        try:
            values = parse_range(config["ranges"][key])
            if key != "map_angles" and not (values > 0).all():
                errors.append(f"config key ranges.{key}: speeds must be > 0 m/s")
            if key == "map_angles" and not ((values > 0) & (values <= 90)).all():
                errors.append("config key ranges.map_angles: angles to the surface must be in (0, 90] degrees")
        except ValueError as err:
            errors.append(f"config key ranges.{key}: {err}")
    contact = config["contact"]
    if contact.get("model") not in LAWS:
        errors.append(f"config key contact.model: {contact.get('model')!r} is not a registered law ({', '.join(LAWS)})")
        return errors
    if ("contact_time" in contact or "cor_relation" in contact and contact["cor_relation"] != "exact") \
            and "cor" not in contact:
        errors.append("config key contact: contact_time and cor_relation need cor")
    law = LAWS[contact["model"]]
    probe = {k: v for k, v in contact.items() if k not in ("cor", "contact_time", "cor_relation")}
    if "cor" in contact and law.damping is not None and law.damping not in contact:
        probe[law.damping] = 0.0  # a stand-in where the calibration will set it
    if "contact_time" in contact and "k" not in contact and "modulus" not in contact:
        probe["k"] = _starting_k(law, config["ball"]["mass"], contact["contact_time"], contact.get("cor_speed", 1.0))
    try:  # the ball and every bounce as Scene checks them, without the (slower) calibration
        ball = ball_scene(config | {"contact": probe})
        ball_options(config)
    except (ValueError, TypeError) as err:
        errors.append(f"config key contact (or ball, surface, plugins): {err}")
        return errors
    for name, spec in config.get("bounces", {}).items():
        try:
            bounce_scene(ball, spec)
        except ValueError as err:
            errors.append(f"config key bounces.{name}: {err}")
    return errors


def outputs(config: dict) -> dict:
    """Every file of the study, by role (paths relative to the project): what the pipeline's rule ``all``
    asks for."""
    root = folder(config)
    bounces = list(config["bounces"])
    return {"ball": f"{root}/ball.json", "outcomes": f"{root}/outcomes.csv",
            "histories": {b: f"{root}/histories/{b}.csv" for b in bounces},
            "bounce_figures": {b: f"{root}/figures/{b}.png" for b in bounces},
            "speed": f"{root}/speed.csv", "maps": f"{root}/maps.csv",
            "figures": {name: f"{root}/figures/{name}.png" for name in ("speed", "spin_map", "rebound_map")},
            "page": {"md": f"{root}/index.md", "html": f"{root}/index.html"}}


