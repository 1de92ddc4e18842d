"""Command line: ``sphereimpact simulate`` and ``sphereimpact sweep``, a thin layer over the API.

Every input is answered with a result or one line: ``sphereimpact: error: <what> <allowed range>``,
exit status 2 for bad input (argparse's convention) and 1 for a failure that a change of input does not
fix (a full disk, say) or a failing verdict (``benchmark compare``).  Never a traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import warnings
from dataclasses import replace

import numpy as np

from . import __version__, plugins
from .impact.ball import (APPROACH, Ball, Measurement, ball_columns, ball_scene, calibrated_ball, chapter_parts,
                          check_described, load_ball, save_ball, undescribed)
from .errors import BeyondRadiusWarning, ImpactError, SphereImpactWarning
from .integrators import method_names
from .contact.laws import LAWS, PARAMETER_NAMES, Relation
from .impact.outcome import OUTPUT_KEYS, OUTPUT_UNITS
from .impact.pair import PARTNER_FIELDS, PARTNER_UNITS
from .parsing import parse_number, range_count
from .impact.inputs import PATH_RULES, RULES, SEPARATION_CRITERIA, check_columns, magnitude_problem
from .impact.scene import ATOL_RANGE, RTOL_RANGE, STANDARD_GRAVITY, Scene, SolverOptions
from .impact.solve import BODIES, simulate
from .contact.declared import own_parameters, settings as declared_settings
from .contact.materials import material_fields
from .contact.tangential import STIFFNESS, TANGENTIAL_PARAMETERS, TANGENTIALS
from .fit import FIT_FILES, FREE, MEASURABLE, PLAN_FILES

_D = Scene()
_O = SolverOptions()

#: Output units for the readable (non-JSON) output of ``simulate``.
UNITS = {key: unit for key, unit in (OUTPUT_UNITS | PARTNER_UNITS).items()
         if unit and key not in ("switches", "rtol", "atol", "nfev")}


def _tangential_help() -> dict:
    """Help for ``--tangential`` and its stiffness flags, built from the registered tangential models."""
    texts = {"tangential": "tangential contact: " + "; ".join(f"{name} ({model.doc})"
                                                               for name, model in TANGENTIALS.items())}
    for p in STIFFNESS:
        users = ", ".join(TANGENTIALS.taking(p.name))
        texts[p.name] = f"{p.doc} [{p.unit}], {p.allowed.removeprefix('a finite number ')}: {users}"
    return texts


#: Sweep parameters that take ranges, with their units (the law's parameters too, see _law_flags).
RANGED = {"angle": "deg", "speed": "m/s", "mu": "-", "mass": "kg", "diameter": "m", "inertia_factor": "-",
          "gravity": "m/s^2", "spin": "rad/s"}
#: Help for --plugin.
PLUGIN_HELP = ("import MODULE first (repeatable): a plug-in that registers laws, tangential models or integrators, "
               "whose names and parameters the other options then take")
#: How the outputs give a direction, in both conventions the inputs accept (the help's last paragraph).
OUTPUT_ANGLES = ("Rebound directions: rebound_angle is the centre's, from the surface normal [deg], in (-90, 90), "
                 "negative when the ball kicks back against its incoming tangential motion (rebound_angle_contact: "
                 "the contact point's); rebound_angle_to_surface = 90 - rebound_angle is the same direction as its "
                 "angle to the surface, the convention of --angle-to-surface, in (0, 180), above 90 when the ball "
                 "kicks back. energy_gained flags a tangential model that made energy (work_t > 0).")
#: Seconds after which a sweep on a terminal shows its progress.
PROGRESS_AFTER = 2.0
#: Help for the approach and the incoming spin, shared by simulate and sweep.
APPROACH_HELP = {
    "angle": "inclination of the flat to the horizontal [deg], in [0, 90), the ball arriving vertically (the "
             "chapter's description)",
    "speed": "approach speed of the centre along its path [m/s], > 0 (vertical unless --incidence or "
             "--angle-to-surface is given)",
    "spin": "incoming spin [rad/s]: positive topspin, negative backspin (relative to the direction of travel)",
    "incidence": "the ball's path instead of the flat's tilt: incidence from the flat's normal [deg], in [0, 90), "
                 "on a level flat",
    "angle_to_surface": "the ball's path as its angle to the surface [deg], in (0, 90] (90 - incidence), on a "
                        "level flat",
}
#: Help for --chapter-ball, shared by simulate, fit and sweep.
CHAPTER_BALL_HELP = ("the chapter's ball where the options are silent: mass 0.145 kg, diameter 0.063 m and, for its "
                     "linear laws, k 60000 N/m and b 10.5 N s/m; for sweep, the chapter's 3 m/s too (simulate takes "
                     "them by default and says so; sweep and fit refuse a ball that is not described); with --ball, "
                     "the parts the file took from the chapter's ball")
#: Help for the partner sphere, shared by simulate, fit and sweep.
PARTNER_HELP = {
    "partner_mass": "strike a partner sphere at rest instead of the flat: its mass [kg], > 0 (with "
                    "--partner-diameter; the contact law's k, --modulus and --ramp are then the contact's, at the "
                    "Hertz radius R1 R2 / (R1 + R2); no gravity)",
    "partner_diameter": "the partner sphere's diameter [m], > 0",
    "partner_inertia_factor": "the partner's alpha in I = alpha m R^2 [-], in (0, 2/3] (default 0.4)",
    "partner_spin": "the partner's spin [rad/s] in the ball's rotational sense (both positive: the spheres rub at "
                    "the contact) (default 0)",
}


def _law_flags() -> dict:
    """Law parameter -> help text: what it is, its units and range per law, which laws use it, defaults.

    Built from the registered laws, so a new law's parameters are documented without touching the CLI.
    """
    texts = {}
    for name in PARAMETER_NAMES:
        users = [law for law in LAWS.values() if name in law.parameter_names]
        if not users:
            continue
        if name == "modulus":
            texts[name] = ("effective modulus E* [Pa], > 0, instead of k for "
                           + ", ".join(law.name for law in users) + ": k = (4/3) E* sqrt(R)")
            continue
        described = {}
        for law in users:
            p = law.parameter(name)
            default = "required" if p.default is None else f"default {p.default:g}"
            described.setdefault(f"{p.doc} [{p.unit}], {p.allowed.removeprefix('a finite number ')}", []).append(
                f"{law.name} ({default})")
        texts[name] = "; ".join(f"{what}: {', '.join(laws)}" for what, laws in described.items())
    return texts


def _setting_flags() -> dict:
    """Setting -> help text, for every numerical setting a registered tangential model declares."""
    return {name: f"{s.doc}, an integer in [{s.low}, {s.high}] (default: {s.default})"
            for name, s in declared_settings().items()}


def _own_flags() -> dict:
    """Own parameter -> help text, for every parameter a registered law or tangential model declares beyond the
    Scene's fields (:mod:`sphereimpact.contact.parameters`)."""
    texts = {}
    for name, p in own_parameters().items():
        users = [law.name for law in LAWS.values() if p in law.own_parameters]
        users += [model.name for model in TANGENTIALS.values() if p in model.own_parameters]
        default = "required" if p.default is None else f"default {p.default:g}"
        texts[name] = f"{p.doc} [{p.unit}], {p.allowed.removeprefix('a finite number ')}: {', '.join(users)} ({default})"
    return texts


def _settings(args) -> dict:
    """The settings given on the command line."""
    return {name: getattr(args, name) for name in declared_settings() if getattr(args, name) is not None}


