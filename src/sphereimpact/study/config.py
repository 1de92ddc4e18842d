"""Scenes and solver options from the validated pipeline configuration (config/config.yaml)."""

from __future__ import annotations

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
