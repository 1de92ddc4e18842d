"""Chung & Ooi's eight DEM benchmark tests (Granular Matter 13, 2011, 643-656), with exact references.

The tests' inputs, each number with its source, are :data:`~.chung_ooi_definition.DEFINITION`.  Each test is a list
of scenes, one per case (material and varied input); its reference is this project's exact solution of the same contact: elastic
Hertz (tests 1, 2, 5) or Hunt-Crossley damping set so that each row's normal COR is the test's (3, 4, 6, 7, 8),
and the exact elastic microslip contact of Cattaneo and Mindlin for the tangential motion (tests 4-8).  Where
e < 1 the reference is exact for that model, whose tangential contact is undamped; DEM codes damp their
tangential spring too, and may differ from it by that choice (each file's ``model`` and ``tangential`` columns
name the model).  Beside
it, the simplified rules DEM codes use (:data:`DEM_RULES`), and for test 3 every damped law of the project.
:func:`write_reference` writes one CSV per test for DEM developers (units in the header), and
:func:`sphereimpact.study.dem_compare.compare` judges a code's files against them.
"""

from __future__ import annotations

import functools
import math
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from ..contact.laws import LAWS
from ..errors import UnitWarning
from ..files import replacing
from ..contact.materials import dundurs_beta, effective_moduli
from ..contact.tangential import TANGENTIALS
from ..impact.calibrate import calibrate
from ..impact.planar_pair import serves
from ..impact.scene import Scene
from ..impact.solve import simulate, simulate_many
from .chung_ooi_definition import DEFINITION, listed, load_tests, variant_tests
from .benchmark_columns import CLOSED_FORMS, INPUTS, OUTCOME_OUTPUTS, OUTPUTS, STATEMENTS
from .dem_compare import read_with_units, rule_verdicts
from .tables import text_table

#: The exact tangential contact: elastic microslip (checked against Cattaneo-Mindlin and Maw's gross-slip line).
EXACT = "microslip"
#: The simplified tangential rules DEM codes use, solved beside the exact contact (``linear``: with the linear
#: spring-dashpot normal law it needs, its spring giving the Hertz contact's elastic contact time).  ``+dashpot``: the
#: rule with the tangential dashpot Kratos sets from the test's normal COR (``dashpot_cor``,
#: :mod:`sphereimpact.contact.tangential.dashpot`); ``mindlin+dashpot`` is Kratos's DEM_D_Hertz_viscous_Coulomb.
DEM_RULES = ("mindlin", "mindlin+dashpot", "mindlin-displacement", "linear", "linear+dashpot", "rigid")
#: The reference files' variants: ``exact`` the exact elastic microslip contact with damping in the normal law
#: only; ``damped-mindlin`` the damped Mindlin spring of the DEM codes (rule ``mindlin+dashpot``), written for the
#: oblique tests whose COR is below 1, where the two differ (:func:`variant_tests`), in a folder of its own.
VARIANTS = {"exact": EXACT, "damped-mindlin": "mindlin+dashpot"}

#: The damped laws of test 3, each with its damping set to the requested COR (the linear springs with the
#: Hertz contact's elastic contact time).
DAMPED_LAWS = ("hunt-crossley", "linear-hunt-crossley", "kelvin-voigt", "modified")
#: Hertz's contact time of two elastic spheres, t_f = HERTZ_TIME (m*^2 / (R* E*^2 v))^(1/5): twice the time to
#: delta_m, 2 delta_m / v int_0^1 (1 - x^(5/2))^(-1/2) dx = (4/5) B(2/5, 1/2) delta_m / v (Johnson, Contact Mechanics,
#: 1985, sec. 11.4), with delta_m = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5): 2.868...
HERTZ_TIME = 0.8 * math.sqrt(math.pi) * math.gamma(0.4) / math.gamma(0.9) * (15.0 / 16.0) ** 0.4
def parse_rule(rule: str) -> tuple[str, bool]:
    """A rule of :data:`DEM_RULES` (or any model's name, ``+dashpot`` or not) as (tangential model, with the dashpot
    set from the COR)."""
    tangential, _, extra = rule.partition("+")
    if extra not in ("", "dashpot"):
        raise ValueError(f"a rule is a tangential model's name, with '+dashpot' or without; got {rule!r}")
    return tangential, bool(extra)


