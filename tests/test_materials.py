"""The contact from the bodies' materials, as DEM decks give them: E* and kappa against their formulas, through the
API, the command line and a study's config."""

import json
from pathlib import Path

import pandas as pd
import pytest
import yaml

from sphereimpact import Scene, simulate
from sphereimpact.cli import run
from sphereimpact.contact.materials import material_fields


def test_effective_modulus_and_kappa_of_the_formulas():
    """E* from 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2; like materials give kappa = 2 (1 - nu)/(2 - nu) (Mindlin), and a
    rigid flat E* = E / (1 - nu^2)."""
    fields = material_fields((380e9, 0.23), (70e9, 0.25), compliant=True)
    assert fields["modulus"] == pytest.approx(1 / ((1 - 0.23 ** 2) / 380e9 + (1 - 0.25 ** 2) / 70e9), rel=1e-14)
    g1, g2 = 380e9 / (2 * 1.23), 70e9 / (2 * 1.25)
    assert fields["kappa"] == pytest.approx(4 / ((2 - 0.23) / g1 + (2 - 0.25) / g2) / fields["modulus"], rel=1e-14)
    like = material_fields((70e9, 0.33), (70e9, 0.33), compliant=True)
    assert like["kappa"] == pytest.approx(2 * (1 - 0.33) / (2 - 0.33), rel=1e-14)
    assert like["modulus"] == pytest.approx(70e9 / (2 * (1 - 0.33 ** 2)), rel=1e-14)
    rigid = material_fields((70e9, 0.33))
    assert rigid == {"modulus": pytest.approx(70e9 / (1 - 0.33 ** 2), rel=1e-14)}


def test_materials_refuse_bad_values_and_a_second_description():
    with pytest.raises(ValueError, match=r"surface_material: Poisson's ratio nu must be a finite number in \(-1, 0.5\]"):
        material_fields((70e9, 0.3), (70e9, 0.7))
    with pytest.raises(ValueError, match="ball_material: Young's modulus E must be a finite number > 0 Pa"):
        material_fields((-1.0, 0.3))
    with pytest.raises(ValueError, match="give kappa or the materials"):
        material_fields((70e9, 0.3), compliant=True, given={"kappa"})


def test_command_line_takes_the_materials(tmp_path, capsys):
    argv = ["--model", "hertz", "--tangential", "microslip", "--incidence", "30", "--speed", "3.9", "--mass", "2.6e-4",
            "--diameter", "5e-3", "--mu", "0.092", "--ball-material", "380e9,0.23", "--surface-material", "70e9,0.25"]
    assert run(["simulate", *argv, "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    scene = Scene(model="hertz", tangential="microslip", incidence=30, speed=3.9, mass=2.6e-4, diameter=5e-3, mu=0.092,
                  **material_fields((380e9, 0.23), (70e9, 0.25), compliant=True))
    assert printed["omega_f"] == pytest.approx(simulate(scene).omega_f, rel=1e-12)
    out = tmp_path / "sweep.csv"
    assert run(["sweep", *argv, "--out", str(out)]) == 0
    table = pd.read_csv(out)
    assert table["kappa"].iloc[0] == pytest.approx(scene.kappa, rel=1e-12)
    assert table["k"].iloc[0] == pytest.approx(scene.k, rel=1e-12)
    assert run(["simulate", "--model", "hertz", "--ball-material", "70e9,0.3", "--modulus", "1e9"]) == 2
    assert "give modulus or the materials" in capsys.readouterr().err


def test_a_study_config_takes_the_materials():
    from sphereimpact.study.config import with_defaults
    from sphereimpact.study.own import study_ball

    schema = yaml.safe_load((Path(__file__).parents[1] / "config/schema.yaml").read_text())
    config = with_defaults(schema, {"study": "alumina", "ball": {"mass": 2.1e-4, "diameter": 5e-3}, "contact": {
        "model": "hertz", "tangential": "mindlin",
        "materials": {"ball": {"E": 380e9, "nu": 0.23}, "surface": {"E": 70e9, "nu": 0.25}}}})
    scene = study_ball(config).scene
    expected = material_fields((380e9, 0.23), (70e9, 0.25), compliant=True)
    assert scene.modulus == pytest.approx(expected["modulus"], rel=1e-14)
    assert scene.kappa == pytest.approx(expected["kappa"], rel=1e-14)
