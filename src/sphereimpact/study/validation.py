"""The model against real impacts: Kharaz, Gorham & Salman (2001), and where compliance matters for the chapter.

Kharaz et al. measured 5 mm alumina spheres on a glass anvil at 3.9 m/s, incidence 0-60 deg from the
normal (``data/kharaz2001.csv``, source note beside it).  The experiment's scene is built from the
paper's own numbers: E and nu of sphere and anvil give E* and G*, the density and diameter the mass,
mu = 0.092; the normal damping (Hunt-Crossley on the Hertz spring) is calibrated to the measured
e_n = 0.98 at normal incidence (:func:`sphereimpact.impact.calibrate.calibrate`).  Nothing is fitted to the
oblique data: the tangential stiffness follows from G* / E*.  Every configured tangential model is run
(the rigid contact, the Mindlin springs, the exact microslip contact) over the incidences
(:func:`sphereimpact.impact.solve.simulate_many`).

For the chapter's own ball, a map of impact angle x kappa says where the rigid tangential contact is
within a tolerance of the compliant one, on spin and on rebound velocity.
"""

from __future__ import annotations

import logging

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..contact.materials import dundurs_beta, effective_moduli
from ..impact.calibrate import calibrate
from ..parsing import parse_range
from ..impact.scene import Scene
from ..impact.solve import simulate_many
from ..sweep.engine import sweep
from ..contact.tangential import TANGENTIALS, kappa_from_poisson
from .config import hertz_twin, scene_for_primary

log = logging.getLogger(__name__)

