"""The sweep engine: a table of scenes in, a table of outcomes out.

Each scene takes the cheapest path that its law declares and that is exact for it
(:class:`sphereimpact.laws.ContactLaw`):

1. a law with the kelvin-voigt closed form, without gravity: the explicit closed form, vectorised
   (:mod:`.closed`);
2. a law on the ``modified`` kernel without gravity, many scenes sharing zeta and criterion (one ball):
   Chebyshev interpolation in lam over the whole sweep's range, checked against the integrator
   (:mod:`.similarity`);
3. the other scenes of the ``modified`` kernel without gravity, at least PLANE_MIN of them with zeta up to
   :data:`.plane.ZETA_MAX` (many balls: k, b, m, D drawn per scene): one Chebyshev interpolant in
   (zeta, lam) over the whole sweep's rectangle, its nodes solved by the batched Taylor lanes
   (:mod:`.plane`);
4. other scenes of a law with a batched kernel, without tangential gravity, in chunks: eq. 4.2 without
   gravity up to critical damping on the batched Taylor lanes (:mod:`.series_lanes`), the rest on the
   batched Runge-Kutta lanes (:mod:`.batch`);
5. a law without a kernel, without tangential gravity: its similarity family (``ContactLaw.family``)
   fixes the dimensionless normal motion.  Without gravity, where at least FAMILY_MIN scenes share all
   but the family's last number (and the criterion), and that number is proportional to the approach
   speed (chi v_n of the Hunt-Crossley laws), a Chebyshev interpolant in it, built like the one in lam
   from single-impact solves and checked (:class:`.similarity.FamilyInterpolant`); otherwise the
   single-impact integrator solves one scene per distinct family (and gamma and criterion) and the
   others are scaled from it;
6. gravity on an inclined flat (stick-slip with re-slip as P falls), or a compliant tangential contact
   (a model not ``batched``: ``linear``, ``mindlin``) at an angle: the single-impact model, scene by scene; so too the scenes the
   lanes would solve at more cost than alone (a cost model on the estimated steps: an over-damped creep
   under the penetration criterion, where one slow lane makes every step of its batch pay).

Tangential velocity, spin and regime follow from the normal impulse as in the
single-impact core.  Results do not depend on the chunk size: every lane is
integrated independently and interpolants are built on the whole sweep.
"""

from __future__ import annotations

import warnings
from dataclasses import fields
from types import SimpleNamespace

import numpy as np
import pandas as pd

from ..errors import BeyondRadiusWarning, ImpactError, InterpolationError
from ..laws import LAWS, PARAMETER_NAMES
from ..parsing import parse_range  # noqa: F401  (re-exported: sweeps take ranges as text)
from ..scene import (PATH_RULES, SEPARATION_CRITERIA, TANGENTIAL_PARAMETERS, TEXT_FIELDS, Scene, SolverOptions,
                     check_columns, scale_problem)
from ..outcome import SCALAR_OUTPUTS
from ..solve import normal_motion, simulate, simulate_many
from ..tangential import TANGENTIALS, impulse_outcome
from . import batch, closed, plane, series_lanes
from .similarity import FamilyInterpolant, LambdaInterpolant, dimensionless_motion

