"""Numpy geometric kernels (float64); twins of ``web/src/core``."""
