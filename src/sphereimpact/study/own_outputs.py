"""The files of a study of one's own ball: the calibrated ball, its bounces and their time histories, its COR,
contact time and peak force against speed, spin and rebound maps, and one page (see :mod:`.own`)."""

from __future__ import annotations

from html import escape
from pathlib import Path

import pandas as pd

from ..contact.laws import Spring, hertz_modulus, spring_exponent
from ..contact.tangential import TANGENTIALS
from ..impact.ball import FAR, ball_columns, load_ball, save_ball
from ..impact.outcome import OUTPUT_UNITS, SCALAR_OUTPUTS
from ..impact.solve import simulate
from ..parsing import parse_range
from ..sweep.engine import grid, sweep
from ..sweep.io import write_table
from .own import bounce_scene, study_ball
from .workflow import job_seconds

#: Units of the columns of ``outcomes.csv`` (in its header, as the histories have them).
BOUNCE_UNITS = {"speed": "m/s", "angle_to_surface": "deg", "incidence": "deg", "spin": "rad/s"} | {
    key: unit for key, unit in OUTPUT_UNITS.items() if unit and unit != "-"}
#: The outputs the speed curve and the maps keep.
CURVE_OUTPUTS = ("cor", "t_f", "force_max", "delta_m")
MAP_OUTPUTS = ("omega_f", "vc_t", "vc_n", "rebound_angle_to_surface", "rebound_angle", "rebound_angle_contact",
               "regime", "cor")


def write_ball(config: dict, json_path: str, fitted: str | None = None) -> None:
    """The study's ball (calibrated, with what was measured and fitted; the ``fit`` section's fitted ball
    ``fitted`` when it has one), as a ball file every door reads (:func:`~sphereimpact.impact.ball.save_ball`)."""
    save_ball(study_ball(config, fitted), json_path)


def read_history(path) -> pd.DataFrame:
    """A table written with its units in the CSV header (``t [s]``: a history, ``outcomes.csv``): plain names,
    units in attrs."""
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
    ball, rows = load_ball(ball_json, config.get("plugins", ())), []
    for name, spec in config["bounces"].items():
        scene = bounce_scene(ball.scene, spec)
        out = simulate(scene, ball.options)
        rows.append({"bounce": name, "speed": scene.speed, "angle_to_surface": 90.0 - scene.incidence_deg,
                     "incidence": scene.incidence_deg, "spin": scene.spin,
                     **{key: getattr(out, key) for key in SCALAR_OUTPUTS}})
        history = out.history(config.get("samples", 401))
        write_table(history, histories[name], units=history.attrs["units"])
    write_table(pd.DataFrame(rows), outcomes_csv, units=BOUNCE_UNITS)


def write_speed_curve(config: dict, ball_json: str, csv_path: str) -> None:
    """COR, contact time, peak force and maximum compression of normal impacts across ``ranges.speeds``."""
    ball = load_ball(ball_json, config.get("plugins", ()))
    speeds = parse_range(config["ranges"]["speeds"])
    table = sweep(grid(speed=speeds, angle_to_surface=[90.0]).assign(**ball_columns(ball)), outputs=CURVE_OUTPUTS,
                  settings=ball.options.settings)
    table[["speed", *CURVE_OUTPUTS]].to_csv(csv_path, index=False, float_format="%.10g")


def write_maps(config: dict, ball_json: str, csv_path: str) -> None:
    """Spin, rebound velocity and angles over angle to the surface x speed (``ranges``), at ``map_spin``."""
    ball, ranges = load_ball(ball_json, config.get("plugins", ())), config["ranges"]
    scenes = grid(angle_to_surface=parse_range(ranges["map_angles"]), speed=parse_range(ranges["map_speeds"]))
    table = sweep(scenes.assign(spin=ranges["map_spin"], **ball_columns(ball)), outputs=MAP_OUTPUTS,
                  settings=ball.options.settings)
    table[["angle_to_surface", "speed", "spin", *MAP_OUTPUTS]].to_csv(csv_path, index=False, float_format="%.10g")


