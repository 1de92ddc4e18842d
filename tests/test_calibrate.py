"""Calibration: damping from a COR by a root find on the law itself, to 1e-9; the published relations as data."""

import numpy as np
import pytest

from sphereimpact import Scene, SolverOptions, simulate
from sphereimpact.impact.calibrate import calibrate
from sphereimpact.cli import run

DAMPED = {"kelvin-voigt": {}, "modified": {}, "linear-hunt-crossley": {}, "hunt-crossley": {"modulus": 1e7}}
TIGHT = SolverOptions(rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("name", list(DAMPED))
@pytest.mark.parametrize("cor", [0.1, 0.5, 0.85, 0.99])
def test_cor_is_hit_to_1e9_for_every_damped_law(name, cor):
    scene = Scene(model=name, angle=30.0, speed=7.0, **DAMPED[name])
    fitted = calibrate(scene, cor)
    assert abs(fitted.cor - cor) <= 1e-9 * cor
    assert abs(simulate(fitted.scene, TIGHT).cor - cor) <= 1e-9 * cor  # an independent solve of the fitted scene
    assert fitted.parameter == scene.law.damping


def test_relations_are_the_published_formulas():
    scene = Scene(model="hunt-crossley", modulus=1e7, speed=2.0)
    e, v = 0.8, 2.0
    relations = calibrate(scene, e).relations
    assert relations == pytest.approx({"hunt-crossley": 3 * (1 - e) / (2 * v),
                                       "lankarani-nikravesh": 3 * (1 - e**2) / (4 * v),
                                       "flores": 8 * (1 - e) / (5 * e * v), "gonthier": (1 - e**2) / (e * v)}, rel=1e-15)
    chosen = calibrate(scene, e, relation="lankarani-nikravesh")
    assert chosen.value == pytest.approx(3 * (1 - e**2) / (4 * v), rel=1e-15) and chosen.relation == "lankarani-nikravesh"


def test_stiffness_and_damping_from_cor_and_contact_time():
    fitted = calibrate(Scene(), 0.8, contact_time=4e-3)
    out = simulate(fitted.scene, TIGHT)
    assert out.cor == pytest.approx(0.8, rel=1e-9) and out.t_f == pytest.approx(4e-3, rel=1e-9)


IMPOSSIBLE = [
    (Scene(), 1.0, {}, r"cor must be a finite number in \(0, 1\)"),
    (Scene(), 0.0, {}, r"cor must be a finite number in \(0, 1\)"),
    (Scene(), float("nan"), {}, r"cor must be a finite number in \(0, 1\)"),
    (Scene(model="hertz", k=1e6), 0.8, {}, "model 'hertz' has no damping parameter"),
    (Scene(), 0.8, {"relation": "flores"}, "cor_relation 'flores' is not available for model 'modified'"),
    (Scene(), 0.8, {"relation": "newton"}, "cor_relation must be one of"),
    (Scene(), 0.8, {"contact_time": -1.0}, "contact_time must be a finite number > 0"),
]


@pytest.mark.parametrize("scene, cor, kwargs, message", IMPOSSIBLE, ids=[m[:20] for *_, m in IMPOSSIBLE])
def test_impossible_requests_are_refused(scene, cor, kwargs, message):
    with pytest.raises(ValueError, match=message):
        calibrate(scene, cor, **kwargs)


def test_cor_next_to_a_damping_that_never_separates_is_still_found():
    """kelvin-voigt under the penetration criterion never returns to delta = 0 once over-damped (zeta >= 1), and
    COR -> 0 as zeta -> 1-: the bracket must close in from the non-separating side, not give up."""
    scene = Scene(model="kelvin-voigt", separation="penetration")
    fitted = calibrate(scene, 0.001)
    assert abs(fitted.cor - 0.001) <= 1e-12 and fitted.scene.zeta < 1
    zeta = fitted.scene.zeta  # closed form: COR = exp(-pi zeta / sqrt(1 - zeta^2))
    assert np.exp(-np.pi * zeta / np.sqrt(1 - zeta**2)) == pytest.approx(0.001, rel=1e-9)


def test_cli_cor_sets_the_damping_and_reports_the_relations(capsys):
    assert run(["simulate", "--model", "hunt-crossley", "--modulus", "1e7", "--cor", "0.7", "--json"]) == 0
    import json

    out = json.loads(capsys.readouterr().out)
    assert out["cor"] == pytest.approx(0.7, rel=1e-9)
    assert set(out) >= {"fitted_chi", "chi_hunt-crossley", "chi_lankarani-nikravesh", "chi_flores", "chi_gonthier"}


@pytest.mark.parametrize("argv, message", [
    (["--model", "hertz", "--b", "3"], "b is not a parameter of model 'hertz'"),
    (["--cor", "0.8", "--b", "3"], "give b or cor, not both (cor sets b)"),
    (["--cor-relation", "flores"], "--cor-relation needs --cor"),
    (["--contact-time", "1e-3"], "--contact-time needs --cor"),
    (["--cor-speed", "3"], "--cor-speed needs --cor"),
    (["--model", "hertz", "--k", "1e6", "--cor", "0.9"], "model 'hertz' has no damping parameter"),
])
def test_cli_refuses_flags_the_law_does_not_use(argv, message, capsys):
    assert run(["simulate", *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err and err.count("\n") == 1


def test_calibrated_damping_is_monotone_in_cor():
    values = [calibrate(Scene(model="kelvin-voigt"), e).value for e in (0.9, 0.7, 0.5)]
    assert np.all(np.diff(values) > 0)


@pytest.mark.parametrize("name", ["hunt-crossley", "linear-hunt-crossley"])
@pytest.mark.parametrize("cor", [0.1, 0.5, 0.9])
def test_hunt_crossley_calibration_meets_the_exact_energy_relation(name, cor):
    """m v dv/d delta = -k delta^n (1 + chi v) separates, so the COR e of Hunt-Crossley damping on any spring solves
    chi v (1 + e) = ln[(1 + chi v) / (1 - chi e v)]: an independent closed-form reference for the root find."""
    from scipy.optimize import brentq

    scene = Scene(model=name, speed=4.0, **({"modulus": 1e7} if name == "hunt-crossley" else {}))
    exact = brentq(lambda c: c * (1 + cor) - np.log((1 + c) / (1 - c * cor)), 1e-3, (1 - 1e-15) / cor, xtol=1e-15)
    assert calibrate(scene, cor).value * scene.v_normal == pytest.approx(exact, rel=1e-8)
