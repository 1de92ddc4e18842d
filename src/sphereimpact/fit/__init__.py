"""From measured bounces to a ball: weighted least squares of its parameters, with their uncertainties.

``fit(read_measured(path), ball, free=["mu", "kappa"])`` returns a :class:`FitResult` whose ``ball`` every door
reuses (``save_ball``, ``--ball``, a study's ``ball_file``).  The names (:mod:`.names`) load at once; the fitting
(pandas, scipy.optimize) on first use, so that a command which only names them starts fast.
"""

from .names import FIT_FILES, FREE, MEASURABLE, PLAN_FILES

#: Attribute -> the module that defines it, imported when first asked for.
_LAZY = {"FitResult": "least_squares", "FittedParameter": "least_squares", "fit": "least_squares",
         "with_values": "least_squares", "Measured": "measured", "read_measured": "measured"}

__all__ = ["FIT_FILES", "FREE", "MEASURABLE", "PLAN_FILES", "FitResult", "Measured", "FittedParameter", "fit", "read_measured",
           "with_values"]


def __getattr__(name: str):
    if name in _LAZY:
        from importlib import import_module

        value = getattr(import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
