"""A plug-in for the tests: a tangential model with a parameter and a numerical setting of its own, in this one
file, registered on import (``--plugin plugin_model``, the study config's ``plugins: [plugin_model]``, or
``import plugin_model``; the tests put this folder on the module path).

The model: the contact slides throughout under a fraction ``slide_share`` of Coulomb's friction, F = -s mu P+
(its own parameter, required, in (0, 1]).  Its setting ``trapezoid_steps`` replaces the exact normal impulse by
the trapezoid rule on that many equal steps over the contact (not given: exact), so a test can see the setting
arrive: the impulse's error falls as the square of the steps.
"""

import numpy as np

from sphereimpact import Parameter, Setting
from sphereimpact.contact.tangential import TANGENTIALS, Phase, PositiveImpulse, TangentialModel, from_impulse

NAME = "share-slide"
SHARE = Parameter("slide_share", "-", "fraction of Coulomb's friction the sliding contact carries",
                  "a finite number in (0, 1]", lambda x: (x > 0) & (x <= 1), bounds=(1e-3, 1.0))
STEPS = Setting("trapezoid_steps", "the share-slide model's trapezoid steps over the contact", 2, 1_000_000,
                default="the exact impulse")


class ShareSlide:
    """The tangential motion: -s mu J+(t) of tangential impulse, J+ exact or by the trapezoid rule."""

    def __init__(self, normal, options):
        scene = self.scene = normal.scene
        self.normal, self.jp = normal, PositiveImpulse(normal)
        steps = options.setting(STEPS.name)
        if steps is None:
            self.scale = 1.0
        else:  # the trapezoid rule's J+ over the exact one: the whole impulse history scaled by it
            t = np.linspace(0.0, normal.t_f, steps + 1)
            p = np.maximum(normal.force(t), 0.0)
            self.scale = float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(t)) / np.ravel(self.jp(normal.t_f))[0])
        self.share = -scene.slide_share * scene.mu * self.scale
        self._phase = Phase("sliding", 0.0, normal.t_f, scene.v_tangent, scene.spin, 0.0)
        self.t_roll, self.regime, self.switches = None, "sliding", 0

    def at(self, t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return np.array(from_impulse(self.scene, self._phase, t, self.share * self.jp(t),
                                     self.share * self.jp.integral(t)))

    def force(self, t):
        return self.share * np.maximum(self.normal.force(t), 0.0)


MODEL = TANGENTIALS.register(TangentialModel(
    NAME, doc="slides under a share of mu P (test plug-in)", stiffness="", parameters=(SHARE,), spring=None,
    motion=ShareSlide, settings=(STEPS,)))
