"""A measurement plan's files: the chosen bounces as ``fit`` reads them once measured, the expected errors, every
candidate's numbers and the figure."""

from __future__ import annotations

import json
from contextlib import ExitStack
from pathlib import Path

from ..figures.plan import plan_figure
from ..files import replacing
from ..fit.names import PLAN_FILES
from .fitting import finite


def study_plan(config: dict, ball_json: str, folder: str) -> None:
    """An own study's ``plan`` section: its candidates planned for the study's ball (``ball_json``, the file the
    study's ball job wrote), the plan's files in ``folder``."""
    from ..fit.plan import plan
    from ..impact.ball import load_ball

    section = config["plan"]
    result = plan(section["candidates"], load_ball(ball_json, config.get("plugins", ())), section["free"],
                  section["noise"], section.get("size"), section["criterion"])
    write_plan(result, folder, {"candidates_file": section["candidates"]})


def write_plan(plan, folder, extra: dict | None = None) -> None:
    """Write a :class:`~sphereimpact.fit.plan.Plan` into ``folder`` (made if missing): ``plan.csv`` (the chosen
    bounces in ``fit``'s columns, each planned output empty and its ``sigma_<output>``), ``plan.json`` (the expected
    errors, correlations and notes, with the keys of ``extra`` besides), ``candidates.csv`` (every candidate's model
    values, noise and single-bounce errors) and ``plan.png``; written beside and renamed together."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    with ExitStack() as stack:
        table, summary, candidates, figure = (stack.enter_context(replacing(folder / name)) for name in PLAN_FILES)
        plan.table().to_csv(table, index=False, float_format="%.10g")
        Path(summary).write_text(json.dumps(finite(plan.as_dict() | (extra or {})), indent=2) + "\n", encoding="utf-8")
        plan.candidates.to_csv(candidates, index=False, float_format="%.10g")
        plan_figure(plan, [figure])


def kharaz_ball(section: dict, tangential: str):
    """The Kharaz experiment's ball (``validation`` section: alumina on glass, its e_n the measured COR the
    damping is calibrated to, so that ``cor`` may be freed) with ``tangential`` contact, kappa = 4 G*/E*."""
    from ..impact.ball import Measurement, calibrated_ball
    from .validation import experiment

    exp = experiment(section)  # the materials' E*, kappa and the sphere's mass, as the validation has them
    compliant = {} if tangential == "rigid" else {"kappa": exp.kappa}
    return calibrated_ball(Measurement(cor=section["cor"], speed=section["speed"]), model=section["model"],
                           modulus=exp.e_star, mass=exp.scene.mass, diameter=exp.scene.diameter,
                           inertia_factor=exp.scene.inertia_factor, mu=section["mu"], tangential=tangential,
                           speed=section["speed"], incidence=20.0, source="Kharaz et al. (2001)", **compliant)


def planning_study(config: dict, data_csv: str, schema_yaml: str, out: dict) -> None:
    """The pipeline's planning study (config ``planning``), written to the paths of ``out``:

    - ``kharaz`` (a folder) and ``figure``: which ``kharaz.size`` incidences of ``kharaz.incidences`` would have
      pinned the Kharaz ball's mu and kappa (exact microslip) best, each measuring every output of ``noise``,
      against the values the experiment measured (``data_csv``, each with the same noise);
    - ``checks`` (a CSV): each entry of ``checks`` planned, its predictions against the spread of fits of its
      synthetic bounces over ``seeds`` seeds, one row per parameter;
    - ``tennis`` (a folder): the plan of ``tennis`` for the ball of its own-study config (its defaults from the
      schema ``schema_yaml``);
    - ``plan_md`` and ``checks_md``: the README's and the fit guide's blocks.
    """
    import pandas as pd
    import yaml

    from ..files import copy_file, replacing, write_text
    from ..fit.plan import expected_errors, plan, realised_spread
    from ..parsing import parse_range
    from .config import with_defaults
    from .own import study_ball
    from .validation import load_data

    section = config["planning"]
    spec = section["kharaz"]
    candidates = pd.DataFrame({"incidence": parse_range(spec["incidences"])})
    ball = kharaz_ball(config["validation"], "microslip")
    chosen = plan(candidates, ball, ["mu", "kappa"], spec["noise"], spec["size"])
    data = load_data(data_csv)
    names = {"e_t": "e_t", "omega_rad_s": "abs_omega_f", "rebound_angle_deg": "rebound_angle"}
    measured = pd.DataFrame({"incidence": data["incidence_deg"].to_numpy(float),
                             "quantity": data["quantity"].map(names).to_numpy()})
    measured = measured[measured["quantity"].isin(list(spec["noise"]))]
    errors = expected_errors(measured, ball, ["mu", "kappa"], spec["noise"])
    write_plan(chosen, out["kharaz"], {"measured": {"values": len(measured), "stderr": errors,
                                                    "source": "the incidences and quantities Kharaz et al. (2001) "
                                                              "measured, each with the planned noise"}})
    copy_file(Path(out["kharaz"]) / "plan.png", out["figure"])  # the plan's own figure, not drawn twice

    rows = []
    for check in section["checks"]:
        checked_ball = kharaz_ball(config["validation"], check["tangential"])
        checked = plan(candidates, checked_ball, check["free"], check["noise"], check["size"])
        table = realised_spread(checked, checked_ball, check["seeds"])
        rows.append(table.assign(scenario=check["name"], tangential=check["tangential"], size=check["size"],
                                 notes=" | ".join(checked.notes)))
    columns = ["scenario", "tangential", "size", "seeds", "parameter", "value", "predicted", "realised", "mc_error",
               "ratio", "z", "mean", "notes"]
    checks = (pd.concat(rows, ignore_index=True) if rows else pd.DataFrame(columns=columns))
    checks["z"] = (checks["realised"] - checks["predicted"]) / checks["mc_error"]
    with replacing(out["checks"]) as partial:
        checks[columns].to_csv(partial, index=False, float_format="%.6g")

    tennis = section["tennis"]
    schema = yaml.safe_load(Path(schema_yaml).read_text(encoding="utf-8"))
    study = with_defaults(schema, yaml.safe_load(Path(tennis["study"]).read_text(encoding="utf-8")))
    tennis_plan = plan(tennis["candidates"], study_ball(study), tennis["free"], tennis["noise"], tennis["size"])
    write_plan(tennis_plan, out["tennis"], {"candidates_file": tennis["candidates"], "study": tennis["study"]})
    write_text(out["plan_md"], tennis_block(tennis_plan, tennis))
    write_text(out["checks_md"], checks_block(chosen, errors, len(measured), checks, spec))


def tennis_block(result, spec: dict) -> str:
    """The README's example: the tennis ball's plan, its expected errors beside as many bounces spread evenly."""
    chosen = result.candidates.iloc[list(result.chosen)]
    lines = [f"The pipeline's run of it (`results/plan/tennis/`, the ball of `{spec['study']}`, the candidates of "
             f"`{spec['candidates']}`): the {result.criterion}-optimal {len(result.chosen)} of "
             f"{len(result.candidates)} candidate bounces, noise "
             + ", ".join(f"{k} {v}" for k, v in result.noise.items()) + ".", "",
             "| parameter | expected value | the plan | as many, evenly spread | every candidate |",
             "|---|---|---|---|---|"]
    for name in result.free:
        lines.append(f"| `{name}` | {result.values[name]:.4g} | " + " | ".join(
            _error(result.stderr[label][name]) for label in ("chosen", "even", "all")) + " |")
    lines += ["", "Chosen: " + "; ".join(f"{row.angle_to_surface:g}° to the court, spin {row.spin:g} rad/s"
                                         for row in chosen.itertuples()) + "."]
    lines += [f"Note: {note}" for note in result.notes]
    return "\n".join(lines) + "\n"


def checks_block(kharaz, measured_errors: dict, measured_values: int, checks, spec: dict) -> str:
    """The fit guide's block: the Kharaz ball's best incidences against the measured ones, and each check of the
    predictions by simulation."""
    chosen = kharaz.candidates.iloc[list(kharaz.chosen)]["incidence_deg"]
    lines = ["The Kharaz ball (`results/plan/kharaz/`, `paper_figures/plan_kharaz.png`), exact microslip, noise "
             + ", ".join(f"{k} {v}" for k, v in kharaz.noise.items())
             + f": the {kharaz.criterion}-optimal {len(kharaz.chosen)} incidences of {len(kharaz.candidates)} "
             f"candidates ({spec['incidences']}°) are " + ", ".join(f"{v:g}°" for v in chosen)
             + f", each measuring every output, against the {measured_values} values Kharaz et al. measured (their "
             "incidences and quantities, each with the same noise):", "",
             "| parameter | the plan | as many, evenly spread | the measured values |", "|---|---|---|---|"]
    for name in kharaz.free:
        lines.append(f"| `{name}` | {_error(kharaz.stderr['chosen'][name])} | {_error(kharaz.stderr['even'][name])} "
                     f"| {_error(measured_errors[name])} |")
    if len(checks):
        lines += ["", "Predicted standard errors against the spread of the estimates when synthetic bounces of each "
                      "plan, with the planned noise, are fitted by `fit` over many seeds (`results/plan/checks.csv`; "
                      "z: the difference over the realised spread's own Monte Carlo error):", "",
                  "| check | bounces | seeds | parameter | predicted | realised | Monte Carlo error | z |",
                  "|---|---|---|---|---|---|---|---|"]
        for row in checks.itertuples():
            lines.append(f"| {row.scenario} ({row.tangential}) | {row.size} | {row.seeds} | `{row.parameter}` | "
                         f"{row.predicted:.3g} | {row.realised:.3g} | {row.mc_error:.2g} | {row.z:+.2f} |")
    return "\n".join(lines) + "\n"


def _error(value: float) -> str:
    import math

    return f"{value:.3g}" if math.isfinite(value) else "unbounded"
