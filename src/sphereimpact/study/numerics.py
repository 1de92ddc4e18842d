"""Write the numerical studies' result files from the pipeline configuration."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

from ..contact.separation import Separation
from ..numerics.ablation import ablation
from ..numerics.resolution import resolution_study
from ..numerics.bench_sweep import DAMPED_MAP, damped_map_command, run as bench_sweep, write_accuracies
from ..numerics.bench import (bench_scenes, kernel_bench, microslip_bench, profile_call, simulate_vs_handwritten, stages,
                               startup_bench)
from ..parsing import parse_range
from ..numerics.reference import stored_references, write_references
from ..numerics.stability import stability, stiffness_scenes
from ..numerics.workprecision import work_precision
from .config import scene_for
from .replication import load_published

CSV = {"index": False, "float_format": "%.6g"}


def chapter_cases(config: dict, models=("modified", "kelvin-voigt")) -> dict:
    """Every configured case under each model (force criterion), keyed 'case/model'."""
    return {f"{case}/{model}": scene_for(config, case, model, config["primary"]["separation"])
            for model in models for case in config["cases"]}


def domain_cases(config: dict, models=("modified", "kelvin-voigt")) -> dict:
    """The work-precision scenes beyond the chapter's (``numerics.domain``: name -> changes to the first
    case), under each model (force criterion), keyed 'name/model'."""
    first = next(iter(config["cases"]))
    return {f"{name}/{model}": scene_for(config, first, model, config["primary"]["separation"], **changes)
            for model in models for name, changes in config["numerics"].get("domain", {}).items()}


def write_numerics_references(config: dict, json_path: str) -> None:
    """The reference solutions the timed numerical studies compare with (the work-precision cases', and the
    stiffness study's points where ``numerics.stability`` has it), into ``json_path``
    (:func:`~sphereimpact.numerics.reference.write_references`): computed in a job of their own, so that the timed jobs,
    which run alone, spend their time timing."""
    scenes = list((chapter_cases(config) | domain_cases(config)).values())
    if "stiffness" in config["numerics"]["stability"]:
        scenes += [scene for _, _, scene in stiffness_scenes(_stability_ball(config))]
    write_references(scenes, json_path)


def write_work_precision(config: dict, csv_path: str, references: str | None = None) -> None:
    """The work-precision table; ``references`` the file of :func:`write_numerics_references` (else computed)."""
    numerics = config["numerics"]
    with stored_references(references):
        frame = work_precision(chapter_cases(config) | domain_cases(config), numerics["tolerances"],
                               numerics["methods"], numerics["cost_cap"])
    frame["case"] = frame["case"].str.split("/").str[0]
    frame.to_csv(csv_path, **CSV)


def write_kernel_bench(config: dict, csv_path: str) -> None:
    """The compiled kernels' compilation on a fresh machine and their load (:func:`~..numerics.bench.kernel_bench`,
    ``bench.repeats`` loads) into ``csv_path``, rows of the bench table (``write_bench`` takes them in)."""
    kernel_bench(config["bench"]["repeats"]).to_csv(csv_path, **CSV)


def write_bench(config: dict, csv_path: str, stages_csv: str, profile_csv: str, kernels_csv: str | None = None) -> None:
    """``simulate`` against the hand-written script on the chapter's cases and scenes across the domain, with the
    rows of ``kernels_csv`` (:func:`write_kernel_bench`) after the microslip contact's; where its time goes, stage
    by stage on each scene and function by function (a profile) on the most oblique configured case under the
    primary law."""
    bench = config["bench"]
    scenes = bench_scenes(chapter_cases(config), bench["domain"])
    from .validation import experiment

    section = config["numerics"]["microslip"]
    exact = experiment(config["validation"]).with_tangential("microslip").with_(angle=_first_oblique(section["angles"]))
    reference = (section["reference"]["elements"], section["reference"]["time_steps"])
    microslip = microslip_bench(exact, reference, bench["repeats"])
    kernels = [] if kernels_csv is None else [pd.read_csv(kernels_csv)]
    startup = [startup_bench(bench["repeats"])] if bench["startup"] else []
    pd.concat([simulate_vs_handwritten(scenes, bench["repeats"]), microslip, *kernels, *startup],
              ignore_index=True).to_csv(csv_path, **CSV)
    stages(scenes, bench["repeats"]).to_csv(stages_csv, **CSV)
    oblique = max(config["cases"], key=lambda case: config["cases"][case].get("angle", 0.0))
    profiled = scene_for(config, oblique, config["primary"]["model"], config["primary"]["separation"])
    profile_call(profiled).to_csv(profile_csv, **CSV)


def write_bench_sweep_accuracy(config: dict, json_path: str) -> None:
    """The untimed half of the sweep benchmark with ``bench``'s settings: each sweep's accuracy and its contenders'
    tolerances (:func:`~sphereimpact.numerics.bench_sweep.write_accuracies`), into ``json_path``, which
    :func:`write_bench_sweep` times with."""
    bench = config["bench"]
    write_accuracies(json_path, sample=bench["sample"], lanes=bench["lanes"], million=bench["million"],
                     laws=bench["laws"])


def write_bench_sweep(config: dict, csv_path: str, data_csv: str | None = None,
                      accuracy_json: str | None = None) -> None:
    """The sweep benchmark (:func:`~sphereimpact.numerics.bench_sweep.run`) with ``bench``'s settings (with
    ``bench.million``, the damped microslip map of Kharaz's ball as a whole command); with
    ``bench.fit``, also the fit of ``kharaz_fit``'s free parameters to the noise-free curve of Kharaz's ball (the
    validation's, with ``kharaz_fit``'s tangential model) at the validation's incidences, and with ``data_csv`` (the
    shipped Kharaz data) the fit of those parameters and the COR to the measured bounces, from ``kharaz_fit``'s start
    and the measured e_n; ``accuracy_json`` the file of :func:`write_bench_sweep_accuracy` (else each sweep's
    accuracy is computed before its timing)."""
    from ..fit import read_measured, with_values
    from ..impact.ball import Ball, Measurement, calibrated_ball
    from .validation import experiment

    bench, spec, section = config["bench"], config["kharaz_fit"], config["validation"]
    fit_of = data_fit_of = command_of = None
    if bench["million"]:
        scene = experiment(section).with_tangential("microslip")
        command_of = (f"Kharaz's ball, Hunt-Crossley chi {DAMPED_MAP['chi']}, microslip: incidence "
                      f"{DAMPED_MAP['incidence']} x speed {DAMPED_MAP['speed']}", damped_map_command(scene))
    if bench["fit"]:
        scene = experiment(section).with_tangential(spec["tangential"])
        start = {name: spec["start"][name] for name in spec["free"]}
        fit_of = (Ball(scene), start, parse_range(section["angles"]))
        if data_csv is not None:  # the COR free too: the ball calibrated to the measured e_n, as a user's would be
            free = [*spec["free"], *(["cor"] if "cor" not in spec["free"] else [])]
            ball = calibrated_ball(Measurement(section["cor"], section["speed"]), source="Kharaz et al. (2001)",
                                   **{name: getattr(scene, name) for name in (
                                       "mass", "diameter", "inertia_factor", "mu", "model", "modulus", "tangential",
                                       "kappa")})
            data_fit_of = (f"fit of {', '.join(free)} to {Path(data_csv).name}'s measured bounces ({scene.model}, "
                           f"{scene.tangential})", read_measured(data_csv, source=Path(data_csv).name),
                           with_values(ball, start), free)
    bench_sweep(csv_path, repeats=bench["repeats"], sample=bench["sample"], lanes=bench["lanes"],
                million=bench["million"], laws=bench["laws"], fit_of=fit_of, data_fit_of=data_fit_of,
                accuracies=None if accuracy_json is None else json.loads(Path(accuracy_json).read_text()),
                command_of=command_of)


def _stability_ball(config: dict):
    """The failure-mode studies' scene: the first configured case's ball under eq. 4.2, force criterion."""
    return scene_for(config, next(iter(config["cases"])), "modified", Separation.FORCE)


def write_stability(config: dict, csv_path: str, study: str | None = None, references: str | None = None) -> None:
    """The failure-mode studies on the first configured case's ball (each study sets its own angle): those of
    ``numerics.stability``, or ``study`` alone (the pipeline runs each in its own job, the timed one alone);
    ``references`` the file of :func:`write_numerics_references` (else computed)."""
    numerics = config["numerics"]
    if study is not None and study not in numerics["stability"]:
        raise ValueError(f"stability study {study!r} is not one of numerics.stability {numerics['stability']}")
    studies = numerics["stability"] if study is None else [study]
    with stored_references(references):
        stability(_stability_ball(config), studies, numerics["methods"]).to_csv(csv_path, **CSV)


def merge_stability(parts: list[str], csv_path: str) -> None:
    """The failure-mode studies' tables (:func:`write_stability` of one study each), in the order given, as the
    one table :func:`write_stability` writes for them all."""
    pd.concat([pd.read_csv(part) for part in parts], ignore_index=True).to_csv(csv_path, **CSV)


def write_ablation(config: dict, published_path: str, csv_path: str) -> None:
    cases = {case: scene_for(config, case, config["primary"]["model"], config["primary"]["separation"])
             for case in config["cases"]}
    ablation(cases, load_published(published_path)).to_csv(csv_path, **CSV)


def _first_oblique(angles) -> float:
    """The first of ``angles`` [deg] from 8 deg up (below it Kharaz's data scatter most), else the last."""
    return next((a for a in angles if a >= 8.0), angles[-1])


def microslip_scenes(config: dict) -> dict:
    """The resolution study's scenes: the validation's ball (Kharaz et al.) with the exact microslip contact at
    each of ``numerics.microslip.angles`` (kappa from the materials), and at the first of them from 8 deg up
    with each of ``kappas``."""
    from .validation import experiment

    section = config["numerics"]["microslip"]
    exact = experiment(config["validation"]).with_tangential("microslip")
    scenes = {f"{angle:g} deg": exact.with_(angle=angle) for angle in section["angles"]}
    oblique = _first_oblique(section["angles"])
    for kappa in section["kappas"]:
        scenes[f"{oblique:g} deg, kappa {kappa:g}"] = exact.with_(angle=oblique, kappa=kappa, shear_modulus=None)
    return scenes


def write_microslip_resolution(config: dict, csv_path: str) -> None:
    """The microslip contact's accuracy against cost over its resolution (``numerics.microslip``)."""
    section = config["numerics"]["microslip"]
    reference = (section["reference"]["elements"], section["reference"]["time_steps"])
    table = resolution_study(microslip_scenes(config), section["elements"], section["time_steps"], reference,
                             config["bench"]["repeats"], section["target"])
    table.to_csv(csv_path, **CSV)


def write_study(rule: str, config: dict, csv_path: str, published: str | None = None,
                references: str | None = None) -> None:
    """The study of workflow rule ``rule`` (``work_precision``, ``ablation`` or ``microslip_resolution``; the
    stability studies: :func:`write_stability`)."""
    if rule == "microslip_resolution":
        write_microslip_resolution(config, csv_path)
    elif rule == "ablation":
        write_ablation(config, published, csv_path)
    elif rule == "work_precision":
        write_work_precision(config, csv_path, references)
    else:
        raise ValueError(f"no numerical study for rule {rule!r}")
