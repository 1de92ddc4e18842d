"""A law registered from outside the package (here, in this file only) is served by every layer, or refused.

The law: a linear spring with damping that grows with the contact, P = k delta + b delta_dot delta / R
(parameters k and b, declared by reusing the chapter's).  It has no closed form and no batched kernel, so
the sweep must take its exact per-family path; before the laws became plug-ins the sweep computed the
kelvin-voigt closed form for it (COR 0.6788 against 0.5864 from simulate, no error).
"""

import importlib
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from sphereimpact import LAWS, ContactLaw, Scene, SolverOptions, simulate
from sphereimpact.cli import run
from sphereimpact.contact.laws.linear import B, K, damping_ratio, natural_frequency
from sphereimpact.sweep.engine import grid, sweep

NAME = "growing-damping"
OUTPUTS = ("t_m", "delta_m", "t_f", "vc_t", "vc_n", "ve_t", "ve_n", "omega_f", "cor")


def _continued(delta, delta_dot, p):
    delta = np.asarray(delta, dtype=float)
    return p.k * delta + p.b * np.asarray(delta_dot, dtype=float) * delta / p.radius


GROWING = ContactLaw(
    NAME, "P = k delta + b delta_dot delta / R (test law)", (K, B), _continued, natural_frequency,
    family=lambda p: {"zeta": damping_ratio(p), "depth": p.v_normal / (natural_frequency(p) * p.radius)},
    horizon=lambda p: 100.0 * np.pi * (1.0 + 2.0 * damping_ratio(p)), damping="b")


@pytest.fixture
def law():
    LAWS.register(GROWING)
    yield GROWING
    del LAWS[NAME]


