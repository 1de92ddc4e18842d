"""The files of a study of one's own ball: the calibrated ball, its bounces and their time histories, its COR,
contact time and peak force against speed, spin and rebound maps, and one page (see :mod:`.own`)."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd

from ..impact.ball import ball_columns, load_ball, save_ball
from ..impact.outcome import OUTPUT_UNITS, SCALAR_OUTPUTS
from ..impact.solve import simulate
from ..parsing import parse_range
from ..sweep.engine import grid, sweep
from ..sweep.io import write_table
from .own import bounce_scene, study_ball

#: The outputs the speed curve and the maps keep.
CURVE_OUTPUTS = ("cor", "t_f", "force_max", "delta_m")
MAP_OUTPUTS = ("omega_f", "vc_t", "vc_n", "rebound_angle", "rebound_angle_contact", "regime", "cor")


def write_ball(config: dict, json_path: str) -> None:
    """The study's ball (calibrated, with what was measured and fitted), as a ball file every door reads
    (:func:`~sphereimpact.impact.ball.save_ball`)."""
    save_ball(study_ball(config), json_path)


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
    ball, rows = load_ball(ball_json), []
    for name, spec in config["bounces"].items():
        scene = bounce_scene(ball.scene, spec)
        out = simulate(scene, ball.options)
        rows.append({"bounce": name, "speed": scene.speed, "angle_to_surface": 90.0 - scene.incidence_deg,
                     "incidence": scene.incidence_deg, "spin": scene.spin,
                     **{key: getattr(out, key) for key in SCALAR_OUTPUTS},
                     "rebound_angle_to_surface": 90.0 - out.rebound_angle})
        history = out.history(config.get("samples", 401))
        write_table(history, histories[name], units=history.attrs["units"])
    pd.DataFrame(rows).to_csv(outcomes_csv, index=False, float_format="%.10g")


def write_speed_curve(config: dict, ball_json: str, csv_path: str) -> None:
    """COR, contact time, peak force and maximum compression of normal impacts across ``ranges.speeds``."""
    ball = load_ball(ball_json)
    speeds = parse_range(config["ranges"]["speeds"])
    table = sweep(grid(speed=speeds, angle_to_surface=[90.0]).assign(**ball_columns(ball)), outputs=CURVE_OUTPUTS,
                  settings=ball.options.settings)
    table[["speed", *CURVE_OUTPUTS]].to_csv(csv_path, index=False, float_format="%.10g")


def write_maps(config: dict, ball_json: str, csv_path: str) -> None:
    """Spin, rebound velocity and angles over angle to the surface x speed (``ranges``), at ``map_spin``."""
    ball, ranges = load_ball(ball_json), config["ranges"]
    scenes = grid(angle_to_surface=parse_range(ranges["map_angles"]), speed=parse_range(ranges["map_speeds"]))
    table = sweep(scenes.assign(spin=ranges["map_spin"], **ball_columns(ball)), outputs=MAP_OUTPUTS,
                  settings=ball.options.settings)
    table[["angle_to_surface", "speed", "spin", *MAP_OUTPUTS]].to_csv(csv_path, index=False, float_format="%.10g")


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
