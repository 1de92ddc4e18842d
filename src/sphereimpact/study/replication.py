"""Compare the reproduction with every value the chapter prints, and test why values differ.

Status of a published value (``resolution`` = one unit of its last printed digit):

- ``match``: within half a unit, i.e. the reproduction rounds to the printed value;
- ``agree``: within one unit.  A value truncated instead of rounded, or read
  off a plot, can be off by up to one unit of its last digit, no more;
- ``discrepancy``: anything else.

Explanations are measured, not guessed: every published value is recomputed
under each hypothesis in :data:`HYPOTHESES` (other separation criterion,
gravity on, the other force law, other definitions of t_m and t_f), and the
report names those that reproduce the printed value.
"""

from __future__ import annotations

import math

import pandas as pd
import yaml

from ..contact.separation import Separation
from ..ode.events import extremum
from ..numerics.workprecision import TARGET
from ..impact.scene import STANDARD_GRAVITY
from ..impact.solve import simulate
from ..contact.tangential import kappa_from_poisson
from .config import hertz_twin, options_for, scene_for
from .tables import load_runs, markdown_table

#: Hypotheses: name -> (description, scene changes from the primary, or a derived time).
HYPOTHESES = {
    "penetration": ("contact ends when δ returns to 0 (not P)", {"separation": Separation.PENETRATION}),
    "gravity": (f"gravity on (g = {STANDARD_GRAVITY} m/s²), force criterion", {"gravity": STANDARD_GRAVITY}),
    "gravity+penetration": ("gravity on, penetration criterion",
                            {"gravity": STANDARD_GRAVITY, "separation": Separation.PENETRATION}),
    "kelvin-voigt": ("previous model (eq. 4.1), force criterion", {"model": "kelvin-voigt"}),
    "kelvin-voigt+penetration": ("previous model (eq. 4.1), penetration criterion",
                                 {"model": "kelvin-voigt", "separation": Separation.PENETRATION}),
    "peak-force-time": ("t_m read as the time of peak force", "peak"),
    "half-contact": ("t_m read as t_f / 2 (symmetric compression and restitution)", "half"),
    "undamped": ("undamped oscillator: t_m = (π/2)√(m/k), t_f = π√(m/k)", "undamped"),
}
#: Hypotheses that only redefine a time.
TIME_ONLY = ("peak-force-time", "half-contact", "undamped")

AGREE_UNITS = 1.0


def load_published(path: str) -> list[dict]:
    """The entries of config/published.yaml."""
    with open(path) as handle:
        return yaml.safe_load(handle)["values"]


def as_printed(quantity: str, value: float) -> float:
    """An output in the chapter's sign convention (its delta_m is the centre's displacement, negative)."""
    return -value if quantity == "delta_m" else value


def status(published: float, reproduced: float, resolution: float) -> str:
    """``match``, ``agree`` or ``discrepancy`` (see module docstring)."""
    diff = abs(reproduced - published)
    slack = 1e-9 * resolution  # the printed value's own floating-point representation
    if diff <= 0.5 * resolution + slack:
        return "match"
    if diff <= AGREE_UNITS * resolution + slack:
        return "agree"
    return "discrepancy"


def reproduce(config: dict, entry: dict, **changes) -> float:
    """A published entry's quantity from the primary model and criterion, with Scene ``changes``,
    in the chapter's sign convention."""
    primary = config["primary"]
    fields = {"model": primary["model"], "separation": primary["separation"], **changes}
    scene = scene_for(config, entry["case"], fields.pop("model"), fields.pop("separation"), **fields)
    return as_printed(entry["quantity"], getattr(simulate(scene, options_for(config, scene)), entry["quantity"]))


def _hypothesis_value(config: dict, entry: dict, name: str) -> float | None:
    """The entry's quantity under one hypothesis, or None where it does not apply."""
    primary = config["primary"]
    quantity, case = entry["quantity"], entry["case"]
    changes = HYPOTHESES[name][1]
    if name in TIME_ONLY:
        if quantity not in ("t_m", "t_f"):
            return None
        scene = scene_for(config, case, primary["model"], primary["separation"])
        if name == "undamped":
            period = math.sqrt(scene.mass / scene.k)
            return (0.5 if quantity == "t_m" else 1.0) * math.pi * period
        if quantity != "t_m":
            return None
        out = simulate(scene, options_for(config, scene))
        if name == "half-contact":
            return 0.5 * out.t_f
        return extremum(out.motion.force, out.motion.grid, "max")[0]
    return reproduce(config, entry, **changes)