#: Scene parameters, with the single-impact defaults for missing columns.
SCENE_COLUMNS = tuple(f.name for f in fields(Scene))
DEFAULTS = {f.name: f.default for f in fields(Scene)}
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
#: Scenes solved by the single-impact model per call of :func:`~sphereimpact.solve.simulate_many` (a batched
#: tangential kernel runs them together; progress is reported after each).
SINGLES_CHUNK = 100
#: The ``path`` column's values: which path solved a row's normal motion, in the order the engine tries them
#: (its tangential outputs follow from the impulse algebra on every path but ``single``).
PATHS = {
    "single": "simulate, one impact at a time (gravity on a slope, compliant contact, outside the paths below)",
    "family-interpolant": "a kernel-less law's interpolant in its last family number",
    "per-family": "one single-impact solve per dimensionless family, shared by its scenes",
    "closed": "the linear law's closed-form events",
    "lambda-interpolant": "eq. 4.2's interpolant in lam at one damping ratio",
    "plane": "eq. 4.2's interpolant on the (zeta, lam) plane",
    "taylor-lanes": "batched Taylor-series lanes",
    "runge-kutta-lanes": "batched Runge-Kutta lanes",
}
#: The regime column's values, by index.
REGIMES = np.array(["none", "sliding", "rolling"], dtype=object)
#: Path thresholds, each where the faster path changes on the sweep benchmark's scenes: fewest scenes sharing
#: (zeta, criterion) for the lam interpolant; fewest scenes of one criterion for the (zeta, lam) plane; fewest
#: distinct values of a kernel-less law's last family number for interpolating in it.
SIMILARITY_MIN = 2000
PLANE_MIN = 3000
FAMILY_MIN = 200
#: Largest damping ratio the lanes, the similarity path and the closed form take (the accepted domain's edge,
#: where their contract is tested); beyond it an over-damped creep makes a lane's steps unbounded.
LANES_ZETA_MAX = 100.0
#: Largest lam of eq. 4.2 on the Runge-Kutta lanes with gravity or beyond critical damping (beyond it their
#: COR missed the target against scipy's DOP853); such scenes are solved one by one.
LANES_LAM_MAX = 1e4
#: Cost model choosing between the batched lanes and single impacts: a batched step costs LANE_STEP_COST [s]
#: plus LANE_COST per lane; one impact SINGLE_COST plus SINGLE_EVAL_COST per evaluation.  It only chooses a
#: path, never sets an accuracy.
LANE_STEP_COST, LANE_COST = 160e-6, 0.26e-6
SINGLE_COST, SINGLE_EVAL_COST = 1e-3, 2.5e-6


def scene_table(scenes) -> pd.DataFrame:
    """Scene parameters as a DataFrame with every column, validated (ValueError names the first bad row).

    A DataFrame is one scene per row; a dict of values or lists is every combination of them (:func:`grid`),
    as the command line's ranges are."""
    given = grid(**scenes) if isinstance(scenes, dict) else pd.DataFrame(scenes)
    unknown = [c for c in given.columns if c not in SCENE_COLUMNS]
    if unknown:
        raise ValueError(f"unknown scene parameter {unknown[0]!r}; expected some of {', '.join(SCENE_COLUMNS)}")
    n = len(given)
    columns = {name: given[name].to_numpy() if name in given
               else _objects(n, DEFAULTS[name]) if name in TEXT_FIELDS else np.full(n, DEFAULTS[name])
               for name in SCENE_COLUMNS if name in given or DEFAULTS[name] is not None}
    laws = check_columns(columns)  # each row's law parameters: checked, defaults filled, modulus -> k
    columns |= {name: laws[name] for name in PARAMETER_NAMES if name != "modulus"}
    for name in ("modulus", *TANGENTIAL_PARAMETERS, *PATH_RULES):
        columns.setdefault(name, np.full(n, np.nan))
    # text as object columns: pandas' string dtype costs as much to build as the rest of a sweep's overhead
    frame = pd.DataFrame({name: pd.Series(np.asarray(columns[name], dtype=object), dtype=object) if name in TEXT_FIELDS
                          else np.asarray(columns[name], dtype=float) for name in SCENE_COLUMNS})
    paths = ~np.isnan(frame[list(PATH_RULES)].to_numpy())
    for i in np.flatnonzero(paths.any(axis=1) & ((frame["angle"].to_numpy() != 0) | paths.all(axis=1))):
        try:  # one description of the approach per scene: checked as the Scene checks it
            scene_of(frame.iloc[i].to_dict())
        except ValueError as err:
            raise ValueError(f"{err} (row {i})") from None
    tangential = np.column_stack([frame[name].to_numpy() for name in TANGENTIAL_PARAMETERS])
    for i in np.flatnonzero(_compliant(frame) | ~np.isnan(tangential).all(axis=1)):
        try:  # the tangential model's parameters depend on the law: checked as the Scene checks them
            scene = scene_of(frame.iloc[i].to_dict())
        except ValueError as err:
            raise ValueError(f"{err} (row {i})") from None
        frame.loc[frame.index[i], "kappa"] = np.nan if scene.kappa is None else scene.kappa
    return frame


def _objects(n: int, value) -> np.ndarray:
    """An object array of n references to ``value`` (np.full fills object arrays 20x slower)."""
    out = np.empty(n, dtype=object)
    out[:] = value
    return out


