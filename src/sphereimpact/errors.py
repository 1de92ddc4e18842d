"""The package's exceptions and warnings, in one place.

``ImpactError`` is what a user meets: the impact has no valid outcome.  The others are raised between
layers and caught by a caller that knows what to do next (``auto`` hands an overflowing series to the next
integrator; the sweep integrates scene by scene where an interpolant fails its check).
"""

from __future__ import annotations


class ImpactError(RuntimeError):
    """The impact has no valid outcome (e.g. the ball never separates) or an event was missed."""


class SphereImpactWarning(UserWarning):
    """What the reader of a result must know; every door says it (the command line prints each as one line,
    ``sphereimpact: warning: ...``; the API warns with the subclass below)."""


class BeyondRadiusWarning(SphereImpactWarning):
    """The maximum compression exceeds the ball's radius: the result lies outside the model."""


class EnergyGainWarning(SphereImpactWarning):
    """The tangential contact model did positive work on the ball: it made energy, outside passive physics."""


class ExtrapolationWarning(SphereImpactWarning):
    """A law calibrated to a measured COR is used at a normal speed far from the measurement's."""


class UnitWarning(SphereImpactWarning):
    """An input no real ball has, most likely a unit slip (grams typed for kilograms, millimetres for metres)."""


class StepBudgetError(RuntimeError):
    """The Taylor method needed more than its step budget (:data:`sphereimpact.ode.series.MAX_STEPS`)."""


class SeriesOverflowError(ArithmeticError):
    """The series' coefficients left double precision (a rate such as lam beyond about 1e12)."""


class InterpolationError(ValueError):
    """A sweep interpolant failed its check with the most nodes allowed (the caller then integrates scene by
    scene)."""
