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
    return parser


def run(argv=None) -> int:
    """Parse ``argv``, simulate, print JSON; return the exit status."""
    parser = _parser()
    args = parser.parse_args(argv)
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
