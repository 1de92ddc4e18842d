"""The compiled normal motion: each law's force kernel is its scalar formula to the bit, each series kernel its
series, and the compiled DOP853 (sphereimpact.integrators.dop853_kernel) gives the Python-float DOP853's answer to
the bit (that one takes scipy's steps: tests/test_dop853.py), the compiled Taylor method
(sphereimpact.integrators.taylor_kernel) the Python-float one's, on every built-in law, both separation criteria,
gravity and eq. 4.2's ramp band."""

from dataclasses import replace

import numpy as np
import pytest

from sphereimpact import ImpactError, Scene, SolverOptions, simulate
from sphereimpact.contact.laws import LAWS
from sphereimpact.contact.laws import kernels
from sphereimpact.contact.laws.base import Kernel
from sphereimpact.integrators import compiled as compiled_rule, runge_kutta
from sphereimpact.ode import dop853

@pytest.fixture(autouse=True)
def compiled_from_the_start(monkeypatch):
    """The compiled integrator from the first motion (a process loads it only once it has integrated much)."""
    monkeypatch.setattr(compiled_rule, "COMPILE_AFTER", 0)


SCENES = {
    "kelvin-voigt": Scene(model="kelvin-voigt", incidence=60.0),
    "modified": Scene(incidence=60.0, spin=-40.0),
    "modified-band": Scene(b=500.0, incidence=30.0),  # zeta 2.6: restitution restarts in the ramp band
    "linear-hunt-crossley": Scene(model="linear-hunt-crossley", chi=0.2, incidence=45.0, gravity=9.81),
    "hertz": Scene(model="hertz", modulus=1e8, incidence=30.0),
    "hunt-crossley": Scene(model="hunt-crossley", modulus=1e7, chi=0.1, incidence=50.0, gravity=9.81),
    "hunt-crossley-n1.3-penetration": Scene(model="hunt-crossley", modulus=1e7, chi=0.1, exponent=1.3,
                                             separation="penetration"),
    "kelvin-voigt-overdamped": Scene(model="kelvin-voigt", b=200.0),
}
#: Over-damped scenes whose landing on t_f takes all four of its steps (Newton's corrections in between), at the
#: tolerance given (at 1e-4 their rebound is below what it resolves, and refused).
LANDED_FOUR_TIMES = {"kelvin-voigt-b1e4": (Scene(model="kelvin-voigt", b=1e4), 1e-10),
                     "modified-band-b1.2e4": (Scene(b=1.2e4), 1e-12)}


@pytest.mark.parametrize("name", sorted(LAWS))
def test_every_built_in_law_has_a_kernel_equal_to_its_scalar_formula_to_the_bit(name):
    law = LAWS[name]
    scene = next(s for s in SCENES.values() if s.model == name)
    assert law.kernel is not None
    force, params = law.kernel.load(), np.array(law.kernel.parameters(scene), dtype=float)
    rng = np.random.default_rng(7)
    deltas = np.concatenate([rng.uniform(-1e-3, 1e-2, 300), [0.0, -0.0, 1e-300, -1e-300]])
    rates = np.concatenate([rng.uniform(-5.0, 5.0, 300), [0.0, 1.0, -1.0, 3.0]])
    for delta, rate in zip(deltas.tolist(), rates.tolist()):  # inside and past separation (the continuation)
        assert force(delta, rate, params) == law.scalar(delta, rate, scene), (delta, rate)


def _python_floats(rhs, span, z0, rtol, atol, max_step, events, first_step):
    return dop853.solve(rhs, span, z0, rtol, atol, max_step=max_step, events=events, first_step=first_step)


def _in_python_floats(monkeypatch):
    """DOP853-scalar run by run in Python floats from now on: neither the compiled drive nor the compiled runs."""
    monkeypatch.setattr(runge_kutta, "_compiled_drive", lambda run, band: None)
    monkeypatch.setattr(runge_kutta, "_compiled", _python_floats)