def _compliant(frame: pd.DataFrame) -> np.ndarray:
    """Scenes whose tangential model is not ``batched`` (its motion is integrated: solved scene by scene)."""
    names = frame["tangential"].to_numpy()
    out = np.ones(names.shape, dtype=bool)
    for name, model in TANGENTIALS.items():
        if model.batched:
            out &= names != name  # numpy's comparison: pandas' is 4x slower
    return out


def scene_of(row: dict) -> Scene:
    """The Scene of one row of a :func:`scene_table` (its NaN law parameters are the ones its law lacks)."""
    values = {name: (value if name in TEXT_FIELDS else float(value)) for name, value in row.items()}
    for name in PARAMETER_NAMES:
        if name == "modulus" or np.isnan(values[name]):  # k is already resolved from the modulus
            values[name] = None
    for name in PATH_RULES:
        if np.isnan(values[name]):
            values[name] = None
    resolved = not np.isnan(values["kappa"])  # kappa is already resolved from poisson or shear_modulus
    for name in TANGENTIAL_PARAMETERS:
        if np.isnan(values[name]) or (name != "kappa" and resolved):
            values[name] = None
    return Scene(**values)


def incidence(frame: pd.DataFrame) -> np.ndarray:
    """Each scene's incidence from the flat's normal [deg]: its ``incidence``, 90 - ``angle_to_surface``, or
    the flat's tilt ``angle`` for a vertical approach (as :attr:`sphereimpact.Scene.incidence_deg`)."""
    given, surface = frame["incidence"].to_numpy(), frame["angle_to_surface"].to_numpy()
    return np.where(~np.isnan(given), given, np.where(~np.isnan(surface), 90.0 - surface, frame["angle"].to_numpy()))


def _one_by_one(frame: pd.DataFrame) -> np.ndarray:
    """Scenes solved one by one: gravity on an inclined flat (stick-slip with re-slip as P falls), or a
    compliant tangential contact with tangential motion (its tangential motion is integrated)."""
    tangential = (incidence(frame) > 0) | (frame["spin"].to_numpy() != 0)
    return (((frame["gravity"].to_numpy() > 0) & (frame["angle"].to_numpy() > 0))
            | (_compliant(frame) & tangential))


def _series_lanes(d: dict) -> np.ndarray:
    """Scenes the batched Taylor lanes take (:mod:`.series_lanes`): eq. 4.2 without gravity up to critical
    damping and lam 1e12 (their tested domain; faster than the Runge-Kutta lanes, and right at large lam)."""
    with np.errstate(invalid="ignore"):
        return d["modified"] & (d["gamma"] == 0) & series_lanes.covers(d["zeta"], d["lam"]) & np.isfinite(d["w"])


def _beyond_lanes(d: dict) -> np.ndarray:
    """Scenes of a batched kernel or closed form that those paths cannot bound: damping beyond
    :data:`LANES_ZETA_MAX`, dimensionless numbers that are not finite (e.g. mass 1e-300, b 1e300), or lam
    beyond :data:`LANES_LAM_MAX` on the Runge-Kutta lanes.  They go to the single-impact path, whose cost is
    bounded (:data:`sphereimpact.normal.MAX_NFEV`)."""
    with np.errstate(invalid="ignore"):
        wild = ~(np.isfinite(d["zeta"]) & np.isfinite(d["lam"]) & np.isfinite(d["w"]) & np.isfinite(d["gamma"]))
        sharp = d["modified"] & (d["lam"] > LANES_LAM_MAX) & ~_series_lanes(d)
        return d["batched"] & (wild | (d["zeta"] > LANES_ZETA_MAX) | sharp)


def _lane_limit(steps: np.ndarray, alone: np.ndarray) -> float:
    """The most estimated steps a lane may take before the single-impact path is cheaper for it, given each
    lane's estimated steps and cost alone [s] (one criterion).

    The lanes' cost is paid per step until the slowest lane ends (:data:`LANE_STEP_COST`), so a few slow
    lanes (an over-damped creep under the penetration criterion) can cost more than all the others.  The
    scenes are ordered by estimated steps and the slowest move to the single path while that lowers the
    estimated total.
    """
    order = np.argsort(-steps, kind="stable")
    steps, alone = steps[order], alone[order]
    # total cost when the k slowest go alone (k = 0 .. n): theirs, plus the lanes' from the k-th on
    total = (np.concatenate([[0.0], np.cumsum(alone)]) + np.append(steps, 0.0) * LANE_STEP_COST
             + np.append(np.cumsum(steps[::-1])[::-1], 0.0) * LANE_COST)
    best = int(np.argmin(total))
    return float(steps[best]) if best < steps.size else -np.inf