def _approaches(test: dict) -> list[dict]:
    """The varied input of a test as Scene approach fields (speed, incidence, spin) and the COR, one per row."""
    cors = listed(test, "cor")
    if "incidence" in test:
        return [dict(speed=test["speed"], incidence=float(a), cor=cors[0]) for a in listed(test, "incidence")]
    v_n = test["normal_speed"]
    if "surface_speed" in test:  # the spin alone makes the contact point slip at omega R
        return [dict(speed=v_n, incidence=0.0, spin=-s / test["radius"], cor=cors[0])
                for s in listed(test, "surface_speed")]
    if "tangential_speed" in test:
        return [dict(speed=math.hypot(v_n, v_t), incidence=math.degrees(math.atan2(v_t, v_n)), cor=cors[0])
                for v_t in listed(test, "tangential_speed")]
    if "spin" in test:
        return [dict(speed=v_n, incidence=0.0, spin=float(w), cor=cors[0]) for w in listed(test, "spin")]
    return [dict(speed=v_n, incidence=0.0, cor=c) for c in cors]


def scenes_of_test(number: int, tangential: str = EXACT, model: str = "hunt-crossley", path=DEFINITION) -> pd.DataFrame:
    """Test ``number``'s scenes, one row per case: the inputs (:data:`INPUTS`) and the ``scene`` column, with the
    tangential rule ``tangential`` (a model's name; ``NAME+dashpot`` the model with the tangential dashpot set from
    each row's COR, :data:`DEM_RULES`) and, where the COR is below 1, the damped law ``model`` calibrated at each
    row's normal speed (elastic ``hertz`` where the COR is 1; a linear law gets the Hertz contact's elastic
    contact time)."""
    materials, tests = load_tests(path)
    test = tests[number]
    with warnings.catch_warnings():  # test 8's partner is 1000 times denser than any material, on purpose
        warnings.simplefilter("ignore", UnitWarning)
        return _scenes(number, test, materials, tangential, model)


def _scenes(number: int, test: dict, materials: dict, rule: str, model: str) -> pd.DataFrame:
    """:func:`scenes_of_test`'s rows: per material (and, for a test with ``shear_cases``, per case of the spheres'
    shear modulus), one per varied input."""
    rows = []
    for name in test["materials"]:
        material = materials[name]
        radius, partner = test["radius"], test.get("partner")
        body = dict(mass=material["rho"] * 4.0 / 3.0 * math.pi * radius ** 3, diameter=2 * radius)
        other = math.inf if partner is None else material["E"]  # a rigid plane, or a partner of the same material
        e_star, g_star = effective_moduli(material["E"], material["nu"], other, material["nu"])
        beta = dundurs_beta(material["E"], material["nu"], other, material["nu"])
        if partner is not None:
            r2 = radius * partner["radius_factor"]
            body |= dict(partner_mass=material["rho"] * partner["density_factor"] * 4.0 / 3.0 * math.pi * r2 ** 3,
                         partner_diameter=2 * r2)
        for label, factor in test.get("shear_cases", {"": 1.0}).items():  # G times factor: G* and kappa too
            case = {"case": f"{name}, case {label}" if label else name, "kappa": factor * 4.0 * g_star / e_star,
                    "modulus": e_star, "dundurs_beta": beta}
            rows += [_row(number, test, case, body, approach, rule, model) for approach in _approaches(test)]
    return pd.DataFrame(rows)


def _row(number: int, test: dict, case: dict, body: dict, approach: dict, rule: str, model: str) -> dict:
    """One row of a test: its ``case`` (name, E*, kappa, Dundurs' beta), the bodies' fields and one approach."""
    tangential, extra = parse_rule(rule)
    approach = dict(approach)
    cor, spin = approach.pop("cor"), approach.get("spin", 0.0)
    both = {"opposite": dict(partner_spin=-spin), None: {}}[test.get("partner_spins")]  # in the ball's sense
    dashpot = {"parameters": {"dashpot_cor": cor}} if extra else {}
    scene = _scene(dict(mu=test["mu"], **body, **approach, **both, **dashpot), case["modulus"], case["kappa"], cor,
                   tangential, "kelvin-voigt" if tangential == "linear" else model)
    return {"test": number, "case": case["case"], "model": scene.model, "tangential": tangential, "rule": rule,
            "dashpot_cor": scene.parameters.get("dashpot_cor", math.nan),
            "speed": scene.speed, "incidence": scene.incidence_deg, "spin": scene.spin, "mass": body["mass"],
            "diameter": body["diameter"], "partner_mass": body.get("partner_mass", math.nan),
            "partner_diameter": body.get("partner_diameter", math.nan),
            "partner_spin": scene.partner_spin if scene.has_partner else math.nan,
            "modulus": case["modulus"], "kappa": case["kappa"], "mu": test["mu"], "cor_target": cor,
            "dundurs_beta": case["dundurs_beta"], **_frame(scene, test.get("lab")), "scene": scene}


