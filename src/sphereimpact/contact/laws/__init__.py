"""Normal contact force laws: one definition each, in a registry keyed by name.

=====================  ==============================================  =====================
name                   force inside contact (delta > 0)                 module
=====================  ==============================================  =====================
kelvin-voigt           k delta + b delta_dot (eq. 4.1)                  :mod:`.linear`
modified               k delta + b delta_dot (1 - exp(-c delta/R)) (4.2) :mod:`.linear`
linear-hunt-crossley   k delta (1 + chi delta_dot)                      :mod:`.linear`
hertz                  k delta^(3/2)                                    :mod:`.hertz`
hunt-crossley          k delta^n (1 + chi delta_dot)                    :mod:`.hertz`
=====================  ==============================================  =====================

Adding a law is one :class:`ContactLaw` passed to ``LAWS.register`` (see :mod:`.base` for what it
declares); every layer then serves it or says it cannot.
"""

from . import hertz, linear  # noqa: F401  (registers the laws)
from .base import (LAWS, PARAMETER_NAMES, ContactLaw, Kernel, Relation, Spring, force_rate, hertz_constant,
                   hertz_modulus, spring_exponent, spring_stiffness)
from .linear import ramp_continued

__all__ = ["LAWS", "PARAMETER_NAMES", "ContactLaw", "Kernel", "Relation", "Spring", "force_rate", "hertz_constant",
           "hertz_modulus", "ramp_continued", "spring_exponent", "spring_stiffness"]