def _solved_alone(frame: pd.DataFrame, d: dict, target: float, limits: dict | None = None) -> tuple[np.ndarray, dict]:
    """(scenes solved one by one, the lane limit per criterion).

    One by one: :func:`_one_by_one` and :func:`_beyond_lanes` scenes, and the scenes the Runge-Kutta lanes
    would integrate (a kernel, not the closed form's nor the Taylor lanes') whose estimated steps
    (:func:`batch.estimated_steps`) exceed their criterion's limit (:func:`_lane_limit`).  The limits are
    computed on these scenes unless ``limits`` is given: a shard takes the whole sweep's (``span``), so shards
    and chunk sizes do not change which path a scene takes.
    """
    alone = _one_by_one(frame) | _beyond_lanes(d)
    lanes = d["batched"] & ~(d["closed"] & (d["gamma"] == 0)) & ~_series_lanes(d) & ~alone  # Runge-Kutta lanes
    computed = {}
    for separation in SEPARATION_CRITERIA:
        mine = np.flatnonzero(lanes & _criterion(d, separation))
        if not mine.size:
            continue
        zeta, lam = d["zeta"][mine], d["lam"][mine]
        steps = batch.estimated_steps(zeta, lam, separation, target)
        if limits is None:
            evaluations = 400.0 + 100.0 * batch.estimated_contact_time(zeta, lam, separation)
            computed[separation] = _lane_limit(steps, SINGLE_COST + SINGLE_EVAL_COST * evaluations)
        alone[mine] |= steps > (computed if limits is None else limits).get(separation, np.inf)
    return alone, computed if limits is None else limits


def _law_view(frame: pd.DataFrame, v_n: np.ndarray) -> SimpleNamespace:
    """The columns a law's vectorised functions read: mass, radius, v_normal and its parameters."""
    return SimpleNamespace(mass=frame["mass"].to_numpy(), radius=0.5 * frame["diameter"].to_numpy(), v_normal=v_n,
                           **{name: frame[name].to_numpy() for name in PARAMETER_NAMES})


def _dimensionless(frame: pd.DataFrame) -> dict:
    """Per scene: w = 1 / T (the law's frequency), v_n, gamma, the kernel's zeta and lam, the law's
    closed form and kernel (``batched``: it has one), its similarity family (as a hashable key; laws without a
    kernel only, None otherwise), and the criterion (``force``: the force criterion's).  The masks are
    compared once here (an elementwise comparison of an object array is not cheap)."""
    beta = np.radians(incidence(frame))
    v_n = frame["speed"].to_numpy() * np.cos(beta)
    n = len(frame)
    w, zeta, lam = np.empty(n), np.zeros(n), np.zeros(n)
    closed_form, kernel, family = (_objects(n, None) for _ in range(3))
    modified, linear = np.zeros(n, bool), np.zeros(n, bool)
    models, separation = frame["model"].to_numpy(), frame["separation"].to_numpy()
    for model in dict.fromkeys(models.tolist()):
        rows = np.flatnonzero(models == model)
        law = LAWS[model]
        if law.kernel is not None and law.kernel not in batch.KERNELS:
            raise ValueError(f"model {model!r} declares kernel {law.kernel!r}, which the batched lanes do not have "
                             f"({', '.join(batch.KERNELS)}); declare kernel=None to be solved per family")
        if law.closed_form is not None and law.closed_form != closed.CLOSED_FORM:
            raise ValueError(f"model {model!r} declares closed form {law.closed_form!r}, which the sweep does not "
                             f"have ({closed.CLOSED_FORM})")
        view = _law_view(frame if rows.size == n else frame.iloc[rows], v_n[rows])
        with np.errstate(all="ignore"):  # extreme rows are refused below, with the row named
            w[rows] = np.broadcast_to(law.frequency(view), rows.shape)
            numbers = {name: np.broadcast_to(np.asarray(value, dtype=float), rows.shape)
                       for name, value in law.family(view).items()}
        problem = scale_problem(view.mass, v_n[rows], w[rows], law, rows)
        if problem:
            raise ValueError(problem)
        closed_form[rows], kernel[rows] = law.closed_form, law.kernel
        modified[rows], linear[rows] = law.kernel == "modified", law.closed_form == closed.CLOSED_FORM
        if law.kernel is not None:  # the batched kernels read zeta and (modified) lam
            zeta[rows] = numbers["zeta"]
            lam[rows] = numbers.get("lam", 0.0)
        if law.kernel is None:  # the family as a key, for the paths of kernel-less laws (10^6 tuples: 0.19 s)
            keys = zip(*numbers.values()) if numbers else [()] * rows.size
            family[rows] = [(model, *values) for values in keys]
    return {"zeta": zeta, "w": w, "v_n": v_n, "lam": lam,
            # gravity along the normal of the flat, tilted by `angle` (w v_n: normal, see scale_problem)
            "gamma": frame["gravity"].to_numpy() * np.cos(np.radians(frame["angle"].to_numpy())) / (w * v_n),
            "modified": modified, "closed": linear, "kernel": kernel, "batched": kernel != None,  # noqa: E711
            "family": family, "separation": separation, "force": separation == "force"}


