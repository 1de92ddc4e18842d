"""The sweep's paths: each takes some of a sweep's scenes and solves them; :data:`ORDER` is their precedence.

One contract (:class:`SweepPath`): ``take(work, todo, span_todo)`` says which of the rows still to do the
path takes and how it solves them (:class:`Take`).  A task's ``solve()`` returns, for its rows, the
dimensionless normal outputs :data:`NORMAL_OUTPUTS`, from which the engine's impulse algebra gives every
tangential output; only the single-impact path (``gives = Gives.ALL``) returns every output itself.  A path that
builds on the whole sweep (an interpolant over its range) reads the sweep's scenes that no earlier path
took (``span_todo``), so a shard takes the paths the whole sweep would.  Which path solved each row is the
sweep table's ``path`` column; ``results/sweep_paths.csv`` measures the paths against each other where two
apply (:mod:`sphereimpact.numerics.sweep_paths`).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from enum import Enum
from typing import Callable

import numpy as np

from ..contact.laws import LAWS
from ..contact.separation import Separation
from ..contact.tangential import TANGENTIALS
from ..errors import BeyondRadiusWarning, EnergyGainWarning, ImpactError, InterpolationError
from ..impact.declarations import SCALES
from ..impact.outcome import NUMERIC_OUTPUTS
from ..impact.scene import TANGENTIAL_ONLY, SolverOptions
from ..impact.solve import reusing_normal_motions, simulate, simulate_many
from ..integrators.compiled import expect_evaluations
from . import batch, plane, series_lanes
from .outputs import EXTREMES, NORMAL_OUTPUTS, Needs
from .processes import solved_chunks
from .scenes import CLOSED_FORMS, SCENE_COLUMNS, Numbers, SceneColumns, _compliant, first_rows, incidence, scene_of
from .similarity import FamilyInterpolant, LambdaInterpolant, dimensionless_motion

#: Path thresholds, each where the faster path changes on the sweep benchmark's scenes: fewest scenes sharing
#: (zeta, criterion) for the lam interpolant; fewest scenes of one criterion for the (zeta, lam) plane; fewest
#: distinct values of a kernel-less law's last family number for interpolating in it.
SIMILARITY_MIN = 2000
PLANE_MIN = 3000
FAMILY_MIN = 200
#: Fewest scenes asking a grip instant for the lam interpolant to tabulate them (its grip tables cost about
#: as much to build as the Taylor lanes take to reach that many instants, each stopping there).
GRIP_TABLE_MIN = 40_000
#: Largest damping ratio the lanes, the similarity path and the closed form take (the accepted domain's edge,
#: where their contract is tested); beyond it an over-damped creep makes a lane's steps unbounded.
LANES_ZETA_MAX = 100.0
#: Largest lam of eq. 4.2 on the Runge-Kutta lanes with gravity or beyond critical damping; such scenes are
#: solved one by one.  Beyond it the lanes' landing on delta = 0 under the penetration criterion lost the COR
#: (2e-4 at zeta 0.01, lam 1e4, with gravity; the sweep-path study's check against plain-float DOP853).
LANES_LAM_MAX = 1e3
#: Cost model choosing between the batched lanes and single impacts: a batched step costs LANE_STEP_COST [s]
#: plus LANE_COST per lane; one impact SINGLE_COST plus SINGLE_EVAL_COST per evaluation.  It only chooses a
#: path, never sets an accuracy.
LANE_STEP_COST, LANE_COST = 160e-6, 0.26e-6
SINGLE_COST, SINGLE_EVAL_COST = 1e-3, 2.5e-6
#: Right-hand-side evaluations of a typical impact solved alone (DOP853 on a Hertz law: 510-585 across the Kharaz
#: ball's map; the Taylor method on eq. 4.2: about 220), which tells the single-impact path how much it will integrate.
SINGLE_EVALUATIONS = 300


def single_options(target: float, settings=None) -> SolverOptions:
    """The single-impact model's options in a sweep of accuracy ``target``: tolerance target / 10^4 (at most
    1e-10; rtol 1e-10 left the instant a contact grips near its end, where the impulse levels off, 3e-8 of
    t_f off), and the tangential model's resolution."""
    tol = min(max(target * 1e-4, 1e-13), 1e-10)
    return SolverOptions(rtol=tol, atol=tol, settings=settings or {})


