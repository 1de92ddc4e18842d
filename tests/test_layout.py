"""The package's layers as folders: every module that moved still imports under its old name, as the same
module object, with a DeprecationWarning naming the new one (one release)."""

import importlib
import sys

import pytest

import sphereimpact


@pytest.mark.parametrize("old", sorted(sphereimpact.MOVED))
def test_a_moved_module_imports_under_its_old_name_with_a_warning(old):
    new = sphereimpact.MOVED[old]
    sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning, match=f"{old} moved to {new}"):
        module = importlib.import_module(old)
    assert module is importlib.import_module(new)


def test_a_submodule_of_a_moved_package_keeps_its_state():
    """The old name is the same object: a law registered through it is in the registry the package uses."""
    sys.modules.pop("sphereimpact.laws.base", None)
    with pytest.warns(DeprecationWarning, match="sphereimpact.laws.base moved to sphereimpact.contact.laws.base"):
        from sphereimpact.laws.base import LAWS
    assert LAWS is sphereimpact.LAWS


def test_the_public_api_is_where_it_was():
    from sphereimpact import LAWS, Scene, SolverOptions, simulate  # noqa: F401
    from sphereimpact.sweep import sweep  # noqa: F401
    from sphereimpact.impact.calibrate import calibrate  # noqa: F401
    assert simulate(Scene(angle=60.0)).cor == pytest.approx(0.865, abs=1e-3)  # the chapter's oblique case


def test_the_input_rules_still_import_from_the_scene_module():
    """impact/inputs.py took the input rules out of impact/scene.py, which re-exports them unchanged."""
    from sphereimpact.impact import inputs, scene
    for name in ("RULES", "PATH_RULES", "SEPARATION_CRITERIA", "SQUARE_LIMIT", "TEXT_FIELDS", "as_number",
                 "check_columns", "law_parameters", "magnitude_problem", "scale_problem"):
        assert getattr(scene, name) is getattr(inputs, name), name