def _criterion(d: dict, separation: str) -> np.ndarray:
    """Scenes of ``d`` (see :func:`_dimensionless`) under the criterion ``separation``."""
    return d["force"] if separation == "force" else ~d["force"]


def _interpolants(d: dict, target: float) -> dict:
    """(zeta, separation) -> LambdaInterpolant for every group of the span's scenes ``d`` (see
    :func:`_dimensionless`) large enough to pay off."""
    similar = np.flatnonzero(d["modified"] & (d["gamma"] == 0))
    interpolants = {}
    for criterion in SEPARATION_CRITERIA:
        mine = similar[_criterion(d, criterion)[similar]]
        zetas, group, counts = np.unique(d["zeta"][mine], return_inverse=True, return_counts=True)
        for i in np.flatnonzero(counts >= SIMILARITY_MIN):
            lam = d["lam"][mine[group == i]]
            try:
                interpolants[(float(zetas[i]), criterion)] = LambdaInterpolant(float(zetas[i]), lam.min(), lam.max(),
                                                                               criterion, target)
            except InterpolationError:  # such a group is integrated scene by scene instead
                continue
    return interpolants


def _plane_scenes(d: dict, interpolants: dict, separation: str) -> np.ndarray:
    """Scenes of ``d`` (one criterion) the (zeta, lam) plane may take: the modified kernel without gravity,
    not taken by a one-ball interpolant, within the plane's zeta and lam ranges."""
    one_ball = np.isin(d["zeta"], [z for z, criterion in interpolants if criterion == separation])
    return np.flatnonzero(d["modified"] & (d["gamma"] == 0) & _criterion(d, separation) & ~one_ball
                          & (d["zeta"] > 0) & (d["zeta"] <= plane.ZETA_MAX)
                          & (d["lam"] >= plane.LAM_MIN) & (d["lam"] <= plane.LAM_MAX))


def _plane_groups(d: dict, interpolants: dict) -> dict:
    """separation -> :func:`_plane_scenes` of ``d``."""
    return {separation: _plane_scenes(d, interpolants, separation) for separation in SEPARATION_CRITERIA}


def _planes(d: dict, groups: dict, target: float) -> dict:
    """separation -> PlaneInterpolant on the span's scenes ``d`` where at least PLANE_MIN may take it
    (``groups``: their :func:`_plane_groups`)."""
    built = {}
    for separation, mine in groups.items():
        if mine.size >= PLANE_MIN:
            zeta, lam = d["zeta"][mine], d["lam"][mine]
            try:
                built[separation] = plane.PlaneInterpolant(zeta.min(), zeta.max(), lam.min(), lam.max(), separation,
                                                           target)
            except InterpolationError:  # integrated by the lanes instead
                continue
    return built


