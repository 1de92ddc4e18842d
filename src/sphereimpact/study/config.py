"""Scenes and solver options from the validated pipeline configuration (config/config.yaml)."""

from __future__ import annotations

from ..scene import Scene, SolverOptions

#: Config key -> Scene field, for the parameters shared by every case.  k and b are spelled out in the
#: config because snakemake's --config accepts only keys of two or more characters.
SCENE_KEYS = {"mass": "mass", "diameter": "diameter", "inertia_factor": "inertia_factor", "mu": "mu",
              "stiffness": "k", "damping": "b", "ramp": "ramp", "speed": "speed", "gravity": "gravity"}


def shared_fields(config: dict) -> dict:
    """The Scene fields every case shares (ball, surface, contact, approach), from the config's keys."""
    return {field: config[key] for key, field in SCENE_KEYS.items()}


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
    fields = shared_fields(config)
    fields.update(config["cases"][case])
    fields.update(model=model, separation=separation, **changes)
    return Scene(**fields)


def solver_options(config: dict) -> SolverOptions:
    """SolverOptions from the config's method, rtol and atol (``closed`` falls back per model)."""
    return SolverOptions(method=config["method"], rtol=config["rtol"], atol=config["atol"])


def options_for(config: dict, scene: Scene) -> SolverOptions:
    """The configured options, except that ``closed`` is used only where it exists (kelvin-voigt)."""
    options = solver_options(config)
    if options.method == "closed" and scene.model != "kelvin-voigt":
        return SolverOptions(method="DOP853", rtol=options.rtol, atol=options.atol)
    return options


def config_errors(config: dict, schema_path: str) -> list[str]:
    """Every violation of the JSON schema, one line each, naming the config key first."""
    import jsonschema
    import yaml

    with open(schema_path) as handle:
        schema = yaml.safe_load(handle)
    validator = jsonschema.Draft202012Validator(schema)
    lines = []
    for error in sorted(validator.iter_errors(config), key=lambda e: list(map(str, e.absolute_path))):
        key = ".".join(map(str, error.absolute_path)) or "(top level)"
        hint = error.schema.get("description", "") if isinstance(error.schema, dict) else ""
        lines.append(f"config key {key}: {error.message}" + (f" ({hint})" if hint else ""))
    return lines


def check_config(config: dict, schema_path: str) -> None:
    """Raise ``ValueError`` listing every schema violation (see :func:`config_errors`)."""
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
