"""A sweep's scenes: the table of scene parameters, checked, and the dimensionless numbers its paths read.

A sweep is a DataFrame with one scene per row, its columns named as :class:`sphereimpact.Scene` fields
(:func:`rows` pairs values, :func:`grid` takes every combination).  :func:`scene_table` fills and checks it
as the Scene does; :func:`numbers` gives each row the numbers that choose and drive a path
(:class:`Numbers`).
"""

from __future__ import annotations

from collections.abc import Mapping

from dataclasses import dataclass, fields
from types import SimpleNamespace

import numpy as np
import pandas as pd

from ..contact.laws import LAWS, PARAMETER_NAMES
from ..contact.separation import Separation
from ..contact.declared import own_parameters
from ..impact.inputs import PATH_RULES, TEXT_FIELDS, check_columns, own_parameter_columns, scale_problem
from ..impact.pair import PARTNER_FIELDS
from ..impact.scene import FIELD_DEFAULTS, SCENE_KEYS, Scene, bodies_judged
from ..memory import check_size
from ..contact.tangential import TANGENTIAL_PARAMETERS, TANGENTIALS
from . import batch

#: Scene parameters, with the single-impact defaults for missing columns.  A model's own parameters are
#: columns too, after these (those of the models a table names: :func:`own_parameter_columns`).  A partner
#: sphere's columns are not: a table that names them is swept as its reduced spheres' (:mod:`.pairs`).
SCENE_COLUMNS = tuple(name for name in SCENE_KEYS if name not in PARTNER_FIELDS)
DEFAULTS = {name: FIELD_DEFAULTS.get(name) for name in SCENE_COLUMNS}  # None: a parameter (its law's default)


class SceneColumns:
    """A checked table of scenes (:func:`scene_columns`) as one numpy array per column (text columns as object
    arrays), read and sliced as the sweep reads them: a DataFrame cost a fit's twenty-bounce sweep more to build,
    read and slice than its solve.  ``len`` is the number of scenes, ``name in`` asks for a column, ``[name]``
    gives its array, read-only (as a DataFrame's column is: a law's function cannot change the table); :meth:`frame`
    is the DataFrame :func:`scene_table` returns."""

    __slots__ = ("_arrays", "_n")

    def __init__(self, arrays: dict, n: int):
        for values in arrays.values():
            values.flags.writeable = False
        self._arrays, self._n = arrays, n

    def __len__(self) -> int:
        return self._n

    def __contains__(self, name) -> bool:
        return name in self._arrays

    def __getitem__(self, name: str) -> np.ndarray:
        return self._arrays[name]

    def __setitem__(self, name: str, values: np.ndarray) -> None:
        values.flags.writeable = False
        self._arrays[name] = values

    @property
    def columns(self) -> list:
        """The column names, in the table's order."""
        return list(self._arrays)

    def items(self):
        """(name, array) of every column, in order."""
        return self._arrays.items()

    def take(self, rows) -> "SceneColumns":
        """The scenes ``rows`` (a mask or indices), in their order."""
        arrays = {name: values[rows] for name, values in self._arrays.items()}
        return SceneColumns(arrays, len(next(iter(arrays.values()))))

    def record(self, i: int) -> dict:
        """Scene ``i`` as name -> value (what :func:`scene_of` takes)."""
        return {name: values[i] for name, values in self._arrays.items()}

    def records(self, rows=None) -> list[dict]:
        """The scenes ``rows`` (indices; default every scene), each as name -> Python value."""
        columns = [(values if rows is None else values[rows]).tolist() for values in self._arrays.values()]
        names = list(self._arrays)
        return [dict(zip(names, values)) for values in zip(*columns)]

    def frame(self, more: dict | None = None) -> pd.DataFrame:
        """The scenes as a DataFrame (text as object columns), followed by the columns of ``more`` (name -> array
        or Series), built in one go."""
        columns = {name: pd.Series(values, dtype=object) if values.dtype == object else values
                   for name, values in self._arrays.items()}
        return pd.DataFrame(columns | (more or {}))


