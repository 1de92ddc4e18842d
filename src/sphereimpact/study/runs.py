"""Simulate one configured case under one force model and write its run files."""

from __future__ import annotations

import json

import pandas as pd

from ..impact.solve import simulate
from .config import options_for, scene_for

#: Outputs that vary between identical runs, kept out of every results file.
TIMING_KEYS = ("wall_time",)


def outcome_record(outcome) -> dict:
    """The outputs of one impact without timings, so results files are byte-reproducible."""
    return {k: v for k, v in outcome.to_dict().items() if k not in TIMING_KEYS}


def run_case(config: dict, case: str, model: str, csv_path: str, json_path: str) -> None:
    """Simulate ``case`` with ``model`` under every configured separation criterion.

    Writes
    ------
    csv_path
        Time histories (columns of :data:`sphereimpact.HISTORY_COLUMNS` plus ``separation``),
        ``config['samples']`` instants per criterion.
    json_path
        ``{"case", "model", "scene", "outcomes": {separation: outputs}}``.
    """
    histories, outcomes, scene_fields = [], {}, None
    for separation in config["separations"]:
        scene = scene_for(config, case, model, separation)
        outcome = simulate(scene, options_for(config, scene))
        outcomes[separation] = outcome_record(outcome)
        frame = outcome.history(config["samples"])
        frame.insert(0, "separation", separation)
        histories.append(frame)
        scene_fields = {k: v for k, v in scene.as_dict().items() if k != "separation"}
    pd.concat(histories, ignore_index=True).to_csv(csv_path, index=False, float_format="%.12g")
    with open(json_path, "w") as handle:
        json.dump({"case": case, "model": model, "scene": scene_fields, "outcomes": outcomes}, handle, indent=2)
        handle.write("\n")
