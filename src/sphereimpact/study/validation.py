"""The model against real impacts: Kharaz, Gorham & Salman (2001), and where compliance matters for the chapter.

Kharaz et al. measured 5 mm alumina spheres on a glass anvil at 3.9 m/s, incidence 0-60 deg from the
normal (``data/kharaz2001.csv``, source note beside it).  The experiment's scene is built from the
paper's own numbers: E and nu of sphere and anvil give E* and G*, the density and diameter the mass,
mu = 0.092; the normal damping (Hunt-Crossley on the Hertz spring) is calibrated to the measured
e_n = 0.98 at normal incidence (:func:`sphereimpact.calibrate.calibrate`).  Nothing is fitted to the
oblique data: the tangential stiffness follows from G* / E*.

For the chapter's own ball, a map of impact angle x kappa says where the rigid tangential contact is
within a tolerance of the compliant one, on spin and on rebound velocity.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..calibrate import calibrate
from ..parsing import parse_range
from ..scene import Scene
from ..tangential import TANGENTIALS, kappa_from_poisson
from ..solve import simulate
from ..sweep.engine import sweep
from .config import shared_fields

#: The digitised quantities and how a simulated outcome gives each (scene, outcome) -> value.
QUANTITIES = {
    "e_t": lambda scene, out: out.vc_t / scene.v_tangent,
    "omega_rad_s": lambda scene, out: abs(out.omega_f),
    "rebound_angle_deg": lambda scene, out: out.rebound_angle,
}
CSV = dict(index=False, float_format="%.10g")


@dataclass(frozen=True)
class Experiment:
    """The experiment's scene (rigid tangential contact) and its contact constants.

    Attributes
    ----------
    scene : Scene
        Normal damping calibrated to ``cor``; tangential ``rigid``.
    e_star, g_star : float
        Effective Young's and shear moduli of the pair [Pa].
    kappa : float
        k_t / k_n = 4 G* / E* [-].
    """

    scene: Scene
    e_star: float
    g_star: float
    kappa: float

    def model(self, tangential: str) -> Scene:
        """The scene with tangential model ``tangential``, its stiffness (if it has one) from the materials' G*."""
        if "shear_modulus" in TANGENTIALS.model(tangential).parameter_names:
            return self.scene.with_(tangential=tangential, shear_modulus=self.g_star)
        return self.scene.with_(tangential=tangential)


def effective_moduli(e1: float, nu1: float, e2: float, nu2: float) -> tuple[float, float]:
    """E* and G* [Pa] of two elastic bodies in contact (Johnson, Contact Mechanics, 1985, ch. 4 and 7):
    1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 and 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2, G = E / (2 (1 + nu))."""
    g1, g2 = e1 / (2.0 * (1.0 + nu1)), e2 / (2.0 * (1.0 + nu2))
    return 1.0 / ((1.0 - nu1 ** 2) / e1 + (1.0 - nu2 ** 2) / e2), 1.0 / ((2.0 - nu1) / g1 + (2.0 - nu2) / g2)


def experiment(section: dict) -> Experiment:
    """The Kharaz experiment from the config's ``validation`` section (materials, speed, mu, e_n)."""
    sphere, anvil = section["sphere"], section["anvil"]
    e_star, g_star = effective_moduli(sphere["modulus"], sphere["poisson"], anvil["modulus"], anvil["poisson"])
    diameter = sphere["diameter"]
    mass = sphere["density"] * math.pi * diameter ** 3 / 6.0
    base = Scene(mass=mass, diameter=diameter, inertia_factor=0.4, speed=section["speed"], mu=section["mu"],
                 model=section["model"], modulus=e_star)
    scene = calibrate(base, section["cor"]).scene
    return Experiment(scene, e_star, g_star, 4.0 * g_star / e_star)


def load_data(path: str) -> pd.DataFrame:
    """The digitised data: quantity, incidence_deg, value (comment lines skipped)."""
    data = pd.read_csv(path, comment="#")
    unknown = sorted(set(data["quantity"]) - set(QUANTITIES))
    if unknown:
        raise ValueError(f"{path}: unknown quantity {unknown[0]!r}; expected {', '.join(QUANTITIES)}")
    return data