def ball_parameters(ball) -> list[tuple[str, str]]:
    """The ball's description for its page, each value with its unit: ball, surface, the normal law and every
    parameter it uses (fitted ones marked; E* beside k for a Hertz spring), the tangential model and what the
    user gave of its stiffness and own parameters, settings, plug-ins and what it was calibrated to."""
    scene, law = ball.scene, ball.scene.law
    rows = [("mass", f"{scene.mass:g} kg"), ("diameter", f"{scene.diameter:g} m"),
            ("inertia factor α", f"{scene.inertia_factor:g}"), ("friction μ", f"{scene.mu:g}"),
            ("gravity", f"{scene.gravity:g} m/s²"), ("normal law", f"{scene.model}: {law.doc}"),
            ("separation", f"{scene.separation} (contact ends when {scene.separation.end_quantity} returns to 0)")]
    exponent = f"^{spring_exponent(law, scene):g}"
    for parameter in law.parameters:
        unit = "" if parameter.unit == "-" else f" {parameter.unit.replace('^n', exponent)}"
        rows.append((parameter.name, f"{getattr(scene, parameter.name):.6g}{unit}"
                                     + (" (fitted)" if parameter.name in ball.fitted else "")))
    if law.spring is Spring.HERTZ:
        rows.append(("E* (effective modulus)", f"{hertz_modulus(scene):.6g} Pa"
                                               + (" (given)" if scene.modulus is not None else " (from k)")))
    model = TANGENTIALS.model(scene.tangential)
    rows.append(("tangential contact", f"{scene.tangential}: {model.doc}"))
    for parameter in model.parameters:
        value = getattr(scene, parameter.name)
        if value is not None:
            rows.append((parameter.name, f"{value:.6g}" + ("" if parameter.unit == "-" else f" {parameter.unit}")))
    rows += [(name, str(value)) for name, value in ball.options.settings.items()]
    if ball.plugins:
        rows.append(("plug-ins", ", ".join(ball.plugins)))
    measured = ball.measurement
    if measured is not None:
        rows.append(("calibrated to", f"COR {measured.cor:g}" + (
            f" and contact time {1e3 * measured.contact_time:g} ms" if measured.contact_time is not None else "")
            + f" at {measured.speed:g} m/s, normal impact ({measured.relation})"))
    return rows


