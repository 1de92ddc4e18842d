"""Scene.with_'s copy of a scene whose approach alone changes (Scene._approached): every attribute the full build
gives, the same refusals, and the same impact."""

import math

import numpy as np
import pytest

from sphereimpact.impact import scene as scene_module
from sphereimpact.impact.scene import FIELDS, Scene, _CACHED
from sphereimpact.impact.solve import simulate

#: Every built-in law and tangential model, the chapter's values (ChapterValue) and a user's, every way of giving
#: kappa, gravity, a tilt and both path descriptions, spin.
BALLS = {
    "chapter": Scene(angle=60.0),
    "kelvin-voigt": Scene(model="kelvin-voigt", angle=30.0, mu=0.4),
    "linear": Scene(model="linear-hunt-crossley", k=5e4, chi=0.3, tangential="linear", kappa=0.7, mass=0.1,
                    diameter=0.05, angle=20.0),
    "mindlin": Scene(model="hertz", modulus=1e8, tangential="mindlin", poisson=0.3, gravity=9.81, angle=10.0),
    "microslip": Scene(model="hunt-crossley", modulus=6.3e10, chi=0.0078, tangential="microslip",
                       shear_modulus=1.35e10, mass=2.56e-4, diameter=5e-3, incidence=20.0),
    "displacement": Scene(model="hertz", k=1e7, tangential="mindlin-displacement", kappa=0.8, angle_to_surface=50.0,
                          spin=-30.0),
}

#: Changes of the approach alone, each as with_ takes it.
CHANGES = ({}, {"angle": 45.0}, {"speed": 7.5, "spin": 120.0}, {"mu": 0.05, "gravity": 3.0}, {"incidence": 33.0},
           {"angle_to_surface": 80.0, "speed": 1.5}, {"angle": 0.0, "spin": 0.0}, {"speed": 2, "angle": 5})


class _NoApproach:
    """No change counts as the approach's alone, none at all included."""

    @staticmethod
    def issuperset(changes) -> bool:
        return False


def _full_build(monkeypatch):
    """with_ with no change counted as the approach's: every copy built from its fields, the reference."""
    monkeypatch.setattr(scene_module, "APPROACH", _NoApproach())


def _attributes(scene: Scene) -> dict:
    """Every field, parameter and derived quantity of ``scene``, each with its type."""
    names = (FIELDS - {"parameters"}) | set(_CACHED) | set(scene.parameters)
    return {name: (type(value := getattr(scene, name)), value) for name in sorted(names)} | {
        "parameters": [(name, type(value), value) for name, value in scene.parameters.items()]}


@pytest.mark.parametrize("ball", BALLS)
def test_a_copy_of_a_new_approach_is_the_scene_built_from_its_fields(ball, monkeypatch):
    scene, taken = BALLS[ball], []
    approached = Scene._approached
    monkeypatch.setattr(Scene, "_approached", lambda self, changes: taken.append(1) or approached(self, changes))
    changes = [*CHANGES, {"speed": scene.speed}]  # the chapter's speed handed back: still the chapter's
    copies = [_attributes(scene.with_(**change)) for change in changes]
    assert len(taken) == len(changes)  # each took the copy
    _full_build(monkeypatch)
    built = [_attributes(scene.with_(**change)) for change in changes]
    assert len(taken) == len(changes)
    assert copies == built


def test_a_copy_reads_the_new_approach_and_solves_as_the_built_scene(monkeypatch):
    scene = BALLS["chapter"]
    copy = scene.with_(speed=5.0, incidence=25.0)
    assert (copy.angle, copy.incidence, copy.v_normal) == (0.0, 25.0, 5.0 * math.cos(math.radians(25.0)))
    assert scene.speed == 3.0 and scene.v_normal == 3.0 * math.cos(math.radians(60.0))  # the original untouched
    _full_build(monkeypatch)
    solved, built = simulate(copy).to_dict(), simulate(scene.with_(speed=5.0, incidence=25.0)).to_dict()
    assert solved.pop("wall_time") > 0 and built.pop("wall_time") > 0
    assert solved == built


@pytest.mark.parametrize("change", [{"angle": 90.0}, {"speed": -1.0}, {"spin": math.nan}, {"mu": -0.1},
                                    {"incidence": 95.0}, {"angle_to_surface": 0.0}, {"speed": 1e200},
                                    {"speed": True}, {"gravity": 1e9}, {"speed": np.float64(1e-300)}])
def test_a_bad_approach_is_refused_by_the_copy_as_by_the_full_build(change, monkeypatch):
    scene = BALLS["mindlin"]
    with pytest.raises((ValueError, TypeError)) as copied:
        scene.with_(**change)
    _full_build(monkeypatch)
    with pytest.raises((ValueError, TypeError)) as built:
        scene.with_(**change)
    assert (type(copied.value), str(copied.value)) == (type(built.value), str(built.value))


def test_changes_beyond_the_approach_build_the_scene_again(monkeypatch):
    taken = []
    monkeypatch.setattr(Scene, "_approached", lambda self, changes: taken.append(changes))
    scene = BALLS["displacement"]
    for change in ({"diameter": 0.05}, {"k": 2e7}, {"poisson": 0.25}, {"tangential": "rigid"}, {"model": "hertz"},
                   {"parameters": {"k": 2e7, "kappa": 0.8}}, {"partner_mass": 0.1, "partner_diameter": 0.05}):
        scene.with_(**change)
    assert taken == []
    assert scene.with_(parameters={"k": 2e7, "kappa": 0.8}).k == 2e7  # a parameter given by a mapping is read
