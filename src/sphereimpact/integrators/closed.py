"""``closed``: the law's closed-form normal motion, exact to round-off (:mod:`sphereimpact.integrators.closed_form`)."""

from __future__ import annotations

from .closed_form import ClosedFormNormal
from ..contact.laws import LAWS
from .base import INTEGRATORS, Integrator


def _cannot(scene):
    if scene.law.closed_form is None:
        closed = ", ".join(name for name, law in LAWS.items() if law.closed_form is not None)
        return f"needs a law with a closed form ({closed}); got model {scene.model!r}"
    return None


CLOSED = INTEGRATORS.register(Integrator(
    "closed", "the exact solution of a law with a closed form", lambda scene, options: ClosedFormNormal(scene),
    cannot=_cannot))
