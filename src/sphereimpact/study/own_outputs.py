"""The files of a study of one's own ball: the calibrated ball, its bounces and their time histories, its COR,
contact time and peak force against speed, spin and rebound maps, and one page (see :mod:`.own`)."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

from .. import plugins
from ..impact.outcome import OUTPUT_UNITS, SCALAR_OUTPUTS
from ..parsing import parse_range
from ..impact.inputs import PATH_RULES
from ..impact.scene import Scene, SolverOptions
from ..impact.solve import simulate
from ..sweep.engine import grid, sweep
from ..sweep.io import write_table
from .own import ball_options, ball_scene, bounce_scene

#: The outputs the speed curve and the maps keep.
CURVE_OUTPUTS = ("cor", "t_f", "force_max", "delta_m")
MAP_OUTPUTS = ("omega_f", "vc_t", "vc_n", "rebound_angle", "rebound_angle_contact", "regime", "cor")


def load_ball(path: str) -> tuple[Scene, SolverOptions]:
    """The calibrated ball written by :func:`write_ball` and the options its models' settings give (the
    plug-ins it names imported first)."""
    with open(path) as handle:
        record = json.load(handle)
    plugins.load(record.get("plugins", []))
    return Scene(**record["scene"]), SolverOptions(settings=record.get("settings", {}))


def write_ball(config: dict, json_path: str) -> None:
    """The calibrated ball's scene and what was fitted, as JSON."""
    scene = ball_scene(config)
    contact = config["contact"]
    settings = ball_options(config).settings
    record = {"study": config["study"], "source": config["ball"].get("source", ""),
              **({"plugins": list(config["plugins"])} if config.get("plugins") else {}),
              **({"settings": dict(settings)} if settings else {}),
              "scene": {k: v for k, v in scene.as_dict().items() if k != "modulus" or scene.modulus is not None},
              "fitted": ({scene.law.damping: getattr(scene, scene.law.damping)} if "cor" in contact else {})
              | ({"k": scene.k} if "contact_time" in contact else {})}
    Path(json_path).write_text(json.dumps(record, indent=2) + "\n", encoding="utf-8")


def read_history(path: str) -> pd.DataFrame:
    """A history table written with its units in the CSV header (``t [s]``): plain names, units in attrs."""
    frame = pd.read_csv(path)
    units = {}
    for column in frame.columns:
        name, _, unit = column.partition(" [")
        units[name] = unit.rstrip("]")
    frame.columns = list(units)
    frame.attrs["units"] = units
    return frame


def write_bounces(config: dict, ball_json: str, outcomes_csv: str, histories: dict) -> None:
    """Each bounce's outputs (one row each: its approach and every scalar output) and its time history
    (``histories``: bounce -> CSV path, units in the header)."""
    (ball, options), rows = load_ball(ball_json), []
    for name, spec in config["bounces"].items():
        scene = bounce_scene(ball, spec)
        out = simulate(scene, options)
        rows.append({"bounce": name, "speed": scene.speed, "angle_to_surface": 90.0 - scene.incidence_deg,
                     "incidence": scene.incidence_deg, "spin": scene.spin,
                     **{key: getattr(out, key) for key in SCALAR_OUTPUTS},
                     "rebound_angle_to_surface": 90.0 - out.rebound_angle})
        history = out.history(config.get("samples", 401))
        write_table(history, histories[name], units=history.attrs["units"])
    pd.DataFrame(rows).to_csv(outcomes_csv, index=False, float_format="%.10g")


def write_speed_curve(config: dict, ball_json: str, csv_path: str) -> None:
    """COR, contact time, peak force and maximum compression of normal impacts across ``ranges.speeds``."""
    ball, options = load_ball(ball_json)
    speeds = parse_range(config["ranges"]["speeds"])
    table = sweep(_ball_rows(ball, grid(speed=speeds, angle_to_surface=[90.0])), outputs=CURVE_OUTPUTS,
                  settings=options.settings)
    table[["speed", *CURVE_OUTPUTS]].to_csv(csv_path, index=False, float_format="%.10g")


def write_maps(config: dict, ball_json: str, csv_path: str) -> None:
    """Spin, rebound velocity and angles over angle to the surface x speed (``ranges``), at ``map_spin``."""
    (ball, options), ranges = load_ball(ball_json), config["ranges"]
    scenes = grid(angle_to_surface=parse_range(ranges["map_angles"]), speed=parse_range(ranges["map_speeds"]))
    table = sweep(_ball_rows(ball, scenes.assign(spin=ranges["map_spin"])), outputs=MAP_OUTPUTS,
                  settings=options.settings)
    table[["angle_to_surface", "speed", "spin", *MAP_OUTPUTS]].to_csv(csv_path, index=False, float_format="%.10g")


