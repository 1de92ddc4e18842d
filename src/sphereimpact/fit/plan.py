"""Which bounces to measure: the expected uncertainty of a measurement plan, and the plan of N bounces that pins
the parameters best, before anything is measured.

Linearised, as the fit reports its own errors: at the parameters the user expects, the Jacobian J of the planned
outputs with respect to the free parameters (the fit's model and parametrisation, :mod:`.least_squares`: each
positive scale in its logarithm, a forward difference of relative step ``DIFF_STEP`` as the fit's least squares
takes it), weighted by the planned noise, gives a plan's Fisher information F = J^T W J and the covariance F^-1
that a fit of its bounces would report.  A parameter no planned output depends on has no finite error, and the
plan says which and why.

The best plan of N distinct candidates maximises det F (``D``-optimal, the default: it does not depend on the
parameters' units) or minimises the sum of the squared relative standard errors (``A``-optimal), by Fedorov's
exchange algorithm from a greedy start (Fedorov 1972, *Theory of Optimal Experiments*).  Where the linearisation
does not hold, a bounce whose outputs bend within the step (the grip-slide boundary near it) or a parameter at its
bound, the plan says so: its errors there are a linear estimate only.  :func:`realised_spread` checks the
predictions by simulation: synthetic bounces of the plan with the planned noise, fitted by
:func:`~sphereimpact.fit.fit` over many seeds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..impact.ball import APPROACH, Ball, ball_columns, check_described
from ..impact.solve import reusing_normal_motions
from ..sweep.engine import sweep
from ..sweep.scenes import incidence, with_constants
from .least_squares import DIFF_STEP, _bounces, _start, _uncertainties, fit_limits, free_names
from .measured import SOURCES, quantity
from .names import MEASURABLE

#: Criteria of the best plan: ``D`` (largest determinant of the information) and ``A`` (smallest sum of squared
#: relative standard errors).
CRITERIA = ("D", "A")
#: A bounce's outputs "bend within the step" when the forward and the backward difference of an output that the
#: noise lets matter differ by more than this fraction of the larger.
BENDING = 0.1
#: Two parameters whose expected correlation exceeds this in magnitude are named together when one is not
#: identifiable.
CORRELATED = 0.99
#: A difference of the model values below this many times their accuracy (the sweep's target, relative), over the
#: step, is taken as no dependence: the model's own error would otherwise read as a tiny sensitivity.
NOISE_FLOOR = 10.0


@dataclass(frozen=True)
class Noise:
    """A planned output's measurement noise: ``sigma`` in the output's unit, or a fraction of its value when
    ``relative``."""

    sigma: float
    relative: bool = False

    def of(self, value):
        """The standard uncertainty of measured ``value`` (array-like)."""
        return self.sigma * np.abs(value) if self.relative else np.full(np.shape(value), self.sigma)

    def __str__(self) -> str:
        return f"{self.sigma * 100:g}%" if self.relative else f"{self.sigma:g}"


def parse_noise(noise) -> dict[str, Noise]:
    """The noise of each planned output from ``"e_t=0.02,abs_omega_f=5%"`` or a mapping (values a number, a
    ``"5%"`` text or a :class:`Noise`).

    Raises
    ------
    ValueError
        An output that cannot be measured (:data:`MEASURABLE`), a noise that is not a positive finite number, a name
        given twice, or no output at all.
    """
    if isinstance(noise, str):
        pairs = []
        for item in (part.strip() for part in noise.split(",")):
            if not item:
                continue
            name, sep, value = item.partition("=")
            if not sep:
                raise ValueError(f"noise: {item!r} is not OUTPUT=SIGMA (e.g. e_t=0.02 or abs_omega_f=5%)")
            pairs.append((name.strip(), value.strip()))
    else:
        pairs = list(dict(noise).items())
    if not pairs:
        raise ValueError(f"noise: name at least one output and its noise, of {', '.join(MEASURABLE)}")
    out = {}
    for name, value in pairs:
        if name not in MEASURABLE:
            raise ValueError(f"noise: {name!r} is not a measurable output; expected one of {', '.join(MEASURABLE)}")
        if name in out:
            raise ValueError(f"noise: {name!r} is given twice")
        out[name] = value if isinstance(value, Noise) else _noise(name, value)
    return out


def _noise(name: str, value) -> Noise:
    relative = isinstance(value, str) and value.endswith("%")
    text = value[:-1] if relative else value
    try:
        sigma = float(text)
    except (TypeError, ValueError):
        sigma = math.nan
    if isinstance(value, bool) or not (math.isfinite(sigma) and sigma > 0):
        raise ValueError(f"noise: {name}={value!r}: the noise must be a finite number > 0 in the output's unit "
                         f"({MEASURABLE[name] or '-'}) or a percentage of its value (e.g. 5%)")
    return Noise(sigma / 100 if relative else sigma, relative)


def read_candidates(data, source: str = "") -> pd.DataFrame:
    """Candidate bounces from a CSV file's path or a DataFrame: one approach per row, in ``fit``'s columns
    (:data:`~sphereimpact.impact.ball.APPROACH`: speed, incidence or angle_to_surface or angle, spin; a column left
    out takes the ball's value).

    Raises
    ------
    ValueError
        An unreadable file, no rows, a column that is not an approach, or a cell that is not a finite number.
    """
    if isinstance(data, pd.DataFrame):
        frame, source = data.reset_index(drop=True), source or "a DataFrame"
    else:
        try:
            frame = pd.read_csv(data, comment="#")
        except (OSError, pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as err:
            raise ValueError(f"candidates: cannot read {str(data)!r} "
                             f"({getattr(err, 'strerror', None) or err})") from None
        source = source or str(data)
    unknown = [c for c in frame.columns if c not in APPROACH]
    if unknown:
        raise ValueError(f"candidates: {source}: column {unknown[0]!r} is not an approach; expected some of "
                         f"{', '.join(APPROACH)}")
    if frame.empty:
        raise ValueError(f"candidates: {source}: no candidate bounces")
    checked = {}
    for column in frame.columns:
        numbers = pd.to_numeric(frame[column], errors="coerce")
        bad = ~np.isfinite(numbers.to_numpy(float))
        if bad.any():
            raise ValueError(f"candidates: {source}: column {column!r} row {int(np.flatnonzero(bad)[0])}: "
                             f"{frame[column].iloc[int(np.flatnonzero(bad)[0])]!r} is not a finite number")
        checked[column] = numbers.to_numpy(float)
    return pd.DataFrame(checked)


@dataclass(frozen=True)
class Plan:
    """A measurement plan and what a fit of it is expected to give.

    Attributes
    ----------
    free : tuple of str
        The parameters to be fitted.
    values : dict
        Their expected values (the ball's), natural units.
    noise : dict
        Output -> :class:`Noise`.
    criterion : str
        ``D`` or ``A`` (:data:`CRITERIA`).
    candidates : DataFrame
        Every candidate: its approach, ``incidence_deg`` (from the normal), ``chosen``, each planned output's model
        value and noise (``sigma_<output>``), and ``stderr_<parameter>``: that parameter's standard error from this bounce alone,
        the others known (inf where the bounce does not inform it).
    chosen : tuple of int
        The rows of ``candidates`` in the plan.
    stderr : dict
        ``chosen``, ``even`` (as many bounces spread evenly over the candidates, in their order) and ``all`` (every
        candidate): parameter -> expected standard error (inf: not identifiable).
    correlation : DataFrame
        The chosen plan's expected correlations.
    notes : list of str
        Parameters the plan cannot identify and why; where the linearisation does not hold.
    """

    free: tuple
    values: dict
    noise: dict
    criterion: str
    candidates: pd.DataFrame
    chosen: tuple
    stderr: dict
    correlation: pd.DataFrame
    notes: list = field(default_factory=list)

    def table(self) -> pd.DataFrame:
        """The chosen bounces in ``fit``'s columns: the approach, each planned output empty (to be measured) and its
        planned uncertainty ``sigma_<output>``; ``sphereimpact fit`` reads it once the outputs are filled in."""
        rows = self.candidates.iloc[list(self.chosen)]
        table = rows[[c for c in APPROACH if c in rows and rows[c].notna().any()]].reset_index(drop=True)
        for name in self.noise:
            table[name] = np.nan
            table[f"sigma_{name}"] = rows[f"sigma_{name}"].to_numpy()
        return table

    def as_dict(self) -> dict:
        """Everything but the candidate table as plain Python types, as :meth:`FitResult.as_dict` (an unbounded
        error is inf: ``study.fitting.finite`` writes it as JSON's null)."""
        return {"free": list(self.free), "values": {k: float(v) for k, v in self.values.items()},
                "noise": {k: str(v) for k, v in self.noise.items()}, "criterion": self.criterion,
                "size": len(self.chosen), "candidates": len(self.candidates),
                "chosen": [{k: float(v) for k, v in row.items()} for row in
                           self.candidates.iloc[list(self.chosen)][
                               [c for c in (*APPROACH, "incidence_deg") if c in self.candidates]].to_dict("records")],
                "stderr": {plan: dict(errors) for plan, errors in self.stderr.items()},
                "correlation": {a: {b: float(self.correlation.loc[a, b]) for b in self.correlation.columns}
                                for a in self.correlation.index},
                "notes": list(self.notes)}


def size_problem(size, free: int, candidates: int) -> str | None:
    """What is wrong with a plan of ``size`` bounces for ``free`` parameters from ``candidates`` (None: nothing)."""
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or not free <= size <= candidates:
        return (f"must be an integer in [{free}, {candidates}] (the free parameters to the candidates); "
                f"got {size!r}")
    return None


def plan(candidates, ball: Ball, free, noise, size: int | None = None, criterion: str = "D",
         target: float = 1e-8, chapter_ball: bool = False) -> Plan:
    """The expected standard errors of fitting ``free`` to the ``noise``-d outputs of bounces, and the best plan.

    Parameters
    ----------
    candidates : DataFrame or path
        The bounces one could measure (:func:`read_candidates`).
    ball : Ball
        The ball as expected: the free parameters at the values one expects them to have.
    free : sequence of str
        Parameters to fit, as for :func:`~sphereimpact.fit.fit`.
    noise : str or mapping
        Each planned output's noise (:func:`parse_noise`).
    size : int, optional
        Bounces in the plan, from the number of free parameters to the number of candidates; default: every
        candidate (the plan is then the candidates themselves).
    criterion : str
        ``D`` or ``A`` (:data:`CRITERIA`).
    target : float
        The sweep's relative accuracy of each model value.
    chapter_ball : bool
        Accept a ball that took parts of the chapter's where its Scene was silent (default False: refused).

    Raises
    ------
    ValueError
        A parameter that cannot be freed, a size out of range, an unknown criterion, bad candidates or noise, or a
        ball not described (unless ``chapter_ball``).
    """
    check_described(ball, "plan", chapter_ball)
    table = read_candidates(candidates)
    names = free_names(ball, free)
    noise = parse_noise(noise)
    if criterion not in CRITERIA:
        raise ValueError(f"criterion must be one of {', '.join(CRITERIA)}; got {criterion!r}")
    size = len(table) if size is None else size
    problem = size_problem(size, len(names), len(table))
    if problem:
        raise ValueError(f"size {problem}")
    if not (math.isfinite(target) and 1e-12 <= target <= 1e-3):
        raise ValueError(f"target must be a finite number in [1e-12, 1e-3]; got {target!r}")
    design = _design(table, ball, names, noise, target)
    x, logs, lower, upper = design.x, design.logs, design.lower, design.upper
    rows, outputs, model, sigma, weights, weighted = (design.rows, design.outputs, design.model, design.sigma,
                                                      design.weights, design.weighted)
    forward, backward, usable = design.forward, design.backward, design.usable
    information = np.einsum("iop,ioq->ipq", weighted, weighted)

    chosen = _exchange(information, size, criterion, x, logs)
    even = np.unique(np.round(np.linspace(0, len(rows) - 1, size)).astype(int))
    stderr, correlations, identifiable = {}, {}, {}
    for label, picked in (("chosen", chosen), ("even", even), ("all", np.arange(len(rows)))):
        jac = weighted[picked].reshape(-1, len(names))
        _, errors, correlation, ok = _uncertainties(jac, x, logs)
        stderr[label] = dict(zip(names, map(float, errors)))
        correlations[label], identifiable[label] = correlation, ok

    notes = _identifiability(names, x, weighted, chosen, correlations["chosen"], identifiable)
    notes += _bending(forward, backward, weights, chosen, incidence(rows), names)
    notes += [f"{name} = {value:g} is at its bound: the expected errors there are a linear estimate only"
              for name, value, low, high in zip(names, x, lower, upper) if value <= low or value >= high]
    if np.any(~usable):
        notes.append(f"{int((~usable).sum())} planned values carry no information (a relative noise of a zero "
                     "value, or an output undefined there, such as e_t at normal incidence): left out")

    diagonal = np.einsum("ipp->ip", information)
    with np.errstate(divide="ignore"):
        single = np.where(diagonal > 0, 1.0 / np.sqrt(diagonal), math.inf)
    single = np.where(logs, x * single, single)
    frame = table.copy()
    frame["incidence_deg"] = incidence(rows)
    frame["chosen"] = np.isin(np.arange(len(rows)), chosen)
    for j, name in enumerate(outputs):
        frame[name] = model[:, j]
        frame[f"sigma_{name}"] = sigma[:, j]
    for j, name in enumerate(names):
        frame[f"stderr_{name}"] = single[:, j]
    return Plan(tuple(names), dict(zip(names, map(float, x))), noise, criterion, frame,
                tuple(int(i) for i in chosen), stderr,
                pd.DataFrame(correlations["chosen"], index=names, columns=names), notes)


@dataclass(frozen=True)
class _Design:
    """The model at the candidates, the ball's expected parameters: what a plan's information is made of."""

    rows: pd.DataFrame
    outputs: list
    x: np.ndarray
    logs: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    model: np.ndarray
    forward: np.ndarray
    backward: np.ndarray
    sigma: np.ndarray
    usable: np.ndarray
    weights: np.ndarray
    weighted: np.ndarray


def _design(table: pd.DataFrame, ball: Ball, names: list, noise: dict, target: float, bending: bool = True) -> _Design:
    """Each candidate's planned outputs, their noise and their differences in the fit's variables; a value the
    noise cannot weigh (a relative noise of zero, an undefined output) gets weight 0.  ``bending``: also the
    backward differences that tell where the linearisation does not hold (NaN without)."""
    rows = _bounces(table, ball)
    outputs = list(noise)
    lower, upper, logs = fit_limits(ball, names)
    x = _start(ball, names)
    with reusing_normal_motions():
        forward, backward, model = _jacobians(rows, ball, names, outputs, x, logs, lower, upper, target, bending)
    sigma = np.column_stack([noise[name].of(model[:, j]) for j, name in enumerate(outputs)])
    usable = np.isfinite(model) & (sigma > 0)
    weights = np.where(usable, 1.0 / np.where(usable, sigma, 1.0), 0.0)  # 1/sigma; 0 where the value says nothing
    weighted = np.nan_to_num(forward) * weights[:, :, None]
    return _Design(rows, outputs, x, logs, lower, upper, model, forward, backward, sigma, usable, weights, weighted)


def expected_errors(bounces, ball: Ball, free, noise, target: float = 1e-8) -> dict:
    """The expected standard error of each ``free`` parameter from measured values as a table gives them: one row
    per value, its bounce's approach (``fit``'s columns) and the ``quantity`` measured (an output named in
    ``noise``), e.g. the values of an experiment already made.  Returns parameter -> standard error (inf: not
    identifiable)."""
    frame = pd.DataFrame(bounces).reset_index(drop=True)
    if "quantity" not in frame:
        raise ValueError("bounces: a 'quantity' column names the output each row measures")
    names, noise = free_names(ball, free), parse_noise(noise)
    blocks, x, logs = [], None, None
    for name, part in frame.groupby("quantity", sort=True):
        if name not in noise:
            raise ValueError(f"noise: give the noise of {name!r}, which the bounces measure")
        design = _design(read_candidates(part.drop(columns="quantity")), ball, names, {name: noise[name]}, target,
                         bending=False)
        blocks.append(design.weighted.reshape(-1, len(names)))
        x, logs = design.x, design.logs
    _, errors, _, _ = _uncertainties(np.vstack(blocks), x, logs)
    return dict(zip(names, map(float, errors)))


def _jacobians(rows, ball, names, outputs, x, logs, lower, upper, target, bending=True):
    """The model's planned outputs at ``x`` and their forward and, with ``bending``, backward differences in the
    fit's variables (a positive scale's logarithm), each with the fit's step: (forward, backward, model), shapes
    (rows, outputs, parameters) and (rows, outputs).  The backward difference is NaN where it would leave the
    bounds, or without ``bending``."""
    from .least_squares import with_values

    sources = sorted({SOURCES.get(name, name) for name in outputs})
    theta = np.where(logs, np.log(np.where(logs, x, 1.0)), x)
    low = np.where(logs, -np.inf, lower)
    high = np.where(logs, np.inf, upper)

    expected = dict(zip(names, x))

    def values(point):
        # Only what moved from the ball's own values: a ball calibrated to a measured COR is calibrated again only
        # when the COR or a normal-law parameter moves, not for each step in friction or the tangential stiffness.
        trial = dict(zip(names, np.where(logs, np.exp(point), point)))
        current = with_values(ball, {n: v for n, v in trial.items() if v != expected[n]})
        out = sweep(with_constants(rows, ball_columns(current)), target=target, outputs=sources,
                    settings=dict(current.options.settings))
        return np.column_stack([quantity(name, out) for name in outputs])

    model = values(theta)
    forward = np.empty((*model.shape, len(names)))
    backward = np.full_like(forward, np.nan)
    for j in range(len(names)):
        step = DIFF_STEP * max(1.0, abs(theta[j])) * (1.0 if theta[j] >= 0 else -1.0)  # least_squares' 2-point
        if not low[j] <= theta[j] + step <= high[j]:
            step = -step
        shifted = theta.copy()
        shifted[j] += step
        forward[:, :, j] = (values(shifted) - model) / step
        shifted[j] = theta[j] - step
        if bending and low[j] <= shifted[j] <= high[j]:
            backward[:, :, j] = (model - values(shifted)) / step
        # A difference within the model values' own accuracy over the step is noise, not a dependence: zero.
        floor = NOISE_FLOOR * target * np.abs(model) / abs(step)
        forward[:, :, j] = np.where(np.abs(forward[:, :, j]) > floor, forward[:, :, j], 0.0)
        backward[:, :, j] = np.where(np.abs(backward[:, :, j]) > floor, backward[:, :, j], 0.0)
    return forward, backward, model


def _logdet(matrices):
    sign, logdet = np.linalg.slogdet(matrices)
    return np.where(sign > 0, logdet, -np.inf)


def _exchange(information, size, criterion, x, logs):
    """The ``size`` candidates (rows of ``information``, each bounce's p x p Fisher information) that optimise
    ``criterion``: a greedy start, then Fedorov's exchange of one chosen candidate for one left out while it
    improves the criterion; ties go to the earlier candidate, so the same inputs give the same plan."""
    n, p = information.shape[0], information.shape[1]
    scale = np.where(logs, 1.0, np.where(x != 0, np.abs(x), 1.0))  # an A-criterion of relative errors
    ridge = 1e-12 * np.diag(information.sum(axis=0)).max() * np.eye(p) + 1e-300 * np.eye(p)

    def cost(matrices):
        matrices = matrices + ridge
        if criterion == "D":
            return -_logdet(matrices)
        try:
            inverse = np.linalg.inv(matrices)
        except np.linalg.LinAlgError:
            return np.full(len(matrices), np.inf)
        return np.einsum("kii->k", inverse / np.outer(scale, scale))

    chosen = []
    total = np.zeros((p, p))
    for _ in range(size):
        left = np.setdiff1d(np.arange(n), chosen)
        best = left[int(np.argmin(cost(total + information[left])))]
        chosen.append(int(best))
        total = total + information[best]
    for _ in range(50 * size):  # each exchange improves the criterion strictly; it ends well before this
        current = float(cost(total[None])[0])
        left = np.setdiff1d(np.arange(n), chosen)
        if not len(left):
            break
        best_gain, swap = 0.0, None
        for position, out in enumerate(chosen):
            trial = cost(total - information[out] + information[left])
            k = int(np.argmin(trial))
            gain = current - float(trial[k])
            if gain > best_gain + 1e-12 * max(abs(current), 1.0):
                best_gain, swap = gain, (position, int(left[k]))
        if swap is None:
            break
        position, into = swap
        total = total - information[chosen[position]] + information[into]
        chosen[position] = into
    return np.array(sorted(chosen))


def _identifiability(names, x, weighted, chosen, correlation, identifiable) -> list[str]:
    """Why each parameter the chosen plan cannot identify is so: no planned output depends on it at these bounces,
    it moves with another parameter, or its expected error exceeds its value; and whether any candidate would."""
    notes = []
    jac = weighted[chosen].reshape(-1, len(names))
    norms = np.linalg.norm(jac, axis=0)
    for j, name in enumerate(names):
        if identifiable["chosen"][j]:
            continue
        if norms[j] <= 1e-9 * max(norms.max(), 1e-300):
            why = "no planned output depends on it at these bounces"
        else:
            partners = [names[k] for k in range(len(names)) if k != j and abs(correlation[j, k]) > CORRELATED]
            why = (f"it moves with {', '.join(partners)} (expected correlation above {CORRELATED})" if partners
                   else f"its expected error exceeds its value {x[j]:g}")
        anywhere = ("; no candidate identifies it: add bounces that do (e.g. ones that grip, for kappa or the "
                    "inertia factor), or measure other outputs" if not identifiable["all"][j] else
                    "; the candidates together would")
        notes.append(f"{name} is not identifiable from the plan: {why}{anywhere}")
    return notes


def _bending(forward, backward, weights, chosen, incidences, names) -> list[str]:
    """The chosen bounces whose planned outputs bend within the fit's step (forward and backward differences
    disagree by more than :data:`BENDING`, where the noise lets the output matter)."""
    f, b = forward[chosen] * weights[chosen][:, :, None], backward[chosen] * weights[chosen][:, :, None]
    scale = np.nanmax(np.abs(f), axis=(0, 1), keepdims=True)
    with np.errstate(invalid="ignore"):
        bent = (np.abs(f - b) > BENDING * np.maximum(np.abs(f), np.abs(b))) & (np.abs(f) > 1e-3 * scale)
    rows = np.flatnonzero(np.nan_to_num(bent).any(axis=(1, 2)))
    if not len(rows):
        return []
    where = ", ".join(f"{incidences[chosen[r]]:.4g}°" for r in rows[:8]) + (" ..." if len(rows) > 8 else "")
    which = sorted({names[p] for p in np.flatnonzero(np.nan_to_num(bent).any(axis=(0, 1)))})
    return [f"the linearisation does not hold at {len(rows)} chosen bounces (incidence {where}): their outputs bend "
            f"within the fit's step in {', '.join(which)} (a grip-slide boundary near them); the expected errors "
            "there are a linear estimate only"]


def realised_spread(plan_: Plan, ball: Ball, seeds: int, target: float = 1e-8) -> pd.DataFrame:
    """The predicted standard errors of ``plan_`` against the spread of the estimates over ``seeds`` fits of
    synthetic bounces: the plan's model values plus Gaussian noise of the planned sigma (seeded 0, 1, ...), each
    fitted by :func:`~sphereimpact.fit.fit` from the ball's values with the planned sigmas given.  One row per
    parameter: ``predicted``, ``realised`` (the sample standard deviation), ``mc_error`` (the realised value's
    own standard error, realised / sqrt(2 (seeds - 1))) and ``ratio`` = realised / predicted."""
    from .least_squares import fit
    from .measured import read_measured

    if isinstance(seeds, bool) or not isinstance(seeds, (int, np.integer)) or seeds < 3:
        raise ValueError(f"seeds must be an integer >= 3; got {seeds!r}")
    table = plan_.table()
    rows = plan_.candidates.iloc[list(plan_.chosen)].reset_index(drop=True)
    estimates = []
    for seed in range(seeds):
        rng = np.random.default_rng(seed)
        synthetic = table.copy()
        for name in plan_.noise:
            synthetic[name] = rows[name].to_numpy() + rng.normal(0.0, 1.0, len(rows)) * rows[f"sigma_{name}"].to_numpy()
        result = fit(read_measured(synthetic, f"synthetic bounces, seed {seed}"), ball, list(plan_.free),
                     target=target, chapter_ball=True)  # bounces of this very ball: the plan judged its description
        estimates.append([result.parameters[name].value for name in plan_.free])
    estimates = np.array(estimates)
    realised = estimates.std(axis=0, ddof=1)
    predicted = np.array([plan_.stderr["chosen"][name] for name in plan_.free])
    return pd.DataFrame({"parameter": plan_.free, "value": [plan_.values[n] for n in plan_.free],
                         "predicted": predicted, "realised": realised,
                         "mc_error": realised / math.sqrt(2 * (seeds - 1)), "ratio": realised / predicted,
                         "mean": estimates.mean(axis=0), "seeds": seeds})
