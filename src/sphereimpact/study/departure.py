"""What a DEM code's tangential rule costs: each rule's largest departure from the exact elastic microslip contact.

DEM codes replace the exact tangential contact of Cattaneo and Mindlin by a spring capped by Coulomb friction, and
damp it (:mod:`sphereimpact.contact.tangential.dashpot`).  No code publishes what that choice costs; here it is
measured on the scenes the field checks against: Chung & Ooi's oblique tests 4-6 (from the ``chung_ooi`` study's
``deviations.csv``) and the Kharaz ball (the validation's alumina-on-glass experiment, over its incidences),
each rule solved on the same normal motion as the exact contact.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from ..impact.solve import simulate_many
from .chung_ooi import EXACT, deviation, parse_rule
from .tables import text_table

#: The tests of Chung & Ooi whose departures are shown (the oblique ones on a plane).
TESTS = (4, 5, 6)
#: The rules solved for the Kharaz ball beside the exact contact (a Hertz spring: the linear rule needs a linear law).
KHARAZ_RULES = ("mindlin", "mindlin+dashpot", "mindlin-displacement", "rigid")
#: The quantities compared, in the order figures and tables show them.
QUANTITIES = ("omega_f", "rebound_angle_contact", "e_t", "vc_t")
#: The Kharaz ball's scene set, as the tables name it.
KHARAZ = "Kharaz ball"


def kharaz_table(section: dict, angles, rules=KHARAZ_RULES) -> pd.DataFrame:
    """The Kharaz ball (the config's ``validation`` section, :func:`~.validation.experiment`) at each incidence of
    ``angles`` [deg], under the exact contact and each rule of ``rules`` (a model's name, ``+dashpot`` with the
    tangential dashpot set from the measured e_n): columns ``rule``, ``incidence`` and :data:`QUANTITIES`."""
    from .validation import experiment

    exp = experiment(section)
    parts = []
    for rule in (EXACT, *rules):
        model, dashpot = parse_rule(rule)
        scene = exp.with_tangential(model)
        if dashpot:
            scene = scene.with_(dashpot_cor=section["cor"])
        outcomes = simulate_many([scene.with_(angle=float(a)) for a in angles])
        parts.append(pd.DataFrame({"rule": rule, "incidence": np.asarray(angles, dtype=float),
                                   **{q: [float(getattr(o, q)) for o in outcomes] for q in QUANTITIES}}))
    return pd.concat(parts, ignore_index=True)


def departures(chung_deviations: pd.DataFrame, kharaz: pd.DataFrame) -> pd.DataFrame:
    """One row per scene set, rule and quantity: the largest departure from the exact contact, relative to the exact
    quantity's largest magnitude over the set (``max_rel``), from Chung & Ooi's deviations (tests :data:`TESTS` that
    were run) and the Kharaz ball's table (:func:`kharaz_table`)."""
    rows = []
    for number in TESTS:
        mine = chung_deviations[(chung_deviations["test"] == number) & chung_deviations["quantity"].isin(QUANTITIES)]
        for item in mine.itertuples(index=False):
            rows.append({"scenes": f"Chung & Ooi test {number}", "rule": item.rule, "quantity": item.quantity,
                         "max_rel": float(item.max_rel)})
    exact = kharaz[kharaz["rule"] == EXACT].reset_index(drop=True)
    for rule, part in kharaz[kharaz["rule"] != EXACT].groupby("rule", sort=False):
        for quantity in QUANTITIES:
            found = deviation(part.reset_index(drop=True), exact, quantity)
            if found is not None:
                rows.append({"scenes": KHARAZ, "rule": rule, "quantity": quantity, "max_rel": found["max_rel"]})
    return pd.DataFrame(rows, columns=["scenes", "rule", "quantity", "max_rel"])


def run_departure(section: dict, deviations_csv, kharaz_csv, departure_csv) -> pd.DataFrame:
    """The pipeline's study (rule ``dem_departure``): the Kharaz ball's table over the validation's incidences
    (``section['angles']``) and every departure, written."""
    from ..parsing import parse_range

    kharaz = kharaz_table(section, parse_range(section["angles"]))
    kharaz.to_csv(kharaz_csv, index=False, float_format="%.10g", lineterminator="\n")
    table = departures(pd.read_csv(deviations_csv), kharaz)
    table.to_csv(departure_csv, index=False, float_format="%.6g", lineterminator="\n")
    return table


def readme_block(departure_csv) -> str:
    """The docs' block: per rule and scene set, its largest departure in spin and in the contact point's rebound."""
    table = pd.read_csv(departure_csv)
    scenes = list(dict.fromkeys(table["scenes"]))
    rules = list(dict.fromkeys(table["rule"]))
    rows = []
    for rule in rules:
        cells = []
        for name in scenes:
            part = table[(table["scenes"] == name) & (table["rule"] == rule)].set_index("quantity")["max_rel"]
            cells.append(" / ".join(f"{part[q]:.2g}" if q in part else "—" for q in ("omega_f", "rebound_angle_contact")))
        rows.append((f"`{rule}`", *cells))
    return ("What a DEM code's tangential rule costs (`results/chung_ooi/departure.csv`, rule `dem_departure`): each "
            "rule's largest departure from the exact elastic microslip contact, relative to the exact quantity's largest "
            "magnitude, in the ball's spin ω_f / the contact point's rebound angle (`+dashpot`: Kratos' tangential "
            "dashpot set from the scenes' normal COR; `paper_figures/dem_departure.png`):\n\n"
            + text_table(("rule", *scenes), rows) + "\n")


def write_report(departure_csv, png, md) -> None:
    """The departure figure (:func:`sphereimpact.figures.departure.departure_figure`) and the docs' block."""
    from ..figures.departure import departure_figure
    from ..files import replacing

    departure_figure(departure_csv, [png])
    with replacing(md) as partial:
        Path(partial).write_text(readme_block(departure_csv), encoding="utf-8")
