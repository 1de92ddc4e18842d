"""Numerical studies: reference solutions, work-precision, where methods fail, and model ablation."""
