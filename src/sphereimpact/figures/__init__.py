"""Figures: one function per chapter figure, reading result files (never simulating)."""