def test_simulate_sweep_and_cli_agree(law, capsys):
    scene = Scene(model=NAME, b=400.0, angle=30.0)
    ref = simulate(scene, SolverOptions(rtol=1e-12, atol=1e-12))
    assert ref.cor < 0.9  # the law damps: not mistaken for an elastic or another law
    kv = simulate(Scene(model="kelvin-voigt", b=400.0, angle=30.0))
    assert abs(kv.cor - ref.cor) > 0.01  # and it is not kelvin-voigt
    table = sweep(grid(angle=[0.0, 30.0, 60.0], speed=[1.0, 3.0]).assign(model=NAME, b=400.0), chapter_ball=True)
    for row in table.to_dict("records"):
        one = simulate(Scene(model=NAME, b=400.0, angle=row["angle"], speed=row["speed"]),
                       SolverOptions(rtol=1e-12, atol=1e-12))
        for key in OUTPUTS:
            assert row[key] == pytest.approx(getattr(one, key), rel=1e-8, abs=1e-12), key
        assert row["regime"] == one.regime
    assert run(["simulate", "--model", NAME, "--b", "400", "--angle", "30", "--rtol", "1e-12", "--atol", "1e-12",
                "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    for key in OUTPUTS:
        assert cli[key] == getattr(ref, key), key  # the same call: bit for bit


def test_a_law_without_a_scalar_formula_runs_on_scipys_dop853(law):
    """The default DOP853-scalar needs ContactLaw.scalar: without it, the same algorithm through scipy."""
    scene = Scene(model=NAME, b=400.0, angle=30.0)
    out, ref = simulate(scene), simulate(scene, SolverOptions(method="DOP853"))
    assert out.method == "DOP853"
    assert out.to_dict() | {"wall_time": 0.0} == ref.to_dict() | {"wall_time": 0.0}


def _growing_scalar(delta, delta_dot, p):
    return p.k * delta + p.b * delta_dot * delta / p.radius


def _growing_kernel(delta, delta_dot, p):  # compiled by numba when the law is first integrated
    return p[0] * delta + p[1] * delta_dot * delta / p[2]


def test_a_law_that_brings_its_own_kernel_is_integrated_compiled_with_the_python_floats_answer(law, capsys,
                                                                                          monkeypatch):
    """The growing-damping law with its scalar formula and a kernel of its own (a plain function of this file):
    DOP853-scalar integrates it compiled, to the bit of the Python floats' answer, in simulate, the sweep and the
    command line."""
    from dataclasses import replace

    from sphereimpact import Kernel
    from sphereimpact.integrators import compiled as compiled_rule, runge_kutta
    from sphereimpact.ode import dop853

    compiled_law = LAWS.register(replace(GROWING, name="growing-compiled", scalar=_growing_scalar,
                                         kernel=Kernel(_growing_kernel, lambda p: (p.k, p.b, p.radius))))
    monkeypatch.setattr(compiled_rule, "COMPILE_AFTER", 0)
    calls, driven = [], []
    compiled, drive = runge_kutta._compiled, runge_kutta._compiled_drive
    monkeypatch.setattr(runge_kutta, "_compiled", lambda *args: calls.append(1) or compiled(*args))
    monkeypatch.setattr(runge_kutta, "_compiled_drive", lambda *args: driven.append(1) or drive(*args))
    try:
        scene = Scene(model="growing-compiled", b=400.0, angle=30.0)
        out = simulate(scene).to_dict()
        assert out["method"] == "DOP853-scalar" and len(driven) == 1 and not calls  # the whole motion, compiled
        assert out["cor"] == pytest.approx(simulate(Scene(model=NAME, b=400.0, angle=30.0)).cor, rel=1e-8)
        monkeypatch.setattr(runge_kutta, "_compiled_drive", lambda run, band: None)
        stepwise = simulate(scene).to_dict()
        assert len(calls) == 2  # run by run, compiled: to separation, the landing
        monkeypatch.setattr(runge_kutta, "_compiled", lambda rhs, span, z0, rtol, atol, max_step, events, first:
                            dop853.solve(rhs, span, z0, rtol, atol, max_step=max_step, events=events,
                                         first_step=first))
        floats = simulate(scene).to_dict()
        assert out | {"wall_time": 0.0} == floats | {"wall_time": 0.0} == stepwise | {"wall_time": 0.0}
        monkeypatch.setattr(runge_kutta, "_compiled", compiled)
        monkeypatch.setattr(runge_kutta, "_compiled_drive", drive)
        row = sweep(grid(angle=[30.0]).assign(model="growing-compiled", b=400.0), chapter_ball=True).iloc[0]
        assert row["cor"] == pytest.approx(out["cor"], rel=1e-8)
        assert run(["simulate", "--model", "growing-compiled", "--b", "400", "--angle", "30", "--json"]) == 0
        assert json.loads(capsys.readouterr().out)["cor"] == out["cor"]
    finally:
        del LAWS[compiled_law.name]


def _uncompilable_kernel(delta, delta_dot, p):
    return p.k * delta + p.b * delta_dot * delta / p.radius  # the scalar formula's p: an array has no .k


def _doubled_kernel(delta, delta_dot, p):
    return 2.0 * (p[0] * delta + p[1] * delta_dot * delta / p[2])


@pytest.mark.parametrize("kernel, message", [
    (_uncompilable_kernel, r"law 'growing-bad': its kernel does not compile \(TypingError: Unknown attribute 'k'"),
    (_doubled_kernel,
     r"law 'growing-bad': its kernel gives P = .* N where its scalar formula gives .* a kernel must be the scalar"),
])
def test_a_kernel_that_does_not_compile_or_is_not_the_scalar_formula_is_refused_by_name(kernel, message, capsys,
                                                                                        monkeypatch):
    """A plug-in's kernel is compiled and checked against its scalar formula on its first use: refused in one line
    (API and command line), never integrated in the formula's place."""
    from dataclasses import replace

    from sphereimpact import Kernel
    from sphereimpact.integrators import compiled as compiled_rule

    bad = LAWS.register(replace(GROWING, name="growing-bad", scalar=_growing_scalar,
                                kernel=Kernel(kernel, lambda p: (p.k, p.b, p.radius))))
    monkeypatch.setattr(compiled_rule, "COMPILE_AFTER", 0)
    try:
        with pytest.raises(ValueError, match=message):
            simulate(Scene(model="growing-bad", b=400.0, angle=30.0))
        assert run(["simulate", "--model", "growing-bad", "--b", "400", "--angle", "30", "--json"]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "law 'growing-bad': its kernel" in err
    finally:
        del LAWS[bad.name]


def test_tilted_gravity_and_calibration_reach_the_law(law):
    from sphereimpact.impact.calibrate import calibrate

    scene = Scene(model=NAME, b=400.0, angle=20.0, gravity=9.81)
    row = sweep(grid(angle=[20.0]).assign(model=NAME, b=400.0, gravity=9.81), chapter_ball=True).iloc[0]
    assert row["cor"] == pytest.approx(simulate(scene).cor, rel=1e-8)
    assert calibrate(scene, 0.6).cor == pytest.approx(0.6, rel=1e-9)


def test_the_law_refuses_parameters_it_does_not_declare(law):
    with pytest.raises(ValueError, match=f"ramp is not a parameter of model '{NAME}'"):
        Scene(model=NAME, ramp=100.0)
    with pytest.raises(ValueError, match="method 'closed' needs a law with a closed form"):
        simulate(Scene(model=NAME), SolverOptions(method="closed"))


def test_a_law_with_a_parameter_of_its_own_is_served_by_every_door(law, capsys):
    """P = k delta + g b delta_dot delta / R with its own growth factor g (default 1): the growing-damping law with
    b scaled by g, so g = 2 at b = 400 must give what b = 800 gives, in simulate, sweep and the command line."""
    from sphereimpact import Parameter

    growth = Parameter("growth", "-", "damping growth factor", "a finite number > 0", lambda x: x > 0, default=1.0)

    def continued(delta, delta_dot, p):
        return _continued(delta, delta_dot, p) + (p.growth - 1.0) * (_continued(delta, delta_dot, p) - p.k * np.asarray(
            delta, dtype=float))

    grown = LAWS.register(ContactLaw(
        "grown", "growing damping scaled by its own factor (test law)", (K, B, growth), continued, natural_frequency,
        family=lambda p: {"zeta": damping_ratio(p) * p.growth, "depth": p.v_normal / (natural_frequency(p) * p.radius)},
        horizon=GROWING.horizon, damping="b"))
    try:
        assert grown.own_parameters == (growth,)
        scene = Scene(model="grown", b=400.0, angle=30.0, parameters={"growth": 2.0})
        same = simulate(Scene(model=NAME, b=800.0, angle=30.0))
        assert simulate(scene).cor == pytest.approx(same.cor, rel=1e-9)
        assert Scene(model="grown", b=400.0).growth == 1.0  # its default
        copied = Scene(model="grown", b=400.0, growth=2.0).with_(model=NAME)  # by name, as a built-in one
        assert "growth" not in copied.parameters and copied.growth is None and copied.b == 400.0
        assert Scene(model="grown", b=400.0, growth=2.0) == scene.with_(angle=0.0)
        table = sweep(grid(angle=[0.0, 30.0], growth=[1.0, 2.0]).assign(model="grown", b=400.0), chapter_ball=True)
        for row in table.to_dict("records"):
            ref = simulate(Scene(model=NAME, b=400.0 * row["growth"], angle=row["angle"]))
            assert row["cor"] == pytest.approx(ref.cor, rel=1e-8) and row["omega_f"] == pytest.approx(ref.omega_f, rel=1e-8)
        assert run(["simulate", "--model", "grown", "--b", "400", "--growth", "2", "--angle", "30", "--json"]) == 0
        assert json.loads(capsys.readouterr().out)["cor"] == simulate(scene).cor
        with pytest.raises(ValueError, match=r"growth must be a finite number > 0; got -1.0"):
            Scene(model="grown", b=400.0, parameters={"growth": -1.0})
    finally:
        del LAWS["grown"]


def test_a_capability_the_sweep_lacks_is_refused_not_borrowed():
    """The batched lanes take a law by its own dimensionless force, never by a claim: a law whose force equals
    eq. 4.2 but is its own function is solved per family."""
    from dataclasses import replace

    modified = LAWS["modified"]
    LAWS.register(replace(modified, name="own-form", scaled=lambda x, y, n: modified.scaled(x, y, n)))
    try:
        scenes = grid(angle=[0.0, 30.0], speed=[1.0, 3.0])
        own, chapter = sweep(scenes.assign(model="own-form"), chapter_ball=True), sweep(scenes, chapter_ball=True)
        assert set(own["path"]) == {"per-family"} and "per-family" not in set(chapter["path"])
        assert np.allclose(own["cor"], chapter["cor"], rtol=1e-8)
    finally:
        del LAWS["own-form"]


# --- a tangential model registered from outside ----------------------------------------------------------
class _AlwaysSliding:
    """Toy tangential model: the contact slides throughout under a fraction kappa of Coulomb's friction,
    F = -kappa mu P+, never gripping; its motion follows from the normal impulse."""

    def __init__(self, normal, options):
        from sphereimpact.contact.tangential import Phase, PositiveImpulse

        self.normal, self.scene = normal, normal.scene
        self.jp = PositiveImpulse(normal)
        self._phase = Phase("sliding", 0.0, normal.t_f, self.scene.v_tangent, self.scene.spin, 0.0)
        self.t_roll, self.regime, self.switches = None, "sliding", 0

    def at(self, t):
        from sphereimpact.contact.tangential import from_impulse

        t = np.atleast_1d(np.asarray(t, dtype=float))
        share = -self.scene.kappa * self.scene.mu
        return np.array(from_impulse(self.scene, self._phase, t, share * self.jp(t), share * self.jp.integral(t)))

    def force(self, t):
        return -self.scene.kappa * self.scene.mu * np.maximum(self.normal.force(t), 0.0)


def _always_sliding_end(rows, impulse, instants):
    """The toy model's end state for many scenes at once: the kick of a tangential impulse -kappa mu J+."""
    from sphereimpact.contact.tangential import kick

    vc_t, omega = kick(rows.v_tangent, rows.spin, -rows.kappa * rows.mu * impulse, rows.mass, rows.radius,
                       rows.inertia_factor)
    n = vc_t.size
    return {"vc_t": vc_t, "omega_f": omega, "t_roll": np.full(n, np.nan), "switches": np.zeros(n, int),
            "regime": np.full(n, "sliding", dtype=object)}


@pytest.fixture(params=["one by one", "swept"])
def tangential_model(request):
    """The toy model, solved scene by scene in sweeps or with its own vectorised end state (``swept``)."""
    from sphereimpact.contact.tangential import KAPPA, TANGENTIALS, SweptTangential, TangentialModel

    swept = SweptTangential(levels=lambda rows: np.full(rows.mass.size, np.nan), end=_always_sliding_end)
    model = TANGENTIALS.register(TangentialModel("toy-slide", doc="slides under kappa mu P (test model)",
                                                 stiffness="F = -kappa mu P", parameters=(KAPPA,), spring=None,
                                                 motion=_AlwaysSliding,
                                                 swept=swept if request.param == "swept" else None))
    yield model
    del TANGENTIALS["toy-slide"]


def test_a_registered_tangential_model_is_served_by_simulate_sweep_and_cli(tangential_model, capsys):
    scene = Scene(angle=30.0, tangential="toy-slide", kappa=0.5)
    out = simulate(scene)
    impulse = scene.mass * scene.v_normal * (1.0 + out.cor)  # normal impulse: the force never pulls at 30 deg
    assert out.vc_t == pytest.approx(scene.v_tangent - 0.5 * scene.mu * impulse / scene.mass, rel=1e-9)
    assert out.omega_f == pytest.approx(0.5 * scene.mu * impulse * scene.radius / scene.inertia, rel=1e-9)
    assert out.regime == "sliding" and out.switches == 0
    steep = scene.with_(angle=60.0)  # where the rigid contact slides throughout, half its friction: half its spin
    assert simulate(steep).omega_f == pytest.approx(0.5 * simulate(steep.with_(tangential="rigid")).omega_f, rel=1e-9)
    table = sweep(grid(incidence=[0.0, 30.0, 60.0], speed=[1.0, 3.0], spin=[-40.0, 0.0],
                       gravity=[0.0, 9.81]).assign(tangential="toy-slide", kappa=0.5), chapter_ball=True)  # a level flat
    moving = set(table.loc[(table["incidence"] > 0) | (table["spin"] != 0), "path"])  # with tangential motion
    assert moving == ({"single"} if tangential_model.swept is None else {"taylor-lanes", "runge-kutta-lanes"})
    for row in table.to_dict("records"):
        one = simulate(Scene(incidence=row["incidence"], speed=row["speed"], spin=row["spin"], gravity=row["gravity"],
                             tangential="toy-slide", kappa=0.5), SolverOptions(rtol=1e-12, atol=1e-12))
        for key in (*OUTPUTS, "switches", "work_t", "rebound_angle"):
            assert row[key] == pytest.approx(getattr(one, key), rel=1e-8, abs=1e-12), key
        assert row["regime"] == one.regime
    assert run(["simulate", "--angle", "30", "--tangential", "toy-slide", "--kappa", "0.5", "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    assert cli["vc_t"] == out.vc_t and cli["omega_f"] == out.omega_f
    assert run(["simulate", "--angle", "30", "--tangential", "toy-slide", "--poisson", "0.5"]) == 2
    assert "poisson sets kappa of tangential 'linear' or 'mindlin'" in capsys.readouterr().err
    with pytest.raises(ValueError, match="body 'planar' has the rigid tangential contact only on the flat; tangential "
                                         "'toy-slide' is solved by body 'reduced'"):
        simulate(scene, body="planar")


def test_the_planar_body_serves_the_contacts_it_implements_and_refuses_a_copy():
    """The planar body implements the rigid Coulomb contact, as an object: a registered copy of the rigid
    model under another name (which a flag would have let through to the built-in contact) is refused."""
    from dataclasses import replace

    from sphereimpact.contact.tangential import TANGENTIALS

    TANGENTIALS.register(replace(TANGENTIALS["rigid"], name="rigid-copy"))
    try:
        scene = Scene(angle=30.0, tangential="rigid-copy")
        assert simulate(scene).omega_f == simulate(scene.with_(tangential="rigid")).omega_f
        assert simulate(scene.with_(tangential="rigid"), body="planar").omega_f == pytest.approx(
            simulate(scene).omega_f, rel=1e-8)
        with pytest.raises(ValueError, match="tangential 'rigid-copy' is solved by body 'reduced'"):
            simulate(scene, body="planar")
    finally:
        del TANGENTIALS["rigid-copy"]


# --- an integrator registered from outside ---------------------------------------------------------------
@pytest.fixture
def integrator():
    from dataclasses import replace

    from sphereimpact.integrators import INTEGRATORS, Integrator
    from sphereimpact.integrators.normal import IntegratedNormal

    def solve(scene, options):  # DOP853 in plain floats, steps capped at 1/100 of the undamped period
        return IntegratedNormal(scene, replace(options, method="DOP853-scalar",
                                               max_step=2 * np.pi / scene.frequency / 100))

    def cannot(scene):
        return None if scene.law.scalar is not None else f"needs a law with a scalar formula; got {scene.model!r}"

    toy = INTEGRATORS.register(Integrator("toy-capped", "DOP853-scalar, steps capped (test integrator)", solve,
                                          cannot=cannot))
    yield toy
    del INTEGRATORS["toy-capped"]


def test_a_registered_integrator_is_served_by_simulate_and_cli_and_refuses_what_it_cannot(integrator, law, capsys):
    scene = Scene(angle=30.0)
    out = simulate(scene, SolverOptions(method="toy-capped"))
    period = 2 * np.pi / scene.frequency
    same = simulate(scene, SolverOptions(method="DOP853-scalar", max_step=period / 100))
    assert out.to_dict() | {"wall_time": 0} == same.to_dict() | {"wall_time": 0}
    assert out.nfev > simulate(scene, SolverOptions(method="DOP853-scalar")).nfev  # the cap took effect
    exact = simulate(scene.with_(model="kelvin-voigt"), SolverOptions(method="closed"))
    capped = simulate(scene.with_(model="kelvin-voigt"), SolverOptions(method="toy-capped"))
    assert capped.cor == pytest.approx(exact.cor, rel=1e-9) and capped.t_f == pytest.approx(exact.t_f, rel=1e-9)
    assert simulate(scene).method == "taylor"  # auto keeps its declared order
    assert run(["simulate", "--angle", "30", "--method", "toy-capped", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["cor"] == out.cor
    with pytest.raises(SystemExit):
        run(["simulate", "--help"])
    assert "toy-capped" in capsys.readouterr().out
    with pytest.raises(ValueError, match="method 'toy-capped' needs a law with a scalar formula; got 'growing-damping'"):
        simulate(Scene(model=NAME, b=400.0, angle=30.0), SolverOptions(method="toy-capped"))
    assert run(["simulate", "--model", NAME, "--b", "400", "--method", "toy-capped"]) == 2
    assert "needs a law with a scalar formula" in capsys.readouterr().err


def test_a_registered_stepper_is_driven_like_the_built_in_ones():
    """An integrator that declares only a ``stepper`` gets the driver's events, ramp band and landing on t_f:
    scipy's DOP853 wrapped from outside gives exactly what the built-in ``DOP853`` gives, and is called."""
    from scipy.integrate import solve_ivp

    from sphereimpact.integrators import INTEGRATORS, Integrator
    from sphereimpact.integrators.normal import IntegratedNormal

    calls = []

    def stepper(rhs, span, z0, rtol, atol, max_step, events, first_step):
        calls.append(span)
        return solve_ivp(rhs, span, z0, method="DOP853", rtol=rtol, atol=atol, dense_output=True,
                         max_step=max_step, events=events, first_step=first_step)

    INTEGRATORS.register(Integrator("toy-stepper", "scipy's DOP853 from outside (test)", IntegratedNormal,
                                    ivp="DOP853", stepper=stepper))
    try:
        for scene in (Scene(angle=60.0), Scene(model="hertz", modulus=1e7, angle=30.0)):
            out = simulate(scene, SolverOptions(method="toy-stepper"))
            ref = simulate(scene, SolverOptions(method="DOP853"))
            assert {k: getattr(out, k) for k in OUTPUTS} == {k: getattr(ref, k) for k in OUTPUTS}
            assert out.method == "toy-stepper" and ref.method == "DOP853"
        assert len(calls) >= 4  # a first run, the ramp band's restart and the landing, per scene
    finally:
        del INTEGRATORS["toy-stepper"]
    with pytest.raises(ValueError, match="method 'taylor' is not a step-by-step integrator"):
        IntegratedNormal(Scene(), SolverOptions(method="taylor"))


def test_a_closed_form_declared_from_outside_serves_simulate_and_the_sweep():
    """A law may bring its own exact solution (a ClosedForm): the ``closed`` integrator and the sweep's closed
    path use it, also in a sweep that mixes two laws' closed forms (here eq. 4.1's solution declared anew).
    Without its ``jet`` the closed path gives the events only: rows that need the force's extremes or the
    grip instant take another exact path (the Runge-Kutta lanes here), and agree."""
    from dataclasses import replace

    from sphereimpact.contact.laws.closed_form import ClosedForm
    from sphereimpact.contact.laws.spring_damper import SpringDamperMotion, events, jet
    from sphereimpact.numerics.reference import reference
    from sphereimpact.numerics.workprecision import work_precision
    from sphereimpact.sweep.engine import FAST_OUTPUTS

    calls = []

    def counted(numbers, separation):
        calls.append(len(numbers["zeta"]))
        return events(numbers["zeta"], separation)

    LAWS.register(replace(LAWS["kelvin-voigt"], name="kv-again",
                          closed_form=ClosedForm("eq. 4.1 again", SpringDamperMotion, counted, ("zeta",), jet)))
    LAWS.register(replace(LAWS["kelvin-voigt"], name="kv-events",
                          closed_form=ClosedForm("eq. 4.1's events only", SpringDamperMotion, counted, ("zeta",))))
    try:
        scene = Scene(model="kv-again", angle=30.0)
        assert simulate(scene, SolverOptions(method="closed")).to_dict() | {"wall_time": 0, "model": 0} == \
            simulate(scene.with_(model="kelvin-voigt"), SolverOptions(method="closed")).to_dict() | {
                "wall_time": 0, "model": 0}
        scenes = grid(angle=[0.0, 30.0, 60.0], speed=[1.0, 3.0], b=[5.0, 50.0])
        mixed = sweep(scenes.assign(model=["kv-again", "kelvin-voigt"] * 6), chapter_ball=True)
        alone = sweep(scenes.assign(model="kelvin-voigt"), chapter_ball=True)
        assert set(mixed["path"]) == {"closed"} and sum(calls) == 6
        assert mixed.drop(columns="model").equals(alone.drop(columns="model"))
        events_only = sweep(scenes.assign(model="kv-events"), chapter_ball=True)
        assert set(events_only["path"]) == {"runge-kutta-lanes"}
        assert set(sweep(scenes.assign(model="kv-events"), outputs=FAST_OUTPUTS, chapter_ball=True)["path"]) == {"closed"}
        for key in ("t_roll", "force_max", "force_min", "omega_f", "cor"):
            assert np.allclose(events_only[key], alone[key], rtol=1e-8, atol=1e-9 * alone["force_max"].max(),
                               equal_nan=True), key
        assert reference(scene).how == "closed form"
        chart = work_precision({"again": scene}, tolerances=(1e-6,), methods=("DOP853-scalar",))
        assert list(chart["body"]) == ["closed", "reduced"] and chart["error"].iloc[0] == 0.0
    finally:
        del LAWS["kv-again"], LAWS["kv-events"]


# --- a tangential model with a parameter and a setting of its own, from a plug-in module ------------------
TESTS = Path(__file__).resolve().parent


@pytest.fixture
def share_slide(monkeypatch):
    """tests/plugin_model.py imported as a plug-in (it registers ``share-slide`` on import), and removed after."""
    from sphereimpact.contact.tangential import TANGENTIALS

    monkeypatch.syspath_prepend(str(TESTS))
    sys.modules.pop("plugin_model", None)
    module = importlib.import_module("plugin_model")
    yield module
    del TANGENTIALS[module.NAME]
    sys.modules.pop("plugin_model", None)


def _exact_share_slide(scene, out):
    """Centre velocity and spin after a contact that slides throughout under s mu P+: the kick of -s mu J+, J+
    from the COR (the force never pulls at these scenes)."""
    impulse = scene.mass * scene.v_normal * (1.0 + out.cor)
    share = scene.slide_share * scene.mu * impulse
    return scene.v_tangent - share / scene.mass, share * scene.radius / scene.inertia


@pytest.mark.filterwarnings("ignore::sphereimpact.EnergyGainWarning")  # sliding on past rolling: the toy makes energy
def test_an_own_parameter_and_setting_reach_the_model_through_the_api(share_slide):
    scene = Scene(angle=30.0, tangential="share-slide", parameters={"slide_share": 0.5})
    assert scene.slide_share == 0.5 and scene.parameters == {"k": 6e4, "b": 10.5, "ramp": 100.0, "slide_share": 0.5}
    assert Scene(angle=30.0, tangential="share-slide", slide_share=0.5) == scene  # by name, as a built-in one
    out = simulate(scene)
    vc_t, omega = _exact_share_slide(scene, out)
    assert out.vc_t == pytest.approx(vc_t, rel=1e-9) and out.omega_f == pytest.approx(omega, rel=1e-9)
    assert scene.with_(slide_share=0.25).slide_share == 0.25
    assert simulate(scene.with_(slide_share=0.25)).omega_f == pytest.approx(0.5 * out.omega_f, rel=1e-9)
    assert "slide_share" not in scene.with_(tangential="rigid").parameters  # the rigid contact has none of it
    # the setting arrives: the trapezoid rule's spin error falls as the square of its steps
    errors = [abs(simulate(scene, SolverOptions(settings={"trapezoid_steps": n})).omega_f / out.omega_f - 1)
              for n in (16, 32, 64)]
    assert 3.5 < errors[0] / errors[1] < 4.5 and 3.5 < errors[1] / errors[2] < 4.5
    # a sweep reads the parameter as a column, row by row, and the setting as simulate does
    table = sweep(grid(incidence=[20.0, 45.0], speed=[1.0, 3.0], slide_share=[0.2, 0.9]).assign(
        tangential="share-slide"), settings={"trapezoid_steps": 16}, chapter_ball=True)
    assert list(table.columns[:len(table.columns)]).count("slide_share") == 1
    for row in table.to_dict("records"):
        one = simulate(Scene(incidence=row["incidence"], speed=row["speed"], tangential="share-slide",
                             parameters={"slide_share": row["slide_share"]}),
                       SolverOptions(rtol=1e-12, atol=1e-12, settings={"trapezoid_steps": 16}))
        assert row["omega_f"] == pytest.approx(one.omega_f, rel=1e-8) and row["vc_t"] == pytest.approx(one.vc_t, rel=1e-8)


@pytest.mark.parametrize("make, message", [
    (lambda: Scene(tangential="share-slide"), r"slide_share is required by tangential 'share-slide': fraction of"),
    (lambda: Scene(tangential="share-slide", parameters={"slide_share": 1.5}),
     r"slide_share must be a finite number in \(0, 1\]; got 1.5"),
    (lambda: Scene(parameters={"slide_share": 0.5}),
     "slide_share is not a parameter of model 'modified' or tangential 'rigid'; their own parameters: none"),
    (lambda: SolverOptions(settings={"trapezoid_steps": 1}), r"trapezoid_steps must be an integer in \[2, 1000000\]"),
    (lambda: SolverOptions(settings={"cells": 4}), "cells is not a setting of any tangential model"),
    (lambda: sweep(grid(angle=[30.0], slide_share=[0.5]), chapter_ball=True),
     r"slide_share is not a parameter of model 'modified' or tangential 'rigid' \(row 0\)"),
    (lambda: sweep(grid(angle=[30.0]).assign(tangential="share-slide"), chapter_ball=True),
     r"slide_share is required by tangential 'share-slide': .* \(row 0\)"),
])
def test_an_own_parameter_or_setting_out_of_place_is_refused(share_slide, make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_an_own_parameter_and_setting_reach_the_model_through_the_command_line(share_slide, tmp_path, capsys):
    """In the process (run) and as a user runs it (a new interpreter, ``--plugin`` importing the module)."""
    flags = ["--tangential", "share-slide", "--slide-share", "0.5", "--trapezoid-steps", "16"]
    api = simulate(Scene(angle=30.0, tangential="share-slide", parameters={"slide_share": 0.5}),
                   SolverOptions(settings={"trapezoid_steps": 16}))
    assert run(["simulate", "--plugin", "plugin_model", "--angle", "30", *flags, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["omega_f"] == api.omega_f
    env = os.environ | {"PYTHONPATH": os.pathsep.join([str(TESTS), os.environ.get("PYTHONPATH", "")])}
    cli = subprocess.run([sys.executable, "-m", "sphereimpact", "simulate", "--plugin", "plugin_model", "--angle",
                          "30", *flags, "--json"], capture_output=True, text=True, env=env)
    assert cli.returncode == 0, cli.stderr
    assert json.loads(cli.stdout)["omega_f"] == api.omega_f
    out = tmp_path / "share.csv"
    swept = subprocess.run([sys.executable, "-m", "sphereimpact", "sweep", "--chapter-ball", "--plugin", "plugin_model",
                            "--angle",
                            "20:40:20", "--tangential", "share-slide", "--slide-share", "0.25:0.5:0.25",
                            "--trapezoid-steps", "16", "--out", str(out)], capture_output=True, text=True, env=env)
    assert swept.returncode == 0, swept.stderr
    table = pd.read_csv(out)
    assert sorted(table["slide_share"]) == [0.25, 0.25, 0.5, 0.5]
    row = table[(table["angle"] == 40.0) & (table["slide_share"] == 0.5)].iloc[0]
    one = simulate(Scene(angle=40.0, tangential="share-slide", parameters={"slide_share": 0.5}),
                   SolverOptions(settings={"trapezoid_steps": 16}))
    assert row["omega_f"] == pytest.approx(one.omega_f, rel=1e-8)
    helped = subprocess.run([sys.executable, "-m", "sphereimpact", "simulate", "--plugin", "plugin_model", "--help"],
                            capture_output=True, text=True, env=env)
    assert "--slide-share" in helped.stdout and "--trapezoid-steps" in helped.stdout
    missing = subprocess.run([sys.executable, "-m", "sphereimpact", "simulate", "--plugin", "no_such_plugin"],
                             capture_output=True, text=True, env=env)
    assert missing.returncode == 2 and "plugin 'no_such_plugin' cannot be imported" in missing.stderr


@pytest.mark.pipeline
def test_an_own_parameter_and_setting_reach_the_model_through_the_pipeline(share_slide, tmp_path):
    """A study of one's own ball whose config names the plug-in, the model's parameter and its setting: the
    ball file records them, and its bounce and map jobs (other processes) give the API's numbers."""
    from conftest import project_copy, snakemake

    work = project_copy(tmp_path)
    config = tmp_path / "plug.yaml"
    config.write_text("study: plug\nplugins: [plugin_model]\nball: {mass: 0.145, diameter: 0.063}\n"
                      "contact: {model: kelvin-voigt, k: 60000.0, b: 10.5, tangential: share-slide,\n"
                      "          slide_share: 0.5, settings: {trapezoid_steps: 16}}\n"
                      "bounces: {oblique: {speed: 3.0, incidence: 30.0}}\n"
                      "ranges: {speeds: '1:3:1', map_speeds: '2:4:2', map_angles: '30:60:30'}\n")
    folder = "results/studies/plug"
    done = snakemake(work, f"{folder}/outcomes.csv", f"{folder}/maps.csv", configfiles=[str(config)], path=[TESTS])
    assert done.returncode == 0, done.stderr[-3000:]
    ball = json.loads((work / folder / "ball.json").read_text())
    assert ball["plugins"] == ["plugin_model"] and ball["settings"] == {"trapezoid_steps": 16}
    assert ball["contact"]["slide_share"] == 0.5  # by name, beside the built-in parameters
    options = SolverOptions(settings={"trapezoid_steps": 16})
    scene = Scene(model="kelvin-voigt", b=10.5, tangential="share-slide",  # gravity 0, the one default
                  parameters={"slide_share": 0.5})
    from sphereimpact.study.own_outputs import read_history

    bounce = read_history(work / folder / "outcomes.csv").iloc[0]
    assert bounce["omega_f"] == pytest.approx(simulate(scene.with_(incidence=30.0), options).omega_f, rel=1e-9)
    maps = pd.read_csv(work / folder / "maps.csv")
    row = maps[(maps["angle_to_surface"] == 30.0) & (maps["speed"] == 4.0)].iloc[0]
    assert row["omega_f"] == pytest.approx(simulate(scene.with_(angle_to_surface=30.0, speed=4.0), options).omega_f,
                                           rel=1e-7)


@pytest.mark.filterwarnings("ignore::sphereimpact.EnergyGainWarning")  # sliding on past rolling: the toy makes energy
def test_a_fit_frees_an_own_parameter_through_the_api_and_the_command_line(share_slide, tmp_path, capsys):
    """Bounces made with slide_share = 0.6 give it back from 0.3 within the range it declares for a fit, through fit()
    and `sphereimpact fit --plugin plugin_model --free slide_share`; a parameter declaring no range is moved in its
    logarithm when it allows only positive values, else anywhere."""
    from sphereimpact import Parameter
    from sphereimpact.fit import fit, read_measured
    from sphereimpact.fit.least_squares import fit_range, own_bounds
    from sphereimpact.impact.ball import Ball

    assert fit_range(Parameter("p", "-", "", "> 0", lambda x: x > 0)) == (0.0, math.inf, True)
    assert fit_range(Parameter("q", "-", "", "any", lambda x: x == x)) == (-math.inf, math.inf, False)

    rows = []
    for incidence in (20.0, 40.0, 60.0):
        out = simulate(Scene(incidence=incidence, tangential="share-slide", parameters={"slide_share": 0.6}))
        rows.append({"speed": 3.0, "incidence": incidence, "vc_t": out.vc_t, "omega_f": out.omega_f})
    path = tmp_path / "bounces.csv"
    pd.DataFrame(rows).to_csv(path, index=False)
    ball = Ball(Scene(tangential="share-slide", parameters={"slide_share": 0.3}), plugins=("plugin_model",))
    assert own_bounds(ball) == {"slide_share": (1e-3, 1.0, False)}
    result = fit(read_measured(path), ball, ["slide_share"], chapter_ball=True)
    assert result.parameters["slide_share"].value == pytest.approx(0.6, rel=1e-7)
    assert result.ball.scene.slide_share == pytest.approx(0.6, rel=1e-7)
    chapter = ["--mass", "0.145", "--diameter", "0.063", "--k", "60000", "--b", "10.5"]  # the ball of Scene()
    assert run(["fit", str(path), "--plugin", "plugin_model", "--tangential", "share-slide", "--slide-share", "0.3",
                "--free", "slide_share", *chapter, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["parameters"]["slide_share"]["value"] == pytest.approx(0.6, rel=1e-7)
    assert run(["fit", str(path), "--free", "slide_share", *chapter]) == 2
    assert "'slide_share' cannot be fitted" in capsys.readouterr().err


@pytest.mark.filterwarnings("ignore::sphereimpact.EnergyGainWarning")
def test_a_model_that_does_not_declare_itself_scale_free_is_solved_scene_by_scene(share_slide):
    """The similar-scenes path takes only models that declare ``scale_free``: the plug-in's scenes, alike but for
    their speed, each go to simulate; a built-in compliant model's share one solve."""
    table = grid(incidence=[30.0], speed=[1.0, 2.0, 4.0])
    plugin = sweep(table.assign(tangential="share-slide", slide_share=0.5), chapter_ball=True)
    assert set(plugin["path"]) == {"single"}
    builtin = sweep(table.assign(model="hertz", modulus=1e8, tangential="mindlin", kappa=0.8), chapter_ball=True)
    assert set(builtin["path"]) == {"similar"}