def compare(config: dict, published: list[dict], runs: list[dict]) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The replication table and the hypothesis table.

    Returns
    -------
    table : DataFrame
        One row per published value: published, reproduced (primary model and
        criterion, from the run files), difference, resolution, status, explanation.
    hypotheses : DataFrame
        One row per published value x hypothesis: value and status.
    """
    primary = config["primary"]
    outputs = {(r["case"], r["model"]): r["outcomes"] for r in runs}
    rows, tests = [], []
    for entry in published:
        key = (entry["case"], primary["model"])
        if key not in outputs or primary["separation"] not in outputs[key]:
            raise ValueError(f"no run for case {entry['case']!r}, model {primary['model']!r}, "
                             f"separation {primary['separation']!r}: check 'cases', 'models' and 'separations'")
        value = as_printed(entry["quantity"], outputs[key][primary["separation"]][entry["quantity"]])
        verdict = status(entry["value"], value, entry["resolution"])
        matching = []
        for name in HYPOTHESES:
            alt = _hypothesis_value(config, entry, name)
            if alt is None:
                continue
            alt_status = status(entry["value"], alt, entry["resolution"])
            tests.append({"id": entry["id"], "hypothesis": name, "value": alt, "status": alt_status})
            if alt_status == "match":
                matching.append(f"{name} ({alt:.4g})")
        if verdict == "match":
            why = ""
        elif matching:
            why = "printed value reproduced by: " + "; ".join(matching)
        else:
            closest = min((t for t in tests if t["id"] == entry["id"]),
                          key=lambda t: abs(t["value"] - entry["value"]))
            why = (f"no hypothesis reproduces it; closest: {closest['hypothesis']} "
                   f"({closest['value']:.4g}, {closest['status']})")
        rows.append({"id": entry["id"], "case": entry["case"], "quantity": entry["quantity"], "unit": entry["unit"],
                     "published": entry["value"], "printed": entry["printed"], "reproduced": value,
                     "difference": value - entry["value"], "resolution": entry["resolution"],
                     "status": verdict, "explanation": why, "where": entry["where"]})
    return pd.DataFrame(rows), pd.DataFrame(tests)


#: What the default solver resolves, relative to an output's scale: the accuracy every output is held to
#: (the work-precision target).  A force counts as pulling only when P_min < -RESOLUTION * P_max (a smaller
#: negative P_min is the event location's round-off, not tension), and two CORs differ only beyond it.
RESOLUTION = TARGET


def pulls(force_min: float, force_max: float) -> bool:
    """True when the force pulls beyond the solver's resolution (see :data:`RESOLUTION`)."""
    return force_min < -RESOLUTION * force_max


#: Display of an output in the findings: (label, scale, unit).
_SHOW = {"t_m": ("t_m", 1e3, "ms"), "delta_m": ("δ_m", 1e3, "mm"), "t_f": ("t_f", 1e3, "ms"),
         "vc_t": ("v_C,t", 1.0, "m/s"), "vc_n": ("v_C,n", 1.0, "m/s"), "ve_t": ("v_E,t", 1.0, "m/s"),
         "ve_n": ("v_E,n", 1.0, "m/s"), "omega_f": ("ω_f", 1.0, "rad/s"), "cor": ("COR", 1.0, "")}


def _tension(config: dict, case: str) -> str:
    scene = scene_for(config, case, "modified", Separation.PENETRATION)
    res = simulate(scene, options_for(config, scene))
    limit = scene.k * scene.radius / (scene.ramp * scene.b)
    predicted = res.vc_n > limit  # near delta = 0, P ~ delta (k + c b delta_dot / R)
    found = pulls(res.force_min, res.force_max)
    verdict = (f"pulls: P_min = {res.force_min:.4g} N" if found else
               f"does not pull: P_min = {res.force_min:.3g} N is round-off (above −{RESOLUTION:g} × P_max "
               f"= {-RESOLUTION * res.force_max:.3g} N)")
    agree = "as" if predicted == found else "**unlike** what"
    return (f"**Tension, modified law, {case}** ({scene.angle:g}°): with contact held until δ = 0 the force "
            f"{verdict}. Near δ = 0, P ≈ δ (k + c b δ̇ / R), negative once the rebound speed exceeds kR/(c b) "
            f"= {limit:.3g} m/s; the rebound is {res.vc_n:.4g} m/s, {'above' if predicted else 'below'} it, "
            f"{agree} the force shows.")