@pytest.mark.parametrize("rtol", [1e-4, 1e-10, 1e-12])
@pytest.mark.parametrize("name", sorted(SCENES))
def test_the_compiled_normal_motion_is_the_python_floats_one_to_the_bit(name, rtol, monkeypatch):
    scene, options = SCENES[name], SolverOptions(method="DOP853-scalar", rtol=rtol, atol=rtol)
    compiled = simulate(scene, options).to_dict()
    _in_python_floats(monkeypatch)
    floats = simulate(scene, options).to_dict()
    compiled.pop("wall_time"), floats.pop("wall_time")
    assert compiled == floats


def test_the_compiled_run_reports_its_evaluations_and_its_steps_like_the_python_one(monkeypatch):
    """Every event, step end and dense value of one run, not only the outcome."""
    from sphereimpact.integrators.normal import IntegratedNormal

    scene, options = SCENES["modified-band"], SolverOptions(method="DOP853-scalar")
    compiled = IntegratedNormal(scene, options)
    _in_python_floats(monkeypatch)
    floats = IntegratedNormal(scene, options)
    assert compiled.stats == floats.stats and np.array_equal(compiled.grid, floats.grid)
    t = np.linspace(0.0, floats.t_f, 301)
    assert np.array_equal(np.array(compiled.state(t)), np.array(floats.state(t)))


def test_the_compiled_loop_locates_every_event_as_the_python_run_does(monkeypatch):
    """The compiled loop finds its events' roots itself (ode.roots.bracketed_root and the crossing rule, those very
    functions compiled, on the interpolant's arithmetic): every run's roots, terminal or not, and the states there
    are the Python-float run's to the bit."""
    from sphereimpact.integrators.normal import IntegratedNormal

    runs, compiled = [], runge_kutta._compiled

    def both(rhs, span, z0, rtol, atol, max_step, events, first_step):
        sol = compiled(rhs, span, z0, rtol, atol, max_step, events, first_step)
        runs.append((sol, _python_floats(rhs, span, z0, rtol, atol, max_step, events, first_step)))
        return sol

    monkeypatch.setattr(runge_kutta, "_compiled", both)
    monkeypatch.setattr(runge_kutta, "_compiled_drive", lambda run, band: None)  # run by run
    for name in ("modified-band", "hunt-crossley", "hunt-crossley-n1.3-penetration", "kelvin-voigt-overdamped"):
        IntegratedNormal(SCENES[name], SolverOptions(method="DOP853-scalar"))
    assert len(runs) >= 4 and sum(len(t) for sol, _ in runs for t in sol.t_events) >= 8
    for sol, floats in runs:
        assert [t.tolist() for t in sol.t_events] == [t.tolist() for t in floats.t_events]
        assert [y.tolist() for y in sol.y_events] == [y.tolist() for y in floats.y_events]
        assert np.array_equal(sol.t, floats.t) and np.array_equal(sol.y, floats.y)


def _drive_spy(monkeypatch):
    """The compiled drive's answers (None where it left the motion to the driver), as it gives them."""
    answers, drive = [], runge_kutta._compiled_drive
    monkeypatch.setattr(runge_kutta, "_compiled_drive", lambda run, band: answers.append(drive(run, band)) or
                        answers[-1])
    return answers


@pytest.mark.parametrize("scene, rtol", [pytest.param(SCENES[name], rtol, id=f"{name}-{rtol:g}") for name in sorted(SCENES)
                                         for rtol in (1e-4, 1e-10, 1e-12)]
                         + [pytest.param(*case, id=name) for name, case in LANDED_FOUR_TIMES.items()])
def test_the_compiled_drive_is_the_driver_run_by_run_to_the_bit(scene, rtol, monkeypatch):
    """The whole normal motion in one compiled call (the runs, the ramp band's restart, the landing and its Newton
    corrections) against the driver's runs of the compiled loop: the same dense output, step ends, grid, times
    and evaluations, every bit."""
    from sphereimpact.integrators.normal import IntegratedNormal

    options = SolverOptions(method="DOP853-scalar", rtol=rtol, atol=rtol)
    answers = _drive_spy(monkeypatch)
    driven, stepwise = IntegratedNormal(scene, options), IntegratedNormal(scene, options, drive=False)
    assert len(answers) == 1 and answers[0] is not None
    assert (driven.t_m, driven.t_f, driven.stats) == (stepwise.t_m, stepwise.t_f, stepwise.stats)
    assert np.array_equal(driven.grid, stepwise.grid)
    for field in ("ts", "f", "y_old", "t_old", "h"):
        assert np.array_equal(getattr(driven._sol, field), getattr(stepwise._sol, field)), field