#: Scenes solved by the single-impact model per call of :func:`~sphereimpact.impact.solve.simulate_many` (a batched
#: tangential kernel runs them together; progress is reported after each).
SINGLES_CHUNK = 100


@dataclass(frozen=True)
class Work:
    """What a path reads: the scenes to solve (``frame``, their ``numbers``, what each ``needs`` beyond the
    normal outputs), the whole sweep they belong to (``span_frame``, ``span``, ``span_needs``; the same
    objects when the sweep is not sharded), the accuracy ``target``, the scenes integrated at once
    (``chunk_size``), the single-impact ``options``, ``progress(done, total)`` and the most processes the
    single impacts may share (``jobs``)."""

    frame: SceneColumns
    numbers: Numbers
    needs: Needs
    span_frame: SceneColumns
    span: Numbers
    span_needs: Needs
    target: float
    chunk_size: int
    options: SolverOptions
    progress: Callable | None = None
    jobs: int = 1

    @property
    def sharded(self) -> bool:
        return self.span is not self.numbers


@dataclass(frozen=True)
class Task:
    """Rows of the scenes (indices) and how to solve them: ``solve()`` -> output name -> values per row."""

    rows: np.ndarray
    solve: Callable[[], dict]


@dataclass(frozen=True)
class Take:
    """What a path takes: its ``tasks``, and the mask of the span's scenes it takes (hidden from later paths)."""

    tasks: list
    span: np.ndarray


class Gives(Enum):
    """What a path's tasks return for their rows."""

    #: :data:`NORMAL_OUTPUTS`, with ``p_max`` and ``p_min`` where the rows' :class:`~.outputs.Needs` ask for the
    #: force's extremes and ``tau_g`` where they ask for the instant of a level of the impulse: the engine's
    #: impulse algebra and the rows' tangential models give the rest
    NORMAL = "normal"
    #: every output of ``simulate``
    ALL = "all"


class SweepPath:
    """One way to solve some scenes of a sweep.  ``name`` is the value of the sweep's ``path`` column,
    ``summary`` one line for its help; ``gives`` what its tasks return (:class:`Gives`).  A path takes only rows
    it can give all of that."""

    name = ""
    summary = ""
    gives = Gives.NORMAL

    def take(self, work: Work, todo: np.ndarray, span_todo: np.ndarray) -> Take:
        """The rows of ``todo`` (a mask of ``work.frame``) this path takes, and its rows of the span's
        ``span_todo``."""
        raise NotImplementedError


def _chunked(rows: np.ndarray, chunk_size: int, solve: Callable[[np.ndarray], dict], progress=None) -> dict:
    """``solve`` on ``rows`` in chunks of ``chunk_size`` (memory stays bounded), the outputs joined."""
    parts = []
    for start in range(0, rows.size, chunk_size):
        parts.append(solve(rows[start:start + chunk_size]))
        if progress:
            progress(min(start + chunk_size, rows.size), rows.size)
    return {key: np.concatenate([part[key] for part in parts]) for key in parts[0]} if parts else {}


# ---------------------------------------------------------------- the single-impact path and its rule


def _columns(outcomes: list) -> dict:
    """The outcomes' :data:`NUMERIC_OUTPUTS` as float arrays (NaN where an output is None) and their ``regime``."""
    out = {key: np.array([np.nan if getattr(one, key) is None else getattr(one, key) for one in outcomes], dtype=float)
           for key in NUMERIC_OUTPUTS}
    return out | {"regime": np.array([one.regime for one in outcomes], dtype=object)}


def _one_by_one(frame: SceneColumns) -> np.ndarray:
    """Scenes solved one by one: gravity on an inclined flat (stick-slip with re-slip as P falls), or a
    compliant tangential contact with tangential motion (its tangential motion is integrated)."""
    tangential = (incidence(frame) > 0) | (frame["spin"] != 0)
    return ((frame["gravity"] > 0) & (frame["angle"] > 0)) | (_compliant(frame) & tangential)


def _series_lanes(d: Numbers) -> np.ndarray:
    """Scenes the batched Taylor lanes take (:mod:`.series_lanes`): eq. 4.2 without gravity up to critical
    damping and lam 1e12 (their tested domain)."""
    with np.errstate(invalid="ignore"):
        return d.modified & (d.gamma == 0) & series_lanes.covers(d.zeta, d.lam) & np.isfinite(d.w)


