"""When a contact ends: the separation criterion, one value that carries its behaviour.

A rigid flat cannot pull, so by default the contact ends when the normal force P returns to 0 (``force``);
the textbook spring-damper instead ends it when the compression delta returns to 0 (``penetration``), keeping
the pull of its damper before then.  Every layer asks the criterion what it does, and only :meth:`Separation.parse`
reads its name.
"""

from __future__ import annotations

from ..choice import Choice


class Separation(Choice):
    """The separation criterion of a contact; its value is the name the inputs and tables use."""

    FORCE = "force"
    PENETRATION = "penetration"

    @classmethod
    def parse(cls, value, name: str = "separation") -> Separation:
        """The criterion named ``value`` (a member or its name); ValueError naming ``name`` and the choices."""
        return super().parse(value, name)

    @property
    def on_force(self) -> bool:
        """True when contact ends at P = 0: the force never pulls, and the end is a root of P."""
        return self is Separation.FORCE

    @property
    def pulls(self) -> bool:
        """True when the force may pull before the contact ends (it ends at delta = 0)."""
        return self is Separation.PENETRATION

    @property
    def end_quantity(self) -> str:
        """The quantity that returns to 0 at the end, as messages name it (``P`` or ``delta``)."""
        return "P" if self.on_force else "delta"