@pytest.mark.parametrize("scene, options, match", [
    (Scene(model="kelvin-voigt", b=1e5, separation="penetration"), SolverOptions(method="DOP853-scalar"),
     r"no separation within 1e\+06 right-hand-side evaluations .*zeta = 536"),
    (Scene(model="hertz", modulus=1e8), SolverOptions(method="DOP853-scalar", max_step=1e-9),
     r"no separation within 1e\+06 right-hand-side evaluations"),
    (Scene(model="hunt-crossley", k=1e300, exponent=3.0, chi=1e300, speed=1e10), SolverOptions(),
     r"the contact force overflows \(exponent = 3, chi_v = inf"),
], ids=["over-damped-penetration-budget", "1ns-steps-budget", "force-overflow"])
def test_where_the_drive_stops_short_the_driver_says_why(scene, options, match, monkeypatch):
    """A spent budget (an over-damped contact under the penetration criterion, steps of 1 ns) and a force that
    leaves the finite numbers: the drive hands the motion back, and the driver refuses it as before."""
    answers = _drive_spy(monkeypatch)
    with pytest.raises(ImpactError, match=match):
        simulate(scene, options)
    assert answers == [None]


def test_a_force_that_leaves_the_finite_numbers_is_refused_by_name_at_once():
    """Hunt-Crossley with chi v_n = 1e310 (inf): the force is inf or NaN from the first stage.  The compiled run
    stops there and names it; the Python floats' run spent its 10^6 evaluations first and blamed the budget."""
    scene = Scene(model="hunt-crossley", k=1e300, exponent=3.0, chi=1e300, speed=1e10)
    with pytest.raises(ImpactError, match=r"the contact force overflows \(exponent = 3, chi_v = inf"):
        simulate(scene)


def test_a_kernel_is_named_by_its_module_or_given_itself_and_compiled_once():
    hertz = Kernel("hertz", lambda p: (p.k,)).load()
    assert hertz.py_func is kernels.hertz and Kernel(kernels.hertz, lambda p: ()).load() is hertz
    named = Kernel("sphereimpact.contact.laws.kernels:hunt_crossley", lambda p: ()).load()
    assert named.py_func is kernels.hunt_crossley and Kernel(named, lambda p: ()).load() is named


def test_a_kernel_without_the_scalar_formula_it_compiles_is_refused():
    with pytest.raises(ValueError, match="must declare the scalar formula it compiles"):
        replace(LAWS["hertz"], name="no-scalar", scalar=None)


def test_a_process_loads_the_compiled_integrator_once_it_has_spent_as_much_in_python_floats(monkeypatch):
    calls, drive = [], runge_kutta._compiled_drive

    def spy(*args):
        calls.append(1)
        return drive(*args)

    monkeypatch.setattr(compiled_rule, "COMPILE_AFTER", 10**9)
    monkeypatch.setattr(compiled_rule, "_spent_in_floats", 0)
    monkeypatch.setattr(compiled_rule, "_KERNEL_MODULE", "not loaded")
    monkeypatch.setattr(runge_kutta, "_compiled_drive", spy)
    scene, options = SCENES["hertz"], SolverOptions(method="DOP853-scalar")
    first = simulate(scene, options)
    assert not calls and compiled_rule._spent_in_floats == first.nfev  # 510 evaluations in two runs
    monkeypatch.setattr(compiled_rule, "COMPILE_AFTER", 3 * first.nfev)
    for _ in range(2):
        simulate(scene, options)
    assert not calls and compiled_rule._spent_in_floats == 3 * first.nfev
    last = simulate(scene, options)
    assert len(calls) == 1 and compiled_rule._spent_in_floats == 3 * first.nfev  # the whole motion, compiled
    assert last.to_dict() | {"wall_time": 0} == first.to_dict() | {"wall_time": 0}


