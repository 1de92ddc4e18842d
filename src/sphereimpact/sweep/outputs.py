"""What the fast sweep paths give: the dimensionless normal outputs (one definition, read by all of them), and
what a sweep's rows need of a path beyond them."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Times tau = t / T, the largest compression x_m = delta_m / (v_n T), the rebound rate y_f = -v_f / v_n, and
#: j_p = J+ / (m v_n), the friction-carrying impulse: J+ is the integral of max(P, 0) over the contact, gravity's
#: share included; T = 1 / w, the law's time scale.
NORMAL_OUTPUTS = ("tau_m", "x_m", "tau_f", "y_f", "j_p")
#: The extremes of the normal force over the contact, P / (m v_n / T): what force_max and force_min scale.
EXTREMES = ("p_max", "p_min")


@dataclass(frozen=True)
class Needs:
    """What the rows of a sweep need of a fast path beyond :data:`NORMAL_OUTPUTS`.

    Attributes
    ----------
    extremes : bool
        The force's extremes :data:`EXTREMES` (for force_min and force_max).
    levels : ndarray
        Per row, a level of j = J+ / (m v_n) whose first instant ``tau_g`` = t / T the row's tangential model
        needs (the rigid contact: where it grips; for t_roll), NaN where none.  Where j never reaches it (the
        level exceeds j_p: the rigid contact slides throughout), a path may give NaN or the instant j is
        largest (P first falls to 0); a tangential model reads the instant only where j_p reaches the level.
    completes : ndarray of bool
        Per row, whether its tangential end follows from the normal motion (no tangential motion, or a model
        with a ``swept`` end state): only such rows can a path that gives the normal motion take.
    """

    extremes: bool
    levels: np.ndarray
    completes: np.ndarray

    def grips(self, rows) -> np.ndarray:
        """Whether each of ``rows`` (indices or a mask) needs a level's instant."""
        return np.isfinite(self.levels[rows])

    def levels_of(self, rows):
        """The levels of ``rows``, or None where none of them needs one (a path then computes no instants)."""
        levels = self.levels[rows]
        return levels if np.isfinite(levels).any() else None
