"""Guard rail of a refactoring: record what the package computes, then compare two records.

    python tools/snapshot.py record DIR [--results results]   # after `snakemake --cores 2`
    python tools/snapshot.py compare BEFORE AFTER             # exit 1 when anything differs

A record holds every table the pipeline wrote (``results/**/*.csv``, ``*.parquet`` and ``*.md``) with its
timing columns dropped, the JSON of ``sphereimpact simulate`` on the benchmark scenes and on scenes across
every law, tangential model, body, method and option, the tables of a few ``sphereimpact sweep`` commands,
and the command line's help texts.  Timings differ from run to run and are not compared; everything else
must be byte-identical.  The tool runs the installed package through its command line only, so it
records any version alike.
"""

from __future__ import annotations

import argparse
import hashlib
import io
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pandas as pd

#: Columns that hold timings (wall-clock seconds, ratios of them such as ``all_over_fast``, or a verdict drawn
#: from them: the sweep-path study's ``dominated``, where two paths are near their crossover): dropped before
#: comparing.
TIMING = re.compile(r"(^|_)(time|times|seconds|wall_time|ms|us|speedup|speed_up|throughput|memory|per_second|"
                    r"ratio|share|over|dominated)($|_)")
#: Files that are timings through and through (a profile names functions by file and line): not recorded.
TIMED = ("readme/speed.md", "bench_profile.csv")
#: `sphereimpact simulate` argument lists recorded with --json: the benchmark's scenes, then every law,
#: tangential model, body, method, criterion and option.
SIMULATE = [
    [], ["--angle", "60"], ["--model", "kelvin-voigt"], ["--model", "kelvin-voigt", "--angle", "60"],
    ["--angle", "30"], ["--angle", "45", "--speed", "20"], ["--model", "kelvin-voigt", "--angle", "45", "--speed", "20"],
    ["--angle", "30", "--model", "linear-hunt-crossley", "--k", "6e4", "--chi", "0.05"],
    ["--angle", "30", "--model", "hertz", "--k", "8.8e5"],
    ["--angle", "30", "--model", "hunt-crossley", "--k", "8.8e5", "--chi", "0.05"],
    ["--angle", "30", "--model", "hunt-crossley", "--modulus", "1e7", "--cor", "0.85"],
    ["--angle", "30", "--model", "hunt-crossley", "--modulus", "1e7", "--cor", "0.85", "--cor-relation", "flores"],
    ["--model", "modified", "--cor", "0.85", "--contact-time", "4.8e-3"],
    ["--angle", "20", "--gravity"], ["--angle", "20", "--separation", "penetration"],
    ["--angle", "20", "--gravity", "--separation", "penetration", "--model", "kelvin-voigt"],
    ["--angle", "20", "--body", "planar"], ["--angle", "60", "--body", "planar", "--gravity"],
    ["--angle", "20", "--method", "RK45"], ["--angle", "20", "--method", "DOP853"],
    ["--angle", "20", "--method", "DOP853-scalar"], ["--angle", "20", "--method", "taylor"],
    ["--angle", "20", "--method", "Radau", "--rtol", "1e-8", "--atol", "1e-8"],
    ["--angle", "20", "--model", "kelvin-voigt", "--method", "closed"],
    ["--angle", "20", "--model", "kelvin-voigt", "--b", "1000"],
    ["--angle", "30", "--b", "1000", "--separation", "penetration"],
    ["--angle", "20", "--tangential", "linear", "--poisson", "0.5"],
    ["--angle", "45", "--model", "kelvin-voigt", "--tangential", "linear", "--kappa", "1"],
    ["--angle", "10", "--tangential", "linear", "--kappa", "5", "--gravity"],
    *[["--model", "hunt-crossley", "--modulus", "6.3e10", "--mass", "2.618e-4", "--diameter", "0.005",
       "--speed", "3.9", "--mu", "0.092", "--cor", "0.98", "--angle", angle, "--tangential", "mindlin",
       "--kappa", "0.86"] for angle in ("3", "10", "20", "45")],
    ["--angle", "20", "--inertia-factor", "2/3", "--mass", "0.0577", "--diameter", "0.0654", "--mu", "0.5"],
    ["--speed", "1e4"], ["--angle", "89.9", "--speed", "0.01"],
]
#: `sphereimpact sweep` argument lists recorded (the table's CSV).
SWEEP = [
    ["--angle", "0:80:20", "--speed", "1:5:2"],
    ["--angle", "0:80:20", "--speed", "1:5:2", "--model", "kelvin-voigt"],
    ["--angle", "10:70:30", "--speed", "3", "--gravity"],
    ["--angle", "10:70:30", "--k", "3e4:9e4:3e4", "--b", "5:15:5"],
    ["--angle", "20:60:20", "--tangential", "linear", "--kappa", "0.5:1.5:0.5"],
    ["--angle", "20:60:20", "--model", "hunt-crossley", "--k", "8.8e5", "--chi", "0.02:0.06:0.02"],
]
HELP = [["--help"], ["simulate", "--help"], ["sweep", "--help"]]