def test_a_process_loads_the_compiled_stick_phase_once_its_python_stick_phases_have_spent_as_much(monkeypatch):
    """A compliant tangential contact's stick phases run in Python floats count their evaluations towards the
    rule for loading the compiled code, as the normal integrators' do (a job of many stick phases and few normal
    motions, the compliance map, never loaded it); once over, the stick phase runs compiled, to the same bits.  So
    do eq. 4.1's closed form's, whose weightless motion has a compiled form; with gravity it has none and counts
    none."""
    from sphereimpact.contact.tangential import stick_kernel

    calls = []
    real = stick_kernel.stick
    monkeypatch.setattr(stick_kernel, "stick", lambda *args: calls.append(1) or real(*args))
    monkeypatch.setattr(compiled_rule, "COMPILE_AFTER", 10**9)
    monkeypatch.setattr(compiled_rule, "_KERNEL_MODULE", "not loaded")
    monkeypatch.setattr(compiled_rule, "_TAYLOR_MODULE", "not loaded")
    scene = Scene(angle=30.0, tangential="linear", kappa=0.8)
    for counted in (scene.with_(tangential="rigid"), scene):
        monkeypatch.setattr(compiled_rule, "_spent_in_floats", 0)
        first = simulate(counted)
        spent = compiled_rule._spent_in_floats
    rigid = simulate(scene.with_(tangential="rigid"))
    assert not calls and spent > 2 * rigid.nfev > 0  # the stick phases' evaluations, beyond the normal motion's
    monkeypatch.setattr(compiled_rule, "COMPILE_AFTER", spent)
    again = simulate(scene)
    assert calls and again.to_dict() | {"wall_time": 0} == first.to_dict() | {"wall_time": 0}
    monkeypatch.setattr(compiled_rule, "COMPILE_AFTER", 10**9)
    for gravity, counts in ((0.0, True), (9.80665, False)):
        monkeypatch.setattr(compiled_rule, "_spent_in_floats", 0)
        simulate(scene.with_(model="kelvin-voigt", gravity=gravity))
        assert (compiled_rule._spent_in_floats > 0) == counts, gravity


def test_across_the_domain_the_compiled_answer_is_the_python_floats_one_to_the_bit(monkeypatch):
    """300 random scenes of the differential test's domain (every law with its parameters over decades, both
    criteria, gravity on level and sloped flats, spin), each by DOP853-scalar compiled and in Python floats:
    the same outcome, or the same refusal."""
    import warnings

    from sphereimpact.numerics.consistency import random_scenes
    from sphereimpact.sweep.engine import scene_of, scene_table

    frame = scene_table(random_scenes(300, seed=11, groups=0))
    options = SolverOptions(method="DOP853-scalar")

    def outcomes():
        answers = []
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for i in range(len(frame)):
                scene = scene_of(frame.iloc[i].to_dict()).with_(tangential="rigid")
                try:
                    answers.append({k: v for k, v in simulate(scene, options).to_dict().items() if k != "wall_time"})
                except ImpactError as err:
                    answers.append(str(err))
        return answers

    compiled = outcomes()
    _in_python_floats(monkeypatch)
    floats = outcomes()
    assert sum(isinstance(a, dict) for a in compiled) > 250
    assert compiled == floats


#: The built-in laws with a series: each has a series kernel.
SERIES_LAWS = ("kelvin-voigt", "linear-hunt-crossley", "modified")


@pytest.mark.parametrize("name", sorted(LAWS))
def test_a_built_in_law_has_a_series_kernel_exactly_where_it_has_a_series(name):
    law = LAWS[name]
    assert (law.series_kernel is not None) == (law.series is not None) == (name in SERIES_LAWS)


@pytest.mark.parametrize("name", SERIES_LAWS)
def test_every_series_kernel_is_its_law_series_to_the_bit(name):
    """At random states (inside and past separation, either rate), orders and gravity, with the family numbers
    over decades."""
    law = LAWS[name]
    kernel = law.series_kernel.load(series=True)
    rng = np.random.default_rng(3)
    for _ in range(500):
        x, y, order = rng.uniform(-0.1, 1.5), rng.uniform(-1.2, 1.2), int(rng.integers(8, 25))
        gamma = 0.0 if rng.uniform() < 0.5 else rng.uniform(-0.05, 0.05)
        numbers = {"zeta": 10 ** rng.uniform(-3, 1), "lam": 10 ** rng.uniform(0, 3), "chi_v": 10 ** rng.uniform(-3, 0.5)}
        scene = SCENES[name]
        numbers = {key: numbers[key] for key in scene.family}
        xs, ys = np.empty(order + 1), np.empty(order + 1)
        kernel(x, y, np.array(list(numbers.values())), gamma, order, xs, ys)
        python_xs, python_ys = law.series(x, y, numbers, gamma, order)
        np.testing.assert_array_equal(xs, python_xs)  # to the bit (NaN where both overflowed)
        np.testing.assert_array_equal(ys, python_ys)


