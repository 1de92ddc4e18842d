"""Write the numerical studies' result files from the pipeline configuration."""

from __future__ import annotations

import pandas as pd

from ..numerics.ablation import ablation
from ..numerics.bench import speedups
from ..numerics.stability import stability
from ..numerics.workprecision import work_precision
from .config import scene_for
from .replication import load_published

CSV = {"index": False, "float_format": "%.6g"}


def chapter_cases(config: dict, models=("modified", "kelvin-voigt")) -> dict:
    """Every configured case under each model (force criterion), keyed 'case/model'."""
    return {f"{case}/{model}": scene_for(config, case, model, config["primary"]["separation"])
            for model in models for case in config["cases"]}


def write_work_precision(config: dict, csv_path: str) -> None:
    frame = work_precision(chapter_cases(config))
    frame["case"] = frame["case"].str.split("/").str[0]
    frame.to_csv(csv_path, **CSV)


def write_bench(work_precision_csv: str, csv_path: str) -> None:
    speedups(pd.read_csv(work_precision_csv)).to_csv(csv_path, **CSV)


def write_stability(config: dict, csv_path: str) -> None:
    """The failure-mode studies on the first configured case's ball (each study sets its own angle)."""
    base = scene_for(config, next(iter(config["cases"])), "modified", "force")
    stability(base).to_csv(csv_path, **CSV)


def write_ablation(config: dict, published_path: str, csv_path: str) -> None:
    cases = {case: scene_for(config, case, config["primary"]["model"], config["primary"]["separation"])
             for case in config["cases"]}
    ablation(cases, load_published(published_path)).to_csv(csv_path, **CSV)
