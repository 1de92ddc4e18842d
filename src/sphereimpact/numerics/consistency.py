"""One answer whatever the path: seeded random scenes across the accepted domain, mixed in one table, swept,
and every row compared with ``simulate`` of its scene (the differential test of the sweep's paths).

The scenes (:func:`random_scenes`) draw every law with its own parameters (a Hertz law by k or by modulus),
every tangential model a sweep serves, spin of both signs, gravity on level and sloped flats, the three ways
of giving the approach (the flat's tilt, the incidence, the angle to the surface), both separation criteria,
and mass, size and speed over decades; every description is written as a table a user may write, an empty
cell meaning "not given".  Balls come in groups of scenes (one ball at many angles and speeds, as a map
asks), so that the interpolants' paths take rows too.  :func:`compare` sweeps the table and measures every
row against ``simulate`` (at rtol 1e-12, :data:`REFERENCE`) on every
output, in the measure of :func:`sphereimpact.numerics.reference.relative_errors`; :func:`summary` tabulates the
worst error per path, law and tangential model.  The test suite runs a few thousand rows (tests/
test_consistency.py, every path also forced alone); the pipeline at least 10^5 (``results/consistency.csv``).
"""

from __future__ import annotations

import logging
import warnings
from types import SimpleNamespace

import numpy as np
import pandas as pd

from ..contact.laws import LAWS, Spring
from ..contact.separation import Separation
from ..errors import BeyondRadiusWarning, EnergyGainWarning, ImpactError
from ..impact.outcome import NUMERIC_OUTPUTS, SCALAR_OUTPUTS
from ..impact.scene import SolverOptions
from ..impact.solve import simulate
from ..sweep.engine import SCENE_COLUMNS, scene_of, sweep
from ..sweep.paths import single_options
from ..sweep.scenes import law_view, numbers, scene_columns
from .reference import output_scales

log = logging.getLogger(__name__)
#: The outputs compared (every scalar output; regime and beyond_radius must be equal).
COMPARED = NUMERIC_OUTPUTS
#: The reference's options (see :func:`references`).
REFERENCE = SolverOptions(rtol=1e-12, atol=1e-12)
#: Largest dimensionless gravity g_n / (w v_n) drawn (see :func:`random_scenes`).
GRAVITY_SHARE = 0.05
#: Share of the balls with a compliant tangential model (solved by simulate itself in a sweep: the single path).
COMPLIANT_SHARE = 0.05
#: Share of the compliant contacts with a stiff tangential spring, kappa log-uniform in STIFF_KAPPA: microslip then
#: needs more time steps than its default, so the table mixes resolutions in one batch of the single path.
STIFF_SHARE = 0.1
STIFF_KAPPA = (20.0, 200.0)
#: Tangential models by the spring they need: a compliant scene draws one that serves its law.
COMPLIANT = {Spring.LINEAR: ("linear",), Spring.HERTZ: ("mindlin", "mindlin-displacement", "microslip")}


def _loguniform(rng, low: float, high: float, n: int) -> np.ndarray:
    return np.exp(rng.uniform(np.log(low), np.log(high), n))


