"""The normal motion of a law with a closed form: its exact solution (``ContactLaw.closed_form``, e.g.
eq. 4.1's in :mod:`sphereimpact.contact.laws.spring_damper`) with its events.

Without gravity the law's solution gives the events as formulas.  With gravity they are the roots of its
exact functions, bracketed on a dense grid (uniform plus geometric, for the fast and slow time scales)
and refined with Brent's method to a few ulp.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..errors import ImpactError
from ..ode.events import first_root
from ..contact.laws import LAWS
from ..contact.motion import KernelState, NormalMotion
from ..ode.dense import SMALL
from .normal import CompiledReads, no_separation_message, separation_function

if TYPE_CHECKING:
    from ..impact.scene import Scene

#: Uniform and geometric samples used to bracket events.
GRID_POINTS = 4097
#: Uniform samples over [0, t_f] (and a quarter as many geometric ones, for an over-damped start) when the
#: events are in closed form: the grid then only brackets the tangential switch and the force's extremes.
EVENT_FREE_GRID = 129


def _scan_grid(t_end: float) -> np.ndarray:
    uniform = np.linspace(0.0, t_end, GRID_POINTS)
    geometric = np.geomspace(t_end * 1e-9, t_end, GRID_POINTS // 2)
    return np.unique(np.concatenate([uniform, geometric]))


class ClosedFormNormal(CompiledReads, NormalMotion):
    """The exact normal motion of a scene whose law declares a closed form.

    Parameters
    ----------
    scene : Scene
        Its law must declare ``closed_form``.

    Raises
    ------
    ValueError
        For a law without a closed form.
    ImpactError
        When the contact never separates under the scene's criterion.
    """

    def __init__(self, scene: Scene):
        if scene.law.closed_form is None:
            closed = ", ".join(name for name, law in LAWS.items() if law.closed_form is not None)
            raise ValueError(f"method 'closed' needs a law with a closed form ({closed}); got model {scene.model!r}")
        self.scene = scene
        self.solution = solution = scene.law.closed_form.motion(scene)
        self.stats = {"method": "closed", "rtol": 0.0, "atol": 0.0, "nfev": 0}
        if solution.weightless:  # the events are in closed form too
            self.t_m, self.t_f = solution.events()
            if self.t_f is None:
                raise ImpactError(no_separation_message(scene, math.inf))
            self.grid = np.unique(np.concatenate([np.linspace(0.0, self.t_f, EVENT_FREE_GRID),
                                                  np.geomspace(self.t_f * 1e-9, self.t_f, EVENT_FREE_GRID // 4)]))
            return
        scan = _scan_grid(solution.scan_end)
        t_m = first_root(lambda t: self.state(t)[1], scan, direction=-1)
        sep = separation_function(scene)
        t_f = first_root(lambda t: sep(*self.state(t)), scan, direction=-1)
        if t_f is None:
            raise ImpactError(no_separation_message(scene, solution.scan_end))
        if t_m is None or t_m > t_f:
            raise ImpactError("no maximum compression before separation")
        self.t_m, self.t_f = t_m, t_f
        self.grid = np.append(scan[scan < t_f], t_f)

    def _has_kernel_state(self) -> bool:
        """Whether compiled code can read this motion: its closed form declares a compiled kind and the motion is read
        instant by instant (``per_instant``), and its law has a kernel and the scalar formula the kernel compiles."""
        law = self.scene.law
        return (law.closed_form.kernel_kind is not None and self.solution.per_instant and law.kernel is not None
                and law.scalar is not None)

    def _kernel_state(self) -> KernelState:
        """The closed form's constants as its compiled kind reads them, with the law's checked kernel."""
        from .compiled import checked_kernel

        scene, none = self.scene, np.empty(0)
        v = scene.v_normal
        return KernelState(scene.law.closed_form.kernel_kind, np.array(self.solution.constants, dtype=float), none,
                           none, np.empty((0, 0)), np.empty((0, 0)), np.empty((0, 7, 2)), np.empty((0, 2)), 1.0, 1.0,
                           1.0, checked_kernel(scene, (v / scene.frequency, v)),
                           np.array(scene.law.kernel.parameters(scene), dtype=float))

    def state(self, t):
        """The closed form's state (:meth:`SpringDamperMotion.state`, instant by instant in plain floats); at many
        instants compiled (:func:`~sphereimpact.contact.normal_kernel.normal_states`, the same values to the bit) where
        :meth:`kernel_state` has the motion, else counted towards loading the compiled code."""
        if np.ndim(t) == 1 and len(t) > SMALL:
            compiled = self._compiled_states(t)
            if compiled is not None:
                return compiled
            self.spend_in_floats(len(t))
        return self.solution.state(t)