def _beyond_lanes(d: Numbers, series: np.ndarray) -> np.ndarray:
    """Scenes of a batched kernel or closed form that those paths cannot bound: damping beyond
    :data:`LANES_ZETA_MAX`, dimensionless numbers that are not finite (e.g. mass 1e-300, b 1e300), or lam
    beyond :data:`LANES_LAM_MAX` on the Runge-Kutta lanes (not the Taylor lanes' ``series`` scenes).  They
    go to the single-impact path, whose cost is bounded (:data:`sphereimpact.integrators.normal.MAX_NFEV`)."""
    with np.errstate(invalid="ignore"):
        wild = ~(np.isfinite(d.zeta) & np.isfinite(d.lam) & np.isfinite(d.w) & np.isfinite(d.gamma))
        sharp = d.modified & (d.lam > LANES_LAM_MAX) & ~series
        return d.batched & (wild | (d.zeta > LANES_ZETA_MAX) | sharp)


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


def solved_alone(frame: SceneColumns, d: Numbers, target: float, limits: dict | None = None) -> tuple[np.ndarray, dict]:
    """(scenes solved one by one, the lane limit per criterion).

    One by one: :func:`_one_by_one` and :func:`_beyond_lanes` scenes, and the scenes the Runge-Kutta lanes
    would integrate (a kernel, not the closed form's nor the Taylor lanes') whose estimated steps
    (:func:`batch.estimated_steps`) exceed their criterion's limit (:func:`_lane_limit`).  The limits are
    computed on these scenes unless ``limits`` is given: a shard takes the whole sweep's (``span``), so shards
    and chunk sizes do not change which path a scene takes.
    """
    series = _series_lanes(d)
    alone = _one_by_one(frame) | _beyond_lanes(d, series)
    lanes = d.batched & ~(d.closed & (d.gamma == 0)) & ~series & ~alone  # Runge-Kutta lanes
    computed = {}
    for separation in Separation:
        mine = np.flatnonzero(lanes & d.criterion(separation))
        if not mine.size:
            continue
        zeta, lam = d.zeta[mine], d.lam[mine]
        steps = batch.estimated_steps(zeta, lam, separation, target)
        if limits is None:
            evaluations = 400.0 + 100.0 * batch.estimated_contact_time(zeta, lam, separation)
            computed[separation] = _lane_limit(steps, SINGLE_COST + SINGLE_EVAL_COST * evaluations)
        alone[mine] |= steps > (computed if limits is None else limits).get(separation, np.inf)
    return alone, computed if limits is None else limits


