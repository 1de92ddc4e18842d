"""Scenes and solver options from the validated pipeline configuration (config/config.yaml)."""

from __future__ import annotations

import math

import numpy as np

from .. import plugins
from .own import CHAPTER
from ..impact.calibrate import calibrate
from ..integrators import DEFAULT_INTEGRATOR, INTEGRATORS
from ..contact.laws import LAWS, PARAMETER_NAMES
from ..impact.scene import Scene, SolverOptions
from ..impact.solve import simulate

#: Config key -> Scene field, for the parameters shared by every case.  k and b are spelled out in the
#: config because snakemake's --config accepts only keys of two or more characters.
SCENE_KEYS = {"mass": "mass", "diameter": "diameter", "inertia_factor": "inertia_factor", "mu": "mu",
              "stiffness": "k", "damping": "b", "ramp": "ramp", "speed": "speed", "gravity": "gravity"}


def shared_fields(config: dict, model: str | None = None) -> dict:
    """The Scene fields every case shares (ball, surface, contact, approach), from the config's keys.

    With ``model``, only the law parameters that law uses: the config's contact keys (stiffness, damping,
    ramp) are the chapter's laws' (``models``), and ramp is eq. 4.2's alone.
    """
    uses = () if model is None else LAWS.law(model).parameter_names
    return {field: config[key] for key, field in SCENE_KEYS.items()
            if key in config and (model is None or field not in PARAMETER_NAMES or field in uses)}


def scene_for(config: dict, case: str, model: str, separation: str, **changes) -> Scene:
    """The Scene of one case under one force model and separation criterion.

    Parameters
    ----------
    config : dict
        The validated configuration.
    case : str
        A key of ``config['cases']``.
    model, separation : str
        Force-law name and separation criterion.
    **changes
        Further Scene fields to override (used by the replication's hypotheses).
    """
    fields = shared_fields(config, model)
    fields.update(config["cases"][case])
    fields.update(model=model, separation=separation, **changes)
    return Scene(**fields)


def hertz_twin(config: dict) -> Scene:
    """The chapter's ball as a Hertz contact: Hunt-Crossley (k delta^(3/2) (1 + chi delta_dot)) with k and chi
    fitted so that the primary law's normal impact at the configured speed keeps its COR and contact time.
    The tangential models that need a Hertz spring (``mindlin``, ``microslip``) run on it."""
    primary = scene_for_primary(config)
    normal = simulate(primary)
    base = Scene(**shared_fields(config, "hunt-crossley"), model="hunt-crossley", separation=primary.separation)
    return calibrate(base, normal.cor, contact_time=normal.t_f).scene


def scene_for_primary(config: dict) -> Scene:
    """The chapter's ball under the primary law and criterion (angle 0, the config's speed)."""
    primary = config["primary"]
    return Scene(**shared_fields(config, primary["model"]), model=primary["model"], separation=primary["separation"])


def solver_options(config: dict) -> SolverOptions:
    """SolverOptions from the config's method, rtol and atol (``closed`` falls back per model)."""
    return SolverOptions(method=config["method"], rtol=config["rtol"], atol=config["atol"])


def options_for(config: dict, scene: Scene) -> SolverOptions:
    """The configured options, except that a method that cannot serve the scene's law (``closed`` without a
    closed form, ``taylor`` without a series) gives way to the default integrator."""
    options = solver_options(config)
    if options.method != "auto" and INTEGRATORS[options.method].cannot(scene) is not None:
        return SolverOptions(method=DEFAULT_INTEGRATOR, rtol=options.rtol, atol=options.atol)
    return options


#: Sections only a study of one's own ball reads.
OWN_SECTIONS = ("ball_file", "ball", "surface", "contact", "bounces", "ranges", "fit")


def config_errors(config: dict, schema_path: str) -> list[str]:
    """Every problem of ``config``, one line each naming the config key first.

    The JSON schema's violations (a YAML 1.1 number read as text, like ``1e4``, gets a hint), numbers
    that are not finite (NaN passes every schema bound, since NaN comparisons are false), and the sweep
    section's ranges: parsed, checked against the scene's ranges, sized against memory, with
    ``map_speed`` on the speed grid.
    """
    import jsonschema
    import yaml

    with open(schema_path) as handle:
        schema = yaml.safe_load(handle)
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
        lines += (_sweep_errors(config, schema) + _law_errors(config) + _tangential_errors(config)
                  + own_errors(with_defaults(schema, config)))
    return lines


def with_defaults(schema: dict, value):
    """``value`` with the schema's defaults filled in, as snakemake's validation fills them (objects only)."""
    if schema.get("type") != "object" or not isinstance(value, dict):
        return value
    out = dict(value)
    for name, sub in schema.get("properties", {}).items():
        if name not in out and "default" in sub:
            out[name] = sub["default"]
        if name in out:
            out[name] = with_defaults(sub, out[name])
    extra = schema.get("additionalProperties")
    if isinstance(extra, dict):
        for name in out:
            if name not in schema.get("properties", {}):
                out[name] = with_defaults(extra, out[name])
    return out


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


def write_config(config: dict, path: str) -> None:
    """Write the validated configuration of a run as YAML (keys in the config's order)."""
    import yaml

    with open(path, "w") as handle:
        handle.write("# The configuration this run used (validated, schema defaults filled in).\n")
        yaml.safe_dump(_plain(config), handle, sort_keys=False, allow_unicode=True)


def _plain(value):
    """Snakemake's config as plain dicts and lists (YAML cannot represent its mapping types)."""
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value