def _frame(scene: Scene, lab: str | None) -> dict:
    """A row's approach as the DEM codes set it up (:data:`FRAME_INPUTS`)."""
    half = 0.5 * scene.v_normal if lab == "symmetric" and scene.has_partner else math.nan
    return {"v_n": scene.v_normal, "v_t": scene.v_tangent, "slip": scene.slip0, "lab_ball_v_n": -half,
            "lab_partner_v_n": half}


#: The 3.5 of Kratos' friction_ratio (:data:`~.benchmark_columns.FRAME_OUTPUTS`): 1 + 1/alpha, alpha = 2/5.
FRICTION_FACTOR = 3.5


def _frame_outputs(out: pd.DataFrame) -> pd.DataFrame:
    """:data:`FRAME_OUTPUTS` of solved rows: the lab frame after (each velocity shifted by the partner's lab velocity
    before) and, on a plane with slip, the normalised quantities."""
    plane, slipping = out["partner_mass"].isna(), out["slip"] != 0
    mu_v_n = out["mu"] * out["v_n"]
    with np.errstate(divide="ignore", invalid="ignore"):
        return pd.DataFrame({
            "slip_ratio": np.where(plane, out["slip"] / mu_v_n, np.nan),
            "spin_ratio": np.where(plane, 0.5 * out["diameter"] * out["omega_f"] / mu_v_n, np.nan),
            "beta": np.where(slipping, -out["ve_t"] / out["slip"], np.nan),
            "friction_ratio": np.where(slipping, FRICTION_FACTOR * mu_v_n * (1 + out["cor_target"]) / out["slip"].abs(),
                                       np.nan),
            "lab_ball_vc_n": out["vc_n"] + out["lab_partner_v_n"],
            "lab_partner_vc_n": out["partner_vc_n"] + out["lab_partner_v_n"]}, index=out.index)


def _scene(fields: dict, e_star: float, kappa: float, cor: float, tangential: str, model: str) -> Scene:
    """One test scene: elastic Hertz at COR 1, else ``model`` with its damping calibrated at this normal speed."""
    stiffness = dict(kappa=kappa) if tangential != "rigid" else {}
    hertzian = model in ("hertz", "hunt-crossley")
    if cor == 1.0 and hertzian:
        return Scene(model="hertz", modulus=e_star, tangential=tangential, **stiffness, **fields)
    if hertzian:
        scene = Scene(model="hunt-crossley", modulus=e_star, tangential=tangential, **stiffness, **fields)
    else:  # a linear spring with the Hertz contact's elastic contact time
        elastic = Scene(model="hertz", modulus=e_star, **{k: v for k, v in fields.items() if k != "parameters"})
        k = elastic.reduced.mass * (math.pi / hertz(elastic)["hertz_t_f"]) ** 2
        damping = {LAWS.law(model).damping: 0.0} if cor == 1.0 else {}
        scene = Scene(model=model, k=k, tangential=tangential, **stiffness, **fields, **damping)
        if cor == 1.0:
            return scene
    return _calibrated(scene, cor)


#: The damping each normal problem and COR calibrated to, per process: a test's rows share a few normal problems
#: (test 6 and 7 vary the spin alone), and the damping depends on nothing else (``Scene.normal_problem``).
_DAMPING: dict = {}


def _calibrated(scene: Scene, cor: float) -> Scene:
    """``scene`` with its law's damping set so that its normal COR is ``cor`` (:func:`calibrate`), once per normal
    problem: the same value calibrating each row again would find."""
    key = (scene.normal_problem, cor)
    if key not in _DAMPING:
        found = calibrate(scene, cor)
        _DAMPING[key] = (found.parameter, found.value)
    name, value = _DAMPING[key]
    return scene.with_(**{name: value})


def hertz(scene: Scene) -> dict:
    """Hertz's elastic closed forms (:data:`CLOSED_FORMS`) for the normal approach of ``scene`` (Johnson, Contact
    Mechanics, 1985, sec. 11.4): delta_m = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5), P_max = 4/3 E* sqrt(R*)
    delta_m^(3/2), t_f = :data:`HERTZ_TIME` (m*^2 / (R* E*^2 v))^(1/5), with m*, R* of the contact."""
    reduced, v = scene.reduced, scene.v_normal
    e_star = 0.75 * scene.k / math.sqrt(reduced.radius)
    delta_m = (15.0 * reduced.mass * v * v / (16.0 * e_star * math.sqrt(reduced.radius))) ** 0.4
    return {"hertz_t_f": HERTZ_TIME * (reduced.mass ** 2 / (reduced.radius * e_star ** 2 * v)) ** 0.2,
            "hertz_delta_m": delta_m, "hertz_force_max": 4.0 / 3.0 * e_star * math.sqrt(reduced.radius) * delta_m ** 1.5}