def _cor(config: dict, published: list[dict]) -> str:
    separation = config["primary"]["separation"]
    parts, spread = [], {}
    for model in ("kelvin-voigt", "modified"):
        values = []
        for case in config["cases"]:
            scene = scene_for(config, case, model, separation)
            cor = simulate(scene, options_for(config, scene)).cor
            values.append(cor)
            parts.append(f"{model}, {case} (v_n = {scene.v_normal:.3g} m/s): {cor:.4f}")
        spread[model] = max(values) - min(values)
    printed = ", ".join(f"{e['value']:g} ({e['case']})" for e in published if e["quantity"] == "cor")
    linear_same = spread["kelvin-voigt"] < RESOLUTION
    if linear_same and spread["modified"] > RESOLUTION:
        why = (f"so the chapter's two printed CORs ({printed}) differ because the modified law's COR depends on "
               "v_n, and its cases approach at different v_n")
    else:
        why = f"against the chapter's printed CORs ({printed})"
    return ("**COR and approach speed**: " + "; ".join(parts) + ". Across these normal approach speeds the "
            f"linear law's COR {'does not change' if linear_same else 'changes'} (spread "
            f"{spread['kelvin-voigt']:.2g}) and the modified law's changes by {spread['modified']:.4f}, {why}.")


def _gravity(config: dict, table: pd.DataFrame, tests: pd.DataFrame) -> str:
    primary = config["primary"]
    parts = []
    for case in config["cases"]:
        scene = scene_for(config, case, primary["model"], primary["separation"])
        base = simulate(scene, options_for(config, scene))
        heavy = simulate(scene.with_(gravity=STANDARD_GRAVITY), options_for(config, scene))
        changes = {k: getattr(heavy, k) / getattr(base, k) - 1 for k in _SHOW if getattr(base, k) != 0}
        largest = max(changes, key=lambda k: abs(changes[k]))
        listed = ", ".join(f"{_SHOW[k][0]} {v:+.2%}" for k, v in changes.items())
        parts.append(f"{case} ({scene.angle:g}°): {listed} (largest: {_SHOW[largest][0]}, "
                     f"{getattr(base, largest) * _SHOW[largest][1]:.4g} → "
                     f"{getattr(heavy, largest) * _SHOW[largest][1]:.4g} {_SHOW[largest][2]})")
    moved = []
    for _, row in table.iterrows():
        with_g = tests[(tests["id"] == row["id"]) & (tests["hypothesis"] == "gravity")]
        if len(with_g) and with_g["status"].iloc[0] != row["status"]:
            moved.append(f"{row['id']} ({row['status']} → {with_g['status'].iloc[0]})")
    verdict = ("gravity changes the status of " + "; ".join(moved)) if moved else \
        "gravity changes the status of no printed value"
    return (f"**Gravity** (g = {STANDARD_GRAVITY} m/s²) changes the outputs by: " + "; ".join(parts)
            + f". Against the printed values, {verdict}.")


