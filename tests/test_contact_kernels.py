"""The contact layer's compiled kernels against the Python-float code they replace, to the bit, on random scenes of the
consistency test's domain: the normal force's extremes (:mod:`sphereimpact.contact.normal_kernel`) on every law, and
the compliant springs' stick phase (:mod:`sphereimpact.contact.tangential.stick_kernel`: the same steps, events and
dense output; every spring, with and without the dashpot) and the rigid contact's grip
(:mod:`sphereimpact.contact.tangential.rigid_kernel`), on Taylor and DOP853 normal motions and the closed form's."""

import warnings

import numpy as np
import pytest

from sphereimpact import SolverOptions, simulate
from sphereimpact.errors import BeyondRadiusWarning, EnergyGainWarning
from sphereimpact.integrators import closed_form as closed_module, normal as normal_module
from sphereimpact.integrators.compiled import load_compiled
from sphereimpact.numerics.consistency import random_scenes
from sphereimpact.sweep.scenes import scene_of, scene_table


def _scenes(n: int, seed: int, tangentials=("linear", "mindlin", "mindlin-displacement"), models=None,
            draws: int | None = None) -> list:
    """The first ``n`` scenes with one of ``tangentials`` (and of ``models``, if given) among the consistency test's
    ``draws`` (40 n) random scenes of ``seed``."""
    scenes = []
    for row in scene_table(random_scenes(draws or 40 * n, seed=seed)).to_dict("records"):
        if row["tangential"] in tangentials and (models is None or row["model"] in models):
            scenes.append(scene_of(row))
        if len(scenes) == n:
            return scenes
    raise AssertionError("too few compliant scenes drawn")


def _in_python_floats(monkeypatch) -> None:
    """Normal motions without a compiled form (``kernel_state`` None: the dense outputs' and the closed form's), so
    that the contact's kernels compute in Python floats, as in a process that has not loaded the compiled code."""
    for motion in (normal_module._DimensionlessNormal, closed_module.ClosedFormNormal):
        monkeypatch.setattr(motion, "kernel_state", lambda self: None)


def _solve(scenes, options, compiled: bool, monkeypatch) -> list:
    """Each scene simulated, its stick phases compiled or (``compiled`` False) in Python floats; refused ones None."""
    load_compiled()  # the normal motions expose their compiled form only in a process that integrates compiled
    if not compiled:
        _in_python_floats(monkeypatch)
    outcomes = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BeyondRadiusWarning)
        warnings.simplefilter("ignore", EnergyGainWarning)
        for scene in scenes:
            try:
                outcomes.append(simulate(scene, options))
            except Exception as err:  # noqa: BLE001  (compared below: both runs refuse alike)
                outcomes.append(f"{type(err).__name__}: {err}")
    monkeypatch.undo()
    return outcomes


def _same_outputs(a, b) -> bool:
    """Every output of two outcomes equal to the bit (NaN equal to NaN), but the wall time."""
    return {k: v for k, v in a.to_dict().items() if k != "wall_time"} == pytest.approx(
        {k: v for k, v in b.to_dict().items() if k != "wall_time"}, rel=0, abs=0, nan_ok=True)


def _solved_pairs(scenes, method: str, monkeypatch) -> list:
    """(scene, Python outcome, compiled outcome) of each scene both runs solve at ``method``, every output equal to
    the bit; a scene refused must be refused alike by both."""
    options = SolverOptions(method=method)
    python, compiled = (_solve(scenes, options, flag, monkeypatch) for flag in (False, True))
    pairs = []
    for scene, a, b in zip(scenes, python, compiled):
        if isinstance(a, str):
            assert a == b, scene
            continue
        assert _same_outputs(a, b), scene
        pairs.append((scene, a, b))
    return pairs


@pytest.mark.parametrize("method", ["auto", "DOP853-scalar"])
def test_the_compiled_stick_phase_is_the_python_run_to_the_bit(method, monkeypatch):
    sticks = kinds = closed = 0
    # the consistency test's compliant scenes, and eq. 4.1's law (its motion the closed form's under ``auto``)
    scenes = _scenes(70, seed=11) + _scenes(20, seed=18, tangentials=("linear",), models=("kelvin-voigt",),
                                                 draws=4000)
    for scene, a, b in _solved_pairs(scenes, method, monkeypatch):
        if a.motion.tangential is None:
            continue
        for pa, pb in zip(a.motion.tangential.phases, b.motion.tangential.phases, strict=True):
            assert (pa.mode, pa.t0, pa.t1, pa.v0, pa.omega0, pa.sigma) == (pb.mode, pb.t0, pb.t1, pb.v0, pb.omega0,
                                                                         pb.sigma)
            if pa.solution is not None:
                sticks += 1
                assert np.array_equal(pa.solution.ts, pb.solution.ts)
                assert np.array_equal(pa.solution.f, pb.solution.f)
        kinds += b.motion.normal.kernel_state() is not None
        closed += b.method == "closed" and b.motion.normal.kernel_state() is not None
    assert sticks >= 30 and kinds >= 30  # the compiled path was taken, on many stick phases
    assert closed >= (15 if method == "auto" else 0), closed  # and on the closed form's motions


