"""What a law's closed form is: an exact solution of its normal motion, in the two forms the layers need
(:class:`ClosedForm`; eq. 4.1's is :data:`sphereimpact.contact.laws.spring_damper.SPRING_DAMPER`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...ode.roots import falling_root


@dataclass(frozen=True)
class ClosedForm:
    """An exact solution of a law's normal motion, in the two forms the layers need.

    Attributes
    ----------
    name : str
        What it solves, for messages (``linear spring-damper``).
    motion : callable
        ``motion(scene)``: one scene's exact motion in SI units, with ``weightless``, ``scan_end`` [s],
        ``state(t) -> (delta [m], delta_dot [m/s])``, when weightless ``events() -> (t_m, t_f or None)`` [s], and
        with a ``kernel_kind`` its ``constants`` and ``per_instant`` (see :class:`SpringDamperMotion`).
    events : callable
        ``events(numbers, separation) -> dict`` of the weightless motion's dimensionless outputs
        (:data:`sphereimpact.sweep.outputs.NORMAL_OUTPUTS`), vectorised over the arrays of ``numbers``.
    reads : tuple of str
        The family numbers ``events`` reads (a law declaring this closed form must have them).
    jet : callable or None
        ``jet(numbers, tau) -> (x, y, P_hat, P_hat', P_hat'')``: the weightless dimensionless motion at tau
        (arrays broadcasting with ``numbers``) and its force with two rates, from which :meth:`extremes` and
        :meth:`grip_instants` follow.  None: the sweep's closed path gives the normal events only (rows that
        need the force's extremes or a grip instant take another path).
    kernel_kind : int or None
        The kind of compiled normal motion (:class:`~sphereimpact.contact.motion.KernelState`) that evaluates this
        closed form's motion from its ``constants`` with the arithmetic of its ``state``, where the motion says so
        (``per_instant``; :data:`sphereimpact.contact.laws.spring_damper.KERNEL_KIND`).  None: compiled code does
        not read it (the contact's kernels then compute in Python, the same answer).
    """

    name: str
    motion: object
    events: object
    reads: tuple
    jet: object = None
    kernel_kind: int | None = None

    def extremes(self, numbers: dict, tau_f) -> dict:
        """``p_max`` and ``p_min``, the extremes of P_hat over [0, tau_f] of the weightless motion: at its ends
        and its turning points (roots of P_hat', bracketed on TURN_SAMPLES samples and refined by Newton on
        P_hat''), computed once per distinct family (the scenes of one ball share it)."""
        unique, inverse, numbers_u, tau_u = _distinct(numbers, tau_f)
        grid = tau_u[None, :] * np.linspace(0.0, 1.0, TURN_SAMPLES)[:, None]
        _, _, p, dp, _ = self.jet({k: v[None, :] for k, v in numbers_u.items()}, grid)
        p_max, p_min = np.maximum(p[0], p[-1]), np.minimum(p[0], p[-1])
        for sign, best in ((1.0, np.maximum), (-1.0, np.minimum)):  # maxima: P_hat' falls through 0; minima: rises
            f = sign * dp
            step, lane = np.nonzero((f[:-1] > 0) & (f[1:] <= 0))
            if step.size:
                a, b = grid[step, lane], grid[step + 1, lane]
                where = {k: v[lane] for k, v in numbers_u.items()}

                def slope(t, where=where, sign=sign):
                    _, _, _, d, dd = self.jet(where, t)
                    return sign * d, sign * dd

                t = falling_root(slope, a, b, f[step, lane], f[step + 1, lane])
                value = self.jet(where, t)[2]
                target = p_max if sign > 0 else p_min
                best.at(target, lane, value)
        return {"p_max": p_max[inverse], "p_min": p_min[inverse]}

    def grip_instants(self, numbers: dict, levels, tau_m, tau_f, j_p):
        """tau_g: where the impulse of P_hat, j = 1 - y, first reaches each level (``levels`` > 0), by Newton on
        dj/dtau = P_hat within [0, tau_p], tau_p where P_hat first falls to 0 after tau_m (a level beyond j_p is
        clamped: tau_p)."""
        _, y_f, p_f, _, _ = self.jet(numbers, tau_f)
        tau_p = tau_f.copy()
        pulls = p_f < 0  # P_hat falls to 0 before separation (tension under the penetration criterion)
        if pulls.any():
            where = {k: v[pulls] for k, v in numbers.items()}
            p_m = self.jet(where, tau_m[pulls])[2]
            tau_p[pulls] = falling_root(lambda t: self.jet(where, t)[2:4], tau_m[pulls], tau_f[pulls], p_m, p_f[pulls])
        clamped = np.minimum(levels, j_p)
        tau_g = tau_p.copy()
        inside = clamped < j_p
        if inside.any():
            where = {k: v[inside] for k, v in numbers.items()}
            level = clamped[inside]

            def gap(t):  # level - j falls through 0; its slope -P_hat
                _, y, p, _, _ = self.jet(where, t)
                return level - (1.0 - y), -p

            tau_g[inside] = falling_root(gap, np.zeros(level.size), tau_p[inside], level, level - j_p[inside])
        return np.where(levels == 0, 0.0, tau_g)


#: Samples of P_hat' over the contact that bracket its turning points (a damped oscillation of at most half a
#: period: two turns at most, far apart).
TURN_SAMPLES = 65


def _distinct(numbers: dict, tau_f):
    """The distinct (family numbers, tau_f) of many scenes: (unique rows, inverse, numbers, tau_f) of them."""
    stacked = np.column_stack([np.asarray(v, dtype=float) for v in numbers.values()] + [np.asarray(tau_f, float)])
    unique, inverse = np.unique(stacked, axis=0, return_inverse=True)
    return unique, inverse.ravel(), {k: unique[:, i] for i, k in enumerate(numbers)}, unique[:, -1]
