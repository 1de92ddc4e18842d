"""Sweeps: many impacts at once (batched integration, vectorised closed form, similarity interpolation).

``sweep(table)`` solves one scene per row of a DataFrame; ``sweep(dict)`` every combination of the dict's
values, as the command line's ranges.  ``grid`` and ``rows`` build the two kinds of table.
"""

from .engine import FAST_OUTPUTS, SWEEP_OUTPUTS, grid, rows, sweep

__all__ = ["FAST_OUTPUTS", "SWEEP_OUTPUTS", "grid", "rows", "sweep"]
