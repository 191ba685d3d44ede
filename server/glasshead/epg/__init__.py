"""Electropalatography data: contact indices, recording formats and comparison.

``indices`` computes the emuR indices; ``sequence`` holds a checked recording in memory;
``formats`` reads and writes emuR JSON, the documented CSV and SSFF; ``compare`` measures the
agreement of two sequences; ``plot`` draws index tracks as SVG.
"""
