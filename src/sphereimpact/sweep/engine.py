"""The sweep engine: a table of scenes in, a table of outcomes out.

Each scene takes the first path of :data:`.paths.ORDER` that takes it (:mod:`.paths`: the single-impact
model for gravity on a slope, compliant contact and scenes the fast paths cannot bound; a kernel-less law's
interpolant or per-family solves; the kelvin-voigt closed form; eq. 4.2's interpolants in lam or on the
(zeta, lam) plane; the batched Taylor and Runge-Kutta lanes).  Every path but the single-impact one gives
the dimensionless normal motion, from which the tangential velocity, spin and regime follow by the
single-impact core's impulse algebra (:func:`sphereimpact.contact.tangential.impulse_outcome`), and the outputs
that need the force's history (:data:`FAMILY_OUTPUTS`) from one single-impact solve per dimensionless
family.  Results do not depend on the chunk size or on sharding: every lane is integrated independently
and interpolants are built on the whole sweep.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..errors import ImpactError
from ..impact.outcome import SCALAR_OUTPUTS
from ..parsing import parse_range  # noqa: F401  (re-exported: sweeps take ranges as text)
from ..impact.scene import SolverOptions
from ..impact.solve import normal_motion
from ..contact.tangential import impulse_outcome
from .outputs import NORMAL_OUTPUTS
from .paths import ORDER, PATHS, Work
from .scenes import SCENE_COLUMNS, Numbers, _objects, grid, incidence, numbers, rows, scene_of, scene_table

#: The engine's public names; the scene table's and the paths' are re-exported from :mod:`.scenes` and
#: :mod:`.paths`, where they are defined.
__all__ = ["FAMILY_OUTPUTS", "FAST_OUTPUTS", "PATHS", "SCENE_COLUMNS", "SWEEP_OUTPUTS", "grid", "incidence",
           "outputs_wanted", "parse_range", "rows", "scene_of", "scene_table", "sweep"]

#: Outputs of a sweep: every scalar output of ``simulate``, named as it names them (one list, shared).
SWEEP_OUTPUTS = SCALAR_OUTPUTS
#: The outputs that depend on the whole time history of the normal force, not only on its end state: the
#: fast paths (closed form, lanes, interpolants) get them from one single-impact solve per dimensionless family,
#: scaled to each scene (exact: the family fixes the dimensionless motion).
FAMILY_OUTPUTS = ("t_roll", "force_min", "force_max")
#: The outputs the fast paths compute from the end state alone (``outputs=FAST_OUTPUTS``: the fastest sweep).
FAST_OUTPUTS = tuple(key for key in SWEEP_OUTPUTS if key not in FAMILY_OUTPUTS)
#: Newton steps refining a grip instant from its interpolate on the solver's grid (quadratic convergence).
GRIP_NEWTON = 5
#: The regime column's values, by index.
REGIMES = np.array(["none", "sliding", "rolling"], dtype=object)


def sweep(scenes, target: float = 1e-8, chunk_size: int = 100_000, progress=None, span=None,
          outputs=None, elements: int | None = None, time_steps: int | None = None) -> pd.DataFrame:
    """Simulate every scene of a table.

    Parameters
    ----------
    scenes : DataFrame or dict
        Named as :class:`sphereimpact.Scene` fields (``angle`` [deg], ``speed`` [m/s], ``mass``,
        ``diameter``, ``inertia_factor``, ``mu``, ``model``, ``k``, ``b``, ``ramp``, ``gravity``,
        ``separation``, ``tangential``, ``kappa``, ``spin``, ...); missing ones take the chapter's defaults.
        A DataFrame is one scene per row (:func:`rows` builds one from paired lists); a dict of values or
        lists is every combination of them (:func:`grid`), as on the command line.
    target : float
        Relative accuracy of every output (1e-8: within 1e-8 of the single-impact reference).
    chunk_size : int
        Scenes integrated at once (memory stays bounded; results do not depend on it).
    progress : callable, optional
        ``progress(done, total)`` after each chunk of integrated scenes (and every 100 scenes solved one by
        one: gravity on a slope, compliant tangential contact).
    span : DataFrame or dict, optional
        The whole sweep when ``scenes`` is one shard of it: interpolants are built on the whole
        sweep's range, so the merged shards equal the sweep run at once.  Defaults to ``scenes``.
    outputs : sequence of str, optional
        The outputs wanted, some of :data:`SWEEP_OUTPUTS` (default: all, every scalar output of
        ``simulate``).  :data:`FAST_OUTPUTS` spares the per-family solves of :data:`FAMILY_OUTPUTS`.
    elements, time_steps : int, optional
        The resolution of a tangential model that resolves the contact (``microslip``), as
        :class:`sphereimpact.SolverOptions` takes it.

    Returns
    -------
    DataFrame
        The scene columns followed by the outputs (in :data:`SWEEP_OUTPUTS`' order; SI units, angles in
        degrees), one row per scene, in order, then ``path``: which path solved the row (:data:`PATHS`).
        ``t_roll`` is empty (NaN) where the contact point never stops slipping, as ``simulate`` gives None.

    Raises
    ------
    ValueError
        A parameter out of range (naming it and the first bad row), or a bad target or chunk size.
    ImpactError
        A scene that never separates.
    """
    if isinstance(target, (bool, np.bool_)) or not isinstance(target, (float, np.floating)) \
            or not 1e-12 <= target <= 1e-3:
        raise ValueError(f"target must be a number in [1e-12, 1e-3]; got {target!r}")
    if isinstance(chunk_size, (bool, np.bool_)) or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ValueError(f"chunk_size must be an integer >= 1; got {chunk_size!r}")
    wanted = outputs_wanted(outputs)
    frame = scene_table(scenes)
    n = len(frame)
    result = {key: np.full(n, np.nan) for key in SWEEP_OUTPUTS if key not in ("regime", "beyond_radius")}
    regime, path = _objects(n, "none"), _objects(n, "")
    options = SolverOptions(rtol=min(1e-10, target / 100), atol=min(1e-10, target / 100), elements=elements,
                            time_steps=time_steps)
    d = numbers(frame)
    span_frame = frame if span is None else scene_table(span)
    work = Work(frame, d, span_frame, d if span is None else numbers(span_frame), target, chunk_size, options,
                progress)
    normal = {key: np.full(n, np.nan) for key in NORMAL_OUTPUTS}
    todo, span_todo, rest = np.ones(n, bool), np.ones(len(span_frame), bool), np.zeros(n, bool)
    for way in ORDER:
        taken = way.take(work, todo, span_todo)
        for task in taken.tasks:
            for key, values in task.solve().items():
                (regime if key == "regime" else result[key] if way.gives == "all" else normal[key])[task.rows] = values
            path[task.rows] = way.name
            todo[task.rows] = False
            rest[task.rows] = way.gives == "normal"  # completed below by the impulse algebra
        span_todo &= ~taken.span
    if todo.any():  # every row has a path: the last one takes every batched kernel, an earlier one the others
        raise ImpactError(f"sweep: no path takes row {int(np.flatnonzero(todo)[0])}")
    if rest.any():
        part = frame[rest]
        d = d[rest]
        dim = {key: values[rest] for key, values in normal.items()}
        w, v_n, m = d.w, d.v_n, part["mass"].to_numpy()
        radius = 0.5 * part["diameter"].to_numpy()
        alpha, mu = part["inertia_factor"].to_numpy(), part["mu"].to_numpy()
        angle, spin = incidence(part), part["spin"].to_numpy()
        v_t = np.where(angle == 0, 0.0, part["speed"].to_numpy() * np.sin(np.radians(angle)))
        slip0 = v_t - spin * radius
        # friction acts while P > 0, so its impulse is mu J+ with J+ = m v_n (1 - y_p): y_p is the
        # dimensionless rate where P first falls to 0 (at separation if it never pulls); no gravity here
        vc_t, omega, ve_t, slides = impulse_outcome(v_t, spin, m * v_n * (1.0 - dim["y_p"]), m, radius, alpha, mu)
        vc_n = -dim["y_f"] * v_n
        moving = (v_t != 0) | (spin != 0)  # tangential motion at all
        values = {"t_m": dim["tau_m"] / w, "delta_m": dim["x_m"] * v_n / w, "t_f": dim["tau_f"] / w,
                  "vc_t": vc_t, "vc_n": vc_n, "ve_t": ve_t, "ve_n": vc_n, "omega_f": omega, "cor": -dim["y_f"],
                  "switches": np.where(moving & ~slides & (slip0 != 0), 1.0, 0.0),
                  "rebound_angle": np.degrees(np.arctan2(vc_t, vc_n)),
                  "rebound_angle_contact": np.degrees(np.arctan2(ve_t, vc_n)),
                  # no gravity along the flat on these paths: the change of tangential kinetic energy
                  "work_t": 0.5 * m * (vc_t * vc_t - v_t * v_t) + 0.5 * alpha * m * radius * radius * (
                      omega * omega - spin * spin)}
        extras = [key for key in FAMILY_OUTPUTS if key in wanted]
        if extras:
            grips = moving & ~slides
            values |= _history_outputs(part, d, extras, grips, slip0, mu * (1.0 + 1.0 / alpha) * v_n, options)
        for key, value in values.items():
            result[key][rest] = value
        regime[rest] = REGIMES[np.where(~moving, 0, np.where(slides, 1, 2))]
    checked = [key for key in result if key in wanted and key != "t_roll"]
    finite = np.logical_and.reduce([np.isfinite(result[key]) for key in checked]) if checked else np.ones(n, bool)
    if not finite.all():  # never a NaN in a table
        i = int(np.flatnonzero(~finite)[0])
        scene = ", ".join(f"{k}={v}" for k, v in frame.iloc[i].to_dict().items())
        raise ImpactError(f"sweep: no finite outputs for row {i} ({scene}); its contact lies outside what the "
                          "sweep resolves: try `sphereimpact simulate` on that scene")
    beyond = result["delta_m"] > 0.5 * frame["diameter"].to_numpy()  # outside the model, as simulate flags it
    result["switches"] = result["switches"].astype(np.int64)
    outputs = pd.DataFrame(result | {"regime": pd.Series(regime, dtype=object), "beyond_radius": beyond})
    return pd.concat([frame, outputs[[key for key in SWEEP_OUTPUTS if key in wanted]],
                      pd.DataFrame({"path": pd.Series(path, dtype=object)})], axis=1)


def outputs_wanted(outputs) -> set:
    """The outputs asked for (all when None), checked against :data:`SWEEP_OUTPUTS`."""
    if outputs is None:
        return set(SWEEP_OUTPUTS)
    names = [outputs] if isinstance(outputs, str) else list(outputs)
    unknown = [name for name in names if name not in SWEEP_OUTPUTS]
    if unknown or not names:
        got = unknown[0] if unknown else "none"
        raise ValueError(f"outputs must be some of {', '.join(SWEEP_OUTPUTS)}; got {got!r}")
    return set(names)


def _grip_times(normal, impulses: np.ndarray) -> np.ndarray:
    """The instants [s] at which the normal impulse of P+ reaches each of ``impulses`` [N s] (each reached
    by t_f): bracketed on the solver's grid (the impulse never decreases), then Newton's method on
    dJ+/dt = P+, kept inside the bracket, to the last bits."""
    from ..contact.tangential import PositiveImpulse

    impulse = PositiveImpulse(normal)
    times = np.append(normal.grid[normal.grid < normal.t_f], normal.t_f)
    on_grid = impulse(times)
    upper = np.clip(np.searchsorted(on_grid, impulses, side="left"), 1, times.size - 1)
    low, high = times[upper - 1], times[upper]
    j_low, j_high = on_grid[upper - 1], on_grid[upper]
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(j_high > j_low, low + (impulses - j_low) / (j_high - j_low) * (high - low), high)
    for _ in range(GRIP_NEWTON):
        rate = np.maximum(normal.force(t), 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            step = np.where(rate > 0, (impulse(t) - impulses) / rate, 0.0)
        t = np.clip(t - step, low, high)
    return np.where(impulses <= 0, 0.0, t)


def _history_outputs(part: pd.DataFrame, d: Numbers, wanted, grips, slip0, grip_rate, options) -> dict:
    """force_min, force_max and t_roll of scenes on the fast paths, from one single-impact normal solve per
    dimensionless family (model, its numbers, gamma, criterion), scaled to each scene: forces by m v_n / T and
    times by T.  A scene grips when the normal impulse of P+ reaches m |slip0| / (mu (1 + 1/alpha)), which
    ``grip_rate`` = mu (1 + 1/alpha) v_n turns into the family's dimensionless impulse; that instant is found
    on the family's impulse (:func:`_grip_times`)."""
    from ..ode.events import extremum

    n = len(part)
    out = {key: np.full(n, np.nan) for key in wanted}
    w, v_n, m = d.w, d.v_n, part["mass"].to_numpy()
    scale = m * v_n * w  # force scale [N]
    labels = [part["model"].to_numpy(), d.separation, d.gamma, d.zeta, d.lam,
              np.array([str(f) for f in d.family], dtype=object)]
    codes, _ = pd.MultiIndex.from_arrays(labels).factorize()
    target = np.abs(slip0) / np.where(grip_rate > 0, grip_rate, np.inf)  # the dimensionless impulse at grip
    for code in range(codes.max() + 1 if n else 0):
        members = np.flatnonzero(codes == code)
        first = members[0]
        normal = normal_motion(scene_of(part.iloc[first].to_dict()), options)
        if "force_min" in wanted or "force_max" in wanted:
            forces = normal.force(normal.grid)
            for key, kind in (("force_min", "min"), ("force_max", "max")):
                if key in wanted:
                    out[key][members] = extremum(normal.force, normal.grid, kind, forces)[1] / scale[first] * scale[members]
        if "t_roll" in wanted:
            gripping = members[grips[members]]
            if gripping.size:
                out["t_roll"][gripping] = _grip_times(normal, target[gripping] * m[first] * v_n[first]) * (
                    w[first] / w[gripping])
    return out
