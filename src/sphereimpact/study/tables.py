"""The summary table: one row per case x force model x separation criterion."""

from __future__ import annotations

import json

import pandas as pd

from ..impact.outcome import OUTPUT_KEYS

#: Physical outputs in the summary (solver statistics and timings are left out).
SUMMARY_KEYS = OUTPUT_KEYS[: OUTPUT_KEYS.index("force_max") + 1]

#: How each column is shown in the Markdown table: (header with unit, scale factor).
DISPLAY = {
    "t_m": ("t_m [ms]", 1e3), "delta_m": ("δ_m [mm]", 1e3), "t_f": ("t_f [ms]", 1e3),
    "vc_t": ("v_C,t [m/s]", 1.0), "vc_n": ("v_C,n [m/s]", 1.0), "ve_t": ("v_E,t [m/s]", 1.0),
    "ve_n": ("v_E,n [m/s]", 1.0), "omega_f": ("ω_f [rad/s]", 1.0), "cor": ("COR [-]", 1.0),
    "regime": ("regime", None), "t_roll": ("t_roll [ms]", 1e3),
    "force_min": ("P_min [N]", 1.0), "force_max": ("P_max [N]", 1.0),
}


def load_runs(json_paths) -> list[dict]:
    """The run files written by :func:`sphereimpact.study.runs.run_case`."""
    runs = []
    for path in json_paths:
        with open(path) as handle:
            runs.append(json.load(handle))
    return runs


def summary_frame(runs: list[dict]) -> pd.DataFrame:
    """One row per case x model x separation, sorted, SI units."""
    rows = []
    for run in runs:
        for separation, out in run["outcomes"].items():
            rows.append({"case": run["case"], "angle": run["scene"]["angle"], "model": run["model"],
                         "separation": separation, **{k: out[k] for k in SUMMARY_KEYS}})
    frame = pd.DataFrame(rows)
    return frame.sort_values(["angle", "case", "model", "separation"], kind="stable").reset_index(drop=True)


def _cell(value, scale) -> str:
    if value is None or (isinstance(value, float) and pd.isna(value)):
        return "—"
    if scale is None or isinstance(value, str):
        return str(value)
    return f"{value * scale:.5g}"


def markdown_table(frame: pd.DataFrame, columns: dict) -> str:
    """A GitHub Markdown table of ``frame``; ``columns`` maps column -> (header, scale or None)."""
    lines = ["| " + " | ".join(h for h, _ in columns.values()) + " |",
             "|" + "|".join("---" for _ in columns) + "|"]
    for _, row in frame.iterrows():
        lines.append("| " + " | ".join(_cell(row[c], s) for c, (_, s) in columns.items()) + " |")
    return "\n".join(lines) + "\n"


def text_table(headers, rows) -> str:
    """Rows of cells already written as text, as a :func:`markdown_table` under ``headers`` (no trailing newline)."""
    return markdown_table(pd.DataFrame(rows, columns=list(headers)), {h: (h, None) for h in headers}).rstrip("\n")


def write_summary(json_paths, csv_path: str, md_path: str) -> None:
    """Write ``summary.csv`` (SI, full precision) and ``summary.md`` (readable units)."""
    frame = summary_frame(load_runs(json_paths))
    frame.to_csv(csv_path, index=False, float_format="%.12g")
    columns = {"case": ("case", None), "angle": ("β [deg]", None), "model": ("model", None),
               "separation": ("separation", None), **DISPLAY}
    with open(md_path, "w") as handle:
        handle.write("# Summary: every case x force model x separation criterion\n\n")
        handle.write("SI outputs in `summary.csv`; here in ms, mm, m/s, rad/s and N. "
                     "Contact-frame components: t along the flat, n away from it.\n\n")
        handle.write(markdown_table(frame, columns))