class SinglePath(SweepPath):
    """Gravity on a slope, a compliant tangential contact at an angle, and the scenes the lanes cannot bound
    or would solve at more cost than alone (:func:`solved_alone`): ``simulate``, one impact at a time."""

    name = "single"
    summary = "simulate, one impact at a time (gravity on a slope, compliant contact, outside the paths below)"
    gives = Gives.ALL

    def take(self, work, todo, span_todo):
        alone_span, limits = solved_alone(work.span_frame, work.span, work.target)
        alone = solved_alone(work.frame, work.numbers, work.target, limits)[0] if work.sharded else alone_span
        rows = np.flatnonzero(alone & todo)
        return Take([Task(rows, lambda: self._solve(rows, work))] if rows.size else [], alone_span)

    @staticmethod
    def _solve(rows: np.ndarray, work: Work) -> dict:
        """Every output of ``simulate`` on each row (:meth:`solve_rows`)."""
        return SinglePath.solve_rows(work.frame, rows, work, "sweep row")

    @staticmethod
    def solve_rows(frame: SceneColumns, rows, work: Work, what: str) -> dict:
        """``simulate`` on each of ``frame``'s ``rows``, :data:`SINGLES_CHUNK` per call (a batched tangential kernel
        runs them together), the chunks shared among ``work.jobs`` processes (:mod:`.processes`), progress after
        each; their outputs as columns (:func:`_columns`), in ``rows``' order.  An ImpactError names the first
        failing one as ``what`` ``rows[i]``.

        Memory is bounded by the chunk, not the rows: a chunk's scenes and outcomes (a solved motion keeps its
        dense output, tens of kB) are dropped once their outputs are read.  The rows of one normal problem (a map
        over spin, friction or the tangential stiffness; grouped by the table's columns but those the normal motion
        does not read) are solved in one call, sharing their normal motion
        (:func:`~sphereimpact.impact.solve.reusing_normal_motions`, which keeps a call's motions only while it
        runs): each outcome is still the one ``simulate`` gives its scene alone."""
        rows = np.asarray(rows)
        problem = first_rows({name: values[rows] for name, values in frame.items() if name not in TANGENTIAL_ONLY})[0]
        order = np.argsort(problem, kind="stable")  # each problem's rows together, in order of first appearance
        places = [order[start:start + SINGLES_CHUNK] for start in range(0, len(rows), SINGLES_CHUNK)]
        compiled = sum(int(np.count_nonzero(frame["model"][rows] == name)) for name in np.unique(frame["model"][rows])
                       if LAWS[name].kernel is not None or LAWS[name].series_kernel is not None)
        expect_evaluations(compiled * SINGLE_EVALUATIONS)  # the work is known: the compiled integrators at once

        def solve(place: np.ndarray) -> dict:
            chunk = rows[place]
            scenes = [scene_of(row) for row in frame.records(chunk)]
            with warnings.catch_warnings():  # the table flags these in its beyond_radius, energy_gained columns
                warnings.simplefilter("ignore", BeyondRadiusWarning)
                warnings.simplefilter("ignore", EnergyGainWarning)
                try:
                    with reusing_normal_motions():
                        return _columns(simulate_many(scenes, work.options))
                except ImpactError:
                    for i, scene in zip(chunk, scenes):  # the first that fails alone
                        try:
                            simulate(scene, work.options)
                        except ImpactError as err:
                            raise ImpactError(f"{what} {i}: {err}") from None
                    raise

        out: dict = {}
        done = 0
        for place, columns in zip(places, solved_chunks(solve, places, work.jobs)):
            for key, values in columns.items():
                out.setdefault(key, np.empty(len(rows), dtype=values.dtype))[place] = values
            done += len(place)
            if work.progress:
                work.progress(done, len(rows))
        return out


# ---------------------------------------------------------------- scenes alike but for their scales




def _similar_keys(frame: SceneColumns, d: Numbers, rows: np.ndarray) -> dict:
    """The dimensionless problem of each of ``rows`` (a compliant tangential contact, no gravity) as a hashable
    key: its law's family (or zeta and lam), separation criterion, tangential model, kappa, inertia factor,
    friction, incidence, spin R / v_n and its models' own parameters.  Two scenes with one key differ only in
    their scales: every output of one is the other's, scaled (:data:`SCALES`)."""
    if not len(rows):  # (a table without such scenes reads none of its columns)
        return {}
    angle = incidence(frame)
    columns = [frame[name] for name in ("tangential", "kappa", "inertia_factor", "mu")]
    own = [values for name, values in frame.items() if name not in SCENE_COLUMNS]  # the models' own
    spin_ratio = frame["spin"] * 0.5 * frame["diameter"] / d.v_n
    def same(value):  # an empty cell (NaN) equals another, as a key
        return None if isinstance(value, float) and value != value else value

    keys = {}
    for i in rows:
        normal = d.family[i] if d.family[i] is not None else (frame["model"][i], d.zeta[i], d.lam[i])
        keys[i] = tuple(same(v) for v in (normal, bool(d.force[i]), *(c[i] for c in columns), angle[i], spin_ratio[i],
                                          *(float(c[i]) for c in own)))
    return keys


def _scales(frame: SceneColumns, d: Numbers, rows) -> dict:
    """The scales (:data:`SCALES`) of the scenes ``rows`` (indices), as arrays."""
    mass, radius = frame["mass"][rows], 0.5 * frame["diameter"][rows]
    v_n, w = d.v_n[rows], d.w[rows]
    return {"time": 1.0 / w, "length": v_n / w, "speed": v_n, "spin": v_n / radius, "force": mass * v_n * w,
            "energy": mass * v_n * v_n}


