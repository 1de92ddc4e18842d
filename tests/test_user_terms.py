"""The user's terms, not ours (issue 42): nothing of the user's description is substituted, a data file runs no
code, a failed write keeps the old file, and the answers that broke the model's own bounds stay inside them.
Each test failed before its fix."""

import json
import sys
import textwrap

import pytest

from sphereimpact import Scene, load_ball, save_ball
from sphereimpact.cli import run
from sphereimpact.impact.ball import Ball


@pytest.fixture
def trap(tmp_path, monkeypatch):
    """A module that leaves a marker file when imported, on the module path, and a ball file that names it."""
    marker = tmp_path / "imported"
    (tmp_path / "trap_module.py").write_text(f"open({str(marker)!r}, 'w').write('ran')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, "trap_module", raising=False)
    path = tmp_path / "ball.json"
    save_ball(Ball(Scene(), plugins=("trap_module",)), path)
    return path, marker


def test_a_ball_file_never_imports_code(trap, capsys):
    path, marker = trap
    with pytest.raises(ValueError, match="uses the plug-in 'trap_module', which is not loaded"):
        load_ball(path)
    assert run(["simulate", "--ball", str(path), "--json"]) == 2
    assert "never imports code" in capsys.readouterr().err
    assert not marker.exists()


def test_a_ball_file_loads_with_the_plugins_the_user_names(trap):
    path, marker = trap
    ball = load_ball(path, plugins=["trap_module"])
    assert marker.exists() and ball.plugins == ("trap_module",)


def test_the_study_config_check_does_not_import_a_ball_files_plugins(trap, tmp_path):
    from sphereimpact.study.config_check import config_errors

    path, marker = trap
    config = yaml_config(tmp_path, f"study: mine\nball_file: {path}\n")
    errors = config_errors(config, "config/schema.yaml")
    assert any("never imports code" in line for line in errors) and not marker.exists()


def yaml_config(tmp_path, text: str) -> dict:
    import yaml

    return yaml.safe_load(textwrap.dedent(text))


def test_plugins_in_a_ball_file_must_be_a_list_of_names(tmp_path):
    path = tmp_path / "ball.json"
    save_ball(Ball(Scene()), path)
    record = json.loads(path.read_text())
    path.write_text(json.dumps(record | {"plugins": "trap_module"}))
    with pytest.raises(ValueError, match="plugins must be a list of module names"):
        load_ball(path)
