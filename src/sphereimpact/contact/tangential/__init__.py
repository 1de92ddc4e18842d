"""Tangential contact models: one definition each, in a registry keyed by name.

=========  ================================================================  =====================
name       tangential force at the contact point                             module
=========  ================================================================  =====================
rigid      slips (mu P) or rolls: the chapter's                              :mod:`.rigid`
linear     spring k_t = kappa k capped by mu P (linear-spring laws)          :mod:`.springs`
mindlin    Hertz-Mindlin spring k_t = 8 G* a on force increments, rescaled  :mod:`.springs`
           while the contact shrinks, capped by mu P (Hertz laws)
mindlin-   the same stiffness on the total displacement (LAMMPS ``mindlin``) :mod:`.springs`
displace-
ment
microslip  exact elastic microslip of a Hertz contact (MDR; Hertz laws)      :mod:`.microslip`
=========  ================================================================  =====================

Adding a model is one :class:`TangentialModel` passed to ``TANGENTIALS.register`` (see :mod:`.base`).
"""

from .base import (KAPPA, KAPPA_FROM, POISSON, SHEAR_MODULUS, STIFFNESS, TANGENTIAL_PARAMETERS, TANGENTIALS, Regime,
                   SweptTangential, TangentialModel, kappa_from_poisson, kappa_from_shear_modulus)
from .rigid import (MAX_PHASES, Phase, PositiveImpulse, TangentialMotion, by_phase, from_impulse, impulse_outcome, kick,
                    phase_index)
from .springs import CompliantTangential
from .microslip import MicroslipTangential

__all__ = ["CompliantTangential", "KAPPA", "KAPPA_FROM", "MAX_PHASES", "MicroslipTangential", "POISSON", "Phase",
           "PositiveImpulse", "Regime", "SHEAR_MODULUS", "STIFFNESS", "SweptTangential", "TANGENTIALS", "TANGENTIAL_PARAMETERS",
           "TangentialModel", "TangentialMotion", "by_phase", "from_impulse", "impulse_outcome", "kick",
           "kappa_from_poisson", "kappa_from_shear_modulus", "phase_index"]