def write_page(config: dict, ball_json: str, outcomes_csv: str, speed_csv: str, maps_csv: str, figures: dict,
               md_path: str, html_path: str, benchmarks=(), fit: tuple[str, str] | None = None,
               plan: tuple[str, str] | None = None) -> None:
    """One page, Markdown and HTML, that shows the study: the ball and what was fitted, each bounce's outputs
    and figure, the speed curve and the maps (``figures``: name -> path relative to the page), each figure with
    its caption, a line for every bounce far from the calibration's speed, and what the study's jobs took
    (``benchmarks``: Snakemake's benchmark files of its jobs, the page's own aside); with a ``fit`` section, the
    fit (``fit``: its ``fit.json`` and its figure's path relative to the page); with a ``plan`` section, the plan
    (``plan``: its ``plan.json`` and its figure's path)."""
    ball, outcomes = load_ball(ball_json, config.get("plugins", ())), read_history(outcomes_csv)
    scene, speed, maps = ball.scene, pd.read_csv(speed_csv), pd.read_csv(maps_csv)
    measured = ball.measurement
    shown = ["bounce", "speed", "angle_to_surface", "spin", "cor", "t_f", "force_max", "vc_t", "vc_n", "omega_f",
             "rebound_angle_to_surface", "regime"]
    header = [f"{c} [{BOUNCE_UNITS[c]}]" if BOUNCE_UNITS.get(c) else c for c in shown]
    at = speed.iloc[(speed["speed"] - (speed["speed"].median() if measured is None else measured.speed)).abs().argmin()]
    curve = (f"COR {speed['cor'].min():.3f}–{speed['cor'].max():.3f}, contact time "
             f"{1e3 * speed['t_f'].min():.3g}–{1e3 * speed['t_f'].max():.3g} ms, peak force up to "
             f"{speed['force_max'].max():.4g} N over {speed['speed'].min():g}–{speed['speed'].max():g} m/s "
             f"(COR {at['cor']:.4f} at {at['speed']:g} m/s).")
    if measured is not None and measured.extrapolates(speed["speed"]).any():
        low, high = speed["speed"].min() / measured.speed, speed["speed"].max() / measured.speed
        curve += (f" The curve spans {low:.2g}–{high:.2g} times the measurement's {measured.speed:g} m/s; beyond "
                      f"{FAR:g} times either way the calibrated law extrapolates.")
    far = [f"{name}: {line}" for name, spec in config["bounces"].items()
           if (line := ball.far_from_measurement(bounce_scene(scene, spec)))]
    took = [job_seconds(path) for path in benchmarks]
    blocks = [("h1", f"Study `{config['study']}`: {scene.model} contact, {len(outcomes)} bounces"),
              ("p", f"Source of the ball's numbers: {ball.source or '—'}"),
              *([("p", f"The run that wrote this page: its {len(took)} jobs took {sum(took):.3g} s in all, the "
                       f"longest {max(took):.3g} s (Snakemake's benchmarks, `benchmarks/`).")] if took else []),
              ("table", (["parameter", "value"], ball_parameters(ball))),
              *(_fit_blocks(config["fit"], *fit) if fit else []),
              *(_plan_blocks(*plan) if plan else []),
              ("h2", "Bounces (`outcomes.csv`, histories in `histories/`)"),
              ("table", (header, [[_cell(v) for v in row] for row in outcomes[shown].itertuples(index=False)]))]
    blocks += [("p", "Outside the calibration: " + line) for line in far]
    blocks += [("figure", (figures[name], 900, _bounce_caption(name, row)))
               for name, row in outcomes.set_index("bounce").iterrows()]
    spin = maps["spin"].iloc[0]
    blocks += [("h2", "Against speed, normal impacts (`speed.csv`)"), ("p", curve),
               ("figure", (figures["speed"], 900, "Normal impacts of the ball against impact speed: COR, contact time "
                           "and peak normal force" + ("" if measured is None else
                                                      f"; the dotted line marks the measurement's {measured.speed:g} m/s")
                           + ".")),
               ("h2", "Maps (`maps.csv`)"),
               ("figure", (figures["spin_map"], 640, f"Rebound spin ω_f [rad/s] over the angle to the surface and the "
                           f"speed along the path, incoming spin {spin:g} rad/s (positive: topspin).")),
               ("figure", (figures["rebound_map"], 640, "Rebound angle of the centre to the surface [deg] over the same "
                           "grid: 90° less its angle from the normal; above 90° the ball leaves backwards."))]
    Path(md_path).write_text(_markdown(blocks), encoding="utf-8")
    Path(html_path).write_text(_html(config["study"], blocks), encoding="utf-8")


def _fit_blocks(section: dict, fit_json: str, figure: str) -> list:
    """The page's account of the fit: each free parameter with its standard error, the fit's quality, its notes
    and the figure of data against model."""
    import json

    record = json.loads(Path(fit_json).read_text(encoding="utf-8"))
    stats = record["statistics"]
    rows = [[name, f"{p['value']:.6g}", "unbounded" if p["stderr"] is None else f"{p['stderr']:.3g}",
             "yes" if p["identifiable"] else "no"] for name, p in record["parameters"].items()]
    return [("h2", f"Fitted to measured bounces (`fit/`, from `{section['data']}`)"),
            ("p", f"{stats['values']} measured values of {stats['bounces']} bounces; χ²/dof {stats['reduced_chi2']:.3g}; "
                  + "; ".join(f"residual RMS of {q} {v:.3g}" for q, v in stats["rms"].items()) + ". The parameters "
                  "above are the fitted ball's."),
            ("table", (["parameter", "fitted", "standard error", "identifiable"], rows)),
            *[("p", "Note: " + note) for note in record["notes"]],
            ("figure", (figure, 640, "Measured values against the fitted model at each bounce; the band is ±2 "
                        "standard errors of the model from the parameters' covariance."))]


