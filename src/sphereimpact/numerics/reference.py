"""Reference solutions and the error measure of the accuracy studies.

``kelvin-voigt``: the law's closed form (:mod:`sphereimpact.contact.laws.spring_damper`), exact to round-off.  Other
laws (Hertz, Hunt-Crossley): scipy's DOP853 at rtol 1e-13, for the benchmarks (their accuracy is tested in
tests/test_laws.py against closed forms and calibration).
``modified``: the normal problem in dimensionless form integrated with
mpmath's arbitrary-precision Taylor method (:func:`mpmath.odefun`), with
events found by :func:`mpmath.findroot`, at two working precisions; their
agreement bounds the error of the coarser one, and the finer one is the
reference.  Without gravity, every output follows from t_m, delta_m, t_f and
delta_dot(t_f) exactly: the tangential outputs by the impulse algebra
(sliding: J_t = mu J_n; grip: v_t = vt0 / (1 + alpha)).
"""

from __future__ import annotations

import json
import math
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

from ..impact.scene import Scene, SolverOptions
from ..impact.solve import simulate
from ..contact.tangential import impulse_outcome

#: Working precisions [decimal digits] of the Taylor reference and of the solve that bounds its error: both
#: far beyond float64, and their outputs round to the same doubles.
FINE_DIGITS, COARSE_DIGITS = 24, 18
#: Outputs compared in the accuracy studies.
ERROR_KEYS = ("t_m", "delta_m", "t_f", "cor", "omega_f", "ve_t")


def output_scales(scene: Scene, t_f: float, delta_m: float, force_max: float = 1.0) -> dict:
    """Natural size of each output, so that an output that is exactly zero (a normal impact's spin, a
    rolling ball's slip) is measured on the scale of the impact rather than relative to zero."""
    v = scene.speed
    return {"t_m": t_f, "t_f": t_f, "t_roll": t_f, "delta_m": delta_m, "vc_t": v, "vc_n": v, "ve_t": v,
            "ve_n": v, "cor": 1.0, "omega_f": v / scene.radius, "force_min": force_max, "force_max": force_max,
            "switches": 1.0, "rebound_angle": 90.0, "rebound_angle_contact": 90.0,
            "rebound_angle_to_surface": 90.0,
            "work_t": 0.5 * scene.mass * v * v}


def _never(value) -> bool:
    """An output that did not happen (``t_roll`` of a contact that never stops slipping): None or NaN."""
    return value is None or value != value


def relative_errors(got: dict, ref: dict, scene: Scene, keys=ERROR_KEYS) -> dict:
    """|got - ref| / max(|ref|, scale) for each key; 0 where neither happened (None or NaN), inf where one
    did and the other did not."""
    scales = output_scales(scene, ref["t_f"], ref["delta_m"], ref.get("force_max", 1.0))
    out = {}
    for k in keys:
        if _never(got[k]) or _never(ref[k]):
            out[k] = 0.0 if _never(got[k]) and _never(ref[k]) else math.inf
        else:
            out[k] = abs(got[k] - ref[k]) / max(abs(ref[k]), scales[k])
    return out


def worst_error(got: dict, ref: dict, scene: Scene) -> float:
    """The largest relative error over :data:`ERROR_KEYS`."""
    return max(relative_errors(got, ref, scene).values())


@dataclass(frozen=True)
class Reference:
    """Reference outputs of one scene and a bound on their relative error."""

    outputs: dict
    bound: float
    how: str


def outputs_from_normal(scene: Scene, t_m: float, delta_m: float, t_f: float, rate_f: float) -> dict:
    """Every output from the normal events (g = 0, friction impulse mu J), by the impulse algebra
    (:func:`sphereimpact.contact.tangential.impulse_outcome`).

    Exact where the force does not pull before separation (always under the force criterion).
    """
    if scene.gravity != 0:
        raise ValueError("outputs from the normal events need gravity = 0")
    vc_n = -rate_f
    vc_t, omega, ve_t, _ = (float(x) for x in impulse_outcome(
        scene.v_tangent, scene.spin, scene.mass * (scene.v_normal + vc_n), scene.mass, scene.radius,
        scene.inertia_factor, scene.mu))
    return {"t_m": t_m, "delta_m": delta_m, "t_f": t_f, "cor": vc_n / scene.v_normal, "omega_f": omega,
            "ve_t": ve_t, "vc_t": vc_t, "vc_n": vc_n, "ve_n": vc_n}


