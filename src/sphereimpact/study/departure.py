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
from .chung_ooi import EXACT, dem_rules, deviation, deviations, parse_rule, reference
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


def chung_deviations(numbers=TESTS) -> pd.DataFrame:
    """Each DEM rule's deviations from the exact contact on Chung & Ooi's oblique tests ``numbers`` (some of
    :data:`TESTS`), as the ``chung_ooi`` study's ``deviations.csv`` holds them (ValueError naming another test)."""
    return pd.concat([deviations(dem_rules(n), reference(n)) for n in check_tests(numbers)], ignore_index=True)


def check_tests(numbers) -> list[int]:
    """``numbers`` (None: :data:`TESTS`) as a list without repeats, each one of :data:`TESTS` (ValueError otherwise)."""
    numbers = list(dict.fromkeys(TESTS if numbers is None else numbers))
    other = [n for n in numbers if n not in TESTS]
    if other or not numbers:
        raise ValueError(f"tests must be some of {', '.join(map(str, TESTS))} (the oblique tests on a plane); got "
                         f"{other[0] if other else 'none'}")
    return numbers


def write_departure(folder, numbers=TESTS, section: dict | None = None) -> pd.DataFrame:
    """The study on its own (the command line's door, ``sphereimpact benchmark departure``): in ``folder``,
    ``departure.csv`` (:func:`departures`) for Chung & Ooi's tests ``numbers`` (:func:`chung_deviations`) and, with
    a study config's ``validation`` section ``section``, the Kharaz ball over its incidences
    (``departure_kharaz.csv``), and its figure ``departure.png``.  Each file is written beside and renamed."""
    from ..figures.departure import departure_figure

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    table = _write_tables(chung_deviations(numbers), section, folder / "departure_kharaz.csv", folder / "departure.csv")
    departure_figure(folder / "departure.csv", [folder / "departure.png"])
    return table


#: Digits of the written tables: the Kharaz ball's outputs, and the departures.
KHARAZ_DIGITS, DEPARTURE_DIGITS = "%.10g", "%.6g"


def _write(frame: pd.DataFrame, path, digits: str) -> None:
    """``frame`` as CSV at ``path``, written beside and renamed (a failed write keeps the old file)."""
    from ..files import replacing

    with replacing(path) as partial:
        frame.to_csv(partial, index=False, float_format=digits, lineterminator="\n")


def departures(chung_deviations: pd.DataFrame, kharaz: pd.DataFrame | None) -> pd.DataFrame:
    """One row per scene set, rule and quantity: the largest departure from the exact contact, relative to the exact
    quantity's largest magnitude over the set (``max_rel``), from Chung & Ooi's deviations (tests :data:`TESTS` that
    were run) and the Kharaz ball's table (:func:`kharaz_table`; None: left out)."""
    rows = []
    for number in TESTS:
        mine = chung_deviations[(chung_deviations["test"] == number) & chung_deviations["quantity"].isin(QUANTITIES)]
        for item in mine.itertuples(index=False):
            rows.append({"scenes": f"Chung & Ooi test {number}", "rule": item.rule, "quantity": item.quantity,
                         "max_rel": float(item.max_rel)})
    if kharaz is None:
        return pd.DataFrame(rows, columns=["scenes", "rule", "quantity", "max_rel"])
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
    return _write_tables(pd.read_csv(deviations_csv), section, kharaz_csv, departure_csv)


def _write_tables(chung: pd.DataFrame, section: dict | None, kharaz_csv, departure_csv) -> pd.DataFrame:
    """The departures of Chung & Ooi's deviations ``chung`` and, with a validation section, of the Kharaz ball over
    its incidences, written to ``departure_csv`` (and its table to ``kharaz_csv``): the pipeline's and the command
    line's one writer."""
    from ..parsing import parse_range

    kharaz = None if section is None else kharaz_table(section, parse_range(section["angles"]))
    if kharaz is not None:
        _write(kharaz, kharaz_csv, KHARAZ_DIGITS)
    table = departures(chung, kharaz)
    _write(table, departure_csv, DEPARTURE_DIGITS)
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