def _in_python_floats(monkeypatch):
    """This process integrates in Python floats from now on (as one that has integrated little)."""
    monkeypatch.setattr(compiled_rule, "COMPILE_AFTER", 10**12)
    monkeypatch.setattr(compiled_rule, "_KERNEL_MODULE", "not loaded")


def _counting_compiled_taylor(monkeypatch) -> list:
    """The compiled Taylor loop's runs from now on, one entry each (so a test sees which path answered)."""
    from sphereimpact.integrators import taylor_kernel

    runs, solved = [], taylor_kernel.solved
    monkeypatch.setattr(taylor_kernel, "solved", lambda *args: runs.append(1) or solved(*args))
    return runs


@pytest.mark.parametrize("rtol", [1e-4, 1e-10, 1e-12])
@pytest.mark.parametrize("name", [name for name in sorted(SCENES) if SCENES[name].law.series_kernel is not None])
def test_the_compiled_taylor_method_is_the_python_floats_one_to_the_bit(name, rtol, monkeypatch):
    scene, options = SCENES[name], SolverOptions(method="taylor", rtol=rtol, atol=rtol)
    runs = _counting_compiled_taylor(monkeypatch)
    compiled = simulate(scene, options).to_dict()
    assert len(runs) == 1
    _in_python_floats(monkeypatch)
    floats = simulate(scene, options).to_dict()
    assert len(runs) == 1  # the second in Python floats
    compiled.pop("wall_time"), floats.pop("wall_time")
    assert compiled == floats


def test_across_the_domain_the_compiled_taylor_answer_is_the_python_floats_one_to_the_bit(monkeypatch):
    """400 random scenes of the differential test's domain with a series (eq. 4.1, eq. 4.2 with its ramp over
    decades, linear Hunt-Crossley; both criteria, gravity on level and sloped flats, spin), each by the Taylor method
    compiled and in Python floats at two tolerances: the same outcome, or the same refusal."""
    import warnings

    from sphereimpact.numerics.consistency import random_scenes
    from sphereimpact.sweep.engine import scene_of, scene_table

    frame = scene_table(random_scenes(800, seed=12, groups=0))
    frame = frame[frame["model"].isin(SERIES_LAWS)].iloc[:400]

    def outcomes():
        answers = []
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for row in frame.to_dict("records"):
                scene = scene_of(row).with_(tangential="rigid")
                for rtol in (1e-8, 1e-12):
                    try:
                        outcome = simulate(scene, SolverOptions(method="taylor", rtol=rtol, atol=rtol))
                        answers.append({k: v for k, v in outcome.to_dict().items() if k != "wall_time"})
                    except ImpactError as err:
                        answers.append(f"{type(err).__name__}: {err}")
        return answers

    runs = _counting_compiled_taylor(monkeypatch)
    compiled = outcomes()
    compiled_runs = len(runs)
    _in_python_floats(monkeypatch)
    floats = outcomes()
    assert compiled_runs >= 700 and len(runs) == compiled_runs  # the first pass compiled, the second in floats
    assert len(frame) == 400 and sum(isinstance(a, dict) for a in compiled) > 700
    assert compiled == floats


def test_a_process_counts_its_taylor_steps_in_python_floats_toward_loading_the_compiled_method(monkeypatch):
    _in_python_floats(monkeypatch)
    monkeypatch.setattr(compiled_rule, "_spent_in_floats", 0)
    first = simulate(SCENES["modified"], SolverOptions(method="taylor"))
    assert compiled_rule._spent_in_floats == first.nfev > 0  # its steps times its order
    second = simulate(SCENES["hertz"], SolverOptions(method="DOP853-scalar"))
    assert compiled_rule._spent_in_floats == first.nfev + second.nfev  # and DOP853's evaluations alike


