"""The baseline of the exact microslip contact's speed: the compiled port a competent numba user writes by hand.

One compiled call per impact, on the scene's numbers alone: the normal motion of a Hunt–Crossley (or elastic
Hertz) contact P = k delta^n (1 + chi delta_dot) by classical fixed-step Runge–Kutta (RK4), once on a step guessed
from elastic Hertz to find the separation t_f (the last step's cubic Hermite root), then again on exactly the march's
M equal steps of [0, t_f], the contact radius, P+ and the impulse of each step read off those steps (the impulse as
m times the change of the compression rate); then the package's own compiled element-row march
(:func:`sphereimpact.contact.tangential.microslip_march.march`: the same cells, steps, cell weighting and entry rule)
and the ball's tangential velocity and spin from its impulse.

What it leaves out is what the package adds around the march: building and checking the Scene, the adaptive
normal integration with its events and dense output, the resolution's choice, the stick and roll bookkeeping, the
Outcome's every output.  So ``simulate``'s time over this port's, on the same scene and resolution with both errors
in the same table (``results/bench.csv``), is what that machinery costs.  Gravity-free scenes of a damping that
keeps pushing until the compression ends (1 + chi delta_dot > 0 throughout, as at every speed of a real ball): a
baseline, not a second implementation of the package.  Compiled in the process that first calls it (no disk
cache: a benchmark's contender, not a kernel of the package).
"""

from __future__ import annotations

import math

#: Most RK4 steps of the first pass, in multiples of the march's steps, before a contact that never ends is refused.
MAX_PASSES = 8
_PORT = None


def _compiled():
    """The port's compiled function, compiled on first use (numba imported only then)."""
    global _PORT
    if _PORT is None:
        import numba
        import numpy as np

        from ..contact.tangential.microslip_march import march

        @numba.njit(nogil=True, error_model="numpy")
        def rate(delta, delta_dot, k, exponent, chi, mass):
            force = k * delta ** exponent * (1.0 + chi * delta_dot) if delta > 0.0 else 0.0
            return -force / mass

        @numba.njit(nogil=True, error_model="numpy")
        def rk4(delta, delta_dot, h, k, exponent, chi, mass):
            a1 = rate(delta, delta_dot, k, exponent, chi, mass)
            a2 = rate(delta + 0.5 * h * delta_dot, delta_dot + 0.5 * h * a1, k, exponent, chi, mass)
            a3 = rate(delta + 0.5 * h * (delta_dot + 0.5 * h * a1), delta_dot + 0.5 * h * a2, k, exponent, chi, mass)
            a4 = rate(delta + h * (delta_dot + 0.5 * h * a2), delta_dot + h * a3, k, exponent, chi, mass)
            return (delta + h * (delta_dot + h * (a1 + a2 + a3) / 6.0),
                    delta_dot + h * (a1 + 2.0 * a2 + 2.0 * a3 + a4) / 6.0)

        @numba.njit(nogil=True, error_model="numpy")
        def hermite(s, h, d0, v0, d1, v1):
            """The cubic Hermite of a step's ends at s in [0, 1] of it, and its rate."""
            value = (2 * s**3 - 3 * s**2 + 1) * d0 + (s**3 - 2 * s**2 + s) * h * v0 \
                + (-2 * s**3 + 3 * s**2) * d1 + (s**3 - s**2) * h * v1
            slope = ((6 * s**2 - 6 * s) * d0 + (3 * s**2 - 4 * s + 1) * h * v0
                     + (-6 * s**2 + 6 * s) * d1 + (3 * s**2 - 2 * s) * h * v1) / h
            return value, slope

        @numba.njit(nogil=True, error_model="numpy")
        def root(which, h, d0, v0, d1, v1):
            """Where in [0, 1] of a step its Hermite's value (``which`` 0) or rate (1) falls through zero: 60
            bisections, from positive at 0 to non-positive at 1."""
            low, high = 0.0, 1.0
            for _ in range(60):
                mid = 0.5 * (low + high)
                if hermite(mid, h, d0, v0, d1, v1)[which] > 0.0:
                    low = mid
                else:
                    high = mid
            return 0.5 * (low + high)

        @numba.njit(nogil=True, error_model="numpy")
        def port(k, exponent, chi, mass, radius, v_normal, v_tangent, spin, mu, shear_modulus, inertia_factor,
                 elements, steps, guess):
            # first pass: the separation, on steps of guess / steps
            h = guess / steps
            delta, delta_dot, t, taken = 0.0, v_normal, 0.0, 0
            for taken in range(1, MAX_PASSES * steps + 1):
                d1, v1 = rk4(delta, delta_dot, h, k, exponent, chi, mass)
                if d1 < 0.0:
                    break
                delta, delta_dot, t = d1, v1, t + h
            else:
                return math.nan, math.nan, 0
            t_f = t + root(0, h, delta, delta_dot, d1, v1) * h
            # second pass: the march's M equal steps of [0, t_f]
            h = t_f / steps
            points = steps + 1
            depth, speed = np.empty(points), np.empty(points)
            depth[0], speed[0] = 0.0, v_normal
            delta_m = 0.0
            for n in range(steps):
                depth[n + 1], speed[n + 1] = rk4(depth[n], speed[n], h, k, exponent, chi, mass)
                if speed[n] > 0.0 >= speed[n + 1]:  # maximum compression in this step: its Hermite's peak
                    ends = (h, depth[n], speed[n], depth[n + 1], speed[n + 1])
                    delta_m = hermite(root(1, *ends), *ends)[0]
            xi_a, cap, impulse = np.empty(points), np.zeros(points), np.empty(steps)
            for n in range(points):
                xi_a[n] = math.sqrt(max(depth[n], 0.0) / delta_m)
                if 0 < n < steps:
                    cap[n] = mu * max(-mass * rate(depth[n], speed[n], k, exponent, chi, mass), 0.0)
                if n < steps:
                    impulse[n] = mu * mass * (speed[n] - speed[n + 1])
            stiffness = 2.0 * shear_modulus * math.sqrt(radius * delta_m)
            inverse_mass = (1.0 + 1.0 / inertia_factor) / mass
            _, j_t = march(xi_a, cap, impulse, h, stiffness, inverse_mass, 0.0, v_tangent - spin * radius,
                           np.zeros(elements))
            return (v_tangent + j_t[-1] / mass, spin - j_t[-1] / (inertia_factor * mass * radius),
                    4 * (taken + steps) + steps - 1)

        _PORT = port
    return _PORT


