"""Deprecated alias: the tangential springs moved to :mod:`sphereimpact.tangential.springs` (one release)."""

import warnings

from .tangential.springs import *  # noqa: F401,F403
from .tangential.springs import CompliantTangential, CompliantPhase  # noqa: F401

warnings.warn("sphereimpact.compliance is deprecated: use sphereimpact.tangential (the registry TANGENTIALS, "
              "sphereimpact.tangential.springs for the spring models)", DeprecationWarning, stacklevel=2)