def scene_table(scenes) -> pd.DataFrame:
    """Scene parameters as a DataFrame with every column, validated (ValueError names the first bad row): the
    :class:`SceneColumns` of :func:`scene_columns`, as a DataFrame."""
    return scene_columns(scenes).frame()


def scene_columns(scenes) -> SceneColumns:
    """Scene parameters with every column, validated (ValueError names the first bad row), as arrays.

    A DataFrame is one scene per row; a dict of values or lists is every combination of them (:func:`grid`),
    as the command line's ranges are.  An empty cell (NaN or None) is a parameter the row does not give, as a
    missing column is for every row: it takes the default, or its law's or model's (so one table may describe
    one row's approach by incidence and another's by the flat's tilt, one Hertz law by k and another by
    modulus), as the sweep's own tables write them."""
    given = given_table(scenes)
    own = own_parameters()
    unknown = [c for c in given.columns if c not in SCENE_COLUMNS and c not in own]
    if unknown:
        raise ValueError(f"unknown scene parameter {unknown[0]!r}; expected some of {', '.join([*SCENE_COLUMNS, *own])}")
    n, arrays = len(given), {name: column.to_numpy() for name, column in given.items()}  # each column read once
    columns = {name: _defaulted(arrays[name], DEFAULTS[name]) if name in arrays
               else _objects(n, DEFAULTS[name]) if name in TEXT_FIELDS else np.full(n, DEFAULTS[name])
               for name in SCENE_COLUMNS if name in arrays or DEFAULTS[name] is not None}
    laws = check_columns(columns | {name: arrays[name] for name in own if name in arrays})
    columns |= {name: laws[name] for name in PARAMETER_NAMES if name != "modulus"}  # checked, modulus -> k
    own_columns = own_parameter_columns(columns | {name: arrays[name] for name in own if name in arrays}, n)
    for name in ("modulus", *TANGENTIAL_PARAMETERS, *PATH_RULES):
        columns.setdefault(name, np.full(n, np.nan))
    columns = {name: np.asarray(columns[name], dtype=object if name in TEXT_FIELDS else float)
               for name in SCENE_COLUMNS} | {name: np.asarray(values, dtype=float) for name, values in own_columns.items()}
    frame = SceneColumns(columns, n)
    paths = ~np.isnan(np.column_stack([columns[name] for name in PATH_RULES]))
    for i in np.flatnonzero(paths.any(axis=1) & ((frame["angle"] != 0) | paths.all(axis=1))):
        try:  # one description of the approach per scene: checked as the Scene checks it
            scene_of(frame.record(i))
        except ValueError as err:
            raise ValueError(f"{err} (row {i})") from None
    tangential = np.column_stack([columns[name] for name in TANGENTIAL_PARAMETERS])
    rows = np.flatnonzero(_compliant(frame) | ~np.isnan(tangential).all(axis=1))
    if rows.size:  # the tangential model's parameters depend on the law: checked as the Scene checks them
        kappa = columns["kappa"].copy()
        # once per ball, contact and surface: the approach does not reach these checks (the flat's tilt does,
        # with gravity, through the weight it presses)
        keys = {name: np.asarray(values)[rows] for name, values in columns.items()
                if name not in ("speed", "spin", *PATH_RULES)}
        keys["angle"] = np.where(keys["gravity"] == 0, 0.0, keys["angle"])
        groups, firsts = first_rows(keys)
        checked = np.empty(firsts.size)
        for g, first in enumerate(firsts):  # in the order of their first rows: the first bad row is named
            i = int(rows[first])
            try:
                scene = scene_of(frame.record(i))
            except ValueError as err:
                raise ValueError(f"{err} (row {i})") from None
            checked[g] = np.nan if scene.kappa is None else scene.kappa
        kappa[rows] = checked[groups]
        frame["kappa"] = kappa
    return frame