def _cli(args: list[str]) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "sphereimpact", *args], capture_output=True, text=True,
                          env=os.environ | {"COLUMNS": "120"})


def _without_timing(table: pd.DataFrame) -> pd.DataFrame:
    return table[[c for c in table.columns if not TIMING.search(str(c))]]


def _table_text(path: Path) -> str:
    table = pd.read_parquet(path) if path.suffix == ".parquet" else pd.read_csv(path, comment=None)
    buffer = io.StringIO()
    _without_timing(table).to_csv(buffer, index=False, float_format="%.17g")
    return buffer.getvalue()


def record(out: Path, results: Path) -> None:
    """Write the record into ``out`` (replaced if it exists)."""
    if out.exists():
        shutil.rmtree(out)
    (out / "tables").mkdir(parents=True)
    for path in sorted(results.rglob("*")):
        rel = path.relative_to(results).as_posix()
        if rel in TIMED:
            continue
        if path.suffix in (".csv", ".parquet"):
            (out / "tables" / (rel.replace("/", "__") + ".csv")).write_text(_table_text(path))
        elif path.suffix == ".md" and rel not in TIMED:
            shutil.copy(path, out / "tables" / rel.replace("/", "__"))
    simulated = {}
    for args in SIMULATE:
        run = _cli(["simulate", *args, "--json"])
        if run.returncode == 0:
            outputs = json.loads(run.stdout)
            outputs.pop("wall_time", None)
            simulated[" ".join(args)] = outputs
        else:
            simulated[" ".join(args)] = {"exit": run.returncode, "stderr": run.stderr}
    (out / "simulate.json").write_text(json.dumps(simulated, indent=1, sort_keys=False) + "\n")
    (out / "sweeps").mkdir()
    for i, args in enumerate(SWEEP):
        target = out / "sweeps" / f"sweep{i}.csv"
        run = _cli(["sweep", "--chapter-ball", *args, "--out", str(target)])
        if run.returncode != 0:
            target.write_text(f"exit {run.returncode}\n{run.stderr}")
        else:
            target.write_text(_table_text(target))
        (out / "sweeps" / f"sweep{i}.args").write_text(" ".join(args) + "\n")
    (out / "help").mkdir()
    for args in HELP:
        (out / "help" / ("_".join(a.strip("-") for a in args) + ".txt")).write_text(_cli(args).stdout)
    print(f"recorded {sum(1 for _ in out.rglob('*') if _.is_file())} files in {out}")


def _digests(root: Path) -> dict:
    return {p.relative_to(root).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(root.rglob("*")) if p.is_file()}


def _column_changes(old_path: Path, new_path: Path) -> None:
    """Print which columns of a table were added, removed or changed."""
    try:
        old, new = pd.read_csv(old_path), pd.read_csv(new_path)
    except (ValueError, pd.errors.ParserError):  # not a table (an error message)
        return
    common = [c for c in old.columns if c in new.columns]
    differ = [c for c in common if len(old) != len(new) or not old[c].equals(new[c])]
    for label, cols in (("columns added", [c for c in new.columns if c not in old.columns]),
                        ("columns removed", [c for c in old.columns if c not in new.columns]),
                        ("columns changed", differ)):
        if cols:
            print(f"  {label}: {', '.join(cols)}")
    if not differ:
        print(f"  the other {len(common)} columns identical")


def compare(before: Path, after: Path) -> int:
    """Print what differs between two records; 0 when they are identical, 1 otherwise."""
    a, b = _digests(before), _digests(after)
    same = [k for k in a if b.get(k) == a[k]]
    changed = [k for k in a if k in b and b[k] != a[k]]
    missing, added = [k for k in a if k not in b], [k for k in b if k not in a]
    print(f"identical: {len(same)} of {len(a)} files")
    for label, names in (("differ", changed), ("only before", missing), ("only after", added)):
        for name in names:
            print(f"{label}: {name}")
            if label == "differ" and name.endswith(".csv"):
                _column_changes(before / name, after / name)
    if "simulate.json" in changed:
        old, new = (json.loads((root / "simulate.json").read_text()) for root in (before, after))
        for key in old:
            if old[key] != new.get(key):
                print(f"  simulate {key or '(defaults)'}: "
                      + ", ".join(f"{k} {old[key].get(k)!r} -> {new.get(key, {}).get(k)!r}"
                                  for k in old[key] if old[key].get(k) != new.get(key, {}).get(k)))
    return 0 if not (changed or missing or added) else 1


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    rec = sub.add_parser("record")
    rec.add_argument("out", type=Path)
    rec.add_argument("--results", type=Path, default=Path("results"))
    cmp_ = sub.add_parser("compare")
    cmp_.add_argument("before", type=Path)
    cmp_.add_argument("after", type=Path)
    args = parser.parse_args()
    if args.command == "record":
        record(args.out, args.results)
        return 0
    return compare(args.before, args.after)


if __name__ == "__main__":
    sys.exit(main())