class SimilarPath(SweepPath):
    """Scenes of a compliant tangential contact (solved one impact at a time) whose model declares itself
    ``scale_free`` and that share their dimensionless problem with others of the sweep: ``simulate`` once per
    problem, on its first scene in the sweep's span, each output scaled to the others (the solvers work in the
    contact's own scales, so the outputs scale exactly, to the tolerance of one solve).  A map of one ball over
    angle and speed has one problem per angle when the law's family does not change with speed (an elastic
    Hertz contact, a damping set per speed)."""

    name = "similar"
    summary = "simulate once per dimensionless problem, scaled to the scenes that share it (compliant contact)"
    gives = Gives.ALL

    def take(self, work, todo, span_todo):
        def eligible(frame, d, mask):
            names = frame["tangential"]
            free = np.zeros(names.shape, bool)
            for name, model in TANGENTIALS.items():
                if model.scale_free:  # a model that does not declare it is solved scene by scene
                    free |= names == name
            if not (mask & free).any():
                return np.zeros(0, dtype=np.int64)
            return np.flatnonzero(mask & free & _one_by_one(frame) & (frame["gravity"] == 0)
                                  & np.isfinite(d.w))

        span_keys = _similar_keys(work.span_frame, work.span, eligible(work.span_frame, work.span, span_todo))
        first, count = {}, {}
        for i, key in span_keys.items():
            first.setdefault(key, i)
            count[key] = count.get(key, 0) + 1
        shared = {key for key, n in count.items() if n > 1}
        taken = np.zeros(len(work.span_frame), bool)
        taken[[i for i, key in span_keys.items() if key in shared]] = True
        keys = span_keys if not work.sharded else _similar_keys(work.frame, work.numbers,
                                                                  eligible(work.frame, work.numbers, todo))
        members: dict = {}
        for i, key in keys.items():
            if key in shared and todo[i]:
                members.setdefault(key, []).append(i)
        if not members:
            return Take([], taken)
        rows = np.sort(np.concatenate([np.array(group) for group in members.values()]))
        return Take([Task(rows, lambda: self._solve(rows, members, first, work))], taken)

    @staticmethod
    def _solve(rows: np.ndarray, members: dict, first: dict, work: Work) -> dict:
        """Each problem's representative solved by ``simulate`` (a batched tangential kernel runs them together),
        its outputs scaled to every member."""
        keys = list(members)
        firsts = np.array([first[key] for key in keys])
        solved = SinglePath.solve_rows(work.span_frame, firsts, work, "sweep span row")
        which = np.empty(rows.size, dtype=np.int64)  # each row's problem, as an index into keys
        position = np.searchsorted(rows, np.concatenate([members[key] for key in keys]))
        which[position] = np.repeat(np.arange(len(keys)), [len(members[key]) for key in keys])
        theirs, own = _scales(work.frame, work.numbers, rows), _scales(work.span_frame, work.span, firsts[which])
        out = {name: values[which] for name, values in solved.items()}
        for name, scale in SCALES.items():
            out[name] = out[name] * (theirs[scale] / own[scale])
        return out


# ---------------------------------------------------------------- laws without a batched kernel


def _family_groups(d: Numbers, mask: np.ndarray) -> dict:
    """(model, the family's other numbers, criterion) -> indices of the kernel-less weightless scenes of
    ``mask`` with a positive last family number, the one :class:`FamilyInterpolant` interpolates in."""
    groups: dict = {}
    for i in np.flatnonzero(mask & ~d.batched & (d.gamma == 0)):
        family = d.family[i]
        if len(family) > 1 and family[-1] > 0:
            groups.setdefault((*family[:-1], d.criterion_of(i)), []).append(i)
    return groups


class FamilyInterpolantPath(SweepPath):
    """A kernel-less law's weightless scenes where at least :data:`FAMILY_MIN` distinct values of its last
    family number (proportional to the approach speed: chi v_n of the Hunt-Crossley laws) share the rest:
    a Chebyshev interpolant in that number over the span's range, from single-impact solves, checked."""

    name = "family-interpolant"
    summary = "a kernel-less law's interpolant in its last family number"

    def take(self, work, todo, span_todo):
        span, d = work.span, work.numbers
        built = {}
        taken = np.zeros(len(span), bool)
        # grouping is a Python pass over the rows: made once when the scenes to solve are the span's
        span_todo, todo = span_todo & work.span_needs.completes, todo & work.needs.completes
        span_groups = _family_groups(span, span_todo)
        same = not work.sharded and np.array_equal(todo, span_todo)
        for key, rows in span_groups.items():
            q = np.array([span.family[i][-1] for i in rows])
            if np.unique(q).size < FAMILY_MIN:
                continue
            try:
                built[key] = FamilyInterpolant(scene_of(work.span_frame.record(rows[0])), float(q.min()),
                                               float(q.max()), key[-1], work.target, extremes=work.needs.extremes,
                                               grips=work.span_needs.grips(rows).any())
            except InterpolationError:  # such a group is solved family by family
                continue
            taken[rows] = True
        tasks = []
        for key, rows in (span_groups if same else _family_groups(d, todo)).items():
            if key in built:
                rows = np.array(rows)
                q = np.array([d.family[i][-1] for i in rows])
                levels = work.needs.levels_of(rows)
                tasks.append(Task(rows, lambda interpolant=built[key], q=q, levels=levels: interpolant(q, levels)))
        return Take(tasks, taken)