def first_rows(columns: dict) -> tuple[np.ndarray, np.ndarray]:
    """(the group of each row, the first row of each group) of the rows of ``columns`` (name -> array, one value
    per row), rows alike when every column's values are: groups numbered in the order of their first rows, empty
    cells (NaN) alike, -0.0 as 0.0 (as pandas groups them).  A table's rows as one array of bytes each, not a
    pandas groupby: on a fit's few bounces that cost most of building the table."""
    numbers = []
    for values in columns.values():
        values = np.asarray(values)
        if values.dtype.kind != "f":  # names: their codes
            values = pd.factorize(values, use_na_sentinel=False)[0].astype(float)
        numbers.append(np.where(np.isnan(values), np.nan, values + 0.0))  # one NaN, one zero
    table = np.ascontiguousarray(np.column_stack(numbers))
    rows = table.view(np.dtype((np.void, table.dtype.itemsize * table.shape[1]))).ravel()
    _, first, inverse = np.unique(rows, return_index=True, return_inverse=True)
    order = np.argsort(first)  # the groups in the order of their first rows
    rank = np.empty(order.size, dtype=np.int64)
    rank[order] = np.arange(order.size)
    return rank[inverse.ravel()], first[order]


def undescribed_row(scenes) -> tuple[int, list[str]] | None:
    """The first row of ``scenes`` (a sweep's table or dict, as given) whose ball or approach speed the table does not
    describe, and what it lacks (:func:`~sphereimpact.impact.ball.undescribed`: mass, diameter, and a chapter law's
    stiffness and damping; then ``speed``), each given by a column with the row's cell filled; None when every row
    describes them.  A dict names the row of its grid's first combination."""
    if isinstance(scenes, dict):
        given = {name for name, values in scenes.items() if not pd.isna(pd.Series(np.ravel(
            np.asarray(values, dtype=object)), dtype=object)).any()}
        models = pd.unique(np.ravel(np.asarray(scenes.get("model", DEFAULTS["model"]), dtype=object)))
        for model in models:
            missing = _undescribed(given, model if isinstance(model, str) else DEFAULTS["model"])
            if missing:
                return 0, missing
        return None
    table = scenes if isinstance(scenes, pd.DataFrame) and "parameters" not in scenes else given_table(scenes)
    named = [name for name in _describing() if name in table]
    filled = {name: ~pd.isna(table[name].to_numpy()) for name in named}
    model = ([DEFAULTS["model"] if not isinstance(v, str) else v for v in table["model"].tolist()] if "model" in table
             else [DEFAULTS["model"]] * len(table))
    if all(cells.all() for cells in filled.values()):  # the common table: every cell filled, one check per law
        patterns = {model.index(law): set(named) for law in dict.fromkeys(model)}
    else:
        cells = pd.DataFrame(filled).assign(model=model).drop_duplicates()
        patterns = {i: {name for name in named if row[name]} for i, row in zip(cells.index, cells.to_dict("records"))}
    for i, given in patterns.items():
        if model[i] in LAWS:  # an unknown law is refused by the scene checks, naming its row
            missing = _undescribed(given, model[i])
            if missing:
                return int(i), missing
    return None


def _undescribed(given: set, model: str) -> list[str]:
    """What a row with the columns ``given`` lacks: the ball's parts (as columns) and the approach speed."""
    from ..impact.ball import undescribed

    return _as_columns(undescribed(given, model, approach=True))


def _describing() -> set:
    """The columns that can describe a ball (:func:`~sphereimpact.impact.ball.undescribed`'s parts: its mass and
    diameter, the stiffness, and every registered law's damping) and its approach speed."""
    from ..impact.ball import STIFFNESS_GIVEN

    return {"mass", "diameter", "speed", *STIFFNESS_GIVEN, *(law.damping for law in LAWS.values() if law.damping)}