def _family_groups(d: dict) -> dict:
    """(model, the family's other numbers, criterion) -> indices of the kernel-less weightless scenes of
    ``d`` with a positive last family number, the one :class:`FamilyInterpolant` interpolates in."""
    groups: dict = {}
    for i in np.flatnonzero(~d["batched"] & (d["gamma"] == 0)):
        family = d["family"][i]
        if len(family) > 1 and family[-1] > 0:
            groups.setdefault((*family[:-1], d["separation"][i]), []).append(i)
    return groups


def _family_interpolants(span: dict, span_frame: pd.DataFrame, groups: dict, target: float) -> dict:
    """Group key (see :func:`_family_groups`) -> FamilyInterpolant, for the span's ``groups`` (its
    :func:`_family_groups`) with at least FAMILY_MIN distinct numbers, built from the group's first scene in
    the span and its whole range."""
    built = {}
    for key, rows in groups.items():
        q = np.array([span["family"][i][-1] for i in rows])
        if np.unique(q).size < FAMILY_MIN:
            continue
        try:
            built[key] = FamilyInterpolant(scene_of(span_frame.iloc[rows[0]].to_dict()), float(q.min()),
                                           float(q.max()), key[-1], target)
        except InterpolationError:  # such a group is solved family by family
            continue
    return built


def _normal_outputs(d: dict, span: dict, span_frame: pd.DataFrame, target: float, chunk_size: int, progress,
                    frame: pd.DataFrame) -> dict:
    """Dimensionless normal outputs of the scenes ``frame`` (``d`` as :func:`_dimensionless` gives them),
    interpolants built on the scenes ``span`` (whose table is ``span_frame``)."""
    zeta, lam, gamma, modified = d["zeta"], d["lam"], d["gamma"], d["modified"]
    interpolants = _interpolants(span, target)
    plane_groups = _plane_groups(d, interpolants)
    planes = _planes(span, plane_groups if span is d else _plane_groups(span, interpolants), target)
    out = {key: np.full(zeta.size, np.nan) for key in ("tau_m", "x_m", "tau_f", "y_f", "y_p")}
    path = _objects(zeta.size, "")
    todo = np.ones(zeta.size, bool)
    series = _series_lanes(d)
    groups = _family_groups(d)
    span_groups = groups if span is d else _family_groups(span)  # one pass when the scenes are the span
    family_interpolants = _family_interpolants(span, span_frame, span_groups, target)
    for key, rows in groups.items():
        if key in family_interpolants:
            rows = np.array(rows)
            _put(out, rows, family_interpolants[key](np.array([d["family"][i][-1] for i in rows])))
            path[rows] = "family-interpolant"
            todo[rows] = False
    by_family = np.flatnonzero(~d["batched"] & todo)
    if by_family.size:
        _put(out, by_family, _family_outputs(frame.iloc[by_family], d["family"][by_family],
                                             d["gamma"][by_family], target))
        path[by_family] = "per-family"
        todo[by_family] = False
    for separation in ("force", "penetration"):
        sep = _criterion(d, separation)
        linear = sep & d["closed"] & (gamma == 0)
        if linear.any():
            _put(out, linear, closed.events(zeta[linear], separation))
            path[linear] = "closed"
            todo &= ~linear
        for (z, criterion), interpolant in interpolants.items():
            group = np.flatnonzero((criterion == separation) & sep & modified & (gamma == 0) & (zeta == z))
            outside = group[(lam[group] < interpolant.lo) | (lam[group] > interpolant.hi)]
            if outside.size:  # a span that does not cover its shard: interpolation would extrapolate
                raise ValueError(f"span does not cover the scenes: scene {int(outside[0])} has lam = "
                                 f"{lam[outside[0]]:.6g} outside the span's [{interpolant.lo:.6g}, "
                                 f"{interpolant.hi:.6g}]; pass the whole sweep as span")
            for start in range(0, group.size, chunk_size):  # evaluated in chunks: memory stays bounded
                i = group[start:start + chunk_size]
                _put(out, i, interpolant(lam[i]))
            path[group] = "lambda-interpolant"
            todo[group] = False
        if separation in planes:
            group = plane_groups[separation]
            interpolant = planes[separation]
            outside = group[(zeta[group] < interpolant.zeta_min) | (zeta[group] > interpolant.zeta_max)
                            | (lam[group] < interpolant.lam_min) | (lam[group] > interpolant.lam_max)]
            if outside.size:
                raise ValueError(f"span does not cover the scenes: scene {int(outside[0])} (zeta = "
                                 f"{zeta[outside[0]]:.6g}, lam = {lam[outside[0]]:.6g}) lies outside the span's plane; "
                                 "pass the whole sweep as span")
            for start in range(0, group.size, chunk_size):
                i = group[start:start + chunk_size]
                _put(out, i, interpolant(zeta[i], lam[i]))
            path[group] = "plane"
            todo[group] = False
        rest = np.concatenate([np.flatnonzero(todo & sep & series), np.flatnonzero(todo & sep & ~series)])
        for start in range(0, rest.size, chunk_size):
            i = rest[start:start + chunk_size]
            taylor, runge_kutta = i[series[i]], i[~series[i]]
            if taylor.size:
                _put(out, taylor, series_lanes.integrate(zeta[taylor], lam[taylor], separation, target))
                path[taylor] = "taylor-lanes"
            if runge_kutta.size:
                _put(out, runge_kutta, batch.integrate(zeta[runge_kutta], lam[runge_kutta], gamma[runge_kutta],
                                                       modified[runge_kutta], separation, target))
                path[runge_kutta] = "runge-kutta-lanes"
            if progress:
                progress(min(start + chunk_size, rest.size), rest.size)
    return out | {"path": path}


