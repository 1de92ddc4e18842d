"""Speed-up at equal accuracy, read off one work-precision run (so the timings share a machine state)."""

from __future__ import annotations

import pandas as pd

from .workprecision import TARGET


def cheapest(frame: pd.DataFrame, target: float = TARGET) -> pd.DataFrame:
    """Per case, model and body: the fastest point whose error meets ``target``."""
    ok = frame[(frame["status"] == "ok") & (frame["error"] <= target)]
    best = ok.loc[ok.groupby(["case", "model", "body"])["time"].idxmin()]
    return best[["case", "model", "body", "method", "rtol", "error", "time", "nfev"]].reset_index(drop=True)


def speedups(frame: pd.DataFrame, target: float = TARGET) -> pd.DataFrame:
    """Reduced over planar at equal accuracy, and the closed form over both (kelvin-voigt)."""
    best = cheapest(frame, target)
    rows = []
    for (case, model), group in best.groupby(["case", "model"], sort=True):
        times = dict(zip(group["body"], group["time"]))
        for _, row in group.iterrows():
            rows.append({**row.to_dict(), "target": target,
                         "speedup_over_planar": times["planar"] / row["time"],
                         "closed_speedup": times["reduced"] / times["closed"] if "closed" in times else None})
    return pd.DataFrame(rows)
