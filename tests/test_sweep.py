"""The sweep engine: the accuracy contract on every path, chunk/shard invariance, validation, CLI."""

import numpy as np
import pandas as pd
import pytest

from sphereimpact import ImpactError, Scene, SolverOptions, simulate
from sphereimpact.cli import run
from sphereimpact.contact.separation import Separation
from sphereimpact.impact.outcome import NUMERIC_OUTPUTS
from sphereimpact.numerics.reference import relative_errors
from sphereimpact.sweep import batch
from sphereimpact.sweep.paths import SIMILARITY_MIN
from sphereimpact.sweep.engine import (
    HISTORY_OUTPUTS,
    FAST_OUTPUTS,
    SCENE_COLUMNS,
    SWEEP_OUTPUTS,
    grid,
    parse_range,
    scene_of,
    sweep,
)

KEYS = [k for k in SWEEP_OUTPUTS if k in NUMERIC_OUTPUTS]
#: The interpolant paths' own outputs: the large one-ball sweeps below check those (the per-family outputs
#: are one single-impact solve per family, checked on every path by test_history_outputs_on_every_path).
FAST = FAST_OUTPUTS
CONTRACT = 1e-8
#: Random scenes include compressions beyond the radius: the sweep flags them, the reference warns.
pytestmark = pytest.mark.filterwarnings("ignore::sphereimpact.BeyondRadiusWarning")


def assert_contract(table: pd.DataFrame, sample: int, seed: int = 0, target: float = CONTRACT) -> None:
    """A random sample of the sweep matches the single-impact reference to ``target`` on every output.

    The reference runs at rtol 1e-12, or 1e-13 for targets below 1e-9: at rtol 1e-12 its own worst error
    is about 1.6e-10 (results/bench_sweep.csv, against rtol 1e-13), too close to a 1e-10 target.
    """
    rtol = 1e-12 if target >= 1e-9 else 1e-13
    rows = np.random.default_rng(seed).choice(len(table), size=min(sample, len(table)), replace=False)
    for row in table.iloc[np.sort(rows)].to_dict("records"):
        scene = scene_of({k: row[k] for k in SCENE_COLUMNS})
        ref = simulate(scene, SolverOptions(rtol=rtol, atol=rtol))
        assert row["regime"] == ref.regime and row["beyond_radius"] == ref.beyond_radius, row
        errors = relative_errors(row, ref.to_dict(), scene, [k for k in KEYS if k in row])
        assert max(errors.values()) <= target, (row, errors)


def varied(n: int, seed: int = 1, gravity: bool = True) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    return pd.DataFrame({
        "angle": rng.uniform(0, 89, n), "speed": rng.uniform(0.1, 30, n), "mu": rng.uniform(0, 0.6, n),
        "inertia_factor": rng.uniform(0.2, 2 / 3, n), "k": rng.uniform(1e4, 1e6, n), "b": rng.uniform(0, 40, n),
        "mass": rng.uniform(0.05, 0.5, n), "model": rng.choice(["modified", "kelvin-voigt"], n),
        "separation": rng.choice(["force", "penetration"], n),
        "gravity": rng.choice([0.0, 9.81], n) if gravity else np.zeros(n)})


def test_contract_batched_integrator_with_per_lane_parameters():
    assert_contract(sweep(varied(400), chapter_ball=True), sample=120)


@pytest.mark.parametrize("target", [1e-3, 1e-6, 1e-10])
def test_contract_holds_across_the_target_range(target):
    """Loose targets still take a dozen steps per contact and resolve the ramp (steps are capped)."""
    assert_contract(sweep(varied(150, seed=7, gravity=False), target=target, chapter_ball=True), sample=60, target=target)


@pytest.mark.parametrize("target", [1e-6, 1e-8, 1e-10])
def test_runge_kutta_lanes_meet_their_target_where_ramp_and_damping_are_both_strong(target):
    """The sweep-path study (results/sweep_paths.csv) found the Runge-Kutta lanes up to 3.8x their target on
    eq. 4.2 at zeta 0.5-1, lam 2-10, a corner the random samples above seldom draw.  On a grid over zeta
    0.01-1 and lam 0.1-1000, against the Taylor lanes at 1e-12 (a second method)."""
    from sphereimpact.sweep import series_lanes
    from sphereimpact.sweep.outputs import NORMAL_OUTPUTS
    from sphereimpact.sweep.similarity import _errors

    zeta, lam = (a.ravel() for a in np.meshgrid(10 ** np.linspace(-2, 0, 9), 10 ** np.arange(-1, 3.01, 0.25)))
    for separation in Separation:
        got = batch.integrate(zeta, lam, np.zeros(zeta.size), np.ones(zeta.size, bool), separation, target)
        assert _errors(got, series_lanes.integrate(zeta, lam, separation, 1e-12), NORMAL_OUTPUTS) <= target


