"""Two elastic bodies' materials as one contact: the effective moduli and Dundurs' beta.

DEM decks give each body's Young's modulus E [Pa] and Poisson's ratio nu [-]; the contact laws take the
pair's effective modulus E* (``modulus``) and, for a tangential spring, kappa = 4 G* / E*.  A rigid flat is
``e2 = math.inf``: then E* = E1 / (1 - nu1^2).
"""

from __future__ import annotations

import math


def effective_moduli(e1: float, nu1: float, e2: float, nu2: float) -> tuple[float, float]:
    """E* and G* [Pa] of two elastic bodies in contact (Johnson, Contact Mechanics, 1985, ch. 4 and 7):
    1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 and 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2, G = E / (2 (1 + nu)).
    ``e2 = math.inf`` is a rigid flat."""
    g1, g2 = e1 / (2.0 * (1.0 + nu1)), e2 / (2.0 * (1.0 + nu2))
    return 1.0 / ((1.0 - nu1 ** 2) / e1 + (1.0 - nu2 ** 2) / e2), 1.0 / ((2.0 - nu1) / g1 + (2.0 - nu2) / g2)


def dundurs_beta(e1: float, nu1: float, e2: float, nu2: float) -> float:
    """Dundurs' beta = [(1 - 2 nu1)/G1 - (1 - 2 nu2)/G2] / [2 ((1 - nu1)/G1 + (1 - nu2)/G2)] [-] (Johnson,
    Contact Mechanics, 1985, eq. 5.26b): how strongly normal pressure drives tangential displacement across
    the interface of two different materials."""
    g1, g2 = e1 / (2.0 * (1.0 + nu1)), e2 / (2.0 * (1.0 + nu2))
    return ((1.0 - 2.0 * nu1) / g1 - (1.0 - 2.0 * nu2) / g2) / (2.0 * ((1.0 - nu1) / g1 + (1.0 - nu2) / g2))


def _material(name: str, value) -> tuple[float, float]:
    """(E [Pa], nu [-]) of one body, checked: ValueError naming ``name`` and the allowed ranges."""
    try:
        e, nu = (float(x) for x in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be Young's modulus E [Pa] and Poisson's ratio nu, e.g. 70e9,0.33; "
                         f"got {value!r}") from None
    if not (math.isfinite(e) and e > 0):
        raise ValueError(f"{name}: Young's modulus E must be a finite number > 0 Pa; got {e!r}")
    if not (math.isfinite(nu) and -1 < nu <= 0.5):
        raise ValueError(f"{name}: Poisson's ratio nu must be a finite number in (-1, 0.5]; got {nu!r}")
    return e, nu


def material_fields(ball, surface=None, compliant: bool = False, given=()) -> dict:
    """The contact's Scene fields from the two bodies' materials, as DEM decks give them: ``modulus`` E* [Pa]
    (:func:`effective_moduli`) and, for a compliant tangential model (``compliant``), ``kappa`` = 4 G* / E* [-]
    (Mindlin's k_t / k_n).  ``ball`` and ``surface`` are (E [Pa], nu [-]); the surface is the struck one, the flat's
    or the partner sphere's, None for a rigid flat.  ``given``: the Scene fields given besides, refused where the
    materials set them (ValueError naming both)."""
    e1, nu1 = _material("ball_material", ball)
    e2, nu2 = (math.inf, nu1) if surface is None else _material("surface_material", surface)
    e_star, g_star = effective_moduli(e1, nu1, e2, nu2)
    fields = {"modulus": e_star} | ({"kappa": 4.0 * g_star / e_star} if compliant else {})
    for name in ("k", "modulus", "kappa", "poisson", "shear_modulus"):
        if name in given and (name in fields or name == "k" or compliant):
            raise ValueError(f"give {name} or the materials (ball_material, surface_material), not both: the materials "
                             "set the contact's modulus E* and, for a compliant tangential model, kappa = 4 G*/E*")
    return fields