class UsageError(Exception):
    """A bad command line (exit status 2)."""


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors, no abbreviated options, and negative numbers as values."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, allow_abbrev=False, **kwargs)

    def error(self, message):
        raise UsageError(f"{message} (see `{self.prog} --help`)")


class _Help(argparse.ArgumentDefaultsHelpFormatter):
    """Defaults in the help, except for required options and options without one."""

    def _get_help_string(self, action):
        if action.required or action.default in (None, argparse.SUPPRESS) or action.const is not None \
                or isinstance(action, argparse._StoreTrueAction):
            return action.help
        return super()._get_help_string(action)


def _number(text: str) -> float:
    try:
        return parse_number(text)
    except ValueError as err:
        raise argparse.ArgumentTypeError(str(err)) from None


def _material_pair(text: str) -> tuple[float, float]:
    """``E,NU`` as two numbers (Young's modulus [Pa], Poisson's ratio)."""
    parts = text.split(",")
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"give Young's modulus and Poisson's ratio as E,NU, e.g. 70e9,0.33; got {text!r}")
    return _number(parts[0]), _number(parts[1])


#: Help for the bodies' materials, shared by simulate, fit and sweep.
MATERIAL_HELP = {
    "ball_material": "the ball's Young's modulus [Pa] and Poisson's ratio, E,NU (a DEM deck's): they set the contact's "
                     "--modulus E* and, for a compliant tangential model, --kappa = 4 G*/E* (Johnson 1985)",
    "surface_material": "with --ball-material: the struck surface's E,NU, the flat's or the partner sphere's (default: "
                        "a rigid flat)",
}