def test_a_series_kernel_that_is_not_the_series_is_refused_by_name(monkeypatch):
    from dataclasses import replace

    wrong = replace(LAWS["modified"], name="modified-wrong-series",
                    series_kernel=Kernel("kelvin_voigt_series", lambda p: (p.family["zeta"],)))
    monkeypatch.setitem(LAWS, wrong.name, wrong)
    with pytest.raises(ValueError, match="law 'modified-wrong-series': its series kernel's coefficients differ"):
        simulate(Scene(model=wrong.name, incidence=30.0), SolverOptions(method="taylor"))


def test_compiling_the_kernels_by_group_refuses_a_group_it_does_not_have():
    with pytest.raises(ValueError, match="group must be one of dop853, taylor, contact, or None for every kernel; got 'numpy'"):
        compiled_rule.compile_all("numpy")


def test_the_kernel_sources_are_every_module_the_kernels_compile_from():
    """:data:`sphereimpact.kernel_cache.KERNELS` are the package's modules that cache kernels on disk, and ``SOURCES``
    holds every package module they import, directly or not (their parent packages' ``__init__`` aside): a function
    or constant a kernel compiles comes from one of them."""
    import re
    from pathlib import Path

    from sphereimpact import kernel_cache
    from sphereimpact.study import workflow

    root = kernel_cache.ROOT
    cached = {str(p.relative_to(root)) for p in root.rglob("*.py")
              if re.search(r"""["']cache["']: True|cache=True""", p.read_text(encoding="utf-8"))}
    assert cached == set(kernel_cache.KERNELS)
    seen, todo = set(), [root / name for name in kernel_cache.KERNELS]
    while todo:
        path = todo.pop()
        if path in seen:
            continue
        seen.add(path)
        for name in workflow._imports(path):
            if name.startswith("sphereimpact."):
                found = workflow._module_file(name) or workflow._module_file(name.rsplit(".", 1)[0])
                if found is not None and found.name != "__init__.py":
                    todo.append(Path(found))
    assert {str(p.relative_to(root)) for p in seen} - {"kernel_cache.py"} <= set(kernel_cache.SOURCES)  # its own


def test_an_edited_source_recompiles_the_kernels_that_compile_it(tmp_path):
    """numba recompiles a cached kernel when its own module's text changes, not when a function it compiles from
    another module does; the refresh deletes the kernel modules' caches when any source changed.  A kernel compiling
    ``dep.f`` is cached in one process; ``dep.py`` is edited; a second process gets the new ``f`` (numba alone, the
    old one: the refresh's line removed, this test fails)."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    from sphereimpact import kernel_cache

    (tmp_path / "dep.py").write_text("def f(x):\n    return x + 1.0\n")
    (tmp_path / "ker.py").write_text(  # the refresh's module alone, not the package (a second per process)
        "import importlib.util\n"
        "from pathlib import Path\n"
        f"spec = importlib.util.spec_from_file_location('kernel_cache', {str(Path(kernel_cache.__file__))!r})\n"
        "cache = importlib.util.module_from_spec(spec)\n"
        "spec.loader.exec_module(cache)\n"
        "here = Path(__file__).parent\n"
        "cache.refresh(here, here / 'record' / 'k.stamps', ('ker.py',), ('ker.py', 'dep.py'))\n"
        "import numba\n"
        "from dep import f\n"
        "_f = numba.njit(cache=True)(f)\n\n\n"
        "@numba.njit(cache=True)\n"
        "def k(x):\n"
        "    return _f(x)\n")
    env = os.environ | {"PYTHONPATH": str(tmp_path)}
    env.pop("NUMBA_CACHE_DIR", None)

    def run():
        return subprocess.run([sys.executable, "-c", "from ker import k; print(k(1.0), k.stats.cache_hits.total())"],
                              cwd=tmp_path, env=env, capture_output=True, text=True, check=True).stdout.split()

    assert run() == ["2.0", "0"] and list((tmp_path / "__pycache__").glob("ker.k-*.nbi"))
    (tmp_path / "dep.py").write_text("def f(x):\n    return x + 2.0\n")
    assert run() == ["3.0", "0"]  # (unchanged sources keep the cache: the test below)


def test_the_refresh_deletes_the_kernels_caches_only_when_a_source_changed(tmp_path):
    """No record (a fresh folder) or a changed source: every kernel module's cached kernels (its index and machine
    code files, in numba's folder for it) are deleted and the sources recorded; unchanged: nothing is."""
    from sphereimpact.kernel_cache import cache_folder, refresh

    for name in ("a.py", "b.py", "c.py"):
        (tmp_path / name).write_text("x = 1\n")
    record, kernels, sources = tmp_path / "record" / "k.stamps", ("a.py", "b.py"), ("a.py", "b.py", "c.py")
    folder = cache_folder(tmp_path / "a.py")

    def plant():
        for name in ("a.k-3.py311.nbi", "a.k-3.py311.1.nbc", "b.g-9.py311.nbi", "c.h-1.py311.nbi"):
            (folder / name).write_text("")

    plant()
    assert refresh(tmp_path, record, kernels, sources) == 3 and record.is_file()
    assert sorted(p.name for p in folder.iterdir()) == ["c.h-1.py311.nbi"]  # not a kernel module's
    plant()
    assert refresh(tmp_path, record, kernels, sources) == 0 and len(list(folder.iterdir())) == 4
    (tmp_path / "c.py").write_text("x = 2\n")
    assert refresh(tmp_path, record, kernels, sources) == 3
    assert refresh(tmp_path, record, kernels, sources) == 0