def test_large_lam_with_gravity_leaves_the_runge_kutta_lanes():
    """Beyond LANES_LAM_MAX the lanes' landing on delta = 0 under the penetration criterion lost the COR (2e-4
    at zeta 0.01, lam 1e4, gravity on): such scenes are solved one by one and meet the contract (a crowd of
    200, which the cost model would otherwise keep in the lanes)."""
    from sphereimpact.numerics.sweep_paths import scene_for
    from sphereimpact.sweep.paths import LANES_LAM_MAX

    lam = np.logspace(2, 4, 200)
    scenes = [scene_for(0.01, q, "penetration") for q in lam]
    table = sweep(pd.DataFrame({"b": [s.b for s in scenes], "speed": [s.speed for s in scenes],
                                "gravity": 9.81, "separation": "penetration"}), chapter_ball=True)
    assert (table["path"] == np.where(lam > LANES_LAM_MAX, "single", "runge-kutta-lanes")).all()
    assert_contract(table[lam > 2e3], sample=4)


def test_contract_similarity_path_for_one_ball():
    scenes = grid(angle=np.arange(0, 90, 1.0), speed=np.arange(0.5, 30.01, 0.5))
    assert len(scenes) >= SIMILARITY_MIN
    assert_contract(sweep(scenes, outputs=FAST, chapter_ball=True), sample=60)


@pytest.mark.parametrize("target", [1e-4, 1e-6, 1e-10])
def test_contract_similarity_path_across_the_target_range(target):
    scenes = grid(angle=np.arange(0, 90, 1.0), speed=np.arange(0.1, 30.01, 0.5), separation=["force", "penetration"])
    assert_contract(sweep(scenes, target=target, outputs=FAST, chapter_ball=True), sample=30, seed=2, target=target)


def test_contract_closed_form_path():
    scenes = grid(angle=np.arange(0, 90, 3.0), speed=np.arange(0.5, 30.01, 2.5), b=[0.0, 10.5, 80.0])
    assert_contract(sweep(scenes.assign(model="kelvin-voigt"), chapter_ball=True), sample=40)


def test_results_do_not_depend_on_chunk_size():
    scenes = varied(300, seed=3, gravity=False)
    assert sweep(scenes, chunk_size=7, chapter_ball=True).equals(sweep(scenes, chunk_size=300, chapter_ball=True))
    few = scenes.iloc[:12]
    # one lane per batch, too
    assert sweep(few, chunk_size=1, chapter_ball=True).equals(sweep(few, chunk_size=12, chapter_ball=True))


@pytest.mark.parametrize("width", [1, 2, 7, 8, 33, 1000])
def test_stage_sums_are_sequential_whatever_the_batch_width(width):
    """Each lane's Runge-Kutta sums equal the plain left-to-right sum, bit for bit (pairwise or BLAS
    summation would round a lane differently in batches of different widths)."""
    stages = np.random.default_rng(width).standard_normal((12, width)) * np.exp(np.linspace(-20, 20, 12))[:, None]
    stage_weights, step_weights = batch._tableau()
    for weights in stage_weights[1:] + [step_weights]:
        index, column = weights
        total = column[0, 0] * stages[index[0]]
        for j in range(1, index.size):
            total = total + column[j, 0] * stages[index[j]]
        assert np.array_equal(batch._combine(weights, stages), total)


def test_merged_shards_equal_the_whole_sweep():
    scenes = grid(angle=np.arange(0, 90, 1.0), speed=np.arange(0.5, 30.01, 0.5))
    whole = sweep(scenes, outputs=FAST, chapter_ball=True)
    shards = [sweep(scenes.iloc[i], span=scenes, outputs=FAST, chapter_ball=True)
              for i in np.array_split(np.arange(len(scenes)), 3)]
    assert pd.concat(shards, ignore_index=True).equals(whole)
    few = scenes.iloc[::97]  # the per-family outputs too, shard by shard
    assert pd.concat([sweep(few.iloc[i], span=few, chapter_ball=True) for i in np.array_split(np.arange(len(few)), 3)],
                     ignore_index=True).equals(sweep(few, chapter_ball=True))


