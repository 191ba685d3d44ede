"""Synthetic EPG from articulation parameters, as the browser computes it each frame.

parameters -> tongue surface (``geometry.tongue_surface``) -> collision correction against the
palate (``geometry.collision``) -> electrode contacts (``epg.contacts``) -> indices
(``epg.indices``, for the Reading palate).

The browser keeps tongue positions in Float32Arrays: the evaluator writes float32 positions and
the correction writes float32 results back. The reference rounds to float32 at the same two
places, so it answers about the very surface the browser draws, and its contacts are the
browser's (``tests/vectors/epg-contacts.json`` checks this on seeded poses).
"""

from dataclasses import dataclass

import numpy as np

from glasshead.epg.contacts import Probes, contact_grid, electrode_contacts
from glasshead.geometry.collision import correct_vertices


@dataclass
class SyntheticFrame:
    """contacts (k,) uint8 per electrode; grid (rows, columns) uint8; vertices (n, 3) float64 the
    corrected tongue (float32 values); collision counts (screened, tested, corrected)."""

    contacts: np.ndarray
    grid: np.ndarray
    vertices: np.ndarray
    collision: dict


def corrected_tongue(rig, values, tables):
    """The corrected tongue for parameter values (P,): ((n, 3) float64 of float32 values,
    counts)."""
    positions = rig.vertices(values).astype(np.float32).astype(np.float64)
    corrected, _flags, counts = correct_vertices(positions, tables)
    return corrected.astype(np.float32).astype(np.float64), counts


def synthetic_frame(rig, values, tables, probes: Probes) -> SyntheticFrame:
    """The EPG frame of one parameter set (values (P,) float64, see ``TongueRig.values_from``)."""
    vertices, counts = corrected_tongue(rig, values, tables)
    contacts = electrode_contacts(vertices, rig.triangles, probes)
    return SyntheticFrame(contacts, contact_grid(contacts, probes), vertices, counts)