def _plan_blocks(plan_json: str, figure: str) -> list:
    """The page's account of the measurement plan: each free parameter's expected standard error from the plan,
    from as many bounces spread evenly and from every candidate, the chosen bounces, the notes and the figure."""
    import json

    record = json.loads(Path(plan_json).read_text(encoding="utf-8"))

    def shown(value):
        return "unbounded" if value is None else f"{value:.3g}"

    rows = [[name, f"{record['values'][name]:.6g}",
             *(shown(record["stderr"][label][name]) for label in ("chosen", "even", "all"))]
            for name in record["free"]]
    chosen = "; ".join(f"{row['incidence_deg']:.4g}°" for row in record["chosen"])
    return [("h2", f"Which bounces to measure (`plan/`, from `{record['candidates_file']}`)"),
            ("p", f"{record['criterion']}-optimal plan of {record['size']} bounces of {record['candidates']} "
                  f"candidates, noise " + ", ".join(f"{k} {v}" for k, v in record["noise"].items())
                  + f"; incidences from the normal: {chosen}. `plan/plan.csv` holds them in `fit`'s columns, each "
                  "output to fill in once measured."),
            ("table", (["parameter", "expected value", "plan", "as many, evenly spread", "every candidate"], rows)),
            *[("p", "Note: " + note) for note in record["notes"]],
            ("figure", (figure, 640, "Each parameter's standard error from one bounce alone against incidence, the "
                        "chosen bounces circled, and the expected errors of the plan, of as many evenly spread bounces "
                        "and of every candidate."))]


def _bounce_caption(name: str, row) -> str:
    return (f"Bounce {name}: {row['speed']:g} m/s at {row['angle_to_surface']:g}° to the surface, spin {row['spin']:g} "
            "rad/s. Over the contact, from first touch to separation: compression and normal force, the centre's and "
            "the contact point's velocities, the spin, and the force against compression.")


def _markdown(blocks) -> str:
    lines = []
    for kind, value in blocks:
        if kind in ("h1", "h2"):
            lines += [f"{'#' if kind == 'h1' else '##'} {value}", ""]
        elif kind == "p":
            lines += [value, ""]
        elif kind == "table":
            head, rows = value
            lines += ["| " + " | ".join(head) + " |", "|" + "---|" * len(head),
                      *["| " + " | ".join(row) + " |" for row in rows], ""]
        else:
            path, _, caption = value
            lines += [f"![{Path(path).stem}]({path})", "", f"*{caption}*", ""]
    return "\n".join(lines)


def _html(title: str, blocks) -> str:
    parts = [f"<!doctype html><html><head><meta charset='utf-8'><title>{escape(title)}</title></head><body>"]
    for kind, value in blocks:
        if kind in ("h1", "h2"):
            parts.append(f"<{kind}>{escape(value.replace('`', ''))}</{kind}>")
        elif kind == "p":
            parts.append(f"<p>{escape(value)}</p>")
        elif kind == "table":
            head, rows = value
            parts.append(pd.DataFrame(rows, columns=head).to_html(index=False))
        else:
            path, width, caption = value
            parts.append(f"<figure><img src='{escape(path)}' width='{width}' alt='{escape(caption)}'>"
                         f"<figcaption>{escape(caption)}</figcaption></figure>")
    return "\n".join([*parts, "</body></html>"])


def _cell(value) -> str:
    return f"{value:.5g}" if isinstance(value, float) else str(value)