def _scene_options(parser: argparse.ArgumentParser) -> None:
    """The options that describe a scene (the approach, the ball, its contact and surface, a ball file, the
    calibration from a measured COR): ``simulate``'s and ``fit``'s."""
    add = parser.add_argument
    add("--plugin", action="append", default=None, metavar="MODULE", help=PLUGIN_HELP)
    add("--angle", type=_number, default=_D.angle, metavar="DEG", help=APPROACH_HELP["angle"])
    add("--speed", type=_number, default=_D.speed, metavar="M_S", help=APPROACH_HELP["speed"])
    add("--incidence", type=_number, default=None, metavar="DEG", help=APPROACH_HELP["incidence"])
    add("--angle-to-surface", type=_number, default=None, metavar="DEG", help=APPROACH_HELP["angle_to_surface"])
    add("--spin", type=_number, default=_D.spin, metavar="RAD_S", help=APPROACH_HELP["spin"])
    add("--model", default=_D.model, metavar="NAME",
        help="normal force law: " + "; ".join(f"{k}: {m.doc}" for k, m in LAWS.items()))
    add("--mu", type=_number, default=_D.mu, help="kinetic friction coefficient [-], >= 0")
    for name, text in _law_flags().items():
        add("--" + name, type=_number, default=None, help=text + ". A parameter the law does not use is refused")
    add("--cor", type=_number, default=None, metavar="E",
        help="set the law's damping so that the normal COR is E, in (0, 1) (replaces its damping parameter)")
    add("--cor-relation", default=Relation.EXACT.value, metavar="|".join(Relation),
        help="how --cor sets the damping: exact (root find, to 1e-9) or a published relation of the law")
    add("--cor-speed", type=_number, default=None, metavar="M_S",
        help="normal impact speed at which --cor (and --contact-time) was measured [m/s] (default: this scene's "
             "normal speed); a scene far from it is an extrapolation, and a warning says so")
    add("--contact-time", type=_number, default=None, metavar="S",
        help="with --cor: fit the stiffness k too, so that the contact time t_f is S [s] (k and --modulus are then "
             "not given)")
    add("--ball", default=None, metavar="FILE",
        help="the ball, its contact and surface from a ball file (--save-ball, a study's ball.json); give only "
             "the approach, the surface (--mu, --gravity) and the solver's options")
    add("--chapter-ball", action="store_true", help=CHAPTER_BALL_HELP)
    tangential_help = _tangential_help()
    add("--tangential", choices=tuple(TANGENTIALS), default=_D.tangential, help=tangential_help["tangential"])
    for name in TANGENTIAL_PARAMETERS:
        add("--" + name.replace("_", "-"), type=_number, default=None, help=tangential_help[name])
    for name, text in _own_flags().items():
        add("--" + name.replace("_", "-"), type=_number, default=None, help=text)
    add("--mass", type=_number, default=_D.mass, help="ball mass [kg], > 0")
    add("--diameter", type=_number, default=_D.diameter, help="ball diameter [m], > 0")
    add("--inertia-factor", type=_number, default=_D.inertia_factor,
        help="alpha in I = alpha m R^2 [-], in (0, 2/3]: 0.4 solid sphere, 2/3 thin shell")
    add("--separation", default=_D.separation, metavar="|".join(SEPARATION_CRITERIA),
        help="contact ends when the force P (first of P = 0 and delta = 0) or the penetration delta returns to 0")
    add("--gravity", type=_number, nargs="?", const=STANDARD_GRAVITY, default=_D.gravity, metavar="G",
        help=f"gravitational acceleration [m/s^2], >= 0; the bare flag means {STANDARD_GRAVITY} "
             f"(default: {_D.gravity})")
    for name, text in _setting_flags().items():
        add("--" + name.replace("_", "-"), type=int, default=None, metavar="N", help=text)
    for name, text in PARTNER_HELP.items():
        add("--" + name.replace("_", "-"), type=_number, default=None, help=text)
    for name, text in MATERIAL_HELP.items():
        add("--" + name.replace("_", "-"), type=_material_pair, default=None, metavar="E,NU", help=text)


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="sphereimpact",
                     description="Impact of a rigid-body sphere on a rigid inclined flat (spring-damper contact, "
                                 "Coulomb friction).")
    parser.add_argument("--version", action="version", version=f"sphereimpact {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    sim = sub.add_parser(
        "simulate", help="simulate one impact and print its outputs", formatter_class=_Help,
        description="Simulate one impact and print its outputs (SI units). Defaults are the chapter's. "
                    "Numbers may be fractions (2/3).", epilog=OUTPUT_ANGLES)
    _scene_options(sim)
    add = sim.add_argument
    add("--save-ball", default=None, metavar="FILE",
        help="also write this ball (calibrated, with --cor) to FILE as JSON, for --ball, load_ball and a study's "
             "ball_file")
    add("--method", default=_O.method, metavar="NAME",
        help="integrator: " + ", ".join(method_names()) + " (default auto: the law's closed form where it has one, "
             "else the Taylor method where it has a series (eq. 4.2, linear-hunt-crossley), else DOP853-scalar; "
             "'closed' is the exact solution, kelvin-voigt only)")
    add("--rtol", type=_number, default=_O.rtol, help=f"relative tolerance, {RTOL_RANGE}")
    add("--atol", type=_number, default=_O.atol,
        help=f"absolute tolerance on the dimensionless state (delta scaled by v_n/omega_n, rate by v_n), {ATOL_RANGE}")
    add("--body", choices=[body.value for body in BODIES], default="reduced",
        help="reduced: normal ODE plus impulse algebra (exact, cheapest); planar: full rigid-body cross-check")
    add("--strict", action="store_true",
        help="refuse a result outside the model (maximum compression beyond the radius) instead of flagging it")
    add("--json", action="store_true", help="print one JSON object instead of the readable table")
    add("--history", default=None, metavar="FILE",
        help="also write the time history, .csv (units in the header: 't [s]') or .parquet (units in the schema's "
             "metadata), SI units, contact and global frames")
    add("--plot", default=None, metavar="FILE",
        help="also draw the history: displacement, velocities, spin, force against compression (.png, .pdf, .svg)")
    add("--samples", type=int, default=401, metavar="N", help="instants of --history and --plot, an integer >= 2")
    add("--force", action="store_true", help="overwrite the --history, --plot and --save-ball files if they exist")

    swp = sub.add_parser(
        "sweep", help="simulate a grid of impacts and write one row per scene", formatter_class=_Help,
        description="Simulate every combination of the given values (START:STOP:STEP ranges, stop included, or "
                    "single numbers; a negative value is read as a value, so --angle -10:10:1 reaches the range "
                    "check) and write one row per scene: its parameters and the outputs of `simulate` (every scalar "
                    "output by default; --outputs chooses), SI units. The size and memory of the sweep and the "
                    "output file are checked before any work.", epilog=OUTPUT_ANGLES)
    swp.add_argument("--plugin", action="append", default=None, metavar="MODULE", help=PLUGIN_HELP)
    for name, unit in RANGED.items():
        default = getattr(_D, name)
        allowed = RULES[name][0].removeprefix("a finite number ")
        kwargs = {"nargs": "?", "const": repr(STANDARD_GRAVITY)} if name == "gravity" else {}
        what = f"{name} [{unit}], {allowed}" + (f" ({APPROACH_HELP[name]})" if name in APPROACH_HELP else "")
        swp.add_argument("--" + name.replace("_", "-"), default=repr(default), metavar="RANGE", **kwargs,
                         help=f"{what}: a value or START:STOP:STEP"
                              + (f"; the bare flag means {STANDARD_GRAVITY}" if name == "gravity" else ""))
    for name in PATH_RULES:
        swp.add_argument("--" + name.replace("_", "-"), default=None, metavar="RANGE",
                         help=APPROACH_HELP[name] + ": a value or START:STOP:STEP (then --angle stays 0)")
    for name, text in PARTNER_HELP.items():
        swp.add_argument("--" + name.replace("_", "-"), default=None, metavar="RANGE",
                         help=text + ": a value or START:STOP:STEP")
    for name, text in MATERIAL_HELP.items():
        swp.add_argument("--" + name.replace("_", "-"), type=_material_pair, default=None, metavar="E,NU", help=text)
    for name, text in _law_flags().items():
        swp.add_argument("--" + name, default=None, metavar="RANGE",
                         help=text + ": a value or START:STOP:STEP. A parameter the law does not use is refused")
    swp.add_argument("--model", default=_D.model, help="force law: " + ", ".join(LAWS))
    tangential_help = _tangential_help()
    swp.add_argument("--tangential", choices=tuple(TANGENTIALS), default=_D.tangential,
                     help=tangential_help["tangential"] + " (compliant scenes are solved one by one)")
    for name in TANGENTIAL_PARAMETERS:
        swp.add_argument("--" + name.replace("_", "-"), default=None, metavar="RANGE",
                         help=tangential_help[name] + ": a value or START:STOP:STEP")
    for name, text in _own_flags().items():
        swp.add_argument("--" + name.replace("_", "-"), default=None, metavar="RANGE",
                         help=text + ": a value or START:STOP:STEP")
    swp.add_argument("--separation", default=_D.separation, help="force or penetration")
    swp.add_argument("--cor", type=_number, default=None, metavar="E",
                     help="set the law's damping so that a normal impact at --cor-speed has the COR E, in (0, 1): "
                          "calibrated once per distinct ball, then swept")
    swp.add_argument("--cor-speed", type=_number, default=None, metavar="M_S",
                     help="normal impact speed at which --cor (and --contact-time) was measured [m/s] (default: the "
                          "scenes' normal speed, as simulate's, when they share one)")
    swp.add_argument("--cor-relation", default=Relation.EXACT.value, metavar="|".join(Relation),
                     help="how --cor sets the damping: exact (root find, to 1e-9) or a published relation of the law")
    swp.add_argument("--contact-time", type=_number, default=None, metavar="S",
                     help="with --cor: fit the stiffness k too, so that the contact time is S [s] (k and --modulus "
                          "are then not given)")
    swp.add_argument("--chapter-ball", action="store_true", help=CHAPTER_BALL_HELP)
    swp.add_argument("--ball", default=None, metavar="FILE",
                     help="the ball, its contact and surface from a ball file (simulate --save-ball, a study's "
                          "ball.json); give only the approach's ranges, the surface's (--mu, --gravity) and options")
    for name, text in _setting_flags().items():
        swp.add_argument("--" + name.replace("_", "-"), type=int, default=None, metavar="N", help=text)
    swp.add_argument("--outputs", default=None, metavar="LIST",
                     help="comma-separated outputs to write (default: all, every scalar output of simulate; "
                          "'fast': all but t_roll and the force extremes, which take one solve per family)")
    swp.add_argument("--target", type=_number, default=1e-8, help="relative accuracy of every output, in [1e-12, 1e-3]")
    swp.add_argument("--chunk-size", type=int, default=100_000,
                     help="scenes integrated at once, >= 1 (bounds the integration's working memory)")
    swp.add_argument("--jobs", type=int, default=None, metavar="N",
                     help="most processes sharing the scenes solved one at a time (compliant contact at an angle, "
                          "gravity on a slope), >= 1 (default: $SPHEREIMPACT_JOBS, else every CPU this process may use; the "
                          "table is the same whatever N)")
    swp.add_argument("--out", required=True, metavar="FILE",
                     help="output table, .csv or .parquet (its folder must exist)")
    swp.add_argument("--force", action="store_true", help="overwrite FILE if it exists")

    fit = sub.add_parser(
        "fit", help="fit a ball's parameters to measured bounces", formatter_class=_Help,
        description="Fit the --free parameters of the ball (described as for simulate, or --ball FILE) to measured "
                    "bounces by weighted least squares, and print each with its standard error. MEASURED is a CSV: "
                    "one bounce per row, its approach (speed, incidence or angle_to_surface or angle, spin; a "
                    "column left out takes the value of the options) and measured outputs named like simulate's "
                    f"({', '.join(MEASURABLE)}; SI, contact frame), any subset, each with an optional "
                    "sigma_<output> column (standard uncertainty); or the long layout of the shipped Kharaz data "
                    "(quantity, incidence_deg, value).", epilog=OUTPUT_ANGLES)
    fit.add_argument("measured", metavar="MEASURED", help="the measured bounces, a CSV file")
    fit.add_argument("--free", required=True, metavar="NAMES",
                     help=f"comma-separated parameters to fit, of {', '.join(FREE)} (cor: the measured COR the "
                          "damping is calibrated to, with --cor), or a plug-in model's own parameters")
    _scene_options(fit)
    fit.add_argument("--bootstrap", type=int, default=0, metavar="N",
                     help="also refit N resamplings of the bounces, an integer in [0, 10000]: their spread is a "
                          "second standard error")
    fit.add_argument("--seed", type=int, default=0, help="the bootstrap's random seed, an integer >= 0")
    fit.add_argument("--target", type=_number, default=1e-8, help="relative accuracy of every model value, in "
                     "[1e-12, 1e-3]")
    fit.add_argument("--json", action="store_true", help="print one JSON object (per parameter value, stderr, "
                     "identifiable; the correlation; the residual statistics) instead of the readable table")
    fit.add_argument("--out", default=None, metavar="DIR",
                     help=f"also write {', '.join(FIT_FILES)} into DIR (made if missing): the fitted ball for "
                          "--ball, load_ball and a study's ball_file, the residuals and data against model")
    fit.add_argument("--force", action="store_true", help="overwrite the files in DIR if they exist")

    pln = sub.add_parser(
        "plan", help="which bounces to measure: a plan's expected errors, and the best plan", formatter_class=_Help,
        description="Before measuring: the expected standard error of each --free parameter that a fit of bounces "
                    "would give, for the ball described as for fit (its parameters at the values you expect), with "
                    "the --noise of each output you will measure; and the best plan of --size bounces chosen from "
                    "CANDIDATES (a CSV of approaches in fit's columns: speed, incidence or angle_to_surface or angle, "
                    "spin), beside as many spread evenly. Linearised: the Fisher information of fit's Jacobian.",
        epilog=OUTPUT_ANGLES)
    pln.add_argument("candidates", metavar="CANDIDATES", help="the bounces you could measure, a CSV file")
    pln.add_argument("--free", required=True, metavar="NAMES",
                     help=f"comma-separated parameters to be fitted, of {', '.join(FREE)}, or a plug-in model's own")
    pln.add_argument("--noise", required=True, metavar="OUTPUT=SIGMA,...",
                     help=f"each output you will measure and its noise: absolute in its unit (e_t=0.02) or relative "
                          f"(abs_omega_f=5%%); outputs of {', '.join(MEASURABLE)}")
    pln.add_argument("--size", type=int, default=None, metavar="N",
                     help="bounces in the plan, from the free parameters' number to the candidates' (default: all)")
    pln.add_argument("--criterion", default="D", choices=("D", "A"),
                     help="D: the largest determinant of the information (default); A: the smallest sum of squared "
                          "relative standard errors")
    _scene_options(pln)
    pln.add_argument("--target", type=_number, default=1e-8, help="relative accuracy of every model value, in "
                     "[1e-12, 1e-3]")
    pln.add_argument("--json", action="store_true", help="print one JSON object (the chosen bounces, the expected "
                     "errors of the plan, of as many evenly spread and of every candidate, correlations, notes)")
    pln.add_argument("--out", default=None, metavar="DIR",
                     help="also write plan.csv (the chosen bounces for fit, each output to fill in), plan.json, "
                          "candidates.csv and plan.png into DIR (made if missing)")
    pln.add_argument("--force", action="store_true", help="overwrite the files in DIR if they exist")

    bench = sub.add_parser(
        "benchmark", help="the field's benchmark tests, exact, and a DEM code's deviation from them",
        description="Reference files of Chung & Ooi's eight DEM benchmark tests (Granular Matter 13, 2011), solved "
                    "exactly, and a DEM code's deviation from them.")
    tests = bench.add_subparsers(dest="benchmark", required=True, parser_class=_Parser)
    chung = tests.add_parser(
        "chung-ooi", help="write one CSV per test: inputs and exact outputs", formatter_class=_Help,
        description="Write test1.csv ... test8.csv to DIR: each test's cases (inputs and exact outputs, SI units in "
                    "the header). The exact contact: Hertz, Hunt-Crossley damping set to the test's COR, and the "
                    "exact elastic microslip tangential contact.")
    chung.add_argument("--out", required=True, metavar="DIR", help="folder of the reference files (created)")
    chung.add_argument("--tests", default=None, metavar="LIST", help="comma-separated test numbers (default: all)")
    chung.add_argument("--variant", default="exact", choices=("exact", "damped-mindlin"),
                       help="exact: the exact elastic microslip contact, damping in the normal law only; "
                            "damped-mindlin: the DEM codes' Mindlin spring with the tangential dashpot Kratos sets from "
                            "the test's COR (only the oblique tests with a COR below 1: 4, 6, 7, 8)")
    chung.add_argument("--force", action="store_true", help="overwrite the files in DIR if they exist")
    costs = tests.add_parser(
        "departure", help="what a DEM code's tangential rule costs: each rule's largest departure from the exact contact",
        formatter_class=_Help,
        description="Solve Chung & Ooi's oblique tests on a plane (4, 5, 6) with each DEM tangential rule (the linear "
                    "spring and Mindlin's, capped by Coulomb friction, with and without Kratos' tangential dashpot; "
                    "the rigid contact) and the exact elastic microslip contact, and write DIR/departure.csv (each "
                    "rule's largest departure from the exact contact per test and quantity, relative to the exact "
                    "quantity's largest magnitude) and DIR/departure.png. With --config, the Kharaz ball of a study "
                    "config's validation section too, over its incidences (DIR/departure_kharaz.csv).")
    costs.add_argument("--out", required=True, metavar="DIR", help="folder of the files (created)")
    costs.add_argument("--tests", default=None, metavar="LIST", help="comma-separated, some of 4,5,6 (default: all)")
    costs.add_argument("--config", default=None, metavar="FILE",
                       help="a study config (e.g. config/config.yaml) whose validation section describes the Kharaz "
                            "ball: its materials, speed, mu, measured e_n, normal law and incidences")
    costs.add_argument("--force", action="store_true", help="overwrite the files in DIR if they exist")
    against = tests.add_parser(
        "compare", help="judge a DEM code's results against the reference files (exit 0 pass, 1 fail, 2 bad input)",
        formatter_class=_Help,
        description="For every test<N>.csv in THEIRS (the reference's rows, in any order, matched by their case and "
                    "approach; the code's outputs in the reference's columns, each headed 'name [unit]' and converted "
                    "where the unit is known), every input checked against the reference's and each output's largest "
                    "deviation, relative to the reference column's scale, judged against its tolerance. A value "
                    "missing where the reference has one fails. Exit status 0 when every test passes, 1 when one "
                    "fails, 2 for bad input.")
    against.add_argument("reference", metavar="DIR", help="the reference files (benchmark chung-ooi --out DIR)")
    against.add_argument("theirs", metavar="THEIRS", help="the DEM code's files, named as DIR's")
    against.add_argument("--tolerance", default=None, metavar="TOL",
                         help="relative tolerance of every output (e.g. 0.05) or of some (omega_f=0.1,e_t=0.05); "
                              "default 0.02 for each")
    against.add_argument("--json", action="store_true", help="print one JSON object (overall, per test, per output)")
    return parser