@pytest.mark.parametrize("scenes", [
    grid(angle=np.arange(0, 90, 15.0), speed=[0.5, 3.0, 20.0], spin=[-200.0, 0.0, 150.0]),
    grid(angle=[10.0, 50.0], speed=[1.0, 5.0], b=[0.0, 10.5, 80.0], separation=["force", "penetration"]).assign(
        model="kelvin-voigt"),
    grid(angle=[10.0, 50.0], speed=[1.0, 5.0], chi=[0.02, 0.2]).assign(model="hunt-crossley", k=8.8e5),
    grid(angle=[0.0, 30.0], speed=[3.0], gravity=[9.81], separation=["force", "penetration"]),
], ids=["modified-spin", "closed-form", "kernel-less", "gravity-lanes"])
def test_history_outputs_on_every_path(scenes):
    """t_roll, force_min and force_max from one solve per dimensionless family, scaled to each scene, equal
    simulate's on every fast path; the fast outputs alone leave those columns out."""
    table = sweep(scenes, chapter_ball=True)
    assert_contract(table, sample=len(table))
    assert not set(HISTORY_OUTPUTS) & set(sweep(scenes, outputs=FAST, chapter_ball=True).columns)
    assert list(sweep(scenes, outputs=["cor"], chapter_ball=True).columns) == [*SCENE_COLUMNS, "cor", "path"]
    with pytest.raises(ValueError, match="outputs must be some of"):
        sweep(scenes, outputs=["spin_rate"], chapter_ball=True)


def test_table_layout():
    table = sweep({"angle": [0.0, 30.0, 60.0]}, chapter_ball=True)
    assert list(table.columns) == [*SCENE_COLUMNS, *SWEEP_OUTPUTS, "path"]
    assert list(table["regime"]) == ["none", "rolling", "sliding"]


@pytest.mark.parametrize("scenes, message", [
    ({"angle": [10.0, 95.0]}, r"angle must be a finite number in \[0, 90\) degrees; got 95.0 \(row 1\)"),
    ({"mass": [0.1, -1.0]}, r"mass must be a finite number > 0 kg; got -1.0 \(row 1\)"),
    ({"mass": [0.1, np.inf]}, r"mass must be a finite number > 0 kg; got inf \(row 1\)"),
    ({"model": ["hertz", "hertz"], "k": [np.nan, 1e6]}, r"k is required by model 'hertz'.*\(row 0\)"),
    ({"model": ["hertz"] * 2, "k": [1e6, 2e6], "modulus": [np.nan, 1e7]},
     r"give k or modulus for model 'hertz', not both .*\(row 1\)"),
    ({"model": ["hooke"]}, "model must be one of kelvin-voigt, modified, linear-hunt-crossley"),
    ({"colour": ["red"]}, "unknown scene parameter 'colour'"),
])
def test_bad_scene_tables_name_the_parameter(scenes, message):
    with pytest.raises(ValueError, match=message):
        sweep(scenes, chapter_ball=True)


def test_one_table_however_its_rows_are_described():
    """An empty cell (NaN, None) is a parameter that row does not give: rows describing the approach by
    incidence, by angle to the surface or by the flat's tilt, and Hertz rows by k or by modulus, sweep as
    one table, each row as its scene alone (and as simulate), and the sweep's own table reads back."""
    table = pd.DataFrame({
        "angle": [30.0, np.nan, np.nan, np.nan, 0.0, np.nan],
        "incidence": [np.nan, 30.0, np.nan, 20.0, np.nan, np.nan],
        "angle_to_surface": [np.nan, np.nan, 60.0, np.nan, 70.0, np.nan],
        "model": ["modified", None, "hertz", "hertz", "hertz", np.nan],
        "k": [np.nan, 6e4, 1.2e6, np.nan, np.nan, np.nan],
        "modulus": [np.nan, np.nan, np.nan, 1e7, 1e7, np.nan],
        "mass": [np.nan, 0.1, 0.145, np.nan, 0.2, 0.145]})
    swept = sweep(table, chapter_ball=True)
    for i, row in table.iterrows():
        given = {k: v for k, v in row.items() if v is not None and v == v}
        alone = sweep(pd.DataFrame([given]), chapter_ball=True).iloc[0]
        assert list(swept[list(SCENE_COLUMNS)].iloc[i].dropna()) == list(alone[list(SCENE_COLUMNS)].dropna())
        scene = Scene(**given)
        one = simulate(scene, SolverOptions(rtol=1e-12, atol=1e-12)).to_dict()
        for got in (swept.iloc[i], alone):  # the same scene, within the target, alone or with the others
            assert max(relative_errors(got, one, scene, KEYS).values()) <= CONTRACT, i
    assert swept.equals(sweep(swept[list(SCENE_COLUMNS)], chapter_ball=True))