def _as_columns(missing: list[str]) -> list[str]:
    """Parts of a description (``"k or contact_time"``) as the columns of a sweep's table that give them: a measured
    COR or contact time is no column (:func:`~.calibrate.calibrate_table` turns it into the damping or k)."""
    columns = set(SCENE_COLUMNS) | set(own_parameters())
    return [" or ".join(name for name in part.split(" or ") if name in columns) for part in missing]


def given_table(scenes) -> pd.DataFrame:
    """The scenes as given, one per row: a DataFrame as is, a dict every combination of its values (:func:`grid`),
    sized before the grid is made, as the command line sizes its ranges.  A ``parameters`` column (rows of
    :meth:`Scene.as_dict <sphereimpact.Scene.as_dict>`: each a mapping of own parameters, or empty) becomes one
    column per own parameter, as a table names them."""
    if not isinstance(scenes, dict):
        table = _own_columns(pd.DataFrame(scenes))
        text = [c for c, dtype in table.dtypes.items() if isinstance(dtype, pd.StringDtype)]
        if not text:
            return table
        # as object columns, whatever dtype the user's text has: one table, however built (with_constants, assign)
        return table.assign(**{c: pd.Series(table[c].to_numpy(dtype=object), index=table.index, dtype=object)
                               for c in text})
    check_size({name: int(np.size(values)) for name, values in scenes.items()},
               "sweep shards of it (span= keeps them one sweep) or coarser values")
    return grid(**scenes)


def _own_columns(table: pd.DataFrame) -> pd.DataFrame:
    """``table`` with its ``parameters`` column (mappings, or empty cells) spread into one column per name."""
    if "parameters" not in table:
        return table
    cells = [value if isinstance(value, Mapping) else {} for value in table["parameters"].tolist()]
    if any(not isinstance(v, Mapping) and not (v is None or (isinstance(v, float) and v != v))
           for v in table["parameters"].tolist()):
        raise ValueError("parameters must hold a mapping of own parameter name to value in each row (or nothing)")
    spread = pd.DataFrame(cells, index=table.index)
    twice = [name for name in spread.columns if name in table]
    if twice:
        raise ValueError(f"{twice[0]} is given twice: as a column and in parameters")
    return pd.concat([table.drop(columns="parameters"), spread], axis=1)


def _defaulted(values: np.ndarray, default) -> np.ndarray:
    """A column with its empty cells (NaN or None: not given) set to the field's ``default``, if it has one (the
    law's and the tangential model's parameters, and the approach by the ball's path, stay empty: each row's
    law or model reads them)."""
    if default is None:
        return values
    if values.dtype.kind == "f":
        return np.where(np.isnan(values), default, values)
    if values.dtype == object:
        empty = np.array([v is None or (isinstance(v, float) and v != v) for v in values.tolist()], dtype=bool)
        if empty.any():
            values = values.copy()
            values[empty] = default
    return values


def _objects(n: int, value) -> np.ndarray:
    """An object array of n references to ``value`` (np.full fills object arrays 20x slower)."""
    out = np.empty(n, dtype=object)
    out[:] = value
    return out


def _compliant(frame: SceneColumns) -> np.ndarray:
    """Scenes whose tangential model has no ``swept`` end state (its motion is integrated: solved scene by
    scene)."""
    names = frame["tangential"]
    out = np.ones(names.shape, dtype=bool)
    for name, model in TANGENTIALS.items():
        if model.swept is not None:
            out &= names != name  # numpy's comparison: pandas' is 4x slower
    return out


def scene_of(row: dict) -> Scene:
    """The Scene of one row of a :func:`scene_table` (its NaN law parameters are the ones its law lacks)."""
    values = {name: (value if name in TEXT_FIELDS else float(value)) for name, value in row.items()}
    own = {name: values.pop(name) for name in list(values) if name not in DEFAULTS}
    values["parameters"] = {name: value for name, value in own.items() if not np.isnan(value)}
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
    with bodies_judged():  # the sweep judges its table once (engine.sweep), not each row
        return Scene(**values)