def _values_as_one_token(argv: list[str], parser: argparse.ArgumentParser) -> list[str]:
    """Join ``--opt VALUE`` into ``--opt=VALUE`` where VALUE starts with '-' (``--angle -10:10:1``,
    ``--gravity -inf``), so that argparse reads it as a value (it would take it for an option) and the
    value reaches the range check."""
    takes_value = set()
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                takes_value |= {o for a in sub._actions if a.nargs != 0 for o in a.option_strings}
    out, i = [], 0
    while i < len(argv):
        token = argv[i]
        if token in takes_value and i + 1 < len(argv) and argv[i + 1].startswith("-") \
                and not argv[i + 1].startswith("--") and argv[i + 1] != "-":
            out.append(f"{token}={argv[i + 1]}")
            i += 2
            continue
        out.append(token)
        i += 1
    return out


#: Figure formats of --plot.
FIGURE_EXTENSIONS = (".png", ".pdf", ".svg")


def check_out(path: str, force: bool, extensions=None, what: str = "out") -> None:
    """Refuse an output path that cannot be written, before any work (ValueError naming it): ``what`` names
    the option in messages, ``extensions`` the endings allowed (default: the tables')."""
    from .sweep.io import EXTENSIONS

    extensions = EXTENSIONS if extensions is None else extensions
    if os.path.isdir(path):
        raise ValueError(f"{what} is a folder, not a file: {path!r}")
    if not path.endswith(extensions):
        raise ValueError(f"{what} must end in {' or '.join(extensions)}; got {path!r}")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise ValueError(f"{what}: folder {folder!r} does not exist")
    probe = os.path.join(folder, f".{os.path.basename(path)}.{os.getpid()}.probe")
    try:  # a file made and removed: os.access says yes to root in read-only places (/sys, a read-only mount)
        with open(probe, "w"):
            pass
        os.unlink(probe)
    except OSError as err:
        raise ValueError(f"{what}: folder {folder!r} is not writable ({err.strerror or err})") from None
    if os.path.exists(path) and not force:
        raise ValueError(f"{what}: {path!r} exists; pass --force to overwrite it")


