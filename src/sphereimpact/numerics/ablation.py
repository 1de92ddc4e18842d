"""Model no more than a scene needs: the change in every output when the model adds or drops one thing."""

from __future__ import annotations

import pandas as pd

from ..contact.separation import Separation
from ..impact.scene import STANDARD_GRAVITY, Scene, SolverOptions
from ..impact.solve import simulate
from .reference import output_scales

#: Outputs followed by the ablation.
KEYS = ("t_m", "delta_m", "t_f", "vc_t", "ve_t", "ve_n", "cor", "omega_f")

#: Variant -> (what changes, Scene changes, body).
VARIANTS = {
    "gravity on": ("adds g = 9.80665 m/s²", {"gravity": STANDARD_GRAVITY}, "reduced"),
    "thin shell": ("rotational inertia α = 2/3 instead of 2/5", {"inertia_factor": 2 / 3}, "reduced"),
    "light core": ("rotational inertia α = 0.2", {"inertia_factor": 0.2}, "reduced"),
    "no friction": ("drops friction (μ = 0)", {"mu": 0.0}, "reduced"),
    "penetration": ("contact ends at δ = 0 instead of P = 0", {"separation": Separation.PENETRATION}, "reduced"),
    "ramp 10": ("eq. 4.2 ramp constant 10 instead of 100", {"ramp": 10.0}, "reduced"),
    "ramp 1000": ("eq. 4.2 ramp constant 1000 instead of 100", {"ramp": 1000.0}, "reduced"),
    "previous law": ("eq. 4.1 instead of eq. 4.2", {"model": "kelvin-voigt"}, "reduced"),
    "full planar model": ("integrates centre, spin and slip instead of the normal ODE only", {}, "planar"),
    "compliant contact": ("adds a tangential spring k_t = κ k, κ = 2/3 (rubber, ν = 0.5)",
                          {"tangential": "linear", "poisson": 0.5}, "reduced"),
}

TIGHT = SolverOptions(rtol=1e-12, atol=1e-12)


def ablation(cases: dict[str, Scene], published: list[dict]) -> pd.DataFrame:
    """One row per case x variant x output: baseline, variant value, change, and whether it moves a printed digit.

    ``change`` is relative to the output's scale (see :func:`output_scales`);
    ``visible`` is True when the change exceeds half a unit of the chapter's
    printed value for that output (empty where the chapter prints none).
    """
    rows = []
    for case, scene in cases.items():
        base = simulate(scene, TIGHT).to_dict()
        scales = output_scales(scene, base["t_f"], base["delta_m"])
        printed = {e["quantity"]: e["resolution"] for e in published if e["case"] == case}
        for name, (what, changes, body) in VARIANTS.items():
            got = simulate(scene.with_(**changes), TIGHT, body=body).to_dict()
            for key in KEYS:
                delta = got[key] - base[key]
                visible = "" if key not in printed else str(abs(delta) > 0.5 * printed[key])
                rows.append({"case": case, "variant": name, "what": what, "output": key, "baseline": base[key],
                             "value": got[key], "change": delta / max(abs(base[key]), scales[key]),
                             "visible": visible})
    return pd.DataFrame(rows)
