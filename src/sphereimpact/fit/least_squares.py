"""Fit a ball's parameters to measured bounces: weighted least squares with honest uncertainties.

The model of every bounce is :func:`sphereimpact.sweep.sweep` (``simulate``'s answer to the sweep's target) of
the ball with the free parameters changed; a ball calibrated to a measured COR keeps that COR while its other
normal-law parameters move (its damping is calibrated again), and ``cor`` itself may be free.  scipy's
``least_squares`` (trust-region reflective, bounds) minimises the residuals weighted by each value's
uncertainty; the free parameters that are positive scales are fitted in their logarithm.

Uncertainties: a quantity measured with a stated ``sigma`` is weighted by it (absolute weights); a quantity
without one is weighted by its own residual scatter at the solution, estimated in a second pass (so each
quantity counts by how well the model fits it).  Standard errors come from the Jacobian at the solution
(the covariance (J^T J)^-1 of the weighted problem); an optional bootstrap refits resampled bounces.  A
parameter whose standard error exceeds its value, or whose column of the Jacobian is numerically zero, is
reported as not identifiable from the data given.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd
from scipy.optimize import least_squares
from scipy.special import chdtrc, fdtrc

from ..contact.tangential import TANGENTIALS
from ..impact.ball import APPROACH, Ball, ball_columns, calibrated_ball, check_described
from ..impact.pair import PARTNER_UNITS
from ..impact.solve import reusing_normal_motions
from ..sweep.engine import sweep
from ..sweep.scenes import incidence, with_constants
from .measured import MEASURABLE, SOURCES, Measured, quantity
from .names import FREE

#: Relative step of the forward-difference Jacobian.  The model is accurate to the sweep's target (1e-8), so a
#: difference over this step carries about 1e-4 relative of its noise, as much as the forward difference's own
#: error (half the step times the curvature): a central difference, twice the evaluations, would gain nothing.
DIFF_STEP = 1e-4
#: A parameter fitted in its logarithm stays within this factor of its start either way (a flat direction of
#: the residuals, a parameter the data do not constrain, must not walk to overflow).
LOG_WINDOW = 1e6
#: A parameter is not identifiable when its standard error exceeds this fraction of its value.
UNIDENTIFIABLE = 1.0


@dataclass(frozen=True)
class FittedParameter:
    """One fitted parameter: its value, standard error (Jacobian), bootstrap standard error (NaN without a
    bootstrap) and whether the data pin it down."""

    value: float
    stderr: float
    bootstrap_stderr: float = math.nan
    identifiable: bool = True


@dataclass(frozen=True)
class FitResult:
    """What :func:`fit` found.

    Attributes
    ----------
    ball : Ball
        The ball with the fitted values (``fitted`` lists them; ``source`` says from which data).
    parameters : dict
        Name -> :class:`FittedParameter`.
    correlation : DataFrame
        The free parameters' correlation matrix.
    residuals : DataFrame
        One row per measured value: the bounce's approach, ``quantity`` and its ``unit``, ``measured``, ``model``, ``sigma`` (the
        weight used), ``sigma_given`` (whether it was measured), ``residual`` (model - measured) and
        ``model_stderr`` (the model's standard error there, from the parameters' covariance).
    statistics : dict
        ``values`` (n), ``free`` (p), ``dof``, ``chi2`` and ``reduced_chi2`` of the weighted residuals, ``weights``
        (``given``, ``scatter``: every uncertainty estimated from the residuals, so chi2/dof is near 1 by
        construction, or ``mixed``), ``rms`` per quantity, ``evaluations`` of the model (each a sweep of the bounces,
        the Jacobians' included), the optimiser's ``status`` message, the ``gravity`` [m/s^2] the bounces were
        solved with and the ``start`` of the free parameters.
    notes : list of str
        What the reader must know (a parameter not identifiable, weights estimated from the residuals).
    """

    ball: Ball
    parameters: dict
    correlation: pd.DataFrame
    residuals: pd.DataFrame
    statistics: dict
    notes: list = field(default_factory=list)

    def as_dict(self) -> dict:
        """The result as JSON-ready values: parameters (value, stderr, ...), correlation, statistics, notes."""
        return {"parameters": {name: {"value": p.value, "stderr": p.stderr,
                                      **({} if math.isnan(p.bootstrap_stderr) else {"bootstrap_stderr": p.bootstrap_stderr}),
                                      "identifiable": p.identifiable} for name, p in self.parameters.items()},
                "correlation": {a: {b: float(self.correlation.loc[a, b]) for b in self.correlation.columns}
                                for a in self.correlation.index},
                "statistics": self.statistics, "notes": list(self.notes)}


def with_values(ball: Ball, values: dict) -> Ball:
    """``ball`` with some parameters changed: a ball calibrated to a measured COR is calibrated again (its
    damping keeps that COR, or follows a changed ``cor``); ``modulus`` replaces ``k`` and ``kappa`` replaces
    the Poisson's ratio or shear modulus it was given as."""
    changes = dict(values)
    cor = changes.pop("cor", None)
    if "modulus" in changes:
        changes["k"] = None
    elif "k" in changes:
        changes["modulus"] = None
    if "kappa" in changes:
        changes |= {"poisson": None, "shear_modulus": None}
    measurement = ball.measurement
    if cor is not None:
        if measurement is None:
            raise ValueError("cor: the ball has no measured COR to free (give --cor and --cor-speed, or free its "
                             "damping parameter)")
        measurement = replace(measurement, cor=cor)
    normal = set(changes) & {"k", "modulus", "exponent", "inertia_factor", "mass", "diameter"}
    if measurement is not None and (cor is not None or normal):
        fields = ball.scene.as_dict() | changes
        damping = ball.scene.law.damping
        if damping is not None:
            fields[damping] = None
        if measurement.contact_time is not None:
            fields |= {"k": None, "modulus": None}
        fresh = calibrated_ball(measurement, ball.options, ball.plugins, ball.source, **fields)
        return replace(fresh, fitted=ball.fitted | fresh.fitted)
    return replace(ball, scene=ball.scene.with_(**changes))


def own_bounds(ball: Ball) -> dict:
    """The own parameters of ``ball``'s law and tangential model (a plug-in's), as :data:`FREE` gives the others:
    name -> (lower, upper, fitted in its logarithm), from each parameter's declared ``bounds``, or above 0 in its
    logarithm when it allows only positive values, else unbounded."""
    scene = ball.scene
    return {parameter.name: fit_range(parameter)
            for parameter in (*scene.law.own_parameters, *TANGENTIALS.model(scene.tangential).own_parameters)}


def fit_range(parameter) -> tuple[float, float, bool]:
    """(lower, upper, fitted in its logarithm) of a declared :class:`~sphereimpact.contact.parameters.Parameter`:
    its ``bounds``, else above 0 in its logarithm when its ``ok`` allows only positive values, else unbounded."""
    if parameter.bounds is not None:
        return float(parameter.bounds[0]), float(parameter.bounds[1]), False
    positive = bool(parameter.ok(1.0)) and not bool(parameter.ok(0.0)) and not bool(parameter.ok(-1.0))
    return (0.0, math.inf, True) if positive else (-math.inf, math.inf, False)


def fit_limits(ball: Ball, names) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(lower bounds, upper bounds, fitted in its logarithm) of the parameters ``names`` of ``ball`` (:data:`FREE`
    and :func:`own_bounds`), as arrays in their order: the fit's variables, which a plan linearises in too."""
    limits = FREE | own_bounds(ball)
    lower, upper, logs = (np.array([limits[n][i] for n in names]) for i in range(3))
    return lower, upper, logs.astype(bool)


def free_names(ball: Ball, free) -> list[str]:
    """The names of ``free`` checked against what ``ball`` can free (:data:`FREE`, its law's and tangential
    model's parameters and own parameters, ``cor`` only for a ball calibrated to a measured COR), without
    solving anything."""
    names = [free] if isinstance(free, str) else list(free)
    freeable = [*FREE, *own_bounds(ball)]
    if not names:
        raise ValueError(f"free: name at least one parameter to fit, of {', '.join(freeable)}")
    for name in names:
        if name not in freeable:
            raise ValueError(f"free: {name!r} cannot be fitted; the parameters a fit may free are "
                             f"{', '.join(freeable)}")
    if len(set(names)) != len(names):
        raise ValueError("free: a parameter is named twice")
    if "cor" in names and ball.measurement is None:
        raise ValueError("free: 'cor' needs a ball calibrated to a measured COR (give --cor and --cor-speed), or "
                         "free its damping parameter")
    for name in names:
        if name != "cor" and getattr(ball.scene, name) is None:
            whose = (f"the {ball.scene.tangential!r} tangential contact" if name == "kappa"
                     else f"the {ball.scene.model!r} law")
            raise ValueError(f"free: {name!r} is not a parameter of {whose}")
        if name == ball.scene.law.damping and ball.measurement is not None:
            raise ValueError(f"free: {name!r} is set by the measured COR; free 'cor' instead, or describe the ball "
                             f"with {name} rather than a COR")
    return names


def _start(ball: Ball, names) -> np.ndarray:
    return np.array([ball.measurement.cor if n == "cor" else float(getattr(ball.scene, n)) for n in names])


def fit(measured: Measured, ball: Ball, free, bootstrap: int = 0, seed: int = 0, target: float = 1e-8,
        chapter_ball: bool = False) -> FitResult:
    """Fit the ``free`` parameters of ``ball`` to ``measured`` bounces.

    Parameters
    ----------
    measured : Measured
        The bounces and their measured values (:func:`~sphereimpact.fit.read_measured`).
    ball : Ball
        The ball as known: its other parameters stay as they are; the free ones start from its values.
    free : sequence of str
        Names of :data:`FREE`, or own parameters of the ball's law or tangential model (:func:`own_bounds`).
    bootstrap : int
        Refits on this many resamplings of the bounces (0: none); their spread is ``bootstrap_stderr``.
    seed : int
        The bootstrap's random seed (the same seed gives the same result).
    target : float
        The sweep's relative accuracy of each model value.
    chapter_ball : bool
        Accept a ball that took parts of the chapter's where its Scene was silent (default False: refused, as the
        command line refuses an undescribed ball).

    Raises
    ------
    ValueError
        A parameter that cannot be freed, fewer measured values than free parameters, a measured e_t of
        a normal impact, or a ball not described (unless ``chapter_ball``).
    """
    check_described(ball, "fit", chapter_ball)
    with reusing_normal_motions():  # the bounces' normal motions are solved once when only mu, kappa... are free
        return _fit(measured, ball, free_names(ball, free), bootstrap, seed, target)


def _fit(measured: Measured, ball: Ball, names: list, bootstrap: int, seed: int, target: float) -> FitResult:
    values = measured.values
    if len(values) <= len(names):
        raise ValueError(f"free: {len(names)} free parameters need more than {len(names)} measured values; "
                         f"the data give {len(values)}")
    partner = sorted(set(values["quantity"]) & set(PARTNER_UNITS))
    if partner and not ball.scene.has_partner:
        raise ValueError(f"measured: {partner[0]} is the partner sphere's, and the ball strikes the flat: describe the "
                         "partner (--partner-mass, --partner-diameter; a study's surface.partner)")
    table = _bounces(measured.bounces, ball)
    theta_incidence = incidence(table)
    e_t_rows = values["quantity"] == "e_t"
    if (theta_incidence[values.loc[e_t_rows, "bounce"].to_numpy()] == 0).any():
        raise ValueError("measured: e_t of a normal impact (incidence 0) is undefined; leave it out")
    outputs = sorted({SOURCES.get(q, q) for q in values["quantity"]})
    lower, upper, logs = fit_limits(ball, names)

    evaluations = 0  # of the model: the optimiser's, its Jacobians' and the bootstrap's

    def natural(theta):
        return np.where(logs, np.exp(theta), theta)

    def model(theta, bounces=None):
        nonlocal evaluations
        evaluations += 1
        trial = dict(zip(names, natural(theta)))
        try:
            current = with_values(ball, trial)
        except ValueError as err:
            raise ValueError(f"fit: the ball cannot be built at {', '.join(f'{n} = {v:.6g}' for n, v in trial.items())} "
                             f"({err}); start nearer the data or fix a parameter") from None
        rows = table if bounces is None else table.iloc[bounces].reset_index(drop=True)
        return sweep(with_constants(rows, ball_columns(current)), target=target, outputs=outputs,
                     settings=dict(current.options.settings))

    def readings(vals):
        """(quantity, its rows of ``vals``, their bounces) per measured quantity: grouped once per set of values,
        not at each of the optimiser's evaluations."""
        return [(name, np.asarray(rows), vals.loc[rows, "bounce"].to_numpy())
                for name, rows in vals.groupby("quantity").groups.items()]

    every_reading = readings(values)

    def predictions(theta, read=every_reading, bounces=None):
        out = model(theta, bounces)
        result = np.empty(sum(rows.size for _, rows, _ in read))
        for name, rows, at in read:
            result[rows] = quantity(name, out)[at]
        return result

    measured_values = values["value"].to_numpy(float)
    given = values["sigma"].notna().to_numpy()
    sigma = np.where(given, values["sigma"].to_numpy(float), _scale(values))
    initial = _start(ball, names)
    log_start = np.log(np.where(logs, initial, 1.0))
    bounds = (np.where(logs, log_start - math.log(LOG_WINDOW), lower),
              np.where(logs, log_start + math.log(LOG_WINDOW), upper))
    start = _inside(np.where(logs, log_start, initial), *bounds)

    def solve(theta0, weights, vals=values, data=measured_values, bounces=None):
        read = every_reading if vals is values else readings(vals)

        def residual(theta):
            return (predictions(theta, read, bounces) - data) / weights

        result = least_squares(residual, theta0, bounds=bounds, method="trf", jac="2-point", diff_step=DIFF_STEP,
                               x_scale="jac", xtol=1e-10, ftol=1e-10, gtol=1e-10, max_nfev=200)
        return result

    result = solve(start, sigma)
    notes = []
    if _covariance(result.jac)[1].any():  # a flat direction: the start may lie where the data do not depend on it
        result, note = _restarted(result, solve, sigma, names, initial, bounds, logs, natural)
        notes.append(note)
    notes += _unreachable(values, ball)
    if not given.all():  # weights of the unmeasured sigmas from each quantity's residual scatter
        r = predictions(result.x) - measured_values
        sigma = np.where(given, sigma, _scatter(values, r, len(names), sigma))
        result = solve(result.x, sigma)
        estimated = sorted(set(values.loc[~given, "quantity"]))
        notes.append(f"no uncertainty given for {', '.join(estimated)}: each weighted by its own residual scatter "
                     "at the solution")
    theta, jac = result.x, result.jac
    x = natural(theta)
    cov, stderr, correlation, identifiable = _uncertainties(jac, x, logs)
    for name, ok, value, err in zip(names, identifiable, x, stderr):
        if not ok:
            why = ("the measured values do not depend on it (its standard error is unbounded)" if math.isinf(err)
                   else f"its standard error {err:.3g} exceeds its value {value:.3g}")
            notes.append(f"{name} is not identifiable from these data: {why}")
    boot = np.full(len(names), math.nan)
    if bootstrap:
        boot = _bootstrap(solve, measured, values, sigma, theta, natural, bootstrap, seed)
    model_values = predictions(theta)
    model_jac = jac * sigma[:, None]  # of the unweighted model values
    model_stderr = np.sqrt(np.clip(np.einsum("ij,jk,ik->i", model_jac, cov, model_jac), 0.0, None))
    fitted = with_values(ball, dict(zip(names, x)))
    fitted = replace(fitted, fitted=fitted.fitted | {n: float(v) for n, v in zip(names, x) if n != "cor"},
                     source=f"fitted to {len(values)} measured values of {len(measured.bounces)} bounces "
                            f"({measured.source}); free: {', '.join(names)}" + (f"; {ball.source}" if ball.source else ""))
    residuals = _residual_table(measured, model_values, sigma, given, model_stderr, theta_incidence)
    weighted = residuals["residual"].to_numpy() / sigma
    chi2, dof = float(weighted @ weighted), len(values) - len(names)
    rms = {q: float(np.sqrt(np.mean(part ** 2))) for q, part in residuals.groupby("quantity")["residual"]}
    weights = "given" if given.all() else "scatter" if not given.any() else "mixed"
    statistics = {"values": len(values), "bounces": len(measured.bounces), "free": len(names), "dof": dof,
                  "chi2": chi2, "reduced_chi2": chi2 / dof, "weights": weights, "rms": rms,
                  "evaluations": int(evaluations), "status": result.message, "gravity": ball.scene.gravity,
                  "start": {n: float(v) for n, v in zip(names, initial)}}
    misfit = _misfit_p(chi2, dof) if weights == "given" and dof > 0 else 1.0
    if misfit < MISFIT_P:
        notes.append(f"the model misses the data beyond their stated uncertainties: chi2/dof {chi2 / dof:.3g} "
                     f"({dof} degrees of freedom, p = {misfit:.2g})")
    parameters = {n: FittedParameter(float(v), float(e), float(b), bool(ok))
                  for n, v, e, b, ok in zip(names, x, stderr, boot, identifiable)}
    return FitResult(fitted, parameters, pd.DataFrame(correlation, index=names, columns=names), residuals,
                     statistics, notes)


#: Directions of the weighted Jacobian whose singular value is below this fraction of the largest are taken as
#: unconstrained: the finite-difference Jacobian is accurate to about DIFF_STEP, far above round-off.
SINGULAR = 1e-7


#: Starts a fit tries besides the ball's own when the data do not depend on a parameter there: each free
#: parameter's start times these factors (a parameter fitted in its logarithm, or friction), or these fractions of
#: its bounded range (the COR, the inertia factor, the exponent).
RESTART_FACTORS = (0.1, 0.3, 3.0, 10.0)
RESTART_FRACTIONS = (0.1, 0.3, 0.7, 0.9)
#: A restart replaces the fit when its gain in cost is this unlikely by chance (:func:`_significant`).
RESTART_P = 0.01
#: Stated uncertainties that the residuals exceed with a chi-square probability below this are a misfit, said.
MISFIT_P = 1e-3


def _significant(cost: float, better: float, n: int, p: int) -> bool:
    """Whether lowering the weighted cost from ``cost`` to ``better`` (n values, p parameters) is more than noise:
    an F test of the gain on one degree of freedom against the better fit's residual variance, at
    :data:`RESTART_P`."""
    if not better < cost:
        return False
    if n <= p or better <= 0:
        return True
    statistic = (cost - better) / (better / (n - p))
    # the F distribution's survival function, the one scipy.stats.f.sf calls (scipy.stats' import is slow)
    return bool(fdtrc(1, n - p, statistic) < RESTART_P)


def _misfit_p(chi2: float, dof: int) -> float:
    """The chance of a chi-square at least ``chi2`` with ``dof`` degrees of freedom, were the stated uncertainties
    right."""
    return float(chdtrc(dof, chi2))  # the chi-square survival function, the one scipy.stats.chi2.sf calls


def _restarted(result, solve, sigma, names, initial, bounds, logs, natural):
    """The best of ``result`` and fits from the alternative starts (:data:`RESTART_FACTORS`,
    :data:`RESTART_FRACTIONS`), for a first solution with a flat direction; and a note naming the starts and the one
    kept.  A restart replaces the fit only where it lowers the cost significantly (:func:`_significant`): one that
    merely fits the noise in another regime does not, and a parameter the data truly do not constrain stays
    reported as such."""
    best, kept, tried = result, initial, []
    low, high = _natural_bounds(bounds, logs)
    ranged = ~logs & (low != 0) & np.isfinite(high)  # a bounded range (the COR, the inertia factor, the exponent)
    for factor, fraction in zip(RESTART_FACTORS, RESTART_FRACTIONS):
        with np.errstate(invalid="ignore"):  # the unranged lanes' -inf + inf, not taken
            start = np.where(ranged, low + fraction * (high - low), initial * factor)
        theta = _inside(np.where(logs, np.log(np.where(logs, start, 1.0)), start), *bounds)
        trial = solve(theta, sigma)
        tried.append(natural(theta))
        if _significant(best.cost, trial.cost, len(trial.fun), len(names)):
            best, kept = trial, natural(theta)
    shown = "; ".join(", ".join(f"{n} = {v:.3g}" for n, v in zip(names, point)) for point in tried)
    first = ", ".join(f"{n} = {v:.3g}" for n, v in zip(names, initial))
    chosen = ", ".join(f"{n} = {v:.3g}" for n, v in zip(names, kept))
    return best, (f"the data did not depend on every parameter at the start ({first}); also started from {shown}; "
                  f"kept the fit from {chosen}")


def _natural_bounds(bounds, logs):
    """The fitted variables' bounds in the parameters' own units."""
    return tuple(np.where(logs, np.exp(b), b) for b in bounds)


def _unreachable(values: pd.DataFrame, ball: Ball) -> list[str]:
    """A note for each measured quantity with values outside what the ball's model can give (:data:`REACHABLE`):
    no parameter reaches them, and the fit only spreads its misfit."""
    notes = []
    for name, (low, high, needs) in REACHABLE.items():
        if needs == "passive" and not ball.scene.law.passive:
            continue
        mine = values[values["quantity"] == name]
        outside = mine[(mine["value"] < low) | (mine["value"] > high)]
        if len(outside):
            notes.append(f"{len(outside)} of {len(mine)} measured {name} lie outside what the model can give "
                         f"([{low:g}, {high:g}]{' for a passive contact' if needs == 'passive' else ''}; e.g. "
                         f"{outside['value'].iloc[0]:g} at bounce {int(outside['bounce'].iloc[0])}): no parameter "
                         "reaches them")
    return notes


#: Measured quantities with bounds any ball of the model respects -> (low, high, what it needs): the COR of a
#: passive contact (``ContactLaw.passive``), magnitudes and durations that are never negative.
REACHABLE = {"cor": (0.0, 1.0, "passive"), "abs_omega_f": (0.0, math.inf, ""), "t_f": (0.0, math.inf, ""),
             "t_m": (0.0, math.inf, ""), "delta_m": (0.0, math.inf, ""), "force_max": (0.0, math.inf, "")}


def _uncertainties(jac: np.ndarray, x: np.ndarray, logs: np.ndarray):
    """(covariance of the fitted variables, standard errors of the parameters, correlation, identifiable) from
    the weighted Jacobian at the solution: a parameter fitted in its logarithm has the error x * its log's."""
    cov, unbounded = _covariance(jac)
    stderr_theta = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    stderr_theta[unbounded] = math.inf
    stderr = np.where(logs, x * stderr_theta, stderr_theta)
    with np.errstate(invalid="ignore", divide="ignore"):
        correlation = cov / np.outer(stderr_theta, stderr_theta)
    correlation[unbounded, :] = correlation[:, unbounded] = math.nan
    return cov, stderr, correlation, ~unbounded & (stderr <= UNIDENTIFIABLE * np.abs(x))


def _residual_table(measured: Measured, model, sigma, given, model_stderr, incidences) -> pd.DataFrame:
    """One row per measured value: its bounce's approach (the incidence from the normal resolved), the
    quantity and its unit, measured and model values, the weight, the residual and the model's error."""
    values, bounce = measured.values, measured.values["bounce"].to_numpy()
    approach = measured.bounces.drop(columns=["incidence"], errors="ignore").iloc[bounce].reset_index(drop=True)
    return pd.concat([approach, pd.DataFrame({
        "quantity": values["quantity"], "unit": values["quantity"].map(MEASURABLE).to_numpy(),
        "measured": values["value"].to_numpy(float), "model": model, "sigma": sigma, "sigma_given": given,
        "residual": model - values["value"].to_numpy(float), "model_stderr": model_stderr,
        "incidence": incidences[bounce]})], axis=1)


def _covariance(jac: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The covariance (J^T J)^-1 of the fitted (transformed) parameters, on the directions the data constrain,
    and which parameters load on a direction they do not (a singular value below :data:`SINGULAR` of the
    largest): those have no finite standard error."""
    _, s, vt = np.linalg.svd(jac, full_matrices=False)
    kept = s > SINGULAR * max(s.max(), 1e-300)
    cov = (vt[kept].T / s[kept] ** 2) @ vt[kept]
    unbounded = (np.abs(vt[~kept]) > 1e-3).any(axis=0) if (~kept).any() else np.zeros(jac.shape[1], bool)
    return cov, unbounded


def _bounces(bounces: pd.DataFrame, ball: Ball) -> pd.DataFrame:
    """The measured bounces as scene rows: their approach, the ball's where they leave it out (its speed, its
    spin, and its one description of the direction when the table gives none)."""
    table = bounces.copy()
    scene = ball.scene
    if not any(c in table for c in ("incidence", "angle_to_surface", "angle")):
        direction = next((name for name in ("incidence", "angle_to_surface") if getattr(scene, name) is not None),
                         "angle")
        table[direction] = getattr(scene, direction)
    for name in ("speed", "spin"):
        if name not in table:
            table[name] = getattr(scene, name)
    for name, absent in (("incidence", np.nan), ("angle_to_surface", np.nan), ("angle", 0.0)):
        if name not in table:
            table[name] = absent
    return table[list(APPROACH)].reset_index(drop=True)


def _scale(values: pd.DataFrame) -> np.ndarray:
    """First-pass weights where no uncertainty is given: each quantity's typical magnitude."""
    typical = values.groupby("quantity")["value"].transform(lambda v: np.sqrt(np.mean(v ** 2)))
    return np.where(typical > 0, typical, 1.0)


def _scatter(values: pd.DataFrame, residual: np.ndarray, free: int, fallback: np.ndarray) -> np.ndarray:
    """Each quantity's residual scatter: its RMS, scaled by n / (n - p) for the p parameters fitted to all n
    values, and floored far below the quantity's magnitude (``fallback``) so a perfect fit stays finite."""
    n = len(values)
    mean = pd.Series(residual ** 2).groupby(values["quantity"].to_numpy()).transform("mean").to_numpy()
    return np.maximum(np.sqrt(mean * n / max(n - free, 1)), 1e-9 * fallback)


def _bootstrap(solve, measured: Measured, values: pd.DataFrame, sigma, theta, natural, count: int, seed: int):
    """The spread of the estimates over ``count`` refits, each on the bounces resampled with replacement."""
    rng = np.random.default_rng(seed)
    n = len(measured.bounces)
    estimates = []
    for _ in range(count):
        picked = rng.integers(0, n, n)
        rows = [np.flatnonzero(values["bounce"].to_numpy() == b) for b in picked]
        index = np.concatenate(rows)
        renumbered = values.iloc[index].assign(bounce=np.repeat(np.arange(n), [len(r) for r in rows]))
        if len(renumbered) <= len(theta):
            continue
        result = solve(theta, sigma[index], renumbered.reset_index(drop=True), values["value"].to_numpy(float)[index],
                       picked)
        estimates.append(natural(result.x))
    return np.std(np.array(estimates), axis=0, ddof=1) if len(estimates) > 1 else np.full(len(theta), math.nan)


def _inside(theta, low, high):
    """A start strictly inside the bounds (least_squares requires it)."""
    span = np.where(np.isfinite(high - low), high - low, 1.0)
    return np.clip(theta, low + 1e-9 * span, high - 1e-9 * span)