def _outcome(scene: Scene, angle: float):
    return simulate(scene.with_(angle=max(float(angle), 1e-3)))  # a normal impact has no e_t: 0.001 deg


def curves(exp: Experiment, angles, models) -> pd.DataFrame:
    """Model curves against incidence: e_t, spin, rebound angles, switches, and Maw's psi_1 and psi_2.

    psi_1 = kappa tan(theta) / mu and psi_2 = kappa tan(theta_c) / mu, theta_c the contact point's rebound
    angle (Maw, Barber & Fawcett 1976; kappa = 2 (1 - nu) / (2 - nu) for like materials, 4 G*/E* here).
    """
    rows = []
    for model in models:
        scene = exp.model(model)
        for angle in angles:
            out = _outcome(scene, angle)
            oblique = scene.with_(angle=max(float(angle), 1e-3))
            rows.append({"model": model, "incidence_deg": float(angle),
                         **{q: f(oblique, out) for q, f in QUANTITIES.items()},
                         "rebound_angle_contact_deg": out.rebound_angle_contact, "cor": out.cor,
                         "switches": out.switches, "regime": out.regime,
                         "psi1": exp.kappa * math.tan(math.radians(angle)) / scene.mu,
                         "psi2": exp.kappa * out.ve_t / out.vc_n / scene.mu})
    return pd.DataFrame(rows)


def residuals(exp: Experiment, data: pd.DataFrame, models) -> pd.DataFrame:
    """Each data point against each model at its own incidence: predicted, residual, relative residual."""
    rows = []
    for model in models:
        scene = exp.model(model)
        for row in data.itertuples(index=False):
            out = _outcome(scene, row.incidence_deg)
            value = QUANTITIES[row.quantity](scene.with_(angle=max(row.incidence_deg, 1e-3)), out)
            rows.append({"model": model, "quantity": row.quantity, "incidence_deg": row.incidence_deg,
                         "measured": row.value, "predicted": value, "residual": value - row.value,
                         "relative": (value - row.value) / row.value})
    return pd.DataFrame(rows)


def summary(table: pd.DataFrame, targets: dict) -> pd.DataFrame:
    """Per model: the issue's measures over incidence >= ``targets['min_incidence']`` and the points below it.

    e_t RMS, spin's worst relative residual above ``spin_above`` rad/s, rebound-angle RMS, each with its
    target and whether it is met; the worst e_t residual below the minimum incidence.
    """
    rows = []
    low = targets["min_incidence"]
    for model, group in table.groupby("model", sort=False):
        above = group[group["incidence_deg"] >= low]
        e_t = above[above["quantity"] == "e_t"]["residual"]
        spin = above[(above["quantity"] == "omega_rad_s") & (above["measured"] > targets["spin_above"])]["relative"]
        angle = above[above["quantity"] == "rebound_angle_deg"]["residual"]
        below = group[(group["incidence_deg"] < low) & (group["quantity"] == "e_t")]["residual"]
        e_t_rms = float(np.sqrt(np.mean(e_t ** 2)))
        spin_worst = float(spin.abs().max())
        rows.append({"model": model, "e_t_rms": e_t_rms, "e_t_target": targets["e_t_rms"],
                     "e_t_met": bool(e_t_rms <= targets["e_t_rms"]),
                     "spin_worst_relative": spin_worst, "spin_target": targets["spin_relative"],
                     "spin_met": bool(spin_worst <= targets["spin_relative"]),
                     "spin_points": int(spin.size), "rebound_angle_rms_deg": float(np.sqrt(np.mean(angle ** 2))),
                     "e_t_worst_below": float(below.abs().max()) if below.size else float("nan"),
                     "e_t_points": int(e_t.size), "min_incidence": low})
    return pd.DataFrame(rows)


