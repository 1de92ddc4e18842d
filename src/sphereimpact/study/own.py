"""A study of one's own ball: its scenes from its config sections, and their checks (the tables, figures and
page it writes are :mod:`.own_outputs`'), all under ``results/studies/<name>/``.

A study other than the chapter's (config key ``study``) reads only its own sections: ``ball`` (mass,
diameter, inertia factor, the numbers' source), ``surface`` (friction, gravity along the level surface's
normal, or a partner sphere the ball strikes instead), ``contact`` (a law and its parameters, or its damping,
and stiffness, set from a COR, and contact time, measured at ``cor_speed``; a tangential model), ``bounces``
(name -> speed along the path, one description of the approach, spin), ``ranges`` (the speed curve's and the
maps' grids) and, optionally, ``fit`` (measured bounces and the parameters to fit to them: the study then uses
the fitted ball).  It never reads or writes the chapter's files.
"""

from __future__ import annotations

from .. import plugins
from ..impact.ball import Ball, Measurement, calibrated_ball, load_ball, uncalibrated, undescribed
from ..contact.laws import LAWS, Relation
from ..memory import check_size
from ..parsing import parse_range, range_count
from ..impact.inputs import PATH_RULES
from ..impact.scene import Scene, SolverOptions
from ..contact.materials import material_fields
from ..contact.tangential import TANGENTIALS

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


#: The keys of a study's ``contact`` section that are not a parameter of its models: every other key is one,
#: built-in or a plug-in's, by name (the Scene checks that its models declare it).
CONTACT_KEYS = ("model", "separation", "tangential", "materials", "settings", "cor", "contact_time", "cor_speed",
                "cor_relation")


def _fields(config: dict) -> dict:
    """The Scene fields of the study's ball, contact and surface sections (without the measurement)."""
    ball, surface, contact = config["ball"], config["surface"], config["contact"]
    given = {name: value for name, value in contact.items() if name not in CONTACT_KEYS}
    if "materials" in contact:  # E* (and kappa) of the two bodies, as a DEM deck gives them
        body = {name: (m["E"], m["nu"]) for name, m in contact["materials"].items()}
        given |= material_fields(body["ball"], body.get("surface"),
                                 bool(TANGENTIALS.model(contact["tangential"]).stiffness_parameters), set(given))
    return dict(mass=ball["mass"], diameter=ball["diameter"], inertia_factor=ball["inertia_factor"], mu=surface["mu"],
                gravity=surface["gravity"], model=contact["model"], separation=contact["separation"],
                tangential=contact["tangential"], **given,
                **{f"partner_{name}": value for name, value in surface.get("partner", {}).items()})


def measurement(config: dict) -> Measurement | None:
    """What the study's ``contact`` section says was measured (COR at ``cor_speed``, contact time), if anything."""
    contact = config["contact"]
    if "cor" not in contact:
        return None
    return Measurement(contact["cor"], contact.get("cor_speed", 1.0), contact.get("contact_time"),
                       contact["cor_relation"])


def study_ball(config: dict, fitted: str | None = None) -> Ball:
    """The study's ball: from its ``ball_file``, or from its ball, surface and contact sections, its damping (and k)
    calibrated to the configured COR (and contact time) at ``cor_speed`` (1 m/s if not given) when one is given.
    The config's ``plugins`` are imported first; ``contact`` gives its models' parameters by name, a plug-in's as
    the built-in ones, and ``contact.settings`` their settings.  ``fitted``: the ball file its ``fit`` section's
    fit wrote, which then is the study's ball."""
    names = tuple(plugins.load(config.get("plugins", [])))
    if fitted:
        return load_ball(fitted)
    if config.get("ball_file"):
        return load_ball(config["ball_file"])
    options = SolverOptions(settings=config["contact"].get("settings", {}))
    source = config["ball"].get("source", "")
    measured = measurement(config)
    if measured is None:
        return Ball(Scene(**_fields(config)), options=options, plugins=names, source=source)
    return calibrated_ball(measured, options, names, source, **_fields(config))


