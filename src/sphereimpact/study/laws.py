"""The contact laws compared on the chapter's ball: each calibrated to one COR and contact time, then swept in speed.

Every damped law is fitted (stiffness and damping, :func:`sphereimpact.impact.calibrate.calibrate`) to the same
normal COR and the same contact time at one speed, the contact time being the chapter's own (eq. 4.2
with the chapter's k, b and c) there; elastic Hertz is fitted to the contact time alone.  The laws then
differ only in how they extrapolate: COR, contact time and peak force against impact speed, the force
against deflection, whether a law pulls and whether it starts with a force jump.  The published
COR-to-damping relations of the Hunt-Crossley laws are measured against the exact calibration.
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd

from ..contact.laws import Spring
from ..contact.separation import Separation
from ..impact.calibrate import calibrate, contact_time
from ..parsing import parse_range
from ..impact.scene import Scene
from ..errors import BeyondRadiusWarning
from ..impact.solve import simulate
from .config import shared_fields

#: Tension below this fraction of the peak force is round-off, not a pull (as in the replication report).
PULL_THRESHOLD = 1e-9


def base_scene(config: dict) -> Scene:
    """The configured ball, at the laws section's calibration speed, in a normal impact (eq. 4.2)."""
    ball = {k: v for k, v in shared_fields(config, "modified").items() if k not in ("speed", "gravity")}
    return Scene(**ball, speed=config["laws"]["speed"], angle=0.0, model="modified")


def fitted_laws(config: dict) -> dict:
    """Law name -> :class:`~sphereimpact.impact.calibrate.Calibration` at the configured COR and the chapter's
    contact time (the base scene's t_f)."""
    base = base_scene(config)
    target_time = contact_time(base)
    section = config["laws"]
    fitted = {}
    for name in section["models"]:
        scene = _scene_of_law(base, name)
        cor = section["cor"] if scene.law.damping is not None else 1.0
        fitted[name] = calibrate(scene, cor, contact_time=target_time)
    return fitted


def _scene_of_law(base: Scene, name: str) -> Scene:
    """``base`` under law ``name``, with a starting stiffness of the right units for the fit."""
    scene = base.with_(model=name, k=base.k)
    if scene.law.spring is Spring.HERTZ:  # start from the Hertz k with the same peak force as the linear spring
        scene = scene.with_(k=base.k * (base.v_normal / base.omega_n) ** -0.5)
    return scene


def fitted_table(fitted: dict) -> pd.DataFrame:
    """One row per law: the calibration speed, the fitted stiffness and damping with units, and the COR and
    t_f they give."""
    rows = []
    for name, calibration in fitted.items():
        scene = calibration.scene
        damping = scene.law.damping
        rows.append({"law": name, "speed": scene.speed, "k": scene.k, "k_unit": scene.law.parameter("k").unit,
                     "damping": damping or "", "damping_value": getattr(scene, damping) if damping else np.nan,
                     "damping_unit": scene.law.parameter(damping).unit if damping else "",
                     "cor": calibration.cor, "t_f": calibration.contact_time, "doc": scene.law.doc})
    return pd.DataFrame(rows)


def speed_table(fitted: dict, speeds) -> pd.DataFrame:
    """COR, contact time, maximum compression and peak force against impact speed (force criterion); the
    force at first touch; and whether the law pulls (P < 0 before delta returns to 0, from the same impact
    under the penetration criterion, where the contact is not cut at P = 0).  ``beyond_radius`` flags
    delta_m > R (outside the model, kept and flagged)."""
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BeyondRadiusWarning)  # the table's beyond_radius column flags it
        for name, calibration in fitted.items():
            for speed in speeds:
                scene = calibration.scene.with_(speed=float(speed))
                out = simulate(scene)
                whole = simulate(scene.with_(separation=Separation.PENETRATION))
                rows.append({"law": name, "speed": float(speed), "cor": out.cor, "t_f": out.t_f,
                             "delta_m": out.delta_m, "force_max": out.force_max,
                             "force_at_touch": float(scene.stage_force(0.0, scene.v_normal)),
                             "force_min_penetration": whole.force_min,
                             "pulls": bool(whole.force_min < -PULL_THRESHOLD * whole.force_max),
                             "beyond_radius": out.beyond_radius})
    return pd.DataFrame(rows)


def force_curves(fitted: dict, samples: int) -> pd.DataFrame:
    """P against delta along each law's impact at the calibration speed, penetration criterion (so a law that
    pulls shows it before delta returns to 0)."""
    frames = []
    for name, calibration in fitted.items():
        out = simulate(calibration.scene.with_(separation=Separation.PENETRATION))
        history = out.history(samples)
        frames.append(pd.DataFrame({"law": name, "t": history["t"], "delta": history["delta"],
                                    "force": history["force"]}))
    return pd.concat(frames, ignore_index=True)


def relations_table(config: dict) -> pd.DataFrame:
    """What COR each published relation really gives, against the COR asked and the exact calibration.

    For the Hunt-Crossley laws the COR depends on chi v_n alone (and n), so the table holds at every speed.
    """
    base = base_scene(config)
    rows = []
    for name in config["laws"]["relation_models"]:
        scene = _scene_of_law(base, name)
        for cor in config["laws"]["relation_cors"]:
            exact = calibrate(scene, cor)
            rows.append({"law": name, "relation": exact.relation, "cor_asked": cor, "chi": exact.value,
                         "cor_obtained": exact.cor, "error": exact.cor - cor})
            for relation in scene.law.cor_relations:
                got = calibrate(scene, cor, relation=relation)
                rows.append({"law": name, "relation": relation, "cor_asked": cor, "chi": got.value,
                             "cor_obtained": got.cor, "error": got.cor - cor})
    return pd.DataFrame(rows)


def write_laws(config: dict, fitted_csv: str, speed_csv: str, force_csv: str) -> None:
    """Fit every configured law and write the fitted parameters, the speed table and the force curves."""
    fitted = fitted_laws(config)
    fitted_table(fitted).to_csv(fitted_csv, index=False, float_format="%.10g")
    speed_table(fitted, parse_range(config["laws"]["speeds"])).to_csv(speed_csv, index=False, float_format="%.10g")
    force_curves(fitted, config["samples"]).to_csv(force_csv, index=False, float_format="%.10g")


def write_relations(config: dict, csv: str) -> None:
    """Write :func:`relations_table`."""
    relations_table(config).to_csv(csv, index=False, float_format="%.10g")