def given_fields(row: dict) -> dict:
    """The Scene fields a raw table row gives (its empty cells, NaN or None, left out; a model's own parameters
    under ``parameters``), for building a Scene from a row no :func:`scene_table` has filled in."""
    given = {name: value for name, value in row.items()
             if value is not None and not (isinstance(value, float) and value != value)}
    own = {name: given.pop(name) for name in list(given) if name not in DEFAULTS and name not in PARTNER_FIELDS}
    return given | ({"parameters": own} if own else {})


def incidence(frame) -> np.ndarray:
    """Each scene's incidence from the flat's normal [deg]: its ``incidence``, 90 - ``angle_to_surface``, or
    the flat's tilt ``angle`` for a vertical approach (as :attr:`sphereimpact.Scene.incidence_deg`), of a
    :func:`scene_table` or its :class:`SceneColumns`."""
    given, surface = np.asarray(frame["incidence"]), np.asarray(frame["angle_to_surface"])
    return np.where(~np.isnan(given), given, np.where(~np.isnan(surface), 90.0 - surface, np.asarray(frame["angle"])))


def approach_speeds(frame) -> tuple[np.ndarray, np.ndarray]:
    """Each scene's approach along the normal and along the flat [m/s]: v cos(theta) and v sin(theta), the latter
    exactly 0 at normal incidence, theta its :func:`incidence` (as :attr:`sphereimpact.Scene.v_normal` and
    :attr:`sphereimpact.Scene.v_tangent`)."""
    theta = np.radians(incidence(frame))
    speed = np.asarray(frame["speed"])
    return speed * np.cos(theta), np.where(theta == 0, 0.0, speed * np.sin(theta))


def law_view(frame: SceneColumns, v_n: np.ndarray) -> SimpleNamespace:
    """The columns of scenes of one law that its vectorised functions read: mass, radius, v_normal and its
    parameters (the ``p`` of :class:`~sphereimpact.contact.laws.ContactLaw`'s functions)."""
    own = [name for name in own_parameters() if name in frame]  # the laws' own parameters (and the models')
    return SimpleNamespace(mass=frame["mass"], radius=0.5 * frame["diameter"], v_normal=v_n,
                           **{name: frame[name] for name in (*PARAMETER_NAMES, *own)})


@dataclass(frozen=True)
class Numbers:
    """Per scene, what chooses and drives a sweep path: the law's frequency ``w`` = 1 / T [1/s], the normal and
    tangential approach speeds ``v_n`` and ``v_t`` [m/s] (:func:`approach_speeds`), the dimensionless gravity
    ``gamma`` = g_n / (w v_n), the family's ``zeta`` and ``lam`` where the batched lanes or a closed form read them
    (0 elsewhere), masks of eq. 4.2's form (``modified``), a law's ``closed`` form, a form of the ``batched`` lanes
    and the ``force`` criterion (compared once here: an elementwise comparison of an object array is not cheap), the
    law's closed form as an index into :data:`CLOSED_FORMS` (``closed_form``, -1 without), the similarity ``family``
    as a hashable key (laws the lanes do not take; None otherwise)."""

    w: np.ndarray
    v_n: np.ndarray
    v_t: np.ndarray
    gamma: np.ndarray
    zeta: np.ndarray
    lam: np.ndarray
    modified: np.ndarray
    closed: np.ndarray
    batched: np.ndarray
    force: np.ndarray
    closed_form: np.ndarray
    family: np.ndarray

    def __getitem__(self, rows) -> "Numbers":
        """The numbers of some scenes (a mask or indices)."""
        return Numbers(**{f.name: getattr(self, f.name)[rows] for f in fields(self)})

    def __len__(self) -> int:
        return self.w.size

    def criterion(self, separation: Separation) -> np.ndarray:
        """Mask of the scenes under the criterion ``separation``."""
        return self.force if separation.on_force else ~self.force

    def criterion_of(self, i: int) -> Separation:
        """The separation criterion of scene ``i``."""
        return Separation.FORCE if self.force[i] else Separation.PENETRATION