def described_ball(config: dict) -> Ball:
    """The study's ball as its sections describe it, without solving anything: its ball file's, or its scene
    with stand-ins for what the measurement will calibrate (:func:`~sphereimpact.impact.ball.uncalibrated`) and
    the measurement; what the config checks check."""
    if config.get("ball_file"):
        return study_ball(config)
    measured = measurement(config)
    return Ball(Scene(**_fields(config)) if measured is None else uncalibrated(measured, **_fields(config)), measured)


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
    try:  # sized before any range is made: a fine step would otherwise fail inside a job, out of memory
        counts = {key: range_count(config["ranges"][key]) for key in ("speeds", "map_speeds", "map_angles")}
        check_size({"speeds": counts["speeds"]}, "a coarser ranges.speeds")
        check_size({"map_angles": counts["map_angles"], "map_speeds": counts["map_speeds"]},
                   "coarser ranges.map_angles or ranges.map_speeds")
    except ValueError as err:
        return errors + [f"config key ranges: {err}"]
    for key in ("speeds", "map_speeds", "map_angles"):
        try:
            values = parse_range(config["ranges"][key])
            if key != "map_angles" and not (values > 0).all():
                errors.append(f"config key ranges.{key}: speeds must be > 0 m/s")
            if key == "map_angles" and not ((values > 0) & (values <= 90)).all():
                errors.append("config key ranges.map_angles: angles to the surface must be in (0, 90] degrees")
        except ValueError as err:
            errors.append(f"config key ranges.{key}: {err}")
    if config.get("ball_file"):
        try:
            ball = study_ball(config).scene
        except ValueError as err:
            return errors + [f"config key ball_file: {err}"]
        if ball.chapter_ball:  # saved from simulate's defaults: its file says so
            return errors + [f"config key ball_file: {config['ball_file']!r} takes the chapter's "
                             f"{', '.join(ball.chapter_ball)} (saved from simulate's defaults), not your ball's: "
                             "describe your ball; no ball is assumed"]
    else:
        contact = config["contact"]
        if contact.get("model") not in LAWS:
            errors.append(f"config key contact.model: {contact.get('model')!r} is not a registered law "
                          f"({', '.join(LAWS)})")
            return errors
        given = {*config["ball"], *contact, *(["ball_material"] if "materials" in contact else [])}
        missing = undescribed(given, contact["model"])
        if missing:
            keys = {"mass": "ball.mass", "diameter": "ball.diameter", "ball_material": "contact.materials"}
            errors.append("config key ball (or contact): describe your ball: give " + ", ".join(
                " or ".join(keys.get(part, f"contact.{part}") for part in name.split(" or ")) for name in missing)
                + " (or a ball_file); no ball is assumed")
            return errors
        if ("contact_time" in contact or "cor_relation" in contact and contact["cor_relation"] != Relation.EXACT
                or "cor_speed" in contact) and "cor" not in contact:
            errors.append("config key contact: contact_time, cor_speed and cor_relation need cor")
        try:  # the ball and every bounce as Scene checks them, without the (slower) calibration
            ball = described_ball(config).scene
            SolverOptions(settings=config["contact"].get("settings", {}))
        except (ValueError, TypeError) as err:
            errors.append(f"config key contact (or ball, surface, plugins): {err}")
            return errors
    for name, spec in config.get("bounces", {}).items():
        try:
            bounce_scene(ball, spec)
        except ValueError as err:
            errors.append(f"config key bounces.{name}: {err}")
    return errors + _range_errors(config["ranges"], ball)


def _range_errors(ranges: dict, ball: Scene) -> list[str]:
    """The speed curve's and the maps' scenes at the corners of their grids (where a scale or a square overflows
    first), as Scene checks them: what the jobs would refuse, refused before any job runs."""
    try:
        grids = {"speeds": [{"speed": v, "angle_to_surface": 90.0} for v in _ends(ranges["speeds"])],
                 "map_speeds, map_angles, map_spin": [{"speed": v, "angle_to_surface": a, "spin": ranges["map_spin"]}
                                                       for v in _ends(ranges["map_speeds"])
                                                       for a in _ends(ranges["map_angles"])]}
    except ValueError:  # a range that does not parse: said above, with its key
        return []
    errors = []
    for keys, specs in grids.items():
        for spec in specs:
            try:
                bounce_scene(ball, spec)
            except ValueError as err:
                errors.append(f"config key ranges ({keys}): {err}")
                break
    return errors


def _ends(text: str) -> tuple:
    """A range's first and last value."""
    values = parse_range(text)
    return float(values.min()), float(values.max())


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


