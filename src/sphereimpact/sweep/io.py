"""Write sweep tables: CSV or Parquet, through pyarrow.

CSV floats are written in their shortest round-trip form, so a table read back (pandas or pyarrow) is
bit-identical to the one written; pyarrow's CSV writer does that about ten times faster than pandas'
``to_csv``, and writing dominated large sweeps.
"""

from __future__ import annotations

import json

import pandas as pd
import pyarrow as pa
import pyarrow.csv as pa_csv
import pyarrow.parquet as pq

from ..files import replacing

#: Output formats by file extension.
EXTENSIONS = (".csv", ".parquet")


def write_table(table: pd.DataFrame, path: str, units: dict | None = None) -> None:
    """Write ``table`` to ``path``: ``.csv`` (shortest round-trip floats, strings quoted) or ``.parquet``, through a
    temporary file beside it renamed at the end (an interrupted run never leaves a truncated table).

    ``units`` (column -> unit) names each column's unit: in a CSV header as ``name [unit]``, in a Parquet
    file's schema metadata (key ``units``, JSON) with the names unchanged.

    Raises
    ------
    ValueError
        For another extension.
    """
    if not path.endswith(EXTENSIONS):
        raise ValueError(f"out must end in {' or '.join(EXTENSIONS)}; got {path!r}")
    with replacing(path) as partial:  # written beside it, then renamed: a killed run leaves the old file whole
        if path.endswith(".csv"):
            if units:
                table = table.rename(columns={c: f"{c} [{units[c]}]" for c in table.columns if units.get(c)})
            pa_csv.write_csv(pa.Table.from_pandas(table, preserve_index=False), partial)
        else:
            arrow = pa.Table.from_pandas(table, preserve_index=False)
            if units:
                arrow = arrow.replace_schema_metadata({**(arrow.schema.metadata or {}), b"units": json.dumps(units)})
            pq.write_table(arrow, partial)