class PerFamilyPath(SweepPath):
    """The other scenes of a kernel-less law: the single-impact integrator (exact for every law) solves one
    scene of each distinct (family, gamma, criterion), the whole sweep's first (so a shard solves the scene
    the whole sweep would), and the others, which share its dimensionless motion, take its values."""

    name = "per-family"
    summary = "one single-impact solve per dimensionless family, shared by its scenes"

    def take(self, work, todo, span_todo):
        d = work.numbers
        rows = np.flatnonzero(~d.batched & todo & work.needs.completes)
        span = span_todo & ~work.span.batched & work.span_needs.completes
        task = Task(rows, lambda: self._solve(work, rows, np.flatnonzero(span)))
        return Take([task] if rows.size else [], span)

    @staticmethod
    def _keys(d: Numbers, rows: np.ndarray) -> list:
        """The family key (model, numbers, gamma, force criterion) of each of ``rows``."""
        return [(*f, float(g), bool(force)) for f, g, force in zip(d.family[rows], d.gamma[rows], d.force[rows])]

    @classmethod
    def _solve(cls, work: Work, rows: np.ndarray, span_rows: np.ndarray) -> dict:
        """The rows' normal outputs, each family's from its first scene among the span's rows this path takes
        (``span_rows``: not those an earlier path took)."""
        extremes, levels = work.needs.extremes, work.needs.levels[rows]
        options = work.options
        keys = cls._keys(work.numbers, rows)
        members: dict = {}
        for i, key in enumerate(keys):
            members.setdefault(key, []).append(i)
        first = {}  # each family's first scene in the whole sweep: what a shard solves is the sweep's
        if work.sharded:
            for i, key in zip(span_rows, cls._keys(work.span, span_rows)):
                if key in members:
                    first.setdefault(key, work.span_frame.record(i))
        names = [*NORMAL_OUTPUTS, *(EXTREMES if extremes else ())]
        out = {name: np.empty(len(keys)) for name in names} | {"tau_g": np.full(len(keys), np.nan)}
        for key, mine in members.items():
            mine = np.array(mine)
            known = mine[np.isfinite(levels[mine])]  # the family's dimensionless motion serves every level
            scene = first[key] if key in first else work.frame.record(rows[mine[0]])
            solved = dimensionless_motion(scene_of(scene), options, extremes,
                                          levels[known] if known.size else None)
            for name in names:
                out[name][mine] = solved[name]
            if known.size:
                out["tau_g"][known] = solved["tau_g"]
        return out


# ---------------------------------------------------------------- laws with a batched kernel, without gravity


class _ByCriterion(SweepPath):
    """A path that takes every remaining row it admits, one task per separation criterion, solved in chunks
    of ``work.chunk_size`` (progress after each)."""

    def admits(self, d: Numbers, needs: Needs) -> np.ndarray:
        """Mask of the scenes of ``d`` this path can solve, giving what ``needs`` asks."""
        raise NotImplementedError

    def solve(self, d: Numbers, rows: np.ndarray, separation: Separation, target: float, needs: Needs) -> dict:
        """:data:`NORMAL_OUTPUTS` of the scenes ``rows`` of ``d`` under ``separation``, and what ``needs``
        asks of them."""
        raise NotImplementedError

    def take(self, work, todo, span_todo):
        d = work.numbers
        admitted = self.admits(d, work.needs) & work.needs.completes
        tasks = []
        for separation in Separation:
            rows = np.flatnonzero(todo & d.criterion(separation) & admitted)
            if rows.size:
                tasks.append(Task(rows, lambda rows=rows, s=separation: _chunked(
                    rows, work.chunk_size, lambda i: self.solve(d, i, s, work.target, work.needs), work.progress)))
        return Take(tasks, span_todo & self.admits(work.span, work.span_needs) & work.span_needs.completes)