def test_never_separating_scene_is_an_error():
    with pytest.raises(ImpactError, match="no separation"):
        sweep({"model": ["kelvin-voigt"], "b": [500.0], "separation": ["penetration"]}, chapter_ball=True)


def test_parse_range():
    assert len(parse_range("0:89:1")) == 90 and parse_range("0:89:1")[-1] == 89
    np.testing.assert_allclose(parse_range("0.5:30:0.5"), np.arange(1, 61) * 0.5)
    assert list(parse_range("3")) == [3.0]
    with pytest.raises(ValueError, match="START:STOP:STEP"):
        parse_range("5:1:1")


def test_cli_sweep_writes_one_row_per_scene(tmp_path):
    out = tmp_path / "s.csv"
    assert run(["sweep", "--chapter-ball", "--angle", "0:60:30", "--speed", "1:3:2", "--out", str(out)]) == 0
    table = pd.read_csv(out)
    assert len(table) == 6 and list(table.columns) == [*SCENE_COLUMNS, *SWEEP_OUTPUTS, "path"]
    one = simulate(Scene(angle=30.0, speed=3.0))
    row = table[(table.angle == 30) & (table.speed == 3)].iloc[0]
    assert row["omega_f"] == pytest.approx(one.omega_f, rel=1e-9)


@pytest.mark.parametrize("args, message", [
    (["--angle", "0:95:5"], "angle must be"),
    (["--speed", "x"], "speed: range must be"),
    (["--target", "1"], "target must be"),
])
def test_cli_sweep_bad_input_exits_2(args, message, tmp_path, capsys):
    assert run(["sweep", "--chapter-ball", *args, "--out", str(tmp_path / "s.csv")]) == 2
    assert message in capsys.readouterr().err


def _stiff_mix():
    """Chapter-ball scenes plus two that creep back under the penetration criterion (zeta 64 and 30)."""
    base = Scene()
    b_of = lambda zeta: zeta * 2 * np.sqrt(base.k * base.mass)  # noqa: E731
    easy = grid(angle=np.arange(0, 90, 10.0), speed=[1.0, 3.0, 9.0]).assign(b=base.b, separation="penetration")
    stiff = pd.DataFrame({"angle": [30.0, 45.0], "speed": [3.0, 6.0], "b": [b_of(64.0), b_of(30.0)],
                          "separation": "penetration"})
    return pd.concat([easy, stiff], ignore_index=True)


def test_slow_lanes_go_to_the_single_impact_path():
    """The lanes pay per step until their slowest lane ends: one zeta = 64 creep took 3.4 s there against
    11 ms alone.  The cost model sends such scenes alone, keeps a crowd of them in lanes (where the per-step
    cost is shared), and leaves ordinary scenes in lanes."""
    from sphereimpact.sweep.paths import solved_alone
    from sphereimpact.sweep.scenes import numbers, scene_table

    def costly(scenes):
        frame = scene_table(scenes)
        return solved_alone(frame, numbers(frame), CONTRACT)[0]

    mixed = costly(_stiff_mix())
    assert mixed[-2:].all() and not mixed[:-2].any()
    zeta_10 = Scene().with_(b=10 * 2 * np.sqrt(Scene().k * Scene().mass)).b
    crowd = grid(angle=np.linspace(0, 80, 50), speed=np.linspace(1, 10, 40)).assign(b=zeta_10, separation="penetration")
    assert not costly(crowd).any()  # 2000 lanes of ~1000 steps: cheaper together than 2000 impacts alone


def test_a_slow_lane_sent_alone_keeps_shards_equal_and_meets_the_contract():
    scenes = _stiff_mix()
    whole = sweep(scenes, chapter_ball=True)
    shards = [sweep(scenes.iloc[i], span=scenes, chapter_ball=True) for i in np.array_split(np.arange(len(scenes)), 3)]
    assert pd.concat(shards, ignore_index=True).equals(whole)
    assert_contract(whole.iloc[-3:], sample=3)


