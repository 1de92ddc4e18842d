"""What a fit can free and measure, and the files it writes: the names the command line builds its options from,
kept apart from the fitting itself so that naming them imports neither pandas nor scipy."""

from __future__ import annotations

import math

from ..impact.outcome import NUMERIC_OUTPUTS, OUTPUT_UNITS
from ..impact.pair import PARTNER_UNITS

#: Parameters a fit may free -> (lower bound, upper bound, fitted in its logarithm).
FREE = {
    "mu": (0.0, math.inf, False), "kappa": (0.0, math.inf, True), "k": (0.0, math.inf, True),
    "modulus": (0.0, math.inf, True), "b": (0.0, math.inf, True), "chi": (0.0, math.inf, True),
    "cor": (1e-6, 1.0 - 1e-9, False), "inertia_factor": (1e-6, 2.0 / 3.0, False), "exponent": (1.0, 3.0, False),
}
#: The files of a fit's folder (``sphereimpact fit --out DIR``, the pipeline's fits).
FIT_FILES = ("ball.json", "fit.json", "residuals.csv", "fit.png")
#: The files of a measurement plan's folder (``sphereimpact plan --out DIR``, a study's ``plan`` section).
PLAN_FILES = ("plan.csv", "plan.json", "candidates.csv", "plan.png")
#: Measured quantities that are not outputs of ``simulate`` but follow from them and the approach: the
#: tangential coefficient of restitution of the centre, v_t' / v_t [-], and the rebound spin's magnitude.
DERIVED = {"e_t": "-", "abs_omega_f": "rad/s"}
#: Every quantity a measured table may give, with its unit.
MEASURABLE = {name: OUTPUT_UNITS[name] for name in NUMERIC_OUTPUTS} | PARTNER_UNITS | DERIVED
