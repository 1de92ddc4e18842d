"""One answer whatever the path: every row of a random mixed table, swept, agrees with ``simulate`` of its
scene within the sweep's target, on every path, whatever the chunk size or sharding, and on each path forced
alone (the differential test; the pipeline runs it on 10^5 rows, results/consistency.csv)."""

import numpy as np
import pandas as pd
import pytest

from sphereimpact.numerics.consistency import compare, random_scenes, references
from sphereimpact.sweep import paths, processes
from sphereimpact.sweep.engine import PATHS, sweep

TARGET = 1e-8
#: Thresholds at which a table of a few thousand rows takes every path (the engine's own are sized for
#: sweeps of thousands of scenes per ball): the interpolants on the table's groups of one ball.
SMALL = {"SIMILARITY_MIN": 100, "PLANE_MIN": 60, "FAMILY_MIN": 40, "GRIP_TABLE_MIN": 50}
pytestmark = pytest.mark.filterwarnings("ignore::sphereimpact.BeyondRadiusWarning")


@pytest.fixture(scope="module")
def solved():
    """1200 random scenes and simulate's outcome of each: (scenes, references), the scenes simulate refuses
    left out."""
    table = random_scenes(1200, seed=3, groups=6, group_size=120)
    reference = references(table)
    kept = (reference["refused"] == "").to_numpy()
    assert (~kept).sum() <= 5, reference.loc[~kept, "refused"]  # the generator stays inside the domain but for a few
    return table[kept].reset_index(drop=True), reference[kept].reset_index(drop=True)


@pytest.fixture
def small_thresholds(monkeypatch):
    for name, value in SMALL.items():
        monkeypatch.setattr(paths, name, value)


def assert_agrees(errors: pd.DataFrame) -> None:
    """Every compared row within the target, with regime and beyond_radius equal; the worst rows named."""
    bad = errors[(errors["error"] > TARGET) | ~errors["regime_agrees"] | ~errors["beyond_radius_agrees"]]
    assert bad.empty, bad.sort_values("error").tail(10).to_string()


def test_every_row_of_a_mixed_table_agrees_with_simulate_whatever_the_chunks_and_shards(solved, small_thresholds):
    table, reference = solved
    whole = sweep(table, chapter_ball=True)
    assert set(whole["path"]) == set(PATHS)  # the table reaches every path
    assert_agrees(compare(table, reference, whole))
    shards = [sweep(table.iloc[rows], span=table, chunk_size=size, chapter_ball=True)
              for rows, size in zip(np.array_split(np.arange(len(table)), 2), (97, 100_000))]
    assert pd.concat(shards, ignore_index=True).equals(whole)  # as shards, and in chunks of 97 scenes


@pytest.mark.parametrize("path", [name for name in PATHS if name != "single"])
def test_each_path_alone_agrees_with_simulate_on_the_rows_it_admits(solved, small_thresholds, path):
    """Forced alone, a path takes every row it admits (not only those no earlier path took)."""
    table, reference = solved
    alone = sweep(table, paths=[path], chapter_ball=True)
    taken = alone["path"] == path
    assert taken.sum() >= 40 and set(alone.loc[~taken, "path"]) <= {""}
    assert_agrees(compare(table, reference, alone))


def test_paths_are_named():
    with pytest.raises(ValueError, match="paths must be some of similar, single, family-interpolant"):
        sweep({"angle": [30.0]}, paths=["fastest"], chapter_ball=True)


def test_compare_measures_each_row_as_relative_errors_does(solved):
    """compare's measure, computed on every row at once, is relative_errors' on each row (worst output)."""
    from sphereimpact import Scene
    from sphereimpact.numerics.consistency import COMPARED
    from sphereimpact.numerics.reference import relative_errors
    from sphereimpact.sweep.engine import SCENE_COLUMNS, scene_of

    table, reference = solved
    rows = np.arange(0, len(table), 97)
    swept = sweep(table.iloc[rows], chapter_ball=True).reset_index(drop=True)
    errors = compare(table.iloc[rows].reset_index(drop=True), reference.iloc[rows].reset_index(drop=True), swept)
    for i in range(len(rows)):
        scene = scene_of(swept.loc[i, list(SCENE_COLUMNS)].to_dict())
        assert isinstance(scene, Scene)
        expected = relative_errors(swept.iloc[i], reference.iloc[rows[i]].to_dict(), scene, COMPARED)
        assert errors["error"].iloc[i] == pytest.approx(max(expected.values()), rel=1e-12, abs=1e-300)


@pytest.mark.skipif(not processes.can_fork(), reason="this system's processes cannot fork")
def test_the_one_at_a_time_rows_shared_among_processes_give_the_table_of_one_process(solved, small_thresholds,
                                                                                    monkeypatch):
    """The single-impact path's chunks (of 8 rows here) in two processes: the mixed table to the bit."""
    table, _ = solved
    monkeypatch.setattr(paths, "SINGLES_CHUNK", 8)
    alone = sweep(table, chapter_ball=True, jobs=1)
    assert (alone["path"] == "single").sum() >= 8 * processes.PARALLEL_MIN_CHUNKS
    assert sweep(table, chapter_ball=True, jobs=2).equals(alone)
