"""Numbers and ranges written as text (command line, config): checked and counted before any allocation.

A number is a decimal or a fraction ``a/b`` (``2/3`` for a thin shell's inertia factor); a range is one
number or ``START:STOP:STEP`` with STOP included when it lies on the grid.
"""

from __future__ import annotations

import math

import numpy as np

#: Largest number of values one range may hold (a sweep's size is checked separately, against memory).
MAX_RANGE = 10**9


def parse_number(text: str) -> float:
    """A decimal number or a fraction ``a/b`` as a float.

    Raises
    ------
    ValueError
        For anything else (the message says what is accepted).
    """
    text = str(text).strip()
    try:
        if "/" in text:
            num, den = text.split("/")
            return float(num) / float(den)
        return float(text)
    except (ValueError, ZeroDivisionError):
        raise ValueError(f"expected a number (like 0.4, -10, 1e4 or 2/3); got {text!r}") from None


def _bounds(text: str) -> tuple[float, float, float] | float:
    parts = str(text).split(":")
    if len(parts) not in (1, 3):
        raise ValueError(f"range must be START:STOP:STEP or a number; got {text!r}")
    try:
        numbers = [parse_number(p) for p in parts]
    except ValueError:
        raise ValueError(f"range must be START:STOP:STEP or a number; got {text!r}") from None
    if len(numbers) == 1:
        return numbers[0]
    start, stop, step = numbers
    if not all(math.isfinite(x) for x in numbers) or step <= 0 or stop < start:
        raise ValueError(f"range must be START:STOP:STEP with finite numbers, STEP > 0 and STOP >= START; "
                         f"got {text!r}")
    return start, stop, step


def _count(bounds) -> int:
    """Values of parsed bounds: 1 for a number, else those of START:STOP:STEP with STOP included."""
    if isinstance(bounds, float):
        return 1
    start, stop, step = bounds
    return int(math.floor((stop - start) / step + 1e-9)) + 1


def range_count(text: str) -> int:
    """How many values ``text`` holds, without making them (a range of 10^12 values costs nothing here)."""
    return _count(_bounds(text))


def parse_range(text: str) -> np.ndarray:
    """``START:STOP:STEP`` (STOP included when on the grid) or a single number, as an array.

    Raises
    ------
    ValueError
        A malformed range, or one of more than :data:`MAX_RANGE` values.
    """
    bounds = _bounds(text)
    if isinstance(bounds, float):
        return np.array([bounds])
    count = _count(bounds)
    if count > MAX_RANGE:
        raise ValueError(f"range {text!r} holds {count:.3g} values, more than {MAX_RANGE:.0e}: use a larger STEP")
    start, _, step = bounds
    values = start + step * np.arange(count)
    places = _decimal_places(str(text).split(":"))
    if places is not None:  # 0:0.3:0.1 is 0, 0.1, 0.2, 0.3, not 0.30000000000000004: the decimals as written
        values = np.round(values, places)
    return values


def _decimal_places(parts) -> int | None:
    """The most decimal places a range's parts are written with (``0.25`` -> 2, ``1e-7`` -> 7), or None where a
    part is a fraction or needs more places than double precision holds (then the values are left as computed)."""
    from decimal import Decimal, InvalidOperation

    places = 0
    for part in parts:
        try:
            exponent = Decimal(part.strip()).as_tuple().exponent
        except InvalidOperation:
            return None
        if not isinstance(exponent, int):
            return None
        places = max(places, -exponent)
    return places if places <= 15 else None