def _tangential(config: dict) -> str:
    """Which of the chapter's oblique results survive a compliant tangential contact (rubber's kappa): the
    ``linear`` spring on the primary law, and the exact ``microslip`` contact on the chapter's ball as a Hertz
    contact (its normal COR and contact time kept)."""
    primary, nu = config["primary"], config["compliance"]["poisson"]
    kappa = kappa_from_poisson(nu)
    twin = None
    parts = []
    for case in config["cases"]:
        scene = scene_for(config, case, primary["model"], primary["separation"])
        if not scene.has_tangential_motion:
            parts.append(f"{case} ({scene.angle:g}°): no tangential motion, so no tangential model can change it")
            continue
        twin = hertz_twin(config) if twin is None else twin
        verdicts = []
        for label, ball, tangential in (("linear spring", scene, "linear"),
                                        ("exact microslip, Hertz ball", twin.with_(angle=scene.angle), "microslip")):
            options = options_for(config, ball)
            rigid = simulate(ball, options)
            compliant = simulate(ball.with_(tangential=tangential, kappa=kappa), options)
            changes = {k: getattr(compliant, k) / getattr(rigid, k) - 1 for k in ("vc_t", "ve_t", "omega_f")
                       if getattr(rigid, k) != 0}
            listed = ", ".join(f"{_SHOW[k][0]} {v:+.3g}" for k, v in changes.items())
            if compliant.switches == 0 and compliant.regime == "sliding" and rigid.regime == "sliding":
                verdicts.append(f"{label}: slides throughout under both contacts, so the chapter's result stands "
                                f"(relative changes {listed}: round-off)")
            else:
                verdicts.append(f"{label}: part of the contact sticks ({compliant.switches} switches), and the "
                                f"chapter's rigid contact misstates the result: {listed}")
        parts.append(f"{case} ({scene.angle:g}°): " + "; ".join(verdicts))
    return (f"**Tangential compliance** (κ = k_t/k_n = 2(1 − ν)/(2 − ν) = {kappa:.4g} for ν = {nu:g}, beside the "
            "chapter's rigid contact; a linear tangential spring on the chapter's law, and the exact microslip "
            "contact on the chapter's ball as a Hertz contact with its normal COR and contact time): "
            + "; ".join(parts) + ". Every angle and κ: `results/compliance_map.csv`, notebook `validation`.")


def findings(config: dict, published: list[dict], table: pd.DataFrame, tests: pd.DataFrame) -> list[str]:
    """Measured statements about the chapter's claims, one Markdown bullet each, every number computed.

    Parameters
    ----------
    table, tests : DataFrame
        The replication and hypothesis tables of :func:`compare`.
    """
    out = [_tension(config, case) for case in config["cases"]]
    out.append(_cor(config, published))
    out.append(_gravity(config, table, tests))
    out.append(_tangential(config))
    return out


def write_report(config: dict, published_path: str, json_paths, csv_path: str, md_path: str,
                 findings_path: str | None = None) -> None:
    """Write ``replication.csv``, ``replication.md`` and (optionally) the findings alone as Markdown bullets."""
    published = load_published(published_path)
    table, tests = compare(config, published, load_runs(json_paths))
    table.to_csv(csv_path, index=False, float_format="%.12g")
    primary = config["primary"]
    counts = table["status"].value_counts()
    lines = [
        "# Replication: every value the chapter prints\n",
        f"Reproduction: `{primary['model']}` force law, `{primary['separation']}` separation criterion, "
        f"g = {config['gravity']:g} m/s², {config['method']} at rtol {config['rtol']:g}. "
        "Status: **match** within half a unit of the last printed digit, **agree** within one unit "
        "(a truncated or plot-read value can be that far off), **discrepancy** otherwise.\n",
        f"Totals: {', '.join(f'{counts.get(s, 0)} {s}' for s in ('match', 'agree', 'discrepancy'))}.\n",
        markdown_table(table, {"id": ("value", None), "printed": ("printed", None), "unit": ("unit", None),
                               "reproduced": ("reproduced", 1.0), "difference": ("difference", 1.0),
                               "status": ("status", None), "explanation": ("explanation", None)}),
        "\n## Hypotheses tested\n",
        "Each published value recomputed under each hypothesis; ✓ marks a match.\n",
        "\n".join(f"- `{name}`: {desc}" for name, (desc, _) in HYPOTHESES.items()) + "\n",
    ]
    grid = tests.assign(cell=[f"{v:.4g}{' ✓' if s == 'match' else ''}" for v, s in zip(tests["value"], tests["status"])])
    pivot = grid.pivot(index="id", columns="hypothesis", values="cell").reindex(table["id"]).reset_index()
    pivot = pivot.fillna("")
    lines.append(markdown_table(pivot, {c: (c, None) for c in ["id", *[h for h in HYPOTHESES if h in pivot]]}))
    bullets = "\n".join(f"- {f}" for f in findings(config, published, table, tests)) + "\n"
    lines += ["\n## Findings\n", bullets]
    with open(md_path, "w") as handle:
        handle.write("\n".join(lines))
    if findings_path is not None:
        with open(findings_path, "w") as handle:
            handle.write(bullets)
