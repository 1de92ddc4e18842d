"""Every parameter and setting the registered contact models declare beyond the Scene's fields (see
:mod:`.parameters`): what the command line's flags, a sweep table's columns and the study config read."""

from __future__ import annotations

from .laws import LAWS
from .tangential import TANGENTIALS


def _collect(items, what: str) -> dict:
    """name -> declaration over ``items`` (pairs of owner, declaration); a name declared twice must be the
    same declaration."""
    found: dict = {}
    owners: dict = {}
    for owner, item in items:
        if item.name in found and found[item.name] != item:
            raise ValueError(f"{what} {item.name!r} is declared differently by {owners[item.name]} and {owner}")
        found.setdefault(item.name, item)
        owners.setdefault(item.name, owner)
    return found


def own_parameters() -> dict:
    """name -> :class:`~.parameters.Parameter` of every registered law's and tangential model's own parameters (those that are
    not Scene fields), in registration order."""
    pairs = [(f"model {law.name!r}", p) for law in LAWS.values() for p in law.own_parameters]
    pairs += [(f"tangential {model.name!r}", p) for model in TANGENTIALS.values() for p in model.own_parameters]
    return _collect(pairs, "parameter")


def settings() -> dict:
    """name -> :class:`~.parameters.Setting` of every registered tangential model's numerical settings."""
    return _collect([(f"tangential {m.name!r}", s) for m in TANGENTIALS.values() for s in m.settings], "setting")