def _balls(rng, n: int) -> pd.DataFrame:
    """``n`` random balls: mass, size, law and its parameters, friction, criterion, tangential model."""
    models = np.array(sorted(LAWS))
    model = rng.choice(models, n)
    mass, diameter = _loguniform(rng, 0.005, 2.0, n), _loguniform(rng, 0.005, 0.3, n)
    pulls = rng.uniform(size=n) < 0.3
    separation = np.where(pulls, Separation.PENETRATION.value, Separation.FORCE.value)
    spring = np.array([LAWS[m].spring for m in model])
    k_linear = _loguniform(rng, 1e3, 1e7, n)
    zeta = np.where(pulls, _loguniform(rng, 1e-3, 0.9, n), _loguniform(rng, 1e-3, 3.0, n))
    zeta[rng.uniform(size=n) < 0.05] = 0.0  # undamped
    modulus = _loguniform(rng, 1e6, 1e10, n)
    by_modulus = rng.uniform(size=n) < 0.5
    k_hertz = 4.0 / 3.0 * modulus * np.sqrt(0.5 * diameter)
    table = pd.DataFrame({
        "mass": mass, "diameter": diameter, "inertia_factor": rng.uniform(0.2, 2 / 3, n),
        "mu": np.where(rng.uniform(size=n) < 0.1, 0.0, rng.uniform(0.0, 0.8, n)), "model": model,
        "k": np.where(spring == Spring.LINEAR, k_linear, np.where(by_modulus, np.nan, k_hertz)),
        "modulus": np.where((spring == Spring.HERTZ) & by_modulus, modulus, np.nan),
        "b": np.where(np.isin(model, ["kelvin-voigt", "modified"]), 2.0 * zeta * np.sqrt(k_linear * mass), np.nan),
        "ramp": np.where(model == "modified", _loguniform(rng, 20.0, 500.0, n), np.nan),
        "chi": np.where(np.isin(model, ["hunt-crossley", "linear-hunt-crossley"]), _loguniform(rng, 1e-3, 0.3, n),
                        np.nan),
        "exponent": np.where((model == "hunt-crossley") & (rng.uniform(size=n) < 0.3), rng.uniform(1.2, 2.0, n),
                             np.nan),
        "separation": separation})
    hertzian = (spring == Spring.HERTZ) & np.isnan(table["exponent"].to_numpy())  # exponent 3/2: the Hertz models
    compliant = rng.uniform(size=n) < COMPLIANT_SHARE
    tangential = np.full(n, "rigid", dtype=object)
    for i in np.flatnonzero(compliant & ((spring == Spring.LINEAR) | hertzian)):
        tangential[i] = rng.choice(COMPLIANT[spring[i]])
    table["tangential"] = tangential
    stiff = rng.uniform(size=n) < STIFF_SHARE
    kappa = np.where(stiff, _loguniform(rng, *STIFF_KAPPA, n), rng.uniform(0.5, 1.2, n))
    table["kappa"] = np.where(tangential != "rigid", kappa, np.nan)
    return table


def _approaches(rng, diameter: np.ndarray) -> pd.DataFrame:
    """One random approach for each ball of diameter ``diameter`` [m]: speed, one description of the
    direction (tilt, incidence or angle to the surface), spin of either sign, gravity on or off."""
    n = diameter.size
    speed = _loguniform(rng, 0.2, 40.0, n)
    way = rng.choice(3, n)
    direction = rng.uniform(0.0, 85.0, n)
    direction[rng.uniform(size=n) < 0.08] = 0.0  # a normal approach
    spin = np.where(rng.uniform(size=n) < 0.5, 0.0, rng.uniform(-1.5, 1.5, n) * speed / (0.5 * diameter))
    return pd.DataFrame({
        "speed": speed, "angle": np.where(way == 0, direction, np.nan),
        "incidence": np.where(way == 1, direction, np.nan),
        "angle_to_surface": np.where(way == 2, 90.0 - direction, np.nan),
        "spin": spin, "gravity": np.where(rng.uniform(size=n) < 0.3, 9.80665, 0.0)})


#: The groups of :func:`random_scenes`, in turn: one ball of each law an interpolant serves at many angles
#: and speeds (eq. 4.2: the lam interpolant; the Hunt-Crossley laws: the family interpolant), many balls
#: of eq. 4.2 at one scene each (the (zeta, lam) plane), and one elastic Hertz ball of a compliant tangential
#: contact over a few incidences and many speeds (a map: the similar-scenes path).
GROUPS = ("modified", "hunt-crossley", "linear-hunt-crossley", "many modified balls", "compliant map")
#: Most scenes of the compliant map's group (each reference is one compliant impact, milliseconds each).
COMPLIANT_MAP_ROWS = 400


