"""Deprecated alias: the tangential springs moved to :mod:`sphereimpact.contact.tangential.springs` (one release)."""

import warnings

from .contact.tangential.springs import *  # noqa: F401,F403
from .contact.tangential.springs import CompliantTangential, CompliantPhase  # noqa: F401

warnings.warn("sphereimpact.compliance is deprecated: use sphereimpact.contact.tangential (the registry TANGENTIALS, "
              "sphereimpact.contact.tangential.springs for the spring models)", DeprecationWarning, stacklevel=2)
