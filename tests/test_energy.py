"""Energy: the kinetic energy lost equals the work of damping and friction (plus spring energy left at separation)."""

import numpy as np
import pytest
from scipy.integrate import quad

from conftest import TIGHT
from sphereimpact import Scene, simulate

SCENES = {
    "60deg-modified-sliding": dict(angle=60.0),
    "30deg-modified-grip": dict(angle=30.0),
    "60deg-kv-penetration-tension": dict(angle=60.0, model="kelvin-voigt", separation="penetration"),
    "45deg-kv-force": dict(angle=45.0, model="kelvin-voigt"),
    "normal-modified-penetration": dict(angle=0.0, separation="penetration"),
}


def _integral(f, out):
    """Integral of f(t) over the contact, split at every kink (phase switches, force sign changes)."""
    motion = out.motion
    breaks = {0.0, out.t_f, out.t_m}
    if motion.tangential is not None:
        breaks |= {p.t0 for p in motion.tangential.phases}
        breaks |= {c for interval in motion.tangential.jp.intervals for c in interval}
    edges = sorted(breaks)
    return sum(quad(f, a, b, epsabs=0.0, epsrel=1e-13, limit=500)[0] for a, b in zip(edges[:-1], edges[1:]))


@pytest.mark.parametrize("name", SCENES)
def test_energy_balance(name):
    scene = Scene(**SCENES[name])
    out = simulate(scene, TIGHT)
    m, inertia, radius, k = scene.mass, scene.inertia, scene.radius, scene.k
    before = 0.5 * m * scene.speed**2
    after = 0.5 * m * (out.vc_t**2 + out.vc_n**2) + 0.5 * inertia * out.omega_f**2
    assert after <= before

    def damping_power(t):
        kin = out.motion.kinematics(t)
        return float(((out.motion.force(t) - k * kin["delta"]) * kin["delta_dot"])[0])

    def friction_power(t):
        kin = out.motion.kinematics(t)
        slip = kin["vc_t"] - kin["omega"] * radius
        return float((scene.mu * np.maximum(out.motion.force(t), 0.0) * slip)[0])

    delta_f = float(out.motion.kinematics(out.t_f)["delta"][0])
    damping = _integral(damping_power, out)
    friction = _integral(friction_power, out) if scene.has_tangential_motion else 0.0
    assert damping > 0 and friction >= 0
    assert before - after == pytest.approx(damping + friction + 0.5 * k * delta_f**2, rel=1e-8, abs=1e-8 * before)