def derived_maw_points(data: pd.DataFrame, exp: Experiment) -> pd.DataFrame:
    """Maw's psi_2 of the measurements, where both e_t and spin were digitised near one incidence.

    The contact point's rebound velocity is v_t e_t - omega R; e_t is interpolated (linear in incidence) to
    the spin points' incidences and the rebound normal velocity is e_n v_n with the calibrated law's e_n.
    Derived, so drawn apart from the measured points.
    """
    scene = exp.scene
    e_t = data[data["quantity"] == "e_t"].sort_values("incidence_deg")
    spin = data[data["quantity"] == "omega_rad_s"].sort_values("incidence_deg")
    spin = spin[(spin["incidence_deg"] >= e_t["incidence_deg"].min()) & (spin["incidence_deg"] <= e_t["incidence_deg"].max())]
    rows = []
    for row in spin.itertuples(index=False):
        theta = math.radians(row.incidence_deg)
        ratio = float(np.interp(row.incidence_deg, e_t["incidence_deg"], e_t["value"]))
        oblique = scene.with_(angle=row.incidence_deg)
        out = simulate(oblique)
        v_t, v_n = scene.speed * math.sin(theta), scene.speed * math.cos(theta)
        contact = ratio * v_t - row.value * scene.radius
        rows.append({"incidence_deg": row.incidence_deg, "e_t": ratio, "omega_rad_s": row.value,
                     "psi1": exp.kappa * math.tan(theta) / scene.mu,
                     "psi2": exp.kappa * contact / (out.cor * v_n) / scene.mu})
    return pd.DataFrame(rows)


def write_validation(config: dict, data_path: str, residual_csv: str, summary_csv: str, curves_csv: str,
                     maw_csv: str) -> None:
    """The validation study's tables (see :func:`residuals`, :func:`summary`, :func:`curves`)."""
    section = config["validation"]
    exp = experiment(section)
    data = load_data(data_path)
    models = section["tangential"]
    table = residuals(exp, data, models)
    table.to_csv(residual_csv, **CSV)
    summary(table, section["targets"]).assign(
        kappa=exp.kappa, e_star=exp.e_star, g_star=exp.g_star, chi=exp.scene.chi, mass=exp.scene.mass).to_csv(
        summary_csv, **CSV)
    curves(exp, parse_range(section["angles"]), models).to_csv(curves_csv, **CSV)
    derived_maw_points(data, exp).to_csv(maw_csv, **CSV)


# --- the chapter's ball --------------------------------------------------------------------------------
def compliance_map(config: dict) -> pd.DataFrame:
    """Angle x kappa for the chapter's ball (eq. 4.2, tangential ``linear``) against the rigid contact.

    Columns: angle, kappa, the compliant and rigid spin and tangential velocity, the relative differences of
    spin, of v_t and of the rebound velocity vector (|dv_t| / |v|), the larger of spin's and the rebound
    velocity's (``difference``) and whether the rigid model is within the configured tolerance.  Solved by the sweep engine (compliant scenes one by one).
    """
    section = config["compliance"]
    ball = {k: v for k, v in shared_fields(config, "modified").items() if k not in ("gravity",)}
    angles = parse_range(section["angles"])
    kappas = np.geomspace(section["kappa_min"], section["kappa_max"], section["kappa_count"])
    kappas = np.unique(np.append(kappas, kappa_from_poisson(section["poisson"])))
    scenes = pd.DataFrame([{**ball, "model": "modified", "angle": a, "tangential": "linear", "kappa": k}
                           for a in angles for k in kappas])
    compliant = sweep(scenes)
    rigid = sweep(scenes.assign(tangential="rigid", kappa=np.nan))
    out = compliant[["angle", "kappa", "omega_f", "vc_t", "vc_n", "ve_t", "regime"]].copy()
    out["omega_rigid"], out["vc_t_rigid"], out["regime_rigid"] = rigid["omega_f"], rigid["vc_t"], rigid["regime"]
    out["spin_difference"] = (compliant["omega_f"] - rigid["omega_f"]) / rigid["omega_f"].abs()
    out["vc_t_difference"] = (compliant["vc_t"] - rigid["vc_t"]) / rigid["vc_t"].abs()
    # the rebound velocity as a vector: its normal part does not depend on the tangential model
    out["rebound_velocity_difference"] = ((compliant["vc_t"] - rigid["vc_t"]).abs()
                                          / np.hypot(rigid["vc_t"], rigid["vc_n"]))
    out["difference"] = out[["spin_difference", "rebound_velocity_difference"]].abs().max(axis=1)
    out["rigid_within"] = out["difference"] <= section["tolerance"]
    return out


def write_compliance_map(config: dict, csv_path: str) -> None:
    compliance_map(config).to_csv(csv_path, **CSV)
