"""Write sweep tables: CSV always, Parquet when pyarrow is installed."""

from __future__ import annotations

import pandas as pd


def write_table(table: pd.DataFrame, path: str) -> None:
    """Write ``table`` to ``path``: ``.csv`` (12 significant digits) or ``.parquet``.

    Raises
    ------
    ValueError
        For another extension, or Parquet without pyarrow.
    """
    if path.endswith(".csv"):
        table.to_csv(path, index=False, float_format="%.12g")
    elif path.endswith(".parquet"):
        try:
            table.to_parquet(path, index=False)
        except ImportError:
            raise ValueError("out: writing .parquet needs pyarrow (pip install pyarrow); use .csv") from None
    else:
        raise ValueError(f"out must end in .csv or .parquet; got {path!r}")