def port_numbers(scene, elements: int, time_steps: int) -> tuple:
    """The port's arguments for ``scene`` at ``elements`` cells and ``time_steps`` steps: floats and ints only,
    what the user's script holds before its loop.

    Raises
    ------
    ValueError
        ``scene`` is not what the port solves: a Hertz spring with Hunt–Crossley or no damping, on the flat,
        gravity-free, with the microslip contact.
    """
    from ..contact.laws.hertz import HERTZ
    from ..contact.tangential.microslip import hertz_moduli

    if scene.model not in ("hunt-crossley", "hertz") or scene.tangential != "microslip" or scene.gravity != 0.0 \
            or scene.has_partner:
        raise ValueError("the compiled port solves a gravity-free microslip contact of law hunt-crossley or hertz "
                         f"on the flat; got law {scene.model!r}, tangential {scene.tangential!r}, gravity "
                         f"{scene.gravity:g} m/s^2{', a partner sphere' if scene.has_partner else ''}")
    damped = scene.model == "hunt-crossley"
    k, exponent, chi = float(scene.k), float(scene.exponent) if damped else HERTZ, float(scene.chi) if damped else 0.0
    elastic = (0.5 * (exponent + 1.0) * scene.mass * scene.v_normal ** 2 / k) ** (1.0 / (exponent + 1.0))
    guess = 3.5 * elastic / scene.v_normal  # a little beyond elastic Hertz's t_f (2.94 delta_m / v_n)
    return (k, exponent, chi, float(scene.mass), float(scene.radius), float(scene.v_normal), float(scene.v_tangent),
            float(scene.spin), float(scene.mu), float(hertz_moduli(scene)[1]), float(scene.inertia_factor),
            int(elements), int(time_steps), guess)


def compiled_port(*numbers) -> tuple[float, float, int]:
    """One impact by the port (see module docstring) on :func:`port_numbers`: the ball's tangential centre velocity
    [m/s] and spin [rad/s] after it, and the normal force's evaluations (RK4's four a step, and P+ at the steps).

    Raises
    ------
    RuntimeError
        The contact did not end within :data:`MAX_PASSES` times the guessed contact time.
    """
    v_t, omega, evaluations = _compiled()(*numbers)
    if math.isnan(v_t):
        raise RuntimeError(f"the compiled port's contact did not end within {MAX_PASSES} times its guessed "
                           "contact time")
    return v_t, omega, int(evaluations)