class ClosedPath(_ByCriterion):
    """A law with a closed form, without gravity: its weightless events, vectorised (``ClosedForm.events``;
    eq. 4.1's in :mod:`sphereimpact.contact.laws.spring_damper`)."""

    name = "closed"
    summary = "the law's closed-form events"

    def admits(self, d, needs):
        """Weightless scenes of a law with a closed form; where a row needs more than the events, a closed
        form that declares its ``jet`` (from which the extremes and grip instants follow)."""
        jets = np.array([form.jet is not None for form in CLOSED_FORMS] + [False])  # code -1: no closed form
        extras = needs.extremes | np.isfinite(needs.levels)
        return d.closed & (d.gamma == 0) & (jets[d.closed_form] | ~extras) & ~_beyond_lanes(d, _series_lanes(d))

    def solve(self, d, rows, separation, target, needs):
        codes = d.closed_form[rows]
        out = None
        for code in np.unique(codes):
            mine = np.flatnonzero(codes == code)
            form = CLOSED_FORMS[code]
            numbers = {name: getattr(d, name)[rows[mine]] for name in form.reads}
            values = form.events(numbers, separation)
            if needs.extremes:
                values |= form.extremes(numbers, values["tau_f"])
            levels = needs.levels[rows[mine]]
            if np.isfinite(levels).any():
                values["tau_g"] = np.full(mine.size, np.nan)
                known = np.flatnonzero(np.isfinite(levels))
                values["tau_g"][known] = form.grip_instants({k: v[known] for k, v in numbers.items()}, levels[known],
                                                            *(values[k][known] for k in ("tau_m", "tau_f", "j_p")))
            if codes.size == mine.size:  # one law's closed form (the usual case)
                return values
            if out is None:
                out = {name: np.full(rows.size, np.nan) for name in values}
            for name, value in values.items():
                out.setdefault(name, np.full(rows.size, np.nan))[mine] = value
        return out


class LambdaInterpolantPath(SweepPath):
    """Eq. 4.2 without gravity, at least :data:`SIMILARITY_MIN` scenes of the span sharing zeta and the
    criterion (one ball): a Chebyshev interpolant in lam over the span's range, checked against the
    integrator (:class:`.similarity.LambdaInterpolant`)."""

    name = "lambda-interpolant"
    summary = "eq. 4.2's interpolant in lam at one damping ratio"

    def take(self, work, todo, span_todo):
        span, d = work.span, work.numbers
        taken = np.zeros(len(span), bool)
        tasks = []
        similar = np.flatnonzero(span_todo & span.modified & (span.gamma == 0) & work.span_needs.completes)
        for criterion in Separation:
            mine = similar[span.criterion(criterion)[similar]]
            zetas, group, counts = np.unique(span.zeta[mine], return_inverse=True, return_counts=True)
            for i in np.flatnonzero(counts >= SIMILARITY_MIN):
                members = mine[group == i]
                lam = span.lam[members]
                try:
                    interpolant = LambdaInterpolant(float(zetas[i]), lam.min(), lam.max(), criterion, work.target,
                                                    extremes=work.needs.extremes,
                                                    grips=work.span_needs.grips(members).sum() >= GRIP_TABLE_MIN)
                except InterpolationError:  # such a group is integrated scene by scene instead
                    continue
                taken[members] = True
                rows = np.flatnonzero(todo & d.criterion(criterion) & d.modified & (d.gamma == 0)
                                      & (d.zeta == zetas[i]) & work.needs.completes)
                outside = rows[(d.lam[rows] < interpolant.lo) | (d.lam[rows] > interpolant.hi)]
                if outside.size:  # a span that does not cover its shard: interpolation would extrapolate
                    raise ValueError(f"span does not cover the scenes: scene {int(outside[0])} has lam = "
                                     f"{d.lam[outside[0]]:.6g} outside the span's [{interpolant.lo:.6g}, "
                                     f"{interpolant.hi:.6g}]; pass the whole sweep as span")
                tasks.append(Task(rows, lambda rows=rows, f=interpolant: _chunked(
                    rows, work.chunk_size, lambda i: f(d.lam[i], work.needs.levels_of(i)))))
        return Take(tasks, taken)