def test_every_registered_law_sweeps_from_the_command_line(tmp_path, capsys):
    """Each law with its own parameters (Hertz laws by k or by modulus) through `sphereimpact sweep`, a sample
    of rows against simulate; one closing line on standard error."""
    from sphereimpact import LAWS

    flags = {"kelvin-voigt": [], "modified": [], "linear-hunt-crossley": ["--k", "6e4", "--chi", "0.05"],
             "hertz": ["--modulus", "1e7"], "hunt-crossley": ["--k", "8.8e5", "--chi", "0.05"]}
    assert set(flags) == set(LAWS)  # a new built-in law gets a row here
    for law, extra in flags.items():
        out = tmp_path / f"{law}.csv"
        assert run(["sweep", "--chapter-ball", "--angle", "0:60:30", "--speed", "1:5:4", "--model", law, *extra,
                    "--out", str(out)]) == 0
        assert capsys.readouterr().err.startswith("sphereimpact sweep: 6 scenes in")
        table = pd.read_csv(out)
        for row in table.iloc[[1, 5]].to_dict("records"):
            one = simulate(scene_of({k: row[k] for k in SCENE_COLUMNS}))
            errors = relative_errors(row, one.to_dict(), one.scene, KEYS)
            assert max(errors.values()) <= CONTRACT, (law, errors)


def test_the_command_line_calibrates_each_ball_once(tmp_path):
    """--cor sets the damping of each distinct ball from a normal impact at --cor-speed, then sweeps it; the
    API's calibrate_table does the same."""
    from sphereimpact.impact.ball import Measurement
    from sphereimpact.impact.calibrate import calibrate
    from sphereimpact.sweep.calibrate import calibrate_table

    out = tmp_path / "cor.csv"
    assert run(["sweep", "--chapter-ball", "--angle", "0:60:30", "--speed", "2:6:2", "--mass", "0.1:0.2:0.1", "--model",
                "hunt-crossley", "--modulus", "1e7", "--cor", "0.8", "--cor-speed", "3", "--out", str(out)]) == 0
    table = pd.read_csv(out)
    for mass, rows in table.groupby("mass"):
        assert rows["chi"].nunique() == 1  # one calibration per ball
        fitted = calibrate(Scene(model="hunt-crossley", modulus=1e7, mass=mass, speed=3.0), 0.8).scene
        assert rows["chi"].iloc[0] == pytest.approx(fitted.chi, rel=1e-12)
    api = calibrate_table(grid(angle=[0.0, 30.0], mass=[0.1, 0.2]).assign(model="hunt-crossley", modulus=1e7),
                          Measurement(0.8, 3.0))
    assert sorted(api["chi"].unique()) == pytest.approx(sorted(table["chi"].unique()), rel=1e-12)
    assert run(["sweep", "--chapter-ball", "--speed", "1:3:1", "--model", "hunt-crossley", "--modulus", "1e7", "--cor", "0.8",
                "--out", str(tmp_path / "x.csv")]) == 2  # several speeds: which one was measured?


def test_lists_mean_every_combination_in_the_api_and_on_the_command_line(tmp_path):
    out = tmp_path / "grid.csv"
    assert run(["sweep", "--chapter-ball", "--angle", "30:45:15", "--speed", "3:20:17", "--out", str(out)]) == 0
    cli = pd.read_csv(out)
    api = sweep({"angle": [30.0, 45.0], "speed": [3.0, 20.0]}, chapter_ball=True)
    assert len(api) == len(cli) == 4
    np.testing.assert_allclose(api["omega_f"], cli["omega_f"], rtol=1e-15)
    from sphereimpact.sweep import rows

    assert len(sweep(rows(angle=[30.0, 45.0], speed=[3.0, 20.0]), chapter_ball=True)) == 2


def test_the_path_column_names_the_path_that_solved_each_row():
    """Each row says which path solved it, and that path is the one the engine's rules give the row."""
    from sphereimpact.sweep.engine import PATHS

    paths = {name: list(sweep(scenes, chapter_ball=True)["path"]) for name, scenes in {
        "closed": grid(angle=[0.0, 30.0], speed=[1.0, 3.0], model="kelvin-voigt"),  # linear, no gravity
        "taylor-lanes": grid(angle=[30.0], speed=[1.0, 3.0], model="modified"),  # a few modified scenes
        "single": grid(angle=[30.0], speed=[3.0], tangential="linear", kappa=0.7),  # compliant: one by one
        "per-family": grid(angle=[20.0], speed=[3.0], model="hertz", modulus=1e7),  # kernel-less law
    }.items()}
    assert paths == {"closed": ["closed"] * 4, "taylor-lanes": ["taylor-lanes"] * 2, "single": ["single"],
                     "per-family": ["per-family"]}
    many = sweep(grid(angle=[30.0], speed=np.linspace(0.5, 30.0, SIMILARITY_MIN)), outputs=["cor"], chapter_ball=True)  # many lam
    assert set(many["path"]) == {"lambda-interpolant"} and set(paths) <= set(PATHS)