def _group_balls(kind: str, rng, n: int) -> pd.DataFrame:
    """``n`` balls of a group (see :data:`GROUPS`): the law's parameters drawn as for any ball, eq. 4.2 at a
    damping ratio up to 0.5 (the plane's domain), a rigid contact; the many balls are sports balls, so that
    the plane's rectangle spans a few decades of lam."""
    model = {"many modified balls": "modified", "compliant map": "hertz"}.get(kind, kind)
    balls = _balls(rng, n).assign(model=model, tangential="rigid", kappa=np.nan, k=np.nan, modulus=np.nan,
                                  b=np.nan, ramp=np.nan, chi=np.nan, exponent=np.nan)
    if kind == "compliant map":
        return balls.assign(modulus=_loguniform(rng, 1e6, 1e10, n), kappa=rng.uniform(0.5, 1.2, n),
                            tangential=rng.choice(COMPLIANT[Spring.HERTZ], n))
    if kind == "many modified balls":
        balls = balls.assign(mass=rng.uniform(0.05, 0.5, n), diameter=rng.uniform(0.04, 0.08, n), ramp=100.0,
                             k=rng.uniform(2e4, 2e5, n))
    elif model == "modified":
        balls = balls.assign(k=_loguniform(rng, 1e3, 1e7, n), ramp=_loguniform(rng, 20.0, 500.0, n))
    if model == "modified":
        balls["b"] = 2.0 * rng.uniform(0.01, 0.5, n) * np.sqrt(balls["k"] * balls["mass"])
    elif model == "hunt-crossley":
        balls = balls.assign(modulus=_loguniform(rng, 1e6, 1e10, n), chi=_loguniform(rng, 1e-3, 0.3, n))
    else:
        balls = balls.assign(k=_loguniform(rng, 1e3, 1e7, n), chi=_loguniform(rng, 1e-3, 0.3, n))
    return balls