@pytest.mark.parametrize("method", ["auto", "DOP853-scalar"])
def test_the_compiled_force_extremes_are_the_python_ones_to_the_bit(method, monkeypatch):
    laws, taken = set(), 0
    for scene, a, b in _solved_pairs(_scenes(150, seed=12, tangentials=("rigid", "microslip")), method, monkeypatch):
        assert (a.force_min, a.force_max) == (b.force_min, b.force_max), scene
        laws.add(scene.model)
        taken += b.motion.normal.kernel_state() is not None
    assert taken >= 100 and len(laws) >= 4  # the compiled path, on most laws


@pytest.mark.parametrize("method", ["auto", "DOP853-scalar"])
def test_the_compiled_states_at_many_instants_are_the_dense_outputs_to_the_bit(method, monkeypatch):
    """``normal_kernel.normal_states`` (a normal motion read at many instants: a microslip march's steps, a history)
    against the dense output's vectorised evaluation, on random scenes of every law (Taylor series under ``auto``
    where the law has one, the closed form where it has one, DOP853's interpolants otherwise), at uniform instants,
    the grid and past t_f."""
    taken, kinds = 0, set()
    for scene, _, b in _solved_pairs(_scenes(60, seed=14, tangentials=("rigid", "microslip")), method, monkeypatch):
        normal = b.motion.normal
        state = normal.kernel_state()
        if state is None:
            continue
        t = np.concatenate([np.linspace(0.0, 1.2 * normal.t_f, 1001), normal.grid])
        compiled = normal.state(t)
        _in_python_floats(monkeypatch)
        python = normal.state(t)
        monkeypatch.undo()
        assert np.array_equal(compiled[0], python[0]) and np.array_equal(compiled[1], python[1]), scene
        taken, kinds = taken + 1, kinds | {state.kind}
    assert taken >= 40 and len(kinds) == (3 if method == "auto" else 1), (taken, kinds)


@pytest.mark.parametrize("method", ["auto", "DOP853-scalar"])
def test_the_compiled_grip_is_the_python_search_to_the_bit(method, monkeypatch):
    """The rigid contact's grip (:mod:`sphereimpact.contact.tangential.rigid_kernel`) and, under the penetration
    criterion, the force's sign changes that bound its pushes (``normal_kernel.force_roots``) on random rigid scenes
    (spin, gravity along the flat, every law): the same pushes, phases, t_roll and outputs as the Python search."""
    grips = pulls = 0
    for scene, a, b in _solved_pairs(_scenes(200, seed=13, tangentials=("rigid",)), method, monkeypatch):
        if a.motion.tangential is None:
            continue
        assert [(p.mode, p.t0, p.t1, p.v0, p.omega0, p.x0) for p in a.motion.tangential.phases] == [
            (p.mode, p.t0, p.t1, p.v0, p.omega0, p.x0) for p in b.motion.tangential.phases], scene
        assert a.motion.tangential.jp.intervals == b.motion.tangential.jp.intervals, scene
        grips += b.t_roll is not None and b.t_roll > 0 and b.motion.tangential.jp.kernel_terms() is not None
        pulls += not scene.separation.on_force and b.motion.normal.kernel_state() is not None
    assert grips >= 40 and pulls >= 20, (grips, pulls)  # the compiled searches were taken, many times


@pytest.mark.parametrize("method", ["auto", "DOP853-scalar"])
def test_the_compiled_grip_instants_are_the_python_ones_to_the_bit(method, monkeypatch):
    """The sweep's grip instants (``PositiveImpulse.instants``, with J+ on the grid and the function of its Newton
    iteration compiled: :mod:`sphereimpact.contact.tangential.rigid_kernel`'s ``positive_impulses`` and
    ``impulse_gaps``) on the normal motions of random rigid scenes, at random levels, 0, J+(t_f), beyond it and a
    tiny one: the Python search's instants to the bit."""
    from sphereimpact.contact.tangential import PositiveImpulse
    from sphereimpact.impact.solve import shared_normal_motion

    load_compiled()
    rng = np.random.default_rng(5)
    served = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BeyondRadiusWarning)
        for scene in _scenes(150, seed=17, tangentials=("rigid",)):
            try:
                normal = shared_normal_motion(scene, SolverOptions(method=method))
            except Exception:  # noqa: BLE001  (a scene simulate refuses has no motion to search)
                continue
            impulse = PositiveImpulse(normal)
            top = float(impulse(normal.t_f))
            levels = np.concatenate([rng.uniform(0.0, top, 6), [0.0, top, 1.1 * top, 1e-9 * top]])
            served += impulse.kernel_terms() is not None
            compiled = impulse.instants(levels)
            _in_python_floats(monkeypatch)
            python = PositiveImpulse(normal).instants(levels)
            monkeypatch.undo()
            assert compiled.tolist() == python.tolist(), scene
    assert served >= 100, served  # the compiled search was taken, many times
