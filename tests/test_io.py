"""Sweep tables read back bit-identical."""

import numpy as np
import pandas as pd
import pytest

from sphereimpact.sweep.engine import grid, sweep
from sphereimpact.sweep.io import write_table


@pytest.mark.parametrize("ext", [".csv", ".parquet"])
def test_table_reads_back_bit_identical(tmp_path, ext):
    table = sweep(grid(angle=np.array([0.0, 33.3, 60.0]), speed=np.array([0.1 + 0.2, 3.0, 29.9])), chapter_ball=True)
    table["cor"] = table["cor"] * (1 + 1e-16 * np.arange(len(table)))  # digits beyond 12 significant
    path = str(tmp_path / f"t{ext}")
    write_table(table, path)
    back = pd.read_csv(path) if ext == ".csv" else pd.read_parquet(path)
    assert list(back.columns) == list(table.columns)
    for column in table.columns:
        if table[column].dtype.kind == "f":  # a CSV cell "60000" reads back as an integer: compare as floats
            got = back[column].to_numpy(dtype=float)
            assert np.array_equal(got.view(np.int64), table[column].to_numpy().view(np.int64))
        else:
            assert back[column].astype(str).tolist() == table[column].astype(str).tolist()


def test_unknown_extension_is_refused(tmp_path):
    with pytest.raises(ValueError, match=r"out must end in \.csv or \.parquet"):
        write_table(pd.DataFrame({"a": [1.0]}), str(tmp_path / "t.xlsx"))