def taylor_normal(scene: Scene, digits: int) -> tuple[float, float, float, float]:
    """(t_m, delta_m, t_f, delta_dot(t_f)) of the modified law by mpmath's Taylor integrator."""
    if scene.model != "modified":
        raise ValueError("the Taylor reference is written for the modified law")
    import mpmath  # only the reference needs arbitrary precision; the metrics above do not

    with mpmath.workdps(digits):
        w, v = scene.omega_n, scene.v_normal
        zeta, lam = mpmath.mpf(scene.zeta), mpmath.mpf(scene.ramp * v / (w * scene.radius))

        def rhs(tau, y):
            return [y[1], -y[0] - 2 * zeta * y[1] * (1 - mpmath.exp(-lam * y[0]))]

        sol = mpmath.odefun(rhs, 0, [mpmath.mpf(0), mpmath.mpf(1)], tol=mpmath.mpf(10) ** (2 - digits))
        guess = simulate(scene, SolverOptions(rtol=1e-10, atol=1e-12))  # starting points for the root search
        def bracket(t):  # the float64 estimate is good to far better than 0.1 %
            return (t * w * (1 - 1e-3), t * w * (1 + 1e-3))

        tau_m = mpmath.findroot(lambda t: sol(t)[1], bracket(guess.t_m), solver="anderson")

        def separation(t):
            # force: the (smooth) force law; near x = 0 it is x (1 + 2 zeta lam y), so where P stays
            # positive until x = 0 its root is x = 0, the first of P = 0 and delta = 0 either way
            x, y = sol(t)
            return x if scene.separation.pulls else x + 2 * zeta * y * (1 - mpmath.exp(-lam * x))

        tau_f = mpmath.findroot(separation, bracket(guess.t_f), solver="anderson")
        x_m, y_f = sol(tau_m)[0], sol(tau_f)[1]
        return float(tau_m / w), float(x_m * v / w), float(tau_f / w), float(y_f * v)


#: The references read from a file inside :func:`stored_references`, by scene (:func:`_key`); None outside.
_STORED: ContextVar[dict | None] = ContextVar("stored references", default=None)


def _key(scene: Scene) -> str:
    """The scene as a stored reference names it: its repr, every input to the last digit."""
    return repr(scene)


def write_references(scenes, path: str) -> None:
    """:func:`reference` of each of ``scenes`` into the JSON file ``path`` (each scene's repr beside its reference;
    floats written to the last bit), for :func:`stored_references`: a timed study reads its references there, so the
    job that must run alone does not spend its time computing them."""
    entries = []
    for scene in scenes:
        ref = reference(scene)
        entries.append({"scene": _key(scene), "outputs": ref.outputs, "bound": ref.bound, "how": ref.how})
    with open(path, "w") as out:
        json.dump(entries, out, indent=1)


@contextmanager
def stored_references(path: str | None):
    """Inside this block :func:`reference` of a scene the file ``path`` (:func:`write_references`) holds returns it
    as stored (the same outputs to the bit); any other scene is computed.  ``path`` None: nothing stored."""
    stored = {}
    if path is not None:
        with open(path) as file:
            stored = {entry["scene"]: Reference(entry["outputs"], entry["bound"], entry["how"])
                      for entry in json.load(file)}
    token = _STORED.set(stored)
    try:
        yield
    finally:
        _STORED.reset(token)


def reference(scene: Scene) -> Reference:
    """The reference outputs of ``scene``: the law's closed form where it declares one (kelvin-voigt),
    Taylor at :data:`FINE_DIGITS` bounded by :data:`COARSE_DIGITS` (modified), or for any other law scipy's
    DOP853 at rtol 1e-13, bounded by its distance from rtol 1e-12 (a second implementation beside the
    package's DOP853-scalar, not an exact one); inside :func:`stored_references`, the stored one where the file has
    the scene."""
    stored = (_STORED.get() or {}).get(_key(scene))
    if stored is not None:
        return stored
    if scene.law.closed_form is not None:
        out = simulate(scene, SolverOptions(method="closed")).to_dict()
        return Reference(out, 4 * 2.2e-16, "closed form")
    if scene.model != "modified":
        fine = simulate(scene, SolverOptions(method="DOP853", rtol=1e-13, atol=1e-15)).to_dict()
        coarse = simulate(scene, SolverOptions(method="DOP853", rtol=1e-12, atol=1e-14)).to_dict()
        return Reference(fine, max(worst_error(coarse, fine, scene), 2.2e-16), "scipy DOP853, rtol 1e-13")
    fine = outputs_from_normal(scene, *taylor_normal(scene, FINE_DIGITS))
    coarse = outputs_from_normal(scene, *taylor_normal(scene, COARSE_DIGITS))
    bound = max(worst_error(coarse, fine, scene), 2.2e-16)
    return Reference(fine, bound, f"mpmath Taylor ({FINE_DIGITS} digits); bound = its distance from "
                                  f"{COARSE_DIGITS} digits")


def float64_check(scene: Scene, ref: Reference) -> float:
    """Independent check: worst error of DOP853 at rtol 1e-13 against the reference."""
    got = simulate(scene, SolverOptions(method="DOP853", rtol=1e-13, atol=1e-15)).to_dict()
    return worst_error(got, ref.outputs, scene)