def random_scenes(n: int, seed: int = 0, groups: int = len(GROUPS), group_size: int = 0) -> pd.DataFrame:
    """``n`` random scenes (see the module docstring), shuffled: ``groups`` groups of ``group_size`` scenes
    (:data:`GROUPS` in turn; default: a quarter of ``n`` between them), the rest one to four scenes per ball.

    A group's scenes are weightless, of a rigid contact, and of eq. 4.2 at damping ratios up to 0.5 or of a
    Hunt-Crossley law, so that a table large enough takes the interpolants.
    """
    rng = np.random.default_rng(seed)
    group_size = group_size or max(1, n // (4 * max(groups, 1)))
    parts, left = [], n
    for g in range(groups):
        kind = GROUPS[g % len(GROUPS)]
        size = min(group_size, left, COMPLIANT_MAP_ROWS if kind == "compliant map" else left)
        if size <= 0:
            break
        balls = _group_balls(kind, rng, size if kind == "many modified balls" else 1)
        balls = balls.loc[np.zeros(size, int) if len(balls) == 1 else np.arange(size)].reset_index(drop=True)
        scenes = _approaches(rng, balls["diameter"].to_numpy())
        if kind == "many modified balls":
            scenes["speed"] = rng.uniform(0.5, 30.0, size)
        if kind == "compliant map":  # a few incidences, each at many speeds: scenes alike but for their scales
            scenes = scenes.assign(angle=np.nan, angle_to_surface=np.nan, spin=0.0,
                                   incidence=rng.choice(rng.uniform(1.0, 85.0, 8), size))
        parts.append(pd.concat([balls, scenes.assign(gravity=0.0)], axis=1))
        left -= size
    if left > 0:  # one to four scenes per ball
        counts = rng.integers(1, 5, left)
        counts = counts[:np.searchsorted(np.cumsum(counts), left) + 1]
        counts[-1] -= counts.sum() - left
        balls = _balls(rng, counts.size).loc[np.repeat(np.arange(counts.size), counts)].reset_index(drop=True)
        parts.append(pd.concat([balls, _approaches(rng, balls["diameter"].to_numpy())], axis=1))
    table = pd.concat(parts, ignore_index=True)
    table["gravity"] = _gravity_where_it_bounces(table)
    return table.iloc[rng.permutation(len(table))].reset_index(drop=True)


def _gravity_where_it_bounces(table: pd.DataFrame) -> np.ndarray:
    """The table's gravity, off where the ball would not bounce: a weight comparable with the contact's force,
    or damping beyond critical, keeps it on the flat (no separation: outside what a bounce is); and where the
    weight alone would compress the contact beyond the radius (a scene refuses that)."""
    weight = table["gravity"].to_numpy().copy()
    frame = scene_columns(table.assign(gravity=0.0))
    d = numbers(frame)
    tilt = np.radians(frame["angle"])
    gamma = weight * np.cos(tilt) / (d.w * d.v_n)
    zeta = np.where(np.isnan(table["b"]), 0.0, d.zeta)  # the linear damping's ratio (eq. 4.1, 4.2)
    chi_v = np.where(np.isnan(table["chi"]), 0.0, table["chi"] * d.v_n)  # Hunt-Crossley's damping number
    weight[(gamma > GRAVITY_SHARE) | (zeta > 1.0) | (chi_v > 1.0)] = 0.0
    radius = 0.5 * frame["diameter"]
    models = frame["model"]
    for model in dict.fromkeys(models.tolist()):  # the spring at delta = R must hold the weight
        rows = np.flatnonzero((models == model) & (weight > 0))
        if rows.size:
            view = law_view(frame.take(rows), d.v_n[rows])
            holds = LAWS[model].force(radius[rows], np.zeros(rows.size), view)
            weight[rows[holds < frame["mass"][rows] * weight[rows] * np.cos(tilt[rows])]] = 0.0
    return weight


def references(table: pd.DataFrame) -> pd.DataFrame:
    """``simulate`` of every scene of ``table`` at :data:`REFERENCE` (the tolerance the sweep's accuracy
    tests take: at the default 1e-10 a grip near the end of the contact, where the impulse levels off, is
    itself off by up to 3e-8 of t_f): one row per scene, in order, of its outputs (:data:`SCALAR_OUTPUTS`, NaN
    t_roll where it never grips) and ``refused``, simulate's message where it refuses the scene (outside the
    accepted domain: not compared), else ''."""
    frame = scene_columns(table)
    rows = []
    with warnings.catch_warnings():  # compressions beyond the radius, energy made: flagged in both, not warned
        warnings.simplefilter("ignore", BeyondRadiusWarning)
        warnings.simplefilter("ignore", EnergyGainWarning)
        for row in frame.records():
            try:
                outcome = simulate(scene_of(row), REFERENCE)
            except ImpactError as err:
                rows.append({"refused": str(err)})
                continue
            values = {key: getattr(outcome, key) for key in SCALAR_OUTPUTS}
            rows.append(values | {"t_roll": np.nan if outcome.t_roll is None else outcome.t_roll, "refused": ""})
    return pd.DataFrame(rows, columns=[*SCALAR_OUTPUTS, "refused"])


def compare(table: pd.DataFrame, reference: pd.DataFrame, swept: pd.DataFrame | None = None,
            target: float = 1e-8) -> pd.DataFrame:
    """Each row of ``swept`` (the sweep of ``table``, swept here when not given) against ``reference``
    (:func:`references` of the same rows, none refused): the row's path, law and tangential model, its worst
    relative error over :data:`COMPARED` (the measure of :func:`~.reference.relative_errors`, on every row at
    once) and on which output, and whether regime and beyond_radius agree.  A row of the single-impact path is
    ``simulate`` itself at the sweep's options (which are the reference's at the default target: it must
    equal it to the bit; simulate's own accuracy is the work-precision study's); rows no path took (a sweep
    restricted to some paths) are left out."""
    if (reference["refused"] != "").any():
        raise ValueError("compare: leave out the scenes simulate refuses (reference['refused'])")
    swept = sweep(table, target=target, chapter_ball=True) if swept is None else swept  # as simulate takes them
    taken = np.flatnonzero(swept["path"].to_numpy() != "")
    got, ref = swept.iloc[taken].reset_index(drop=True), reference.iloc[taken].reset_index(drop=True).copy()
    alone = single_options(target)
    if alone != REFERENCE:  # the single path's rows: simulate at the sweep's own options
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", BeyondRadiusWarning)
            warnings.simplefilter("ignore", EnergyGainWarning)
            for i in np.flatnonzero(got["path"].to_numpy() == "single"):
                outcome = simulate(scene_of(got.loc[i, list(SCENE_COLUMNS)].to_dict()), alone)
                for key in COMPARED:
                    value = getattr(outcome, key)
                    ref.loc[i, key] = np.nan if value is None else value
    ball = SimpleNamespace(speed=got["speed"].to_numpy(), radius=0.5 * got["diameter"].to_numpy(),
                           mass=got["mass"].to_numpy())
    scales = output_scales(ball, ref["t_f"].to_numpy(), ref["delta_m"].to_numpy(), ref["force_max"].to_numpy())
    errors = np.empty((len(COMPARED), len(got)))
    for k, key in enumerate(COMPARED):
        a, b = got[key].to_numpy(dtype=float), ref[key].to_numpy(dtype=float)
        with np.errstate(invalid="ignore"):
            errors[k] = np.abs(a - b) / np.maximum(np.abs(b), scales[key])
        errors[k] = np.where(np.isnan(a) & np.isnan(b), 0.0, np.where(np.isnan(a) | np.isnan(b), np.inf, errors[k]))
    worst = np.argmax(errors, axis=0)
    return pd.DataFrame({"row": taken, "path": got["path"], "model": got["model"], "tangential": got["tangential"],
                         "error": errors[worst, np.arange(len(got))], "output": np.array(COMPARED)[worst],
                         "regime_agrees": got["regime"].to_numpy() == ref["regime"].to_numpy(),
                         "beyond_radius_agrees": got["beyond_radius"].to_numpy(bool) == ref["beyond_radius"].to_numpy(bool)})


def summary(errors: pd.DataFrame) -> pd.DataFrame:
    """Per path, law and tangential model: rows, the worst relative error and its output, and the rows whose
    regime or beyond_radius disagree."""
    def worst(group):
        top = group.loc[group["error"].idxmax()]
        return pd.Series({"rows": len(group), "worst_error": top["error"], "worst_output": top["output"],
                          "regime_disagrees": int((~group["regime_agrees"]).sum()),
                          "beyond_radius_disagrees": int((~group["beyond_radius_agrees"]).sum())})

    return (errors.groupby(["path", "model", "tangential"], sort=True).apply(worst, include_groups=False)
            .reset_index())


def reference_shard(rows: int, seed: int, shard: int, shards: int) -> pd.DataFrame:
    """:func:`references` of one of ``shards`` contiguous blocks of :func:`random_scenes` (``rows``,
    ``seed``), with each scene's ``row`` in the whole table (the pipeline's jobs share the references' cost)."""
    table = random_scenes(rows, seed=seed)
    block = np.array_split(np.arange(len(table)), shards)[shard]
    return references(table.iloc[block]).assign(row=block)


def run(csv_path: str, reference_files, rows: int, seed: int = 0, target: float = 1e-8) -> pd.DataFrame:
    """The pipeline's differential test: :func:`random_scenes` (``rows``, ``seed``) with the references of
    ``reference_files`` (:func:`reference_shard`), those simulate solves swept in one table and compared row
    by row; writes the summary (:func:`summary`, one row ``refused by simulate`` counting the others) to
    ``csv_path``."""
    table = random_scenes(rows, seed=seed)
    reference = pd.concat([pd.read_parquet(path) for path in reference_files]).sort_values("row")
    solved = reference["refused"] == ""
    kept = reference["row"].to_numpy()[solved.to_numpy()]
    log.info("consistency: %d random scenes, %d refused by simulate (outside the accepted domain)", rows,
             int((~solved).sum()))
    errors = compare(table.iloc[kept].reset_index(drop=True),
                     reference[solved].drop(columns="row").reset_index(drop=True), target=target)
    frame = summary(errors)
    refused = pd.DataFrame([{"path": "refused by simulate", "model": "", "tangential": "",
                             "rows": int((~solved).sum())}])
    frame = pd.concat([frame, refused], ignore_index=True)
    frame.to_csv(csv_path, index=False, float_format="%.3g")
    log.info("consistency: worst relative error %.3g over %d rows", errors["error"].max(), len(errors))
    return frame