def check_out_folder(path: str) -> None:
    """Refuse an output folder that is a file or whose parent does not exist, before any work (ValueError naming
    it); its files are checked by :func:`check_out`."""
    if not path.strip():  # "" would be the current folder, whose files the caller never named
        raise ValueError(f"out: give a folder's name; got {path!r}")
    if os.path.exists(path) and not os.path.isdir(path):
        raise ValueError(f"out is a file, not a folder: {path!r}")
    if not os.path.isdir(os.path.dirname(os.path.abspath(path))):
        raise ValueError(f"out: folder {os.path.dirname(os.path.abspath(path))!r} does not exist")


def _each_range(args, read) -> dict:
    """``read(text)`` of every ranged parameter given, a ValueError naming the parameter that fails."""
    out = {}
    for name in [*RANGED, *PATH_RULES, *PARTNER_FIELDS, *_law_flags(), *TANGENTIAL_PARAMETERS, *own_parameters()]:
        if getattr(args, name) is None:  # a law or tangential parameter not given: the default
            continue
        try:
            out[name] = read(getattr(args, name))
        except ValueError as err:
            raise ValueError(f"{name}: {err}") from None
    return out


def _sweep(args) -> None:
    import time

    from .sweep.calibrate import calibrate_table, normal_speeds, warn_if_extrapolating
    from .memory import check_size
    from .parsing import parse_range
    from .sweep.engine import FAST_OUTPUTS, grid, outputs_wanted, sweep
    from .sweep.io import write_table
    from .sweep.processes import checked_jobs

    start = time.perf_counter()
    if args.chunk_size < 1:
        raise ValueError(f"chunk_size must be an integer >= 1; got {args.chunk_size}")
    checked_jobs(args.jobs)
    check_out(args.out, args.force)
    outputs = _outputs(args.outputs, FAST_OUTPUTS)
    outputs_wanted(outputs)  # checked before any work
    SolverOptions(settings=_settings(args))  # their ranges, before any work
    check_size(_each_range(args, range_count),  # counted before any range is made
               "split it into shards (the pipeline's sweep.shards) or use coarser ranges (--chunk-size, "
               f"now {args.chunk_size}, bounds only the integration's working memory)")
    ranges = _each_range(args, parse_range)
    laws = {*_law_flags(), *own_parameters()}  # checked per row, against each row's models
    # before any work: each range, then the names.  The ranges have different lengths: checks across columns
    # (magnitudes of m v^2, the law's parameters, one path description) run per row in sweep, on the grid
    for name, values in ranges.items():
        if name not in laws:
            check_columns({name: values})
    largest = {name: float(np.max(np.abs(ranges[name]))) for name in ("mass", "speed", "diameter", "spin")}
    problem = magnitude_problem(**largest)  # the squares and products overflow first at the largest values
    if problem:
        raise ValueError(problem)
    check_columns({"model": [args.model], "separation": [args.separation]})
    _described(args, "sweep")
    settings, measurement = _settings(args), None
    if args.ball is not None:
        ball = _ball(args)
        check_described(ball, "sweep", args.chapter_ball)  # a file saved from the chapter's defaults says so
        measurement, settings = ball.measurement, dict(ball.options.settings) | settings
        kept = {name: values for name, values in ranges.items()
                if name in APPROACH or name in PARTNER_FIELDS or (name in SURFACE and name in args.given)}
        table = grid(**kept).assign(**ball_columns(ball, exclude=kept))
    else:
        table = grid(**ranges).assign(model=args.model, separation=args.separation,  # law parameters: checked by sweep
                                      tangential=args.tangential,
                                      **_materials(args, {n for n in ("k", "modulus", *TANGENTIAL_PARAMETERS)
                                                          if n in ranges}))
    if args.ball is None and args.cor is None:
        unused = [name for name in CALIBRATION[1:] if name in args.given]
        if unused:
            raise ValueError(f"--{unused[0].replace('_', '-')} needs --cor")
    if args.ball is None and args.cor is not None:
        damping = LAWS.law(args.model).damping
        if damping is not None and ranges.get(damping) is not None:
            raise ValueError(f"give --{damping} or --cor, not both (--cor sets {damping})")
        for name in ("k", "modulus"):
            if args.contact_time is not None and ranges.get(name) is not None:
                raise ValueError(f"give --{name} or --contact-time, not both (--contact-time fits k)")
        speeds = np.unique(normal_speeds(table))  # as simulate: the scenes' normal speed, if they share one
        if args.cor_speed is None and speeds.size > 1:
            raise ValueError("cor_speed is required when the sweep's scenes have several normal speeds: the speed "
                             "[m/s] of the normal impact whose COR was measured")
        measurement = Measurement(args.cor, speeds[0] if args.cor_speed is None else args.cor_speed,
                                  args.contact_time, args.cor_relation)
        table = calibrate_table(table, measurement)
    elif measurement is not None:  # a ball file's: calibrate_table says it for --cor
        warn_if_extrapolating(table, measurement)
    tty = sys.stderr.isatty()
    result = sweep(table, target=args.target, chunk_size=args.chunk_size, outputs=outputs, chapter_ball=args.chapter_ball,
                   progress=_Progress(start) if tty else None, settings=settings, jobs=args.jobs)
    write_table(result, args.out)
    seconds = time.perf_counter() - start
    sys.stderr.write(f"{chr(13) if tty else ''}sphereimpact sweep: {len(result)} scenes in {seconds:.3g} s -> "
                     f"{args.out}\n")


def _outputs(text: str | None, fast) -> list | None:
    """The --outputs list: None for all, FAST_OUTPUTS for 'fast', else the names (checked by sweep)."""
    if text is None:
        return None
    if text.strip() == "fast":
        return list(fast)
    return [name.strip() for name in text.split(",") if name.strip()]


class _Progress:
    """Scenes done out of the total on standard error, once a run has taken more than :data:`PROGRESS_AFTER`
    seconds (a quick sweep prints only its closing line)."""

    def __init__(self, start: float):
        self.start = start

    def __call__(self, done: int, total: int) -> None:
        import time

        if time.perf_counter() - self.start > PROGRESS_AFTER:
            sys.stderr.write(f"\rsphereimpact sweep: {done}/{total} scenes solved ...")


def _readable(outputs: dict, units: dict) -> str:
    """The outputs as aligned ``name  value  unit`` lines (the outputs first, then any fitted values)."""
    lines, width = [], max(10, *map(len, outputs))
    for key in [*OUTPUT_KEYS, *(key for key in outputs if key not in OUTPUT_KEYS)]:
        value = outputs[key]
        shown = f"{value:.10g}" if isinstance(value, float) else "—" if value is None else str(value)
        unit = units.get(key, "") if isinstance(value, (int, float)) and not isinstance(value, bool) else ""
        lines.append(f"{key:<{width}} {shown:>18} {unit}".rstrip())
    return "\n".join(lines)


#: The surface (which may differ from the ball file's; the approach, APPROACH, is what a ball file leaves to the
#: command line).
SURFACE = ("mu", "gravity")
#: Options that describe the ball and its contact: a ball file gives them all.
CALIBRATION = ("cor", "cor_speed", "contact_time", "cor_relation")


