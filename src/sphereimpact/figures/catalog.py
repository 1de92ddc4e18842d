"""Which chapter figures exist, what they draw and which run files they read (no matplotlib here).

The workflow asks this catalogue when it plans jobs, so parsing the Snakefile never imports a plotting
library; :mod:`sphereimpact.figures.paper` draws them.
"""

from __future__ import annotations

from typing import NamedTuple


class FigureSpec(NamedTuple):
    """One chapter figure.

    Attributes
    ----------
    kind : str
        ``displacement``, ``velocity``, ``spin`` or ``force_deflection`` (a drawing function of
        :mod:`sphereimpact.figures.paper`).
    case : str
        The configured case whose runs it reads.
    models : tuple of str
        Force laws whose run files it reads, in the order the drawing function takes them.
    title : str
    """

    kind: str
    case: str
    models: tuple
    title: str


#: The chapter's name of each force law the figures draw.
EQUATIONS = {"kelvin-voigt": "eq. 4.1", "modified": "eq. 4.2"}

#: How each separation criterion ends a contact, as figures and captions name it.
CRITERIA = {"force": "P returns to 0 (force criterion)", "penetration": "δ returns to 0 (penetration criterion)"}

FIGURES = {
    "fig4_2": FigureSpec("displacement", "normal", ("modified",), "Fig. 4.2: displacement of the centre, normal impact"),
    "fig4_3": FigureSpec("displacement", "oblique60", ("modified",), "Fig. 4.3: displacement of the centre, 60° impact"),
    "fig4_4": FigureSpec("velocity", "normal", ("modified",), "Fig. 4.4: velocities, normal impact"),
    "fig4_5": FigureSpec("velocity", "oblique60", ("modified",), "Fig. 4.5: velocities, 60° impact"),
    "fig4_6": FigureSpec("spin", "oblique60", ("modified",), "Fig. 4.6: angular velocity, 60° impact"),
    "fig4_7": FigureSpec("force_deflection", "normal", ("kelvin-voigt", "modified"),
                         "Fig. 4.7: normal force, normal impact"),
    "fig4_8": FigureSpec("force_deflection", "oblique60", ("kelvin-voigt", "modified"),
                         "Fig. 4.8: normal force, 60° impact"),
}