#: The digitised quantities and how a simulated outcome gives each (scene, outcome) -> value.
QUANTITIES = {
    "e_t": lambda scene, out: out.e_t,
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
    beta : float
        Dundurs' second constant of the pair [-]: the coupling of normal and tangential tractions that
        every model here neglects (zero for like materials).
    """

    scene: Scene
    e_star: float
    g_star: float
    kappa: float
    beta: float

    def with_tangential(self, tangential: str) -> Scene:
        """The scene with tangential model ``tangential``, its stiffness (if it has one) from the materials' G*."""
        if "shear_modulus" in TANGENTIALS.model(tangential).parameter_names:
            return self.scene.with_(tangential=tangential, shear_modulus=self.g_star)
        return self.scene.with_(tangential=tangential)


def experiment(section: dict) -> Experiment:
    """The Kharaz experiment from the config's ``validation`` section (materials, speed, mu, e_n)."""
    sphere, anvil = section["sphere"], section["anvil"]
    e_star, g_star = effective_moduli(sphere["modulus"], sphere["poisson"], anvil["modulus"], anvil["poisson"])
    diameter = sphere["diameter"]
    mass = sphere["density"] * math.pi * diameter ** 3 / 6.0
    base = Scene(mass=mass, diameter=diameter, inertia_factor=0.4, speed=section["speed"], mu=section["mu"],
                 model=section["model"], modulus=e_star)
    scene = calibrate(base, section["cor"]).scene
    beta = dundurs_beta(sphere["modulus"], sphere["poisson"], anvil["modulus"], anvil["poisson"])
    return Experiment(scene, e_star, g_star, 4.0 * g_star / e_star, beta)


def load_data(path: str) -> pd.DataFrame:
    """The digitised data: quantity, incidence_deg, value (comment lines skipped)."""
    data = pd.read_csv(path, comment="#")
    unknown = sorted(set(data["quantity"]) - set(QUANTITIES))
    if unknown:
        raise ValueError(f"{path}: unknown quantity {unknown[0]!r}; expected {', '.join(QUANTITIES)}")
    return data


def _oblique(scene: Scene, angle: float) -> Scene:
    return scene.with_(angle=max(float(angle), 1e-3))  # a normal impact has no e_t: 0.001 deg


def _outcomes(scene: Scene, angles) -> list:
    """The outcomes at each incidence [deg], the scenes batched where the tangential model allows."""
    return simulate_many([_oblique(scene, angle) for angle in angles])


def curves(exp: Experiment, angles, tangentials) -> pd.DataFrame:
    """Model curves against incidence: e_t, spin, rebound angles, switches, and Maw's psi_1 and psi_2.

    psi_1 = kappa tan(theta) / mu and psi_2 = kappa tan(theta_c) / mu, theta_c the contact point's rebound
    angle (Maw, Barber & Fawcett 1976; kappa = 2 (1 - nu) / (2 - nu) for like materials, 4 G*/E* here).
    """
    rows = []
    for tangential in tangentials:
        log.info("validation: tangential model %s", tangential)
        scene = exp.with_tangential(tangential)
        for angle, out in zip(angles, _outcomes(scene, angles)):
            rows.append({"tangential": tangential, "incidence_deg": float(angle),
                         **{q: f(out.scene, out) for q, f in QUANTITIES.items()},
                         "rebound_angle_contact_deg": out.rebound_angle_contact, "cor": out.cor,
                         "switches": out.switches, "regime": out.regime,
                         "psi1": exp.kappa * math.tan(math.radians(angle)) / scene.mu,
                         "psi2": exp.kappa * out.ve_t / out.vc_n / scene.mu})
    return pd.DataFrame(rows)


def residuals(exp: Experiment, data: pd.DataFrame, tangentials, angle_uncertainty: float = 0.0) -> pd.DataFrame:
    """Each data point against each tangential model at its own incidence: predicted, residual, relative residual, and
    ``angle_effect``, how far the prediction moves when the incidence moves by the digitised angle's
    uncertainty [deg] either way (the larger of the two)."""
    rows = []
    theta = data["incidence_deg"].to_numpy(dtype=float)
    for tangential in tangentials:
        log.info("validation: tangential model %s", tangential)
        scene = exp.with_tangential(tangential)
        outs = _outcomes(scene, np.concatenate([theta, theta - angle_uncertainty, theta + angle_uncertainty]))
        for i, row in enumerate(data.itertuples(index=False)):
            value, low, high = (QUANTITIES[row.quantity](out.scene, out) for out in outs[i::len(theta)])
            rows.append({"tangential": tangential, "quantity": row.quantity, "incidence_deg": row.incidence_deg,
                         "measured": row.value, "predicted": value, "residual": value - row.value,
                         "relative": (value - row.value) / row.value,
                         "angle_effect": max(abs(low - value), abs(high - value))})
    return pd.DataFrame(rows)


def summary(table: pd.DataFrame, targets: dict) -> pd.DataFrame:
    """Per tangential model: each of the targets, its measured value and whether it is met.

    e_t RMS over incidence >= ``min_incidence`` and over every angle, the worst e_t residual of any point,
    spin's worst relative residual where more than ``spin_above`` rad/s was measured, the centre's
    rebound-angle RMS; and the worst e_t residual below the minimum incidence.
    """
    rows = []
    low = targets["min_incidence"]
    for tangential, group in table.groupby("tangential", sort=False):
        above = group[group["incidence_deg"] >= low]
        e_t_all = group[group["quantity"] == "e_t"]["residual"]
        e_t = above[above["quantity"] == "e_t"]["residual"]
        spin = group[(group["quantity"] == "omega_rad_s") & (group["measured"] > targets["spin_above"])]["relative"]
        angle = group[group["quantity"] == "rebound_angle_deg"]["residual"]
        below = group[(group["incidence_deg"] < low) & (group["quantity"] == "e_t")]["residual"]
        measures = {"e_t_rms": float(np.sqrt(np.mean(e_t ** 2))), "e_t_rms_all": float(np.sqrt(np.mean(e_t_all ** 2))),
                    "e_t_worst": float(e_t_all.abs().max()), "spin_worst_relative": float(spin.abs().max()),
                    "rebound_angle_rms_deg": float(np.sqrt(np.mean(angle ** 2)))}
        checks = {"e_t": ("e_t_rms", "e_t_rms"), "e_t_all": ("e_t_rms_all", "e_t_rms_all"),
                  "e_t_point": ("e_t_worst", "e_t_point"), "spin": ("spin_worst_relative", "spin_relative"),
                  "rebound_angle": ("rebound_angle_rms_deg", "rebound_angle_rms")}
        row = {"tangential": tangential, **measures}
        for name, (measure, target) in checks.items():
            row[f"{name}_target"] = targets[target]
            row[f"{name}_met"] = bool(measures[measure] <= targets[target])
        row.update({"targets_met": sum(row[f"{name}_met"] for name in checks), "targets": len(checks),
                    "spin_points": int(spin.size), "e_t_points": int(e_t.size), "e_t_points_all": int(e_t_all.size),
                    "e_t_worst_below": float(below.abs().max()) if below.size else float("nan"),
                    "min_incidence": low, "spin_above": targets["spin_above"]})
        rows.append(row)
    return pd.DataFrame(rows)


def derived_maw_points(data: pd.DataFrame, exp: Experiment) -> pd.DataFrame:
    """What the measurements imply by themselves, at the spin points inside the e_t points' range.

    e_t is interpolated (linear in incidence) to the spin points' incidences, the rebound normal velocity
    is e_n v_n with the calibrated law's e_n.  From these: Maw's psi_2 of the contact point (v_t e_t - omega R
    its rebound velocity); ``omega_from_e_t`` = (1 - e_t) v_t / (alpha R), the spin that the measured e_t
    implies for any force at the contact point (the tangential impulse turns the ball: omega' =
    dv_t / (alpha R)), and ``spin_excess``, the measured spin over it, less one; ``mu_implied`` = omega alpha
    R / ((1 + e_n) v_n), the friction coefficient the measured spin implies if the contact slides throughout.
    Derived, so drawn apart from the measured points.
    """
    scene = exp.scene
    e_t = data[data["quantity"] == "e_t"].sort_values("incidence_deg")
    spin = data[data["quantity"] == "omega_rad_s"].sort_values("incidence_deg")
    spin = spin[(spin["incidence_deg"] >= e_t["incidence_deg"].min()) & (spin["incidence_deg"] <= e_t["incidence_deg"].max())]
    rows = []
    alpha_r = scene.inertia_factor * scene.radius
    for row, out in zip(spin.itertuples(index=False), simulate_many([scene.with_(angle=a) for a in spin["incidence_deg"]])):
        theta = math.radians(row.incidence_deg)
        ratio = float(np.interp(row.incidence_deg, e_t["incidence_deg"], e_t["value"]))
        v_t, v_n = scene.speed * math.sin(theta), scene.speed * math.cos(theta)
        contact = ratio * v_t - row.value * scene.radius
        from_e_t = (1.0 - ratio) * v_t / alpha_r
        rows.append({"incidence_deg": row.incidence_deg, "e_t": ratio, "omega_rad_s": row.value,
                     "psi1": exp.kappa * math.tan(theta) / scene.mu,
                     "psi2": exp.kappa * contact / (out.cor * v_n) / scene.mu,
                     "omega_from_e_t": from_e_t, "spin_excess": row.value / from_e_t - 1.0,
                     "mu_implied": row.value * alpha_r / ((1.0 + out.cor) * v_n)})
    return pd.DataFrame(rows)


def write_validation(config: dict, data_path: str, residual_csv: str, summary_csv: str, curves_csv: str,
                     maw_csv: str) -> None:
    """The validation study's tables (see :func:`residuals`, :func:`summary`, :func:`curves`)."""
    section = config["validation"]
    exp = experiment(section)
    data = load_data(data_path)
    tangentials = section["tangential"]
    table = residuals(exp, data, tangentials, section["angle_uncertainty"])
    table.to_csv(residual_csv, **CSV)
    summary(table, section["targets"]).assign(
        kappa=exp.kappa, e_star=exp.e_star, g_star=exp.g_star, chi=exp.scene.chi, mass=exp.scene.mass,
        dundurs_beta=exp.beta).to_csv(summary_csv, **CSV)
    curves(exp, parse_range(section["angles"]), tangentials).to_csv(curves_csv, **CSV)
    derived_maw_points(data, exp).to_csv(maw_csv, **CSV)


# --- the chapter's ball --------------------------------------------------------------------------------
def _envelope(values: np.ndarray, kappas: np.ndarray, window: float) -> np.ndarray:
    """Each value's largest neighbour in kappa within a factor ``window`` either side (the values of one
    angle, in increasing kappa)."""
    low, high = np.searchsorted(kappas, kappas / window, "left"), np.searchsorted(kappas, kappas * window, "right")
    return np.array([values[a:b].max() for a, b in zip(low, high)])


def compliance_map(config: dict) -> pd.DataFrame:
    """Angle x kappa for the chapter's ball, each configured compliant tangential model against the rigid
    contact.

    A model with a linear spring (``linear``) runs on the primary law; a model that needs a Hertz spring
    (``microslip``) on the chapter's ball as a Hertz contact (:func:`hertz_twin`).  Columns: tangential,
    model (the law), angle, kappa, the compliant and rigid spin and tangential velocity, the signed relative
    differences of spin and of v_t, that of the rebound velocity vector (|dv_t| / |v|), their larger
    (``difference``), its ``envelope`` (the largest over kappa within ``compliance.kappa_window`` either
    side: an undamped tangential spring rings, so the difference passes through zero between kappas where
    it is large) and whether the rigid model is within the configured tolerance there (on the envelope).
    Solved by the sweep engine.
    """
    section = config["compliance"]
    primary = scene_for_primary(config)
    twin = None
    angles = parse_range(section["angles"])
    kappas = np.geomspace(section["kappa_min"], section["kappa_max"], section["kappa_count"])
    kappas = np.unique(np.append(kappas, kappa_from_poisson(section["poisson"])))
    parts = []
    for tangential in section["tangential"]:
        log.info("compliance map: tangential model %s", tangential)
        if TANGENTIALS.model(tangential).spring in (None, primary.law.spring):
            ball = primary
        else:
            twin = hertz_twin(config) if twin is None else twin
            ball = twin
        fields = {name: getattr(ball, name) for name in ("mass", "diameter", "inertia_factor", "speed", "mu",
                                                         "model", "separation", *ball.law.parameter_names)
                  if name != "modulus"}
        scenes = pd.DataFrame([{**fields, "angle": a, "tangential": tangential, "kappa": k}
                               for a in angles for k in kappas])
        compliant = sweep(scenes)
        rigid = sweep(scenes.assign(tangential="rigid", kappa=np.nan))
        out = compliant[["angle", "kappa", "omega_f", "vc_t", "vc_n", "ve_t", "regime"]].copy()
        out.insert(0, "model", ball.model)
        out.insert(0, "tangential", tangential)
        out["omega_rigid"], out["vc_t_rigid"], out["regime_rigid"] = rigid["omega_f"], rigid["vc_t"], rigid["regime"]
        out["spin_difference"] = (compliant["omega_f"] - rigid["omega_f"]) / rigid["omega_f"].abs()
        out["vc_t_difference"] = (compliant["vc_t"] - rigid["vc_t"]) / rigid["vc_t"].abs()
        # the rebound velocity as a vector: its normal part does not depend on the tangential model
        out["rebound_velocity_difference"] = ((compliant["vc_t"] - rigid["vc_t"]).abs()
                                              / np.hypot(rigid["vc_t"], rigid["vc_n"]))
        out["difference"] = out[["spin_difference", "rebound_velocity_difference"]].abs().max(axis=1)
        out["envelope"] = np.concatenate([_envelope(group["difference"].to_numpy(), group["kappa"].to_numpy(),
                                                    section["kappa_window"]) for _, group in out.groupby("angle")])
        out["rigid_within"] = out["envelope"] <= section["tolerance"]
        parts.append(out)
    return pd.concat(parts, ignore_index=True)


def write_compliance_map(config: dict, csv_path: str) -> None:
    compliance_map(config).to_csv(csv_path, **CSV)
