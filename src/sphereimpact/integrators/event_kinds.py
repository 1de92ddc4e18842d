"""What each event of the normal motion is, so that the compiled loop evaluates it by kind (no physics here)."""

from __future__ import annotations

from enum import IntEnum


class EventKind(IntEnum):
    """An event of the normal motion, each falling through zero; its value is the compiled loop's code for it
    (:mod:`.dop853_kernel`), which evaluates it from the state alone."""

    MAX_COMPRESSION = 0  # y: maximum compression
    PENETRATION = 1  # delta: separation under the penetration criterion
    FORCE = 2  # the force inside contact, -1 outside: separation under the force criterion
    BAND = 3  # max(lam x - band edge, y): eq. 4.2's ramp band entered in restitution
