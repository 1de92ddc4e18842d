"""Sweeps: many impacts at once (batched integration, vectorised closed form, similarity interpolation)."""

from .engine import sweep

__all__ = ["sweep"]