def solve(table: pd.DataFrame, spring_gap: bool = False) -> pd.DataFrame:
    """The table's scenes solved (:func:`~sphereimpact.impact.solve.simulate_many`): its inputs and
    :data:`OUTPUTS` (e_t = vc_t / v_t where the approach has a tangential speed; the partner's where there is
    one), the line's turn and the rigid contact's :func:`reduction_gap` (:data:`STATEMENTS`), with ``spring_gap``
    the spring's too (a reference's: seconds a row where a stiff spring rings), and Hertz's closed forms for the
    elastic rows."""
    outcomes = simulate_many(table["scene"].tolist())
    out = table.drop(columns="scene").copy()
    for key in OUTCOME_OUTPUTS:
        out[key] = [math.nan if getattr(outcome, key) is None else float(getattr(outcome, key)) for outcome in outcomes]
    out = pd.concat([out, _frame_outputs(out)], axis=1)
    forms = [hertz(scene) if scene.model == "hertz" else dict.fromkeys(CLOSED_FORMS, math.nan) for scene in table["scene"]]
    out["line_turn"] = [_line_turn(scene, outcome) for scene, outcome in zip(table["scene"], outcomes)]
    out["reduction_gap"] = [reduction_gap(scene) for scene in table["scene"]]
    if spring_gap:
        out = with_spring_gap(out, table["scene"])
    return pd.concat([out, pd.DataFrame(forms, index=out.index)], axis=1)


def _line_turn(scene: Scene, outcome) -> float:
    """The angle [rad] the line of centres of two spheres would turn during the contact (:data:`STATEMENTS`); NaN on
    a plane."""
    if not scene.has_partner:
        return math.nan
    after = abs(outcome.vc_t - outcome.partner_vc_t)
    return max(abs(scene.v_tangent), after) * outcome.t_f / (scene.radius + 0.5 * scene.partner_diameter)


def reduction_gap(scene: Scene, tangential: str = "rigid") -> float:
    """What the reduction of two spheres to one on a flat costs by holding the line of centres fixed [m/s]: the
    largest difference of either body's velocity or spin times its radius between ``simulate``'s reduction and the
    planar two-body model (``body='planar'``), both with the rigid tangential contact, or (``tangential='spring'``)
    both with the scene's own tangential spring where the two-body model has it (the damped Mindlin variant's, the
    DEM rules'), else with Mindlin's undamped spring at the scene's kappa: the two-body model's contact nearest the
    exact microslip one, which it has not (:mod:`sphereimpact.impact.planar_pair`).  NaN on a plane, and for the
    spring where the scene has no kappa (a rigid contact)."""
    if not scene.has_partner:
        return math.nan
    if tangential == "rigid":
        return _gap(scene.with_(tangential="rigid"))
    if tangential != "spring":
        raise ValueError(f"tangential must be 'rigid' or 'spring'; got {tangential!r}")
    if scene.kappa is None:
        return math.nan
    return _gap(scene if serves(TANGENTIALS[scene.tangential]) else scene.with_(tangential="mindlin"))


def with_spring_gap(solved: pd.DataFrame, scenes) -> pd.DataFrame:
    """``solved`` (:func:`solve`'s table) with the spring's :func:`reduction_gap` of each of ``scenes`` (its rows, in
    order) beside the rigid contact's: a reference's column."""
    out = solved.copy()
    out.insert(out.columns.get_loc("reduction_gap") + 1, "reduction_gap_spring",
               [reduction_gap(scene, "spring") for scene in scenes])
    return out


@functools.lru_cache(maxsize=1024)
def _gap(pair: Scene) -> float:
    """:func:`reduction_gap` of a scene with the contact it is measured with, once per scene (every rule of a row
    shares it)."""
    planar, reduced = simulate(pair, body="planar"), simulate(pair)
    radii = {"omega_f": pair.radius, "partner_omega_f": 0.5 * pair.partner_diameter}
    return max(abs(getattr(planar, key) - getattr(reduced, key)) * radii.get(key, 1.0)
               for key in ("vc_t", "vc_n", "omega_f", "partner_vc_t", "partner_vc_n", "partner_omega_f"))


