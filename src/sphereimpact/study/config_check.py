"""The configuration's checks, run before any job: the schema's violations, numbers that are not finite, the
sweep's ranges, the laws' and tangential models' names, and an own study's sections, each one line naming the
config key (:func:`check_config`, called by the Snakefile)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import plugins
from ..files import load_yaml
from ..contact.laws import LAWS
from .config import with_defaults
from .own import CHAPTER


#: The configuration's schema, shipped with the package: a link to the project's ``config/schema.yaml`` (one file;
#: a built wheel holds its content), for the command line's doors that read a study config themselves.
SCHEMA = str(Path(__file__).with_name("schema.yaml"))
#: Sections only a study of one's own ball reads.
OWN_SECTIONS = ("ball_file", "ball", "surface", "contact", "bounces", "ranges", "fit", "plan")


def config_errors(config: dict, schema_path: str) -> list[str]:
    """Every problem of ``config``, one line each naming the config key first.

    The JSON schema's violations (a YAML 1.1 number read as text, like ``1e4``, gets a hint), numbers
    that are not finite (NaN passes every schema bound, since NaN comparisons are false), and the sweep
    section's ranges: parsed, checked against the scene's ranges, sized against memory, with
    ``map_speed`` on the speed grid.
    """
    import jsonschema

    with open(schema_path) as handle:
        schema = load_yaml(handle)
    validator = jsonschema.Draft202012Validator(schema)
    lines = [f"config key {key}: {value!r} is not a finite number" for key, value in _non_finite(config)]
    for error in sorted(validator.iter_errors(config), key=lambda e: list(map(str, e.absolute_path))):
        key = ".".join(map(str, error.absolute_path)) or "(top level)"
        hint = error.schema.get("description", "") if isinstance(error.schema, dict) else ""
        if _number_as_text(error):
            hint = (f"YAML 1.1 reads {error.instance} as text: write it with a decimal point and a signed "
                    f"exponent, e.g. {_yaml_number(error.instance)}")
        lines.append(f"config key {key}: {error.message}" + (f" ({hint})" if hint else ""))
    if not lines:
        from .own import own_errors

        own_sections = [key for key in OWN_SECTIONS if key in config]
        if config.get("study", CHAPTER) == CHAPTER and own_sections:
            return [f"config key study: the config describes a ball of one's own ({', '.join(own_sections)}) but the "
                    f"study is {CHAPTER!r}, the replication, which would ignore it: give study: NAME"]
        try:  # the plug-ins first: the names below may be theirs
            plugins.load(config.get("plugins", []))
        except ValueError as err:
            return [f"config key plugins: {err}"]
        filled = with_defaults(schema, config)
        lines += (_sweep_errors(config, schema) + _law_errors(config) + _tangential_errors(config)
                  + own_errors(filled))
        if config.get("fit"):
            lines += _fit_errors(filled)
        if config.get("plan"):
            lines += _plan_errors(filled)
    return lines


def _plan_errors(config: dict) -> list[str]:
    """An own study's ``plan`` section: its candidates unreadable, a free parameter the study's ball cannot free,
    a noise or size its job would refuse (checked on the ball as described, without calibrating it)."""
    from ..fit.least_squares import free_names
    from ..fit.plan import parse_noise, read_candidates, size_problem
    from .own import described_ball

    section, errors = config["plan"], []
    try:
        candidates = read_candidates(section["candidates"])
    except ValueError as err:
        errors.append(f"config key plan.candidates: {err}")
        candidates = None
    try:
        parse_noise(section["noise"])
    except ValueError as err:
        errors.append(f"config key plan.noise: {err}")
    try:
        names = free_names(described_ball(config), section["free"])
    except ValueError as err:
        errors.append(f"config key plan.free: {err}")
        names = None
    except TypeError:
        names = None
    size = section.get("size")
    if size is not None and candidates is not None and names is not None:
        problem = size_problem(size, len(names), len(candidates))
        if problem:
            errors.append(f"config key plan.size: {problem}")
    return errors


def _fit_errors(config: dict) -> list[str]:
    """An own study's ``fit`` section: its data unreadable, a free parameter the study's ball cannot free
    (checked on the ball as described, without calibrating it).  Nothing when there is no ball to check it
    against: :func:`~.own.own_errors` names what is wrong with the ball."""
    from ..fit import read_measured
    from ..fit.least_squares import free_names
    from .own import described_ball

    try:
        ball = described_ball(config)
    except (ValueError, TypeError):
        return []
    section, errors = config["fit"], []
    try:
        read_measured(section["data"])
    except ValueError as err:
        errors.append(f"config key fit.data: {err}")
    try:
        free_names(ball, section["free"])
    except ValueError as err:
        errors.append(f"config key fit.free: {err}")
    return errors


def _law_errors(config: dict) -> list[str]:
    """The laws section: registered laws, relations that exist, a valid speed range."""
    from ..parsing import parse_range

    section = config.get("laws", {})
    errors = []
    for key in ("models", "relation_models"):
        for name in section.get(key, []):
            if name not in LAWS:
                errors.append(f"config key laws.{key}: {name!r} is not a registered law ({', '.join(LAWS)})")
            elif key == "relation_models" and not LAWS[name].cor_relations:
                errors.append(f"config key laws.relation_models: {name!r} declares no COR relations")
    if "speeds" in section:
        try:
            speeds = parse_range(section["speeds"])
            if not (speeds > 0).all():
                errors.append(f"config key laws.speeds: speed must be > 0 m/s; the range holds {speeds.min():g}")
        except ValueError as err:
            errors.append(f"config key laws.speeds: {err}")
    return errors


def _tangential_errors(config: dict) -> list[str]:
    """The tangential models named by the validation and compliance sections: registered; the validation's
    able to serve its law's spring; the compliance map's compliant (with a stiffness to map over)."""
    from ..contact.tangential import TANGENTIALS

    errors = []
    validation = config.get("validation", {})
    law = LAWS.get(validation.get("model"))
    for key, names in (("validation.tangential", validation.get("tangential", [])),
                       ("compliance.tangential", config.get("compliance", {}).get("tangential", []))):
        for name in names:
            model = TANGENTIALS.get(name)
            if model is None:
                errors.append(f"config key {key}: {name!r} is not a registered tangential model "
                              f"({', '.join(TANGENTIALS)})")
            elif key.startswith("validation") and law is not None and model.spring not in (None, law.spring):
                errors.append(f"config key {key}: {name!r} needs a {model.spring}-spring law; the validation's "
                              f"model {law.name!r} has a {law.spring} spring")
            elif key.startswith("compliance") and not model.stiffness_parameters:
                errors.append(f"config key {key}: {name!r} has no tangential stiffness to map over kappa")
    return errors


def _non_finite(value, key=""):
    """(key, value) of every float in a nested config that is NaN or infinite."""
    if isinstance(value, dict):
        for k, v in value.items():
            yield from _non_finite(v, f"{key}.{k}" if key else str(k))
    elif isinstance(value, (list, tuple)):
        for i, v in enumerate(value):
            yield from _non_finite(v, f"{key}[{i}]")
    elif isinstance(value, float) and not math.isfinite(value):
        yield key, value


def _number_as_text(error) -> bool:
    from ..parsing import parse_number

    if error.validator != "type" or not isinstance(error.instance, str):
        return False
    if {"number", "integer"} & set(np.atleast_1d(error.validator_value)):
        try:
            parse_number(error.instance)
        except ValueError:
            return False
        return "/" not in error.instance
    return False


def _yaml_number(text: str) -> str:
    mantissa, _, exponent = text.lower().partition("e")
    if "." not in mantissa:
        mantissa += ".0"
    return f"{mantissa}e{'' if exponent.startswith(('+', '-')) else '+'}{exponent}" if exponent else mantissa


def _sweep_errors(config: dict, schema: dict) -> list[str]:
    """The sweep section's ranges, parsed and checked before any job (see :func:`config_errors`)."""
    from ..parsing import parse_range, range_count
    from ..impact.inputs import RULES
    from ..memory import check_size

    defaults = {k: v.get("default") for k, v in schema["properties"]["sweep"]["properties"].items()}
    sweep = defaults | config.get("sweep", {})
    values, errors = {}, []
    for key, rule in (("angle", "angle"), ("speed", "speed"), ("cor_speed", "speed")):
        try:
            count = range_count(sweep[key])
            check_size({key: count}, "use a larger STEP")
            values[key] = parse_range(sweep[key])
        except ValueError as err:
            errors.append(f"config key sweep.{key}: {err}")
            continue
        allowed, ok = RULES[rule]
        bad = values[key][~ok(values[key])]
        if bad.size:
            errors.append(f"config key sweep.{key}: {rule} must be {allowed}; the range holds {bad[0]:g}")
    if errors:
        return errors
    try:
        check_size({"angle": values["angle"].size, "speed": values["speed"].size},
                   "split it with sweep.shards over several machines, or use coarser ranges")
    except ValueError as err:
        errors.append(f"config key sweep: {err}")
    if not np.isclose(values["speed"], sweep["map_speed"], rtol=1e-12, atol=0.0).any():
        errors.append(f"config key sweep.map_speed: {sweep['map_speed']!r} is not on the speed grid "
                      f"{sweep['speed']!r}, so the spin map would be empty: pick one of its speeds")
    return errors


def check_config(config: dict, schema_path: str) -> None:
    """Raise ``ValueError`` listing every problem of the configuration (see :func:`config_errors`)."""
    errors = config_errors(config, schema_path)
    if errors:
        raise ValueError("invalid configuration:\n  " + "\n  ".join(errors))


