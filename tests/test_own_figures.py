"""An own study's maps say what they show: a signed quantity (the rebound spin) on a diverging scale centred on zero,
so that topspin and backspin read off the colour (issue 44)."""

import numpy as np
import pandas as pd


def test_the_spin_map_is_diverging_and_centred_on_zero(tmp_path, monkeypatch):
    import sphereimpact.figures.own as own

    angles, speeds = np.meshgrid(np.arange(5.0, 90.0, 10.0), np.arange(5.0, 45.0, 5.0))
    spin = np.sin(np.radians(angles)) * 300.0 - 200.0  # from -190 (backspin) to +99 (topspin)
    path = tmp_path / "maps.csv"
    pd.DataFrame({"angle_to_surface": angles.ravel(), "speed": speeds.ravel(), "spin": -200.0,
                  "omega_f": spin.ravel()}).to_csv(path, index=False)
    drawn = []
    monkeypatch.setattr(own, "save", lambda fig, outputs: drawn.append(fig))
    own.map_figure(str(path), "demo", "omega_f", "rebound spin [rad/s]", [], centre=0.0)
    own.map_figure(str(path), "demo", "omega_f", "rebound spin [rad/s]", [])
    centred, plain = (fig.axes[0].collections[0] for fig in drawn)
    assert centred.get_cmap().name == "RdBu_r" and centred.norm.vmin == -centred.norm.vmax == -abs(spin).max()
    assert plain.get_cmap().name == "viridis"