def reference(number: int, path=DEFINITION, variant: str = "exact") -> pd.DataFrame:
    """Test ``number``'s reference: the exact contact (:data:`EXACT`) for the oblique tests, the normal motion alone
    for the normal ones (1-3; test 3 once per law of :data:`DAMPED_LAWS`); ``variant`` ``damped-mindlin`` (an oblique
    test with a COR below 1) the damped Mindlin spring of the DEM codes instead (:data:`VARIANTS`)."""
    if variant not in VARIANTS:
        raise ValueError(f"variant must be one of {', '.join(VARIANTS)}; got {variant!r}")
    if variant != "exact" and number not in variant_tests([number], path):
        raise ValueError(f"test {number} has no {variant!r} reference: only the oblique tests with a COR below 1 "
                         f"({', '.join(map(str, variant_tests(chosen_tests(None, path), path)))}), where it differs")
    oblique = number >= 4
    laws = DAMPED_LAWS if number == 3 else ("hunt-crossley",)
    rule = VARIANTS[variant] if oblique else "rigid"
    return solve(pd.concat([scenes_of_test(number, rule, law, path) for law in laws], ignore_index=True),
                 spring_gap=True)


def dem_rules(number: int, path=DEFINITION) -> pd.DataFrame:
    """Test ``number`` (an oblique one) solved with each simplified DEM rule of :data:`DEM_RULES`."""
    return solve(pd.concat([scenes_of_test(number, rule, path=path) for rule in DEM_RULES], ignore_index=True))


def deviations(rules: pd.DataFrame, exact: pd.DataFrame, quantities=("e_t", "omega_f", "vc_t", "rebound_angle_contact",
                                                                      "partner_omega_f")) -> pd.DataFrame:
    """Per tangential rule (column ``rule``) and quantity, the largest deviation of ``rules`` from ``exact`` (rows matched by case
    and position): absolute, and relative to the largest magnitude of the exact column."""
    rows = []
    exact = exact.reset_index(drop=True)
    for rule, part in rules.groupby("rule", sort=False):
        part = part.reset_index(drop=True)
        for quantity in quantities:
            found = deviation(part, exact, quantity)
            if found is not None:
                rows.append({"test": int(exact["test"].iloc[0]), "rule": rule, "quantity": quantity,
                             "max_abs": found["max_abs"], "max_rel": found["max_rel"]})
    return pd.DataFrame(rows)


def deviation(code: pd.DataFrame, exact: pd.DataFrame, quantity: str) -> dict | None:
    """How far ``code``'s column ``quantity`` is from ``exact``'s, row by row: the rows compared, the largest absolute
    difference and that over the exact column's largest magnitude; None where either lacks the column or the exact
    solution holds it at 0 (a normal test's tangential outputs: nothing to compare)."""
    if quantity not in code or quantity not in exact or not (np.abs(exact[quantity]) > 0).any():
        return None
    diff = np.abs(code[quantity].to_numpy(dtype=float) - exact[quantity].to_numpy(dtype=float))
    largest = float(np.nanmax(diff))
    return {"rows": int(np.isfinite(diff).sum()), "max_abs": largest,
            "max_rel": largest / float(np.nanmax(np.abs(exact[quantity])))}


def header(units: dict) -> dict:
    """Column name -> ``name [unit]`` (no brackets for text columns)."""
    return {name: f"{name} [{unit}]" if unit else name for name, unit in units.items()}


def write_table(table: pd.DataFrame, path) -> None:
    """A reference table as CSV, each column headed ``name [unit]``, numbers to 12 significant digits."""
    units = INPUTS | OUTPUTS | CLOSED_FORMS | STATEMENTS
    with replacing(path) as partial:  # a reference file is whole or the old one
        table.rename(columns=header({name: units[name] for name in table.columns if name in units})).to_csv(
            partial, index=False, float_format="%.12g", lineterminator="\n")


def read_table(path) -> pd.DataFrame:
    """A reference table (or a DEM code's, in the same columns), the units stripped from its header
    (:func:`~.dem_compare.read_with_units`, which also gives them)."""
    return read_with_units(path)[0]


def chosen_tests(numbers=None, path=DEFINITION) -> list[int]:
    """``numbers``, sorted, checked against the definition's tests (all of them when None): ValueError names one
    it lacks."""
    _, tests = load_tests(path)
    unknown = [n for n in numbers or () if n not in tests]
    if unknown:
        raise ValueError(f"tests must be some of {', '.join(map(str, sorted(tests)))}; got {unknown[0]!r}")
    return sorted(numbers or tests)


def write_reference(folder, numbers=None, path=DEFINITION, variant: str = "exact") -> list[Path]:
    """One CSV per test, ``test<N>.csv``, in ``folder`` (created): each test's inputs and outputs of the reference
    ``variant`` (:data:`VARIANTS`; ``damped-mindlin`` for the tests that have it, :func:`variant_tests`); every test
    of the definition, or those ``numbers``."""
    folder = Path(folder)
    numbers = chosen_tests(numbers, path)
    if variant != "exact":
        numbers = variant_tests(numbers, path)
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for number in numbers:
        target = folder / f"test{number}.csv"
        write_table(reference(number, path, variant), target)
        written.append(target)
    return written