def _ball_rows(ball: Scene, approaches: pd.DataFrame) -> pd.DataFrame:
    """The ball's fields beside each row of ``approaches`` (speed, approach, spin)."""
    keep = {k: v for k, v in ball.as_dict().items()
            if k not in ("speed", "angle", "spin", "parameters", *PATH_RULES) and v is not None and k != "modulus"}
    return approaches.assign(**keep, **ball.parameters)  # its models' own parameters as columns too


def write_page(config: dict, ball_json: str, outcomes_csv: str, speed_csv: str, maps_csv: str, figures: dict,
               md_path: str, html_path: str) -> None:
    """One page, Markdown and HTML, that shows the study: the ball and what was fitted, each bounce's outputs
    and figure, the speed curve and the maps (``figures``: name -> path relative to the page)."""
    with open(ball_json) as handle:
        ball = json.load(handle)
    scene, outcomes = ball["scene"], pd.read_csv(outcomes_csv)
    speed = pd.read_csv(speed_csv)
    parameters = [("mass", f"{scene['mass']:g} kg"), ("diameter", f"{scene['diameter']:g} m"),
                  ("inertia factor α", f"{scene['inertia_factor']:g}"), ("friction μ", f"{scene['mu']:g}"),
                  ("gravity", f"{scene['gravity']:g} m/s²"), ("normal law", scene["model"]),
                  ("tangential contact", scene["tangential"])]
    parameters += [(name, f"{value:.6g}") for name, value in ball["fitted"].items()]
    contact = config["contact"]
    if "cor" in contact:
        parameters.append(("calibrated to", f"COR {contact['cor']:g}"
                           + (f" and contact time {1e3 * contact['contact_time']:g} ms" if "contact_time" in contact
                              else "") + f" at {contact.get('cor_speed', 1.0):g} m/s, normal impact"))
    shown = ["bounce", "speed", "angle_to_surface", "spin", "cor", "t_f", "force_max", "vc_t", "vc_n", "omega_f",
             "rebound_angle_to_surface", "regime"]
    units = {"speed": "m/s", "angle_to_surface": "deg", "spin": "rad/s", "rebound_angle_to_surface": "deg"} | OUTPUT_UNITS
    header = [f"{c} [{units[c]}]" if units.get(c) else c for c in shown]
    table = outcomes[shown].copy()
    at = speed.iloc[(speed["speed"] - contact.get("cor_speed", speed["speed"].median())).abs().argmin()]
    text = {"title": f"Study `{config['study']}`: {scene['model']} contact, {len(outcomes)} bounces",
            "source": ball.get("source") or "—",
            "curve": f"COR {speed['cor'].min():.3f}–{speed['cor'].max():.3f}, contact time "
                     f"{1e3 * speed['t_f'].min():.3g}–{1e3 * speed['t_f'].max():.3g} ms, peak force up to "
                     f"{speed['force_max'].max():.4g} N over {speed['speed'].min():g}–{speed['speed'].max():g} m/s "
                     f"(COR {at['cor']:.4f} at {at['speed']:g} m/s)."}
    md = [f"# {text['title']}", "", f"Source of the ball's numbers: {text['source']}", "",
          "| parameter | value |", "|---|---|", *[f"| {k} | {v} |" for k, v in parameters], "",
          "## Bounces (`outcomes.csv`, histories in `histories/`)", "",
          "| " + " | ".join(header) + " |", "|" + "---|" * len(header),
          *["| " + " | ".join(_cell(v) for v in row) + " |" for row in table.itertuples(index=False)], ""]
    md += [f"![{name}]({figures[name]})" for name in config["bounces"]]
    md += ["", "## Against speed, normal impacts (`speed.csv`)", "", text["curve"], "", f"![speed]({figures['speed']})",
           "", "## Maps (`maps.csv`)", "", f"![spin]({figures['spin_map']})", f"![rebound]({figures['rebound_map']})",
           ""]
    Path(md_path).write_text("\n".join(md), encoding="utf-8")
    html = [f"<!doctype html><html><head><meta charset='utf-8'><title>{config['study']}</title></head><body>",
            f"<h1>{text['title']}</h1><p>Source of the ball's numbers: {text['source']}</p>",
            pd.DataFrame(parameters, columns=["parameter", "value"]).to_html(index=False),
            "<h2>Bounces (outcomes.csv, histories in histories/)</h2>",
            table.set_axis(header, axis=1).to_html(index=False, float_format=lambda v: f"{v:.5g}"),
            *[f"<p><img src='{figures[name]}' width='900'></p>" for name in config["bounces"]],
            f"<h2>Against speed, normal impacts (speed.csv)</h2><p>{text['curve']}</p>",
            f"<p><img src='{figures['speed']}' width='900'></p><h2>Maps (maps.csv)</h2>",
            f"<p><img src='{figures['spin_map']}' width='640'><img src='{figures['rebound_map']}' width='640'></p>",
            "</body></html>"]
    Path(html_path).write_text("\n".join(html), encoding="utf-8")


def _cell(value) -> str:
    return f"{value:.5g}" if isinstance(value, float) else str(value)
