"""Plug-ins: modules that register laws, tangential models or integrators when imported.

A plug-in is any importable Python module that calls ``LAWS.register``, ``TANGENTIALS.register`` or
``INTEGRATORS.register`` at import.  Each door loads the plug-ins it is told of before it reads a model's
name: the command line's ``--plugin MODULE``, the study config's ``plugins`` list, or an ``import`` in one's own
Python code.  A ball file names the plug-ins its models need but is never a door: reading it imports nothing
(:func:`~sphereimpact.impact.ball.load_ball` refuses a plug-in the user did not load).
"""

from __future__ import annotations

import importlib
import re

#: A module name as ``import`` takes it.
MODULE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*$")


def load(names) -> list[str]:
    """Import each module in ``names`` (once: Python caches it); the names, in order.

    Raises
    ------
    ValueError
        A name that is not a module name, or a module that cannot be imported (with the reason, one line).
    """
    loaded = []
    for name in names:
        if not isinstance(name, str) or not MODULE.match(name):
            raise ValueError(f"plugin must be a module name (as for import: my_models or package.models); got {name!r}")
        try:
            importlib.import_module(name)
        except ImportError as err:
            raise ValueError(f"plugin {name!r} cannot be imported ({err}); is its folder on PYTHONPATH?") from None
        loaded.append(name)
    return loaded