def test_no_two_kernel_modules_compile_a_helper_into_the_same_cache_files():
    """numba names a kernel's cache files after its Python function's module and qualified name: two modules compiling
    the same helper (ode.dense.grown, in three) into one index raced when their groups compiled at once on a fresh
    clone, and its compile failed.  Every cached, not inlined, dispatcher of the package's kernel modules has cache
    files of its own (kernel_cache.owned), or is one and the same dispatcher imported."""
    import importlib

    from numba.core.caching import NullCache
    from numba.core.registry import CPUDispatcher

    from sphereimpact.kernel_cache import KERNELS

    owners: dict = {}
    for path in KERNELS:
        module = importlib.import_module("sphereimpact." + path.removesuffix(".py").replace("/", "."))
        for value in vars(module).values():
            if not isinstance(value, CPUDispatcher) or isinstance(value._cache, NullCache):
                continue  # not numba's: or not cached on disk
            if value.targetoptions.get("inline", "never") != "never":
                continue  # inlined into its callers: compiled and cached with them
            key = (value.py_func.__module__, value.py_func.__qualname__)
            assert owners.setdefault(key, value) is value, f"{key} is compiled by two modules into one cache"
    assert ("sphereimpact.ode.dense", "grown_stick_kernel") in owners


def test_each_compile_group_imports_kernel_modules_of_its_own():
    """The groups tests/conftest.py compiles in parallel processes on a fresh clone share no kernel module but the laws'
    (whose kernels each group loads its own of): a module imported by two groups compiles its kernels declared with
    a signature in both at once, into one cache (the microslip sampler's imports of normal_kernel did, from every
    group, until the march's compile moved into the contact group)."""
    import subprocess
    import sys

    from sphereimpact.integrators.compiled import GROUPS
    from sphereimpact.kernel_cache import KERNELS

    names = ["sphereimpact." + path.removesuffix(".py").replace("/", ".") for path in KERNELS]
    script = ("import sys; from sphereimpact.integrators.compiled import compile_all; compile_all({group!r}); "
              "print(' '.join(name for name in {names!r} if name in sys.modules))")
    imported = {group: set(subprocess.run([sys.executable, "-c", script.format(group=group, names=names)],
                                          capture_output=True, text=True, check=True).stdout.split())
                for group in GROUPS}
    shared = {"sphereimpact.contact.laws.kernels"}
    for i, first in enumerate(GROUPS):
        assert "sphereimpact.contact.laws.kernels" in imported[first]
        for second in GROUPS[i + 1:]:
            assert imported[first] & imported[second] == shared, (first, second)
    assert set().union(*imported.values()) == set(names)