def _family_outputs(frame: pd.DataFrame, family: np.ndarray, gamma: np.ndarray, target: float) -> dict:
    """Dimensionless normal outputs of scenes whose law has no batched kernel: the single-impact integrator
    (exact for every law) solves the first scene of each distinct (family, gamma, criterion), and the
    others, which share its dimensionless motion, take its values."""
    options = SolverOptions(rtol=min(1e-10, target / 100), atol=min(1e-10, target / 100))
    keys = [(*f, float(g), sep) for f, g, sep in zip(family, gamma, frame["separation"].to_numpy())]
    first: dict = {}
    for i, key in enumerate(keys):
        first.setdefault(key, i)
    solved = {key: dimensionless_motion(scene_of(frame.iloc[i].to_dict()), options) for key, i in first.items()}
    return {name: np.array([solved[key][name] for key in keys]) for name in ("tau_m", "x_m", "tau_f", "y_f", "y_p")}


def _put(out: dict, where, values: dict) -> None:
    for key in out:
        out[key][where] = values[key]


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
    regime, path = _objects(n, "none"), _objects(n, "single")
    d_all = _dimensionless(frame)
    whole = frame if span is None else scene_table(span)
    d_whole = d_all if span is None else _dimensionless(whole)
    alone_whole, limits = _solved_alone(whole, d_whole, target)
    single = alone_whole if span is None else _solved_alone(frame, d_all, target, limits)[0]
    singles = np.flatnonzero(single)
    options = SolverOptions(rtol=min(1e-10, target / 100), atol=min(1e-10, target / 100), elements=elements,
                            time_steps=time_steps)
    for start in range(0, singles.size, SINGLES_CHUNK):  # stick-slip with re-slip, compliance, extremes
        rows = singles[start:start + SINGLES_CHUNK]
        scenes = [scene_of(frame.iloc[i].to_dict()) for i in rows]
        with warnings.catch_warnings():  # the table flags delta_m > R in its beyond_radius column
            warnings.simplefilter("ignore", BeyondRadiusWarning)
            try:
                outs = simulate_many(scenes, options)
            except ImpactError:
                _raise_for_first_failure(rows, scenes, options)
                raise
        for i, out in zip(rows, outs):
            for key in result:
                value = getattr(out, key)
                result[key][i] = np.nan if value is None else value
            regime[i] = out.regime
        if progress:
            progress(start + rows.size, singles.size)
    rest = ~single
    if rest.any():
        part = frame[rest]
        d = {key: values[rest] for key, values in d_all.items()}
        if span is None:
            d_span, span_part = d, part
        else:
            keep = ~alone_whole
            d_span, span_part = {key: values[keep] for key, values in d_whole.items()}, whole[keep]
        dim = _normal_outputs(d, d_span, span_part, target, chunk_size, progress, part)
        w, v_n, m = d["w"], d["v_n"], part["mass"].to_numpy()
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
        path[rest] = dim["path"]
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
    from ..tangential import PositiveImpulse

    impulse = PositiveImpulse(normal)
    grid = np.append(normal.grid[normal.grid < normal.t_f], normal.t_f)
    on_grid = impulse(grid)
    upper = np.clip(np.searchsorted(on_grid, impulses, side="left"), 1, grid.size - 1)
    low, high = grid[upper - 1], grid[upper]
    j_low, j_high = on_grid[upper - 1], on_grid[upper]
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.where(j_high > j_low, low + (impulses - j_low) / (j_high - j_low) * (high - low), high)
    for _ in range(GRIP_NEWTON):
        rate = np.maximum(normal.force(t), 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            step = np.where(rate > 0, (impulse(t) - impulses) / rate, 0.0)
        t = np.clip(t - step, low, high)
    return np.where(impulses <= 0, 0.0, t)


def _history_outputs(part: pd.DataFrame, d: dict, wanted, grips, slip0, grip_rate, options) -> dict:
    """force_min, force_max and t_roll of scenes on the fast paths, from one single-impact normal solve per
    dimensionless family (model, its numbers, gamma, criterion), scaled to each scene: forces by m v_n / T and
    times by T.  A scene grips when the normal impulse of P+ reaches m |slip0| / (mu (1 + 1/alpha)), which
    ``grip_rate`` = mu (1 + 1/alpha) v_n turns into the family's dimensionless impulse; that instant is found
    on the family's impulse (:func:`_grip_times`)."""
    from ..events import extremum

    n = len(part)
    out = {key: np.full(n, np.nan) for key in wanted}
    w, v_n, m = d["w"], d["v_n"], part["mass"].to_numpy()
    scale = m * v_n * w  # force scale [N]
    labels = [part["model"].to_numpy(), d["separation"], d["gamma"], d["zeta"], d["lam"],
              np.array([str(f) for f in d["family"]], dtype=object)]
    codes, _ = pd.MultiIndex.from_arrays(labels).factorize()
    target = np.abs(slip0) / np.where(grip_rate > 0, grip_rate, np.inf)  # the dimensionless impulse at grip
    for code in range(codes.max() + 1 if n else 0):
        rows = np.flatnonzero(codes == code)
        first = rows[0]
        normal = normal_motion(scene_of(part.iloc[first].to_dict()), options)
        if "force_min" in wanted or "force_max" in wanted:
            forces = normal.force(normal.grid)
            for key, kind in (("force_min", "min"), ("force_max", "max")):
                if key in wanted:
                    out[key][rows] = extremum(normal.force, normal.grid, kind, forces)[1] / scale[first] * scale[rows]
        if "t_roll" in wanted:
            gripping = rows[grips[rows]]
            if gripping.size:
                out["t_roll"][gripping] = _grip_times(normal, target[gripping] * m[first] * v_n[first]) * (
                    w[first] / w[gripping])
    return out


def _raise_for_first_failure(rows, scenes, options) -> None:
    """Raise the ImpactError of the first of ``scenes`` that fails alone, naming its sweep row."""
    for i, scene in zip(rows, scenes):
        try:
            simulate(scene, options)
        except ImpactError as err:
            raise ImpactError(f"sweep row {i}: {err}") from None


def rows(**columns) -> pd.DataFrame:
    """Scenes row by row: the i-th scene takes the i-th value of every column (equal lengths; a single value
    is repeated).  :func:`grid` takes every combination instead."""
    lengths = {name: np.size(values) for name, values in columns.items()}
    longest = max(lengths.values(), default=0)
    if any(length not in (1, longest) for length in lengths.values()):
        listed = ", ".join(f"{name} ({length})" for name, length in lengths.items())
        raise ValueError(f"scene columns must have the same length; got {listed}")
    listed = {name: list(values) if np.ndim(values) else [values] for name, values in columns.items()}
    return pd.DataFrame({name: values * longest if len(values) == 1 else values for name, values in listed.items()})


def grid(**ranges) -> pd.DataFrame:
    """Every combination of parameter values, one row per scene (the first parameter varies slowest): what a
    dict given to :func:`sweep` and the command line's ranges mean.  :func:`rows` pairs values instead."""
    names = list(ranges)
    mesh = np.meshgrid(*[np.atleast_1d(ranges[n]) for n in names], indexing="ij")
    return pd.DataFrame({n: m.ravel() for n, m in zip(names, mesh)})
