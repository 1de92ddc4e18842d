"""sphereimpact: oblique impact of a rigid-body sphere on a rigid flat, after Chapter 4 of the study.

Quick use::

    from sphereimpact import Scene, simulate
    out = simulate(Scene(angle=60))        # the chapter's oblique case, modified model
    out.cor, out.omega_f, out.history()    # outputs and time histories (SI units)
"""

import importlib.abc
import importlib.util
import sys
import warnings

from .errors import BeyondRadiusWarning, ImpactError
from .contact.laws import LAWS, ContactLaw, Parameter
from .impact.outcome import HISTORY_COLUMNS, OUTPUT_KEYS, Outcome
from .impact.scene import Scene, SolverOptions
from .impact.solve import simulate

__all__ = ["BeyondRadiusWarning", "ContactLaw", "HISTORY_COLUMNS", "ImpactError", "LAWS", "OUTPUT_KEYS", "Outcome",
           "Parameter", "Scene", "SolverOptions", "simulate"]
__version__ = "0.1.0"

#: Modules that moved when the package was laid out in layers, old name -> new name.  The old names still
#: import, with a DeprecationWarning, for one release (:class:`_Moved`).
MOVED = {f"sphereimpact.{old}": f"sphereimpact.{new}" for old, new in {
    "laws": "contact.laws", "tangential": "contact.tangential", "scene": "impact.scene", "solve": "impact.solve",
    "outcome": "impact.outcome", "planar": "impact.planar", "calibrate": "impact.calibrate",
    "normal": "integrators.normal", "closed": "integrators.closed_form", "taylor": "ode.series", "dop853": "ode.dop853",
    "dense": "ode.dense", "events": "ode.events", "sweep.closed": "contact.laws.exact"}.items()}


class _Moved(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Imports a moved module (or one of its submodules) under its old name: the same module object, so
    that its state and a test's monkeypatching are shared, after a DeprecationWarning naming the new one."""

    @staticmethod
    def _new(fullname: str) -> str | None:
        for old, new in MOVED.items():
            if fullname == old or fullname.startswith(old + "."):
                return new + fullname[len(old):]
        return None

    def find_spec(self, fullname, path=None, target=None):
        return importlib.util.spec_from_loader(fullname, self) if self._new(fullname) else None

    def create_module(self, spec):
        new = self._new(spec.name)
        warnings.warn(f"{spec.name} moved to {new}; the old name is deprecated and goes in the next release",
                      DeprecationWarning, stacklevel=2)
        module = importlib.import_module(new)
        spec.loader_state = module.__spec__  # the import system sets __spec__ to this alias's: restored below
        return module

    def exec_module(self, module):
        module.__spec__ = module.__spec__.loader_state


if not any(isinstance(finder, _Moved) for finder in sys.meta_path):
    sys.meta_path.insert(0, _Moved())
