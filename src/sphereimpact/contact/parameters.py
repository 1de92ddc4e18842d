"""What a contact model declares about its inputs: its physical parameters and its numerical settings.

A law (:mod:`.laws`) and a tangential model (:mod:`.tangential`) each list the :class:`Parameter` objects it
reads and, for a model that discretises the contact, the :class:`Setting` objects that fix its resolution.
Scene validation, the command line, sweep tables and the study config read these declarations: a model
registered from outside with a parameter or a setting of its own reaches every door without another file
changing.  :mod:`.declared` collects them over the registries.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Callable

#: A parameter's or setting's name: a Python identifier in lower case (Scene attribute, table column,
#: config key, and ``--name`` with ``-`` for ``_`` on the command line).
NAME = re.compile(r"^[a-z][a-z0-9_]*$")


@dataclass(frozen=True)
class Parameter:
    """One physical parameter of a contact model.

    Attributes
    ----------
    name : str
        Scene attribute, table column and command-line flag ``--name``.  The built-in laws' parameters are
        Scene fields (``k``, ``b``, ...), as are the tangential stiffness's (``kappa``, ...); any other name
        is a model's own parameter, carried in ``Scene.parameters``.
    unit : str
        SI unit, as printed in help texts (``-``: dimensionless).
    doc : str
        What it is, one phrase.
    allowed : str
        The allowed range, as messages state it ("a finite number > 0").
    ok : callable
        Vectorised test of the allowed range (finite values only reach it).
    default : float or None
        Used when the parameter is not given; None makes it required.
    bounds : (float, float) or None
        The range a fit may explore (``sphereimpact fit --free name``), inside ``allowed``; None: above 0, in its
        logarithm, when ``ok`` allows only positive values, else unbounded.
    """

    name: str
    unit: str
    doc: str
    allowed: str
    ok: Callable
    default: float | None = None
    bounds: tuple | None = None

    def __post_init__(self):
        if not NAME.match(self.name):
            raise ValueError(f"parameter name {self.name!r}: lower-case letters, digits and _, starting with a letter")

    @property
    def range_text(self) -> str:
        """The allowed range with its unit, as messages state it: ``a finite number > 0 N/m``."""
        return self.allowed if self.unit == "-" else f"{self.allowed} {self.unit}"


@dataclass(frozen=True)
class Setting:
    """One numerical setting of a contact model: an integer resolution with its bounds.

    Attributes
    ----------
    name : str
        Key of ``SolverOptions.settings``, the study config's ``settings`` and command-line flag ``--name``
        (``-`` for ``_``).
    doc : str
        What it resolves, one phrase (``cells of the element row``).
    low, high : int
        The allowed range, inclusive.
    default : str
        What None (not given) means, for help texts (``the convergence study's``).
    """

    name: str
    doc: str
    low: int
    high: int
    default: str = "the model's default"

    def __post_init__(self):
        if not NAME.match(self.name):
            raise ValueError(f"setting name {self.name!r}: lower-case letters, digits and _, starting with a letter")
        if not 1 <= self.low <= self.high:
            raise ValueError(f"setting {self.name!r}: need 1 <= low <= high; got [{self.low}, {self.high}]")

    def check(self, value) -> int:
        """``value`` as an int; ValueError naming the setting and its range when it is not one inside it."""
        import numbers

        if isinstance(value, bool) or not isinstance(value, numbers.Integral) or not self.low <= value <= self.high:
            raise ValueError(f"{self.name} must be an integer in [{self.low}, {self.high}]; got {value!r}")
        return int(value)
