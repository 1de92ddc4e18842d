"""The sweep engine: a table of scenes in, a table of outcomes out.

Each scene takes the first path of :data:`.paths.ORDER` that takes it (:mod:`.paths`: the single-impact
model for gravity on a slope, compliant contact and scenes the fast paths cannot bound; a kernel-less law's
interpolant or per-family solves; a law's closed form; eq. 4.2's interpolants in lam or on the (zeta, lam)
plane; the batched Taylor and Runge-Kutta lanes).  Every path but the single-impact one gives the
dimensionless normal motion (:data:`~.outputs.NORMAL_OUTPUTS`) and what each row needs beyond it
(:class:`~.outputs.Needs`: the force's extremes, the instant the friction-carrying impulse reaches the level
the row's tangential model asks for), from which the row's tangential model gives its tangential end state
(:class:`~sphereimpact.contact.tangential.SweptTangential`) and :func:`~sphereimpact.impact.outcome.outputs`
every output, as for ``simulate``.  Results do not depend on the chunk size or on sharding: every lane is
integrated independently and interpolants are built on the whole sweep.
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd

from ..errors import EnergyGainWarning, ImpactError, UnitWarning
from ..impact.declarations import HISTORY_OUTPUTS
from ..impact.inputs import check_flag, density_problem
from ..impact.outcome import NUMERIC_OUTPUTS, SCALAR_OUTPUTS, EndState, gains_energy, outputs
from ..parsing import parse_range  # noqa: F401  (re-exported: sweeps take ranges as text)
from ..contact.tangential import TANGENTIALS, Regime
from .outputs import EXTREMES, NORMAL_OUTPUTS, Needs
from .pairs import has_partner, pair_sweep
from .processes import checked_jobs
from .paths import ORDER, PATHS, Gives, Work, single_options
from .scenes import (SCENE_COLUMNS, Numbers, SceneColumns, _objects, given_table, grid, incidence, numbers, rows,
                     scene_columns, scene_of, scene_table, undescribed_row)

#: The engine's public names; the scene table's and the paths' are re-exported from :mod:`.scenes` and
#: :mod:`.paths`, where they are defined.
__all__ = ["HISTORY_OUTPUTS", "FAST_OUTPUTS", "PATHS", "SCENE_COLUMNS", "SWEEP_OUTPUTS", "grid", "incidence",
           "outputs_wanted", "parse_range", "rows", "scene_of", "scene_table", "sweep"]

#: Outputs of a sweep: every scalar output of ``simulate``, named as it names them (one list, shared).
SWEEP_OUTPUTS = SCALAR_OUTPUTS
#: The outputs the fast paths compute from the end state alone (``outputs=FAST_OUTPUTS``: the fastest sweep).
FAST_OUTPUTS = tuple(key for key in SWEEP_OUTPUTS if key not in HISTORY_OUTPUTS)


def sweep(scenes, target: float = 1e-8, chunk_size: int = 100_000, progress=None, span=None,
          outputs=None, settings=None, paths=None, chapter_ball: bool = False, jobs: int | None = None) -> pd.DataFrame:
    """Simulate every scene of a table.

    Parameters
    ----------
    scenes : DataFrame or dict
        Named as :class:`sphereimpact.Scene` fields (``angle`` [deg], ``speed`` [m/s], ``mass``,
        ``diameter``, ``inertia_factor``, ``mu``, ``model``, ``k``, ``b``, ``ramp``, ``gravity``,
        ``separation``, ``tangential``, ``kappa``, ``spin``, ...) or a model's own parameters; missing ones take
        their defaults, but the ball and its speed are the user's: each row gives ``mass``, ``diameter``,
        ``speed`` and, for a law whose defaults are the chapter's (``modified``, ``kelvin-voigt``), its stiffness
        and damping, unless ``chapter_ball``.  ``partner_mass`` and ``partner_diameter`` (``partner_inertia_factor``,
        ``partner_spin``) give a row a partner sphere instead of the flat (empty cells: the flat): the table then
        gains the partner's outputs (:mod:`.pairs`).
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
        ``simulate``).  :data:`FAST_OUTPUTS` leaves out :data:`HISTORY_OUTPUTS`.
    settings : mapping of str to int, optional
        The tangential models' numerical settings (``microslip``'s ``elements`` and ``time_steps``), as
        :class:`sphereimpact.SolverOptions` takes them.
    paths : sequence of str, optional
        Only these paths (names of :data:`PATHS`, in their precedence), for studies of a path alone: a row
        none of them takes is left empty (NaN outputs, ``path`` ''), where the default (every path) solves
        every row.
    chapter_ball : bool
        Take the chapter's ball (0.145 kg, 0.063 m, k = 60000 N/m, b = 10.5 N s/m) and speed (3 m/s) where a row is
        silent (default False: such a row is refused, as on the command line; only ``simulate`` takes the chapter's
        scene unasked).
    jobs : int or None
        Most processes that share the scenes solved one at a time by ``simulate`` (the single-impact path), forks
        of this one (:mod:`.processes`; default None: the environment's ``SPHEREIMPACT_JOBS``, else every CPU this
        process may use; 1: this process alone).  The
        table is the same to the bit whatever it is; the other paths run in this process.

    Returns
    -------
    DataFrame
        The scene columns followed by the outputs (in :data:`SWEEP_OUTPUTS`' order; SI units, angles in
        degrees), one row per scene, in order, then ``path``: which path solved the row (:data:`PATHS`).
        ``t_roll`` is empty (NaN) where the contact point never stops slipping, as ``simulate`` gives None.

    Raises
    ------
    ValueError
        A parameter out of range (naming it and the first bad row), a row that does not describe its ball (unless
        ``chapter_ball``), or a bad target or chunk size.
    ImpactError
        A scene that never separates.
    """
    if isinstance(target, (bool, np.bool_)) or not isinstance(target, (float, np.floating)) \
            or not 1e-12 <= target <= 1e-3:
        raise ValueError(f"target must be a number in [1e-12, 1e-3]; got {target!r}")
    if isinstance(chunk_size, (bool, np.bool_)) or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1:
        raise ValueError(f"chunk_size must be an integer >= 1; got {chunk_size!r}")
    jobs = checked_jobs(jobs)
    check_flag("chapter_ball", chapter_ball)
    if not isinstance(scenes, dict):  # once: the ball's check and the table read the same columns
        scenes = given_table(scenes)
    silent = None if chapter_ball else undescribed_row(scenes)
    if silent is not None:
        row, missing = silent
        raise ValueError(f"sweep: describe your ball and its speed: row {row} lacks {', '.join(missing)} (a column "
                         "each, its cell filled; a measured COR through calibrate_table; or chapter_ball=True for the "
                         "chapter's); only simulate takes the chapter's scene unasked")
    if has_partner(scenes) or (span is not None and has_partner(span)):  # each pair as its reduced sphere
        return pair_sweep(sweep, scenes, target=target, chunk_size=chunk_size, progress=progress, span=span,
                          outputs=outputs, settings=settings, paths=paths, chapter_ball=True, jobs=jobs)  # described
    wanted = outputs_wanted(outputs)
    order = ORDER if paths is None else [way for way in ORDER if way.name in set(_path_names(paths))]
    frame = scene_columns(scenes)
    n = len(frame)
    slip = density_problem(frame["mass"], frame["diameter"])
    if slip:  # once for the table (a row's Scene does not repeat it)
        warnings.warn(slip, UnitWarning, stacklevel=2)
    result = {key: np.full(n, np.nan) for key in SWEEP_OUTPUTS if key in NUMERIC_OUTPUTS}
    regime, path = _objects(n, Regime.NONE), _objects(n, "")
    options = single_options(target, settings)
    d = numbers(frame)
    needs = needs_of(frame, d, wanted)
    if span is None:
        span_frame, span_d, span_needs = frame, d, needs
    else:
        span_frame = scene_columns(span)
        span_d = numbers(span_frame)
        span_needs = needs_of(span_frame, span_d, wanted)
    work = Work(frame, d, needs, span_frame, span_d, span_needs, target, chunk_size, options, progress, jobs)
    normal = {key: np.full(n, np.nan) for key in (*NORMAL_OUTPUTS, *EXTREMES, "tau_g")}
    todo, span_todo, rest = np.ones(n, bool), np.ones(len(span_frame), bool), np.zeros(n, bool)
    for way in order:
        taken = way.take(work, todo, span_todo)
        for task in taken.tasks:
            for key, values in task.solve().items():
                (regime if key == "regime" else result[key] if way.gives is Gives.ALL else normal[key])[task.rows] = values
            path[task.rows] = way.name
            todo[task.rows] = False
            rest[task.rows] = way.gives is Gives.NORMAL  # completed below: tangential models, then outputs()
        span_todo &= ~taken.span
    if todo.any() and paths is None:  # every row has a path: the last takes every batched kernel, earlier the others
        raise ImpactError(f"sweep: no path takes row {int(np.flatnonzero(todo)[0])}")
    if rest.any():
        values = _complete(frame.take(rest), d[rest], {key: values[rest] for key, values in normal.items()})
        for key, value in values.items():
            if key == "regime":
                regime[rest] = value
            elif key in result:
                result[key][rest] = value
    checked = [key for key in result if key in wanted and key != "t_roll"]
    finite = np.logical_and.reduce([np.isfinite(result[key]) for key in checked]) if checked else np.ones(n, bool)
    finite |= todo  # rows no path took (only with ``paths``) stay empty
    if not finite.all():  # never a NaN in a table
        i = int(np.flatnonzero(~finite)[0])
        scene = ", ".join(f"{k}={v}" for k, v in frame.record(i).items())
        raise ImpactError(f"sweep: no finite outputs for row {i} ({scene}); its contact lies outside what the "
                          "sweep resolves: try `sphereimpact simulate` on that scene")
    radius = 0.5 * frame["diameter"]
    beyond = result["delta_m"] > radius  # outside the model, as simulate flags it
    mass = frame["mass"]
    gained = gains_energy(result["work_t"], mass, frame["speed"], frame["inertia_factor"] * mass * radius * radius,
                          frame["spin"])
    if not todo.any():  # (rows no path took, with ``paths``, keep NaN)
        result["switches"] = result["switches"].astype(np.int64)
    if gained.any():
        warnings.warn(f"in {int(gained.sum())} of {n} scenes the tangential model made energy (column energy_gained; "
                      f"work_t up to +{result['work_t'][gained].max():.3g} J): an artefact of the model, not of the "
                      "ball", EnergyGainWarning, stacklevel=2)
    values = result | {"regime": pd.Series(regime, dtype=object), "beyond_radius": beyond, "energy_gained": gained}
    outputs = {key: values[key] for key in SWEEP_OUTPUTS if key in wanted}  # only these: a frame of all cost more
    return frame.frame(outputs | {"path": pd.Series(path, dtype=object)})


def needs_of(frame: SceneColumns, d: Numbers, wanted: set) -> Needs:
    """What each row needs of a fast path beyond the normal outputs (:class:`~.outputs.Needs`): the force's
    extremes when force_min or force_max is wanted; with t_roll, the level of J+ / (m v_n) at which its
    tangential model needs the instant (its ``swept.levels``; NaN for a normal impact, and for a model a
    sweep solves scene by scene); and whether its tangential end follows from the normal motion at all."""
    levels = np.full(len(frame), np.nan)
    rows = tangential_rows(frame, d)
    moving = (rows.v_tangent != 0) | (rows.spin != 0)
    slope = (rows.gravity > 0) & (rows.angle > 0)  # gravity along the flat: no tangential end in closed form
    completes = ~moving & ~slope
    names = frame["tangential"]
    for name in dict.fromkeys(names[moving].tolist()):
        model = TANGENTIALS[name].swept
        if model is None:
            continue
        mine = np.flatnonzero(moving & (names == name))
        completes[mine] = ~slope[mine]
        if "t_roll" in wanted:
            levels[mine] = model.levels(_Rows(rows, mine)) / (rows.mass[mine] * rows.v_normal[mine])
    return Needs(extremes=bool({"force_min", "force_max"} & wanted), levels=levels, completes=completes)


def _complete(part: SceneColumns, d: Numbers, dim: dict) -> dict:
    """Every output of the rows ``part`` that a path solved in dimensionless normal form ``dim``
    (:data:`NORMAL_OUTPUTS`, the force's extremes and the instants of the tangential models' levels where
    asked): the normal events and extremes in SI units, the tangential motion's end from each row's
    tangential model (its :class:`~sphereimpact.contact.tangential.SweptTangential`, given the friction-carrying
    impulse J+ = m v_n j_p and those instants), then :func:`~sphereimpact.impact.outcome.outputs`, as
    ``simulate`` derives them."""
    n = len(part)
    w, v_n, m = d.w, d.v_n, part["mass"]
    rows = tangential_rows(part, d)
    impulse, instants = m * v_n * dim["j_p"], dim["tau_g"] / w
    tangential = {"vc_t": np.zeros(n), "omega_f": np.zeros(n), "t_roll": np.full(n, np.nan),
                  "switches": np.zeros(n, np.int64), "regime": _objects(n, Regime.NONE)}
    moving = (rows.v_tangent != 0) | (rows.spin != 0)  # tangential motion at all: a normal impact has none
    names = part["tangential"]
    for name in dict.fromkeys(names[moving].tolist()):
        mine = np.flatnonzero(moving & (names == name))
        for key, value in TANGENTIALS[name].swept.end(_Rows(rows, mine), impulse[mine], instants[mine]).items():
            tangential[key][mine] = value
    force = m * v_n * w  # the force scale [N]
    end = EndState(mass=m, radius=rows.radius, inertia_factor=rows.inertia_factor, v_normal=v_n,
                   v_tangent=rows.v_tangent, spin=rows.spin, g_tangent=np.zeros(n), t_m=dim["tau_m"] / w,
                   delta_m=dim["x_m"] * v_n / w, t_f=dim["tau_f"] / w, vc_n=-dim["y_f"] * v_n, u_t=np.zeros(n),
                   force_min=dim["p_min"] * force, force_max=dim["p_max"] * force, **tangential)
    return outputs(end)


class _Rows:
    """The columns of ``rows`` (a :func:`tangential_rows` view) at ``index``, each sliced when a model first
    reads it (a model reads a few of the table's columns; slicing them all cost a tenth of a large sweep)."""

    def __init__(self, rows, index: np.ndarray):
        self._rows, self._index = rows, index

    def __getattr__(self, name: str):
        value = getattr(self._rows, name)[self._index]
        setattr(self, name, value)
        return value


class _Columns:
    """The numeric columns of a scene table as arrays, each read when first asked for (a tangential model reads a
    few of them)."""

    def __init__(self, part: SceneColumns, **given):
        self._part = part
        self.__dict__.update(given)

    def __getattr__(self, name: str):
        if name.startswith("_") or name not in self._part or name in TEXT_COLUMNS:
            raise AttributeError(name)
        value = self._part[name]
        setattr(self, name, value)
        return value


#: The text columns of a scene table, which a tangential model does not read as numbers.
TEXT_COLUMNS = ("model", "separation", "tangential")


def tangential_rows(part: SceneColumns, d: Numbers) -> _Columns:
    """The rows' columns as arrays, with ``radius`` [m], ``v_normal`` and ``v_tangent`` [m/s] (the rows'
    :class:`~.scenes.Numbers` ``d``): what a tangential model's :class:`~sphereimpact.contact.tangential.SweptTangential`
    reads."""
    return _Columns(part, radius=0.5 * part["diameter"], v_normal=d.v_n, v_tangent=d.v_t)


def _path_names(paths) -> list:
    """``paths`` as a list of names of :data:`PATHS` (ValueError naming an unknown one)."""
    names = [paths] if isinstance(paths, str) else list(paths)
    unknown = [name for name in names if name not in PATHS]
    if unknown or not names:
        raise ValueError(f"paths must be some of {', '.join(PATHS)}; got {unknown[0] if unknown else 'none'!r}")
    return names


def outputs_wanted(outputs) -> set:
    """The outputs asked for (all when None), checked against :data:`SWEEP_OUTPUTS`."""
    if outputs is None:
        return set(SWEEP_OUTPUTS)
    names = [outputs] if isinstance(outputs, str) else list(outputs)
    unknown = [name for name in names if name not in SWEEP_OUTPUTS]
    if unknown or not names:
        got = unknown[0] if unknown else Regime.NONE
        raise ValueError(f"outputs must be some of {', '.join(SWEEP_OUTPUTS)}; got {got!r}")
    return set(names)
