"""The configured sweeps: the sharded angle x speed table and the speed table behind the maps."""

from __future__ import annotations

import logging

import warnings

import numpy as np
import pandas as pd

from ..impact.scene import Scene
from ..errors import BeyondRadiusWarning
from ..impact.solve import simulate
from ..sweep.engine import grid, parse_range, sweep
from ..sweep.io import write_table
from .config import options_for, shared_fields


log = logging.getLogger(__name__)


def angle_speed_scenes(config: dict) -> pd.DataFrame:
    """The whole angle x speed sweep of the configured ball (primary model and criterion)."""
    spec = config["sweep"]
    scenes = grid(angle=parse_range(spec["angle"]), speed=parse_range(spec["speed"]))
    primary = config["primary"]
    ball = {k: v for k, v in shared_fields(config, primary["model"]).items() if k != "speed"}  # speeds: the grid
    return scenes.assign(**ball, model=primary["model"], separation=primary["separation"])


def write_shard(config: dict, shard: int, shards: int, csv_path: str) -> None:
    """Rows ``shard`` of ``shards`` contiguous blocks; interpolants span the whole sweep, so the merged
    shards equal the sweep run at once."""
    whole = angle_speed_scenes(config)
    rows = np.array_split(np.arange(len(whole)), shards)[shard]
    table = sweep(whole.iloc[rows], target=config["sweep"]["target"], span=whole,
                  progress=lambda done, total: log.info("sweep shard %d: %d of %d integrated scenes", shard, done, total))
    write_table(table, csv_path)


def merge(paths, csv_path: str) -> None:
    """Concatenate shard tables in shard order (bytes as written, no re-formatting)."""
    with open(csv_path, "w") as out:
        for i, path in enumerate(paths):
            with open(path) as handle:
                header = handle.readline()
                if i == 0:
                    out.write(header)
                out.write(handle.read())


#: A compression left at separation below this fraction of the maximum is delta = 0 to round-off.
END_DELTA = 1e-9


def write_speed_table(config: dict, csv_path: str) -> None:
    """Normal impact against speed, both force laws: COR and t_f (sweep), peak force and the compression left
    at separation ``delta_f`` [m] (single impacts: 0 where the contact ends at delta = 0, > 0 where it ends at
    P = 0 first, the damping about to pull), and whether the compression exceeds the radius (``beyond_radius``,
    outside the model)."""
    speeds = parse_range(config["sweep"]["cor_speed"])
    frames = []
    for model in config["models"]:
        scenes = pd.DataFrame(shared_fields(config, model) | {"speed": speeds}).assign(
            angle=0.0, model=model, separation=config["primary"]["separation"])
        table = sweep(scenes, target=config["sweep"]["target"])
        peaks, left = [], []
        with warnings.catch_warnings():  # the table's beyond_radius column flags delta_m > R
            warnings.simplefilter("ignore", BeyondRadiusWarning)
            for speed in speeds:
                scene = Scene(**(shared_fields(config, model) | {"speed": float(speed)}), angle=0.0, model=model,
                              separation=config["primary"]["separation"])
                out = simulate(scene, options_for(config, scene))
                peaks.append(out.force_max)
                at_end = float(out.motion.normal.state(out.t_f)[0])
                left.append(at_end if at_end > END_DELTA * out.delta_m else 0.0)  # round-off of delta = 0: 0
        frames.append(table.assign(force_max=peaks, delta_f=left))
    pd.concat(frames, ignore_index=True).to_csv(csv_path, index=False, float_format="%.12g")