#: The laws' closed forms met by :func:`numbers`, in order: :attr:`Numbers.closed_form` indexes it, so a path groups
#: rows by closed form with integer arithmetic, not by comparing objects row by row.
CLOSED_FORMS: list = []


def _closed_form_code(form) -> int:
    """The index of ``form`` in :data:`CLOSED_FORMS` (appended when new), -1 for None."""
    if form is None:
        return -1
    for code, known in enumerate(CLOSED_FORMS):
        if known is form:
            return code
    CLOSED_FORMS.append(form)
    return len(CLOSED_FORMS) - 1


def numbers(frame: SceneColumns) -> Numbers:
    """The :class:`Numbers` of every scene of a :func:`scene_columns`, each from its law's ``frequency`` and
    ``family`` (ValueError names a law whose closed form reads numbers the sweep does not carry, and a row
    whose scales overflow)."""
    v_n, v_t = approach_speeds(frame)
    n = len(frame)
    w, zeta, lam = np.empty(n), np.zeros(n), np.zeros(n)
    closed_form, family = np.full(n, -1), _objects(n, None)
    modified, batched = np.zeros(n, bool), np.zeros(n, bool)
    models, separation = frame["model"], frame["separation"]
    for model in dict.fromkeys(models.tolist()):
        rows = np.flatnonzero(models == model)
        law = LAWS[model]
        lanes = law.scaled in batch.FORMS
        if law.closed_form is not None and not set(law.closed_form.reads) <= {"zeta", "lam"}:
            raise ValueError(f"model {model!r} declares a closed form reading {', '.join(law.closed_form.reads)}; "
                             f"the sweep carries zeta and lam only: declare closed_form=None to be solved per family")
        view = law_view(frame if rows.size == n else frame.take(rows), v_n[rows])
        with np.errstate(all="ignore"):  # extreme rows are refused below, with the row named
            w[rows] = np.broadcast_to(law.frequency(view), rows.shape)
            values = {name: np.broadcast_to(np.asarray(value, dtype=float), rows.shape)
                      for name, value in law.family(view).items()}
        problem = scale_problem(view.mass, v_n[rows], w[rows], law, rows)
        if problem:
            raise ValueError(problem)
        closed_form[rows] = _closed_form_code(law.closed_form)
        batched[rows], modified[rows] = lanes, lanes and batch.FORMS[law.scaled]
        if lanes or law.closed_form is not None:  # the lanes and the closed forms read zeta and lam
            zeta[rows] = values.get("zeta", 0.0)
            lam[rows] = values.get("lam", 0.0)
        if not lanes:  # the family as a key, for the paths of the laws the lanes do not take (10^6 tuples: 0.19 s)
            keys = zip(*values.values()) if values else [()] * rows.size
            family[rows] = [(model, *key) for key in keys]
    # gravity along the normal of the flat, tilted by `angle` (w v_n: normal, see scale_problem)
    gamma = frame["gravity"] * np.cos(np.radians(frame["angle"])) / (w * v_n)
    return Numbers(w=w, v_n=v_n, v_t=v_t, gamma=gamma, zeta=zeta, lam=lam, modified=modified, closed=closed_form >= 0,
                   batched=batched, force=separation == Separation.FORCE, closed_form=closed_form,
                   family=family)


def with_constants(table: pd.DataFrame, constants: dict) -> pd.DataFrame:
    """``table`` with a column per name of ``constants``, its value in every row (replacing a column of that name),
    built in one go with text as object columns, as :func:`given_table` gives them: ``DataFrame.assign`` of a ball's
    dozen columns (:func:`~sphereimpact.impact.ball.ball_columns`) cost each of a fit's evaluations a quarter of its
    time."""
    n, index = len(table), table.index
    columns = dict(table.items())
    for name, value in constants.items():  # in the column's place, as assign puts it
        columns[name] = (pd.Series(_objects(n, value), index=index, dtype=object) if isinstance(value, str)
                         else np.full(n, value))
    return pd.DataFrame(columns, index=index)


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