def read_curves(path) -> pd.DataFrame:
    """The paper's reference curves as shipped (``data/chung_ooi_paper/curves.csv``: its header and README say what
    they are, whose digitisation and under which licence)."""
    return pd.read_csv(path, comment="#", keep_default_na=False, dtype={"case": str})


def covers(curve_case: str, case: str) -> bool:
    """Whether a published curve of ``curve_case`` (a material, test 8's ``case A`` or ``case B``, or '' for every
    case) is one of the reference's ``case`` (a material, or ``<material>, case A``)."""
    return curve_case in ("", case) or case.endswith(f", {curve_case}")


def published_points(curves: pd.DataFrame, number: int, exact: pd.DataFrame) -> pd.DataFrame:
    """Test ``number``'s published curves in the figures' columns: each point's ``case`` (every case of ``exact``
    where the curve is not one material's), ``column`` (vc_t, omega_f or rebound_angle_contact), ``x`` (in the
    test's varied input, :data:`VARIED`) and ``y`` (in this project's units and sign); ``material`` the curve's
    own case ('' for one of every case) and ``quantity`` its own quantity.  The conversions: e_t v_t = vc_t;
    R omega' / (mu v_n) and v_t / (mu v_n) at the test's v_n and radius; friction_ratio to the ball's spin where the
    spin alone slips (tests 6 and 8); the paper's spin sign by ``sign``."""
    mine = curves[curves["test"] == number]
    rows = []
    for case in dict.fromkeys(exact["case"]):
        part = exact[exact["case"] == case]
        speed, radius, mu, v_n, cor = (float(part[c].iloc[0]) for c in ("speed", "diameter", "mu", "v_n", "cor_target"))
        radius /= 2
        for curve in mine[[covers(name, case) for name in mine["case"]]].itertuples(index=False):
            x, y = float(curve.x), float(curve.y) * curve.sign
            if curve.quantity == "e_t":  # at this test's speed along the path
                column, y = "vc_t", y * speed * math.sin(math.radians(x))
            elif curve.quantity == "spin_ratio":
                column, y = "omega_f", y * mu * v_n / radius
            else:
                column = curve.quantity
            if curve.x_quantity == "slip_ratio":  # v_t = x mu v_n: the incidence at this test's v_n
                x = math.degrees(math.atan(x * mu))
            elif curve.x_quantity == "friction_ratio":  # the spin alone slips: |omega| R = 3.5 mu (1 + e) v_n / x
                if (part["v_t"] != 0).any() or (part["partner_spin"].fillna(0.0) != 0).any():
                    raise ValueError(f"test {number}: friction_ratio is read as the ball's spin only where the spin "
                                     "alone makes the contact slip")
                x = math.copysign(FRICTION_FACTOR * mu * (1 + cor) * v_n / (x * radius), part["spin"].iloc[0])
            rows.append({"case": case, "material": curve.case, "quantity": curve.quantity, "column": column, "x": x,
                         "y": y})
    return pd.DataFrame(rows, columns=["case", "material", "quantity", "column", "x", "y"])


def published_deviations(curves: pd.DataFrame, exact_by_test: dict) -> pd.DataFrame:
    """Each published curve's largest deviation from the exact reference, per test, case and quantity, in the curve's
    own quantities (the reference's columns of them; the paper's spin sign converted): the exact answer interpolated linearly
    at the curve's points within its range; ``max_rel`` over the exact quantity's largest magnitude, ``at`` the
    curve's x there, ``outside`` its points beyond the reference's range."""
    rows = []
    for number, exact in exact_by_test.items():
        mine = curves[curves["test"] == number]
        for curve_key, curve in mine.groupby(["quantity", "x_quantity", "case"], sort=False):
            quantity, x_quantity, case = curve_key
            for name in [name for name in dict.fromkeys(exact["case"]) if covers(case, name)]:
                part = exact[exact["case"] == name]
                order = np.argsort(part[x_quantity].to_numpy(), kind="stable")
                xs, ys = part[x_quantity].to_numpy(float)[order], part[quantity].to_numpy(float)[order]
                x, y = curve["x"].to_numpy(float), curve["y"].to_numpy(float) * curve["sign"].to_numpy(float)
                inside = (x >= xs.min()) & (x <= xs.max())
                if not inside.any():
                    continue
                diff = np.abs(y[inside] - np.interp(x[inside], xs, ys))
                worst = int(np.argmax(diff))
                rows.append({"test": number, "case": name, "quantity": quantity, "x_quantity": x_quantity,
                             "points": int(inside.sum()), "outside": int((~inside).sum()),
                             "max_abs": float(diff[worst]), "max_rel": float(diff[worst] / np.abs(ys).max()),
                             "at": float(x[inside][worst])})
    return pd.DataFrame(rows, columns=["test", "case", "quantity", "x_quantity", "points", "outside", "max_abs",
                                       "max_rel", "at"])


