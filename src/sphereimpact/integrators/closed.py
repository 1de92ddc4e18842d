"""``closed``: the law's closed-form normal motion, exact to round-off (kelvin-voigt:
:mod:`sphereimpact.integrators.closed_form`)."""

from __future__ import annotations

from .closed_form import CLOSED_FORMS
from ..contact.laws import LAWS
from .base import INTEGRATORS, Integrator


def _cannot(scene):
    if scene.law.closed_form is None:
        closed = ", ".join(name for name, law in LAWS.items() if law.closed_form is not None)
        return f"needs a law with a closed form ({closed}); got model {scene.model!r}"
    if scene.law.closed_form not in CLOSED_FORMS:
        return (f"finds no closed form {scene.law.closed_form!r} declared by model {scene.model!r} (known: "
                f"{', '.join(CLOSED_FORMS)})")
    return None


CLOSED = INTEGRATORS.register(Integrator(
    "closed", "the exact solution of a law with a closed form", lambda scene, options: CLOSED_FORMS[
        scene.law.closed_form](scene), cannot=_cannot))
