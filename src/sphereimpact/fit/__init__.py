"""From measured bounces to a ball: weighted least squares of its parameters, with their uncertainties.

``fit(read_measured(path), ball, free=["mu", "kappa"])`` returns a :class:`FitResult` whose ``ball`` every door
reuses (``save_ball``, ``--ball``, a study's ``ball_file``).
"""

from .least_squares import FIT_FILES, FREE, FitResult, Parameter, fit, with_values
from .measured import MEASURABLE, Measured, read_measured

__all__ = ["FIT_FILES", "FREE", "MEASURABLE", "FitResult", "Measured", "Parameter", "fit", "read_measured", "with_values"]