#: The varied input of each oblique test, plotted along x: (column, label).
VARIED = {4: ("incidence", "incidence [deg]"), 5: ("incidence", "incidence [deg]"), 6: ("spin", "spin [rad/s]"),
          7: ("spin", "spin of each sphere [rad/s]"), 8: ("spin", "spin of the ball [rad/s]")}


def run_study(folder, numbers=None, path=DEFINITION, curves_csv=None) -> None:
    """The pipeline's study (rule ``chung_ooi``): in ``folder``, each test's reference ``test<N>.csv`` (and in
    ``folder/damped-mindlin/`` the DEM codes' damped Mindlin spring's, for the tests that have it), the DEM
    rules' solutions of the oblique tests (``dem_rules.csv``), their deviations from the reference
    (``deviations.csv``) and the verdict ``benchmark compare`` gives each rule at its default tolerance
    (``verdicts.csv``), the checks of each reference against its closed forms (``checks.csv``), and with
    ``curves_csv`` (the paper's curves, :func:`read_curves`) each curve's largest deviation from the reference, and
    from the damped Mindlin spring's where a test has that variant (``published.csv``, :func:`published_deviations`;
    its ``reference`` column names which)."""
    folder = Path(folder)
    numbers = chosen_tests(numbers, path)
    folder.mkdir(parents=True, exist_ok=True)
    rules, deviation, checks, verdicts, exacts, variants = [], [], [], [], {}, {}
    for number in numbers:
        exact = exacts[number] = reference(number, path)
        write_table(exact, folder / f"test{number}.csv")
        checks.append(_checks(number, exact))
        if number >= 4:
            solved = dem_rules(number, path)
            if number in variant_tests([number], path):  # the same rows as the variant's reference
                rule = VARIANTS["damped-mindlin"]
                damped = variants[number] = with_spring_gap(solved[solved["rule"] == rule].reset_index(drop=True),
                                                            scenes_of_test(number, rule, path=path)["scene"])
                (folder / "damped-mindlin").mkdir(exist_ok=True)
                write_table(damped, folder / "damped-mindlin" / f"test{number}.csv")
            rules.append(solved)
            deviation.append(deviations(solved, exact))
            verdicts.append(rule_verdicts(solved, exact))
    (pd.concat(verdicts, ignore_index=True) if verdicts else pd.DataFrame(
        columns=["test", "quantity", "max_rel", "tolerance", "passed", "rule"])).to_csv(
        folder / "verdicts.csv", index=False, float_format="%.6g", lineterminator="\n")
    write_table(pd.concat(rules, ignore_index=True) if rules else pd.DataFrame(columns=list(INPUTS)),
                folder / "dem_rules.csv")
    (pd.concat(deviation, ignore_index=True) if deviation else pd.DataFrame(
        columns=["test", "rule", "quantity", "max_abs", "max_rel"])).to_csv(
        folder / "deviations.csv", index=False, float_format="%.6g", lineterminator="\n")
    pd.concat(checks, ignore_index=True).to_csv(folder / "checks.csv", index=False, float_format="%.6g",
                                                lineterminator="\n")
    if curves_csv is not None:
        curves = read_curves(curves_csv)
        published = pd.concat([published_deviations(curves, tables).assign(reference=variant) for variant, tables
                               in (("exact", exacts), ("damped-mindlin", variants))], ignore_index=True)
        published.insert(1, "reference", published.pop("reference"))
        published.to_csv(folder / "published.csv", index=False, float_format="%.6g", lineterminator="\n")


