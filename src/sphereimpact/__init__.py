"""sphereimpact: oblique impact of a rigid-body sphere on a rigid flat, after Chapter 4 of the study.

Quick use::

    from sphereimpact import Scene, simulate
    out = simulate(Scene(angle=60))        # the chapter's oblique case, modified model
    out.cor, out.omega_f, out.history()    # outputs and time histories (SI units)
"""

from .errors import BeyondRadiusWarning, EnergyGainWarning, ImpactError
from .contact.laws import LAWS, ContactLaw, Kernel
from .contact.materials import effective_moduli
from .contact.parameters import Parameter, Setting
from .contact.separation import Separation
from .impact.ball import Ball, Measurement, ball_scene, calibrated_ball, load_ball, save_ball
from .impact.outcome import HISTORY_COLUMNS, OUTPUT_KEYS, Outcome
from .impact.scene import Scene, SolverOptions
from .impact.solve import simulate

__all__ = ["Ball", "BeyondRadiusWarning", "ContactLaw", "EnergyGainWarning", "HISTORY_COLUMNS", "ImpactError", "Kernel",
           "LAWS", "Measurement", "OUTPUT_KEYS", "Outcome", "Parameter", "Scene", "Separation", "Setting",
           "SolverOptions", "ball_scene", "calibrated_ball", "effective_moduli", "load_ball", "save_ball",
           "simulate"]
__version__ = "0.1.0"
