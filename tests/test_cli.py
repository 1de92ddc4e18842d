"""Command line: JSON output with exactly the documented keys; every bad input exits 2 naming its parameter."""

import json
import subprocess
import sys

import numpy as np
import pytest

from sphereimpact import OUTPUT_KEYS, Scene, SolverOptions, simulate
from sphereimpact.cli import run


def test_json_has_exactly_the_output_keys(capsys):
    assert run(["simulate", "--angle", "60", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert tuple(data) == (*OUTPUT_KEYS, "gravity") and data["gravity"] == 0.0  # the default, recorded
    reference = simulate(Scene(angle=60.0)).to_dict()
    for key in OUTPUT_KEYS:
        if key != "wall_time":
            assert data[key] == reference[key], key


def test_options_reach_the_model(capsys):
    run(["simulate", "--angle", "30", "--model", "kelvin-voigt", "--method", "closed", "--separation",
         "penetration", "--mu", "0.3", "--inertia-factor", "0.6666666666666666", "--json"])
    data = json.loads(capsys.readouterr().out)
    scene = Scene(angle=30.0, model="kelvin-voigt", separation="penetration", mu=0.3,
                  inertia_factor=0.6666666666666666)
    assert data["method"] == "closed" and data["regime"] == "rolling"
    assert data["vc_t"] == pytest.approx(scene.v_tangent / (1 + 0.6666666666666666), rel=1e-13)
    assert data["cor"] == simulate(scene, SolverOptions(method="closed")).cor


BAD = [
    (["--mass", "0"], "mass", "> 0 kg"),
    (["--mass", "-1"], "mass", "> 0 kg"),
    (["--diameter", "0"], "diameter", "> 0 m"),
    (["--k", "0"], "k", "> 0 N/m"),
    (["--b", "-0.1"], "b", ">= 0"),
    (["--mu", "-0.2"], "mu", ">= 0"),
    (["--speed", "0"], "speed", "> 0 m/s"),
    (["--angle", "90"], "angle", "[0, 90)"),
    (["--angle", "-1"], "angle", "[0, 90)"),
    (["--model", "hooke"], "model", "kelvin-voigt, modified, linear-hunt-crossley, hertz, hunt-crossley"),
    (["--method", "Euler"], "method", "DOP853"),
    (["--separation", "sometimes"], "separation", "force, penetration"),
    (["--inertia-factor", "0.9"], "inertia_factor", "(0, 2/3]"),
    (["--inertia-factor", "0.66666666666667"], "inertia_factor", "2/3 = 0.6666666666666666"),
    (["--k", "nan"], "k", "finite"),
    (["--speed", "inf"], "speed", "finite"),
    (["--gravity", "-9.81"], "gravity", ">= 0"),
    (["--rtol", "0"], "rtol", "[1e-13, 1e-2]"),
    (["--mu", "abc"], "--mu", "expected a number"),
    (["--method", "closed"], "method 'closed'", "kelvin-voigt"),
    (["--model", "kelvin-voigt", "--b", "500", "--separation", "penetration"], "no separation", "penetration"),
]


@pytest.mark.parametrize("args, name, allowed", BAD, ids=[" ".join(a) for a, _, _ in BAD])
def test_bad_input_exits_2_naming_the_parameter(args, name, allowed, capsys):
    assert run(["simulate", *args, "--json"]) == 2
    err = capsys.readouterr()
    assert err.out == ""
    assert name in err.err and allowed in err.err and "Traceback" not in err.err


def test_api_raises_value_error_with_the_same_message(capsys):
    with pytest.raises(ValueError, match=r"^mass must be a finite number > 0 kg; got -1.0$"):
        Scene(mass=-1.0)
    assert run(["simulate", "--mass", "-1"]) == 2
    assert capsys.readouterr().err.strip() == "sphereimpact: error: mass must be a finite number > 0 kg; got -1.0"


def test_installed_command_runs():
    """The console script (and python -m) exit 2 on bad input with one line and no traceback."""
    bad = subprocess.run([sys.executable, "-m", "sphereimpact", "simulate", "--speed", "-3"],
                         capture_output=True, text=True)
    assert bad.returncode == 2
    assert bad.stderr.strip().splitlines() == ["sphereimpact: error: speed must be a finite number > 0 m/s; got -3.0"]
    good = subprocess.run([sys.executable, "-m", "sphereimpact", "simulate", "--json"], capture_output=True, text=True)
    assert good.returncode == 0 and json.loads(good.stdout)["regime"] == "none"


def test_readable_output_has_every_output_with_its_unit(capsys):
    assert run(["simulate", "--angle", "60"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert [line.split()[0] for line in lines] == [*OUTPUT_KEYS, "gravity"]
    cor = next(line for line in lines if line.startswith("cor "))
    assert float(cor.split()[1]) == pytest.approx(simulate(Scene(angle=60.0)).cor, rel=1e-9)
    assert next(line for line in lines if line.startswith("t_f ")).endswith(" s")


def test_help_documents_every_option_with_units():
    out = subprocess.run([sys.executable, "-m", "sphereimpact", "simulate", "--help"], capture_output=True, text=True)
    for text in ("[deg]", "[m/s]", "[N/m]", "[N s/m]", "[kg]", "[m]", "(default: 0.145)", "(default 60000)",
                 "[N/m^n]", "[s/m]", "[Pa]"):
        assert text in out.stdout, text
    sweep = subprocess.run([sys.executable, "-m", "sphereimpact", "sweep", "--help"], capture_output=True, text=True)
    assert "in [0, 90) degrees" in sweep.stdout and "> 0 kg" in sweep.stdout
    assert "default: None" not in sweep.stdout
    for text in (out.stdout, sweep.stdout):  # the rebound direction in both conventions, with their signs
        flat = " ".join(text.split())
        assert "from the surface normal [deg], in (-90, 90), negative when the ball kicks back" in flat
        assert "rebound_angle_to_surface = 90 - rebound_angle" in flat and "above 90 when the ball kicks back" in flat


def test_history_and_plot_from_the_command_line(tmp_path, capsys):
    """--history writes Outcome.history()'s table (CSV: units in the header; Parquet: in the schema's
    metadata), --plot its figure; both refused before any work when they cannot be written."""
    import pandas as pd
    import pyarrow.parquet as pq

    from sphereimpact import HISTORY_COLUMNS, Scene, simulate

    csv, parquet, png = tmp_path / "h.csv", tmp_path / "h.parquet", tmp_path / "h.png"
    args = ["simulate", "--angle", "30", "--spin", "100", "--samples", "51"]
    assert run([*args, "--history", str(csv), "--plot", str(png)]) == 0
    assert run([*args, "--history", str(parquet)]) == 0
    expected = simulate(Scene(angle=30.0, spin=100.0)).history(51)
    assert expected.attrs["units"] == HISTORY_COLUMNS
    written = pd.read_csv(csv)
    assert list(written.columns) == [f"{name} [{unit}]" for name, unit in HISTORY_COLUMNS.items()]
    np.testing.assert_array_equal(written.to_numpy(), expected.to_numpy())  # shortest round-trip floats
    assert pd.read_parquet(parquet).equals(expected)
    assert json.loads(pq.read_schema(parquet).metadata[b"units"]) == HISTORY_COLUMNS
    assert png.stat().st_size > 10_000
    capsys.readouterr()
    assert run([*args, "--history", str(csv)]) == 2  # exists
    assert run([*args, "--plot", str(tmp_path / "h.txt")]) == 2
    assert run([*args, "--samples", "1", "--history", str(tmp_path / "x.csv")]) == 2
    assert "samples must be an integer >= 2" in capsys.readouterr().err


def test_the_command_line_imports_what_a_subcommand_needs_when_it_needs_it():
    """Issue 43: `sphereimpact` imported the fit (pandas, scipy.optimize, scipy.stats) before parsing its
    arguments. Now loading the command line imports none of them, and `simulate` neither pandas nor the fit."""
    import subprocess
    import sys

    probe = ("import sys, io, contextlib\n"
             "import sphereimpact.cli as cli\n"
             "loaded = [m for m in ('pandas', 'scipy.optimize', 'scipy.stats', 'matplotlib') if m in sys.modules]\n"
             "with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):\n"
             "    cli.run(['simulate', '--json', '--angle', '60'])\n"
             "after = [m for m in ('pandas', 'scipy.stats', 'matplotlib', 'sphereimpact.fit.least_squares')\n"
             "         if m in sys.modules]\n"
             "print(loaded, after)\n")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[] []"