def _checks(number: int, exact: pd.DataFrame) -> pd.DataFrame:
    """How far test ``number``'s reference is from its independent check: Hertz's closed forms (elastic rows), the
    requested COR (damped rows), and, where the contact slides throughout (slip never stops: the last rows of
    tests 5 and 6), Maw's gross-slip line vc_t = v_t - mu (1 + e) v_n."""
    rows = []
    elastic = exact["model"] == "hertz"
    for name in ("t_f", "delta_m", "force_max"):
        if elastic.any():
            part = exact[elastic]
            rows.append({"test": number, "check": f"{name} against Hertz's closed form",
                         "max_rel": float(np.max(np.abs(part[name] / part[f"hertz_{name}"] - 1)))})
    rows.append({"test": number, "check": "COR against the requested one",
                 "max_rel": float(np.max(np.abs(exact["cor"] / exact["cor_target"] - 1)))})
    if exact["partner_spin"].notna().any() and (exact["partner_spin"] == -exact["spin"]).all():  # test 7: no slip
        rows.append({"test": number, "check": "vc_t and omega_f against the paper's V'ct = 0 and omega' = omega",
                     "max_rel": float(max(np.max(np.abs(exact["vc_t"]) / (exact["spin"] * 0.5 * exact["diameter"])),
                                          np.max(np.abs(exact["omega_f"] / exact["spin"] - 1))))})
    if exact["reduction_gap"].notna().any():  # two spheres: what holding the line of centres fixed costs
        rows.append({"test": number, "check": "the reduction against the planar two-body model (rigid contact), "
                                               "over the approach speed",
                     "max_rel": float(np.max(exact["reduction_gap"] / exact["speed"]))})
    if exact["reduction_gap_spring"].notna().any():
        rows.append({"test": number, "check": "the reduction against the planar two-body model (a spring), "
                                               "over the approach speed",
                     "max_rel": float(np.max(exact["reduction_gap_spring"] / exact["speed"]))})
    if number in (5, 6):  # sliding throughout, far beyond the rigid contact's limit (1 + 1/alpha) mu (1 + e) v_n
        v_n = exact["speed"] * np.cos(np.radians(exact["incidence"]))
        v_t = exact["speed"] * np.sin(np.radians(exact["incidence"]))
        slip = v_t - exact["spin"] * 0.5 * exact["diameter"]
        limit = (1 + 1 / Scene().inertia_factor) * exact["mu"] * (1 + exact["cor"]) * v_n
        sliding = np.abs(slip) > 3.5 * limit
        if sliding.any():
            line = v_t - np.sign(slip) * exact["mu"] * (1 + exact["cor"]) * v_n
            rows.append({"test": number, "check": "vc_t against the gross-slip line (sliding rows)",
                         "max_rel": float(np.max(np.abs(exact["vc_t"] - line)[sliding]) / np.abs(line[sliding]).max())})
    return pd.DataFrame(rows)


def readme_block(folder) -> str:
    """The README's block: per test, its reference's worst check, Dundurs' beta of its pairs (the coupling the exact
    elastic solution neglects) and the DEM rules' largest deviation."""
    folder = Path(folder)
    checks, deviation = pd.read_csv(folder / "checks.csv"), pd.read_csv(folder / "deviations.csv")
    _, tests = load_tests()
    rows = []
    for number, part in checks.groupby("test", sort=True):
        worst = part.loc[part["max_rel"].idxmax()]
        mine = deviation[deviation["test"] == number]
        rules = "; ".join(f"`{rule}` {group['max_rel'].max():.2g} ({group.loc[group['max_rel'].idxmax(), 'quantity']})"
                          for rule, group in mine.groupby("rule", sort=False)) or "—"
        cases = read_table(folder / f"test{number}.csv").drop_duplicates("case")
        beta = ", ".join(f"{b:.2f}" for b in cases["dundurs_beta"])
        rows.append((str(number), tests[number]["title"], f"{worst['max_rel']:.1e} ({worst['check']})", beta, rules))
    table = text_table(("test", "what", "reference against its check (largest relative difference)",
                        "Dundurs' β (neglected)", "DEM rules' largest relative deviation from the exact contact"), rows)
    text = ("Chung & Ooi's benchmark tests, exact (`results/chung_ooi/`, rule `chung_ooi`; inputs and sources in "
            "`src/sphereimpact/study/chung_ooi.yaml`):\n\n" + table + "\n")
    published = folder / "published.csv"
    if published.exists():
        curves = pd.read_csv(published)
        if len(curves):
            worst = curves.loc[curves.groupby(["test", "quantity", "reference"], sort=False)["max_rel"].idxmax()]
            text += ("\nThe paper's own curves (digitised by the Kratos developers, `data/chung_ooi_paper/`) against the "
                     "exact references (and, where the COR is below 1, the damped Mindlin spring's), each curve's "
                     "largest relative deviation and where: " + "; ".join(
                         f"test {r.test} {r.quantity} {r.max_rel:.2g}"
                         f"{'' if r.reference == 'exact' else ' from ' + r.reference} ({r.case}, at {r.x_quantity} "
                         f"{r.at:.3g})" for r in worst.sort_values(["test", "quantity"], kind="stable").itertuples())
                     + ".\n")
    return text