class PlanePath(SweepPath):
    """Eq. 4.2 without gravity, at least :data:`PLANE_MIN` scenes of one criterion with zeta up to
    :data:`.plane.ZETA_MAX` (many balls: k, b, m, D drawn per scene): one Chebyshev interpolant in
    (zeta, lam) over the span's rectangle, its nodes solved by the batched Taylor lanes (:mod:`.plane`)."""

    name = "plane"
    summary = "eq. 4.2's interpolant on the (zeta, lam) plane"

    @staticmethod
    def _inside(d: Numbers, mask: np.ndarray, separation: Separation) -> np.ndarray:
        return np.flatnonzero(mask & d.modified & (d.gamma == 0) & d.criterion(separation) & (d.zeta > 0)
                              & (d.zeta <= plane.ZETA_MAX) & (d.lam >= plane.LAM_MIN) & (d.lam <= plane.LAM_MAX))

    def take(self, work, todo, span_todo):
        span, d = work.span, work.numbers
        taken = np.zeros(len(span), bool)
        tasks = []
        for separation in Separation:
            members = self._inside(span, span_todo & work.span_needs.completes, separation)
            if members.size < PLANE_MIN:
                continue
            zeta, lam = span.zeta[members], span.lam[members]
            try:
                f = plane.PlaneInterpolant(zeta.min(), zeta.max(), lam.min(), lam.max(), separation, work.target,
                                           extremes=work.needs.extremes)
            except InterpolationError:  # integrated by the lanes instead
                continue
            taken[members] = True
            rows = self._inside(d, todo & work.needs.completes, separation)
            outside = rows[(d.zeta[rows] < f.zeta_min) | (d.zeta[rows] > f.zeta_max)
                           | (d.lam[rows] < f.lam_min) | (d.lam[rows] > f.lam_max)]
            if outside.size:
                raise ValueError(f"span does not cover the scenes: scene {int(outside[0])} (zeta = "
                                 f"{d.zeta[outside[0]]:.6g}, lam = {d.lam[outside[0]]:.6g}) lies outside the span's "
                                 "plane; pass the whole sweep as span")
            tasks.append(Task(rows, lambda rows=rows, f=f: _chunked(
                rows, work.chunk_size, lambda i: f(d.zeta[i], d.lam[i], work.needs.levels_of(i)))))
        return Take(tasks, taken)


class TaylorLanesPath(_ByCriterion):
    """Eq. 4.2 without gravity up to critical damping: the batched Taylor-series lanes (:mod:`.series_lanes`)."""

    name = "taylor-lanes"
    summary = "batched Taylor-series lanes"

    def admits(self, d, needs):
        return _series_lanes(d)

    def solve(self, d, rows, separation, target, needs):
        return series_lanes.integrate(d.zeta[rows], d.lam[rows], separation, target, levels=needs.levels_of(rows),
                                      extremes=needs.extremes)


class RungeKuttaLanesPath(_ByCriterion):
    """Every other scene of a batched kernel: the batched Runge-Kutta lanes (:mod:`.batch`)."""

    name = "runge-kutta-lanes"
    summary = "batched Runge-Kutta lanes"

    def admits(self, d, needs):  # (eq. 4.2 beyond LANES_LAM_MAX also where the Taylor lanes would take it)
        return d.batched & ~_beyond_lanes(d, np.zeros(len(d), bool))

    def solve(self, d, rows, separation, target, needs):
        return batch.integrate(d.zeta[rows], d.lam[rows], d.gamma[rows], d.modified[rows], separation, target,
                               levels=needs.levels_of(rows), extremes=needs.extremes)


#: The paths in their precedence: the first that takes a row solves it.
ORDER = (SimilarPath(), SinglePath(), FamilyInterpolantPath(), PerFamilyPath(), ClosedPath(), LambdaInterpolantPath(),
         PlanePath(), TaylorLanesPath(), RungeKuttaLanesPath())
#: name -> summary of every path, in precedence order (the ``path`` column's values).
PATHS = {path.name: path.summary for path in ORDER}