def _materials(args, given) -> dict:
    """The contact's modulus (and kappa) from --ball-material and --surface-material, if given
    (:func:`~sphereimpact.contact.materials.material_fields`); ``given``: the contact's fields given besides."""
    if args.ball_material is None:
        if args.surface_material is not None:
            raise ValueError("surface_material needs ball_material (the ball's E,NU): the contact's E* is of both bodies")
        return {}
    compliant = bool(TANGENTIALS.model(args.tangential).stiffness_parameters)
    return material_fields(args.ball_material, args.surface_material, compliant, given)


def _ball_fields(args) -> dict:
    """The Scene fields the command line gives besides the approach: ball, contact, surface."""
    contact = {name: getattr(args, name) for name in ("k", "modulus", *TANGENTIAL_PARAMETERS)
               if getattr(args, name, None) is not None}
    return dict(mass=args.mass, diameter=args.diameter, inertia_factor=args.inertia_factor, mu=args.mu,
                model=args.model, gravity=args.gravity, separation=args.separation, tangential=args.tangential,
                **{name: getattr(args, name) for name in (*TANGENTIAL_PARAMETERS, *_law_flags())},
                parameters={name: getattr(args, name) for name in own_parameters() if getattr(args, name) is not None},
                **_partner(args)) | _materials(args, contact)


def _partner(args) -> dict:
    """The partner sphere's fields the command line gives (none: the flat)."""
    return {name: getattr(args, name) for name in PARTNER_FIELDS if getattr(args, name) is not None}


def _ball(args) -> Ball | None:
    """The ball of ``--ball FILE``, or the one ``--cor`` (``--cor-speed``, ``--contact-time``) calibrates from the
    other flags; None when neither is given.  With a ball file, a flag that describes the ball is refused."""
    if args.ball is not None:
        describing = {"mass", "diameter", "inertia_factor", "model", "separation", "tangential",
                      *TANGENTIAL_PARAMETERS,
                      *_law_flags(), *own_parameters(), *CALIBRATION, *MATERIAL_HELP}
        clash = sorted(name for name in args.given if name in describing)
        if clash:
            raise ValueError(f"--{clash[0].replace('_', '-')}: the ball file {args.ball!r} describes the ball and "
                             "its contact; give the approach, the surface (--mu, --gravity) and the solver's options")
        return load_ball(args.ball)
    if args.cor is None:
        unused = [name for name in CALIBRATION[1:] if name in args.given]
        if unused:
            raise ValueError(f"--{unused[0].replace('_', '-')} needs --cor")
        return None
    incidence = Scene(**{name: getattr(args, name) for name in APPROACH}).incidence_deg
    speed = args.cor_speed if args.cor_speed is not None else args.speed * math.cos(math.radians(incidence))
    measurement = Measurement(args.cor, speed, args.contact_time, args.cor_relation)
    return calibrated_ball(measurement, SolverOptions(settings=_settings(args)), tuple(args.plugin or ()),
                           **_ball_fields(args))


