"""Command line: ``sphereimpact simulate [...] --json``, a thin layer over :func:`sphereimpact.simulate`.

Bad input prints one line naming the parameter and its allowed range and exits
with status 2 (argparse's convention), never a traceback.
"""

from __future__ import annotations

import argparse
import json
import sys

from .events import ImpactError
from .forces import FORCE_MODELS
from .scene import METHODS, SEPARATION_CRITERIA, STANDARD_GRAVITY, Scene, SolverOptions
from .solve import MODELS, simulate

_D = Scene()
_O = SolverOptions()


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="sphereimpact",
        description="Impact of a rigid-body sphere on a rigid inclined flat (spring-damper contact, Coulomb friction).")
    sub = parser.add_subparsers(dest="command", required=True)
    sim = sub.add_parser(
        "simulate", help="simulate one impact and print its outputs",
        description="Simulate one impact and print its outputs (SI units). Defaults are the chapter's.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    add = sim.add_argument
    add("--angle", type=float, default=_D.angle, metavar="DEG",
        help="inclination of the flat to the horizontal [deg], in [0, 90)")
    add("--speed", type=float, default=_D.speed, metavar="M_S",
        help="vertical approach speed of the centre [m/s], > 0")
    add("--model", default=_D.model, metavar="NAME",
        help="normal force law: " + "; ".join(f"{k}: {m.doc}" for k, m in FORCE_MODELS.items()))
    add("--mu", type=float, default=_D.mu, help="kinetic friction coefficient [-], >= 0")
    add("--k", type=float, default=_D.k, help="contact stiffness [N/m], > 0")
    add("--b", type=float, default=_D.b, help="contact damping [N s/m], >= 0")
    add("--ramp", type=float, default=_D.ramp,
        help="constant c of the modified model's ramp 1 - exp(-c delta/R) [-], > 0")
    add("--mass", type=float, default=_D.mass, help="ball mass [kg], > 0")
    add("--diameter", type=float, default=_D.diameter, help="ball diameter [m], > 0")
    add("--inertia-factor", type=float, default=_D.inertia_factor,
        help="alpha in I = alpha m R^2 [-], in (0, 2/3]: 0.4 solid sphere, 2/3 thin shell")
    add("--separation", default=_D.separation, metavar="|".join(SEPARATION_CRITERIA),
        help="contact ends when the force P (first of P = 0 and delta = 0) or the penetration delta returns to 0")
    add("--gravity", type=float, nargs="?", const=STANDARD_GRAVITY, default=_D.gravity, metavar="G",
        help=f"gravitational acceleration [m/s^2], >= 0; the bare flag means {STANDARD_GRAVITY}")
    add("--method", default=_O.method, metavar="NAME",
        help="integrator: " + ", ".join(METHODS) + " ('closed' is the exact solution, kelvin-voigt only)")
    add("--rtol", type=float, default=_O.rtol, help="relative tolerance, in [1e-13, 1)")
    add("--atol", type=float, default=_O.atol,
        help="absolute tolerance on the dimensionless state (delta scaled by v_n/omega_n, rate by v_n), > 0")
    add("--body", choices=MODELS, default="reduced",
        help="reduced: normal ODE plus impulse algebra (exact, cheapest); planar: full rigid-body cross-check")
    add("--json", action="store_true", help="print one JSON object (the only output format)")

    swp = sub.add_parser(
        "sweep", help="simulate a grid of impacts and write one row per scene",
        description="Simulate every combination of the given values (START:STOP:STEP ranges, stop included, or "
                    "single numbers) and write one row per scene: its parameters and the outputs of "
                    "`simulate` (t_m, delta_m, t_f, vc_t, vc_n, ve_t, ve_n, omega_f, cor, regime), SI units.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    ranged = {"angle": ("deg", _D.angle), "speed": ("m/s", _D.speed), "mu": ("-", _D.mu), "k": ("N/m", _D.k),
              "b": ("N s/m", _D.b), "mass": ("kg", _D.mass), "diameter": ("m", _D.diameter),
              "inertia_factor": ("-", _D.inertia_factor), "ramp": ("-", _D.ramp), "gravity": ("m/s^2", _D.gravity)}
    for name, (unit, default) in ranged.items():
        swp.add_argument("--" + name.replace("_", "-"), default=repr(default), metavar="RANGE",
                         help=f"{name} [{unit}]: a value or START:STOP:STEP")
    swp.add_argument("--model", default=_D.model, help="force law: " + ", ".join(FORCE_MODELS))
    swp.add_argument("--separation", default=_D.separation, help="force or penetration")
    swp.add_argument("--target", type=float, default=1e-8, help="relative accuracy of every output, in [1e-12, 1e-3]")
    swp.add_argument("--chunk-size", type=int, default=100_000, help="scenes integrated at once (memory bound)")
    swp.add_argument("--out", required=True, metavar="FILE", help="output table: .csv or .parquet")
    return parser


def _progress(done: int, total: int) -> None:
    sys.stderr.write(f"\rsphereimpact sweep: {done}/{total} integrated scenes")
    if done == total:
        sys.stderr.write("\n")


def _sweep(args) -> None:
    from .sweep.engine import grid, parse_range, sweep
    from .sweep.io import write_table

    names = ("angle", "speed", "mu", "k", "b", "mass", "diameter", "inertia_factor", "ramp", "gravity")
    ranges = {}
    for name in names:
        try:
            ranges[name] = parse_range(getattr(args, name))
        except ValueError as err:
            raise ValueError(f"{name}: {err}") from None
    scenes = grid(**ranges).assign(model=args.model, separation=args.separation)
    big = len(scenes) >= 100_000 and sys.stderr.isatty()
    table = sweep(scenes, target=args.target, chunk_size=args.chunk_size, progress=_progress if big else None)
    write_table(table, args.out)


def run(argv=None) -> int:
    """Parse ``argv``, run the command; return the exit status."""
    parser = _parser()
    args = parser.parse_args(argv)
    if args.command == "sweep":
        try:
            _sweep(args)
        except (ValueError, ImpactError) as err:
            parser.exit(2, f"sphereimpact: error: {err}\n")
        return 0
    try:
        scene = Scene(mass=args.mass, diameter=args.diameter, inertia_factor=args.inertia_factor,
                      angle=args.angle, speed=args.speed, mu=args.mu, model=args.model, k=args.k, b=args.b,
                      ramp=args.ramp, gravity=args.gravity, separation=args.separation)
        options = SolverOptions(method=args.method, rtol=args.rtol, atol=args.atol)
        outcome = simulate(scene, options, model=args.body)
    except (ValueError, ImpactError) as err:
        parser.exit(2, f"sphereimpact: error: {err}\n")
    json.dump(outcome.to_dict(), sys.stdout, indent=2)
    sys.stdout.write("\n")
    return 0


def main() -> None:
    """Console-script entry point."""
    try:
        status = run()
        sys.stdout.flush()
    except BrokenPipeError:  # e.g. `sphereimpact simulate --json | head`
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        status = 0
    sys.exit(status)