def test_constant_columns_built_at_once_are_those_assign_gives():
    """with_constants (a fit's and a plan's table at each evaluation) is DataFrame.assign of the same values: the same
    table as the sweep reads it, a column of the same name replaced, and the same sweep."""
    from sphereimpact.impact.ball import Ball, ball_columns
    from sphereimpact.sweep.scenes import given_table, with_constants

    table = pd.DataFrame({"speed": [2.0, 3.0, 4.0], "incidence": [10.0, 30.0, 50.0], "mu": [0.9, 0.9, 0.9]},
                         index=[4, 5, 6])
    constants = ball_columns(Ball(Scene(model="hunt-crossley", modulus=2e7, chi=0.1, mass=0.05, diameter=0.04,
                                        tangential="mindlin", kappa=0.7)))
    assert {"model", "tangential", "mu", "chi"} <= set(constants)
    built, assigned = with_constants(table, constants), table.assign(**constants)
    pd.testing.assert_frame_equal(given_table(built), given_table(assigned))
    assert (built["mu"] == constants["mu"]).all()
    pd.testing.assert_frame_equal(sweep(built.reset_index(drop=True)), sweep(assigned.reset_index(drop=True)))


def test_scene_columns_read_and_slice_as_the_scene_table_does():
    """SceneColumns (the checked table as the sweep reads it, one read-only array per column) gives what the
    DataFrame of scene_table gives: each column, a slice of rows, each row as a record, with the models' own
    parameters and text columns; and a Scene from a record is the Scene from the DataFrame's row."""
    from sphereimpact.numerics.consistency import random_scenes
    from sphereimpact.sweep.scenes import scene_columns, scene_of, scene_table

    table = random_scenes(400, seed=5)
    columns, frame = scene_columns(table), scene_table(table)
    assert len(columns) == len(frame) == 400 and columns.columns == list(frame.columns)
    assert {"chi", "model", "tangential"} <= set(columns.columns)
    for name in frame.columns:
        np.testing.assert_array_equal(columns[name], frame[name].to_numpy())
        assert not columns[name].flags.writeable  # read-only, as a DataFrame's column
    rows = np.array([399, 3, 3, 150])
    pd.testing.assert_frame_equal(columns.take(rows).frame(), frame.iloc[rows].reset_index(drop=True))
    for got, expected in ((columns.records(rows), frame.iloc[rows].to_dict("records")),
                          (columns.records(), frame.to_dict("records"))):  # (NaN cells: compared as frames)
        assert [type(v) for v in got[0].values()] == [type(v) for v in expected[0].values()]
        pd.testing.assert_frame_equal(pd.DataFrame(got), pd.DataFrame(expected))
    assert all(scene_of(columns.record(i)) == scene_of(frame.iloc[i].to_dict()) for i in (0, 77, 399))


def test_rows_alike_are_grouped_as_pandas_groups_them():
    """first_rows (the scene checks' and the single path's grouping of alike rows) is pandas' groupby ngroup (sort
    off, empty cells kept): groups in the order of their first rows, NaN alike, -0.0 as 0.0, names by value."""
    from sphereimpact.sweep.scenes import first_rows

    rng = np.random.default_rng(3)
    n = 400
    table = pd.DataFrame({"a": rng.choice([0.0, -0.0, 1.5, np.nan], n), "b": rng.choice([2.0, np.nan], n),
                          "model": pd.Series(rng.choice(["hertz", "modified"], n), dtype=object),
                          "c": rng.choice([1e-300, 3.0], n)})
    groups, firsts = first_rows({name: table[name].to_numpy() for name in table.columns})
    expected = table.groupby(list(table.columns), dropna=False, sort=False).ngroup().to_numpy()
    assert groups.tolist() == expected.tolist() and 2 < firsts.size < n
    assert firsts.tolist() == np.unique(expected, return_index=True)[1].tolist()