def _simulate(args) -> None:
    if args.history is not None:
        check_out(args.history, args.force, what="history")
    if args.plot is not None:
        check_out(args.plot, args.force, FIGURE_EXTENSIONS, what="plot")
    if args.save_ball is not None:
        check_out(args.save_ball, args.force, (".json",), what="save-ball")
    if args.samples < 2:
        raise ValueError(f"samples must be an integer >= 2 (instants from 0 to t_f); got {args.samples}")
    ball, approach = _ball(args), {name: getattr(args, name) for name in APPROACH}
    if ball is None:
        scene = Scene(**_ball_fields(args), **approach)
    else:
        surface = {name: getattr(args, name) for name in SURFACE if name in args.given}
        scene = ball_scene(ball, **{k: v for k, v in approach.items() if v is not None}).with_(**surface,
                                                                                               **_partner(args))
        if args.ball is None and args.cor_speed is None and scene.incidence_deg != 0:
            sys.stderr.write(f"sphereimpact: note: --cor calibrated the law at this scene's normal speed "
                             f"{scene.v_normal:.6g} m/s; give --cor-speed, the normal speed of the measurement\n")
    options = SolverOptions(method=args.method, rtol=args.rtol, atol=args.atol,
                            settings=({} if ball is None else dict(ball.options.settings)) | _settings(args))
    fitted, units = {}, UNITS | {"gravity": "m/s^2"}
    if ball is not None and args.ball is None:  # calibrated here: what was fitted, and the published relations
        damping = scene.law.damping
        for name, value in ball.fitted.items():
            fitted[f"fitted_{name}"] = value
            units = units | {f"fitted_{name}": scene.law.parameter(name).unit}
        fitted |= {f"{damping}_{name}": value for name, value in ball.relations.items()}
        units = units | {f"{damping}_{name}": scene.law.parameter(damping).unit for name in ball.relations}
    if args.save_ball is not None:
        save_ball(replace(ball, options=SolverOptions(settings=options.settings)) if ball is not None
                  else Ball(scene, options=SolverOptions(settings=options.settings), plugins=tuple(args.plugin or ())),
                  args.save_ball)
    outcome = simulate(scene, options, body=args.body, strict=args.strict)
    outputs = outcome.to_dict() | fitted | {"gravity": scene.gravity}  # the one input a default sets, recorded
    chapter = [] if args.chapter_ball else chapter_parts(outcome.scene)  # what the API says of its ball
    if chapter and args.ball is not None:  # the file was saved from the chapter's defaults
        sys.stderr.write(f"sphereimpact: note: the ball file {args.ball!r} holds the chapter's ball where its maker "
                         f"was silent ({_defaults(scene, chapter)})\n")
    elif chapter:  # said once the impact is solved: an error stays one line
        sys.stderr.write(f"sphereimpact: note: the chapter's ball where the options are silent "
                         f"({_defaults(scene, chapter)}); describe yours with {_as_options(chapter)}\n")
    if outcome.scene.chapter_approach and not args.chapter_ball:  # what the API says of its approach
        sys.stderr.write(f"sphereimpact: note: the chapter's approach speed {scene.speed:g} m/s where --speed is "
                         "silent\n")
    if args.history is not None or args.plot is not None:
        history = outcome.history(args.samples)
        if args.history is not None:
            from .sweep.io import write_table

            write_table(history, args.history, units=history.attrs["units"])
        if args.plot is not None:
            from .figures.history import history_figure

            title = (f"{scene.model} law, {scene.tangential} contact: {scene.speed:g} m/s at {scene.incidence_deg:g}° "
                     f"from the normal, spin {scene.spin:g} rad/s; COR {outcome.cor:.4g}, ω_f {outcome.omega_f:.4g} rad/s")
            history_figure(history, title, scene.separation, [args.plot])
    if args.json:
        json.dump(outputs, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        sys.stdout.write(_readable(outputs, units) + "\n")


def _described(args, command: str) -> None:
    """Refuse a ball that ``command``'s options do not describe (ValueError naming what is missing): only
    simulate takes the chapter's ball unasked; --ball FILE and --chapter-ball describe it too."""
    if args.chapter_ball:
        return
    missing = undescribed(args.given, args.model, approach=command == "sweep")
    if args.ball is not None:  # the file describes the ball, not a sweep's approach
        missing = [part for part in missing if part == "speed"]
    if missing == ["speed"]:
        raise ValueError("sweep: give --speed, the approach speed [m/s], a value or a range (or --chapter-ball "
                         "for the chapter's 3 m/s); only simulate takes the chapter's scene unasked")
    if missing:
        whose = {"fit": "the ball you measured", "plan": "the ball you will measure"}.get(
            command, "your ball and its speed" if "speed" in missing else "your ball")
        raise ValueError(f"{command}: describe {whose}: give {_as_options(missing)} (or --ball FILE, or "
                         "--chapter-ball for the chapter's); only simulate takes the chapter's ball unasked")


def _as_options(names) -> str:
    """Parts of a description (:func:`~sphereimpact.impact.ball.undescribed`) as the options that give them."""
    return ", ".join(" or ".join("--" + word.replace("_", "-") for word in name.split(" or ")) for name in names)


def _defaults(scene: Scene, names) -> str:
    """The values ``scene`` took for the undescribed parts ``names``, with their units."""
    units = {"mass": "kg", "diameter": "m", "k": "N/m", "b": "N s/m"}
    shown = [name.split(" or ")[0] for name in names]
    return ", ".join(f"{name} {getattr(scene, name):g} {units.get(name, '')}".rstrip() for name in shown)


def _check_out_files(folder: str, names, force: bool) -> None:
    """Refuse, before any work, a folder ``names`` cannot be written into (existing files without ``force``)."""
    check_out_folder(folder)
    if os.path.isdir(folder):
        for name in names:
            check_out(os.path.join(folder, name), force, (os.path.splitext(name)[1],))
    else:  # made once the work has succeeded, so a failure leaves nothing behind: its parent must take it
        check_out(os.path.abspath(folder) + ".json", True, (".json",))


def _user_ball(args) -> Ball:
    """The ball of ``fit`` and ``plan``: a ball file's (its approach replaced by the options that give one) or the
    options' own, with their solver settings and plug-ins."""
    ball = _ball(args)
    approach = {name: getattr(args, name) for name in APPROACH if name in args.given}
    if ball is None:
        return Ball(Scene(**_ball_fields(args), **{name: getattr(args, name) for name in APPROACH}),
                    options=SolverOptions(settings=_settings(args)), plugins=tuple(args.plugin or ()))
    if approach or _partner(args):
        return replace(ball, scene=ball_scene(ball, **approach).with_(**_partner(args)))
    return ball


def _names(text: str) -> list[str]:
    """A comma-separated list of names (``--free``)."""
    return [name.strip() for name in text.split(",") if name.strip()]


def _fit(args) -> None:
    """``sphereimpact fit``: the ball from the options, the bounces from MEASURED, the fit printed (and
    written with --out).  The ball is the user's: described by the options or a ball file, never the chapter's
    by default; so is the bounces' speed, from MEASURED or --speed."""
    from .fit import fit, read_measured
    from .study.fitting import write_fit

    _described(args, "fit")

    if not 0 <= args.bootstrap <= 10_000:
        raise ValueError(f"bootstrap must be an integer in [0, 10000]; got {args.bootstrap}")
    if args.seed < 0:
        raise ValueError(f"seed must be an integer >= 0; got {args.seed}")
    if not (math.isfinite(args.target) and 1e-12 <= args.target <= 1e-3):
        raise ValueError(f"target must be a finite number in [1e-12, 1e-3]; got {args.target!r}")
    if args.out is not None:
        _check_out_files(args.out, FIT_FILES, args.force)
    ball = _user_ball(args)
    free = _names(args.free)
    measured = read_measured(args.measured)
    if "speed" not in measured.bounces and "speed" not in args.given:
        raise ValueError(f"fit: {args.measured!r} has no speed column: give the bounces' approach speed along the "
                         "path with --speed [m/s]")
    result = fit(measured, ball, free, args.bootstrap, args.seed, args.target, chapter_ball=args.chapter_ball)
    if _delivered(result, args, write_fit):
        return
    stats = result.statistics
    lines = [f"fitted to {stats['values']} measured values of {stats['bounces']} bounces ({args.measured})"]
    for name, p in result.parameters.items():
        boot = "" if math.isnan(p.bootstrap_stderr) else f"  (bootstrap {p.bootstrap_stderr:.3g})"
        flag = "" if p.identifiable else "  not identifiable"
        lines.append(f"{name:<16}{p.value:>16.8g} ± {p.stderr:<12.3g}{boot}{flag}")
    construction = ("; near 1 by construction: every uncertainty was estimated from the residual scatter, so this is "
                    "no test of the fit") if stats["weights"] == "scatter" else ""
    lines.append(f"chi2 / dof       {stats['reduced_chi2']:.4g} ({stats['dof']} degrees of freedom{construction})")
    lines += [f"rms {q:<12}{v:>16.6g} {MEASURABLE[q]}" for q, v in stats["rms"].items()]
    lines += [f"note: {note}" for note in result.notes]
    sys.stdout.write("\n".join(lines) + "\n")


def _delivered(result, args, write) -> bool:
    """Write ``result`` into ``--out`` with ``write`` and, with ``--json``, print its ``as_dict`` (True: printed,
    nothing more to say)."""
    from .study.fitting import finite

    if args.out is not None:
        write(result, args.out)
    if args.json:
        json.dump(finite(result.as_dict()), sys.stdout, indent=2)
        sys.stdout.write("\n")
    return args.json


def _plan(args) -> None:
    """``sphereimpact plan``: the ball from the options (described, as for fit), the candidates from CANDIDATES,
    the plan's expected errors printed (and written with --out)."""
    from .fit.plan import plan, read_candidates
    from .study.planning import write_plan

    _described(args, "plan")
    if args.out is not None:
        _check_out_files(args.out, PLAN_FILES, args.force)
    candidates = read_candidates(args.candidates)  # read once: plan takes the table
    # as fit: the approach is the candidates' or the options', never a ball file's (the speed it was calibrated at)
    if "speed" not in candidates and "speed" not in args.given:
        raise ValueError(f"plan: {args.candidates!r} has no speed column: give the bounces' approach speed along the "
                         "path with --speed [m/s]")
    result = plan(candidates, _user_ball(args), _names(args.free), args.noise, args.size, args.criterion,
                  args.target, chapter_ball=args.chapter_ball)
    if _delivered(result, args, write_plan):
        return
    size, total = len(result.chosen), len(result.candidates)
    lines = [f"{result.criterion}-optimal plan of {size} bounces of {total} candidates ({args.candidates}); noise "
             + ", ".join(f"{name} {noise}" for name, noise in result.noise.items()),
             f"{'parameter':<16}{'expected':>14}{'plan':>14}{'evenly spread':>16}{'every candidate':>18}"]
    for name in result.free:
        errors = [result.stderr[label][name] for label in ("chosen", "even", "all")]
        lines.append(f"{name:<16}{result.values[name]:>14.6g}" + "".join(
            f"{e:>{w}.3g}" if math.isfinite(e) else f"{'unbounded':>{w}}" for e, w in zip(errors, (14, 16, 18))))
    chosen = result.candidates.iloc[list(result.chosen)]
    lines.append("chosen: " + "; ".join(
        f"incidence {row.incidence_deg:.4g} deg" + "".join(f", {c} {getattr(row, c):g}" for c in ("speed", "spin")
                                                          if c in chosen)
        for row in chosen.itertuples()))
    lines += [f"note: {note}" for note in result.notes]
    sys.stdout.write("\n".join(lines) + "\n")


def _benchmark(args) -> None:
    """``sphereimpact benchmark``: the reference files of Chung & Ooi's tests, a code's deviation from them, or the
    DEM rules' departure from the exact contact."""
    from .study.chung_ooi import chosen_tests, write_reference
    from .study.chung_ooi_definition import variant_tests

    if args.benchmark == "compare":
        from .study.dem_compare import compare, parse_tolerances

        for name, folder in (("DIR", args.reference), ("THEIRS", args.theirs)):
            if not os.path.isdir(folder):
                raise ValueError(f"{name}: {folder!r} is not a folder")
        verdict = compare(args.reference, args.theirs, parse_tolerances(args.tolerance))
        if args.json:
            json.dump(verdict.as_dict(), sys.stdout, indent=2)
            sys.stdout.write("\n")
        else:
            shown = verdict.table.assign(passed=verdict.table["passed"].map({True: "pass", False: "FAIL"}))
            sys.stdout.write(shown.to_string(index=False, float_format=lambda x: f"{x:.3g}") + "\n")
            for number, ok in verdict.tests.items():
                sys.stdout.write(f"test {number}: {'pass' if ok else 'FAIL'}\n")
            worst = verdict.table.loc[(verdict.table["max_rel"] / verdict.table["tolerance"].clip(lower=1e-300)).idxmax()]
            sys.stdout.write(f"overall: {'pass' if verdict.passed else 'FAIL'} (worst: test {worst['test']} "
                             f"{worst['quantity']} {worst['max_rel']:.3g} of tolerance {worst['tolerance']:g}, "
                             f"{worst['worst']})\n")
        return 0 if verdict.passed else 1
    numbers = _test_numbers(args.tests)
    if args.benchmark == "departure":
        return _departure(args, numbers)
    check_out_folder(args.out)
    numbers = chosen_tests(numbers)
    if args.variant != "exact":
        asked, numbers = numbers, variant_tests(numbers)
        if not numbers:
            raise ValueError(f"tests: none of {','.join(map(str, asked))} has a {args.variant!r} reference (only the "
                             f"oblique tests with a COR below 1: {','.join(map(str, variant_tests(chosen_tests(None))))})")
    os.makedirs(args.out, exist_ok=True)
    for number in numbers:
        check_out(os.path.join(args.out, f"test{number}.csv"), args.force, (".csv",))
    for path in write_reference(args.out, numbers, variant=args.variant):
        sys.stdout.write(f"{path}\n")


def _test_numbers(text: str | None) -> list[int] | None:
    """The --tests list as test numbers (None: not given)."""
    try:
        return None if text is None else [int(n) for n in text.split(",") if n.strip()]
    except ValueError:
        raise ValueError(f"tests must be comma-separated test numbers, e.g. 1,4; got {text!r}") from None


#: What ``benchmark departure --config`` reads of a study config's validation section: the Kharaz ball.
KHARAZ_KEYS = {"sphere": ("modulus", "poisson", "density", "diameter"), "anvil": ("modulus", "poisson"), "speed": (),
               "mu": (), "cor": (), "model": (), "angles": ()}


def _departure(args, numbers) -> None:
    """``sphereimpact benchmark departure``: each DEM rule's largest departure from the exact contact."""
    from .study.departure import check_tests, write_departure

    numbers, section = check_tests(numbers), None
    if args.config is not None:
        import yaml

        try:
            with open(args.config, encoding="utf-8") as handle:
                config = yaml.safe_load(handle)
        except (OSError, yaml.YAMLError) as err:
            raise ValueError(f"config: cannot read {args.config!r}: {str(err).splitlines()[0]}") from None
        section = config.get("validation") if isinstance(config, dict) else None
        if isinstance(section, dict):  # its values as the pipeline checks them, against the project's schema
            from .study.config_check import SCHEMA, config_errors

            errors = config_errors({"validation": section}, SCHEMA)
            if errors:
                raise ValueError(f"config: {args.config!r}: {'; '.join(errors)}")
        missing = ["validation"] if not isinstance(section, dict) else [
            f"validation.{key}" + (f".{part}" if part else "") for key, parts in KHARAZ_KEYS.items()
            for part in (parts or ("",)) if key not in section
            or (part and not (isinstance(section[key], dict) and part in section[key]))]
        if missing:
            raise ValueError(f"config: {args.config!r} lacks {', '.join(missing)} (a study config's validation "
                             "section describes the Kharaz ball, as config/config.yaml does)")
    _check_out_files(args.out, ("departure.csv", "departure.png", *(("departure_kharaz.csv",) if section else ())),
                     args.force)
    write_departure(args.out, numbers, section)
    sys.stdout.write(f"{os.path.join(args.out, 'departure.csv')}\n")
    if section is None:
        sys.stderr.write("sphereimpact: note: Chung & Ooi's tests only; give --config FILE for the Kharaz ball too\n")


def run(argv=None) -> int:
    """Parse ``argv`` and run the command; return the exit status (0 done, 1 failed or a failing verdict, 2 bad
    input).

    Every error is one line on standard error: ``sphereimpact: error: ...``.
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    try:
        with warnings.catch_warnings(record=True) as caught:  # what the API warns, said once the command succeeds
            warnings.simplefilter("always", SphereImpactWarning)
            plugins.load(_plugin_names(argv))  # before the parser, whose choices and flags the registries give
            parser = _parser()
            args = parser.parse_args(_values_as_one_token(argv, parser))
            args.given = _given(argv, parser, args.command)
            status = {"sweep": _sweep, "simulate": _simulate, "fit": _fit, "plan": _plan,
                      "benchmark": _benchmark}[args.command](args)
        _say(caught, getattr(args, "strict", False))
    except (UsageError, ValueError, TypeError, ImpactError) as err:
        return _fail(2, err)
    except MemoryError:
        return _fail(1, "out of memory: use coarser ranges or split the sweep into shards")
    except BrokenPipeError:  # the reader left (`| head`): main() ends quietly
        raise
    except OSError as err:
        return _fail(1, f"{err.strerror or err}: {err.filename or ''}".rstrip(": "))
    return status or 0  # a verdict's 1 (benchmark compare), else 0


def _say(caught, strict: bool) -> None:
    """The API's warnings as one line each on standard error (each said once), others as Python shows them."""
    said = set()
    for warning in caught:
        if not issubclass(warning.category, SphereImpactWarning):
            warnings.showwarning(warning.message, warning.category, warning.filename, warning.lineno)
            continue
        refused = " (--strict refuses it)" if warning.category is BeyondRadiusWarning and not strict else ""
        line = f"sphereimpact: warning: {warning.message}{refused}\n"
        if line not in said:
            said.add(line)
            sys.stderr.write(line)


def _given(argv: list[str], parser: argparse.ArgumentParser, command: str) -> set:
    """The options ``argv`` gives explicitly (their ``dest`` names), as opposed to defaults."""
    flags = {}
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            flags = {option: a.dest for a in action.choices[command]._actions for option in a.option_strings}
    return {flags[token.partition("=")[0]] for token in argv if token.partition("=")[0] in flags}


def _plugin_names(argv: list[str]) -> list[str]:
    """The modules named by ``--plugin MODULE`` (or ``--plugin=MODULE``) anywhere in ``argv``."""
    names = []
    for i, token in enumerate(argv):
        if token == "--plugin" and i + 1 < len(argv):
            names.append(argv[i + 1])
        elif token.startswith("--plugin="):
            names.append(token.partition("=")[2])
    return names


def _fail(status: int, message) -> int:
    sys.stderr.write(f"sphereimpact: error: {message}\n")
    return status


def main() -> None:
    """Console-script entry point."""
    try:
        status = run()
        sys.stdout.flush()
    except BrokenPipeError:  # e.g. `sphereimpact simulate --json | head`
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        status = 0
    except KeyboardInterrupt:
        sys.stderr.write("sphereimpact: interrupted\n")
        status = 130
    sys.exit(status)
