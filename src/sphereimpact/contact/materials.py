"""Two elastic bodies' materials as one contact: the effective moduli and Dundurs' beta.

DEM decks give each body's Young's modulus E [Pa] and Poisson's ratio nu [-]; the contact laws take the
pair's effective modulus E* (``modulus``) and, for a tangential spring, kappa = 4 G* / E*.  A rigid flat is
``e2 = math.inf``: then E* = E1 / (1 - nu1^2).
"""

from __future__ import annotations


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
