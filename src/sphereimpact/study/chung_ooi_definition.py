"""Chung & Ooi's eight DEM benchmark tests as their definition file states them: read without the solvers, so that
a workflow building its jobs (which tests have a damped-Mindlin variant) does not import them."""

from __future__ import annotations

from pathlib import Path

from ..files import load_yaml

#: The tests' inputs and their sources.
DEFINITION = Path(__file__).with_name("chung_ooi.yaml")


def load_tests(path=DEFINITION) -> tuple[dict, dict]:
    """The materials and the tests of a definition file (:data:`DEFINITION` by default)."""
    definition = load_yaml(Path(path).read_text(encoding="utf-8"))
    return definition["materials"], {int(number): test for number, test in definition["tests"].items()}


def listed(test: dict, name: str) -> list:
    """A test's entry ``name`` as a list (empty where the test does not give it)."""
    value = test.get(name)
    return [] if value is None else list(value) if isinstance(value, list) else [value]


def variant_tests(numbers, path=DEFINITION) -> list[int]:
    """Those of ``numbers`` whose reference has a ``damped-mindlin`` variant: oblique, with a COR below 1."""
    _, tests = load_tests(path)
    return [n for n in numbers if n >= 4 and min(listed(tests[n], "cor")) < 1.0]
